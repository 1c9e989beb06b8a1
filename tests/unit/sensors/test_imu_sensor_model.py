"""The IMU as Gazebo's ImuSensor and gazebo_ros_imu_sensor make it: the acceleration differenced from the velocity
last recorded (the previous measurement, or a `prime`), per-axis noise with a bias drawn once, and
initialOrientationAsReference. No ROS."""
import math

import numpy as np
import pytest

from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion
from racebot_sim_bridge.sensors.imu_reading import ImuKinematics
from racebot_sim_bridge.sensors.noise import AxisNoise

G = (0.0, 0.0, -9.8)
LEVEL = (0.0, 0.0, 0.0, 1.0)


def test_acceleration_is_the_velocitys_change_since_the_velocity_last_recorded():
    imu = ImuKinematics(G)
    imu.prime(0.0, (0.0, 0.0, 0.0))
    assert imu.measure(0.5, LEVEL, (0.0, 0.0, 0.0), (0, 0, 0)) is not None  # at rest for half a second
    # a 1 Hz IMU: the velocity is recorded one step (1 ms) before its next update, then it has sped up by 0.002
    imu.prime(1.499, (0.0, 0.0, 0.0))
    m = imu.measure(1.5, LEVEL, (0.002, 0.0, 0.0), (0, 0, 0))
    assert m.linear_acceleration == pytest.approx([2.0, 0.0, 9.8])  # not 0.002 m/s over the whole second


def test_no_velocity_before_the_update_gives_no_reading():
    imu = ImuKinematics(G)
    assert imu.measure(1.0, LEVEL, (0.0, 0.0, 0.0), (0, 0, 0)) is None
    imu.reset()
    assert imu.measure(2.0, LEVEL, (0.0, 0.0, 0.0), (0, 0, 0)) is None


def test_initial_orientation_as_reference():
    start = rpy_to_quaternion(0.0, 0.0, math.pi / 2)
    world = ImuKinematics(G)
    relative = ImuKinematics(G, reference=start)
    for imu in (world, relative):
        imu.prime(0.0, (0, 0, 0))
    turned = rpy_to_quaternion(0.0, 0.0, math.pi / 2 + 0.3)
    assert world.measure(0.01, turned, (0, 0, 0), (0, 0, 0)).orientation == pytest.approx(turned)
    assert relative.measure(0.01, turned, (0, 0, 0), (0, 0, 0)).orientation == \
        pytest.approx(rpy_to_quaternion(0.0, 0.0, 0.3))


def test_axis_noise_has_a_bias_drawn_once_and_its_own_spread_per_axis():
    noise = AxisNoise([(0.0, 0.1, 0.0, 0.0), (0.0, 0.0, 0.5, 0.0), (0.2, 0.0, 0.0, 0.0)],
                      rng=np.random.default_rng(3))
    samples = np.array([noise.apply((1.0, 1.0, 1.0)) for _ in range(4000)])
    assert samples[:, 0].std() == pytest.approx(0.1, rel=0.05) and samples[:, 0].mean() == pytest.approx(1.0, abs=0.01)
    assert np.all(samples[:, 1] == samples[0, 1]) and abs(samples[0, 1] - 1.0) == pytest.approx(0.5)  # +-bias
    assert np.all(samples[:, 2] == pytest.approx(1.2))  # the mean, no spread
    assert AxisNoise.make([(0.0, 0.0, 0.0, 0.0)] * 3) is None
    assert AxisNoise.make([(0.0, 0.1, 0.0, 0.0)] * 3, enabled=False) is None
    with pytest.raises(ValueError):
        AxisNoise([(0.0, -0.1, 0.0, 0.0)] * 3)
    # the sign of the bias is flipped half the time, as Gazebo does
    signs = {np.sign(AxisNoise([(0.0, 0.0, 0.5, 0.0)], rng=np.random.default_rng(k)).bias[0]) for k in range(20)}
    assert signs == {-1.0, 1.0}
