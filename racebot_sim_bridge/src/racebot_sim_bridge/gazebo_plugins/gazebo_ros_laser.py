"""libgazebo_ros_laser.so and libgazebo_ros_gpu_laser.so (gazebo_plugins noetic-devel): the ray sensor's
sensor_msgs/LaserScan. The rays are cast on the physics client inside the step (../sensors/raycast.py), ranges and
noise as Gazebo reports them (../sensors/ray.py, noise.py), intensities from the laser_retro of what they hit.

Parameters as its Load(): robotNamespace (plugin_namespace.py), topicName (default /world, odd as it is, warned;
empty: nothing advertised), frameName (default /world, warned) resolved with the tf_prefix parameter of its
namespace as tf::resolve.
"""
from sensor_msgs.msg import LaserScan

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.config_types import join_topic, set_frame
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.noise import make_noise
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.sensors.raycast import cast_rays


class LaserSensor(Sensor, libraries=('libgazebo_ros_laser.so', 'libgazebo_ros_gpu_laser.so'),
                  sensor_types=('ray', 'gpu_ray'), kind=SensorKind.LASER, main_topic='scan', block='ray',
                  topic_param='topicName'):
    """gazebo_ros_laser and gazebo_ros_gpu_laser: sensor_msgs/LaserScan of the ray sensor's beams."""

    @classmethod
    def load(cls, config, sdf):
        params, what, warnings = sdf.params, sdf.what, config.warnings
        topic = params.get('topicName')
        if topic is None:
            topic = '/world'  # gazebo_ros_laser's default, odd as it is
            warnings.append('%s has no <topicName>; publishing on /world as gazebo_ros_laser does' % what)
        if params.get('frameName') is None:
            warnings.append('%s has no <frameName>; frame_id world, as gazebo_ros_laser defaults' % what)
        ns = sdf.namespace(cls.kind)
        set_frame(config, params, '/world', ns)  # resolved with <ns>/tf_prefix, as upstream
        config.topics['scan'] = join_topic(ns, topic)
        return config

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        self.geometry = ScanGeometry(spec.ray)
        ray = spec.ray
        self.noise = make_noise(ray.noise_type, ray.noise_mean, ray.noise_stddev, manager.noise_enabled)
        self.advertise('scan', LaserScan, 5)

    def update(self, time, stamp):
        if not self.listened():
            return
        position, orientation = self.mount.pose()
        starts, ends = self.geometry.endpoints(position, quaternion_to_matrix(orientation))
        world = self.sim.world
        retro = world.laser_retro
        intensities = None
        if retro:  # Gazebo's ray intensity: the laser_retro of the collision hit, 0 for a miss or none set
            fractions, hit, objects = cast_rays(world, starts, ends, objects=True)
            intensities = [retro.get(o, 0.0) for o in objects]
        else:
            fractions, hit = cast_rays(world, starts, ends)
        ranges = self.geometry.report(self.geometry.ranges_from_hits(fractions, hit), self.noise)
        self.publishers['scan'].publish(msgs.laser_scan(stamp, self.config.frame_id, self.geometry, ranges,
                                                        intensities))
        self.meter.tick()
