"""gazebo_ros_control (libgazebo_ros_control.so): the RobotHWSim of a spawned robot (joints and
transmissions, PID gains) and its controller manager's services, hooked in as a plugin like any other."""
