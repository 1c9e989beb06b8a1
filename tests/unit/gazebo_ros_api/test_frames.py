"""racebot_sim_bridge.gazebo_ros_api.frames and spawn_xml: entity names, quaternions, poses and twists in a reference
frame, as gazebo_ros_api_plugin (noetic) and ignition math give them; the spawn services' XML checks.
Pure: no master, no PyBullet."""
import math

import pytest

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.description import spawn_xml
from racebot_sim_bridge.gazebo_ros_api.frames import Entity, ModelEntry
from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy, rpy_to_quaternion

WORLD = [ModelEntry('ground_plane', ['link'], []),
         ModelEntry('car', ['base_link', 'wheel'], ['wheel_joint']),
         ModelEntry('box', ['link', 'wheel_joint', 'car'], [])]


def close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def same_rotation(q1, q2, tol=1e-9):
    return abs(abs(sum(a * b for a, b in zip(q1, q2))) - 1.0) <= tol


# -- names --------------------------------------------------------------------------------------
@pytest.mark.parametrize('name, expected', [
    ('car', Entity('car', None)),                # a model name: the model
    ('car::wheel', Entity('car', 'wheel')),      # scoped link
    ('wheel', Entity('car', 'wheel')),           # bare link name: the first model having it
    ('link', Entity('ground_plane', 'link')),    # ... ground_plane comes first in the world
    ('box::link', Entity('box', 'link')),
    ('box::car', Entity('box', 'car')),          # a link that happens to be called like a model
])
def test_resolve_finds_as_entity_by_name(name, expected):
    assert frames.resolve(name, WORLD) == expected


@pytest.mark.parametrize('name', ['', 'world', 'nobody', 'car::nobody', 'nobody::wheel', 'car::base_link::x',
                                  'wheel_joint', 'car::wheel_joint'])
def test_resolve_unknowns_and_joints_are_none(name):
    # 'wheel_joint' is a joint of car before it is a link of box: Gazebo's walk stops at the joint
    assert frames.resolve(name, WORLD) is None


def test_world_frames():
    for name in ('', 'world', 'map', '/map'):
        assert frames.is_world_frame(name)
    assert not frames.is_world_frame('World')


# -- quaternions --------------------------------------------------------------------------------
def test_zero_quaternion_is_the_identity():
    assert frames.normalised((0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 1.0)
    assert frames.normalised((0.0, 0.0, 0.0, 1e-9)) == (0.0, 0.0, 0.0, 1.0)


def test_quaternion_is_normalised():
    assert close(frames.normalised((0.0, 0.0, 2.0, 2.0)), (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)))


@pytest.mark.parametrize('bad', [(math.nan, 0, 0, 1), (0, math.inf, 0, 1)])
def test_non_finite_quaternion_is_none(bad):
    assert frames.normalised(bad) is None


# -- poses ----------------------------------------------------------------------------------------
FRAME = ((1.0, 2.0, 0.5), rpy_to_quaternion(0.0, 0.0, math.pi / 2))  # at (1, 2, 0.5), yawed 90 degrees


def test_in_world_of_a_yawed_frame():
    p, q = frames.in_world(FRAME, ((1.0, 0.0, 0.0), rpy_to_quaternion(0, 0, 0.3)))
    assert close(p, (1.0, 3.0, 0.5))  # 1 m ahead of the frame is +y in the world
    assert quaternion_to_rpy(q)[2] == pytest.approx(math.pi / 2 + 0.3)


def test_in_world_applies_the_local_rotation_first():
    rolled = ((0.0, 0.0, 0.0), rpy_to_quaternion(math.pi / 2, 0, 0))   # frame: 90 degrees about x
    q = frames.in_world(rolled, ((0.0, 0.0, 0.0), rpy_to_quaternion(0, 0, math.pi / 2)))[1]  # local: yaw 90
    from racebot_sim_bridge.kinematics.rotations import rotate
    assert close(rotate(q, (1.0, 0.0, 0.0)), (0.0, 0.0, 1.0))  # local x -> frame's y -> world z


def test_relative_to_inverts_in_world():
    local = ((0.3, -0.7, 1.1), frames.normalised((0.1, -0.2, 0.3, 0.9)))
    frame = ((-1.0, 4.0, 2.0), frames.normalised((0.4, 0.1, -0.5, 0.7)))
    p, q = frames.relative_to(frame, frames.in_world(frame, local))
    assert close(p, local[0]) and same_rotation(q, local[1])


def test_relative_to_itself_is_the_identity():
    p, q = frames.relative_to(FRAME, FRAME)
    assert close(p, (0, 0, 0)) and same_rotation(q, (0, 0, 0, 1))


# -- twists, per service ----------------------------------------------------------------------------
def test_get_state_twist_is_relative_and_in_frame_axes():
    frame_twist = ((1.0, 0.0, 0.0), (0.0, 0.0, 0.5))
    lin, ang = frames.twist_seen_from(FRAME, frame_twist, ((1.0, 2.0, 0.0), (0.0, 0.0, 1.5)))
    assert close(lin, (2.0, 0.0, 0.0))   # world +y (2 - 0) is the frame's +x
    assert close(ang, (0.0, 0.0, 1.0))


def test_set_model_twist_rotates_from_frame_axes_only():
    lin, ang = frames.set_model_twist(FRAME, ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)))
    assert close(lin, (0.0, 1.0, 0.0)) and close(ang, (-1.0, 0.0, 0.0))


def test_set_link_twist_subtracts_without_rotating():
    lin, ang = frames.set_link_twist(((1.0, 0.0, 0.0), (0.0, 0.0, 0.5)), ((3.0, 1.0, 0.0), (0.0, 0.0, 0.5)))
    assert close(lin, (2.0, 1.0, 0.0)) and close(ang, (0.0, 0.0, 0.0))


# -- spawn XML --------------------------------------------------------------------------------------
def test_formats_by_root_element():
    assert spawn_xml.is_urdf('<?xml version="1.0"?><robot name="r"><link name="a"/></robot>')
    assert spawn_xml.is_sdf('<sdf version="1.6"><model name="m"/></sdf>')
    assert spawn_xml.is_sdf('<gazebo version="1.2"><model name="m"/></gazebo>')
    for text in ('', 'not xml', '<robot name="r">', '<model name="m"/>'):
        assert not spawn_xml.is_urdf(text) and not spawn_xml.is_sdf(text)


def test_robot_namespace_goes_to_plugins_without_one():
    sdf = ('<sdf version="1.6"><model name="m"><plugin name="a" filename="a.so"/>'
           '<link name="l"><sensor name="s" type="ray"><plugin name="b" filename="b.so">'
           '<robotNamespace>/own</robotNamespace></plugin></sensor></link></model></sdf>')
    out = spawn_xml.add_robot_namespace(sdf, '/ns')
    import xml.etree.ElementTree as ET
    plugins = {p.get('name'): [n.text for n in p.findall('robotNamespace')] for p in ET.fromstring(out).iter('plugin')}
    assert plugins == {'a': ['/ns'], 'b': ['/own']}
    assert spawn_xml.add_robot_namespace(sdf, '') == sdf
