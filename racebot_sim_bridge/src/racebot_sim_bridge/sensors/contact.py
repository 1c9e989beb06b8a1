"""A contact sensor's contacts as Gazebo's ContactSensor and gazebo_ros_bumper report them.

Pure numpy: no rospy, no pybullet (contact_points.py reads PyBullet).
- Collision names: Gazebo names a URDF link's collisions as sdformat 9's URDF reader does: the
  k-th collision of link L is (its name attribute, or L) + '_collision' (+ '_k' for k > 0); a
  collision lumped in from a fixed child C keeps its name attribute or takes C's name, and comes
  after L's own, children in joint-name order (urdfdom's order), each followed by its own lumped
  children; a final name not starting with L gets the prefix L + '_fixed_joint_lump__'. So a
  bumper link lumped into base_link is 'base_link_fixed_joint_lump__bumper_collision_1'. The
  sensor's <contact><collision> names one of these (the lumped link's own default name,
  C_collision, is rewritten by sdformat to P_collision_C, which names nothing: the reader does that,
  description/sdf_reduction; Gazebo's bumper then reports nothing; so does this one, with a warning); a
  contact names it in full, model::link::collision.
- Which collision a contact point touches: PyBullet reports contacts per link, not per shape, so
  a point is given to the collision of its link whose surface it lies nearest to (boxes, spheres,
  cylinders exactly; a mesh by the distance to its origin).
- ContactState, per pair of collisions: positions and normals in the world frame (the normal
  pointing into the sensor's collision), depths (penetration, >= 0), and per point the wrench on
  the sensor's link, as Gazebo's ODE engine fills body_1_wrench: force and torque (about the
  link's centre of mass) rotated into the link's frame; total_wrench their sum. The frame_id is
  the plugin's frameName, but nothing is transformed into it (upstream does not either).
"""
from dataclasses import dataclass, field

import numpy as np

from racebot_sim_bridge.kinematics.rotations import compose, rotate_back

LUMP_PREFIX = '_fixed_joint_lump__'
COLLISION_SUFFIX = '_collision'


@dataclass
class NamedShape:
    """One collision of a link: its Gazebo name, its geometry and its pose in the link frame."""
    name: str
    kind: str                   # box, sphere, cylinder, mesh, plane
    size: tuple = None          # box full sizes
    radius: float = None
    length: float = None
    position: tuple = (0.0, 0.0, 0.0)
    orientation: tuple = (0.0, 0.0, 0.0, 1.0)


def urdf_collision_shapes(model, link):
    """[NamedShape] of the collisions Gazebo gives `link` (a link PyBullet keeps, with the links
    lumped into it), in sdformat's order, poses in `link`'s frame. `model`: urdf_model.RobotModel."""
    entries = _lumped_collisions(model, link)
    shapes = []
    for k, (name, geometry, pose) in enumerate(entries):
        full = (name or link) + COLLISION_SUFFIX + ('_%d' % k if k > 0 else '')
        if not full.startswith(link):
            full = link + LUMP_PREFIX + full
        shapes.append(NamedShape(full, geometry.kind, geometry.size, geometry.radius, geometry.length,
                                 tuple(pose[0]), tuple(pose[1])))
    return shapes


