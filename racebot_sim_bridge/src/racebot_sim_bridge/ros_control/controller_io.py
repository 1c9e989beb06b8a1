"""The controllers' I/O: rospy publishers and subscribers (`RosIO`); the observer of the command path that make
bench uses is command_trace.py's."""
import math

from racebot_sim_bridge.engine.sim_time import ros_time


class RosIO:
    """Publishers and subscribers through rospy (the simulator's real I/O)."""
    command_trace = None  # a command_trace.CommandObserver of the command path: measurements only

    def __init__(self, rospy):
        self.rospy = rospy
        self._last_warning = {}  # key -> wall time of its last warning

    def publisher(self, topic, cls, queue_size):
        return self.rospy.Publisher(topic, cls, queue_size=queue_size)

    def subscriber(self, topic, cls, callback):
        return self.rospy.Subscriber(topic, cls, callback, queue_size=10)

    def service(self, name, cls, handler):
        return _Unregisters(self.rospy.Service(name, cls, handler), 'shutdown')

    def action_server(self, ns, action_cls, goal_cb, cancel_cb):
        """actionlib's ActionServer on `ns` (goal, cancel, status, feedback, result), started."""
        import actionlib
        server = actionlib.ActionServer(ns, action_cls, goal_cb, cancel_cb, auto_start=False)
        server.start()
        return _Unregisters(server, 'stop')

    def stamp(self, time):
        return ros_time(self.rospy.Time, time)

    def warn_throttle(self, key, period, message):
        """A warning at most every `period` wall seconds per key (one bad publisher must not flood
        the log, nor hide another controller's warning)."""
        import time
        now = time.monotonic()
        if now - self._last_warning.get(key, -math.inf) >= period:
            self._last_warning[key] = now
            self.rospy.logwarn(message)


class _Unregisters:
    """A service or action server that goes away with unregister(), as a topic does (Controller.shutdown)."""

    def __init__(self, target, method):
        self.target = target
        self._method = method

    def unregister(self):
        getattr(self.target, self._method)()
