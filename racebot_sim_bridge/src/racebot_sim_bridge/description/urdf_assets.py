"""A URDF's meshes and colours made concrete before PyBullet loads it.

No rospy, no pybullet. resolve_assets() gives the URDF (text, or its parsed tree) with
- every <mesh filename> (package://, file://, plain path; STL, OBJ, DAE) replaced by the absolute
  path of its checked OBJ in the mesh cache (meshes.convert); a mesh that cannot be found or read
  is left out with one warning per file naming the URI, the elements that use it, where it was looked for
  and a file there of that name in other capitals (Gazebo too loads the robot without it);
- every visual given its colour inline, in Gazebo's order of precedence: the link's
  <gazebo reference><material>Gazebo/Name</material>, else the URDF <material> colour (also one
  named at robot level), else the mesh file's own single colour, else none (PyBullet's default).
The RobotModel's Geometry entries are updated to match. The result names only absolute files, so
a copy of the robot in another process needs no ROS package path; resolving it again changes nothing.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import TYPE_CHECKING

from racebot_sim_bridge.description import meshes, model_path
from racebot_sim_bridge.description.materials import gazebo_material_rgba

if TYPE_CHECKING:
    from racebot_sim_bridge.description.urdf_model import RobotModel

__all__ = ['resolve_assets']


def resolve_assets(urdf: str | ET.Element, urdf_model: RobotModel,
                   warn: Callable[[str], None] | None = None) -> str | ET.Element:
    """Meshes resolved and colours inline; warn(message) for what was left out. `urdf`: the URDF text, whose
    resolved text is returned, or its root element (as parsed once per spawn), changed in place and returned."""
    warn = warn or (lambda message: None)
    root = urdf if isinstance(urdf, ET.Element) else ET.fromstring(urdf)
    failed = {}  # mesh filename -> (why, [the elements left out]): one warning per file
    for link_elem in root.findall('link'):
        name = link_elem.get('name')
        spec = urdf_model.links.get(name)
        if spec is None:
            continue
        gazebo_rgba = _gazebo_colour(urdf_model, name, warn)
        for kind, geometries in (('collision', spec.collisions), ('visual', spec.visuals)):
            elements = link_elem.findall(kind)
            kept = []
            for index, (elem, geometry) in enumerate(zip(elements, geometries)):
                mesh_rgba = None
                mesh = elem.find('geometry/mesh')
                if mesh is not None:
                    try:
                        if geometry.scale is not None and not all(geometry.scale):
                            raise meshes.MeshError('mesh %s: scale %s has a zero factor, which flattens it; give '
                                                   'factors other than 0' % (mesh.get('filename'), ' '.join(
                                                       '%g' % c for c in geometry.scale)))
                        path = model_path.resolve_uri(mesh.get('filename'))
                        converted = meshes.convert(path)
                    except (model_path.ResolveError, meshes.MeshError) as err:
                        failed.setdefault(mesh.get('filename'), (err, []))[1].append(
                            "link '%s' <%s> #%d" % (name, kind, index + 1))
                        link_elem.remove(elem)
                        continue
                    mesh.set('filename', converted.obj_path)
                    geometry.filename = converted.obj_path
                    mesh_rgba = converted.rgba
                if kind == 'visual':
                    rgba = gazebo_rgba or geometry.rgba or mesh_rgba
                    if rgba is not None:
                        _set_colour(elem, rgba, '%s_visual_%d' % (name, index))
                        geometry.rgba = tuple(rgba)
                kept.append(geometry)
            geometries[:] = kept
    for err, places in failed.values():  # Gazebo too loads the robot, its links, their inertia, without the mesh
        warn('%s: %s; left out (the robot is spawned without %s, its links keep their inertia)'
             % (', '.join(places), err, 'it' if len(places) == 1 else 'them'))
    return root if root is urdf else ET.tostring(root, encoding='unicode')


def _gazebo_colour(urdf_model, link, warn):
    name = urdf_model.gazebo_refs.get(link, {}).get('material')
    if not isinstance(name, str) or not name:
        return None
    rgba = gazebo_material_rgba(name)
    if rgba is None:
        message = ("<gazebo reference='%s'> material '%s' is not one of Gazebo's standard colours racebot "
                   "knows (e.g. Gazebo/Red, Gazebo/Grey); the link keeps its URDF colour" % (link, name))
        warn(message)
    return rgba


def _set_colour(visual, rgba, material_name):
    for old in visual.findall('material'):
        visual.remove(old)
    material = ET.SubElement(visual, 'material', name='racebot_%s' % material_name)
    ET.SubElement(material, 'color', rgba=' '.join('%g' % c for c in rgba))
