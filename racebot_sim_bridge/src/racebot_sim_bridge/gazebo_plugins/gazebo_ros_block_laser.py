"""libgazebo_ros_block_laser.so (gazebo_plugins noetic-devel): a ray sensor with horizontal and vertical samples as
sensor_msgs/PointCloud, as GazeboRosBlockLaser::PutLaserData lays it out.

Parameters as its Load(): robotNamespace (text + '/'; none: the node's namespace; spawn's -robot_namespace fills
it), topicName (default /world; empty: nothing advertised), frameName (default /world) resolved with the
tf_prefix parameter of its namespace as tf::resolve, gaussianNoise (0), hokuyoMinIntensity (101: read and only
logged upstream, no clipping), updateRate (0: read and not used upstream, which publishes every sensor update).
Published while subscribed, at the sensor's <update_rate>, stamped with the scan's sim time.

The cloud reads the raw rays (../sensors/ray_shape.py: one ray per sample, a miss reads range max, never inf; the
sensor's <noise> is not in them) and interpolates them to samples x resolution points per layer and vertical
samples x vertical resolution layers, layer after layer from the lowest, each from min_angle to max_angle:
each point's range the bilinear mix of its four corner rays, < range min: -inf, > range max: +inf; its intensity
channel (channels[0], no name, as upstream) the mean laser_retro of the four; its direction the mean angle of
the corner rays (upstream's `0.5 * (a + b) * diff / (count - 1)`, so one sample or one layer divides 0 by 0:
NaN coordinates, as upstream; warned at spawn). gaussianNoise: N(0, sigma) on x, y and z of every point not at
range max, and on every intensity.
"""
import math

import numpy as np
from geometry_msgs.msg import Point32
from sensor_msgs.msg import ChannelFloat32, PointCloud

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors.config_types import join_topic, set_frame
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.messages import header
from racebot_sim_bridge.sensors.ray import range_count
from racebot_sim_bridge.sensors.ray_shape import RayShape
from racebot_sim_bridge.sensors.raycast import cast_with_retro

EPSILON_DIFF = 0.000001  # upstream's: no noise on a point this close to range max


def point32(x, y, z, new=Point32.__new__):
    """A Point32 without genpy's keyword-handling __init__ (ten times faster: a cloud has thousands)."""
    p = new(Point32)
    p.x, p.y, p.z = x, y, z
    return p


def corners(points, rays):
    """For `points` interpolated from `rays` rays (PutLaserData's hb / vb): (lower ray, upper ray, fraction)."""
    b = np.zeros(points) if points == 1 else np.arange(points) * (rays - 1) / (points - 1)
    low = np.floor(b).astype(int)
    return low, np.minimum(low + 1, rays - 1), b - np.floor(b)


def mean_angles(low, high, diff, rays, min_angle):
    """The angle PutLaserData gives a point: the mean of its corner rays' indices on (rays - 1) steps (0 / 0 for
    one ray: NaN, as upstream)."""
    with np.errstate(divide='ignore', invalid='ignore'):
        return 0.5 * (low + high) * diff / np.float64(rays - 1) + min_angle


def block_cloud(shape_ranges, retro, ray, range_min, range_max):
    """(points N x 3, intensities N) of PutLaserData from the raw rays' ranges and laser_retro (each `samples x
    vertical samples`, index i + j * samples), before noise. `ray`: the sensor's urdf_model.RaySpec."""
    rays_h, rays_v = max(1, int(ray.samples)), max(1, int(ray.vertical_samples))
    count_h = range_count(ray.samples, ray.resolution)
    count_v = range_count(ray.vertical_samples, getattr(ray, 'vertical_resolution', 1.0))
    ha, hb, hf = corners(count_h, rays_h)
    va, vb, vf = corners(count_v, rays_v)
    grid = np.asarray(shape_ranges, dtype=np.float64).reshape(rays_v, rays_h)
    retro = np.asarray(retro, dtype=np.float64).reshape(rays_v, rays_h)
    hf, vf = hf[np.newaxis, :], vf[:, np.newaxis]
    r1, r2 = grid[va][:, ha], grid[va][:, hb]
    r3, r4 = grid[vb][:, ha], grid[vb][:, hb]
    r = (1 - vf) * ((1 - hf) * r1 + hf * r2) + vf * ((1 - hf) * r3 + hf * r4)
    r = np.where(r < range_min, -math.inf, np.where(r > range_max, math.inf, r))
    intensity = 0.25 * (retro[va][:, ha] + retro[va][:, hb] + retro[vb][:, ha] + retro[vb][:, hb])
    yaw = mean_angles(ha, hb, ray.max_angle - ray.min_angle, rays_h, ray.min_angle)[np.newaxis, :]
    pitch = mean_angles(va, vb, ray.vertical_max_angle - ray.vertical_min_angle, rays_v,
                        ray.vertical_min_angle)[:, np.newaxis]
    with np.errstate(invalid='ignore'):  # inf * 0 where an angle's cosine is 0: NaN, as in C++
        points = np.stack([r * np.cos(pitch) * np.cos(yaw), r * np.cos(pitch) * np.sin(yaw),
                           r * np.sin(pitch)], axis=-1)
    return points.reshape(-1, 3), r.reshape(-1), intensity.reshape(-1)


