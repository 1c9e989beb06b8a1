"""A URDF robot spawned as one PyBullet body, set up as Gazebo would simulate it; the Model that holds it.

No ROS here. PhysicsWorld.spawn_urdf calls spawn(). Gazebo behaviours reproduced here, because the car drives
differently without them:
- fixed-joint children are merged into their parent link as Gazebo lumps them (bullet_urdf.py and
  urdf_lumping.py, not PyBullet's URDF_MERGE_FIXED_LINKS, which would also merge a joint Gazebo keeps:
  preserveFixedJoint);
- a URDF link without <inertial> would get 1 kg in PyBullet; Gazebo ignores its mass, so it gets a negligible
  one here (the racebot would otherwise be ~6 kg too heavy);
- friction: ODE takes the smaller mu of two touching surfaces, Bullet multiplies them. A robot link gets
  min(its mu, the ground's mu) (static world surfaces have 1: sdf_bodies.py), so the product is Gazebo's
  minimum for the contacts that matter (robot on ground);
- inertia as Gazebo's ODE takes it (bullet_urdf.py, ../kinematics/inertia.py): one that is not positive definite
  is the identity (1 kg m^2 about each axis, dBodySetMass's fallback; PyBullet would zero it), with one warning;
  one PyBullet's importer would zero though ODE takes it (a moment larger than the other two together) is set
  after loading;
- joint velocity motors (PyBullet's default) are switched off: joints move only by applied effort;
- a static URDF (sdformat's model <static> from <gazebo><static>true</static></gazebo>) gets a fixed base: it
  neither falls nor is pushed (its movable joints still move, where Gazebo holds every link of it);
- URDF cylinders (the wheels) stay true cylinders (URDF_USE_IMPLICIT_CYLINDER): PyBullet's default
  convex-hull approximation makes the contact point jump between hull vertices, and the car veered
  ~2 degrees per metre driving straight with the hinges locked.
Meshes arrive as checked OBJ files in the mesh cache (urdf_assets.py); a dynamic body collides with one convex
hull per part of a mesh. URDF colours are written into the URDF before loadURDF, so a copy built from its
BodySource (the viewer's) looks the same.
"""
from __future__ import annotations

import os
import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import TYPE_CHECKING

import pybullet as pb

from racebot_sim_bridge.description import urdf_assets
from racebot_sim_bridge.engine import mimic_joints
from racebot_sim_bridge.engine.bullet_urdf import FrictionAxes, joint_friction, link_friction, link_friction_axes, \
    link_laser_retro, prepare_urdf_for_bullet, wheel_axes
from racebot_sim_bridge.engine.joint_damping import ImplicitDampers, implicit_joints
from racebot_sim_bridge.engine.model import Model
from racebot_sim_bridge.engine.physics_types import BodyKind, BodySource, PhysicsError
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.engine.wheel_friction import AlignedWheel, WheelFriction
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3, rotate_back

if TYPE_CHECKING:
    from racebot_sim_bridge.description.urdf_model import RobotModel
    from racebot_sim_bridge.engine.load_trial import LoadTrial

# Links in one PyBullet body whose state it can report (SharedMemoryPublic.h MAX_DEGREE_OF_FREEDOM): with
# more, loadURDF succeeds and then every state query (getBasePositionAndOrientation, ...) fails.
MAX_BULLET_LINKS = 128
ALIGNED = 0.999  # |cos| of the angle within which <fdir1> or an axle lies along an axis of a link's frame
FLAGS = pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_MAINTAIN_LINK_ORDER | pb.URDF_USE_IMPLICIT_CYLINDER


