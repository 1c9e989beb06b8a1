"""An SDF robot model (sdf_model.SdfModel with joints, plugins or sensors) as the URDF this simulator spawns.

Pure Python: no rospy, no pybullet.  Gazebo simulates an SDF model's joints and runs its model plugins
and sensors; here those live on the URDF path (urdf_model, physics.spawn_urdf, the plugin and sensor
managers), so an SDF robot is written out as the URDF that path reads:

- each link with its inertial, visuals and collisions (meshes already converted by sdf_reader), its
  ODE friction and laser_retro as ``<gazebo reference>`` values, its ``<sensor>``s as written;
- each joint with the origin of its child in its parent, the axis in the child's frame, SDF's
  limits (none: ``continuous``, effort/velocity 0, which the hardware reads as unlimited) and dynamics;
  a fixed joint with ``preserveFixedJoint``, as Gazebo keeps an SDF fixed joint's child link (only its
  URDF reader lumps them);
- the model's ``<plugin>``s in a ``<gazebo>`` block, as written;
- a ``world`` root link when a joint names ``world`` as parent, or when the model is static (a
  fixed base, as Gazebo holds a static model); every link of a static model (or of a static nested model)
  that hangs from no joint is fixed to it.

URDF puts a joint's axis through its child's origin.  An SDF joint whose ``<pose>`` moves the axis off
the child's origin (sideways of the axis: along it changes nothing) gets its child's URDF frame moved
to the joint, and everything of that link moved back by as much, so the physics is Gazebo's; that
link's frame as the services report it is then the joint's (docs/COMING_FROM_GAZEBO.md lists this).

The links must form one tree under the joints, as URDF needs: ConversionError says which do not.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import NamedTuple

from racebot_sim_bridge.description.geometry import ShapeKind
from racebot_sim_bridge.description.sdf_model import SdfModel
from racebot_sim_bridge.kinematics.rotations import (as_transform, compose, inverse, quaternion_to_rpy, rotate,
                                                     rotate_back)

__all__ = ['ConversionError', 'Conversion', 'model_urdf']

WORLD = 'world'
IDENTITY = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


class ConversionError(ValueError):
    """The SDF model cannot be written as a URDF; the message says why and what to change."""


class Conversion(NamedTuple):
    root: ET.Element  # the URDF document's <robot> element: the spawn reads it as parsed, no text in between
    root_pose: tuple  # the URDF root's frame in the SDF model frame, (xyz, quaternion): where to spawn it
    warnings: list

    @property
    def urdf(self) -> str:
        """The URDF document as text."""
        return ET.tostring(self.root, encoding='unicode')


def _fmt(values):
    return ' '.join('%.17g' % v for v in values)


def _origin(parent_elem, transform):
    xyz, quat = as_transform(transform)
    ET.SubElement(parent_elem, 'origin', xyz=_fmt(xyz), rpy=_fmt(quaternion_to_rpy(quat)))


def _tree(model):
    """{child link: joint} after checking that the joints join every link in one tree."""
    names = {link.name for link in model.links}
    parent_joint = {}
    for joint in model.joints:
        for role, link in (('parent', joint.parent), ('child', joint.child)):
            if link not in names and not (role == 'parent' and link == WORLD):
                raise ConversionError("joint '%s' names %s link '%s', which model '%s' does not have (links: %s)"
                                      % (joint.name, role, link, model.name, ', '.join(sorted(names))))
        if joint.child in parent_joint:
            raise ConversionError("link '%s' is the child of two joints ('%s' and '%s'); a link hangs from one "
                                  "joint (URDF is a tree)" % (joint.child, parent_joint[joint.child].name, joint.name))
        if joint.parent == joint.child:
            raise ConversionError("joint '%s' joins link '%s' to itself" % (joint.name, joint.child))
        parent_joint[joint.child] = joint
    for link in names:  # a loop: walking up from a link comes back to it
        seen, node = set(), link
        while node in parent_joint:
            if node in seen:
                raise ConversionError("the joints of model '%s' form a loop through link '%s'; URDF is a tree: "
                                      "remove one joint of the loop" % (model.name, node))
            seen.add(node)
            node = parent_joint[node].parent
    roots = sorted(name for name in names if name not in parent_joint)
    # Links that hold still (a static model's, a static nested model's) are each fixed to the world: they need
    # no joint between them, as in Gazebo.
    if len(roots) > 1 and not all(model.link(name).is_static(model) for name in roots):
        raise ConversionError("the links of model '%s' are not all joined: %s hang from no joint. Join them "
                              "with joints (a fixed joint for links that do not move), or fix them to the world "
                              "with <parent>world</parent>" % (model.name, ', '.join(roots)))
    return parent_joint


def _shift(joint, child_rotation):
    """The move of ``joint``'s child's URDF frame to the joint: identity unless the joint's <pose>
    takes a revolute axis off the child's origin (sideways of the axis)."""
    if joint is None or joint.type != 'revolute':
        return IDENTITY
    offset, joint_rotation = as_transform(joint.pose)
    axis = _axis_in_child(joint, child_rotation)
    along = sum(o * a for o, a in zip(offset, axis))
    sideways = [o - along * a for o, a in zip(offset, axis)]
    if math.sqrt(sum(c * c for c in sideways)) < 1e-9:
        return IDENTITY
    return tuple(offset), (0.0, 0.0, 0.0, 1.0)


