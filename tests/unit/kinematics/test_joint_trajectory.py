"""joint_trajectory_controller's trajectory maths (kinematics/trajectory.py) against what
ros_controllers noetic-devel computes: spline orders, sampling bounds, dropping past points, replacement
with a bridge segment, tolerances and their parameter/goal layout. No ROS master."""
import math
from types import SimpleNamespace

import pytest

from racebot_sim_bridge.kinematics import trajectory as jt


def P(positions, t, velocities=(), accelerations=()):
    return jt.Point(list(positions), list(velocities), list(accelerations), t)


def test_linear_segment_with_positions_only():
    seg = jt.Segment.between(1.0, (0.0, None, None), 3.0, (2.0, None, None))
    assert seg.sample(2.0) == pytest.approx((1.0, 1.0, 0.0))
    # before the start: the start position at rest; after the end: the end position at rest
    assert seg.sample(0.0) == (0.0, 0.0, 0.0)
    assert seg.sample(5.0) == (pytest.approx(2.0), 0.0, 0.0)


def test_cubic_segment_meets_both_ends_positions_and_velocities():
    seg = jt.Segment.between(0.0, (1.0, 0.5, None), 2.0, (3.0, -0.25, None))
    p0, v0, _ = seg.sample(0.0)
    p1, v1, _ = seg.sample(2.0)
    assert (p0, v0) == pytest.approx((1.0, 0.5))
    assert (p1, v1) == pytest.approx((3.0, -0.25))


def test_quintic_segment_meets_accelerations_too():
    seg = jt.Segment.between(0.0, (0.0, 0.0, 1.0), 1.5, (1.0, 0.2, -0.5))
    assert seg.sample(0.0) == pytest.approx((0.0, 0.0, 1.0))
    assert seg.sample(1.5) == pytest.approx((1.0, 0.2, -0.5))
    # the midpoint of a rest-to-rest quintic is half way
    rest = jt.Segment.between(0.0, (0.0, 0.0, 0.0), 2.0, (4.0, 0.0, 0.0))
    assert rest.sample(1.0)[0] == pytest.approx(2.0)


def test_find_segment_and_sample_before_the_start():
    traj = [jt.Segment.between(0.0, (0.0, None, None), 1.0, (1.0, None, None)),
            jt.Segment.between(1.0, (1.0, None, None), 2.0, (3.0, None, None))]
    assert jt.find_segment(traj, -0.1) is None
    assert jt.find_segment(traj, 0.5) == 0
    assert jt.find_segment(traj, 1.0) == 1
    assert jt.find_segment(traj, 9.0) == 1
    assert jt.sample(traj, 1.5) == (1, pytest.approx((2.0, 2.0, 0.0)))
    assert jt.sample(traj, -1.0) == (None, (0.0, 0.0, 0.0))


def test_build_from_hold_bridges_the_current_state_to_the_first_point():
    hold = jt.hold_trajectory(0.0, [0.5, -0.5])
    traj = jt.build_trajectory(['a', 'b'], [P([1.0, 1.0], 1.0), P([2.0, 0.0], 3.0)], 0.0, 10.0, ['a', 'b'],
                               current=hold)
    # stamp 0: starts at the next update (10 s): the bridge from the held positions to point 1 at 11 s
    a = traj[0]
    assert [round(s.start_time, 9) for s in a] == [0.0, 10.0, 11.0]
    assert jt.sample(a, 10.0)[1][0] == pytest.approx(0.5)
    assert jt.sample(a, 11.0)[1][0] == pytest.approx(1.0)
    assert jt.sample(a, 13.0)[1][0] == pytest.approx(2.0)
    assert jt.sample(traj[1], 13.0)[1][0] == pytest.approx(0.0)


def test_joints_in_another_order_are_mapped_by_name():
    hold = jt.hold_trajectory(0.0, [0.0, 0.0])
    traj = jt.build_trajectory(['b', 'a'], [P([2.0, 1.0], 1.0)], 0.0, 0.0, ['a', 'b'], current=hold)
    assert jt.sample(traj[0], 1.0)[1][0] == pytest.approx(1.0)
    assert jt.sample(traj[1], 1.0)[1][0] == pytest.approx(2.0)


def test_points_in_the_past_are_dropped_and_all_past_is_an_error():
    hold = jt.hold_trajectory(0.0, [0.0])
    # stamped at 5 s, now 6.5 s: the point at 1 s (6 s) is past, the one at 2 s (7 s) is next
    traj = jt.build_trajectory(['a'], [P([1.0], 1.0), P([2.0], 2.0), P([3.0], 3.0)], 5.0, 6.5, ['a'], current=hold)
    assert jt.sample(traj[0], 7.0)[1][0] == pytest.approx(2.0)
    assert traj[0][-1].end_time == pytest.approx(8.0)
    with pytest.raises(jt.TrajectoryError, match='Dropping all 2 trajectory point'):
        jt.build_trajectory(['a'], [P([1.0], 1.0), P([2.0], 2.0)], 1.0, 6.5, ['a'], current=hold)


