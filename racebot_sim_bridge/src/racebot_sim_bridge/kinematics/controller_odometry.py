"""diff_drive_controller's (ros_controllers noetic-devel) kinematics: its Odometry (wheel positions ->
pose by exact integration, velocities as a rolling mean), its SpeedLimiter (velocity, acceleration
and jerk limits on one command component) and the wheel separation and radius it reads from the
URDF when the parameters are not given. Pure Python; the controller (ros_controllers/diff_drive_controller.py)
wraps them."""
import math
from collections import deque

MIN_INTEGRATION_DT = 0.0001  # upstream: "Interval too small to integrate with"


class Odometry:
    """Odometry::update / updateOpenLoop: the pose integrated exactly (Runge-Kutta 2 when the turn is
    below 1e-6 rad), linear and angular velocity the mean of the last `window` estimates."""

    def __init__(self, window=10):
        self.window = max(int(window), 1)
        self.timestamp = 0.0
        self.x = self.y = self.heading = 0.0
        self.linear = self.angular = 0.0
        self.wheel_separation = self.left_radius = self.right_radius = 0.0
        self._left_old = self._right_old = 0.0
        self._lin = deque(maxlen=self.window)
        self._ang = deque(maxlen=self.window)

    def init(self, time):
        self._lin.clear()
        self._ang.clear()
        self.timestamp = time

    def set_wheel_params(self, separation, left_radius, right_radius):
        self.wheel_separation, self.left_radius, self.right_radius = separation, left_radius, right_radius

    def update(self, left_pos, right_pos, time):
        """Wheel angles (rad) at `time`; False when the interval is too small (upstream keeps the pose
        moved but the velocities unchanged then)."""
        left = left_pos * self.left_radius
        right = right_pos * self.right_radius
        left_step, right_step = left - self._left_old, right - self._right_old
        self._left_old, self._right_old = left, right
        linear = (right_step + left_step) * 0.5
        angular = (right_step - left_step) / self.wheel_separation
        self.integrate_exact(linear, angular)
        dt = time - self.timestamp
        if dt < MIN_INTEGRATION_DT:
            return False
        self.timestamp = time
        self._lin.append(linear / dt)
        self._ang.append(angular / dt)
        self.linear = sum(self._lin) / len(self._lin)
        self.angular = sum(self._ang) / len(self._ang)
        return True

    def update_open_loop(self, linear, angular, time):
        self.linear, self.angular = linear, angular
        dt = time - self.timestamp
        self.timestamp = time
        self.integrate_exact(linear * dt, angular * dt)

    def integrate_runge_kutta2(self, linear, angular):
        direction = self.heading + angular * 0.5
        self.x += linear * math.cos(direction)
        self.y += linear * math.sin(direction)
        self.heading += angular

    def integrate_exact(self, linear, angular):
        if abs(angular) < 1e-6:
            self.integrate_runge_kutta2(linear, angular)
            return
        old = self.heading
        r = linear / angular
        self.heading += angular
        self.x += r * (math.sin(self.heading) - math.sin(old))
        self.y += -r * (math.cos(self.heading) - math.cos(old))


class SpeedLimiter:
    """SpeedLimiter::limit: jerk, then acceleration, then velocity limits on a command `v`, given the
    last two commands v0, v1 and the period dt. Limits are off unless their has_* flag is set."""

    def __init__(self, has_velocity_limits=False, has_acceleration_limits=False, has_jerk_limits=False,
                 min_velocity=0.0, max_velocity=0.0, min_acceleration=0.0, max_acceleration=0.0,
                 min_jerk=0.0, max_jerk=0.0):
        self.has_velocity_limits = has_velocity_limits
        self.has_acceleration_limits = has_acceleration_limits
        self.has_jerk_limits = has_jerk_limits
        self.min_velocity, self.max_velocity = min_velocity, max_velocity
        self.min_acceleration, self.max_acceleration = min_acceleration, max_acceleration
        self.min_jerk, self.max_jerk = min_jerk, max_jerk

    def limit(self, v, v0, v1, dt):
        if self.has_jerk_limits:
            dv, dv0 = v - v0, v0 - v1
            dt2 = 2.0 * dt * dt
            v = v0 + dv0 + _clamp(dv - dv0, self.min_jerk * dt2, self.max_jerk * dt2)
        if self.has_acceleration_limits:
            v = v0 + _clamp(v - v0, self.min_acceleration * dt, self.max_acceleration * dt)
        if self.has_velocity_limits:
            v = _clamp(v, self.min_velocity, self.max_velocity)
        return v


