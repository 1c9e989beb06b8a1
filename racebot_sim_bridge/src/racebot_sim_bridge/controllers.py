"""The ros_controllers this simulator offers, with ros_control's parameters, topics and semantics.

A controller is built from its parameters (the dict under `<ns>/<name>` on the parameter server),
the robot's hardware (hardware.RobotHW) and an I/O object that makes publishers and subscribers
(`RosIO` below for the real thing; tests pass their own). Construction is ros_control's init():
it raises ControllerInitError with a message that says what is wrong and what to do.

Types:
  joint_state_controller/JointStateController
  effort_controllers/JointEffortController, JointVelocityController, JointPositionController
  velocity_controllers/JointVelocityController, JointPositionController
  position_controllers/JointPositionController
"""
import math

from control_msgs.msg import JointControllerState
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from . import hardware
from .hardware import EFFORT, POSITION, STATE, VELOCITY, shortest_angular_distance
from .pid import Pid

STATE_PUBLISH_EVERY = 10  # ros_controllers publish their state topic every 10th update
# A command further than this beyond its joint's limit is warned about (clamping is exact; rounding
# of a command computed right at the limit, e.g. by servo_commands, is not worth a warning).
LIMIT_WARN_TOLERANCE = 1e-6


class ControllerInitError(ValueError):
    """init() of a controller failed; the message names the parameter or joint at fault."""


def shortest_angular_distance_with_limits(current, target, lower, upper):
    """Error that takes `current` to `target` without leaving [lower, upper] (angles' idea of
    shortest_angular_distance_with_large_limits): the short way round if it stays inside the
    limits, else the long way."""
    delta = shortest_angular_distance(current, target)
    if lower - 1e-12 <= current + delta <= upper + 1e-12:
        return delta
    other = delta - math.copysign(2.0 * math.pi, delta) if delta != 0.0 else 0.0
    if lower - 1e-12 <= current + other <= upper + 1e-12:
        return other
    return delta


class Controller(object):
    type_name = None
    interface = None  # the hardware interface it claims resources from

    def __init__(self, name, ns, params, hw, io):
        self.name = name
        self.ns = ns.rstrip('/')
        self.params = params if isinstance(params, dict) else {}
        self.hw = hw
        self.io = io
        self._topics = []

    @property
    def param_ns(self):
        return '%s/%s' % (self.ns, self.name)

    def topic(self, leaf):
        return '%s/%s/%s' % (self.ns, self.name, leaf)

    def claimed_resources(self):
        """[(interface, [resources])] as list_controllers reports them."""
        return [(self.interface, [])]

    def starting(self, time):
        pass

    def update(self, time, period):
        pass

    def stopping(self, time):
        pass

    def shutdown(self):
        for t in self._topics:
            t.unregister()
        self._topics = []

    def _pub(self, topic, cls, queue_size=1):
        p = self.io.publisher(topic, cls, queue_size)
        self._topics.append(p)
        return p

    def _sub(self, topic, cls, cb):
        s = self.io.subscriber(topic, cls, cb)
        self._topics.append(s)
        return s

    def _joint_param(self):
        joint = self.params.get('joint')
        if not isinstance(joint, str) or not joint:
            raise ControllerInitError("No joint given (namespace: %s): set '%s/joint' to one of the robot's "
                                      "joints (%s)" % (self.param_ns, self.param_ns, ', '.join(self.hw.names)))
        try:
            return self.hw.handle(joint, self.interface)
        except hardware.HardwareError as err:
            raise ControllerInitError('%s: %s' % (self.param_ns, err))

    def _pid(self):
        pid = self.params.get('pid')
        if not isinstance(pid, dict):
            raise ControllerInitError("No PID gains given (namespace: %s/pid): set at least pid: {p: ...}"
                                      % self.param_ns)
        try:
            return Pid.from_params(pid, self.param_ns + '/pid')
        except ValueError as err:
            raise ControllerInitError(str(err))


