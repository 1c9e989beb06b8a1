"""gazebo_ros_control's pid_gains on a real Simulator: a position or velocity joint whose
`<ns>/gazebo_ros_control/pid_gains/<joint>` is set is driven by effort = PID(error), clamped to its
effort limit (DefaultRobotHWSim's POSITION_PID / VELOCITY_PID); without gains it follows its command
directly; gains that are set and wrong are warned about and the joint follows its command directly."""
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog

ARM = """<robot name="turret">
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.5 0.5 0.2"/></geometry></collision></link>
  <link name="top"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial></link>
  <link name="wheel"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial></link>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="top"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="%(effort)s" velocity="5"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 0 1"/><limit effort="%(effort)s" velocity="20"/></joint>
  <transmission name="t1"><joint name="yaw">
    <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="spin">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""


def turret(params, effort=10):
    log = FakeLog()
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=log, get_params=params.get)
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('turret', ARM % {'effort': effort}, position=(0, 0, 0.1))
    return sim, robot, log


def run(sim, robot, yaw, spin, seconds):
    hw = robot.control.hw.handles
    for _ in range(int(round(seconds / sim.step_size))):
        hw['yaw'].command, hw['spin'].command = yaw, spin
        sim.step()
    return hw['yaw'], hw['spin']


GAINS = {'/turret/gazebo_ros_control/pid_gains/yaw': {'p': 40.0, 'd': 2.0},
         '/turret/gazebo_ros_control/pid_gains/spin': {'p': 5.0}}


def test_with_gains_the_joints_are_driven_by_a_pid_effort():
    sim, robot, log = turret(GAINS)
    assert sorted(h.name for h, _, _ in robot.control.hw.pid_joints) == ['spin', 'yaw']
    yaw, spin = run(sim, robot, 1.0, 3.0, 2.0)
    assert yaw.position == pytest.approx(1.0, abs=0.02)
    assert spin.velocity == pytest.approx(3.0, rel=0.05)
    assert log.warnings == []
    sim.close()


def test_the_pid_effort_is_clamped_to_the_effort_limit():
    sim, robot, log = turret(GAINS, effort=0.05)
    yaw, spin = run(sim, robot, 1.0, 3.0, 0.05)
    assert abs(yaw.effort) == pytest.approx(0.05) and abs(spin.effort) == pytest.approx(0.05)
    sim.close()


def test_without_gains_the_joints_follow_their_command_directly():
    sim, robot, log = turret({})
    assert robot.control.hw.pid_joints == []
    yaw, spin = run(sim, robot, 1.0, 3.0, 1.0)
    assert yaw.position == pytest.approx(1.0, abs=0.02)
    assert spin.velocity == pytest.approx(3.0, rel=0.02)
    assert yaw.effort == 0.0  # no PID effort: the joint motor does it
    sim.close()


def test_wrong_gains_are_warned_about_and_the_joint_follows_directly():
    sim, robot, log = turret({'/turret/gazebo_ros_control/pid_gains/yaw': {'i': 1.0},
                              '/turret/gazebo_ros_control/pid_gains/spin': {'p': 'fast'}})
    assert robot.control.hw.pid_joints == []
    assert len(log.warnings) == 2
    assert "no 'p' gain" in log.warnings[0] and 'pid_gains/yaw' in log.warnings[0]
    assert 'follows its command directly' in log.warnings[1]
    yaw, spin = run(sim, robot, 1.0, 3.0, 1.0)
    assert yaw.position == pytest.approx(1.0, abs=0.02)
    sim.close()
