"""gazebo_ros_control (libgazebo_ros_control.so), as gazebo_ros_pkgs' package of that name:

  robot_hw_sim.py                DefaultRobotHWSim: a spawned robot's joints from its transmissions, PID gains,
                                 readSim / writeSim on its PyBullet body
  gazebo_ros_control_plugin.py   GazeboRosControlPlugin: per robot, its namespace, control period, RobotHWSim,
                                 controller manager and the controller manager's services; attach() hooks it
                                 into a Simulator (gazebo_plugins/registry.py knows it by its library)

ros_control's own parts (hardware interfaces, the controller manager and its services, PID) are in ../ros_control/.
"""
