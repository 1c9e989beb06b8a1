"""The world server node, our gzserver + gazebo_ros: `rosrun racebot_sim_bridge world_server WORLD`.

Loads WORLD (an SDF file, looked up as gzserver does and in this package) into a Simulator and runs
its update loop. Around it, as gazebo_ros's node does: /clock; the services and topics of
gazebo_services (/gazebo/spawn_urdf_model, get/set_model_state, ..., model_states and link_states);
/gazebo/performance_metrics (performance_metrics); the physics dynamic_reconfigure server
(/gazebo/set_parameters, gazebo_ros.physics_reconfigure); every spawned model's sensors (sensors,
SensorManager), model plugins (gazebo_plugins, PluginManager) and gazebo_ros_control (its controller
manager and services, GazeboRosControlPlugin). Windows are separate processes that attach to it
(gzclient.py; viewer.AttachedWindows).

Command line (as gzserver's, via empty_world.launch): `[-u|--pause] [--verbose] [-e ENGINE] [-s LIBRARY ...]
[other gzserver options, ignored with a log line] WORLD_FILE`. `-u` starts paused; `-s` (--server-plugin) loads a
compiled system plugin (CompiledPlugins.load_system); `-e` other than ode and `-r` (recording) are said to have
no meaning here. Private parameters:
  ~gzclient_address (set here)   the Unix socket windows attach through (viewer.AttachedWindows):
                                 `rosrun gazebo_ros gzclient` reads it; removed at shutdown
  ~gui (bool)                    no longer opens a window: the window is gzclient, a node of its own
                                 (empty_world.launch's gazebo_gui); true is said once in the log
  ~pub_clock_frequency (Hz, 0)   if > 0, /clock at most this often in sim time (gazebo_ros's
                                 /gazebo/pub_clock_frequency); 0 = every world update, as Gazebo
  ~enable_ros_network (bool, true)  false: none of gazebo_ros's services, state topics, performance
                                 metrics or reconfigure server (as gazebo_ros); /clock, sensors,
                                 model plugins and controller managers still publish and serve
  ~fast_clock_wall_period (s, 0.001)  as fast as possible only (real_time_update_rate 0): /clock at
                                 most once per this many wall seconds, carrying the latest update's
                                 time, so subscribers see sim time advance in steps of about
                                 real-time factor x 1 ms; 0 = every update. In real-time mode every
                                 update is published, as Gazebo does. A pause or a reset is
                                 published at once; while paused /clock repeats every 0.2 wall s.
  ~states_publish_rate (Hz, 100) /gazebo/model_states and link_states in sim time when subscribed
                                 (Gazebo: every update; 0 here means that too)
  ~command_trace (path, '')      measurements only (make bench): append to this file when each
                                 controller command arrives and when an update first applies it
                                 (ros_control/command_trace.py, the controllers' observer); '' = off:
                                 one attribute test per update
  ~load_check_timeout (s, 60)    each URDF is loaded in a helper process first (engine/load_trial.py);
                                 one that crashes it or loads longer than this is refused, the world
                                 goes on. 0: no check (one load less per spawn)
Services and topics live under the node's own name, as gazebo_ros's (node `gazebo`: /gazebo/...).
/use_sim_time is set true when nobody has set it (gazebo_ros does). This node drives ROS time, so
it does not subscribe to its own /clock (init_clock_source) and rospy's timers cannot pace it:
pacing is in wall time, the world's real_time_update_rate updates per wall second, or as fast as
possible when it is 0. Messages, /clock included, are handed to a writer thread (queued_publishing).
"""
import math
import os
import signal
import sys
import time

import rospy
from rosgraph_msgs.msg import Clock

from racebot_sim_bridge.transport import queued_publishing
from racebot_sim_bridge.description import model_path, sdf_reader
from racebot_sim_bridge.ros_control.controller_io import RosIO
from racebot_sim_bridge.ros_control.command_trace import CommandTrace
from racebot_sim_bridge.gazebo_ros_api.services import GazeboServices
from racebot_sim_bridge.gazebo_ros_api.performance_metrics import PerformanceMetricsPublisher
from racebot_sim_bridge.engine.load_trial import DEFAULT_TIMEOUT, LoadTrial
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.gazebo_plugins.compiled_plugins import CompiledPlugins
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager
from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.engine.rospy_log import RospyLog
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.window.viewer import SYNC_PERIOD as VIEWER_SYNC_PERIOD, AttachedWindows

