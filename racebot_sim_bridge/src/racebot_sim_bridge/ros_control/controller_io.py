"""The controllers' I/O: rospy publishers and subscribers (`RosIO`), and the observer of the
command path that make bench uses (`CommandObserver`, `CommandTrace`)."""
import math

from racebot_sim_bridge.engine.sim_time import ros_time


class CommandObserver:
    """What a command controller tells an observer of its command path (the I/O object's
    `command_trace`): `command_taken` on the subscriber's thread once a command is in force
    (`received` as published, `kept` after clamping; ignored non-finite commands are not told), and
    `command_applied` on the physics thread after each update, with the command that update used."""

    def command_taken(self, controller, received, kept):
        pass

    def command_applied(self, controller, command):
        pass


class CommandTrace(CommandObserver):
    """Opt-in record of the command path, for measurements (make bench): for every command a
    controller takes, a line `arrived <wall time> <controller> <value>`, and `applied <wall time>
    <controller> <value>` after the first update that uses it (a command overtaken by a newer one
    before any update is never applied). Wall time is time.monotonic() (CLOCK_MONOTONIC, comparable
    across processes on one machine)."""

    def __init__(self, path, clock=None):
        import threading
        import time
        self.clock = clock or time.monotonic
        self._file = open(path, 'a', buffering=1)  # line-buffered: a reader sees whole lines
        self._lock = threading.Lock()
        self._unapplied = {}  # controller -> the last command taken, until an update uses it

    def record(self, event, controller, value, when):
        with self._lock:
            self._file.write('%s %.9f %s %r\n' % (event, when, controller, value))

    def command_taken(self, controller, received, kept):
        when = self.clock()
        with self._lock:
            self._unapplied[controller] = kept
        self.record('arrived', controller.param_ns, received, when)

    def command_applied(self, controller, command):
        # Compared with the value, not a flag: an update that read the command just before a new
        # one was taken applied the old one, and the new one is still to be applied.
        with self._lock:
            if controller not in self._unapplied or self._unapplied[controller] != command:
                return
            del self._unapplied[controller]
        self.record('applied', controller.param_ns, command, self.clock())

    def close(self):
        self._file.close()


class RosIO:
    """Publishers and subscribers through rospy (the simulator's real I/O)."""
    command_trace = None  # a CommandObserver (CommandTrace) of the command path: measurements only

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
