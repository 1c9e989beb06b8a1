"""The PyBullet bodies of an SDF model: one body per link, its collision shapes, visual shapes and colours.

No ROS here. PhysicsWorld.add_sdf_model calls build_model; the Model it returns holds the bodies (its first
link's is the Model's own, the others `extra_bodies`). Every link is a body, also one with no collision and no
visual left (none written, or a missing mesh skipped by the reader): Gazebo keeps such a link and its model.
A static body collides with the exact surface of its meshes, each triangle one-sided as in ODE
(one_sided_mesh.py); a dynamic one with one convex hull per mesh part. Colours are given when a body is built
(visual shapes with their rgba), so a copy built from its BodySource (the viewer's) looks the same. Friction: ODE
takes the smaller mu of two touching surfaces, Bullet multiplies them, so a static surface gets friction 1 and a
dynamic one its own mu; a ground plane's mu is reported to the world (PhysicsWorld.ground_mu), which gives robots
min(their mu, the ground's). Inertia as Gazebo's ODE takes it (../kinematics/inertia.py): one that is not positive
definite is the identity (dBodySetMass's fallback), with one warning.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import pybullet as pb

from racebot_sim_bridge.description.geometry import ShapeKind
from racebot_sim_bridge.engine import one_sided_mesh
from racebot_sim_bridge.engine.model import Model
from racebot_sim_bridge.engine.physics_types import BodyKind, BodySource, PhysicsError
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.kinematics import inertia as inertia_maths
from racebot_sim_bridge.kinematics.rotations import as_transform

if TYPE_CHECKING:
    from racebot_sim_bridge.description import sdf_model


def build_model(client: PybulletClient, applied: dict, model: sdf_model.SdfModel, visuals: bool,
                laser_retro: dict, warn: Callable[[str], None] | None = None) -> tuple[Model, float | None]:
    """The Model of an SDF model, one PyBullet body per link (joints between SDF links are not supported), and
    the mu of its ground plane if it has one (else None). `visuals`: build visual shapes; `laser_retro`: the
    world's {(body id, link index): laser_retro}, given this model's; warn(message) hears of an inertia that is
    not positive definite. PhysicsError when it cannot be built: nothing of it stays behind then."""
    ids, ground_mu, one_sided = [], None, []
    warn = warn or (lambda message: None)
    try:
        for link in model.links:
            prisms = []
            body_id, mu = _link_body(client, model, link, visuals, warn, prisms)
            if prisms:
                one_sided.append(body_id)
            ground_mu = mu if mu is not None else ground_mu
            ids.append((link.name, body_id))
            retro = next((c.laser_retro for c in link.collisions if c.laser_retro), 0.0)
            if retro:
                laser_retro[(body_id, -1)] = retro
    except Exception as err:  # the links built so far go too: nothing of a refused model stays behind
        for _, body_id in ids:
            client.removeBody(body_id)
            laser_retro.pop((body_id, -1), None)
        if isinstance(err, PhysicsError):
            raise
        raise PhysicsError("model '%s' link '%s' could not be built (%s: %s)"
                           % (model.name, link.name, type(err).__name__, err)) from err
    if not ids:  # sdformat 9 refuses a model without a link ("A model must have at least one link")
        raise PhysicsError("model '%s' has no link; a model needs at least one <link>" % model.name)
    # A multi-link SDF model is kept as its first link's body plus extra bodies named model::link.
    first_link, first_id = ids[0]
    built = Model(client, applied, model.name, first_id, model.static, BodySource(BodyKind.SDF, model),
                  extra_bodies=ids[1:], root_link=first_link)
    built.one_sided_bodies = one_sided
    return built, ground_mu


def _link_body(client, model, link, visuals, warn, prisms):
    """(PyBullet body of one SDF link, mu of its ground plane or None). A link left with no shape (none written,
    or each skipped: a mesh that is missing, a degenerate size) is still a body, as Gazebo keeps the link and
    its model: its mass and inertia, nothing to collide with or draw. `prisms` hears of the one-sided prism
    files its meshes collide through (_mesh_file)."""
    shapes, drawn = [], []
    static = link.is_static(model) or link.mass is None or link.mass <= 0  # a nested model's: its own
    try:
        for col in link.collisions:
            pos, orn = as_transform(col.pose)
            shape = _collision_shape(client, col.shape, pos, orn, static, prisms)
            if shape is not None:
                shapes.append((shape, col))
        drawn = [v for v in link.visuals if _drawable(v.shape)] if visuals else []
        vis_id = _visual_shapes(client, drawn)
    except pb.error as err:
        raise PhysicsError("model '%s' link '%s': PyBullet could not build its shapes (%s)"
                           % (model.name, link.name, err))
    world_pos, world_orn = model.world_pose_of(link)
    mass = 0.0 if static else link.mass
    col_id = shapes[0][0] if len(shapes) == 1 else _compound(client, link, static, []) if shapes else -1
    body = client.createMultiBody(baseMass=mass, baseCollisionShapeIndex=col_id, baseVisualShapeIndex=vis_id,
                                  basePosition=world_pos, baseOrientation=world_orn)
    try:
        if len(drawn) > 1:  # createVisualShapeArray takes no colours: one call per shape
            for i, vis in enumerate(drawn):
                client.changeVisualShape(body, -1, shapeIndex=i, rgbaColor=_rgba(vis))
        # Without a shape PyBullet has no inertia to derive: the SDF's, else SDF's default (1 kg m^2 each)
        inertia = link.inertia if link.inertia is not None or shapes else _SDF_DEFAULT_INERTIA
        if not static and inertia is not None:
            ixx, _, _, iyy, _, izz = _as_ode_takes_it(model, link, inertia, warn)
            client.changeDynamics(body, -1, localInertiaDiagonal=(ixx, iyy, izz))
        mus = [c.mu for _, c in shapes if c.mu is not None]
        is_ground = any(c.shape.kind is ShapeKind.PLANE for _, c in shapes)
        # Static world surfaces get 1 so that Bullet's product equals the robot side's min(mu).
        friction = 1.0 if static else (min(mus) if mus else 1.0)
        client.changeDynamics(body, -1, lateralFriction=friction)
    except Exception:
        client.removeBody(body)
        raise
    return body, (min(mus) if is_ground and mus else None)


_SDF_DEFAULT_INERTIA = (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)  # <inertia>'s defaults: ixx, ixy, ixz, iyy, iyz, izz


def _as_ode_takes_it(model, link, inertia, warn):
    """(ixx, ixy, ixz, iyy, iyz, izz) as Gazebo's ODE simulates them: the identity, with one warning, when they are
    not positive definite (dBodySetMass's fallback), else as given."""
    if inertia_maths.ode_positive_definite(inertia_maths.tensor(*inertia)):
        return inertia
    warn(inertia_maths.not_positive_definite(model.name, link.name, inertia, link.mass))
    return inertia_maths.IDENTITY


def _compound(client, link, static, prisms):
    """One compound collision shape of a link's collisions (planes left out), -1 for none."""
    kwargs = dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], planeNormals=[], fileNames=[],
                  meshScales=[], flags=[], collisionFramePositions=[], collisionFrameOrientations=[])
    for col in link.collisions:
        s = col.shape
        if s.kind is ShapeKind.PLANE:
            continue
        pos, orn = as_transform(col.pose)
        kwargs['shapeTypes'].append({'box': pb.GEOM_BOX, 'cylinder': pb.GEOM_CYLINDER,
                                     'sphere': pb.GEOM_SPHERE, 'mesh': pb.GEOM_MESH}[s.kind])
        filename, scale, flags = _mesh_file(s, static, prisms) if s.kind is ShapeKind.MESH else \
            ('', [1.0, 1.0, 1.0], 0)
        kwargs['fileNames'].append(filename)
        kwargs['meshScales'].append(scale)
        kwargs['flags'].append(flags)
        kwargs['radii'].append(s.radius or 0.0)
        kwargs['halfExtents'].append([x / 2.0 for x in (s.size or (0, 0, 0))])
        kwargs['lengths'].append(s.length or 0.0)
        kwargs['planeNormals'].append([0, 0, 1])
        kwargs['collisionFramePositions'].append(pos)
        kwargs['collisionFrameOrientations'].append(orn)
    if not kwargs['shapeTypes']:
        return -1
    return client.createCollisionShapeArray(**kwargs)


