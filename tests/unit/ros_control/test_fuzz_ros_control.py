"""Property tests (hypothesis) of the ros_control stand-in: the PID never produces a non-finite
output from finite inputs, the hardware never writes a non-finite or over-limit effort whatever
the command, and the controller manager never raises, whatever names, strictness or
configurations its services are given. No ROS master.
"""
import copy
import math

import rospy
from hypothesis import HealthCheck, example, given, settings, strategies as st

from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.controller_manager import ControllerManager
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, JointHandle, RobotHW
from racebot_sim_bridge.ros_control.pid import Pid
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES

from fakes import FakeLog

SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])

gain = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False)
signal = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)
period = st.floats(min_value=1e-6, max_value=1.0, allow_nan=False)
any_float = st.floats(allow_nan=True, allow_infinity=True)


# -- PID ------------------------------------------------------------------------------------------

@SETTINGS
@given(p=gain, i=gain, d=gain, i_clamp=st.floats(min_value=0.0, max_value=1e6), antiwindup=st.booleans(),
       steps=st.lists(st.tuples(signal, period), min_size=1, max_size=30))
def test_pid_output_finite_for_finite_inputs(p, i, d, i_clamp, antiwindup, steps):
    pid = Pid(p, i, d, -i_clamp, i_clamp, antiwindup)
    for error, dt in steps:
        out = pid.compute(error, dt)
        assert math.isfinite(out)
        assert out == pid.command
        assert -i_clamp - 1e-9 <= pid.i_term <= i_clamp + 1e-9


@SETTINGS
@given(p=gain, error=any_float, dt=any_float)
@example(p=1.0, error=math.nan, dt=0.001)
@example(p=1.0, error=1.0, dt=math.inf)
@example(p=1.0, error=1.0, dt=0.0)
@example(p=-2.0, error=8.98846567431158e+307, dt=0.5)  # once p * error -> -inf and error_dot -> +inf: NaN
def test_pid_never_raises_and_bad_input_gives_zero(p, error, dt):
    pid = Pid(p, 1.0, 1.0, -1.0, 1.0)
    pid.compute(0.5, 0.01)
    before = (pid.p_error, pid.i_error, pid.d_error, pid.command)
    out = pid.compute(error, dt)
    if not (math.isfinite(error) and math.isfinite(dt) and dt > 0):
        assert out == 0.0
        assert (pid.p_error, pid.i_error, pid.d_error, pid.command) == before
    else:
        assert math.isfinite(out)  # errors and gains near the float range saturate instead of overflowing
        assert out == pid.command


# -- hardware limits ------------------------------------------------------------------------------

@SETTINGS
@given(command=any_float, position=any_float, velocity=any_float,
       max_effort=st.floats(min_value=1e-3, max_value=1e6),
       kind=st.sampled_from(['revolute', 'continuous', 'prismatic']))
@example(command=math.nan, position=0.0, velocity=0.0, max_effort=5.0, kind='revolute')
@example(command=math.inf, position=0.0, velocity=0.0, max_effort=5.0, kind='continuous')
@example(command=-math.inf, position=math.nan, velocity=math.nan, max_effort=5.0, kind='revolute')
@example(command=1e300, position=1.0, velocity=-2000.0, max_effort=5.0, kind='revolute')
def test_limited_effort_finite_and_within_limit(command, position, velocity, max_effort, kind):
    h = JointHandle('j', kind, EFFORT, lower=-0.6, upper=0.6, max_effort=max_effort, max_velocity=1000.0)
    h.reset_position(position)
    h.velocity = velocity
    h.command = command
    out = h.limited_command()
    assert math.isfinite(out)
    assert -max_effort <= out <= max_effort
    if math.isfinite(command) and -max_effort <= command <= max_effort:
        assert out in (command, 0.0)  # passed through, or cut at a position or velocity limit


@SETTINGS
@given(readings=st.lists(st.floats(min_value=-math.pi, max_value=math.pi), min_size=1, max_size=50))
def test_unwrapped_position_is_congruent_to_the_reading(readings):
    h = JointHandle('w', 'continuous', EFFORT, max_effort=10.0)
    previous = None
    for r in readings:
        h.read(r, 0.0)
        assert math.isfinite(h.position)
        turns = (h.position - r) / (2 * math.pi)
        assert abs(turns - round(turns)) < 1e-6
        if previous is not None:  # each reading moves the joint the short way round
            assert abs(h.position - previous) <= math.pi + 1e-9
        previous = h.position


# -- controller manager ---------------------------------------------------------------------------

JOINTS = ('left_rear_wheel_joint', 'right_rear_wheel_joint', 'left_steering_hinge_joint')
CONFIGS = {
    'jsc': {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50},
    'lrw': {'type': 'effort_controllers/JointVelocityController', 'joint': JOINTS[0], 'pid': {'p': 1.0}},
    'rrw': {'type': 'effort_controllers/JointVelocityController', 'joint': JOINTS[1], 'pid': {'p': 1.0}},
    'lrw_effort': {'type': 'effort_controllers/JointEffortController', 'joint': JOINTS[0]},
    'steer': {'type': 'effort_controllers/JointPositionController', 'joint': JOINTS[2],
              'pid': {'p': 1.0, 'i': 0.1, 'i_clamp': 1.0}},
    'bad': {'type': 'effort_controllers/JointVelocityController', 'joint': 'nope', 'pid': {'p': 1.0}},
    'untyped': {'joint': JOINTS[0]},
}


