"""A two-wheeled differential-drive base, as gazebo_ros_diff_drive (gazebo_plugins noetic-devel) drives it
and integrates its encoder odometry. Plain functions: speeds in m/s (wheel rims) and rad/s (joints),
lengths in m, times in s, angles in radians. Left and right as REP 103 has them (y to the left):
noetic's plugin no longer reads legacyMode, which swapped the sides (kinetic and older).

The acceleration ramp is upstream's arithmetic, quirks included: the commanded speed moves by the
gap between the target and the wheel's MEASURED speed (at most acceleration * dt), so it can run
ahead of a lagging wheel; and both wheels get their targets directly once either of them is within
SPEED_REACHED of its own.
"""
import math

SPEED_REACHED = 0.01  # m/s: upstream's "target speed is reached" threshold of the ramp


def wheel_speeds(vx, wz, separation):
    """(left, right) rim speeds for a cmd_vel (linear.x, angular.z) and the wheels' separation."""
    half = wz * separation / 2.0
    return vx - half, vx + half


def joint_velocity(rim_speed, diameter):
    """A wheel's joint velocity (rad/s) for a rim speed (m/s): rim / radius."""
    return rim_speed / (diameter / 2.0)


def rim_speed(joint_velocity_, diameter):
    """A wheel's rim speed (m/s) for its joint velocity (rad/s)."""
    return joint_velocity_ * (diameter / 2.0)


def base_twist(left, right, separation):
    """(vx, wz) of a base whose wheels' rims move at `left`, `right` without slip (wheel_speeds' inverse)."""
    return (left + right) / 2.0, (right - left) / separation


def ramp_step(target, measured, commanded, acceleration, dt):
    """One wheel's new commanded rim speed under the acceleration ramp: `commanded` moved by the gap
    between `target` and the `measured` speed, that move limited to acceleration * dt either way."""
    step = acceleration * dt
    gap = target - measured
    return commanded + (min(gap, step) if gap >= 0 else max(gap, -step))


def ramped_speeds(targets, measured, commanded, acceleration, dt):
    """What one update of the plugin sets: (rim speeds to command, the ramp's state after it), each a
    (left, right) pair. With no acceleration limit (0), or either wheel within SPEED_REACHED of its
    target, the targets are commanded and the ramp's state is kept as it was (upstream never resets it)."""
    if acceleration == 0 or any(abs(t - m) < SPEED_REACHED for t, m in zip(targets, measured)):
        return tuple(targets), tuple(commanded)
    ramped = tuple(ramp_step(t, m, c, acceleration, dt) for t, m, c in zip(targets, measured, commanded))
    return ramped, ramped


def encoder_step(pose, left_velocity, right_velocity, diameter, separation, dt):
    """UpdateOdometryEncoder: the pose (x, y, theta) after dt at these wheel joint velocities (rad/s),
    and the twist upstream reports with it, (v, w): v is the distance moved over dt, so never negative
    (a base reversing reports a positive speed, as upstream), w the yaw change over dt.
    dt <= 0 moves nothing and gives (0, 0) (upstream would divide by zero)."""
    x, y, theta = pose
    if dt <= 0:
        return pose, (0.0, 0.0)
    radius = diameter / 2.0
    sl = left_velocity * radius * dt
    sr = right_velocity * radius * dt
    ssum, sdiff = sl + sr, sr - sl
    heading = theta + sdiff / (2.0 * separation)  # the mid-step heading (Siegwart 2011, p. 337)
    dx = ssum / 2.0 * math.cos(heading)
    dy = ssum / 2.0 * math.sin(heading)
    dtheta = sdiff / separation
    return (x + dx, y + dy, theta + dtheta), (math.hypot(dx, dy) / dt, dtheta / dt)


class EncoderOdometry:
    """UpdateOdometryEncoder's state, integrated at every world update (the diff drive plugin's every_update): the
    pose (x, y, theta) and the twist (v, w) upstream reports with it, from the wheels' joint velocities that
    read_wheels() gives ((left, right) joint states, velocity second: PyBullet's getJointStates), by encoder_step.
    Compiled with Cython where built (differential.pxd): it runs every update for every diff-drive robot."""

    def __init__(self, read_wheels, diameter, separation):
        self.read_wheels = read_wheels
        self.diameter = diameter
        self.separation = separation
        self.x = self.y = self.theta = 0.0
        self.v = self.w = 0.0
        self.last_ns = 0  # upstream's last_odom_update_ starts at time 0 and is never reset
        self.wheels = None  # what read_wheels() gave at the latest update,
        self.wheels_ns = -1  # and that update's time (ns)

    def update(self, now):
        """Reads the wheels and integrates from the last update to `now` (integer ns) at their velocities."""
        wheels = self.read_wheels()
        self.wheels = wheels
        self.wheels_ns = now
        dt = (now - self.last_ns) / 1e9
        self.last_ns = now
        pose, twist = encoder_step((self.x, self.y, self.theta), wheels[0][1], wheels[1][1], self.diameter,
                                   self.separation, dt)
        self.x, self.y, self.theta = pose
        self.v, self.w = twist


def yaw_quaternion(theta):
    """(x, y, z, w) of a rotation by theta about z (tf's setRPY(0, 0, theta))."""
    return 0.0, 0.0, math.sin(theta / 2.0), math.cos(theta / 2.0)


# nav_msgs/Odometry pose covariance upstream publishes (x, y, z, roll, pitch, yaw on the diagonal); the
# twist covariance it leaves all zero.
POSE_COVARIANCE_DIAGONAL = (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)


def pose_covariance():
    cov = [0.0] * 36
    for i, value in enumerate(POSE_COVARIANCE_DIAGONAL):
        cov[7 * i] = value
    return cov
