"""Helpers shared by the rostest nodes in this folder (not a test node itself)."""
import math
import statistics
import time

import rospy


def wait_for(condition, what, timeout=90.0, period=0.02):
    """condition()'s first truthy value; AssertionError naming `what` after `timeout` wall seconds.
    Waits are bounded in wall time (the machine may be slow); what the tests judge is in sim time."""
    deadline = time.time() + timeout
    while time.time() < deadline and not rospy.is_shutdown():
        value = condition()
        if value:
            return value
        time.sleep(period)
    raise AssertionError('timed out after %.0f s waiting for %s' % (timeout, what))


def yaw_of(q):
    """Yaw of a geometry_msgs/Quaternion."""
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def theil_sen_period(stamps):
    """The period of a stream from its stamps: the median over all pairs i < j of (stamp_j - stamp_i) / (j - i),
    Theil and Sen's slope of stamp against message count."""
    n = len(stamps)
    return statistics.median((stamps[j] - stamps[i]) / (j - i) for i in range(n) for j in range(i + 1, n))


class Latest:
    """The latest message of a topic, and how many came."""

    def __init__(self, topic, cls):
        self.msg = None
        self.count = 0
        self.sub = rospy.Subscriber(topic, cls, self._on, queue_size=1, buff_size=2 ** 24)

    def _on(self, msg):
        self.msg = msg
        self.count += 1

    def after(self, sim_time, what, timeout=90.0):
        """The first message stamped at or after sim_time."""
        return wait_for(lambda: self.msg if self.msg is not None and self.msg.header.stamp.to_sec() >= sim_time
                        else None, what, timeout, period=0.01)
