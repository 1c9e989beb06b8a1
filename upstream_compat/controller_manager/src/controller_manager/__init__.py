"""racebot's stand-in for the Python side of ros_control's controller_manager package.

Modules:
    spawner                       -- the ``spawner`` node (``parse_args`` is pure, no ROS needed)
    cli                           -- the ``controller_manager`` command
    controller_manager_interface  -- one-call helpers around the controller_manager services,
                                     named like ros_control's module of the same name

Everything talks to a controller manager only through controller_manager_msgs services, so it
works against the racebot simulator and against a real ros_control controller manager alike.
"""

#: Marks this package as racebot's stand-in (the real controller_manager has no such attribute).
RACEBOT_COMPAT = True
