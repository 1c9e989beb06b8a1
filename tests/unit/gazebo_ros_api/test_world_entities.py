"""racebot_sim_bridge.gazebo_ros_api.entities with real PyBullet (DIRECT), no master: models and links found by
name, an SDF model's pose is its model frame, moves keep a model rigid (joint velocities zeroed), and
set_link_state on a URDF link carries its model along with the link's twist."""
import math

import pytest

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities

ARM = ('<robot name="arm">'
       '<link name="base"><inertial><origin xyz="0.05 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" '
       'izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>'
       '<link name="arm_link"><inertial><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
       'ixz="0" iyz="0"/></inertial></link>'
       '<joint name="hinge" type="continuous"><parent link="base"/><child link="arm_link"/>'
       '<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/></joint></robot>')
SHELF = ('<sdf version="1.6"><world name="w"><model name="shelf"><pose>1 2 0 0 0 0</pose>' + ''.join(
    '<link name="%s"><pose>0 0 %g 0 0 0</pose><collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box>'
    '</geometry></collision></link>' % (n, z) for n, z in (('base', 0.5), ('top', 1.0))) + '</model></world></sdf>')
YAW_90 = (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001, gravity=(0.0, 0.0, 0.0))
    w.load_world(sdf_reader.parse_world(SHELF))
    w.spawn_urdf('arm', urdf_reader.parse_urdf(ARM), ARM, (0.0, 0.0, 1.0))
    yield w
    w.close()


def close(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_names(world):
    e = WorldEntities(world)
    assert e.resolve('shelf') == frames.Entity('shelf', None)
    assert e.resolve('shelf::top') == frames.Entity('shelf', 'top')  # an SDF model's second link
    assert e.resolve('arm_link') == frames.Entity('arm', 'arm_link')
    assert e.find_link('arm') is None and e.resolve('hinge') is None


def test_sdf_model_pose_is_its_model_frame(world):
    e = WorldEntities(world)
    assert close(e.model_state(world.bodies['shelf'])[0].position, (1, 2, 0))
    assert close(e.link_state(world.bodies['shelf'], 'top')[0].position, (1, 2, 1))


def test_set_model_state_moves_every_sdf_link(world):
    e = WorldEntities(world)
    shelf = world.bodies['shelf']
    e.set_model_state(shelf, ((5.0, 5.0, 0.0), YAW_90), ((1.0, 0.0, 0.0), (0.0, 0.0, 0.0)))
    assert close(e.model_state(shelf)[0].position, (5, 5, 0))
    top_pose, top_twist = e.link_state(shelf, 'top')
    assert close(top_pose.position, (5, 5, 1)) and close(top_twist.linear, (1, 0, 0))


def test_set_model_state_zeroes_joint_velocities(world):
    e = WorldEntities(world)
    arm = world.bodies['arm']
    arm.joints['hinge'].set_position(0.4, velocity=3.0)
    e.set_model_state(arm, ((0.0, 0.0, 2.0), (0.0, 0.0, 0.0, 1.0)), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)))
    state = arm.joint_states([arm.joints['hinge'].index])[0]
    assert state.position == pytest.approx(0.4) and state.velocity == 0.0
    assert close(e.model_state(arm)[0].position, (0, 0, 2))  # the root link's frame, not its centre of mass


def test_set_link_state_of_a_urdf_child_link_carries_the_model(world):
    e = WorldEntities(world)
    arm = world.bodies['arm']
    arm.joints['hinge'].set_position(0.5)
    target = ((2.0, -3.0, 2.0), YAW_90)
    e.set_link_state(arm, 'arm_link', target, ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
    link_pose, link_twist = e.link_state(arm, 'arm_link')
    assert close(link_pose.position, target[0]) and abs(abs(sum(a * b for a, b in zip(link_pose.orientation,
                                                                                     YAW_90))) - 1) < 1e-6
    assert close(link_twist.angular, (0, 0, 1))
    # the link spins about its own origin: its centre of mass, at its origin, stands still
    assert close(link_twist.linear, (0, 0, 0), tol=1e-3)
    assert arm.joint_states([arm.joints['hinge'].index])[0].position == pytest.approx(0.5)
