"""The ROS side the corpus's checks share (checks.py): bounded waits in sim time, one message, a service, a
constant command, the newest message of a topic, a model's ground-truth pose, and a check's verdict (CheckFailed).
Waits are bounded in wall time, so a world whose /clock stops ends a check with a reason instead of hanging."""
import math
import threading
import time

import rospy
from roslib.message import get_message_class

WALL_MARGIN_S = 60.0     # sim-time waits may take this much wall time beyond their length (RTF < 1)
MESSAGE_TIMEOUT_S = 20.0


class CheckFailed(Exception):
    """A check's verdict: the message is its first reason; `numbers`, what was measured all the same."""

    def __init__(self, reason, numbers=''):
        super().__init__(reason)
        self.numbers = numbers


def sim_sleep(seconds):
    """Sleeps `seconds` of sim time; fails when the clock does not get there in wall time."""
    end = rospy.get_rostime() + rospy.Duration(seconds)
    deadline = time.time() + seconds * 4 + WALL_MARGIN_S
    while rospy.get_rostime() < end:
        if time.time() > deadline or rospy.is_shutdown():
            raise CheckFailed('sim time stalled: %.1f s of sim time did not pass in %.0f s' % (
                seconds, seconds * 4 + WALL_MARGIN_S))
        time.sleep(0.02)


def message(topic, type_name, timeout=MESSAGE_TIMEOUT_S):
    cls = get_message_class(type_name)
    if cls is None:
        raise CheckFailed('message type %s unknown here' % type_name)
    try:
        return rospy.wait_for_message(topic, cls, timeout=timeout)
    except rospy.ROSException:
        raise CheckFailed('no %s on %s in %.0f s' % (type_name, topic, timeout))


def service(name, srv_type, timeout=30.0):
    try:
        rospy.wait_for_service(name, timeout=timeout)
    except rospy.ROSException:
        raise CheckFailed('service %s not offered in %.0f s' % (name, timeout))
    return rospy.ServiceProxy(name, srv_type)


def yaw_of(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class Commander:
    """Publishes one command at 20 Hz (wall) until stopped, then a zero command."""

    def __init__(self, check):
        kind = check.get('msg', 'twist')
        if kind == 'ackermann':
            from ackermann_msgs.msg import AckermannDriveStamped
            self.pub = rospy.Publisher(check['cmd_topic'], AckermannDriveStamped, queue_size=1)
            self.msg, self.zero = AckermannDriveStamped(), AckermannDriveStamped()
            self.msg.drive.speed = check.get('speed', 0.0)
            self.msg.drive.steering_angle = check.get('steer', 0.0)
            self.zero.drive.steering_angle = check.get('steer', 0.0)
        else:
            from geometry_msgs.msg import Twist
            self.pub = rospy.Publisher(check['cmd_topic'], Twist, queue_size=1)
            self.msg, self.zero = Twist(), Twist()
            self.msg.linear.x, self.msg.linear.y = check.get('vx', 0.0), check.get('vy', 0.0)
            self.msg.linear.z = check.get('vz', 0.0)
            self.msg.angular.z = check.get('wz', 0.0)
        self.running = True
        self.thread = threading.Thread(target=self._loop, daemon=True)
        self.thread.start()

    def _loop(self):
        while self.running and not rospy.is_shutdown():
            if hasattr(self.msg, 'header'):
                self.msg.header.stamp = rospy.get_rostime()
            self.pub.publish(self.msg)
            time.sleep(0.05)

    def hold(self):
        """From now on the zero command, still at 20 Hz (a robot that stops without commands must not)."""
        self.msg = self.zero

    def stop(self):
        self.running = False
        self.thread.join()
        for _ in range(3):
            self.pub.publish(self.zero)
            time.sleep(0.05)


class Latest:
    """The newest message of a topic."""

    def __init__(self, topic, type_name):
        self.msg = None
        self.sub = rospy.Subscriber(topic, get_message_class(type_name), self._cb, queue_size=1)

    def _cb(self, msg):
        self.msg = msg


def model_pose(getter, model):
    reply = getter(model_name=model, relative_entity_name='')
    if not reply.success:
        raise CheckFailed('get_model_state(%s): %s' % (model, reply.status_message))
    p = reply.pose
    stamp = reply.header.stamp.to_sec() or rospy.get_rostime().to_sec()
    return p.position.x, p.position.y, yaw_of(p.orientation), stamp
