"""libgazebo_ros_range.so (gazebo_plugins noetic-devel): a ray sensor's shortest ray as sensor_msgs/Range
(../sensors/range_reading.py).

Parameters as its Load(): robotNamespace (text + '/'; none: the node's namespace), topicName (/range; empty:
nothing advertised), frameName (/world) resolved with the tf_prefix parameter of its namespace, radiation
(ultrasound, warned when absent; any text but 'ultrasound' is INFRARED), fov (0.05 rad, warned when absent),
gaussianNoise (0), updateRate (0: every sensor update; else whole periods, as a camera's).
"""
from sensor_msgs.msg import Range

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.config_types import join_topic, set_frame
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.noise import make_noise
from racebot_sim_bridge.sensors.range_reading import radiation_type, range_reading, ray_lengths
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.sensors.raycast import cast_rays
from racebot_sim_bridge.sensors.schedule import FrameThrottle


# a gpu_ray is refused: gazebo_ros_range needs a RaySensor (gzthrow upstream)
class RangeSensor(Sensor, libraries=('libgazebo_ros_range.so',), sensor_types=('ray',),
                  kind=SensorKind.RANGE, main_topic='range', block='ray', topic_param='topicName'):
    """gazebo_ros_range: the ray sensor's shortest ray as sensor_msgs/Range (range_reading.py)."""

    @classmethod
    def load(cls, config, sdf):
        params, what, warnings = sdf.params, sdf.what, config.warnings
        topic = params.get('topicName')
        radiation = params.get('radiation')
        if radiation is None:
            radiation = 'ultrasound'
            warnings.append('%s has no <radiation>; ultrasound, as gazebo_ros_range defaults' % what)
        elif radiation not in ('ultrasound', 'infrared'):
            warnings.append("%s: <radiation> %r is neither 'ultrasound' nor 'infrared'; published as INFRARED, as "
                            "gazebo_ros_range does with any text but 'ultrasound'" % (what, radiation))
        if params.get('fov') is None:
            warnings.append('%s has no <fov>; field_of_view 0.05 rad, as gazebo_ros_range defaults' % what)
        ns = sdf.namespace(cls.kind)
        set_frame(config, params, '/world', ns)
        config.topics['range'] = join_topic(ns, '/range' if topic is None else topic)
        config.params['radiation'] = radiation
        config.params['fov'] = sdf.number('fov', 0.05)
        config.params['gaussian_noise'] = sdf.number('gaussianNoise', 0.0)
        config.params['update_rate'] = sdf.number('updateRate', 0.0)
        return config

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        self.geometry = ScanGeometry(spec.ray)
        self.throttle = FrameThrottle(config.params['update_rate'])
        stddev = config.params['gaussian_noise']
        self.noise = make_noise('gaussian', 0.0, stddev, manager.noise_enabled) if stddev > 0 else None
        self.radiation = radiation_type(config.params['radiation'])
        self.advertise('range', Range, 1)

    def update(self, time, stamp):
        if not self.throttle.passes(time) or not self.listened():
            return
        position, orientation = self.mount.pose()
        starts, ends = self.geometry.endpoints(position, quaternion_to_matrix(orientation))
        fractions, hit = cast_rays(self.sim.world, starts, ends)
        g = self.geometry
        sample = float(self.noise.apply(0.0)) if self.noise is not None else 0.0
        reading = range_reading(ray_lengths(fractions, hit, g.range_min, g.range_max), g.range_max, sample)
        self.publishers['range'].publish(msgs.range_message(
            stamp, self.config.frame_id, self.radiation, self.config.params['fov'], g.range_min, g.range_max,
            reading))
        self.meter.tick()
