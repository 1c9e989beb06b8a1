"""Gazebo's fixed-joint lumping, applied to the URDF that PyBullet loads.

No rospy, no pybullet. Gazebo (sdformat's URDF reader) merges a link hanging on a fixed joint into
its parent: its collisions, visuals and mass move there and its frame is gone. A fixed joint whose
``<gazebo reference="JOINT">`` sets preserveFixedJoint (or the older disableFixedJointLumping) is
kept, and its child stays a link of its own, with a pose of its own.

PyBullet's URDF_MERGE_FIXED_LINKS merges every fixed joint and cannot keep one, so the simulator
lumps here instead, with urdf_model's rule (``RobotModel.lumped_link``), and lets PyBullet load
what is left: a kept fixed joint becomes one of PyBullet's fixed links, rigid in its multibody.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

import numpy as np

from racebot_sim_bridge.description import urdf_elements
from racebot_sim_bridge.kinematics.rotations import compose, matrix, quaternion_to_rpy

if TYPE_CHECKING:
    from racebot_sim_bridge.description.urdf_model import RobotModel

__all__ = ['lump_fixed_links']


def lump_fixed_links(robot: ET.Element, model: RobotModel) -> None:
    """Merges in place, in the <robot> element `robot` of urdf_model.RobotModel `model`, every link
    Gazebo lumps into the link it is lumped into: collisions and visuals moved with their origins
    composed, inertials combined (mass, centre of mass, inertia tensor about it), the joints below
    re-attached to that link; the merged links and their fixed joints removed."""
    merged = [name for name in model.links if model.lumped_link(name) != name]
    if not merged:
        return
    links = {elem.get('name'): elem for elem in robot.findall('link')}
    joints = {elem.get('name'): elem for elem in robot.findall('joint')}
    inertials = {}  # lumped link -> [(mass, centre of mass, inertia tensor about it), ...] in its frame
    for name in merged:
        target = model.lumped_link(name)
        offset = model.pose_in_lumped_link(name)
        source, destination = links[name], links[target]
        for tag in ('collision', 'visual'):
            for elem in source.findall(tag):
                _set_origin(elem, compose(offset, _origin(elem)))
                source.remove(elem)
                destination.append(elem)
        if model.links[name].inertial is not None:
            inertials.setdefault(target, []).append(_inertial_in(model.links[name].inertial, offset))
        for joint in model.child_joints(name):
            if joint.child in merged:
                continue  # lumped too: removed with its child
            elem = joints[joint.name]
            elem.find('parent').set('link', target)
            _set_origin(elem, compose(offset, joint.origin_xyz + joint.origin_rpy))
        robot.remove(source)
        robot.remove(joints[model.parent_joint(name).name])
    for target, parts in inertials.items():
        own = model.links[target].inertial
        if own is not None and own.mass == 0.0 and model.parent_joint(target) is None:
            continue  # a massless root is PyBullet's fixed base: it stays so, as PyBullet's own merge keeps it
        if own is not None:
            parts.insert(0, _inertial_in(own, ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))))
        _write_inertial(links[target], *_combine(parts))


def _origin(elem):
    """The 6-tuple <origin> of a URDF element, read as the URDF reader reads it (which has validated it already)."""
    xyz, rpy = urdf_elements.origin(elem, '<%s>' % elem.tag)
    return xyz + rpy


def _set_origin(elem, transform):
    origin = elem.find('origin')
    if origin is None:
        origin = elem.makeelement('origin', {})
        elem.insert(0, origin)
    xyz, quaternion = transform
    origin.set('xyz', ' '.join(repr(float(v)) for v in xyz))
    origin.set('rpy', ' '.join(repr(float(v)) for v in quaternion_to_rpy(quaternion)))


def _inertial_in(inertial, offset):
    """(mass, centre of mass, inertia tensor about it) of an urdf_model.Inertial, in the frame in
    which its link's frame sits at `offset` ((xyz, quaternion))."""
    xyz, quaternion = compose(offset, inertial.origin_xyz + inertial.origin_rpy)
    rotation = np.array(matrix(quaternion))
    tensor = np.array([[inertial.ixx, inertial.ixy, inertial.ixz],
                       [inertial.ixy, inertial.iyy, inertial.iyz],
                       [inertial.ixz, inertial.iyz, inertial.izz]])
    return inertial.mass, np.array(xyz), rotation @ tensor @ rotation.T


def _combine(parts):
    """One rigid body of several: total mass, common centre of mass, inertia about it (parallel axes)."""
    mass = sum(m for m, _, _ in parts)
    if mass <= 0.0:
        return mass, parts[0][1], sum(t for _, _, t in parts)
    centre = sum(m * c for m, c, _ in parts) / mass
    tensor = np.zeros((3, 3))
    for m, c, t in parts:
        d = c - centre
        tensor += t + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return mass, centre, tensor


def _write_inertial(link, mass, centre, tensor):
    for old in link.findall('inertial'):
        link.remove(old)
    inertial = link.makeelement('inertial', {})
    link.insert(0, inertial)
    inertial.append(inertial.makeelement('origin', {
        'xyz': ' '.join(repr(float(v)) for v in centre), 'rpy': '0 0 0'}))
    inertial.append(inertial.makeelement('mass', {'value': repr(float(mass))}))
    inertial.append(inertial.makeelement('inertia', {
        key: repr(float(tensor[i, j])) for key, (i, j) in (
            ('ixx', (0, 0)), ('ixy', (0, 1)), ('ixz', (0, 2)), ('iyy', (1, 1)), ('iyz', (1, 2)), ('izz', (2, 2)))}))
