"""effort_controllers: JointEffortController (forward), JointVelocityController and
JointPositionController (PID on the error, effort out)."""
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, position_error
from racebot_sim_bridge.ros_control.controller_interface import STATE_PUBLISH_EVERY, PidCommandController, Setpoint
from racebot_sim_bridge.ros_controllers.forward_command_controller import (ForwardCommandController,
                                                                           ForwardJointGroupCommandController)


class EffortForwardController(ForwardCommandController):
    type_name = 'effort_controllers/JointEffortController'
    interface = EFFORT
    setpoint = Setpoint.EFFORT


class JointGroupEffortController(ForwardJointGroupCommandController):
    type_name = 'effort_controllers/JointGroupEffortController'
    interface = EFFORT


class JointVelocityController(PidCommandController):
    """effort_controllers/JointVelocityController: effort = PID(command - velocity)."""
    type_name = 'effort_controllers/JointVelocityController'
    interface = EFFORT
    setpoint = Setpoint.VELOCITY

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
    setpoint = Setpoint.POSITION

    def clamp(self, position):
        return self.joint.clamped_position(position)

    def starting(self, time):
        self.command = self.clamp(self.joint.position)
        self.pid.reset()

    def update(self, time, period):
        cmd = self.command
        j = self.joint
        target = j.clamped_position(cmd)
        error = position_error(j, target)
        out = self.pid.compute(error, period)
        j.command = out
        n = self.loop_count
        self.loop_count = n + 1
        if n % STATE_PUBLISH_EVERY == 0 and self._state_wanted():
            self._publish_state(time, period, target, j.position, j.velocity, error, out)
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


TYPES = (JointGroupEffortController, EffortForwardController, JointVelocityController, JointPositionController)
