"""{position,velocity,effort}_controllers/JointTrajectoryController on a real Simulator (a two-joint turret, no
gravity load), driven through its `command` topic and its action callbacks with goal handles recorded in memory:
each variant reaches a two-point trajectory within 0.02 rad at its time; goals are accepted, preempted,
canceled and finished as upstream's goal callbacks decide; query_state samples the trajectory. No ROS master."""
import pytest
import rospy
from control_msgs.msg import FollowJointTrajectoryGoal, FollowJointTrajectoryResult, JointTolerance
from control_msgs.srv import QueryTrajectoryStateRequest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.ros_controllers.joint_trajectory_controller import (EffortJointTrajectoryController,
                                                                            PositionJointTrajectoryController,
                                                                            VelocityJointTrajectoryController)
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from trajectory_io import IO, GoalHandle, trajectory
from fakes import FakeLog

TURRET = """<robot name="turret">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="20" velocity="5"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="b"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit effort="20" velocity="5"/></joint>
  <transmission name="t1"><joint name="j1">
    <hardwareInterface>hardware_interface/%(iface)s</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="j2">
    <hardwareInterface>hardware_interface/%(iface)s</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""
GAINS = {'j1': {'p': 60.0, 'd': 2.0, 'i': 5.0, 'i_clamp': 2.0}, 'j2': {'p': 60.0, 'd': 2.0, 'i': 5.0, 'i_clamp': 2.0}}
VARIANTS = [(PositionJointTrajectoryController, 'PositionJointInterface', {}),
            # velocity_ff 1: the desired velocity fed forward (a P term alone lags a ramp by velocity / p)
            (VelocityJointTrajectoryController, 'VelocityJointInterface', {'gains': {'j1': {'p': 20.0},
                                                                                     'j2': {'p': 20.0}},
                                                                           'velocity_ff': {'j1': 1.0, 'j2': 1.0}}),
            (EffortJointTrajectoryController, 'EffortJointInterface', {'gains': GAINS})]


def arm(cls, iface, params):
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('turret', TURRET % {'iface': iface})
    io = IO()
    params = dict(params, joints=['j1', 'j2'], constraints={'goal_time': 0.5, 'j1': {'goal': 0.02},
                                                            'j2': {'goal': 0.02}})
    controller = cls('arm', '/turret', params, robot.control.hw, io)
    controller.starting(sim.time)
    return sim, robot, io, controller


def run(sim, controller, seconds):
    for _ in range(int(round(seconds / sim.step_size))):
        controller.update(sim.time, sim.step_size)
        sim.robots['turret'].control.write(sim.world, sim.step_size)
        sim.world.step()
        sim.steps += 1
        sim.time += sim.step_size
        sim.robots['turret'].control.read(sim.world)


@pytest.mark.parametrize('cls, iface, params', VARIANTS)
def test_each_variant_follows_a_command_to_its_points_in_time(cls, iface, params):
    sim, robot, io, controller = arm(cls, iface, params)
    io.topics['/turret/arm/command'].callback(trajectory([((0.5, -0.4), 1.0), ((1.0, 0.6), 2.0)]))
    run(sim, controller, 1.0)
    h = robot.control.hw.handles
    assert (h['j1'].position, h['j2'].position) == (pytest.approx(0.5, abs=0.02), pytest.approx(-0.4, abs=0.02))
    run(sim, controller, 1.5)
    assert (h['j1'].position, h['j2'].position) == (pytest.approx(1.0, abs=0.02), pytest.approx(0.6, abs=0.02))
    states = io.topics['/turret/arm/state'].messages
    assert states and list(states[-1].joint_names) == ['j1', 'j2']  # published at state_publish_rate (50 Hz)
    assert len(states) == pytest.approx(2.5 * 50, abs=2)


def test_goals_succeed_are_preempted_canceled_and_rejected_as_upstream():
    sim, robot, io, controller = arm(*VARIANTS[0])
    goal_cb, cancel_cb = io.actions['/turret/arm/follow_joint_trajectory']
    first = GoalHandle(FollowJointTrajectoryGoal(trajectory=trajectory([((1.5, 1.5), 3.0)])))
    goal_cb(first)
    assert first.status == 'active'
    run(sim, controller, 0.5)
    second = GoalHandle(FollowJointTrajectoryGoal(trajectory=trajectory([((0.3, -0.3), 0.5)])))
    goal_cb(second)
    assert (first.status, second.status) == ('canceled', 'active')  # a new goal preempts the active one
    run(sim, controller, 1.0)
    assert second.status == 'succeeded' and second.result.error_code == FollowJointTrajectoryResult.SUCCESSFUL
    assert second.feedback  # at action_monitor_rate
    third = GoalHandle(FollowJointTrajectoryGoal(trajectory=trajectory([((-1.5, 1.0), 3.0)])))
    goal_cb(third)
    run(sim, controller, 0.5)
    cancel_cb(third)
    assert third.status == 'canceled'
    held = robot.control.hw.handles['j1'].position
    run(sim, controller, 0.5)
    assert robot.control.hw.handles['j1'].position == pytest.approx(held, abs=0.02)  # holds where it was
    unknown = GoalHandle(FollowJointTrajectoryGoal(trajectory=trajectory([((0.1, 0.1), 1.0)], ('j1', 'nope'))))
    goal_cb(unknown)
    assert unknown.status == 'rejected' and unknown.result.error_code == FollowJointTrajectoryResult.INVALID_JOINTS
    past = GoalHandle(FollowJointTrajectoryGoal(trajectory=trajectory([((0.1, 0.1), 1.0)])))
    past.goal.trajectory.header.stamp = rospy.Time.from_sec(0.01)  # long gone
    goal_cb(past)
    assert past.status == 'rejected' and past.result.error_code == FollowJointTrajectoryResult.INVALID_GOAL
    assert 'before the current time' in past.result.error_string


def test_path_tolerance_aborts_a_goal_the_arm_cannot_follow():
    sim, robot, io, controller = arm(*VARIANTS[2])  # effort: a PID, so it lags a fast trajectory
    goal_cb, _ = io.actions['/turret/arm/follow_joint_trajectory']
    goal = FollowJointTrajectoryGoal(trajectory=trajectory([((1.9, 0.0), 0.05)]))
    goal.path_tolerance = [JointTolerance(name='j1', position=0.05)]
    handle = GoalHandle(goal)
    goal_cb(handle)
    run(sim, controller, 0.2)
    assert handle.status == 'aborted'
    assert handle.result.error_code == FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED
    assert handle.result.error_string.startswith('j1 path error')


def test_query_state_samples_the_trajectory():
    sim, robot, io, controller = arm(*VARIANTS[0])
    io.topics['/turret/arm/command'].callback(trajectory([((1.0, 0.0), 2.0)]))
    run(sim, controller, 0.1)
    res = io.services['/turret/arm/query_state'](QueryTrajectoryStateRequest(rospy.Time.from_sec(sim.time + 1.0)))
    assert list(res.name) == ['j1', 'j2'] and 0.4 < res.position[0] < 0.6 and res.velocity[0] > 0
