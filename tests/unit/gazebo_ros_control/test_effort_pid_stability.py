"""An effort JointTrajectoryController's PID on our physics, with ur_gazebo's UR5 wrist gains (p 500, d 1, i 1,
i_clamp 1, effort limit 28 N m) at 1 kHz, on a real Simulator.

gazebo_ros_control's writeSim applies the controller's effort (SetForce) from the last joint reading, and ODE steps
it as PyBullet does (semi-implicit Euler), so the PD acts explicitly in both: stable while
(d * dt + p * dt^2 / 2) / I_eff < 2, where I_eff is the inertia the joint's torque meets; above, the velocity flips
sign every step with the effort saturated. The UR5's joints are below (wrist_2: I_eff 3.0e-3 kg m^2, 0.42); its URDF
damping is 0, so Gazebo does not damp them either (docs/SIMULATION.md, joint damping)."""
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.ros_control.pid import Pid

from fakes import FakeLog

WRIST = """<robot name="wrist">
  <link name="world"/>
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="disc"><inertial><mass value="1"/><inertia ixx="%(i)s" iyy="%(i)s" izz="%(i)s" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="wrist_2_joint" type="continuous"><parent link="base"/><child link="disc"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 0 1"/><limit effort="28" velocity="3.14"/><dynamics damping="0" friction="0"/></joint>
  <transmission name="t"><joint name="wrist_2_joint">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""
STOPPED_VELOCITY_TOLERANCE = 0.05  # ur5_controllers.yaml


def hold(inertia, target=0.01, seconds=1.0):
    """The joint under the PID holding `target` from 0: (final position, velocities and efforts of the last 0.1 s).
    The PID runs in each world update between the joint's reading and the physics step, as the controller manager
    runs between readSim and writeSim; its effort is applied with the hardware's apply_efforts."""
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('wrist', WRIST % dict(i=inertia))
    index = robot.body.joints['wrist_2_joint'].index
    pid = Pid(500, 1, 1, -1, 1)
    dt = sim.step_size
    assert dt == 0.001
    log = []

    def control(_t):
        position, velocity = robot.body.joint_states([index])[0]
        effort = min(max(pid.compute_with_error_dot(target - position, -velocity, dt), -28.0), 28.0)
        robot.body.apply_efforts([index], [effort])
        log.append((position, velocity, effort))

    sim.before_physics.append(control)
    for _ in range(int(round(seconds / dt))):
        sim.step()
    return robot.body.joint_states([index])[0].position, [(v, e) for _, v, e in log[-100:]]


def test_the_ur5_wrist_gains_hold_still_on_the_ur5_wrist_inertia():
    position, tail = hold(3.0e-3)  # (d dt + p dt^2 / 2) / I = 0.42
    assert position == pytest.approx(0.01, abs=2e-4)
    assert max(abs(v) for v, _ in tail) < 1e-3


def test_on_a_smaller_inertia_the_same_gains_chatter_with_the_effort_saturated():
    position, tail = hold(4.0e-4)  # (d dt + p dt^2 / 2) / I = 3.1: explicit feedback, as Gazebo's
    assert position == pytest.approx(0.01, abs=0.05)  # it stays near the target, the velocity flipping every step
    assert max(abs(v) for v, _ in tail) > STOPPED_VELOCITY_TOLERANCE
    assert all(abs(e) == pytest.approx(28.0) for _, e in tail)
    assert all(a * b < 0 for (a, _), (b, _) in zip(tail, tail[1:]))
