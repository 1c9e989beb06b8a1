"""sdformat 9's fixed-joint reduction of the <gazebo> extensions (description/sdf_reduction), one rule per test,
on URDFs written as robot packages write them. The expected numbers are derived by hand from each rule of
parser_urdf.cc (sdf9) in the comments; sdformat writes them with C++'s six significant digits."""
import math
import xml.etree.ElementTree as ET

import pytest

from racebot_sim_bridge.description.sdf_reduction import cpp_text, reduction_order, urdf_rpy
from racebot_sim_bridge.description.urdf_reader import parse_urdf
from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy, rpy_to_quaternion

HALF_PI = '1.5707963267948966'

# A mobile base as community packages write it: base_link with mass, an imu_link without <inertial> on a
# fixed joint, 0.1 0.2 0.3 away and turned a quarter turn about z (J below); a wheel on a moving joint.
BASE = """<robot name="bot">
  <link name="base_link">
    <inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/><child link="imu_link"/>
    <origin xyz="0.1 0.2 0.3" rpy="0 0 %s"/>
  </joint>
  <link name="wheel">
    <inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel"/><origin xyz="0 0.2 0"/><axis xyz="0 1 0"/>
  </joint>
  %%s
</robot>""" % HALF_PI

IMU_PLUGIN = """<gazebo><plugin name="imu_plugin" filename="libgazebo_ros_imu.so">
  <topicName>imu</topicName>%s</plugin></gazebo>"""


def model(extra='', robot=BASE):
    return parse_urdf(robot % extra)


def numbers(text):
    return tuple(float(v) for v in text.split())


def plugin(extra, robot=BASE):
    (p,) = model(extra, robot).plugins
    return p


# -- which links, in which order (ReduceFixedJoints, FixedJointShouldBeReduced) ------------------------------

CHAIN = """<robot name="chain">
  <link name="base_footprint"/><link name="base_link"/><link name="a_link"/><link name="a_tip"/>
  <link name="imu_link"/><link name="wheel"/><link name="wheel_marker"/><link name="kept"/>
  <joint name="base_joint" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
  <joint name="a_joint" type="fixed"><parent link="base_link"/><child link="a_link"/></joint>
  <joint name="a_tip_joint" type="fixed"><parent link="a_link"/><child link="a_tip"/></joint>
  <joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/></joint>
  <joint name="marker_joint" type="fixed"><parent link="wheel"/><child link="wheel_marker"/></joint>
  <joint name="kept_joint" type="fixed"><parent link="base_link"/><child link="kept"/></joint>
  <gazebo reference="kept_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
</robot>"""


def test_links_are_reduced_depth_first_fixed_children_before_their_parent_in_joint_name_order():
    # ReduceFixedJoints(base_footprint): its fixed child base_link first, whose fixed children go in urdfdom's
    # joint-name order (a_joint, imu_joint; kept_joint is preserved): a_link's own child a_tip before a_link;
    # then base_link itself; then the moving children (wheel, whose fixed child wheel_marker is reduced).
    m = parse_urdf(CHAIN)
    assert [(link, joint.name) for link, joint in reduction_order(m)] == [
        ('a_tip', 'a_tip_joint'), ('a_link', 'a_joint'), ('imu_link', 'imu_joint'), ('base_link', 'base_joint'),
        ('wheel_marker', 'marker_joint')]


@pytest.mark.parametrize('switch', ['<preserveFixedJoint>true</preserveFixedJoint>',
                                    '<disableFixedJointLumping>1</disableFixedJointLumping>',
                                    '<disableFixedJointLumping>yes</disableFixedJointLumping>'
                                    '<preserveFixedJoint>true</preserveFixedJoint>'])
