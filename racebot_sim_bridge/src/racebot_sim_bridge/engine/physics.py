"""PhysicsWorld: one PyBullet physics client and the models in it, as gazebo::physics::World is the world.

No ROS here. PhysicsWorld owns its client through a pybullet_client.PybulletClient (`world.client`),
whose functions carry the client's id, so several worlds can live in one process (tests do that). It keeps
the models by name (`bodies`), gravity, the step size and solver settings, and steps; the rest belongs to
the objects it holds, named after Gazebo's:
- Model (model.py): a model's body, its links and joints by name, its pose and velocity, the joints' array
  I/O of the update loop, reset to its spawn state, removal;
- Link (link.py): a link's pose, velocities, forces and torques, mass;
- Joint (joint.py): a joint's position, velocity, effort, limits and damping, motor commands.
A world's static SDF models are built by sdf_bodies.py, spawned URDF robots by urdf_spawn.py (where the
Gazebo behaviours they reproduce are listed).
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import TYPE_CHECKING

import pybullet as pb

from racebot_sim_bridge.engine import one_sided_mesh, sdf_bodies
from racebot_sim_bridge.engine.model import Model
from racebot_sim_bridge.engine.physics_types import BodyKind, BodySource, PhysicsError
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.engine.urdf_spawn import UrdfSpawn
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3

if TYPE_CHECKING:
    from racebot_sim_bridge.description import sdf_model
    from racebot_sim_bridge.description.urdf_model import RobotModel


class PhysicsWorld:
    """Owns one PyBullet client (`client`, a pybullet_client.PybulletClient) and its models (`bodies`, {name:
    Model}). `gui=True` opens PyBullet's own window (needs a display). `visuals=False` builds no visual shapes
    (no meshes to draw, no colours): for a client that only steps physics and casts rays while another client
    draws.

    `laser_retro`: {(PyBullet body id, link index): laser_retro of its collisions} (a laser ray's intensity;
    0 if absent). `applied`: {(body id, link index): [fx, fy, fz, tx, ty, tz]} applied since the last step
    (Link.apply_wrench; cleared by step()). `ground_mu`: the ground plane's mu (robots' friction is held to it).
    `load_trial`: a LoadTrial (engine/load_trial.py) that loads each URDF in a helper first (the world
    server's world), else None. Both dicts are changed in place, never replaced: the Models and the ray sensors
    hold them."""

    def __init__(self, step_size: float = 0.001, gravity: Vec3 = (0.0, 0.0, -9.8), gui: bool = False,
                 visuals: bool = True, friction_model: str = 'pyramid_model') -> None:
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
        self.set_friction_model(friction_model)
        self.bodies = {}
        self.laser_retro = {}
        self.ground_mu = 1.0
        self.applied = {}
        self._damped = []  # the models with implicitly damped joints (Model.dampers), in spawn order
        self._wheeled = []  # the models with fdir1-aligned wheel friction (Model.wheel_friction)
        self.load_trial = None
        self._urdf = UrdfSpawn(self.client, self.applied, self.laser_retro, visuals)

    # -- models -------------------------------------------------------------------------------
    def load_world(self, world: sdf_model.World, warn: Callable[[str], None] | None = None) -> list[str]:
        """Creates every model of a parsed sdf_model.World but its robots (Model.is_robot, spawned through
        the URDF path by the Simulator); returns the names created. A model whose links have no shape left
        (a mesh missing, none written) is built all the same, as Gazebo keeps it (sdf_bodies.py). With `warn`,
        a model that cannot be built (no link, a shape PyBullet refuses) is skipped and warn(message) told;
        without it, PhysicsError."""
        created = []
        for model in world.models:
            if model.is_robot:
                continue  # joints, plugins or sensors: Simulator.spawn_world_robots spawns it as a URDF
            try:
                self.add_sdf_model(model, warn)
            except PhysicsError as err:
                if warn is None:
                    raise
                warn('%s; the model is skipped, the world loads without it' % err)
                continue
            created.append(model.name)
        return created

    def add_sdf_model(self, model: sdf_model.SdfModel, warn: Callable[[str], None] | None = None) -> Model:
        """One PyBullet body per SDF link (sdf_bodies.py); returns the new Model. warn(message) hears of what is
        simulated otherwise than written (an inertia that is not positive definite)."""
        if model.name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % model.name)
        built, ground_mu = sdf_bodies.build_model(self.client, self.applied, model, self.visuals, self.laser_retro,
                                                  warn)
        if ground_mu is not None:
            self.ground_mu = ground_mu
        self.bodies[model.name] = built
        return built

    def spawn_urdf(self, name: str, urdf_model: RobotModel, urdf: str | ET.Element, position: Vec3 = (0, 0, 0),
                   orientation: Quat = (0, 0, 0, 1), warn: Callable[[str], None] | None = None) -> Model:
        """Spawns a parsed URDF (urdf_model.RobotModel) under `name`; returns its Model (urdf_spawn.py says
        how). `urdf`: the URDF text, or its root element as already parsed (rewritten in place). warn(message)
        hears of meshes that cannot be resolved (the element is left out, the robot is spawned). A robot spawned
        sunk into a one-sided floor mesh is lifted onto its top (one_sided_mesh.lift_onto_floor)."""
        if name in self.bodies:
            raise PhysicsError("a model named '%s' already exists" % name)
        model = self._urdf.spawn(name, urdf_model, urdf, position, orientation, warn, self.ground_mu,
                                 self.load_trial)
        if not (urdf_model.static or urdf_model.root_link == 'world'):  # a body held in place is never pushed
            floors = [i for m in self.bodies.values() for i in m.one_sided_bodies]
            if one_sided_mesh.lift_onto_floor(self.client, model.id, floors):
                model.spawn_pose = model.pose()  # Model::Reset puts it back where it stands, not inside the floor
        if model.dampers is not None:
            self._damped.append(model)
        if model.wheel_friction is not None:
            self._wheeled.append(model)
        self.bodies[name] = model
        return model

    def add_copy(self, name: str, source: BodySource) -> Model:
        """Builds here a copy of another client's model from its Model.source (a window's or a render
        worker's copy of the simulated world); returns the new Model."""
        if source.kind is BodyKind.SDF:
            return self.add_sdf_model(source.model)
        return self.spawn_urdf(name, source.model, source.urdf_xml)

    def remove(self, name: str) -> None:
        """Takes model `name` out of the world (KeyError when there is none)."""
        model = self.bodies.pop(name)
        model.remove()
        if model in self._damped:
            self._damped = [m for m in self._damped if m is not model]
        if model in self._wheeled:
            self._wheeled = [m for m in self._wheeled if m is not model]
        gone = set(model.body_ids())
        for key in [k for k in self.laser_retro if k[0] in gone]:
            del self.laser_retro[key]

    # -- world settings -----------------------------------------------------------------------
    def set_gravity(self, gravity: Vec3) -> None:
        self.gravity = tuple(gravity)
        self.client.setGravity(*self.gravity)

    def set_step_size(self, step_size: float) -> None:
        self.step_size = step_size
        self.client.setTimeStep(step_size)

    def set_friction_model(self, friction_model: str) -> None:
        """ODE's friction model by its SDF name (sdf_model.FRICTION_MODELS). Gazebo's default is the pyramid: each
        of the two friction directions is limited to mu times the normal force on its own, where Bullet's default,
        the cone, limits their sum; a wheel that rolls while it pulls sliding casters slips less on the pyramid
        (docs/COMING_FROM_GAZEBO.md)."""
        self.friction_model = friction_model
        self.client.setPhysicsEngineParameter(enableConeFriction=int(friction_model == 'cone_model'))

    def set_solver(self, **params: float) -> None:
        """Constraint solver parameters by PyBullet's names (numSolverIterations, erp, globalCFM)."""
        self.client.setPhysicsEngineParameter(**params)

    # -- time ---------------------------------------------------------------------------------
    def step(self) -> None:
        """One physics step: the implicit dampers' torques and the wheels' friction first, then the applied wrenches
        are forgotten."""
        for model in self._damped:
            model.damp(self.step_size)
        for model in self._wheeled:
            model.wheel_friction.apply(self.step_size)
        self.client.stepSimulation()
        if self.applied:
            self.applied.clear()

    def reset(self) -> None:
        """Every model back to where it was spawned (Model.reset): World::Reset's part in the physics."""
        for model in self.bodies.values():  # static models too: set_model_state moves them
            model.reset()

    def close(self) -> None:
        if self.load_trial is not None:
            self.load_trial.close()
        self.client.close()
