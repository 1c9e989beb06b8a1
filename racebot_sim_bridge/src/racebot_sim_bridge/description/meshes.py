"""Mesh files (STL, OBJ, COLLADA .dae) checked and converted to what PyBullet reads safely.

No rospy, no pybullet. trimesh (with pycollada for .dae) reads the file; the result is written
as a plain Wavefront OBJ into a cache folder, one `o` object per mesh part of the file, and that
OBJ is what PyBullet loads. So PyBullet's own C++ loaders never see a user's file (a malformed one
must give a message, not a crash), .dae works everywhere (PyBullet's createCollisionShape reads
no .dae), and a copy of the world in another process needs only the cached file's path.

How PyBullet then uses the OBJ (physics.py): a static body collides with the exact triangles
(concave triangle mesh); a dynamic one with one convex hull per part, so a concave dynamic
mesh should be made of convex parts (separate objects or geometries in the file).

Limits (MeshError beyond them): MAX_FILE_BYTES of file, MAX_TRIANGLES in all parts.
The cache is $RACEBOT_MESH_CACHE, else $ROS_HOME/racebot_mesh_cache (~/.ros/...), keyed by
the file's content, so an edited mesh is converted again.
"""
from __future__ import annotations

import hashlib
import json
import os
import tempfile
from collections.abc import Mapping

import numpy as np

from racebot_sim_bridge.description.materials import Rgba

__all__ = ['MeshError', 'MAX_FILE_BYTES', 'MAX_TRIANGLES', 'FORMATS', 'ConvertedMesh', 'cache_dir',
           'convert', 'read_parts']

MAX_FILE_BYTES = 64 * 1024 * 1024
MAX_TRIANGLES = 1000000
FORMATS = {'.stl': 'stl', '.obj': 'obj', '.dae': 'dae'}
_CONVERTER_VERSION = '2'  # part of the cache key: bump when the written OBJ changes


class MeshError(ValueError):
    """A mesh file cannot be used; the message names it and says what to do."""


class ConvertedMesh(tuple):
    """(obj_path, rgba or None, triangles): the cached OBJ and the file's own colour, when it
    gives one colour (a .dae material's diffuse colour or an .obj's .mtl Kd)."""
    __slots__ = ()

    def __new__(cls, obj_path, rgba, triangles):
        return tuple.__new__(cls, (obj_path, rgba, triangles))

    obj_path = property(lambda self: self[0])
    rgba = property(lambda self: self[1])
    triangles = property(lambda self: self[2])


def cache_dir(environ: Mapping[str, str] | None = None) -> str:
    environ = os.environ if environ is None else environ
    folder = environ.get('RACEBOT_MESH_CACHE')
    if not folder:
        ros_home = environ.get('ROS_HOME') or os.path.join(environ.get('HOME') or os.path.expanduser('~'), '.ros')
        folder = os.path.join(ros_home, 'racebot_mesh_cache')
    return os.path.abspath(os.path.expanduser(folder))


