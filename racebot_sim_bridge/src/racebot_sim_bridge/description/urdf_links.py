"""A URDF's <link>s and <material>s read into urdf_model's dataclasses (part of urdf_reader.parse_urdf).

Pure Python: no rospy, no pybullet. A link's inertial, collisions and visuals, each shape checked as urdfdom
checks it; a visual's material looked up among the robot's named <material>s (RobotModel.materials), a missing
one warned about in RobotModel.warnings.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.geometry import ShapeKind
from racebot_sim_bridge.description.urdf_elements import attr_number, element_name, origin, vector
from racebot_sim_bridge.description.urdf_model import Geometry, Inertial, UrdfLink, RobotModel, UrdfError

__all__ = ['read_link', 'read_material', 'URDF_SHAPES']

# The shapes a URDF <geometry> may hold (urdfdom; a <plane> is SDF only).
URDF_SHAPES = (ShapeKind.BOX, ShapeKind.CYLINDER, ShapeKind.SPHERE, ShapeKind.MESH)


def read_material(model: RobotModel, elem: ET.Element, what: str) -> tuple[str, tuple | None]:
    """(name, rgba) of a <material>, its rgba looked up by name if it has no colour (None: unknown); a robot-level
    one with a colour is kept in the model's materials."""
    name = elem.get('name', '')
    color = elem.find('color')
    rgba = None
    if color is not None:
        rgba = vector(color.get('rgba'), 4,
                      "%s '%s' <color> rgba" % (what, name))
    if name and rgba is not None and name not in model.materials:
        model.materials[name] = rgba
    if rgba is None and name:
        rgba = model.materials.get(name)
    return name, rgba


def _geometry(model, elem, what, visual):
    xyz, rpy = origin(elem, what)
    geometry = elem.find('geometry')
    shapes = list(geometry) if geometry is not None else []
    if not shapes:
        raise UrdfError('%s has no <geometry> shape; add <geometry><box size="..."/>'
                        '</geometry> (or cylinder, sphere, mesh)' % what)
    shape = shapes[0]
    if shape.tag not in URDF_SHAPES:
        raise UrdfError('%s: unknown geometry <%s>; use box, cylinder, sphere or mesh'
                        % (what, shape.tag))
    result = Geometry(shape.tag, origin_xyz=xyz, origin_rpy=rpy, name=elem.get('name'))
    where = '%s <%s>' % (what, shape.tag)
    if shape.tag == 'box':
        result.size = vector(shape.get('size'), 3, where + ' size')
    elif shape.tag == 'cylinder':
        result.radius = attr_number(shape, 'radius', where, required=True)
        result.length = attr_number(shape, 'length', where, required=True)
    elif shape.tag == 'sphere':
        result.radius = attr_number(shape, 'radius', where, required=True)
    else:  # mesh
        result.filename = shape.get('filename')
        if not result.filename:
            raise UrdfError('%s has no filename attribute; add filename="package://..."'
                            % where)
        scale = shape.get('scale')
        result.scale = (1.0, 1.0, 1.0) if scale is None else vector(scale, 3,
                                                                    where + ' scale')
    if visual:
        material = elem.find('material')
        if material is not None:
            result.material, result.rgba = read_material(model, material, what + ' <material>')
            if result.rgba is None and material.find('texture') is None and result.material:
                model.warnings.append("%s: material '%s' is not defined at the robot level and has no "
                                      "<color>; drawn in the default colour" % (what, result.material))
    return result


def _inertial(inertial, what):
    mass = inertial.find('mass')
    if mass is None:
        raise UrdfError('%s <inertial> has no <mass>; add <mass value="..."/>' % what)
    xyz, rpy = origin(inertial, what + ' <inertial>')
    inertia = inertial.find('inertia')
    if inertia is None:
        raise UrdfError('%s <inertial> has no <inertia>; add <inertia ixx="..." ixy="0" '
                        'ixz="0" iyy="..." iyz="0" izz="..."/>' % what)
    values = {key: attr_number(inertia, key, what + ' <inertia>', required=True)
              for key in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')}
    return Inertial(attr_number(mass, 'value', what + ' <mass>', required=True), xyz, rpy, **values)


def read_link(model: RobotModel, elem: ET.Element) -> UrdfLink:
    """The Link of a <link>: inertial, collisions, visuals (materials of `model`, warnings into it)."""
    name = element_name(elem)
    what = "link '%s'" % name
    link = UrdfLink(name)
    inertial = elem.find('inertial')
    if inertial is not None:
        link.inertial = _inertial(inertial, what)
    for index, child in enumerate(elem.findall('collision')):
        link.collisions.append(_geometry(model, child, '%s <collision> #%d' % (what, index + 1),
                                         visual=False))
    for index, child in enumerate(elem.findall('visual')):
        link.visuals.append(_geometry(model, child, '%s <visual> #%d' % (what, index + 1),
                                      visual=True))
    return link