def test_a_kept_fixed_joint_reduces_nothing_and_rewrites_nothing(switch):
    # FixedJointShouldBeReduced is false for a joint named by either switch (both: preserveFixedJoint wins,
    # still kept): imu_link stays a link, the plugin keeps its name and gets no offsets
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName>' + '<gazebo reference="imu_joint">%s</gazebo>' % switch)
    assert p.params == {'topicName': 'imu', 'bodyName': 'imu_link'} and p.rewrites == []


def test_the_switch_on_the_link_instead_of_the_joint_does_not_keep_it():
    # sdformat compares the switch's reference with joint names only
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName>'
               + '<gazebo reference="imu_link"><preserveFixedJoint>true</preserveFixedJoint></gazebo>')
    assert p.params['bodyName'] == 'base_link'


def test_nothing_is_reduced_into_a_link_named_world():
    # ReduceFixedJoints skips a link whose parent is "world" (the model is then fixed to the world)
    robot = BASE.replace('<link name="base_link">', '<link name="world"/><joint name="fix" type="fixed">'
                         '<parent link="world"/><child link="base_link"/></joint><link name="base_link">')
    m = model(IMU_PLUGIN % '<bodyName>base_link</bodyName>', robot)
    assert [link for link, _ in reduction_order(m)] == ['imu_link']
    assert m.plugins[0].params['bodyName'] == 'base_link'


# -- ReduceSDFExtensionPluginFrameReplace -------------------------------------------------------------------

def test_a_model_plugins_body_name_becomes_the_parent_with_the_joint_as_offsets():
    # bodyName imu_link -> base_link; no offsets written, so the block's reduction transform (identity for a
    # model-level block) stands in, composed with J: xyzOffset = J's xyz, rpyOffset = J's rpy (six digits)
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName><updateRate>50</updateRate>')
    assert p.reference is None
    assert p.params['bodyName'] == 'base_link' and p.params['updateRate'] == '50' and p.params['topicName'] == 'imu'
    assert numbers(p.params['xyzOffset']) == (0.1, 0.2, 0.3)
    assert numbers(p.params['rpyOffset']) == (0.0, 0.0, 1.5708)  # pi/2 written with six significant digits
    assert p.params['ignition::corrected_offsets'] == '1'


def test_offsets_the_plugin_gives_are_composed_with_the_joint():
    # J * (xyzOffset, rpyOffset): the offset position turned by J's quarter turn, (0.05, 0, 0) -> (0, 0.05, 0),
    # plus J's xyz; the yaws add: pi/2 + 0.5 = 2.0708 (six digits)
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName><xyzOffset>0.05 0 0</xyzOffset>'
               '<rpyOffset>0 0 0.5</rpyOffset>')
    assert numbers(p.params['xyzOffset']) == pytest.approx((0.1, 0.25, 0.3), abs=1e-12)
    assert numbers(p.params['rpyOffset']) == (0.0, 0.0, 2.0708)


def test_an_offset_the_plugin_lacks_comes_from_the_reduction_transform():
    # only rpyOffset written: the position is the model-level block's (identity), so xyzOffset = J's xyz; the
    # rotation J * Rz(0.5). A bad xyzOffset reads as 0 0 0 (ParseVector3) and is replaced.
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName><rpyOffset>0 0 0.5</rpyOffset>')
    assert numbers(p.params['xyzOffset']) == (0.1, 0.2, 0.3) and numbers(p.params['rpyOffset'])[2] == 2.0708
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName><xyzOffset>a b c</xyzOffset>')
    assert numbers(p.params['xyzOffset']) == (0.1, 0.2, 0.3)


def test_a_frame_name_is_rewritten_the_same_way():
    # frameName imu_link -> base_link with the offsets, even though bodyName names a kept link: the IMU's
    # frame_id becomes base_link and its orientation gets J's rotation
    p = plugin(IMU_PLUGIN % '<bodyName>base_link</bodyName><frameName>imu_link</frameName>')
    assert (p.params['bodyName'], p.params['frameName']) == ('base_link', 'base_link')
    assert numbers(p.params['xyzOffset']) == (0.1, 0.2, 0.3) and numbers(p.params['rpyOffset'])[2] == 1.5708


