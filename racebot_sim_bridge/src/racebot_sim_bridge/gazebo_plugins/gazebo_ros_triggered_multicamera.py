"""libgazebo_ros_triggered_multicamera.so (gazebo_plugins noetic-devel): a multicamera sensor whose cameras publish
as gazebo_ros_triggered_camera under <cameraName>/left and <cameraName>/right (read as gazebo_ros_multicamera.py reads
them: which side, the right camera's baseline), each with its own trigger topic
(<cameraName>/left/image_trigger, .../right/image_trigger).

Upstream's cameras share one parent sensor: a trigger of either enables it, so every render publishes both
cameras' frames and takes one off each camera's counter (never below 0). One trigger on either side: one stereo
pair; a trigger on each side at once: still one pair. racebot does the same (gazebo_ros_triggered_camera.Shutter).
"""
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_multicamera import MultiCameraSensor
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_triggered_camera import Shutter, TriggeredCameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind


class TriggeredMultiCameraSensor(TriggeredCameraSensor, MultiCameraSensor,
                                 libraries=('libgazebo_ros_triggered_multicamera.so',),
                                 sensor_types=('multicamera',), kind=SensorKind.MULTICAMERA):
    """One camera of a triggered multicamera sensor: its own pose, topics and trigger, the sensor's Shutter. Loaded
    as a multicamera (MultiCameraSensor.load), run as a triggered camera."""

    @classmethod
    def create(cls, manager, robot, spec, config):
        """One sensor per side (config.params['parts'], as gazebo_ros_multicamera's), one Shutter for them."""
        shutter = Shutter()
        sensors = [cls(manager, robot, part_spec, part) for part_spec, part in config.params['parts']]
        for sensor in sensors:
            sensor.use_shutter(shutter)
        return sensors
