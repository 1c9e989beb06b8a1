"""libgazebo_ros_f3d.so (gazebo_plugins noetic-devel): the force and torque applied to a link, as
geometry_msgs/WrenchStamped.

Parameters: bodyName (required), topicName (required), frameName (default world; upstream puts it in
header.frame_id under tf_prefix but does not use it: the values are in world axes whatever it says),
robotNamespace (text + '/', none: the node's namespace). Every world update (WorldUpdateBegin) while someone
subscribes, it publishes Link::WorldForce/WorldTorque: what has been added to the link's force accumulators
since the last physics step (ODE clears them after each), the torque about its centre of mass, stamped with
the sim time. So, as in Gazebo, it reads what apply_body_wrench and the model plugins that run before it in
the same update (gazebo_ros_force listed earlier in the robot) apply, never gravity, contacts or joint
constraints (solved inside the step). Refused: a missing bodyName or topicName, a bodyName that is no link of
the model; one naming a link Gazebo lumps arrives as its parent (sdformat's rewrite).
Not counted here: a joint effort (gazebo_ros_control's SetForce, apply_joint_effort), which ODE adds to both
links' torque accumulators at once.
"""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.odometry_output import tf_prefix, tf_resolve
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in


class F3D(ModelPlugin):
    libraries = ('libgazebo_ros_f3d.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.body_name = self.link_param('bodyName', 'the link whose applied wrench is published')
        if not p.has('topicName'):
            raise PluginError('<topicName> is missing: give the topic to publish geometry_msgs/WrenchStamped on')
        self.index = robot.body.link_index[self.body_name]
        frame_name = p.string('frameName', 'world')
        if p.has('frameName'):
            self.info('<frameName> [%s] is not used, as upstream: the wrench is in world axes' % frame_name)
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        self.frame_id = tf_resolve(tf_prefix(ctx.rospy, ns, search=False), frame_name)
        from geometry_msgs.msg import WrenchStamped
        self.msg_class = WrenchStamped
        self.pub = self.publisher(name_in(ns, p.string('topicName', '')), WrenchStamped)

    def before_physics(self, time):
        if self.pub.get_num_connections() == 0:
            return
        force, torque = self.robot.body.links[self.body_name].applied_wrench()
        self.publish_wrench(time, force, torque)