PAUSED_CLOCK_PERIOD = 0.2  # wall seconds between /clock repeats while paused (late joiners get the time)
# As fast as possible, /clock at every update (10,000+ a second) costs the world server and every
# subscriber more than the physics itself; one per wall millisecond is what real time gives them.
FAST_CLOCK_WALL_PERIOD = 0.001
# Real time: the loop sleeps once it is at least this far (s) ahead of its schedule: at 1 kHz after every
# second update, at 100 Hz after each. Each sleep and wake-up costs the loop about as much as an update
# (20-40 us of CPU: the timer, the switch, cold caches); sleeping after every update at 1 kHz kept the
# world server at 20.5 % of a core, after every second one it is at 18-19 %. The price: a command that
# arrives while it sleeps waits up to 2 ms for its update, not 1 (the bench's command path p99 shows it).
PACING_SLACK = 0.001


def clock_publisher():
    """The /clock publisher: queued as every publisher of this process (queued_publishing: the update loop hands
    each message to the writer thread, or sends it without blocking), so that a subscriber that stops reading (a
    process stopped in a debugger) never holds the loop up; queue_size 1: it then gets the latest time, not a
    backlog of old ones."""
    return rospy.Publisher('/clock', Clock, queue_size=1)


LOG = RospyLog(rospy)  # what the simulator, its plugins and the windows log through


# gzserver options that take a value: their value must not be mistaken for the world file.
SERVER_PLUGIN_OPTIONS = ('-s', '--server-plugin')
GZSERVER_VALUE_OPTIONS = {*SERVER_PLUGIN_OPTIONS, '-o', '--profile', '--seed', '--iters', '--record_path',
                          '--record_period', '--record_filter', '--record_resources', '--record_encoding',
                          '-p', '--play'}


def parse_args(argv):
    """gzserver-style arguments -> (world path or None, paused, verbose, ignored options)."""
    world, paused, verbose, ignored = None, False, False, []
    it = iter(argv)
    for a in it:
        if a in ('-u', '--pause'):
            paused = True
        elif a == '--verbose':
            verbose = True
        elif a in ('-r', '--record'):
            ignored.append('%s (recording:=true: there are no Gazebo state logs here)' % a)
        elif a in ('-e', '--physics'):
            engine = next(it, 'ode')
            if engine != 'ode':
                ignored.append('-e %s (the physics engine is always PyBullet here)' % engine)
        elif a in SERVER_PLUGIN_OPTIONS:
            next(it, None)  # server_plugins' to load
        elif a.startswith('--server-plugin='):
            pass
        elif a in GZSERVER_VALUE_OPTIONS:
            ignored.append('%s %s' % (a, next(it, '')))
        elif a.startswith('-'):
            ignored.append(a)
        elif a.strip():
            world = a
    return world, paused, verbose, ignored


def server_plugins(argv):
    """The system plugins gzserver's command line names (-s LIBRARY, --server-plugin LIBRARY or
    --server-plugin=LIBRARY), in order, as Server::ParseArgs hands them to gazebo::addPlugin."""
    plugins, it = [], iter(argv)
    for a in it:
        if a in SERVER_PLUGIN_OPTIONS:
            value = next(it, '')
        elif a.startswith('--server-plugin='):
            value = a.split('=', 1)[1]
        else:
            continue
        if value.strip():
            plugins.append(value.strip())
    return plugins


def resolve_world(name):
    """The world file gzserver loads for `name`: an absolute path as it is; a relative one as Gazebo's
    SystemPaths::FindFile finds it (the working directory, then NAME, models/NAME, media/models/NAME under each
    folder of GAZEBO_RESOURCE_PATH and of the packages' gazebo_media_path exports, which gazebo_ros_paths_plugin
    adds), then in this package (its worlds/). Not found: `name`, for load_world to report."""
    if not name:
        name = 'worlds/empty.world'
    if os.path.isabs(name):
        return name
    found, _ = model_path.find_file(name)
    if found is not None and os.path.isfile(found):
        return found
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = []
    try:
        import rospkg
        candidates.append(os.path.join(rospkg.RosPack().get_path('racebot_sim_bridge'), name))
    except Exception:  # rospkg missing or package not on ROS_PACKAGE_PATH: fall through to the source tree
        pass
    candidates.append(os.path.join(here, '..', '..', name))
    for c in candidates:
        if os.path.isfile(c):
            return os.path.abspath(c)
    return name  # load_world reports it missing, with the path


