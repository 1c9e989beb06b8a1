"""libgazebo_ros_velodyne_laser.so (velodyne_gazebo_plugins, velodyne_simulator): a ray sensor's scan as
sensor_msgs/PointCloud2 with x y z intensity ring, as GazeboRosVelodyneLaser::OnScan lays it out;
gazebo_ros_velodyne_gpu_laser.py is the same plugin built for a gpu_ray sensor.

Parameters as its Load(): robotNamespace (default /; spawn's -robot_namespace fills it), topicName (/points;
empty: nothing advertised), frameName (/world) resolved with tf::resolve and a prefix: the tf_prefix parameter of
its namespace when robotNamespace is /, else robotNamespace itself (trailing slashes trimmed); min_range (0),
max_range (inf), min_intensity (none), gaussianNoise (0), organize_cloud (false). Published while subscribed, at
the sensor's <update_rate>, stamped with the scan's sim time.

The scan is what Gazebo's RaySensor reports (../sensors/ray.py, as gazebo_ros_laser: +inf for a miss, -inf
inside range min, the sensor's <noise>; intensities the laser_retro of what each ray hits). A reading is dropped
when it is not strictly between max(min_range, range min) and min(max_range, range max) or its intensity is
below min_intensity; gaussianNoise then adds N(0, sigma) to the range (a reading the noise takes out of the band
is dropped too). Points go azimuth after azimuth, each from the lowest laser up; ring = the laser's index from
the lowest (0). The point's direction: yaw i * (max - min) / (count - 1) + min (min for one), pitch likewise
over the layers (vertical min for one layer, where the ray itself is cast level, as upstream).

Two layouts, by the release a URDF is written for. `<organize_cloud>` came with velodyne_simulator 1.0.11, whose
description always writes it, and whose points (since 1.0.10) are 22 bytes: x y z intensity float32 at 0 4 8
12, ring uint16 at 16, time float32 at 18 (always 0). Without it, the 1.0.9 layout (the corpus pins lmark1's
fork of 1.0.9): 32 bytes, x y z at 0 4 8, intensity at 16, ring at 20, the rest zeros. Unorganized: height 1,
width the points kept, is_dense true. organize_cloud: every reading kept, a dropped one as NaN x y z intensity
with its ring, width the lasers, height the azimuths, is_dense false.
Not here: staticTopicName/staticFrameName of lmark1's fork (a second cloud transformed through tf): warned.
"""
import math

import numpy as np
from sensor_msgs.msg import PointCloud2, PointField

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors.config_types import join_topic, tf_resolve
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.messages import header
from racebot_sim_bridge.sensors.noise import make_noise
from racebot_sim_bridge.sensors.ray import ScanGeometry, range_count
from racebot_sim_bridge.sensors.raycast import cast_with_retro


def _field(name, offset, datatype):
    return PointField(name=name, offset=offset, datatype=datatype, count=1)


F32, U16 = PointField.FLOAT32, PointField.UINT16
# (point_step, fields, intensity offset, ring offset, time offset) of each release's points
LAYOUT_1_0_9 = (32, [_field('x', 0, F32), _field('y', 4, F32), _field('z', 8, F32), _field('intensity', 16, F32),
                     _field('ring', 20, U16)], 16, 20, None)
LAYOUT_1_0_11 = (22, [_field('x', 0, F32), _field('y', 4, F32), _field('z', 8, F32), _field('intensity', 12, F32),
                      _field('ring', 16, U16), _field('time', 18, F32)], 12, 16, 18)
TRUE, FALSE = ('true', '1'), ('false', '0')  # sdformat's bool


def velodyne_points(ranges, intensities, ray, min_range, max_range, min_intensity, noise=None, organize=False):
    """OnScan's points from the scan: (xyz float64 K x 3 with NaN rows where organize keeps a dropped reading,
    intensity K, ring K, azimuth index K). `ranges`, `intensities`: the RaySensor's scan, index i + j * count;
    `ray`: the urdf_model.RaySpec; `noise`: a noise.GaussianNoise for gaussianNoise, or None."""
    count = range_count(ray.samples, ray.resolution)
    layers = len(ranges) // count  # the scan's layers (ray.ScanGeometry casts one per vertical sample)
    # azimuth-major: [i][j] = scan[i + j * count]
    r = np.asarray(ranges, dtype=np.float64).reshape(layers, count).T.reshape(-1)
    intensity = np.asarray(intensities, dtype=np.float64).reshape(layers, count).T.reshape(-1)
    azimuth, ring = np.divmod(np.arange(count * layers), layers)
    low, high = max(min_range, ray.range_min), min(max_range, ray.range_max)
    with np.errstate(invalid='ignore'):
        keep = (low < r) & (r < high) & ~(intensity < min_intensity)
    if not organize:
        r, intensity, azimuth, ring = r[keep], intensity[keep], azimuth[keep], ring[keep]
    if noise is not None:
        r = noise.apply(r)
    yaw_step = (ray.max_angle - ray.min_angle) / (count - 1) if count > 1 else 0.0
    yaw = azimuth * yaw_step + ray.min_angle
    with np.errstate(divide='ignore', invalid='ignore'):  # layers == 1 under 2+ vertical samples: as C++
        pitch_step = (ray.vertical_max_angle - ray.vertical_min_angle) / np.float64(layers - 1)
    pitch = ring * pitch_step + ray.vertical_min_angle if int(ray.vertical_samples) > 1 else \
        np.full(len(ring), float(ray.vertical_min_angle))
    inside = (low < r) & (r < high)
    with np.errstate(invalid='ignore'):
        xyz = np.stack([r * np.cos(pitch) * np.cos(yaw), r * np.cos(pitch) * np.sin(yaw), r * np.sin(pitch)], axis=-1)
    if organize:
        xyz[~inside] = math.nan
        intensity = np.where(inside, intensity, math.nan)
        return xyz, intensity, ring, azimuth
    return xyz[inside], intensity[inside], ring[inside], azimuth[inside]


