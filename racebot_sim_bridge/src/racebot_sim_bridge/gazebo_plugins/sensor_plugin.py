"""What every simulated sensor plugin shares: its schedule, mount, publishers and rate meter.

A sensor plugin is the `<plugin filename="libgazebo_ros_X.so">` inside a URDF's `<gazebo reference><sensor>` (a
model's own <plugin>s are model_plugin.py's). ../sensors/config.py reads the block into a SensorConfig (topics,
frame, rate, the plugin's parameters as its Load() reads them) and names the class registry.py gives for the
library; ../sensors/sensor_manager.py builds it with create() when the robot spawns and calls step(time) on the
physics thread after every physics step, under Simulator.lock: the schedule says whether an update is due
(../sensors/schedule.py); if anybody listens, update() measures with the pipeline stages in ../sensors/ and
publishes messages stamped with the sim time of the measurement. close() when the robot goes.
"""
from enum import Enum

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.sensors.mount import SensorMount
from racebot_sim_bridge.sensors.schedule import RateMeter, UpdateSchedule


class SensorKind(str, Enum):
    """What config.py reads a sensor plugin's parameters as, and the log calls it. A str ('laser' == LASER)."""
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


class Sensor:
    """One simulated sensor: its schedule, mount, publishers and rate meter.

    A plugin class declares in its class line what registry.py and config.py read of it:
    `class RangeSensor(Sensor, libraries=('libgazebo_ros_range.so',), sensor_types=('ray',), kind=..., main_topic=...)`.
    """
    libraries = ()     # upstream's library names it answers, e.g. ('libgazebo_ros_range.so',): registry.py
    plugin_kind = PluginKind.SENSOR
    sensor_types = ()  # the <sensor type>s it works in; in another, config.py refuses it (upstream's Load throws)
    kind = None        # a SensorKind
    main_topic = None  # the role whose rate is reported

    def __init_subclass__(cls, libraries=None, sensor_types=None, kind=None, main_topic=None, **kwargs):
        super().__init_subclass__(**kwargs)
        declared = {'libraries': libraries, 'sensor_types': sensor_types, 'kind': kind, 'main_topic': main_topic}
        for name, value in declared.items():
            if value is not None:  # not declared: inherited (a multicamera's main topic is the camera's)
                setattr(cls, name, value)

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
        self.meter = RateMeter()
        self.publishers = {}
        self.failed = False

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
        publishers, self.publishers = self.publishers, {}
        for p in publishers.values():
            p.unregister()

    @property
    def topic(self):
        return self.config.topics[self.main_topic]