def test_body_name_and_frame_name_both_on_the_lumped_link_count_the_joint_twice():
    # bodyName first: offsets J (written as text, six digits); then frameName reads them back: J * J.
    # Position: (0.1, 0.2, 0.3) + Rz(pi/2) (0.1, 0.2, 0.3) = (0.1 - 0.2, 0.2 + 0.1, 0.6); yaw pi/2 + 1.5708,
    # just past pi, so getRPY gives it as -3.14159: compare the angles modulo a turn
    p = plugin(IMU_PLUGIN % '<bodyName>imu_link</bodyName><frameName>imu_link</frameName>')
    assert (p.params['bodyName'], p.params['frameName']) == ('base_link', 'base_link')
    assert numbers(p.params['xyzOffset']) == pytest.approx((-0.1, 0.3, 0.6), abs=1e-12)
    yaw = numbers(p.params['rpyOffset'])[2]
    assert math.remainder(yaw - (math.pi / 2 + 1.5708), 2 * math.pi) == pytest.approx(0.0, abs=5e-6)


def test_a_plugin_in_the_lumped_links_own_block_moves_and_counts_the_joint_twice():
    # <gazebo reference="imu_link"><plugin>: the block moves to base_link and its reduction transform becomes
    # J; without offsets of its own the plugin takes J's, then composes J again: J * J, as above
    (p,) = model('<gazebo reference="imu_link"><plugin name="p3d" filename="libgazebo_ros_p3d.so">'
                 '<bodyName>imu_link</bodyName><topicName>odom</topicName></plugin></gazebo>').plugins
    assert p.reference == 'base_link' and p.params['bodyName'] == 'base_link'
    assert numbers(p.params['xyzOffset']) == pytest.approx((-0.1, 0.3, 0.6), abs=1e-12)
    assert math.remainder(numbers(p.params['rpyOffset'])[2] - math.pi, 2 * math.pi) == pytest.approx(0.0, abs=5e-6)
    assert [r.element for r in p.rewrites][:2] == ['reference', 'bodyName']


def test_a_chain_of_lumped_links_rewrites_once_per_joint():
    # tip -(0 0 0.1)-> mid -(0.2 0 0, yaw pi/2)-> base: first bodyName tip -> mid, offsets (0, 0, 0.1); then
    # mid -> base, offsets J_mid * that = (0.2, 0, 0.1) and yaw pi/2
    robot = """<robot name="c"><link name="base"/><link name="mid"/><link name="tip"/>
      <joint name="j1" type="fixed"><parent link="base"/><child link="mid"/><origin xyz="0.2 0 0" rpy="0 0 %s"/></joint>
      <joint name="j2" type="fixed"><parent link="mid"/><child link="tip"/><origin xyz="0 0 0.1"/></joint>
      %%s</robot>""" % HALF_PI
    p = plugin(IMU_PLUGIN % '<bodyName>tip</bodyName>', robot)
    assert p.params['bodyName'] == 'base'
    assert numbers(p.params['xyzOffset']) == (0.2, 0.0, 0.1) and numbers(p.params['rpyOffset'])[2] == 1.5708
    assert [(r.element, r.written, r.now) for r in p.rewrites if r.element == 'bodyName'] == [
        ('bodyName', 'tip', 'mid'), ('bodyName', 'mid', 'base')]