EMPTY_WORLD = 'worlds/empty.world'


def load_world_spec(path, fallback_to_empty=False, log=LOG):
    """(path, World) of the world to run. A file that cannot be loaded (not found, unreadable, not an SDF
    world) raises WorldError, unless `fallback_to_empty`: then, as gzserver's Server::ParseArgs does, the
    failure is an error ("Could not open file[...]"), a warning says "Falling back on worlds/empty.world" and
    that world is loaded (launch files naming a world that is not there, e.g. jackal_gazebo's
    $(find gazebo_ros)/worlds/empty_world.world, run on the empty world in Gazebo)."""
    try:
        return path, sdf_reader.load_world(path, model_path.resource_path())
    except sdf_reader.WorldError as err:
        if not fallback_to_empty:
            raise
        log.error('Could not open file[%s]: %s' % (path, err))
        log.warn('Falling back on %s' % EMPTY_WORLD)
    empty = resolve_world(EMPTY_WORLD)
    return empty, sdf_reader.load_world(empty, model_path.resource_path())


class WorldServer:
    def __init__(self, world_path, paused, gui, fallback_to_empty=False, system_plugins=(), server_argv=()):
        """`system_plugins`: gzserver's -s libraries, loaded before the world's models with `server_argv`, the
        command line as gzserver got it, for their Load(argc, argv)."""
        # the resource path: a name not found is reported with the folders it was looked for in
        world_path, spec = load_world_spec(world_path, fallback_to_empty)
        for w in spec.warnings:
            rospy.logwarn('%s: %s' % (os.path.basename(world_path), w))
        if gui:
            rospy.logwarn('~gui:=true: the world server has no window of its own; the window is gzclient '
                          '(gazebo_ros empty_world.launch gui:=true starts it as gazebo_gui, or '
                          '`rosrun gazebo_ros gzclient`), which attaches to this server')
        io = RosIO(rospy)
        trace_path = rospy.get_param('~command_trace', '')
        if trace_path:
            io.command_trace = CommandTrace(trace_path)
            rospy.logwarn('command trace on (~command_trace): every controller command is logged to %s; '
                          'for measurements only' % trace_path)
        self.sim = Simulator(spec, io, LOG, self._get_param)
        # every URDF is loaded in a helper first: its PyBullet, not this one, meets what crashes or spins
        load_check = self._seconds_param('~load_check_timeout', DEFAULT_TIMEOUT)
        self.sim.world.load_trial = LoadTrial(load_check) if load_check > 0 else None
        self.sim.node_namespace = rospy.get_namespace()  # plugins' relative robotNamespaces resolve here
        self.windows = AttachedWindows(self.sim.world, LOG)  # gzclient attaches here
        rospy.set_param('~gzclient_address', self.windows.address)
        self.sim.rendering = False
        self.sim.set_paused(paused)
        self.update_rate = self.sim.real_time_update_rate
        self.clock_period = self._rate_param('~pub_clock_frequency', 0.0)
        self.clock_wall_period = 0.0
        if self.update_rate <= 0:
            self.clock_wall_period = self._seconds_param('~fast_clock_wall_period', FAST_CLOCK_WALL_PERIOD)
        self.last_clock_wall = -math.inf
        self.states_period = self._rate_param('~states_publish_rate', 100.0)
        self.clock_pub = clock_publisher()
        # compiled plugins (model, world, sensor and system ones, with roscpp as node <this node>_cpp): one host
        self.compiled = CompiledPlugins(rospy, self.sim, rospy.get_name().rsplit('/', 1)[-1] + '_cpp')
        if system_plugins:  # gazebo_shared::setup loads them before the world
            self.compiled.load_system(system_plugins, server_argv)
        # before the services: every spawn gets its sensors
        self.sensors = SensorManager(rospy, self.sim, compiled=self.compiled)
        # and its model plugins (diff drive, p3d, ...)
        self.plugins = PluginManager(rospy, self.sim, compiled=self.compiled)
        # and gazebo_ros_control with its controller manager's services, whatever ~enable_ros_network says
        # (the flag is gazebo_ros_api_plugin's; upstream's gazebo_ros_control reads none)
        # (C++ controllers with roscpp, as the compiled plugins have it; a package's RobotHWSim on their model)
        GazeboRosControlPlugin.attach(self.sim, rospy, ensure_roscpp=self.plugins.compiled.roscpp.ensure,
                                      model_capsule=self.plugins.compiled.model_capsule)
        # gazebo_ros advertises in its node's namespace (a node `gazebo` in ns /sim serves /sim/gazebo/...)
        # and, with ~enable_ros_network false, nothing but /clock.
        self.services = self.metrics = self.reconfigure = None
        if rospy.get_param('~enable_ros_network', True):
            self.services = GazeboServices(rospy, self.sim, rospy.get_name())
            self.metrics = PerformanceMetricsPublisher(rospy, self.sim, self.sensors, self.services.ns)
            self.reconfigure = physics_reconfigure(self.services.properties, self.services.ns)
        else:
            rospy.loginfo('ROS gazebo topics/services are disabled (~enable_ros_network is false)')
        self.sim.spawn_world_robots()  # the world file's models with joints, plugins or sensors
        with self.sim.lock:
            self.compiled.world_created()  # World::Load's last word, which system plugins wait for
            self.plugins.load_world_plugins()  # then its world plugins, as Gazebo's World loads them
        self.clock_msg = Clock()
        self.last_clock = -math.inf
        self.last_states = -math.inf
        rospy.loginfo('world %s loaded: %d models, step %g s, %s, %s' % (
            world_path, len(self.sim.model_names()), self.sim.step_size,
            'as fast as possible' if self.update_rate <= 0 else '%g updates/s' % self.update_rate,
            'paused' if paused else 'running'))

    @staticmethod
    def _get_param(path):
        try:
            return rospy.get_param(path)
        except KeyError:
            return None

    @staticmethod
    def _rate_param(name, default):
        rate = rospy.get_param(name, default)
        try:
            rate = float(rate)
        except (TypeError, ValueError):
            rospy.logwarn('%s must be a number of Hz, got %r; using %g' % (name, rate, default))
            rate = default
        return 1.0 / rate if rate > 0 and math.isfinite(rate) else 0.0

    @staticmethod
    def _seconds_param(name, default):
        value = rospy.get_param(name, default)
        try:
            value = float(value)
            if value >= 0 and math.isfinite(value):
                return value
        except (TypeError, ValueError):
            pass
        rospy.logwarn('%s must be a number of seconds >= 0, got %r; using %g' % (name, value, default))
        return default

    def publish_clock(self, force=False):
        t = self.sim.time
        if not force:
            if self.clock_period and t - self.last_clock < self.clock_period - 1e-9:
                return
            if self.clock_wall_period:
                now = time.perf_counter()
                if now - self.last_clock_wall < self.clock_wall_period:
                    return
                self.last_clock_wall = now
        self.last_clock = t
        self.clock_msg.clock = ros_time(rospy.Time, t)
        try:
            self.clock_pub.publish(self.clock_msg)
        except rospy.ROSException:
            # rospy shut down between the loop's is_shutdown() and this publish (Ctrl-C, roslaunch's
            # stop): the topic is closed and the loop ends at its next check; anything else is a fault
            if not (rospy.is_shutdown() or rospy.core.is_shutdown_requested()):
                raise
            return
        if _OWN_SIM_TIME:
            set_own_ros_time(self.clock_msg.clock)

    def run(self):
        queued_publishing.writer_pace(bursts=self.update_rate > 0)
        self.publish_clock(force=True)
        sim, perf_counter = self.sim, time.perf_counter  # looked up once: the loop runs 10,000s of times a second
        step_unless_paused = sim.step_unless_paused
        wall_start, steps_since = perf_counter(), 0
        last_paused_clock = 0.0
        next_view = 0.0
        stop = STOP
        while stop.received is None and not rospy.is_shutdown():
            if perf_counter() >= next_view:  # paused or not: windows attach, bodies move
                next_view = perf_counter() + VIEWER_SYNC_PERIOD
                with sim.lock:
                    self.windows.sync()
                    sim.rendering = self.windows.count > 0
            if self.update_rate <= 0 and self.clock_wall_period > 0:
                # as fast as possible: the updates until the next /clock (wall) or, while somebody listens, state
                # topics (sim) are due (nobody listening, no stop every 10 ms of sim time to publish nothing)
                states_due = self.last_states + self.states_period - 1e-9 if self._states_wanted() else math.inf
                stepped = sim.steps_until(states_due, self.last_clock_wall + self.clock_wall_period)
            else:
                stepped = step_unless_paused()  # no update starts once pause_physics has answered
            if not stepped:
                now = time.perf_counter()
                # at once if the latest update's time was held back (fast mode), then now and then
                if self.last_clock != self.sim.time or now - last_paused_clock >= PAUSED_CLOCK_PERIOD:
                    self.publish_clock(force=True)
                    last_paused_clock = now
                time.sleep(0.002)
                wall_start, steps_since = time.perf_counter(), 0
                continue
            steps_since += stepped
            t = sim.time
            # A reset sent time back (perhaps while paused, between two of our steps): publish at once.
            if t < self.last_clock or t < self.last_states:
                self.last_clock = self.last_states = self.last_clock_wall = -math.inf
            self.publish_clock()
            if t - self.last_states >= self.states_period - 1e-9:
                self.last_states = t
                if self.services is not None:
                    self.services.publish_states()
            if self.update_rate != sim.real_time_update_rate:  # set_physics_properties changed it
                self.update_rate = sim.real_time_update_rate
                queued_publishing.writer_pace(bursts=self.update_rate > 0)
                wall_start, steps_since = time.perf_counter(), 0
            if self.update_rate > 0:
                ahead = wall_start + steps_since / self.update_rate - time.perf_counter()
                if ahead >= PACING_SLACK:  # sleep until this update's wall time
                    time.sleep(ahead)
                elif ahead < -0.5:  # far behind (a slow machine, a debugger): do not sprint to catch up
                    wall_start, steps_since = time.perf_counter(), 0

    def _states_wanted(self):
        return self.services is not None and self.services.states_wanted()

    def shutdown(self):
        # roscpp first, as gzserver's gazebo_ros_api_plugin shuts ROS down on SIGINT before the world and its
        # sensors are finished: a plugin's destructor then finds ros::ok() false (velodyne_gazebo_plugins' queue
        # thread reads its deleted NodeHandle unless ros::ok() is false already); a signal's stop and sigInt events
        # come before, as gzserver's Server::SigInt fires them
        if STOP.received is not None:
            with self.sim.lock:
                self.compiled.sig_int()
        self.compiled.roscpp.stop()
        if self.services is not None:
            self.services.shutdown()
            self.metrics.shutdown()
        if self.reconfigure is not None:
            self.reconfigure.shutdown()
        self.sensors.close()  # the render worker stops with us
        self.plugins.close()
        self.windows.close()  # each window is told, and closes
        try:
            if rospy.get_param('~gzclient_address', None) == self.windows.address:  # not a successor's
                rospy.delete_param('~gzclient_address')
        except Exception:  # noqa: BLE001 (the master may be gone first; a stale address is harmless)
            pass
        self.sim.close()


