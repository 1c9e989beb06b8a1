"""The simulated sensors: what gazebo_ros's laser, camera, multicamera, depth camera (openni_kinect),
IMU, range and bumper plugins publish.

The pipeline, module by module:
  config.py        which sensors, topics, frames and rates a URDF's <sensor> blocks declare
  schedule.py      when: update times in sim time, achieved rates, the in-thread render budget
  mount.py         where: a sensor's pose on its robot
  raycast.py       laser: the ray casts; ray.py: beam geometry and ranges as Gazebo reports them
  render.py        cameras: renderer choice (EGL / TinyRenderer) and one camera's frame;
                   camera.py: pinhole maths; scene.py: colours and analytic ground planes;
                   egl_shadow_map.py: the EGL plugin's per-frame shadow pass, switched off
  render_worker.py the worker process that renders frames off the physics thread, from a
                   ../world_copy.py posed at the frame's sim time; render_process.py: its main
  imu.py, noise.py what an IMU measures; Gazebo's noise models
  range_reading.py range: gazebo_ros_range's reading of the ray casts
  contact.py       bumper: Gazebo's collision names, contact groups and wrenches;
                   contact_points.py: PyBullet's contact points of a link
  messages.py      the ROS messages, filled as gazebo_ros fills them
  devices.py       one class per plugin, running the pipeline for its sensor
  manager.py       SensorManager: sensors of every spawned robot, hooked into the Simulator
Only devices.py, manager.py and messages.py touch ROS (message classes; manager gets rospy passed in).
"""
from racebot_sim_bridge.sensors.sensor_manager import SensorManager  # noqa: F401
