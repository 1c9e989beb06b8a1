"""SensorManager: the simulated sensors of every spawned robot, hooked into a Simulator.

When a URDF robot spawns, every <gazebo reference><sensor> block of its URDF that carries a
gazebo_ros plugin becomes a sensor: the first of its plugins the registry has a sensor class for (one module per
plugin library) reads its <sensor> and <plugin> in its own configure() (sensor_plugin.py: topics, frame, rate);
after every physics step each sensor whose update is due in sim time measures the world and publishes, stamped
with that sim time. A sensor plugin whose library a package built (a ray or gpu_ray sensor's) is hosted as Gazebo
hosts it (compiled_sensors.py), in place of racebot's class for the same library where it has one.

Cost is paid only for what somebody reads: a sensor whose topics have no subscriber does no ray
cast, render or message at all, and a depth camera works out depth only while its depth image or
point cloud is subscribed. Ray casts run on the physics client inside the step. Cameras render in
a worker process (render_worker.py) from the world's poses at their stamp, on another core, with
the EGL renderer when it loads (the log says which renderer, once); a frame due while the camera's
previous one is still rendering is skipped (counted, never faked). Without the worker (parameter
below, or after it died MAX_RESTARTS times) cameras render in the physics thread with the
TinyRenderer, within the render budget.

Private parameters of the world server node (/gazebo), read once at start:
  ~sensors/noise          (bool, true)  false: all sensor noise off, whatever the URDF declares
                                        (tests that compare readings with the world's geometry)
  ~sensors/render_worker  (bool, true)  false: render in the physics thread (the old path)
  ~sensors/renderer       (auto)        auto: EGL when it loads and draws correctly, else the
                                        TinyRenderer; egl / tiny: that one (egl failing: TinyRenderer
                                        with an error). Only the worker uses EGL.
  ~sensors/render_budget  (float, 0.5)  rendering in the physics thread only: share of wall time it
                                        may use; >= 1 renders every due frame, slowing the simulation
                                        instead. The worker has a core of its own and no budget.
  ~sensors/report_period  (s, 10)       wall seconds between rate reports; 0 = none
Reported: a loginfo line per period with each busy topic's rate in sim time and wall time,
frames skipped and the real-time factor, and the same numbers in the parameter ~sensors/rates
({real_time_factor, renderer, topics: [{topic, sim_hz, wall_hz, skipped}]}).
"""
import dataclasses
import math
import threading
import time as walltime

from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_plugins.compiled_plugins import find_library
from racebot_sim_bridge.gazebo_plugins.compiled_sensors import HOSTED_TYPES
from racebot_sim_bridge.gazebo_plugins.plugin_manager import dynamic_reconfigure_server
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE
from racebot_sim_bridge.sensors.config_types import SensorConfigError, resolve_frame
from racebot_sim_bridge.sensors.render import RENDERER_CHOICES, RENDERER_NAMES, TINY
from racebot_sim_bridge.sensors.render_worker import RenderWorker
from racebot_sim_bridge.sensors.scene import SceneColours
from racebot_sim_bridge.sensors.schedule import TIME_EPS, RenderBudget
from racebot_sim_bridge.engine.world_copy import snapshot
from racebot_sim_bridge.engine.rospy_log import RospyLog

DEFAULT_RENDER_BUDGET = 0.5
DEFAULT_REPORT_PERIOD = 10.0


def sensor_config(spec, spawn_namespace='', model_name='', node_namespace='/'):
    """The SensorConfig of a urdf_model.SensorSpec, as the first of its plugins that the registry has a sensor class
    for reads it (that class's configure()), or None when none of them publishes to ROS (Gazebo would run such a
    sensor for nobody). Raises SensorConfigError for a plugin that does not fit its sensor (e.g. a camera plugin
    in a ray sensor). spawn_namespace: the spawn request's robot_namespace; model_name: the spawned model's name;
    node_namespace: the world server's."""
    for plugin in spec.plugins:
        cls = REGISTRY.find(plugin.filename, PluginKind.SENSOR)
        if cls is not None:
            return cls.configure(spec, plugin, spawn_namespace, model_name, node_namespace)
    return None


