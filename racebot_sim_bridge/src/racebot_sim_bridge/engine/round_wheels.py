"""A faceted wheel mesh rolled as the round wheel its facets approximate: the cylinder of its tread.

No ROS, no PyBullet here: the URDF's collision elements are rewritten before loadURDF (bullet_urdf.py).

A wheel's collision mesh is a polygon around its axle: fetch_description's wheels are 53-gons (6.8 degrees a facet).
Rolled rigidly, a polygon's centre rises and falls by r (1 - cos(pi / n)) at each facet (0.11 mm for Fetch's
0.0603 m wheel) and lands on the next facet with an impact. Bullet's contacts are rigid, so a faceted wheel under a
heavy base chatters: Fetch driving at 0.5 m/s had no load on its wheels in 54 to 69 % of the 1 ms steps, its wheels
ran ahead of the ground while unloaded, and the base drove 20 % slower than its wheels turned (the corpus row's
drive check). More facets do not cure it: the same wheel resampled with 256 facets still took an impact at every
facet (every 3 steps). Gazebo's ODE collides the same facets, but through soft contacts: the surface's kp and kd
make each contact a spring and damper, and a wheel's `<minDepth>` (fetch.gazebo.xacro: 1 cm) lets it sink that far
with no push back (Gazebo's ODE, joints/contact.cpp: the depth corrected is the depth less min_depth), so a tenth
of a millimetre of facet never lifts the wheel off. racebot's contacts are rigid (kp and kd are not simulated,
COMING_FROM_GAZEBO.md), so the wheel is made round instead, as URDF cylinders already are (urdf_spawn.py,
URDF_USE_IMPLICIT_CYLINDER): the mesh becomes a true cylinder on the axle, of the mesh's largest radius, as wide as
its tread (where its profile lies within TREAD of that radius: a flat tyre's whole width, a crowned tyre's crown;
Fetch's 13 of its 90 mm). With that, Fetch drives 0.496 m/s with its wheels turning for 0.497 (the row's drive).
What it leaves out: the tyre's shoulders and sides, which touch only a wheel leaning over or meeting a wall, and
Bullet's 1 mm collision margin around a mesh's hull (a mesh wheel stood 1 mm higher than its radius).

What counts as a wheel: a collision mesh of the child link of a `continuous` joint, a link that carries no other
moving joint (an arm's roll link carries the rest of the arm), whose rolling height, the
mesh's extent from the axle in each direction square to it, varies by at most MAX_OUT_OF_ROUND of the largest
(a regular polygon of 10 sides or more, centred on the axle). A mesh off the axle, a box, a cam, a gear with few
teeth, a link of a limited revolute joint: left as they are.
"""
from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET

import numpy as np

from racebot_sim_bridge.description import urdf_elements
from racebot_sim_bridge.description.urdf_model import UrdfError
from racebot_sim_bridge.engine.one_sided_mesh import read_obj
from racebot_sim_bridge.kinematics.rotations import matrix, quaternion_to_rpy, rpy_to_quaternion

__all__ = ['MAX_OUT_OF_ROUND', 'TREAD', 'round_wheel_meshes', 'rolling_heights', 'tread']

MAX_OUT_OF_ROUND = 0.05  # a regular 10-gon's rolling height varies by 1 - cos(18 deg) = 4.9 %
TREAD = 0.01  # the tread: where the profile lies within 1 % of the largest radius (a flat tyre: all its width)
MIN_LENGTH = 1e-4  # m: the shortest cylinder written (a ball's tread is a ring)
_DIRECTIONS = 720  # directions square to the axle in which the rolling height is measured


def rolling_heights(points: np.ndarray, axis: np.ndarray, directions: int = _DIRECTIONS) -> np.ndarray:
    """The extent of `points` (N x 3) from the line through the origin along unit `axis`, in each of `directions`
    directions square to the axis: the height of the axle above flat ground as the body turns about it."""
    u = _unit_square_to(axis)
    w = np.cross(axis, u)
    angles = np.linspace(0.0, 2.0 * math.pi, directions, endpoint=False)
    dirs = np.outer(np.cos(angles), u) + np.outer(np.sin(angles), w)  # D x 3
    return (points @ dirs.T).max(axis=0)


def tread(points: np.ndarray, axis: np.ndarray) -> tuple[float, float, float]:
    """(radius, start, end) of the tread of `points` about the line through the origin along unit `axis`: the
    largest distance from the line, and the stretch along the axis where the profile (the largest distance at each
    position along it, its upper convex envelope: the profile of a convex body is concave) lies within TREAD of
    that radius."""
    s = points @ axis
    r = np.linalg.norm(points - np.outer(s, axis), axis=1)
    profile = np.array(_upper_envelope(s, r))
    radius = float(profile[:, 1].max())
    floor = radius * (1.0 - TREAD)
    inside = np.nonzero(profile[:, 1] >= floor)[0]
    first, last = inside[0], inside[-1]
    return radius, _crossing(profile, first, first - 1, floor), _crossing(profile, last, last + 1, floor)


