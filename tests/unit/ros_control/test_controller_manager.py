"""Unit tests of racebot_sim_bridge.ros_control.controller_manager.ControllerManager: ros_control's load / unload /
switch / list / reload_libraries / update semantics (INTERFACES.md; ros_control controller_manager.cpp).

The manager gets the racebot's RobotHW (a URDF with its six effort joints, written out here), an
in-memory I/O object, a parameter dict and a log that records what it is told. No ROS master.
"""
import contextlib
import copy
import threading
import time

import pytest

from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.controller_interface import Controller, ControllerInitError
from racebot_sim_bridge.ros_control.controller_manager import ControllerManager
from racebot_sim_bridge.ros_control.controller_switch import BEST_EFFORT, STRICT
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, STATE, VELOCITY, RobotHW

from fakes import FakeIO, FakeLog

NS = 'racebot'
DT = 0.001
STEERING = ('left_steering_hinge_joint', 'right_steering_hinge_joint')
WHEELS = ('left_front_wheel_joint', 'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint')


def racebot_like_urdf():
    """The racebot's actuated joints, limits and transmissions (racecar.xacro), without the geometry."""
    parts = ['<robot name="racebot"><link name="base_link"/>']
    for j in STEERING:
        parts.append('<link name="%s_l"/><joint name="%s" type="revolute"><parent link="base_link"/>'
                     '<child link="%s_l"/><axis xyz="0 0 1"/><limit lower="-0.6" upper="0.6" effort="5" '
                     'velocity="1000"/></joint>' % (j, j, j))
    for j in WHEELS:
        parts.append('<link name="%s_l"/><joint name="%s" type="continuous"><parent link="base_link"/>'
                     '<child link="%s_l"/><axis xyz="0 1 0"/><limit effort="10" velocity="1000"/></joint>'
                     % (j, j, j))
    for j in STEERING + WHEELS:
        parts.append('<transmission name="%s_t"><type>transmission_interface/SimpleTransmission</type>'
                     '<joint name="%s"><hardwareInterface>hardware_interface/EffortJointInterface'
                     '</hardwareInterface></joint></transmission>' % (j, j))
    parts.append('</robot>')
    return ''.join(parts)


class Recorder(Controller):
    """A controller that writes what happens to it into a shared journal."""
    type_name = 'test_controllers/Recorder'
    interface = EFFORT
    journal = None

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        self.joints = list(self.params.get('joints', []))
        for j in self.joints:
            hw.handle(j, EFFORT)

    def claimed_resources(self):
        return [(self.params.get('claim_as', EFFORT), list(self.joints))]

    def starting(self, time):
        self.journal.append(('start', self.name, time))

    def stopping(self, time):
        self.journal.append(('stop', self.name, time))

    def update(self, time, period):
        self.journal.append(('update', self.name, time))


def vel(joint, **pid):
    return {'type': 'effort_controllers/JointVelocityController', 'joint': joint, 'pid': pid or {'p': 1.0}}


def pos(joint, **pid):
    return {'type': 'effort_controllers/JointPositionController', 'joint': joint, 'pid': pid or {'p': 1.0}}


PARAMS = {
    'joint_state_controller': {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50},
    'left_rear_wheel_velocity_controller': vel('left_rear_wheel_joint'),
    'right_rear_wheel_velocity_controller': vel('right_rear_wheel_joint'),
    'left_steering_hinge_position_controller': pos('left_steering_hinge_joint', p=1.0, i=1.0, i_clamp=10.0),
    'rear_wheel_effort': {'type': 'effort_controllers/JointEffortController', 'joint': 'left_rear_wheel_joint'},
    'no_type': {'joint': 'left_rear_wheel_joint'},
    'bad_type': {'type': 'pos_vel_controllers/JointTrajectoryController', 'joint': 'left_rear_wheel_joint'},
    'bad_joint': vel('wing_joint'),
    'no_pid': {'type': 'effort_controllers/JointVelocityController', 'joint': 'left_rear_wheel_joint'},
    'rec_a': {'type': Recorder.type_name, 'joints': ['left_front_wheel_joint']},
    'rec_b': {'type': Recorder.type_name, 'joints': ['right_front_wheel_joint']},
    'rec_c': {'type': Recorder.type_name, 'joints': []},
}


