"""What every simulated sensor plugin shares: its loading, schedule, mount, publishers and rate meter.

A sensor plugin is the `<plugin filename="libgazebo_ros_X.so">` inside a URDF's `<gazebo reference><sensor>` (a
model's own <plugin>s are model_plugin.py's). sensor_manager.py finds the class registry.py gives for the library
and calls its configure(): the shared prologue here (the plugin fits the sensor's type, the sensor has the block
the plugin reads), then the plugin's own load(), which reads its <sensor> and <plugin> (a SensorSdf) into a
SensorConfig (topics, frame, rate, its parameters as its Load() reads them), as upstream's Load() does. The manager
builds it with create() when the robot spawns and calls step(time) on the physics thread after every physics step,
under Simulator.lock: the schedule says whether an update is due (../sensors/schedule.py); if anybody listens,
update() measures with the pipeline stages in ../sensors/ and publishes messages stamped with the sim time of the
measurement. close() when the robot goes.
"""
from enum import Enum

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import after_spawn, resolve, sensor_namespace
from racebot_sim_bridge.sensors.config_types import SensorConfig, SensorConfigError, number
from racebot_sim_bridge.sensors.mount import SensorMount
from racebot_sim_bridge.sensors.schedule import RateMeter, UpdateSchedule


class SensorKind(str, Enum):
    """What a sensor plugin's SensorConfig says it is, and the log calls it. A str ('laser' == LASER)."""
    LASER = 'laser'
    CAMERA = 'camera'
    MULTICAMERA = 'multicamera'
    DEPTH = 'depth'
    IMU = 'imu'
    RANGE = 'range'
    BUMPER = 'bumper'
    BLOCK_LASER = 'block_laser'
    VELODYNE = 'velodyne'
    SONAR = 'sonar'

    def __str__(self):
        return self.value


class SensorSdf:
    """What a sensor plugin's Load() is given: its <sensor> (`spec`, a urdf_model.SensorSpec), its <plugin>
    (`plugin`, its `params`), where the model was spawned, and the warnings its loading gives (said at spawn)."""

    def __init__(self, spec, plugin, spawn_namespace='', model_name='', node_namespace='/'):
        self.spec = spec
        self.plugin = plugin
        self.params = plugin.params
        self.spawn_namespace = spawn_namespace  # the spawn request's robot_namespace
        self.model_name = model_name
        self.node_namespace = node_namespace    # the world server's
        self.what = "sensor '%s' plugin '%s'" % (spec.name, plugin.name)
        self.warnings = []

    def number(self, key, default):
        """The parameter `key` as a number; `default` when absent or empty, and when not a number (warned)."""
        return number(self.params, key, default, self.warnings, self.what)

    def own_namespace(self):
        """The plugin's <robotNamespace> text after gazebo_ros's spawn walk, or None when it has none."""
        return after_spawn(self.params.get('robotNamespace'), self.spawn_namespace)

    def resolve(self, name):
        """ros::NodeHandle(name)'s namespace in the world server's node."""
        return resolve(name, self.node_namespace)

    def namespace(self, kind, camera_name=''):
        """Where a gazebo_plugins sensor plugin of `kind` advertises (plugin_namespace.sensor_namespace)."""
        return sensor_namespace(kind, self.params.get('robotNamespace'), self.spawn_namespace, self.model_name,
                                camera_name, self.node_namespace)


