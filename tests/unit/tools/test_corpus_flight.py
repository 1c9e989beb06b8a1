"""tools/corpus/flight.py: the flight check's fits and its estop prediction."""
import pytest

from corpus import flight


def climb(rate_m_s, t0=0.0, t1=4.0, z0=0.2, step=0.02):
    n = int(round((t1 - t0) / step)) + 1
    return [(t0 + i * step, z0 + rate_m_s * i * step) for i in range(n)]


def test_rate_is_the_slope_within_the_window_only():
    samples = climb(0.5) + [(4.0 + 0.02 * i, 2.2) for i in range(1, 200)]
    assert flight.rate(samples, 2.0, 4.0) == pytest.approx(0.5)
    assert flight.rate(samples, 5.0, 7.0) == pytest.approx(0.0, abs=1e-12)


def test_rate_needs_three_samples():
    assert flight.rate([(0.0, 0.0), (1.0, 1.0)], 0.0, 1.0) is None
    assert flight.rate(climb(0.5), 10.0, 11.0) is None


def test_height_is_interpolated_and_none_outside_the_log():
    samples = [(0.0, 1.0), (1.0, 2.0)]
    assert flight.height_at(samples, 0.25) == pytest.approx(1.25)
    assert flight.height_at(samples, 1.5) is None


def test_the_estop_drop_is_the_integral_of_a_linearly_growing_deceleration():
    # a = d * t: v = d t^2 / 2, z = d t^3 / 6; checked against a fine Euler integration of the same ramp
    d, seconds, dt = 1.0, 1.5, 1e-5
    v = z = t = 0.0
    while t < seconds - dt / 2:
        v += d * t * dt
        z += v * dt
        t += dt
    assert flight.estop_drop(d, seconds) == pytest.approx(z, rel=1e-3)
    assert flight.estop_drop(1.0, 1.5) == pytest.approx(0.5625)
