"""The pipeline behind the simulated sensor plugins. The plugins themselves (laser, camera, multicamera, openni_kinect
/ depth camera, imu_sensor, range, bumper: one class each, what they read and publish) are in ../gazebo_plugins/,
each in the module named after its library (gazebo_ros_laser.py, ...), on the base gazebo_plugins/sensor_plugin.Sensor;
gazebo_plugins/sensor_manager.py loads them when a robot spawns and steps them. Nothing here imports a layer above.

The stages, module by module:
  config_types.py    SensorConfig (a sensor's topics, frame, rate and parameters) and the topic, frame and number
                     helpers each plugin's own load() reads its <sensor> and <plugin> with
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
Only messages.py (and the plugin classes) touch ROS: message classes; the render worker's parts get a log passed in.
This package's namespace is empty on purpose: the plugins import its stages.
"""
