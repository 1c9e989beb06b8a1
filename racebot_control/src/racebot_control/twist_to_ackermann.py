"""geometry_msgs/Twist -> ackermann_msgs/AckermannDrive fields (no rospy here).

Navigation (move_base) speaks Twist: a forward speed linear.x [m/s] and a yaw rate angular.z
[rad/s]. The car takes a speed and a steering angle. Two conversions:

tutorial (default, ``convert_yaw_rate=False``): speed = linear.x and steering_angle = angular.z,
passed through unconverted as chapter 6's transform.py does (a yaw rate used as an angle; the
hinge limit clamps it later, in servo_commands).

``convert_yaw_rate=True``: the bicycle model, omega = v tan(delta) / L, solved for the angle:
delta = atan(wheelbase * omega / v), clamped to +-max_steering_angle. Reverse works unchanged
(backing up with a positive yaw rate steers right). At v = 0 (|v| < MIN_SPEED) no angle yields a
yaw rate, and the formula would divide by zero: the steering angle then stays what it was for
the previous command (0 before any), so stopping at the end of an arc does not swing the wheels
straight, and a stop Twist (all zeros) just stops the car.

Both modes fill acceleration, jerk and steering_angle_velocity with 1, as the tutorial does.
A Twist with a non-finite linear.x or angular.z gives None: the caller skips it; so does one
beyond the float32 range of AckermannDrive's fields, which could not be sent.
"""

import collections
import math
import numbers

from racebot_control.wheel_commands import MAX_STEERING_ANGLE, WHEELBASE, clamp

# The tutorial's constant fields of every command (1 m/s^2, 1 m/s^3, 1 rad/s).
ACCELERATION = 1.0
JERK = 1.0
STEERING_ANGLE_VELOCITY = 1.0
FRAME_ID = 'base_link'
FLOAT32_MAX = 3.4028234663852886e38
# Below this |linear.x| [m/s] the car counts as standing still for the yaw-rate conversion.
MIN_SPEED = 1e-6

AckermannCommand = collections.namedtuple('AckermannCommand', [
    'speed', 'steering_angle', 'steering_angle_velocity', 'acceleration', 'jerk'])


class TwistToAckermann:
    """Converts (linear.x, angular.z) pairs; keeps the last steering angle for v = 0."""

    def __init__(self, convert_yaw_rate=False, wheelbase=WHEELBASE,
                 max_steering_angle=MAX_STEERING_ANGLE):
        if not (_finite(wheelbase) and wheelbase > 0.0):
            raise ValueError('wheelbase must be a finite number > 0, got %r' % (wheelbase,))
        if not (_finite(max_steering_angle) and 0.0 < max_steering_angle < math.pi / 2):
            raise ValueError('max_steering_angle must be in (0, pi/2), got %r' % (max_steering_angle,))
        self.convert_yaw_rate = bool(convert_yaw_rate)
        self.wheelbase = float(wheelbase)
        self.max_steering_angle = float(max_steering_angle)
        self.last_steering_angle = 0.0

    def steering_angle(self, linear_x, angular_z):
        """The steering angle for one Twist (assumes finite inputs)."""
        if not self.convert_yaw_rate:
            return angular_z
        if abs(linear_x) < MIN_SPEED:
            return self.last_steering_angle
        return clamp(math.atan(self.wheelbase * angular_z / linear_x), self.max_steering_angle)

    def convert(self, linear_x, angular_z):
        """AckermannCommand for a Twist's linear.x and angular.z, or None if either is not finite
        (or beyond float32)."""
        if not (_finite(linear_x, angular_z) and abs(linear_x) <= FLOAT32_MAX and abs(angular_z) <= FLOAT32_MAX):
            return None
        steer = self.steering_angle(linear_x, angular_z)
        self.last_steering_angle = steer
        return AckermannCommand(speed=linear_x, steering_angle=steer,
                                steering_angle_velocity=STEERING_ANGLE_VELOCITY,
                                acceleration=ACCELERATION, jerk=JERK)


def _finite(*values):
    return all(isinstance(v, numbers.Real) and math.isfinite(v) for v in values)
