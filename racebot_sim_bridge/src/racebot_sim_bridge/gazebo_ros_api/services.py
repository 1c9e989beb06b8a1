"""gazebo_ros's ROS API over a Simulator: the /gazebo services and the model/link state topics.

Names, request and response fields, and status messages follow gazebo_ros_api_plugin, so scripts
written against Gazebo read the same answers. Each group of services is a module of its own: spawn and delete
(spawn_services.py), model and link state (state_services.py), pause and reset (world_control.py), properties
(properties.py), forces (forces.py); the state topics are state_topics.py's. GazeboServices advertises them all,
in gazebo_ros's order, and answers each service's handler by the service's name (`api.get_model_state(req)`).
A robot's controller manager services are gazebo_ros_control's, offered by its plugin.
"""

from gazebo_msgs import srv
from gazebo_msgs.msg import LinkState, ModelState

from racebot_sim_bridge.gazebo_ros_api.forces import GazeboForces
from racebot_sim_bridge.gazebo_ros_api.properties import GazeboProperties
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroups
from racebot_sim_bridge.gazebo_ros_api.spawn_services import SpawnServices
from racebot_sim_bridge.gazebo_ros_api.state_services import StateServices
from racebot_sim_bridge.gazebo_ros_api.state_topics import StateTopics
from racebot_sim_bridge.gazebo_ros_api.world_control import WorldControl

# The order of gazebo_ros_api_plugin.cpp's advertiseServices(): a client that waits for one service finds
# those before it (registering takes a master call each; reset_world, the last, means all are there)
ADVERTISED = (
    'spawn_sdf_model', 'spawn_urdf_model', 'delete_model', 'delete_light', 'get_model_properties',
    'get_model_state', 'get_world_properties', 'get_joint_properties', 'get_link_properties', 'get_link_state',
    'get_light_properties', 'set_light_properties', 'get_physics_properties', 'set_link_properties',
    'set_physics_properties', 'set_model_state', 'set_model_configuration', 'set_joint_properties',
    'set_link_state', 'pause_physics', 'unpause_physics', 'apply_body_wrench', 'apply_joint_effort',
    'clear_joint_forces', 'clear_body_wrenches', 'reset_simulation', 'reset_world',
)


class GazeboServices(ServiceGroups):
    """Every /gazebo service and the state topics of a Simulator under `ns`. ``properties`` (GazeboProperties)
    is what physics_reconfigure works on; ``topics`` publishes the states."""

    def __init__(self, rospy, sim, ns='/gazebo'):
        self.rospy = rospy
        self.sim = sim
        self.ns = ns.rstrip('/')
        self.topics = StateTopics(rospy, sim, self.ns)
        self.state = StateServices(rospy, sim)
        self.properties = GazeboProperties(rospy, sim)
        self.forces = GazeboForces(rospy, sim)
        super().__init__((SpawnServices(rospy, sim, self.ns), self.state, WorldControl(rospy, sim), self.properties,
                          self.forces))
        self.services = [rospy.Service('%s/%s' % (self.ns, name), *self.handlers[name]) for name in ADVERTISED]
        # the topic forms of set_model_state / set_link_state: the same handlers, answers only logged
        self.subscribers = [
            rospy.Subscriber(self.ns + '/set_model_state', ModelState,
                             lambda m: self.state.set_model_state(srv.SetModelStateRequest(model_state=m)),
                             queue_size=10),
            rospy.Subscriber(self.ns + '/set_link_state', LinkState,
                             lambda m: self.state.set_link_state(srv.SetLinkStateRequest(link_state=m)),
                             queue_size=10),
        ]

    def states_wanted(self):
        """Whether somebody listens to model_states or link_states."""
        return self.topics.states_wanted()

    def publish_states(self):
        """model_states and link_states, each only when somebody listens."""
        self.topics.publish_states()

    def states(self, want_models=True, want_links=True):
        """(ModelStates, LinkStates) of the world now, each left empty unless wanted."""
        return self.topics.states(want_models, want_links)

    def shutdown(self):
        for s in self.services:
            s.shutdown()
        for sub in self.subscribers:
            sub.unregister()