def _collision_shape(client, shape, pos, orn, static, prisms):
    """A collision shape for one geometry.Shape at (pos, orn), None for a kind PyBullet has no shape for."""
    if shape.kind is ShapeKind.MESH:
        filename, scale, flags = _mesh_file(shape, static, prisms)
        return client.createCollisionShape(pb.GEOM_MESH, fileName=filename, meshScale=scale, flags=flags,
                                           collisionFramePosition=pos, collisionFrameOrientation=orn)
    if shape.kind is ShapeKind.BOX:
        return client.createCollisionShape(pb.GEOM_BOX, halfExtents=[x / 2.0 for x in shape.size],
                                      collisionFramePosition=pos, collisionFrameOrientation=orn)
    if shape.kind is ShapeKind.CYLINDER:
        return client.createCollisionShape(pb.GEOM_CYLINDER, radius=shape.radius, height=shape.length,
                                      collisionFramePosition=pos, collisionFrameOrientation=orn)
    if shape.kind is ShapeKind.SPHERE:
        return client.createCollisionShape(pb.GEOM_SPHERE, radius=shape.radius, collisionFramePosition=pos)
    if shape.kind is ShapeKind.PLANE:
        return client.createCollisionShape(pb.GEOM_PLANE, planeNormal=list(shape.normal or (0, 0, 1)),
                                      collisionFramePosition=pos)
    return None


