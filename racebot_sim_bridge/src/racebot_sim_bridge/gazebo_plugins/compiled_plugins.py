"""Compiled Gazebo plugins: a `<plugin filename>` racebot has no Python class for, loaded from its library (or
one it has a class for, whose library a package built).

A robot package's own model plugin, built with its own `find_package(gazebo)` against racebot's Gazebo 11 plugin API
(upstream_compat/gazebo_dev: the headers, libgazebo, the gazebo config), is found as Gazebo finds a plugin
(find_library: GAZEBO_PLUGIN_PATH, then the dynamic linker's LD_LIBRARY_PATH, where a sourced devel space puts
its lib/) and loaded through the gazebo_host module (src/cpp/gazebo_host.cpp): Gazebo's RegisterPlugin, its type
check, Load with the model and the <plugin> element, Init. The world update fires Gazebo's events in its order
(worldUpdateBegin and beforePhysicsUpdate before the physics step, worldUpdateEnd after); reset_world calls each
plugin's Reset and worldReset. Every physics call a plugin makes comes back to EngineAdapter, on the engine's
objects. A plugin whose library cannot be loaded, is of another kind, or throws in Load, Init, Reset or an event
callback is reported with its library and the reason, unloaded, and the world goes on. A <sensor>'s compiled
plugins are loaded on a C++ sensor the host makes for it (load_sensor; compiled_sensors.py measures it). gzserver's
system plugins (-s LIBRARY) are loaded before the world's models with gzserver's command line (load_system) and
meet the world at its worldCreated event (world_created).
"""
import os
import sys
import xml.etree.ElementTree as ET

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_ft_sensor import wrench_at_link_origin
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE


# The system plugins gazebo_ros's gzserver adds, which racebot's world server is itself: named, never loaded.
OWN_SYSTEM_PLUGINS = {
    'libgazebo_ros_api_plugin.so': "the /gazebo services and topics are racebot's world server's own",
    'libgazebo_ros_paths_plugin.so': "the packages' gazebo_model_path, gazebo_media_path and plugin_path exports "
                                     "are added by racebot's gzserver itself",
}


def find_library(filename, environ=None):
    """The path Gazebo would dlopen for a <plugin filename>: an absolute path as is; else the first
    GAZEBO_PLUGIN_PATH folder that has the file (gazebo::common::SystemPaths' plugin paths), else the first
    LD_LIBRARY_PATH folder that has it (where dlopen itself looks). None when there is none."""
    environ = os.environ if environ is None else environ
    if os.path.isabs(filename):
        return filename if os.path.isfile(filename) else None
    for variable in ('GAZEBO_PLUGIN_PATH', 'LD_LIBRARY_PATH'):
        for folder in environ.get(variable, '').split(':'):
            path = os.path.join(folder, filename)
            if folder and os.path.isfile(path):
                return path
    return None


def roscpp_remappings(argv):
    """The command line's remappings (name:=value, __ns:= among them) for ros::init, without the node's own name
    and log file: roscpp gets a name of its own beside the rospy node's."""
    remappings = {}
    for arg in argv:
        if ':=' in arg and not arg.startswith('-'):
            name, value = arg.split(':=', 1)
            if name not in ('__name', '__log'):
                remappings[name] = value
    return remappings


def plugin_xml(spec, spawn_namespace=''):
    """The <plugin> element as sdformat reads it from the URDF: as written, with the values sdformat's fixed-joint
    reduction rewrote (spec.params holds them: <bodyName> of a lumped link names the link it went into), and, as
    gazebo_ros's spawn walks the model before Gazebo loads it (walkChildAddRobotNamespace), a <robotNamespace> of
    the spawn request's non-empty `spawn_namespace` (spawn_model's default: its own namespace, "/") in a plugin that
    has none."""
    element = spec.element
    if element is None:
        copy = ET.Element('plugin', {'name': spec.name, 'filename': spec.filename})
        for tag, text in spec.params.items():
            ET.SubElement(copy, tag).text = text
    else:
        copy = ET.fromstring(ET.tostring(element, encoding='unicode'))
        seen = set()
        for child in copy:
            if child.tag in spec.params and child.tag not in seen:
                seen.add(child.tag)
                if (child.text or '') != spec.params[child.tag] and len(child) == 0:
                    child.text = spec.params[child.tag]
    if spawn_namespace and copy.find('robotNamespace') is None:
        ET.SubElement(copy, 'robotNamespace').text = spawn_namespace
    return ET.tostring(copy, encoding='unicode')


