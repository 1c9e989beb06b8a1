"""The simulated world: physics, models, spawned robots, and time.

This is what gzserver does, minus the ROS services (gazebo_ros_api) and the pacing loop (world_server.py).
Plugins hook in (on_create, on_spawn, ...): gazebo_ros_control gives a robot the control loop that step()
runs. One `step()` is one world update, in gazebo_ros_control's order: for each robot with a control loop,
read its joints, update its controller manager when a control period has elapsed, write the (limited)
efforts; then step the physics. All mutation happens under `lock`, which service threads take.
"""
from __future__ import annotations

import threading
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from racebot_sim_bridge.engine import physics
from racebot_sim_bridge.engine.control_hook import ControlHook
from racebot_sim_bridge.engine.model import Model
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.description import sdf_urdf, urdf_model, urdf_reader
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3, compose

if TYPE_CHECKING:
    from typing import Protocol

    from racebot_sim_bridge.description.sdf_model import SdfModel, World

    class Log(Protocol):
        """What the simulator and its plugins log through (rospy_log.RospyLog: rospy's logerr & co);
        for annotations only, nothing checks it at run time."""
        def error(self, message: str) -> None: ...
        def warn(self, message: str) -> None: ...
        def info(self, message: str) -> None: ...


class SpawnError(ValueError):
    """A spawn request that cannot be carried out; the message is the status_message."""


class Robot:
    """A spawned URDF model: its engine model (`body`, a physics.Model) and its parsed model
    (urdf_model.RobotModel).

    spawn_namespace: the spawn request's robot_namespace (plugins without their own use it). `control`
    is the loop that drives its joints (a control_hook.ControlHook), set by the plugin that does
    (gazebo_ros_control's, when the URDF declares it), else None; step() runs it."""

    def __init__(self, name: str, body: Model, model: urdf_model.RobotModel, spawn_namespace: str = '') -> None:
        self.name = name
        self.body = body
        self.model = model
        self.spawn_namespace = spawn_namespace
        self.control: ControlHook | None = None


