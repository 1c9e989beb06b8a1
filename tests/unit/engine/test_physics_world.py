"""racebot_sim_bridge.engine.physics.PhysicsWorld with real PyBullet (DIRECT) and the racebot model rendered from
racecar.xacro with the xacro module. No ROS master.

What Gazebo does and the world must reproduce: the car weighs 13.25 kg (links without <inertial> add
nothing), six movable joints, no joint motor of its own (a joint moves only by applied effort), the
model pose is the root link's frame (base_footprint, at wheel-bottom level), friction of a wheel on
the ground is min(wheel mu, ground mu), and stepping is deterministic.
"""
import math
from pathlib import Path

import pybullet as pb
import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader

from racebot_model import render_racebot
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.engine.bullet_urdf import NEGLIGIBLE_MASS
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.engine.simulator import Simulator

from fakes import FakeLog

REPO = Path(__file__).resolve().parents[3]
EMPTY_WORLD = REPO / 'racebot_sim_bridge' / 'worlds' / 'empty.world'

CAR_MASS = 13.25  # 4 chassis + 2 x 0.5 hinges + 4 x 2 wheels + 0.25 sensors (RACEBOT.md)
WHEEL_RADIUS = 0.032
WHEEL_MU = 2.0
MOVABLE = {
    'left_steering_hinge_joint': 'revolute', 'right_steering_hinge_joint': 'revolute',
    'left_front_wheel_joint': 'revolute', 'right_front_wheel_joint': 'revolute',  # continuous: no limits
    'left_rear_wheel_joint': 'revolute', 'right_rear_wheel_joint': 'revolute',
}
WHEEL_LINKS = ('left_front_wheel', 'right_front_wheel', 'left_rear_wheel', 'right_rear_wheel')


@pytest.fixture(scope='module')
def racebot_model(racebot_xml):
    return urdf_reader.parse_urdf(racebot_xml)


@pytest.fixture
def make_world():
    worlds = []

    def make(world_file=EMPTY_WORLD, world_text=None):
        w = PhysicsWorld(step_size=0.001, gravity=(0.0, 0.0, -9.8))
        spec = sdf_reader.parse_world(world_text) if world_text else sdf_reader.load_world(str(world_file))
        w.load_world(spec)
        worlds.append(w)
        return w

    yield make
    for w in worlds:
        w.close()


@pytest.fixture
def world(make_world):
    return make_world()


@pytest.fixture
def car(world, racebot_model, racebot_xml):
    return world.spawn_urdf('racebot', racebot_model, racebot_xml)


def dynamics(world, body, link):
    return world.client.getDynamicsInfo(body.id, body.link_index[link])


def total_mass(world, body):
    return sum(dynamics(world, body, link)[0] for link in body.link_index)


def settle(world, steps=1000):
    for _ in range(steps):
        world.step()


# -- the model ----------------------------------------------------------------------------------

def test_total_mass_is_the_urdfs(world, car):
    assert total_mass(world, car) == pytest.approx(CAR_MASS, abs=0.001)


def test_links_without_inertial_get_negligible_mass(world, car, racebot_xml):
    # base_footprint, base_link and realsense_depth declare no <inertial>; lumped into the root as Gazebo
    # lumps them, they add nothing: its mass is the chassis' 4 kg plus the fixed sensors' 0.25 kg.
    assert dynamics(world, car, 'base_footprint')[0] == pytest.approx(4.25, abs=1e-9)
    # A link of its own without <inertial> (here kept by preserveFixedJoint) gets a negligible mass.
    xml = racebot_xml.replace('</robot>', '<gazebo reference="realsense_depth_joint">'
                                          '<preserveFixedJoint>true</preserveFixedJoint></gazebo></robot>')
    kept = world.spawn_urdf('kept', urdf_reader.parse_urdf(xml), xml)
    assert dynamics(world, kept, 'realsense_depth')[0] == pytest.approx(NEGLIGIBLE_MASS, abs=1e-12)
    assert dynamics(world, kept, 'base_footprint')[0] == pytest.approx(4.25, abs=1e-9)


def test_fixed_links_are_merged_into_their_parent(car):
    assert set(car.link_index) == {'base_footprint'} | set(WHEEL_LINKS) | {'left_steering_hinge',
                                                                            'right_steering_hinge'}
    assert car.link_index['base_footprint'] == -1


def test_six_movable_joints(car):
    assert {n: j.type for n, j in car.joints.items()} == MOVABLE
    hinge = car.joints['left_steering_hinge_joint']
    assert (hinge.lower, hinge.upper, hinge.max_effort, hinge.max_velocity) == (-0.6, 0.6, 5.0, 1000.0)
    assert car.joints['left_rear_wheel_joint'].max_effort == 10.0
    assert car.joints['left_front_wheel_joint'].child_link == 'left_front_wheel'


