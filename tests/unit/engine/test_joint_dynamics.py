"""URDF <dynamics damping friction> act as Gazebo applies them (its URDF -> SDF joint damping and friction:
a viscous torque -damping * velocity, and Coulomb friction holding the joint until the effort exceeds it), on
a real Simulator: an effort-driven disc (inertia 0.01 kg m^2) turning about a vertical axis."""
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog

SPINNER = """<robot name="spinner">
  <link name="world"/>
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="disc"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="disc"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 0 1"/><limit effort="100" velocity="1000"/>%s</joint>
  <transmission name="t"><joint name="spin">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""


def spin(dynamics, effort, seconds):
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('spinner', SPINNER % dynamics)
    handle = robot.control.hw.handles['spin']
    for _ in range(int(round(seconds / sim.step_size))):
        handle.command = effort
        sim.step()
    return handle.velocity


def test_damping_sets_the_terminal_velocity_to_effort_over_damping():
    assert spin('<dynamics damping="0.5"/>', 1.0, 3.0) == pytest.approx(2.0, rel=0.01)


def test_without_dynamics_the_effort_accelerates_freely():
    assert spin('', 1.0, 0.5) == pytest.approx(50.0, rel=0.02)  # 1 N m / 0.01 kg m^2 * 0.5 s


def test_friction_holds_the_joint_below_it_and_takes_its_share_above():
    assert abs(spin('<dynamics friction="2.0"/>', 1.0, 1.0)) < 1e-3
    assert abs(spin('<dynamics friction="2.0"/>', -1.9, 1.0)) < 1e-3
    assert spin('<dynamics friction="2.0"/>', 3.0, 0.5) == pytest.approx(50.0, rel=0.02)  # (3 - 2) / 0.01 * 0.5
