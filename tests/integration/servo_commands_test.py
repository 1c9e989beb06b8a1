#!/usr/bin/env python3
"""Black-box test of the servo_commands node, started alone (no simulator, wall time).

~check: `stream` publishes 200 distinct commands at 50 Hz on /ackermann_cmd_mux/output (plus two
non-finite ones, which must be skipped) and checks that every one reaches all six controller
command topics, in order, with the values of the node's steering mode; then that nothing more
comes (no timeout stop when ~command_timeout is 0). `timeout` checks that, with the node's
~command_timeout > 0, one speed-0 command follows the last command after that long, only one, and
that driving resumes on the next command.
The expected values come from racebot_control.wheel_commands with the node's own parameters;
that module's geometry is checked by tests/unit/tutorial/test_servo_logic.py.
"""

import math
import struct
import threading
import time
import unittest

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped
from std_msgs.msg import Float64

from racebot_control.wheel_commands import CarGeometry, wheel_commands

NODE = '/servo_commands'
TOPICS = ['/racebot/%s/command' % name for name in (
    'left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
    'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
    'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller')]
N_COMMANDS = 200
RATE_HZ = 50.0


def f32(x):
    """x as it comes out of a float32 message field."""
    return struct.unpack('f', struct.pack('f', x))[0]


class Recorder:
    """Every Float64 on the six command topics, with its wall arrival time."""

    def __init__(self):
        self.lock = threading.Lock()
        self.received = {topic: [] for topic in TOPICS}
        self.subscribers = [rospy.Subscriber(topic, Float64, self._on_value, callback_args=topic,
                                             queue_size=1000, tcp_nodelay=True) for topic in TOPICS]

    def _on_value(self, msg, topic):
        with self.lock:
            self.received[topic].append((msg.data, time.time()))

    def counts(self):
        with self.lock:
            return [len(self.received[t]) for t in TOPICS]

    def values(self, topic):
        with self.lock:
            return [v for v, _ in self.received[topic]]

    def times(self, topic):
        with self.lock:
            return [t for _, t in self.received[topic]]

    def wait_for(self, count, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline and min(self.counts()) < count:
            time.sleep(0.01)
        return self.counts()


class ServoCommandsBase(unittest.TestCase):
    """Connections and helpers; the checks are in the two subclasses."""

    @classmethod
    def setUpClass(cls):
        cls.mode = rospy.get_param(NODE + '/steering_mode', 'parallel')
        cls.timeout = float(rospy.get_param(NODE + '/command_timeout', 0.0))
        cls.geometry = CarGeometry(**{name: rospy.get_param('%s/%s' % (NODE, name), default)
                                      for name, default in CarGeometry()._asdict().items()})
        cls.recorder = Recorder()
        cls.pub = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=1000,
                                  tcp_nodelay=True)
        deadline = time.time() + 30.0
        while time.time() < deadline and not (
                cls.pub.get_num_connections() >= 1
                and all(s.get_num_connections() >= 1 for s in cls.recorder.subscribers)):
            time.sleep(0.05)
        time.sleep(0.5)  # let the node's side of the connections settle too

    def setUp(self):
        self.assertGreaterEqual(self.pub.get_num_connections(), 1, 'servo_commands does not subscribe')
        for sub in self.recorder.subscribers:
            self.assertGreaterEqual(sub.get_num_connections(), 1, '%s has no publisher' % sub.name)

    def send(self, speed, steering_angle):
        msg = AckermannDriveStamped()
        msg.header.stamp = rospy.Time.now()
        msg.header.frame_id = 'base_link'
        msg.drive.speed = speed
        msg.drive.steering_angle = steering_angle
        self.pub.publish(msg)

    def expected(self, speed, steering_angle):
        return wheel_commands(f32(speed), f32(steering_angle), self.mode, self.geometry)

    def assert_values(self, topic, got, want):
        self.assertEqual(len(got), len(want), '%s: %d values, expected %d' % (topic, len(got), len(want)))
        for i, (g, w) in enumerate(zip(got, want)):
            self.assertTrue(math.isfinite(g), '%s[%d] = %r' % (topic, i, g))
            self.assertAlmostEqual(g, w, places=9, msg='%s[%d]: got %r, expected %r (%s mode)'
                                   % (topic, i, g, w, self.mode))


