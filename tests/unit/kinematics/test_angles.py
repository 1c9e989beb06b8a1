"""kinematics/angles.py: ROS's angles package as ros_control and ros_controllers use it."""
import math

import pytest

from racebot_sim_bridge.kinematics.angles import shortest_angular_distance, shortest_angular_distance_with_limits

TWO_PI = 2.0 * math.pi


def test_shortest_angular_distance():
    assert shortest_angular_distance(0.0, 1.0) == pytest.approx(1.0)
    assert shortest_angular_distance(3.0, -3.0) == pytest.approx(TWO_PI - 6.0)
    assert shortest_angular_distance(-3.0, 3.0) == pytest.approx(6.0 - TWO_PI)
    assert shortest_angular_distance(0.0, 7.0) == pytest.approx(7.0 - TWO_PI)
    assert shortest_angular_distance(20.0, 20.0) == 0.0
    assert -math.pi < shortest_angular_distance(0.0, math.pi) <= math.pi


@pytest.mark.parametrize('current, target, lower, upper, expected', [
    (0.0, 1.0, -2.0, 2.0, 1.0),
    (0.5, -0.5, -0.6, 0.6, -1.0),
    (4.0, -0.5, -1.0, 5.0, -4.5),        # short way leaves the range: long way
    (-0.5, 4.0, -1.0, 5.0, 4.5),
    (3.0, -3.0, -4.0, 4.0, 2 * math.pi - 6.0),  # across pi inside wide limits: short way
    (3.0, -3.0, -3.5, 3.1, -6.0),        # ... unless that leaves the range
    (1.0, 1.0, -1.0, 1.0, 0.0),
])
def test_shortest_angular_distance_with_limits(current, target, lower, upper, expected):
    assert shortest_angular_distance_with_limits(current, target, lower, upper) == pytest.approx(expected)
