"""Unit tests of racebot_sim_bridge.description.urdf_reader and urdf_model (URDF + Gazebo extensions)."""

import math

import pytest
from hypothesis import given, settings, strategies as st

from racebot_sim_bridge.description.urdf_model import UrdfError, normalise_interface
from racebot_sim_bridge.description.urdf_reader import parse_urdf

from urdf_fixture import EFFORT, FIXTURE, with_body


@pytest.fixture(scope='module')
def model():
    return parse_urdf(FIXTURE)


def test_links_joints_and_root_in_document_order(model):
    assert model.name == 'minicar'
    assert list(model.links) == ['base_footprint', 'base_link', 'lidar', 'left_hinge',
                                 'left_wheel']
    assert list(model.joints) == ['base_joint', 'lidar_joint', 'left_hinge_joint',
                                  'left_wheel_joint']
    assert model.root_link == 'base_footprint'
    assert model.children('base_link') == ['lidar', 'left_hinge']
    assert model.parent_joint('left_wheel').name == 'left_wheel_joint'


def test_inertial_and_geometry(model):
    base = model.links['base_link']
    assert base.inertial.mass == 4.0
    assert base.inertial.origin_xyz == (0.0, 0.0, 0.01)
    assert (base.inertial.ixx, base.inertial.izz) == (0.0264, 0.00364)
    assert model.links['base_footprint'].inertial is None
    assert base.collisions[0].kind == 'box' and base.collisions[0].size == (0.28, 0.10, 0.03)
    visual = base.visuals[0]
    assert visual.kind == 'mesh' and visual.scale == (0.001, 0.001, 0.001)
    assert visual.origin_rpy == (0.0, 0.0, 1.5708)
    assert visual.rgba == (0.0, 0.0, 0.0, 1.0)  # named robot-level material
    wheel = model.links['left_wheel']
    assert wheel.collisions[0].kind == 'sphere' and wheel.collisions[0].radius == 0.032
    assert (wheel.visuals[0].radius, wheel.visuals[0].length) == (0.033, 0.02)
    assert wheel.visuals[0].rgba == (1.0, 0.0, 0.0, 1.0)


def test_joint_fields(model):
    hinge = model.joints['left_hinge_joint']
    assert (hinge.type, hinge.parent, hinge.child) == ('revolute', 'base_link', 'left_hinge')
    assert hinge.axis == (0.0, 0.0, 1.0)
    assert hinge.origin_xyz == (0.13, 0.065, 0.0)
    assert (hinge.limit.lower, hinge.limit.upper, hinge.limit.effort,
            hinge.limit.velocity) == (-0.6, 0.6, 5.0, 1000.0)
    assert hinge.dynamics is None
    wheel = model.joints['left_wheel_joint']
    assert wheel.type == 'continuous' and wheel.axis == (0.0, 1.0, 0.0)
    assert (wheel.limit.lower, wheel.limit.upper) == (0.0, 0.0)
    assert (wheel.dynamics.damping, wheel.dynamics.friction) == (0.1, 0.2)
    assert model.joints['base_joint'].axis == (1.0, 0.0, 0.0)


def test_transmissions_normalise_interfaces_and_warn_on_bare_spelling(model):
    hinge, wheel = model.transmissions
    assert hinge.type == 'transmission_interface/SimpleTransmission'
    assert hinge.joints == [('left_hinge_joint', [EFFORT])]
    assert hinge.actuators == [('left_hinge_motor', [EFFORT], 1.0)]
    assert wheel.joints == [('left_wheel_joint', [EFFORT])]
    assert wheel.actuators == [('left_wheel_motor', [], 2.0)]
    assert any("deprecated interface spelling 'EffortJointInterface'" in w
               for w in model.warnings)


def test_gazebo_references_hold_simple_properties(model):
    assert model.gazebo_refs['left_wheel'] == {
        'mu1': 2.0, 'mu2': 2.0, 'kp': 1e7, 'kd': 1.0, 'material': 'Gazebo/Black'}



def test_gazebo_extensions_take_the_value_attribute_else_the_text():
    """sdformat's URDF reader (parser_urdf.cc, GetKeyValueAsString) reads the extensions it knows from
    their value attribute when there is one, else from the text; it copies the others as they are."""
    model = parse_urdf(with_body("""
      <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
      <gazebo reference="a"><mu1 value="0.5"/><mu2 value="0.7">9</mu2><kp value="1e7"/><kd>2</kd>
        <material value="Gazebo/Red"/><fdir1 value="0 1 0"/><maxContacts value="4"/>
        <turnGravityOff value="true"/><selfCollide value="yes"/><static>0</static>
        <gravity value="0"/></gazebo>"""))
    assert model.warnings == []
    assert model.gazebo_refs['a'] == {
        'mu1': 0.5, 'mu2': 0.7, 'kp': 1e7, 'kd': 2.0, 'material': 'Gazebo/Red', 'fdir1': '0 1 0',
        'maxContacts': 4.0, 'turnGravityOff': True, 'selfCollide': True, 'static': False,
        'gravity': ''}  # not an extension sdformat reads: copied into the SDF as written, value unread
    from racebot_sim_bridge.engine.bullet_urdf import link_friction
    assert link_friction(model, 'a') == 0.5


