"""One PyBullet physics client: the world's static and dynamic bodies, spawned robots, stepping.

No ROS here. PhysicsWorld owns its client through a pybullet_client.PybulletClient (`world.client`),
whose functions carry the client's id, so several worlds can live in one process (tests do that).
Bodies are addressed by model name; joints and links by their URDF names.

Gazebo behaviours reproduced here, because the car drives differently without them:
- fixed-joint children are merged into their parent link as Gazebo lumps them (urdf_lumping.py, not
  PyBullet's URDF_MERGE_FIXED_LINKS, which would also merge a joint Gazebo keeps: preserveFixedJoint);
- a URDF link without <inertial> would get 1 kg in PyBullet; Gazebo ignores its mass, so it gets
  a negligible one here (the racebot would otherwise be ~6 kg too heavy);
- friction: ODE takes the smaller mu of two touching surfaces, Bullet multiplies them. Static world
  surfaces get friction 1 and a robot link gets min(its mu, the ground's mu), so the product is
  Gazebo's minimum for the contacts that matter (robot on ground);
- joint velocity motors (PyBullet's default) are switched off: joints move only by applied effort;
- URDF cylinders (the wheels) stay true cylinders (URDF_USE_IMPLICIT_CYLINDER): PyBullet's default
  convex-hull approximation makes the contact point jump between hull vertices, and the car veered
  ~2 degrees per metre driving straight with the hinges locked.

Meshes (URDF and SDF) arrive as checked OBJ files in the mesh cache (meshes.py; urdf_assets.py for
URDFs, sdf_elements.py for SDF). A static SDF body collides with the exact triangles (concave triangle
mesh, as Gazebo does); a dynamic body (every URDF link) with one convex hull per part of the mesh.
Colours are given when a body is built (visual shapes with their rgba; URDF colours written into the
URDF before loadURDF), so any copy built from `Body.source` (the viewer's) looks the same.
"""
from __future__ import annotations

import math
import os
import tempfile
import xml.etree.ElementTree as ET
from collections import namedtuple
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING

import pybullet as pb

from racebot_sim_bridge.description import urdf_assets
from racebot_sim_bridge.description.geometry import ShapeKind
from racebot_sim_bridge.engine.bullet_urdf import (NEGLIGIBLE_INERTIA, NEGLIGIBLE_MASS,  # noqa: F401 (re-exported)
                                                  joint_friction, link_friction, link_laser_retro,
                                                  prepare_urdf_for_bullet)
from racebot_sim_bridge.engine import mimic_joints
from racebot_sim_bridge.engine.joint_damping import ImplicitDampers, implicit_joints
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3, as_transform

if TYPE_CHECKING:
    from racebot_sim_bridge.description.sdf_model import Model, World
    from racebot_sim_bridge.description.urdf_model import RobotModel

# Links in one PyBullet body whose state it can report (SharedMemoryPublic.h MAX_DEGREE_OF_FREEDOM): with
# more, loadURDF succeeds and then every state query (getBasePositionAndOrientation, ...) fails.
MAX_BULLET_LINKS = 128

JointInfo = namedtuple('JointInfo', 'index name type lower upper max_effort max_velocity child_link')
JointState = namedtuple('JointState', 'position velocity')
Pose = namedtuple('Pose', 'position orientation')  # xyz, quaternion xyzw
Twist = namedtuple('Twist', 'linear angular')
LinkDynamics = namedtuple('LinkDynamics', 'mass inertia_diagonal inertial_position inertial_orientation')

JOINT_TYPES = {pb.JOINT_REVOLUTE: 'revolute', pb.JOINT_PRISMATIC: 'prismatic',
               pb.JOINT_FIXED: 'fixed', pb.JOINT_SPHERICAL: 'spherical', pb.JOINT_PLANAR: 'planar'}


class PhysicsError(RuntimeError):
    """A request the physics world cannot carry out; the message says why."""


class BodyKind(str, Enum):
    """What a body was built from: a URDF (a robot, one PyBullet body) or an SDF model (a body per link)."""
    URDF = 'urdf'
    SDF = 'sdf'

    def __str__(self):
        return self.value


@dataclass(frozen=True)
class BodySource:
    """What a body was built from, all another client needs to build a copy (picklable: the viewer and
    the render worker get it through a pipe). kind SDF: `model` is the sdf_model.Model; kind URDF:
    `model` is the urdf_model.RobotModel and `urdf_xml` its URDF, meshes resolved to files."""
    kind: BodyKind
    model: object
    urdf_xml: str = None


