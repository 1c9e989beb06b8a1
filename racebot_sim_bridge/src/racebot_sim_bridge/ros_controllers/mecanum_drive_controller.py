"""mecanum_drive_controller/MecanumDriveController (ridgeback_control, the Ridgeback's own ros_control
controller) on VelocityJointInterface wheels: `cmd_vel` (x, y and yaw) in, four wheel velocities out, `odom`
(nav_msgs/Odometry, with linear.y) and the odom -> base TF at publish_rate.

As upstream: wheels front_left (0), back_left (1), back_right (2), front_right (3); wheel_separation_x and _y
(both or neither; neither: k from the joints' origins in their parents) give k = (sx + sy) / 2, wheel_radius
else the first wheel's collision cylinder or sphere; the odometry from the wheel *velocities* each update
(vx = r/4 (w0 + w1 + w2 + w3), vy = r/4 (-w0 + w1 - w2 + w3), wz = r/(4k) (-w0 - w1 + w2 + w3), integrated in
the heading after turning); the command zeroed after cmd_vel_timeout, each component limited in velocity then
acceleration (linear/x, linear/y, angular/z), then w = (vx -+ vy -+ k wz) / r. use_realigned_roller_joints is
not simulated (warned)."""
from __future__ import annotations

import math

from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry as OdometryMsg
from tf2_msgs.msg import TFMessage

from racebot_sim_bridge.kinematics.controller_odometry import wheel_params_from_urdf
from racebot_sim_bridge.ros_control import hardware_interface as hardware
from racebot_sim_bridge.ros_control.controller_interface import Controller, ControllerInitError
from racebot_sim_bridge.ros_control.hardware_interface import VELOCITY
from racebot_sim_bridge.ros_controllers.diff_drive_controller import covariance_diagonal, publish_odometry

WHEELS = ('front_left_wheel_joint', 'back_left_wheel_joint', 'back_right_wheel_joint', 'front_right_wheel_joint')
AXES = ('linear/x', 'linear/y', 'angular/z')


def wheel_velocities(vx, vy, wz, k, radius):
    """Wheel rates (0..3) for a body twist, as MecanumDriveController::update."""
    return ((vx - vy - k * wz) / radius, (vx + vy - k * wz) / radius, (vx - vy + k * wz) / radius,
            (vx + vy + k * wz) / radius)


def body_twist(w, k, radius):
    """(vx, vy, wz) from the four wheel rates, as mecanum_drive_controller's Odometry::update."""
    return (0.25 * radius * (w[0] + w[1] + w[2] + w[3]), 0.25 * radius * (-w[0] + w[1] - w[2] + w[3]),
            0.25 * radius / k * (-w[0] - w[1] + w[2] + w[3]))


def k_from_origins(origins):
    """wheels_k_ from the four joints' (x, y) origins in their parents, as setWheelParamsFromUrdf."""
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = origins
    return (-(-x0 - y0) - (x1 - y1) + (-x2 - y2) + (x3 - y3)) / 4.0


class Limiter:
    """mecanum_drive_controller's SpeedLimiter: the velocity clamped, then the change from the last command."""

    def __init__(self, has_velocity, has_acceleration, max_v, min_v, max_a, min_a):
        self.has_velocity, self.has_acceleration = has_velocity, has_acceleration
        self.max_v, self.min_v, self.max_a, self.min_a = max_v, min_v, max_a, min_a

    def limit(self, v, v0, dt):
        if self.has_velocity:
            v = min(max(v, self.min_v), self.max_v)
        if self.has_acceleration:
            v = v0 + min(max(v - v0, self.min_a * dt), self.max_a * dt)
        return v


