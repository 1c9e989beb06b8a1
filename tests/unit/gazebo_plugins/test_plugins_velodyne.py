"""velodyne_gazebo_plugins' GazeboRosVelodyneLaser on a real Simulator: PyBullet's rays against ray_world's wall,
the PointCloud2 as OnScan lays it out (1.0.9's 32-byte points without <organize_cloud>, 1.0.11's 22-byte ones
with it), out-of-band readings dropped, ring numbering, frames."""
import math

import numpy as np
import pytest
from sensor_msgs import point_cloud2

from ray_world import WALL_RETRO, hits_wall, listen, make_world, on_wall, ray_sensor, run

YAWS = list(np.arange(8) * 0.6 / 7 - 0.3)
PITCHES = [-0.1, -0.1 + 0.2 / 3, 0.1 - 0.2 / 3, 0.1]


def plugin(extra='', topic='/velodyne_points', filename='libgazebo_ros_velodyne_laser.so'):
    return ('<plugin name="velodyne" filename="%s"><topicName>%s</topicName><frameName>velodyne</frameName>'
            '<min_range>0.2</min_range><max_range>4.5</max_range>%s</plugin>' % (filename, topic, extra))


def cloud(tmp_path, extra='', seconds=0.05, topic='/velodyne_points', namespace='/', kind='ray',
          filename='libgazebo_ros_velodyne_laser.so', **kwargs):
    sensor = ray_sensor('vlp', plugin(extra, topic, filename), (8, 1, -0.3, 0.3), (4, 1, -0.1, 0.1),
                        range_max=4.0, kind=kind)
    sim, fake, manager, robot = make_world(tmp_path, sensor, namespace=namespace, **kwargs)
    try:
        if topic:
            listen(fake, *fake.publishers)
        run(sim, seconds)
        return fake, {t: p.messages for t, p in fake.publishers.items()}
    finally:
        sim.close()


def points(msg, fields=('x', 'y', 'z', 'intensity', 'ring')):
    return list(point_cloud2.read_points(msg, field_names=fields))


def test_the_pinned_1_0_9_layout_azimuth_after_azimuth_rings_from_the_lowest(tmp_path):
    fake, published = cloud(tmp_path, params={'/tf_prefix': 'bot/'})
    m = published['/velodyne_points'][-1]
    assert m.header.frame_id == 'bot/velodyne'  # tf_prefix (trailing slash trimmed) as robotNamespace is /
    assert [(f.name, f.offset, f.datatype, f.count) for f in m.fields] == [
        ('x', 0, 7, 1), ('y', 4, 7, 1), ('z', 8, 7, 1), ('intensity', 16, 7, 1), ('ring', 20, 4, 1)]
    expected = [(i, j) for i, yaw in enumerate(YAWS) for j in range(4) if hits_wall(yaw)]
    assert len(expected) == 16  # the 4 azimuths to the right of the wall's edge miss (+inf): dropped
    assert (m.height, m.width, m.point_step, m.row_step, m.is_dense, m.is_bigendian) == (1, 16, 32, 512, True, False)
    assert len(m.data) == 512
    got = points(m)
    for (i, j), p in zip(expected, got):
        x, y, z, _ = on_wall(YAWS[i], PITCHES[j])
        assert p[:3] == pytest.approx((x, y, z), abs=1e-4)
        assert p[3] == WALL_RETRO and p[4] == j
    assert max(p[4] for p in got) == 3


def test_organize_cloud_the_1_0_11_layout_with_time_and_nan_placeholders(tmp_path):
    _, published = cloud(tmp_path, extra='<organize_cloud>true</organize_cloud>')
    m = published['/velodyne_points'][-1]
    assert [(f.name, f.offset, f.datatype) for f in m.fields] == [
        ('x', 0, 7), ('y', 4, 7), ('z', 8, 7), ('intensity', 12, 7), ('ring', 16, 4), ('time', 18, 7)]
    assert (m.height, m.width, m.point_step, m.row_step, m.is_dense) == (8, 4, 22, 88, False)
    assert len(m.data) == 8 * 4 * 22
    got = points(m, ('x', 'y', 'z', 'intensity', 'ring', 'time'))
    for k, p in enumerate(got):
        i, j = divmod(k, 4)
        assert p[4] == j and p[5] == 0.0
        if hits_wall(YAWS[i]):
            assert p[:3] == pytest.approx(on_wall(YAWS[i], PITCHES[j])[:3], abs=1e-4) and p[3] == WALL_RETRO
        else:
            assert all(math.isnan(v) for v in p[:4])


