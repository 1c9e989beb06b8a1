"""position_controllers: JointPositionController (forward)."""
from ..hardware import POSITION
from .forward_command import ForwardCommandController


class PositionForwardController(ForwardCommandController):
    type_name = 'position_controllers/JointPositionController'
    interface = POSITION
    setpoint = 'position'


TYPES = (PositionForwardController,)
