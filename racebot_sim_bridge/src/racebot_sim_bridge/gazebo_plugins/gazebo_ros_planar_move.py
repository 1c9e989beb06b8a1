"""libgazebo_ros_planar_move.so (gazebo_plugins noetic-devel): a holonomic base moved by its velocity.

Parameters (upstream's defaults): commandTopic cmd_vel, odometryTopic odom, odometryFrame odom,
robotBaseFrame base_footprint, odometryRate 20 (<= 0: no odometry and no TF), cmdTimeout -1 (< 0:
a command lasts until the next; else zeroed when older than this many seconds of sim time),
robotNamespace.

Every world update, before the physics step, the model gets cmd_vel's linear.x, linear.y (the robot's
axes, turned into the world's by its yaw) as its linear velocity with z = 0, and angular.z as its
angular velocity with roll and pitch rates 0. At odometryRate: nav_msgs/Odometry (pose: the model's
world x, y, orientation, z left 0; twist: finite differences of the pose since the last publication,
in the robot's axes; fixed covariances 1e-5, 1e-5, 1e-3) and the odom -> base TF, stamped with sim time.
"""
from racebot_sim_bridge.kinematics.planar import covariance, finite_difference_twist, model_velocity
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import yaw_of
from racebot_sim_bridge.engine.sim_time import to_ns
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve, transform
from racebot_sim_bridge.gazebo_plugins.update_timing import SincePublished

COVARIANCE = covariance(0.00001, 0.00001, 0.001)


class PlanarMove(ModelPlugin):
    libraries = ('libgazebo_ros_planar_move.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.odometry_rate = p.number('odometryRate', 20.0)
        self.cmd_timeout = p.number('cmdTimeout', -1.0)
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        prefix = tf_prefix(ctx.rospy, ns)
        self.odom_frame = tf_resolve(prefix, p.string('odometryFrame', 'odom'))
        self.base_frame = tf_resolve(prefix, p.string('robotBaseFrame', 'base_footprint'))
        self.command = (0.0, 0.0, 0.0)  # (linear.x, linear.y, angular.z)
        self.command_time = None  # sim time (ns) the command arrived, for cmdTimeout
        self.clock = SincePublished(self.odometry_rate, ctx.sim.time)
        self.last_pose = self._pose()
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        self.odom_pub = self.publisher(name_in(ns, p.string('odometryTopic', 'odom')), Odometry)
        self.tf_pub = ctx.tf_publisher()
        self.subscriber(name_in(ns, p.string('commandTopic', 'cmd_vel')), Twist, self._on_cmd_vel)

    def _on_cmd_vel(self, msg):
        # one assignment: the physics thread sees the old pair or the new one, never half of each
        self.command, self.command_time = ((msg.linear.x, msg.linear.y, msg.angular.z),
                                           to_ns(self.ctx.sim.time))

    def _pose(self):
        frame = self.robot.body.frame_pose()
        return frame.position, frame.orientation

    def before_physics(self, time):
        command = self.command
        if self.cmd_timeout >= 0 and (self.command_time is None
                                      or (to_ns(time) - self.command_time) / 1e9 > self.cmd_timeout):
            command = self.command = (0.0, 0.0, 0.0)
        position, orientation = self._pose()
        linear, angular = model_velocity(command, yaw_of(orientation))
        self.robot.body.set_velocity(linear, angular)
        if self.odometry_rate > 0:
            due, since = self.clock.due(time)
            if due:
                self._publish_odometry(time, since, position, orientation, command[2])

    def _publish_odometry(self, time, dt, position, orientation, commanded_wz):
        (x0, y0, _), q0 = self.last_pose
        twist = finite_difference_twist((x0, y0, yaw_of(q0)), (position[0], position[1], yaw_of(orientation)),
                                        dt, commanded_wz)
        self.last_pose = (position, orientation)
        stamp = self.stamp(time)
        self.tf_pub.publish(transform(stamp, self.odom_frame, self.base_frame, position, orientation))
        self.odom_pub.publish(odometry(stamp, self.odom_frame, self.base_frame, (position[0], position[1], 0.0),
                                       orientation, (twist[0], twist[1], 0.0), (0.0, 0.0, twist[2]),
                                       COVARIANCE, (0.0,) * 36))
