"""Gazebo's model plugins (gazebo_plugins noetic-devel; hector_gazebo_plugins' GPS and IMU), simulated: one
module per plugin.

MODEL_PLUGINS maps a plugin's library name, as `plugin_key` spells it ('gazebo_ros_diff_drive'
for filename="libgazebo_ros_diff_drive.so", a path or the bare name alike), to its class (a
base.ModelPlugin). A new plugin is a module here with one such class, added to MODULES below.
manager.PluginManager builds them for each spawned robot and runs them with the physics.
Sensor plugins (a <sensor>'s <plugin>) are in ../sensors; gazebo_ros_control is simulator.py's.
"""
import os

from racebot_sim_bridge.gazebo_plugins import (gazebo_ros_diff_drive as diff_drive,
                                               hector_gazebo_ros_gps as hector_gps,
                                               hector_gazebo_ros_imu as hector_imu, gazebo_ros_imu as imu,
                                               gazebo_ros_joint_state_publisher as joint_state_publisher,
                                               gazebo_ros_p3d as p3d, gazebo_ros_planar_move as planar_move,
                                               gazebo_ros_skid_steer_drive as skid_steer_drive)

MODULES = (skid_steer_drive, planar_move, p3d, joint_state_publisher, diff_drive, imu, hector_gps, hector_imu)


def plugin_key(filename):
    """'libgazebo_ros_diff_drive.so', '/opt/x/libgazebo_ros_diff_drive.so' -> 'gazebo_ros_diff_drive'."""
    base = os.path.basename(filename or '')
    if base.endswith('.so'):
        base = base[:-3]
    if base.startswith('lib'):
        base = base[3:]
    return base


def _registry():
    classes = [c for m in MODULES for c in getattr(m, 'PLUGINS', ())]
    return {plugin_key(c.filename): c for c in classes}


MODEL_PLUGINS = _registry()
