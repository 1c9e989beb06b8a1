"""kinematics.skid_steer: gazebo_ros_skid_steer_drive's side speeds and wheel joint velocities."""
import pytest

from racebot_sim_bridge.kinematics import skid_steer


def test_straight_ahead_every_wheel_turns_at_speed_over_radius():
    assert skid_steer.wheel_velocities(0.5, 0.0, 0.4, 0.2) == pytest.approx((5.0, 5.0, 5.0, 5.0))


def test_a_left_turn_slows_the_left_side_and_speeds_up_the_right():
    # v 0.2, w 0.8, track 0.4: each side 0.16 m/s off the centre
    left, right = skid_steer.side_speeds(0.2, 0.8, 0.4)
    assert (left, right) == pytest.approx((0.04, 0.36))
    lf, rf, lr, rr = skid_steer.wheel_velocities(0.2, 0.8, 0.4, 0.2)
    assert (lf, rf, lr, rr) == pytest.approx((0.4, 3.6, 0.4, 3.6))


def test_turning_on_the_spot_drives_the_sides_opposite():
    lf, rf, lr, rr = skid_steer.wheel_velocities(0.0, -1.0, 0.5, 0.15)
    assert lf == pytest.approx(0.25 / 0.075) and rf == pytest.approx(-0.25 / 0.075)
    assert (lr, rr) == (lf, rf)


@pytest.mark.parametrize('vx, wz', [(0.3, 0.0), (0.2, 0.8), (-0.1, -0.4), (0.0, 2.0)])
def test_base_twist_inverts_side_speeds(vx, wz):
    assert skid_steer.base_twist(*skid_steer.side_speeds(vx, wz, 0.37), 0.37) == pytest.approx((vx, wz))