def test_single_line_urdf_loads(world, racebot_model):
    # xacro's toxml(), `rosparam set robot_description "$(cat compact.urdf)"` or any generator that
    # writes no newlines: the model must load as the pretty form does.
    xml = render_racebot(pretty=False)
    body = world.spawn_urdf('compact', urdf_reader.parse_urdf(xml), xml)
    assert total_mass(world, body) == pytest.approx(CAR_MASS, abs=0.001)


def test_an_axis_without_xyz_is_urdfdoms_default(world):
    # PyBullet reads uninitialised memory for <axis/> (found by test_robustness_fuzz: NaN poses now and then)
    xml = ('<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" '
           'ixz="0" iyz="0"/></inertial></link><link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" '
           'izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link><joint name="j" type="revolute"><parent link="a"/>'
           '<child link="b"/><axis/><limit effort="1" lower="-1" upper="1" velocity="1"/></joint></robot>')
    model = urdf_reader.parse_urdf(xml)
    body = world.spawn_urdf('r', model, xml)
    assert model.joints['j'].axis == (1.0, 0.0, 0.0)
    assert world.client.getJointInfo(body.id, body.joints['j'].index)[13] == (1.0, 0.0, 0.0)


def test_duplicate_name_refused(world, car, racebot_model, racebot_xml):
    with pytest.raises(PhysicsError) as err:
        world.spawn_urdf('racebot', racebot_model, racebot_xml)
    assert 'racebot' in str(err.value)


def test_remove_then_spawn_again(world, car, racebot_model, racebot_xml):
    world.remove('racebot')
    assert 'racebot' not in world.bodies
    assert world.spawn_urdf('racebot', racebot_model, racebot_xml).name == 'racebot'


@pytest.mark.parametrize('step', [0.0, -0.001, math.nan, math.inf])
def test_bad_step_size(step):
    with pytest.raises(PhysicsError):
        PhysicsWorld(step_size=step)


# -- joints: no motors, efforts for one step -------------------------------------------------------

def _spin_in_the_air(world, racebot_model, racebot_xml, steps=100):
    """Wheel at 5 rad/s and hinge at 0.5 rad/s, then `steps` steps of free fall with no effort."""
    body = world.spawn_urdf('racebot', racebot_model, racebot_xml, position=(0.0, 0.0, 2.0))
    joints = ['left_rear_wheel_joint', 'left_steering_hinge_joint']
    body.joints[joints[0]].set_position(0.0, velocity=5.0)
    body.joints[joints[1]].set_position(0.0, velocity=0.5)
    for _ in range(steps):  # nothing touches the car
        world.step()
    return body.joint_states([body.joints[n].index for n in joints])


def test_joint_velocity_motors_are_off(world, racebot_model, racebot_xml):
    wheel, hinge = _spin_in_the_air(world, racebot_model, racebot_xml)
    assert wheel.velocity > 4.0  # PyBullet's default motor brakes it to 0 within a few ms
    assert hinge.velocity > 0.4
    assert hinge.position == pytest.approx(0.05, rel=0.05)


def test_free_joint_is_not_damped(world, racebot_model, racebot_xml):
    # Gazebo (ODE) applies no velocity damping unless the URDF asks for it; PyBullet's default link
    # damping (0.04, quadratic in speed) slows a free wheel from 5 to ~4.88 rad/s in 0.1 s.
    wheel, _ = _spin_in_the_air(world, racebot_model, racebot_xml)
    assert wheel.velocity == pytest.approx(5.0, rel=1e-3)


def test_effort_accelerates_a_joint_for_one_step_only(world, racebot_model, racebot_xml):
    body = world.spawn_urdf('racebot', racebot_model, racebot_xml, position=(0.0, 0.0, 2.0))
    index = body.joints['right_rear_wheel_joint'].index
    body.apply_efforts([index], [0.5])
    world.step()
    v1 = body.joint_states([index])[0].velocity
    assert v1 > 0.1  # 0.5 N m on ~7e-4 kg m^2 for 1 ms: ~0.7 rad/s
    for _ in range(10):
        world.step()  # no effort given again
    assert body.joint_states([index])[0].velocity == pytest.approx(v1, rel=0.02)
    body.apply_efforts([index], [-0.5])
    world.step()
    assert body.joint_states([index])[0].velocity < v1 / 2


# -- poses ----------------------------------------------------------------------------------------