_OWN_SIM_TIME = False  # True when this node's ROS time is set by publish_clock (see init_clock_source)


def physics_reconfigure(properties, ns):
    """gazebo_ros's physics dynamic_reconfigure server under `ns`, or None (said why) where
    dynamic_reconfigure's Python side is not installed."""
    try:
        from racebot_sim_bridge.gazebo_ros_api.physics_reconfigure import PhysicsReconfigure
        return PhysicsReconfigure(rospy, properties, ns)
    except ImportError as err:
        rospy.logwarn('no physics dynamic_reconfigure server (%s/set_parameters): %s; install '
                      'python3-dynamic-reconfigure (make setup)' % (ns, err))
        return None


class StopSignals:
    """SIGINT and SIGTERM as a request that the update loop reads between two updates. rospy's own handler runs
    signal_shutdown wherever the main thread happens to be when the signal comes: inside a publish (the loop's
    /clock), whose connection's lock close_all then waits for in the same thread, for ever; Ctrl-C on roslaunch
    stops the subscribers at the same moment, so it came exactly there one time in ten. Here the handler only
    records the signal: the loop ends at its next check, and rospy shuts down after it, outside any publish.
    A second signal before that (roslaunch's SIGTERM after its SIGINT) ends the process at once."""

    def __init__(self):
        self.received = None  # the name of the first signal, once one came

    def install(self):
        for number in (signal.SIGINT, signal.SIGTERM):
            signal.signal(number, self._on_signal)
        return self

    def _on_signal(self, number, _frame):
        if self.received is not None:
            os._exit(128 + number)
        self.received = signal.Signals(number).name


