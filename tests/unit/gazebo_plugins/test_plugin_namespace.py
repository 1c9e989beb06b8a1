"""Where plugins land (issue 16, row 1): a plugin's own <robotNamespace> wins; the spawn request's
robot_namespace applies only to plugins without one; each plugin's default otherwise (gazebo_ros
noetic-devel: gazebo_ros_api_plugin's walk, gazebo_ros_control, GetRobotNamespace, imu_sensor).
Pure rules, the sensors' topics, and the controller manager's namespace of a spawned robot."""
import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import (after_spawn, control_namespace, resolve,
                                                                sensor_namespace)
from racebot_sim_bridge.gazebo_plugins.sensor_manager import sensor_config
from racebot_sim_bridge.engine.simulator import Simulator, SpawnError
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from wheel_robot import EMPTY_WORLD, _robot
from fakes import FakeLog


def test_the_plugins_own_element_wins_even_empty():
    assert after_spawn('/mine', '/fleet') == '/mine'
    assert after_spawn('', '/fleet') == ''
    assert after_spawn(None, '/fleet') == '/fleet'
    assert after_spawn(None, '/') == '/'
    assert after_spawn(None, '') is None  # an empty request adds nothing


@pytest.mark.parametrize('name, node_ns, expected', [
    ('', '/', '/'), ('/', '/', '/'), ('bot', '/', '/bot'), ('/bot/', '/', '/bot'), ('a//b', '/', '/a/b'),
    ('bot', '/sim/', '/sim/bot'), ('', '/sim', '/sim'), ('/bot', '/sim', '/bot')])
def test_resolve_as_a_node_handle(name, node_ns, expected):
    assert resolve(name, node_ns) == expected


@pytest.mark.parametrize('own, requested, expected', [
    (None, '', '/car'),          # no element, nothing requested: the model name
    (None, '/', '/'),            # spawn_model at the root sends '/'
    (None, '/fleet', '/fleet'),
    ('/mine', '/fleet', '/mine'),
    ('', '/fleet', '/'),         # an empty element: NodeHandle('') is the node's namespace
])
def test_control_plugin(own, requested, expected):
    assert control_namespace(own, requested, 'car') == expected


@pytest.mark.parametrize('kind, own, requested, camera, expected', [
    ('laser', None, '', '', '/'),
    ('laser', None, '/fleet', '', '/fleet'),
    ('laser', '', '/fleet', '', '/car'),        # GetRobotNamespace: an empty element -> the model name
    ('laser', 'bot', '/fleet', '', '/bot'),
    ('camera', None, '', 'cam', '/cam'),        # robotNamespace + '/' + cameraName
    ('camera', None, '/fleet', 'cam', '/fleet/cam'),
    ('depth', '/own', '/fleet', 'rs', '/own/rs'),
    ('imu', None, '', '', '/car'),              # gazebo_ros_imu_sensor: '/<model>/' without the element
    ('imu', None, '/', '', '/'),
    ('imu', '', '/fleet', '', '/'),
    ('imu', 'own', '/fleet', '', '/own'),
])
def test_sensor_plugins(kind, own, requested, camera, expected):
    assert sensor_namespace(kind, own, requested, 'car', camera) == expected


def test_relative_namespaces_resolve_in_the_world_servers_namespace():
    assert control_namespace(None, 'fleet', 'car', '/sim') == '/sim/fleet'
    assert sensor_namespace('laser', None, '', 'car', node_namespace='/sim') == '/sim'
    assert sensor_namespace('camera', None, '', 'car', 'cam', '/sim') == '/cam'  # '/' + cameraName: absolute


def test_racebot_sensors_spawned_at_the_root_and_with_an_empty_namespace(racebot_xml):
    model = urdf_reader.parse_urdf(racebot_xml)

    def topics(requested):
        return {c.kind: c.topics for c in (sensor_config(s, requested, 'racebot') for s in model.sensors)}
    root = topics('/')  # spawn_model run at the root
    assert root['imu'] == {'imu': '/imu'}
    assert root['laser'] == {'scan': '/scan'}  # an absolute topicName stays
    assert root['camera']['image'] == '/rrbot/camera1/image_raw'
    assert topics('')['imu'] == {'imu': '/racebot/imu'}  # as gazebo_ros_imu_sensor without robotNamespace
    fleet = topics('/fleet')
    assert fleet['imu'] == {'imu': '/fleet/imu'}
    assert fleet['camera']['image'] == '/fleet/rrbot/camera1/image_raw'
    assert fleet['depth']['points'] == '/fleet/real_sense/depth/points'
    assert fleet['laser'] == {'scan': '/scan'}


def _laser(plugin_body):
    xml = ('<robot name="r"><link name="a"/><gazebo reference="a"><sensor type="ray" name="s"><ray><scan>'
           '<horizontal><samples>5</samples></horizontal></scan><range><min>0.1</min><max>4</max></range></ray>'
           '<plugin name="p" filename="libgazebo_ros_laser.so">%s</plugin></sensor></gazebo></robot>' % plugin_body)
    return urdf_reader.parse_urdf(xml).sensors[0]


def test_laser_topic_defaults_as_gazebo_ros_laser():
    c = sensor_config(_laser('<frameName>a</frameName>'), '/fleet', 'r')
    assert c.topics == {'scan': '/world'} and any('/world' in w for w in c.warnings)
    assert sensor_config(_laser('<topicName>scan</topicName>'), '/fleet', 'r').topics == {'scan': '/fleet/scan'}
    assert sensor_config(_laser('<topicName></topicName>'), '/fleet', 'r') is None  # advertises nothing


@pytest.mark.parametrize('element, requested, expected_ns', [
    ('', '', '/bot'), ('', '/', ''), ('', '/fleet', '/fleet'),
    ('<robotNamespace>/mine</robotNamespace>', '/fleet', '/mine'),  # the request no longer overrides it
    ('<robotNamespace>/mine</robotNamespace>', '', '/mine'),
])
def test_spawned_robot_controller_manager_namespace(element, requested, expected_ns):
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    GazeboRosControlPlugin.attach(sim)
    try:
        robot = sim.spawn_urdf('bot', _robot(element), requested)
        assert robot.control.ns == expected_ns and robot.control.cm.ns == expected_ns
        assert robot.spawn_namespace == requested
    finally:
        sim.close()


def test_two_robots_cannot_share_a_controller_manager_namespace():
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    GazeboRosControlPlugin.attach(sim)
    try:
        sim.spawn_urdf('one', _robot(''), '/')
        with pytest.raises(SpawnError) as err:
            sim.spawn_urdf('two', _robot(''), '/')  # spawn_model at the root, no robotNamespace of its own
        assert "robot namespace '/' is already used by model 'one'" in str(err.value)
        assert 'another <robotNamespace>' in str(err.value) and 'another -robot_namespace' in str(err.value)
        assert sim.spawn_urdf('two', _robot(''), '/two').control.ns == '/two'
    finally:
        sim.close()
