"""Wheel odometry of the Ackermann car (kinematic bicycle model) and the body-frame twist of the
ground truth; pure maths, no master."""
import math

import pytest

from racebot_gazebo.odometry import (REAR_AXLE_X, WHEEL_RADIUS, WHEELBASE, WheelSpeedOdometry, rotate_back,
                                     yaw_quaternion)
from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion


def drive(odo, seconds, wheel_speed, steering, dt=0.02, start=0.0):
    t = start
    for _ in range(int(round(seconds / dt)) + 1):
        odo.update(t, [wheel_speed, wheel_speed], [steering, steering])
        t += dt
    return t


def test_model_defaults_are_the_racebots():
    assert (WHEEL_RADIUS, WHEELBASE, REAR_AXLE_X) == (0.032, 0.26, -0.13)


def test_straight_drive():
    odo = WheelSpeedOdometry()
    drive(odo, 5.0, 10.0, 0.0)  # 10 rad/s x 0.032 m = 0.32 m/s for 5 s
    x, y, yaw = odo.pose
    assert x == pytest.approx(1.6, rel=1e-9) and y == pytest.approx(0.0) and yaw == pytest.approx(0.0)
    assert odo.twist == pytest.approx((0.32, 0.0, 0.0))
    assert odo.distance == pytest.approx(1.6)


def test_full_circle_closes_with_the_bicycle_radius():
    odo = WheelSpeedOdometry()
    delta = 0.3
    radius = WHEELBASE / math.tan(delta)  # of the rear axle centre
    v = 10.0 * WHEEL_RADIUS
    t = drive(odo, 2 * math.pi * radius / v, 10.0, delta, dt=0.001)
    x, y, yaw = odo.pose
    assert math.hypot(x, y) < 0.005 and abs(math.sin(yaw)) < 0.01
    drive(odo, math.pi * radius / v, 10.0, delta, dt=0.001, start=t)  # half way on: the rear axle at 2R in y
    x, y, yaw = odo.pose
    rear_y = y - (-REAR_AXLE_X) * math.sin(yaw)
    assert rear_y == pytest.approx(2 * radius, rel=0.01)
    vx, vy, wz = odo.twist
    assert wz == pytest.approx(v * math.tan(delta) / WHEELBASE) and vy == pytest.approx(wz * 0.13)


def test_time_going_back_does_not_move_and_reset_starts_over():
    odo = WheelSpeedOdometry()
    drive(odo, 1.0, 10.0, 0.0)
    x = odo.pose[0]
    odo.update(0.5, [10.0, 10.0], [0.0, 0.0])
    assert odo.pose[0] == x
    odo.reset(1.0, 2.0, math.pi / 2)
    assert odo.pose == pytest.approx((1.0, 2.0, math.pi / 2))
    with pytest.raises(ValueError):
        WheelSpeedOdometry(wheel_radius=0)


def test_quaternion_helpers_the_nodes_use():
    q = yaw_quaternion(1.2)  # wheel odometry's orientation
    assert q == pytest.approx((0.0, 0.0, math.sin(0.6), math.cos(0.6)))
    assert q == pytest.approx(rpy_to_quaternion(0.0, 0.0, 1.2))
    # ground truth's twist: a world velocity along +y seen from a body facing +y is straight ahead
    assert rotate_back(yaw_quaternion(math.pi / 2), (0.0, 2.0, 0.0)) == pytest.approx((2.0, 0.0, 0.0))
    # the inverse of an arbitrary turn, as the simulator's own maths has it
    q = rpy_to_quaternion(0.3, -0.7, 2.1)
    assert rotate_back(q, (0.4, -1.5, 2.2)) == pytest.approx(rotations.rotate_back(q, (0.4, -1.5, 2.2)), abs=1e-12)


def _published(ticks, arrivals):
    return [t for t in arrivals if ticks.due(t)]


def test_ground_truth_ticks_hold_the_rate_when_the_stream_comes_late():
    from racebot_gazebo.odometry import SimTimeTicks
    ticks = SimTimeTicks(20.0)
    # link_states every 1 ms of sim time, but a loaded machine delivers none from 1.00 to 1.33 s
    arrivals = [i / 1000.0 for i in range(0, 3001) if not 1000 < i < 1330]
    stamps = _published(ticks, arrivals)
    assert len(stamps) == 61  # as many as 0, 0.05, ..., 3.0: the ticks due in the gap come on arrival, one each
    assert sum(1 for t in stamps if 1.33 <= t < 1.34) == 7  # those due from 1.0 to 1.3 s


def test_ground_truth_ticks_start_again_after_a_stall_or_a_reset():
    from racebot_gazebo.odometry import SimTimeTicks
    ticks = SimTimeTicks(20.0)
    assert _published(ticks, [0.0, 0.01, 0.05]) == [0.0, 0.05]
    assert ticks.due(5.0) and not ticks.due(5.001)  # 5 s without a message: no burst of 100
    assert ticks.due(0.2) and not ticks.due(0.21)   # time went back (a world reset)
    every = SimTimeTicks(0.0)
    assert _published(every, [0.0, 0.001, 0.002]) == [0.0, 0.001, 0.002]


def test_ground_truth_ticks_never_stamp_two_messages_alike():
    """Under load two link_states arrive within one clock tick while ticks are owed: one message per time, so tf
    never sees one transform twice (TF_REPEATED_DATA); the owed tick goes with the next later time."""
    from racebot_gazebo.odometry import SimTimeTicks
    ticks = SimTimeTicks(20.0)
    assert ticks.due(0.0)
    arrivals = [0.2, 0.2, 0.2, 0.201, 0.201, 0.202]  # three ticks owed (0.05 ... 0.15), the clock at 0.2 twice
    stamps = _published(ticks, arrivals)
    assert stamps == [0.2, 0.201, 0.202]
