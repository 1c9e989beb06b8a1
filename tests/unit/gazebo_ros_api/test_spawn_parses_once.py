"""One spawn, one parse: the model XML of a spawn request is parsed once, and the tree and the model read
from it go along (issue 28, item 3). Every XML parse goes through xml.etree's XMLParser (fromstring, parse),
which the test wraps to count; the spawn runs through gazebo_ros_api's spawn services with real rospy (no
master), gazebo_ros_control and model plugins attached, as in the world server."""
import xml.etree.ElementTree as ET

import pytest
import rospy
from gazebo_msgs.srv import SpawnModelRequest
from geometry_msgs.msg import Pose, Quaternion

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_ros_api.services import GazeboServices
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog
from wheel_robot import EMPTY_WORLD, _robot

# An SDF robot: links and a joint (the URDF path simulates it), no plugin or sensor blocks (sdf_model keeps
# those as text, which the conversion to URDF reads again).
SDF_ROBOT = '''<sdf version="1.6"><model name="arm">
  <link name="base"><inertial><mass>1</mass></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.1</size></box></geometry></collision></link>
  <link name="top"><pose>0 0 0.1 0 0 0</pose><inertial><mass>0.1</mass></inertial></link>
  <joint name="yaw" type="revolute"><parent>base</parent><child>top</child><axis><xyz>0 0 1</xyz></axis></joint>
</model></sdf>'''


@pytest.fixture
def parses(monkeypatch):
    """The number of XML documents parsed since the fixture was set up."""
    count = [0]

    class CountingParser(ET.XMLParser):
        def __init__(self, *args, **kwargs):
            count[0] += 1
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(ET, 'XMLParser', CountingParser)
    return count


@pytest.fixture
def world():
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    plugins = PluginManager(rospy, sim)
    GazeboRosControlPlugin.attach(sim, rospy)
    services = GazeboServices(rospy, sim, '/gazebo')
    yield sim, services
    services.shutdown()
    plugins.close()
    sim.close()


def _request(name, xml, namespace=''):
    return SpawnModelRequest(model_name=name, model_xml=xml, robot_namespace=namespace,
                             initial_pose=Pose(orientation=Quaternion(0, 0, 0, 1)), reference_frame='')


def test_the_counter_counts_every_parse(parses):
    ET.fromstring('<a/>')
    sdf_reader.parse_world(EMPTY_WORLD)
    assert parses[0] == 2


def test_spawn_urdf_model_parses_the_urdf_once(world, parses):
    sim, services = world
    res = services.spawn_urdf_model(_request('bot', _robot(''), '/fleet'))
    assert res.success, res.status_message
    assert sim.robots['bot'].control.ns == '/fleet'  # the whole spawn: body, controller manager, plugins
    assert parses[0] == 1


def test_spawn_sdf_model_parses_the_sdf_once(world, parses):
    sim, services = world
    res = services.spawn_sdf_model(_request('arm', SDF_ROBOT))
    assert res.success, res.status_message
    assert 'yaw' in sim.body('arm').joints  # spawned through the URDF path, from the converted tree
    assert parses[0] == 1


def test_the_simulator_parses_urdf_text_once(world, parses):
    sim, _ = world
    assert sim.spawn_urdf('bot', _robot(''), '/').control is not None
    assert parses[0] == 1
