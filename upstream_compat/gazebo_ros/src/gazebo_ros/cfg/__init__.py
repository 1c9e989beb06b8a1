"""gazebo_ros's dynamic_reconfigure config types (upstream generates them from cfg/*.cfg)."""
