"""Mesh files, Gazebo model folders and ROS packages written by the tests themselves (no binary fixtures).

Used by tests/unit/description/test_meshes.py and tests/integration/meshes_test.py. trimesh writes the meshes; the
OBJ writer leaves normals out (they would need scipy) and the DAE gets its diffuse colour set here
(trimesh's exporter writes black).
"""
import os
import re
import xml.etree.ElementTree as ET

import trimesh
from trimesh.exchange.obj import export_obj


def box(size):
    return trimesh.creation.box(extents=size)


def cylinder(radius, length, sections=48):
    return trimesh.creation.cylinder(radius=radius, height=length, sections=sections)


def write_mesh(mesh, path, rgba=None):
    """Writes `mesh` as .stl, .obj or .dae (by the extension); a .dae gets `rgba` as its material colour."""
    ext = os.path.splitext(path)[1].lower()
    os.makedirs(os.path.dirname(path) or '.', exist_ok=True)
    if ext == '.obj':
        text = export_obj(mesh, include_normals=False, include_color=False, include_texture=False)
        with open(path, 'w') as f:
            f.write(text)
        return path
    data = mesh.export(file_type=ext[1:])
    if ext == '.dae':
        text = data.decode() if isinstance(data, bytes) else data
        if rgba is not None:
            colour = '<diffuse>\n              <color>%s</color>' % ' '.join('%g' % c for c in rgba)
            text = re.sub(r'<diffuse>\s*<color>[^<]*</color>', colour, text)
        data = text.encode()
    with open(path, 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    return path


def write_model(models_dir, name, sdf_model, sdf_file='model.sdf', config=True):
    """A Gazebo model folder models_dir/name with model.config naming `sdf_file`."""
    folder = os.path.join(models_dir, name)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, sdf_file), 'w') as f:
        f.write('<?xml version="1.0"?>\n<sdf version="1.6">%s</sdf>\n' % sdf_model)
    if config:
        with open(os.path.join(folder, 'model.config'), 'w') as f:
            f.write('<?xml version="1.0"?><model><name>%s</name><version>1.0</version>'
                    '<sdf version="1.6">%s</sdf></model>\n' % (name, sdf_file))
    return folder


def write_package(root, name, exports=''):
    """A minimal catkin package root/name (package.xml only: what rospkg needs to find it)."""
    folder = os.path.join(root, name)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, 'package.xml'), 'w') as f:
        f.write('<?xml version="1.0"?><package format="2"><name>%s</name><version>0.0.1</version>'
                '<description>racebot test fixture</description><maintainer email="t@example.com">t</maintainer>'
                '<license>BSD</license><buildtool_depend>catkin</buildtool_depend><export>%s</export></package>\n'
                % (name, exports))
    return folder


def meshify_urdf(urdf_xml, package_root, package='racebot_mesh_fixture'):
    """The URDF with every box and cylinder replaced by a mesh of the same shape in a package under
    package_root, named by package:// URIs: collisions as STL (cylinders) and OBJ (boxes, written at
    twice the size with scale 0.5), visuals as DAE. Returns (urdf text, number of meshes replaced)."""
    folder = write_package(package_root, package)
    root = ET.fromstring(urdf_xml)
    count = 0
    for link in root.findall('link'):
        for kind in ('collision', 'visual'):
            for elem in link.findall(kind):
                geometry = elem.find('geometry')
                shape = geometry[0] if geometry is not None and len(geometry) else None
                if shape is None or shape.tag not in ('box', 'cylinder'):
                    continue
                attrs = {}
                if shape.tag == 'box':
                    size = [float(v) for v in shape.get('size').split()]
                    if kind == 'collision':
                        name = 'box_%s.obj' % '_'.join('%g' % v for v in size)
                        mesh, attrs['scale'] = box([2 * v for v in size]), '0.5 0.5 0.5'
                    else:
                        name, mesh = 'box_%s.dae' % '_'.join('%g' % v for v in size), box(size)
                else:
                    r, length = float(shape.get('radius')), float(shape.get('length'))
                    name = 'cyl_%g_%g.%s' % (r, length, 'stl' if kind == 'collision' else 'dae')
                    mesh = cylinder(r, length)
                path = os.path.join(folder, 'meshes', name)
                if not os.path.exists(path):
                    write_mesh(mesh, path)
                geometry.remove(shape)
                ET.SubElement(geometry, 'mesh', filename='package://%s/meshes/%s' % (package, name), **attrs)
                count += 1
    return ET.tostring(root, encoding='unicode'), count
