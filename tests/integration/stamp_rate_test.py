#!/usr/bin/env python3
"""A topic's publishing rate in sim time, read from its messages' header stamps: rostest's hztest with the
clock taken from the message instead of from the moment it arrives.

hztest stamps each message with rospy.get_rostime() in its callback, so under load (three rostests on two
cores) a backlog of messages handled at one /clock reading shortens the measured span: it once read 52.002 Hz
for /racebot/joint_states, which publishes at exactly 50 Hz of sim time. The stamps are what the publisher
promises (joint_state_controller's publish_rate, a sensor's update_rate), whatever the subscriber's load.

Params (hztest's names): ~topic, ~hz, ~hzerror, ~test_duration (sim seconds), ~wait_time (wall seconds for
the first message). Checks, over the stamps received in test_duration:
- stamps strictly increase (a republished or reordered message fails);
- the rate, the Theil-Sen slope of stamp against message count (theil_sen_period), is within hz +- hzerror. A lost
  message lowers it by its share of the count. Jitter does not move it: gazebo_odometry stamps each message when a
  link_states arrives and catches up on the ticks a stall made it miss (SimTimeTicks), so its intervals spread from
  1 to 98 ms under load with the count exact. The median interval of such a stream read 18.9 Hz for 20 (its long
  intervals outnumber the short ones that pay for them), and the average over a window that opens on a catch-up
  burst 21.8 Hz; the median of the slopes over all pairs, where the far pairs are exact, read 19.98 to 20.08 Hz on
  both (measured beside bench_quick and compiled_plugins, and with SimTimeTicks fed stalls of up to 0.8 s).
"""
import statistics
import threading
import time
import unittest

import rospy
import rostest
import rostopic

from integration_common import theil_sen_period, wait_for  # next to this file

MIN_INTERVALS = 10  # fewer than this in test_duration is no measurement


class StampRateTest(unittest.TestCase):

    def test_rate_from_stamps(self):
        topic = rospy.get_param('~topic')
        hz, hzerror = float(rospy.get_param('~hz')), float(rospy.get_param('~hzerror'))
        duration, wait = float(rospy.get_param('~test_duration', 5.0)), float(rospy.get_param('~wait_time', 20.0))
        self.assertGreater(hz - hzerror, 0.0, '~hz must exceed ~hzerror')

        deadline = time.time() + wait  # for the topic and its first message together
        cls = wait_for(lambda: rostopic.get_topic_class(topic)[0], '%s to be advertised' % topic, wait, period=0.1)
        self.assertIn('header', cls.__slots__, '%s has no header to take the stamps from' % topic)

        stamps, lock = [], threading.Lock()

        def on_msg(msg):
            with lock:
                stamps.append(msg.header.stamp.to_sec())
        sub = rospy.Subscriber(topic, cls, on_msg, queue_size=10000)
        wait_for(lambda: stamps, 'a message on %s' % topic, max(0.0, deadline - time.time()), period=0.05)
        end = rospy.get_time() + duration
        # a stalled simulator fails, it does not hang
        wait_for(lambda: rospy.get_time() >= end, '%.1f s of sim time' % duration, wait + 10 * duration, period=0.05)
        sub.unregister()
        with lock:
            got = list(stamps)

        intervals = [b - a for a, b in zip(got, got[1:])]
        self.assertGreaterEqual(len(intervals), MIN_INTERVALS, '%d messages on %s in %.1f s of sim time'
                                % (len(got), topic, duration))
        bad = [(a, b) for a, b in zip(got, got[1:]) if b <= a]
        self.assertFalse(bad, '%s stamps do not increase: %r' % (topic, bad[:5]))
        period = theil_sen_period(got)
        deciles = statistics.quantiles(intervals, n=10)
        self.assertAlmostEqual(1.0 / period, hz, delta=hzerror, msg='%s: %.3f Hz of sim time (the median slope of '
                               'stamp over message count, %.4f s), expected %.1f +- %.1f Hz; %d messages stamped over '
                               '%.3f s, intervals 10th/90th percentile %.4f/%.4f s, shortest %.4f s, longest %.4f s'
                               % (topic, 1.0 / period, period, hz, hzerror, len(got), got[-1] - got[0],
                                  deciles[0], deciles[-1], min(intervals), max(intervals)))


if __name__ == '__main__':
    rospy.init_node('stamp_rate_test', anonymous=True)
    rostest.rosrun('racebot_tests', 'stamp_rate_test', StampRateTest)