def _check_file(path):
    ext = os.path.splitext(path)[1].lower()
    if ext not in FORMATS:
        raise MeshError("mesh %s: format '%s' is not supported; convert it to STL, OBJ or COLLADA (.dae)"
                        % (path, ext or '(no extension)'))
    try:
        size = os.path.getsize(path)
    except OSError as err:
        raise MeshError('mesh %s cannot be read: %s' % (path, err.strerror))
    if size == 0:
        raise MeshError('mesh %s is an empty file; export the mesh again' % path)
    if size > MAX_FILE_BYTES:
        raise MeshError('mesh %s is %.0f MB, more than the %d MB racebot loads; simplify it (e.g. Blender\'s '
                        'Decimate modifier) to fewer triangles' % (path, size / 1e6, MAX_FILE_BYTES // 2 ** 20))
    return ext


def read_parts(path: str) -> tuple[list[tuple[np.ndarray, np.ndarray]], Rgba | None]:
    """([(vertices N x 3 float, faces M x 3 int)], rgba or None) of a mesh file, in its own frame
    (a .dae's node transforms applied). MeshError for anything unusable."""
    ext = _check_file(path)
    try:
        import trimesh
        scene = trimesh.load(path, file_type=FORMATS[ext], force='scene', process=False)
        placed = _placed(scene)
        unit = _metres_per_unit(scene) if ext == '.dae' else 1.0
    except MeshError:
        raise
    except Exception as err:  # trimesh and pycollada raise many kinds on malformed files
        raise MeshError('mesh %s could not be read as %s: %s: %s; check that the file is a valid mesh '
                        '(open it in Blender or MeshLab)' % (path, FORMATS[ext].upper(), type(err).__name__,
                                                              str(err)[:200]))
    parts, triangles = [], 0
    for vertices, faces, _ in placed:
        vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3) * unit
        faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
        if not len(faces):
            continue  # points or lines: nothing to collide with or draw
        if not np.isfinite(vertices).all():
            raise MeshError('mesh %s has vertices that are not finite numbers; export it again' % path)
        if faces.min() < 0 or faces.max() >= len(vertices):
            raise MeshError('mesh %s has faces naming vertices that do not exist; export it again' % path)
        triangles += len(faces)
        if triangles > MAX_TRIANGLES:
            raise MeshError('mesh %s has more than %d triangles, the most racebot loads; simplify it (e.g. '
                            "Blender's Decimate modifier)" % (path, MAX_TRIANGLES))
        parts.append((vertices, faces))
    if not parts:
        raise MeshError('mesh %s contains no triangles; export the surface as triangles' % path)
    if max(float(np.ptp(v, axis=0).max()) for v, _ in parts) <= 0.0:
        raise MeshError('mesh %s is degenerate (all vertices at one point)' % path)
    return parts, _single_colour([mesh for _, _, mesh in placed])


def _placed(scene):
    """[(vertices, faces, mesh)] of each instance of a triangle mesh in the scene, moved to its place as
    trimesh's Scene.dump moves it (Trimesh.apply_transform: the same points; faces reversed where the transform
    mirrors), without dump's copies: copying a mesh copies its visual, which decodes every texture image (40 % of
    a cold start of a textured world), and racebot uses none. Points and paths (no faces) are left out."""
    from trimesh import transformations, util
    placed = []
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        mesh = scene.geometry[name]
        if not hasattr(mesh, 'faces'):
            continue
        vertices, faces = mesh.vertices, mesh.faces
        matrix = np.asanyarray(transform, order='C', dtype=np.float64)
        if not util.allclose(matrix, _IDENTITY4, 1e-8):
            vertices = transformations.transform_points(vertices, matrix=matrix)
            if not util.allclose(matrix[:3, :3], _IDENTITY4[:3, :3], atol=1e-6) and \
                    transformations.flips_winding(matrix):
                faces = np.fliplr(faces)
        placed.append((vertices, faces, mesh))
    return placed


_IDENTITY4 = np.eye(4)


def _metres_per_unit(scene):
    """A .dae's <unit meter="0.0254"/> (trimesh reports it as '0.0254 * meters'), which Gazebo applies."""
    units = getattr(scene, 'units', None)
    if isinstance(units, str) and units.endswith('* meters'):
        try:
            value = float(units.split('*')[0])
        except ValueError:
            return 1.0
        return value if value > 0 and np.isfinite(value) else 1.0
    return 1.0


def _single_colour(meshes):
    """The one diffuse colour the file's materials give, or None (several, textured or none)."""
    colours = set()
    for mesh in meshes:
        material = getattr(getattr(mesh, 'visual', None), 'material', None)
        if material is None:
            continue
        if getattr(material, 'image', None) is not None or getattr(material, 'baseColorTexture', None) is not None:
            return None
        colour = getattr(material, 'baseColorFactor', None)
        if colour is None:
            colour = getattr(material, 'diffuse', None)
        if colour is None:
            continue
        colour = np.asarray(colour, dtype=np.float64).ravel()
        if colour.max() > 1.0:
            colour = colour / 255.0
        if len(colour) == 3:
            colour = np.append(colour, 1.0)
        colours.add(tuple(round(float(c), 4) for c in colour[:4]))
    return colours.pop() if len(colours) == 1 else None


def convert(path: str) -> ConvertedMesh:
    """The ConvertedMesh of a mesh file, converting it once into the cache (a file already in
    the cache is returned as it is)."""
    path = os.path.abspath(path)
    cache = cache_dir()
    if os.path.dirname(path) == cache and path.endswith('.obj'):
        return _cached(path)
    _check_file(path)
    digest = hashlib.sha256(_CONVERTER_VERSION.encode())
    with open(path, 'rb') as handle:
        for block in iter(lambda: handle.read(1 << 20), b''):
            digest.update(block)
    digest.update(os.path.splitext(path)[1].lower().encode())  # the same bytes as .obj and .stl differ
    target = os.path.join(cache, digest.hexdigest()[:32] + '.obj')
    if os.path.isfile(target) and os.path.isfile(target + '.json'):
        return _cached(target)
    parts, rgba = read_parts(path)
    os.makedirs(cache, exist_ok=True)
    lines, offset = ['# converted by racebot from %s' % path], 1
    for i, (vertices, faces) in enumerate(parts):
        lines.append('o part%d' % i)
        lines.extend('v %.9g %.9g %.9g' % tuple(v) for v in vertices)
        lines.extend('f %d %d %d' % tuple(f) for f in faces + offset)
        offset += len(vertices)
    triangles = sum(len(f) for _, f in parts)
    # Written under temporary names, then renamed: a concurrent reader never sees half a file.
    _write_atomic(target + '.json', json.dumps({'source': path, 'rgba': rgba, 'triangles': triangles}))
    _write_atomic(target, '\n'.join(lines) + '\n')
    return ConvertedMesh(target, rgba, triangles)


def _cached(target):
    try:
        with open(target + '.json') as handle:
            info = json.load(handle)
    except (OSError, ValueError):
        info = {}
    rgba = info.get('rgba')
    return ConvertedMesh(target, tuple(rgba) if rgba else None, info.get('triangles'))


def _write_atomic(path, text):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix='.tmp_')
    with os.fdopen(fd, 'w') as handle:
        handle.write(text)
    os.replace(tmp, path)