@pytest.mark.parametrize('text, flag', [('true', True), ('TRUE', True), ('yes', True), ('1', True),
                                        ('1.0', False), ('false', False), ('', False)])
def test_gazebo_flags_are_true_as_sdformat_reads_them(text, flag):
    model = parse_urdf(with_body(
        '<link name="a"/><gazebo reference="a"><selfCollide value="%s"/><turnGravityOff>%s</turnGravityOff>'
        '</gazebo>' % (text, 'no' if flag else 'on')))
    assert model.gazebo_refs['a'] == {'selfCollide': flag, 'turnGravityOff': not flag}


def test_gazebo_ros_control_plugin_parameters(model):
    (plugin,) = [p for p in model.plugins if p.is_ros_control]
    assert plugin.name == 'gazebo_ros_control' and plugin.reference is None
    assert plugin.robot_namespace == '/minicar'
    assert plugin.robot_param == 'robot_description'
    assert plugin.control_period == 0.002


def test_gazebo_ros_control_plugin_defaults():
    (plugin,) = parse_urdf(with_body(
        '<link name="a"/><gazebo><plugin name="x" filename="libgazebo_ros_control.so"/>'
        '</gazebo>')).plugins
    assert plugin.is_ros_control
    assert plugin.robot_namespace is None and plugin.control_period is None


def test_ray_sensor(model):
    (sensor,) = model.sensors
    # lidar is lumped into base_link, that into base_footprint: the sensor is Gazebo's on base_footprint, its
    # pose the two joints' (sdf_reduction; test_sdf_reduction has the rules)
    assert (sensor.name, sensor.type, sensor.reference) == ('hokuyo', 'ray', 'base_footprint')
    assert sensor.pose == (0.09, 0.0, 0.152, 0.0, 0.0, 1.5708)
    assert sensor.update_rate == 40.0 and sensor.visualize is False
    ray = sensor.ray
    assert ray.samples == 1081 and ray.resolution == 1.0
    assert (ray.min_angle, ray.max_angle) == (-2.3561944902, 2.3561944902)
    assert (ray.range_min, ray.range_max, ray.range_resolution) == (0.1, 10.0, 0.01)
    assert (ray.noise_type, ray.noise_mean, ray.noise_stddev) == ('gaussian', 0.0, 0.01)
    assert sensor.plugins[0].params == {'topicName': '/scan', 'frameName': 'lidar'}
    assert sensor.camera is None


def test_ray_sensor_has_no_lens():
    """<distortion> is a camera's (sdformat's <camera><distortion>); inside <ray> it means nothing, so a
    bad value there cannot refuse the laser."""
    model = parse_urdf(with_body(
        '<link name="l"/><gazebo reference="l"><sensor type="ray" name="r"><ray><scan><horizontal>'
        '<samples>8</samples></horizontal></scan><range><min>0.1</min><max>5</max></range>'
        '<distortion><k1>abc</k1></distortion></ray></sensor></gazebo>'))
    (sensor,) = model.sensors
    assert sensor.ray.samples == 8 and not hasattr(sensor.ray, 'distortion')


def test_camera_depth_and_imu_sensors():
    model = parse_urdf(with_body("""
      <link name="cam"/>
      <gazebo reference="cam">
        <sensor type="depth" name="rs">
          <always_on>true</always_on><update_rate>20</update_rate>
          <camera name="head">
            <horizontal_fov>1.0471975512</horizontal_fov>
            <image><width>640</width><height>480</height><format>R8G8B8</format></image>
            <clip><near>0.05</near><far>8</far></clip>
            <noise><type>gaussian</type><mean>0</mean><stddev>0.007</stddev></noise>
          </camera>
          <plugin name="kinect" filename="libgazebo_ros_openni_kinect.so">
            <cameraName>real_sense</cameraName>
            <depthImageTopicName>depth/image_raw</depthImageTopicName>
            <pointCloudTopicName>depth/points</pointCloudTopicName>
          </plugin>
        </sensor>
        <sensor type="imu" name="imu_sensor">
          <update_rate>100</update_rate>
          <imu><angular_velocity><x><noise type="gaussian"><mean>0.1</mean>
            <stddev>0.2</stddev></noise></x></angular_velocity></imu>
        </sensor>
      </gazebo>"""))
    depth, imu = model.sensors
    assert depth.type == 'depth' and depth.always_on is True and depth.update_rate == 20.0
    camera = depth.camera
    assert (camera.name, camera.width, camera.height, camera.format) == \
        ('head', 640, 480, 'R8G8B8')
    assert (camera.clip_near, camera.clip_far, camera.noise_stddev) == (0.05, 8.0, 0.007)
    assert camera.horizontal_fov == pytest.approx(math.radians(60))
    assert depth.plugins[0].params['pointCloudTopicName'] == 'depth/points'
    # per axis (mean, stddev, bias_mean, bias_stddev): only x was given
    assert imu.imu.angular_velocity_noise == ((0.1, 0.2, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0))
    assert imu.imu.linear_acceleration_noise == ((0.0, 0.0, 0.0, 0.0),) * 3


