"""diff_drive_controller/DiffDriveController (ros_controllers noetic-devel) on VelocityJointInterface
wheels: `cmd_vel` (geometry_msgs/Twist) in, wheel velocities out, `odom` (nav_msgs/Odometry) and the
odom -> base TF at publish_rate. Parameters, defaults and errors as upstream's init(); the kinematics
are kinematics/controller_odometry.py. Upstream's dynamic_reconfigure server and
publish_wheel_joint_controller_state are not here (docs/SUPPORTED.md)."""
import math

from geometry_msgs.msg import TransformStamped, TwistStamped
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry as OdometryMsg
from tf2_msgs.msg import TFMessage

from racebot_sim_bridge.ros_control.hardware_interface import VELOCITY
from racebot_sim_bridge.kinematics.controller_odometry import Odometry, SpeedLimiter, wheel_params_from_urdf
from racebot_sim_bridge.ros_control.controller_interface import Controller, ControllerInitError
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE


def covariance_diagonal(params, param_ns, key):
    """A pose/twist_covariance_diagonal parameter: six finite numbers; absent: zeros (upstream's XmlRpc reads an
    absent list as zeros)."""
    value = params.get(key)
    if value is None:
        return (0.0,) * 6
    if not isinstance(value, list) or len(value) != 6 or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value):
        raise ControllerInitError('%s/%s must be a list of 6 numbers, got %r' % (param_ns, key, value))
    return tuple(float(v) for v in value)


def publish_odometry(controller, stamp, pose, twist):
    """nav_msgs/Odometry of a planar base on the controller's odom_pub, and its odom -> base transform on tf_pub when
    it publishes one: pose (x, y, heading) in the odom frame, twist (vx, vy, wz) in the base frame, the covariance
    diagonals pose_cov and twist_cov (the drive controllers' publishing step, upstream's realtime publishers)."""
    x, y, heading = pose
    qz, qw = math.sin(heading / 2.0), math.cos(heading / 2.0)
    msg = OdometryMsg()
    msg.header.stamp = stamp
    msg.header.frame_id = controller.odom_frame_id
    msg.child_frame_id = controller.base_frame_id
    msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
    msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = qz, qw
    msg.twist.twist.linear.x, msg.twist.twist.linear.y, msg.twist.twist.angular.z = twist
    msg.pose.covariance = _diagonal(controller.pose_cov)
    msg.twist.covariance = _diagonal(controller.twist_cov)
    controller.odom_pub.publish(msg)
    if controller.tf_pub is not None:
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id = controller.odom_frame_id
        t.child_frame_id = controller.base_frame_id
        t.transform.translation.x, t.transform.translation.y = x, y
        t.transform.rotation.z, t.transform.rotation.w = qz, qw
        controller.tf_pub.publish(TFMessage(transforms=[t]))