def test_other_plugins_other_tags_and_a_sensors_own_plugin_are_left_alone():
    # only <bodyName> and <frameName> of a top-level <plugin> are looked at: robotBaseFrame stays, a plugin
    # naming kept links gets no offsets, and the <plugin> inside a <sensor> keeps frameName imu_link
    m = model('<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><robotBaseFrame>imu_link'
              '</robotBaseFrame></plugin><plugin name="p3d" filename="libgazebo_ros_p3d.so"><bodyName>wheel'
              '</bodyName></plugin></gazebo><gazebo reference="imu_link"><sensor name="imu" type="imu">'
              '<plugin name="i" filename="libgazebo_ros_imu_sensor.so"><frameName>imu_link</frameName></plugin>'
              '</sensor></gazebo>')
    dd, p3d = m.plugins
    assert dd.params == {'robotBaseFrame': 'imu_link'} and dd.rewrites == []
    assert p3d.params == {'bodyName': 'wheel'} and p3d.rewrites == []
    assert m.sensors[0].plugins[0].params == {'frameName': 'imu_link'}


# -- ReduceSDFExtensionToParent + ReduceSDFExtensionElementTransformReduction --------------------------------

CAMERA = """<robot name="cam">
  <link name="link0"/><link name="camera_link"/>
  <joint name="camera_joint" type="fixed"><parent link="link0"/><child link="camera_link"/>
    <origin xyz="333 0 0" rpy="0 0 1.57079632679"/></joint>
  <gazebo reference="camera_link">%s</gazebo>
</robot>"""


def sensor(body, robot=CAMERA):
    (s,) = parse_urdf(robot % ('<sensor name="cam" type="camera"><camera><image><width>8</width><height>6</height>'
                               '</image></camera>%s</sensor>' % body)).sensors
    return s


def test_a_sensor_moves_to_the_parent_with_its_pose_composed():
    # sdformat's own test (urdf_gazebo_extensions, sensorPose): J = (333 0 0, yaw 1.57079632679), pose
    # (111 0 0, yaw -1): J * pose = (333 + 111 cos(J), 111 sin(J), 0) = (333, 111, 0) in six digits, yaw
    # 1.5708 - 1 = 0.570796
    s = sensor('<pose>111 0 0 0 0 -1</pose>')
    assert s.reference == 'link0'
    assert s.pose == (333.0, 111.0, 0.0, 0.0, 0.0, 0.570796)
    assert [(r.element, r.written) for r in s.rewrites] == [('pose', '111 0 0 0 0 -1'),
                                                             ('reference', 'camera_link')]


def test_a_sensor_without_a_pose_gets_the_joints():
    # sensorNoPose: pose 0, so J itself: (333, 0, 0, yaw 1.5708)
    assert sensor('').pose == (333.0, 0.0, 0.0, 0.0, 0.0, 1.5708)


def test_a_sensor_two_lumped_links_down_is_composed_twice():
    # sensorPoseTwoLevel: link0 -(0 0 222)-> a -(333 0 0, yaw pi/2)-> b, pose (111 0 0, yaw -1): first
    # (333, 111, 0, yaw 0.570796) in a, then + (0, 0, 222) in link0
    robot = CAMERA.replace('<link name="camera_link"/>', '<link name="a"/><link name="camera_link"/>').replace(
        '<parent link="link0"/>', '<parent link="a"/>').replace(
        '</robot>', '<joint name="j0" type="fixed"><parent link="link0"/><child link="a"/>'
                    '<origin xyz="0 0 222"/></joint></robot>')
    s = sensor('<pose>111 0 0 0 0 -1</pose>', robot)
    assert s.reference == 'link0' and s.pose == (333.0, 111.0, 222.0, 0.0, 0.0, 0.570796)


def test_a_sensor_on_a_kept_link_is_left_alone():
    s = parse_urdf(BASE % '<gazebo reference="wheel"><sensor name="s" type="imu"><pose>1 2 3 0 0 0</pose>'
                          '</sensor></gazebo>').sensors[0]
    assert (s.reference, s.pose, s.rewrites) == ('wheel', (1.0, 2.0, 3.0, 0.0, 0.0, 0.0), [])


