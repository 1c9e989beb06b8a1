"""libgazebo_ros_joint_state_publisher.so (gazebo_plugins noetic-devel): sensor_msgs/JointState of
named joints.

Parameters: jointName (a comma-separated list; spaces are dropped), updateRate 100 (<= 0: every world
update), robotNamespace (none or empty: the model's name). Publishes `joint_states` in that namespace
(queue 1000), stamped with the sim time: name, position and velocity of each joint in the order given,
effort empty. Without jointName it publishes empty messages, as upstream; a name that is no movable
joint of the model refuses the plugin (upstream logs a fatal error and then dereferences a null joint).
"""
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.update_timing import FixedPeriod


def joint_names(text):
    """jointName's list as upstream splits it: every space removed, then split at each comma."""
    return text.replace(' ', '').split(',')


class JointStatePublisher(ModelPlugin):
    libraries = ('libgazebo_ros_joint_state_publisher.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        names = []
        if p.has('jointName'):
            names = joint_names(p.string('jointName', ''))
        else:
            self.warn('<jointName> is missing: publishing JointState messages with no joints, as upstream does; '
                      'list the joints, separated by commas')
        joints = self.robot.body.joints
        unknown = [n for n in names if n not in joints]
        if unknown:
            raise PluginError('<jointName>%s</jointName>: %s not movable joints of the model (its movable joints: '
                              '%s); list joint names separated by commas'
                              % (p.string('jointName', ''), ', '.join(repr(n) for n in unknown),
                                 ', '.join(sorted(joints)) or 'none'))
        self.names = names
        self.indices = [joints[n].index for n in names]
        self.clock = FixedPeriod(p.number('updateRate', 100.0), ctx.sim.time)
        ns = model_plugin_namespace('joint_state_publisher', p.string('robotNamespace', None),
                                    robot.spawn_namespace, robot.name, ctx.sim.node_namespace)
        from sensor_msgs.msg import JointState
        self.msg_class = JointState
        self.pub = self.publisher(name_in(ns, 'joint_states'), JointState, queue_size=1000)

    def before_physics(self, time):
        if not self.clock.due(time):
            return
        states = self.robot.body.joint_states_raw(self.indices) if self.indices else []
        msg = self.msg_class(name=list(self.names), position=[s[0] for s in states],
                             velocity=[s[1] for s in states])
        msg.header.stamp = self.stamp(time)
        self.pub.publish(msg)