@pytest.mark.parametrize('names, points, message', [
    (['a'], [], 'empty trajectory'),
    (['a'], [P([1.0], 2.0), P([2.0], 2.0)], 'not strictly increasing'),
    (['a', 'x'], [P([1.0, 1.0], 1.0)], 'does not contain the expected joints'),
    (['a'], [P([1.0], 1.0)], 'does not contain the expected joints'),  # partial, not allowed
    (['a', 'b'], [P([1.0], 1.0)], 'Size mismatch'),
    (['a', 'b'], [P([1.0, float('nan')], 1.0)], 'not finite'),
])
def test_bad_messages_get_upstream_errors(names, points, message):
    with pytest.raises(jt.TrajectoryError, match=message):
        jt.build_trajectory(names, points, 0.0, 0.0, ['a', 'b'], current=jt.hold_trajectory(0.0, [0.0, 0.0]))


def test_partial_goal_keeps_the_other_joint_trajectory_when_allowed():
    hold = jt.hold_trajectory(0.0, [0.0, 0.7])
    traj = jt.build_trajectory(['a'], [P([1.0], 1.0)], 0.0, 0.0, ['a', 'b'], current=hold, allow_partial=True)
    assert jt.sample(traj[0], 1.0)[1][0] == pytest.approx(1.0)
    assert jt.sample(traj[1], 1.0)[1][0] == pytest.approx(0.7)


def test_replacement_while_moving_starts_from_where_the_old_one_is_then():
    old = jt.build_trajectory(['a'], [P([4.0], 4.0)], 0.0, 0.0, ['a'], current=jt.hold_trajectory(0.0, [0.0]))
    # at 2 s the old trajectory is at 2.0 (linear 0 -> 4 over 4 s); a new one to -1 at 1 s from now
    new = jt.build_trajectory(['a'], [P([-1.0], 1.0)], 0.0, 2.0, ['a'], current=old)
    assert jt.sample(new[0], 2.0)[1][0] == pytest.approx(2.0)
    assert jt.sample(new[0], 3.0)[1][0] == pytest.approx(-1.0)
    assert jt.sample(new[0], 9.0)[1][0] == pytest.approx(-1.0)
    # a future start keeps the old trajectory running until then
    later = jt.build_trajectory(['a'], [P([-1.0], 1.0)], 3.0, 2.0, ['a'], current=old)
    assert jt.sample(later[0], 2.5)[1][0] == pytest.approx(2.5)
    assert jt.sample(later[0], 4.0)[1][0] == pytest.approx(-1.0)


def test_continuous_joints_go_the_short_way_round():
    hold = jt.hold_trajectory(0.0, [3.0])
    traj = jt.build_trajectory(['a'], [P([-3.0], 1.0)], 0.0, 0.0, ['a'], current=hold, wraps=[True])
    end = jt.sample(traj[0], 1.0)[1][0]
    assert end == pytest.approx(-3.0 + 2 * math.pi)
    assert jt.wraparound_offset(3.0, -3.0, False) == 0.0


def test_stop_trajectory_comes_to_rest_in_its_duration():
    traj = jt.stop_trajectory(0.0, [1.0], [0.5], 0.2)
    p, v, _ = jt.sample(traj[0], 0.2)[1]
    assert v == pytest.approx(0.0, abs=1e-9)
    assert 1.0 < p < 1.1
    assert jt.sample(traj[0], 0.0)[1][:2] == pytest.approx((1.0, 0.5))


def test_tolerances_from_parameters_as_upstream_lays_them_out():
    tol = jt.tolerances_from_params({'goal_time': 0.5, 'stopped_velocity_tolerance': 0.02,
                                     'a': {'trajectory': 0.1, 'goal': 0.01}}, ['a', 'b'])
    assert tol[0] == jt.JointTolerances(jt.StateTolerance(0.1), jt.StateTolerance(0.01, 0.02), 0.5)
    assert tol[1] == jt.JointTolerances(jt.StateTolerance(0.0), jt.StateTolerance(0.0, 0.02), 0.5)
    assert jt.tolerances_from_params(None, ['a'])[0].goal.velocity == 0.01  # upstream's default
    with pytest.raises(jt.TrajectoryError, match='goal_time'):
        jt.tolerances_from_params({'goal_time': 'soon'}, ['a'])


def test_goal_tolerances_replace_clear_or_keep():
    defaults = jt.tolerances_from_params({'goal_time': 0.5, 'a': {'trajectory': 0.1, 'goal': 0.01}}, ['a'])
    jtol = lambda name, p, v=0.0, a=0.0: SimpleNamespace(name=name, position=p, velocity=v, acceleration=a)
    out = jt.tolerances_from_goal(defaults, ['a'], [jtol('a', -1.0)], [jtol('a', 0.05), jtol('other', 9.0)], 2.0)
    assert out[0].path.position == 0.0     # negative: cleared
    assert out[0].goal.position == 0.05    # positive: replaced
    assert out[0].goal.velocity == 0.01    # 0: kept
    assert out[0].goal_time == 2.0
    assert jt.tolerances_from_goal(defaults, ['a'], [], [], -1.0)[0].goal_time == 0.0


def test_state_tolerance_checks_only_nonzero_bounds():
    tol = jt.StateTolerance(position=0.1, velocity=0.0)
    assert tol.holds((0.05, 100.0, 0.0))
    assert not tol.holds((-0.2, 0.0, 0.0))
    assert jt.StateTolerance().holds((1e9, 1e9, 1e9))
