"""The floor under a point, read from a world file: the highest collision surface a vertical ray meets below a
height. Pure (no ROS, no racebot): the world's SDF, its models' SDF and their collision meshes, read as Gazebo
reads them, so the corpus's `floor` check judges a robot's height against the world's own files.

Read: top-level <model>s and <include>s, models nested in models (<model> or <include>), every link's
<collision> with its <pose> chain (world <model>, <include>'s pose or the included model's own, link, collision);
geometries box, plane (infinite, as ODE's), sphere, cylinder (its flat ends and side) and mesh (COLLADA through
pycollada with its <unit meter>, STL/OBJ through trimesh, <scale>); model://, package:// (rospkg) and file://
URIs (a relative file:// in the model's folder, else on the resource path: gazebo_media_path, as Gazebo's
SystemPaths finds it). A mesh file that cannot be found or read is skipped and said (Gazebo loads such a model
without it).
"""
import math
import os
import xml.etree.ElementTree as ET

import numpy as np

GROUND_PLANE = 'model://ground_plane'  # Gazebo ships it: a static plane, normal +z, at its pose


def pose_matrix(text):
    """An SDF <pose> 'x y z roll pitch yaw' as a 4x4 matrix (rotation Rz(yaw) Ry(pitch) Rx(roll))."""
    values = [float(v) for v in (text or '').split()] if text and text.strip() else []
    x, y, z, roll, pitch, yaw = (values + [0.0] * 6)[:6]
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    m = np.eye(4)
    m[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    m[:3, 3] = [x, y, z]
    return m


def _pose(element):
    found = element.find('pose')
    return pose_matrix(found.text if found is not None else None)


class WorldCollisions:
    """The collision geometries of a world file, read once; height_at(x, y, below) asks for the floor under a point."""

    def __init__(self, path, model_paths, resource_paths=(), find_package=None):
        self.path = path
        self.model_paths = list(model_paths)
        self.resource_paths = list(resource_paths)  # where a relative file:// is looked for (gazebo_media_path)
        self.find_package = find_package
        self.notes = []
        self.shapes = []  # (name, kind, 4x4 world-from-shape, data)
        self._meshes = {}
        with open(path, 'rb') as f:
            root = ET.fromstring(f.read().strip())
        world = root.find('world')
        for child in world:
            if child.tag == 'model':
                self._model(child, np.eye(4), child.get('name'), os.path.dirname(path))
            elif child.tag == 'include':
                self._include(child, np.eye(4), None)

    # --- reading -------------------------------------------------------------------------------------

    def _model_dir(self, uri):
        name = uri.replace('model://', '', 1).strip('/')
        for root in self.model_paths:
            if os.path.isfile(os.path.join(root, name, 'model.config')):
                return os.path.join(root, name)
        return None

    def _include(self, include, parent, outer_name):
        uri = (include.findtext('uri') or '').strip()
        pose = include.find('pose')
        folder = self._model_dir(uri)
        if folder is None:
            if uri == GROUND_PLANE:
                at = parent @ pose_matrix(pose.text if pose is not None else None)
                self.shapes.append(((outer_name or 'ground_plane') + '::link::collision', 'plane', at, (0.0, 0.0, 1.0)))
            elif uri != 'model://sun':
                self.notes.append('%s not found on the model path' % uri)
            return
        config = ET.parse(os.path.join(folder, 'model.config')).getroot()
        sdf = os.path.join(folder, (config.findtext('sdf') or 'model.sdf').strip())
        model = ET.parse(sdf).getroot().find('model')
        if model is None:
            return  # a light
        name = (include.findtext('name') or '').strip() or model.get('name')
        if pose is not None:  # an <include>'s pose replaces the model's own
            at = parent @ pose_matrix(pose.text)
            self._model(model, at, '%s::%s' % (outer_name, name) if outer_name else name, folder, posed=True)
        else:
            self._model(model, parent, '%s::%s' % (outer_name, name) if outer_name else name, folder)

    def _model(self, model, parent, name, folder, posed=False):
        at = parent if posed else parent @ _pose(model)
        for link in model.findall('link'):
            link_at = at @ _pose(link)
            for collision in link.findall('collision'):
                geometry = collision.find('geometry')
                if geometry is None:
                    continue
                where = '%s::%s::%s' % (name, link.get('name'), collision.get('name'))
                self._geometry(geometry, link_at @ _pose(collision), where, folder)
        for nested in model.findall('model'):
            self._model(nested, at, '%s::%s' % (name, nested.get('name')), folder)
        for include in model.findall('include'):
            self._include(include, at, name)

    def _geometry(self, geometry, at, where, folder):
        for shape in geometry:
            if shape.tag == 'box':
                size = [float(v) for v in (shape.findtext('size') or '1 1 1').split()]
                self.shapes.append((where, 'box', at, np.array(size)))
            elif shape.tag == 'plane':
                normal = [float(v) for v in (shape.findtext('normal') or '0 0 1').split()]
                self.shapes.append((where, 'plane', at, tuple(normal)))
            elif shape.tag == 'sphere':
                self.shapes.append((where, 'sphere', at, float(shape.findtext('radius') or 1.0)))
            elif shape.tag == 'cylinder':
                self.shapes.append((where, 'cylinder', at, (float(shape.findtext('radius') or 1.0),
                                                            float(shape.findtext('length') or 1.0))))
            elif shape.tag == 'mesh':
                scale = [float(v) for v in (shape.findtext('scale') or '1 1 1').split()]
                path = self._mesh_path((shape.findtext('uri') or '').strip(), folder)
                triangles = self._triangles(path, where) if path else None
                if triangles is None:
                    if not path:
                        self.notes.append('%s: mesh %s not found' % (where, shape.findtext('uri')))
                    continue
                scaled = triangles * np.array(scale)
                points = scaled.reshape(-1, 3) @ at[:3, :3].T + at[:3, 3]
                self.shapes.append((where, 'mesh', np.eye(4), points.reshape(-1, 3, 3)))

    def _mesh_path(self, uri, folder):
        if uri.startswith('model://'):
            rest = uri[len('model://'):]
            model, _, inside = rest.partition('/')
            found = self._model_dir('model://' + model)
            path = os.path.join(found, inside) if found else None
        elif uri.startswith('package://') and self.find_package:
            package, _, inside = uri[len('package://'):].partition('/')
            path = os.path.join(self.find_package(package), inside)
        elif uri.startswith('file://'):  # relative: in the model's folder, else on Gazebo's resource path
            path = uri[len('file://'):]
            if not os.path.isabs(path):
                path = next((os.path.join(root, path) for root in [folder] + self.resource_paths
                             if os.path.isfile(os.path.join(root, path))), None)
        else:
            path = os.path.join(folder, uri)
        return path if path and os.path.isfile(path) else None

    def _triangles(self, path, where):
        if path in self._meshes:
            return self._meshes[path]
        try:
            if path.lower().endswith('.dae'):
                triangles = collada_triangles(path)
            else:
                import trimesh
                mesh = trimesh.load(path, force='mesh', process=False)
                triangles = np.asarray(mesh.triangles, dtype=float)
        except Exception as err:  # pycollada and trimesh raise many kinds on files they cannot read
            self.notes.append('%s: %s unreadable (%s)' % (where, os.path.basename(path), err))
            triangles = None
        self._meshes[path] = triangles
        return triangles

    # --- asking --------------------------------------------------------------------------------------

    def height_at(self, x, y, below):
        """(z, name) of the highest collision surface at (x, y) no higher than `below`, or (None, None)."""
        best, name = None, None
        for where, kind, at, data in self.shapes:
            for z in _heights(kind, at, data, x, y):
                if z <= below + 1e-9 and (best is None or z > best):
                    best, name = z, where
        return best, name


def collada_triangles(path):
    """Every triangle of a COLLADA file's scene, in metres (its <unit meter>), its nodes' transforms applied."""
    import collada
    mesh = collada.Collada(path, ignore=[collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError,
                                         collada.common.DaeIncompleteError])
    unit = float(getattr(mesh.assetInfo, 'unitmeter', None) or 1.0)
    parts = []
    scene = mesh.scene
    if scene is None:
        return np.zeros((0, 3, 3))
    for geometry in scene.objects('geometry'):
        for primitive in geometry.primitives():
            if isinstance(primitive, (collada.triangleset.BoundTriangleSet, collada.polylist.BoundPolylist,
                                      collada.polygons.BoundPolygons)):
                tris = primitive if isinstance(primitive, collada.triangleset.BoundTriangleSet) else \
                    primitive.triangleset()
                if len(tris.vertex_index):
                    parts.append(np.asarray(tris.vertex)[np.asarray(tris.vertex_index)])
    return np.concatenate(parts) * unit if parts else np.zeros((0, 3, 3))


def _heights(kind, at, data, x, y):
    """The z of every point where the vertical line through (x, y) meets a shape's surface."""
    if kind == 'mesh':
        return _mesh_heights(data, x, y)
    inverse = np.linalg.inv(at)
    origin = inverse @ np.array([x, y, 0.0, 1.0])
    direction = inverse[:3, :3] @ np.array([0.0, 0.0, 1.0])  # the line x, y, z = t, in the shape's frame
    o, d = origin[:3], direction
    ts = []
    if kind == 'plane':
        n = np.array(data, dtype=float)
        if abs(n @ d) > 1e-12:
            ts.append(-(n @ o) / (n @ d))
    elif kind == 'box':
        half = data / 2.0
        lo, hi = -math.inf, math.inf
        for i in range(3):
            if abs(d[i]) < 1e-12:
                if abs(o[i]) > half[i]:
                    return []
                continue
            a, b = (-half[i] - o[i]) / d[i], (half[i] - o[i]) / d[i]
            lo, hi = max(lo, min(a, b)), min(hi, max(a, b))
        if lo <= hi:
            ts += [lo, hi]
    elif kind == 'sphere':
        b, c = o @ d, o @ o - data * data
        disc = b * b - (d @ d) * c
        if disc >= 0:
            ts += [(-b - math.sqrt(disc)) / (d @ d), (-b + math.sqrt(disc)) / (d @ d)]
    elif kind == 'cylinder':
        radius, length = data
        for cap in (-length / 2.0, length / 2.0):
            if abs(d[2]) > 1e-12:
                t = (cap - o[2]) / d[2]
                p = o + t * d
                if p[0] ** 2 + p[1] ** 2 <= radius * radius:
                    ts.append(t)
        a = d[0] ** 2 + d[1] ** 2
        if a > 1e-12:
            b, c = o[0] * d[0] + o[1] * d[1], o[0] ** 2 + o[1] ** 2 - radius * radius
            disc = b * b - a * c
            for sign in (-1.0, 1.0):
                if disc >= 0:
                    t = (-b + sign * math.sqrt(disc)) / a
                    if abs(o[2] + t * d[2]) <= length / 2.0:
                        ts.append(t)
    return [float(t) for t in ts]  # t is the world z: the line is (x, y, t)


def _mesh_heights(triangles, x, y):
    """z where the vertical line through (x, y) crosses each triangle it crosses (barycentric in x-y)."""
    if not len(triangles):
        return []
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    v0, v1 = b[:, :2] - a[:, :2], c[:, :2] - a[:, :2]
    v2 = np.array([x, y]) - a[:, :2]
    den = v0[:, 0] * v1[:, 1] - v1[:, 0] * v0[:, 1]
    ok = np.abs(den) > 1e-15
    den = np.where(ok, den, 1.0)
    u = (v2[:, 0] * v1[:, 1] - v1[:, 0] * v2[:, 1]) / den
    v = (v0[:, 0] * v2[:, 1] - v2[:, 0] * v0[:, 1]) / den
    eps = 1e-9
    inside = ok & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps)
    z = a[:, 2] + u * (b[:, 2] - a[:, 2]) + v * (c[:, 2] - a[:, 2])
    return [float(h) for h in z[inside]]
