"""The pipeline behind the simulated sensor plugins. The plugins themselves (laser, camera, multicamera, openni_kinect
/ depth camera, imu_sensor, range, bumper: one class each, what they publish) are in ../gazebo_plugins/, each in the
module named after its library (gazebo_ros_laser.py, ...), on the base gazebo_plugins/sensor_plugin.Sensor.

The stages, module by module:
  config.py          which sensors, topics, frames and rates a URDF's <sensor> blocks declare, and which
                     registered plugin class runs each (../gazebo_plugins/registry.py); config_types.py:
                     SensorConfig and the helpers a plugin's own `configure` uses
  schedule.py        when: update times in sim time, achieved rates, the in-thread render budget
  mount.py           where: a sensor's pose on its robot
  raycast.py         laser, range: the ray casts; ray.py: beam geometry and ranges as Gazebo reports them;
                     ray_shape.py: the raw rays (Gazebo's MultiRayShape) block_laser and hector's sonar read
  render.py          cameras: renderer choice (EGL / TinyRenderer) and one camera's frame;
                     camera.py: pinhole maths; scene.py: colours and analytic ground planes;
                     egl_shadow_map.py: the EGL plugin's per-frame shadow pass, switched off
  render_worker.py   the worker process that renders frames off the physics thread, from a
                     ../engine/world_copy.py posed at the frame's sim time; render_process.py: its main
  imu_reading.py     what an IMU measures; noise.py: Gazebo's noise models
  range_reading.py   range: gazebo_ros_range's reading of the ray casts
  contact.py         bumper: Gazebo's collision names, contact groups and wrenches;
                     contact_points.py: PyBullet's contact points of a link
  messages.py        the ROS messages, filled as gazebo_ros fills them
  sensor_manager.py  SensorManager: the sensors of every spawned robot, hooked into the Simulator
Only sensor_manager.py and messages.py (and the plugin classes) touch ROS: message classes; the manager gets rospy
passed in. This package's namespace is empty on purpose: the plugins import its stages, the registry the plugins.
"""
