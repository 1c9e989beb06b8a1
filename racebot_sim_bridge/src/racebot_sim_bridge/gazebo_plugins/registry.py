"""REGISTRY: every plugin library racebot simulates -> the class that answers it, for model plugins, sensor
plugins and gazebo_ros_control alike; and the one warning about a library it does not simulate.

A class lists the library names it answers in `libraries` (the filenames a URDF writes) and where it sits in
`plugin_kind` (a PluginKind); the module that holds it is named after (one of) those libraries, so that
filename="libgazebo_ros_laser.so" leads to gazebo_ros_laser.py. Filenames are looked up by library_key, so a
path or a bare name finds the same class. A plugin that another kind of block asks for (a model plugin inside a
<sensor>) is not found there, and warned about as Gazebo would fail to load it.
"""
from racebot_sim_bridge.description.plugin_library import library_key
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_block_laser import BlockLaserSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_bumper import BumperSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_diff_drive import DiffDrive
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_elevator import Elevator
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_f3d import F3D
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_force import Force
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_ft_sensor import FTSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_hand_of_god import HandOfGod
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_harness import Harness
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_imu import Imu
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_imu_sensor import ImuSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_joint_pose_trajectory import JointPoseTrajectory
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_joint_state_publisher import JointStatePublisher
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_laser import LaserSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_multicamera import MultiCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_openni_kinect import DepthCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_p3d import P3D
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_planar_move import PlanarMove
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_projector import Projector
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_prosilica import ProsilicaCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_range import RangeSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_skid_steer_drive import SkidSteerDrive
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_template import Template
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_tricycle_drive import TricycleDrive
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_triggered_camera import TriggeredCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_triggered_multicamera import TriggeredMultiCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_vacuum_gripper import VacuumGripper
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_velodyne_gpu_laser import VelodyneGpuLaser
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_velodyne_laser import VelodyneLaser
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_video import Video
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_wheel_slip import WheelSlip
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_baro import HectorBaro
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_gps import HectorGps
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_imu import HectorImu
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_magnetic import HectorMagnetic
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_sonar import HectorSonar
from racebot_sim_bridge.gazebo_plugins.ridgeback_ros_force_based_move import RidgebackForceBasedMove
from racebot_sim_bridge.gazebo_plugins.roboticsgroup_upatras_gazebo_mimic_joint_plugin import MimicJointPlugin
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE

# What a plugin that is not simulated would have done, by where it sits: its warning says so.
LOST = {PluginKind.MODEL: 'what it would do does not happen', PluginKind.SENSOR: 'it publishes nothing'}


class Registry:
    """Library key -> class, built from classes that list their `libraries` and `plugin_kind`."""

    def __init__(self, classes):
        self.classes = {}
        for cls in classes:
            for library in cls.libraries:
                key = library_key(library)
                if key in self.classes:
                    raise ValueError('%s and %s both answer %s' % (self.classes[key].__name__, cls.__name__, library))
                self.classes[key] = cls

    def find(self, filename, kind=None):
        """The class answering a plugin's filename (of that PluginKind, when given), or None."""
        cls = self.classes.get(library_key(filename))
        if cls is None or (kind is not None and cls.plugin_kind is not kind):
            return None
        return cls

    def not_simulated(self, robot_name, plugin, sensor=None):
        """The warning about a <plugin> (a GazeboPlugin spec) racebot does not simulate, where it sits: a
        model's block, or the <sensor> (a SensorSpec) it is in. None when it is simulated there (a model's
        gazebo_ros_control is: by GazeboRosControlPlugin, hooked into the simulator)."""
        kind = PluginKind.MODEL if sensor is None else PluginKind.SENSOR
        found = self.find(plugin.filename)
        if found is not None and (found.plugin_kind is kind or
                                  (sensor is None and found.plugin_kind is PluginKind.ROBOT_HARDWARE)):
            return None
        where = '' if sensor is None else "sensor '%s' (type %s): " % (sensor.name, sensor.type)
        return ("%s: %splugin '%s' (%s) is not simulated by racebot, so %s; the rest of the robot works; see %s"
                % (robot_name, where, plugin.name, plugin.filename, LOST[kind], SUPPORTED_TABLE))


REGISTRY = Registry((
    # model plugins: plugin_manager.PluginManager
    DiffDrive, SkidSteerDrive, PlanarMove, P3D, JointStatePublisher, Imu, HectorGps, HectorImu, FTSensor,
    Force, F3D, Template, TricycleDrive, HandOfGod, VacuumGripper, JointPoseTrajectory, HectorMagnetic, HectorBaro,
    Video, Projector, RidgebackForceBasedMove, MimicJointPlugin, Elevator, Harness, WheelSlip,
    # sensor plugins: sensor_manager.SensorManager
    LaserSensor, CameraSensor, MultiCameraSensor, DepthCameraSensor, ImuSensor, RangeSensor, BumperSensor,
    TriggeredCameraSensor, TriggeredMultiCameraSensor, ProsilicaCameraSensor,
    BlockLaserSensor, VelodyneLaser, VelodyneGpuLaser, HectorSonar,
    # robot hardware: GazeboRosControlPlugin.attach hooks it into the simulator
    GazeboRosControlPlugin,
))