def _axis_in_child(joint, child_rotation):
    """The joint's unit axis in its child link's frame."""
    if joint.axis_in_model:
        axis = rotate_back(child_rotation, joint.axis)
    else:
        axis = rotate(as_transform(joint.pose)[1], joint.axis)
    norm = math.sqrt(sum(c * c for c in axis))
    return tuple(c / norm for c in axis)


def _geometry(parent_elem, shape):
    geometry = ET.SubElement(parent_elem, 'geometry')
    if shape.kind is ShapeKind.BOX:
        ET.SubElement(geometry, 'box', size=_fmt(shape.size))
    elif shape.kind is ShapeKind.CYLINDER:
        ET.SubElement(geometry, 'cylinder', radius='%.17g' % shape.radius, length='%.17g' % shape.length)
    elif shape.kind is ShapeKind.SPHERE:
        ET.SubElement(geometry, 'sphere', radius='%.17g' % shape.radius)
    else:
        ET.SubElement(geometry, 'mesh', filename=shape.filename, scale=_fmt(shape.scale or (1.0, 1.0, 1.0)))


def _shifted_sensor(xml, back):
    """A <sensor> element's XML with its <pose> (in the link frame) moved by ``back``."""
    if back == IDENTITY:
        return ET.fromstring(xml)
    sensor = ET.fromstring(xml)
    pose = sensor.find('pose')
    values = [float(v) for v in pose.text.split()] if pose is not None and (pose.text or '').strip() else [0.0] * 6
    xyz, quat = compose(back, values)
    if pose is None:
        pose = ET.SubElement(sensor, 'pose')
    pose.text = _fmt(tuple(xyz) + tuple(quaternion_to_rpy(quat)))
    return sensor


def _limits(joint):
    """URDF joint type and <limit> attributes of an SDF revolute or prismatic joint."""
    unbounded = joint.lower <= -1e15 and joint.upper >= 1e15
    kind = 'continuous' if joint.type == 'revolute' and unbounded else joint.type
    attrs = {'effort': '%.17g' % max(joint.effort, 0.0), 'velocity': '%.17g' % max(joint.velocity, 0.0)}
    if kind != 'continuous':
        attrs['lower'], attrs['upper'] = '%.17g' % max(joint.lower, -1e15), '%.17g' % min(joint.upper, 1e15)
    return kind, attrs


