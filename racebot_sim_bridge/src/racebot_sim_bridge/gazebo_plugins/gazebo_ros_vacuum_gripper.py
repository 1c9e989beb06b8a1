"""libgazebo_ros_vacuum_gripper.so (gazebo_plugins noetic-devel): a link that pulls in and holds nearby links.

Parameters: bodyName (required: the gripping link), topicName (required: where std_msgs/Bool grasping is
published, every world update), robotNamespace (text + '/', none: the node's namespace); std_srvs/Empty
services `on` and `off` in that namespace (a warning when it already is so). While on, every world update
(WorldUpdateBegin), for every link of every other model (not this one, nor one named as bodyName) whose frame
is within 5 cm of bodyName's frame, as upstream computes (vacuum_step): the link gets bodyName's linear and
angular velocity (Link::SetLinearVel/SetAngularVel), within 1 cm it is put at bodyName's position (its
rotation kept), and a force of min(1 / distance, 20) N, so always 20 N, is added at its centre of mass along
the gripper's offset EXPRESSED IN THE LINK'S OWN AXES (ignition's Pose3 subtraction) but applied in world
axes, as upstream does: toward the gripper only while the link is not rotated. grasping is true when any link
was within reach. Refused: a missing bodyName or topicName, a bodyName that is no link of the model (upstream
logs a fatal error and does nothing).
Not as Gazebo: PyBullet keeps an articulated model in reduced coordinates, so a link that is not its model's
root gets its velocity and position by moving the whole model rigidly (gazebo_ros_api/entities, as
set_link_state); a static model's links are counted in grasping but not moved or pushed (static bodies do not
move in PyBullet).
"""
import math

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities
from racebot_sim_bridge.kinematics.rotations import rotate_back

REACH = 0.05  # m: a link closer than this is grasped
SNAP = 0.01  # m: ... and closer than this is put at the gripper
MAX_FORCE = 20.0  # N


def vacuum_step(gripper_position, link_position, link_orientation):
    """(grasped, snapped, force in world axes) upstream computes for one link: None when out of reach."""
    offset = rotate_back(link_orientation, tuple(g - p for g, p in zip(gripper_position, link_position)))
    norm = math.sqrt(sum(c * c for c in offset))
    if norm >= REACH:
        return None
    magnitude = min(1.0 / norm, MAX_FORCE) if norm > 0 else MAX_FORCE
    direction = tuple(c / norm for c in offset) if norm > 0 else (0.0, 0.0, 0.0)  # Normalize leaves zero alone
    return norm < SNAP, tuple(magnitude * c for c in direction)


class VacuumGripper(ModelPlugin):
    libraries = ('libgazebo_ros_vacuum_gripper.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        if not p.has('bodyName'):
            raise PluginError('<bodyName> is missing: give the gripping link')
        self.link = self.link_param('bodyName', 'the gripping link')
        if not p.has('topicName'):
            raise PluginError('<topicName> is missing: give the topic to publish std_msgs/Bool grasping on')
        self.on = False  # upstream's status_, set by the services on rospy's threads (one assignment)
        self.entities = WorldEntities(self.world)
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        from std_msgs.msg import Bool
        from std_srvs.srv import Empty, EmptyResponse
        self.bool_class, self.empty_response = Bool, EmptyResponse
        self.pub = self.publisher(name_in(ns, p.string('topicName', '')), Bool)
        self.service(name_in(ns, 'on'), Empty, self._on)
        self.service(name_in(ns, 'off'), Empty, self._off)

    def _on(self, request):
        if self.on:
            self.warn("gazebo_ros_vacuum_gripper: already status is 'on'")
        else:
            self.on = True
            self.info('gazebo_ros_vacuum_gripper: status: off -> on')
        return self.empty_response()

    def _off(self, request):
        if self.on:
            self.on = False
            self.info('gazebo_ros_vacuum_gripper: status: on -> off')
        else:
            self.warn("gazebo_ros_vacuum_gripper: already status is 'off'")
        return self.empty_response()

    def before_physics(self, time):
        grasping = False
        if self.on:
            position, _, linear, angular = link_motion(self.world, self.robot.body, self.link)
            for name, body in list(self.world.bodies.items()):
                if name == self.link or body is self.robot.body:
                    continue
                for link in WorldEntities.link_names(body):
                    grasping = self._pull(body, link, position, (linear, angular)) or grasping
        self.pub.publish(self.bool_class(data=grasping))

    def _pull(self, body, link, gripper_position, gripper_twist):
        pose, _ = self.entities.link_state(body, link)
        step = vacuum_step(gripper_position, pose.position, pose.orientation)
        if step is None:
            return False
        snapped, force = step
        if body.static:
            return True
        target = (gripper_position, pose.orientation) if snapped else (pose.position, pose.orientation)
        self.entities.set_link_state(body, link, target, gripper_twist)
        body.links[link].apply_wrench(force, (0.0, 0.0, 0.0))
        return True
