"""What every controller shares: ros_control's Controller life cycle over an injected I/O, the
init error, the action controllers'
goal (`GoalController`), and the single-joint command controllers' `command` topic with its limits."""
import math
from enum import Enum

from std_msgs.msg import Float64
from control_msgs.msg import JointControllerState

from racebot_sim_bridge.ros_control import hardware_interface as hardware
from racebot_sim_bridge.ros_control.pid import Pid


STATE_PUBLISH_EVERY = 10  # ros_controllers publish their state topic every 10th update
# A command further than this beyond its joint's limit is warned about (clamping is exact; rounding
# of a command computed right at the limit, e.g. by servo_commands, is not worth a warning).
LIMIT_WARN_TOLERANCE = 1e-6


class ControllerInitError(ValueError):
    """init() of a controller failed; the message names the parameter or joint at fault."""


class Controller:
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

    # -- parameters: `path` is relative to the controller's namespace, parts joined by "/" --
    def _lookup(self, path):
        node = self.params
        for part in path.split('/'):
            if not isinstance(node, dict) or part not in node:
                return None
            node = node[part]
        return node

    def _number(self, path, default, positive=False):
        value = self._lookup(path)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
                or (positive and value <= 0):
            raise ControllerInitError('%s/%s must be a %snumber, got %r' % (self.param_ns, path,
                                                                           'positive ' if positive else '', value))
        return float(value)

    def _flag(self, path, default):
        return self._typed(path, default, bool, 'true or false')

    def _text(self, path, default):
        return self._typed(path, default, str, 'a string')

    def _typed(self, path, default, kind, what):
        """The parameter at `path` (`default` when unset), which must be a `kind` (`what` says so)."""
        value = self._lookup(path)
        if value is None:
            return default
        if not isinstance(value, kind):
            raise ControllerInitError('%s/%s must be %s, got %r' % (self.param_ns, path, what, value))
        return value

    def _joint_param(self):
        joint = self.params.get('joint')
        if not isinstance(joint, str) or not joint:
            raise ControllerInitError("No joint given (namespace: %s): set '%s/joint' to one of the robot's "
                                      "joints (%s)" % (self.param_ns, self.param_ns, ', '.join(self.hw.names)))
        return self._handle(joint)

    def _handle(self, joint, interface=None):
        """The hardware's handle of `joint` through `interface` (the controller's own when None), as init()
        claims it: a joint or interface the robot does not offer is a ControllerInitError naming the controller."""
        try:
            return self.hw.handle(joint, interface or self.interface)
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


class GoalController(Controller):
    """What the action controllers share (joint_trajectory_controller's, gripper_action_controller's): one
    accepted goal at a time (`active_goal`), changed under `_lock` with `running`; stopping cancels it, as
    upstream's preemptActiveGoal does."""

    def stopping(self, time):
        with self._lock:
            self.running = False
            goal, self.active_goal = self.active_goal, None
        if goal is not None:
            goal.set_canceled()


class Setpoint(str, Enum):
    """What a single-joint controller's command sets (the limit that applies to it)."""
    POSITION = 'position'
    VELOCITY = 'velocity'
    EFFORT = 'effort'

    def __str__(self):
        return self.value


class CommandController(Controller):
    """A single-joint controller with a std_msgs/Float64 `command` topic. Non-finite commands are
    ignored and commands beyond the joint's URDF limit clamped, each with a throttled warning."""
    setpoint = None  # what the command sets: a Setpoint

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
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
            self.io.warn_throttle(self.param_ns, 5.0, '%s: ignored a non-finite command (%r) on %s; the last '
                                  'command (%g) stays in force. Publish a finite number.'
                                  % (self.param_ns, value, self.topic('command'), self.command))
            return
        kept, bounds, reaches = self.limit_command(value)
        if bounds is not None:
            self.io.warn_throttle(self.param_ns + '/limit', 5.0, '%s: command %g on %s is beyond the %s limit of joint '
                                  '%s (%s); %s %g. Publish a value within the URDF <limit> of the joint.'
                                  % (self.param_ns, value, self.topic('command'), self.setpoint, self.joint.name,
                                     bounds, 'the hardware saturates it to' if kept == value else 'clamped to',
                                     reaches))
        self.command = kept  # a float assignment is atomic: the update loop reads the latest
        if self.observer is not None:
            self.observer.command_taken(self, value, kept)

    def limit_command(self, value):
        """(command to keep, None, value) for a command within the joint's URDF limit for what it
        sets; else (command to keep, the limit as text, what reaches the joint). A velocity or a
        position is clamped here, as ros_control's joint_limits_interface clamps what reaches the
        joint; an effort is kept and saturated by the hardware (hardware_interface.JointHandle.limited_command)."""
        j = self.joint
        if self.setpoint is Setpoint.VELOCITY and j.max_velocity is not None:
            lo, hi, text = -j.max_velocity, j.max_velocity, '+-%g' % j.max_velocity
        elif self.setpoint is Setpoint.EFFORT and j.max_effort is not None:
            lo, hi, text = -j.max_effort, j.max_effort, '+-%g' % j.max_effort
        elif self.setpoint is Setpoint.POSITION and j.has_position_limits:
            lo, hi, text = j.lower, j.upper, '[%g, %g]' % (j.lower, j.upper)
        else:
            return value, None, value
        reaches = min(max(value, lo), hi)
        kept = value if self.setpoint is Setpoint.EFFORT else reaches
        if lo - LIMIT_WARN_TOLERANCE <= value <= hi + LIMIT_WARN_TOLERANCE:
            return kept, None, reaches
        return kept, text, reaches

    def claimed_resources(self):
        return [(self.interface, [self.joint.name])]


class PidCommandController(CommandController):
    def _init_extra(self):
        self.pid = self._pid()
        self.state_pub = self._pub(self.topic('state'), JointControllerState, 1)
        self.loop_count = 0
        self.state = JointControllerState()
        # The message is filled only when somebody listens (publishing it to nobody is a no-op anyway).
        connections = getattr(self.state_pub, 'get_num_connections', None)
        self._state_wanted = (lambda: connections() > 0) if connections is not None else (lambda: True)

    def _publish_state(self, time, period, set_point, process_value, process_value_dot, error, command):
        """Fills and publishes the state message (ros_controllers' JointControllerState). The caller's
        update counts its updates in `loop_count` and calls this at the first and every
        STATE_PUBLISH_EVERY-th after it while `_state_wanted()`: inline, as a call per update per
        controller is measurable in the world's step."""
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