class Rig:
    def __init__(self, params=None):
        model = urdf_reader.parse_urdf(racebot_like_urdf())
        self.hw = RobotHW(model, hardware_joints(model))
        for h in self.hw.handles.values():
            h.read(0.0, 0.0)
        self.params = dict(PARAMS if params is None else params)
        self.io = FakeIO(one_publisher_per_topic=False)  # controllers of the manager's tests share topics
        self.log = FakeLog()
        self.journal = []
        recorder = type('JournalRecorder', (Recorder,), {'journal': self.journal})
        types = dict(CONTROLLER_TYPES)
        types[Recorder.type_name] = recorder
        self.cm = ControllerManager(NS, self.hw, lambda name: copy.deepcopy(self.params.get(name)), self.io,
                                    self.log, types=types)

    def switch(self, start, stop, strictness, t=0.0, start_asap=False):
        """switch_controller as its service runs it: the checks, then the update at t carries it out."""
        request = self.cm.request_switch(start, stop, strictness, start_asap)
        if request is None:
            return False
        self.cm.update(t, DT)
        assert request.done.is_set() and self.cm.pending is None
        return request.ok

    def events(self):
        """The journal's starts and stops."""
        return [e for e in self.journal if e[0] != 'update']

    @contextlib.contextmanager
    def updating(self):
        """The simulation's update loop, in a thread, while the block runs."""
        stop = threading.Event()

        def loop():
            t = 0.0
            while not stop.is_set():
                t += DT
                self.cm.update(t, DT)
                time.sleep(0.001)
        thread = threading.Thread(target=loop, daemon=True)
        thread.start()
        try:
            yield
        finally:
            stop.set()
            thread.join()

    def states(self):
        return {name: state for name, _, state, _ in self.cm.list()}

    def load_all(self, *names):
        for n in names:
            assert self.cm.load(n), self.log.errors


@pytest.fixture
def rig():
    return Rig()


# -- load ---------------------------------------------------------------------------------------

def test_load_gives_an_initialized_controller(rig):
    assert rig.cm.load('left_rear_wheel_velocity_controller')
    assert rig.states() == {'left_rear_wheel_velocity_controller': 'initialized'}
    assert '/racebot/left_rear_wheel_velocity_controller/command' in rig.io.topics
    assert not rig.log.errors


def test_load_duplicate(rig):
    assert rig.cm.load('joint_state_controller')
    assert not rig.cm.load('joint_state_controller')
    assert "A controller named 'joint_state_controller' was already loaded" in rig.log.errors[-1]
    assert len(rig.cm.list()) == 1


@pytest.mark.parametrize('name', ['no_type', 'not_on_the_parameter_server'])
def test_load_missing_type(rig, name):
    assert not rig.cm.load(name)
    msg = rig.log.errors[-1]
    assert "Could not load controller '%s' because the type was not specified" % name in msg
    assert '/racebot/%s' % name in msg
    assert rig.cm.list() == []


def test_load_unknown_type(rig):
    assert not rig.cm.load('bad_type')
    msg = rig.log.errors[-1]
    assert ("Could not load controller 'bad_type' because controller type "
            "'pos_vel_controllers/JointTrajectoryController' does not exist") in msg
    assert '/racebot/controller_manager/list_controller_types' in msg
    assert 'Supported plugins, sensors and controllers' in msg
    assert rig.cm.list() == []


