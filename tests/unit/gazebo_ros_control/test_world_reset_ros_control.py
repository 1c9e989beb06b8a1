"""reset_world / reset_simulation leave ros_control as it was (issue 16, row 4), as
gazebo_ros_control does: its Reset() only sets the last update time back to 0; the controllers
are not restarted, their commands and PID state stay, the joint readings keep unwrapping. The
next update comes at once after reset_world (its period: the time since 0) and one control
period after reset_simulation. A Simulator with real PyBullet, no master."""
import math

import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.ros_control.controller_switch import STRICT
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeIO, FakeLog
from wheel_robot import EMPTY_WORLD, _robot

PARAMS = {
    '/wheel': {'type': 'effort_controllers/JointVelocityController', 'joint': 'wheel_joint',
               'pid': {'p': 0.05, 'i': 0.5, 'i_clamp': 0.2}},
    '/joints': {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50},
}


@pytest.fixture
def driving():
    """A robot at the root namespace, its wheel controller started and commanded to 3 rad/s for 0.3 s."""
    io = FakeIO()
    world = sdf_reader.parse_world(EMPTY_WORLD.replace('<physics', '<gravity>0 0 0</gravity><physics'))
    sim = Simulator(world, io, FakeLog(), lambda path: PARAMS.get(path))
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('bot', _robot(''), '/')
    cm = robot.control.cm
    assert cm.load('wheel') and cm.load('joints')
    assert cm.request_switch(['wheel', 'joints'], [], STRICT)
    sim.step()
    from std_msgs.msg import Float64
    io.topics['/wheel/command'].callback(Float64(3.0))
    periods = []
    update = cm.update
    cm.update = lambda t, period, *a: (periods.append((t, period)), update(t, period, *a))
    while sim.time < 0.3 - 1e-9:
        sim.step()
    yield sim, robot, periods
    sim.close()


def _wheel(robot):
    return robot.control.cm.loaded['wheel'].controller


def test_reset_world_leaves_controllers_commands_and_pid_state(driving):
    sim, robot, periods = driving
    wheel, handle = _wheel(robot), robot.control.hw.handles['wheel_joint']
    assert handle.velocity > 0.5
    i_error, effort, position = wheel.pid.i_error, handle.command, handle.position
    t = sim.time
    sim.reset_world()
    assert {n: s for n, _, s, _ in robot.control.cm.list()} == {'wheel': 'running', 'joints': 'running'}
    assert wheel.command == 3.0  # the command stays in force
    assert wheel.pid.i_error == i_error and handle.command == effort  # nothing restarted, nothing zeroed
    del periods[:]
    sim.step()
    assert periods == [(pytest.approx(t), pytest.approx(t))]  # at once, with the time since 0 as its period
    # the reading unwraps from where it was: the joint is back at 0, the reading at the nearest equivalent
    assert handle.position == pytest.approx(position + math.remainder(-position, 2 * math.pi), abs=1e-3)
    while sim.time < t + 0.2:
        sim.step()
    assert handle.velocity > 0.5  # the controller drives the wheel again, with no new command


def test_reset_simulation_leaves_controllers_and_updates_one_period_later(driving):
    sim, robot, periods = driving
    wheel = _wheel(robot)
    sim.reset_simulation()
    assert sim.time == 0.0
    assert {n: s for n, _, s, _ in robot.control.cm.list()} == {'wheel': 'running', 'joints': 'running'}
    assert wheel.command == 3.0
    del periods[:]
    sim.step()
    assert periods == []  # gazebo_ros_control: no update until a control period has passed since 0
    sim.step()
    assert periods == [(pytest.approx(0.001), pytest.approx(0.001))]
