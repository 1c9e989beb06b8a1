"""Unit tests of ros_control.hardware_interface: gazebo_ros_control's DefaultRobotHWSim as our RobotHW.

Checks the promises of reference/INTERFACES.md: continuous (and revolute) joint positions are
accumulated across +-pi, never wrapped; effort joints are limited as joint_limits_interface's
EffortJointSaturationHandle does (saturation to the URDF effort, no effort further past a position
or velocity limit); a NaN command writes no effort; resource errors name joint and interface.
No ROS master, no PyBullet: a small URDF is parsed with urdf_model.
"""
import math

import pytest

from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.kinematics.angles import shortest_angular_distance
from racebot_sim_bridge.ros_control.hardware_interface import (EFFORT, POSITION, STATE, VELOCITY, HardwareError,
                                                               JointHandle, RobotHW, cpp_name)

TWO_PI = 2.0 * math.pi


def _transmission(joint, interface):
    return ('<transmission name="%s_tr"><type>transmission_interface/SimpleTransmission</type>'
            '<joint name="%s"><hardwareInterface>%s</hardwareInterface></joint>'
            '<actuator name="%s_motor"><mechanicalReduction>1</mechanicalReduction></actuator>'
            '</transmission>' % (joint, joint, interface, joint))


# name: (type, limit attributes, interface)
JOINTS = {
    'hinge': ('revolute', 'lower="-0.6" upper="0.6" effort="5" velocity="1000"', EFFORT),
    'wheel': ('continuous', 'effort="10" velocity="1000"', EFFORT),
    'slider': ('prismatic', 'lower="0" upper="0.5" effort="20" velocity="2"', EFFORT),
    'spinner': ('continuous', 'effort="3" velocity="4"', VELOCITY),
    'servo': ('revolute', 'lower="-1" upper="1" effort="2" velocity="3"', POSITION),
    'welded': ('fixed', None, EFFORT),
}


def make_urdf():
    links = ['<link name="base"/>'] + ['<link name="%s_link"/>' % n for n in JOINTS]
    joints, transmissions = [], []
    for name, (kind, limit, interface) in JOINTS.items():
        joints.append('<joint name="%s" type="%s"><parent link="base"/><child link="%s_link"/>%s%s</joint>'
                      % (name, kind, name, '<axis xyz="0 0 1"/>' if kind != 'fixed' else '',
                         '<limit %s/>' % limit if limit else ''))
        transmissions.append(_transmission(name, interface))
    return '<robot name="t">%s%s%s</robot>' % (''.join(links), ''.join(joints), ''.join(transmissions))


@pytest.fixture
def hw():
    model = urdf_reader.parse_urdf(make_urdf())
    return RobotHW(model, hardware_joints(model))


