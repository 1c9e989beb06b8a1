"""What every simulated Gazebo model plugin shares: its life cycle, its parameters, its ROS I/O.

A model plugin is one `<gazebo><plugin filename="libgazebo_ros_X.so">` block of a spawned robot
(not gazebo_ros_control, which the simulator runs, and not a `<sensor>`'s plugin: sensor_plugin.py). It is
built when the robot spawns (Gazebo's Load): bad parameters are warned about with the value used
instead (PluginParams), or the plugin is refused with PluginError and the robot spawns without it.
Then, on the physics thread under Simulator.lock:
  before_physics(time)  just before each physics step (drives set their wheels here: Gazebo's
                        plugins act on WorldUpdateBegin), `time` the sim time the step ends at;
  after_step(time)      after each physics step, with the new sim time (publishers);
  reset()               after reset_world / reset_simulation (Gazebo's Reset);
  close()               when the robot is deleted or the world server stops.
Subscriber callbacks run on rospy's threads: they only store the latest command (one attribute
assignment, atomic), which the physics thread reads.
"""
import math

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind


class PluginError(ValueError):
    """The plugin cannot work with these parameters; the message says which and what to do."""


class PluginParams:
    """A plugin's SDF parameters (child tag -> text), read with upstream's defaults. A value that is
    missing gets the default silently (as upstream, which logs at most a debug line); a value that is
    present and wrong gets a warning naming the tag, what was wrong and the value used instead."""

    def __init__(self, spec, warn):
        self.spec = spec
        self._warn = warn
        self.values = spec.params

    def has(self, tag):
        return tag in self.values

    def warn(self, message):
        self._warn(message)

    def string(self, tag, default):
        text = self.values.get(tag)
        return default if text is None else text

    def number(self, tag, default, minimum=None, exclusive=False):
        """A float; `minimum` (with `exclusive`: strictly greater) bounds what is accepted."""
        text = self.values.get(tag)
        if text is None:
            return default
        try:
            value = float(text)
        except ValueError:
            value = None
        if value is None or not math.isfinite(value):
            self.warn('<%s>%s</%s> is not a finite number; using %r' % (tag, text, tag, default))
            return default
        if minimum is not None and (value < minimum or (exclusive and value == minimum)):
            self.warn('<%s>%s</%s> must be %s %g; using %r' % (tag, text, tag, '>' if exclusive else '>=',
                                                                minimum, default))
            return default
        return value

    def integer(self, tag, default, minimum=None):
        text = self.values.get(tag)
        if text is None:
            return default
        try:
            value = int(text)
        except ValueError:
            self.warn('<%s>%s</%s> is not an integer; using %r' % (tag, text, tag, default))
            return default
        if minimum is not None and value < minimum:
            self.warn('<%s>%s</%s> must be >= %d; using %r' % (tag, text, tag, minimum, default))
            return default
        return value

    def boolean(self, tag, default):
        """sdformat's bool: true/false/1/0 (case-insensitive)."""
        text = self.values.get(tag)
        if text is None:
            return default
        low = text.strip().lower()
        if low in ('true', '1'):
            return True
        if low in ('false', '0'):
            return False
        self.warn('<%s>%s</%s> is not a boolean (true, false, 1, 0); using %r' % (tag, text, tag, default))
        return default

    def vector(self, tag, count, default):
        """`count` numbers separated by spaces (an xyz or rpy)."""
        text = self.values.get(tag)
        if text is None:
            return tuple(default)
        try:
            values = tuple(float(v) for v in text.split())
        except ValueError:
            values = ()
        if len(values) != count or not all(math.isfinite(v) for v in values):
            self.warn('<%s>%s</%s> must be %d finite numbers; using %s'
                      % (tag, text, tag, count, ' '.join('%g' % v for v in default)))
            return tuple(default)
        return values

    def choice(self, tag, choices, default):
        """One of `choices` (strings, compared as written, or numbers given as text)."""
        text = self.values.get(tag)
        if text is None:
            return default
        if text in choices:
            return text
        self.warn('<%s>%s</%s> must be one of %s; using %s' % (tag, text, tag, ', '.join(choices), default))
        return default


