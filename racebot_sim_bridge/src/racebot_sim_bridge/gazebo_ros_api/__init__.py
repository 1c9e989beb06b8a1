"""gazebo_ros's API plugin (gazebo_ros_api_plugin.cpp): the /gazebo services and topics, properties, forces,
entities and frames, performance metrics and the physics dynamic_reconfigure server; and what every gazebo_ros
plugin shares (gazebo_ros_control's and gazebo_plugins' alike): where it sits (plugin_kind.py) and where its
topics go (plugin_namespace.py)."""
