"""forward_command_controller: the command goes to the joint as it is (the base of
effort_controllers/JointEffortController, velocity_controllers/JointVelocityController and
position_controllers/JointPositionController), and to a group of joints (the base of the
JointGroup{Effort,Velocity,Position}Controllers)."""
import math

from std_msgs.msg import Float64MultiArray

from racebot_sim_bridge.ros_control.hardware_interface import POSITION
from racebot_sim_bridge.ros_control.controller_interface import CommandController, Controller, ControllerInitError


class ForwardCommandController(CommandController):
    """ForwardCommandController: the command goes to the joint as it is."""

    def starting(self, time):
        self.command = self.joint.position if self.interface == POSITION else 0.0

    def update(self, time, period):
        cmd = self.command
        self.joint.command = cmd
        if self.observer is not None:
            self.observer.command_applied(self, cmd)


class ForwardJointGroupCommandController(Controller):
    """ForwardJointGroupCommandController (JointGroup{Position,Velocity,Effort}Controller): `joints`, a
    std_msgs/Float64MultiArray on `command` with one value per joint, in the order of `joints`; a command
    of another size is refused with upstream's error. Starts with zeros (velocity, effort) or the joints'
    positions (position, whose commands are clamped to the URDF limits as JointGroupPositionController's
    enforceJointLimits does)."""

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        names = self.params.get('joints')
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise ControllerInitError("Failed to getParam 'joints' (namespace: %s): set '%s/joints' to a list of the "
                                      "robot's joints (%s)" % (self.param_ns, self.param_ns, ', '.join(self.hw.names)))
        if not names:
            raise ControllerInitError('List of joint names is empty (namespace: %s): list the joints in %s/joints'
                                      % (self.param_ns, self.param_ns))
        self.joints = [self._handle(n) for n in names]
        self.commands = (0.0,) * len(self.joints)
        self._sub(self.topic('command'), Float64MultiArray, self._on_command)

    def _on_command(self, msg):
        values = tuple(msg.data)
        if len(values) != len(self.joints):
            self.io.warn_throttle(self.param_ns, 5.0, '%s: Dimension of command (%d) does not match number of joints '
                                  '(%d)! Not executing! Publish one value per joint of %s/joints, in that order.'
                                  % (self.param_ns, len(values), len(self.joints), self.param_ns))
            return
        if not all(math.isfinite(v) for v in values):
            self.io.warn_throttle(self.param_ns, 5.0, '%s: ignored a command with a non-finite value (%r); the last '
                                  'command stays in force. Publish finite numbers.' % (self.param_ns, list(values)))
            return
        self.commands = values  # one tuple assignment: the update reads a whole command, never half of one

    def starting(self, time):
        if self.interface == POSITION:
            self.commands = tuple(j.position for j in self.joints)
        else:
            self.commands = (0.0,) * len(self.joints)

    def update(self, time, period):
        for joint, cmd in zip(self.joints, self.commands):
            if self.interface == POSITION:
                cmd = joint.clamped_position(cmd)
            joint.command = cmd

    def claimed_resources(self):
        return [(self.interface, sorted(j.name for j in self.joints))]

