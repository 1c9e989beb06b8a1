"""Gazebo's anisotropic friction, <mu1> along <fdir1> and <mu2> across it, as Bullet's anisotropic friction
(urdf_spawn.py, bullet_urdf.link_friction_axes).

The report: AgileX hunter's rear wheels say mu1 0.8 along fdir1 "1 0 0" (square to their axle) and mu2 10 across:
they roll with little grip and hold sideways. racebot took the smaller, 0.8, both ways, the rear slid out, and the car
turned at a third of the rate its steering asks. Here the robots are written by the test: a skid (a box on a fixed
base) and a wheel on a continuous joint, each with the hunter's kind of <gazebo> block.
"""
import math

import pybullet as pb
import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld

from test_physics_world import EMPTY_WORLD

MASS = 10.0
G = 9.8


def skid(fdir1='1 0 0', rpy='0 0 0'):
    """A 10 kg box, mu1 1.0 along `fdir1` (its collision turned by `rpy`), mu2 0.1 across."""
    return ('<robot name="skid"><link name="box"><collision><origin rpy="%s"/><geometry><box size="0.2 0.2 0.1"/>'
            '</geometry></collision><inertial><mass value="%g"/><inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" '
            'izz="0.05"/></inertial></link><gazebo reference="box"><mu1>1.0</mu1><mu2>0.1</mu2><fdir1>%s</fdir1>'
            '</gazebo></robot>' % (rpy, MASS, fdir1))


def cart():
    """A 10 kg frame on two wheels on continuous joints about y and a frictionless caster sphere behind; the wheels
    (cylinders turned onto the axle) have mu1 0.1 along fdir1 "1 0 0" (square to the axle) and mu2 1.0 across."""
    def wheel(side, y):
        return ('<joint name="%s_axle" type="continuous"><parent link="frame"/><child link="%s_wheel"/><origin '
                'xyz="0 %g 0.1"/><axis xyz="0 1 0"/></joint><link name="%s_wheel"><collision><origin '
                'rpy="1.5707963 0 0"/><geometry><cylinder radius="0.1" length="0.04"/></geometry></collision>'
                '<inertial><mass value="0.1"/><inertia ixx="3e-4" ixy="0" ixz="0" iyy="5e-4" iyz="0" izz="3e-4"/>'
                '</inertial></link><gazebo reference="%s_wheel"><mu1>0.1</mu1><mu2>1.0</mu2><fdir1>1 0 0</fdir1>'
                '</gazebo>' % (side, side, y, side, side))
    return ('<robot name="cart"><link name="frame"><collision><origin xyz="-0.3 0 0.05"/><geometry><sphere '
            'radius="0.05"/></geometry></collision><inertial><origin xyz="-0.05 0 0.1"/><mass value="%g"/><inertia '
            'ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link><gazebo reference="frame">'
            '<mu1>0</mu1><mu2>0</mu2></gazebo>%s%s</robot>' % (MASS, wheel('left', 0.2), wheel('right', -0.2)))


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001, gravity=(0.0, 0.0, -G))
    w.load_world(sdf_reader.load_world(str(EMPTY_WORLD)))
    yield w
    w.close()


def pushed(world, body, force, steps=500, links=()):
    """How far a point of `body` moves in `steps` under the world force `force` at it, after settling: its base's
    centre, or the midpoint of `links` (a cart's wheels: pushed between them, it does not turn on its caster)."""
    client = world.client

    def point():
        if not links:
            return client.getBasePositionAndOrientation(body.id)[0]
        frames = [client.getLinkState(body.id, body.link_index[name])[4] for name in links]
        return [sum(c) / len(frames) for c in zip(*frames)]

    for _ in range(200):
        world.step()
    start = point()
    for _ in range(steps):
        client.applyExternalForce(body.id, -1, force, point(), pb.WORLD_FRAME)
        world.step()
    end = point()
    return math.hypot(end[0] - start[0], end[1] - start[1])


@pytest.mark.parametrize('fdir1, rpy, held, slides', [
    ('1 0 0', '0 0 0', (1, 0), (0, 1)),
    ('0 1 0', '0 0 0', (0, 1), (1, 0)),
    ('1 0 0', '0 0 1.5707963', (0, 1), (1, 0)),  # fdir1 is in the collision's frame, turned a quarter
])
def test_a_skid_grips_with_mu1_along_fdir1_and_slides_across(world, fdir1, rpy, held, slides):
    xml = skid(fdir1, rpy)
    force = 0.5 * MASS * G  # half what mu1 holds, five times what mu2 does
    body = world.spawn_urdf('skid', urdf_reader.parse_urdf(xml), xml, position=(0, 0, 0.05))
    assert pushed(world, body, [force * held[0], force * held[1], 0]) < 1e-3
    world.remove('skid')
    body = world.spawn_urdf('skid2', urdf_reader.parse_urdf(xml), xml, position=(0, 0, 0.05))
    assert pushed(world, body, [force * slides[0], force * slides[1], 0]) > 0.1


@pytest.mark.parametrize('turned', [0.0, 1.0, 2.5])
def test_wheels_hold_with_mu2_along_their_axle_however_far_they_have_turned(world, turned):
    xml = cart()
    body = world.spawn_urdf('cart', urdf_reader.parse_urdf(xml), xml)
    for joint in ('left_axle', 'right_axle'):
        world.client.resetJointState(body.id, body.joints[joint].index, turned)
    force = 0.3 * (MASS + 0.2) * G  # three times what mu1 (0.1) would hold, less than the wheels' share of mu2's
    # held: about 1 mm of creep in the 0.5 s (with mu1's 0.1 both ways it slides 0.3 m)
    assert pushed(world, body, [0, force, 0], links=('left_wheel', 'right_wheel')) < 0.005


def test_fdir1_off_the_links_axes_takes_the_smaller_mu_with_one_warning(world):
    xml = skid('1 1 0')
    warnings = []
    body = world.spawn_urdf('skid', urdf_reader.parse_urdf(xml), xml, position=(0, 0, 0.05), warn=warnings.append)
    assert len(warnings) == 1 and "<fdir1> 0.707107 0.707107 0" in warnings[0] and 'smaller, 0.1' in warnings[0]
    assert pushed(world, body, [0.5 * MASS * G, 0, 0]) > 0.1
