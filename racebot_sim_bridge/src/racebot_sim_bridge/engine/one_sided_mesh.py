"""A static mesh's triangles made one-sided, as ODE's trimesh colliders treat them, for Bullet.

No ROS here. ODE (Gazebo classic's engine) collides a shape with a trimesh triangle by triangle, and a triangle
pushes only towards its front (the side its normal, by the winding, points to): dCollideBTL takes the triangle's
normal as a separating axis that is never flipped (collision_trimesh_box.cpp, _cldTestNormal), so a box whose centre
is behind a face is pushed out through the front; a cylinder whose centre is behind a face gets no contact from it
(collision_cylinder_trimesh.cpp: "Sphere must be over positive side of triangle"). Bullet's triangle mesh is
two-sided: a shape is pushed out on the side its centre is on. A robot spawned where a link's centre starts just
below the top of a closed floor mesh (a COLLADA box floor posed below z = 0, a race track's slab) is therefore held
from above by the top face, against the pushes from below on its other links: it stands there and its wheels spin
in place, where Gazebo lifts it onto the floor.

Here each triangle becomes a convex prism: the triangle itself, extruded backwards (against its normal) halfway
to the mesh's next face behind it (rays cast from the triangle backwards, at most MAX_DEPTH; OPEN_DEPTH where
nothing is behind it: an open surface). A shape that has sunk into a face from the front is pushed out through the
front, as by ODE, as long as its centre is less deep than the prism (deeper inside a closed mesh, the nearest face
pushes it out); nothing stands outside the mesh's volume where the mesh is closed. PyBullet builds one convex
hull per OBJ object (`o`), so the prisms are written as one OBJ, one object each, cached beside the converted mesh
(keyed by it and the scale); static bodies only.

A model spawned deeper into such a floor than its prisms reach (a robot spawned at z = 0 onto a race track's 10 cm
slab: its wheels' centres lie behind the top face, inside the bottom face's prism) is held there by Bullet's
nearest-face pushes. ODE pushes it up: each face pushes a box that crosses its plane out through its front, and
gives a cylinder or sphere whose centre is behind it nothing, so the links that cross the top face lift the model
until its wheels stand on it. lift_onto_floor does that at the spawn: the model is raised straight up onto the top
face that crosses it (PhysicsWorld.spawn_urdf; its spawn pose is then the lifted one).
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Sequence

import numpy as np
import pybullet as pb

from racebot_sim_bridge.description import meshes
from racebot_sim_bridge.engine.pybullet_client import PybulletClient

MAX_DEPTH = 1.0  # m: the deepest a prism goes into a closed mesh's volume
OPEN_DEPTH = 0.05  # m: behind a face with nothing of the mesh behind it (an open surface)
MIN_DEPTH = 1e-4  # m: a face with another just behind it (a sheet) stays a flat slab
MARGIN = 0.001  # m: PyBullet's collision margin around a convex hull: the prism's front is set back by it
# Beyond: the plain two-sided triangle mesh. A prism costs PyBullet about 3.4 KB (a convex hull with its polyhedral
# features): the bench's generated big world (90 static meshes, 139,412 triangles) held 163 MB as triangle meshes,
# 630 MB as prisms, 276 MB with this limit. The collision meshes worlds give robots to stand on are small: the AWS
# bookstore's, warehouse's and racetrack's hold 28 to 1,418 triangles each.
MAX_TRIANGLES = 2000
SUNK = 0.002  # m: a model whose lowest point starts this far below a one-sided floor's top is lifted onto it
FLOOR_NORMAL_Z = 0.7  # a face whose normal points this much up is a floor's top
FOOTPRINT_RAYS = 5  # per side: rays cast down over a model's footprint find the top faces under it
_VERSION = '4'  # part of the cache key: bump when the written prisms change
_RAY_BATCH = 8192  # PyBullet 3.2.7 refuses more than 16384 rays and answers 16383 of a batch of 16384


def prism_mesh(path: str, scale: Sequence[float] | None) -> str | None:
    """The path of the cached OBJ of one-sided prisms for a mesh file (STL, OBJ, COLLADA; the mesh cache's OBJ as
    it is) at `scale`, in metres (to be loaded with scale 1), or None when the mesh has more than MAX_TRIANGLES
    triangles."""
    converted = meshes.convert(path)
    if converted.triangles is not None and converted.triangles > MAX_TRIANGLES:
        return None  # known from the cache's record: nothing read or parsed again at every load
    scale = tuple(float(s) for s in (scale or (1.0, 1.0, 1.0)))
    # the converted OBJ's name is already the hash of its source's content (meshes.convert): no need to read it
    key = hashlib.sha256(('%s|%s|%r' % (_VERSION, os.path.basename(converted.obj_path), scale)).encode())
    target = os.path.join(meshes.cache_dir(), 'prisms_' + key.hexdigest()[:32] + '.obj')
    if os.path.isfile(target):
        return target
    vertices, faces = read_obj(converted.obj_path)
    if len(faces) > MAX_TRIANGLES:  # a cache entry without its record of triangles
        return None
    vertices = vertices * np.asarray(scale)
    if np.prod(np.sign(scale)) < 0:  # a mirroring scale turns the winding over
        faces = faces[:, ::-1]
    text = prisms_obj(vertices, faces)
    os.makedirs(os.path.dirname(target), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(target), prefix='.tmp_')
    with os.fdopen(fd, 'w') as handle:
        handle.write(text)
    os.replace(tmp, target)
    return target


def read_obj(path: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices N x 3, triangles M x 3, 0-based) of an OBJ as meshes.convert writes it (v and triangular f)."""
    vertices, faces = [], []
    with open(path) as handle:
        for line in handle:
            if line.startswith('v '):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith('f '):
                faces.append([int(x.split('/')[0]) - 1 for x in line.split()[1:4]])
    return np.asarray(vertices, dtype=np.float64).reshape(-1, 3), np.asarray(faces, dtype=np.int64).reshape(-1, 3)