@pytest.mark.parametrize('name, detail', [('bad_joint', "'wing_joint'"), ('no_pid', '/racebot/no_pid/pid')])
def test_load_init_failure(rig, name, detail):
    assert not rig.cm.load(name)
    msg = rig.log.errors[-1]
    assert "Initializing controller '%s' failed" % name in msg
    assert detail in msg
    assert rig.cm.list() == []


def test_load_empty_name(rig):
    assert not rig.cm.load('')
    assert rig.log.errors


@pytest.mark.parametrize('config', [
    {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50, 'joints': 5},
    {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50, 'extra_joints': 5},
    {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50,
     'extra_joints': [{'name': 'x', 'position': 'up'}]},
    {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50, 'joints': [['a']]},
    {'type': 'effort_controllers/JointVelocityController', 'joint': ['left_rear_wheel_joint'], 'pid': {'p': 1}},
], ids=['joints-int', 'extra_joints-int', 'extra-position-text', 'joints-nested-list', 'joint-list'])
def test_load_malformed_config_fails_cleanly(config):
    # ros_control: an exception in init is caught, logged, and the load answered ok=false.
    rig = Rig({'c': config})
    assert rig.cm.load('c') is False
    assert rig.log.errors and "'c'" in rig.log.errors[-1]
    assert rig.cm.list() == []


# -- unload -------------------------------------------------------------------------------------

def test_unload(rig):
    rig.load_all('left_rear_wheel_velocity_controller')
    assert rig.cm.unload('left_rear_wheel_velocity_controller')
    assert rig.cm.list() == []
    assert rig.io.topics['/racebot/left_rear_wheel_velocity_controller/command'].unregistered
    assert rig.io.topics['/racebot/left_rear_wheel_velocity_controller/state'].unregistered
    assert rig.cm.load('left_rear_wheel_velocity_controller')  # the name is free again


def test_unload_unknown(rig):
    assert not rig.cm.unload('ghost')
    assert "Could not unload controller with name 'ghost' because no controller with this name exists" \
        in rig.log.errors[-1]


def test_unload_running_is_refused(rig):
    rig.load_all('joint_state_controller')
    assert rig.switch(['joint_state_controller'], [], STRICT, 0.0)
    assert not rig.cm.unload('joint_state_controller')
    assert 'still running' in rig.log.errors[-1]
    assert rig.states() == {'joint_state_controller': 'running'}
    assert rig.switch([], ['joint_state_controller'], STRICT, 0.0)
    assert rig.cm.unload('joint_state_controller')


# -- switch -------------------------------------------------------------------------------------

def test_switch_start_and_stop(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a', 'rec_b'], [], STRICT, 1.0)
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'running'}
    assert rig.switch([], ['rec_a'], STRICT, 2.0)
    assert rig.states() == {'rec_a': 'stopped', 'rec_b': 'running'}
    assert rig.events() == [('start', 'rec_a', 1.0), ('start', 'rec_b', 1.0), ('stop', 'rec_a', 2.0)]


def test_strict_unknown_name_changes_nothing(rig):
    rig.load_all('rec_a')
    assert not rig.switch(['rec_a', 'ghost'], [], STRICT, 0.0)
    assert "'ghost'" in rig.log.errors[-1]
    assert rig.states() == {'rec_a': 'initialized'}
    assert rig.events() == []


def test_best_effort_unknown_name_is_skipped(rig):
    rig.load_all('rec_a')
    assert rig.switch(['rec_a', 'ghost'], ['ghost2'], BEST_EFFORT, 0.0)
    assert rig.states() == {'rec_a': 'running'}
    assert any("'ghost'" in w for w in rig.log.warnings)
    assert any("'ghost2'" in w for w in rig.log.warnings)
    assert not rig.log.errors


def test_strict_start_already_running(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.cm.request_switch(['rec_a', 'rec_b'], [], STRICT) is None
    assert "Controller 'rec_a' is already running" in rig.log.errors[-1]
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'initialized'}
    assert rig.events() == [('start', 'rec_a', 0.0)]


