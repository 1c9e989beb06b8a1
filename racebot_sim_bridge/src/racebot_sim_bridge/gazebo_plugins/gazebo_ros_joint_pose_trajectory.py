"""libgazebo_ros_joint_pose_trajectory.so (gazebo_plugins noetic-devel): a trajectory_msgs/JointTrajectory played
by setting joint positions, with the world's physics off while it plays.

Parameters: topicName (set_joint_trajectory; empty: no subscription), robotNamespace (text + '/', none: the node's
namespace); serviceName and updateRate are read and not used, as upstream (its service is compiled out,
ENABLE_SERVICE undefined; every world update is an update). noetic builds no libgazebo_ros_joint_trajectory.so
(removed in gazebo_ros_pkgs #708), so that name stays unsimulated, as Gazebo could not load it.
A trajectory (queue 100) is taken at the next world update, as upstream's callback does:
- header.frame_id other than world, map, /map names a reference link (World::EntityByName: any model's, scoped
  or not), whose model becomes the one played on (and stays so for later trajectories, as upstream's model_);
  none of that name: an error and the message is dropped (so an empty frame_id is refused, as upstream);
- joint_names are looked up in that model (an unknown one is skipped); start = header.stamp, or now if earlier;
- physics is turned off (World::SetPhysicsEnabled(false)), after saving whether it was on.
Then at every world update from the start, the next point's positions are set (Joint::SetPosition, kinematic),
the reference link (else the model) kept where it was before, and the start moves on by that point's
time_from_start: upstream adds each point's time_from_start to the previous point's time, so points at 1 s and
2 s play at start, start + 1 s and start + 3 s. The update after the last point ends the trajectory and puts
physics back as saved: a trajectory sent while one plays saves "off", so physics stays off after it, as in
Gazebo (a warning says so). Not as upstream: a point with fewer positions than joint_names is refused with an
error (upstream reads past its end); a deleted plugin puts physics back (upstream leaves the world frozen).
"""
import collections

from racebot_sim_bridge.engine.sim_time import to_ns
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities

WORLD_FRAMES = ('world', '/map', 'map')

Trajectory = collections.namedtuple('Trajectory', 'model reference joints points')  # points: [(positions, ns)]


class JointPoseTrajectory(ModelPlugin):
    libraries = ('libgazebo_ros_joint_pose_trajectory.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        for tag in ('serviceName', 'updateRate'):
            if p.has(tag):
                self.info('<%s> is not used, as upstream (no service; every world update)' % tag)
        self.entities = WorldEntities(self.world)
        self.model = robot.name  # upstream's model_: replaced by a reference link's model
        self.pending = collections.deque()  # messages from rospy's threads, taken at the next update
        self.trajectory = None
        self.index = 0
        self.start_ns = 0
        self.saved_physics = None  # what physics was when this plugin turned it off; None: not turned off
        self.left_off = False  # a trajectory ended with physics off (the saved "off" of a second trajectory)
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        topic = p.string('topicName', 'set_joint_trajectory')
        if topic:
            from trajectory_msgs.msg import JointTrajectory
            self.subscriber(name_in(ns, topic), JointTrajectory, self.pending.append, queue_size=100)

    def error(self, message):
        self.ctx.rospy.logerr('%s: %s' % (self.label, message))

    def before_physics(self, time):
        now = to_ns(time)
        while self.pending:
            self._take(self.pending.popleft(), now)
        if self.trajectory is None or now < self.start_ns:
            return
        if self.index < len(self.trajectory.points):
            positions, duration = self.trajectory.points[self.index]
            self.info('time [%f] updating configuration [%d/%d]' % (time, self.index, len(self.trajectory.points)))
            self._set(positions)
            self.start_ns += duration
            self.index += 1
            return
        self.trajectory = None  # the update after the last point
        self._restore_physics()

    def _take(self, msg, now):
        frame = msg.header.frame_id
        model, reference = self.model, None
        if frame not in WORLD_FRAMES:
            entity = self.entities.find_link(frame)
            if entity is None:
                self.error('ros_joint_trajectory plugin needs a reference link [%s] as frame_id, aborting.' % frame)
                return
            model, reference = entity.model, entity.link
        count = len(msg.joint_names)
        short = [i for i, point in enumerate(msg.points) if len(point.positions) < count]
        if short:
            self.error('point %d has %d positions for %d joint_names: trajectory refused (upstream reads past the '
                       'end)' % (short[0], len(msg.points[short[0]].positions), count))
            return
        self.model = model
        body = self.world.bodies.get(model)
        joints = [body.joints.get(name) if body is not None else None for name in msg.joint_names]
        points = [(list(point.positions[:count]), point.time_from_start.to_nsec()) for point in msg.points]
        self.trajectory = Trajectory(model, reference, joints, points)
        self.index = 0
        self.start_ns = max(msg.header.stamp.to_nsec(), now)
        if self.saved_physics is not None and not self.ctx.sim.physics_enabled:
            self.warn('a trajectory came while one plays with physics off: as in Gazebo, physics stays off after '
                      'it ends (upstream saves "off" now); send a trajectory after the last one ended')
        self.saved_physics = self.ctx.sim.physics_enabled
        self.ctx.sim.physics_enabled = False

    def _set(self, positions):
        body = self.world.bodies.get(self.trajectory.model)
        if body is None:  # the model was deleted
            return
        reference = self.trajectory.reference
        before = self.entities.link_state(body, reference)[0] if reference is not None else None
        for joint, position in zip(self.trajectory.joints, positions):
            if joint is not None:  # SetPosition(0, p, preserveWorldVelocity): the joint's rate is kept
                joint.set_position(position, joint.state().velocity)
        if reference is not None and body.link_index.get(reference, -1) >= 0:
            # Model::SetLinkWorldPose: the model moved rigidly so that the reference link is back where it was
            after = self.entities.link_state(body, reference)[0]
            root = frames.in_world(before, frames.relative_to(after, body.frame_pose()))
            com = body.com_pose_for_frame(*root)
            linear, angular = body.twist()
            body.set_pose(com.position, com.orientation, linear, angular)

    def _restore_physics(self):
        if self.saved_physics is not None:
            self.ctx.sim.physics_enabled = self.saved_physics
            self.left_off = not self.saved_physics
            self.saved_physics = None

    def close(self):
        if self.saved_physics is not None or self.left_off:  # off by this plugin: on again (upstream: left off)
            self.ctx.sim.physics_enabled = True
            self.saved_physics = None
        super().close()