def _urdf():
    parts = ['<robot name="r"><link name="base"/>']
    for j in JOINTS:
        kind, limit = (('revolute', 'lower="-0.6" upper="0.6" effort="5" velocity="1000"') if 'hinge' in j
                       else ('continuous', 'effort="10" velocity="1000"'))
        parts.append('<link name="%s_l"/><joint name="%s" type="%s"><parent link="base"/><child link="%s_l"/>'
                     '<axis xyz="0 0 1"/><limit %s/></joint>' % (j, j, kind, j, limit))
        parts.append('<transmission name="%s_t"><joint name="%s"><hardwareInterface>'
                     'hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>' % (j, j))
    return ''.join(parts) + '</robot>'


class _Topic:
    def publish(self, msg):
        pass

    def unregister(self):
        pass


class _IO:
    def publisher(self, topic, cls, queue_size):
        return _Topic()

    def subscriber(self, topic, cls, callback):
        return _Topic()

    def stamp(self, t):
        return rospy.Time.from_sec(t)

    def warn_throttle(self, key, period, message):
        pass


def _manager(configs):
    model = urdf_reader.parse_urdf(_urdf())
    hw = RobotHW(model, hardware_joints(model))
    for h in hw.handles.values():
        h.read(0.0, 0.0)
    return ControllerManager('/racebot', hw, lambda n: copy.deepcopy(configs.get(n)), _IO(), FakeLog(),
                             CONTROLLER_TYPES), hw


names = st.one_of(st.sampled_from(sorted(CONFIGS) + ['', 'ghost', '/racebot/lrw', 'lrw ']), st.text(max_size=12))
operation = st.one_of(
    st.tuples(st.just('load'), names),
    st.tuples(st.just('unload'), names),
    st.tuples(st.just('switch'), st.lists(names, max_size=4), st.lists(names, max_size=4),
              st.integers(min_value=-3, max_value=300)),
    st.tuples(st.just('update'), st.booleans()),
    st.tuples(st.just('list')),
    st.tuples(st.just('reload'), st.booleans()),
)


@SETTINGS
@given(preload=st.booleans(), ops=st.lists(operation, max_size=25))
@example(preload=True, ops=[('switch', ['lrw', 'lrw_effort'], [], 2), ('switch', ['lrw'], [], 1),
                            ('switch', ['lrw_effort'], [], 0), ('update', True)])
def test_controller_manager_never_raises(preload, ops):
    cm, hw = _manager(CONFIGS)
    if preload:  # every configured controller loaded: switches then meet real resource conflicts
        for name in sorted(CONFIGS):
            cm.load(name)
    t = 0.0
    for op in ops:
        kind = op[0]
        if kind == 'load':
            assert cm.load(op[1]) in (True, False)
        elif kind == 'unload':
            assert cm.unload(op[1]) in (True, False)
        elif kind == 'switch':  # accepted or refused; an accepted one happens at the next update
            request = cm.request_switch(op[1], op[2], op[3])
            if request is not None:
                cm.update(t, 0.001)
                assert request.done.is_set() and request.ok
        elif kind == 'update':
            cm.update(t, 0.001, reset_controllers=op[1])
            t += 0.001
        elif kind == 'reload':
            if not op[1] or not cm.loaded:  # a force_kill with controllers loaded waits for an update
                assert cm.reload_libraries(op[1]) in (True, False)
        listed = cm.list()
        assert {s for _, _, s, _ in listed} <= {'initialized', 'running', 'stopped'}
        # Never two running controllers on one joint.
        claimed = [r for _, _, s, res in listed if s == 'running' for _, rs in res for r in rs]
        assert len(claimed) == len(set(claimed))
        assert all(math.isfinite(h.command) for h in hw.handles.values())


scalar = st.one_of(st.none(), st.booleans(), st.integers(min_value=-5, max_value=5), st.floats(),
                   st.text(max_size=6), st.sampled_from(JOINTS))
config_value = st.one_of(scalar, st.lists(scalar, max_size=3),
                         st.dictionaries(st.sampled_from(['p', 'i', 'name', 'position']), scalar, max_size=2),
                         st.lists(st.dictionaries(st.sampled_from(['name', 'position', 'x']), scalar, max_size=2),
                                  max_size=2))
config_key = st.sampled_from(['joint', 'joints', 'pid', 'publish_rate', 'extra_joints', 'p'])


VALID_BASE = {'publish_rate': 50, 'joint': 'left_rear_wheel_joint', 'pid': {'p': 1.0}}


@SETTINGS
@given(type_name=st.sampled_from(['joint_state_controller/JointStateController',
                                  'effort_controllers/JointVelocityController',
                                  'effort_controllers/JointPositionController',
                                  'effort_controllers/JointEffortController']),
       overrides=st.dictionaries(config_key, config_value, min_size=1, max_size=2))
def test_load_never_raises_for_any_configuration(type_name, overrides):
    # A valid configuration with one or two parameters replaced by anything YAML can hold.
    config = dict(VALID_BASE, type=type_name)
    config.update(overrides)
    cm, _ = _manager({'c': config})
    ok = cm.load('c')
    assert ok in (True, False)
    if ok:
        request = cm.request_switch(['c'], [], 2)
        cm.update(0.0, 0.001)
        assert request is None or request.ok