STOP = StopSignals()


def init_clock_source(name):
    """rospy.init_node for the node that publishes /clock. With /use_sim_time set, rospy would
    subscribe this node to its own /clock: a receive thread, a second connection and a message to
    deserialize for every one we send. disable_rostime=True (public; rostopic does the same) leaves
    that out; the node's ROS time (its /rosout stamps) is then set where /clock is
    published, to the same value, so it reads exactly what its subscribers read."""
    global _OWN_SIM_TIME
    rospy.init_node(name, anonymous=False, disable_rostime=True, disable_signals=True)
    STOP.install()  # rospy's signal handling, apart from the publishing path
    if rospy.get_param('/use_sim_time', False):
        _OWN_SIM_TIME = True
        set_own_ros_time(rospy.Time(0))


def set_own_ros_time(stamp):
    """This node's ROS time. No public rospy API sets it: rospy's only public way to sim time is the
    /clock subscription init_node makes (see init_clock_source), so this does what that subscription's
    callback does (rospy.rostime._set_rostime): sets rospy's current time and wakes the threads waiting for time
    to pass (rospy.sleep, rospy.Timer). Waking them takes the condition's lock, and at 1000 /clock a wall second
    it was ~1 % of the loop with nobody waiting, so it is done only when somebody waits (a thread that starts to
    wait meanwhile checks the time itself within 0.5 s, rospy.sleep's own period)."""
    if not isinstance(stamp, rospy.Time):
        stamp = rospy.Time(stamp.secs, stamp.nsecs)
    rospy.rostime._rostime_current = stamp
    cond = rospy.rostime.get_rostime_cond()
    if getattr(cond, '_waiters', True):
        with cond:
            cond.notify_all()


