"""URDF joint damping explicit or implicit as Gazebo's ODEJoint::ApplyStiffnessDamping chooses (joint_damping.py):
explicit by default (a torque -damping * velocity from the velocity before the step), implicit where the joint's
<gazebo reference> sets <implicitSpringDamper> (the damping force from the velocity after the step: stable at any
damping). On a real Simulator: an effort-driven disc (inertia 0.01 kg m^2, 1 ms steps) about a vertical axis, so
damping * dt / I is damping / 10."""
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog

SPINNER = """<robot name="spinner">
  %(world)s
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="disc"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="spin" type="%(type)s"><parent link="base"/><child link="disc"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 0 1"/><limit effort="100" velocity="1000" lower="-1" upper="1"/>
    <dynamics damping="%(damping)s"/></joint>
  %(gazebo)s
  <transmission name="t"><joint name="spin">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>"""
FIXED = '<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>'
IMPLICIT = '<gazebo reference="spin"><implicitSpringDamper>1</implicitSpringDamper></gazebo>'
DT = 0.001


def spinner(damping, implicit, fixed=True, joint_type='continuous'):
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    GazeboRosControlPlugin.attach(sim)
    urdf = SPINNER % dict(world=FIXED if fixed else '', type=joint_type, damping=damping,
                          gazebo=IMPLICIT if implicit else '')
    robot = sim.spawn_urdf('spinner', urdf, position=(0, 0, 1))
    assert sim.step_size == DT
    return sim, robot


def velocities(damping, implicit, v0=1.0, steps=5, effort=0.0, **kw):
    """The joint's velocity after each of `steps` steps from velocity v0 with a constant effort."""
    sim, robot = spinner(damping, implicit, **kw)
    robot.body.joints['spin'].set_position(0.0, v0)
    handle = robot.control.hw.handles['spin']
    result = []
    for _ in range(steps):
        handle.command = effort
        sim.step()
        result.append(robot.body.joint_states([robot.body.joints['spin'].index])[0].velocity)
    return result


def test_damping_without_the_switch_stays_explicit_as_in_gazebo():
    # ApplyExplicitStiffnessDamping: v' = v - dt * damping * v / I
    assert velocities(0.5, False, steps=1)[0] == pytest.approx(1 - 0.05, abs=1e-9)
    # and, as in Gazebo, it overshoots once damping * dt / I > 2: 1 -> -4 -> 16
    assert velocities(50.0, False, steps=2) == pytest.approx([-4.0, 16.0], rel=1e-6)


def test_implicit_spring_damper_damps_with_the_velocity_after_the_step():
    # v' = v / (1 + dt * damping / I): 1 / 1.05 (explicit would give 0.95)
    assert velocities(0.5, True, steps=1)[0] == pytest.approx(1 / 1.05, abs=1e-9)


def test_implicit_damping_never_overshoots_however_large():
    # damping * dt / I = 5 (explicit: -4, 16, -64, ...) and 500
    for damping in (50.0, 5000.0):
        v = velocities(damping, True, steps=20)
        assert v[0] == pytest.approx(1 / (1 + damping / 10), rel=1e-6)
        assert all(0 <= b < a for a, b in zip([1.0] + v, v)), v


def test_implicit_damping_settles_at_effort_over_damping():
    # the effort applied this step is in the prediction: terminal velocity effort / damping, as ODE's constraint row
    assert velocities(0.5, True, v0=0.0, steps=3000, effort=1.0)[-1] == pytest.approx(2.0, rel=0.01)
    assert velocities(50.0, True, v0=0.0, steps=200, effort=1.0)[-1] == pytest.approx(0.02, rel=0.01)


def test_implicit_damping_on_a_floating_base():
    # no world link: the mass matrix has the base's 6 dofs first; the disc's own block of M^-1 still governs it
    v = velocities(50.0, True, steps=20, fixed=False)
    assert all(abs(b) < abs(a) for a, b in zip([1.0] + v, v)), v


def test_off_beyond_the_limits_as_gazebo_hands_the_row_to_the_limit():
    # revolute in [-1, 1]: at 0.9995 moving up at 1 rad/s, angle + 2 v dt passes the upper limit: no damping
    sim, robot = spinner(50.0, True, joint_type='revolute')
    dampers = robot.body.dampers
    robot.body.joints['spin'].set_position(0.9995, 1.0)
    assert dampers.torques(DT, {}) == ([], [])
    robot.body.joints['spin'].set_position(0.0, 1.0)
    indices, torques = dampers.torques(DT, {})
    assert torques == pytest.approx([-50.0 / 6])


def test_set_joint_properties_damping_keeps_the_joint_implicit():
    sim, robot = spinner(0.5, True)
    robot.body.joints['spin'].set_dynamics(damping=50.0)
    robot.body.joints['spin'].set_position(0.0, 1.0)
    sim.step()
    assert robot.body.joint_states([robot.body.joints['spin'].index])[0].velocity == pytest.approx(1 / 6)
