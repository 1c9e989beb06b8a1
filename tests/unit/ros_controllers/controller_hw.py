"""A RobotHW of a URDF, its joints read once at time 0."""
from racebot_sim_bridge.gazebo_ros_control.robot_hw_sim import hardware_joints
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.hardware_interface import RobotHW


def make_hw(xml):
    model = urdf_reader.parse_urdf(xml)
    hw = RobotHW(model, hardware_joints(model))
    for h in hw.handles.values():
        h.read(0.0, 0.0)
    return hw
