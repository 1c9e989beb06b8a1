"""Unit tests of racebot_control.wheel_commands (servo_commands' logic: Ackermann -> six joint commands)."""

import math

import pytest
from hypothesis import given, strategies as st

from racebot_control.wheel_commands import (ACKERMANN, PARALLEL, CarGeometry, WheelCommands,
                                            ackermann_commands, curvature, parallel_commands,
                                            wheel_commands)

G = CarGeometry()
speeds = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False)
angles = st.floats(min_value=-1.5, max_value=1.5, allow_nan=False)
NOT_FINITE = [math.nan, math.inf, -math.inf]


def test_defaults_are_the_models():
    assert (G.wheel_radius, G.wheelbase, G.track, G.max_steering_angle) == (0.032, 0.26, 0.18, 0.6)
    assert G.hinge_y == pytest.approx(0.065)  # hinges at y = +-0.065, wheels 0.025 further out


def test_parallel_is_the_tutorials_mapping():
    # 0.5 m/s * 31.25 (= 1 / 0.032 m) = 15.625 rad/s on every wheel, both hinges the angle.
    assert parallel_commands(0.5, 0.3) == WheelCommands(15.625, 15.625, 15.625, 15.625, 0.3, 0.3)
    assert parallel_commands(-1.0, -0.2) == WheelCommands(-31.25, -31.25, -31.25, -31.25, -0.2, -0.2)
    assert parallel_commands(0.0, 0.0) == WheelCommands(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    assert wheel_commands(0.5, 0.3) == parallel_commands(0.5, 0.3)  # parallel is the default


def test_wheel_radius_is_a_parameter():
    assert parallel_commands(0.5, 0.0, CarGeometry(wheel_radius=0.05)).left_rear_wheel == pytest.approx(10.0)


@pytest.mark.parametrize('mode', [PARALLEL, ACKERMANN])
def test_steering_is_clamped_to_the_hinge_limit(mode):
    for angle, sign in [(0.9, 1), (-2.0, -1), (math.pi / 2, 1)]:
        cmd = wheel_commands(0.5, angle, mode)
        for hinge in (cmd.left_steering_hinge, cmd.right_steering_hinge):
            assert abs(hinge) <= 0.6 + 1e-12
            assert hinge * sign > 0
    # the inner hinge sits exactly at the limit at full lock
    assert wheel_commands(0.5, 0.9, mode).left_steering_hinge == pytest.approx(0.6)
    assert wheel_commands(0.5, -0.9, mode).right_steering_hinge == pytest.approx(-0.6)
    limited = CarGeometry(max_steering_angle=0.3)
    assert wheel_commands(0.5, 0.5, mode, limited).left_steering_hinge == pytest.approx(0.3)


@pytest.mark.parametrize('mode', [PARALLEL, ACKERMANN])
@pytest.mark.parametrize('bad', NOT_FINITE)
def test_non_finite_commands_are_rejected(mode, bad):
    assert wheel_commands(bad, 0.1, mode) is None
    assert wheel_commands(0.5, bad, mode) is None
    assert wheel_commands(bad, bad, mode) is None


def test_unknown_mode_and_bad_geometry_raise():
    with pytest.raises(ValueError):
        wheel_commands(0.5, 0.1, 'tank')
    for bad in [dict(wheel_radius=0.0), dict(wheelbase=-1.0), dict(track=math.nan),
                dict(max_steering_angle=2.0), dict(wheel_hinge_offset=0.1), dict(wheel_radius='x')]:
        with pytest.raises(ValueError):
            CarGeometry(**bad)


def test_ackermann_straight_line_equals_parallel():
    for speed in (0.5, -0.7, 0.0):
        assert ackermann_commands(speed, 0.0) == pytest.approx(parallel_commands(speed, 0.0))


def test_ackermann_textbook_angles_without_hinge_offset():
    g = CarGeometry(wheel_hinge_offset=0.0)
    cmd = ackermann_commands(0.5, 0.3, g)
    radius = g.wheelbase / math.tan(0.3)
    assert cmd.left_steering_hinge == pytest.approx(math.atan(g.wheelbase / (radius - g.track / 2)))
    assert cmd.right_steering_hinge == pytest.approx(math.atan(g.wheelbase / (radius + g.track / 2)))


def _front_wheel_centres(g, cmd):
    """Centres of the left and right front wheels: wheel_hinge_offset outboard of each hinge,
    along the turned axle."""
    off, left, right = g.wheel_hinge_offset, cmd.left_steering_hinge, cmd.right_steering_hinge
    return ((g.wheelbase - off * math.sin(left), g.hinge_y + off * math.cos(left)),
            (g.wheelbase + off * math.sin(right), -g.hinge_y - off * math.cos(right)))


def _icr_from_hinge(g, y_hinge, angle):
    """Where the hinge's axle line (through the hinge, perpendicular to the wheel) crosses the
    rear axle line x = 0: the y of that point."""
    return y_hinge + g.wheelbase / math.tan(angle)


@given(speeds, angles)
def test_ackermann_one_turning_centre_and_speeds_proportional_to_radii(speed, angle):
    cmd = ackermann_commands(speed, angle)
    if abs(angle) < 1e-6:
        assert cmd.left_steering_hinge == pytest.approx(cmd.right_steering_hinge, abs=1e-9)
        return
    k = curvature(angle)
    radius = 1.0 / k
    # both hinges point at the same ICR (0, R) on the rear axle line
    assert _icr_from_hinge(G, G.hinge_y, cmd.left_steering_hinge) == pytest.approx(radius, rel=1e-9)
    assert _icr_from_hinge(G, -G.hinge_y, cmd.right_steering_hinge) == pytest.approx(radius, rel=1e-9)
    # the inner hinge turns more than the outer one, same direction as asked
    inner, outer = ((cmd.left_steering_hinge, cmd.right_steering_hinge) if angle > 0
                    else (cmd.right_steering_hinge, cmd.left_steering_hinge))
    assert abs(inner) > abs(outer) > 0 and inner * angle > 0 and outer * angle > 0
    assert abs(inner) <= G.max_steering_angle + 1e-12
    # each wheel's speed is proportional to its distance to the ICR: omega = v / |R|
    omega = speed / abs(radius)
    points = [(0.0, G.track / 2), (0.0, -G.track / 2)] + list(_front_wheel_centres(G, cmd))
    expected = [math.hypot(x, y - radius) for x, y in points]
    got = [cmd.left_rear_wheel, cmd.right_rear_wheel, cmd.left_front_wheel, cmd.right_front_wheel]
    for wheel, distance in zip(got, expected):
        assert wheel * G.wheel_radius == pytest.approx(omega * distance, rel=1e-9, abs=1e-12)
    # outer wheels faster than inner ones, front faster than rear on each side
    if abs(speed) > 1e-3 and abs(angle) > 1e-3:
        left_inner = angle > 0
        rear_in, rear_out = (got[0], got[1]) if left_inner else (got[1], got[0])
        assert abs(rear_out) > abs(rear_in)
        assert abs(got[2]) > abs(got[0]) and abs(got[3]) > abs(got[1])


def test_ackermann_front_wheel_centres_lie_on_the_hinge_axle_line():
    # The front wheel centres the speeds are computed for must also point at the ICR.
    cmd = ackermann_commands(1.0, 0.4)
    radius = 1.0 / curvature(0.4)
    lf, _ = _front_wheel_centres(G, cmd)
    # direction hinge -> wheel centre is parallel to hinge -> ICR
    d1 = (lf[0] - G.wheelbase, lf[1] - G.hinge_y)
    d2 = (0.0 - G.wheelbase, radius - G.hinge_y)
    assert d1[0] * d2[1] - d1[1] * d2[0] == pytest.approx(0.0, abs=1e-12)


def test_ackermann_reverse_mirrors_forward():
    forward = ackermann_commands(0.5, 0.3)
    backward = ackermann_commands(-0.5, 0.3)
    assert backward[:4] == pytest.approx([-w for w in forward[:4]])
    assert backward[4:] == pytest.approx(forward[4:])
    # a right turn is the left turn mirrored: left and right swap
    right = ackermann_commands(0.5, -0.3)
    assert right.left_rear_wheel == pytest.approx(forward.right_rear_wheel)
    assert right.left_front_wheel == pytest.approx(forward.right_front_wheel)
    assert right.left_steering_hinge == pytest.approx(-forward.right_steering_hinge)


@given(speeds, angles, st.sampled_from([PARALLEL, ACKERMANN]))
def test_outputs_are_always_finite(speed, angle, mode):
    assert all(math.isfinite(v) for v in wheel_commands(speed, angle, mode))
