"""What the drive, p3d and joint_state_publisher plugins share: their update clocks (Gazebo's whole
nanoseconds), tf::resolve and tf_prefix, their namespaces (plugin_namespace), a point's velocity."""
import copy

import pytest

from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.link_motion import point_velocity
from racebot_sim_bridge.gazebo_plugins.odometry_output import tf_prefix, tf_resolve
from racebot_sim_bridge.gazebo_plugins.update_timing import AtLeastPeriod, FixedPeriod, SincePublished
from racebot_sim_bridge.engine.sim_time import to_ns

STEP = 0.001


def due_times(clock, seconds, start=0.0):
    times = []
    for i in range(1, int(round(seconds / STEP)) + 1):
        t = start + i * STEP
        result = clock.due(t) if not isinstance(clock, AtLeastPeriod) else clock.since(t) is not None
        if isinstance(result, tuple):
            result = result[0]
        if result:
            if isinstance(clock, AtLeastPeriod):
                clock.mark(t)
            times.append(round(t, 6))
    return times


def test_fixed_period_keeps_the_rate_exactly():
    # skid_steer_drive / joint_state_publisher at 100 Hz: first when 11 ms passed, then every 10 ms
    assert due_times(FixedPeriod(100.0, 0.0), 0.05) == [0.011, 0.021, 0.031, 0.041]
    assert len(due_times(FixedPeriod(0.0, 0.0), 0.01)) == 10  # rate 0: every world update
    assert len(due_times(FixedPeriod(-5.0, 0.0), 0.01)) == 10


def test_since_published_drifts_by_one_step_per_period():
    # planar_move's odometry at 20 Hz: more than 50 ms since the last, which becomes now: every 51 ms
    assert due_times(SincePublished(20.0, 0.0), 0.2) == [0.051, 0.102, 0.153]
    clock = SincePublished(20.0, 0.0)
    for i in range(1, 51):
        assert clock.due(i * STEP) == (False, pytest.approx(i * STEP))
    assert clock.due(0.051) == (True, pytest.approx(0.051))


def test_at_least_period_publishes_on_the_period():
    assert due_times(AtLeastPeriod(50.0, 0.0), 0.1) == [0.02, 0.04, 0.06, 0.08, 0.1]
    assert len(due_times(AtLeastPeriod(0.0, 0.0), 0.01)) == 10


@pytest.mark.parametrize('make', [FixedPeriod, SincePublished, AtLeastPeriod])
@pytest.mark.parametrize('rate, step', [(50.0, 0.001), (100.0, 0.001), (30.0, 0.001), (1000.0, 0.001), (7.0, 0.0003),
                                        (0.0, 0.001)])
def test_quiet_never_hides_a_due_update_and_ends_where_one_is_due(make, rate, step):
    # the plugins' shortcut (clock.quiet, inline in diff drive and imu) skips due()/since() only where neither fires,
    # and everywhere else one does: PluginManager calls a plugin past its quiet span for an update, never in vain
    clock, times, skipped = make(rate, 0.0), [], 0
    for i in range(1, 3000):
        t = i * step
        if clock.quiet(to_ns(t)):
            skipped += 1
            probe = copy.copy(clock)
            due = probe.since(t) is not None if make is AtLeastPeriod else probe.due(t)
            assert not (due[0] if isinstance(due, tuple) else due), (t, clock.last)
            continue
        due = clock.since(t) is not None if make is AtLeastPeriod else clock.due(t)
        assert (due[0] if isinstance(due, tuple) else due), (t, clock.last)
        if make is AtLeastPeriod:
            clock.mark(t)
        times.append(t)
    if rate and rate * step < 0.5:
        assert skipped > 0
    if not rate:  # every update
        assert skipped == 0
    assert not clock.quiet(clock.last - 1)  # time gone back: due() / since() restart the clock


def test_time_going_back_restarts_the_clock():
    clock = FixedPeriod(100.0, 5.0)
    assert not clock.due(0.001)  # reset_simulation: time back near 0
    assert due_times(clock, 0.03, start=0.001) == [0.012, 0.022]


@pytest.mark.parametrize('prefix, frame, expected', [
    ('', 'odom', 'odom'), ('', '/odom', 'odom'), ('robot1', 'odom', 'robot1/odom'),
    ('/robot1', 'odom', 'robot1/odom'), ('robot1', '/odom', 'odom'), ('', '//odom', '/odom')])
def test_tf_resolve(prefix, frame, expected):
    assert tf_resolve(prefix, frame) == expected


class Params:
    def __init__(self, values):
        self.values = values

    def has_param(self, name):
        return name in self.values

    def get_param(self, name):
        return self.values[name]


def test_tf_prefix_is_searched_upwards_from_the_namespace():
    params = Params({'/fleet/tf_prefix': 'f', '/tf_prefix': 'root'})
    assert tf_prefix(params, '/fleet/robot1') == 'f'
    assert tf_prefix(params, '/other') == 'root'
    assert tf_prefix(params, '/fleet/robot1', search=False) == ''  # p3d: getParam in its own namespace only
    assert tf_prefix(params, '/fleet', search=False) == 'f'
    assert tf_prefix(Params({}), '/a/b') == ''


@pytest.mark.parametrize('kind, own, requested, expected', [
    ('drive', None, '/', '/'), ('drive', None, '', '/'), ('drive', None, '/skid', '/skid'),
    ('drive', 'mine', '/skid', '/mine'), ('drive', '', '/skid', '/'),
    ('planar_move', 'planar', '/', '/planar'), ('planar_move', None, '', '/'),
    ('joint_state_publisher', None, '', '/bot'), ('joint_state_publisher', '', '/x', '/bot'),
    ('joint_state_publisher', None, '/', '/'), ('joint_state_publisher', 'js', '/', '/js')])
def test_model_plugin_namespaces(kind, own, requested, expected):
    assert model_plugin_namespace(kind, own, requested, 'bot') == expected


def test_relative_namespaces_resolve_in_the_world_servers():
    assert model_plugin_namespace('drive', 'skid', '', 'bot', '/sim') == '/sim/skid'


@pytest.mark.parametrize('ns, name, expected', [
    ('/', 'odom', '/odom'), ('/skid', 'odom', '/skid/odom'), ('/skid', '/odom', '/odom'),
    ('/skid', 'ground_truth/state', '/skid/ground_truth/state')])
def test_name_in(ns, name, expected):
    assert name_in(ns, name) == expected


def test_point_velocity_adds_the_turn_about_the_centre_of_mass():
    # turning at 2 rad/s about z, a point 0.5 m ahead of the centre of mass moves 1 m/s to the left
    assert point_velocity((0.1, 0.0, 0.0), (0.0, 0.0, 2.0), (1.0, 1.0, 0.0), (1.5, 1.0, 0.0)) == \
        pytest.approx((0.1, 1.0, 0.0))