def _crossing(profile, inside, outside, floor):
    """Where the profile's segment from point `inside` (at or above `floor`) to point `outside` (below it, if there
    is one) crosses `floor`."""
    if outside < 0 or outside >= len(profile):
        return float(profile[inside, 0])
    (s0, r0), (s1, r1) = profile[inside], profile[outside]
    return float(s0 + (s1 - s0) * (r0 - floor) / (r0 - r1))


def round_wheel_meshes(root: ET.Element) -> list[str]:
    """Each wheel mesh of a URDF root (lumped, meshes resolved to the mesh cache's OBJ files) replaced, in place,
    by its round wheel; the names of the links whose collisions changed."""
    links = {link.get('name'): link for link in root.findall('link')}
    # A wheel carries no moving part: fetch's wrist_roll_link turns on a continuous joint too, and holds the fingers.
    carriers = {j.find('parent').get('link') for j in root.findall('joint')
                if j.get('type') != 'fixed' and j.find('parent') is not None}
    changed = []
    for joint in root.findall('joint'):
        if joint.get('type') != 'continuous':
            continue
        child = joint.find('child')
        link = links.get(child.get('link')) if child is not None else None
        if link is None or link.get('name') in carriers:
            continue
        axis_elem = joint.find('axis')
        text = axis_elem.get('xyz') if axis_elem is not None else None
        try:  # urdfdom's default axis, 1 0 0
            axis = np.array((1.0, 0.0, 0.0) if text is None else urdf_elements.vector(text, 3, 'axis'))
        except UrdfError:
            continue
        if np.linalg.norm(axis) < 1e-9:
            continue
        axis = axis / np.linalg.norm(axis)
        rounded = False
        for collision in link.findall('collision'):
            mesh = collision.find('geometry/mesh')
            if mesh is not None and _round(collision, mesh, axis):
                rounded = True
        if rounded:
            changed.append(link.get('name'))
    return changed


def _round(collision: ET.Element, mesh: ET.Element, axis_in_link: np.ndarray) -> bool:
    """Replace one collision mesh by the cylinder of its tread when it is a wheel; whether it was."""
    path = mesh.get('filename') or ''
    if not path.endswith('.obj') or not os.path.isfile(path):
        return False
    try:  # as the URDF reader reads them (urdf_links)
        scale = np.array((1.0, 1.0, 1.0) if mesh.get('scale') is None else
                         urdf_elements.vector(mesh.get('scale'), 3, 'scale'))
        xyz, rpy = urdf_elements.origin(collision, 'collision')
    except UrdfError:  # the reader has warned of a malformed value; Bullet gets the mesh as it is
        return False
    xyz = np.array(xyz)
    vertices, _ = read_obj(path)
    if len(vertices) < 3:
        return False
    # The mesh in the link's frame, whose origin the axle goes through (the joint's frame is the child's).
    rotation = np.array(matrix(rpy_to_quaternion(*rpy)))
    points = (vertices * scale) @ rotation.T + xyz
    if not np.all(np.isfinite(points)):
        return False
    heights = rolling_heights(points, axis_in_link)
    if heights.max() <= 0.0 or (heights.max() - heights.min()) > MAX_OUT_OF_ROUND * heights.max():
        return False
    radius, start, end = tread(points, axis_in_link)
    length = max(end - start, MIN_LENGTH)
    centre = axis_in_link * (start + end) / 2.0
    for old in collision.findall('origin') + collision.findall('geometry'):
        collision.remove(old)
    ET.SubElement(collision, 'origin', xyz='%.9g %.9g %.9g' % tuple(centre),
                  rpy='%.9g %.9g %.9g' % quaternion_to_rpy(_z_onto(axis_in_link)))
    geometry = ET.SubElement(collision, 'geometry')
    ET.SubElement(geometry, 'cylinder', radius='%.9g' % radius, length='%.9g' % length)
    return True


def _z_onto(axis):
    """The unit quaternion (x, y, z, w) turning the z axis (a URDF cylinder's) onto unit `axis`."""
    z = np.array([0.0, 0.0, 1.0])
    k = np.cross(z, axis)
    sin, cos = np.linalg.norm(k), float(axis[2])
    if sin < 1e-12:
        return (0.0, 0.0, 0.0, 1.0) if cos > 0 else (1.0, 0.0, 0.0, 0.0)
    half = math.atan2(sin, cos) / 2.0
    k = k / sin * math.sin(half)
    return (float(k[0]), float(k[1]), float(k[2]), math.cos(half))


def _unit_square_to(axis):
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    return u / np.linalg.norm(u)


def _upper_envelope(s, r):
    """[(s, r)] of the upper convex envelope of the points (s_i, r_i), from the least s to the greatest (Andrew's
    monotone chain, upper half)."""
    order = np.lexsort((-r, s))
    hull = []
    for p in zip(s[order], r[order]):
        while len(hull) >= 2 and ((hull[-1][0] - hull[-2][0]) * (p[1] - hull[-2][1])
                                  - (hull[-1][1] - hull[-2][1]) * (p[0] - hull[-2][0])) >= 0.0:
            hull.pop()
        if hull and abs(p[0] - hull[-1][0]) < 1e-12:  # the same s: the larger r came first
            continue
        hull.append(p)
    return hull
