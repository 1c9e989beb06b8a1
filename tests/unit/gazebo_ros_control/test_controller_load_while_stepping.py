"""The world keeps stepping while a controller loads or unloads (issue 18): the parameter read and
the controller's publishers and subscribers (calls to the master, slow on a busy machine) run
outside the controller manager's lock, which every Simulator.step needs.

A Simulator with real PyBullet, no master: the parameter read, a publisher's creation or a topic's
unregistration is made to block on an event the test holds; while it is blocked, the world must
complete steps in another thread. No timing is asserted: with the slow work under the lock the
steps cannot happen until the event is released, and the wait for them fails at its bound.
"""
import threading

import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from wheel_robot import EMPTY_WORLD, _robot
from fakes import FakeLog

BOUND = 10.0  # s: only how long a failing run waits before it is reported
GATE_LIMIT = 3 * BOUND  # s: a blocked call gives up after the test has (a test never hangs)
STEPS = 50  # steps the world must complete while the load is blocked
PARAMS = {
    '/wheel': {'type': 'effort_controllers/JointVelocityController', 'joint': 'wheel_joint', 'pid': {'p': 0.05}},
    '/joints': {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50},
}


class Gate:
    """Blocks the thread that passes it until released; says when one is waiting."""

    def __init__(self):
        self.armed = False
        self.waiting = threading.Event()
        self.release = threading.Event()

    def passing(self):
        if self.armed:
            self.waiting.set()
            assert self.release.wait(GATE_LIMIT), 'the test never released the gate'


class _Topic:
    def __init__(self, gate):
        self.gate = gate

    def publish(self, msg):
        pass

    def unregister(self):
        self.gate.passing()


class GatedIO:
    """The controllers' I/O; creating a publisher or unregistering a topic passes the gate."""

    def __init__(self, gate):
        self.gate = gate

    def publisher(self, topic, cls, queue_size):
        self.gate.passing()
        return _Topic(self.gate)

    def subscriber(self, topic, cls, callback):
        self.gate.passing()
        return _Topic(self.gate)

    def stamp(self, t):
        return t

    def warn_throttle(self, key, period, message):
        pass


class Rig:
    def __init__(self):
        self.gate = Gate()
        self.log = FakeLog()

        def get_params(path):
            self.gate.passing()
            return PARAMS.get(path)
        world = sdf_reader.parse_world(EMPTY_WORLD)
        self.sim = Simulator(world, GatedIO(self.gate), self.log, get_params)
        GazeboRosControlPlugin.attach(self.sim)
        self.cm = self.sim.spawn_urdf('bot', _robot(''), '/').control.cm
        self.sim.step()

    def in_thread(self, call, *args):
        result = []
        thread = threading.Thread(target=lambda: result.append(call(*args)), daemon=True)
        thread.start()
        return thread, result

    def steps_while_blocked(self, call, *args):
        """call(*args) in a thread, blocked at the gate; the steps the world makes meanwhile, then
        what call returned once released."""
        self.gate.armed = True
        thread, result = self.in_thread(call, *args)
        assert self.gate.waiting.wait(BOUND), 'the call never reached the gate'
        stepper, _ = self.in_thread(lambda: [self.sim.step() for _ in range(STEPS)])
        stepper.join(BOUND)
        stepped = not stepper.is_alive()
        self.gate.armed = False
        self.gate.release.set()
        thread.join(BOUND)
        stepper.join(BOUND)
        assert not thread.is_alive()
        return stepped, result[0]


@pytest.fixture
def rig():
    r = Rig()
    yield r
    r.gate.release.set()
    r.sim.close()


@pytest.mark.parametrize('blocked_in', ['parameter read', 'publisher creation'])
def test_the_world_steps_while_a_controller_loads(rig, blocked_in):
    if blocked_in == 'publisher creation':  # the parameter read passes, the publisher blocks
        get_params = rig.cm.get_params
        rig.cm.get_params = lambda name: (setattr(rig.gate, 'armed', False), get_params(name),
                                          setattr(rig.gate, 'armed', True))[1]
    start = rig.sim.steps
    stepped, loaded = rig.steps_while_blocked(rig.cm.load, 'joints')
    assert stepped, 'the world did not step while a controller load was blocked in its %s' % blocked_in
    assert loaded and 'joints' in rig.cm.loaded
    assert rig.sim.steps >= start + STEPS


def test_the_world_steps_while_a_controller_unloads(rig):
    assert rig.cm.load('joints')
    stepped, unloaded = rig.steps_while_blocked(rig.cm.unload, 'joints')
    assert stepped, 'the world did not step while a controller unload was unregistering its topics'
    assert unloaded and 'joints' not in rig.cm.loaded


def test_a_name_being_loaded_cannot_be_loaded_twice(rig):
    rig.gate.armed = True
    first, result = rig.in_thread(rig.cm.load, 'joints')
    assert rig.gate.waiting.wait(BOUND)
    rig.gate.armed = False
    second, second_result = rig.in_thread(rig.cm.load, 'joints')
    second.join(BOUND)
    assert second_result == [False], 'a second load of a name waited for the first, or loaded it again'
    assert "A controller named 'joints' was already loaded" in rig.log.errors[-1]
    rig.gate.release.set()
    first.join(BOUND)
    assert result == [True] and list(rig.cm.loaded) == ['joints']


def test_a_load_finishing_after_the_model_was_deleted_is_undone(rig):
    rig.gate.armed = True
    thread, result = rig.in_thread(rig.cm.load, 'joints')
    assert rig.gate.waiting.wait(BOUND)
    deleting, _ = rig.in_thread(rig.sim.delete_model, 'bot')
    deleting.join(BOUND)
    assert not deleting.is_alive(), 'delete_model waited for a controller load'
    rig.gate.armed = False
    rig.gate.release.set()
    thread.join(BOUND)
    assert result == [False] and not rig.cm.loaded
    assert 'was shut down while it loaded' in rig.log.errors[-1]
