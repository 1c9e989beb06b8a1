"""racebot's stand-in for the Python side of gazebo_ros.

Modules:
    gazebo_interface  -- spawn_sdf_model_client, spawn_urdf_model_client, set_model_configuration_client:
                         gazebo_ros's wrappers around its services, same signatures
    spawn_model       -- the ``spawn_model`` command (``parse_args`` is pure, no ROS needed)
    server            -- ``gzserver`` / ``debug``: racebot's world server with gzserver's command line
"""

#: Marks this package as racebot's stand-in (the real gazebo_ros has no such attribute).
RACEBOT_COMPAT = True
