"""A URDF's <joint>s read into urdf_model's dataclasses, and the checks on them (part of urdf_reader.parse_urdf).

Pure Python: no rospy, no pybullet. A joint's type, links, origin, axis, limit, dynamics and mimic as urdfdom
reads them; then the links and joints checked to form one tree under one root link (urdfdom's initTree and
initRoot), and the <mimic> joints racebot drives checked (a loop refused, the others warned about).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.urdf_elements import attr_number, element_name, origin, vector
from racebot_sim_bridge.description.urdf_model import (
    JOINT_TYPES, Dynamics, UrdfJoint, Limit, Mimic, RobotModel, UrdfError)

__all__ = ['read_joint', 'check_tree', 'check_mimics']


def read_joint(elem: ET.Element) -> UrdfJoint:
    """The Joint of a <joint>; UrdfError for what urdfdom refuses."""
    name = element_name(elem)
    what = "joint '%s'" % name
    kind = elem.get('type')
    if kind not in JOINT_TYPES:
        raise UrdfError('%s has type %r; use one of %s'
                        % (what, kind, ', '.join(JOINT_TYPES)))
    ends = {}
    for tag in ('parent', 'child'):
        end = elem.find(tag)
        if end is None or not end.get('link'):
            raise UrdfError('%s has no <%s link="..."/>; add it' % (what, tag))
        ends[tag] = end.get('link')
    xyz, rpy = origin(elem, what)
    joint = UrdfJoint(name, kind, ends['parent'], ends['child'], xyz, rpy)
    axis = elem.find('axis')
    if axis is not None and axis.get('xyz') is not None and kind not in ('fixed', 'floating'):
        joint.axis = vector(axis.get('xyz'), 3, what + ' <axis> xyz')
        if not any(joint.axis):
            raise UrdfError('%s <axis> is the zero vector; give a direction, e.g. "0 1 0"'
                            % what)
    limit = elem.find('limit')
    if limit is not None:
        where = what + ' <limit>'
        joint.limit = Limit(attr_number(limit, 'lower', where, 0.0),
                            attr_number(limit, 'upper', where, 0.0),
                            attr_number(limit, 'effort', where, required=True),
                            attr_number(limit, 'velocity', where, required=True))
    elif kind in ('revolute', 'prismatic'):
        raise UrdfError('%s is %s but has no <limit>; add <limit lower="..." upper="..." '
                        'effort="..." velocity="..."/> or make it continuous' % (what, kind))
    dynamics = elem.find('dynamics')
    if dynamics is not None:
        where = what + ' <dynamics>'
        joint.dynamics = Dynamics(attr_number(dynamics, 'damping', where, 0.0),
                                  attr_number(dynamics, 'friction', where, 0.0))
    mimic = elem.find('mimic')
    if mimic is not None:
        where = what + ' <mimic>'
        if not mimic.get('joint'):
            raise UrdfError('%s has no joint attribute; add joint="the joint it follows"' % where)
        joint.mimic = Mimic(mimic.get('joint'), attr_number(mimic, 'multiplier', where, 1.0),
                            attr_number(mimic, 'offset', where, 0.0))
    return joint


def check_mimics(model: RobotModel) -> None:
    """Checks the <mimic> joints racebot drives (Gazebo 11 ignores them): one it cannot drive is warned
    about; a loop of them is refused, as no position satisfies it."""
    joints = model.joints
    for joint in joints.values():
        if joint.mimic is None:
            continue
        leader = joints.get(joint.mimic.joint)
        if leader is None:
            model.warnings.append("joint '%s' <mimic joint='%s'>: the URDF has no such joint; the joint moves "
                                  "freely, as in Gazebo" % (joint.name, joint.mimic.joint))
        elif joint.name not in model.mimics():
            model.warnings.append("joint '%s' (%s) <mimic joint='%s'> (%s): racebot drives a <mimic> only between "
                                  "revolute, continuous or prismatic joints; it is ignored, as Gazebo ignores it"
                                  % (joint.name, joint.type, leader.name, leader.type))
    mimics = model.mimics()
    for start in mimics:
        path = [start]
        while path[-1] in mimics:
            path.append(mimics[path[-1]].joint)
            if path[-1] in path[:-1]:
                loop = path[path.index(path[-1]):]
                if start == loop[0]:
                    raise UrdfError(
                        'the <mimic> joints form a loop (%s): racebot drives each <mimic> joint from the joint it '
                        'names (Gazebo 11 ignores <mimic>), and no position satisfies a loop; let one of them '
                        'mimic none' % ' mimics '.join("'%s'" % n for n in loop))
                break


def _parents(model):
    """{child link: its joint's name}, after checking that every joint joins two links of the model."""
    links, joints = model.links, model.joints
    parent_of = {}
    for joint in joints.values():
        for role, link in (('parent', joint.parent), ('child', joint.child)):
            if link not in links:
                raise UrdfError(
                    "joint '%s': %s link '%s' does not exist; add <link name=\"%s\"/> or "
                    'fix the joint\'s <%s link="..."/>'
                    % (joint.name, role, link, link, role))
        if joint.parent == joint.child:
            raise UrdfError("joint '%s' connects link '%s' to itself; its parent and child "
                            'must differ' % (joint.name, joint.child))
        if joint.child in parent_of:
            raise UrdfError("link '%s' is the child of two joints ('%s' and '%s'); a link "
                            'has at most one parent joint'
                            % (joint.child, parent_of[joint.child], joint.name))
        parent_of[joint.child] = joint.name
    return parent_of


def check_tree(model: RobotModel) -> None:
    """Checks that the links and joints form one tree and sets the model's root_link; UrdfError otherwise."""
    links = model.links
    if not links:
        raise UrdfError("robot '%s' has no links (so no root link); add at least one "
                        '<link name="..."/>' % model.name)
    parent_of = _parents(model)
    roots = [name for name in links if name not in parent_of]
    if not roots:
        raise UrdfError('no root link: every link is the child of a joint, so the joints '
                        'form a loop; remove a joint to make a tree')
    if len(roots) > 1:
        raise UrdfError('several root links (%s): every link but one must be the child of '
                        'a joint; connect them with joints (e.g. fixed ones)'
                        % ', '.join("'%s'" % r for r in roots))
    reached, stack = {roots[0]}, [roots[0]]
    while stack:
        for child in model.children(stack.pop()):
            if child not in reached:
                reached.add(child)
                stack.append(child)
    loose = [name for name in links if name not in reached]
    if loose:
        raise UrdfError('links %s are not connected to the root link %r: their joints form '
                        'a loop; remove a joint to make a tree'
                        % (', '.join("'%s'" % n for n in loose), roots[0]))
    model.root_link = roots[0]
