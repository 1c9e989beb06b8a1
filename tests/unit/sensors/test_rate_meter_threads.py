"""sensors.schedule.RateMeter from several threads at once, as the bridge uses it: ticks from the
physics thread and the render worker's reader thread, skips from the physics thread, snapshots
from the diagnostics timer. The threads are forced to switch before any bytecode of schedule.py
(interleaving.interleaved); without that, CPython 3.11's GIL never switched inside `+=`
(8 threads x 200,000 unlocked ticks lost none), so the race would go unseen."""
import threading

import pytest

from racebot_sim_bridge.sensors import schedule
from racebot_sim_bridge.sensors.schedule import RateMeter

from interleaving import interleaved

THREADS = 4
EVENTS = 2000  # per thread


def _run(meter, snapshots, calls=('tick', 'skip')):
    """THREADS threads each make the `calls` EVENTS times, all let go at once; with `snapshots`,
    this thread takes snapshots 1 s of sim and wall time apart (so each one's Hz is its count)
    until they are done. Returns what the snapshots saw."""
    methods = [getattr(meter, name) for name in calls]
    start = threading.Barrier(THREADS + 1)

    def work():
        start.wait()
        for _ in range(EVENTS):
            for method in methods:
                method()
    assert meter.snapshot(0.0, 0.0) is None  # the first one sets where counting starts
    seen = []
    with interleaved(schedule):
        workers = [threading.Thread(target=work) for _ in range(THREADS)]
        for worker in workers:
            worker.start()
        start.wait()
        while snapshots and any(worker.is_alive() for worker in workers):
            seen.append(meter.snapshot(len(seen) + 1.0, len(seen) + 1.0))
        for worker in workers:
            worker.join()
    seen.append(meter.snapshot(len(seen) + 1.0, len(seen) + 1.0))
    return seen


@pytest.mark.parametrize('calls', [('tick',), ('skip',), ('tick', 'skip')])
def test_no_tick_or_skip_is_lost_between_threads(calls):
    meter = RateMeter()
    _run(meter, False, calls)
    ticks = THREADS * EVENTS if 'tick' in calls else 0
    skips = THREADS * EVENTS if 'skip' in calls else 0
    assert (meter.count, meter.total, meter.skipped) == (ticks, ticks, skips)


def test_snapshots_taken_meanwhile_count_each_event_once():
    meter = RateMeter()
    seen = _run(meter, snapshots=True)
    assert len(seen) > 10  # taken while the threads ran
    assert sum(sim_hz for sim_hz, _, _ in seen) == THREADS * EVENTS
    assert sum(wall_hz for _, wall_hz, _ in seen) == THREADS * EVENTS
    assert sum(skipped for _, _, skipped in seen) == THREADS * EVENTS
