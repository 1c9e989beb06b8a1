"""The engine's objects named after Gazebo's: PhysicsWorld (World), Model, Link, Joint, and the ControlHook a
robot's control loop must be. Real PyBullet (DIRECT), no ROS master.

Fixtures: a floating two-link URDF (a 2 kg base, a 1 kg arm on a hinge about y, 0.5 m up) lying on the empty
world's ground, and a static-free SDF model of two boxes (one PyBullet body per link)."""
import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.control_hook import ControlHook
from racebot_sim_bridge.engine.joint import Joint
from racebot_sim_bridge.engine.link import Link
from racebot_sim_bridge.engine.model import Model
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.engine.simulator import Simulator, SpawnError
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin


def inertial(mass):
    return ('<inertial><mass value="%g"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
            '</inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>' % mass)


HINGED = ('<robot name="hinged"><link name="base">%s</link><link name="arm">%s</link>'
          '<joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.5"/>'
          '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="50" velocity="10"/></joint></robot>'
          % (inertial(2.0), inertial(1.0)))
PAIR = ('<sdf version="1.6"><world name="w"><model name="pair">'
        '<link name="a"><pose>0 0 2 0 0 0</pose><inertial><mass>1</mass></inertial>'
        '<collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link>'
        '<link name="b"><pose>1 0 2 0 0 0</pose><inertial><mass>1</mass></inertial>'
        '<collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry>'
        '<surface><contact><ode/></contact></surface></collision></link>'
        '</model></world></sdf>')


def flat(nested):
    """A pose, twist or pair of them as one flat tuple of numbers (pytest.approx takes no nesting)."""
    if isinstance(nested, (tuple, list)):
        return tuple(x for item in nested for x in flat(item))
    return (nested,)


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001)
    w.load_world(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF))
    yield w
    w.close()


@pytest.fixture
def hinged(world):
    return world.spawn_urdf('hinged', urdf_reader.parse_urdf(HINGED), HINGED, position=(0, 0, 3))


@pytest.fixture
def pair(world):
    return world.add_sdf_model(sdf_reader.parse_world(PAIR).models[0])


# -- World ------------------------------------------------------------------------------------------

def test_the_world_keeps_its_models_by_name_and_removes_them_with_their_bodies(world, hinged, pair):
    assert world.bodies['hinged'] is hinged and world.bodies['pair'] is pair
    bodies = world.client.getNumBodies()
    world.remove('pair')
    assert 'pair' not in world.bodies and world.client.getNumBodies() == bodies - 2
    with pytest.raises(PhysicsError, match='already exists'):
        world.spawn_urdf('hinged', urdf_reader.parse_urdf(HINGED), HINGED)


def test_world_settings_reach_pybullet(world, hinged):
    world.set_gravity((0.0, 0.0, 0.0))
    world.set_step_size(0.002)
    assert world.client.getPhysicsEngineParameters()['fixedTimeStep'] == pytest.approx(0.002)
    start = hinged.pose().position
    for _ in range(100):
        world.step()
    assert hinged.pose().position == pytest.approx(start, abs=1e-9)  # no gravity: it floats


