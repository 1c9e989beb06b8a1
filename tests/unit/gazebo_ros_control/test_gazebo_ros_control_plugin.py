"""libgazebo_ros_control.so hooked into a Simulator (GazeboRosControlPlugin.attach), with real PyBullet and
real rospy services (no master: rospy keeps them in its service manager, unregistered).

The plugin, not gazebo_ros_api, offers a robot's controller manager services, so they exist without any
/gazebo services (the world server with ~enable_ros_network false), for a robot from the world file as for
a spawned one, and go when the robot is deleted. A Simulator without the plugin attached runs no control."""
import rospy
from controller_manager_msgs.srv import ListControllersRequest
from rospy.impl.registration import get_service_manager

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog
from wheel_robot import EMPTY_WORLD, _robot

SERVICES = ('load_controller', 'unload_controller', 'switch_controller', 'list_controllers', 'list_controller_types',
            'reload_controller_libraries')

# A world file's robot: an SDF model with a joint and the plugin, in its own namespace.
WORLD_ROBOT = EMPTY_WORLD.replace('</world>', '''
  <model name="wbot"><pose>0 0 0.2 0 0 0</pose>
    <link name="base"><inertial><mass>1</mass></inertial>
      <collision name="c"><geometry><box><size>0.2 0.2 0.1</size></box></geometry></collision></link>
    <link name="wheel"><pose>0 0 0.1 0 0 0</pose><inertial><mass>0.1</mass></inertial></link>
    <joint name="spin" type="revolute"><parent>base</parent><child>wheel</child><axis><xyz>0 0 1</xyz></axis>
    </joint>
    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"><robotNamespace>/wbot</robotNamespace>
    </plugin>
  </model>
</world>''')


def _offered(ns):
    manager = get_service_manager()
    return [name for name in SERVICES if manager.get_service('%s/controller_manager/%s' % (ns, name)) is not None]


def test_a_world_file_robot_gets_its_controller_manager_services_without_gazebo_services():
    sim = Simulator(sdf_reader.parse_world(WORLD_ROBOT), None, FakeLog(), lambda path: None)
    GazeboRosControlPlugin.attach(sim, rospy)
    try:
        (robot,) = sim.spawn_world_robots()
        assert robot.control.ns == '/wbot' and robot.control.robot_sim_type == 'gazebo_ros_control/DefaultRobotHWSim'
        assert _offered('/wbot') == list(SERVICES)
        service = get_service_manager().get_service('/wbot/controller_manager/list_controllers')
        assert service.handler(ListControllersRequest()).controller == []  # it answers
        assert not any(name.startswith('/gazebo/') for name, _ in get_service_manager().get_services())
    finally:
        sim.close()
    assert _offered('/wbot') == []  # closing the world shuts them down


def test_a_spawned_robots_services_go_with_it_and_its_namespace_is_free_again():
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    GazeboRosControlPlugin.attach(sim, rospy)
    try:
        robot = sim.spawn_urdf('bot', _robot(''), '/fleet')
        assert _offered('/fleet') == list(SERVICES)
        assert sim.step() is None and robot.control.last_update == 0.0  # its loop runs in the world update
        sim.delete_model('bot')
        assert _offered('/fleet') == []
        assert robot.control.cm.loaded == {} and sim.spawn_urdf('bot', _robot(''), '/fleet').control.ns == '/fleet'
    finally:
        sim.close()


def test_without_the_plugin_attached_a_robot_has_no_control():
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    try:
        robot = sim.spawn_urdf('bot', _robot(''), '/alone')
        sim.step()
        assert robot.control is None and _offered('/alone') == []
    finally:
        sim.close()


def test_a_robot_without_the_plugin_is_told_why_it_has_no_controller_manager():
    log = FakeLog()
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, log, lambda path: None)
    GazeboRosControlPlugin.attach(sim, rospy)
    try:
        robot = sim.spawn_urdf('bot', _robot('').replace('libgazebo_ros_control.so', 'libsomething_else.so'), '/x')
        assert robot.control is None and _offered('/x') == []
        assert log.said('has <transmission>s but declares no libgazebo_ros_control.so plugin')
    finally:
        sim.close()