class EngineAdapter:
    """What gazebo::physics asks of the engine, by the host's handles: models, links and joints are numbered
    here as they are added (gazebo_host keeps the numbers in its Model, Link and Joint objects)."""

    def __init__(self, sim):
        self.sim = sim
        self.models = []  # handle -> engine Model
        self.links = []   # handle -> engine Link
        self.joints = []  # handle -> engine Joint
        self.measured = set()  # joint handles whose wrench PyBullet measures

    def add_model(self, body):
        """Numbers an engine Model's links (its root first) and joints; returns gazebo_host.add_model's
        arguments after the name."""
        handle = len(self.models)
        self.models.append(body)
        by_index = {index: name for name, index in body.link_index.items()}
        links = []
        for name in sorted(body.links, key=lambda n: body.links[n].index if n in body.link_index else 1 << 30):
            links.append((name, len(self.links)))
            self.links.append(body.links[name])
        joints = []
        for name, joint in body.joints.items():
            parent_index = body.client.getJointInfo(body.id, joint.index)[16]
            effort = joint.max_effort if joint.max_effort > 0 else -1.0
            velocity = joint.max_velocity if joint.max_velocity > 0 else -1.0
            joints.append((name, len(self.joints), by_index.get(parent_index, ''), joint.child_link,
                           joint.lower, joint.upper, effort, velocity))
            self.joints.append(joint)
        return handle, body.static, links, joints

    # -- world ------------------------------------------------------------------------------------------
    def sim_time(self):  # between updates (gazebo_host answers during one)
        return self.sim.time

    def step_size(self):
        return self.sim.step_size

    def gravity(self):
        return tuple(self.sim.world.gravity)

    # -- joints ----------------------------------------------------------------------------------------
    def joint_position(self, j):
        return self.joints[j].state().position

    def joint_velocity(self, j):
        return self.joints[j].state().velocity

    def joint_set_velocity(self, j, velocity):
        joint = self.joints[j]
        joint.set_position(joint.state().position, velocity)

    def joint_set_force(self, j, total):
        """The effort for the coming step: gazebo_host sums a plugin's SetForce calls of one update."""
        joint = self.joints[j]
        joint.model.apply_efforts([joint.index], [total])

    def joint_set_position(self, j, position):
        self.joints[j].set_position(position, 0.0)

    def joint_set_motor(self, j, velocity, fmax):
        self.joints[j].drive_velocity(velocity, fmax)

    # -- links -----------------------------------------------------------------------------------------
    def _com(self, link):
        """(CoM position, inertial frame orientation) in the world."""
        client = link.model.client
        if link.index >= 0:
            s = client.getLinkState(link.body_id, link.index, computeForwardKinematics=1)
            return tuple(s[0]), tuple(s[1])
        pos, orn = client.getBasePositionAndOrientation(link.body_id)
        return tuple(pos), tuple(orn)

    def link_world_pose(self, k):
        pose, _ = self.links[k].state()
        return tuple(pose.position) + tuple(pose.orientation)

    def link_world_cog_pose(self, k):
        pos, orn = self._com(self.links[k])
        return pos + orn

    def link_world_cog_linear_vel(self, k):
        return tuple(self.links[k].state()[1].linear)

    def link_world_linear_vel(self, k):
        """Of the link frame's origin: the CoM's velocity plus w x (origin - CoM)."""
        link = self.links[k]
        pose, twist = link.state()
        com, _ = self._com(link)
        w, v = twist.angular, twist.linear
        r = [pose.position[i] - com[i] for i in range(3)]
        return (v[0] + w[1] * r[2] - w[2] * r[1], v[1] + w[2] * r[0] - w[0] * r[2], v[2] + w[0] * r[1] - w[1] * r[0])

    def link_world_angular_vel(self, k):
        return tuple(self.links[k].state()[1].angular)

    def link_add_force(self, k, force):
        self.links[k].apply_wrench(tuple(force), (0.0, 0.0, 0.0))

    def link_add_torque(self, k, torque):
        self.links[k].apply_wrench((0.0, 0.0, 0.0), tuple(torque))

    def link_mass(self, k):
        return self.links[k].dynamics().mass

    def link_inertial(self, k):
        """Link::GetInertial: mass, the inertial frame in the link frame (x y z qx qy qz qw), principal moments."""
        d = self.links[k].dynamics()
        return d.mass, tuple(d.inertial_position) + tuple(d.inertial_orientation), tuple(d.inertia_diagonal)

    def link_world_force(self, k):
        return self.links[k].applied_wrench()[0]

    def link_world_torque(self, k):
        return self.links[k].applied_wrench()[1]

    def joint_wrench(self, j):
        """Joint::GetForceTorque's body2 (gazebo_ros_ft_sensor's reading, in the child link's frame about its
        origin); PyBullet measures a joint's wrench from the first time it is asked for."""
        joint = self.joints[j]
        link = joint.model.links[joint.child_link]
        if j not in self.measured:
            self.measured.add(j)
            link.enable_parent_wrench()
        force, torque = link.parent_wrench()
        dyn = link.dynamics()
        return wrench_at_link_origin(force, torque, dyn.inertial_position, dyn.inertial_orientation)

    # -- models ----------------------------------------------------------------------------------------
    def model_world_pose(self, m):
        pose = self.models[m].frame_pose()
        return tuple(pose.position) + tuple(pose.orientation)

    def model_set_world_pose(self, m, pose):
        body = self.models[m]
        com = body.com_pose_for_frame(tuple(pose[:3]), tuple(pose[3:]))
        twist = body.twist()
        body.set_pose(com.position, com.orientation, twist.linear, twist.angular)

    def model_set_linear_vel(self, m, velocity):
        body = self.models[m]
        body.set_velocity(tuple(velocity), body.twist().angular)

    def model_set_angular_vel(self, m, velocity):
        body = self.models[m]
        body.set_velocity(body.twist().linear, tuple(velocity))


