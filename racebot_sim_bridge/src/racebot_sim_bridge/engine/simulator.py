"""The simulated world: physics, models, spawned robots with their ros_control, and time.

This is what gzserver plus gazebo_ros_control do, minus the ROS services (gazebo_services.py) and
the pacing loop (world_server.py). One `step()` is one world update, in gazebo_ros_control's order:
read joints, update the controller manager when a control period has elapsed, write the
(limited) efforts, step the physics. All mutation happens under `lock`, which service threads take.
"""
import threading

from racebot_sim_bridge.engine import physics
from racebot_sim_bridge.gazebo_plugins import plugin_namespace
from racebot_sim_bridge.description import sdf_urdf, urdf_model, urdf_reader
from racebot_sim_bridge.ros_control.controller_manager import ControllerManager
from racebot_sim_bridge.ros_control.hardware_interface import (EFFORT, POSITION, VELOCITY, RobotHW, limited_efforts,
                                                               position_error, read_joint_states)
from racebot_sim_bridge.ros_control.pid import Pid
from racebot_sim_bridge.kinematics.rotations import compose

CONTROL_PLUGIN = 'libgazebo_ros_control.so'


class SpawnError(ValueError):
    """A spawn request that cannot be carried out; the message is the status_message."""


class Robot(object):
    """A spawned URDF model with its RobotHW and (if it declares the control plugin) controllers."""

    def __init__(self, name, body, model, robot_ns, hardware_joints, control_period, spawn_namespace='',
                 pid_gains=None):
        """hardware_joints: urdf_model.hardware_joints(model), or None without gazebo_ros_control;
        spawn_namespace: the spawn request's robot_namespace (plugins without their own use it);
        pid_gains: {joint: Pid} of position or velocity joints that gazebo_ros_control drives through a
        PID (`<ns>/gazebo_ros_control/pid_gains/<joint>` set); the others follow their command directly."""
        self.name = name
        self.body = body
        self.model = model
        self.ns = robot_ns
        self.spawn_namespace = spawn_namespace
        self.control_period = control_period
        self.cm = None
        self.last_update = None
        self.hw = RobotHW(model, hardware_joints) if hardware_joints is not None else None
        self.handles = []
        if self.hw is not None:
            missing = [n for n in self.hw.handles if n not in body.joints]
            if missing:
                raise SpawnError('SpawnModel: Failure - joints %s of the transmissions are not movable joints of '
                                 'the model' % missing)
            self.handles = [self.hw.handles[n] for n in self.hw.names]
            self.indices = [body.joints[h.name].index for h in self.handles]
            self.effort_idx = [i for i, h in zip(self.indices, self.handles) if h.interface == EFFORT]
            self.effort_handles = [h for h in self.handles if h.interface == EFFORT]
            pid_gains = pid_gains or {}
            # DefaultRobotHWSim's POSITION_PID / VELOCITY_PID joints: effort = PID(error), clamped to
            # the effort limit, applied as a force (its writeSim, every world update).
            self.pid_joints = [(h, pid_gains[h.name], body.joints[h.name].index) for h in self.handles
                               if h.interface in (POSITION, VELOCITY) and h.name in pid_gains]
            self.velocity_handles = [h for h in self.handles if h.interface == VELOCITY and h.name not in pid_gains]
            self.position_handles = [h for h in self.handles if h.interface == POSITION and h.name not in pid_gains]
            # What write() passes every step, built once.
            self._drives = [(hs, drive, [body.joints[h.name].index for h in hs], [h.max_effort or 1e3 for h in hs])
                            for hs, drive in ((self.velocity_handles, 'drive_velocities'),
                                              (self.position_handles, 'drive_positions')) if hs]

    def read(self, world):
        if not self.handles:
            return
        # one PyBullet call for all joints; raw tuples (position, velocity, ...), no per-joint objects
        read_joint_states(self.handles, world.joint_states_raw(self.body, self.indices))

    def write(self, world, dt):
        """gazebo_ros_control's writeSim: `dt` is the time since the last write (one world update)."""
        if not self.handles:
            return
        if self.pid_joints:
            efforts = [self._pid_effort(h, pid, dt) for h, pid, _ in self.pid_joints]
            world.apply_efforts(self.body, [i for _, _, i in self.pid_joints], efforts)
        if self.effort_handles:
            world.apply_efforts(self.body, self.effort_idx, limited_efforts(self.effort_handles))
        for hs, drive, indices, forces in self._drives:
            getattr(world, drive)(self.body, indices, [h.limited_command() for h in hs], forces)

    @staticmethod
    def _pid_effort(h, pid, dt):
        target = h.limited_command()
        if h.interface == VELOCITY:
            error = target - h.velocity
        else:
            error = position_error(h, target)
        effort = pid.compute(error, dt)
        if h.max_effort is not None:
            effort = min(max(effort, -h.max_effort), h.max_effort)
        h.effort = effort
        return effort

    def reset_joint_readings(self, world):
        if self.handles:
            for h, s in zip(self.handles, world.joint_states(self.body, self.indices)):
                h.reset_position(s.position)
            self.hw.reset_commands()


