"""A tricycle (one steered and driven wheel, two passive encoder wheels), as gazebo_ros_tricycle_drive
(gazebo_plugins noetic-devel) commands it and integrates its encoder odometry. Plain functions: joint speeds in
rad/s, angles in radians, lengths in m, times in s.

Upstream's arithmetic, quirks included:
- cmd_vel's angular.z is the steering ANGLE (clamped to +-pi/2), not a yaw rate;
- the wheel ramp lowers the speed at wheelAcceleration and raises it at wheelDeceleration;
- with steeringSpeed > 0 the direction to steer compares the angle error with the target WHEEL speed;
- the encoder yaw grows with (left - right) travel: a turn to the left (REP 103) reads as one to the right,
  and the twist it reports is in odom axes (dx/dt, dy/dt), not the base's.
"""
from racebot_sim_bridge.kinematics import differential

MAX_STEERING = 1.5707963267948966  # M_PI / 2


def wheel_speed(target, current, acceleration, deceleration, tolerance, dt):
    """motorController's actuated wheel speed (rad/s) to command. No ramp when acceleration <= 0."""
    if acceleration <= 0:
        return target
    diff = current - target
    if abs(diff) < tolerance:
        return current
    if abs(diff) > acceleration * dt:
        return current - acceleration * dt if diff > 0 else current + deceleration * dt
    return target


def steering(target_angle, current, target_speed, steering_speed, tolerance, dt):
    """motorController's steering command: ('velocity', rad/s) with steering_speed > 0, else ('position', rad)
    (a kinematic SetPosition). target_speed is the actuated wheel's target (rad/s), as upstream compares it."""
    target = max(-MAX_STEERING, min(MAX_STEERING, target_angle))
    diff = current - target
    if steering_speed > 0:
        if abs(diff) < tolerance:
            return 'velocity', 0.0
        return 'velocity', steering_speed if diff < target_speed else -steering_speed
    if abs(diff) < steering_speed * dt:  # never true: steering_speed is <= 0 here (upstream's dead branch)
        return 'position', current - steering_speed * dt if diff > 0 else current + steering_speed * dt
    return 'position', target


def encoder_step(pose, left_velocity, right_velocity, diameter, separation, dt):
    """UpdateOdometryEncoder: the pose (x, y, theta) after dt at these encoder wheel velocities (rad/s) and the
    twist upstream reports, (dx/dt, dy/dt, dtheta/dt) in odom axes. Upstream's integration is diff_drive's with
    the wheels' roles exchanged (theta grows with left - right). dt <= 0 moves nothing and gives a zero twist."""
    if dt <= 0:
        return pose, (0.0, 0.0, 0.0)
    new, _ = differential.encoder_step(pose, right_velocity, left_velocity, diameter, separation, dt)
    return new, ((new[0] - pose[0]) / dt, (new[1] - pose[1]) / dt, (new[2] - pose[2]) / dt)
