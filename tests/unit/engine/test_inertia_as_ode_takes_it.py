"""A link's inertia as Gazebo 11's ODE takes it (issue 37 item 4), on a real PhysicsWorld (PyBullet DIRECT).

ODE's dBodySetMass (Gazebo's deps/opende/src/ode.cpp) inverts the inertia with dInvertPDMatrix; when its Cholesky
factorisation fails (not positive definite) the inverse inertia is the identity: the link turns as if it had
1 kg m^2 about each axis. PyBullet's URDF importer zeroes such an inertia ("Bad inertia tensor properties"), and also
one that is positive definite but has a moment larger than the other two together, which ODE takes as written.
The arm: two 1 kg links, 0.5 m long, on parallel revolute joints about y, let go horizontal under gravity.
"""
import pybullet as pb
import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.gazebo_ros_api.link_properties import tensor_from_principal

GOOD = dict(ixx=1e-3, ixy=0, ixz=0, iyy=1e-3, iyz=0, izz=1e-3)
IDENTITY = dict(ixx=1, ixy=0, ixz=0, iyy=1, iyz=0, izz=1)
NOT_POSITIVE_DEFINITE = {
    'negative_moment': dict(GOOD, iyy=-1e-3),
    'products_too_large': dict(GOOD, ixz=5e-3),
    'all_zero': dict(ixx=0, ixy=0, ixz=0, iyy=0, iyz=0, izz=0),
}


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001)
    yield w
    w.close()


def arm(inertia, rpy='0 0 0'):
    attrs = ' '.join('%s="%r"' % kv for kv in inertia.items())
    link = ('<link name="%%s"><inertial><origin xyz="0.25 0 0" rpy="%s"/><mass value="1"/><inertia %s/></inertial>'
            '<collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>'
            % (rpy, attrs))
    joint = ('<joint name="%s" type="revolute"><parent link="%s"/><child link="%s"/><origin xyz="%s"/>'
             '<axis xyz="0 1 0"/><limit lower="-10" upper="10" effort="100" velocity="100"/></joint>')
    return ('<robot name="arm"><link name="world"/>%s%s%s%s</robot>'
            % (link % 'upper', link % 'lower', joint % ('shoulder', 'world', 'upper', '0 0 1'),
               joint % ('elbow', 'upper', 'lower', '0.5 0 0')))


def spawn(world, name, xml, y, warnings=None):
    return world.spawn_urdf(name, urdf_reader.parse_urdf(xml), xml, position=(0, y, 0),
                            warn=(warnings.append if warnings is not None else pytest.fail))


def swing(world, bodies, seconds=1.0):
    """Each body's (shoulder, elbow) angles after `seconds` let go, no goal, no controller."""
    for _ in range(int(round(seconds / world.step_size))):
        world.step()
    return [tuple(body.joints[j].state().position for j in ('shoulder', 'elbow')) for body in bodies]


@pytest.mark.parametrize('case', sorted(NOT_POSITIVE_DEFINITE))
def test_a_urdf_arm_whose_inertia_is_not_positive_definite_swings_as_with_identity_inertia(world, case):
    warnings = []
    bad = spawn(world, 'bad', arm(NOT_POSITIVE_DEFINITE[case]), 0.0, warnings)
    reference = spawn(world, 'reference', arm(IDENTITY), 5.0)
    zeroed = spawn(world, 'zeroed', arm(GOOD), 10.0)  # what PyBullet's "Bad inertia" made of it: inertia 0
    for link in ('upper', 'lower'):
        world.client.changeDynamics(zeroed.id, zeroed.link_index[link], localInertiaDiagonal=(0, 0, 0))
    assert [world.client.getDynamicsInfo(bad.id, bad.link_index[link])[2] for link in ('upper', 'lower')] == \
        [(1.0, 1.0, 1.0)] * 2
    got, want, before = swing(world, [bad, reference, zeroed])
    assert got == pytest.approx(want, abs=1e-6)
    assert abs(before[0] - want[0]) > 0.5  # zero inertia: the arm swung more than half a radian further
    assert len(warnings) == 2, warnings  # one per link
    for link, warning in zip(('upper', 'lower'), warnings):
        assert "model 'bad' link '%s'" % link in warning and 'not positive definite' in warning
        assert 'Gazebo/ODE uses the identity inertia' in warning
        assert ', '.join('%s %g' % kv for kv in NOT_POSITIVE_DEFINITE[case].items()) in warning


