"""velocity_controllers: JointVelocityController (forward) and JointPositionController (PID on
position, a velocity out)."""
from racebot_sim_bridge.ros_control.hardware_interface import VELOCITY
from racebot_sim_bridge.ros_controllers.effort_controllers import JointPositionController
from racebot_sim_bridge.ros_control.controller_interface import Setpoint
from racebot_sim_bridge.ros_controllers.forward_command_controller import (ForwardCommandController,
                                                                           ForwardJointGroupCommandController)


class VelocityForwardController(ForwardCommandController):
    type_name = 'velocity_controllers/JointVelocityController'
    interface = VELOCITY
    setpoint = Setpoint.VELOCITY


class JointGroupVelocityController(ForwardJointGroupCommandController):
    type_name = 'velocity_controllers/JointGroupVelocityController'
    interface = VELOCITY


class VelocityJointPositionController(JointPositionController):
    """velocity_controllers/JointPositionController: PID on position, output is a velocity."""
    type_name = 'velocity_controllers/JointPositionController'
    interface = VELOCITY


TYPES = (JointGroupVelocityController, VelocityForwardController, VelocityJointPositionController)
