"""position_controllers: JointPositionController (forward)."""
from ..hardware import POSITION
from .forward_command import ForwardCommandController, ForwardJointGroupCommandController


class PositionForwardController(ForwardCommandController):
    type_name = 'position_controllers/JointPositionController'
    interface = POSITION
    setpoint = 'position'



class JointGroupPositionController(ForwardJointGroupCommandController):
    type_name = 'position_controllers/JointGroupPositionController'
    interface = POSITION


TYPES = (JointGroupPositionController, PositionForwardController,)
