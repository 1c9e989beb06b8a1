"""libgazebo_ros_ft_sensor.so (gazebo_plugins noetic-devel): the wrench through a joint, as
geometry_msgs/WrenchStamped.

Parameters: jointName (required), topicName (required), gaussianNoise 0, updateRate 0 (every world update),
robotNamespace (text + '/', none: the node's namespace). As upstream's UpdateChild (on WorldUpdateBegin,
so it reads the wrench of the step before, stamped with the sim time of the step to come):
- the wrench is Joint::GetForceTorque(0)'s body2Force/body2Torque: what the parent applies to the child link
  (and all that hangs below it) through the joint, in the child link's frame, the torque about the joint
  (the child link's origin in a URDF). PyBullet measures it about the child's centre of mass in its
  inertial axes (physics.joint_wrench): turned into the link frame and moved to its origin here;
- header.frame_id the child link's name under tf_prefix; each of the six components gets its own Gaussian
  sample of gaussianNoise; nothing is computed while nobody subscribes;
- a rate limits it: skipped while less than 1/updateRate has passed since the last message (the clock
  starts at 0, not at the spawn, as upstream leaves last_time_ unset).
Refused: a missing jointName or topicName, a name that is no joint of the model, a fixed joint Gazebo lumps
(sdformat removes it: keep it with <preserveFixedJoint>), a joint holding the root link to the world.
Not verified against ODE: what a moving joint reports along its axis while an effort drives it (Gazebo
corrects for SetForce there); a fixed joint, the usual F/T mount, is.
"""
import random

from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.odometry_output import tf_prefix, tf_resolve
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.update_timing import AtLeastPeriod
from racebot_sim_bridge.kinematics.rotations import rotate


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def wrench_at_link_origin(force, torque, com_position, com_orientation):
    """A wrench measured at a link's centre of mass in its inertial axes (com_position, com_orientation: the
    inertial frame in the link frame) -> the same wrench in link axes, its torque about the link's origin."""
    f = rotate(com_orientation, force)
    t = rotate(com_orientation, torque)
    arm = cross(com_position, f)
    return f, tuple(t[i] + arm[i] for i in range(3))


class FTSensor(ModelPlugin):
    libraries = ('libgazebo_ros_ft_sensor.so',)

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        name = p.string('jointName', None)
        if name is None:
            raise PluginError('<jointName> is missing: give the joint whose wrench is measured')
        model = robot.model
        joint = model.joints.get(name)
        if joint is None:
            raise PluginError("<jointName>%s</jointName> is not a joint of the model (its joints: %s)"
                              % (name, ', '.join(sorted(model.joints))))
        if model.fixed_joint_reduced(joint):
            raise PluginError("<jointName>%s</jointName> is a fixed joint, which Gazebo lumps away (so upstream "
                              "finds no such joint); keep it with <gazebo reference=\"%s\"><preserveFixedJoint>"
                              "true</preserveFixedJoint></gazebo>" % (name, name))
        self.index = robot.body.link_index.get(joint.child)
        if self.index is None or self.index < 0:
            raise PluginError("<jointName>%s</jointName> holds the model's root link to the world: PyBullet "
                              "measures no wrench through it; put the sensor on a joint below" % name)
        if not p.has('topicName'):
            raise PluginError('<topicName> is missing: give the topic to publish geometry_msgs/WrenchStamped on')
        self.child = joint.child
        self.noise = p.number('gaussianNoise', 0.0)
        self.clock = AtLeastPeriod(p.number('updateRate', 0.0), 0.0)
        self.rng = rng or random.Random()
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        self.frame_id = tf_resolve(tf_prefix(ctx.rospy, ns, search=False), self.child)
        self.info('reporting wrench values to the frame [%s]' % self.frame_id)
        robot.body.links[self.child].enable_parent_wrench()
        from geometry_msgs.msg import WrenchStamped
        self.msg_class = WrenchStamped
        self.pub = self.publisher(name_in(ns, p.string('topicName', '')), WrenchStamped)

    def wrench(self):
        """(force, torque) through the joint, as Joint::GetForceTorque(0).body2Force/body2Torque."""
        link = self.robot.body.links[self.child]
        force, torque = link.parent_wrench()
        dyn = link.dynamics()
        return wrench_at_link_origin(force, torque, dyn.inertial_position, dyn.inertial_orientation)

    def before_physics(self, time):
        if self.clock.since(time) is None or self.pub.get_num_connections() == 0:
            return
        force, torque = self.wrench()
        if self.noise:
            gauss = self.rng.gauss
            force = tuple(v + gauss(0.0, self.noise) for v in force)
            torque = tuple(v + gauss(0.0, self.noise) for v in torque)
        self.publish_wrench(time, force, torque)
        self.clock.mark(time)
