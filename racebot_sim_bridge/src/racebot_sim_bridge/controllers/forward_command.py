"""forward_command_controller: the command goes to the joint as it is (the base of
effort_controllers/JointEffortController, velocity_controllers/JointVelocityController and
position_controllers/JointPositionController)."""
from ..hardware import POSITION
from .base import CommandController


class ForwardCommandController(CommandController):
    """ForwardCommandController: the command goes to the joint as it is."""

    def starting(self, time):
        self.command = self.joint.position if self.interface == POSITION else 0.0

    def update(self, time, period):
        cmd = self.command
        self.joint.command = cmd
        if self.observer is not None:
            self.observer.command_applied(self, cmd)