class SensorManager:
    def __init__(self, rospy, sim, clock=walltime.perf_counter, reconfigure=dynamic_reconfigure_server,
                 compiled=None):
        """reconfigure(namespace, config_type, callback): a plugin's dynamic_reconfigure server (tests without a
        master give a stand-in). compiled: the world server's CompiledPlugins, which hosts a sensor's compiled
        plugins (None: none are looked for)."""
        self.rospy = rospy
        self.sim = sim
        self.compiled = compiled
        self.clock = clock
        self.reconfigure = reconfigure
        self.noise_enabled = bool(rospy.get_param('~sensors/noise', True))
        self.budget = RenderBudget(self._number('~sensors/render_budget', DEFAULT_RENDER_BUDGET), clock)
        self.report_period = self._number('~sensors/report_period', DEFAULT_REPORT_PERIOD)
        self.sensors = {}  # robot name -> [Sensor]
        self._active = []
        self._last_report = None
        self.use_worker = bool(rospy.get_param('~sensors/render_worker', True))
        self.renderer_choice = str(rospy.get_param('~sensors/renderer', 'auto'))
        if self.renderer_choice not in RENDERER_CHOICES:
            rospy.logwarn('~sensors/renderer must be one of %s, got %r; using auto'
                          % (', '.join(RENDERER_CHOICES), self.renderer_choice))
            self.renderer_choice = 'auto'
        self.worker = None       # RenderWorker, started for the first frame a camera takes
        self.renderer = None     # what renders, for the log and ~sensors/rates
        self._colours = None     # SceneColours of the physics world, for rendering in this thread
        self._snapshot = None    # the world's poses at this step, taken once for all cameras
        # after_step's shortcut: until sim time reaches the earliest next update of the sensors in
        # _due_for (the list _active was when it was computed, at step size _due_step), no sensor has
        # anything to do; then only those whose own wake time (_wakes, in _due_for's order) has come.
        self._next_due = -math.inf
        self._due_for = None
        self._due_step = None
        self._wakes = []
        self._last_step_time = -math.inf
        self._failures_logged = 0
        sim.on_spawn.append(self.on_spawn)
        sim.on_delete.append(self.on_delete)
        # after_step is hooked in only while there are sensors (_set_active)
        if not self.noise_enabled:
            rospy.loginfo('sensors: noise off (~sensors/noise is false)')
        self._reporter = None
        if self.report_period > 0:
            self._reporter = threading.Thread(target=self._report_loop, name='sensor_rates', daemon=True)
            self._reporter.start()

    def _number(self, name, default):
        value = self.rospy.get_param(name, default)
        try:
            value = float(value)
            if math.isfinite(value) and value >= 0:
                return value
        except (TypeError, ValueError):
            pass
        self.rospy.logwarn('%s must be a number >= 0, got %r; using %g' % (name, value, default))
        return default

    # -- hooks (called under sim.lock) ----------------------------------------------------------
    def _host_compiled(self, robot, spec):
        """The sensor's plugins whose library a package built (find_library), hosted as Gazebo hosts them
        (compiled_sensors.py): (the CompiledRaySensor or None, `spec` with only the plugins racebot simulates left).
        The package's own build of a plugin racebot also simulates wins; racebot's runs when it does not load."""
        built = [p for p in spec.plugins if find_library(p.filename) is not None]
        if self.compiled is None or not built:
            return None, spec
        if spec.type not in HOSTED_TYPES:
            unsimulated = []
            for plugin in built:
                simulated = REGISTRY.find(plugin.filename, PluginKind.SENSOR) is not None
                self.rospy.logwarn("%s: sensor '%s' (type %s): plugin '%s' (%s) is compiled, and racebot hosts the "
                                   'compiled plugins of %s sensors only: %s; see %s'
                                   % (robot.name, spec.name, spec.type, plugin.name, plugin.filename,
                                      ', '.join(HOSTED_TYPES), 'racebot simulates it instead' if simulated
                                      else 'it publishes nothing', SUPPORTED_TABLE))
                if not simulated:
                    unsimulated.append(plugin)
            # said once: the registry's "not simulated" warning is not said again for them
            return None, dataclasses.replace(spec, plugins=[p for p in spec.plugins
                                                            if all(p is not u for u in unsimulated)])
        fallbacks = [p.filename for p in built if REGISTRY.find(p.filename, PluginKind.SENSOR) is not None]
        try:
            sensor, loaded = self.compiled.load_sensor(self, robot, spec, built, fallbacks)
        except (KeyError, ValueError) as err:
            self.rospy.logwarn("%s: sensor '%s' cannot host its compiled plugins: %s" % (robot.name, spec.name, err))
            return None, spec
        left = [p for p in spec.plugins if all(p is not done for done in loaded)]
        return sensor, dataclasses.replace(spec, plugins=left)

    def on_spawn(self, robot):
        created = []
        for spec in robot.model.sensors:
            compiled, spec = self._host_compiled(robot, spec)
            if compiled is not None:
                created.append(compiled)
                self.rospy.loginfo("%s: %s sensor '%s' on %s at %s with compiled plugins, Gazebo topic %s" % (
                    robot.name, spec.type, spec.name, spec.reference,
                    '%g Hz' % spec.update_rate if spec.update_rate > 0 else 'every update', compiled.topic))
                if not spec.plugins:
                    continue
            try:
                config = sensor_config(spec, robot.spawn_namespace, robot.name, self.sim.node_namespace)
            except SensorConfigError as err:
                self.rospy.logwarn('%s: %s; not simulated' % (robot.name, err))
                continue
            unsupported = [w for w in (REGISTRY.not_simulated(robot.name, p, spec) for p in spec.plugins) if w]
            for warning in unsupported:  # said once, at spawn
                self.rospy.logwarn(warning)
            if config is None:
                if spec.plugins and not unsupported:
                    self.rospy.loginfo("%s: sensor '%s' publishes nothing: its plugin has an empty topic name"
                                       % (robot.name, spec.name))
                continue
            if 'tf_prefix_param' in config.params:  # gazebo_ros_range and _bumper resolve their frame with it
                resolve_frame(config, self.rospy.get_param(config.params['tf_prefix_param'], ''))
            try:
                sensors = config.sensor_class.create(self, robot, spec, config)
            except (KeyError, ValueError) as err:
                self.rospy.logwarn("%s: sensor '%s' cannot be simulated: %s" % (robot.name, spec.name, err))
                continue
            for w in config.warnings:
                self.rospy.logwarn('%s: %s' % (robot.name, w))
            created.extend(sensors)
            self.rospy.loginfo("%s: %s sensor '%s' on %s at %s, frame %s: %s" % (
                robot.name, config.kind, spec.name, spec.reference,
                '%g Hz' % config.rate if config.rate > 0 else 'every update', config.frame_id,
                ', '.join(sorted(config.topics.values()))))
        if created:
            self.sensors[robot.name] = created
            self._set_active()

    def on_delete(self, robot):
        for sensor in self.sensors.pop(robot.name, []):
            sensor.close()
        self._set_active()

    def _set_active(self):
        self._active = [s for group in self.sensors.values() for s in group]
        self.sim.set_step_hook('after_step', self.after_step, bool(self._active))

    def after_step(self, time):
        self._snapshot = None
        # Most steps have no sensor due (a 1 kHz world, sensors at 10-100 Hz): one comparison instead of
        # asking each schedule; at a due step, only the sensors due are stepped. Time going back (a
        # reset), another set of sensors or another step size asks them all again.
        if self._last_step_time <= time < self._next_due and self._due_for is self._active:
            self._last_step_time = time
            return
        active = self._active
        if not (self._last_step_time <= time and self._due_for is active and self._due_step == self.sim.step_size):
            self._due_for, self._due_step = active, self.sim.step_size
            self._wakes = [-math.inf] * len(active)
        self._last_step_time = time
        wakes = self._wakes
        for i, sensor in enumerate(active):
            if wakes[i] > time:
                continue
            if sensor.failed:
                wakes[i] = math.inf
                continue
            try:
                sensor.step(time)
            except Exception as err:  # one broken sensor must not stop the world
                sensor.failed = True
                wakes[i] = math.inf
                self.rospy.logerr("sensor '%s' of %s failed and is switched off: %s: %s"
                                  % (sensor.spec.name, sensor.robot_name, type(err).__name__, err))
                continue
            wakes[i] = sensor.wake_time() - TIME_EPS  # UpdateSchedule.due: due from next - TIME_EPS on
        self._next_due = min(wakes, default=math.inf)

    def wake(self):
        """Asks every sensor's wake time again at the next step (any thread): a sensor whose wake time an
        outside event moved earlier (a triggered camera's trigger) is then stepped. One assignment, so a wake
        that comes while after_step runs is seen at the step after."""
        self._due_for = None

    # -- cameras ------------------------------------------------------------------------------
    def _start_rendering(self):
        if self.worker is not None or self.renderer is not None:
            return
        if not self.use_worker:
            self._renderer_chosen('%s in the physics thread (~sensors/render_worker is false)' % RENDERER_NAMES[TINY])
            return
        self.worker = RenderWorker(self.renderer_choice, RospyLog(self.rospy),
                                   on_ready=lambda what: self._renderer_chosen('%s, in a worker process' % what))

    def _renderer_chosen(self, description):
        if self.renderer is None:  # once: a restarted worker says nothing new
            self.renderer = description
            self.rospy.loginfo('sensors: cameras render with %s' % description)

    def worker_expected(self):
        """True while cameras should take frames from the worker (even while it (re)starts)."""
        if self.worker is None and self.renderer is None:
            self._start_rendering()  # on the first frame anybody wants: an unwatched camera costs nothing
        worker = self.worker
        if worker is None:
            return False
        if worker.alive:
            return True
        self.renderer = '%s in the physics thread (the render worker died)' % RENDERER_NAMES[TINY]
        return False

    def scene_colours(self):
        """SceneColours of the physics world, made when a camera first renders in this thread."""
        if self._colours is None:
            self._colours = SceneColours(self.sim.world, TINY)
        self._colours.refresh(self.sim.spec.models)
        return self._colours

    def snapshot(self):
        """The world's poses now (this step), for frames stamped with this step's time."""
        if self._snapshot is None:
            self._snapshot = snapshot(self.sim.world)
        return self._snapshot

    def frame_failed(self, sensor, reason):
        if self._failures_logged < 5:  # a reason, not a flood
            self._failures_logged += 1
            self.rospy.logerr("sensor '%s': a frame could not be rendered: %s" % (sensor.spec.name, reason))

    def close(self):
        """Stops the render worker and frees the frame buffers."""
        if self.worker is not None:
            self.worker.close()
        for group in self.sensors.values():
            for sensor in group:
                sensor.close()

    # -- rates --------------------------------------------------------------------------------
    def report(self):
        """One rate report: {topic: (sim Hz, wall Hz, skipped)} and the real-time factor since the
        previous call (None the first time)."""
        now, sim_time = self.clock(), self.sim.time
        rates = {}
        for sensor in list(self._active):
            r = sensor.meter.snapshot(sim_time, now)
            if r is not None:
                rates[sensor.topic] = r
        previous = self._last_report
        self._last_report = (sim_time, now)
        rtf = None
        if previous is not None and now > previous[1]:
            rtf = (sim_time - previous[0]) / (now - previous[1])
        return rates, rtf

    def _report_loop(self):
        self.report()
        while not self.rospy.is_shutdown():
            walltime.sleep(self.report_period)
            rates, rtf = self.report()
            busy = {t: r for t, r in rates.items() if r[0] > 0 or r[2] > 0}
            if not busy or rtf is None or rtf <= 0:
                continue
            self.rospy.loginfo('sensor rates (sim time / wall time): %s; real-time factor %.2f' % (
                ', '.join('%s %.1f/%.1f Hz%s' % (t, r[0], r[1], ', %d skipped' % r[2] if r[2] else '')
                          for t, r in sorted(busy.items())), rtf))
            summary = {'real_time_factor': round(rtf, 3), 'renderer': self.renderer or '',
                       'topics': [{'topic': t, 'sim_hz': round(r[0], 2), 'wall_hz': round(r[1], 2), 'skipped': r[2]}
                                  for t, r in sorted(busy.items())]}
            try:
                self.rospy.set_param('~sensors/rates', summary)
            except Exception:  # the master is going away: nothing to report to
                pass
