#!/usr/bin/env python3
"""The camera and hector plugins of issue 29 item 5 through what gazebo_ros would offer (camera_plugins.test).

The robot (tests/fixtures/camera_plugins/robot.urdf) stands level at the origin of empty_world. In order: the
triggered camera publishes nothing until std_msgs/Empty on /shot/image_trigger, then exactly one frame per
trigger; the Prosilica camera (trigger_mode polled) streams nothing and answers polled_camera/GetPolledImage
at /prosilica with the roi latched under the response namespace; the magnetometer reads hector's default field
(inclination 60 deg) at yaw 0 and the barometer the link's height plus the elevation; the world server subscribes
to the video and projector topics. Waits are bounded in wall time, stamps are sim time.
"""
import functools
import math
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Vector3Stamped
from hector_uav_msgs.msg import Altimeter
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image
from std_msgs.msg import Empty

import integration_common  # next to this file
from integration_common import Latest
from racebot_sim_bridge.gazebo_plugins.polled_camera_types import get_polled_image

WALL_TIMEOUT = 60.0
wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.01)


class Frames:
    """Every message of a topic (a queue deep enough for a burst of triggered frames)."""

    def __init__(self, topic):
        self.messages = []
        self.sub = rospy.Subscriber(topic, Image, self.messages.append, queue_size=20, buff_size=2 ** 24)


class CameraPluginsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('camera_plugins_test')
        cls.clock = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        rospy.wait_for_service('/prosilica', timeout=WALL_TIMEOUT)  # the robot is spawned

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    def wait_sim(self, seconds):
        start = wait_for(lambda: self.clock, '/clock')
        wait_for(lambda: self.clock >= start + seconds, '%g s of sim time' % seconds)

    def test_1_triggered_camera_one_frame_per_trigger(self):
        frames = Frames('/shot/image_raw')
        trigger = rospy.Publisher('/shot/image_trigger', Empty, queue_size=5)
        wait_for(lambda: frames.sub.get_num_connections() and trigger.get_num_connections(), 'the connections')
        self.wait_sim(1.5)  # the sensor's update_rate is 2 Hz: an untriggered camera would have published
        self.assertEqual(frames.messages, [])
        trigger.publish(Empty())
        wait_for(lambda: frames.messages, 'the triggered frame')
        self.wait_sim(1.0)
        self.assertEqual(len(frames.messages), 1)
        self.assertEqual((frames.messages[0].width, frames.messages[0].header.frame_id), (64, 'base_link'))
        # one trigger at a time: upstream subscribes to the trigger with a queue of 1, so two Empty messages that
        # reach the subscriber in one read (back to back, under load) are one trigger, in Gazebo as here
        for count in (2, 3):
            trigger.publish(Empty())
            wait_for(lambda: len(frames.messages) >= count, 'frame %d' % count)
        self.wait_sim(1.0)
        self.assertEqual(len(frames.messages), 3)

    def test_2_prosilica_polled(self):
        streamed = Frames('/prosilica/image_raw')
        wait_for(lambda: streamed.sub.get_num_connections(), 'the connection')
        self.wait_sim(0.5)
        self.assertEqual(streamed.messages, [])  # polled: nothing streamed at the sensor's 10 Hz
        srv = get_polled_image()
        req = srv._request_class(response_namespace='poll')
        req.roi.x_offset, req.roi.y_offset, req.roi.width, req.roi.height = 8, 4, 32, 24
        res = rospy.ServiceProxy('/prosilica', srv)(req)
        self.assertTrue(res.success, res.status_message)
        crop = Latest('/prosilica/poll/image_raw', Image).after(res.stamp.to_sec(), 'the latched roi', WALL_TIMEOUT)
        self.assertEqual((crop.width, crop.height, crop.header.stamp), (32, 24, res.stamp))
        req.binning_x = 2
        refused = rospy.ServiceProxy('/prosilica', srv)(req)
        self.assertEqual((refused.success, refused.status_message),
                         (False, 'Gazebo Prosilica plugin does not support binning'))

    def test_3_magnetometer_and_barometer(self):
        field = Latest('/magnetic', Vector3Stamped).after(self.clock, 'a magnetic field', WALL_TIMEOUT)
        self.assertEqual(field.header.frame_id, 'base_link')
        v = field.vector
        for got, want in zip((v.x, v.y, v.z), (0.5, 0.0, -math.sqrt(3) / 2)):  # hector's defaults, yaw 0
            self.assertAlmostEqual(got, want, delta=1e-3)
        alt = Latest('/altimeter', Altimeter).after(self.clock, 'an altimeter reading', WALL_TIMEOUT)
        self.assertAlmostEqual(alt.altitude, 100.0, delta=0.01)  # base_link on the ground + elevation 100
        self.assertAlmostEqual(alt.pressure, 1013.25 * (1 - alt.altitude / 44330.0) ** 5.263157, places=2)

    def test_4_video_and_projector_topics_are_subscribed_by_the_world_server(self):
        master = rosgraph.Master('/camera_plugins_test')
        _, subscribers, _ = master.getSystemState()
        subscribed = {topic: nodes for topic, nodes in subscribers}
        for topic in ('/screen/video', '/lamp/projector', '/lamp/texture', '/shot/image_trigger'):
            self.assertIn('/gazebo', subscribed.get(topic, []), topic)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'camera_plugins', CameraPluginsTest)