class JointStateController(Controller):
    type_name = 'joint_state_controller/JointStateController'
    interface = STATE

    def __init__(self, name, ns, params, hw, io):
        super(JointStateController, self).__init__(name, ns, params, hw, io)
        rate = self.params.get('publish_rate')
        if isinstance(rate, bool) or not isinstance(rate, (int, float)) or not math.isfinite(rate) or rate <= 0:
            raise ControllerInitError("Parameter 'publish_rate' not set or not a positive number (namespace: %s); "
                                      "e.g. publish_rate: 50" % self.param_ns)
        self.period = 1.0 / float(rate)
        names = self.params.get('joints') or self.hw.names
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise ControllerInitError("'%s/joints' must be a list of joint names, got %r" % (self.param_ns, names))
        try:
            self.handles = [self.hw.handle(n, STATE) for n in names]
        except hardware.HardwareError as err:
            raise ControllerInitError('%s: %s' % (self.param_ns, err))
        extra = self.params.get('extra_joints') or []
        if not isinstance(extra, list):
            raise ControllerInitError("'%s/extra_joints' must be a list of {name: ..., position: ..., velocity: ..., "
                                      "effort: ...}" % self.param_ns)
        self.extra = [self._extra_joint(e) for e in extra]
        self.msg = JointState()
        self.msg.name = [h.name for h in self.handles] + [e[0] for e in self.extra]
        self.pub = self._pub(self.ns + '/joint_states', JointState, 100)
        self.last_publish = None

    def _extra_joint(self, extra):
        """One entry of extra_joints, ros_controllers' form: {name: j, position: p, velocity: v, effort: e},
        the last three optional (0)."""
        if isinstance(extra, dict) and isinstance(extra.get('name'), str):
            try:
                values = [float(extra.get(k, 0.0)) for k in ('position', 'velocity', 'effort')]
            except (TypeError, ValueError):
                raise ControllerInitError("'%s/extra_joints' entry %r: position, velocity and effort must be "
                                          "numbers" % (self.param_ns, extra))
            return (extra['name'],) + tuple(values)
        raise ControllerInitError("'%s/extra_joints' entry %r has no 'name'; write {name: joint, position: 0.0}"
                                  % (self.param_ns, extra))

    def starting(self, time):
        self.last_publish = None

    def update(self, time, period):
        if self.last_publish is not None and time < self.last_publish + self.period - 1e-9:
            return
        # Keep the cadence of the period; after a long gap start again from now.
        if self.last_publish is None or time >= self.last_publish + 2 * self.period:
            self.last_publish = time
        else:
            self.last_publish += self.period
        msg = self.msg
        msg.header.stamp = self.io.stamp(time)
        msg.position = [h.position for h in self.handles] + [e[1] for e in self.extra]
        msg.velocity = [h.velocity for h in self.handles] + [e[2] for e in self.extra]
        msg.effort = [h.effort for h in self.handles] + [e[3] for e in self.extra]
        self.pub.publish(msg)


class _CommandController(Controller):
    """A single-joint controller with a std_msgs/Float64 `command` topic. Non-finite commands are
    ignored and commands beyond the joint's URDF limit clamped, each with a throttled warning."""
    setpoint = None  # what the command sets: 'position', 'velocity' or 'effort'

    def __init__(self, name, ns, params, hw, io):
        super(_CommandController, self).__init__(name, ns, params, hw, io)
        self.joint = self._joint_param()
        self.command = 0.0
        self._init_extra()  # everything that can fail comes before the subscription
        # The I/O's CommandObserver (make bench's CommandTrace), told where a command is taken and
        # where an update applies it; None (the default) costs one test per update.
        self.observer = getattr(io, 'command_trace', None)
        self._sub(self.topic('command'), Float64, self._on_command)

    def _init_extra(self):
        pass

    def _on_command(self, msg):
        value = msg.data
        if not math.isfinite(value):
            self.io.warn_throttle(self.param_ns, 5.0, '%s: ignored a non-finite command (%r) on %s; the last command (%g) stays in '
                                  'force. Publish a finite number.' % (self.param_ns, value, self.topic('command'),
                                                                       self.command))
            return
        kept, bounds, reaches = self.limit_command(value)
        if bounds is not None:
            self.io.warn_throttle(self.param_ns + '/limit', 5.0, '%s: command %g on %s is beyond the %s limit of joint '
                                  '%s (%s); %s %g. Publish a value within the URDF <limit> of the joint.'
                                  % (self.param_ns, value, self.topic('command'), self.setpoint, self.joint.name, bounds,
                                     'the hardware saturates it to' if kept == value else 'clamped to', reaches))
        self.command = kept  # a float assignment is atomic: the update loop reads the latest
        if self.observer is not None:
            self.observer.command_taken(self, value, kept)

    def limit_command(self, value):
        """(command to keep, None, value) for a command within the joint's URDF limit for what it
        sets; else (command to keep, the limit as text, what reaches the joint). A velocity or a
        position is clamped here, as ros_control's joint_limits_interface clamps what reaches the
        joint; an effort is kept and saturated by the hardware (hardware.JointHandle.limited_command)."""
        j = self.joint
        if self.setpoint == 'velocity' and j.max_velocity is not None:
            lo, hi, text = -j.max_velocity, j.max_velocity, '+-%g' % j.max_velocity
        elif self.setpoint == 'effort' and j.max_effort is not None:
            lo, hi, text = -j.max_effort, j.max_effort, '+-%g' % j.max_effort
        elif self.setpoint == 'position' and j.has_position_limits:
            lo, hi, text = j.lower, j.upper, '[%g, %g]' % (j.lower, j.upper)
        else:
            return value, None, value
        reaches = min(max(value, lo), hi)
        kept = value if self.setpoint == 'effort' else reaches
        if lo - LIMIT_WARN_TOLERANCE <= value <= hi + LIMIT_WARN_TOLERANCE:
            return kept, None, reaches
        return kept, text, reaches

    def claimed_resources(self):
        return [(self.interface, [self.joint.name])]


