"""The odometry nodes' publishing while rospy shuts down (no master: the publisher is a stand-in)."""
import pytest
import rospy
from nav_msgs.msg import Odometry

from racebot_gazebo import odometry_nodes


class ClosedTopic:
    def publish(self, msg):
        raise rospy.ROSException('publish() to a closed topic')


def test_a_closed_topic_while_rospy_shuts_down_is_no_error(monkeypatch):
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: True)
    odometry_nodes.publish_unless_closing(ClosedTopic(), None, Odometry())


def test_a_closed_topic_otherwise_is_raised(monkeypatch):
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: False)
    monkeypatch.setattr(rospy.core, 'is_shutdown_requested', lambda: False)
    with pytest.raises(rospy.ROSException, match='closed topic'):
        odometry_nodes.publish_unless_closing(ClosedTopic(), None, Odometry())


def test_the_transform_goes_with_the_message():
    sent = []

    class Topic:
        def publish(self, msg):
            sent.append(('odom', msg.header.frame_id))

    class Broadcaster:
        def sendTransform(self, t):
            sent.append(('tf', t.header.frame_id, t.child_frame_id))

    odom = Odometry()
    odom.header.frame_id, odom.child_frame_id = 'odom', 'base_footprint'
    odometry_nodes.publish_unless_closing(Topic(), Broadcaster(), odom)
    assert sent == [('odom', 'odom'), ('tf', 'odom', 'base_footprint')]
