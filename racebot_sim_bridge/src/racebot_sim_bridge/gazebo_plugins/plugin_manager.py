"""PluginManager: the Gazebo model plugins of every spawned robot, hooked into a Simulator.

When a URDF robot spawns, each of its model-level <gazebo><plugin> blocks (not a sensor's) is looked up
in registry.REGISTRY by its filename and built when it is a model plugin (gazebo_ros_control hooks in
itself: gazebo_ros_control/). A plugin racebot does not simulate gets the registry's one warning naming it, and the
robot works without it; a plugin refused for its parameters (PluginError) gets an error with the
reason. Nothing a plugin raises reaches the world server: a plugin whose update fails is stopped with
an error, the world goes on. At each update a plugin is called only outside its quiet span (ModelPlugin.quiet_span:
its update clock says nothing is due), and what upstream does at every update whatever the rate (the diff drive's
encoder) is its every_update, called first. A plugin library racebot has no class for is looked for as a compiled
plugin (compiled_plugins.py), built against racebot's Gazebo plugin API, and loaded when found; so is one it has a
class for, whose library a package built (ridgeback_gazebo_plugins' own): the library runs, racebot's class only
when the library does not load.
"""
from racebot_sim_bridge.engine.sim_time import to_ns
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_plugins.compiled_plugins import CompiledPlugins, find_library
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY


def dynamic_reconfigure_server(namespace, config_type, callback):
    """dynamic_reconfigure's Python server under `namespace` (its set_parameters service and its
    parameter_descriptions and parameter_updates topics)."""
    from dynamic_reconfigure.server import Server
    return Server(config_type, callback, namespace=namespace)