def _write_link(robot, model, link, back, warnings):
    """`link` as a URDF <link> of `robot` (its inertial, visuals and collisions moved by `back`), and its friction,
    laser_retro and sensors as a <gazebo reference> block."""
    name = link.name
    elem = ET.SubElement(robot, 'link', name=name)
    inertial = ET.SubElement(elem, 'inertial')
    _origin(inertial, compose(back, link.inertial_pose))
    ET.SubElement(inertial, 'mass', value='%.17g' % link.mass)
    ixx, ixy, ixz, iyy, iyz, izz = link.inertia or (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)  # SDF's defaults
    ET.SubElement(inertial, 'inertia', ixx='%.17g' % ixx, ixy='%.17g' % ixy, ixz='%.17g' % ixz,
                  iyy='%.17g' % iyy, iyz='%.17g' % iyz, izz='%.17g' % izz)
    for tag, items in (('visual', link.visuals), ('collision', link.collisions)):
        for item in items:
            if item.shape.kind is ShapeKind.PLANE:
                warnings.append("model '%s' link '%s' %s '%s': a plane cannot be part of a robot; left out"
                                % (model.name, name, tag, item.name))
                continue
            part = ET.SubElement(elem, tag, name=item.name)
            _origin(part, compose(back, item.pose))
            _geometry(part, item.shape)
            if tag == 'visual' and item.rgba is not None:
                material = ET.SubElement(part, 'material', name='%s_%s' % (name, item.name))
                ET.SubElement(material, 'color', rgba=_fmt(item.rgba))
    extension = ET.Element('gazebo', reference=name)
    friction = next((c for c in link.collisions if c.mu is not None or c.mu2 is not None), None)
    if friction is not None:
        for tag, value in (('mu1', friction.mu), ('mu2', friction.mu2)):
            if value is not None:
                ET.SubElement(extension, tag).text = '%.17g' % value
    retro = next((c.laser_retro for c in link.collisions if c.laser_retro), 0.0)
    if retro:
        ET.SubElement(extension, 'laserRetro').text = '%.17g' % retro
    for sensor in link.sensors:
        extension.append(_shifted_sensor(sensor, back))
    if len(extension):
        robot.append(extension)


def _write_joint(robot, joint, frame, pose):
    """An SDF joint as a URDF <joint> of `robot` between its links' URDF frames (`frame`, in the model frame),
    its axis in the child's frame (the child link's SDF `pose`); a fixed one kept by preserveFixedJoint."""
    elem = ET.SubElement(robot, 'joint', name=joint.name, type=joint.type)
    ET.SubElement(elem, 'parent', link=joint.parent)
    ET.SubElement(elem, 'child', link=joint.child)
    _origin(elem, compose(inverse(frame[joint.parent]), frame[joint.child]))
    if joint.type == 'fixed':
        # Gazebo keeps an SDF fixed joint and its child link (only its URDF reader lumps them)
        preserve = ET.SubElement(robot, 'gazebo', reference=joint.name)
        ET.SubElement(preserve, 'preserveFixedJoint').text = 'true'
        return
    kind, limit = _limits(joint)
    elem.set('type', kind)
    ET.SubElement(elem, 'axis', xyz=_fmt(_axis_in_child(joint, pose[joint.child][1])))
    ET.SubElement(elem, 'limit', **limit)
    if joint.damping or joint.friction:
        ET.SubElement(elem, 'dynamics', damping='%.17g' % joint.damping, friction='%.17g' % joint.friction)


def model_urdf(model: SdfModel) -> Conversion:
    """The Conversion of an sdf_model.SdfModel; ConversionError when its links do not form one tree."""
    if not model.links:
        raise ConversionError("model '%s' has no link" % model.name)
    warnings = []
    parent_joint = _tree(model)
    links = {link.name: link for link in model.links}
    pose = {name: as_transform(link.pose) for name, link in links.items()}
    shift = {name: _shift(parent_joint.get(name), pose[name][1]) for name in links}
    frame = {name: compose(pose[name], shift[name]) for name in links}  # each URDF link frame, model frame
    frame[WORLD] = IDENTITY
    root = next((name for name in links if name not in parent_joint), None)  # None: all hang from the world
    fixed_to_world = model.static or any(j.parent == WORLD for j in model.joints) or any(
        link.is_static(model) for name, link in links.items() if name not in parent_joint)

    robot = ET.Element('robot', name=model.name)
    if fixed_to_world:
        ET.SubElement(robot, 'link', name=WORLD)
    for name, link in links.items():
        _write_link(robot, model, link, inverse(shift[name]), warnings)
    held = [name for name, link in links.items() if name not in parent_joint and link.is_static(model)]
    for index, name in enumerate(held):
        joint_name = '%s_static' % model.name if index == 0 else '%s_static_%s' % (model.name, name)
        elem = ET.SubElement(robot, 'joint', name=joint_name, type='fixed')
        ET.SubElement(elem, 'parent', link=WORLD)
        ET.SubElement(elem, 'child', link=name)
        _origin(elem, frame[name])
    for joint in model.joints:
        _write_joint(robot, joint, frame, pose)
    if model.plugins:
        extension = ET.SubElement(robot, 'gazebo')
        for plugin in model.plugins:
            extension.append(ET.fromstring(plugin))
    root_pose = IDENTITY if fixed_to_world else frame[root]
    return Conversion(robot, root_pose, warnings)
