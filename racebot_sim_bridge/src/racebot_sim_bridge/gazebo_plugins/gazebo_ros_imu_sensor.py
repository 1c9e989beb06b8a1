"""libgazebo_ros_imu_sensor.so (gazebo_plugins noetic-devel): an imu sensor's sensor_msgs/Imu. What an IMU
measures: ../sensors/imu_reading.py; Gazebo's noise models: ../sensors/noise.py. (libgazebo_ros_imu.so, the model
plugin, is gazebo_ros_imu.py.)

Parameters as its Load(): robotNamespace (none: /<model>/, plugin_namespace.py), topicName (imu_data), frameName
(written as it is into the header; without one it stops, "missing <frameName>, cannot proceed": refused),
updateRateHZ (1: throttles the sensor's <update_rate> down to it), gaussianNoise (0), rpyOffset (0 0 0),
initialOrientationAsReference (false).

As in Gazebo, the sensor measures at its own <update_rate> whether or not anybody listens (the plugin's Load
switches it on), each measurement's acceleration the velocity's change since the previous one (ImuSensor::UpdateImpl);
the plugin publishes the latest at its updateRateHZ.
"""
import numpy as np
from sensor_msgs.msg import Imu

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.kinematics.rotations import quaternion_multiply, rpy_to_quaternion
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.config_types import SensorConfigError, join_topic
from racebot_sim_bridge.sensors.imu_reading import ImuKinematics
from racebot_sim_bridge.sensors.noise import AxisNoise, make_noise
from racebot_sim_bridge.sensors.schedule import FrameThrottle, UpdateSchedule


class ImuSensor(Sensor, libraries=('libgazebo_ros_imu_sensor.so',), sensor_types=('imu',),
                kind=SensorKind.IMU, main_topic='imu'):
    """gazebo_ros_imu_sensor on Gazebo's ImuSensor: per-axis noise with bias (<imu><angular_velocity><x>...),
    the plugin's gaussianNoise on every field, rpyOffset, initialOrientationAsReference, and the acceleration
    differenced since the previous measurement at the sensor's rate (the module's doc)."""

    @classmethod
    def load(cls, config, sdf):
        params, what, warnings = sdf.params, sdf.what, config.warnings
        # gazebo_ros_imu_sensor writes frameName as it is into the header, and without one it stops
        # ("missing <frameName>, cannot proceed"): no topic at all.
        if params.get('frameName') is None:
            raise SensorConfigError('%s has no <frameName>: gazebo_ros_imu_sensor cannot proceed without one and '
                                    'publishes nothing; add <frameName>LINK</frameName> to the plugin' % what)
        config.frame_id = params.get('frameName')
        config.topics['imu'] = join_topic(sdf.namespace(cls.kind), params.get('topicName') or 'imu_data')
        config.params['sensor_rate'] = config.rate
        config.params['publish_rate'] = sdf.number('updateRateHZ', 1.0)
        config.rate = _throttled(config.rate, config.params['publish_rate'])
        config.params['gaussian_noise'] = sdf.number('gaussianNoise', 0.0)
        config.params['initial_orientation_as_reference'] = \
            (params.get('initialOrientationAsReference') or '').strip().lower() in ('true', '1')
        rpy = (params.get('rpyOffset') or '0 0 0').split()
        try:
            config.params['rpy_offset'] = tuple(float(v) for v in rpy) if len(rpy) == 3 else (0.0, 0.0, 0.0)
        except ValueError:
            config.params['rpy_offset'] = (0.0, 0.0, 0.0)
            warnings.append('%s: <rpyOffset> %r is not three numbers; using 0 0 0' % (what, params.get('rpyOffset')))
        return config

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        reference = self.mount.pose()[1] if config.params.get('initial_orientation_as_reference') else None
        self.kinematics = ImuKinematics(manager.sim.world.gravity, reference)
        enabled = manager.noise_enabled
        imu = spec.imu
        self.gyro_noise = AxisNoise.make(imu.angular_velocity_noise, enabled)
        self.accel_noise = AxisNoise.make(imu.linear_acceleration_noise, enabled)
        self.plugin_stddev = config.params['gaussian_noise']
        self.plugin_noise = make_noise('gaussian', 0.0, self.plugin_stddev, enabled)
        self.offset = rpy_to_quaternion(*config.params['rpy_offset'])
        self.advertise('imu', Imu, 10)
        # the sensor's measurements (Gazebo's ImuSensor, its rate), the plugin's publishing throttled on them
        self.schedule = UpdateSchedule(config.params['sensor_rate'], start=self.sim.time)
        self.throttle = FrameThrottle(config.params['publish_rate'])
        self.kinematics.prime(self.sim.time, self.mount.motion()[2])  # Gazebo's Load records the velocity

    def update(self, time, stamp):
        _, orientation, velocity, omega = self.mount.motion()
        m = self.kinematics.measure(time, orientation, velocity, omega)
        if m is None or not self.throttle.passes(time) or not self.listened():
            return
        q = np.asarray(quaternion_multiply(self.offset, m.orientation))  # the plugin's rpyOffset
        gyro, accel = m.angular_velocity, m.linear_acceleration
        if self.gyro_noise is not None:
            gyro = self.gyro_noise.apply(gyro)
        if self.accel_noise is not None:
            accel = self.accel_noise.apply(accel)
        if self.plugin_noise is not None:  # gazebo_ros_imu_sensor's gaussianNoise: on every field
            gyro, accel = self.plugin_noise.apply(gyro), self.plugin_noise.apply(accel)
            q = self.plugin_noise.apply(q)
            q = q / np.linalg.norm(q)  # unlike the plugin, keep it a unit quaternion
        self.publishers['imu'].publish(msgs.imu(stamp, self.config.frame_id, q, gyro, accel, self.plugin_stddev))
        self.meter.tick()


def _throttled(sensor_rate, plugin_rate):
    """The rate a plugin publishes at: the sensor's, or the plugin's own if that is lower."""
    rates = [r for r in (sensor_rate, plugin_rate) if r and r > 0]
    return min(rates) if rates else 0.0
