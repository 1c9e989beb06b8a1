"""libgazebo_ros_force.so (gazebo_plugins noetic-devel): a wrench from a topic applied to a link.

Parameters: bodyName (required), topicName (required), robotNamespace (text + '/', none: the node's
namespace). geometry_msgs/Wrench messages on topicName replace the wrench held (zero until the first); every
world update (WorldUpdateBegin) the force is added at the link's centre of mass and the torque to the link,
both in world axes (Link::AddForce, AddTorque), until another message comes: a reset keeps it, as upstream has
no Reset. Refused: a missing bodyName or topicName, a bodyName that is no link of the model; one naming a link
Gazebo lumps arrives as its parent (sdformat's rewrite), which the wrench then pushes.
"""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in

ZERO = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


class Force(ModelPlugin):
    libraries = ('libgazebo_ros_force.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.body_name = self.link_param('bodyName', 'the link the wrench pushes')
        if not p.has('topicName'):
            raise PluginError('<topicName> is missing: give the topic of the geometry_msgs/Wrench to apply')
        self.index = robot.body.link_index[self.body_name]
        self.wrench = ZERO
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        from geometry_msgs.msg import Wrench
        self.subscriber(name_in(ns, p.string('topicName', '')), Wrench, self.on_wrench)

    def on_wrench(self, msg):
        f, t = msg.force, msg.torque
        self.wrench = ((f.x, f.y, f.z), (t.x, t.y, t.z))  # one assignment: the physics thread reads it whole

    def before_physics(self, time):
        force, torque = self.wrench
        if force != ZERO[0] or torque != ZERO[1]:
            self.robot.body.links[self.body_name].apply_wrench(force, torque)
