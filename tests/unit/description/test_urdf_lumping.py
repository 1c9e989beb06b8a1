"""Gazebo's fixed-joint lumping on the URDF PyBullet loads (urdf_lumping), and PyBullet keeping a
preserved fixed link as a frame of its own. No ROS master."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.description.urdf_lumping import lump_fixed_links
from racebot_sim_bridge.description.urdf_reader import parse_urdf

# base --fixed (kept unless told)--> arm --fixed--> tip; arm --revolute--> wheel
ROBOT = """<robot name="r">
  <link name="base">
    <inertial><origin xyz="0 0 0.1"/><mass value="2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
    <collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/></inertial>
    <collision><origin xyz="0.1 0 0"/><geometry><box size="0.2 0.05 0.05"/></geometry></collision>
    <visual><origin xyz="0.1 0 0" rpy="0 0 0.5"/><geometry><box size="0.2 0.05 0.05"/></geometry></visual>
  </link>
  <link name="tip"><visual><geometry><sphere radius="0.01"/></geometry></visual></link>
  <link name="wheel">
    <inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="fixed"><parent link="base"/><child link="arm"/>
    <origin xyz="0.2 0 0.3" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="arm"/><child link="tip"/><origin xyz="0.2 0 0"/></joint>
  <joint name="wheel_joint" type="continuous"><parent link="arm"/><child link="wheel"/>
    <origin xyz="0 0.1 0"/><axis xyz="0 1 0"/></joint>
  %s
</robot>"""

PRESERVE_ARM = '<gazebo reference="arm_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'


def lumped(extra=''):
    xml = ROBOT % extra
    root = ET.fromstring(xml)
    lump_fixed_links(root, parse_urdf(xml))
    return root


def origin(elem):
    o = elem.find('origin')
    return ([float(v) for v in o.get('xyz').split()], [float(v) for v in o.get('rpy').split()])


def test_lumping_moves_shapes_and_joints_into_the_link_gazebo_keeps():
    root = lumped()
    assert [link.get('name') for link in root.findall('link')] == ['base', 'wheel']
    assert [j.get('name') for j in root.findall('joint')] == ['wheel_joint']
    base = root.find('link')
    arm_box = base.findall('collision')[1]
    xyz, rpy = origin(arm_box)  # arm frame at (0.2, 0, 0.3) turned 90 deg; the box 0.1 along its x
    assert xyz == pytest.approx([0.2, 0.1, 0.3]) and rpy == pytest.approx([0, 0, math.pi / 2])
    arm_visual, tip_visual = base.findall('visual')
    assert origin(arm_visual)[1] == pytest.approx([0, 0, math.pi / 2 + 0.5])
    assert origin(tip_visual)[0] == pytest.approx([0.2, 0.2, 0.3])
    wheel_joint = root.find('joint')
    assert wheel_joint.find('parent').get('link') == 'base'
    xyz, rpy = origin(wheel_joint)
    assert xyz == pytest.approx([0.1, 0.0, 0.3]) and rpy == pytest.approx([0, 0, math.pi / 2])


def test_lumped_inertia_is_the_rigid_sum_about_the_common_centre_of_mass():
    base = lumped().find('link')
    inertial = base.find('inertial')
    assert float(inertial.find('mass').get('value')) == pytest.approx(3.0)
    centre = np.array(origin(inertial)[0])
    assert origin(inertial)[1] == [0, 0, 0]
    # base: 2 kg at (0, 0, 0.1); arm: 1 kg at (0.2, 0.1, 0.3) (its joint's origin, then its inertial's)
    np.testing.assert_allclose(centre, (2 * np.array([0, 0, 0.1]) + np.array([0.2, 0.1, 0.3])) / 3)
    inertia = inertial.find('inertia')
    tensor = np.array([[float(inertia.get('i' + a + b) or inertia.get('i' + b + a)) for b in 'xyz'] for a in 'xyz'])
    expected = np.diag([0.02, 0.03, 0.04]) + np.diag([0.001, 0.002, 0.003])  # the arm's, turned 180 deg about z
    for mass, point in ((2.0, np.array([0, 0, 0.1])), (1.0, np.array([0.2, 0.1, 0.3]))):
        d = point - centre
        expected += mass * (d @ d * np.eye(3) - np.outer(d, d))
    np.testing.assert_allclose(tensor, expected, atol=1e-12)


def test_a_preserved_fixed_joint_keeps_its_link_and_lumps_below_it():
    root = lumped(PRESERVE_ARM)
    assert [link.get('name') for link in root.findall('link')] == ['base', 'arm', 'wheel']
    assert [j.get('name') for j in root.findall('joint')] == ['arm_joint', 'wheel_joint']
    arm = root.findall('link')[1]
    assert len(arm.findall('visual')) == 2  # the tip's sphere joined it
    assert root.findall('joint')[1].find('parent').get('link') == 'arm'
    assert float(root.find('link').find('inertial').find('mass').get('value')) == 2.0


def test_a_preserved_link_below_a_lumped_one_hangs_on_the_link_that_is_kept():
    root = lumped('<gazebo reference="tip_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>')
    assert [link.get('name') for link in root.findall('link')] == ['base', 'tip', 'wheel']
    tip_joint = root.find("joint[@name='tip_joint']")
    assert tip_joint.find('parent').get('link') == 'base'
    xyz, rpy = origin(tip_joint)
    assert xyz == pytest.approx([0.2, 0.2, 0.3]) and rpy == pytest.approx([0, 0, math.pi / 2])


@pytest.mark.parametrize('flag', [
    '<gazebo reference="arm_joint"><preserveFixedJoint value="1"/></gazebo>',
    '<gazebo reference="arm_joint"><disableFixedJointLumping>yes</disableFixedJointLumping></gazebo>'])
def test_the_other_spellings_keep_the_link_too(flag):
    assert [link.get("name") for link in lumped(flag).findall('link')] == ['base', 'arm', 'wheel']


def test_preserve_on_a_link_reference_is_ignored_as_gazebo_does_with_a_warning_naming_the_joint():
    model = parse_urdf(ROBOT % '<gazebo reference="arm"><preserveFixedJoint>true</preserveFixedJoint></gazebo>')
    assert model.lumped_link('arm') == 'base'
    assert any("<gazebo reference='arm'> <preserveFixedJoint>" in w and "reference=\"arm_joint\"" in w
               for w in model.warnings), model.warnings


def test_pybullet_keeps_a_preserved_link_rigid_on_its_parent():
    xml = ROBOT % PRESERVE_ARM
    world = PhysicsWorld(step_size=0.001, gravity=(0.0, 0.0, -9.8))
    try:
        body = world.spawn_urdf('r', parse_urdf(xml), xml)
        assert sorted(body.link_names()) == ['arm', 'base', 'wheel'] and sorted(body.joints) == ['wheel_joint']
        world.client.resetBaseVelocity(body.id, (0.0, 0.0, 0.0), (1.0, 2.0, 3.0))
        for _ in range(500):  # falling and tumbling for half a second
            world.step()
        base, _ = body.links['base'].state()
        arm, _ = body.links['arm'].state()
        expected = rotations.compose((base.position, base.orientation), (0.2, 0.0, 0.3, 0.0, 0.0, math.pi / 2))
        assert arm.position == pytest.approx(expected[0], abs=1e-5)
        assert arm.orientation == pytest.approx(expected[1], abs=1e-5)
        assert base.position[2] < -1.0  # it did fall
    finally:
        world.close()
