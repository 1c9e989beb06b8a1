"""hector_gazebo_plugins' GazeboRosSonar on a real Simulator: PyBullet's rays against ray_world's wall, the Range
as Update() makes it on hector's UpdateTimer, through its SensorModel."""
import pytest

from model_plugin_sim import Reconfigure
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_sonar import sonar_reading, timer_due
from ray_world import WALL_X, make_world, ray_sensor, run


def plugin(extra=''):
    return '<plugin name="sonar" filename="libhector_gazebo_ros_sonar.so">%s</plugin>' % extra


class Servers(dict):
    def __call__(self, namespace, config_type, callback):
        server = self[namespace] = Reconfigure(config_type, callback)
        return server


def sonar_world(tmp_path, extra='', vertical=(3, 1, -0.05, 0.05), namespace='/', rate=5, **kwargs):
    servers = Servers()
    tmp_path.mkdir(parents=True, exist_ok=True)
    sensor = ray_sensor('sonar', plugin(extra), (3, 1, -0.1, 0.1), vertical, rate=rate, range_min=0.05,
                        range_max=4.0)
    sim, fake, manager, robot = make_world(tmp_path, sensor, namespace=namespace, reconfigure=servers, **kwargs)
    return sim, fake, servers


def readings(tmp_path, seconds=0.35, topic='/sonar', **kwargs):
    sim, fake, servers = sonar_world(tmp_path, **kwargs)
    try:
        run(sim, seconds)  # nobody subscribes: hector publishes all the same
        return fake.publishers[topic].messages
    finally:
        sim.close()


def test_shortest_ray_at_ten_hertz_on_the_world_clock(tmp_path):
    messages = readings(tmp_path)
    # hector's UpdateTimer at 10 Hz, whatever the sensor's <update_rate> (5 here)
    assert [round(m.header.stamp.to_sec(), 3) for m in messages] == [0.1, 0.2, 0.3]
    m = messages[-1]
    assert m.header.frame_id == '/sonar_link' and m.radiation_type == m.ULTRASOUND
    assert m.field_of_view == pytest.approx(0.1)  # min(0.2 horizontal, 0.1 vertical)
    assert (m.min_range, m.max_range) == pytest.approx((0.05, 4.0))
    assert m.range == pytest.approx(WALL_X, abs=1e-5)  # the middle ray, straight at the wall


def test_no_vertical_angles_is_a_zero_field_of_view(tmp_path):
    m = readings(tmp_path, vertical=None, seconds=0.1)[-1]
    assert m.field_of_view == 0.0 and m.range == pytest.approx(WALL_X, abs=1e-5)


def test_error_model_and_clamping(tmp_path):
    assert readings(tmp_path / 'a', extra='<offset>0.5</offset>', seconds=0.1)[-1].range == pytest.approx(2.5, abs=1e-5)
    assert readings(tmp_path / 'b', extra='<scaleError>3</scaleError>', seconds=0.1)[-1].range == 4.0
    assert readings(tmp_path / 'c', extra='<offset>-3</offset>', seconds=0.1)[-1].range == pytest.approx(0.05)
    noisy = readings(tmp_path / 'd', extra='<gaussianNoise>0.1</gaussianNoise>', params={'~sensors/noise': True})
    assert len({m.range for m in noisy}) == 3 and all(abs(m.range - WALL_X) < 0.6 for m in noisy)
    quiet = readings(tmp_path / 'e', extra='<gaussianNoise>0.1</gaussianNoise>')  # ~sensors/noise false
    assert all(m.range == pytest.approx(WALL_X, abs=1e-5) for m in quiet)


def test_nothing_ahead_reads_range_max_without_the_model(tmp_path):
    sim, fake, servers = sonar_world(tmp_path, extra='<offset>-0.5</offset>')
    try:
        sim.world.remove('wall')
        run(sim, 0.1)
        assert fake.publishers['/sonar'].messages[-1].range == 4.0
    finally:
        sim.close()


def test_parameters_rate_namespace_frame_and_the_reconfigure_server(tmp_path):
    sim, fake, servers = sonar_world(tmp_path, extra='<topicName>front</topicName><frameId>front_sonar</frameId>'
                                     '<updateRate>20</updateRate>', namespace='/fleet')
    try:
        run(sim, 0.1)
        messages = fake.publishers['/fleet/front'].messages
        assert [round(m.header.stamp.to_sec(), 3) for m in messages] == [0.05, 0.1]
        assert messages[-1].header.frame_id == 'front_sonar'
        assert servers['/fleet/front'].config['offset'] == 0.0
        servers['/fleet/front'].change(offset=0.25)  # dynamic_reconfigure: the model's offset
        run(sim, 0.05)
        assert fake.publishers['/fleet/front'].messages[-1].range == pytest.approx(WALL_X + 0.25, abs=1e-5)
    finally:
        sim.close()


def test_frame_name_is_not_hectors_parameter(tmp_path):
    sim, fake, servers = sonar_world(tmp_path, extra='<frameName>sonar_link</frameName>')
    try:
        run(sim, 0.1)
        assert fake.publishers['/sonar'].messages[-1].header.frame_id == '/sonar_link'
        assert [w for level, w in fake.logs if level == 'warn' and 'reads <frameId>' in w]
    finally:
        sim.close()


def test_timer_and_reading_as_hector_computes_them():
    assert timer_due(0.1, 0.1, 0.0, 0.001) and timer_due(0.2, 0.1, 0.0, 0.001)
    assert not timer_due(0.101, 0.1, 0.0, 0.001) and not timer_due(0.099, 0.1, 0.0, 0.001)
    assert timer_due(0.125, 0.1, 0.025, 0.001) and timer_due(0.013, 0.0, 0.0, 0.001)
    assert sonar_reading([3.0, 1.5, 4.0], 0.05, 4.0) == 1.5
    assert sonar_reading([4.0, 4.0], 0.05, 4.0) == 4.0
