"""A camera frame that fails to publish is logged as an error, except once ROS is shutting down: rospy closes the
topics at shutdown while a frame may still be on its way ("publish() to a closed topic"), and Gazebo's publishers
drop such a frame silently. soak_short read that ERROR as a defect of the world server. No master."""
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor

from fakes import FakeRospy


class Manager:
    def __init__(self, down):
        self.rospy = FakeRospy()
        self.rospy.is_shutdown = lambda: down


def camera(down):
    sensor = CameraSensor.__new__(CameraSensor)  # only its frame-failure path: no world, no worker
    sensor.manager = Manager(down)
    return sensor


def test_a_frame_that_fails_while_ros_runs_is_an_error():
    sensor = camera(down=False)
    sensor._frame_failed('camera c: ROSException: boom')
    assert sensor.manager.rospy.logs == [('error', 'camera c: ROSException: boom')]


def test_a_frame_that_fails_once_ros_is_shutting_down_is_dropped_silently():
    sensor = camera(down=True)
    sensor._frame_failed('camera c: ROSException: publish() to a closed topic')
    assert sensor.manager.rospy.logs == []