class Sensor:
    """One simulated sensor: its loading, schedule, mount, publishers and rate meter.

    A plugin class declares in its class line what registry.py and configure() read of it:
    `class RangeSensor(Sensor, libraries=('libgazebo_ros_range.so',), sensor_types=('ray',), kind=..., main_topic=...,
    block='ray', topic_param='topicName')`, and reads its own parameters in load().
    """
    libraries = ()     # upstream's library names it answers, e.g. ('libgazebo_ros_range.so',): registry.py
    plugin_kind = PluginKind.SENSOR
    sensor_types = ()  # the <sensor type>s it works in; in another, configure() refuses it (upstream's Load throws)
    kind = None        # a SensorKind
    main_topic = None  # the role whose rate is reported
    block = None       # the <sensor>'s block it reads ('ray', 'camera': SensorSpec's); without it, refused
    topic_param = None  # the parameter naming its topic (topicName) when, written empty, nothing is advertised
    counts_frames = False  # a camera: its updates are frames (performance_metrics reports their rate as fps)

    def __init_subclass__(cls, libraries=None, sensor_types=None, kind=None, main_topic=None, block=None,
                          topic_param=None, **kwargs):
        super().__init_subclass__(**kwargs)
        declared = {'libraries': libraries, 'sensor_types': sensor_types, 'kind': kind, 'main_topic': main_topic,
                    'block': block, 'topic_param': topic_param}
        for name, value in declared.items():
            if value is not None:  # not declared: inherited (a multicamera's main topic is the camera's)
                setattr(cls, name, value)

    @classmethod
    def configure(cls, spec, plugin, spawn_namespace='', model_name='', node_namespace='/'):
        """This plugin's SensorConfig in the <sensor> `spec`, read as its Load() reads the <sensor> and the <plugin>
        (a GazeboPlugin spec), or None when it publishes nothing (an empty topic name). Raises SensorConfigError
        when it cannot run there (upstream's Load throws or stops). spawn_namespace: the spawn request's
        robot_namespace; model_name: the spawned model's name; node_namespace: the world server's."""
        sdf = SensorSdf(spec, plugin, spawn_namespace, model_name, node_namespace)
        if spec.type not in cls.sensor_types:
            raise SensorConfigError('%s: %s is a %s plugin but the sensor is of type %r (expected %s)'
                                    % (sdf.what, plugin.filename, cls.kind, spec.type, ' or '.join(cls.sensor_types)))
        if cls.block is not None and getattr(spec, cls.block) is None:
            raise SensorConfigError('%s: the sensor has no <%s> block' % (sdf.what, cls.block))
        if cls.topic_param is not None and sdf.params.get(cls.topic_param) == '':
            return None  # upstream advertises nothing
        config = SensorConfig(spec.name, cls.kind, spec.reference, '', spec.update_rate, warnings=sdf.warnings,
                              sensor_class=cls)
        return cls.load(config, sdf)

    @classmethod
    def load(cls, config, sdf):
        """The plugin's Load(): reads its parameters (sdf, a SensorSdf) into `config` (its topics, frame, params;
        rate and frame_id when not the sensor's); returns it, or None when the plugin advertises nothing."""
        raise NotImplementedError

    @classmethod
    def create(cls, manager, robot, spec, config):
        """The sensors that run for one <sensor> block (a SensorConfig of this class): this one."""
        return [cls(manager, robot, spec, config)]

    def __init__(self, manager, robot, spec, config):
        self.manager = manager
        self.sim = manager.sim
        self.robot_name = robot.name
        self.spec = spec
        self.config = config
        self.mount = SensorMount(self.sim.world, robot.body, robot.model, spec.reference, spec.pose)
        self.schedule = UpdateSchedule(config.rate, start=self.sim.time)
        self.meter = RateMeter(frames=self.counts_frames)
        self.publishers = {}
        self.failed = False
        self.closed = False  # set by close(), before the topics are unregistered

    def advertise(self, role, msg_class, queue_size):
        self.publishers[role] = self.manager.rospy.Publisher(self.config.topics[role], msg_class,
                                                             queue_size=queue_size)

    def listened(self, *roles):
        """True when any of the roles' topics (all, if none named) has a subscriber."""
        publishers = self.publishers
        for role in roles or publishers:  # a loop, not any(...): every sensor asks at every update
            if publishers[role].get_num_connections() > 0:
                return True
        return False

    def wake_time(self):
        """The sim time this sensor next needs a step(): its next update (the manager skips it till then)."""
        return self.schedule.next

    def step(self, time):
        if not self.schedule.due(time):
            return
        self.schedule.advance(time)
        self.update(time, ros_time(self.manager.rospy.Time, time))

    def update(self, time, stamp):
        raise NotImplementedError

    def close(self):
        self.closed = True
        publishers, self.publishers = self.publishers, {}
        for p in publishers.values():
            p.unregister()

    @property
    def topic(self):
        return self.config.topics[self.main_topic]