class Body:
    """A body in the world: its PyBullet id, links by name and movable joints by name. `client`: the
    PybulletClient of the world it is in.

    `source`: the BodySource it was built from. `extra_bodies`: [(link name, PyBullet id)] of an SDF
    model's links after the first (each link its own body; the first is `id`). `copy_key`: None until
    world_copy.body_key gives the body its identity across a delete and respawn under the same name.
    `model_offset`: for an SDF robot spawned as a URDF (sdf_urdf.py), its root link's pose in the SDF model
    frame, (xyz, quaternion), when not the identity; else None (a URDF's model frame is its root link's)."""

    def __init__(self, client: PybulletClient, name: str, body_id: int, static: bool, source: BodySource,
                 extra_bodies: Iterable[tuple[str, int]] = ()) -> None:
        self.client = client
        self.name = name
        self.id = body_id
        self.static = static
        self.source = source
        self.kind = source.kind
        self.extra_bodies = list(extra_bodies)
        self.copy_key = None
        self.model_offset = None
        dyn = client.getDynamicsInfo(body_id, -1)
        self._inertial = (tuple(dyn[3]), tuple(dyn[4]))  # base inertial frame in the link frame
        self._inertial_inverse = pb.invertTransform(*self._inertial)  # frame_pose's, computed once
        self.spawn_pose = self.pose()
        self.initial_joint_positions = {}
        self.mimics = {}  # URDF <mimic> joints held to their leaders: {joint: mimic_joints.Coupling}
        base_name = client.getBodyInfo(body_id)[0].decode()
        self.link_index = {base_name: -1}
        self.joints = {}
        for j in range(client.getNumJoints(body_id)):
            info = client.getJointInfo(body_id, j)
            link = info[12].decode()
            self.link_index[link] = j
            if info[2] == pb.JOINT_FIXED:
                continue
            name_j = info[1].decode()
            self.joints[name_j] = JointInfo(j, name_j, JOINT_TYPES.get(info[2], 'unknown'), info[8], info[9],
                                            info[10], info[11], link)

    def pose(self) -> Pose:
        """The base's centre-of-mass pose (what PyBullet's base calls take and give)."""
        pos, orn = self.client.getBasePositionAndOrientation(self.id)
        return Pose(tuple(pos), tuple(orn))

    def frame_pose(self, com: Pose | None = None) -> Pose:
        """The pose of the root link's frame, as Gazebo reports a model's pose; `com`: the base's pose() when
        already read (one PyBullet call fewer)."""
        pos, orn = self.pose() if com is None else com
        p, o = pb.multiplyTransforms(pos, orn, *self._inertial_inverse)
        return Pose(tuple(p), tuple(o))

    def com_pose_for_frame(self, position: Vec3, orientation: Quat) -> Pose:
        """The centre-of-mass pose that puts the root link's frame at (position, orientation)."""
        p, o = pb.multiplyTransforms(position, orientation, self._inertial[0], self._inertial[1])
        return Pose(tuple(p), tuple(o))

    def twist(self) -> Twist:
        lin, ang = self.client.getBaseVelocity(self.id)
        return Twist(tuple(lin), tuple(ang))

    def link_names(self) -> list[str]:
        return list(self.link_index)


