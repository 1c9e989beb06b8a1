"""pause_physics is synchronous, as Gazebo's: once Simulator.set_paused(True) has returned, no update
starts (World::SetPaused takes the lock World::Step holds). A request made after the pause, such as a
controller switch that must time out because no update comes, then sees the world stand still.

The world server's loop steps through step_unless_paused; here a thread does the same while the test
pauses and unpauses thousands of times with the threads made to switch as often as Python allows. With
the flag read outside the step lock, a step that had read "running" before the pause ends after it,
and the step count moves while paused. Real PyBullet, no master.
"""
import sys
import threading
import time

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator

from fakes import FakeLog

CYCLES = 3000
BOUND = 10.0  # s: only how long a failing wait lasts before it is reported


def test_no_update_starts_once_a_pause_has_returned():
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    stop = threading.Event()

    def world_loop():  # the world server's loop, without ROS
        while not stop.is_set():
            if not sim.step_unless_paused():
                time.sleep(0)

    switch_interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    stepper = threading.Thread(target=world_loop, daemon=True)
    stepper.start()
    moved = []
    try:
        for _ in range(CYCLES):
            sim.set_paused(True)
            paused_at = sim.steps
            for _ in range(3):
                time.sleep(0)  # the stepper's turn: a step under way before the pause would end now
            if sim.steps != paused_at:
                moved.append(sim.steps - paused_at)
            sim.set_paused(False)
            deadline = time.monotonic() + BOUND
            while sim.steps == paused_at and time.monotonic() < deadline:
                time.sleep(0)  # the world runs again before the next pause
            assert sim.steps > paused_at, 'the world did not step again after unpausing'
    finally:
        stop.set()
        stepper.join(BOUND)
        sys.setswitchinterval(switch_interval)
        sim.close()
    assert moved == [], 'steps after a pause had returned in %d of %d pauses' % (len(moved), CYCLES)


def test_a_paused_world_does_not_step():
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    try:
        sim.set_paused(True)
        assert (sim.step_unless_paused(), sim.steps, sim.time) == (False, 0, 0.0)
        sim.set_paused(False)
        assert (sim.step_unless_paused(), sim.steps) == (True, 1)
    finally:
        sim.close()
