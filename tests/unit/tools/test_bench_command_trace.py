"""The command-path observer of the command controllers (ros_control/command_trace.py: CommandObserver) and make bench's
CommandTrace on it: a line when a command is taken, a line after the first update that applies it,
the controllers' own methods left in place (no method of a live controller replaced). No master."""
import math

import pytest
import rospy
from std_msgs.msg import Float64

from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.controller_interface import CommandController
from racebot_sim_bridge.ros_control.command_trace import CommandObserver, CommandTrace
from racebot_sim_bridge.ros_controllers.effort_controllers import (EffortForwardController, JointPositionController,
                                                                   JointVelocityController)
from racebot_sim_bridge.ros_controllers.position_controllers import PositionForwardController
from racebot_sim_bridge.ros_controllers.velocity_controllers import (VelocityForwardController,
                                                                     VelocityJointPositionController)
from racebot_sim_bridge.ros_control.hardware_interface import RobotHW

NS = '/robot'
DT = 0.001
URDF = """<robot name="traced">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/>
  <joint name="effort_joint" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="50" velocity="10"/></joint>
  <joint name="velocity_joint" type="continuous"><parent link="base"/><child link="b"/><axis xyz="0 1 0"/>
    <limit effort="50" velocity="10"/></joint>
  <joint name="position_joint" type="revolute"><parent link="base"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="50" velocity="10"/></joint>
  <transmission name="t1"><joint name="effort_joint">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="velocity_joint">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t3"><joint name="position_joint">
    <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint></transmission>
</robot>"""
# (class, joint, extra parameters): every command controller type
TYPES = [(EffortForwardController, 'effort_joint', {}),
         (JointVelocityController, 'effort_joint', {'pid': {'p': 1.0}}),
         (JointPositionController, 'effort_joint', {'pid': {'p': 1.0}}),
         (VelocityForwardController, 'velocity_joint', {}),
         (VelocityJointPositionController, 'velocity_joint', {'pid': {'p': 1.0}}),
         (PositionForwardController, 'position_joint', {})]


class Topic:
    def __init__(self, callback=None):
        self.callback = callback

    def publish(self, msg):
        pass

    def unregister(self):
        pass


class IO:
    def __init__(self, trace=None):
        if trace is not None:
            self.command_trace = trace
        self.subscribers = {}

    def publisher(self, topic, cls, queue_size):
        return Topic()

    def subscriber(self, topic, cls, callback):
        self.subscribers[topic] = Topic(callback)
        return self.subscribers[topic]

    def stamp(self, t):
        return rospy.Time.from_sec(t)

    def warn_throttle(self, key, period, message):
        pass


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        self.t += 0.001
        return self.t


def make(cls, joint, extra, io, name='c'):
    model = urdf_reader.parse_urdf(URDF)
    hw = RobotHW(model, hardware_joints(model))
    for h in hw.handles.values():
        h.read(0.0, 0.0)
    controller = cls(name, NS, dict(extra, type=cls.type_name, joint=joint), hw, io)
    controller.starting(0.0)
    return controller


def send(io, controller, value):
    io.subscribers[controller.topic('command')].callback(Float64(value))


def lines(path):
    with open(path) as f:
        return [line.split() for line in f]


@pytest.fixture
def trace(tmp_path):
    t = CommandTrace(str(tmp_path / 'trace.log'), clock=Clock())
    t.path = str(tmp_path / 'trace.log')
    yield t
    t.close()


@pytest.mark.parametrize('cls,joint,extra', TYPES, ids=[t[0].type_name for t in TYPES])
def test_taken_then_applied_once_by_the_next_update(trace, cls, joint, extra):
    io = IO(trace)
    c = make(cls, joint, extra, io)
    c.update(0.0, DT)  # nothing taken yet: nothing applied
    assert lines(trace.path) == []
    send(io, c, 0.25)
    assert [x[0] for x in lines(trace.path)] == ['arrived']
    c.update(DT, DT)
    c.update(2 * DT, DT)  # the same command again: not a new application
    got = lines(trace.path)
    assert [(x[0], x[2], float(x[3])) for x in got] == [('arrived', NS + '/c', 0.25), ('applied', NS + '/c', 0.25)]
    assert float(got[0][1]) < float(got[1][1])  # applied after it arrived, on the trace's clock


def test_a_command_overtaken_before_any_update_is_never_applied(trace):
    io = IO(trace)
    c = make(JointVelocityController, 'effort_joint', {'pid': {'p': 1.0}}, io)
    send(io, c, 1.0)
    send(io, c, 2.0)
    c.update(DT, DT)
    assert [(x[0], float(x[3])) for x in lines(trace.path)] == [('arrived', 1.0), ('arrived', 2.0), ('applied', 2.0)]


def test_an_update_that_read_the_old_command_does_not_apply_the_new(trace):
    """The subscriber's thread takes a command between an update reading the old one and telling
    the observer: that update applied the old command; the next applies the new one."""
    io = IO(trace)
    c = make(EffortForwardController, 'effort_joint', {}, io)
    send(io, c, 1.0)
    c.update(DT, DT)
    send(io, c, 3.0)
    trace.command_applied(c, 1.0)  # as that update would, with the command it read
    assert [x[0] for x in lines(trace.path)] == ['arrived', 'applied', 'arrived']
    c.update(2 * DT, DT)
    assert [(x[0], float(x[3])) for x in lines(trace.path)][-1] == ('applied', 3.0)


def test_a_clamped_command_arrives_as_sent_and_is_applied_as_kept(trace):
    io = IO(trace)
    c = make(JointPositionController, 'effort_joint', {'pid': {'p': 1.0}}, io)
    send(io, c, 5.0)  # beyond the 0.6 rad limit
    c.update(DT, DT)
    assert [(x[0], float(x[3])) for x in lines(trace.path)] == [('arrived', 5.0), ('applied', 0.6)]


def test_an_ignored_non_finite_command_is_not_taken(trace):
    io = IO(trace)
    c = make(EffortForwardController, 'effort_joint', {}, io)
    send(io, c, math.nan)
    c.update(DT, DT)
    assert lines(trace.path) == []


def test_traced_controllers_keep_their_own_methods(trace):
    """The hook is the controllers' own code: nothing on the instance replaces a class method, and
    the command subscription is the controller's own callback."""
    for cls, joint, extra in TYPES:
        io = IO(trace)
        c = make(cls, joint, extra, io)
        assert not {'update', '_on_command', 'starting'} & set(vars(c)), cls
        callback = io.subscribers[c.topic('command')].callback
        assert callback.__self__ is c and callback.__func__ is CommandController._on_command


class Counting(CommandObserver):
    def __init__(self):
        self.taken, self.applied = [], []

    def command_taken(self, controller, received, kept):
        self.taken.append((controller.name, received, kept))

    def command_applied(self, controller, command):
        self.applied.append((controller.name, command))


@pytest.mark.parametrize('cls,joint,extra', TYPES, ids=[t[0].type_name for t in TYPES])
def test_any_observer_is_told_after_every_update_and_none_means_off(cls, joint, extra):
    observer = Counting()
    io = IO(observer)
    c = make(cls, joint, extra, io)
    send(io, c, 0.5)
    c.update(DT, DT)
    c.update(2 * DT, DT)
    assert observer.taken == [('c', 0.5, 0.5)]
    assert observer.applied == [('c', 0.5), ('c', 0.5)]
    off_io = IO()
    off = make(cls, joint, extra, off_io)
    assert off.observer is None  # an I/O without command_trace: no observer, the same updates
    send(off_io, off, 0.5)
    off.update(DT, DT)
    assert off.command == 0.5
