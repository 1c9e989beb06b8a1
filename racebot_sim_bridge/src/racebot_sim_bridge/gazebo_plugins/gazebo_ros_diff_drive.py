"""libgazebo_ros_diff_drive.so (gazebo_plugins noetic-devel): two wheels driven from cmd_vel, odometry out.

Parameters (upstream's names and defaults): commandTopic cmd_vel, odometryTopic odom, odometryFrame odom,
robotBaseFrame base_footprint, leftJoint left_joint, rightJoint right_joint, wheelSeparation 0.34,
wheelDiameter 0.15, wheelAcceleration 0 (m/s^2 at the rim, 0: no limit), wheelTorque 5 (each wheel's
velocity motor's maximum torque), updateRate 100 (<= 0: every world update), odometrySource world
(world | encoder), publishTf true (false: no odometry at all, as upstream), publishOdomTF true,
publishWheelTF false, publishWheelJointState false, rosDebugLevel, robotNamespace (GazeboRos's rule:
none or empty -> the model's name). legacyMode is not read by noetic's plugin (it swapped the wheels
in kinetic): a warning says so when it is true.

Every world update (before the physics step), with encoder odometry the wheel joint velocities are
integrated (kinematics.differential.EncoderOdometry). When more than one update period has passed (the
last update time then moves on by exactly one period): odometry and the odom -> base TF, wheel TFs
(each wheel link's pose relative to the model, from its joint's parent link), wheel joint states
(right then left, positions only), each only while subscribed (rospy sends nothing without a subscriber),
then the wheels' target speeds from the latest cmd_vel, through the acceleration ramp. Stamps are the
sim time; frames go under the tf_prefix parameter found
upwards from the plugin's namespace (tf::resolve).
"""
import functools
import math

from racebot_sim_bridge.kinematics import differential as kin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import yaw_of
from racebot_sim_bridge.engine.sim_time import NS, to_ns
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_utils import GazeboRosPlugin
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion, model_relative_pose
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve, transform
from racebot_sim_bridge.gazebo_plugins.update_timing import FixedPeriod

# GazeboRos logs every parameter left out, with the default it takes (ROS_WARN upstream; one info line here)
DEFAULTS = (('commandTopic', 'cmd_vel'), ('odometryTopic', 'odom'), ('odometryFrame', 'odom'),
            ('robotBaseFrame', 'base_footprint'), ('publishWheelTF', 'false'), ('publishOdomTF', 'true'),
            ('publishWheelJointState', 'false'), ('wheelSeparation', '0.34'), ('wheelDiameter', '0.15'),
            ('wheelAcceleration', '0'), ('wheelTorque', '5'), ('updateRate', '100'), ('odometrySource', 'world'),
            ('publishTf', 'true'))
ZERO_COVARIANCE = [0.0] * 36


