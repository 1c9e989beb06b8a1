"""Odometry maths: the Ackermann car's wheel odometry, and the sim-time schedule of the ground truth.

Pure Python: no rospy, no pybullet (odometry_nodes.py wraps it in a ROS node; the ground truth's
body-frame twist there is rotate_back, below).

WheelSpeedOdometry integrates the kinematic bicycle model of a car with rear-wheel speed and
front steering: the rear axle centre moves at v = wheel radius x mean rear wheel speed, along the
heading; the heading turns at v x kappa with curvature kappa = mean(tan(steering angle)) /
wheelbase (exact for parallel steering, as the tutorial's servo_commands steers, and for ideal
Ackermann the mean of the two tangents is within a fraction of a percent of it at these angles).
Each interval uses the mean of the speeds and curvatures at its two ends and moves the rear axle
along the arc. The pose reported is that of the child frame (base_footprint), whose origin is
-rear_axle_x metres ahead of the rear axle centre (0.13 m for the racebot).
"""
import math


# The racebot's model (racebot_description/urdf/ackermann/racecar.xacro).
WHEEL_RADIUS = 0.032   # m, collision cylinder of every wheel
WHEELBASE = 0.26       # m, rear axle to steering hinges (2 x axle_x)
REAR_AXLE_X = -0.13    # m, x of the rear wheels' axle in base_footprint
REAR_WHEEL_JOINTS = ('left_rear_wheel_joint', 'right_rear_wheel_joint')
STEERING_JOINTS = ('left_steering_hinge_joint', 'right_steering_hinge_joint')


class WheelSpeedOdometry:
    """The racebot's odometry from sampled rear wheel speeds and steering angles (joint_states), not to be
    mistaken for ackermann_steering_controller's, which integrates the rear wheel's position."""

    def __init__(self, wheel_radius=WHEEL_RADIUS, wheelbase=WHEELBASE, rear_axle_x=REAR_AXLE_X):
        if not wheel_radius > 0 or not wheelbase > 0:
            raise ValueError('wheel radius and wheelbase must be > 0, got %r and %r' % (wheel_radius, wheelbase))
        self.wheel_radius = float(wheel_radius)
        self.wheelbase = float(wheelbase)
        self.rear_axle_x = float(rear_axle_x)
        self.reset()

    def reset(self, x=0.0, y=0.0, yaw=0.0):
        """Starts over with the child frame at (x, y, yaw)."""
        self.yaw = yaw
        self.rear_x = x + self.rear_axle_x * math.cos(yaw)
        self.rear_y = y + self.rear_axle_x * math.sin(yaw)
        self.last = None  # (time, speed, curvature)
        self.speed = 0.0
        self.curvature = 0.0
        self.distance = 0.0

    def update(self, time, rear_wheel_velocities, steering_angles):
        """Integrates up to sim `time` (s) from rear wheel speeds (rad/s) and steering angles
        (rad). A sample not later than the previous one restarts the interval (e.g. after a
        simulation reset) without moving."""
        speed = self.wheel_radius * sum(rear_wheel_velocities) / len(rear_wheel_velocities)
        curvature = sum(math.tan(a) for a in steering_angles) / len(steering_angles) / self.wheelbase
        if self.last is not None and time > self.last[0]:
            dt = time - self.last[0]
            v = 0.5 * (speed + self.last[1])
            k = 0.5 * (curvature + self.last[2])
            self._advance(v * dt, k)
        self.last = (time, speed, curvature)
        self.speed, self.curvature = speed, curvature

    def _advance(self, ds, curvature):
        dyaw = ds * curvature
        if abs(dyaw) < 1e-9:
            self.rear_x += ds * math.cos(self.yaw)
            self.rear_y += ds * math.sin(self.yaw)
        else:  # along the arc of radius 1 / curvature
            radius = 1.0 / curvature
            self.rear_x += radius * (math.sin(self.yaw + dyaw) - math.sin(self.yaw))
            self.rear_y -= radius * (math.cos(self.yaw + dyaw) - math.cos(self.yaw))
        self.yaw = math.atan2(math.sin(self.yaw + dyaw), math.cos(self.yaw + dyaw))
        self.distance += abs(ds)

    @property
    def pose(self):
        """(x, y, yaw) of the child frame."""
        ahead = -self.rear_axle_x
        return (self.rear_x + ahead * math.cos(self.yaw), self.rear_y + ahead * math.sin(self.yaw), self.yaw)

    @property
    def twist(self):
        """(vx, vy, yaw rate) of the child frame, in the child frame."""
        yaw_rate = self.speed * self.curvature
        return self.speed, yaw_rate * -self.rear_axle_x, yaw_rate


def yaw_quaternion(yaw):
    """Quaternion (x, y, z, w) of a turn by `yaw` about z."""
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def rotate_back(q, v):
    """Vector v (parent axes) in the axes of a frame turned by the unit quaternion q (x, y, z, w)."""
    x, y, z, w = -q[0], -q[1], -q[2], q[3]  # the inverse turn
    # v' = v + w t + q_vec x t, with t = 2 (q_vec x v)
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + (y * tz - z * ty),
            v[1] + w * ty + (z * tx - x * tz),
            v[2] + w * tz + (x * ty - y * tx))


class SimTimeTicks:
    """When a node that publishes at `rate` Hz of sim time from a faster stream (gazebo_odometry from
    /gazebo/link_states) publishes: a message is due every 1/rate s of sim time, counted from the due time, not
    from the arrival, so a loaded machine that delivers the stream late still gets rate messages per sim second
    (the ticks it missed are published with the next messages that arrive, one each, each at a later time than
    the last: two messages stamped alike are one transform twice, which tf listeners report as TF_REPEATED_DATA).
    Only a gap of more than `resync` s (a stalled node) or time going back (a world reset) starts the schedule
    again from now. Times are seconds."""

    def __init__(self, rate, resync=1.0):
        self.period = 1.0 / rate if rate > 0 else 0.0
        self.resync = resync
        self.next = None  # sim time the next message is due
        self.last = None  # sim time of the last message

    def due(self, now):
        """True when a message is due at sim time `now` (and counts it)."""
        if self.next is not None and now + 2 * self.period < self.next:
            self.next = None  # time went back: a reset
        if now == self.last or (self.next is not None and now < self.next):
            return False  # the same time as the last message (two arrivals within one clock tick): not again
        self.last = now
        behind = self.next is None or now - self.next > max(self.resync, self.period)
        self.next = (now if behind else self.next) + self.period
        return True
