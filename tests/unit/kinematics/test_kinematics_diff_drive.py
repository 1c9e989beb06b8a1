"""kinematics.diff_drive: gazebo_ros_diff_drive's (noetic-devel) wheel speeds, ramp and encoder odometry."""
import math

import pytest

from racebot_sim_bridge.kinematics import differential as dd


def test_wheel_speeds_turning_left_speeds_up_the_right_wheel():
    assert dd.wheel_speeds(0.3, 0.5, 0.4) == pytest.approx((0.2, 0.4))
    assert dd.wheel_speeds(0.0, -1.0, 0.5) == pytest.approx((0.25, -0.25))
    assert dd.base_twist(*dd.wheel_speeds(0.3, 0.5, 0.4), separation=0.4) == pytest.approx((0.3, 0.5))


def test_joint_and_rim_speeds_use_the_radius():
    assert dd.joint_velocity(0.3, 0.15) == pytest.approx(4.0)
    assert dd.rim_speed(4.0, 0.15) == pytest.approx(0.3)


def test_ramp_step_moves_by_the_measured_gap_at_most_acceleration_dt():
    # limited: gap 1.0 > 2 m/s^2 * 0.01 s
    assert dd.ramp_step(1.0, 0.0, 0.0, 2.0, 0.01) == pytest.approx(0.02)
    assert dd.ramp_step(-1.0, 0.0, 0.0, 2.0, 0.01) == pytest.approx(-0.02)
    # the move is the gap to the MEASURED speed, added to what was commanded (it can run ahead)
    assert dd.ramp_step(1.0, 0.995, 0.5, 2.0, 0.01) == pytest.approx(0.505)
    assert dd.ramp_step(0.2, 0.3, 0.5, 2.0, 0.01) == pytest.approx(0.48)


def test_ramped_speeds_without_limit_or_near_target_commands_the_target():
    assert dd.ramped_speeds((0.2, 0.4), (0.0, 0.0), (0.1, 0.1), 0.0, 0.01) == ((0.2, 0.4), (0.1, 0.1))
    # the right wheel within 0.01 m/s of its target: both get their targets, the ramp state is kept
    assert dd.ramped_speeds((0.2, 0.4), (0.0, 0.395), (0.1, 0.1), 1.0, 0.01) == ((0.2, 0.4), (0.1, 0.1))
    speeds, state = dd.ramped_speeds((0.2, 0.4), (0.0, 0.0), (0.0, 0.0), 1.0, 0.01)
    assert speeds == pytest.approx((0.01, 0.01)) and state == speeds


def test_ramp_ends_when_either_wheel_reaches_its_target():
    """Wheels that follow their command exactly, 2 m/s^2 at 100 Hz: both ramp by 0.02 m/s per update; the
    left reaches 0.2 m/s after 10 updates, and at the 11th both get their targets (the right jumps from
    0.2 to 0.4 m/s): upstream's "either wheel reached" test."""
    commanded, measured, history = (0.0, 0.0), (0.0, 0.0), []
    while measured != (0.2, 0.4):
        speeds, commanded = dd.ramped_speeds((0.2, 0.4), measured, commanded, 2.0, 0.01)
        measured = speeds
        history.append(speeds)
        assert len(history) < 100
    assert len(history) == 11
    assert history[9] == pytest.approx((0.2, 0.2))


def test_encoder_step_straight_and_on_the_spot():
    pose, (v, w) = dd.encoder_step((1.0, 2.0, math.pi / 2), 4.0, 4.0, 0.15, 0.34, 0.5)
    assert pose == pytest.approx((1.0, 2.15, math.pi / 2))
    assert (v, w) == pytest.approx((0.3, 0.0))
    pose, (v, w) = dd.encoder_step((0.0, 0.0, 0.0), -2.0, 2.0, 0.2, 0.4, 0.1)
    assert pose == pytest.approx((0.0, 0.0, 0.1))  # sdiff = 0.04 m, / 0.4 m
    assert (v, w) == pytest.approx((0.0, 1.0))


def test_encoder_step_uses_the_mid_step_heading_and_reports_an_unsigned_speed():
    pose, (v, w) = dd.encoder_step((0.0, 0.0, 0.0), 1.0, 3.0, 0.2, 0.5, 0.1)
    sl, sr = 0.01, 0.03
    heading = (sr - sl) / (2 * 0.5)
    assert pose == pytest.approx((0.02 * math.cos(heading), 0.02 * math.sin(heading), 0.04))
    assert (v, w) == pytest.approx((0.2, 0.4))
    _, (v, _) = dd.encoder_step((0.0, 0.0, 0.0), -4.0, -4.0, 0.15, 0.34, 0.5)
    assert v == pytest.approx(0.3)  # reversing: upstream's sqrt(dx^2 + dy^2) / dt


def test_encoder_integration_of_an_arc_matches_the_circle():
    """0.3 m/s, 0.5 rad/s for 2 s at 1 ms steps ends on the circle of radius 0.6 m."""
    separation, diameter = 0.4, 0.2
    left, right = (dd.joint_velocity(s, diameter) for s in dd.wheel_speeds(0.3, 0.5, separation))
    pose = (0.0, 0.0, 0.0)
    for _ in range(2000):
        pose, twist = dd.encoder_step(pose, left, right, diameter, separation, 0.001)
    r, theta = 0.6, 1.0
    assert pose == pytest.approx((r * math.sin(theta), r * (1 - math.cos(theta)), theta), abs=1e-6)
    assert twist == pytest.approx((0.3, 0.5))


def test_encoder_step_without_time_moves_nothing():
    assert dd.encoder_step((1.0, 2.0, 3.0), 5.0, 5.0, 0.15, 0.34, 0.0) == ((1.0, 2.0, 3.0), (0.0, 0.0))


def test_yaw_quaternion_and_covariance():
    assert dd.yaw_quaternion(math.pi / 2) == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)))
    cov = dd.pose_covariance()
    assert cov[0:36:7] == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
    assert sum(cov) == pytest.approx(3e12 + 2e-5 + 1e-3)
