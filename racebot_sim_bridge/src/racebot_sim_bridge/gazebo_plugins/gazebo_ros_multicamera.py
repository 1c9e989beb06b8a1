"""libgazebo_ros_multicamera.so (gazebo_plugins noetic-devel): a multicamera sensor whose cameras each publish as
a gazebo_ros_camera under <cameraName>/left or <cameraName>/right (../sensors/config.py reads which, and the
right camera's baseline).
"""
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind


class MultiCameraSensor(CameraSensor, libraries=('libgazebo_ros_multicamera.so',), sensor_types=('multicamera',),
                        kind=SensorKind.MULTICAMERA):
    """One camera of a multicamera sensor: a CameraSensor of its own, with its own pose and topics."""

    @classmethod
    def create(cls, manager, robot, spec, config):
        """One sensor per side: config.params['parts'] holds each camera's (SensorSpec, SensorConfig)."""
        return [cls(manager, robot, part_spec, part) for part_spec, part in config.params['parts']]
