"""position_controllers: JointPositionController (forward)."""
from racebot_sim_bridge.ros_control.hardware_interface import POSITION
from racebot_sim_bridge.ros_control.controller_interface import Setpoint
from racebot_sim_bridge.ros_controllers.forward_command_controller import (ForwardCommandController,
                                                                           ForwardJointGroupCommandController)


class PositionForwardController(ForwardCommandController):
    type_name = 'position_controllers/JointPositionController'
    interface = POSITION
    setpoint = Setpoint.POSITION


class JointGroupPositionController(ForwardJointGroupCommandController):
    type_name = 'position_controllers/JointGroupPositionController'
    interface = POSITION

TYPES = (JointGroupPositionController, PositionForwardController,)
