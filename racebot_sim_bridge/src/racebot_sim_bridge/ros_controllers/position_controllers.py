"""position_controllers: JointPositionController (forward)."""
from racebot_sim_bridge.ros_control.hardware_interface import POSITION
from racebot_sim_bridge.ros_controllers.forward_command_controller import forward_controllers

PositionForwardController, JointGroupPositionController = forward_controllers(POSITION, __name__)

TYPES = (JointGroupPositionController, PositionForwardController,)
