"""gazebo_ros_block_laser on a real Simulator: PyBullet's rays against ray_world's wall, the PointCloud as
upstream's PutLaserData lays it out (layers from the lowest, corner rays interpolated, their mean angle)."""
import math

import numpy as np
import pytest

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_block_laser import block_cloud
from racebot_sim_bridge.description.urdf_model import RaySpec
from ray_world import WALL_RETRO, hits_wall, listen, make_world, on_wall, ray_sensor, run

PLUGIN = ('<plugin name="block" filename="libgazebo_ros_block_laser.so"><topicName>block_cloud</topicName>'
          '<frameName>sensor_link</frameName>%s</plugin>')
YAWS = [-0.2, -0.1, 0.0, 0.1, 0.2]
PITCHES = [-0.1, 0.0, 0.1]
RANGE_MAX = 4.0  # the ground is 4.5 m away along the lowest rays


def raw_range(yaw, pitch):
    """What Gazebo's LaserShape reads for the ray: the wall, else range max."""
    return on_wall(yaw, pitch)[3] if hits_wall(yaw) else RANGE_MAX


def world_with(tmp_path, extra='', horizontal=(5, 1, -0.2, 0.2), vertical=(3, 1, -0.1, 0.1), **kwargs):
    sensor = ray_sensor('block', PLUGIN % extra, horizontal, vertical, range_max=RANGE_MAX)
    return make_world(tmp_path, sensor, **kwargs)


def cloud(tmp_path, seconds=0.25, **kwargs):
    sim, fake, manager, robot = world_with(tmp_path, **kwargs)
    try:
        listen(fake, '/block_cloud')
        run(sim, seconds)
        return fake, fake.publishers['/block_cloud'].messages
    finally:
        sim.close()


def xyz(points):
    return np.array([(p.x, p.y, p.z) for p in points])


def test_points_layer_by_layer_at_the_corner_rays_mean_angle(tmp_path):
    fake, messages = cloud(tmp_path, params={'/tf_prefix': 'bot'})
    assert len(messages) == 3  # 10 Hz from t = 0: 0, 0.1, 0.2
    m = messages[-1]
    assert m.header.frame_id == 'bot/sensor_link'
    assert m.header.stamp.to_sec() == pytest.approx(0.2)
    assert len(m.points) == 15 and len(m.channels) == 1 and m.channels[0].name == ''
    expected, intensities = [], []
    for j, pitch in enumerate(PITCHES):          # layer after layer, the lowest first
        for i, yaw in enumerate(YAWS):
            r = raw_range(yaw, pitch)            # the point's own corner ray: no resolution, no mixing
            # upstream's angle: the mean of the corner rays (i, min(i + 1, 4)) on 4 steps
            y = 0.5 * (i + min(i + 1, 4)) * 0.4 / 4 - 0.2
            p = 0.5 * (j + min(j + 1, 2)) * 0.2 / 2 - 0.1
            expected.append((r * math.cos(p) * math.cos(y), r * math.cos(p) * math.sin(y), r * math.sin(p)))
            # intensity: the mean laser_retro of the four corners
            corners = [(i, j), (min(i + 1, 4), j), (i, min(j + 1, 2)), (min(i + 1, 4), min(j + 1, 2))]
            intensities.append(sum(WALL_RETRO if hits_wall(YAWS[a]) else 0.0 for a, _ in corners) / 4)
    assert xyz(m.points) == pytest.approx(np.array(expected), abs=1e-4)
    assert list(m.channels[0].values) == pytest.approx(intensities)
    # the first layer's hits (yaw 0, 0.1, 0.2 at pitch -0.1) are 2 m ahead as ranges, not as x: the points
    # lean half a step off their rays, as upstream's
    assert np.linalg.norm(xyz(m.points)[2]) == pytest.approx(on_wall(0.0, -0.1)[3], abs=1e-4)


def test_resolution_interpolates_between_rays(tmp_path):
    _, messages = cloud(tmp_path, horizontal=(3, 2, -0.2, 0.2), vertical=(2, 1, -0.05, 0.05), seconds=0.05)
    m = messages[-1]
    assert len(m.points) == 6 * 2
    ranges = np.linalg.norm(xyz(m.points), axis=1)
    r = [raw_range(yaw, -0.05) for yaw in (-0.2, 0.0, 0.2)]
    # b = i * 2 / 5: i=1 mixes rays 0 and 1 at 0.4, i=3 rays 1 and 2 at 0.2, i=5 is ray 2
    assert ranges[:6] == pytest.approx([r[0], 0.6 * r[0] + 0.4 * r[1], 0.2 * r[0] + 0.8 * r[1],
                                        0.8 * r[1] + 0.2 * r[2], 0.4 * r[1] + 0.6 * r[2], r[2]], abs=1e-4)
    yaws = np.arctan2(xyz(m.points)[:6, 1], xyz(m.points)[:6, 0])
    assert yaws == pytest.approx([-0.1, -0.1, -0.1, 0.1, 0.1, 0.2], abs=1e-6)


def test_one_vertical_sample_gives_nan_points_as_upstream(tmp_path):
    fake, messages = cloud(tmp_path, vertical=None, seconds=0.05)
    assert all(math.isnan(p.x) for p in messages[-1].points) and len(messages[-1].points) == 5
    assert [w for level, w in fake.logs if level == 'warn' and 'NaN point coordinates' in w]


def test_gaussian_noise_spares_points_at_range_max(tmp_path):
    _, messages = cloud(tmp_path, extra='<gaussianNoise>0.05</gaussianNoise>', params={'~sensors/noise': True},
                        seconds=0.05)
    m = messages[-1]
    points, values = xyz(m.points), np.array(m.channels[0].values)
    ranges = np.linalg.norm(points, axis=1)
    missed = [j * 5 + i for j in range(3) for i in range(5) if not hits_wall(YAWS[i])]
    assert ranges[missed] == pytest.approx(RANGE_MAX, abs=1e-5)     # no noise at range max
    hit = [k for k in range(15) if k not in missed]
    assert np.abs(ranges[hit] - 2.0).max() > 1e-3                    # noise on the others
    assert np.all(values != np.round(values))                         # and on every intensity


def test_nothing_published_without_a_subscriber_and_no_topic_no_sensor(tmp_path):
    sim, fake, manager, robot = world_with(tmp_path)
    try:
        run(sim, 0.2)
        assert fake.publishers['/block_cloud'].messages == []
    finally:
        sim.close()
    sensor = ray_sensor('block', PLUGIN.replace('block_cloud', ''), (5, 1, -0.2, 0.2), (3, 1, -0.1, 0.1))
    sim, fake, manager, robot = make_world(tmp_path, sensor)
    try:
        assert fake.publishers == {}
    finally:
        sim.close()


def test_block_cloud_ranges_beyond_the_band_are_infinite():
    ray = RaySpec(samples=2, min_angle=0.0, max_angle=0.0, vertical_samples=2, vertical_min_angle=0.0,
                  vertical_max_angle=0.0, range_min=0.5, range_max=3.0)
    _, ranges, intensity = block_cloud([0.2, 1.0, 3.5, 3.0], [1.0, 2.0, 3.0, 4.0], ray, 0.5, 3.0)
    assert list(ranges) == [-math.inf, 1.0, math.inf, 3.0]
    assert list(intensity) == [2.5, 3.0, 3.5, 4.0]
