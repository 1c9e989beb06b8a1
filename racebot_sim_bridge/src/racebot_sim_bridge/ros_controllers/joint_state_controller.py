"""joint_state_controller/JointStateController."""
import math

from sensor_msgs.msg import JointState

from racebot_sim_bridge.ros_control.hardware_interface import STATE
from racebot_sim_bridge.ros_control.controller_interface import Controller, ControllerInitError


class JointStateController(Controller):
    type_name = 'joint_state_controller/JointStateController'
    interface = STATE

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        rate = self.params.get('publish_rate')
        if isinstance(rate, bool) or not isinstance(rate, (int, float)) or not math.isfinite(rate) or rate <= 0:
            raise ControllerInitError("Parameter 'publish_rate' not set or not a positive number (namespace: %s); "
                                      "e.g. publish_rate: 50" % self.param_ns)
        self.period = 1.0 / float(rate)
        names = self.params.get('joints') or self.hw.names
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise ControllerInitError("'%s/joints' must be a list of joint names, got %r" % (self.param_ns, names))
        self.handles = [self._handle(n, STATE) for n in names]
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

TYPES = (JointStateController,)
