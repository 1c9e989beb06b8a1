"""libgazebo_ros_tricycle_drive.so (gazebo_plugins noetic-devel): a steered, driven front wheel from cmd_vel, two
passive encoder wheels, odometry out.

Parameters (upstream's names and defaults): commandTopic cmd_vel, odometryTopic odom, odometryFrame odom,
robotBaseFrame base_link, steeringJoint front_steering_joint, actuatedWheelJoint front_wheel_joint,
encoderWheelLeftJoint left_wheel_joint, encoderWheelRightJoint right_wheel_joint, actuatedWheelDiameter 0.15,
encoderWheelDiameter 0.15, encoderWheelSeparation 0.5, wheelTorque 5 (the actuated wheel's and the steering
joint's motor force limit), wheelAcceleration 0 (rad/s^2, 0: no ramp), wheelDeceleration (= wheelAcceleration),
wheelSpeedTolerance 0.01, steeringSpeed 0 (0: the steering joint is set to the angle, kinematically; > 0: driven
at that speed), steeringAngleTolerance 0.01, updateRate 100 (<= 0: every world update), odometrySource world
(world | encoder), publishWheelTF false, publishWheelJointState false, rosDebugLevel, robotNamespace (GazeboRos:
none or empty -> the model's name).

cmd_vel's linear.x / (actuatedWheelDiameter / 2) is the driven wheel's target speed and its angular.z the
steering ANGLE (kinematics/tricycle.py has upstream's arithmetic and quirks). Every world update (before the
step) with encoder odometry the encoder wheels are integrated; when more than one period has passed (the last
update time then moves on by exactly one period): odometry (always: no switch upstream) with the odom -> base TF,
wheel TFs (child frame: the JOINT's name, parent: its parent link, pose: the child link in the model frame, as
upstream), joint states (steering, actuated, left, right: position, velocity, effort), then the motors.
Upstream has no Reset: a reset keeps the command, the encoder pose and the clock.
"""
from racebot_sim_bridge.engine.sim_time import NS, to_ns
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_utils import GazeboRosPlugin
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion, model_relative_pose
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve, transform
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.update_timing import FixedPeriod
from racebot_sim_bridge.kinematics import differential, tricycle
from racebot_sim_bridge.kinematics.rotations import rotate_back, yaw_of

DEFAULTS = (('actuatedWheelDiameter', '0.15'), ('encoderWheelDiameter', '0.15'), ('wheelTorque', '5'),
            ('commandTopic', 'cmd_vel'), ('odometryTopic', 'odom'), ('odometryFrame', 'odom'),
            ('robotBaseFrame', 'base_link'), ('updateRate', '100'), ('wheelAcceleration', '0'),
            ('wheelDeceleration', 'wheelAcceleration'), ('wheelSpeedTolerance', '0.01'), ('steeringSpeed', '0'),
            ('steeringAngleTolerance', '0.01'), ('encoderWheelSeparation', '0.5'), ('publishWheelTF', 'false'),
            ('publishWheelJointState', 'false'), ('steeringJoint', 'front_steering_joint'),
            ('actuatedWheelJoint', 'front_wheel_joint'), ('encoderWheelLeftJoint', 'left_wheel_joint'),
            ('encoderWheelRightJoint', 'right_wheel_joint'), ('odometrySource', 'world'))
ZERO_COVARIANCE = [0.0] * 36


