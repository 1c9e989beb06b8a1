"""One PyBullet physics client: the world's static and dynamic bodies, spawned robots, stepping.

No ROS here. Every PyBullet call carries this client's id, so several worlds can live in one
process (tests do that). Bodies are addressed by model name; joints and links by their URDF names.

Gazebo behaviours reproduced here, because the car drives differently without them:
- fixed-joint children are merged into their parent link (URDF_MERGE_FIXED_LINKS), as Gazebo does;
- a URDF link without <inertial> would get 1 kg in PyBullet; Gazebo ignores its mass, so it gets
  a negligible one here (the racebot would otherwise be ~6 kg too heavy);
- friction: ODE takes the smaller mu of two touching surfaces, Bullet multiplies them. Static world
  surfaces get friction 1 and a robot link gets min(its mu, the ground's mu), so the product is
  Gazebo's minimum for the contacts that matter (robot on ground);
- joint velocity motors (PyBullet's default) are switched off: joints move only by applied effort;
- URDF cylinders (the wheels) stay true cylinders (URDF_USE_IMPLICIT_CYLINDER): PyBullet's default
  convex-hull approximation makes the contact point jump between hull vertices, and the car veered
  ~2 degrees per metre driving straight with the hinges locked.
"""
import math
import os
import shutil
import tempfile
import xml.etree.ElementTree as ET
from collections import namedtuple

import pybullet as pb

from . import sdf_world

# Mass and inertia given to links that declare no <inertial> (Gazebo drops such links' mass).
NEGLIGIBLE_MASS = 1e-4
NEGLIGIBLE_INERTIA = 1e-9

JointInfo = namedtuple('JointInfo', 'index name type lower upper max_effort max_velocity child_link')
JointState = namedtuple('JointState', 'position velocity')
Pose = namedtuple('Pose', 'position orientation')  # xyz, quaternion xyzw
Twist = namedtuple('Twist', 'linear angular')

JOINT_TYPES = {pb.JOINT_REVOLUTE: 'revolute', pb.JOINT_PRISMATIC: 'prismatic',
               pb.JOINT_FIXED: 'fixed', pb.JOINT_SPHERICAL: 'spherical', pb.JOINT_PLANAR: 'planar'}


class PhysicsError(RuntimeError):
    """A request the physics world cannot carry out; the message says why."""


class Body(object):
    """A body in the world: its PyBullet id, links by name and movable joints by name."""

    def __init__(self, client, name, body_id, static, kind):
        self.client = client
        self.name = name
        self.id = body_id
        self.static = static
        self.kind = kind  # 'urdf' or 'sdf'
        dyn = pb.getDynamicsInfo(body_id, -1, physicsClientId=client)
        self._inertial = (tuple(dyn[3]), tuple(dyn[4]))  # base inertial frame in the link frame
        self.spawn_pose = self.pose()
        self.initial_joint_positions = {}
        base_name = pb.getBodyInfo(body_id, physicsClientId=client)[0].decode()
        self.link_index = {base_name: -1}
        self.joints = {}
        for j in range(pb.getNumJoints(body_id, physicsClientId=client)):
            info = pb.getJointInfo(body_id, j, physicsClientId=client)
            link = info[12].decode()
            self.link_index[link] = j
            if info[2] == pb.JOINT_FIXED:
                continue
            name_j = info[1].decode()
            self.joints[name_j] = JointInfo(j, name_j, JOINT_TYPES.get(info[2], 'unknown'), info[8], info[9],
                                            info[10], info[11], link)

    def pose(self):
        """The base's centre-of-mass pose (what PyBullet's base calls take and give)."""
        pos, orn = pb.getBasePositionAndOrientation(self.id, physicsClientId=self.client)
        return Pose(tuple(pos), tuple(orn))

    def frame_pose(self):
        """The pose of the root link's frame, as Gazebo reports a model's pose."""
        pos, orn = self.pose()
        inv_pos, inv_orn = pb.invertTransform(self._inertial[0], self._inertial[1])
        p, o = pb.multiplyTransforms(pos, orn, inv_pos, inv_orn)
        return Pose(tuple(p), tuple(o))

    def com_pose_for_frame(self, position, orientation):
        """The centre-of-mass pose that puts the root link's frame at (position, orientation)."""
        p, o = pb.multiplyTransforms(position, orientation, self._inertial[0], self._inertial[1])
        return Pose(tuple(p), tuple(o))

    def twist(self):
        lin, ang = pb.getBaseVelocity(self.id, physicsClientId=self.client)
        return Twist(tuple(lin), tuple(ang))

    def link_names(self):
        return list(self.link_index)