class MecanumDriveController(Controller):
    type_name = 'mecanum_drive_controller/MecanumDriveController'
    interface = VELOCITY

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        names = [self._text(key, '') for key in WHEELS]
        self.wheels = []
        for key, joint in zip(WHEELS, names):
            try:
                self.wheels.append(hw.handle(joint, VELOCITY))
            except hardware.HardwareError as err:
                raise ControllerInitError('%s/%s: %s' % (self.param_ns, key, err))
        if self._flag('use_realigned_roller_joints', False):
            self.io.warn_throttle(self.param_ns + '/rollers', 0.0, '%s: use_realigned_roller_joints is not simulated '
                                  'by racebot; the wheel radius is the wheel link\'s' % self.param_ns)
        self.publish_period = 1.0 / self._number('publish_rate', 50.0, positive=True)
        self.open_loop = self._flag('open_loop', False)
        self.cmd_vel_timeout = self._number('cmd_vel_timeout', 0.5)
        self.base_frame_id = self._text('base_frame_id', 'base_link')
        self.odom_frame_id = self._text('odom_frame_id', 'odom')
        self.enable_odom_tf = self._flag('enable_odom_tf', True)
        self.limiters = [self._limiter(axis) for axis in AXES]
        self.k, self.radius = self._geometry(names)
        self.pose_cov = covariance_diagonal(self.params, self.param_ns, 'pose_covariance_diagonal')
        self.twist_cov = covariance_diagonal(self.params, self.param_ns, 'twist_covariance_diagonal')
        self.odom_pub = self._pub(self.topic('odom'), OdometryMsg, 100)
        self.tf_pub = self._pub('/tf', TFMessage, 100) if self.enable_odom_tf else None
        self.command = (0.0, 0.0, 0.0, -math.inf)  # (x, y, yaw rate, stamp): swapped whole
        self.last = (0.0, 0.0, 0.0)
        self.pose = (0.0, 0.0, 0.0)
        self.twist = (0.0, 0.0, 0.0)
        self.timestamp = self.now = self.last_publish = 0.0
        self.running = False
        self._sub(self.topic('cmd_vel'), Twist, self._on_cmd_vel)

    def _limiter(self, axis):
        max_v = self._number(axis + '/max_velocity', 0.0)
        max_a = self._number(axis + '/max_acceleration', 0.0)
        return Limiter(self._flag(axis + '/has_velocity_limits', False), self._flag(axis + '/has_acceleration_limits',
                                                                                    False),
                       max_v, self._number(axis + '/min_velocity', -max_v), max_a,
                       self._number(axis + '/min_acceleration', -max_a))

    def _geometry(self, names):
        sx, sy = self._lookup('wheel_separation_x'), self._lookup('wheel_separation_y')
        if (sx is None) != (sy is None):
            raise ControllerInitError('%s: Only one wheel separation overrided (set both wheel_separation_x and '
                                      'wheel_separation_y, or neither)' % self.param_ns)
        radius = self._lookup('wheel_radius')
        model = self.hw.model
        if sx is None:
            missing = [n for n in names if n not in model.joints]
            if missing:
                raise ControllerInitError("%s: %s couldn't be retrieved from model description"
                                          % (self.param_ns, missing[0]))
            k = k_from_origins([model.joints[n].origin_xyz[:2] for n in names])
        else:
            k = (float(sx) + float(sy)) / 2.0
        if radius is None:
            try:
                _, radius = wheel_params_from_urdf(model, names[0], names[3], False, True)
            except ValueError as err:
                raise ControllerInitError('%s: %s' % (self.param_ns, err))
        if not (k > 0 and radius > 0):
            raise ControllerInitError('%s: wheels k %g and radius %g must both be > 0' % (self.param_ns, k, radius))
        return float(k), float(radius)

    def claimed_resources(self):
        return [(VELOCITY, sorted(h.name for h in self.wheels))]

    def _on_cmd_vel(self, msg):
        if not self.running:
            self.io.warn_throttle(self.param_ns + '/stopped', 1.0, "%s: Can't accept new commands. Controller is not "
                                  "running." % self.param_ns)
            return
        self.command = (msg.linear.x, msg.linear.y, msg.angular.z, self.now)

    def _brake(self):
        for h in self.wheels:
            h.command = 0.0

    def starting(self, time):
        self._brake()
        self.now = self.last_publish = self.timestamp = time
        self.running = True

    def stopping(self, time):
        self._brake()
        self.running = False

    def _integrate(self, twist, time):
        dt = time - self.timestamp
        if dt < 0.0001:
            return
        self.timestamp = time
        self.twist = twist
        x, y, heading = self.pose
        heading += twist[2] * dt
        c, s = math.cos(heading), math.sin(heading)
        self.pose = (x + (c * twist[0] - s * twist[1]) * dt, y + (s * twist[0] + c * twist[1]) * dt, heading)

    def update(self, time, period):
        self.now = time
        if self.open_loop:
            self._integrate_open_loop(time)
        else:
            rates = [h.velocity for h in self.wheels]
            if any(math.isnan(r) for r in rates):
                return
            self._integrate(body_twist(rates, self.k, self.radius), time)
        if self.last_publish + self.publish_period < time:
            self.last_publish += self.publish_period
            self._publish(time)
        x, y, wz, stamp = self.command
        if time - stamp > self.cmd_vel_timeout:
            x = y = wz = 0.0
        self.last = tuple(lim.limit(v, v0, period) for lim, v, v0 in zip(self.limiters, (x, y, wz), self.last))
        for h, rate in zip(self.wheels, wheel_velocities(*self.last, self.k, self.radius)):
            h.command = rate

    def _integrate_open_loop(self, time):
        dt = time - self.timestamp
        self.timestamp = time
        self.twist = self.last
        x, y, heading = self.pose
        heading += self.last[2] * dt
        c, s = math.cos(heading), math.sin(heading)
        self.pose = (x + (c * self.last[0] - s * self.last[1]) * dt, y + (s * self.last[0] + c * self.last[1]) * dt,
                     heading)

    def _publish(self, time):
        publish_odometry(self, self.io.stamp(time), self.pose, self.twist)


TYPES = (MecanumDriveController,)