class CompiledPlugins:
    """The compiled model, world and sensor plugins of every spawned robot and gzserver's system plugins, one
    gazebo_host.Host for them all (made at the first one). `rospy` logs; `sim` the Simulator, whose lock every call
    here runs under. `roscpp_name`: where a master runs (the world server), the name roscpp's node gets when the
    first plugin loads (plugins make NodeHandles, as in gzserver, where gazebo_ros_api_plugin has started roscpp;
    RoscppNode); None: roscpp is not started (no master)."""

    def __init__(self, rospy, sim, roscpp_name=None):
        self.rospy = rospy
        self.sim = sim
        self.roscpp = RoscppNode(rospy, roscpp_name)
        self.host = None
        self.adapter = None
        self.unavailable = None  # why the host cannot be made, once known
        self.plugins = {}  # id -> (robot name, label)
        self.models = set()  # robot names the host knows


    def missing(self, filename):
        """Why a library racebot has no class for was not loaded: the end of the registry's warning."""
        return ('no library %s was found on GAZEBO_PLUGIN_PATH or LD_LIBRARY_PATH (a plugin you build: source its '
                "workspace's devel/setup.bash before roslaunch)" % filename)

    def load(self, robot, spec, fallback=False):
        """Loads `spec` (a urdf_model.GazeboPlugin) for `robot` when its library is found: True when it runs,
        False when it failed (an error says why), None when there is no such library. fallback: racebot simulates
        the plugin too, and does when this fails (the message says so)."""
        path = find_library(spec.filename)
        if path is None:
            return None
        label = "%s: plugin '%s' (%s)" % (robot.name, spec.name, spec.filename)
        without = ("racebot's own simulation of it runs instead" if fallback else 'The robot works without it')
        if not self._ensure_host():
            self.rospy.logerr('%s: %s. %s' % (label, self.unavailable, without))
            return False
        self._add_model(robot)
        self.host.set_iterations(self.sim.steps)
        plugin_id = self._load_one(robot.name, robot.name, label, path, without, fallback, lambda: self.host.load(
            'model', path, spec.filename, spec.name, robot.name, plugin_xml(spec, robot.spawn_namespace)))
        if plugin_id is None:
            return False
        self._refresh()
        return True

    def _load_one(self, robot_name, where, label, path, without, fallback, load):
        """Runs `load()` (a gazebo_host load call) and records the plugin it loaded under `robot_name` (None: the
        world's); its id, or None after an error naming `where` and saying what happens `without` it. `fallback`:
        racebot simulates the plugin too (the log says the package's build runs instead)."""
        try:
            plugin_id = load()
        except RuntimeError as err:
            self.rospy.logerr('%s: not loaded: %s. %s; see %s' % (where, err, without, SUPPORTED_TABLE))
            return None
        self.plugins[plugin_id] = (robot_name, label)
        self.rospy.loginfo('%s: loaded from %s%s' % (label, path, " (the package's own build, not racebot's "
                                                                    'simulation of it)' if fallback else ''))
        return plugin_id

    def load_world(self, plugin):
        """Loads a world's <plugin> (sdf_model.WorldPlugin), as Gazebo loads them after the world's models: True
        when it runs, False when it failed (an error says why), None when there is no such library."""
        path = find_library(plugin.filename)
        if path is None:
            return None
        label = "world plugin '%s' (%s)" % (plugin.name, plugin.filename)
        if not self._ensure_host():
            self.rospy.logerr('%s: %s. The world goes on without it' % (label, self.unavailable))
            return False
        self._add_models()
        self.host.set_iterations(self.sim.steps)
        plugin_id = self._load_one(None, 'world', label, path, 'The world goes on without it', False,
                                   lambda: self.host.load('world', path, plugin.filename, plugin.name, '', plugin.xml))
        if plugin_id is None:
            return False
        self._refresh()
        return True

    def load_system(self, filenames, argv):
        """gzserver's system plugins (-s LIBRARY, in order), as gazebo_shared::setup loads them before the world's
        models: each library's Load(argc, argv) with gzserver's command line `argv`, then each one's Init. One that
        is not found, is not a system plugin or throws gets an error naming it, and the world server goes on
        without it. The number that run."""
        found = []
        for filename in filenames:
            own = OWN_SYSTEM_PLUGINS.get(os.path.basename(filename))
            path = None if own is not None else find_library(filename)
            if own is not None:
                self.rospy.loginfo('system plugin %s: not loaded: %s' % (filename, own))
            elif path is None:
                self.rospy.logerr('system plugin %s: not loaded: %s. The world server runs without it' % (
                    filename, self.missing(filename)))
            else:
                found.append((filename, path))
        if not found:
            return 0
        if not self._ensure_host():
            self.rospy.logerr('system plugins %s: %s. The world server runs without them' % (
                ', '.join(filename for filename, _ in found), self.unavailable))
            return 0
        # once: a plugin may keep the argv pointers its Load got (gazebo_ros_api_plugin does)
        self.host.set_server_args([str(a) for a in argv])
        self.host.set_iterations(self.sim.steps)
        loaded = []
        for filename, path in found:
            plugin_id = self._load_one(None, 'gzserver', 'system plugin %s' % filename, path,
                                       'The world server runs without it', False,
                                       lambda: self.host.load_system(path, filename))
            if plugin_id is not None:
                loaded.append(plugin_id)
        for plugin_id in loaded:
            try:
                self.host.init_system(plugin_id)
            except RuntimeError as err:
                self.plugins.pop(plugin_id, None)
                self.rospy.logerr('gzserver: %s. The world server runs without it; see %s' % (err, SUPPORTED_TABLE))
        self._refresh()
        return sum(1 for plugin_id in loaded if plugin_id in self.plugins)

    def world_created(self):
        """Gazebo's worldCreated event with the world's name, once the world file's models are in (World::Load
        ends with it), for the plugins loaded by then (system plugins wait for it)."""
        if self.plugins:
            self._add_models()
            self.host.world_created()

    def sig_int(self):
        """gzserver's Server::SigInt for the plugins loaded: the stop event, then sigInt."""
        if self.plugins:
            self.host.sig_int()

    def load_sensor(self, manager, robot, spec, plugins, fallbacks=()):
        """Hosts the compiled `plugins` (GazeboPlugin specs whose library find_library found) of the <sensor> `spec`
        (a ray, gpu_ray, imu, contact or camera sensor, compiled_sensors.HOSTED_TYPES) of `robot`: a C++ sensor,
        and each plugin loaded on it. Returns (the CompiledSensor for `manager` to step, or None when no plugin
        loaded; the plugins that loaded). `fallbacks`: the filenames racebot also simulates (its class runs when
        this one fails)."""
        from racebot_sim_bridge.gazebo_plugins.compiled_sensors import (CompiledCameraSensor, CompiledContactSensor,
                                                                        CompiledImuSensor, CompiledRaySensor,
                                                                        CompiledSensor, camera_geometry, camera_spec,
                                                                        ray_geometry)
        where = "%s: sensor '%s'" % (robot.name, spec.name)
        if not self._ensure_host():
            self.rospy.logerr('%s: %s. It runs without its compiled plugins' % (where, self.unavailable))
            return None, []
        self._add_model(robot)
        self.host.set_iterations(self.sim.steps)
        mount = CompiledSensor.mount_of(self.sim, robot, spec)  # KeyError: not on a link of the body
        common = (spec.name, robot.name, mount.link, tuple(mount.offset[0]) + tuple(mount.offset[1]),
                  float(spec.update_rate), bool(spec.always_on), bool(spec.visualize))
        if spec.type == 'imu':
            kind = CompiledImuSensor
            try:
                sensor_id = self.host.add_imu_sensor(*common)
            except RuntimeError as err:  # Gazebo's "IMU has invalid parent"
                raise ValueError(str(err)) from None
        elif spec.type == 'camera':
            kind = CompiledCameraSensor
            sensor_id = self.host.add_camera_sensor(*common, *camera_geometry(camera_spec(spec)))
        elif spec.type == 'contact':
            kind = CompiledContactSensor
            sensor_id = self.host.add_contact_sensor(*common, list(spec.contact_collisions))
        else:
            kind = CompiledRaySensor
            sensor_id = self.host.add_ray_sensor(spec.type, *common, ray_geometry(spec.ray))
        loaded = []
        for plugin in plugins:
            path = find_library(plugin.filename)
            fallback = plugin.filename in fallbacks
            without = "racebot's own simulation of it runs instead" if fallback else 'The sensor works without it'
            plugin_id = self._load_one(
                robot.name, where, "%s: plugin '%s' (%s)" % (where, plugin.name, plugin.filename), path, without,
                fallback, lambda: self.host.load_sensor_plugin(sensor_id, path, plugin.filename, plugin.name,
                                                               plugin_xml(plugin, robot.spawn_namespace)))
            if plugin_id is not None:
                loaded.append((plugin_id, plugin))
        self._refresh()
        if not loaded:
            self.host.remove_sensor(sensor_id)
            return None, []
        sensor = kind(manager, robot, spec, mount, self.host, sensor_id, [i for i, _ in loaded], self.unload)
        return sensor, [plugin for _, plugin in loaded]

    def unload(self, plugin_id):
        """Unloads one plugin (a compiled sensor's, when its robot goes)."""
        if self.plugins.pop(plugin_id, None) is not None:
            self.host.unload(plugin_id)
            self._refresh()

    def on_spawn(self, robot):
        """A robot spawned once the host runs: its world plugins' World::ModelByName finds it."""
        if self.host is not None:
            self._add_model(robot)

    def _add_models(self):
        """Every robot of the simulator in the host (a world-wide plugin's World::Models lists them)."""
        for name in list(self.sim.robots):
            self._add_model(self.sim.robots[name])

    def _add_model(self, robot):
        if robot.name not in self.models:
            self.host.add_model(robot.name, *self.adapter.add_model(robot.body))
            self.models.add(robot.name)

    def on_delete(self, robot):
        for plugin_id, (name, _) in list(self.plugins.items()):
            if name == robot.name:
                self.host.unload(plugin_id)
                del self.plugins[plugin_id]
        if robot.name in self.models:
            self.host.remove_model(robot.name)
            self.models.discard(robot.name)
        self._refresh()

    def on_reset(self):
        if self.plugins:
            self.host.idle()
            self.host.set_iterations(self.sim.steps)
            self.host.reset()

    def _notified(self, kind, value):
        """gazebo_host's news after events: plugins unloaded for a throwing callback, or worldUpdateEnd wanted."""
        if kind == 'failures':
            for plugin_id, label, message in value:
                _, full = self.plugins.pop(plugin_id, (None, label))
                self.rospy.logerr('%s: unloaded after an exception in its callback: %s. The world goes on without '
                                  'it' % (full, message))
        self._refresh()

    def close(self):
        if self.host is not None:
            self.host.close()
        self.plugins = {}
        self._refresh()
        self.roscpp.stop()

    def _ensure_host(self):
        if self.host is not None:
            return True
        if self.unavailable is not None:
            return False
        try:
            from racebot_sim_bridge.gazebo_plugins import gazebo_host
        except ImportError as err:
            self.unavailable = ("racebot's plugin host (gazebo_host) is not built (%s): run 'make build' in "
                                "racebot's folder" % err)
            return False
        self.adapter = EngineAdapter(self.sim)
        self.host = gazebo_host.Host(self.adapter, self.sim.spec.name, self._notified)
        self.roscpp.ensure()
        return True

    def model_capsule(self, robot):
        """`robot` in racebot's Gazebo plugin API, as gazebo_ros_control hands a RobotHWSim its model (the
        controller_host module takes it). RuntimeError when the plugin host cannot be made."""
        if not self._ensure_host():
            raise RuntimeError(self.unavailable)
        self._add_model(robot)
        return self.host.model_capsule(robot.name)

    def _refresh(self):
        """gazebo_host's own methods as the step hooks while plugins are loaded (no Python between the world update
        and the events: each call costs microseconds at thousands of updates a second); worldUpdateEnd's only
        while a callback wants it (gazebo_host says when that changes)."""
        wanted = bool(self.plugins)
        if self.host is None:
            return
        self.sim.set_step_hook('before_physics', self.host.update_begin, wanted)
        self.sim.set_step_hook('after_step', self.host.update_end, wanted and self.host.wants_end())
        if not wanted:
            self.host.idle()