def prisms_obj(vertices: np.ndarray, faces: np.ndarray) -> str:
    """OBJ text with one object per non-degenerate triangle: the triangle and its copy moved backwards by its
    depth (depths())."""
    tri = vertices[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normals, axis=1)
    keep = length > 1e-12
    tri, normals = tri[keep], normals[keep] / length[keep, None]
    depth = depths(tri, normals)
    # Bullet pads a convex hull with its margin all round: the prism is shrunk by it (front set back, sides moved
    # in), so that contacts and rays meet the padded hull where the mesh's faces are.
    tri = _inset(tri, MARGIN)
    setback = np.where(depth > 2 * MARGIN, MARGIN, 0.0)
    back = tri - ((depth - setback)[:, None] * normals)[:, None, :]
    tri = tri - (setback[:, None] * normals)[:, None, :]
    lines = ['# one-sided prisms written by racebot (engine/one_sided_mesh.py)']
    # the two caps and the three sides, as triangles (PyBullet takes the hull of each object's points)
    sides = ((1, 2, 3), (6, 5, 4), (1, 4, 5), (1, 5, 2), (2, 5, 6), (2, 6, 3), (3, 6, 4), (3, 4, 1))
    for i in range(len(tri)):
        lines.append('o prism%d' % i)
        lines.extend('v %.9g %.9g %.9g' % tuple(p) for p in tri[i])
        lines.extend('v %.9g %.9g %.9g' % tuple(p) for p in back[i])
        base = 6 * i
        lines.extend('f %d %d %d' % (base + a, base + b, base + c) for a, b, c in sides)
    return '\n'.join(lines) + '\n'


def _inset(tri, margin):
    """Each triangle with its edges moved inwards by `margin` in its plane (scaled about its incentre; a triangle
    too small for that is kept)."""
    a = np.linalg.norm(tri[:, 1] - tri[:, 2], axis=1)
    b = np.linalg.norm(tri[:, 2] - tri[:, 0], axis=1)
    c = np.linalg.norm(tri[:, 0] - tri[:, 1], axis=1)
    perimeter = a + b + c
    centre = (a[:, None] * tri[:, 0] + b[:, None] * tri[:, 1] + c[:, None] * tri[:, 2]) / perimeter[:, None]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    inradius = 2.0 * area / perimeter
    factor = np.where(inradius > 2 * margin, (inradius - margin) / np.maximum(inradius, 1e-300), 1.0)
    return centre[:, None, :] + (tri - centre[:, None, :]) * factor[:, None, None]