class DiffDrive(GazeboRosPlugin):
    libraries = ('libgazebo_ros_diff_drive.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec, DEFAULTS)
        p = self.params
        self.right = self.named_joint('rightJoint', 'right_joint', 'right wheel')
        self.left = self.named_joint('leftJoint', 'left_joint', 'left wheel')
        self.indices = [self.left.index, self.right.index]
        # both wheels' PyBullet joint states, read at every world update: one bound call (physics.joint_states_raw)
        self._read_wheels = functools.partial(self.world.client.getJointStates, robot.body.id, self.indices)
        self.separation = p.number('wheelSeparation', 0.34, minimum=0, exclusive=True)
        self.diameter = p.number('wheelDiameter', 0.15, minimum=0, exclusive=True)
        self.acceleration = p.number('wheelAcceleration', 0.0, minimum=0)
        self.torque = p.number('wheelTorque', 5.0, minimum=0)
        self.rate = p.number('updateRate', 100.0)
        self.clock = FixedPeriod(self.rate, ctx.sim.time)
        self.encoder = self.odometry_source() == 'encoder'
        self.publish_odometry = p.boolean('publishTf', True)
        self.publish_odom_tf = p.boolean('publishOdomTF', True)
        self.publish_wheel_tf = p.boolean('publishWheelTF', False)
        self.publish_joint_state = p.boolean('publishWheelJointState', False)
        if p.has('legacyMode') and p.string('legacyMode', '').strip().lower() in ('true', '1'):
            self.warn('<legacyMode>true</legacyMode> is not read: gazebo_plugins noetic removed it (2.8.3), so the '
                      'wheels turn as legacyMode false (REP 103: y to the left); if this robot was written for the '
                      'old swap, exchange <leftJoint> and <rightJoint>')
        ns = model_plugin_namespace('gazebo_ros', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        prefix = tf_prefix(ctx.rospy, ns)
        self.odom_frame = tf_resolve(prefix, p.string('odometryFrame', 'odom'))
        self.base_frame = tf_resolve(prefix, p.string('robotBaseFrame', 'base_footprint'))
        model = robot.model
        # Gazebo's joint parent is the link its URDF parent was lumped into; a moving joint's child is kept
        self.wheel_frames = [(tf_resolve(prefix, model.lumped_link(model.joints[j.name].parent)),
                              tf_resolve(prefix, j.child_link), j.child_link) for j in (self.right, self.left)]
        self.command = (0.0, 0.0)  # cmd_vel's (linear.x, angular.z), replaced whole by the callback
        self.commanded = (0.0, 0.0)  # the ramp's commanded rim speeds (upstream's wheel_speed_instr_)
        # UpdateOdometryEncoder, at every world update whatever the update rate (compiled where built)
        self.odometer = kin.EncoderOdometry(self._read_wheels, self.diameter, self.separation)
        if self.encoder:
            self.every_update = self.odometer.update
        self._driven = None  # the wheels' motor targets last sent
        self._drive([0.0, 0.0])  # SetParam fmax
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState
        self.joint_state_class = JointState
        self.joint_state_pub = (self.publisher(name_in(ns, 'joint_states'), JointState, queue_size=1000)
                                if self.publish_joint_state else None)
        self.tf_pub = ctx.tf_publisher()  # upstream's TransformBroadcaster exists whatever is asked
        self.subscriber(name_in(ns, p.string('commandTopic', 'cmd_vel')), Twist, self._on_cmd_vel)
        self.odom_pub = (self.publisher(name_in(ns, p.string('odometryTopic', 'odom')), Odometry)
                         if self.publish_odometry else None)

    # -- ROS and life cycle ----------------------------------------------------------------------
    def _on_cmd_vel(self, msg):
        self.command = (msg.linear.x, msg.angular.z)

    def reset(self):
        """Upstream's Reset: the update clock restarts now, encoder odometry and the command go to zero,
        the wheels' maximum torque is set again. Their target speed goes to zero too (PyBullet's motor would
        keep the old one until the next update, spinning the wheels of a robot just put back at rest)."""
        self.clock = FixedPeriod(self.rate, self.ctx.sim.time)
        self.odometer.x = self.odometer.y = self.odometer.theta = 0.0
        self.command = (0.0, 0.0)
        self._driven = None
        self._drive([0.0, 0.0])

    @property
    def encoder_pose(self):
        return self.odometer.x, self.odometer.y, self.odometer.theta

    @property
    def encoder_twist(self):
        return self.odometer.v, self.odometer.w

    def quiet_span(self):
        return self.clock.quiet_span()

    def before_physics(self, time):
        now = to_ns(time)
        clock = self.clock
        if 0 <= now - clock.last < clock.quiet_ns:  # clock.quiet(now), inline: most updates stop here
            return
        since = (now - clock.last) / float(NS)  # before due() moves the clock on
        if not clock.due(time):
            return
        odometer = self.odometer
        states = odometer.wheels if odometer.wheels_ns == now else self._read_wheels()  # read this update?
        velocities = (states[0][1], states[1][1])  # left, right (rad/s)
        # Only what somebody subscribes to is worked out: rospy sends nothing (and counts no seq) without a
        # subscriber, so what a subscriber gets is the same.
        tf_heard = self.tf_pub.get_num_connections() > 0
        odom_heard = self.odom_pub is not None and (self.odom_pub.get_num_connections() > 0
                                                    or (self.publish_odom_tf and tf_heard))
        joints_heard = self.joint_state_pub is not None and self.joint_state_pub.get_num_connections() > 0
        if odom_heard or (self.publish_wheel_tf and tf_heard) or joints_heard:
            stamp = self.stamp(time)
            if odom_heard:
                self._publish_odometry(stamp, self.publish_odom_tf and tf_heard)
            if self.publish_wheel_tf and tf_heard:
                self._publish_wheel_tf(stamp)
            if joints_heard:
                self._publish_joint_state(stamp, states)
        targets = kin.wheel_speeds(self.command[0], self.command[1], self.separation)
        measured = tuple(kin.rim_speed(v, self.diameter) for v in velocities)
        speeds, self.commanded = kin.ramped_speeds(targets, measured, self.commanded, self.acceleration, since)
        self._drive([kin.joint_velocity(s, self.diameter) for s in speeds])

    def _drive(self, velocities):
        """The wheels' velocity motors (SetParam fmax and vel); PyBullet keeps a motor's target, so the same again
        (a robot cruising: every update) is not sent."""
        if velocities != self._driven:
            self.robot.body.drive_velocities(self.indices, velocities, [self.torque] * 2)
            self._driven = velocities

    # -- outputs --------------------------------------------------------------------------------
    def _publish_odometry(self, stamp, send_tf):
        if self.encoder:
            x, y, theta = self.encoder_pose
            position, orientation = (x, y, 0.0), kin.yaw_quaternion(theta)
            v, w = self.encoder_twist
            linear, angular = (v, 0.0, 0.0), (0.0, 0.0, w)
        else:
            position, orientation, world_linear, world_angular = link_motion(self.world, self.robot.body,
                                                                             self.robot.model.root_link)
            yaw = yaw_of(orientation)
            vx, vy = world_linear[0], world_linear[1]
            c, s = math.cos(yaw), math.sin(yaw)
            linear, angular = (c * vx + s * vy, c * vy - s * vx, 0.0), (0.0, 0.0, world_angular[2])
        if send_tf:
            self.tf_pub.publish(transform(stamp, self.odom_frame, self.base_frame, position, orientation))
        self.odom_pub.publish(odometry(stamp, self.odom_frame, self.base_frame, position, orientation, linear,
                                       angular, kin.pose_covariance(), ZERO_COVARIANCE))

    def _publish_wheel_tf(self, stamp):
        for parent_frame, child_frame, link in self.wheel_frames:
            relative, turn = model_relative_pose(self.world, self.robot.body, self.robot.model.root_link, link)
            self.tf_pub.publish(transform(stamp, parent_frame, child_frame, relative, turn))

    def _publish_joint_state(self, stamp, states):
        msg = self.joint_state_class(name=[self.right.name, self.left.name],
                                     position=[states[1][0], states[0][0]])
        msg.header.stamp = stamp
        self.joint_state_pub.publish(msg)
