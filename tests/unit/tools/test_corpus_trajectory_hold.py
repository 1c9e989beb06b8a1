"""make corpus's trajectory check on an effort arm that falls until its controller starts (the ur5 row): a
JointTrajectoryController started while the arm still falls holds where its stop trajectory carries the fall
on, below the ground, as upstream's StopTrajectoryBuilder does; a goal sent once the arm rests starts from that
pose and is aborted at once (PATH_TOLERANCE_VIOLATED). The check's hold_command, sent first on the controller's
`command` topic, would make it hold where the arm rests, but a user does not do that: the check, as a user, reads
the abort as that start race (start_race, from the hold the controller's state showed before the goal) and sends
the goal again, which succeeds (upstream's controller carries on along the aborted trajectory).

Real PyBullet, the gazebo_ros_control plugin and its controller manager stepped by a Simulator (loaded and
started as the spawner does), the controller's topics and action in memory (tests/unit/trajectory_io.py's
fakes). No ROS master."""

import pytest
from control_msgs.msg import FollowJointTrajectoryGoal, FollowJointTrajectoryResult

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.ros_control.controller_switch import STRICT

from fakes import FakeLog
from trajectory_io import IO, GoalHandle, trajectory

from corpus.checks import PATH_TOLERANCE_VIOLATED, start_race

# Bolted to the world, both joints about y on effort transmissions; at 0 the arm points along x, level, and
# gravity turns both joints positive (down) until the arm lies on the ground.
ARM = """<robot name="falling_arm">
  <link name="world"/>
  <joint name="bolt" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><origin xyz="0 0 0.05"/><mass value="5"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="upper"><inertial><origin xyz="0.2 0 0"/><mass value="2"/>
      <inertia ixx="0.001" iyy="0.027" izz="0.027" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></collision></link>
  <link name="fore"><inertial><origin xyz="0.15 0 0"/><mass value="1"/>
      <inertia ixx="0.001" iyy="0.008" izz="0.008" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.04 0.04"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0.08 0 0.15"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0.4 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
  <transmission name="t1"><joint name="shoulder">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="elbow">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""
TOLERANCE = 0.1  # rad: path and goal tolerance of each joint, as ur5_controllers.yaml sets them
CONTROLLER = {'type': 'effort_controllers/JointTrajectoryController', 'joints': ['shoulder', 'elbow'],
              'gains': {'shoulder': {'p': 2000.0, 'd': 50.0, 'i': 1.0, 'i_clamp': 1.0},
                        'elbow': {'p': 200.0, 'd': 5.0, 'i': 1.0, 'i_clamp': 1.0}},
              'constraints': {'goal_time': 0.6, 'stopped_velocity_tolerance': 0.05,
                              'shoulder': {'trajectory': TOLERANCE, 'goal': TOLERANCE},
                              'elbow': {'trajectory': TOLERANCE, 'goal': TOLERANCE}},
              'stop_trajectory_duration': 0.5}
LIFT = {'shoulder': -0.5, 'elbow': 0.3}  # the goal, relative to where the arm rests, in 3 s
MID_FALL_STEPS = 60  # the controller starts this many steps after the spawn, the arm still falling
AT_REST_STEPS = 1500  # or this many, the arm lying on the ground
SETTLE_S = 3.0  # as the ur5 row's settle_s


class Rig:
    def __init__(self, start_after_steps):
        self.log = FakeLog()
        self.io = IO()
        self.sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=self.io, log=self.log,
                             get_params=lambda path: CONTROLLER if path.endswith('/arm_controller') else None)
        GazeboRosControlPlugin.attach(self.sim)
        self.hw = self.sim.spawn_urdf('arm', ARM).control.hw
        cm = self.sim.robots['arm'].control.cm
        self.run(start_after_steps * self.sim.step_size)
        self.start_velocity = max(abs(self.hw.handles[j].velocity) for j in LIFT)
        assert cm.load('arm_controller'), self.log.errors  # as the spawner: load, then one STRICT switch
        assert cm.request_switch(['arm_controller'], [], STRICT) is not None, self.log.errors
        self.run(self.sim.step_size)
        assert cm.state['arm_controller'] == 'running'
        self.run(SETTLE_S)

    def run(self, seconds):
        for _ in range(int(round(seconds / self.sim.step_size))):
            self.sim.step()

    def topic(self, leaf):
        return next(t for name, t in self.io.topics.items() if name.endswith('/arm_controller/' + leaf))

    def lift(self, target=None):
        """The row's goal (`target`, else LIFT relative to where the arm is); the goal handle once it has ended
        (or after 5 s)."""
        target = target or [self.hw.handles[j].position + LIFT[j] for j in LIFT]
        goal = FollowJointTrajectoryGoal(trajectory=trajectory([(target, 3.0)], joints=list(LIFT)))
        handle = GoalHandle(goal)
        goal_cb, _ = next(a for ns, a in self.io.actions.items() if ns.endswith('/follow_joint_trajectory'))
        goal_cb(handle)
        for _ in range(5000):
            if handle.status not in ('pending', 'active'):
                break
            self.sim.step()
        return handle

    def close(self):
        self.sim.close()


@pytest.fixture
def rig_at():
    rigs = []

    def make(start_after_steps):
        rigs.append(Rig(start_after_steps))
        return rigs[-1]
    yield make
    for r in rigs:
        r.close()


def hold_error(rig):
    """The controller's |desired - actual| per joint, from its last state message."""
    state = rig.topic('state').messages[-1]
    return dict(zip(state.joint_names, (abs(e) for e in state.error.positions)))