def test_fixed_joint_lumping(model):
    assert [j.name for j in model.fixed_parent_chain('lidar')] == ['lidar_joint', 'base_joint']
    assert model.lumped_link('lidar') == 'base_footprint'
    assert model.lumped_link('left_hinge') == 'left_hinge'
    xyz, quat = model.pose_in_lumped_link('lidar')
    assert xyz == pytest.approx((0.09, 0.0, 0.152))
    assert quat == pytest.approx((0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4)))


def test_pose_in_lumped_link_composes_parent_first():
    model = parse_urdf(with_body("""
      <link name="a"/><link name="b"/><link name="c"/>
      <joint name="ab" type="fixed"><parent link="a"/><child link="b"/>
        <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/></joint>
      <joint name="bc" type="fixed"><parent link="b"/><child link="c"/>
        <origin xyz="1 0 0"/></joint>"""))
    xyz, _ = model.pose_in_lumped_link('c')
    assert xyz == pytest.approx((1.0, 1.0, 0.0))


def test_plugin_params_are_stripped_and_the_first_wins():
    model = parse_urdf(with_body(
        '<link name="a"/><gazebo><plugin name="p" filename="libp.so">'
        '<topicName>\n  /first  \n</topicName><topicName>/second</topicName></plugin></gazebo>'))
    assert model.plugins[0].params == {'topicName': '/first'}


def test_preserve_fixed_joint_stops_lumping():
    model = parse_urdf(with_body("""
      <link name="a"/><link name="b"/>
      <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
      <gazebo reference="j"><preserveFixedJoint>true</preserveFixedJoint></gazebo>"""))
    assert model.lumped_link('b') == 'b'


def test_normalise_interface():
    assert normalise_interface('EffortJointInterface') == EFFORT
    assert normalise_interface(EFFORT) == EFFORT


# -- errors ------------------------------------------------------------------------------