class StreamTest(ServoCommandsBase):

    def test_every_command_arrives_in_order(self):
        self.assertEqual(self.timeout, 0.0, 'the stream check wants command_timeout 0')
        # Distinct speeds and angles; the angles go past the hinge limit at both ends.
        commands = [(-1.0 + 0.0101 * i, -0.7 + 0.007 * i) for i in range(N_COMMANDS)]
        rate = rospy.Rate(RATE_HZ)
        for i, (speed, angle) in enumerate(commands):
            if i in (50, 120):  # not finite: must be skipped, not forwarded
                self.send(float('nan'), 0.1)
                self.send(0.5, float('inf'))
            self.send(speed, angle)
            rate.sleep()
        counts = self.recorder.wait_for(N_COMMANDS, 10.0)
        self.assertEqual(counts, [N_COMMANDS] * 6, 'commands lost (%s mode)' % self.mode)
        want = [self.expected(s, a) for s, a in commands]
        for j, topic in enumerate(TOPICS):
            self.assert_values(topic, self.recorder.values(topic), [w[j] for w in want])
        if self.mode == 'ackermann':  # the mode really differs from parallel for a turn
            self.assertNotAlmostEqual(self.recorder.values(TOPICS[4])[10], self.recorder.values(TOPICS[5])[10])
        # no timeout configured: nothing follows the last command
        time.sleep(1.5)
        self.assertEqual(self.recorder.counts(), [N_COMMANDS] * 6, 'unexpected command after the last one')


class TimeoutTest(ServoCommandsBase):

    def test_stop_after_command_timeout(self):
        self.assertGreater(self.timeout, 0.0, 'the timeout check wants command_timeout > 0')
        commands = [(0.3 + 0.01 * i, 0.2 + 0.01 * i) for i in range(5)]
        rate = rospy.Rate(RATE_HZ)
        for speed, angle in commands:
            self.send(speed, angle)
            rate.sleep()
        last_sent = time.time() - 1.0 / RATE_HZ
        counts = self.recorder.wait_for(len(commands) + 1, self.timeout + 3.0)
        self.assertEqual(counts, [len(commands) + 1] * 6, 'no stop command after the timeout')
        last_angle = commands[-1][1]
        want = [self.expected(s, a) for s, a in commands] + [self.expected(0.0, last_angle)]
        for j, topic in enumerate(TOPICS):
            self.assert_values(topic, self.recorder.values(topic), [w[j] for w in want])
            if j < 4:
                self.assertEqual(self.recorder.values(topic)[-1], 0.0)
            waited = self.recorder.times(topic)[-1] - last_sent
            self.assertGreaterEqual(waited, self.timeout - 0.1,
                                    '%s: stop came too early (%.3f s)' % (topic, waited))
            self.assertLessEqual(waited, self.timeout + 1.0, '%s: stop came too late (%.3f s)' % (topic, waited))
        # one stop, not a stream of them
        time.sleep(self.timeout * 3)
        self.assertEqual(self.recorder.counts(), [len(commands) + 1] * 6, 'more than one stop command')
        # driving resumes with the next command, and stops again after the timeout
        self.send(0.4, -0.1)
        counts = self.recorder.wait_for(len(commands) + 3, self.timeout + 3.0)
        self.assertEqual(counts, [len(commands) + 3] * 6)
        want += [self.expected(0.4, -0.1), self.expected(0.0, -0.1)]
        for j, topic in enumerate(TOPICS):
            self.assert_values(topic, self.recorder.values(topic), [w[j] for w in want])


if __name__ == '__main__':
    rospy.init_node('servo_commands_test')
    CHECKS = {'stream': StreamTest, 'timeout': TimeoutTest}
    check = rospy.get_param('~check')
    rostest.rosrun('racebot_tests', 'servo_commands_' + check, CHECKS[check])
