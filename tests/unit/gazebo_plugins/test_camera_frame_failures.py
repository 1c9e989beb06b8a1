"""A camera frame that fails to publish is logged as an error, except once its topics are going: the world server's
shutdown closes the sensors (unregistering their publishers) before rospy's, and rospy's closes the topics, while a
frame may still be on its way ("publish() to an unregistered() handle", "publish() to a closed topic"). Gazebo's
publishers drop such a frame silently; soak_short read each of those ERRORs as a defect. No master."""
import rospy
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor

from fakes import FakeRospy


class Manager:
    def __init__(self, down):
        self.rospy = FakeRospy()
        self.rospy.is_shutdown = lambda: down


def camera(down, closed=False):
    sensor = CameraSensor.__new__(CameraSensor)  # only its frame-failure path: no world, no worker
    sensor.manager = Manager(down)
    sensor.closed = closed
    return sensor


def test_a_frame_that_fails_while_ros_runs_is_an_error():
    sensor = camera(down=False)
    sensor._frame_failed('camera c: ROSException: boom')
    assert sensor.manager.rospy.logs == [('error', 'camera c: ROSException: boom')]


def test_a_frame_that_fails_once_ros_is_shutting_down_is_dropped_silently():
    sensor = camera(down=True)
    sensor._frame_failed('camera c: ROSException: publish() to a closed topic')
    assert sensor.manager.rospy.logs == []


def test_a_frame_on_its_way_when_the_sensor_closes_is_dropped_silently():
    """The race of soak_short's run: the publishing thread took the camera's publishers, then the world server's
    shutdown closed the sensor (rospy still up) and the frame's publish met an unregistered handle."""
    from sensor_msgs.msg import Image
    taken = rospy.Publisher('/racebot_unit/image', Image, queue_size=1)  # what publish_frame holds
    sensor = camera(down=False, closed=True)  # Sensor.close() sets closed, then unregisters
    taken.unregister()
    try:
        taken.publish(Image())
    except rospy.ROSException as err:
        sensor._frame_failed('camera c: ROSException: %s' % err)
    else:
        raise AssertionError('an unregistered publisher published')
    assert sensor.manager.rospy.logs == []


def test_close_marks_the_sensor_closed_before_its_topics_go():
    from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor
    seen = []

    class Publisher:
        def __init__(self, sensor):
            self.sensor = sensor

        def unregister(self):
            seen.append(self.sensor.closed)

    sensor = Sensor.__new__(Sensor)
    sensor.closed = False
    sensor.publishers = {'image': Publisher(sensor), 'info': Publisher(sensor)}
    sensor.close()
    assert seen == [True, True] and sensor.publishers == {}