@pytest.mark.parametrize('text, message', [
    ('', 'empty'),
    ('   \n', 'empty'),
    ('<robot name="r"><link name="a"></robot>', r'not valid XML: mismatched tag: line 1, column'),
    ('<sdf version="1.6"/>', r'root element is <sdf>, expected <robot>; .*spawn_model -sdf'),
    ('<robot><link name="a"/></robot>', 'no name attribute'),
    (with_body(''), 'has no links'),
    (with_body('<link name="a"/><link name="a"/>'), "link 'a' is defined twice"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
               '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'),
     "joint 'j' is defined twice"),
    (with_body('<link name="a"/>'
               '<joint name="j" type="fixed"><parent link="a"/><child link="ghost"/></joint>'),
     r"joint 'j': child link 'ghost' does not exist; add <link name=\"ghost\"/>"),
    (with_body('<link name="a"/>'
               '<joint name="j" type="fixed"><parent link="nobody"/><child link="a"/></joint>'),
     "joint 'j': parent link 'nobody' does not exist"),
    (with_body('<link name="a"/><link name="b"/>'),
     r"several root links \('a', 'b'\)"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
               '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>'),
     'no root link'),
    (with_body('<link name="r0"/><link name="a"/><link name="b"/>'
               '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
               '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>'),
     'not connected to the root link'),
    (with_body('<link name="a"/><link name="b"/><link name="c"/>'
               '<joint name="j1" type="fixed"><parent link="a"/><child link="c"/></joint>'
               '<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>'),
     "link 'c' is the child of two joints"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="hinge"><parent link="a"/><child link="b"/></joint>'),
     "joint 'j' has type 'hinge'"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="fixed"><parent link="a"/></joint>'),
     r"joint 'j' has no <child link="),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>'),
     "joint 'j' is revolute but has no <limit>"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
               '<limit lower="0" upper="1" velocity="1"/></joint>'),
     "joint 'j' <limit> has no effort attribute"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
               '<limit lower="-x" upper="1" effort="1" velocity="1"/></joint>'),
     r"joint 'j' <limit> lower: '-x' is not a number"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
               '<origin xyz="0 nan 0"/></joint>'),
     "joint 'j' <origin> xyz: 'nan' is not finite"),
    (with_body('<link name="a"/><link name="b"/>'
               '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
               '<origin xyz="0 0"/></joint>'),
     "joint 'j' <origin> xyz: expected 3 numbers"),
    (with_body('<link name="a"><inertial><mass value="heavy"/>'
               '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'),
     r"link 'a' <mass> value: 'heavy' is not a number"),
    (with_body('<link name="a"><inertial><mass value="1"/></inertial></link>'),
     "link 'a' <inertial> has no <inertia>"),
    (with_body('<link name="a"><collision><geometry><box size="1 1"/></geometry>'
               '</collision></link>'), r"link 'a' <collision> #1 <box> size: expected 3"),
    (with_body('<link name="a"><visual><geometry/></visual></link>'),
     r"link 'a' <visual> #1 has no <geometry> shape"),
    (with_body('<link name="a"><visual><geometry><torus/></geometry></visual></link>'),
     'unknown geometry <torus>'),
    (with_body('<link name="a"/><gazebo><plugin name="c" filename="libgazebo_ros_control.so">'
               '<controlPeriod>fast</controlPeriod></plugin></gazebo>'),
     r"plugin 'c' <controlPeriod>: 'fast' is not a number"),
    (with_body('<link name="a"/><gazebo reference="a"><sensor type="ray" name="s">'
               '<update_rate>often</update_rate></sensor></gazebo>'),
     r"sensor 's' \(on 'a'\) <update_rate>: 'often' is not a number"),
    (with_body('<link name="a"/><gazebo reference="a"><sensor type="ray" name="s">'
               '<ray><scan><horizontal><samples>10.5</samples></horizontal></scan></ray>'
               '</sensor></gazebo>'),
     "is not a whole number"),
])
def test_errors(text, message):
    with pytest.raises(UrdfError, match=message):
        parse_urdf(text)


def test_parse_error_carries_line_and_column():
    with pytest.raises(UrdfError, match=r'line 3, column 1'):
        parse_urdf('<robot name="r">\n<link name="a"/>\n<<\n</robot>')


@pytest.mark.parametrize('data', [
    '<robot name="\ud800"/>',  # a lone surrogate cannot be encoded
    b'<?xml version="1.0" encoding="shift_jis"?><robot name="r"/>',  # multi-byte encoding
    b'<?xml version="1.0" encoding="no-such-codec"?><robot name="r"/>',
])
def test_undecodable_input_is_a_urdf_error(data):
    with pytest.raises(UrdfError):
        parse_urdf(data)


def test_non_text_input_is_a_urdf_error():
    with pytest.raises(UrdfError, match='must be URDF text'):
        parse_urdf(None)


def test_gazebo_reference_to_unknown_link_warns():
    model = parse_urdf(with_body('<link name="a"/><gazebo reference="b"><mu1>1</mu1></gazebo>'))
    assert model.gazebo_refs == {}
    assert any("<gazebo reference='b'> names no link" in w for w in model.warnings)


_xmlish = st.text(alphabet=st.sampled_from(list('<>/="\' abcdefghijklmnoprstuvxyz0123456789.-'
                                                '\n')) | st.characters(), max_size=300)
_urdf_words = st.lists(st.sampled_from([
    '<robot name="r">', '</robot>', '<link name="a"/>', '<link name="b">', '</link>',
    '<joint name="j" type="revolute">', '<joint name="k" type="fixed">', '</joint>',
    '<parent link="a"/>', '<child link="b"/>', '<limit effort="1" velocity="x"/>',
    '<origin xyz="1 2"/>', '<transmission name="t">', '</transmission>', '<joint name="j"/>',
    '<gazebo reference="a">', '<gazebo>', '</gazebo>', '<sensor name="s" type="ray">',
    '</sensor>', '<samples>-3</samples>', '<plugin name="p" filename="f.so">', '</plugin>',
    '<inertial>', '</inertial>', '<mass value="1"/>', '<geometry>', '</geometry>',
    '<visual>', '</visual>', '<box size="1 1 1"/>', '<mesh/>']), max_size=25).map(''.join)


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.binary(max_size=300), _xmlish, _urdf_words))
def test_random_input_raises_only_urdf_error(data):
    try:
        parse_urdf(data)
    except UrdfError:
        pass