class PluginManager:
    def __init__(self, rospy, sim, registry=REGISTRY, reconfigure=dynamic_reconfigure_server, roscpp_name=None,
                 compiled=None):
        """reconfigure(namespace, config_type, callback): makes a plugin's dynamic_reconfigure server
        (tests without a master give a stand-in). roscpp_name: the node name roscpp gets for compiled plugins
        (CompiledPlugins; None without a master). compiled: the CompiledPlugins to use (the world server shares one
        with its SensorManager), else one made here."""
        self.rospy = rospy
        self.sim = sim
        self.registry = registry
        self.reconfigure = reconfigure
        self.compiled = compiled if compiled is not None else CompiledPlugins(rospy, sim, roscpp_name)
        self.plugins = {}  # robot name -> [ModelPlugin]
        self._active = []
        # the plugins whose class has a before_physics / after_step of its own: only they are called at each
        # update (the base's do nothing, and a call per plugin per update is what a fleet pays most for)
        self._before = []
        self._after = []
        self._every = []  # (plugin, its every_update)
        # Most updates no plugin is due (a 1 kHz world, plugins at 10-100 Hz): each plugin's quiet span (None:
        # call it every update) and their intersection, [from, until) in integer ns, checked with one comparison
        self._spans = []
        self._quiet = (0, 0)
        self._tf_pub = None
        sim.on_spawn.append(self.on_spawn)
        sim.on_delete.append(self.on_delete)
        sim.on_reset.append(self.on_reset)
        # before_physics and after_step are hooked in only while a plugin is active (_refresh)

    def tf_publisher(self):
        """The one /tf publisher all plugins share (tf::TransformBroadcaster's topic)."""
        if self._tf_pub is None:
            from tf2_msgs.msg import TFMessage
            self._tf_pub = self.rospy.Publisher('/tf', TFMessage, queue_size=100)
        return self._tf_pub

    # -- hooks (called under sim.lock) ----------------------------------------------------------
    def on_spawn(self, robot):
        self.compiled.on_spawn(robot)
        created = []
        for spec in robot.model.plugins:
            cls = self.registry.find(spec.filename, PluginKind.MODEL)
            if cls is not None and find_library(spec.filename) is not None:
                # the package's own build of a plugin racebot also simulates: it runs, as in Gazebo; racebot's
                # class is the fallback when it does not load
                if self.compiled.load(robot, spec, fallback=True):
                    continue
            if cls is None:
                warning = self.registry.not_simulated(robot.name, spec)
                if warning and self.compiled.load(robot, spec) is None:
                    self.rospy.logwarn('%s (%s)' % (warning, self.compiled.missing(spec.filename)))
                continue
            try:
                plugin = cls(self, robot, spec)
            except PluginError as err:
                self.rospy.logerr("%s: plugin '%s' (%s) refused: %s. The robot works without it; fix the "
                                  "plugin's parameters, delete the model and spawn it again"
                                  % (robot.name, spec.name, spec.filename, err))
                continue
            created.append(plugin)
        if created:
            self.plugins[robot.name] = created
            self._refresh()

    def load_world_plugins(self):
        """The world file's <plugin>s, after its models, as Gazebo's World loads them: compiled world plugins
        (racebot simulates none in Python); one without a library gets a warning naming it."""
        for plugin in self.sim.spec.plugins:
            if self.compiled.load_world(plugin) is None:
                self.rospy.logwarn("world: world plugin '%s' (%s) is not simulated by racebot, so what it would do "
                                   'does not happen; the rest of the world works (%s)'
                                   % (plugin.name, plugin.filename, self.compiled.missing(plugin.filename)))

    def on_delete(self, robot):
        for plugin in self.plugins.pop(robot.name, []):
            plugin.close()
        self.compiled.on_delete(robot)
        self._refresh()

    def on_reset(self):
        for plugin in self._active:
            plugin.reset()
        self.compiled.on_reset()
        self._spans = [None] * len(self._before)  # their clocks restarted: ask them all again
        self._quiet = (0, 0)

    def before_physics(self, time):
        now = to_ns(time)
        for plugin, update in self._every:
            try:
                update(now)
            except Exception as err:  # a plugin's bug must not stop the world
                self._stop(plugin, err)
        if self._quiet[0] <= now < self._quiet[1]:
            return
        spans = self._spans
        for i, plugin in enumerate(self._before):
            span = spans[i]
            if span is not None and span[0] <= now < span[1]:
                continue
            try:
                plugin.before_physics(time)
                spans[i] = plugin.quiet_span()
            except Exception as err:
                self._stop(plugin, err)
        if spans is self._spans:  # no plugin stopped meanwhile (that starts the spans again)
            self._quiet = _intersection(spans)

    def after_step(self, time):
        for plugin in self._after:
            try:
                plugin.after_step(time)
            except Exception as err:
                self._stop(plugin, err)

    def close(self):
        for group in self.plugins.values():
            for plugin in group:
                plugin.close()
        self.plugins = {}
        self.compiled.close()
        self._refresh()

    def _stop(self, plugin, err):
        self.rospy.logerr('%s: stopped after an error in its update: %s: %s. The world goes on without it'
                          % (plugin.label, type(err).__name__, err))
        group = self.plugins.get(plugin.robot.name, [])
        if plugin in group:
            group.remove(plugin)
        try:
            plugin.close()
        except Exception:
            pass
        self._refresh()

    def _refresh(self):
        self._active = [p for group in self.plugins.values() for p in group]
        self._before = [p for p in self._active if _overrides(p, 'before_physics')]
        self._after = [p for p in self._active if _overrides(p, 'after_step')]
        self._every = [(p, p.every_update) for p in self._active if p.every_update is not None]
        self._spans = [None] * len(self._before)
        self._quiet = (0, 0)
        self.sim.set_step_hook('before_physics', self.before_physics, bool(self._before or self._every))
        self.sim.set_step_hook('after_step', self.after_step, bool(self._after))


def _intersection(spans):
    """[from, until) in which every span's plugin is quiet; empty when any must be called at every update."""
    if not spans or None in spans:
        return (0, 0)
    return max(span[0] for span in spans), min(span[1] for span in spans)


def _overrides(plugin, hook):
    """True when the plugin's class (or the plugin itself) has its own `hook`, not ModelPlugin's no-op."""
    return getattr(type(plugin), hook) is not getattr(ModelPlugin, hook) or hook in vars(plugin)


__all__ = ['PluginManager', 'PluginError']
