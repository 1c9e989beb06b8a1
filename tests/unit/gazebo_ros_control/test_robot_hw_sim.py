"""gazebo_ros_control's DefaultRobotHWSim rules (robot_hw_sim): which joint and hardware interface each
<transmission> gives, and the plugin's <robotSimType> default. Pure Python, no PyBullet."""
import pytest

from racebot_sim_bridge.description.urdf_model import UrdfError
from racebot_sim_bridge.description.urdf_reader import parse_urdf
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin, control_plugin
from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import DEFAULT_ROBOT_SIM_TYPE, hardware_joints

from urdf_fixture import EFFORT, FIXTURE, with_body


@pytest.fixture(scope='module')
def model():
    return parse_urdf(FIXTURE)


def test_the_control_plugin_is_the_first_that_names_the_library(model):
    plugin = control_plugin(model)
    assert plugin.name == 'gazebo_ros_control' and plugin.robot_namespace == '/minicar'
    assert GazeboRosControlPlugin.filename == 'libgazebo_ros_control.so'
    assert DEFAULT_ROBOT_SIM_TYPE == 'gazebo_ros_control/DefaultRobotHWSim'
    assert control_plugin(parse_urdf(with_body('<link name="a"/>'))) is None
    spelt = parse_urdf(with_body('<link name="a"/><gazebo><plugin name="x" filename="/opt/lib/gazebo_ros_control.so"/>'
                                 '<plugin name="y" filename="libgazebo_ros_control.so"/></gazebo>'))
    assert control_plugin(spelt).name == 'x'
    assert any("only the first ('x') is used" in w for w in spelt.warnings)


def test_hardware_joints_follow_gazebo_ros_control(model):
    assert hardware_joints(model) == [('left_hinge_joint', EFFORT), ('left_wheel_joint', EFFORT)]


def test_hardware_interface_from_actuator_with_warning():
    model = parse_urdf(with_body("""
      <link name="a"/><link name="b"/>
      <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>
      <transmission name="t"><type>x</type><joint name="j"/>
        <actuator name="m"><hardwareInterface>VelocityJointInterface</hardwareInterface>
        </actuator></transmission>"""))
    assert hardware_joints(model) == [('j', 'hardware_interface/VelocityJointInterface')]
    assert any('belongs inside <joint' in w for w in model.warnings)


def test_hardware_joints_skip_unsupported_and_interfaceless_with_warnings():
    model = parse_urdf(with_body("""
      <link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
      <joint name="j2" type="continuous"><parent link="a"/><child link="c"/></joint>
      <transmission name="t1"><joint name="j1">
        <hardwareInterface>hardware_interface/JointCommandInterface</hardwareInterface>
      </joint></transmission>
      <transmission name="t2"><joint name="j2"/></transmission>
      <transmission name="t3"><joint name="j1"><hardwareInterface>x/Y</hardwareInterface>
        </joint><joint name="j2"/></transmission>"""))
    assert hardware_joints(model) == []
    text = '\n'.join(model.warnings)
    assert "'hardware_interface/JointCommandInterface' is not supported" in text
    assert "joint 'j2' has no <hardwareInterface>" in text
    assert "transmission 't3' has 2 joints" in text
    assert hardware_joints(model, supported=('hardware_interface/JointCommandInterface',)) == [
        ('j1', 'hardware_interface/JointCommandInterface')]


def test_hardware_joints_missing_joint_names_transmission_and_joint(model):
    model.transmissions[0].joints[0] = ('gone_joint', [EFFORT])
    try:
        with pytest.raises(UrdfError, match="transmission 'left_hinge_trans'.*'gone_joint'"):
            hardware_joints(model)
    finally:
        model.transmissions[0].joints[0] = ('left_hinge_joint', [EFFORT])
