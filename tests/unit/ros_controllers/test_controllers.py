"""Unit tests of racebot_sim_bridge.ros_controllers against ros_controllers' semantics (INTERFACES.md).

The controllers get the racebot's RobotHW (racecar.xacro rendered with the xacro module) or a small
URDF for joint kinds the racebot lacks, and an in-memory I/O object that records publications and
lets a test deliver command messages. No ROS master.
"""
import math

import pytest
from control_msgs.msg import JointControllerState
from sensor_msgs.msg import JointState

from racebot_sim_bridge.ros_control.controller_interface import STATE_PUBLISH_EVERY, ControllerInitError
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.ros_controllers.effort_controllers import (EffortForwardController, JointPositionController,
                                                                   JointVelocityController)
from racebot_sim_bridge.ros_controllers.joint_state_controller import JointStateController
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, STATE

from controller_hw import make_hw
from fakes import FakeIO

NS = '/racebot'
DT = 0.001
RACEBOT_JOINTS = sorted(['left_steering_hinge_joint', 'right_steering_hinge_joint', 'left_front_wheel_joint',
                         'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint'])


# -- fakes and fixtures ---------------------------------------------------------------------------

@pytest.fixture
def hw(racebot_xml):
    return make_hw(racebot_xml)


EXTRA_URDF = """<robot name="extra">
  <link name="base"/><link name="arm_link"/><link name="slide_link"/>
  <joint name="arm" type="revolute"><parent link="base"/><child link="arm_link"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="5" effort="50" velocity="10"/></joint>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="slide_link"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="50" velocity="10"/></joint>
  <transmission name="t1"><joint name="arm">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="slide">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
</robot>"""


@pytest.fixture
def extra_hw():
    return make_hw(EXTRA_URDF)


@pytest.fixture
def io():
    return FakeIO()


def run(controller, updates, start=0.0, dt=DT):
    """`updates` controller updates at dt from `start` (the first with period dt)."""
    t = start
    for _ in range(updates):
        controller.update(t, dt)
        t += dt
    return t


def velocity_controller(hw, io, pid=None, joint='left_rear_wheel_joint', name='left_rear_wheel_velocity_controller'):
    params = {'type': JointVelocityController.type_name, 'joint': joint, 'pid': pid or {'p': 2.0}}
    c = JointVelocityController(name, NS, params, hw, io)
    c.starting(0.0)
    return c


def position_controller(hw, io, pid=None, joint='left_steering_hinge_joint',
                        name='left_steering_hinge_position_controller'):
    params = {'type': JointPositionController.type_name, 'joint': joint, 'pid': pid or {'p': 1.0}}
    c = JointPositionController(name, NS, params, hw, io)
    c.starting(0.0)
    return c


# -- the type table -------------------------------------------------------------------------------

def test_controller_types_offered():
    for t in ('joint_state_controller/JointStateController', 'effort_controllers/JointEffortController',
              'effort_controllers/JointVelocityController', 'effort_controllers/JointPositionController'):
        assert t in CONTROLLER_TYPES
        assert CONTROLLER_TYPES[t].type_name == t


# -- JointVelocityController ----------------------------------------------------------------------

def test_velocity_controller_topics(hw, io):
    c = velocity_controller(hw, io)
    assert '/racebot/left_rear_wheel_velocity_controller/command' in io.subscribers
    assert io.publishers['/racebot/left_rear_wheel_velocity_controller/state'].cls is JointControllerState
    assert c.claimed_resources() == [(EFFORT, ['left_rear_wheel_joint'])]


def test_velocity_controller_is_p_on_velocity_error(hw, io):
    c = velocity_controller(hw, io, pid={'p': 2.0})
    joint = hw.handles['left_rear_wheel_joint']
    io.send('/racebot/left_rear_wheel_velocity_controller/command', 1.5)
    joint.read(0.0, 0.5)
    c.update(0.0, DT)
    assert joint.command == pytest.approx(2.0 * (1.5 - 0.5))
    joint.read(0.0, 2.0)
    c.update(DT, DT)
    assert joint.command == pytest.approx(2.0 * (1.5 - 2.0))


