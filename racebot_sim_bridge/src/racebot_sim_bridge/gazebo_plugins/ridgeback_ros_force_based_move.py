"""libridgeback_ros_force_based_move.so (ridgeback_simulator's ridgeback_gazebo_plugins): a holonomic base pushed
towards its commanded velocity by forces, its wheels frictionless (ridgeback.gazebo sets mu 0 on them).

Parameters (upstream's defaults): robotNamespace (''), commandTopic cmd_vel, odometryTopic odom, odometryFrame odom,
robotBaseFrame base_footprint (the link pushed), odometryRate 20 (<= 0: none), cmdVelTimeOut 0.25 s of sim time,
publishOdometryTf true, yaw_velocity_p_gain 100, x_velocity_p_gain 10000, y_velocity_p_gain 10000.

Every world update: the force ((x - vx) kx, (y - vy) ky, 0) in the link's axes at its centre of mass and the torque
(0, 0, (wz_cmd - wz) kyaw) in world axes, with vx, vy the model's velocity in its own axes and wz its world yaw
rate (Link::AddRelativeForce, AddTorque). At odometryRate (strictly more than 1/rate since the last): odometry
integrated from the model's forward speed and yaw rate alone, as upstream (its sideways motion is not in it), with
upstream's fixed covariances, and the odom -> base TF when publishOdometryTf.
"""
from __future__ import annotations

import math

from racebot_sim_bridge.engine.sim_time import to_ns
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve, transform
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.update_timing import SincePublished
from racebot_sim_bridge.kinematics.rotations import rotate, rotate_back

BIG = 1000000000000.0


def force_and_torque(command, relative_linear, world_yaw_rate, gains):
    """(force in the link's axes, torque in world axes) pushing towards `command` (x, y, yaw rate)."""
    (x, y, rot), (kx, ky, kyaw) = command, gains
    force = ((x - relative_linear[0]) * kx, (y - relative_linear[1]) * ky, 0.0)
    return force, (0.0, 0.0, (rot - world_yaw_rate) * kyaw)


def motion(pose, linear_x, angular_z, seconds):
    """(x, y, yaw) after driving `linear_x` along the heading and turning at `angular_z` for `seconds` from `pose`:
    getTransformForMotion composed onto the odometry transform (a straight line below 1e-4 rad/s, else an arc)."""
    x, y, yaw = pose
    if abs(angular_z) < 0.0001:
        dx, dy, dyaw = linear_x * seconds, 0.0, 0.0
    else:
        dist, angle = linear_x * seconds, angular_z * seconds
        radius = dist / angle
        dx, dy, dyaw = math.sin(angle) * radius, radius - math.cos(angle) * radius, angle
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * dx - s * dy, y + s * dx + c * dy, yaw + dyaw


def covariances(yaw_rate):
    yaw_var = 0.01 if abs(yaw_rate) < 0.0001 else 100.0
    pose = [0.0] * 36
    twist = [0.0] * 36
    for i, v in enumerate((0.001, 0.001, BIG, BIG, BIG, yaw_var)):
        pose[i * 7] = v
    for i, v in enumerate((0.001, 0.001, 0.001, BIG, BIG, yaw_var)):
        twist[i * 7] = v
    return pose, twist


class RidgebackForceBasedMove(ModelPlugin):
    libraries = ('libridgeback_ros_force_based_move.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.gains = (p.number('x_velocity_p_gain', 10000.0), p.number('y_velocity_p_gain', 10000.0),
                      p.number('yaw_velocity_p_gain', 100.0))
        base = p.string('robotBaseFrame', 'base_footprint')
        self.link_name = self.link_param('robotBaseFrame', 'the link the forces push', name=base)
        self.index = robot.body.link_index[self.link_name]
        self.odometry_rate = p.number('odometryRate', 20.0)
        self.timeout = p.number('cmdVelTimeOut', 0.25)
        self.publish_tf = p.boolean('publishOdometryTf', True)
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        prefix = tf_prefix(ctx.rospy, ns)
        self.odom_frame = tf_resolve(prefix, p.string('odometryFrame', 'odom'))
        self.base_frame = tf_resolve(prefix, base)
        self.command = ((0.0, 0.0, 0.0), None)  # ((x, y, yaw rate), sim time in ns it arrived): swapped whole
        self.clock = SincePublished(self.odometry_rate, ctx.sim.time)
        self.odom_pose = (0.0, 0.0, 0.0)
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        self.odom_pub = self.publisher(name_in(ns, p.string('odometryTopic', 'odom')), Odometry)
        self.tf_pub = ctx.tf_publisher() if self.publish_tf else None
        self.subscriber(name_in(ns, p.string('commandTopic', 'cmd_vel')), Twist, self._on_cmd_vel)

    def _on_cmd_vel(self, msg):
        self.command = ((msg.linear.x, msg.linear.y, msg.angular.z), to_ns(self.ctx.sim.time))

    def _velocities(self):
        """(the model's linear velocity in its own axes, its angular velocity in its own axes, in world axes)."""
        body = self.robot.body
        frame = body.frame_pose()
        twist = body.twist()
        return (rotate_back(frame.orientation, twist.linear), rotate_back(frame.orientation, twist.angular),
                twist.angular)

    def before_physics(self, time):
        command, stamp = self.command
        if stamp is None or (to_ns(time) - stamp) / 1e9 > self.timeout:
            command = (0.0, 0.0, 0.0)
        relative_linear, relative_angular, world_angular = self._velocities()
        force, torque = force_and_torque(command, relative_linear, world_angular[2], self.gains)
        link = self.robot.body.links[self.link_name]
        pose, _ = link.state()
        link.apply_wrench(rotate(pose.orientation, force), torque)
        if self.odometry_rate > 0:
            due, since = self.clock.due(time)
            if due:
                self._publish_odometry(time, since, relative_linear[0], relative_angular[2])

    def _publish_odometry(self, time, seconds, linear_x, yaw_rate):
        self.odom_pose = x, y, yaw = motion(self.odom_pose, linear_x, yaw_rate, seconds)
        orientation = (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))
        stamp = self.stamp(time)
        if self.tf_pub is not None:
            self.tf_pub.publish(transform(stamp, self.odom_frame, self.base_frame, (x, y, 0.0), orientation))
        pose_cov, twist_cov = covariances(yaw_rate)
        self.odom_pub.publish(odometry(stamp, self.odom_frame, self.base_frame, (x, y, 0.0), orientation,
                                       (linear_x, 0.0, 0.0), (0.0, 0.0, yaw_rate), pose_cov, twist_cov))