def at_rest(rig):
    return max(abs(rig.hw.handles[j].velocity) for j in LIFT) < 0.01


def test_a_controller_started_mid_fall_holds_below_the_ground_and_a_goal_then_aborts_as_upstream(rig_at):
    rig = rig_at(MID_FALL_STEPS)
    assert rig.start_velocity > 1.0, 'the arm was not falling when its controller started'
    assert at_rest(rig), 'the arm does not rest on the ground after the settle time'
    assert hold_error(rig)['shoulder'] > TOLERANCE  # its hold is beyond where the ground stops the arm
    handle = rig.lift()
    assert handle.status == 'aborted'
    assert handle.result.error_code == FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED
    assert handle.result.error_string.startswith('shoulder path error')


def test_a_controller_started_at_rest_holds_where_the_arm_lies_and_the_goal_succeeds(rig_at):
    rig = rig_at(AT_REST_STEPS)
    assert rig.start_velocity < 0.01 and at_rest(rig)
    assert max(hold_error(rig).values()) < TOLERANCE
    handle = rig.lift()
    assert handle.status == 'succeeded', handle.result


def worst_hold(rig):
    return max((e, j) for j, e in hold_error(rig).items())


def test_the_check_tells_the_start_race_by_the_hold_and_a_users_second_goal_succeeds(rig_at):
    rig = rig_at(MID_FALL_STEPS)
    assert rig.start_velocity > 1.0 and at_rest(rig)
    held = worst_hold(rig)
    target = [rig.hw.handles[j].position + LIFT[j] for j in LIFT]
    first = rig.lift(target)
    assert start_race(first.result.error_code, held, TOLERANCE)
    rig.run(3.0)  # the user reads the abort while the arm goes on along the aborted trajectory, as upstream's does
    second = rig.lift(target)
    assert second.status == 'succeeded', second.result
    assert all(rig.hw.handles[j].position == pytest.approx(t, abs=TOLERANCE) for j, t in zip(LIFT, target))


def test_an_abort_is_no_start_race_without_a_hold_beyond_the_path_tolerance():
    assert not start_race(PATH_TOLERANCE_VIOLATED, (0.05, 'shoulder'), TOLERANCE)  # a path error of the goal's own
    assert not start_race(PATH_TOLERANCE_VIOLATED, (0.5, 'shoulder'), None)  # no path tolerance: no path abort
    assert not start_race(FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED, (0.5, 'shoulder'), TOLERANCE)
    assert start_race(PATH_TOLERANCE_VIOLATED, (0.5, 'shoulder'), TOLERANCE)
