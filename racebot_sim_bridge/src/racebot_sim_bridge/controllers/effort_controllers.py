"""effort_controllers: JointEffortController (forward), JointVelocityController and
JointPositionController (PID on the error, effort out)."""
import math  # noqa: F401

from ..hardware import EFFORT, shortest_angular_distance
from .base import STATE_PUBLISH_EVERY, PidCommandController, shortest_angular_distance_with_limits
from .forward_command import ForwardCommandController, ForwardJointGroupCommandController


class EffortForwardController(ForwardCommandController):
    type_name = 'effort_controllers/JointEffortController'
    interface = EFFORT
    setpoint = 'effort'


class JointVelocityController(PidCommandController):
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
        n = self.loop_count
        self.loop_count = n + 1
        if n % STATE_PUBLISH_EVERY == 0 and self._state_wanted():
            self._publish_state(time, period, cmd, self.joint.velocity, 0.0, error, effort)
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


class JointPositionController(PidCommandController):
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
        j = self.joint
        target = min(max(cmd, j.lower), j.upper) if j.has_position_limits else cmd  # clamp(), inline
        error = self.position_error(target)
        out = self.pid.compute(error, period)
        j.command = out
        n = self.loop_count
        self.loop_count = n + 1
        if n % STATE_PUBLISH_EVERY == 0 and self._state_wanted():
            self._publish_state(time, period, target, j.position, j.velocity, error, out)
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


class JointGroupEffortController(ForwardJointGroupCommandController):
    type_name = 'effort_controllers/JointGroupEffortController'
    interface = EFFORT


TYPES = (JointGroupEffortController, EffortForwardController, JointVelocityController, JointPositionController)