def test_velocity_controller_uses_the_full_pid(hw, io):
    c = velocity_controller(hw, io, pid={'p': 1.0, 'i': 10.0, 'd': 0.5, 'i_clamp': 100.0})
    joint = hw.handles['left_rear_wheel_joint']
    io.send('/racebot/left_rear_wheel_velocity_controller/command', 1.0)
    c.update(0.0, 0.01)  # error 1: p 1, i 10 * 0.01, no derivative on the first update
    assert joint.command == pytest.approx(1.0 + 0.1)
    joint.read(0.0, 0.5)
    c.update(0.01, 0.01)  # error 0.5: p 0.5, i 10 * 0.015, d 0.5 * (0.5 - 1) / 0.01
    assert joint.command == pytest.approx(0.5 + 0.15 - 25.0)


def test_velocity_controller_start_resets_command_and_pid(hw, io):
    c = velocity_controller(hw, io, pid={'p': 1.0, 'i': 1.0, 'd': 1.0, 'i_clamp': 10.0})
    joint = hw.handles['left_rear_wheel_joint']
    io.send('/racebot/left_rear_wheel_velocity_controller/command', 3.0)
    run(c, 5)
    assert c.pid.i_error != 0.0
    c.stopping(0.005)
    c.starting(0.005)
    assert c.command == 0.0
    assert c.pid.i_error == 0.0 and c.pid.command == 0.0
    joint.read(0.0, 0.0)
    c.update(0.005, DT)
    assert joint.command == 0.0  # command 0, velocity 0, no memory of the old error


def test_velocity_controller_state_every_tenth_update(hw, io):
    c = velocity_controller(hw, io, pid={'p': 2.0, 'i': 0.5, 'd': 0.25, 'i_clamp_min': -3.0, 'i_clamp_max': 4.0,
                                         'antiwindup': True})
    joint = hw.handles['left_rear_wheel_joint']
    joint.read(0.0, 0.25)
    io.send('/racebot/left_rear_wheel_velocity_controller/command', 1.0)
    t = run(c, 21, start=1.0)
    states = io.published('/racebot/left_rear_wheel_velocity_controller/state')
    assert len(states) == 3  # updates 1, 11 and 21
    assert STATE_PUBLISH_EVERY == 10
    assert [s.header.stamp.to_sec() for s in states] == pytest.approx([1.0, 1.01, 1.02])
    s = states[-1]
    assert s.set_point == 1.0
    assert s.process_value == 0.25
    assert s.error == pytest.approx(0.75)
    assert s.time_step == pytest.approx(DT)
    assert s.command == pytest.approx(c.pid.command)
    assert s.command == pytest.approx(joint.command)
    assert (s.p, s.i, s.d, s.i_clamp, s.antiwindup) == (2.0, 0.5, 0.25, 4.0, True)
    run(c, 9, start=t)
    assert len(io.published('/racebot/left_rear_wheel_velocity_controller/state')) == 3
    run(c, 1, start=t + 9 * DT)
    assert len(io.published('/racebot/left_rear_wheel_velocity_controller/state')) == 4


# -- JointPositionController ----------------------------------------------------------------------

@pytest.mark.parametrize('command, set_point', [(2.0, 0.6), (-2.0, -0.6), (0.3, 0.3), (0.6, 0.6)])
def test_position_command_clamped_to_urdf_limits(hw, io, command, set_point):
    c = position_controller(hw, io, pid={'p': 1.0})
    joint = hw.handles['left_steering_hinge_joint']
    io.send('/racebot/left_steering_hinge_position_controller/command', command)
    c.update(0.0, DT)
    state = io.published('/racebot/left_steering_hinge_position_controller/state')[-1]
    assert state.set_point == set_point
    assert joint.command == pytest.approx(set_point)  # p = 1, position 0


def test_position_controller_holds_current_position_when_started(hw, io):
    joint = hw.handles['left_steering_hinge_joint']
    joint.read(0.3, 0.0)
    c = position_controller(hw, io, pid={'p': 5.0, 'd': 1.0})
    assert c.command == pytest.approx(0.3)
    c.update(0.0, DT)
    assert joint.command == 0.0
    state = io.published('/racebot/left_steering_hinge_position_controller/state')[-1]
    assert state.set_point == pytest.approx(0.3) and state.error == 0.0


def test_position_controller_started_beyond_a_limit_holds_the_limit(hw, io):
    joint = hw.handles['left_steering_hinge_joint']
    joint.read(0.7, 0.0)
    c = position_controller(hw, io)
    assert c.command == pytest.approx(0.6)


