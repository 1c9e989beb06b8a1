from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

# One subpackage per upstream component the simulator stands in for (docs/ARCHITECTURE.md).
SUBPACKAGES = ['description', 'engine', 'gazebo_plugins', 'gazebo_ros_api', 'gazebo_ros_control', 'kinematics',
               'ros_control', 'ros_controllers', 'sensors', 'transport', 'window']

setup(**generate_distutils_setup(
    packages=['racebot_sim_bridge'] + ['racebot_sim_bridge.' + name for name in SUBPACKAGES],
    package_dir={'': 'src'}))
