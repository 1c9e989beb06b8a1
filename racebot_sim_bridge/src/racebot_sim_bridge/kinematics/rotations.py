"""Rotations and rigid transforms: quaternions, roll-pitch-yaw angles, poses.

Pure Python: no rospy, no pybullet, no numpy (callers that want arrays wrap `matrix`). The one place
in the package for this maths; frames.py builds Gazebo's reference-frame rules on top of it.

Conventions (those of SDF, URDF, ROS and PyBullet alike):
- quaternions are (x, y, z, w); products are Hamilton products, `a * b` applies b, then a;
- roll, pitch, yaw are fixed-axis rotations about X, then Y, then Z: R = Rz(yaw) Ry(pitch) Rx(roll);
- a transform is an ``(xyz, quaternion)`` pair: a child frame's pose in its parent. Wherever a
  transform is taken, a 6-tuple ``(x, y, z, roll, pitch, yaw)`` (an SDF <pose>, a URDF <origin>) is
  taken too.
"""
import math
from typing import Tuple, Union

IDENTITY = (0.0, 0.0, 0.0, 1.0)

# The shapes of these values, for type annotations (typing's forms: they are evaluated on Python 3.8).
Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # x, y, z, w
Transform = Tuple[Vec3, Quat]  # (xyz, quaternion): a child frame's pose in its parent
XyzRpy = Tuple[float, float, float, float, float, float]  # (x, y, z, roll, pitch, yaw): an SDF <pose>, a URDF <origin>
AnyPose = Union[Transform, XyzRpy]  # what as_transform and compose take


def rpy_to_quaternion(roll, pitch, yaw):
    """Quaternion (x, y, z, w) of R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def quaternion_to_rpy(q):
    """(roll, pitch, yaw) of a unit quaternion (x, y, z, w); inverse of rpy_to_quaternion, with pitch
    in [-pi/2, pi/2]."""
    x, y, z, w = q
    sin_pitch = max(-1.0, min(1.0, 2.0 * (w * y - z * x)))  # rounding can step just past +-1
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(sin_pitch)
    return roll, pitch, yaw_of(q)


def yaw_of(q):
    """The yaw of quaternion_to_rpy(q) alone: the heading of a frame turned by q."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def conjugate(q):
    """The inverse rotation of a unit quaternion."""
    return (-q[0], -q[1], -q[2], q[3])


def quaternion_multiply(a, b):
    """Hamilton product a * b of (x, y, z, w) quaternions (apply b, then a)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def rotate(q, v):
    """Vector v rotated by the unit quaternion q: a vector given in the axes of a frame turned by q,
    in its parent's axes."""
    x, y, z, w = q
    # v' = v + w t + q_vec x t, with t = 2 (q_vec x v)
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + (y * tz - z * ty),
            v[1] + w * ty + (z * tx - x * tz),
            v[2] + w * tz + (x * ty - y * tx))


def rotate_back(q, v):
    """Vector v rotated by the inverse of q: a parent-axes vector in the axes of a frame turned by q."""
    return rotate(conjugate(q), v)


def matrix(q):
    """Rows of the 3 x 3 rotation matrix of a unit quaternion (x, y, z, w)."""
    x, y, z, w = q
    return ((1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)),
            (2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)),
            (2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)))


def as_transform(pose):
    """``(xyz, quaternion)`` of a 6-tuple pose or of an ``(xyz, quaternion)`` pair, as floats."""
    if len(pose) == 6:
        return (tuple(float(c) for c in pose[:3]), rpy_to_quaternion(*pose[3:]))
    xyz, quat = pose
    return tuple(float(c) for c in xyz), tuple(float(c) for c in quat)


def as_xyz_rpy(transform):
    """The 6-tuple ``(x, y, z, roll, pitch, yaw)`` of an ``(xyz, quaternion)`` pair: an SDF <pose>."""
    xyz, quat = transform
    return tuple(xyz) + tuple(quaternion_to_rpy(quat))


def compose(pose_a, pose_b):
    """Pose b (given in frame a) expressed in a's parent frame: ``a * b``.

    Either argument may be a 6-tuple pose or an ``(xyz, quaternion)`` pair; the result is an
    ``(xyz, quaternion xyzw)`` pair.
    """
    pa, qa = as_transform(pose_a)
    pb, qb = as_transform(pose_b)
    moved = rotate(qa, pb)
    return ((pa[0] + moved[0], pa[1] + moved[1], pa[2] + moved[2]),
            quaternion_multiply(qa, qb))


def inverse(pose):
    """The inverse transform, as an ``(xyz, quaternion)`` pair: compose(inverse(a), a) is the identity."""
    p, q = as_transform(pose)
    q_inv = conjugate(q)
    back = rotate(q_inv, p)
    return (-back[0], -back[1], -back[2]), q_inv
