"""The soak's memory verdict (tools/soak.py): RSS read at rest (physics paused, frames delivered) after the
warm-up, every REST_EVERY s, and at the end; the verdict compares the first rest with the last."""
import soak


def test_no_rest_before_the_warm_up_has_ended():
    assert not soak.rest_due(5.0, None, [])      # the sensors are not warm yet
    assert not soak.rest_due(19.0, 20.0, [])     # warm at 20 s of sim time
    assert soak.rest_due(20.0, 20.0, [])


def test_rests_come_every_rest_every_seconds_after_the_last():
    rests = [(20.0, 140000)]
    assert not soak.rest_due(20.0 + soak.REST_EVERY - 0.1, 20.0, rests)
    assert soak.rest_due(20.0 + soak.REST_EVERY, 20.0, rests)


def test_growth_is_the_last_rest_against_the_first():
    rests = [(20.0, 100000), (50.0, 130000), (80.0, 103000)]
    assert abs(soak.rest_growth(rests) - 3.0) < 1e-9
    assert soak.rest_growth(rests[:1]) is None and soak.rest_growth([]) is None


def test_a_leak_reads_as_growth():
    rests = [(20.0 + 30.0 * i, 140000 + 2000 * i) for i in range(5)]  # 2 MB every 30 s
    assert soak.rest_growth(rests) > 5.0


def test_the_median_of_the_readings_stands_for_the_rest():
    assert soak.stats.median([5, 1, 9]) == 5
    assert soak.stats.median([140000] * 7 + [180000]) == 140000  # one reading with a frame freed late


def test_the_launch_runs_with_the_mmap_threshold_fixed():
    env = soak.measured_environ({'PATH': '/usr/bin'})
    assert env['GLIBC_TUNABLES'] == 'glibc.malloc.mmap_threshold=131072' and env['PATH'] == '/usr/bin'


def test_a_users_own_tunables_stay_and_the_threshold_is_ours():
    env = soak.measured_environ({'GLIBC_TUNABLES': 'glibc.malloc.arena_max=2:glibc.malloc.mmap_threshold=1'})
    assert env['GLIBC_TUNABLES'] == 'glibc.malloc.arena_max=2:glibc.malloc.mmap_threshold=131072'