class Simulator(object):
    def __init__(self, world_spec, io, log, get_params):
        """world_spec: sdf_model.World; io: controllers.RosIO-like; get_params(path) -> value or None."""
        self.spec = world_spec
        self.io = io
        self.log = log
        self.get_params = get_params
        self.step_size = world_spec.physics.max_step_size
        self.world = physics.PhysicsWorld(self.step_size, world_spec.physics.gravity)  # DIRECT: see viewer.py
        self.rendering = False  # a window shows this world (set by the world server)
        self.node_namespace = '/'  # the world server node's namespace: relative plugin namespaces resolve in it
        self.lock = threading.RLock()
        self.time = 0.0
        self.steps = 0
        self._epoch = (0, 0.0)  # (steps, time) when the step size last changed: time = t0 + (steps - s0) * step
        self.paused = False
        self.robots = {}
        self.world_models = self.world.load_world(world_spec, warn=lambda m: self.log.warn('world: %s' % m))
        # Extension points (sensors, odometry truth): on_spawn(robot) after a URDF robot is spawned,
        # on_delete(robot) before it goes, after_step(time) after every physics step; all under `lock`.
        # before_physics(time) runs after the robots' writes, just before the physics step, with the
        # time the step ends at (Gazebo's sim time at WorldUpdateBegin): apply_body_wrench & co.
        # on_reset() after reset_world / reset_simulation (model plugins' Reset).
        self.on_spawn = []
        self.on_reset = []
        self.on_delete = []
        self.after_step = []
        self.before_physics = []

    def set_step_hook(self, hooks, hook, wanted):
        """Puts `hook` into (or takes it out of) the step hook list named `hooks` ('before_physics' or
        'after_step'): a component whose work comes and goes (plugins, sensors) is called only while it
        has some, as every hook costs each of the thousands of steps a second. The list is replaced, not
        changed, so a step that is walking it (a hook leaving from its own call) is not disturbed."""
        current = getattr(self, hooks)
        if wanted and hook not in current:
            setattr(self, hooks, current + [hook])
        elif not wanted and hook in current:
            setattr(self, hooks, [h for h in current if h != hook])

    # -- spawning -------------------------------------------------------------------------------
    def spawn_urdf(self, name, xml, robot_namespace='', position=(0, 0, 0), orientation=(0, 0, 0, 1)):
        """Spawns a URDF; returns the Robot. Raises SpawnError with gazebo_ros's status wording."""
        with self.lock:
            if not name:
                raise SpawnError('SpawnModel: Failure - no model name given; pass -model NAME')
            if name in self.world.bodies:
                raise SpawnError('SpawnModel: Failure - model name %s already exist. Delete it first '
                                 '(rosservice call /gazebo/delete_model %s) or spawn with another -model name'
                                 % (name, name))
            try:
                model = urdf_reader.parse_urdf(xml)
            except urdf_model.UrdfError as err:
                raise SpawnError('SpawnModel: Failure - the URDF of %s is not valid: %s' % (name, err))
            plugin = model.control_plugin()
            robot_ns = hw_joints = None
            period = self.step_size
            if plugin is not None:
                # gazebo_ros: the plugin's own robotNamespace wins, else the request's, else the model name
                robot_ns = plugin_namespace.control_namespace(plugin.robot_namespace, robot_namespace, name,
                                                              self.node_namespace).rstrip('/')
                if plugin.control_period:
                    period = plugin.control_period
                    if period < self.step_size:
                        self.log.warn('%s: controlPeriod %g s is shorter than the physics step %g s; using the step'
                                      % (name, period, self.step_size))
                        period = self.step_size
                try:
                    hw_joints = urdf_model.hardware_joints(model)
                except urdf_model.UrdfError as err:
                    # gazebo_ros_control: "Could not initialize robot simulation interface"; the model
                    # stays in the world, without a controller manager.
                    self.log.error("%s: %s. gazebo_ros_control is not active for this model: it is spawned without "
                                   "a controller manager (as Gazebo does), so no controller can be loaded for it. "
                                   "Fix the URDF, delete the model and spawn it again" % (name, err))
                    robot_ns = None
                else:
                    if not model.transmissions:
                        self.log.warn("%s: the %s plugin is declared but the URDF has no <transmission>: its "
                                      "controller manager under %s has no joints to control; add a <transmission> "
                                      "per actuated joint" % (name, CONTROL_PLUGIN, robot_ns or '/'))
                for w in model.warnings:
                    self.log.warn('%s: %s' % (name, w))
            elif model.transmissions:
                self.log.warn("%s has <transmission>s but declares no %s plugin: no controller manager for it, so "
                              "its controllers cannot be loaded; add <gazebo><plugin name=\"gazebo_ros_control\" "
                              "filename=\"%s\"/></gazebo> to the URDF" % (name, CONTROL_PLUGIN, CONTROL_PLUGIN))
            else:
                self.log.info("%s declares no %s plugin: no controller manager for it" % (name, CONTROL_PLUGIN))
            for r in self.robots.values():
                if robot_ns is not None and r.ns == robot_ns:
                    raise SpawnError("SpawnModel: Failure - robot namespace '%s' is already used by model '%s' (its "
                                     "controller manager is there); give this model's gazebo_ros_control plugin "
                                     "another <robotNamespace>, or, if it has none, spawn with another "
                                     "-robot_namespace" % (robot_ns or '/', r.name))
            try:
                body = self.world.spawn_urdf(name, model, xml, position, orientation,
                                             warn=lambda m: self.log.warn('%s: %s' % (name, m)))
            except physics.PhysicsError as err:
                raise SpawnError('SpawnModel: Failure - %s' % err)
            try:
                robot = Robot(name, body, model, robot_ns, hw_joints, period, robot_namespace,
                              pid_gains=self._pid_gains(name, robot_ns, hw_joints))
            except SpawnError:
                self.world.remove(name)
                raise
            if robot.hw is not None:
                for w in robot.hw.warnings:
                    self.log.warn('%s: %s' % (name, w))
                ns = robot_ns
                robot.cm = ControllerManager(
                    ns, robot.hw, lambda c, ns=ns: self.get_params('%s/%s' % (ns, c)), self.io, self.log)
                robot.read(self.world)
            self.robots[name] = robot
            for hook in self.on_spawn:
                hook(robot)
            return robot

    def spawn_sdf_robot(self, model, robot_namespace=''):
        """Spawns an SDF model with joints, plugins or sensors (sdf_model.Model.is_robot) through the URDF
        path (sdf_urdf.py), at its <pose>; returns the Robot. SpawnError when it cannot be."""
        try:
            conversion = sdf_urdf.model_urdf(model)
        except sdf_urdf.ConversionError as err:
            raise SpawnError('SpawnModel: Failure - the SDF model %s cannot be simulated: %s' % (model.name, err))
        for w in conversion.warnings:
            self.log.warn(w)
        position, orientation = compose(model.pose, conversion.root_pose)
        robot = self.spawn_urdf(model.name, conversion.urdf, robot_namespace, position, orientation)
        if conversion.root_pose != sdf_urdf.IDENTITY:  # the services report the SDF model frame
            robot.body.model_offset = conversion.root_pose
        return robot

    def spawn_world_robots(self):
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

    def _pid_gains(self, name, robot_ns, hw_joints):
        """{joint: Pid} for the position and velocity joints whose `<ns>/gazebo_ros_control/pid_gains/<joint>`
        is set, as DefaultRobotHWSim reads them at spawn; gains that are set and wrong are warned about and
        the joint follows its command directly."""
        gains = {}
        for joint, interface in hw_joints or ():
            if interface not in (POSITION, VELOCITY):
                continue
            where = '%s/gazebo_ros_control/pid_gains/%s' % (robot_ns, joint)
            params = self.get_params(where)
            if params is None:
                continue
            try:
                gains[joint] = Pid.from_params(params, where)
            except ValueError as err:
                self.log.warn('%s: %s; joint %s follows its command directly instead of through a PID'
                              % (name, err, joint))
        return gains

    def delete_model(self, name):
        with self.lock:
            if name not in self.world.bodies:
                raise KeyError(name)
            robot = self.robots.pop(name, None)
            if robot is not None:
                for hook in self.on_delete:
                    hook(robot)
                if robot.cm is not None:
                    robot.cm.shutdown()
            self.world.remove(name)

    # -- time ---------------------------------------------------------------------------------
    def set_paused(self, paused):
        """pause_physics / unpause_physics. Taken under the step lock, as Gazebo's World::SetPaused takes
        the lock its World::Step holds: once a pause has returned, the update under way is done and
        step_unless_paused starts no other, so a request made after the pause (a controller switch,
        a state read) sees the world stand still."""
        with self.lock:
            self.paused = paused

    def step_unless_paused(self):
        """step() unless paused, the flag read under the lock that step holds; whether it stepped."""
        with self.lock:
            if self.paused:
                return False
            self.step()
            return True

    def step(self):
        """One world update (physics step), gazebo_ros_control's read-update-write around it."""
        with self.lock:
            t = self.time
            world = self.world
            for r in self.robots.values():
                if r.cm is None:
                    continue
                r.read(world)
                if r.last_update is None or t - r.last_update >= r.control_period - 1e-9:
                    period = 0.0 if r.last_update is None else t - r.last_update
                    r.cm.update(t, period if period > 0 else r.control_period)
                    r.last_update = t
                r.write(world, self.step_size)
            t_next = self._time_at(self.steps + 1)  # the time this step ends at, computed once
            for hook in self.before_physics:
                hook(t_next)
            world.step()
            self.steps += 1
            self.time = t_next
            for hook in self.after_step:
                hook(t_next)

    def _time_at(self, steps):
        s0, t0 = self._epoch
        return t0 + (steps - s0) * self.step_size

    def set_step_size(self, step_size):
        """A new physics step (set_physics_properties); time goes on from where it is."""
        with self.lock:
            self._epoch = (self.steps, self.time)
            self.step_size = step_size
            self.world.set_step_size(step_size)

    def reset_simulation(self):
        """reset_world, and time back to 0."""
        with self.lock:
            self.reset_world()
            self.steps = 0
            self.time = 0.0
            self._epoch = (0, 0.0)

    def reset_world(self):
        """Poses, velocities and joints back to the start; time goes on. ros_control is left as it
        was, as gazebo_ros_control leaves it: controllers keep running with their commands and
        state, joint readings go on unwrapping from where they were, and only the plugin's last
        update time goes back to 0 (its Reset()), so the next update comes at once after
        reset_world, with the time since 0 as its period, and one control period after
        reset_simulation."""
        with self.lock:
            for body in self.world.bodies.values():  # static models too: set_model_state moves them
                self.world.reset_to_spawn(body)
            for r in self.robots.values():
                r.last_update = 0.0
            for hook in self.on_reset:
                hook()

    # -- queries ------------------------------------------------------------------------------
    def model_names(self):
        return list(self.world.bodies)

    def body(self, name):
        return self.world.bodies.get(name)

    def close(self):
        with self.lock:
            for r in self.robots.values():
                if r.cm is not None:
                    r.cm.shutdown()
            self.world.close()