class TricycleDrive(GazeboRosPlugin):
    libraries = ('libgazebo_ros_tricycle_drive.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec, DEFAULTS)
        p = self.params
        self.actuated_diameter = p.number('actuatedWheelDiameter', 0.15, minimum=0, exclusive=True)
        self.encoder_diameter = p.number('encoderWheelDiameter', 0.15, minimum=0, exclusive=True)
        self.torque = p.number('wheelTorque', 5.0, minimum=0)
        self.acceleration = p.number('wheelAcceleration', 0.0)
        self.deceleration = p.number('wheelDeceleration', self.acceleration)
        self.speed_tolerance = p.number('wheelSpeedTolerance', 0.01)
        self.steering_speed = p.number('steeringSpeed', 0.0)
        self.angle_tolerance = p.number('steeringAngleTolerance', 0.01)
        self.separation = p.number('encoderWheelSeparation', 0.5, minimum=0, exclusive=True)
        self.publish_wheel_tf = p.boolean('publishWheelTF', False)
        self.publish_joint_state = p.boolean('publishWheelJointState', False)
        self.steering = self.named_joint('steeringJoint', 'front_steering_joint', 'steering')
        self.actuated = self.named_joint('actuatedWheelJoint', 'front_wheel_joint', 'actuated wheel')
        self.left = self.named_joint('encoderWheelLeftJoint', 'left_wheel_joint', 'left encoder wheel')
        self.right = self.named_joint('encoderWheelRightJoint', 'right_wheel_joint', 'right encoder wheel')
        self.joints = (self.steering, self.actuated, self.left, self.right)  # upstream's joint state order
        self.indices = [j.index for j in self.joints]
        self.encoder = self.odometry_source() == 'encoder'
        self.clock = FixedPeriod(p.number('updateRate', 100.0), ctx.sim.time)
        ns = model_plugin_namespace('gazebo_ros', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        prefix = tf_prefix(ctx.rospy, ns)
        self.odom_frame = tf_resolve(prefix, p.string('odometryFrame', 'odom'))
        self.base_frame = tf_resolve(prefix, p.string('robotBaseFrame', 'base_link'))
        model = robot.model
        # wheel TFs: (parent link as Gazebo has it, the joint's name, the child link whose pose is sent)
        self.wheel_frames = [(tf_resolve(prefix, model.lumped_link(model.joints[j.name].parent)),
                              tf_resolve(prefix, j.name), j.child_link) for j in self.joints]
        self.command = (0.0, 0.0)  # cmd_vel's (linear.x, angular.z), replaced whole by the callback
        self.encoder_pose = (0.0, 0.0, 0.0)
        self.encoder_twist = (0.0, 0.0, 0.0)
        self.last_encoder_ns = 0  # upstream's last_odom_update_ starts at time 0
        # Load: SetParam("fmax", wheelTorque) on the actuated wheel and the steering joint, their speed 0
        robot.body.drive_velocities(self.indices[:2], [0.0, 0.0], [self.torque] * 2)
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState
        self.joint_state_class = JointState
        self.joint_state_pub = (self.publisher(name_in(ns, 'joint_states'), JointState, queue_size=1000)
                                if self.publish_joint_state else None)
        self.tf_pub = ctx.tf_publisher()
        self.subscriber(name_in(ns, p.string('commandTopic', 'cmd_vel')), Twist, self._on_cmd_vel)
        self.odom_pub = self.publisher(name_in(ns, p.string('odometryTopic', 'odom')), Odometry)

    def _on_cmd_vel(self, msg):
        self.command = (msg.linear.x, msg.angular.z)

    def before_physics(self, time):
        now = to_ns(time)
        if self.encoder:
            left, right = self.robot.body.joint_states_raw(self.indices[2:])
            dt = (now - self.last_encoder_ns) / float(NS)
            self.last_encoder_ns = now
            if dt > 0:
                self.encoder_pose, self.encoder_twist = tricycle.encoder_step(
                    self.encoder_pose, left[1], right[1], self.encoder_diameter, self.separation, dt)
        since = (now - self.clock.last) / float(NS)  # before due() moves the clock on
        if not self.clock.due(time):
            return
        stamp = self.stamp(time)
        states = self.robot.body.joint_states_raw(self.indices)
        self._publish_odometry(stamp)
        if self.publish_wheel_tf:
            for parent_frame, child_frame, link in self.wheel_frames:
                position, orientation = model_relative_pose(self.world, self.robot.body, self.robot.model.root_link,
                                                            link)
                self.tf_pub.publish(transform(stamp, parent_frame, child_frame, position, orientation))
        if self.joint_state_pub is not None:
            # effort: Joint::GetForce, the force set with SetForce, which nothing sets here (motors do not count)
            msg = self.joint_state_class(name=[j.name for j in self.joints], position=[s[0] for s in states],
                                         velocity=[s[1] for s in states], effort=[0.0] * 4)
            msg.header.stamp = stamp
            self.joint_state_pub.publish(msg)
        self._motors(states, since)

    def _motors(self, states, dt):
        target_speed = self.command[0] / (self.actuated_diameter / 2.0)
        speed = tricycle.wheel_speed(target_speed, states[1][1], self.acceleration, self.deceleration,
                                     self.speed_tolerance, dt)
        body = self.robot.body
        body.drive_velocities([self.indices[1]], [speed], [self.torque])
        mode, value = tricycle.steering(self.command[1], states[0][0], target_speed, self.steering_speed,
                                        self.angle_tolerance, dt)
        if mode == 'velocity':
            body.drive_velocities([self.indices[0]], [value], [self.torque])
        else:  # SetPosition(0, angle, preserveWorldVelocity): the joint's rate is kept; its motor holds it there
            self.steering.set_position(value, states[0][1])

    def _publish_odometry(self, stamp):
        if self.encoder:
            x, y, theta = self.encoder_pose
            position, orientation = (x, y, 0.0), differential.yaw_quaternion(theta)
            vx, vy, w = self.encoder_twist
            linear, angular = (vx, vy, 0.0), (0.0, 0.0, w)
        else:  # the model's pose (all of it: z, roll, pitch too) and its velocity in the base's yaw-only axes
            position, orientation, world_linear, world_angular = link_motion(self.world, self.robot.body,
                                                                             self.robot.model.root_link)
            vx, vy = world_linear[0], world_linear[1]
            yaw_frame = differential.yaw_quaternion(yaw_of(orientation))
            bx, by, _ = rotate_back(yaw_frame, (vx, vy, 0.0))
            linear, angular = (bx, by, 0.0), (0.0, 0.0, world_angular[2])
        self.tf_pub.publish(transform(stamp, self.odom_frame, self.base_frame, position, orientation))
        self.odom_pub.publish(odometry(stamp, self.odom_frame, self.base_frame, position, orientation, linear,
                                       angular, differential.pose_covariance(), ZERO_COVARIANCE))
