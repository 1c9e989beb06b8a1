"""A base moving in the plane, as gazebo_ros_planar_move (and the odometry of gazebo_ros_skid_steer_drive)
computes it: a twist between the robot's and the world's axes, the odometry twist from two poses, and
the odometry covariance those plugins publish. Angles in radians, speeds in m/s and rad/s."""
import math

UNKNOWN_VARIANCE = 1e12  # what the plugins put on z, roll and pitch: "not measured"


def base_to_world(vx, vy, yaw):
    """A velocity in the robot's axes (cmd_vel's linear x, y) -> world x, y, for a robot heading `yaw`."""
    c, s = math.cos(yaw), math.sin(yaw)
    return vx * c - vy * s, vy * c + vx * s


def world_to_base(vx, vy, yaw):
    """A world-frame velocity -> the robot's axes (odometry's child_frame_id)."""
    c, s = math.cos(yaw), math.sin(yaw)
    return c * vx + s * vy, c * vy - s * vx


def model_velocity(command, yaw):
    """gazebo_ros_planar_move's update: the model's world (linear, angular) velocity for a cmd_vel
    (vx, vy, wz) in the robot's axes. z is set to 0 (upstream sets it, gravity acts within the step),
    and so are the roll and pitch rates."""
    vx, vy, wz = command
    wx, wy = base_to_world(vx, vy, yaw)
    return (wx, wy, 0.0), (0.0, 0.0, wz)


def unwrapped_yaw_change(last_yaw, yaw):
    """yaw - last_yaw brought into [-pi, pi] (the shorter way round)."""
    while yaw < last_yaw - math.pi:
        yaw += 2.0 * math.pi
    while yaw > last_yaw + math.pi:
        yaw -= 2.0 * math.pi
    return yaw - last_yaw


def finite_difference_twist(last_xy_yaw, xy_yaw, dt, commanded_wz):
    """gazebo_ros_planar_move's odometry twist (vx, vy in the robot's axes at the new pose, wz) from the
    pose at the last publication and now, `dt` seconds apart. A commanded turn faster than half a turn
    per publication cannot be told from the poses: the command itself is reported then."""
    (x0, y0, yaw0), (x1, y1, yaw1) = last_xy_yaw, xy_yaw
    vx, vy = world_to_base((x1 - x0) / dt, (y1 - y0) / dt, yaw1)
    if commanded_wz > math.pi / dt:
        wz = commanded_wz
    else:
        wz = unwrapped_yaw_change(yaw0, yaw1) / dt
    return vx, vy, wz


def covariance(var_x, var_y, var_yaw):
    """The 6x6 row-major covariance of a planar odometry: x, y and yaw given, z, roll, pitch unknown."""
    cov = [0.0] * 36
    for i, v in enumerate((var_x, var_y, UNKNOWN_VARIANCE, UNKNOWN_VARIANCE, UNKNOWN_VARIANCE, var_yaw)):
        cov[7 * i] = v
    return cov


def integrate(pose, twist, dt):
    """The (x, y, yaw) reached from `pose` (x, y, yaw) after `dt` seconds at the constant twist (vx, vy, wz)
    of the robot's axes: exact, an arc when wz is not 0."""
    x, y, yaw = pose
    vx, vy, wz = twist
    if abs(wz) < 1e-12:
        dx, dy = base_to_world(vx, vy, yaw)
        return x + dx * dt, y + dy * dt, yaw
    end = yaw + wz * dt
    # integral of R(theta) over [yaw, end] is [[sin, cos], [-cos, sin]] evaluated between the two
    s0, c0, s1, c1 = math.sin(yaw), math.cos(yaw), math.sin(end), math.cos(end)
    ix = ((s1 - s0) * vx + (c1 - c0) * vy) / wz
    iy = ((c0 - c1) * vx + (s1 - s0) * vy) / wz
    return x + ix, y + iy, end