class BlockLaserSensor(Sensor, libraries=('libgazebo_ros_block_laser.so',), sensor_types=('ray',),
                       kind=SensorKind.BLOCK_LASER, main_topic='cloud', block='ray', topic_param='topicName'):
    """gazebo_ros_block_laser: sensor_msgs/PointCloud of the interpolated rays, intensity in channels[0]. An empty
    topicName advertises nothing (upstream says "topic name not set" at every scan)."""

    @classmethod
    def load(cls, config, sdf):
        """As GazeboRosBlockLaser::Load reads the plugin."""
        params, what, warnings, ray = sdf.params, sdf.what, config.warnings, sdf.spec.ray
        text = sdf.own_namespace()
        ns = sdf.resolve('' if text is None else text + '/')
        topic = params.get('topicName')
        if topic is None:
            topic = '/world'
            warnings.append('%s has no <topicName>; publishing on /world as gazebo_ros_block_laser does' % what)
        if max(1, int(ray.samples)) == 1 or max(1, int(ray.vertical_samples)) == 1:
            warnings.append('%s: a single horizontal or vertical sample gives NaN point coordinates in '
                            'gazebo_ros_block_laser (its angle divides 0 by samples - 1); published as upstream' % what)
        set_frame(config, params, '/world', ns)
        config.topics['cloud'] = join_topic(ns, topic)
        config.params['gaussian_noise'] = sdf.number('gaussianNoise', 0.0)
        config.params['hokuyo_min_intensity'] = sdf.number('hokuyoMinIntensity', 101.0)
        config.params['update_rate'] = sdf.number('updateRate', 0.0)
        return config

    def __init__(self, manager, robot, spec, config, rng=None):
        super().__init__(manager, robot, spec, config)
        self.shape = RayShape(spec.ray)
        sigma = config.params['gaussian_noise']
        self.sigma = sigma if manager.noise_enabled else 0.0
        self.rng = rng if rng is not None else np.random.default_rng()
        self.advertise('cloud', PointCloud, 1)

    def measure(self):
        """(points N x 3, ranges N, intensities N) of one scan, with gaussianNoise, as PutLaserData fills them."""
        position, orientation = self.mount.pose()
        starts, ends = self.shape.endpoints(position, quaternion_to_matrix(orientation))
        fractions, hit, retro = cast_with_retro(self.sim.world, starts, ends)
        shape = self.shape
        points, ranges, intensity = block_cloud(shape.ranges(fractions, hit), retro, self.spec.ray,
                                                shape.range_min, shape.range_max)
        if self.sigma > 0.0:
            noisy = np.abs(shape.range_max - ranges) > EPSILON_DIFF
            points[noisy] += self.rng.normal(0.0, self.sigma, (int(noisy.sum()), 3))
            intensity = intensity + self.rng.normal(0.0, self.sigma, len(intensity))
        return points, ranges, intensity

    def update(self, time, stamp):
        if not self.listened():
            return
        points, _, intensity = self.measure()
        points = points.astype(np.float32).tolist()
        msg = PointCloud(header=header(stamp, self.config.frame_id),
                         points=[point32(x, y, z) for x, y, z in points],
                         channels=[ChannelFloat32(name='', values=intensity.astype(np.float32).tolist())])
        self.publishers['cloud'].publish(msg)
        self.meter.tick()