def depths(tri: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """How deep each triangle's prism goes behind it (against its normal): half the way to the mesh's next face
    behind it (the nearest hit of rays cast backwards through the whole mesh from its centre and from points near
    its corners), so that inside a closed mesh the nearest face pushes out, clipped to [MIN_DEPTH, MAX_DEPTH];
    OPEN_DEPTH where no ray meets the mesh (an open surface)."""
    centre = tri.mean(axis=1)
    starts = [centre] + [tri[:, k] + 0.1 * (centre - tri[:, k]) for k in range(3)]
    size = float(np.linalg.norm(np.ptp(tri.reshape(-1, 3), axis=0)))
    lift = max(1e-7, 1e-9 * size)  # off the face itself, so that the ray does not hit its own triangle
    reach = size + 1.0  # through the whole mesh: a miss means nothing of it is behind the face
    origins = np.concatenate([s - lift * normals for s in starts])
    ends = origins - reach * np.tile(normals, (len(starts), 1))
    fractions = _cast(tri, origins, ends).reshape(len(starts), -1)
    nearest = fractions.min(axis=0) * reach
    missed = (fractions >= 1.0).all(axis=0)
    return np.where(missed, OPEN_DEPTH, np.clip(nearest / 2.0, MIN_DEPTH, MAX_DEPTH))


def _cast(tri, origins, ends):
    """Hit fractions (1 for a miss) of rays against the triangles, in a scratch PyBullet client of its own."""
    client = pb.connect(pb.DIRECT)
    try:
        flat = tri.reshape(-1, 3)
        shape = pb.createCollisionShape(pb.GEOM_MESH, vertices=flat.tolist(),
                                        indices=list(range(len(flat))), physicsClientId=client)
        pb.createMultiBody(0, shape, physicsClientId=client)
        fractions = []
        for start in range(0, len(origins), _RAY_BATCH):
            chunk = slice(start, start + _RAY_BATCH)
            results = pb.rayTestBatch(origins[chunk].tolist(), ends[chunk].tolist(), physicsClientId=client)
            if len(results) != len(origins[chunk]):
                raise RuntimeError('PyBullet answered %d of %d rays' % (len(results), len(origins[chunk])))
            fractions.extend(r[2] if r[0] >= 0 else 1.0 for r in results)
        return np.asarray(fractions)
    finally:
        pb.disconnect(client)


def lift_onto_floor(client: PybulletClient, body_id: int, floors: Sequence[int]) -> float:
    """Raises a model just spawned (`body_id`) straight up onto the top face of a one-sided floor (`floors`: body
    ids with prisms, Model.one_sided_bodies) that crosses it, as ODE's faces push out the links that cross them;
    returns the lift in m (0 when no top face crosses it deeper than SUNK)."""
    if not floors:
        return 0.0
    boxes = [client.getAABB(body_id, link) for link in range(-1, client.getNumJoints(body_id))]
    low = np.min([b[0] for b in boxes], axis=0)
    high = np.max([b[1] for b in boxes], axis=0)
    xs = np.linspace(low[0], high[0], FOOTPRINT_RAYS)
    ys = np.linspace(low[1], high[1], FOOTPRINT_RAYS)
    tops = [hit[3][2] for hit in _rays_past(client, body_id, [(x, y, high[2]) for x in xs for y in ys], low[2])
            if hit[0] in floors and hit[4][2] > FLOOR_NORMAL_Z]
    top = max(tops, default=None)
    if top is None or top - low[2] <= SUNK:
        return 0.0
    lift = float(top - low[2])
    position, orientation = client.getBasePositionAndOrientation(body_id)
    client.resetBasePositionAndOrientation(body_id, (position[0], position[1], position[2] + lift), orientation)
    return lift


def _rays_past(client, body_id, starts, bottom, rounds=16):
    """rayTestBatch's results of rays cast straight down from `starts` to z = `bottom`, each carried on past the
    hits on the model `body_id` itself (PyBullet reports only a ray's first hit)."""
    results = [None] * len(starts)
    pending = list(range(len(starts)))
    starts = [tuple(p) for p in starts]
    for _ in range(rounds):
        if not pending:
            break
        hits = client.rayTestBatch([starts[i] for i in pending], [(starts[i][0], starts[i][1], bottom)
                                                                   for i in pending])
        again = []
        for i, hit in zip(pending, hits):
            if hit[0] == body_id and hit[3][2] > bottom:
                starts[i] = (starts[i][0], starts[i][1], hit[3][2] - 1e-5)
                again.append(i)
            else:
                results[i] = hit
        pending = again
    return [r for r in results if r is not None]
