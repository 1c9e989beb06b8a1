"""Gazebo's plugins, simulated: one module per plugin library, named after it (gazebo_ros_diff_drive.py answers
filename="libgazebo_ros_diff_drive.so"; gazebo_ros_laser.py also answers libgazebo_ros_gpu_laser.so).

  registry.py            REGISTRY: library name -> the class that answers it, for every kind of plugin; the one
                         warning about a library racebot does not simulate
  model plugins          gazebo_plugins' (noetic-devel), hector_gazebo_plugins', roboticsgroup's mimic joint,
                         ridgeback's: subclasses of model_plugin.py, built and run by plugin_manager.py
  sensor plugins         gazebo_plugins', hector's sonar, velodyne's: subclasses of sensor_plugin.py (the cameras of
                         gazebo_ros_camera_utils.py), loaded, built and run by sensor_manager.py with the pipeline
                         stages in ../sensors/
                         (every library by name: REGISTRY in registry.py, and docs/SUPPORTED.md)
  robot hardware         gazebo_ros_control: ../gazebo_ros_control/, hooked into the simulator at spawn
  compiled plugins       a library racebot has no class for, built against racebot's Gazebo 11 plugin API
                         (upstream_compat/gazebo_dev): found and loaded by compiled_plugins.py through the gazebo_host
                         module (src/cpp/gazebo_host.cpp, built into the devel space's copy of this folder)
  shared                 odometry_output.py, link_motion.py, update_timing.py, hector_reconfigure.py,
                         gazebo_ros_utils.py, gazebo_pid.py, polled_camera_types.py

A new plugin is a module here named after its library, with one class that lists its `libraries`, added to
registry.py. What every gazebo_ros plugin shares lives below, in ../gazebo_ros_api/: PluginKind (plugin_kind.py)
and where a plugin's topics go (plugin_namespace.py); the one way a filename becomes a library name, library_key,
is the description's (../description/plugin_library.py). A worked example with its test:
docs/WRITE_A_PLUGIN_OR_CONTROLLER.md.
"""
from pkgutil import extend_path

__path__ = [p for p in extend_path([], __name__) if p not in __path__] + list(__path__)