class OdometryDriveController(Controller):
    """What diff_drive_controller and ackermann_steering_controller share (the latter is derived from the
    former upstream): cmd_vel with its timeout and limits, the odometry published at publish_rate with
    its frames, covariances and TF. A subclass reads its joints and geometry (`_init_drive`), feeds the
    odometry (`_read_odometry`) and turns the limited command into joint commands (`_command`)."""

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        publish_rate = self._number('publish_rate', 50.0, positive=True)
        self.publish_period = 1.0 / publish_rate
        self.open_loop = self._flag('open_loop', False)
        window = self.params.get('velocity_rolling_window_size', 10)
        if isinstance(window, bool) or not isinstance(window, int) or window < 1:
            raise ControllerInitError("%s/velocity_rolling_window_size must be an integer >= 1, got %r"
                                      % (self.param_ns, window))
        self.odometry = self.odometry_class(window)
        self.cmd_vel_timeout = self._number('cmd_vel_timeout', 0.5)
        self.allow_multiple_publishers = self._flag('allow_multiple_cmd_vel_publishers', True)
        self.base_frame_id = self._text('base_frame_id', 'base_link')
        self.odom_frame_id = self._text('odom_frame_id', 'odom')
        self.enable_odom_tf = self._flag('enable_odom_tf', True)
        self.limiter_lin = self._limiter('linear/x')
        self.limiter_ang = self._limiter('angular/z')
        self._init_drive()
        self.pose_cov = self._covariance('pose_covariance_diagonal')
        self.twist_cov = self._covariance('twist_covariance_diagonal')
        self.odom_pub = self._pub(self.topic('odom'), OdometryMsg, 100)
        self.tf_pub = self._pub('/tf', TFMessage, 100) if self.enable_odom_tf else None
        self.cmd_pub = None
        self._init_publishers()
        self.command = (0.0, 0.0, -math.inf)  # (linear, angular, stamp): one tuple, swapped whole
        self.last0 = self.last1 = (0.0, 0.0)
        self.now = 0.0
        self.last_publish = 0.0
        self.running = False
        self.sub = self._sub(self.topic('cmd_vel'), Twist, self._on_cmd_vel)

    def _init_publishers(self):
        pass

    def _geometry_param(self, key):
        value = self.params.get(key)
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not math.isfinite(value) or value <= 0):
            raise ControllerInitError('%s/%s must be a number > 0 (m), got %r; or leave it out to read it from '
                                      'the URDF' % (self.param_ns, key, value))
        return value

    def _wheel_geometry(self, keys, from_urdf, problem):
        """The geometry parameters `keys` (m), each one not given measured on the URDF: from_urdf(one flag per
        key, True where it is missing) gives the values in `keys` order, or raises ValueError with upstream's
        reason. ControllerInitError unless every value is > 0 (`problem`, formatted with the values, says what
        to set)."""
        given = [self._geometry_param(key) for key in keys]
        try:
            measured = from_urdf(*[value is None for value in given])
        except ValueError as err:
            raise ControllerInitError('%s: %s' % (self.param_ns, err))
        values = tuple(float(g if g is not None else m) for g, m in zip(given, measured))
        if not all(v > 0 for v in values):
            raise ControllerInitError('%s: %s' % (self.param_ns, problem % values))
        return values

    def _limiter(self, prefix):
        lim = SpeedLimiter(self._flag(prefix + '/has_velocity_limits', False),
                           self._flag(prefix + '/has_acceleration_limits', False),
                           self._flag(prefix + '/has_jerk_limits', False))
        for kind in ('velocity', 'acceleration', 'jerk'):
            high = self._number('%s/max_%s' % (prefix, kind), 0.0)
            low = self._number('%s/min_%s' % (prefix, kind), -high)
            setattr(lim, 'max_' + kind, high)
            setattr(lim, 'min_' + kind, low)
        return lim

    def _covariance(self, key):
        return covariance_diagonal(self.params, self.param_ns, key)

    # -- ROS ------------------------------------------------------------------------------------
    def _on_cmd_vel(self, msg):
        if not self.running:
            self.io.warn_throttle(self.param_ns + '/stopped', 1.0, "%s: Can't accept new commands. Controller is not "
                                  "running." % self.param_ns)
            return
        if not self.allow_multiple_publishers:
            count = getattr(self.sub, 'get_num_connections', lambda: 1)()
            if count > 1:
                self.io.warn_throttle(self.param_ns + '/publishers', 1.0, '%s: Detected %d publishers. Only 1 '
                                      'publisher is allowed. Going to brake.' % (self.param_ns, count))
                self.command = (0.0, 0.0, self.now)
                return
        if not (math.isfinite(msg.angular.z) and math.isfinite(msg.linear.x)):
            self.io.warn_throttle(self.param_ns + '/nan', 1.0, '%s: Received NaN in velocity command. Ignoring.'
                                  % self.param_ns)
            return
        # Stamped with the controller's latest update time (upstream: ros::Time::now(), the same sim clock).
        self.command = (msg.linear.x, msg.angular.z, self.now)

    def starting(self, time):
        self._brake()
        self.now = self.last_publish = time
        self.odometry.init(time)
        self.running = True

    def stopping(self, time):
        self._brake()
        self.running = False

    def update(self, time, period):
        self.now = time
        if self.open_loop:
            self.odometry.update_open_loop(self.last0[0], self.last0[1], time)
        elif not self._read_odometry(time):
            return
        if self.last_publish + self.publish_period < time:
            self.last_publish += self.publish_period
            self._publish_odometry(time)
        lin, ang, stamp = self.command
        if time - stamp > self.cmd_vel_timeout:
            lin = ang = 0.0
        lin = self.limiter_lin.limit(lin, self.last0[0], self.last1[0], period)
        ang = self.limiter_ang.limit(ang, self.last0[1], self.last1[1], period)
        self.last1, self.last0 = self.last0, (lin, ang)
        if self.cmd_pub is not None:
            out = TwistStamped()
            out.header.stamp = self.io.stamp(time)
            out.twist.linear.x, out.twist.angular.z = lin, ang
            self.cmd_pub.publish(out)
        self._command(lin, ang)

    def _publish_odometry(self, time):
        odo = self.odometry
        publish_odometry(self, self.io.stamp(time), (odo.x, odo.y, odo.heading), (odo.linear, 0.0, odo.angular))


