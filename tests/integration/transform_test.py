#!/usr/bin/env python3
"""Black-box test of the transform node, started alone (no simulator, wall time).

Publishes a series of distinct Twists on /cmd_vel (forward, reverse, standing still, beyond the
hinge limit, and two non-finite ones that must be skipped) and checks that each finite one gives
exactly one AckermannDriveStamped on /ackermann_cmd_mux/output, in order, with the fields of the
node's conversion mode (its ~convert_yaw_rate): the tutorial's pass-through of angular.z, or
atan(wheelbase * angular.z / linear.x) clamped, the previous angle kept at linear.x = 0. The
expected angles are computed here from the formula, independently of racebot_control.
"""

import math
import struct
import threading
import time
import unittest

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped
from geometry_msgs.msg import Twist

NODE = '/transform'
RATE_HZ = 50.0
# (linear.x, angular.z)
TWISTS = [(0.5, 0.0), (0.5, 0.4), (0.3, -0.2), (0.0, 0.5), (0.0, 0.0), (-0.5, 0.4), (-0.3, -0.1),
          (0.2, 3.0), (0.1, -5.0), (0.0, -1.0), (1.0, 0.25), (float('nan'), 0.1), (0.5, float('inf')),
          (0.8, 0.05), (-0.05, 2.0), (0.0, 0.0)]


def f32(x):
    """x as it comes out of a float32 message field."""
    return struct.unpack('f', struct.pack('f', x))[0]


class TransformTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.convert = bool(rospy.get_param(NODE + '/convert_yaw_rate', False))
        cls.wheelbase = float(rospy.get_param(NODE + '/wheelbase', 0.26))
        cls.limit = float(rospy.get_param(NODE + '/max_steering_angle', 0.6))
        cls.lock = threading.Lock()
        cls.received = []
        cls.sub = rospy.Subscriber('/ackermann_cmd_mux/output', AckermannDriveStamped, cls._on_command,
                                   queue_size=1000, tcp_nodelay=True)
        cls.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1000, tcp_nodelay=True)
        deadline = time.time() + 30.0
        while time.time() < deadline and not (cls.pub.get_num_connections() >= 1
                                              and cls.sub.get_num_connections() >= 1):
            time.sleep(0.05)
        time.sleep(0.5)

    @classmethod
    def _on_command(cls, msg):
        with cls.lock:
            cls.received.append(msg)

    def expected_steering(self):
        """The steering angle of each finite Twist of TWISTS, in order."""
        angles, last = [], 0.0
        for v, w in TWISTS:
            if not (math.isfinite(v) and math.isfinite(w)):
                continue
            if not self.convert:
                angle = w
            elif v == 0.0:
                angle = last
            else:
                angle = max(-self.limit, min(self.limit, math.atan(self.wheelbase * w / v)))
            angles.append(angle)
            last = angle
        return angles

    def test_each_twist_becomes_one_ackermann_command(self):
        self.assertGreaterEqual(self.pub.get_num_connections(), 1, 'transform does not subscribe to /cmd_vel')
        self.assertGreaterEqual(self.sub.get_num_connections(), 1, 'transform does not publish')
        rate = rospy.Rate(RATE_HZ)
        start = rospy.Time.now()
        for v, w in TWISTS:
            twist = Twist()
            twist.linear.x = v
            twist.angular.z = w
            twist.linear.y = 7.0  # ignored
            self.pub.publish(twist)
            rate.sleep()
        finite = [(v, w) for v, w in TWISTS if math.isfinite(v) and math.isfinite(w)]
        deadline = time.time() + 10.0
        while time.time() < deadline and len(self.received) < len(finite):
            time.sleep(0.01)
        time.sleep(0.5)  # anything extra (a forwarded non-finite Twist) would show up by now
        with self.lock:
            got = list(self.received)
        self.assertEqual(len(got), len(finite), 'expected one command per finite Twist')
        for i, (msg, (v, _w), angle) in enumerate(zip(got, finite, self.expected_steering())):
            where = 'command %d (linear.x %r)' % (i, v)
            self.assertEqual(msg.header.frame_id, 'base_link', where)
            self.assertGreaterEqual(msg.header.stamp, start, where)
            self.assertAlmostEqual(msg.drive.speed, f32(v), places=6, msg=where)
            self.assertAlmostEqual(msg.drive.steering_angle, f32(angle), places=6,
                                   msg='%s: steering %r, expected %r (convert_yaw_rate %s)'
                                   % (where, msg.drive.steering_angle, angle, self.convert))
            self.assertEqual((msg.drive.acceleration, msg.drive.jerk, msg.drive.steering_angle_velocity),
                             (1.0, 1.0, 1.0), where)
        if self.convert:  # the conversion is really on: a yaw rate of 3 rad/s is not sent as 3 rad
            self.assertTrue(all(abs(m.drive.steering_angle) <= self.limit + 1e-6 for m in got))


if __name__ == '__main__':
    rospy.init_node('transform_test')
    rostest.rosrun('racebot_tests', 'transform', TransformTest)
