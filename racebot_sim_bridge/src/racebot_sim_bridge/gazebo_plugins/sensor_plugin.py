"""What every simulated sensor plugin shares: its schedule, mount, publishers and rate meter.

A sensor plugin is the `<plugin filename="libgazebo_ros_X.so">` inside a URDF's `<gazebo reference><sensor>` (a
model's own <plugin>s are model_plugin.py's). ../sensors/config.py reads the block into a SensorConfig (topics,
frame, rate, the plugin's parameters as its Load() reads them) and names the class registry.py gives for the
library; ../sensors/sensor_manager.py builds it with create() when the robot spawns and calls step(time) on the
physics thread after every physics step, under Simulator.lock: the schedule says whether an update is due
(../sensors/schedule.py); if anybody listens, update() measures with the pipeline stages in ../sensors/ and
publishes messages stamped with the sim time of the measurement. close() when the robot goes.
"""
from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_plugins import PluginKind
from racebot_sim_bridge.sensors.mount import SensorMount
from racebot_sim_bridge.sensors.schedule import RateMeter, UpdateSchedule


class Sensor:
    """One simulated sensor: its schedule, mount, publishers and rate meter."""
    libraries = ()     # upstream's library names it answers, e.g. ('libgazebo_ros_range.so',): registry.py
    plugin_kind = PluginKind.SENSOR
    sensor_types = ()  # the <sensor type>s it works in; in another, config.py refuses it (upstream's Load throws)
    kind = None        # what config.py reads its parameters as and the log calls it: laser, camera, depth, imu, ...
    main_topic = None  # the role whose rate is reported

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