class DiffDriveController(OdometryDriveController):
    type_name = 'diff_drive_controller/DiffDriveController'
    interface = VELOCITY
    odometry_class = Odometry

    def _init_drive(self):
        p = self.params
        left_names, right_names = self._wheel_names('left_wheel'), self._wheel_names('right_wheel')
        if len(left_names) != len(right_names):
            raise ControllerInitError('%s: #left wheels (%d) != #right wheels (%d).'
                                      % (self.param_ns, len(left_names), len(right_names)))
        self.separation_multiplier = self._number('wheel_separation_multiplier', 1.0)
        if 'wheel_radius_multiplier' in p:
            self.left_multiplier = self.right_multiplier = self._number('wheel_radius_multiplier', 1.0)
        else:
            self.left_multiplier = self._number('left_wheel_radius_multiplier', 1.0)
            self.right_multiplier = self._number('right_wheel_radius_multiplier', 1.0)
        self.publish_cmd = self._flag('publish_cmd', False)
        if self._flag('publish_wheel_joint_controller_state', False):
            self.io.warn_throttle(self.param_ns + '/state', 0.0, '%s: publish_wheel_joint_controller_state is not '
                                  'simulated by racebot (see %s); the controller runs without it'
                                  % (self.param_ns, SUPPORTED_TABLE))
        self.separation, self.radius = self._wheel_geometry(
            ('wheel_separation', 'wheel_radius'),
            lambda *missing: wheel_params_from_urdf(self.hw.model, left_names[0], right_names[0], *missing),
            'wheel separation %g and radius %g must both be > 0 (from the URDF: the wheel joints coincide, or a zero '
            'radius); set wheel_separation and wheel_radius')
        self.left = [self._handle(n, VELOCITY) for n in left_names]
        self.right = [self._handle(n, VELOCITY) for n in right_names]

    def _init_publishers(self):
        if self.publish_cmd:
            self.cmd_pub = self._pub(self.topic('cmd_vel_out'), TwistStamped, 100)

    # -- parameters -----------------------------------------------------------------------------
    def _wheel_names(self, key):
        value = self.params.get(key)
        if value is None:
            raise ControllerInitError("%s: Couldn't retrieve wheel param '%s'. Set %s/%s to the wheel joint (or a list)"
                                      % (self.param_ns, key, self.param_ns, key))
        if isinstance(value, str):
            return [value]
        if isinstance(value, list):
            if not value:
                raise ControllerInitError("%s: Wheel param '%s' is an empty list" % (self.param_ns, key))
            for i, v in enumerate(value):
                if not isinstance(v, str):
                    raise ControllerInitError("%s: Wheel param '%s' #%d isn't a string." % (self.param_ns, key, i))
            return list(value)
        raise ControllerInitError("%s: Wheel param '%s' is neither a list of strings nor a string."
                                  % (self.param_ns, key))

    def claimed_resources(self):
        return [(VELOCITY, sorted(h.name for h in self.left + self.right))]

    # -- life cycle -----------------------------------------------------------------------------
    def _brake(self):
        for h in self.left + self.right:
            h.command = 0.0

    def _geometry(self):
        """(separation, left radius, right radius) with the multipliers."""
        return (self.separation_multiplier * self.separation, self.left_multiplier * self.radius,
                self.right_multiplier * self.radius)

    def _read_odometry(self, time):
        """False when a wheel position is NaN (upstream skips the whole update then)."""
        self.odometry.set_wheel_params(*self._geometry())
        left = sum(h.position for h in self.left) / len(self.left)
        right = sum(h.position for h in self.right) / len(self.right)
        if math.isnan(left) or math.isnan(right):
            return False
        self.odometry.update(left, right, time)
        return True

    def _command(self, lin, ang):
        ws, lwr, rwr = self._geometry()
        vel_left = (lin - ang * ws / 2.0) / lwr
        vel_right = (lin + ang * ws / 2.0) / rwr
        for h in self.left:
            h.command = vel_left
        for h in self.right:
            h.command = vel_right


def _diagonal(values):
    cov = [0.0] * 36
    for i, v in enumerate(values):
        cov[i * 7] = v
    return cov


TYPES = (DiffDriveController,)
