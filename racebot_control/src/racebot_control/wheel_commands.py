"""Ackermann drive command -> the six joint commands of the racebot (no rospy here).

An `ackermann_msgs/AckermannDrive` command is a bicycle-model command: `speed` is the signed speed
of the middle of the rear axle [m/s] and `steering_angle` the angle of an imaginary wheel in the
middle of the front axle [rad], positive to the left. The racebot has four driven wheels
(velocity controllers, rad/s) and two steering hinges (position controllers, rad).

Two steering modes:

``parallel`` (the tutorial's servo_commands): every wheel turns at speed / wheel_radius (the
tutorial's 31.25 is 1 / 0.032 m) and both hinges take the steering angle, clamped to the hinge
limit. Simple, and what chapter 6 does; in a turn the wheels scrub.

``ackermann``: all wheels roll about one instantaneous centre of rotation (ICR) on the rear axle
line, at signed distance R = wheelbase / tan(steering_angle) to the left of the rear axle middle
(computed through the curvature k = 1/R, so the straight line needs no special case). Each hinge
gets the angle that points its wheel's axle at the ICR, tan(delta) = wheelbase / (R - y_hinge)
(y_hinge = +-(track/2 - wheel_hinge_offset): the inner wheel turns more than the outer one). Each
wheel turns at its own speed, speed * (its distance to the ICR) / |R|, over the wheel radius: rear
wheels by their distance about the ICR, front wheels by the distance of their centre (which sits
wheel_hinge_offset outboard of the hinge axis, on the axle line) to the ICR. With
wheel_hinge_offset = 0 the angles are the textbook tan(delta_i) = L / (R - T/2),
tan(delta_o) = L / (R + T/2). The turn is limited so that the inner hinge stays within
+-max_steering_angle (the hinge limit), which keeps both wheels on one ICR; the command's bicycle
angle is clamped the same way in parallel mode.

Reverse (negative speed) needs nothing special: the ICR is the same and every wheel speed changes
sign. Non-finite inputs give None: the caller skips such a command.
"""

import collections
import math
import numbers

PARALLEL = 'parallel'
ACKERMANN = 'ackermann'
STEERING_MODES = (PARALLEL, ACKERMANN)

# The model's numbers (racebot_description/urdf/ackermann/racecar.xacro).
WHEEL_RADIUS = 0.032        # m; the tutorial's 31.25 rad per metre is 1 / WHEEL_RADIUS
WHEELBASE = 0.26            # m, rear axle to front hinges (hinges at x = +0.13, rear wheels at -0.13)
TRACK = 0.18                # m, between left and right wheel centres (rear y = +-0.09)
WHEEL_HINGE_OFFSET = 0.025  # m, front wheel centre outboard of its hinge axis (hinge y = +-0.065)
MAX_STEERING_ANGLE = 0.6    # rad, the steering hinges' joint limit
# Wheel radius, wheelbase and track accepted [m]: far beyond any car both ways, and far from the
# lengths (1e-59 m, 5e16 m, found by fuzzing) at which the turning geometry rounds to a division by 0.
MIN_LENGTH = 1e-6
MAX_LENGTH = 1e3

# The order of the six commands, the same as the controllers they go to (see servo_commands_node).
WheelCommands = collections.namedtuple('WheelCommands', [
    'left_rear_wheel',        # rad/s
    'right_rear_wheel',       # rad/s
    'left_front_wheel',       # rad/s
    'right_front_wheel',      # rad/s
    'left_steering_hinge',    # rad
    'right_steering_hinge',   # rad
])


