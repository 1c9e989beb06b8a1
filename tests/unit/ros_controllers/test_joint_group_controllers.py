"""forward_command_controller's group controllers: JointGroup{Position,Velocity,Effort}Controller
(`joints`, a Float64MultiArray `command` with one value per joint, upstream's refusal of a command of
another size, the position group's start at the current positions and its clamp to the URDF limits)."""
import pytest
from std_msgs.msg import Float64MultiArray

from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, POSITION, VELOCITY

from controller_hw import make_hw
from fakes import FakeIO

ARM = """<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="50" velocity="10"/></joint>
  <joint name="elbow" type="continuous"><parent link="l1"/><child link="l2"/><axis xyz="0 1 0"/></joint>
  <transmission name="t1"><joint name="shoulder">
    <hardwareInterface>hardware_interface/%(iface)s</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="elbow">
    <hardwareInterface>hardware_interface/%(iface)s</hardwareInterface></joint></transmission>
</robot>"""
GROUPS = [('position_controllers/JointGroupPositionController', 'PositionJointInterface', POSITION),
          ('velocity_controllers/JointGroupVelocityController', 'VelocityJointInterface', VELOCITY),
          ('effort_controllers/JointGroupEffortController', 'EffortJointInterface', EFFORT)]


def group(type_name, iface, joints=('elbow', 'shoulder'), positions=(0.3, -0.2)):
    hw = make_hw(ARM % {'iface': iface})
    hw.handles['elbow'].read(positions[0], 0.0)
    hw.handles['shoulder'].read(positions[1], 0.0)
    io = FakeIO()
    c = CONTROLLER_TYPES[type_name]('arm_controller', '/arm', {'type': type_name, 'joints': list(joints)}, hw, io)
    return c, hw, io


def send(io, values):
    io.subscribers['/arm/arm_controller/command'].callback(Float64MultiArray(data=list(values)))


@pytest.mark.parametrize('type_name,iface,interface', GROUPS)
def test_commands_go_to_the_joints_in_the_order_of_joints(type_name, iface, interface):
    c, hw, io = group(type_name, iface)
    assert c.claimed_resources() == [(interface, ['elbow', 'shoulder'])]
    c.starting(0.0)
    send(io, [0.5, 0.25])
    c.update(0.001, 0.001)
    assert (hw.handles['elbow'].command, hw.handles['shoulder'].command) == (0.5, 0.25)


@pytest.mark.parametrize('type_name,iface,interface', GROUPS)
def test_a_command_of_another_size_or_not_finite_is_refused_and_the_last_stays(type_name, iface, interface):
    c, hw, io = group(type_name, iface)
    c.starting(0.0)
    send(io, [0.5, 0.25])
    send(io, [1.0])
    send(io, [0.1, float('nan')])
    c.update(0.001, 0.001)
    assert (hw.handles['elbow'].command, hw.handles['shoulder'].command) == (0.5, 0.25)
    assert 'Dimension of command (1) does not match number of joints (2)! Not executing!' in io.warnings[0]
    assert 'non-finite' in io.warnings[1]


def test_start_holds_positions_for_position_and_zero_for_the_others():
    c, hw, io = group(*GROUPS[0][:2])
    c.starting(0.0)
    c.update(0.001, 0.001)
    assert (hw.handles['elbow'].command, hw.handles['shoulder'].command) == (0.3, -0.2)
    for type_name, iface, _ in GROUPS[1:]:
        c, hw, io = group(type_name, iface)
        hw.handles['elbow'].command = 7.0
        c.starting(0.0)
        c.update(0.001, 0.001)
        assert (hw.handles['elbow'].command, hw.handles['shoulder'].command) == (0.0, 0.0)


def test_position_group_clamps_to_the_urdf_limits_only_where_there_are_limits():
    c, hw, io = group(*GROUPS[0][:2])
    c.starting(0.0)
    send(io, [12.0, 3.0])
    c.update(0.001, 0.001)
    assert (hw.handles['elbow'].command, hw.handles['shoulder'].command) == (12.0, 1.0)


@pytest.mark.parametrize('params,words', [
    ({}, "Failed to getParam 'joints'"), ({'joints': 'elbow'}, "Failed to getParam 'joints'"),
    ({'joints': []}, 'List of joint names is empty'), ({'joints': ['elbow', 'wrist']}, "'wrist'")])
def test_bad_joints_fail_init_with_the_reason(params, words):
    hw = make_hw(ARM % {'iface': 'VelocityJointInterface'})
    cls = CONTROLLER_TYPES['velocity_controllers/JointGroupVelocityController']
    with pytest.raises(ControllerInitError) as err:
        cls('arm_controller', '/arm', dict(params, type=cls.type_name), hw, FakeIO())
    assert words in str(err.value)