def test_a_positive_definite_inertia_pybullet_would_zero_is_simulated_as_written(world):
    # 5e-3 > 1e-3 + 1e-3: no real body has it, ODE takes it as written (and says nothing), PyBullet zeroed it
    triangle = dict(GOOD, izz=5e-3)
    body = spawn(world, 'triangle', arm(triangle), 0.0)
    reference = spawn(world, 'reference', arm(GOOD), 5.0)  # about y only iyy = 1e-3 counts
    assert world.client.getDynamicsInfo(body.id, body.link_index['upper'])[2] == pytest.approx((1e-3, 1e-3, 5e-3))
    got, want = swing(world, [body, reference])
    assert got == pytest.approx(want, abs=1e-9)


def test_such_an_inertia_with_products_keeps_its_principal_axes(world):
    # diag(1e-3, 5e-3, 1e-3) turned 0.5 rad about x, then the inertial origin turned 0.3 rad about z
    import math
    c, s = math.cos(0.5), math.sin(0.5)
    tensor = dict(ixx=1e-3, ixy=0.0, ixz=0.0, iyy=c * c * 5e-3 + s * s * 1e-3, iyz=c * s * (5e-3 - 1e-3),
                  izz=s * s * 5e-3 + c * c * 1e-3)
    body = spawn(world, 'turned', arm(tensor, rpy='0 0 0.3'), 0.0)
    d = body.links['upper'].dynamics()
    assert sorted(d.inertia_diagonal) == pytest.approx([1e-3, 1e-3, 5e-3])
    # back in the link's axes: the written tensor turned by the origin's 0.3 rad about z
    cz, sz = math.cos(0.3), math.sin(0.3)
    rz = [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]
    t = [[tensor['ixx'], tensor['ixy'], tensor['ixz']], [tensor['ixy'], tensor['iyy'], tensor['iyz']],
         [tensor['ixz'], tensor['iyz'], tensor['izz']]]
    want = [[sum(rz[a][k] * t[k][m] * rz[b][m] for k in range(3) for m in range(3)) for b in range(3)]
            for a in range(3)]
    got = tensor_from_principal(d.inertia_diagonal, d.inertial_orientation)
    assert got == pytest.approx((want[0][0], want[0][1], want[0][2], want[1][1], want[1][2], want[2][2]), abs=1e-12)


def test_a_good_inertia_is_untouched_and_unwarned(world):
    body = spawn(world, 'good', arm(dict(GOOD, iyy=2e-3, ixz=1e-4)), 0.0)
    d = body.links['upper'].dynamics()
    assert sorted(d.inertia_diagonal) == pytest.approx(sorted([2e-3, 1e-3 + 1e-4, 1e-3 - 1e-4]))


def sdf_world(tmp_path, inertia):
    path = tmp_path / 'w.world'
    path.write_text('<sdf version="1.6"><world name="w"><model name="block"><pose>0 0 5 0 0 0</pose><link name="body">'
                    '<inertial><mass>2</mass><inertia>%s</inertia></inertial><collision name="c"><geometry><box>'
                    '<size>0.2 0.2 0.2</size></box></geometry></collision></link></model></world></sdf>'
                    % ''.join('<%s>%r</%s>' % (k, v, k) for k, v in inertia.items()))
    return sdf_reader.load_world(str(path))


@pytest.mark.parametrize('case', sorted(NOT_POSITIVE_DEFINITE))
def test_an_sdf_link_whose_inertia_is_not_positive_definite_gets_identity_inertia(world, tmp_path, case):
    spec = sdf_world(tmp_path, NOT_POSITIVE_DEFINITE[case])
    warnings = []
    assert world.load_world(spec, warn=warnings.append) == ['block']
    body = world.bodies['block']
    assert world.client.getDynamicsInfo(body.id, -1)[2] == (1.0, 1.0, 1.0)
    assert len(warnings) == 1, warnings
    assert "model 'block' link 'body'" in warnings[0] and 'Gazebo/ODE uses the identity inertia' in warnings[0]
    # a torque of 1 N m turns it at 1 rad/s^2, as a body of 1 kg m^2
    world.client.changeDynamics(body.id, -1, angularDamping=0.0)
    for _ in range(100):
        world.client.applyExternalTorque(body.id, -1, (0, 0, 1), pb.WORLD_FRAME)
        world.step()
    assert world.client.getBaseVelocity(body.id)[1][2] == pytest.approx(0.1, rel=1e-3)


def test_an_sdf_link_with_a_good_inertia_is_unwarned(world, tmp_path):
    spec = sdf_world(tmp_path, dict(GOOD, iyy=2e-3))
    assert world.load_world(spec, warn=pytest.fail) == ['block']
    assert world.client.getDynamicsInfo(world.bodies['block'].id, -1)[2] == pytest.approx((1e-3, 2e-3, 1e-3))