def main(argv=None, debugger=False, fallback_to_empty=False):
    """`debugger`: started as gazebo_ros's `debug` (empty_world.launch debug:=true). `fallback_to_empty`: a
    world file that cannot be loaded is replaced by worlds/empty.world, as gzserver does (gazebo_ros's
    gzserver sets it); racebot's own world_server keeps it fatal."""
    server_argv = list(argv if argv is not None else sys.argv)  # a system plugin's Load(argc, argv) gets it all
    argv = rospy.myargv(server_argv)[1:]
    init_clock_source('gazebo')
    queued_publishing.install()  # before any publisher: no thread switch per message from the update loop
    queued_publishing.start_writer(rospy.logwarn)  # and no send either, where the compiled writer is built
    if not rospy.has_param('/use_sim_time'):  # gazebo_ros sets it when nobody has
        rospy.set_param('/use_sim_time', True)
    if debugger:
        rospy.loginfo('debug:=true starts gzserver under gdb in Gazebo; this world server is Python and '
                      'runs without a debugger (attach one to process %d if needed)' % os.getpid())
    world, paused, verbose, ignored = parse_args(argv)
    for opt in ignored:
        rospy.loginfo('gzserver option %s has no meaning here; ignored' % opt)
    if verbose:
        rospy.loginfo('--verbose (verbose:=true): this world server logs all it has to say through ROS '
                      'either way; there are no extra gzserver messages to show')
    path = resolve_world(world)
    try:
        server = WorldServer(path, paused, bool(rospy.get_param('~gui', False)), fallback_to_empty,
                             server_plugins(argv), server_argv)
    except (sdf_reader.WorldError, PhysicsError) as err:
        rospy.logfatal('could not load world: %s' % err)
        rospy.signal_shutdown('could not load world')
        sys.exit(1)
    try:
        server.run()
    finally:  # after the loop, never during a step: the physics client must outlive every step
        server.shutdown()
        queued_publishing.stop_writer()
        rospy.signal_shutdown(STOP.received or 'the world server stopped')