class RoscppNode:
    """roscpp in the world server, as gazebo_ros_api_plugin starts it in gzserver: the node compiled plugins, C++
    controllers and RobotHWSims make their NodeHandles on. `name`: its node name where a master runs; None: roscpp
    is not started (no master)."""

    def __init__(self, rospy, name=None):
        self.rospy = rospy
        self.name = name
        self.started = False

    def ensure(self):
        """Starts roscpp in the world server as node `name`, once, where a master runs: what compiled plugins
        and C++ controllers (ros_control/compiled_controllers.py) make their NodeHandles on. False when it cannot."""
        if self.started or not self.name:
            return self.started
        from racebot_sim_bridge.gazebo_plugins import gazebo_host
        self.started = gazebo_host.start_roscpp(self.name, roscpp_remappings(sys.argv))
        if self.started:
            copied = self._share_private_params()
            self.rospy.loginfo("roscpp runs in the world server as node '%s'%s" % (
                self.name, "; the world server's private parameters are copied under it (%s)" % copied
                if copied else ''))
        return self.started

    def _share_private_params(self):
        """In gzserver one roscpp node is /gazebo, so a plugin's NodeHandle("~") reads what a launch file loaded for
        it there (fetch_gazebo's PID gains and default_controllers under gazebo:). Here roscpp's node has a name of
        its own: the rospy node's private parameters, as they are now, are copied under it (parameters it already
        has are kept). The names copied, comma-separated, or ''."""
        own = self.rospy.get_name()
        cpp = own.rsplit('/', 1)[0] + '/' + self.name
        try:
            private = self.rospy.get_param(own, {})
        except Exception as err:  # noqa: BLE001 (a master that went away: roscpp's own parameters only)
            self.rospy.logwarn("could not read the world server's private parameters for roscpp: %s" % err)
            return ''
        copied = []
        for key, value in sorted(private.items()) if isinstance(private, dict) else ():
            if not self.rospy.has_param('%s/%s' % (cpp, key)):
                self.rospy.set_param('%s/%s' % (cpp, key), value)
                copied.append(key)
        return ', '.join(copied)

    def stop(self):
        """Shuts roscpp in the world server down (once): the world server does it first when it stops, as
        gazebo_ros_api_plugin does on SIGINT, so that plugins are finished with ros::ok() false, as in gzserver."""
        if self.started:
            from racebot_sim_bridge.gazebo_plugins import gazebo_host
            gazebo_host.stop_roscpp()
            self.started = False