def test_lights_and_projectors_of_the_block_move_with_their_poses_unless_relative_to():
    m = parse_urdf(CAMERA % '<light name="l" type="point"><pose>111 0 0 0 0 -1</pose></light>'
                            '<projector name="p"/><projector name="q"><pose relative_to="link0">1 0 0 0 0 0</pose>'
                            '</projector><velocity_decay><linear>0.1</linear></velocity_decay>')
    light, projector, relative = m.gazebo_elements  # velocity_decay is no element a rule names
    assert [e.reference for e in m.gazebo_elements] == ['link0'] * 3
    assert numbers(light.element.find('pose').text) == (333.0, 111.0, 0.0, 0.0, 0.0, 0.570796)
    assert numbers(projector.element.find('pose').text) == (333.0, 0.0, 0.0, 0.0, 0.0, 1.5708)
    assert relative.element.find('pose').text == '1 0 0 0 0 0'  # relative_to: sdformat returns before it


def test_the_properties_stay_under_the_link_they_were_written_for():
    # sdformat moves them too but applies a lumped link's mu1 etc. to that link's lumped collisions only (by
    # their names): racebot keeps them keyed by the link, which its physics reads so
    m = model('<gazebo reference="imu_link"><mu1>0.2</mu1><material>Gazebo/Red</material>'
              '<selfCollide>true</selfCollide></gazebo>')
    assert m.gazebo_refs == {'imu_link': {'mu1': 0.2, 'material': 'Gazebo/Red', 'selfCollide': True}}


# -- ReduceSDFExtensionContactSensorFrameReplace ------------------------------------------------------------

BUMPER = """<robot name="bump">
  <link name="base_link"><collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision></link>
  <link name="bumper_link"><collision><geometry><box size="0.02 0.3 0.05"/></geometry></collision></link>
  <joint name="bumper_joint" type="fixed"><parent link="base_link"/><child link="bumper_link"/>
    <origin xyz="0.21 0 0"/></joint>
  %s
</robot>"""


def contact(reference, *collisions):
    block = ('<gazebo reference="%s"><sensor name="bumper" type="contact"><contact>%s</contact></sensor></gazebo>'
             % (reference, ''.join('<collision>%s</collision>' % c for c in collisions)))
    (s,) = parse_urdf(BUMPER % block).sensors
    return s


def test_the_lumped_links_own_collision_name_becomes_one_no_collision_has():
    # bumper_link_collision -> base_link_collision_bumper_link (Gazebo names the lumped collision
    # base_link_fixed_joint_lump__bumper_link_collision_1: the bumper then reports nothing, as in Gazebo)
    s = contact('bumper_link', 'bumper_link_collision')
    assert s.reference == 'base_link' and s.contact_collisions == ['base_link_collision_bumper_link']
    assert ('contact/collision', 'bumper_link_collision', 'base_link_collision_bumper_link') in [
        (r.element, r.written, r.now) for r in s.rewrites]


def test_only_the_first_collision_is_looked_at_and_it_goes_last():
    s = contact('bumper_link', 'bumper_link_collision', 'base_link_collision')
    assert s.contact_collisions == ['base_link_collision', 'base_link_collision_bumper_link']
    s = contact('bumper_link', 'base_link_collision', 'bumper_link_collision')
    assert s.contact_collisions == ['base_link_collision', 'bumper_link_collision']
    s = contact('bumper_link', 'base_link_fixed_joint_lump__bumper_link_collision_1')
    assert s.contact_collisions == ['base_link_fixed_joint_lump__bumper_link_collision_1'] and s.rewrites[-1].element \
        == 'reference'


def test_a_sensor_on_another_link_naming_the_lumped_links_collision_is_rewritten_too():
    # every extension's sensors are looked at, not only the lumped link's
    s = contact('base_link', 'bumper_link_collision')
    assert s.reference == 'base_link' and s.contact_collisions == ['base_link_collision_bumper_link']


# -- Gripper, Joint and Projector FrameReplace --------------------------------------------------------------

