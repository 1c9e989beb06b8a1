"""kinematics.planar_move: gazebo_ros_planar_move's velocities and odometry twist, the odometry
covariance, and the exact integration of a constant body twist."""
import math

import pytest

from racebot_sim_bridge.kinematics import planar as pm


def test_a_command_in_the_robot_axes_becomes_a_world_velocity_with_z_and_tilt_rates_zero():
    linear, angular = pm.model_velocity((0.3, 0.2, 0.5), math.pi / 2)
    assert linear == pytest.approx((-0.2, 0.3, 0.0))
    assert angular == (0.0, 0.0, 0.5)


@pytest.mark.parametrize('yaw', [0.0, 0.7, -2.5, math.pi])
def test_world_to_base_undoes_base_to_world(yaw):
    assert pm.world_to_base(*pm.base_to_world(0.3, -0.2, yaw), yaw) == pytest.approx((0.3, -0.2))


def test_yaw_change_goes_the_short_way_round():
    assert pm.unwrapped_yaw_change(3.1, -3.1) == pytest.approx(2 * math.pi - 6.2)
    assert pm.unwrapped_yaw_change(-3.1, 3.1) == pytest.approx(6.2 - 2 * math.pi)
    assert pm.unwrapped_yaw_change(0.1, 0.3) == pytest.approx(0.2)


def test_finite_difference_twist_is_in_the_robot_axes_at_the_new_pose():
    # moved 0.1 m along world y in 0.5 s, now heading +90 deg: that is straight ahead
    vx, vy, wz = pm.finite_difference_twist((0.0, 0.0, math.pi / 2 - 0.05), (0.0, 0.1, math.pi / 2), 0.5, 0.1)
    assert (vx, vy, wz) == pytest.approx((0.2, 0.0, 0.1))


def test_a_turn_faster_than_half_a_turn_per_publication_reports_the_command():
    # at 0.05 s per publication, pi / 0.05 = 62.8 rad/s: the poses cannot tell 70 rad/s apart
    assert pm.finite_difference_twist((0, 0, 0), (0, 0, 0.5), 0.05, 70.0)[2] == 70.0
    assert pm.finite_difference_twist((0, 0, 0), (0, 0, 0.5), 0.05, 10.0)[2] == pytest.approx(10.0)


def test_covariance_diagonal():
    cov = pm.covariance(1e-5, 2e-5, 1e-3)
    assert [cov[7 * i] for i in range(6)] == [1e-5, 2e-5, 1e12, 1e12, 1e12, 1e-3]
    assert sum(cov) == pytest.approx(1e-5 + 2e-5 + 3e12 + 1e-3)


def test_integrate_straight_and_along_an_arc():
    assert pm.integrate((1.0, 2.0, math.pi / 2), (0.5, 0.0, 0.0), 2.0) == pytest.approx((1.0, 3.0, math.pi / 2))
    # a quarter circle of radius 1 to the left, starting at the origin heading +x
    x, y, yaw = pm.integrate((0.0, 0.0, 0.0), (math.pi / 2, 0.0, math.pi / 2), 1.0)
    assert (x, y, yaw) == pytest.approx((1.0, 1.0, math.pi / 2))


def test_integrate_matches_small_steps():
    pose, twist = (1.0, 2.0, 0.3), (0.3, 0.2, 0.5)
    x, y, yaw = pose
    n = 20000
    dt = 2.0 / n
    for _ in range(n):
        dx, dy = pm.base_to_world(twist[0], twist[1], yaw + twist[2] * dt / 2)
        x, y, yaw = x + dx * dt, y + dy * dt, yaw + twist[2] * dt
    assert pm.integrate(pose, twist, 2.0) == pytest.approx((x, y, yaw), abs=1e-9)
