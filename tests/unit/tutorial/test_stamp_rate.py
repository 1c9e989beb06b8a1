"""The rate judge of the rostests' stamp_rate_test (integration_common.theil_sen_period) on the streams it
meets: exact stamps, gazebo_odometry's arrival stamps with SimTimeTicks' catch-up after a stall, and lost
messages, which it must not forgive."""
import random
import statistics

import pytest

from integration_common import theil_sen_period  # tests/integration, shared with the rostest node
from racebot_gazebo.odometry import SimTimeTicks


def stamps_after_a_stall(stall_from, stall, seed, window=(5.0, 10.0)):
    """gazebo_odometry's stamps at 20 Hz in `window`: link_states every 10 ms of sim time, each handled 0 to
    40 ms late, none handled from stall_from for `stall` s."""
    rng, ticks, t, stamps = random.Random(seed), SimTimeTicks(20.0), 0.0, []
    while t < window[1]:
        t += 0.01
        if stall_from < t < stall_from + stall:
            continue
        arrival = t + rng.uniform(0.0, 0.04)
        if ticks.due(arrival) and arrival >= window[0]:
            stamps.append(arrival)
    return stamps


def test_exact_stamps():
    assert 1.0 / theil_sen_period([0.02 * i for i in range(250)]) == pytest.approx(50.0)


@pytest.mark.parametrize('stall', [0.1, 0.3, 0.5, 0.8])
@pytest.mark.parametrize('seed', [0, 1, 2])
def test_a_catch_up_burst_at_the_window_start(stall, seed):
    stamps = stamps_after_a_stall(4.8, stall, seed)
    average = (len(stamps) - 1) / (stamps[-1] - stamps[0])
    if stall >= 0.5:
        assert average > 21.5  # what the average over such a window reads
    assert 1.0 / theil_sen_period(stamps) == pytest.approx(20.0, abs=0.2)


@pytest.mark.parametrize('seed', [0, 1, 2])
def test_link_states_handled_at_random_moments(seed):
    # a loaded machine: gazebo_odometry's callback runs at random moments (a mean gap of 30 ms of sim time, the
    # clock read to the ms), so its intervals spread and skew; the median interval reads 21.7 to 23.3 Hz
    rng, ticks, t, stamps = random.Random(seed), SimTimeTicks(20.0), 0.0, []
    while t < 10.0:
        t += rng.expovariate(1.0 / 0.03)
        now = round(t, 3)
        if ticks.due(now) and now >= 5.0:
            stamps.append(now)
    median = statistics.median(b - a for a, b in zip(stamps, stamps[1:]))
    assert abs(1.0 / median - 20.0) > 1.0
    assert 1.0 / theil_sen_period(stamps) == pytest.approx(20.0, abs=0.25)


def test_lost_messages_lower_the_rate():
    stamps = [0.02 * i for i in range(250) if i % 10 != 3]  # one message in ten never comes
    assert 1.0 / theil_sen_period(stamps) == pytest.approx(45.0, abs=0.5)


def test_a_wrong_rate_is_read_as_such():
    assert 1.0 / theil_sen_period([0.025 * i for i in range(200)]) == pytest.approx(40.0)