class _ForwardController(_CommandController):
    """ForwardCommandController: the command goes to the joint as it is."""

    def starting(self, time):
        self.command = self.joint.position if self.interface == POSITION else 0.0

    def update(self, time, period):
        cmd = self.command
        self.joint.command = cmd
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


class EffortForwardController(_ForwardController):
    type_name = 'effort_controllers/JointEffortController'
    interface = EFFORT
    setpoint = 'effort'


class VelocityForwardController(_ForwardController):
    type_name = 'velocity_controllers/JointVelocityController'
    interface = VELOCITY
    setpoint = 'velocity'


class PositionForwardController(_ForwardController):
    type_name = 'position_controllers/JointPositionController'
    interface = POSITION
    setpoint = 'position'


class _PidController(_CommandController):
    def _init_extra(self):
        self.pid = self._pid()
        self.state_pub = self._pub(self.topic('state'), JointControllerState, 1)
        self.loop_count = 0
        self.state = JointControllerState()
        # The message is filled only when somebody listens (publishing it to nobody is a no-op anyway).
        connections = getattr(self.state_pub, 'get_num_connections', None)
        self._state_wanted = (lambda: connections() > 0) if connections is not None else (lambda: True)

    def _publish_state(self, time, period, set_point, process_value, process_value_dot, error, command):
        if self.loop_count % STATE_PUBLISH_EVERY == 0 and self._state_wanted():
            s = self.state
            s.header.stamp = self.io.stamp(time)
            s.set_point = set_point
            s.process_value = process_value
            s.process_value_dot = process_value_dot
            s.error = error
            s.time_step = period
            s.command = command
            g = self.pid
            s.p, s.i, s.d = g.p, g.i, g.d
            s.i_clamp, s.antiwindup = g.i_clamp_max, bool(g.antiwindup)
            self.state_pub.publish(s)
        self.loop_count += 1


class JointVelocityController(_PidController):
    """effort_controllers/JointVelocityController: effort = PID(command - velocity)."""
    type_name = 'effort_controllers/JointVelocityController'
    interface = EFFORT
    setpoint = 'velocity'

    def starting(self, time):
        self.command = 0.0
        self.pid.reset()

    def update(self, time, period):
        cmd = self.command
        error = cmd - self.joint.velocity
        effort = self.pid.compute(error, period)
        self.joint.command = effort
        self._publish_state(time, period, cmd, self.joint.velocity, 0.0, error, effort)
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


class JointPositionController(_PidController):
    """effort_controllers/JointPositionController: effort = PID(position error); the command is
    clamped to the joint's URDF limits; holds the current position when started."""
    type_name = 'effort_controllers/JointPositionController'
    interface = EFFORT
    setpoint = 'position'

    def clamp(self, position):
        j = self.joint
        if j.has_position_limits:
            return min(max(position, j.lower), j.upper)
        return position

    def starting(self, time):
        self.command = self.clamp(self.joint.position)
        self.pid.reset()

    def position_error(self, target):
        j = self.joint
        if j.kind == 'revolute':
            if j.has_position_limits:
                return shortest_angular_distance_with_limits(j.position, target, j.lower, j.upper)
            return shortest_angular_distance(j.position, target)
        if j.kind == 'continuous':
            return shortest_angular_distance(j.position, target)
        return target - j.position

    def update(self, time, period):
        cmd = self.command
        target = self.clamp(cmd)
        error = self.position_error(target)
        out = self.pid.compute(error, period)
        self.joint.command = self._output(out)
        self._publish_state(time, period, target, self.joint.position, self.joint.velocity, error, out)
        if self.observer is not None:
            self.observer.command_applied(self, cmd)

    def _output(self, out):
        return out


class VelocityJointPositionController(JointPositionController):
    """velocity_controllers/JointPositionController: PID on position, output is a velocity."""
    type_name = 'velocity_controllers/JointPositionController'
    interface = VELOCITY


CONTROLLER_TYPES = {c.type_name: c for c in (
    JointStateController, EffortForwardController, JointVelocityController, JointPositionController,
    VelocityForwardController, VelocityJointPositionController, PositionForwardController)}


class CommandObserver(object):
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


class RosIO(object):
    """Publishers and subscribers through rospy (the simulator's real I/O)."""
    command_trace = None  # a CommandObserver (CommandTrace) of the command path: measurements only

    def __init__(self, rospy):
        self.rospy = rospy
        self._last_warning = {}  # key -> wall time of its last warning

    def publisher(self, topic, cls, queue_size):
        return self.rospy.Publisher(topic, cls, queue_size=queue_size)

    def subscriber(self, topic, cls, callback):
        return self.rospy.Subscriber(topic, cls, callback, queue_size=10)

    def stamp(self, time):
        return self.rospy.Time.from_sec(time)

    def warn_throttle(self, key, period, message):
        """A warning at most every `period` wall seconds per key (one bad publisher must not flood
        the log, nor hide another controller's warning)."""
        import time
        now = time.monotonic()
        if now - self._last_warning.get(key, -math.inf) >= period:
            self._last_warning[key] = now
            self.rospy.logwarn(message)