class PhysicsWorld(object):
    """Owns one PyBullet client. `gui=True` opens PyBullet's own window (needs a display)."""

    def __init__(self, step_size=0.001, gravity=(0.0, 0.0, -9.8), gui=False):
        if not (step_size > 0 and math.isfinite(step_size)):
            raise PhysicsError('physics step size must be a positive number of seconds, got %r' % (step_size,))
        self.gui = gui
        self.client = pb.connect(pb.GUI if gui else pb.DIRECT)
        if self.client < 0:
            raise PhysicsError('could not start PyBullet (%s mode)' % ('GUI' if gui else 'DIRECT'))
        if gui:
            pb.configureDebugVisualizer(pb.COV_ENABLE_GUI, 0, physicsClientId=self.client)
        self.step_size = step_size
        self.gravity = tuple(gravity)
        pb.setGravity(*self.gravity, physicsClientId=self.client)
        pb.setTimeStep(step_size, physicsClientId=self.client)
        self.bodies = {}
        self.ground_mu = 1.0
        self._tmpdir = tempfile.mkdtemp(prefix='racebot_urdf_')

    # -- world --------------------------------------------------------------------------------
    def load_world(self, world, warn=None):
        """Creates every model of a parsed sdf_world.World; returns the names created. With `warn`,
        a model that cannot be built (no link with usable geometry left) is skipped and warn(message)
        told, as the reader skips degenerate elements; without it, PhysicsError."""
        created = []
        for model in world.models:
            try:
                self.add_sdf_model(model)
            except PhysicsError as err:
                if warn is None:
                    raise
                warn('%s; the model is skipped, the world loads without it' % err)
                continue
            created.append(model.name)
        return created

    def add_sdf_model(self, model):
        """One PyBullet body per SDF link (joints between SDF links are not supported)."""
        if model.name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % model.name)
        ids = []
        for link in model.links:
            body_id = self._create_sdf_link(model, link)
            if body_id is not None:
                ids.append((link.name, body_id))
        if not ids:
            raise PhysicsError("model '%s' has no link with supported geometry (give it a box, cylinder, sphere "
                               "or plane of positive size)" % model.name)
        # A multi-link SDF model is kept as its first link's body plus extra bodies named model::link.
        first_link, first_id = ids[0]
        body = Body(self.client, model.name, first_id, model.static, 'sdf')
        body.link_index = {first_link: -1}
        body.extra_bodies = ids[1:]
        body.source = ('sdf', model)  # what a viewer needs to build its own copy
        self.bodies[model.name] = body
        return body

    def _create_sdf_link(self, model, link):
        shapes, visuals = [], []
        for col in link.collisions:
            pos, orn = sdf_world.as_transform(col.pose)
            shape = self._collision_shape(col.shape, pos, orn)
            if shape is not None:
                shapes.append((shape, col))
        for vis in link.visuals:
            pos, orn = sdf_world.as_transform(vis.pose)
            shape = self._visual_shape(vis.shape, pos, orn, vis.rgba)
            if shape is not None:
                visuals.append(shape)
        if not shapes and not visuals:
            return None
        world_pos, world_orn = model.world_pose_of(link)
        static = model.static or link.mass is None or link.mass <= 0
        mass = 0.0 if static else link.mass
        col_id = shapes[0][0] if len(shapes) == 1 else self._compound(link) if shapes else -1
        vis_id = visuals[0] if len(visuals) == 1 else -1
        body = pb.createMultiBody(baseMass=mass, baseCollisionShapeIndex=col_id, baseVisualShapeIndex=vis_id,
                                  basePosition=world_pos, baseOrientation=world_orn,
                                  physicsClientId=self.client)
        if not static and link.inertia is not None:
            ixx, _, _, iyy, _, izz = link.inertia
            pb.changeDynamics(body, -1, localInertiaDiagonal=(ixx, iyy, izz), physicsClientId=self.client)
        mus = [c.mu for _, c in shapes if c.mu is not None]
        is_ground = any(c.shape.kind == 'plane' for _, c in shapes)
        if is_ground and mus:
            self.ground_mu = min(mus)
        # Static world surfaces get 1 so that Bullet's product equals the robot side's min(mu).
        friction = 1.0 if static else (min(mus) if mus else 1.0)
        pb.changeDynamics(body, -1, lateralFriction=friction, physicsClientId=self.client)
        return body

    def _compound(self, link):
        kwargs = dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], planeNormals=[],
                                 collisionFramePositions=[], collisionFrameOrientations=[])
        for col in link.collisions:
            s = col.shape
            if s.kind == 'plane':
                continue
            pos, orn = sdf_world.as_transform(col.pose)
            kwargs['shapeTypes'].append({'box': pb.GEOM_BOX, 'cylinder': pb.GEOM_CYLINDER,
                                         'sphere': pb.GEOM_SPHERE}[s.kind])
            kwargs['radii'].append(s.radius or 0.0)
            kwargs['halfExtents'].append([x / 2.0 for x in (s.size or (0, 0, 0))])
            kwargs['lengths'].append(s.length or 0.0)
            kwargs['planeNormals'].append([0, 0, 1])
            kwargs['collisionFramePositions'].append(pos)
            kwargs['collisionFrameOrientations'].append(orn)
        if not kwargs['shapeTypes']:
            return -1
        return pb.createCollisionShapeArray(physicsClientId=self.client, **kwargs)

    def _collision_shape(self, shape, pos, orn):
        c = self.client
        if shape.kind == 'box':
            return pb.createCollisionShape(pb.GEOM_BOX, halfExtents=[x / 2.0 for x in shape.size],
                                           collisionFramePosition=pos, collisionFrameOrientation=orn,
                                           physicsClientId=c)
        if shape.kind == 'cylinder':
            return pb.createCollisionShape(pb.GEOM_CYLINDER, radius=shape.radius, height=shape.length,
                                           collisionFramePosition=pos, collisionFrameOrientation=orn,
                                           physicsClientId=c)
        if shape.kind == 'sphere':
            return pb.createCollisionShape(pb.GEOM_SPHERE, radius=shape.radius, collisionFramePosition=pos,
                                           physicsClientId=c)
        if shape.kind == 'plane':
            return pb.createCollisionShape(pb.GEOM_PLANE, planeNormal=list(shape.normal or (0, 0, 1)),
                                           collisionFramePosition=pos, physicsClientId=c)
        return None

    def _visual_shape(self, shape, pos, orn, rgba):
        if not self.gui:
            return None  # visual shapes only cost memory without a window or a camera
        c = self.client
        rgba = list(rgba) if rgba else [0.7, 0.7, 0.7, 1.0]
        if shape.kind == 'box':
            return pb.createVisualShape(pb.GEOM_BOX, halfExtents=[x / 2.0 for x in shape.size], rgbaColor=rgba,
                                        visualFramePosition=pos, visualFrameOrientation=orn, physicsClientId=c)
        if shape.kind == 'cylinder':
            return pb.createVisualShape(pb.GEOM_CYLINDER, radius=shape.radius, length=shape.length,
                                        rgbaColor=rgba, visualFramePosition=pos, visualFrameOrientation=orn,
                                        physicsClientId=c)
        if shape.kind == 'sphere':
            return pb.createVisualShape(pb.GEOM_SPHERE, radius=shape.radius, rgbaColor=rgba,
                                        visualFramePosition=pos, physicsClientId=c)
        if shape.kind == 'plane':
            size = shape.size or (100.0, 100.0)
            return pb.createVisualShape(pb.GEOM_BOX, halfExtents=[size[0] / 2.0, size[1] / 2.0, 0.0005],
                                        rgbaColor=[0.8, 0.8, 0.8, 1.0], visualFramePosition=pos,
                                        physicsClientId=c)
        return None

    # -- robots ---------------------------------------------------------------------------------
    def spawn_urdf(self, name, urdf_model, urdf_xml, position=(0, 0, 0), orientation=(0, 0, 0, 1)):
        """Spawns a parsed URDF (urdf_model.RobotModel) under `name`; returns its Body."""
        if name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % name)
        path = os.path.join(self._tmpdir, '%s.urdf' % name.replace('/', '_'))
        with open(path, 'w') as f:
            f.write(prepare_urdf_for_bullet(urdf_xml, urdf_model))
        flags = pb.URDF_MERGE_FIXED_LINKS | pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_MAINTAIN_LINK_ORDER \
            | pb.URDF_USE_IMPLICIT_CYLINDER
        try:
            body_id = pb.loadURDF(path, basePosition=position, baseOrientation=orientation, flags=flags,
                                  physicsClientId=self.client)
        except pb.error as err:
            raise PhysicsError("PyBullet could not load the URDF of '%s': %s" % (name, err))
        body = Body(self.client, name, body_id, False, 'urdf')
        body.source = ('urdf', urdf_model, urdf_xml)
        for link, index in body.link_index.items():
            # PyBullet's default link damping (0.04) has no counterpart in Gazebo: a free wheel would slow down.
            pb.changeDynamics(body_id, index, lateralFriction=min(link_friction(urdf_model, link), self.ground_mu),
                              physicsClientId=self.client)
            # separate call: PyBullet ignores the friction when damping comes in the same call
            pb.changeDynamics(body_id, index, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client)
        for joint in body.joints.values():
            pb.setJointMotorControl2(body_id, joint.index, pb.VELOCITY_CONTROL, force=0.0,
                                     physicsClientId=self.client)
        self.bodies[name] = body
        return body

    def remove(self, name):
        body = self.bodies.pop(name)
        pb.removeBody(body.id, physicsClientId=self.client)
        for _, extra in getattr(body, 'extra_bodies', []):
            pb.removeBody(extra, physicsClientId=self.client)

    # -- state ----------------------------------------------------------------------------------
    def joint_states(self, body, indices):
        states = pb.getJointStates(body.id, indices, physicsClientId=self.client)
        return [JointState(s[0], s[1]) for s in states]

    def joint_states_raw(self, body, indices):
        """PyBullet's own tuples (position, velocity, reaction forces, applied torque) of the joints:
        the update loop's read, without building a JointState per joint."""
        return pb.getJointStates(body.id, indices, physicsClientId=self.client)

    def apply_efforts(self, body, indices, efforts):
        """Torques (or forces) for one step: PyBullet clears them after every stepSimulation."""
        pb.setJointMotorControlArray(body.id, indices, pb.TORQUE_CONTROL, forces=efforts,
                                     physicsClientId=self.client)

    def drive_velocities(self, body, indices, velocities, max_forces):
        pb.setJointMotorControlArray(body.id, indices, pb.VELOCITY_CONTROL, targetVelocities=velocities,
                                     forces=max_forces, physicsClientId=self.client)

    def drive_positions(self, body, indices, positions, max_forces):
        pb.setJointMotorControlArray(body.id, indices, pb.POSITION_CONTROL, targetPositions=positions,
                                     forces=max_forces, physicsClientId=self.client)

    def set_joint_position(self, body, joint_name, position, velocity=0.0):
        joint = body.joints[joint_name]
        pb.resetJointState(body.id, joint.index, position, velocity, physicsClientId=self.client)

    def set_pose(self, body, position, orientation, linear=(0, 0, 0), angular=(0, 0, 0)):
        pb.resetBasePositionAndOrientation(body.id, position, orientation, physicsClientId=self.client)
        pb.resetBaseVelocity(body.id, linear, angular, physicsClientId=self.client)

    def link_state(self, body, link):
        """World pose and twist of a link (the base's for index -1)."""
        index = body.link_index[link]
        if index < 0:
            return body.frame_pose(), body.twist()
        s = pb.getLinkState(body.id, index, computeLinkVelocity=1, computeForwardKinematics=1,
                            physicsClientId=self.client)
        return Pose(tuple(s[4]), tuple(s[5])), Twist(tuple(s[6]), tuple(s[7]))

    def apply_joint_effort(self, body, joint_name, effort):
        joint = body.joints[joint_name]
        pb.setJointMotorControl2(body.id, joint.index, pb.TORQUE_CONTROL, force=effort,
                                 physicsClientId=self.client)

    def step(self):
        pb.stepSimulation(physicsClientId=self.client)

    def reset_to_spawn(self, body):
        pos, orn = body.spawn_pose
        self.set_pose(body, pos, orn)
        for joint in body.joints.values():
            pb.resetJointState(body.id, joint.index, body.initial_joint_positions.get(joint.name, 0.0), 0.0,
                               physicsClientId=self.client)

    def follow_with_camera(self, body, distance=1.5, yaw_offset=0.0, pitch=-30.0):
        if not self.gui:
            return
        pos, orn = body.pose()
        yaw = math.degrees(pb.getEulerFromQuaternion(orn)[2]) - 90.0 + yaw_offset
        pb.resetDebugVisualizerCamera(distance, yaw, pitch, pos, physicsClientId=self.client)

    def close(self):
        if self.client >= 0:
            try:
                pb.disconnect(physicsClientId=self.client)
            except pb.error:
                pass
            self.client = -1
        shutil.rmtree(self._tmpdir, ignore_errors=True)