def _clamp(value, low, high):
    return max(min(value, high), low)


def wheel_params_from_urdf(model, left_joint, right_joint, need_separation, need_radius):
    """(separation, radius) as setOdomParamsFromUrdf finds them: the distance between the two wheel
    joints' origins in their parents, and the radius of the left wheel link's first collision (a
    cylinder or a sphere). A value not needed is None. Raises ValueError with upstream's reason."""
    separation = radius = None
    if not (need_separation or need_radius):
        return separation, radius
    for name in (left_joint, right_joint):
        if name not in model.joints:
            raise ValueError('%s couldn\'t be retrieved from model description' % name)
    left, right = model.joints[left_joint], model.joints[right_joint]
    if need_separation:
        separation = math.dist(left.origin_xyz, right.origin_xyz)
    if need_radius:
        link = model.links.get(left.child)
        if link is None or not link.collisions:
            raise ValueError("Couldn't retrieve %s wheel radius: link %s does not have collision description; "
                             "add a <collision> with a cylinder or sphere to it, or set wheel_radius"
                             % (left_joint, left.child))
        geometry = link.collisions[0]
        if geometry.kind not in ('cylinder', 'sphere'):
            raise ValueError("Couldn't retrieve %s wheel radius: wheel link %s is NOT modeled as a cylinder or "
                             "sphere (its collision is a %s); set wheel_radius"
                             % (left_joint, left.child, geometry.kind))
        radius = geometry.radius
    return separation, radius


class AckermannOdometry(Odometry):
    """ackermann_steering_controller's Odometry: the rear wheel's travel and the front steering angle
    (a bicycle model) instead of two wheels; the same integration and rolling means."""

    def set_wheel_params(self, separation_h, radius):
        self.wheel_separation_h, self.radius = separation_h, radius

    def update(self, rear_wheel_pos, front_steer_pos, time):
        rear = rear_wheel_pos * self.radius
        linear = rear - self._left_old
        self._left_old = rear
        angular = math.tan(front_steer_pos) * linear / self.wheel_separation_h
        self.integrate_exact(linear, angular)
        dt = time - self.timestamp
        if dt < MIN_INTEGRATION_DT:
            return False
        self.timestamp = time
        self._lin.append(linear / dt)
        self._ang.append(angular / dt)
        self.linear = sum(self._lin) / len(self._lin)
        self.angular = sum(self._ang) / len(self._ang)
        return True


def ackermann_params_from_urdf(model, rear_joint, steer_joint, need_separation_h, need_radius):
    """(wheel_separation_h, radius) as ackermann_steering_controller's setOdomParamsFromUrdf: the x
    distance between the rear wheel joint's and the front steer joint's origins in their parents, and the
    radius of the rear wheel link's first collision (cylinder or sphere). Raises ValueError."""
    separation_h = radius = None
    if not (need_separation_h or need_radius):
        return separation_h, radius
    for name in (rear_joint, steer_joint):
        if name not in model.joints:
            raise ValueError('%s couldn\'t be retrieved from model description' % name)
    if need_separation_h:
        separation_h = abs(model.joints[rear_joint].origin_xyz[0] - model.joints[steer_joint].origin_xyz[0])
    if need_radius:
        _, radius = wheel_params_from_urdf(model, rear_joint, rear_joint, False, True)
    return separation_h, radius