def _lumped_collisions(model, link):
    """[(name attribute, Geometry, pose in `link`)] of `link`'s own collisions, then those of the
    fixed children lumped into it (recursively), in urdfdom's joint-name order."""
    out = [(geometry.name or '', geometry, compose((0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                                                   tuple(geometry.origin_xyz) + tuple(geometry.origin_rpy)))
           for geometry in model.links[link].collisions]
    for joint in sorted(model.child_joints(link), key=lambda j: j.name):
        if model.lumped_link(joint.child) == joint.child:
            continue  # a moving joint, or a kept fixed one: its child stays a link
        offset = tuple(joint.origin_xyz) + tuple(joint.origin_rpy)
        for name, geometry, pose in _lumped_collisions(model, joint.child):
            if LUMP_PREFIX not in name:
                name = name or joint.child
            out.append((name, geometry, compose(offset, pose)))
    return out


def sdf_collision_shapes(link):
    """[NamedShape] of an sdf_model.SdfLink's collisions, poses in the link frame."""
    shapes = []
    for col in link.collisions:
        s = col.shape
        pose = compose((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), col.pose)
        shapes.append(NamedShape(col.name, s.kind, s.size, s.radius, s.length, tuple(pose[0]), tuple(pose[1])))
    return shapes


def surface_distance(shape, point):
    """Signed distance (m) from `point` (in the link frame) to the shape's surface; a mesh's is
    the distance to its origin (its geometry is not known here)."""
    p = np.asarray(rotate_back(shape.orientation, np.asarray(point, dtype=np.float64) - shape.position))
    if shape.kind == 'box' and shape.size is not None:
        q = np.abs(p) - np.asarray(shape.size, dtype=np.float64) / 2.0
        outside = np.linalg.norm(np.maximum(q, 0.0))
        return float(outside + min(max(q[0], q[1], q[2]), 0.0))
    if shape.kind == 'sphere' and shape.radius is not None:
        return float(np.linalg.norm(p) - shape.radius)
    if shape.kind == 'cylinder' and shape.radius is not None and shape.length is not None:
        d = np.array([np.hypot(p[0], p[1]) - shape.radius, abs(p[2]) - shape.length / 2.0])
        return float(min(max(d[0], d[1]), 0.0) + np.linalg.norm(np.maximum(d, 0.0)))
    if shape.kind == 'plane':
        return float(p[2])
    return float(np.linalg.norm(p))


def nearest_shape(shapes, point):
    """The shape of `shapes` whose surface `point` (link frame) lies nearest to; None for none."""
    if not shapes:
        return None
    if len(shapes) == 1:
        return shapes[0]
    return min(shapes, key=lambda s: abs(surface_distance(s, point)))


@dataclass(frozen=True)
class CollisionKind:
    """What decides which way round Bullet keeps a contact pair: the object's creation order
    ((body id, link index): bodies in order, a body's base before its links), whether its shape is
    a compound (a link of several collisions) and whether it is concave (a plane, a static mesh)."""
    order: tuple
    compound: bool
    concave: bool


def friction_reversed(ours, other):
    """True when PyBullet's friction forces of a contact between `ours` and `other`
    (CollisionKinds) act on `ours` reversed. getContactPoints turns the normal towards body A but
    leaves the friction directions as Bullet's manifold has them, and the manifold's first body
    gets +friction. Bullet puts first: the convex or compound side against a concave one; the
    compound side against a plain convex one; else the one created first (its broadphase proxy
    has the lower id). Measured in PyBullet 3.2.7 for boxes, compounds, URDF links with one and
    two collisions, against box, compound, plane and concave-mesh grounds, both creation orders
    (tests/unit/gazebo_plugins/test_sensor_plugins_sim.py checks it on real physics)."""
    if other.concave:
        return False
    if ours.compound != other.compound:
        return other.compound
    return other.order < ours.order


@dataclass
class ContactPoint:
    """One contact point on the sensor's link, all vectors in the world frame."""
    collision1: str          # the sensor's collision, model::link::collision
    collision2: str          # what it touches
    position: tuple
    normal: tuple            # unit, pointing into collision1
    depth: float             # penetration, >= 0
    force: tuple             # on collision1's link


@dataclass
class ContactGroup:
    """gazebo_msgs/ContactState's fields for one pair of collisions."""
    collision1: str
    collision2: str
    positions: list = field(default_factory=list)
    normals: list = field(default_factory=list)
    depths: list = field(default_factory=list)
    forces: list = field(default_factory=list)     # link frame
    torques: list = field(default_factory=list)    # link frame, about the link's centre of mass

    @property
    def total_force(self):
        return tuple(np.sum(self.forces, axis=0)) if self.forces else (0.0, 0.0, 0.0)

    @property
    def total_torque(self):
        return tuple(np.sum(self.torques, axis=0)) if self.torques else (0.0, 0.0, 0.0)


def group_contacts(points, link_com, link_orientation):
    """[ContactGroup] of contact points, one per (collision1, collision2) pair in first-seen
    order; wrenches about `link_com` (world) and rotated into the link frame (`link_orientation`,
    quaternion xyzw), as Gazebo's ODE engine fills body_1_wrench."""
    groups = {}
    com = np.asarray(link_com, dtype=np.float64)
    for p in points:
        key = (p.collision1, p.collision2)
        group = groups.get(key)
        if group is None:
            group = groups[key] = ContactGroup(p.collision1, p.collision2)
        force = np.asarray(p.force, dtype=np.float64)
        torque = np.cross(np.asarray(p.position, dtype=np.float64) - com, force)
        group.positions.append(tuple(float(v) for v in p.position))
        group.normals.append(tuple(float(v) for v in p.normal))
        group.depths.append(float(p.depth))
        group.forces.append(tuple(float(v) for v in rotate_back(link_orientation, force)))
        group.torques.append(tuple(float(v) for v in rotate_back(link_orientation, torque)))
    return list(groups.values())