class CarGeometry(collections.namedtuple('CarGeometry', [
        'wheel_radius', 'wheelbase', 'track', 'max_steering_angle', 'wheel_hinge_offset'])):
    """The car's dimensions [m] and steering limit [rad]; defaults are the racebot model's."""
    __slots__ = ()

    def __new__(cls, wheel_radius=WHEEL_RADIUS, wheelbase=WHEELBASE, track=TRACK,
                max_steering_angle=MAX_STEERING_ANGLE, wheel_hinge_offset=WHEEL_HINGE_OFFSET):
        values = dict(wheel_radius=wheel_radius, wheelbase=wheelbase, track=track,
                      max_steering_angle=max_steering_angle, wheel_hinge_offset=wheel_hinge_offset)
        for name, value in values.items():
            if not _finite(value):
                raise ValueError('%s must be a finite number, got %r' % (name, value))
        for name in ('wheel_radius', 'wheelbase', 'track'):
            if not MIN_LENGTH <= values[name] <= MAX_LENGTH:
                raise ValueError('%s must be between %g and %g m, got %r'
                                 % (name, MIN_LENGTH, MAX_LENGTH, values[name]))
        if not 0.0 < max_steering_angle < math.pi / 2:
            raise ValueError('max_steering_angle must be in (0, pi/2), got %r' % max_steering_angle)
        if not 0.0 <= wheel_hinge_offset < track / 2:
            raise ValueError('wheel_hinge_offset must be in [0, track/2), got %r' % wheel_hinge_offset)
        return super().__new__(cls, **{k: float(v) for k, v in values.items()})

    @property
    def hinge_y(self):
        """Distance of each steering hinge axis from the centre line [m]."""
        return self.track / 2 - self.wheel_hinge_offset

    @property
    def max_curvature(self):
        """Largest |1/R| [1/m] that keeps the inner hinge within max_steering_angle."""
        tan_max = math.tan(self.max_steering_angle)
        return tan_max / (self.wheelbase + tan_max * self.hinge_y)


def clamp(value, limit):
    """value limited to [-limit, limit]."""
    return max(-limit, min(limit, value))


def _finite(*values):
    return all(isinstance(v, numbers.Real) and math.isfinite(v) for v in values)


def parallel_commands(speed, steering_angle, geometry=CarGeometry()):
    """The tutorial's mapping: every wheel speed / wheel_radius, both hinges the (clamped) angle.

    Returns WheelCommands, or None when speed or steering_angle is not a finite number.
    """
    if not _finite(speed, steering_angle):
        return None
    wheel = speed / geometry.wheel_radius
    steer = clamp(steering_angle, geometry.max_steering_angle)
    return WheelCommands(wheel, wheel, wheel, wheel, steer, steer)


def curvature(steering_angle, geometry=CarGeometry()):
    """Signed curvature 1/R [1/m] of the rear axle middle for a bicycle steering angle, limited so
    that the inner hinge stays within the hinge limit. Positive turns left."""
    k = math.tan(clamp(steering_angle, geometry.max_steering_angle)) / geometry.wheelbase
    return clamp(k, geometry.max_curvature)


def _radius_ratio(k, x, y):
    """|distance of (x, y) to the ICR (0, 1/k)| * |k|: how fast the point (x, y) of the car
    (rear axle middle frame) moves relative to the rear axle middle. 1 for k = 0."""
    return math.hypot(k * x, 1.0 - k * y)


def ackermann_commands(speed, steering_angle, geometry=CarGeometry()):
    """Each hinge its own angle and each wheel its own speed, all about one ICR (module docstring).

    Returns WheelCommands, or None when speed or steering_angle is not a finite number.
    """
    if not _finite(speed, steering_angle):
        return None
    g = geometry
    k = curvature(steering_angle, g)
    half_track = g.track / 2
    hinge_y = g.hinge_y
    # tan(delta) = L / (R - y) = L k / (1 - k y); 1 - k y > 0 because |k| <= max_curvature < 1/hinge_y.
    left_steer = math.atan(g.wheelbase * k / (1.0 - k * hinge_y))
    right_steer = math.atan(g.wheelbase * k / (1.0 + k * hinge_y))
    # Front wheel centres: wheel_hinge_offset outboard of the hinge, along the turned axle.
    off = g.wheel_hinge_offset
    left_front = (g.wheelbase - off * math.sin(left_steer), hinge_y + off * math.cos(left_steer))
    right_front = (g.wheelbase + off * math.sin(right_steer), -hinge_y - off * math.cos(right_steer))
    to_wheel = speed / g.wheel_radius
    return WheelCommands(
        to_wheel * _radius_ratio(k, 0.0, half_track),
        to_wheel * _radius_ratio(k, 0.0, -half_track),
        to_wheel * _radius_ratio(k, *left_front),
        to_wheel * _radius_ratio(k, *right_front),
        left_steer,
        right_steer,
    )


def wheel_commands(speed, steering_angle, mode=PARALLEL, geometry=CarGeometry()):
    """The six joint commands for one Ackermann command in the given steering mode, or None when
    the command is not finite."""
    if mode == PARALLEL:
        return parallel_commands(speed, steering_angle, geometry)
    if mode == ACKERMANN:
        return ackermann_commands(speed, steering_angle, geometry)
    raise ValueError('steering mode must be one of %s, got %r' % (', '.join(STEERING_MODES), mode))