class PhysicsWorld:
    """Owns one PyBullet client (`client`, a pybullet_client.PybulletClient). `gui=True` opens
    PyBullet's own window (needs a display). `visuals=False` builds no visual shapes (no meshes to
    draw, no colours): for a client that only steps physics and casts rays while another client draws."""

    def __init__(self, step_size: float = 0.001, gravity: Vec3 = (0.0, 0.0, -9.8), gui: bool = False,
                 visuals: bool = True) -> None:
        if not (step_size > 0 and math.isfinite(step_size)):
            raise PhysicsError('physics step size must be a positive number of seconds, got %r' % (step_size,))
        self.gui = gui
        self.visuals = visuals
        try:
            self.client = PybulletClient(pb.GUI if gui else pb.DIRECT)
        except pb.error as err:
            raise PhysicsError(str(err))
        if gui:
            self.client.configureDebugVisualizer(pb.COV_ENABLE_GUI, 0)
        self.step_size = step_size
        self.gravity = tuple(gravity)
        self.client.setGravity(*self.gravity)
        self.client.setTimeStep(step_size)
        self.bodies = {}
        # (PyBullet body id, link index) -> laser_retro of its collisions (a laser ray's intensity); 0 if absent
        self.laser_retro = {}
        self.ground_mu = 1.0
        # (body id, link index) -> [fx, fy, fz, tx, ty, tz] applied since the last step: Gazebo's Link force and
        # torque accumulators (ODE clears them after each step, as PyBullet its external forces), for f3d
        self.applied = {}
        # body id -> ImplicitDampers of its <implicitSpringDamper> joints; (body id, joint index) -> effort applied to
        # such a body's joint for the coming step (what the damper's prediction needs)
        self.implicit_dampers = {}
        self.joint_efforts = {}
        # a LoadTrial (engine/load_trial.py) that loads each URDF in a helper first: the world server's world
        self.load_trial = None

    # -- world --------------------------------------------------------------------------------
    def load_world(self, world: World, warn: Callable[[str], None] | None = None) -> list[str]:
        """Creates every model of a parsed sdf_model.World but its robots (Model.is_robot, spawned through
        the URDF path by the Simulator); returns the names created. With `warn`,
        a model that cannot be built (no link with usable geometry left) is skipped and warn(message)
        told, as the reader skips degenerate elements; without it, PhysicsError."""
        created = []
        for model in world.models:
            if model.is_robot:
                continue  # joints, plugins or sensors: Simulator.spawn_world_robots spawns it as a URDF
            try:
                self.add_sdf_model(model)
            except PhysicsError as err:
                if warn is None:
                    raise
                warn('%s; the model is skipped, the world loads without it' % err)
                continue
            created.append(model.name)
        return created

    def add_sdf_model(self, model: Model) -> Body:
        """One PyBullet body per SDF link (joints between SDF links are not supported)."""
        if model.name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % model.name)
        ids = []
        try:
            for link in model.links:
                body_id = self._create_sdf_link(model, link)
                if body_id is not None:
                    ids.append((link.name, body_id))
                    retro = next((c.laser_retro for c in link.collisions if c.laser_retro), 0.0)
                    if retro:
                        self.laser_retro[(body_id, -1)] = retro
        except Exception as err:  # the links built so far go too: nothing of a refused model stays behind
            for _, body_id in ids:
                self.client.removeBody(body_id)
            made = {body_id for _, body_id in ids}
            self.laser_retro = {k: v for k, v in self.laser_retro.items() if k[0] not in made}
            if isinstance(err, PhysicsError):
                raise
            raise PhysicsError("model '%s' link '%s' could not be built (%s: %s)"
                               % (model.name, link.name, type(err).__name__, err)) from err
        if not ids:
            raise PhysicsError("model '%s' has no link with supported geometry (give it a box, cylinder, sphere, "
                               "plane or mesh of positive size)" % model.name)
        # A multi-link SDF model is kept as its first link's body plus extra bodies named model::link.
        first_link, first_id = ids[0]
        body = Body(self.client, model.name, first_id, model.static, BodySource(BodyKind.SDF, model),
                    extra_bodies=ids[1:])
        body.link_index = {first_link: -1}
        self.bodies[model.name] = body
        return body

    def _create_sdf_link(self, model, link):
        shapes, visuals = [], []
        static = link.is_static(model) or link.mass is None or link.mass <= 0  # a nested model's: its own
        try:
            for col in link.collisions:
                pos, orn = as_transform(col.pose)
                shape = self._collision_shape(col.shape, pos, orn, static)
                if shape is not None:
                    shapes.append((shape, col))
            visuals = [v for v in link.visuals if self._drawable(v.shape)] if self.visuals else []
            vis_id = self._visual_shapes(visuals)
        except pb.error as err:
            raise PhysicsError("model '%s' link '%s': PyBullet could not build its shapes (%s)"
                               % (model.name, link.name, err))
        if not shapes and vis_id < 0:
            return None
        world_pos, world_orn = model.world_pose_of(link)
        mass = 0.0 if static else link.mass
        col_id = shapes[0][0] if len(shapes) == 1 else self._compound(link, static) if shapes else -1
        body = self.client.createMultiBody(baseMass=mass, baseCollisionShapeIndex=col_id, baseVisualShapeIndex=vis_id,
                                           basePosition=world_pos, baseOrientation=world_orn)
        try:
            if len(visuals) > 1:  # createVisualShapeArray takes no colours: one call per shape
                for i, vis in enumerate(visuals):
                    self.client.changeVisualShape(body, -1, shapeIndex=i, rgbaColor=_rgba(vis))
            if not static and link.inertia is not None:
                ixx, _, _, iyy, _, izz = link.inertia
                self.client.changeDynamics(body, -1, localInertiaDiagonal=(ixx, iyy, izz))
            mus = [c.mu for _, c in shapes if c.mu is not None]
            is_ground = any(c.shape.kind is ShapeKind.PLANE for _, c in shapes)
            if is_ground and mus:
                self.ground_mu = min(mus)
            # Static world surfaces get 1 so that Bullet's product equals the robot side's min(mu).
            friction = 1.0 if static else (min(mus) if mus else 1.0)
            self.client.changeDynamics(body, -1, lateralFriction=friction)
        except Exception:
            self.client.removeBody(body)
            raise
        return body

    def _compound(self, link, static):
        kwargs = dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], planeNormals=[], fileNames=[],
                      meshScales=[], flags=[], collisionFramePositions=[], collisionFrameOrientations=[])
        for col in link.collisions:
            s = col.shape
            if s.kind is ShapeKind.PLANE:
                continue
            pos, orn = as_transform(col.pose)
            kwargs['shapeTypes'].append({'box': pb.GEOM_BOX, 'cylinder': pb.GEOM_CYLINDER,
                                         'sphere': pb.GEOM_SPHERE, 'mesh': pb.GEOM_MESH}[s.kind])
            kwargs['fileNames'].append(s.filename or '')
            kwargs['meshScales'].append(list(s.scale or (1.0, 1.0, 1.0)))
            kwargs['flags'].append(_mesh_flags(static) if s.kind is ShapeKind.MESH else 0)
            kwargs['radii'].append(s.radius or 0.0)
            kwargs['halfExtents'].append([x / 2.0 for x in (s.size or (0, 0, 0))])
            kwargs['lengths'].append(s.length or 0.0)
            kwargs['planeNormals'].append([0, 0, 1])
            kwargs['collisionFramePositions'].append(pos)
            kwargs['collisionFrameOrientations'].append(orn)
        if not kwargs['shapeTypes']:
            return -1
        return self.client.createCollisionShapeArray(**kwargs)

    def _collision_shape(self, shape, pos, orn, static):
        c = self.client
        if shape.kind is ShapeKind.MESH:
            return c.createCollisionShape(pb.GEOM_MESH, fileName=shape.filename, meshScale=list(shape.scale),
                                          flags=_mesh_flags(static), collisionFramePosition=pos,
                                          collisionFrameOrientation=orn)
        if shape.kind is ShapeKind.BOX:
            return c.createCollisionShape(pb.GEOM_BOX, halfExtents=[x / 2.0 for x in shape.size],
                                          collisionFramePosition=pos, collisionFrameOrientation=orn)
        if shape.kind is ShapeKind.CYLINDER:
            return c.createCollisionShape(pb.GEOM_CYLINDER, radius=shape.radius, height=shape.length,
                                          collisionFramePosition=pos, collisionFrameOrientation=orn)
        if shape.kind is ShapeKind.SPHERE:
            return c.createCollisionShape(pb.GEOM_SPHERE, radius=shape.radius, collisionFramePosition=pos)
        if shape.kind is ShapeKind.PLANE:
            return c.createCollisionShape(pb.GEOM_PLANE, planeNormal=list(shape.normal or (0, 0, 1)),
                                          collisionFramePosition=pos)
        return None

    @staticmethod
    def _drawable(shape):
        return shape.kind in tuple(ShapeKind)

    def _visual_shapes(self, visuals):
        """One visual shape index for a link's visuals (sdf_model.Visual), -1 for none."""
        if not visuals:
            return -1
        c = self.client
        if len(visuals) == 1:
            vis = visuals[0]
            pos, orn = as_transform(vis.pose)
            return c.createVisualShape(rgbaColor=_rgba(vis), visualFramePosition=pos, visualFrameOrientation=orn,
                                       **self._visual_geometry(vis.shape))
        kwargs = dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], fileNames=[], meshScales=[],
                      planeNormals=[], visualFramePositions=[], visualFrameOrientations=[])
        for vis in visuals:
            pos, orn = as_transform(vis.pose)
            geometry = self._visual_geometry(vis.shape)
            kwargs['shapeTypes'].append(geometry['shapeType'])
            kwargs['radii'].append(geometry.get('radius', 0.0))
            kwargs['halfExtents'].append(geometry.get('halfExtents', [0.0, 0.0, 0.0]))
            kwargs['lengths'].append(geometry.get('length', 0.0))
            kwargs['fileNames'].append(geometry.get('fileName', ''))
            kwargs['meshScales'].append(geometry.get('meshScale', [1.0, 1.0, 1.0]))
            kwargs['planeNormals'].append([0.0, 0.0, 1.0])
            kwargs['visualFramePositions'].append(list(pos))
            kwargs['visualFrameOrientations'].append(list(orn))
        return c.createVisualShapeArray(**kwargs)

    @staticmethod
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

    # -- robots ---------------------------------------------------------------------------------
    def spawn_urdf(self, name: str, urdf_model: RobotModel, urdf: str | ET.Element, position: Vec3 = (0, 0, 0),
                   orientation: Quat = (0, 0, 0, 1), warn: Callable[[str], None] | None = None) -> Body:
        """Spawns a parsed URDF (urdf_model.RobotModel) under `name`; returns its Body. `urdf`: the URDF
        text, or its root element as already parsed (rewritten here in place: meshes resolved, then
        what PyBullet reads). Its meshes are resolved and converted first (urdf_assets); warn(message)
        hears of those that cannot be (the element is left out, the robot is spawned)."""
        if name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % name)
        root = urdf if isinstance(urdf, ET.Element) else ET.fromstring(urdf)
        urdf_assets.resolve_assets(root, urdf_model, warn)
        urdf_xml = ET.tostring(root, encoding='unicode')  # what a copy is built from: before PyBullet's rewrite
        flags = pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_MAINTAIN_LINK_ORDER | pb.URDF_USE_IMPLICIT_CYLINDER
        # A root link named world is the world (sdformat's URDF reader): its joints hold the robot to the world.
        fixed = urdf_model.root_link == 'world'
        bullet_urdf = prepare_urdf_for_bullet(root, urdf_model, self.visuals)
        links = len(root.findall('link'))
        if links > MAX_BULLET_LINKS:
            raise PhysicsError("'%s' has %d links once fixed joints are merged as Gazebo merges them; PyBullet "
                               "cannot report the state of a body of more than %d (its MAX_DEGREE_OF_FREEDOM): "
                               "join links with fixed joints or spawn it as several models"
                               % (name, links, MAX_BULLET_LINKS))
        # PyBullet reads a URDF from a file, once: the file lives only as long as the load, so a process
        # that is killed leaves nothing behind in /tmp.
        with tempfile.TemporaryDirectory(prefix='racebot_urdf_') as tmp:
            path = os.path.join(tmp, 'robot.urdf')
            with open(path, 'w') as f:
                f.write(bullet_urdf)
            trouble = self.load_trial.check(path, flags, fixed) if self.load_trial is not None else None
            if trouble is not None:
                raise PhysicsError("'%s' is not loaded: %s; the world goes on without it. Report the URDF to "
                                   'racebot with this message' % (name, trouble))
            try:
                body_id = self.client.loadURDF(path, basePosition=position, baseOrientation=orientation,
                                               flags=flags, useFixedBase=fixed)
            except pb.error as err:
                raise PhysicsError("PyBullet could not load the URDF of '%s': %s" % (name, err))
        try:
            body = self._set_up_urdf_body(name, body_id, urdf_model, urdf_xml)
        except Exception as err:  # a body half set up would stay in the world, stepped and never reported
            self.client.removeBody(body_id)
            self.laser_retro = {k: v for k, v in self.laser_retro.items() if k[0] != body_id}
            raise PhysicsError("PyBullet loaded the URDF of '%s' but could not set its body up (%s: %s); it is "
                               "removed" % (name, type(err).__name__, err)) from err
        self.bodies[name] = body
        return body

    def _set_up_urdf_body(self, name: str, body_id: int, urdf_model: RobotModel, urdf_xml: str) -> Body:
        """The Body of a URDF PyBullet just loaded, with Gazebo's friction, damping and joint motors."""
        # urdf_xml has its meshes resolved: a copy needs no package path
        body = Body(self.client, name, body_id, False, BodySource(BodyKind.URDF, urdf_model, urdf_xml))
        for link, index in body.link_index.items():
            # PyBullet's default link damping (0.04) has no counterpart in Gazebo: a free wheel would slow down.
            friction = min(link_friction(urdf_model, link), self.ground_mu)
            self.client.changeDynamics(body_id, index, lateralFriction=friction)
            # separate call: PyBullet ignores the friction when damping comes in the same call
            self.client.changeDynamics(body_id, index, linearDamping=0.0, angularDamping=0.0)
            retro = link_laser_retro(urdf_model, link)
            if retro:
                self.laser_retro[(body_id, index)] = retro
        for joint_name, joint in body.joints.items():
            # PyBullet's default velocity motors off; in their place the URDF <dynamics friction>, which Gazebo
            # applies as Coulomb friction: a motor holding velocity 0 with at most that force. (<dynamics damping>
            # PyBullet's URDF importer applies itself, explicitly as Gazebo does, but for an implicitSpringDamper
            # joint: joint_damping.py.) A joint a controller drives by velocity or position gets the hardware's
            # motor instead (DefaultRobotHWSim.write_sim).
            self.client.setJointMotorControl2(body_id, joint.index, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                              force=joint_friction(urdf_model, joint_name))
        implicit = implicit_joints(urdf_model, body.joints)
        if implicit:
            for index, *_ in implicit:
                self.client.changeDynamics(body_id, index, jointDamping=0.0)
            self.implicit_dampers[body_id] = ImplicitDampers(self.client, body_id, urdf_model.root_link == 'world',
                                                             implicit)
        body.mimics = mimic_joints.couple(self.client, body_id, body.joints, urdf_model)
        return body

    def add_copy(self, name: str, source: BodySource) -> Body:
        """Builds here a copy of another client's body from its Body.source (a window's or a render
        worker's copy of the simulated world); returns the new Body."""
        if source.kind is BodyKind.SDF:
            return self.add_sdf_model(source.model)
        return self.spawn_urdf(name, source.model, source.urdf_xml)

    def remove(self, name: str) -> None:
        body = self.bodies.pop(name)
        self.client.removeBody(body.id)
        for _, extra in body.extra_bodies:
            self.client.removeBody(extra)
        gone = {body.id} | {extra for _, extra in body.extra_bodies}
        self.implicit_dampers.pop(body.id, None)
        self.laser_retro = {k: v for k, v in self.laser_retro.items() if k[0] not in gone}

    # -- state ----------------------------------------------------------------------------------
    def joint_states(self, body: Body, indices: Sequence[int]) -> list[JointState]:
        states = self.client.getJointStates(body.id, indices)
        return [JointState(s[0], s[1]) for s in states]

    def joint_states_raw(self, body: Body,
                         indices: Sequence[int]) -> list[tuple[float, float, tuple[float, ...], float]]:
        """PyBullet's own tuples (position, velocity, reaction forces, applied torque) of the joints:
        the update loop's read, without building a JointState per joint."""
        return self.client.getJointStates(body.id, indices)

    def apply_efforts(self, body: Body, indices: Sequence[int], efforts: Sequence[float]) -> None:
        """Torques (or forces) for one step: PyBullet clears them after every stepSimulation."""
        self.client.setJointMotorControlArray(body.id, indices, pb.TORQUE_CONTROL, forces=efforts)
        if body.id in self.implicit_dampers:
            for index, effort in zip(indices, efforts):
                self.joint_efforts[(body.id, index)] = self.joint_efforts.get((body.id, index), 0.0) + effort

    def drive_velocities(self, body: Body, indices: Sequence[int], velocities: Sequence[float],
                         max_forces: Sequence[float]) -> None:
        self.client.setJointMotorControlArray(body.id, indices, pb.VELOCITY_CONTROL, targetVelocities=velocities,
                                              forces=max_forces)

    def drive_positions(self, body: Body, indices: Sequence[int], positions: Sequence[float],
                        max_forces: Sequence[float]) -> None:
        self.client.setJointMotorControlArray(body.id, indices, pb.POSITION_CONTROL, targetPositions=positions,
                                              forces=max_forces)

    def set_joint_position(self, body: Body, joint_name: str, position: float, velocity: float = 0.0) -> None:
        joint = body.joints[joint_name]
        self.client.resetJointState(body.id, joint.index, position, velocity)
        if body.mimics:
            mimic_joints.settle(self.client, body.id, body.joints, body.mimics)

    def set_pose(self, body: Body, position: Vec3, orientation: Quat, linear: Vec3 = (0, 0, 0),
                 angular: Vec3 = (0, 0, 0)) -> None:
        self.client.resetBasePositionAndOrientation(body.id, position, orientation)
        self.client.resetBaseVelocity(body.id, linear, angular)

    def link_state(self, body: Body, link: str) -> tuple[Pose, Twist]:
        """World pose and twist of a link (the base's for index -1)."""
        index = body.link_index[link]
        if index < 0:
            return body.frame_pose(), body.twist()
        s = self.client.getLinkState(body.id, index, computeLinkVelocity=1, computeForwardKinematics=1)
        return Pose(tuple(s[4]), tuple(s[5])), Twist(tuple(s[6]), tuple(s[7]))

    def base_state(self, body_id: int) -> tuple[Pose, Twist]:
        """World pose and twist of one PyBullet body's base, by id (an SDF model's extra link body)."""
        pos, orn = self.client.getBasePositionAndOrientation(body_id)
        lin, ang = self.client.getBaseVelocity(body_id)
        return Pose(tuple(pos), tuple(orn)), Twist(tuple(lin), tuple(ang))

    def set_base_state(self, body_id: int, position: Vec3, orientation: Quat, linear: Vec3 = (0, 0, 0),
                       angular: Vec3 = (0, 0, 0)) -> None:
        """Puts one PyBullet body's base (by id) at a pose with a twist."""
        self.client.resetBasePositionAndOrientation(body_id, position, orientation)
        self.client.resetBaseVelocity(body_id, linear, angular)

    def set_base_velocity(self, body_id: int, linear: Vec3, angular: Vec3) -> None:
        """A base's world linear (at its centre of mass) and angular velocity, its pose left as it is."""
        self.client.resetBaseVelocity(body_id, list(linear), list(angular))

    def apply_joint_effort(self, body: Body, joint_name: str, effort: float) -> None:
        self.apply_efforts(body, [body.joints[joint_name].index], [effort])

    # -- dynamics and external forces (gazebo_ros's properties and force services) ----------------
    # A link is addressed (PyBullet body id, link index): an SDF model's extra link is a body of its own.
    def link_dynamics(self, body_id: int, index: int) -> LinkDynamics:
        """LinkDynamics of a link: mass, inertia diagonal, inertial frame in the link frame."""
        d = self.client.getDynamicsInfo(body_id, index)
        return LinkDynamics(d[0], tuple(d[2]), tuple(d[3]), tuple(d[4]))

    def set_link_mass(self, body_id: int, index: int, mass: float, inertia_diagonal: Vec3) -> None:
        # Two calls: PyBullet recomputes the inertia from the collision shapes when the mass changes.
        self.client.changeDynamics(body_id, index, mass=mass)
        self.client.changeDynamics(body_id, index, localInertiaDiagonal=list(inertia_diagonal))

    def com_position(self, body_id: int, index: int) -> Vec3:
        """World position of a link's centre of mass."""
        if index < 0:
            return tuple(self.client.getBasePositionAndOrientation(body_id)[0])
        return tuple(self.client.getLinkState(body_id, index, computeForwardKinematics=1)[0])

    def apply_wrench(self, body_id: int, index: int, force: Vec3, torque: Vec3, accumulate: bool = True) -> None:
        """A world-frame force at the link's centre of mass and a world-frame torque, for one step.
        `accumulate`: it counts in applied_wrench (False: a stand-in for what Gazebo does otherwise)."""
        if accumulate and (any(force) or any(torque)):
            total = self.applied.setdefault((body_id, index), [0.0] * 6)
            for i in range(3):
                total[i] += force[i]
                total[3 + i] += torque[i]
        if any(force):
            at = self.com_position(body_id, index)
            self.client.applyExternalForce(body_id, index, list(force), at, pb.WORLD_FRAME)
        if any(torque):
            self.client.applyExternalTorque(body_id, index, list(torque), pb.WORLD_FRAME)

    def enable_joint_wrench(self, body: Body, index: int) -> None:
        """Has PyBullet measure the wrench through the joint of link `index` (joint_wrench)."""
        self.client.enableJointForceTorqueSensor(body.id, index, True)

    def joint_wrench(self, body: Body, index: int) -> tuple[Vec3, Vec3]:
        """(force, torque) the parent applies to link `index` (and what hangs below it) through its joint, in
        the last step: PyBullet's default feedback, in the link's inertial-frame axes, the torque about its
        centre of mass. Zero unless enable_joint_wrench was called for it."""
        reaction = self.client.getJointState(body.id, index)[2]
        return tuple(reaction[:3]), tuple(reaction[3:])

    def set_joint_dynamics(self, body: Body, joint_name: str, damping: float | None = None,
                           lower: float | None = None, upper: float | None = None) -> None:
        """A joint's viscous damping and position limits (None: unchanged)."""
        joint = body.joints[joint_name]
        dampers = self.implicit_dampers.get(body.id)
        if damping is not None and dampers is not None and joint.index in dampers.joints:
            dampers.set_damping(joint.index, damping)  # Gazebo's SetDamping keeps an implicit joint implicit
        elif damping is not None:
            self.client.changeDynamics(body.id, joint.index, jointDamping=damping)
        if lower is not None or upper is not None:
            self.client.changeDynamics(body.id, joint.index, jointLowerLimit=joint.lower if lower is None else lower,
                                       jointUpperLimit=joint.upper if upper is None else upper)
            body.joints[joint_name] = joint._replace(lower=joint.lower if lower is None else lower,
                                                     upper=joint.upper if upper is None else upper)

    def set_gravity(self, gravity: Vec3) -> None:
        self.gravity = tuple(gravity)
        self.client.setGravity(*self.gravity)

    def set_step_size(self, step_size: float) -> None:
        self.step_size = step_size
        self.client.setTimeStep(step_size)

    def set_solver(self, **params: float) -> None:
        """Constraint solver parameters by PyBullet's names (numSolverIterations, erp, globalCFM)."""
        self.client.setPhysicsEngineParameter(**params)

    def applied_wrench(self, body_id: int, index: int) -> tuple[Vec3, Vec3]:
        """(force, torque), world axes, applied to a link with apply_wrench since the last step: Gazebo's
        Link::WorldForce/WorldTorque (the torque about its centre of mass)."""
        total = self.applied.get((body_id, index), (0.0,) * 6)
        return tuple(total[:3]), tuple(total[3:])

    def step(self) -> None:
        for body_id, dampers in self.implicit_dampers.items():
            applied = {index: e for (b, index), e in self.joint_efforts.items() if b == body_id}
            indices, torques = dampers.torques(self.step_size, applied)
            if indices:
                self.client.setJointMotorControlArray(body_id, indices, pb.TORQUE_CONTROL, forces=torques)
        if self.joint_efforts:
            self.joint_efforts = {}
        self.client.stepSimulation()
        if self.applied:
            self.applied = {}

    def reset_to_spawn(self, body: Body) -> None:
        pos, orn = body.spawn_pose
        self.set_pose(body, pos, orn)
        for link, extra in body.extra_bodies:  # an SDF model's other links, as spawned
            pos, orn = body.source.model.world_pose_of(link)
            self.set_base_state(extra, pos, orn)
        for joint in body.joints.values():
            self.client.resetJointState(body.id, joint.index, body.initial_joint_positions.get(joint.name, 0.0), 0.0)
        mimic_joints.settle(self.client, body.id, body.joints, body.mimics)

    def follow_with_camera(self, body: Body, distance: float = 1.5, yaw_offset: float = 0.0,
                           pitch: float = -30.0) -> None:
        if not self.gui:
            return
        pos, orn = body.pose()
        yaw = math.degrees(pb.getEulerFromQuaternion(orn)[2]) - 90.0 + yaw_offset
        self.client.resetDebugVisualizerCamera(distance, yaw, pitch, pos)

    def close(self) -> None:
        if self.load_trial is not None:
            self.load_trial.close()
        self.client.close()


def _mesh_flags(static):
    # Bullet collides static bodies with triangle meshes, dynamic ones only with convex shapes.
    return pb.GEOM_FORCE_CONCAVE_TRIMESH if static else 0


def _rgba(visual):
    return list(visual.rgba) if visual.rgba else [0.7, 0.7, 0.7, 1.0]  # Gazebo's default grey
