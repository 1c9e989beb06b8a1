"""Frames as gazebo_ros's services use them: entity names, quaternions, poses and twists in a reference.

Pure Python: no rospy, no pybullet. Poses are ``(position xyz, quaternion xyzw)`` pairs (physics.Pose
fits), twists ``(linear, angular)`` pairs of world-frame vectors (pose_in, twist_in read them from a request's
geometry_msgs); the maths is rotations.py's.

Names: Gazebo finds an entity by walking its tree depth first (world -> models in the order they came
-> each model's links, then its joints) and taking the first whose scoped name (``model::link``) or
plain name (``link``) is the one asked for. So a bare link name is that link in the first model that
has one, a model name is the model, and a joint found first hides a later link of the same name (the
joint is not an entity with a pose). ``resolve`` does the same walk.

Twists, per service (gazebo_ros_api_plugin, noetic), with F the reference frame's world pose:
- get_model_state, get_link_state: (v - v_F) rotated into F;
- set_model_state: v rotated from F into the world (F's own velocity is not added);
- set_link_state: v - v_F, not rotated (upstream's arithmetic, kept so scripts get what Gazebo gives).
"""
import math
from collections import namedtuple

from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.kinematics.rotations import IDENTITY

# The names gazebo_ros takes as the world's inertial frame when no entity has the name.
WORLD_FRAMES = ('', 'world', 'map', '/map')

Entity = namedtuple('Entity', 'model link')  # link None: the model itself
ModelEntry = namedtuple('ModelEntry', 'name links joints')  # what resolve() walks, in world order


def resolve(name, models):
    """The Entity called `name` among `models` (ModelEntry, in the world's order), as Gazebo's
    World::EntityByName finds it; None if nothing (or first a joint) has that name."""
    if not name:
        return None
    for m in models:
        if name == m.name:
            return Entity(m.name, None)
        for link in m.links:
            if name == link or name == '%s::%s' % (m.name, link):
                return Entity(m.name, link)
        for joint in m.joints:
            if name == joint or name == '%s::%s' % (m.name, joint):
                return None  # a joint: Gazebo's cast to an entity with a pose fails
    return None


def is_world_frame(name):
    return name in WORLD_FRAMES


def finite(*values):
    return all(math.isfinite(v) for v in values)


def normalised(q):
    """Unit quaternion (x, y, z, w) as ignition's Quaterniond::Normalize gives it: a zero (or
    vanishing) quaternion becomes the identity. None if any component is not finite."""
    if not finite(*q):
        return None
    n = math.sqrt(sum(c * c for c in q))
    if n < 1e-6:  # ignition's equal(s, 0) tolerance
        return IDENTITY
    return tuple(c / n for c in q)


def pose_in(msg):
    """(position, unit quaternion) of a geometry_msgs/Pose, a zero quaternion read as the identity
    (as ignition's Normalize makes it); None if a number is not finite."""
    p, q = msg.position, msg.orientation
    orientation = normalised((q.x, q.y, q.z, q.w))
    if orientation is None or not finite(p.x, p.y, p.z):
        return None
    return (p.x, p.y, p.z), orientation


def twist_in(msg):
    """(linear, angular) of a geometry_msgs/Twist; None if a number is not finite."""
    lin, ang = (msg.linear.x, msg.linear.y, msg.linear.z), (msg.angular.x, msg.angular.y, msg.angular.z)
    return (lin, ang) if finite(*lin + ang) else None


def in_world(frame_pose, local_pose):
    """A pose given in frame F, in the world: F * local (ignition's `local + F`)."""
    return rotations.compose(frame_pose, local_pose)


def relative_to(frame_pose, pose):
    """A world pose expressed in frame F: F^-1 * pose (ignition's `pose - F`)."""
    return rotations.compose(rotations.inverse(frame_pose), pose)


def rotate_into(frame_pose, v):
    """A world vector in F's axes (ignition's RotateVectorReverse)."""
    return rotations.rotate_back(frame_pose[1], v)


def rotate_from(frame_pose, v):
    """A vector given in F's axes, in the world's (ignition's RotateVector)."""
    return rotations.rotate(frame_pose[1], v)


def _minus(a, b):
    return tuple(x - y for x, y in zip(a, b))


def twist_seen_from(frame_pose, frame_twist, twist):
    """get_model_state / get_link_state: a world twist relative to frame F, in F's axes."""
    return (rotate_into(frame_pose, _minus(twist[0], frame_twist[0])),
            rotate_into(frame_pose, _minus(twist[1], frame_twist[1])))


def set_model_twist(frame_pose, twist):
    """set_model_state: a twist given in F's axes, in the world's."""
    return rotate_from(frame_pose, twist[0]), rotate_from(frame_pose, twist[1])


def set_link_twist(frame_twist, twist):
    """set_link_state: upstream subtracts the reference frame's twist, without rotating."""
    return _minus(twist[0], frame_twist[0]), _minus(twist[1], frame_twist[1])