def test_best_effort_start_already_running_restarts_it(rig):
    # controller_manager 0.20: the check skips it, but startControllers() starts every requested one
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.switch(['rec_a', 'rec_b'], [], BEST_EFFORT, 1.0)
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'running'}
    assert rig.events() == [('start', 'rec_a', 0.0), ('start', 'rec_a', 1.0), ('start', 'rec_b', 1.0)]


def test_best_effort_start_asap_leaves_a_running_controller_alone(rig):
    # startControllersAsap() starts only the requested controllers that do not run yet
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.switch(['rec_a', 'rec_b'], [], BEST_EFFORT, 1.0, start_asap=True)
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'running'}
    assert rig.events() == [('start', 'rec_a', 0.0), ('start', 'rec_b', 1.0)]


def test_strict_stop_not_running(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_b'], [], STRICT, 0.0)
    assert rig.cm.request_switch([], ['rec_a', 'rec_b'], STRICT) is None
    assert "Could not stop controller 'rec_a' since it is not running" in rig.log.errors[-1]
    assert rig.states() == {'rec_a': 'initialized', 'rec_b': 'running'}


def test_best_effort_stop_not_running(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_b'], [], STRICT, 0.0)
    assert rig.switch([], ['rec_a', 'rec_b'], BEST_EFFORT, 1.0)
    assert rig.states() == {'rec_a': 'initialized', 'rec_b': 'stopped'}
    assert ('stop', 'rec_a', 1.0) not in rig.journal


@pytest.mark.parametrize('strictness', [STRICT, BEST_EFFORT])
def test_a_running_controller_in_both_lists_is_refused(rig, strictness):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.cm.request_switch(['rec_a', 'rec_b'], ['rec_a'], strictness) is None
    assert ("Could no start or stop controller 'rec_a' because of conflicting switching command"
            in rig.log.errors[-1])
    rig.cm.update(1.0, DT)
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'initialized'}
    assert rig.events() == [('start', 'rec_a', 0.0)]


def test_a_stopped_controller_in_both_lists(rig):
    # not running: STRICT refuses the stop; BEST_EFFORT drops the stop and starts it
    rig.load_all('rec_a')
    assert rig.cm.request_switch(['rec_a'], ['rec_a'], STRICT) is None
    assert "Could not stop controller 'rec_a' since it is not running" in rig.log.errors[-1]
    assert rig.switch(['rec_a'], ['rec_a'], BEST_EFFORT, 1.0)
    assert rig.states() == {'rec_a': 'running'}
    assert rig.events() == [('start', 'rec_a', 1.0)]


def test_stopped_controller_can_be_started_again(rig):
    rig.load_all('rec_a')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.switch([], ['rec_a'], STRICT, 1.0)
    assert rig.switch(['rec_a'], [], STRICT, 2.0)
    assert rig.states() == {'rec_a': 'running'}


@pytest.mark.parametrize('strictness, words', [(0, 'Defaulting to ::BEST_EFFORT'), (3, 'treated as BEST_EFFORT'),
                                               (255, 'treated as BEST_EFFORT')])
def test_other_strictness_falls_back_to_best_effort_with_a_warning(rig, strictness, words):
    rig.load_all('rec_a')
    assert rig.switch(['rec_a', 'ghost'], [], strictness, 0.0)
    assert rig.states() == {'rec_a': 'running'}
    assert any(words in w for w in rig.log.warnings)
    assert any('STRICT (2)' in w and 'BEST_EFFORT (1)' in w for w in rig.log.warnings)


def test_strictness_zero_is_best_effort_not_strict(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert rig.switch(['rec_a', 'rec_b'], [], 0, 1.0)  # STRICT would refuse: rec_a already runs
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'running'}


def test_resource_conflict_refused(rig):
    rig.load_all('left_rear_wheel_velocity_controller', 'rear_wheel_effort')
    for strictness in (STRICT, BEST_EFFORT):
        assert not rig.switch(['left_rear_wheel_velocity_controller', 'rear_wheel_effort'], [], strictness, 0.0)
        assert 'Could not switch controllers, due to resource conflict' in rig.log.errors[-1]
        assert ('Resource conflict on [left_rear_wheel_joint].  Controllers = '
                '[left_rear_wheel_velocity_controller, rear_wheel_effort, ]') in rig.log.warnings[-1]
    assert set(rig.states().values()) == {'initialized'}


def test_conflicts_are_per_joint_whatever_the_interfaces(rig):
    # RobotHW::checkForConflict maps resource names to controllers: one joint claimed through two
    # interfaces is a conflict too
    rig.params['rec_velocity'] = {'type': Recorder.type_name, 'joints': ['left_front_wheel_joint'],
                                  'claim_as': VELOCITY}
    rig.load_all('rec_a', 'rec_velocity', 'rec_b')
    assert rig.cm.request_switch(['rec_a', 'rec_velocity'], [], BEST_EFFORT) is None
    assert 'Resource conflict on [left_front_wheel_joint]' in rig.log.warnings[-1]
    assert rig.switch(['rec_a', 'rec_b'], [], STRICT, 0.0)  # different joints: fine
    assert rig.switch(['rec_velocity'], ['rec_a'], STRICT, 1.0)  # handed over in one switch: fine


def test_resource_conflict_with_a_running_controller(rig):
    rig.load_all('left_rear_wheel_velocity_controller', 'rear_wheel_effort')
    assert rig.switch(['left_rear_wheel_velocity_controller'], [], STRICT, 0.0)
    assert not rig.switch(['rear_wheel_effort'], [], STRICT, 1.0)
    assert rig.states()['rear_wheel_effort'] == 'initialized'
    # Handing the joint over in one switch is fine.
    assert rig.switch(['rear_wheel_effort'], ['left_rear_wheel_velocity_controller'], STRICT, 2.0)
    assert rig.states() == {'left_rear_wheel_velocity_controller': 'stopped', 'rear_wheel_effort': 'running'}


def test_joint_state_controller_claims_nothing_so_no_conflict(rig):
    rig.params['jsc2'] = dict(PARAMS['joint_state_controller'])
    rig.load_all('joint_state_controller', 'jsc2', 'left_rear_wheel_velocity_controller')
    assert rig.switch(['joint_state_controller', 'jsc2', 'left_rear_wheel_velocity_controller'], [], STRICT, 0.0)
    assert rig.io.topics['/racebot/joint_states']


def test_stopping_a_controller_zeroes_its_joints(rig):
    rig.load_all('left_rear_wheel_velocity_controller')
    assert rig.switch(['left_rear_wheel_velocity_controller'], [], STRICT, 0.0)
    rig.io.send('/racebot/left_rear_wheel_velocity_controller/command', 5.0)
    rig.cm.update(0.0, DT)
    assert rig.hw.handles['left_rear_wheel_joint'].command == 5.0
    assert rig.switch([], ['left_rear_wheel_velocity_controller'], STRICT, DT)
    assert rig.hw.handles['left_rear_wheel_joint'].command == 0.0


def test_a_switch_happens_at_the_next_update_with_its_time(rig):
    # ros_control carries a switch out in the realtime loop, after that update's controllers ran
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_b'], [], STRICT, 0.0)
    request = rig.cm.request_switch(['rec_a'], ['rec_b'], STRICT)
    assert request is not None and not request.done.is_set()
    assert rig.states() == {'rec_a': 'initialized', 'rec_b': 'running'}
    rig.cm.update(0.25, DT)
    assert request.done.is_set() and request.ok
    assert rig.journal[-3:] == [('update', 'rec_b', 0.25), ('stop', 'rec_b', 0.25), ('start', 'rec_a', 0.25)]
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'stopped'}