def test_position_controller_state(hw, io):
    joint = hw.handles['left_steering_hinge_joint']
    joint.read(0.1, 0.2)
    c = position_controller(hw, io, pid={'p': 3.0, 'i': 0.0, 'd': 0.0, 'i_clamp': 1.5})
    io.send('/racebot/left_steering_hinge_position_controller/command', 0.5)
    run(c, 11, start=2.0)
    states = io.published('/racebot/left_steering_hinge_position_controller/state')
    assert len(states) == 2
    s = states[-1]
    assert (s.set_point, s.process_value, s.process_value_dot) == (0.5, 0.1, 0.2)
    assert s.error == pytest.approx(0.4)
    assert s.command == pytest.approx(1.2)
    assert (s.p, s.i, s.d, s.i_clamp) == (3.0, 0.0, 0.0, 1.5)
    assert s.header.stamp.to_sec() == pytest.approx(2.01)


def test_position_controller_continuous_joint_takes_the_shortest_way(hw, io):
    joint = hw.handles['left_front_wheel_joint']
    for k in range(1, 200):  # three turns and a bit: unwrapped to 3 * 2 pi + 0.1
        joint.read(math.atan2(math.sin(k * (6 * math.pi + 0.1) / 199), math.cos(k * (6 * math.pi + 0.1) / 199)), 0)
    assert joint.position == pytest.approx(6 * math.pi + 0.1)
    c = position_controller(hw, io, pid={'p': 1.0}, joint='left_front_wheel_joint', name='wheel_position')
    io.send('/racebot/wheel_position/command', 0.0)
    c.update(0.0, DT)
    assert joint.command == pytest.approx(-0.1)  # not -(6 pi + 0.1)
    io.send('/racebot/wheel_position/command', 100.0)  # no clamping for a continuous joint
    c.update(DT, DT)
    expected = math.remainder(100.0 - (6 * math.pi + 0.1), 2 * math.pi)
    assert joint.command == pytest.approx(expected)


def test_position_controller_revolute_error_respects_large_limits(extra_hw, io):
    # Joint at 4.0 in [-1, 5], target -0.5: the short way (+1.78) leaves the range past 5, so the
    # error is the long way round, -4.5 (angles::shortest_angular_distance_with_large_limits).
    joint = extra_hw.handles['arm']
    joint.reset_position(4.0)
    c = position_controller(extra_hw, io, pid={'p': 1.0}, joint='arm', name='arm_controller')
    io.send('/racebot/arm_controller/command', -0.5)
    c.update(0.0, DT)
    assert joint.command == pytest.approx(-4.5)
    # Within the range and short: the plain difference.
    io.send('/racebot/arm_controller/command', 3.5)
    c.update(DT, DT)
    assert joint.command == pytest.approx(-0.5)


def test_position_controller_prismatic_error_is_the_difference(extra_hw, io):
    joint = extra_hw.handles['slide']
    joint.read(0.1, 0.0)
    c = position_controller(extra_hw, io, pid={'p': 2.0}, joint='slide', name='slide_controller')
    io.send('/racebot/slide_controller/command', 0.8)  # clamped to 0.5
    c.update(0.0, DT)
    assert joint.command == pytest.approx(2.0 * 0.4)


def test_position_controller_start_resets_pid(hw, io):
    joint = hw.handles['left_steering_hinge_joint']
    c = position_controller(hw, io, pid={'p': 1.0, 'i': 1.0, 'i_clamp': 5.0})
    io.send('/racebot/left_steering_hinge_position_controller/command', 0.5)
    run(c, 10)
    assert c.pid.i_error > 0.0
    joint.read(0.2, 0.0)
    c.starting(0.01)
    assert c.pid.i_error == 0.0
    assert c.command == pytest.approx(0.2)


# -- JointEffortController --------------------------------------------------------------------