class Simulator:
    def __init__(self, world_spec: World, io: Any, log: Log, get_params: Callable[[str], Any]) -> None:
        """world_spec: sdf_model.World; io: controller_io.RosIO-like; get_params(path) -> value or None."""
        self.spec = world_spec  # what the world file says: read, never written (live state is below)
        self.io = io
        self.log = log
        self.get_params = get_params
        # Live world state, which set_physics_properties and the light services change: the step size, the
        # update rate the world server paces by, the lights (the gravity is the PhysicsWorld's).
        self.step_size = world_spec.physics.max_step_size
        self.real_time_update_rate = world_spec.physics.real_time_update_rate
        self.lights = list(world_spec.lights)
        self.world = physics.PhysicsWorld(self.step_size, world_spec.physics.gravity,  # DIRECT: see viewer.py
                                          friction_model=world_spec.physics.friction_model)
        self.world.set_solver(numSolverIterations=world_spec.physics.ode['sor_pgs_iters'])  # <ode><solver><iters>
        self.rendering = False  # a window shows this world (set by the world server)
        self.node_namespace = '/'  # the world server node's namespace: relative plugin namespaces resolve in it
        self.lock = threading.RLock()
        self.time = 0.0
        self.steps = 0
        self._epoch = (0, 0.0)  # (steps, time) when the step size last changed: time = t0 + (steps - s0) * step
        self.paused = False
        # World::SetPhysicsEnabled: False, the world updates (time, hooks) without a physics step
        # (gazebo_ros_joint_pose_trajectory turns it off while it plays a trajectory)
        self.physics_enabled = True
        self.robots = {}
        self._controls: list[ControlHook] = []  # the robots' control loops (Robot.control), in spawn order
        self.world_models = self.world.load_world(world_spec, warn=lambda m: self.log.warn('world: %s' % m))
        # Extension points (plugins, sensors, odometry truth): on_create(robot) once a URDF robot's body is
        # built, before it joins the world (a plugin that may refuse the spawn, with SpawnError, attaches
        # here: gazebo_ros_control); on_spawn(robot) after it joined; on_delete(robot) before it goes,
        # after_step(time) after every physics step; all under `lock`.
        # before_physics(time) runs after the robots' writes, just before the physics step, with the
        # time the step ends at (Gazebo's sim time at WorldUpdateBegin): apply_body_wrench & co.
        # on_reset() after reset_world / reset_simulation (model plugins' Reset).
        self.on_create = []
        self.on_spawn = []
        self.on_reset = []
        self.on_delete = []
        self.after_step = []
        self.before_physics = []

    def set_step_hook(self, hooks: str, hook: Callable[[float], None], wanted: bool, first: bool = False) -> None:
        """Puts `hook` into (or takes it out of) the step hook list named `hooks` ('before_physics' or
        'after_step'): a component whose work comes and goes (plugins, sensors, force jobs) is called only while
        it has some, as every hook costs each of the thousands of steps a second. `first`: before the hooks
        already there (gazebo_ros's world services: its system plugin's update runs before the model plugins').
        The list is replaced, not changed, so a step that is walking it (a hook leaving from its own call) is
        not disturbed."""
        current = getattr(self, hooks)
        if wanted and hook not in current:
            setattr(self, hooks, [hook] + current if first else current + [hook])
        elif not wanted and hook in current:
            setattr(self, hooks, [h for h in current if h != hook])

    # -- spawning -------------------------------------------------------------------------------
    def spawn_urdf(self, name: str, urdf: str | ET.Element, robot_namespace: str = '', position: Vec3 = (0, 0, 0),
                   orientation: Quat = (0, 0, 0, 1), model: urdf_model.RobotModel | None = None) -> Robot:
        """Spawns a URDF; returns the Robot. Raises SpawnError with gazebo_ros's status wording.

        urdf: the URDF text, or its root element already parsed (the spawn's own: it is rewritten for
        PyBullet in place); model: the urdf_model.RobotModel already read from it, or None to read it here.
        Either way the text is parsed once."""
        with self.lock:
            if not name:
                raise SpawnError('SpawnModel: Failure - no model name given; pass -model NAME')
            if name in self.world.bodies:
                raise SpawnError('SpawnModel: Failure - model name %s already exist. Delete it first '
                                 '(rosservice call /gazebo/delete_model %s) or spawn with another -model name'
                                 % (name, name))
            if model is None:
                try:
                    if isinstance(urdf, (str, bytes, bytearray)):
                        urdf = urdf_reader.urdf_root(urdf)
                    model = urdf_reader.parse_urdf(urdf)
                except urdf_model.UrdfError as err:
                    raise SpawnError('SpawnModel: Failure - the URDF of %s is not valid: %s' % (name, err))
            try:
                body = self.world.spawn_urdf(name, model, urdf, position, orientation,
                                             warn=lambda m: self.log.warn('%s: %s' % (name, m)))
            except PhysicsError as err:
                raise SpawnError('SpawnModel: Failure - %s' % err)
            except Exception as err:  # what the checks before PyBullet missed; nothing was added to the world
                raise SpawnError('SpawnModel: Failure - %s could not be built (%s: %s)'
                                 % (name, type(err).__name__, err)) from err
            # From here on a failure takes out all of the model it made: no description may leave a half-made
            # body in the world (stepped every step, reported by no service) or stop the world server.
            robot = Robot(name, body, model, robot_namespace)
            try:
                for hook in self.on_create:
                    hook(robot)
                if robot.control is not None and not isinstance(robot.control, ControlHook):
                    bad, robot.control = robot.control, None
                    raise TypeError('its control loop %r is no ControlHook (engine/control_hook.py)' % (bad,))
            except Exception as err:
                if robot.control is not None:
                    robot.control.close()
                self.world.remove(name)
                if isinstance(err, SpawnError):
                    raise
                raise SpawnError('SpawnModel: Failure - %s could not be set up (%s: %s); it is removed'
                                 % (name, type(err).__name__, err)) from err
            self.robots[name] = robot
            self._refresh_controls()
            try:
                for hook in self.on_spawn:
                    hook(robot)
            except Exception as err:
                self.delete_model(name)
                raise SpawnError('SpawnModel: Failure - the plugins or sensors of %s could not start (%s: %s); '
                                 'it is removed' % (name, type(err).__name__, err)) from err
            return robot

    def spawn_sdf_robot(self, model: SdfModel, robot_namespace: str = '') -> Robot:
        """Spawns an SDF model with joints, plugins or sensors (sdf_model.SdfModel.is_robot) through the URDF
        path (sdf_urdf.py), at its <pose>; returns the Robot. SpawnError when it cannot be."""
        try:
            conversion = sdf_urdf.model_urdf(model)
        except sdf_urdf.ConversionError as err:
            raise SpawnError('SpawnModel: Failure - the SDF model %s cannot be simulated: %s' % (model.name, err))
        for w in conversion.warnings:
            self.log.warn(w)
        position, orientation = compose(model.pose, conversion.root_pose)
        robot = self.spawn_urdf(model.name, conversion.root, robot_namespace, position, orientation)
        if conversion.root_pose != sdf_urdf.IDENTITY:  # the services report the SDF model frame
            robot.body.model_offset = conversion.root_pose
        return robot

    def spawn_world_robots(self) -> list[Robot]:
        """Spawns the world file's robots (models with joints, plugins or sensors), once the plugin and
        sensor managers listen to on_spawn; returns the Robots. One that cannot be spawned is warned about
        and left out."""
        robots = []
        for model in self.spec.models:
            if model.is_robot and model.name not in self.world.bodies:
                try:
                    robots.append(self.spawn_sdf_robot(model))
                except SpawnError as err:
                    self.log.warn('world: %s; the world loads without it' % err)
        return robots

    def delete_model(self, name: str) -> None:
        with self.lock:
            if name not in self.world.bodies:
                raise KeyError(name)
            robot = self.robots.pop(name, None)
            if robot is not None:
                self._refresh_controls()
                for hook in self.on_delete:
                    hook(robot)
                if robot.control is not None:
                    robot.control.close()
            self.world.remove(name)

    def _refresh_controls(self):
        """A new list (a step walking the old one is not disturbed) when a robot comes or goes."""
        self._controls = [r.control for r in self.robots.values() if r.control is not None]

    # -- time ---------------------------------------------------------------------------------
    def set_paused(self, paused: bool) -> None:
        """pause_physics / unpause_physics. Taken under the step lock, as Gazebo's World::SetPaused takes
        the lock its World::Step holds: once a pause has returned, the update under way is done and
        step_unless_paused starts no other, so a request made after the pause (a controller switch,
        a state read) sees the world stand still."""
        with self.lock:
            self.paused = paused

    def step_unless_paused(self) -> bool:
        """step() unless paused, the flag read under the lock that step holds; whether it stepped."""
        with self.lock:
            if self.paused:
                return False
            self._step()
            return True

    def steps_until(self, time_limit: float, wall_limit: float) -> int:
        """Updates, holding the lock, until the sim time reaches `time_limit`, time.perf_counter() `wall_limit`, or
        a pause (checked before each, as step_unless_paused); how many were made (0: paused). As fast as possible
        the world server runs its updates so between two of its checks (/clock, state topics): the lock and the
        loop's bookkeeping once, not per update. A pause or a service waits for the end of the run, at most
        until wall_limit."""
        count = 0
        perf_counter = time.perf_counter
        with self.lock:
            while not self.paused:
                self._step()
                count += 1
                if self.time >= time_limit or perf_counter() >= wall_limit:
                    break
        return count

    def step(self) -> None:
        """One world update (physics step), each robot's control loop (read, controller manager update
        when its control period has elapsed, write) before it, inline: it runs thousands of times a second."""
        with self.lock:
            self._step()

    def _step(self) -> None:
        """One world update: each robot's ControlHook as control_hook.py describes, the hooks, the physics step."""
        t = self.time
        world = self.world
        for c in self._controls:
            c.read(world)
            if c.last_update is None or t - c.last_update >= c.control_period - 1e-9:
                period = 0.0 if c.last_update is None else t - c.last_update
                c.cm.update(t, period if period > 0 else c.control_period)
                c.last_update = t
            c.write(world, self.step_size)
        s0, t0 = self._epoch  # the time this step ends at: from the last step size change, computed once
        t_next = t0 + (self.steps + 1 - s0) * self.step_size
        for hook in self.before_physics:
            hook(t_next)
        if self.physics_enabled:
            world.step()
        self.steps += 1
        self.time = t_next
        for hook in self.after_step:
            hook(t_next)

    def set_step_size(self, step_size: float) -> None:
        """A new physics step (set_physics_properties); time goes on from where it is."""
        with self.lock:
            self._epoch = (self.steps, self.time)
            self.step_size = step_size
            self.world.set_step_size(step_size)

    def reset_simulation(self) -> None:
        """reset_world, and time back to 0."""
        with self.lock:
            self.reset_world()
            self.steps = 0
            self.time = 0.0
            self._epoch = (0, 0.0)

    def reset_world(self) -> None:
        """Poses, velocities and joints back to the start; time goes on. ros_control is left as it
        was, as gazebo_ros_control leaves it: controllers keep running with their commands and
        state, joint readings go on unwrapping from where they were, and only the plugin's last
        update time goes back to 0 (its Reset()), so the next update comes at once after
        reset_world, with the time since 0 as its period, and one control period after
        reset_simulation."""
        with self.lock:
            self.world.reset()
            for c in self._controls:
                c.last_update = 0.0
            for hook in self.on_reset:
                hook()

    # -- queries ------------------------------------------------------------------------------
    def model_names(self) -> list[str]:
        return list(self.world.bodies)

    def body(self, name: str) -> Model | None:
        return self.world.bodies.get(name)

    def close(self) -> None:
        with self.lock:
            for c in self._controls:
                c.close()
            self.world.close()