class UrdfSpawn:
    """How a world spawns URDFs: its `client`, `applied` (the world's wrench accumulator, given each Model),
    `laser_retro` (the world's {(body id, link index): laser_retro}, given each robot's) and `visuals` (build
    visual shapes)."""

    def __init__(self, client: PybulletClient, applied: dict, laser_retro: dict, visuals: bool) -> None:
        self.client = client
        self.applied = applied
        self.laser_retro = laser_retro
        self.visuals = visuals

    def spawn(self, name: str, urdf_model: RobotModel, urdf: str | ET.Element, position: Vec3 = (0, 0, 0),
              orientation: Quat = (0, 0, 0, 1), warn: Callable[[str], None] | None = None, ground_mu: float = 1.0,
              load_trial: LoadTrial | None = None) -> Model:
        """Spawns a parsed URDF (urdf_model.RobotModel) under `name`; returns its Model. `urdf`: the URDF
        text, or its root element as already parsed (rewritten here in place: meshes resolved, then what
        PyBullet reads). Its meshes are resolved and converted first (urdf_assets); warn(message) hears of
        those that cannot be (the element is left out, the robot is spawned). PhysicsError when it cannot
        be spawned: nothing of it stays in the world then. `ground_mu`: the world's ground's mu (friction above);
        `load_trial`: a LoadTrial that loads the URDF in a helper first, or None."""
        root = urdf if isinstance(urdf, ET.Element) else ET.fromstring(urdf)
        urdf_assets.resolve_assets(root, urdf_model, warn)
        urdf_xml = ET.tostring(root, encoding='unicode')  # what a copy is built from: before PyBullet's rewrite
        # A root link named world is the world (sdformat's URDF reader): its joints hold the robot to the world.
        # A static model (<gazebo><static>true</static></gazebo>) is held where it is spawned, as Gazebo holds it.
        fixed = urdf_model.root_link == 'world' or urdf_model.static
        bullet = prepare_urdf_for_bullet(root, urdf_model, self.visuals, name, warn)
        links = len(root.findall('link'))
        if links > MAX_BULLET_LINKS:
            raise PhysicsError("'%s' has %d links once fixed joints are merged as Gazebo merges them; PyBullet "
                               "cannot report the state of a body of more than %d (its MAX_DEGREE_OF_FREEDOM): "
                               "join links with fixed joints or spawn it as several models"
                               % (name, links, MAX_BULLET_LINKS))
        body_id = self._load(name, bullet.text, position, orientation, fixed, load_trial)
        try:
            return self._set_up(name, body_id, urdf_model, urdf_xml, ground_mu, bullet.moments, warn)
        except Exception as err:  # a body half set up would stay in the world, stepped and never reported
            self.client.removeBody(body_id)
            for key in [k for k in self.laser_retro if k[0] == body_id]:
                del self.laser_retro[key]
            raise PhysicsError("PyBullet loaded the URDF of '%s' but could not set its body up (%s: %s); it is "
                               "removed" % (name, type(err).__name__, err)) from err

    def _load(self, name, bullet_urdf, position, orientation, fixed, load_trial):
        """loadURDF of the rewritten text, tried in the load trial's helper first; the body id."""
        # PyBullet reads a URDF from a file, once: the file lives only as long as the load, so a process
        # that is killed leaves nothing behind in /tmp.
        with tempfile.TemporaryDirectory(prefix='racebot_urdf_') as tmp:
            path = os.path.join(tmp, 'robot.urdf')
            with open(path, 'w') as f:
                f.write(bullet_urdf)
            trouble = load_trial.check(path, FLAGS, fixed) if load_trial is not None else None
            if trouble is not None:
                raise PhysicsError("'%s' is not loaded: %s; the world goes on without it. Report the URDF to "
                                   'racebot with this message' % (name, trouble))
            try:
                return self.client.loadURDF(path, basePosition=position, baseOrientation=orientation,
                                            flags=FLAGS, useFixedBase=fixed)
            except pb.error as err:
                raise PhysicsError("PyBullet could not load the URDF of '%s': %s" % (name, err))

    def _friction_axes(self, name: str, body_id: int, index: int, link: str, axes: FrictionAxes, ground_mu: float,
                       warn: Callable[[str], None] | None) -> None:
        """Gazebo's mu1 along fdir1 and mu2 across it (each the smaller of the link's and the ground's, as ODE takes
        each direction's) as Bullet's anisotropic friction: a scale per axis of the link's collision frame (its
        inertial frame in PyBullet) on the link's friction. Exact where fdir1 lies along one of those axes; a
        wheel's fdir1 square to its axle gives mu1 to both axes square to the axle (the rolling direction's as it
        turns), mu2 to the axle's. Otherwise the smaller mu stays, with one warning."""
        client = self.client
        mu1, mu2 = min(axes.mu1, ground_mu), min(axes.mu2, ground_mu)
        if mu1 == mu2:
            return
        inertial = client.getDynamicsInfo(body_id, index)[4]  # the collision frame's orientation in the link's
        fdir1 = rotate_back(inertial, axes.fdir1)
        along = max(range(3), key=lambda k: abs(fdir1[k]))
        if abs(fdir1[along]) < ALIGNED:
            if warn is not None:
                warn("'%s': link '%s' has <fdir1> %s with mu1 %g and mu2 %g; racebot simulates different mu1 and mu2 "
                     "only along an axis of the link's inertial frame, so it takes the smaller, %g, in every "
                     "direction" % (name, link, ' '.join('%g' % v for v in axes.fdir1), axes.mu1, axes.mu2,
                                    min(mu1, mu2)))
            return
        scale = [mu2, mu2, mu2]
        scale[along] = mu1
        if axes.axle is not None:
            axle = rotate_back(inertial, axes.axle)
            spin = max(range(3), key=lambda k: abs(axle[k]))
            if abs(axle[spin]) >= ALIGNED:
                scale = [mu1, mu1, mu1]
                scale[spin] = mu2
        top = max(scale)
        client.changeDynamics(body_id, index, lateralFriction=top, anisotropicFriction=[v / top for v in scale])

    def _set_up(self, name, body_id, urdf_model, urdf_xml, ground_mu, moments, warn=None):
        """The Model of a URDF PyBullet just loaded, with Gazebo's friction, damping and joint motors, and the
        principal `moments` ({link: (x, y, z)}) its importer would have zeroed."""
        client = self.client
        # urdf_xml has its meshes resolved: a copy needs no package path
        model = Model(client, self.applied, name, body_id, urdf_model.static,
                      BodySource(BodyKind.URDF, urdf_model, urdf_xml))
        free = not (urdf_model.static or urdf_model.root_link == 'world')  # a fixed base is no rigid body to solve
        wheels = []
        for link, index in model.link_index.items():
            # PyBullet's default link damping (0.04) has no counterpart in Gazebo: a free wheel would slow down.
            friction = min(link_friction(urdf_model, link), ground_mu)
            client.changeDynamics(body_id, index, lateralFriction=friction)
            wheel = wheel_axes(urdf_model, link) if free else None
            if wheel is not None:  # wheel_friction.py takes its contacts' friction over while a plugin holds it
                wheels.append(AlignedWheel(index, wheel.axle, min(wheel.mu_roll, ground_mu),
                                           min(wheel.mu_axle, ground_mu)))
            axes = link_friction_axes(urdf_model, link)
            if axes is not None:
                self._friction_axes(name, body_id, index, link, axes, ground_mu, warn)
            # separate call: PyBullet ignores the friction when damping comes in the same call
            client.changeDynamics(body_id, index, linearDamping=0.0, angularDamping=0.0)
            if link in moments:  # changeDynamics takes the moments the importer refuses
                client.changeDynamics(body_id, index, localInertiaDiagonal=moments[link])
            retro = link_laser_retro(urdf_model, link)
            if retro:
                self.laser_retro[(body_id, index)] = retro
        for joint_name, joint in model.joints.items():
            # PyBullet's default velocity motors off; in their place the URDF <dynamics friction>, which Gazebo
            # applies as Coulomb friction: a motor holding velocity 0 with at most that force. (<dynamics damping>
            # PyBullet's URDF importer applies itself, explicitly as Gazebo does, but for an implicitSpringDamper
            # joint: joint_damping.py.) A joint a controller drives by velocity or position gets the hardware's
            # motor instead (DefaultRobotHWSim.write_sim).
            client.setJointMotorControl2(body_id, joint.index, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                         force=joint_friction(urdf_model, joint_name))
        implicit = implicit_joints(urdf_model, model.joints)
        if implicit:
            for index, *_ in implicit:
                client.changeDynamics(body_id, index, jointDamping=0.0)
            model.set_dampers(ImplicitDampers(client, body_id, urdf_model.root_link == 'world', implicit))
        model.mimics = mimic_joints.couple(client, body_id, model.joints, urdf_model)
        if wheels:
            model.wheel_friction = WheelFriction(client, body_id, wheels)
        return model
