"""velocity_controllers: JointVelocityController (forward) and JointPositionController (PID on
position, a velocity out)."""
from ..hardware import VELOCITY
from .effort_controllers import JointPositionController
from .forward_command import ForwardCommandController, ForwardJointGroupCommandController


class VelocityForwardController(ForwardCommandController):
    type_name = 'velocity_controllers/JointVelocityController'
    interface = VELOCITY
    setpoint = 'velocity'


class VelocityJointPositionController(JointPositionController):
    """velocity_controllers/JointPositionController: PID on position, output is a velocity."""
    type_name = 'velocity_controllers/JointPositionController'
    interface = VELOCITY



class JointGroupVelocityController(ForwardJointGroupCommandController):
    type_name = 'velocity_controllers/JointGroupVelocityController'
    interface = VELOCITY


TYPES = (JointGroupVelocityController, VelocityForwardController, VelocityJointPositionController)