class ModelPlugin:
    """Base of every simulated model plugin. `ctx` is the PluginManager (rospy, the Simulator, the
    shared /tf publisher, logging); `robot` the simulator.Robot; `spec` the urdf_model.GazeboPlugin."""
    libraries = ()  # upstream's library names it answers, e.g. ('libgazebo_ros_diff_drive.so',); registry.py
    plugin_kind = PluginKind.MODEL

    def __init__(self, ctx, robot, spec):
        self.ctx = ctx
        self.robot = robot
        self.spec = spec
        self.world = ctx.sim.world
        self.params = PluginParams(spec, self.warn)
        self._topics = []
        if spec.rewrites:  # Gazebo says nothing of it; a user who wrote imu_link and reads base_link hears why
            self.info("as Gazebo 11 loads it, sdformat's fixed-joint lumping rewrote %s" % ', '.join(
                '<%s> %s -> %s' % (element, '(none)' if written is None else written, now)
                for element, (written, now) in _rewritten(spec.rewrites).items()))

    # -- life cycle (physics thread, under Simulator.lock) ------------------------------------
    # Work upstream does at every world update whatever the plugin's rate (the diff drive's encoder): a callable
    # of the update's time in integer ns, or None. PluginManager calls it for every plugin that has one before
    # any plugin's before_physics.
    every_update = None

    def before_physics(self, time):
        pass

    def quiet_span(self):
        """(from_ns, until_ns): before_physics surely does nothing at an update whose time (integer ns) is in
        [from_ns, until_ns), so PluginManager need not call it until then; asked after each call and after a
        reset. None (the base's): call it at every update."""
        return None

    def after_step(self, time):
        pass

    def reset(self):
        pass

    def close(self):
        for t in self._topics:
            t.unregister()
        self._topics = []

    # -- helpers ----------------------------------------------------------------------------
    @property
    def label(self):
        return "%s: plugin '%s' (%s)" % (self.robot.name, self.spec.name, self.libraries[0])

    def warn(self, message):
        self.ctx.rospy.logwarn('%s: %s' % (self.label, message))

    def info(self, message):
        self.ctx.rospy.loginfo('%s: %s' % (self.label, message))

    def root_link(self):
        """The model's root link (the physics' base)."""
        return next(name for name, index in self.robot.body.link_index.items() if index == -1)

    def link_param(self, tag, what, default=None, name=None):
        """The link <tag> names (``name`` when given, else the parameter, else ``default``): a link the
        physics has. A <bodyName> or <frameName> naming a link Gazebo lumps comes here already rewritten to
        the link it went into (description/sdf_reduction, as sdformat). PluginError when it is missing and
        there is no default, when the physics merged it all the same (another tag, or a link fixed to a root
        named world, which sdformat keeps: the hint names where it went), or when the model has no such link."""
        if name is None:
            name = self.params.string(tag, default)
        if name is None:
            raise PluginError('<%s> is missing: give %s' % (tag, what))
        model, body = self.robot.model, self.robot.body
        if name in model.links and name not in body.link_index:
            merged = model.lumped_link(name)
            raise PluginError("<%s>%s</%s>: Gazebo merges this link into '%s' (a fixed joint), so the model has no "
                              "link of that name; name '%s', or keep the joint with <preserveFixedJoint>"
                              % (tag, name, tag, merged, merged))
        if name not in body.link_index:
            raise PluginError("<%s>%s</%s> is not a link of the model (its links: %s)"
                              % (tag, name, tag, ', '.join(sorted(body.link_index))))
        return name

    def publisher(self, topic, cls, queue_size=1):
        p = self.ctx.rospy.Publisher(topic, cls, queue_size=queue_size)
        self._topics.append(p)
        return p

    def subscriber(self, topic, cls, callback, queue_size=1):
        s = self.ctx.rospy.Subscriber(topic, cls, callback, queue_size=queue_size)
        self._topics.append(s)
        return s

    def service(self, name, cls, handler):
        s = self.ctx.rospy.Service(name, cls, handler)
        self._topics.append(_ServiceHandle(s))
        return s

    def reconfigure_server(self, namespace, config_type, callback):
        """A dynamic_reconfigure server under `namespace` (absolute), shut down with the plugin."""
        server = self.ctx.reconfigure(namespace, config_type, callback)
        self._topics.append(_ReconfigureHandle(server))
        return server

    def stamp(self, time):
        return ros_time(self.ctx.rospy.Time, time)

    def publish_wrench(self, time, force, torque):
        """A geometry_msgs/WrenchStamped (`self.msg_class`) in `self.frame_id`, stamped `time`, on `self.pub`: what
        gazebo_ros_ft_sensor and gazebo_ros_f3d publish."""
        msg = self.msg_class()
        msg.header.frame_id = self.frame_id
        msg.header.stamp = self.stamp(time)
        w = msg.wrench
        w.force.x, w.force.y, w.force.z = force
        w.torque.x, w.torque.y, w.torque.z = torque
        self.pub.publish(msg)

    def joint(self, tag, default=None):
        """The movable joint named by <tag> (a physics.Joint); PluginError when it is missing or
        names no movable joint of the robot: nothing sensible can stand in for a wheel."""
        name = self.params.string(tag, default)
        if not name:
            raise PluginError('<%s> is missing: give the name of one of the joints %s'
                              % (tag, ', '.join(sorted(self.robot.body.joints))))
        joint = self.robot.body.joints.get(name)
        if joint is None:
            raise PluginError("<%s>%s</%s> is not a movable joint of the robot (its joints: %s)"
                              % (tag, name, tag, ', '.join(sorted(self.robot.body.joints)) or 'none'))
        return joint

    def link(self, tag, default=None):
        """The link named by <tag>, or `default` (the robot's root link when None) when absent;
        PluginError when it names no link of the robot."""
        name = self.params.string(tag, None)
        if name is None:
            return default if default is not None else self.robot.model.root_link
        if name not in self.robot.model.links:
            raise PluginError("<%s>%s</%s> is not a link of the robot (its links: %s)"
                              % (tag, name, tag, ', '.join(sorted(self.robot.model.links))))
        return name


def _rewritten(rewrites):
    """{element: (as first written, as last rewritten)} of a list of urdf_model.Rewrite, in order."""
    changes = {}
    for r in rewrites:
        changes[r.element] = (changes.get(r.element, (r.written,))[0], r.now)
    return changes


class _ServiceHandle:
    def __init__(self, service):
        self.service = service

    def unregister(self):
        self.service.shutdown()


class _ReconfigureHandle:
    def __init__(self, server):
        self.server = server

    def unregister(self):
        for name in ('descr_topic', 'update_topic'):  # dynamic_reconfigure's Server has no shutdown of its own
            topic = getattr(self.server, name, None)
            if topic is not None:
                topic.unregister()
        service = getattr(self.server, 'set_service', None)
        if service is not None:
            service.shutdown()
