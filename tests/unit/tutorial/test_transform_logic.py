"""Unit tests of racebot_control.twist_to_ackermann (the transform node's logic: Twist -> Ackermann)."""

import math

import pytest
from hypothesis import given, strategies as st

from racebot_control.twist_to_ackermann import AckermannCommand, TwistToAckermann

NOT_FINITE = [math.nan, math.inf, -math.inf]


def test_tutorial_mode_passes_angular_z_through():
    conv = TwistToAckermann()
    assert conv.convert(0.5, 0.3) == AckermannCommand(speed=0.5, steering_angle=0.3, steering_angle_velocity=1.0,
                                                      acceleration=1.0, jerk=1.0)
    # unconverted and unclamped, as the tutorial (servo_commands clamps to the hinge limit)
    assert conv.convert(-0.4, 1.2).steering_angle == 1.2
    assert conv.convert(-0.4, 1.2).speed == -0.4
    assert conv.convert(0.0, 0.7).steering_angle == 0.7


def test_yaw_rate_mode_uses_the_bicycle_model():
    conv = TwistToAckermann(convert_yaw_rate=True)
    cmd = conv.convert(0.5, 0.4)
    assert cmd.speed == 0.5
    assert cmd.steering_angle == pytest.approx(math.atan(0.26 * 0.4 / 0.5))
    assert (cmd.acceleration, cmd.jerk, cmd.steering_angle_velocity) == (1.0, 1.0, 1.0)
    # the angle gives back the yaw rate: omega = v tan(delta) / L
    assert 0.5 * math.tan(cmd.steering_angle) / 0.26 == pytest.approx(0.4)
    assert conv.convert(0.5, -0.4).steering_angle == pytest.approx(-math.atan(0.26 * 0.4 / 0.5))
    assert conv.convert(0.5, 0.0).steering_angle == 0.0


def test_yaw_rate_mode_reverse():
    conv = TwistToAckermann(convert_yaw_rate=True)
    cmd = conv.convert(-0.5, 0.4)
    assert cmd.speed == -0.5
    # backing up with a positive yaw rate steers right
    assert cmd.steering_angle == pytest.approx(-math.atan(0.26 * 0.4 / 0.5))
    assert -0.5 * math.tan(cmd.steering_angle) / 0.26 == pytest.approx(0.4)


def test_yaw_rate_mode_clamps_to_the_hinge_limit():
    conv = TwistToAckermann(convert_yaw_rate=True)
    assert conv.convert(0.1, 5.0).steering_angle == pytest.approx(0.6)
    assert conv.convert(0.1, -5.0).steering_angle == pytest.approx(-0.6)
    assert conv.convert(-1e-3, 5.0).steering_angle == pytest.approx(-0.6)
    narrow = TwistToAckermann(convert_yaw_rate=True, wheelbase=0.5, max_steering_angle=0.2)
    assert narrow.convert(0.1, 5.0).steering_angle == pytest.approx(0.2)
    assert narrow.convert(1.0, 0.1).steering_angle == pytest.approx(math.atan(0.05))


def test_yaw_rate_mode_zero_speed_keeps_the_last_angle():
    conv = TwistToAckermann(convert_yaw_rate=True)
    assert conv.convert(0.0, 0.5).steering_angle == 0.0  # nothing before: straight
    angle = conv.convert(0.5, 0.4).steering_angle
    for omega in (0.0, 0.5, -3.0):
        cmd = conv.convert(0.0, omega)
        assert cmd.steering_angle == angle and cmd.speed == 0.0
    assert conv.convert(-0.0, 1.0).steering_angle == angle
    assert conv.convert(0.5, -0.4).steering_angle == pytest.approx(-angle)


@pytest.mark.parametrize('convert', [False, True])
@pytest.mark.parametrize('bad', NOT_FINITE + [1e39])
def test_non_finite_twists_are_rejected(convert, bad):
    conv = TwistToAckermann(convert_yaw_rate=convert)
    assert conv.convert(bad, 0.1) is None
    assert conv.convert(0.5, bad) is None
    assert conv.convert(bad, bad) is None


def test_bad_parameters_raise():
    for bad in [dict(wheelbase=0.0), dict(wheelbase=math.nan), dict(max_steering_angle=-0.1),
                dict(max_steering_angle=math.inf)]:
        with pytest.raises(ValueError):
            TwistToAckermann(convert_yaw_rate=True, **bad)


finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)


@given(st.lists(st.tuples(finite, finite), min_size=1, max_size=20))
def test_yaw_rate_mode_outputs_are_finite_and_within_limits(twists):
    conv = TwistToAckermann(convert_yaw_rate=True)
    for v, omega in twists:
        cmd = conv.convert(v, omega)
        assert all(math.isfinite(x) for x in cmd)
        assert abs(cmd.steering_angle) <= 0.6