def test_frame_pose_is_the_spawn_pose(world, racebot_model, racebot_xml):
    q = pb.getQuaternionFromEuler((0.0, 0.0, math.pi / 2))
    body = world.spawn_urdf('racebot', racebot_model, racebot_xml, position=(1.0, 2.0, 0.5), orientation=q)
    pos, orn = body.frame_pose()
    assert pos == pytest.approx((1.0, 2.0, 0.5), abs=1e-6)  # PyBullet's transforms are float32
    assert orn == pytest.approx(q, abs=1e-6)
    # The centre of mass is the inertial offset (forward of base_footprint, above it) rotated by yaw.
    com, com_orn = body.pose()
    assert com != pytest.approx(pos, abs=1e-3)
    offset_in_frame = pb.multiplyTransforms(*pb.invertTransform(pos, orn), com, com_orn)[0]
    assert offset_in_frame[2] > WHEEL_RADIUS  # the mass sits at or above base_link
    assert body.com_pose_for_frame(pos, orn)[0] == pytest.approx(com, abs=1e-6)


def test_frame_and_com_pose_stay_consistent_while_moving(world, car):
    for _ in range(200):
        car.apply_efforts([car.joints['left_rear_wheel_joint'].index,
                                  car.joints['right_rear_wheel_joint'].index], [0.5, 0.5])
        world.step()
    frame = car.frame_pose()
    com = car.com_pose_for_frame(*frame)
    assert com.position == pytest.approx(car.pose().position, abs=1e-6)
    assert abs(sum(a * b for a, b in zip(com.orientation, car.pose().orientation))) == pytest.approx(1.0, abs=1e-6)
    assert car.links['base_footprint'].state()[0].position == pytest.approx(frame.position, abs=1e-12)
    # The frame is not the centre of mass: about 4 cm apart (the chassis' mass sits above base_footprint).
    assert math.dist(frame.position, car.pose().position) > 0.03


def test_resting_car_has_base_footprint_at_ground_level(world, car):
    settle(world)
    pos, orn = car.frame_pose()
    assert pos[2] == pytest.approx(0.0, abs=0.002)  # base_footprint is at wheel-bottom level
    roll, pitch, _ = pb.getEulerFromQuaternion(orn)
    assert abs(roll) < 0.01 and abs(pitch) < 0.01
    for wheel in WHEEL_LINKS:
        assert car.links[wheel].state()[0].position[2] == pytest.approx(WHEEL_RADIUS, abs=0.002)
    # ... and it stays put: no drift without efforts
    assert math.hypot(pos[0], pos[1]) < 0.01


# -- friction -----------------------------------------------------------------------------------

def test_wheel_friction_is_min_of_wheel_and_ground(world, car):
    assert world.ground_mu > WHEEL_MU  # Gazebo's ground_plane: mu 100
    for wheel in WHEEL_LINKS:
        assert dynamics(world, car, wheel)[1] == pytest.approx(WHEEL_MU)
    # links with no <gazebo> mu get ODE's default 1
    assert dynamics(world, car, 'left_steering_hinge')[1] == pytest.approx(1.0)


def test_slippery_ground_limits_wheel_friction(make_world, racebot_model, racebot_xml):
    ice = """<sdf version="1.6"><world name="default">
      <model name="ice"><static>true</static><link name="link"><collision name="c">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        <surface><friction><ode><mu>0.3</mu><mu2>0.3</mu2></ode></friction></surface>
      </collision></link></model></world></sdf>"""
    world = make_world(world_text=ice)
    assert world.ground_mu == pytest.approx(0.3)
    body = world.spawn_urdf('racebot', racebot_model, racebot_xml)
    ground = world.bodies['ice']
    assert world.client.getDynamicsInfo(ground.id, -1)[1] == pytest.approx(1.0)
    for wheel in WHEEL_LINKS:
        assert dynamics(world, body, wheel)[1] == pytest.approx(0.3)  # Bullet multiplies: 0.3 x 1


# -- determinism --------------------------------------------------------------------------------

def _drive(world, body, steps):
    names = ['left_rear_wheel_joint', 'right_rear_wheel_joint', 'left_steering_hinge_joint',
             'right_steering_hinge_joint']
    idx = [body.joints[n].index for n in names]
    for k in range(steps):
        steer = 0.3 * math.sin(k * 0.01)
        body.apply_efforts(idx, [0.8, 0.7, steer, steer])
        world.step()
    return body.pose(), body.twist(), body.joint_states([j.index for j in body.joints.values()])


