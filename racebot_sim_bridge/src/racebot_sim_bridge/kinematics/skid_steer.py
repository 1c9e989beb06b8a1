"""A four-wheeled skid-steer base, as gazebo_ros_skid_steer_drive drives it: both wheels of a side turn
at the same speed, the speed a differential drive of track `separation` would give that side. The
sides slip sideways when the base turns, so a real (or simulated) turn is slower than this says."""

LEFT_FRONT, RIGHT_FRONT, LEFT_REAR, RIGHT_REAR = range(4)


def side_speeds(vx, wz, separation):
    """(left, right) ground speeds of the wheel rims in m/s for a cmd_vel (linear.x, angular.z)."""
    half = wz * separation / 2.0
    return vx - half, vx + half


def wheel_velocities(vx, wz, separation, diameter):
    """Joint velocities in rad/s, indexed LEFT_FRONT, RIGHT_FRONT, LEFT_REAR, RIGHT_REAR."""
    left, right = side_speeds(vx, wz, separation)
    radius = diameter / 2.0
    return (left / radius, right / radius, left / radius, right / radius)


def base_twist(left, right, separation):
    """The (vx, wz) of a base whose sides move at `left`, `right` m/s without slip (side_speeds' inverse)."""
    return (left + right) / 2.0, (right - left) / separation
