"""libgazebo_ros_skid_steer_drive.so (gazebo_plugins noetic-devel): four wheels, driven side by side.

Parameters (upstream's defaults): leftFrontJoint left_front_joint, rightFrontJoint right_front_joint,
leftRearJoint left_rear_joint, rightRearJoint right_rear_joint, wheelSeparation 0.4, wheelDiameter 0.15,
torque 5 (each wheel's velocity motor's maximum torque), commandTopic cmd_vel, odometryTopic odom,
odometryFrame odom, robotBaseFrame base_footprint, broadcastTF false, updateRate 100 (<= 0: every
world update), covariance_x 0.0001, covariance_y 0.0001, covariance_yaw 0.01, robotNamespace.

Every update period the plugin publishes odometry and then sets each wheel's target speed from the
latest cmd_vel (linear.x, angular.z). The odometry is the model's true world pose (not the wheels'),
stamped with the sim time: pose x, y and orientation (z left 0), twist x, y in the robot's axes from
the model's world velocity and the world yaw rate; odom -> base TF (with z) when broadcastTF is true.
Frames are resolved with the tf_prefix parameter as tf::resolve does.
"""
from racebot_sim_bridge.kinematics import skid_steer
from racebot_sim_bridge.kinematics.planar import covariance, world_to_base
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import yaw_of
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve, transform
from racebot_sim_bridge.gazebo_plugins.update_timing import FixedPeriod

WHEELS = (('leftFrontJoint', 'left_front_joint', 'left front'),
          ('rightFrontJoint', 'right_front_joint', 'right front'),
          ('leftRearJoint', 'left_rear_joint', 'left rear'),
          ('rightRearJoint', 'right_rear_joint', 'right rear'))  # in kinematics.skid_steer's order


class SkidSteerDrive(ModelPlugin):
    libraries = ('libgazebo_ros_skid_steer_drive.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.joints = [self._wheel(tag, default, what) for tag, default, what in WHEELS]
        self.indices = [j.index for j in self.joints]
        self.separation = p.number('wheelSeparation', 0.4, minimum=0, exclusive=True)
        self.diameter = p.number('wheelDiameter', 0.15, minimum=0, exclusive=True)
        self.torque = p.number('torque', 5.0, minimum=0)
        self.broadcast_tf = p.boolean('broadcastTF', False)
        rate = p.number('updateRate', 100.0)
        self.cov = covariance(p.number('covariance_x', 0.0001, minimum=0), p.number('covariance_y', 0.0001, minimum=0),
                              p.number('covariance_yaw', 0.01, minimum=0))
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        prefix = tf_prefix(ctx.rospy, ns)
        self.odom_frame = tf_resolve(prefix, p.string('odometryFrame', 'odom'))
        self.base_frame = tf_resolve(prefix, p.string('robotBaseFrame', 'base_footprint'))
        self.command = (0.0, 0.0)  # cmd_vel's (linear.x, angular.z), replaced whole by the callback
        self.clock = FixedPeriod(rate, ctx.sim.time)
        # Load: each wheel's motor gets its maximum torque (SetParam "fmax"), target speed 0 until an update
        robot.body.drive_velocities(self.indices, [0.0] * 4, [self.torque] * 4)
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        self.odom_pub = self.publisher(name_in(ns, p.string('odometryTopic', 'odom')), Odometry)
        self.tf_pub = ctx.tf_publisher() if self.broadcast_tf else None
        self.subscriber(name_in(ns, p.string('commandTopic', 'cmd_vel')), Twist, self._on_cmd_vel)

    def _wheel(self, tag, default, what):
        if self.params.has(tag):
            return self.joint(tag)
        joint = self.robot.body.joints.get(default)
        if joint is None:
            raise PluginError("<%s> is missing and the default %s wheel joint '%s' is not a movable joint of the "
                              "robot: name its %s wheel's joint (its joints: %s)"
                              % (tag, what, default, what, ', '.join(sorted(self.robot.body.joints)) or 'none'))
        return joint

    def _on_cmd_vel(self, msg):
        self.command = (msg.linear.x, msg.angular.z)

    def before_physics(self, time):
        if not self.clock.due(time):
            return
        self._publish_odometry(time)
        vx, wz = self.command
        speeds = skid_steer.wheel_velocities(vx, wz, self.separation, self.diameter)
        self.robot.body.drive_velocities(self.indices, list(speeds), [self.torque] * 4)

    def _publish_odometry(self, time):
        body = self.robot.body
        position, orientation, linear, angular = link_motion(self.world, body, self.robot.model.root_link)
        stamp = self.stamp(time)
        if self.tf_pub is not None:
            self.tf_pub.publish(transform(stamp, self.odom_frame, self.base_frame, position, orientation))
        vx, vy = world_to_base(linear[0], linear[1], yaw_of(orientation))
        self.odom_pub.publish(odometry(stamp, self.odom_frame, self.base_frame, (position[0], position[1], 0.0),
                                       orientation, (vx, vy, 0.0), (0.0, 0.0, angular[2]), self.cov, self.cov))