def test_organize_cloud_false_is_the_1_0_11_layout_unorganized(tmp_path):
    _, published = cloud(tmp_path, extra='<organize_cloud>false</organize_cloud>')
    m = published['/velodyne_points'][-1]
    assert (m.height, m.width, m.point_step, m.row_step, m.is_dense) == (1, 16, 22, 16 * 22, True)
    assert [f.name for f in m.fields] == ['x', 'y', 'z', 'intensity', 'ring', 'time']


def last_cloud(folder, plugin_text):
    folder.mkdir()
    sensor = ray_sensor('vlp', plugin_text, (8, 1, -0.3, 0.3), (4, 1, -0.1, 0.1), range_max=4.0)
    sim, fake, manager, robot = make_world(folder, sensor)
    try:
        listen(fake, '/velodyne_points')
        run(sim, 0.05)
        return fake.publishers['/velodyne_points'].messages[-1]
    finally:
        sim.close()


def test_max_range_min_range_and_min_intensity_drop_points(tmp_path):
    # the plugin's max_range below the sensor's: readings at or beyond 2.05 m go
    kept = points(last_cloud(tmp_path / 'near', plugin().replace('4.5', '2.05')))
    expected = [(i, j) for i, yaw in enumerate(YAWS) for j in range(4)
                if hits_wall(yaw) and on_wall(yaw, PITCHES[j])[3] < 2.05]
    assert 0 < len(expected) < 16 and [int(p[4]) for p in kept] == [j for _, j in expected]
    # min_range beyond the wall, min_intensity above the wall's retro: nothing left
    assert last_cloud(tmp_path / 'far', plugin().replace('<min_range>0.2', '<min_range>3.0')).width == 0
    assert last_cloud(tmp_path / 'dim', plugin('<min_intensity>250</min_intensity>')).width == 0
    assert last_cloud(tmp_path / 'bright', plugin('<min_intensity>200</min_intensity>')).width == 16


def test_namespace_is_the_frame_prefix_and_topics_resolve_in_it(tmp_path):
    _, published = cloud(tmp_path, topic='points', namespace='/fleet', params={'/fleet/tf_prefix': 'ignored'})
    m = published['/fleet/points'][-1]
    assert m.header.frame_id == 'fleet/velodyne' and m.width == 16


def test_gaussian_noise_moves_points_along_their_rays(tmp_path):
    _, published = cloud(tmp_path, extra='<gaussianNoise>0.05</gaussianNoise>', params={'~sensors/noise': True})
    got = np.array([p[:3] for p in points(published['/velodyne_points'][-1])])
    assert len(got) == 16 and np.abs(got[:, 0] - 2.0).max() > 1e-3
    # noise on the range, not per axis: every point stays on its ray (y / x is the yaw's tangent)
    hit_yaws = [yaw for yaw in YAWS for _ in range(4) if hits_wall(yaw)]
    assert got[:, 1] / got[:, 0] == pytest.approx(np.tan(hit_yaws), abs=1e-5)


def test_gpu_variant_in_a_gpu_ray_sensor_and_each_refused_in_the_other(tmp_path):
    _, published = cloud(tmp_path, kind='gpu_ray', filename='libgazebo_ros_velodyne_gpu_laser.so')
    assert published['/velodyne_points'][-1].width == 16
    (tmp_path / 'refused').mkdir()
    fake, published = cloud(tmp_path / 'refused', kind='gpu_ray')
    assert published == {}
    assert [w for level, w in fake.logs if level == 'warn' and "of type 'gpu_ray' (expected ray)" in w]
