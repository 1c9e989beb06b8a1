"""libgazebo_ros_control.so: ros_control for a spawned robot, as gazebo_ros_control's plugin gives it.

On spawn (GazeboRosControlPlugin, hooked into a Simulator by attach()): the robotNamespace (the plugin's
own, else the spawn request's, else the model name), the control period (controlPeriod, else the physics
step), the DefaultRobotHWSim of the transmissions, a ControllerManager (given ros_controllers' types, as
pluginlib gives upstream's), and the controller manager's six services under `<ns>/controller_manager/`.
The services are offered whatever ~enable_ros_network says: upstream's plugin reads no such flag (only
gazebo_ros_api_plugin does) and its ControllerManager advertises them. On delete: the services and the
controllers shut down.

Every world update the Simulator runs the plugin's loop inline (step(): read_sim, the controller
manager's update when a control period has elapsed, write_sim), as the plugin's Update() does on
WorldUpdateBegin; `read` and `write` are the RobotHWSim's own methods, so that loop calls nothing more.
"""
from racebot_sim_bridge.description.urdf_model import UrdfError
from racebot_sim_bridge.engine.control_hook import ControlHook
from racebot_sim_bridge.engine.simulator import SpawnError
from racebot_sim_bridge.gazebo_ros_api import plugin_namespace
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_ros_control.compiled_robot_hw_sim import (CompiledControlLoop, RobotHWSimError,
                                                                         load_robot_hw_sim)
from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import (DEFAULT_ROBOT_SIM_TYPE, DefaultRobotHWSim,
                                                                hardware_joints, pid_gains)
from racebot_sim_bridge.ros_control.compiled_controllers import CompiledControllers
from racebot_sim_bridge.ros_control.controller_manager import ControllerManager, ControllerManagerServices
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES


def control_plugin(model):
    """The first gazebo_ros_control <plugin> of a RobotModel (the reader warns of any other), or None."""
    return next((p for p in model.plugins if p.is_ros_control), None)