def test_effort_controller_forwards_the_command(hw, io):
    params = {'type': EffortForwardController.type_name, 'joint': 'right_rear_wheel_joint'}
    c = EffortForwardController('effort', NS, params, hw, io)
    c.starting(0.0)
    joint = hw.handles['right_rear_wheel_joint']
    c.update(0.0, DT)
    assert joint.command == 0.0
    io.send('/racebot/effort/command', 7.5)
    c.update(DT, DT)
    assert joint.command == 7.5
    io.send('/racebot/effort/command', 100.0)  # saturation is the hardware's business
    c.update(2 * DT, DT)
    assert joint.command == 100.0
    assert joint.limited_command() == 10.0
    c.starting(3 * DT)
    c.update(3 * DT, DT)
    assert joint.command == 0.0
    assert c.claimed_resources() == [(EFFORT, ['right_rear_wheel_joint'])]


# -- JointStateController ---------------------------------------------------------------------

def state_controller(hw, io, **params):
    params.setdefault('publish_rate', 50)
    params['type'] = JointStateController.type_name
    c = JointStateController('joint_state_controller', NS, params, hw, io)
    c.starting(0.0)
    return c


@pytest.mark.parametrize('rate', [None, 0, -5, 'fast', True, math.nan, math.inf, [50]])
def test_joint_state_controller_needs_a_valid_publish_rate(hw, io, rate):
    params = {'type': JointStateController.type_name}
    if rate is not None:
        params['publish_rate'] = rate
    with pytest.raises(ControllerInitError) as err:
        JointStateController('joint_state_controller', NS, params, hw, io)
    assert 'publish_rate' in str(err.value)


def test_joint_state_controller_all_joints_in_alphabetical_order(hw, io):
    c = state_controller(hw, io)
    assert io.publishers['/racebot/joint_states'].cls is JointState
    assert c.claimed_resources() == [(STATE, [])]
    for i, name in enumerate(RACEBOT_JOINTS):
        hw.handles[name].read(0.01 * (i + 1), 0.1 * (i + 1))
        hw.handles[name].effort = float(i)
    c.update(0.0, DT)
    msg = io.published('/racebot/joint_states')[0]
    assert list(msg.name) == RACEBOT_JOINTS
    assert list(msg.position) == pytest.approx([0.01 * (i + 1) for i in range(6)])
    assert list(msg.velocity) == pytest.approx([0.1 * (i + 1) for i in range(6)])
    assert list(msg.effort) == [float(i) for i in range(6)]


def test_joint_state_controller_joints_parameter(hw, io):
    c = state_controller(hw, io, joints=['right_rear_wheel_joint', 'left_rear_wheel_joint'])
    c.update(0.0, DT)
    assert list(io.published('/racebot/joint_states')[0].name) == ['right_rear_wheel_joint', 'left_rear_wheel_joint']


def test_joint_state_controller_unknown_joint(hw, io):
    with pytest.raises(ControllerInitError) as err:
        state_controller(hw, io, joints=['no_such_joint'])
    assert 'no_such_joint' in str(err.value)


def test_joint_state_controller_first_publish_on_first_update_then_each_period(hw, io):
    c = state_controller(hw, io, publish_rate=10)
    run(c, 1000, start=5.0)  # one second of 1 kHz updates from t = 5 s
    stamps = [m.header.stamp.to_sec() for m in io.published('/racebot/joint_states')]
    assert stamps[0] == pytest.approx(5.0)
    assert stamps == pytest.approx([5.0 + 0.1 * k for k in range(10)], abs=1e-6)


def test_joint_state_controller_rate_over_a_second(hw, io):
    c = state_controller(hw, io, publish_rate=50)
    run(c, 1000)
    assert len(io.published('/racebot/joint_states')) == 50


def test_joint_state_controller_keeps_the_cadence_between_updates(hw, io):
    # 400 Hz from 1 kHz updates: published at 0, 3, 5, 8, 10 ... ms, 400 times a second on average
    # (ros_controllers adds the period to the last publish time rather than restarting from now).
    c = state_controller(hw, io, publish_rate=400)
    run(c, 1000)
    assert len(io.published('/racebot/joint_states')) == 400


def test_joint_state_controller_uses_sim_time_not_update_count(hw, io):
    c = state_controller(hw, io, publish_rate=10)
    run(c, 100, dt=0.01)  # 100 updates at 100 Hz: one second of sim time
    assert len(io.published('/racebot/joint_states')) == 10