def _drawable(shape):
    return shape.kind in tuple(ShapeKind)


def _visual_shapes(client, visuals):
    """One visual shape index for a link's visuals (sdf_model.Visual), -1 for none."""
    if not visuals:
        return -1
    if len(visuals) == 1:
        vis = visuals[0]
        pos, orn = as_transform(vis.pose)
        return client.createVisualShape(rgbaColor=_rgba(vis), visualFramePosition=pos, visualFrameOrientation=orn,
                                   **_visual_geometry(vis.shape))
    kwargs = dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], fileNames=[], meshScales=[],
                  planeNormals=[], visualFramePositions=[], visualFrameOrientations=[])
    for vis in visuals:
        pos, orn = as_transform(vis.pose)
        geometry = _visual_geometry(vis.shape)
        kwargs['shapeTypes'].append(geometry['shapeType'])
        kwargs['radii'].append(geometry.get('radius', 0.0))
        kwargs['halfExtents'].append(geometry.get('halfExtents', [0.0, 0.0, 0.0]))
        kwargs['lengths'].append(geometry.get('length', 0.0))
        kwargs['fileNames'].append(geometry.get('fileName', ''))
        kwargs['meshScales'].append(geometry.get('meshScale', [1.0, 1.0, 1.0]))
        kwargs['planeNormals'].append([0.0, 0.0, 1.0])
        kwargs['visualFramePositions'].append(list(pos))
        kwargs['visualFrameOrientations'].append(list(orn))
    return client.createVisualShapeArray(**kwargs)


def _visual_geometry(shape):
    """createVisualShape's geometry arguments for a geometry.Shape (a plane: a thin box)."""
    if shape.kind is ShapeKind.BOX:
        return dict(shapeType=pb.GEOM_BOX, halfExtents=[x / 2.0 for x in shape.size])
    if shape.kind is ShapeKind.CYLINDER:
        return dict(shapeType=pb.GEOM_CYLINDER, radius=shape.radius, length=shape.length)
    if shape.kind is ShapeKind.SPHERE:
        return dict(shapeType=pb.GEOM_SPHERE, radius=shape.radius)
    if shape.kind is ShapeKind.MESH:
        return dict(shapeType=pb.GEOM_MESH, fileName=shape.filename, meshScale=list(shape.scale))
    size = shape.size or (100.0, 100.0)
    return dict(shapeType=pb.GEOM_BOX, halfExtents=[size[0] / 2.0, size[1] / 2.0, 0.0005])


def _mesh_file(shape, static, prisms):
    """(file, scale, flags) of a mesh collision: a static one's triangles as one-sided prisms (one_sided_mesh.py,
    ODE's one-sided triangles), or its exact triangles when it has too many for prisms; a dynamic one as one convex
    hull per part (Bullet collides dynamic bodies only with convex shapes). A prisms file is appended to `prisms`."""
    scale = list(shape.scale or (1.0, 1.0, 1.0))
    if not static:
        return shape.filename, scale, 0
    path = one_sided_mesh.prism_mesh(shape.filename, scale)
    if path is None:
        return shape.filename, scale, pb.GEOM_FORCE_CONCAVE_TRIMESH
    prisms.append(path)
    return path, [1.0, 1.0, 1.0], 0


def _rgba(visual):
    return list(visual.rgba) if visual.rgba else [0.7, 0.7, 0.7, 1.0]  # Gazebo's default grey