class GazeboRosControlPlugin(ControlHook):
    """gazebo_ros_control for one robot: its RobotHWSim (`hw`), ControllerManager (`cm`), namespace
    (`ns`), control period and, with rospy, its controller manager's services: the robot's ControlHook
    (engine/control_hook.py), whose `read`, `write`, `cm`, `control_period` and `last_update` the
    Simulator uses every step, and whose close() it calls when the robot goes."""

    libraries = ('libgazebo_ros_control.so',)  # what gazebo_plugins/registry.py knows it by
    plugin_kind = PluginKind.ROBOT_HARDWARE
    filename = libraries[0]

    def __init__(self, sim, robot, spec, rospy=None, controller_types=CONTROLLER_TYPES, ensure_roscpp=None,
                 model_capsule=None):
        """Load(): `spec` is the robot's gazebo_ros_control <plugin> (urdf_model.GazeboPlugin);
        `controller_types` (type name -> class) are what its controller manager can load, and with
        `ensure_roscpp` (what starts roscpp in this process) the C++ controllers pluginlib can make; with
        `model_capsule(robot)` too (the robot in racebot's Gazebo plugin API), a <robotSimType> a package built is
        its RobotHWSim (compiled_robot_hw_sim.py). Leaves
        robot.control unset when the transmissions cannot be simulated (the robot stays, without a
        controller manager, as in Gazebo); SpawnError when the spawn must fail (the namespace of
        another robot's controller manager, joints that are not movable)."""
        name = robot.name
        self.robot = robot
        self.robot_sim_type = spec.params.get('robotSimType') or DEFAULT_ROBOT_SIM_TYPE
        self.cm = self.hw = self.services = None
        self.last_update = None
        # gazebo_ros: the plugin's own robotNamespace wins, else the request's, else the model name
        self.ns = plugin_namespace.control_namespace(spec.robot_namespace, robot.spawn_namespace, name,
                                                     sim.node_namespace).rstrip('/')
        self.control_period = sim.step_size
        if spec.control_period:
            self.control_period = spec.control_period
            if self.control_period < sim.step_size:
                sim.log.warn('%s: controlPeriod %g s is shorter than the physics step %g s; using the step'
                             % (name, self.control_period, sim.step_size))
                self.control_period = sim.step_size
        model = robot.model
        try:
            joints = hardware_joints(model)
        except UrdfError as err:
            # "Could not initialize robot simulation interface": the model stays, without a controller manager.
            sim.log.error("%s: %s. gazebo_ros_control is not active for this model: it is spawned without "
                          "a controller manager (as Gazebo does), so no controller can be loaded for it. "
                          "Fix the URDF, delete the model and spawn it again" % (name, err))
            self._warn_model(sim, robot)
            return
        self._warn_model(sim, robot)
        for other in sim.robots.values():
            if other.control is not None and other.control.ns == self.ns:
                raise SpawnError("SpawnModel: Failure - robot namespace '%s' is already used by model '%s' (its "
                                 "controller manager is there); give this model's gazebo_ros_control plugin "
                                 "another <robotNamespace>, or, if it has none, spawn with another "
                                 "-robot_namespace" % (self.ns or '/', other.name))
        if self.robot_sim_type != DEFAULT_ROBOT_SIM_TYPE:
            compiled = self._compiled_robot_hw_sim(sim, robot, spec, rospy, controller_types, ensure_roscpp,
                                                   model_capsule)
            if compiled is not None:  # loaded (robot.control set), or failed as gazebo_ros_control fails
                return
        if not model.transmissions:  # DefaultRobotHWSim's joints are the transmissions' (a package's own has its own)
            sim.log.warn("%s: the %s plugin is declared but the URDF has no <transmission>: its "
                         "controller manager under %s has no joints to control; add a <transmission> "
                         "per actuated joint" % (name, self.filename, self.ns or '/'))
        self.hw = DefaultRobotHWSim(model, robot.body, joints, pid_gains(sim.get_params, sim.log, name, self.ns,
                                                                         joints))
        for w in self.hw.warnings:
            sim.log.warn('%s: %s' % (name, w))
        self.read, self.write = self.hw.read_sim, self.hw.write_sim  # what step() calls: no layer between
        ns = self.ns
        self.cm = ControllerManager(ns, self.hw, lambda c: sim.get_params('%s/%s' % (ns, c)), sim.io, sim.log,
                                    controller_types, CompiledControllers(ns, self.hw, ensure_roscpp))
        self.read(sim.world)
        if rospy is not None:
            self.services = ControllerManagerServices(rospy, self.cm)
            rospy.loginfo('%s: controller manager ready under %s/controller_manager (control period %g s, '
                          'joints: %s)' % (name, ns, self.control_period, ', '.join(self.hw.names)))
        robot.control = self

    def _compiled_robot_hw_sim(self, sim, robot, spec, rospy, controller_types, ensure_roscpp, model_capsule):
        """A package's own RobotHWSim for <robotSimType>: True when it runs, False when it failed (the robot stays
        without a controller manager, as in Gazebo: "Could not initialize robot simulation interface"), None when
        no package built that class (DefaultRobotHWSim then, with a warning)."""
        host = None
        if ensure_roscpp is not None and model_capsule is not None:
            try:
                from racebot_sim_bridge.ros_control import controller_host
            except ImportError as err:
                sim.log.warn("%s: racebot's controller host is not built (%s): run 'make build'" % (robot.name, err))
            else:
                host = controller_host.Host(self.ns, [])
        if host is None or not host.sim_available(self.robot_sim_type):
            sim.log.warn("%s: <robotSimType> %s: no package built that RobotHWSim class (pluginlib finds none whose "
                         "library is there: build its package and source its devel/setup.bash before roslaunch); "
                         "racebot's DefaultRobotHWSim drives the transmissions' joints instead"
                         % (robot.name, self.robot_sim_type))
            return None
        ensure_roscpp()
        try:
            mirror = load_robot_hw_sim(host, self.robot_sim_type, self.ns, spec.robot_param, model_capsule(robot),
                                       robot.model)
        except (RobotHWSimError, RuntimeError) as err:
            host.close()
            sim.log.error("%s: Could not initialize robot simulation interface %s: %s. The model is spawned without "
                          "a controller manager, as in Gazebo" % (robot.name, self.robot_sim_type, err))
            return False
        self.hw = mirror
        ns = self.ns
        manager = ControllerManager(ns, mirror, lambda c: sim.get_params('%s/%s' % (ns, c)), sim.io, sim.log,
                                    controller_types, CompiledControllers(ns, mirror, ensure_roscpp, host=host))
        self.cm = CompiledControlLoop(host, manager)
        # upstream's Update(): readSim with the controllers (cm.update), writeSim every world update
        self.read = lambda world: None
        self.write = lambda world, dt: host.write_sim(sim.time, dt)
        if rospy is not None:
            self.services = ControllerManagerServices(rospy, manager)
            rospy.loginfo('%s: controller manager ready under %s/controller_manager on the RobotHWSim %s (control '
                          'period %g s, joints: %s)' % (robot.name, ns, self.robot_sim_type, self.control_period,
                                                        ', '.join(mirror.names)))
        robot.control = self
        return True

    @staticmethod
    def _warn_model(sim, robot):
        for w in robot.model.warnings:
            sim.log.warn('%s: %s' % (robot.name, w))

    def reset_joint_readings(self, world):
        if isinstance(self.hw, DefaultRobotHWSim):  # a compiled RobotHWSim reads its joints itself
            self.hw.reset_joint_readings(world)

    def close(self):
        """The robot goes (or the world closes): services first, so that no call reaches a manager that is gone."""
        if self.services is not None:
            self.services.shutdown()
            self.services = None
        if self.cm is not None:
            self.cm.shutdown()

    @classmethod
    def attach(cls, sim, rospy=None, controller_types=CONTROLLER_TYPES, ensure_roscpp=None, model_capsule=None):
        """Hooks gazebo_ros_control into `sim` (sim.on_create): every robot spawned from now on that declares
        the plugin gets one, with its controller manager's services when `rospy` is given, loading
        `controller_types` (type name -> class; ros_controllers' by default) and, with `ensure_roscpp`, C++
        controllers (with `model_capsule` too, a package's own RobotHWSim). Returns the hook."""
        def on_create(robot):
            spec = control_plugin(robot.model)
            if spec is not None:
                cls(sim, robot, spec, rospy, controller_types, ensure_roscpp, model_capsule)
            elif robot.model.transmissions:
                sim.log.warn("%s has <transmission>s but declares no %s plugin: no controller manager for it, so "
                             "its controllers cannot be loaded; add <gazebo><plugin name=\"gazebo_ros_control\" "
                             "filename=\"%s\"/></gazebo> to the URDF" % (robot.name, cls.filename, cls.filename))
            else:
                sim.log.info("%s declares no %s plugin: no controller manager for it" % (robot.name, cls.filename))
        sim.on_create.append(on_create)
        return on_create