def test_one_switch_at_a_time(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.cm.request_switch(['rec_a'], [], STRICT) is not None
    assert rig.cm.request_switch(['rec_b'], [], STRICT) is None
    assert 'still waiting for the simulation to update' in rig.log.errors[-1]


def test_switch_waits_for_the_update_loop(rig):
    rig.load_all('rec_a')
    with rig.updating():
        assert rig.cm.switch(['rec_a'], [], STRICT, timeout=0.0)  # 0: no bound on the wait
    assert rig.states() == {'rec_a': 'running'}


@pytest.mark.parametrize('timeout', [-0.95, -1.5, float('nan')])
def test_switch_timeout_bounds_the_wait_and_withdraws_the_switch(rig, timeout):
    # controller_manager 0.20 waits timeout + 1 s of wall time (no bound for 0), then answers false
    rig.load_all('rec_a')
    begin = time.monotonic()
    assert not rig.cm.switch(['rec_a'], [], STRICT, timeout=timeout)  # no update comes (paused)
    assert time.monotonic() - begin < 1.0
    assert 'did not update within the timeout' in rig.log.errors[-1]
    rig.cm.update(1.0, DT)  # the simulation goes on: the withdrawn switch does not happen
    assert rig.states() == {'rec_a': 'initialized'} and rig.cm.pending is None
    assert rig.switch(['rec_a'], [], STRICT, 2.0)  # and the next one is accepted


def test_switch_stops_waiting_on_shutdown(rig):
    rig.load_all('rec_a')
    assert not rig.cm.switch(['rec_a'], [], STRICT, timeout=0.0, keep_waiting=lambda: False)
    request = rig.cm.request_switch(['rec_a'], [], STRICT)
    rig.cm.shutdown()  # the model is deleted while a switch waits: its caller gets false
    assert request.done.is_set() and not request.ok


# -- list ---------------------------------------------------------------------------------------

def test_list_with_claimed_resources(rig):
    rig.load_all('joint_state_controller', 'left_rear_wheel_velocity_controller',
                 'left_steering_hinge_position_controller')
    assert rig.switch(['joint_state_controller', 'left_steering_hinge_position_controller'], [], STRICT, 0.0)
    assert rig.switch([], ['left_steering_hinge_position_controller'], STRICT, 0.0)
    assert rig.cm.list() == [
        ('joint_state_controller', 'joint_state_controller/JointStateController', 'running', [(STATE, [])]),
        ('left_rear_wheel_velocity_controller', 'effort_controllers/JointVelocityController', 'initialized',
         [(EFFORT, ['left_rear_wheel_joint'])]),
        ('left_steering_hinge_position_controller', 'effort_controllers/JointPositionController', 'stopped',
         [(EFFORT, ['left_steering_hinge_joint'])]),
    ]


# -- reload_controller_libraries ----------------------------------------------------------------

def test_reload_libraries_with_nothing_loaded(rig):
    assert rig.cm.reload_libraries(False)
    assert rig.cm.reload_libraries(True)


def test_reload_libraries_refused_while_controllers_are_loaded(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    assert not rig.cm.reload_libraries(False)
    assert 'force_kill' in rig.log.errors[-1]
    assert rig.states() == {'rec_a': 'running', 'rec_b': 'initialized'}


def test_reload_libraries_force_kill_stops_and_unloads_everything(rig):
    rig.load_all('rec_a', 'rec_b', 'rec_c')
    assert rig.switch(['rec_a', 'rec_c'], [], STRICT, 0.0)
    with rig.updating():  # the stop is carried out by an update
        assert rig.cm.reload_libraries(True)
    assert rig.cm.list() == []
    assert [e[:2] for e in rig.events()[-2:]] == [('stop', 'rec_a'), ('stop', 'rec_c')]
    assert rig.cm.load('rec_a')


# -- update ---------------------------------------------------------------------------------------

def test_update_runs_running_controllers_in_load_order(rig):
    rig.load_all('rec_b', 'rec_c', 'rec_a')
    assert rig.switch(['rec_a', 'rec_b'], [], STRICT, 0.0)
    del rig.journal[:]
    rig.cm.update(0.5, DT)
    assert rig.journal == [('update', 'rec_b', 0.5), ('update', 'rec_a', 0.5)]


def test_update_nothing_when_nothing_runs(rig):
    rig.load_all('rec_a')
    rig.cm.update(0.0, DT)
    assert rig.events() == []


def test_reset_controllers_stops_and_starts_running_ones(rig):
    rig.load_all('rec_a', 'rec_b')
    assert rig.switch(['rec_a'], [], STRICT, 0.0)
    del rig.journal[:]
    rig.cm.update(3.0, DT, reset_controllers=True)
    assert rig.journal == [('stop', 'rec_a', 3.0), ('start', 'rec_a', 3.0), ('update', 'rec_a', 3.0)]


def test_reset_controllers_position_controller_holds_new_position_and_pid_is_reset(rig):
    name = 'left_steering_hinge_position_controller'
    joint = rig.hw.handles['left_steering_hinge_joint']
    rig.load_all(name)
    assert rig.switch([name], [], STRICT, 0.0)
    controller = rig.cm.loaded[name].controller
    rig.io.send('/racebot/%s/command' % name, 0.3)
    t = 0.0
    for _ in range(20):
        rig.cm.update(t, DT)
        t += DT
    assert controller.pid.i_error > 0.0
    # The world was reset with the hinge somewhere else: the controller must hold it there.
    joint.reset_position(-0.2)
    rig.cm.update(t, DT, reset_controllers=True)
    assert controller.command == pytest.approx(-0.2)
    assert controller.pid.i_error == 0.0
    assert joint.command == 0.0
    # Without a reset it would have kept pushing towards the old command.
    rig.io.send('/racebot/%s/command' % name, 0.3)
    rig.cm.update(t + DT, DT)
    assert joint.command > 0.0


def test_shutdown_unloads_everything(rig):
    rig.load_all('joint_state_controller', 'left_rear_wheel_velocity_controller')
    assert rig.switch(['joint_state_controller'], [], STRICT, 0.0)
    rig.cm.shutdown()
    assert rig.cm.list() == []
    assert all(t.unregistered for t in rig.io.topics.values())


def test_namespace_normalised():
    log = FakeLog()
    model = urdf_reader.parse_urdf(racebot_like_urdf())
    hw = RobotHW(model, hardware_joints(model))
    for ns, expected in (('racebot', '/racebot'), ('/racebot/', '/racebot'), ('/', ''), ('', '')):
        assert ControllerManager(ns, hw, lambda n: None, FakeIO(), log, CONTROLLER_TYPES).ns == expected


def test_a_controller_raising_in_update_is_stopped_and_the_others_keep_running():
    """One broken controller must not stop the simulation loop (nor the other controllers)."""
    log = FakeLog()
    model = urdf_reader.parse_urdf(racebot_like_urdf())
    hw = RobotHW(model, hardware_joints(model))
    params = {'broken': {'type': 'test/Broken'}, 'fine': {'type': 'test/Counting'}}

    class Broken(Controller):
        type_name, interface = 'test/Broken', EFFORT

        def update(self, time, period):
            raise ZeroDivisionError('boom')

    class Counting(Controller):
        type_name, interface = 'test/Counting', EFFORT
        updates = 0

        def update(self, time, period):
            Counting.updates += 1

    cm = ControllerManager('/bot', hw, params.get, FakeIO(), log,
                           types={'test/Broken': Broken, 'test/Counting': Counting})
    assert cm.load('broken') and cm.load('fine')
    assert cm.request_switch(['broken', 'fine'], [], STRICT)
    cm.update(0.0, 0.001)
    cm.update(0.001, 0.001)
    cm.update(0.002, 0.001)
    states = {name: state for name, _, state, _ in cm.list()}
    assert states == {'broken': 'stopped', 'fine': 'running'}
    assert Counting.updates == 2
    assert any("Controller 'broken' raised ZeroDivisionError" in m for m in log.errors)


# -- C++ controllers (ros_control/compiled_controllers.py gives them; the rostest compiled_plugins runs real ones) --

class CompiledTypes:
    """What CompiledControllers answers the manager: pluginlib's declared types, those whose library is built,
    and make() (a controller, or ControllerInitError as a C++ init that returned false)."""

    def __init__(self, declared, built, failing=()):
        self.declared, self.built_types, self.failing = set(declared), set(built), set(failing)
        self.made = []

    def types(self):
        return sorted(self.declared)

    def built(self, type_name):
        return type_name in self.built_types

    def make(self, name, type_name):
        if type_name not in self.declared:
            return None
        if type_name in self.failing:
            raise ControllerInitError('C++ controller %s: its init returned false' % type_name)
        self.made.append((name, type_name))
        controller = Recorder(name, NS, {'joints': []}, None, None)
        controller.journal = []
        return controller


def compiled_rig(compiled, **params):
    rig = Rig(dict(PARAMS, **params))
    rig.cm.compiled = compiled
    return rig


def test_a_type_racebot_lacks_is_made_by_pluginlib():
    compiled = CompiledTypes(declared={'lab_controllers/Arm'}, built={'lab_controllers/Arm'})
    rig = compiled_rig(compiled, arm={'type': 'lab_controllers/Arm'})
    assert rig.cm.load('arm'), rig.log.errors
    assert compiled.made == [('arm', 'lab_controllers/Arm')]
    assert rig.cm.list()[0][:3] == ('arm', 'lab_controllers/Arm', 'initialized')
    assert 'lab_controllers/Arm' in rig.cm.type_names()


def test_a_failing_cpp_init_is_an_error_naming_it():
    compiled = CompiledTypes(declared={'lab_controllers/Arm'}, built={'lab_controllers/Arm'},
                             failing={'lab_controllers/Arm'})
    rig = compiled_rig(compiled, arm={'type': 'lab_controllers/Arm'})
    assert not rig.cm.load('arm')
    assert "Initializing controller 'arm' failed: C++ controller lab_controllers/Arm" in rig.log.errors[-1]
    assert rig.cm.list() == []


def test_a_built_cpp_controller_runs_instead_of_racebots_python_one():
    python_type = 'effort_controllers/JointEffortController'
    compiled = CompiledTypes(declared={python_type}, built={python_type})
    rig = compiled_rig(compiled)
    assert rig.cm.load('rear_wheel_effort'), rig.log.errors
    assert compiled.made == [('rear_wheel_effort', python_type)]


def test_racebots_python_controller_is_the_fallback_for_one_not_built_or_not_loading():
    python_type = 'effort_controllers/JointEffortController'
    declared_only = CompiledTypes(declared={python_type}, built=())  # racebot's own plugin XML: no library
    rig = compiled_rig(declared_only)
    assert rig.cm.load('rear_wheel_effort'), rig.log.errors
    assert declared_only.made == [] and rig.log.warnings == []
    failing = CompiledTypes(declared={python_type}, built={python_type}, failing={python_type})
    rig = compiled_rig(failing)
    assert rig.cm.load('rear_wheel_effort'), rig.log.errors
    assert "racebot's Python %s runs instead" % python_type in rig.log.warnings[-1]
    assert rig.cm.list()[0][1] == python_type


def test_list_controller_types_gives_python_then_cpp_types_once():
    compiled = CompiledTypes(declared={'lab_controllers/Arm', 'effort_controllers/JointEffortController'}, built=())
    rig = compiled_rig(compiled)
    names = rig.cm.type_names()
    assert names.count('effort_controllers/JointEffortController') == 1
    assert names[-1] == 'lab_controllers/Arm'
    assert names[:-1] == sorted(names[:-1])
