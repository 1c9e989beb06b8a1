"""The unit tests' stand-ins for what the simulator is given from outside: a log, rospy, a controller's I/O.
One of each, shared by every test module (`from fakes import FakeLog, ...`; tests/unit is on pytest's
pythonpath, tests/unit/pytest.ini)."""
import copy

import rospy


class FakeLog:
    """A log that records every line as (level, message), level one of 'debug', 'info', 'warn', 'error',
    'fatal'. It answers both the simulator's log calls (log.warn(...)) and rospy's (rospy.logwarn(...)),
    so it stands in for either. `errors`, `warnings`, `infos`: the messages of one level, in order."""

    def __init__(self):
        self.lines = []

    def _record(self, level, message, args):
        self.lines.append((level, message % args if args else message))

    def debug(self, message, *args):
        self._record('debug', message, args)

    def info(self, message, *args):
        self._record('info', message, args)

    def warn(self, message, *args):
        self._record('warn', message, args)

    def error(self, message, *args):
        self._record('error', message, args)

    def fatal(self, message, *args):
        self._record('fatal', message, args)

    logdebug, loginfo, logwarn, logerr, logfatal = debug, info, warn, error, fatal

    def messages(self, level=None):
        """The messages of `level`, or of every level."""
        return [m for lv, m in self.lines if level in (None, lv)]

    def said(self, fragment, level=None):
        """Whether a message (of `level`, or of any) contains `fragment`."""
        return any(fragment in m for m in self.messages(level))

    @property
    def errors(self):
        return self.messages('error')

    @property
    def warnings(self):
        return self.messages('warn')

    @property
    def infos(self):
        return self.messages('info')


class NullIO:
    """An I/O object that takes every call and does nothing (the Simulator's io when nothing is published)."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


class FakeTopic:
    """A controller's publisher or subscriber: what it published (copies: controllers reuse their messages)."""

    def __init__(self, io, topic, cls, queue_size=None, callback=None):
        self.io, self.topic, self.cls, self.queue_size, self.callback = io, topic, cls, queue_size, callback
        self.messages = []
        self.unregistered = False

    def publish(self, msg):
        assert isinstance(msg, self.cls)
        self.messages.append(copy.deepcopy(msg))

    def unregister(self):
        self.unregistered = True


class FakeIO:
    """The I/O object controllers take (ros_control.controller_io.RosIO's calls), recorded in memory:
    `publishers` and `subscribers` by topic, `topics` both, `warnings` the throttled warnings. With
    `one_publisher_per_topic` (the default), a second live publisher on a topic fails the test: a controller
    that advertises a topic twice is wrong; two controllers may share one (two joint state controllers)."""

    def __init__(self, one_publisher_per_topic=True):
        self.one_publisher_per_topic = one_publisher_per_topic
        self.publishers = {}
        self.subscribers = {}
        self.topics = {}
        self.warnings = []

    def publisher(self, topic, cls, queue_size):
        old = self.publishers.get(topic)
        assert old is None or old.unregistered or not self.one_publisher_per_topic, 'two publishers on %s' % topic
        self.publishers[topic] = self.topics[topic] = FakeTopic(self, topic, cls, queue_size)
        return self.publishers[topic]

    def subscriber(self, topic, cls, callback):
        self.subscribers[topic] = self.topics[topic] = FakeTopic(self, topic, cls, callback=callback)
        return self.subscribers[topic]

    def stamp(self, t):
        return rospy.Time.from_sec(t)

    def warn_throttle(self, key, period, message):
        self.warnings.append(message)

    def send(self, topic, value):
        """A std_msgs/Float64 `value` delivered to the subscriber of `topic`."""
        from std_msgs.msg import Float64
        sub = self.subscribers[topic]
        assert sub.cls is Float64
        sub.callback(Float64(value))

    def published(self, topic):
        return self.publishers[topic].messages


class FakePublisher:
    """A rospy.Publisher: what was published, and as many subscribers as `connections` says."""

    def __init__(self, topic):
        self.topic = topic
        self.connections = 0
        self.messages = []

    def get_num_connections(self):
        return self.connections

    def publish(self, msg):
        self.messages.append(msg)

    def unregister(self):
        pass


class FakeService:
    def shutdown(self):
        pass


class FakeRospy:
    """The part of rospy the sensor and plugin managers use, without a master: publishers by topic,
    service handlers by name, parameters from a dict, and log lines as (level, message) in `logs`."""
    Time = rospy.Time

    def __init__(self, params=None):
        self.params = dict(params or {})
        self.publishers = {}
        self.services = {}
        self.logs = []

    def get_param(self, name, default=None):
        return self.params.get(name, default)

    def set_param(self, name, value):
        self.params[name] = value

    def Publisher(self, topic, msg_class, queue_size=None):
        assert queue_size, 'every publisher needs a queue_size'
        self.publishers[topic] = FakePublisher(topic)
        return self.publishers[topic]

    def Service(self, name, service_class, handler):
        self.services[name] = handler
        return FakeService()

    def loginfo(self, msg):
        self.logs.append(('info', msg))

    def logwarn(self, msg):
        self.logs.append(('warn', msg))

    def logerr(self, msg):
        self.logs.append(('error', msg))

    def is_shutdown(self):
        return True


class FakeNames:
    """sensors/contact's names of the other body in a contact: 'other<body>::link<link>::collision'."""

    def name(self, body, link, point):
        return 'other%d::link%d::collision' % (body, link)