def test_two_worlds_with_the_same_torques_agree(make_world, racebot_model, racebot_xml):
    a, b = make_world(), make_world()
    assert a.client != b.client
    ca = a.spawn_urdf('racebot', racebot_model, racebot_xml)
    cb = b.spawn_urdf('racebot', racebot_model, racebot_xml)
    sa, sb = _drive(a, ca, 600), _drive(b, cb, 600)
    assert sa[0].position[0] > 0.01  # the car did drive
    flat_a = [x for part in (sa[0] + sa[1]) for x in part] + [x for s in sa[2] for x in s]
    flat_b = [x for part in (sb[0] + sb[1]) for x in part] + [x for s in sb[2] for x in s]
    assert flat_a == pytest.approx(flat_b, abs=1e-12, rel=0)


def test_reset_to_spawn(world, car):
    _drive(world, car, 300)
    car.reset()
    assert car.frame_pose().position == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert car.twist().linear == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    states = car.joint_states([j.index for j in car.joints.values()])
    assert all(s.position == 0.0 and s.velocity == 0.0 for s in states)


TWO_LINKS = """<sdf version="1.6"><world name="w"><model name="pair"><static>true</static>
  <link name="a"><collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link>
  <link name="b"><pose>2 0 0 0 0 0</pose>
    <collision name="c"><geometry><sphere><radius>0.5</radius></sphere></geometry></collision></link>
</model></world></sdf>"""


def test_a_body_declares_where_it_came_from_and_its_extra_bodies(make_world, car, racebot_model):
    import pickle
    from racebot_sim_bridge.engine.physics_types import BodySource
    w = make_world(world_text=TWO_LINKS)
    pair = w.bodies['pair']
    assert pair.source == BodySource('sdf', pair.source.model, None) and pair.source.model.name == 'pair'
    assert [link for link, _ in pair.extra_bodies] == ['b'] and pair.copy_key is None
    assert w.client.getBasePositionAndOrientation(pair.extra_bodies[0][1])[0] == (2, 0, 0)
    assert (car.source.kind, car.source.model, car.extra_bodies) == ('urdf', racebot_model, [])
    assert '<robot' in car.source.urdf_xml
    with pytest.raises(TypeError):
        car.source[0]  # a named record: read by field
    copy = pickle.loads(pickle.dumps(pair.source))  # what the viewer and the render worker receive
    other = make_world(world_text='<sdf version="1.6"><world name="other"/></sdf>')
    assert copy == pair.source and other.add_copy('pair', copy).extra_bodies[0][0] == 'b'


def test_a_spawn_leaves_no_file_behind(make_world, racebot_model, racebot_xml, tmp_path, monkeypatch):
    # A world server is often killed, not closed (roslaunch, CI timeouts): what a spawn writes for
    # PyBullet must be gone once the robot is in the world, not when the world is closed.
    monkeypatch.setattr('tempfile.tempdir', str(tmp_path))
    world = make_world()
    world.spawn_urdf('racebot', racebot_model, racebot_xml, position=(0, 0, 0.05))
    assert 'racebot' in world.bodies
    assert list(tmp_path.iterdir()) == []


BOX_ON_GROUND = """<?xml version="1.0"?>
<sdf version="1.6"><world name="w">%s
  <include><uri>model://ground_plane</uri></include>
  <model name="box"><pose>0 0 0.1 0 0 0</pose><link name="link">
    <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry>
      <surface><friction><ode><mu>0.5</mu><mu2>0.5</mu2></ode></friction></surface></collision>
  </link></model>
</world></sdf>"""


@pytest.mark.parametrize('solver, slides', [
    ('', False),  # Gazebo's default, the pyramid
    ('<physics type="ode"><ode><solver><friction_model>pyramid_model</friction_model></solver></ode></physics>', False),
    ('<physics type="ode"><ode><solver><friction_model>cone_model</friction_model></solver></ode></physics>', True),
])
def test_the_worlds_friction_model_limits_a_diagonal_push_as_odes_does(solver, slides):
    """A box pushed at 45 degrees with 1.2 mu m g: ODE's pyramid limits each of the two friction directions to mu N
    on its own, so the push (0.85 mu m g along each) is held; the cone limits their sum, so the box slides."""
    sim = Simulator(sdf_reader.parse_world(BOX_ON_GROUND % solver), io=None, log=FakeLog(), get_params={}.get)
    try:
        box = sim.world.bodies['box']
        for _ in range(200):
            sim.world.step()
        push = 1.2 * 0.5 * 1.0 * 9.8 / math.sqrt(2)
        start = box.pose()[0]
        for _ in range(1000):
            box.links['link'].apply_wrench((push, push, 0.0), (0.0, 0.0, 0.0))
            sim.world.step()
        moved = math.dist(box.pose()[0][:2], start[:2])
        assert (moved > 0.2) if slides else (moved < 0.001), moved  # cone: 0.5 a t^2 = 0.49 m along the push
    finally:
        sim.world.close()