def link_friction(urdf_model, link):
    """mu of a (merged) PyBullet link: the smaller of mu1/mu2 of the URDF links merged into it that
    carry collision geometry (Gazebo keeps friction per collision; Bullet has one per link), 1 if none says."""
    mus = []
    for name, spec in urdf_model.links.items():
        if urdf_model.lumped_link(name) != link or not spec.collisions:
            continue
        props = urdf_model.gazebo_refs.get(name, {})
        values = [props[k] for k in ('mu1', 'mu2') if isinstance(props.get(k), float)]  # the reader warned of others
        if values:
            mus.append(min(values))
    return min(mus) if mus else 1.0


def prepare_urdf_for_bullet(urdf_xml, urdf_model):
    """The URDF as PyBullet should read it: negligible inertia for links that declare none;
    <gazebo>, <transmission> and sensor blocks dropped; mesh geometry dropped (not loadable here)."""
    root = ET.fromstring(urdf_xml)
    for tag in ('gazebo', 'transmission'):
        for el in root.findall(tag):
            root.remove(el)
    for link in root.findall('link'):
        if link.find('inertial') is None:
            inertial = ET.SubElement(link, 'inertial')
            ET.SubElement(inertial, 'mass', value=repr(NEGLIGIBLE_MASS))
            ET.SubElement(inertial, 'inertia', ixx=repr(NEGLIGIBLE_INERTIA), iyy=repr(NEGLIGIBLE_INERTIA),
                          izz=repr(NEGLIGIBLE_INERTIA), ixy='0', ixz='0', iyz='0')
        for kind in ('visual', 'collision'):
            for el in link.findall(kind):
                geom = el.find('geometry')
                if geom is not None and geom.find('mesh') is not None:
                    link.remove(el)
    ET.indent(root)  # PyBullet's URDF reader fails on some very long lines (a one-line document)
    return ET.tostring(root, encoding='unicode')
