"""ros_control/hardware_interface.py, pid.py, kinematics/differential.py and kinematics/angles.py run compiled (Cython,
typed by the .pxd beside each; see racebot_sim_bridge/CMakeLists.txt): the build must have compiled them, and the
compiled code must give what the same .py gives as plain Python, bit for bit, on any input (NaN, infinities, -0.0,
ints, huge values). The plain modules are loaded from the .py files themselves."""
import importlib.util
import math
import struct
import sysconfig
from pathlib import Path

import pytest
from hypothesis import example, given, settings, strategies as st

from racebot_sim_bridge.kinematics import angles, differential
from racebot_sim_bridge.ros_control import hardware_interface as hardware, pid

SOURCES = Path(__file__).resolve().parents[3] / 'racebot_sim_bridge' / 'src' / 'racebot_sim_bridge'


def plain(module_name, folder='ros_control'):
    """The module run from its .py by the interpreter (no extension module)."""
    spec = importlib.util.spec_from_file_location('plain_' + module_name, SOURCES / folder / (module_name + '.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


PLAIN_ANGLES = plain('angles', 'kinematics')
PLAIN_HARDWARE = plain('hardware_interface')
# the plain hardware_interface on the plain angle helpers (its import found the compiled ones)
PLAIN_HARDWARE.shortest_angular_distance = PLAIN_ANGLES.shortest_angular_distance
PLAIN_HARDWARE.shortest_angular_distance_with_limits = PLAIN_ANGLES.shortest_angular_distance_with_limits
PLAIN_PID = plain('pid')
PLAIN_DIFFERENTIAL = plain('differential', 'kinematics')


def bits(x):
    """A float by its bits (NaN equals NaN, -0.0 differs from 0.0); anything else as itself."""
    return struct.pack('<d', x) if isinstance(x, float) else x


def outcome(function, *args):
    """What a call gives: its value, or the type of what it raised."""
    try:
        return 'value', bits(function(*args))
    except Exception as err:  # noqa: BLE001 (the exception's type is the outcome compared)
        return 'raised', type(err)


@pytest.mark.parametrize('module', [hardware, pid, differential, angles])
def test_the_build_compiled_the_every_step_modules(module):
    # make setup installs Cython and python3-dev and the build compiles them; a plain .py here means the
    # world runs ~10 % slower than docs/BENCHMARK.md says
    assert module.__file__.endswith(sysconfig.get_config_var('EXT_SUFFIX')), module.__file__


floats = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                   st.floats(-10.0, 10.0), st.sampled_from([0.0, -0.0, math.pi, -math.pi, 2 * math.pi]))
finite = st.floats(-1e6, 1e6)
limits = st.one_of(st.none(), st.floats(-4.0, 4.0), st.integers(-3, 3))


def joint_pair(kind, interface, lower, upper, max_effort, max_velocity):
    args = ('j', kind, interface, lower, upper, max_effort, max_velocity)
    return hardware.JointHandle(*args), PLAIN_HARDWARE.JointHandle(*args)


def state(handle):
    return tuple(bits(float(getattr(handle, a))) for a in ('position', 'velocity', 'effort', 'command'))


@settings(max_examples=400, deadline=None)
@given(kind=st.sampled_from(['revolute', 'continuous', 'prismatic']),
       interface=st.sampled_from([hardware.EFFORT, hardware.VELOCITY, hardware.POSITION, 'other']),
       lower=limits, upper=limits, max_effort=limits, max_velocity=limits,
       steps=st.lists(st.tuples(floats, floats, floats, floats), min_size=1, max_size=12))
@example(kind='revolute', interface=hardware.EFFORT, lower=-0.6, upper=0.6, max_effort=10.0, max_velocity=2.0,
         steps=[(3.1, 0.0, 5.0, 0.3), (-3.1, 3.0, -0.0, -0.3), (math.nan, -3.0, math.inf, 9.0)])
def test_a_joint_handle_compiled_reads_limits_and_aims_as_plain_python(kind, interface, lower, upper, max_effort,
                                                                       max_velocity, steps):
    compiled, reference = joint_pair(kind, interface, lower, upper, max_effort, max_velocity)
    assert compiled.has_position_limits == reference.has_position_limits
    for raw_position, velocity, command, target in steps:
        assert outcome(compiled.read, raw_position, velocity) == outcome(reference.read, raw_position, velocity)
        compiled.command = reference.command = command
        assert state(compiled) == state(reference)
        assert outcome(compiled.limited_command) == outcome(reference.limited_command)
        assert outcome(compiled.clamped_position, target) == outcome(reference.clamped_position, target)
        assert outcome(hardware.position_error, compiled, target) == \
            outcome(PLAIN_HARDWARE.position_error, reference, target)
    assert outcome(compiled.reset_position, steps[0][0]) == outcome(reference.reset_position, steps[0][0])
    assert state(compiled) == state(reference)


@settings(max_examples=300, deadline=None)
@given(a=floats, b=floats, lower=finite, upper=finite)
def test_the_angle_functions_compiled_give_what_plain_python_gives(a, b, lower, upper):
    assert outcome(angles.shortest_angular_distance, a, b) == \
        outcome(PLAIN_ANGLES.shortest_angular_distance, a, b)
    assert outcome(angles.shortest_angular_distance_with_limits, a, b, lower, upper) == \
        outcome(PLAIN_ANGLES.shortest_angular_distance_with_limits, a, b, lower, upper)


def test_the_loop_helpers_compiled_read_and_limit_as_plain_python():
    handles = {}
    for module in (hardware, PLAIN_HARDWARE):
        handles[module] = [module.JointHandle('a', 'revolute', module.EFFORT, -0.5, 0.5, 2.0, 1.0),
                           module.JointHandle('b', 'continuous', module.EFFORT, None, None, 3.0, None)]
        module.read_joint_states(handles[module], [(0.7, 1.5, (0.0,) * 6, 0.0), (-3.0, -0.25, (0.0,) * 6, 0.0)])
        for h, command in zip(handles[module], (5.0, -4.0)):  # a: no push past its limits; b: saturated
            h.command = command
    efforts = hardware.limited_efforts(handles[hardware])
    assert efforts == PLAIN_HARDWARE.limited_efforts(handles[PLAIN_HARDWARE]) == [0.0, -3.0]
    assert [state(h) for h in handles[hardware]] == [state(h) for h in handles[PLAIN_HARDWARE]]


gains = st.floats(-100.0, 100.0)
pid_inputs = st.one_of(floats, st.integers(-5, 5), st.just(1e308), st.just(-1e308))


def pid_state(p):
    return tuple(bits(getattr(p, a)) for a in ('p_error', 'i_error', 'd_error', 'p_term', 'i_term', 'd_term',
                                               'command', 'p', 'i', 'd', 'i_clamp_min', 'i_clamp_max', 'antiwindup'))


@settings(max_examples=400, deadline=None)
@given(p=gains, i=gains, d=gains, i_clamp=st.floats(0.0, 50.0), antiwindup=st.booleans(),
       updates=st.lists(st.tuples(pid_inputs, pid_inputs, pid_inputs, st.booleans()), min_size=1, max_size=12))
@example(p=1e300, i=1e300, d=1e300, i_clamp=0.0, antiwindup=False,
         updates=[(1e308, 1e-300, 0.0, False), (-1e308, 1e-300, 0.0, False), (math.nan, 0.01, 0.0, True)])
def test_a_pid_compiled_computes_as_plain_python(p, i, d, i_clamp, antiwindup, updates):
    compiled = pid.Pid(p, i, d, -i_clamp, i_clamp, antiwindup)
    reference = PLAIN_PID.Pid(p, i, d, -i_clamp, i_clamp, antiwindup)
    for error, dt, error_dot, with_dot in updates:
        if with_dot:
            assert outcome(compiled.compute_with_error_dot, error, error_dot, dt) == \
                outcome(reference.compute_with_error_dot, error, error_dot, dt)
        else:
            assert outcome(compiled.compute, error, dt) == outcome(reference.compute, error, dt)
        assert pid_state(compiled) == pid_state(reference)
    compiled.reset()
    reference.reset()
    assert pid_state(compiled) == pid_state(reference)


def test_a_pid_compiled_refuses_what_plain_python_refuses():
    for args in [('1',), (math.nan,), (1.0, 0.0, 0.0, 1.0, -1.0), (1.0, 0.0, 0.0, 0.0, 0.0, 'yes')]:
        with pytest.raises(ValueError) as compiled_error:
            pid.Pid(*args)
        with pytest.raises(ValueError) as plain_error:
            PLAIN_PID.Pid(*args)
        assert str(compiled_error.value) == str(plain_error.value)
    params = {'p': 2.0, 'i': 1.0, 'i_clamp': 3.0, 'antiwindup': True}
    assert pid_state(pid.Pid.from_params(params)) == pid_state(PLAIN_PID.Pid.from_params(params))
    assert repr(pid.Pid.from_params(params)) == repr(PLAIN_PID.Pid.from_params(params))


wheel_inputs = st.one_of(floats, st.integers(-5, 5), st.just(1e308))


@settings(max_examples=400, deadline=None)
@given(pose=st.tuples(floats, floats, floats), left=wheel_inputs, right=wheel_inputs,
       diameter=st.one_of(st.floats(0.01, 2.0), floats), separation=st.one_of(st.floats(0.05, 3.0), floats),
       dt=st.one_of(st.floats(-0.01, 0.1), floats, st.just(0.0)))
@example(pose=(0.0, 0.0, 0.0), left=1e308, right=-1e308, diameter=2.0, separation=1e-308, dt=1.0)
def test_the_encoder_step_compiled_integrates_as_plain_python(pose, left, right, diameter, separation, dt):
    assert tuple(map(bits_tuple, outcome_parts(differential.encoder_step, pose, left, right, diameter, separation,
                                               dt))) == \
        tuple(map(bits_tuple, outcome_parts(PLAIN_DIFFERENTIAL.encoder_step, pose, left, right, diameter,
                                            separation, dt)))


def outcome_parts(function, *args):
    """What a call gives: ('value', its nested tuples of numbers) or ('raised', the exception's type)."""
    try:
        return 'value', function(*args)
    except Exception as err:  # noqa: BLE001 (the exception's type is the outcome compared)
        return 'raised', type(err)


def bits_tuple(value):
    return tuple(bits_tuple(v) for v in value) if isinstance(value, tuple) else bits(value)


def odometer_state(odometer):
    return tuple(bits(float(getattr(odometer, a))) for a in ('x', 'y', 'theta', 'v', 'w')) + (odometer.last_ns,)


@settings(max_examples=200, deadline=None)
@given(updates=st.lists(st.tuples(st.integers(-2_000_000, 50_000_000), finite, finite), min_size=1, max_size=15),
       diameter=st.floats(0.01, 2.0), separation=st.floats(0.05, 3.0))
def test_the_encoder_odometry_compiled_follows_the_wheels_as_plain_python(updates, diameter, separation):
    readings = []
    odometers = [module.EncoderOdometry(lambda: readings[-1], diameter, separation)
                 for module in (differential, PLAIN_DIFFERENTIAL)]
    pose, twist, last, now = (0.0, 0.0, 0.0), (0.0, 0.0), 0, 0
    for gap, left, right in updates:
        now += gap  # time may also go back (a reset): upstream's dt <= 0 moves nothing
        readings.append(((0.0, left, (0.0,) * 6, 0.0), (0.0, right, (0.0,) * 6, 0.0)))
        for odometer in odometers:
            odometer.update(now)
        compiled, reference = odometers
        assert odometer_state(compiled) == odometer_state(reference)
        assert compiled.wheels is reference.wheels is readings[-1] and compiled.wheels_ns == now
        # and each update is encoder_step from the last pose over the time since the last update
        pose, twist = PLAIN_DIFFERENTIAL.encoder_step(pose, left, right, diameter, separation, (now - last) / 1e9)
        last = now
        assert odometer_state(reference)[:5] == tuple(bits(float(v)) for v in pose + twist)
