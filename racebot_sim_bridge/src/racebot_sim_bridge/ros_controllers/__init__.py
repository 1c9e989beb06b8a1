"""The ros_controllers this simulator offers, with ros_control's parameters, topics and semantics.

A controller is built from its parameters (the dict under `<ns>/<name>` on the parameter server),
the robot's hardware (ros_control/hardware_interface.RobotHW) and an I/O object that makes publishers and
subscribers (ros_control/controller_io.RosIO for the real thing; tests pass their own). Construction is
ros_control's init(): it raises ControllerInitError (ros_control/controller_interface.py) with a message that
says what is wrong and what to do.

Types:
  joint_state_controller/JointStateController
  effort_controllers/JointEffortController, JointVelocityController, JointPositionController
  velocity_controllers/JointVelocityController, JointPositionController
  position_controllers/JointPositionController
  {position,velocity,effort}_controllers/JointTrajectoryController
  {position,effort}_controllers/GripperActionController
  mecanum_drive_controller/MecanumDriveController (ridgeback_control's, the Ridgeback's own)

One module per ros_controllers package; each lists its classes in TYPES, and CONTROLLER_TYPES
(type name -> class) is what the controller manager loads from (gazebo_ros_control's plugin gives it to the
manager, which imports no controller). Import a class from its own module. A new controller type is a class
with `type_name`, `interface` and ros_control's init (constructor) / starting / update / stopping,
added to its module's TYPES and to MODULES below (a worked example with its test:
docs/WRITE_A_PLUGIN_OR_CONTROLLER.md).
"""
from racebot_sim_bridge.ros_controllers import (ackermann_steering_controller as ackermann_steering,
                                                diff_drive_controller as diff_drive, effort_controllers,
                                                gripper_action_controller as gripper_action,
                                                joint_state_controller as joint_state,
                                                joint_trajectory_controller as joint_trajectory,
                                                mecanum_drive_controller as mecanum_drive, position_controllers,
                                                velocity_controllers)

MODULES = (joint_state, effort_controllers, velocity_controllers, position_controllers, diff_drive,
           ackermann_steering, joint_trajectory, gripper_action, mecanum_drive)
CONTROLLER_TYPES = {c.type_name: c for m in MODULES for c in getattr(m, 'TYPES', ())}