def wrap(angle):
    """What the physics engine reports for a revolute joint: the angle in (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


# -- RobotHW construction -------------------------------------------------------------------------

def test_handles_for_every_actuated_joint_in_alphabetical_order(hw):
    assert hw.names == ['hinge', 'servo', 'slider', 'spinner', 'wheel']
    assert hw.handles['hinge'].interface == EFFORT
    assert hw.handles['spinner'].interface == VELOCITY
    assert hw.handles['servo'].interface == POSITION
    assert hw.interfaces() == sorted([EFFORT, VELOCITY, POSITION, STATE])


def test_fixed_joint_transmission_is_skipped_with_a_warning(hw):
    assert 'welded' not in hw.handles
    assert any("'welded'" in w and 'fixed' in w for w in hw.warnings), hw.warnings


def test_limits_taken_from_urdf(hw):
    h = hw.handles['hinge']
    assert (h.lower, h.upper, h.max_effort, h.max_velocity) == (-0.6, 0.6, 5.0, 1000.0)
    assert h.has_position_limits
    assert not hw.handles['wheel'].has_position_limits  # continuous: URDF gives lower = upper = 0


def test_cpp_name():
    assert cpp_name(EFFORT) == 'hardware_interface::EffortJointInterface'


# -- unwrapping ---------------------------------------------------------------------------------

def test_continuous_joint_crossing_pi_is_accumulated_not_wrapped(hw):
    h = hw.handles['wheel']
    h.read(3.1, 0.0)
    h.read(-3.1, 0.0)  # the engine wrapped 3.1832 to -3.1
    assert h.position == pytest.approx(6.2 - 3.1 + (TWO_PI - 6.2), abs=1e-12)
    assert h.position > math.pi


@pytest.mark.parametrize('direction', [1.0, -1.0])
def test_continuous_joint_accumulates_many_turns(hw, direction):
    h = hw.handles['wheel']
    true_angle = 0.0
    h.read(0.0, 0.0)
    for _ in range(200):  # 0.3 rad per reading: 60 rad, almost ten turns
        true_angle += direction * 0.3
        h.read(wrap(true_angle), direction * 30.0)
    assert h.position == pytest.approx(direction * 60.0, abs=1e-9)
    assert h.velocity == direction * 30.0


@pytest.mark.parametrize('readings', [
    [0.0, math.pi, 0.0, -math.pi, 0.0],               # steps of exactly +pi and -pi
    [3.0, -3.0, 3.0, math.pi, -math.pi, 1e-300, 0.0],  # across the wrap both ways, and a step of 2 pi
    [0.1 * k for k in range(80)] + [-0.1 * k for k in range(80)],  # beyond pi without wrapping
])
def test_unwrapping_adds_exactly_what_shortest_angular_distance_gives(hw, readings):
    # read() adds a small step as it is (the common case, no fmod); the sum must stay bit for bit the one
    # shortest_angular_distance gives, as a run repeats to the last bit.
    h = hw.handles['wheel']
    h.read(readings[0], 0.0)
    expected = readings[0]
    for previous, raw in zip(readings, readings[1:]):
        h.read(raw, 0.0)
        expected += shortest_angular_distance(previous, raw)
        assert h.position == expected


def test_revolute_joint_is_unwrapped_too(hw):
    # DefaultRobotHWSim accumulates every non-prismatic joint.
    h = hw.handles['hinge']
    h.read(3.0, 0.0)
    h.read(-3.0, 0.0)
    assert h.position == pytest.approx(TWO_PI - 3.0, abs=1e-12)


def test_prismatic_joint_is_not_unwrapped(hw):
    h = hw.handles['slider']
    h.read(3.1, 0.0)
    h.read(-3.1, 0.0)
    assert h.position == -3.1


def test_first_reading_is_taken_as_is(hw):
    h = hw.handles['wheel']
    h.read(2.5, 1.0)
    assert (h.position, h.velocity) == (2.5, 1.0)


def test_reset_position_forgets_the_accumulated_turns(hw):
    h = hw.handles['wheel']
    h.read(0.0, 0.0)
    for k in range(1, 40):
        h.read(wrap(0.3 * k), 0.0)
    assert h.position == pytest.approx(0.3 * 39)
    h.reset_position(0.5)
    assert (h.position, h.velocity) == (0.5, 0.0)
    h.read(0.6, 0.0)
    assert h.position == pytest.approx(0.6)


# -- limits (EffortJointSaturationHandle) --------------------------------------------------------

@pytest.mark.parametrize('command, expected', [(100.0, 5.0), (-100.0, -5.0), (3.0, 3.0), (-4.99, -4.99), (0.0, 0.0)])
def test_effort_saturated_to_urdf_limit(hw, command, expected):
    h = hw.handles['hinge']
    h.command = command
    assert h.limited_command() == expected


def test_wheel_effort_saturated_to_its_own_limit(hw):
    h = hw.handles['wheel']
    h.command = 1e9
    assert h.limited_command() == 10.0
    h.command = -1e9
    assert h.limited_command() == -10.0


@pytest.mark.parametrize('position, command, expected', [
    (0.7, 3.0, 0.0),     # above the upper limit: no effort pushing further up
    (0.7, -3.0, -3.0),   # back towards the range: allowed
    (0.7, -30.0, -5.0),  # ... and still saturated
    (-0.7, -3.0, 0.0),   # below the lower limit: no effort pushing further down
    (-0.7, 3.0, 3.0),
    (0.6, 3.0, 3.0),     # on the limit is not past it
    (-0.6, -3.0, -3.0),
])
def test_no_effort_past_a_position_limit(hw, position, command, expected):
    h = hw.handles['hinge']
    h.read(position, 0.0)
    h.command = command
    assert h.limited_command() == expected


@pytest.mark.parametrize('position, command, expected', [
    (0.6, 7.0, 0.0), (0.6, -7.0, -7.0), (-0.1, -7.0, 0.0), (-0.1, 7.0, 7.0)])
def test_no_force_past_a_prismatic_limit(hw, position, command, expected):
    h = hw.handles['slider']
    h.read(position, 0.0)
    h.command = command
    assert h.limited_command() == expected


@pytest.mark.parametrize('velocity, command, expected', [
    (1001.0, 4.0, 0.0),    # faster than the limit: no effort accelerating further
    (1001.0, -4.0, -4.0),  # braking is allowed
    (-1001.0, -4.0, 0.0),
    (-1001.0, 4.0, 4.0),
    (999.0, 4.0, 4.0),
])
def test_no_effort_past_a_velocity_limit(hw, velocity, command, expected):
    h = hw.handles['wheel']
    h.read(0.0, velocity)
    h.command = command
    assert h.limited_command() == expected


def test_continuous_joint_has_no_position_limit(hw):
    h = hw.handles['wheel']
    h.read(0.0, 0.0)
    for k in range(1, 30):
        h.read(wrap(0.3 * k), 0.0)  # far beyond 0 = "upper" of a continuous joint's <limit>
    h.command = 4.0
    assert h.limited_command() == 4.0
    h.command = -4.0
    assert h.limited_command() == -4.0


@pytest.mark.parametrize('name', ['hinge', 'wheel', 'slider'])
def test_nan_command_writes_no_effort(hw, name):
    h = hw.handles[name]
    h.command = math.nan
    assert h.limited_command() == 0.0


def test_velocity_and_position_commands_are_clamped(hw):
    v = hw.handles['spinner']
    v.command = 10.0
    assert v.limited_command() == 4.0
    v.command = -10.0
    assert v.limited_command() == -4.0
    p = hw.handles['servo']
    p.command = 2.0
    assert p.limited_command() == 1.0
    p.command = -0.5
    assert p.limited_command() == -0.5


def test_zero_or_missing_effort_limit_means_unlimited():
    h = JointHandle('j', 'continuous', EFFORT, max_effort=None)
    h.command = 1e6
    assert h.limited_command() == 1e6


def test_reset_commands(hw):
    for h in hw.handles.values():
        h.command = 1.0
    hw.reset_commands()
    assert all(h.command == 0.0 for h in hw.handles.values())


# -- handle() ------------------------------------------------------------------------------------

def test_handle_returns_the_joint(hw):
    assert hw.handle('hinge', EFFORT) is hw.handles['hinge']
    assert hw.handle('spinner', VELOCITY) is hw.handles['spinner']


def test_state_interface_offers_every_joint(hw):
    for name in hw.names:
        assert hw.handle(name, STATE) is hw.handles[name]


def test_unknown_joint_error_names_resource_and_interface(hw):
    with pytest.raises(HardwareError) as err:
        hw.handle('nope_joint', EFFORT)
    msg = str(err.value)
    assert "'nope_joint'" in msg
    assert 'hardware_interface::EffortJointInterface' in msg
    assert 'hinge' in msg and 'wheel' in msg  # what the robot does offer
    assert 'spinner' not in msg  # a velocity joint is not on offer as an effort joint


def test_wrong_interface_error_names_resource_and_interface(hw):
    with pytest.raises(HardwareError) as err:
        hw.handle('wheel', VELOCITY)
    msg = str(err.value)
    assert "'wheel'" in msg
    assert 'hardware_interface::VelocityJointInterface' in msg


def test_unknown_joint_on_state_interface(hw):
    with pytest.raises(HardwareError) as err:
        hw.handle('nope_joint', STATE)
    assert 'hardware_interface::JointStateInterface' in str(err.value)
