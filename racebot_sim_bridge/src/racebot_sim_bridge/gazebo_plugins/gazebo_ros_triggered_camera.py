"""libgazebo_ros_triggered_camera.so (gazebo_plugins noetic-devel): a gazebo_ros_camera that takes a frame only when
triggered.

Upstream's GazeboRosTriggeredCamera keeps the camera disabled (update rate DBL_MIN); each std_msgs/Empty on
<triggerTopicName> (default image_trigger, in the camera's namespace: <robotNamespace>/<cameraName>/image_trigger)
adds one to a counter; before the next render the camera is enabled (update rate 0: the next render, whatever the
sensor's <update_rate>), and each frame it renders publishes image and camera_info when anybody listens, disables
the camera again and takes one off the counter: n triggers, n frames, one per render, none before. Its updateRate
does not throttle it. Here a trigger wakes the sensor for the next physics step (SensorManager.wake) and each step
while triggers are pending takes one frame with gazebo_ros_camera.py's rendering (worker or physics thread),
stamped with that step's sim time. A trigger nobody listens to is used up without a frame, as upstream renders one
for nobody; a frame the worker cannot take yet (starting, busy) keeps its trigger for the next step. Topics,
camera_info and set_camera_info are gazebo_ros_camera's.
"""
import math
import threading

from std_msgs.msg import Empty

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind


class Shutter:
    """The trigger counters of one Gazebo camera sensor: one per camera (a multicamera's left and right share the
    sensor, so a trigger of either renders both, and each frame takes one off its own camera's counter, never
    below 0: GazeboRosTriggeredCamera's `triggered = max(triggered - 1, 0)`). Triggers come on rospy's threads,
    frames on the physics thread: under a lock."""

    def __init__(self):
        self._lock = threading.Lock()
        self._counts = {}
        self._fired_at = None  # sim time of the last render: the other cameras of the sensor take theirs then too

    def add(self, camera):
        with self._lock:
            self._counts.setdefault(camera, 0)

    def trigger(self, camera):
        with self._lock:
            self._counts[camera] += 1

    def pending(self):
        with self._lock:
            return any(self._counts.values())

    def due(self, time):
        """True when a camera of this sensor takes a frame at sim `time`: a trigger is pending, or another
        camera of the sensor took one at this time."""
        with self._lock:
            return self._fired_at == time or any(self._counts.values())

    def taken(self, camera, time):
        with self._lock:
            self._counts[camera] = max(self._counts[camera] - 1, 0)
            self._fired_at = time


class TriggeredCameraSensor(CameraSensor, libraries=('libgazebo_ros_triggered_camera.so',),
                            sensor_types=('camera',), kind=SensorKind.CAMERA):
    """gazebo_ros_triggered_camera: image + camera_info, one frame per std_msgs/Empty on image_trigger."""

    @classmethod
    def create(cls, manager, robot, spec, config):
        sensor = cls(manager, robot, spec, config)
        sensor.use_shutter(Shutter())
        return [sensor]

    def use_shutter(self, shutter):
        self.shutter = shutter
        shutter.add(self)
        self.trigger_topic = self.config.params['trigger_topic']
        self.trigger_sub = self.manager.rospy.Subscriber(self.trigger_topic, Empty, self.on_trigger, queue_size=1)

    def on_trigger(self, _msg):
        self.shutter.trigger(self)
        self.manager.wake()  # after the count: the step that asks our wake time again sees it

    def wake_time(self):
        """Every step while a trigger is pending; else never (until a trigger wakes the manager)."""
        return -math.inf if self.shutter.pending() else math.inf

    def step(self, time):
        if not self.shutter.due(time):
            return
        stamp = ros_time(self.manager.rospy.Time, time)
        if self.listened('image'):
            if not self.capture(time, stamp, {'image'}, want_depth=False):
                return  # the trigger stays for the next step
        elif self.listened('info'):  # camera_info alone needs no render
            self.publishers['info'].publish(self.info(stamp))
        self.shutter.taken(self, time)

    def close(self):
        sub, self.trigger_sub = getattr(self, 'trigger_sub', None), None
        if sub is not None:
            sub.unregister()
        super().close()
