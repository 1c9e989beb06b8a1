from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=['racebot_sim_bridge', 'racebot_sim_bridge.sensors', 'racebot_sim_bridge.controllers',
              'racebot_sim_bridge.plugins', 'racebot_sim_bridge.kinematics'],
    package_dir={'': 'src'}))
