"""gazebo_ros's API plugin (gazebo_ros_api_plugin.cpp): the /gazebo services and topics, properties, forces,
entities and frames, performance metrics and the physics dynamic_reconfigure server."""
