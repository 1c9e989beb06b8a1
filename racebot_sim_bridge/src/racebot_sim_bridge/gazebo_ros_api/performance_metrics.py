"""The performance_metrics topic (gazebo_msgs/PerformanceMetrics) as Gazebo 11 and gazebo_ros publish it.

Gazebo's sensor manager sends a message at most 5 times a wall second (its publisher is throttled to
5 Hz), only while someone listens and only when sim time went on since the last one (never while
paused): the real-time factor over that interval, and for each sensor that has measured, its update
rate in sim time and in wall time and, for a camera, its frames per second (-1 for other sensors, as
gazebo_ros fills a missing fps). Sensors are named as Gazebo scopes them, world::model::link::sensor,
the link being the one the sensor's link is lumped into. A sensor keeps its last rates through an
interval in which it did not measure (Gazebo keeps them too). Here a sensor measures only while its
topics have subscribers (sensors/sensor_manager.py), so an unread sensor is absent.

MetricsWindow is the arithmetic (no ROS); PerformanceMetricsPublisher the thread and the topic.
"""
import threading
import time as walltime

from racebot_sim_bridge.engine.sim_time import ros_time

PUBLISH_PERIOD = 0.2  # wall seconds: Gazebo advertises /gazebo/performance_metrics at 5 Hz
NO_FPS = -1.0  # gazebo_ros's value for a sensor without frames


class MetricsWindow:
    """Rates between two samples. sample(sim, wall, sensors) with sensors [(name, measurements so far,
    is camera)] returns None (no sim time passed: nothing to say) or (real-time factor,
    [(name, sim Hz, wall Hz, fps)])."""

    def __init__(self):
        self._last = None  # (sim, wall) of the last answer
        self._counts = {}  # name -> measurements at the last answer
        self._rates = {}  # name -> (sim Hz, wall Hz, fps), kept while a sensor is quiet

    def sample(self, sim_time, wall_time, sensors):
        if self._last is None:
            self._last = (sim_time, wall_time)
            self._counts = {name: count for name, count, _ in sensors}
            return None
        dsim, dwall = sim_time - self._last[0], wall_time - self._last[1]
        if dsim <= 0:  # paused (or reset): Gazebo sends nothing
            if dsim < 0:
                self._last = (sim_time, wall_time)
            return None
        rtf = dsim / dwall if dwall > 0 else 0.0
        names = set()
        for name, count, is_camera in sensors:
            names.add(name)
            n = count - self._counts.get(name, count)
            self._counts[name] = count
            if n > 0:
                wall_hz = n / dwall if dwall > 0 else 0.0
                self._rates[name] = (n / dsim, wall_hz, wall_hz if is_camera else NO_FPS)
        for gone in set(self._rates) - names:
            del self._rates[gone]
        self._last = (sim_time, wall_time)
        return rtf, [(name,) + self._rates[name] for name in sorted(self._rates)]


class PerformanceMetricsPublisher:
    """`ns`/performance_metrics from the world's sensors (a SensorManager), in a thread of its own."""

    def __init__(self, rospy, sim, sensor_manager, ns, clock=walltime.perf_counter):
        from gazebo_msgs.msg import PerformanceMetrics
        self.rospy = rospy
        self.sim = sim
        self.sensor_manager = sensor_manager
        self.clock = clock
        self.window = MetricsWindow()
        self.pub = rospy.Publisher(ns.rstrip('/') + '/performance_metrics', PerformanceMetrics, queue_size=10)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name='performance_metrics', daemon=True)
        self._thread.start()

    def sensors(self):
        """[(scoped name, measurements so far, is camera)] of the sensors now in the world."""
        from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
        out, seen = [], set()
        with self.sim.lock:
            for robot_name, group in self.sensor_manager.sensors.items():
                robot = self.sim.robots.get(robot_name)
                if robot is None:
                    continue
                for s in group:
                    link = robot.model.lumped_link(s.spec.reference) if s.spec.reference in robot.model.links \
                        else s.spec.reference
                    name = '%s::%s::%s::%s' % (self.sim.spec.name, robot_name, link, s.config.name)
                    if name not in seen:  # a multicamera's cameras are one Gazebo sensor: its first counts
                        seen.add(name)
                        out.append((name, s.meter.total, isinstance(s, CameraSensor)))
        return out

    def publish_once(self):
        """One sample; publishes when someone listens and sim time went on."""
        if self.pub.get_num_connections() == 0:
            self.window = MetricsWindow()  # the next listener starts a fresh interval
            return
        result = self.window.sample(self.sim.time, self.clock(), self.sensors())
        if result is None:
            return
        from gazebo_msgs.msg import PerformanceMetrics, SensorPerformanceMetric
        msg = PerformanceMetrics()
        msg.header.stamp = ros_time(self.rospy.Time, self.sim.time)
        msg.real_time_factor = result[0]
        msg.sensors = [SensorPerformanceMetric(name=n, sim_update_rate=s, real_update_rate=r, fps=f)
                       for n, s, r, f in result[1]]
        self.pub.publish(msg)

    def _loop(self):
        while not self._stop.wait(PUBLISH_PERIOD):
            try:
                self.publish_once()
            except Exception as err:  # the node is shutting down under us: nothing left to report to
                if not self._stop.is_set() and not self.rospy.is_shutdown():
                    self.rospy.logwarn('performance_metrics: %s' % err)

    def shutdown(self):
        self._stop.set()
        self.pub.unregister()