ARM = """<robot name="arm">
  <link name="base_link"/><link name="wrist"/><link name="palm"/><link name="finger"/><link name="camera_link"/>
  <joint name="wrist_joint" type="revolute"><parent link="base_link"/><child link="wrist"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="palm_joint" type="fixed"><parent link="wrist"/><child link="palm"/><origin xyz="0 0 0.1"/></joint>
  <joint name="finger_joint" type="prismatic"><parent link="palm"/><child link="finger"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="camera_joint" type="fixed"><parent link="wrist"/><child link="camera_link"/></joint>
  %s
</robot>"""


def element(extra):
    (e,) = parse_urdf(ARM % extra).gazebo_elements
    return e.element


def test_a_grippers_palm_and_gripper_links_naming_the_lumped_link_become_the_parent():
    e = element('<gazebo><gripper name="g"><grasp_check><attach_steps>20</attach_steps></grasp_check>'
                '<gripper_link>finger</gripper_link><palm_link>palm</palm_link></gripper></gazebo>')
    assert (e.find('gripper_link').text, e.find('palm_link').text) == ('finger', 'wrist')  # finger moves


def test_an_sdf_joints_parent_and_child_naming_the_lumped_link_become_the_parent():
    e = element('<gazebo><joint name="loop" type="revolute"><parent>palm</parent><child>camera_link</child>'
                '</joint></gazebo>')
    assert (e.find('parent').text, e.find('child').text) == ('wrist', 'wrist')


def test_a_projector_reference_link_slash_name_gets_the_parent():
    m = parse_urdf(ARM % '<gazebo><plugin name="proj" filename="libgazebo_ros_projector.so">'
                         '<projector>camera_link/texture</projector><projector_topic>p</projector_topic></plugin>'
                         '</gazebo>')
    assert m.plugins[0].params['projector'] == 'wrist/texture'
    for kept in ('texture', 'finger/texture'):  # no link named: sdformat complains; a kept link stays
        assert parse_urdf(ARM % '<gazebo><plugin name="proj" filename="libgazebo_ros_projector.so"><projector>'
                                '%s</projector></plugin></gazebo>' % kept).plugins[0].params['projector'] == kept


# -- how sdformat writes numbers ----------------------------------------------------------------------------

def test_numbers_are_written_with_cpps_six_significant_digits():
    assert cpp_text(0.1 + 0.2, 333.0000000005, math.pi, -0.0, 1e-17, 123456789.0) == \
        '0.3 333 3.14159 -0 1e-17 1.23457e+08'


@pytest.mark.parametrize('rpy', [(0.1, 0.2, 0.3), (-2.0, 1.0, 3.0), (0.0, 0.0, math.pi / 2)])
def test_urdf_rpy_is_the_inverse_of_rpy_away_from_gimbal_lock(rpy):
    assert urdf_rpy(rpy_to_quaternion(*rpy)) == pytest.approx(quaternion_to_rpy(rpy_to_quaternion(*rpy)))


def test_urdf_rpy_at_gimbal_lock_puts_the_turn_in_the_yaw():
    # urdfdom's getRPY: |sin pitch| >= 0.99999 -> roll 0, yaw 2 atan2(-x, y) for pitch +pi/2
    # (the same turn as roll 0.3: R = Rz(-0.3) Ry(pi/2) = Ry(pi/2) Rx(0.3))
    q = rpy_to_quaternion(0.3, math.pi / 2, 0.0)
    assert urdf_rpy(q) == pytest.approx((0.0, math.pi / 2, -0.3))
    q = rpy_to_quaternion(0.3, -math.pi / 2, 0.0)
    assert urdf_rpy(q) == pytest.approx((0.0, -math.pi / 2, 0.3))


def test_the_model_still_pickles_with_its_elements():
    import pickle
    m = parse_urdf(ARM % '<gazebo><gripper name="g"><palm_link>palm</palm_link></gripper></gazebo>')
    copy = pickle.loads(pickle.dumps(m))
    assert ET.tostring(copy.gazebo_elements[0].element) == ET.tostring(m.gazebo_elements[0].element)
