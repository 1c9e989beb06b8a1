"""Property tests (hypothesis) of the pure parts against bad input (issue 7), beyond the existing
ones (test_servo_logic, test_transform_logic, test_fuzz_ros_control, the readers' random-text tests):

  Ackermann <-> wheel commands: any float in, never an exception; None exactly for non-finite input;
      for anything an AckermannDrive (float32) can carry, finite commands within the hinge limit that
      imply the commanded (clamped) motion back: speed and curvature recovered from the rear wheels;
  Twist -> Ackermann: any float in; bad Twists leave no trace in the converter's state;
  PID: any parameter dictionary gives a Pid with finite gains or a ValueError naming the namespace;
      reset() leaves no memory (no windup survives it);
  URDF and SDF readers given malformed *documents* (a valid document with one to three mutations:
      elements dropped or duplicated, attributes and values replaced by nasty ones, references broken,
      text cut): only UrdfError / WorldError, and what they accept, the simulator spawns or refuses
      with SpawnError, and the physics builds or skips with a warning, and keeps stepping.
No ROS master; PyBullet in DIRECT mode.
"""
import copy
import math
import xml.etree.ElementTree as ET

import pytest
from hypothesis import HealthCheck, assume, event, example, given, settings, strategies as st

from racebot_control.twist_to_ackermann import FLOAT32_MAX, TwistToAckermann
from racebot_control.wheel_commands import (
    ACKERMANN, PARALLEL, CarGeometry, WheelCommands, curvature, wheel_commands)
from racebot_sim_bridge.description import sdf_reader, urdf_model, urdf_reader
from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.ros_control.pid import Pid

from fakes import FakeLog

SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
HEAVY = settings(max_examples=40, deadline=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
G = CarGeometry()

any_float = st.floats(allow_nan=True, allow_infinity=True)
float32 = st.floats(width=32, allow_nan=False, allow_infinity=False)
modes = st.sampled_from([PARALLEL, ACKERMANN])


# -- Ackermann <-> wheel commands ---------------------------------------------------------------------

@SETTINGS
@given(speed=any_float, steering=any_float, mode=modes)
@example(speed=math.nan, steering=0.0, mode=PARALLEL)
@example(speed=1e300, steering=1e300, mode=ACKERMANN)
@example(speed=-math.inf, steering=5e-324, mode=ACKERMANN)
def test_wheel_commands_any_float_none_exactly_for_non_finite(speed, steering, mode):
    out = wheel_commands(speed, steering, mode)
    if not (math.isfinite(speed) and math.isfinite(steering)):
        assert out is None
    else:
        assert isinstance(out, WheelCommands)
        for hinge in out[4:]:
            assert abs(hinge) <= G.max_steering_angle + 1e-12


@SETTINGS
@given(speed=float32, steering=float32, mode=modes)
@example(speed=FLOAT32_MAX, steering=-FLOAT32_MAX, mode=ACKERMANN)
@example(speed=1e9, steering=1e9, mode=PARALLEL)
def test_wheel_commands_of_any_ackermann_message_are_finite(speed, steering, mode):
    out = wheel_commands(speed, steering, mode)
    assert all(math.isfinite(v) for v in out), out


@SETTINGS
@given(speed=st.floats(-50.0, 50.0).filter(lambda v: abs(v) > 1e-3), steering=st.floats(-3.2, 3.2))
def test_ackermann_wheel_commands_imply_the_commanded_motion(speed, steering):
    """Back from the wheels: the rear wheels' mean is the speed, their difference the curvature."""
    out = wheel_commands(speed, steering, ACKERMANN)
    v_left, v_right = out.left_rear_wheel * G.wheel_radius, out.right_rear_wheel * G.wheel_radius
    assert (v_left + v_right) / 2 == pytest.approx(speed, rel=1e-9, abs=1e-12)
    k = (v_right - v_left) / (G.track * speed)
    assert k == pytest.approx(curvature(steering), rel=1e-9, abs=1e-12)
    # and the hinges point at that turning centre (the bicycle angle of the axle middle)
    assert math.atan(G.wheelbase * k) == pytest.approx(
        math.atan(G.wheelbase * curvature(steering)), abs=1e-9)


@SETTINGS
@given(speed=float32, steering=float32)
def test_parallel_wheel_commands_imply_the_commanded_motion(speed, steering):
    out = wheel_commands(speed, steering, PARALLEL)
    assert set(out[:4]) == {speed / G.wheel_radius}
    assert out[0] * G.wheel_radius == pytest.approx(speed, rel=1e-12)
    assert out[4] == out[5] == max(-G.max_steering_angle, min(G.max_steering_angle, steering))


@SETTINGS
@given(field=st.sampled_from(CarGeometry._fields),
       value=st.one_of(any_float, st.none(), st.text(max_size=3), st.integers(-5, 5),
                       st.sampled_from([0.0, -0.0, 1e-300, -1e-3, math.pi / 2, 0.09, 1e300])))
def test_car_geometry_rejects_bad_numbers_or_gives_finite_commands(field, value):
    """servo_commands' geometry parameters, one of them bad: refused, or the commands stay finite."""
    try:
        g = CarGeometry(**dict(G._asdict(), **{field: value}))
    except (ValueError, TypeError):
        return
    for mode in (PARALLEL, ACKERMANN):
        assert all(math.isfinite(v) for v in wheel_commands(1.0, 0.5, mode, g))


# -- Twist -> Ackermann --------------------------------------------------------------------------

@SETTINGS
@given(linear=any_float, angular=any_float, convert=st.booleans())
@example(linear=4e38, angular=0.0, convert=False)
@example(linear=0.0, angular=-math.inf, convert=True)
def test_twist_any_float_never_raises(linear, angular, convert):
    out = TwistToAckermann(convert_yaw_rate=convert).convert(linear, angular)
    representable = all(math.isfinite(v) and abs(v) <= FLOAT32_MAX for v in (linear, angular))
    if not representable:
        assert out is None
        return
    assert all(math.isfinite(v) for v in out)
    if convert:
        assert abs(out.steering_angle) <= 0.6 + 1e-12
    else:
        assert out.steering_angle == angular


bad_twist = st.tuples(st.sampled_from([math.nan, math.inf, -math.inf, 1e39, -1e300]), float32) | \
    st.tuples(float32, st.sampled_from([math.nan, math.inf, -math.inf, 1e39]))


@SETTINGS
@given(twists=st.lists(st.one_of(st.tuples(float32, float32).map(lambda t: ('good', t)),
                                 bad_twist.map(lambda t: ('bad', t))), max_size=30),
       convert=st.booleans())
def test_bad_twists_leave_no_trace(twists, convert):
    """A converter fed good and bad Twists answers the good ones exactly as one fed only those."""
    mixed, clean = TwistToAckermann(convert_yaw_rate=convert), TwistToAckermann(convert_yaw_rate=convert)
    for kind, (linear, angular) in twists:
        out = mixed.convert(linear, angular)
        if kind == 'bad':
            assert out is None
        else:
            assert out == clean.convert(linear, angular)
    assert math.isfinite(mixed.last_steering_angle)


# -- PID ---------------------------------------------------------------------------------------

param_value = st.one_of(any_float, st.integers(-10 ** 20, 10 ** 20), st.booleans(), st.none(),
                        st.text(max_size=4), st.lists(st.integers(), max_size=2))
pid_params = st.dictionaries(st.sampled_from(['p', 'i', 'd', 'i_clamp', 'i_clamp_min', 'i_clamp_max',
                                              'antiwindup', 'publish_state', 'x']), param_value, max_size=7)


@SETTINGS
@given(params=st.one_of(pid_params, param_value))
@example(params={'p': math.nan})
@example(params={'p': 1.0, 'i_clamp': math.inf})
@example(params={'p': 1.0, 'antiwindup': 'yes'})
def test_pid_from_params_finite_gains_or_a_value_error_naming_where(params):
    where = '/racebot/wheel/pid'
    try:
        pid = Pid.from_params(params, where)
    except ValueError as err:
        assert where in str(err)
        return
    assert all(math.isfinite(g) for g in (pid.p, pid.i, pid.d, pid.i_clamp_min, pid.i_clamp_max))
    assert pid.i_clamp_min <= 0.0 <= pid.i_clamp_max
    assert math.isfinite(pid.compute(1.0, 0.001))


step = st.tuples(st.floats(-1e3, 1e3), st.floats(1e-4, 0.1))


@SETTINGS
@given(gains=st.tuples(st.floats(-100, 100), st.floats(-100, 100), st.floats(-10, 10), st.floats(0, 1e3)),
       antiwindup=st.booleans(), history=st.lists(step, min_size=1, max_size=30),
       after=st.lists(step, min_size=1, max_size=10))
def test_pid_reset_leaves_no_windup(gains, antiwindup, history, after):
    """What a controller's starting() relies on after a reset: a used PID, reset, is a new PID."""
    p, i, d, clamp = gains
    used, fresh = Pid(p, i, d, -clamp, clamp, antiwindup), Pid(p, i, d, -clamp, clamp, antiwindup)
    for error, dt in history:
        used.compute(error, dt)
    used.reset()
    for error, dt in after:
        assert used.compute(error, dt) == fresh.compute(error, dt)


# -- malformed documents: one valid document, a few mutations ---------------------------------------

NASTY = ['', ' ', 'nan', 'inf', '-inf', '-1', '0', '1e400', '-1e400', 'abc', '1 2', '0 0 0', '-0.6 0.6',
         '1 nan 1', '1 1 1', '99999999', 'base_link', 'no_such_link', 'continuous', 'fixed', 'floating',
         'hardware_interface/Nothing']


@st.composite
def mutated(draw, document, max_mutations=3):
    """`document` (XML text) with 1..max_mutations random mutations (or cut short)."""
    root = ET.fromstring(document)
    for _ in range(draw(st.integers(1, max_mutations))):
        elements = list(root.iter())
        parents = {c: p for p in elements for c in p}
        target = draw(st.sampled_from(elements))
        op = draw(st.sampled_from(['drop', 'duplicate', 'attribute', 'text', 'drop_attribute', 'rename']))
        if op == 'drop' and target in parents:
            parents[target].remove(target)
        elif op == 'duplicate' and target in parents:
            parents[target].append(copy.deepcopy(target))
        elif op == 'attribute' and target.attrib:
            target.set(draw(st.sampled_from(sorted(target.attrib))), draw(st.sampled_from(NASTY)))
        elif op == 'text':
            target.text = draw(st.sampled_from(NASTY))
        elif op == 'drop_attribute' and target.attrib:
            del target.attrib[draw(st.sampled_from(sorted(target.attrib)))]
        elif op == 'rename' and target in parents:
            target.tag = draw(st.sampled_from(['link', 'joint', 'model', 'collision', 'geometry', 'box',
                                               'limit', 'transmission', 'gazebo', 'sensor', 'plugin', 'x']))
    text = ET.tostring(root, encoding='unicode')
    if draw(st.booleans()) and draw(st.integers(0, 9)) == 0:
        text = text[:draw(st.integers(0, len(text)))]
    return text


class NoIO:
    """No topics: controllers are not loaded by these tests."""

    def publisher(self, *a):
        raise AssertionError('no publisher expected')

    subscriber = publisher


@pytest.fixture(scope='module')
def racebot_doc():
    from racebot_model import render_racebot
    return render_racebot(pretty=False)


@pytest.fixture(scope='module')
def simulator():
    from racebot_sim_bridge.engine.simulator import Simulator
    from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
    spec = sdf_reader.load_world('worlds/empty.world')
    sim = Simulator(spec, NoIO(), FakeLog(), lambda path: None)
    GazeboRosControlPlugin.attach(sim)
    yield sim
    sim.close()


@HEAVY
@given(data=st.data())
def test_malformed_urdf_documents_raise_only_urdf_error_and_spawn_or_are_refused(racebot_doc, simulator, data):
    from racebot_sim_bridge.engine.simulator import SpawnError
    text = data.draw(mutated(racebot_doc))
    try:
        model = urdf_reader.parse_urdf(text)
    except urdf_model.UrdfError as err:
        assert str(err)
        model = None
    if model is not None:
        try:
            hardware_joints(model)
        except urdf_model.UrdfError as err:
            assert str(err)
    # The simulator faces the same text as robot_description: a robot, or a SpawnError; never a crash.
    name = 'fuzzed'
    try:
        simulator.spawn_urdf(name, text, '/fuzzed')
        event('spawned')
    except SpawnError as err:
        assert str(err).startswith('SpawnModel: Failure')
        event('refused')
    if name in simulator.model_names():
        for _ in range(20):
            simulator.step()
        pose = simulator.body(name).frame_pose()
        assert all(math.isfinite(v) for v in tuple(pose.position) + tuple(pose.orientation)), pose
        simulator.delete_model(name)
    simulator.step()


def test_a_transmission_naming_a_missing_joint_is_gazebo_ros_controls_business(racebot_doc, simulator):
    """urdfdom does not read transmissions: the URDF parses; hardware_joints refuses; the simulator
    spawns the model without a controller manager and says why (as gazebo_ros_control)."""
    text = racebot_doc.replace('<joint name="left_rear_wheel_joint">', '<joint name="no_such_joint">', 1)
    assert text != racebot_doc
    model = urdf_reader.parse_urdf(text)
    with pytest.raises(urdf_model.UrdfError, match="names joint 'no_such_joint', which does not exist"):
        hardware_joints(model)
    simulator.log.lines[:] = []
    robot = simulator.spawn_urdf('missing_joint', text, '/missing_joint')
    try:
        assert robot.control is None
        errors = [m for level, m in simulator.log.lines if level == 'error']
        assert len(errors) == 1 and 'spawned without a controller manager' in errors[0]
    finally:
        simulator.delete_model('missing_joint')


ROOMLET = '''<?xml version="1.0"?>
<sdf version="1.6"><world name="roomlet">
  <physics type="ode"><max_step_size>0.001</max_step_size><real_time_update_rate>0</real_time_update_rate></physics>
  <gravity>0 0 -9.8</gravity>
  <model name="ground"><static>true</static><link name="l"><collision name="c"><geometry>
    <plane><normal>0 0 1</normal><size>20 20</size></plane></geometry></collision></link></model>
  <model name="wall"><static>true</static><pose>2 0 0.5 0 0 0</pose><link name="l">
    <collision name="c"><geometry><box><size>0.1 4 1</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>0.1 4 1</size></box></geometry></visual></link></model>
  <model name="barrel"><pose>-1 1 0.5 0 0 0.3</pose><link name="l"><inertial><mass>2</mass></inertial>
    <collision name="c"><geometry><cylinder><radius>0.2</radius><length>1</length></cylinder></geometry>
      <surface><friction><ode><mu>0.8</mu></ode></friction></surface></collision></link></model>
  <model name="ball"><pose>0 -1 0.3 0 0 0</pose><link name="l"><inertial><mass>1</mass></inertial>
    <collision name="c"><geometry><sphere><radius>0.3</radius></sphere></geometry></collision></link></model>
  <include><uri>model://sun</uri></include>
</world></sdf>'''


@HEAVY
@given(data=st.data())
def test_malformed_sdf_documents_raise_only_world_error_and_load_with_warnings(data):
    from racebot_sim_bridge.engine.physics import PhysicsWorld
    text = data.draw(mutated(ROOMLET))
    try:
        world = sdf_reader.parse_world(text)
    except sdf_reader.WorldError as err:
        assert str(err)
        event('WorldError')
        return
    assume(0.0 < world.physics.max_step_size <= 0.01)  # a step the reader accepted; 1 s steps are slow
    physics = PhysicsWorld(world.physics.max_step_size, world.physics.gravity)
    try:
        warnings = []
        created = physics.load_world(world, warn=warnings.append)
        # every model the reader kept is built, or skipped with a warning naming it, or is a robot (a <plugin>,
        # joint or sensor mutated in), which load_world leaves to the Simulator's URDF path
        plain = [m for m in world.models if not m.is_robot]
        for model in plain:
            assert model.name in created or any("model '%s'" % model.name in w for w in warnings)
        event('loaded, %s' % ('a model skipped' if len(created) < len(plain) else 'all models built'))
        for _ in range(50):
            physics.step()
    finally:
        physics.close()


@pytest.mark.parametrize('value', ['', 'abc', 'nan', '-1'])
def test_friction_that_is_not_a_number_is_ignored_with_a_warning(racebot_doc, simulator, value):
    """Found by the fuzzing above: an empty <mu1/> made the spawn raise a bare ValueError."""
    text = racebot_doc.replace('<gazebo reference="left_rear_wheel"><mu1>2.0</mu1>',
                               '<gazebo reference="left_rear_wheel"><mu1>%s</mu1>' % value, 1)
    assert text != racebot_doc
    model = urdf_reader.parse_urdf(text)
    assert any("<gazebo reference='left_rear_wheel'> <mu1>" in w and 'ignored' in w for w in model.warnings)
    simulator.spawn_urdf('odd_friction', text, '/odd_friction')
    simulator.delete_model('odd_friction')