def test_joint_state_controller_restart_publishes_at_once(hw, io):
    c = state_controller(hw, io, publish_rate=1)
    c.update(0.0, DT)
    c.update(0.5, DT)
    assert len(io.published('/racebot/joint_states')) == 1
    c.stopping(0.5)
    c.starting(0.6)
    c.update(0.6, DT)
    assert len(io.published('/racebot/joint_states')) == 2


def test_joint_state_controller_extra_joints(hw, io):
    # ros_controllers' format (joint_state_controller/test/joint_state_controller_extra_joints_ok.yaml):
    # a list of structs with `name` and optional position, velocity, effort (default 0).
    extra = [{'name': 'extra1', 'position': 10.0, 'velocity': 20.0, 'effort': 30.0},
             {'name': 'extra2', 'position': -10.0},
             {'name': 'extra3'}]
    c = state_controller(hw, io, extra_joints=extra)
    c.update(0.0, DT)
    msg = io.published('/racebot/joint_states')[0]
    assert list(msg.name) == RACEBOT_JOINTS + ['extra1', 'extra2', 'extra3']
    assert list(msg.position[6:]) == [10.0, -10.0, 0.0]
    assert list(msg.velocity[6:]) == [20.0, 0.0, 0.0]
    assert list(msg.effort[6:]) == [30.0, 0.0, 0.0]


# -- init errors ----------------------------------------------------------------------------------

@pytest.mark.parametrize('cls', [JointVelocityController, JointPositionController, EffortForwardController])
def test_missing_joint(hw, io, cls):
    with pytest.raises(ControllerInitError) as err:
        cls('c', NS, {'type': cls.type_name, 'pid': {'p': 1.0}}, hw, io)
    msg = str(err.value)
    assert 'joint' in msg.lower() and '/racebot/c' in msg
    assert 'left_rear_wheel_joint' in msg  # says what the choices are


@pytest.mark.parametrize('cls', [JointVelocityController, JointPositionController, EffortForwardController])
def test_unknown_joint(hw, io, cls):
    with pytest.raises(ControllerInitError) as err:
        cls('c', NS, {'type': cls.type_name, 'joint': 'wing_joint', 'pid': {'p': 1.0}}, hw, io)
    msg = str(err.value)
    assert "'wing_joint'" in msg and 'hardware_interface::EffortJointInterface' in msg


@pytest.mark.parametrize('cls', [JointVelocityController, JointPositionController])
@pytest.mark.parametrize('pid', [None, 5.0, {}])
def test_missing_pid(hw, io, cls, pid):
    params = {'type': cls.type_name, 'joint': 'left_rear_wheel_joint'}
    if pid is not None:
        params['pid'] = pid
    with pytest.raises(ControllerInitError) as err:
        cls('c', NS, params, hw, io)
    assert '/racebot/c/pid' in str(err.value)


@pytest.mark.parametrize('pid, key', [({'p': 'stiff'}, 'p'), ({'p': 1.0, 'i': math.nan}, 'i'),
                                      ({'p': 1.0, 'd': [1]}, 'd'), ({'p': 1.0, 'antiwindup': 'yes'}, 'antiwindup'),
                                      ({'p': True}, 'p')])
def test_bad_pid(hw, io, pid, key):
    with pytest.raises(ControllerInitError) as err:
        JointVelocityController('c', NS, {'type': 'x', 'joint': 'left_rear_wheel_joint', 'pid': pid}, hw, io)
    assert '/racebot/c/pid/%s' % key in str(err.value)


def test_failed_init_leaves_no_subscription_behind(hw, io):
    with pytest.raises(ControllerInitError):
        JointVelocityController('c', NS, {'type': 'x', 'joint': 'left_rear_wheel_joint'}, hw, io)
    # The command subscriber was created before the PID failed; it must not stay registered.
    assert all(s.unregistered for s in io.subscribers.values())


def test_shutdown_unregisters_topics(hw, io):
    c = velocity_controller(hw, io)
    c.shutdown()
    assert all(t.unregistered for t in list(io.subscribers.values()) + list(io.publishers.values()))


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_command_is_ignored_with_a_warning(hw, io, bad):
    c = velocity_controller(hw, io)
    io.send('/racebot/left_rear_wheel_velocity_controller/command', 2.0)
    io.send('/racebot/left_rear_wheel_velocity_controller/command', bad)
    assert c.command == 2.0
    assert io.warnings and 'left_rear_wheel_velocity_controller' in io.warnings[-1]