def velodyne_cloud(stamp, frame_id, xyz, intensity, ring, layout, organize=False, layers=1):
    """The PointCloud2 of velodyne_points' arrays in `layout` (LAYOUT_1_0_9 or LAYOUT_1_0_11)."""
    step, fields, at_intensity, at_ring, at_time = layout
    n = len(xyz)
    buf = np.zeros((n, step), dtype=np.uint8)
    buf[:, 0:12] = np.ascontiguousarray(xyz, dtype='<f4').view(np.uint8).reshape(n, 12)
    buf[:, at_intensity:at_intensity + 4] = np.ascontiguousarray(intensity, dtype='<f4').view(np.uint8).reshape(n, 4)
    buf[:, at_ring:at_ring + 2] = np.ascontiguousarray(ring, dtype='<u2').view(np.uint8).reshape(n, 2)
    # the time field (at_time) stays 0.0: upstream writes 0 for every point
    msg = PointCloud2(header=header(stamp, frame_id), fields=list(fields), is_bigendian=False, point_step=step,
                      data=buf.tobytes())
    if organize:
        msg.width = layers
        msg.height = n // layers
        msg.row_step = step * layers
        msg.is_dense = False
    else:
        msg.width, msg.height, msg.row_step, msg.is_dense = n, 1, n * step, True
    return msg


class VelodyneLaser(Sensor, libraries=('libgazebo_ros_velodyne_laser.so',), sensor_types=('ray',),
                    kind=SensorKind.VELODYNE, main_topic='points', block='ray', topic_param='topicName'):
    """velodyne_gazebo_plugins' GazeboRosVelodyneLaser: sensor_msgs/PointCloud2 of the scan."""

    @classmethod
    def load(cls, config, sdf):
        """As GazeboRosVelodyneLaser::Load reads the plugin."""
        params, what, warnings = sdf.params, sdf.what, config.warnings
        text = sdf.own_namespace()
        robot_namespace = '/' if text is None else text
        ns = sdf.resolve(robot_namespace)
        topic = params.get('topicName')
        config.topics['points'] = join_topic(ns, '/points' if topic is None else topic)
        frame = params.get('frameName')
        config.params['frame_name'] = '/world' if frame is None else frame
        if robot_namespace == '/':
            config.params['velodyne_tf_prefix_param'] = ns.rstrip('/') + '/tf_prefix'
            config.params['prefix'] = ''
        else:
            config.params['prefix'] = robot_namespace
        config.frame_id = tf_resolve(config.params['prefix'].rstrip('/'), config.params['frame_name'])
        config.params['min_range'] = sdf.number('min_range', 0.0)
        config.params['max_range'] = sdf.number('max_range', math.inf)
        config.params['min_intensity'] = sdf.number('min_intensity', -math.inf)
        config.params['gaussian_noise'] = sdf.number('gaussianNoise', 0.0)
        organize = params.get('organize_cloud')
        config.params['layout'] = LAYOUT_1_0_9 if organize is None else LAYOUT_1_0_11
        flag = (organize or 'false').strip().lower()
        if flag not in TRUE + FALSE:
            warnings.append('%s: <organize_cloud> %r is not true or false; false it is' % (what, organize))
        config.params['organize_cloud'] = flag in TRUE
        if 'staticTopicName' in params and 'staticFrameName' in params:
            warnings.append('%s: <staticTopicName>/<staticFrameName> (a second cloud transformed through tf) are '
                            'not simulated; only %s is published' % (what, config.topics['points']))
        return config

    def __init__(self, manager, robot, spec, config, rng=None):
        super().__init__(manager, robot, spec, config)
        if 'velodyne_tf_prefix_param' in config.params:  # robotNamespace /: the tf_prefix parameter is the prefix
            prefix = str(manager.rospy.get_param(config.params['velodyne_tf_prefix_param'], '') or '')
            config.frame_id = tf_resolve(prefix.rstrip('/'), config.params['frame_name'])
        self.geometry = ScanGeometry(spec.ray)
        ray = spec.ray
        self.noise = make_noise(ray.noise_type, ray.noise_mean, ray.noise_stddev, manager.noise_enabled, rng=rng)
        sigma = config.params['gaussian_noise']
        self.plugin_noise = make_noise('gaussian', 0.0, sigma, manager.noise_enabled, rng=rng) \
            if sigma != 0.0 else None
        self.advertise('points', PointCloud2, 1)

    def scan(self):
        """(ranges, intensities) as the RaySensor reports them."""
        position, orientation = self.mount.pose()
        starts, ends = self.geometry.endpoints(position, quaternion_to_matrix(orientation))
        fractions, hit, intensities = cast_with_retro(self.sim.world, starts, ends)
        return self.geometry.report(self.geometry.ranges_from_hits(fractions, hit), self.noise), intensities

    def update(self, time, stamp):
        if not self.listened():
            return
        ranges, intensities = self.scan()
        p = self.config.params
        xyz, intensity, ring, _ = velodyne_points(ranges, intensities, self.spec.ray, p['min_range'], p['max_range'],
                                                  p['min_intensity'], self.plugin_noise, p['organize_cloud'])
        self.publishers['points'].publish(velodyne_cloud(stamp, self.config.frame_id, xyz, intensity, ring,
                                                         p['layout'], p['organize_cloud'],
                                                         self.geometry.vertical_count))
        self.meter.tick()