def test_step_forgets_the_applied_wrenches_and_reset_puts_every_model_back(world, hinged, pair):
    hinged.links['arm'].apply_wrench((1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert world.applied
    for _ in range(300):
        world.step()
    assert not world.applied
    assert hinged.pose().position[2] < 2.9 and pair.links['b'].state()[0].position[2] < 1.9
    world.reset()
    assert flat(hinged.pose()) == pytest.approx(flat(hinged.spawn_pose), abs=1e-12)
    assert pair.links['b'].state()[0].position == pytest.approx((1.0, 0.0, 2.0), abs=1e-9)


# -- Model ------------------------------------------------------------------------------------------

def test_a_model_has_its_links_and_movable_joints_by_name(hinged, pair):
    assert isinstance(hinged, Model) and set(hinged.links) == {'base', 'arm'}
    assert all(isinstance(link, Link) and link.model is hinged for link in hinged.links.values())
    assert hinged.links['base'].address == (hinged.id, -1) and hinged.links['arm'].address == (hinged.id, 0)
    joint = hinged.joints['hinge']
    assert isinstance(joint, Joint) and joint.model is hinged
    assert (joint.index, joint.type, joint.lower, joint.upper, joint.max_effort, joint.child_link) == \
        (0, 'revolute', -1.0, 1.0, 50.0, 'arm')
    # an SDF model: a body per link, the first the model's own
    assert pair.links['a'].address == (pair.id, -1)
    assert pair.links['b'].address == (dict(pair.extra_bodies)['b'], -1) and pair.body_ids()[1] != pair.id


def test_model_pose_and_velocity(hinged):
    hinged.set_pose((1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 1.0), linear=(0.5, 0.0, 0.0))
    assert hinged.pose().position == pytest.approx((1.0, 2.0, 3.0))
    assert hinged.twist().linear == pytest.approx((0.5, 0.0, 0.0))
    hinged.set_velocity((0.0, 0.0, 1.0), (0.0, 0.0, 2.0))
    assert flat(hinged.twist()) == pytest.approx((0.0, 0.0, 1.0, 0.0, 0.0, 2.0))
    assert hinged.pose().position == pytest.approx((1.0, 2.0, 3.0))  # the pose stays
    frame = hinged.frame_pose()
    assert flat(hinged.com_pose_for_frame(*frame)) == pytest.approx(flat(hinged.pose()), abs=1e-12)


def test_model_joint_arrays(world, hinged):
    index = hinged.joints['hinge'].index
    world.set_gravity((0.0, 0.0, 0.0))
    hinged.apply_efforts([index], [1.0])
    world.step()
    raw = hinged.joint_states_raw([index])[0]
    state = hinged.joint_states([index])[0]
    assert (raw[0], raw[1]) == (state.position, state.velocity) and state.velocity > 0
    hinged.drive_velocities([index], [-0.5], [50.0])
    for _ in range(50):
        world.step()
    assert hinged.joint_states([index])[0].velocity == pytest.approx(-0.5, abs=1e-3)
    hinged.drive_positions([index], [0.3], [50.0])
    for _ in range(2000):
        world.step()
    assert hinged.joint_states([index])[0].position == pytest.approx(0.3, abs=0.01)


def test_model_reset_puts_pose_and_joints_back(world, hinged):
    hinged.initial_joint_positions['hinge'] = 0.2
    hinged.joints['hinge'].set_position(-0.7, 1.0)
    hinged.set_pose((5.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0))
    hinged.reset()
    assert flat(hinged.pose()) == pytest.approx(flat(hinged.spawn_pose), abs=1e-12)
    assert tuple(hinged.joints['hinge'].state()) == pytest.approx((0.2, 0.0))


# -- Link -------------------------------------------------------------------------------------------

def test_link_state_dynamics_and_mass(world, hinged):
    arm = hinged.links['arm']
    s = world.client.getLinkState(hinged.id, 0, computeLinkVelocity=1, computeForwardKinematics=1)
    assert flat(arm.state()[0]) == pytest.approx(flat((s[4], s[5])))
    assert flat(hinged.links['base'].state()) == pytest.approx(flat((hinged.frame_pose(), hinged.twist())))
    assert arm.com_position() == pytest.approx(s[0])
    assert arm.dynamics().mass == pytest.approx(1.0)
    arm.set_mass(3.0, (0.02, 0.03, 0.04))
    assert arm.dynamics().mass == pytest.approx(3.0)
    assert arm.dynamics().inertia_diagonal == pytest.approx((0.02, 0.03, 0.04))


def test_link_wrenches_count_once_each_step_unless_told_not_to(world, hinged):
    base = hinged.links['base']
    base.apply_wrench((1.0, 2.0, 3.0), (0.0, 0.0, 0.5))
    base.apply_wrench((1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    base.apply_wrench((0.0, 0.0, 100.0), (0.0, 0.0, 0.0), accumulate=False)
    assert base.applied_wrench() == ((2.0, 2.0, 3.0), (0.0, 0.0, 0.5))
    assert hinged.links['arm'].applied_wrench() == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    world.step()
    assert base.applied_wrench() == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def test_a_wrench_pushes_the_link(world, pair):
    world.set_gravity((0.0, 0.0, 0.0))
    b = pair.links['b']
    b.apply_wrench((10.0, 0.0, 0.0), (0.0, 0.0, 0.0))  # 1 kg: 10 m/s^2 for one step
    world.step()
    assert b.state()[1].linear[0] == pytest.approx(0.01, rel=1e-6)
    assert pair.links['a'].state()[1].linear[0] == 0.0  # another body


def test_link_base_state_moves_a_body_base_only(pair, hinged):
    pair.links['b'].set_base_state((3.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0), linear=(0.0, 1.0, 0.0))
    pose, twist = pair.links['b'].state()
    assert pose.position == pytest.approx((3.0, 0.0, 1.0)) and twist.linear == pytest.approx((0.0, 1.0, 0.0))
    assert pair.links['a'].state()[0].position == pytest.approx((0.0, 0.0, 2.0))
    with pytest.raises(PhysicsError, match='not a body'):
        hinged.links['arm'].set_base_state((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


# -- Joint ------------------------------------------------------------------------------------------

def test_joint_position_effort_and_motor(world, hinged):
    world.set_gravity((0.0, 0.0, 0.0))
    hinge = hinged.joints['hinge']
    hinge.set_position(0.4, 2.0)
    assert tuple(hinge.state()) == pytest.approx((0.4, 2.0))
    hinge.set_position(0.0)
    hinge.apply_effort(0.5)
    world.step()
    assert hinge.state().velocity > 0
    hinge.drive_velocity(0.25, 50.0)
    for _ in range(50):
        world.step()
    assert hinge.state().velocity == pytest.approx(0.25, abs=1e-3)


def spin_down(world, model, steps=200):
    """The hinge's velocity after `steps` steps from 1 rad/s without gravity."""
    world.set_gravity((0.0, 0.0, 0.0))
    model.joints['hinge'].set_position(0.0, 1.0)
    for _ in range(steps):
        world.step()
    return model.joints['hinge'].state().velocity


def test_joint_damping_slows_it(world, hinged):
    free = spin_down(world, hinged)
    hinged.joints['hinge'].set_dynamics(damping=0.05)
    assert spin_down(world, hinged) < 0.5 * free


def test_joint_limits_hold_it(world, hinged):
    hinge = hinged.joints['hinge']
    hinge.set_dynamics(lower=-0.2)
    assert (hinge.lower, hinge.upper) == (-0.2, 1.0)
    world.set_gravity((0.0, 0.0, 0.0))
    hinge.drive_velocity(-1.0, 50.0)
    for _ in range(1000):
        world.step()
    assert hinge.state().position == pytest.approx(-0.2, abs=0.02)


def test_joint_wrench_is_measured_once_enabled(world, hinged):
    hinge = hinged.joints['hinge']
    world.step()
    assert hinge.wrench() == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    hinge.enable_wrench()
    hinged.set_pose((0.0, 0.0, 0.1), (0.0, 0.0, 0.0, 1.0))  # on the ground: the hinge holds the arm up
    for _ in range(500):
        world.step()
    force, _ = hinge.wrench()
    assert max(abs(f) for f in force) > 5.0  # the arm weighs 9.8 N


# -- ControlHook ------------------------------------------------------------------------------------

class Log:
    def __getattr__(self, _name):
        return lambda *a: None


def test_gazebo_ros_controls_plugin_is_a_control_hook_and_the_simulator_refuses_what_is_not():
    assert ControlHook in GazeboRosControlPlugin.__mro__
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=Log(), get_params={}.get)
    try:
        def bad_control(robot):
            robot.control = object()
        sim.on_create.append(bad_control)
        with pytest.raises(SpawnError, match='ControlHook'):
            sim.spawn_urdf('hinged', HINGED)
        assert 'hinged' not in sim.world.bodies
    finally:
        sim.close()
