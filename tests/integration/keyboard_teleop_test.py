#!/usr/bin/env python3
"""keyboard_teleop under a virtual X server, driven by xdotool (no simulator: just a master).

The test starts its own Xvfb (a display number the server picks itself with -displayfd; -noreset so
that xset's state is not reset to defaults when the last client leaves) and runs
`rosrun racebot_gazebo keyboard_teleop.py` with that DISPLAY, then:
- holding W publishes speed 0.5 (config/keyboard_teleop.yaml) at about 10 Hz, W+A steers 0.34 left;
- releasing every key gives exactly one stop command, then silence;
- Q closes the window and the process exits 0; SIGINT and SIGTERM (roslaunch) also stop the car;
- the X session's key auto-repeat (`xset q`) stays on while the window runs and after any exit,
  SIGKILL included: the node never switches it off (the keys above are held with it on, so its
  release/press pairs are told from real releases);
- without a display the node prints one line and exits 0, without a traceback.
Times are wall times: the keyboard runs on the wall clock, and this test has no /clock.
"""
import os
import signal
import subprocess
import sys
import threading
import time
import unittest

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped

from keyboard_teleop_xvfb import auto_repeat, start_xvfb, stop_xvfb  # next to this file

PKG = 'racebot_tests'
TOPIC = '/ackermann_cmd_mux/output'
WINDOW_NAME = '^racebot keyboard teleop$'
SPEED, STEER = 0.5, 0.34  # racebot_gazebo/config/keyboard_teleop.yaml, loaded by the .test file
START_TIMEOUT = 60.0      # s (wall) for the window to appear on a busy 2-core machine
EXIT_TIMEOUT = 20.0       # s (wall) for the node to exit (roslaunch waits 15 s before SIGTERM)


class KeyboardTeleopTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.xvfb, cls.display = start_xvfb()
        cls.env = dict(os.environ, DISPLAY=cls.display)
        cls.lock = threading.Lock()
        cls.msgs = []  # (stamp s, speed, steering_angle)
        rospy.init_node('keyboard_teleop_test')
        cls.sub = rospy.Subscriber(TOPIC, AckermannDriveStamped, cls._on_msg, queue_size=100)
        cls.teleop = None

    @classmethod
    def tearDownClass(cls):
        cls._stop_teleop()
        stop_xvfb(cls.xvfb)

    @classmethod
    def _on_msg(cls, msg):
        with cls.lock:
            cls.msgs.append((msg.header.stamp.to_sec(), msg.drive.speed, msg.drive.steering_angle))

    @classmethod
    def _stop_teleop(cls):
        if cls.teleop is not None and cls.teleop.poll() is None:
            cls.teleop.kill()
            cls.teleop.wait(10)

    def tearDown(self):
        # whatever a failed test left: no node, no key down, auto-repeat on (the next test checks it)
        self._stop_teleop()
        for key in ('w', 'a', 's', 'd'):
            self.x('xdotool', 'keyup', key)
        self.x('xset', 'r', 'on')

    # -- helpers ----------------------------------------------------------------------------------
    def x(self, *args, timeout=20.0):
        return subprocess.run(list(args), env=self.env, capture_output=True, text=True, timeout=timeout)

    def auto_repeat(self):
        return auto_repeat(self.env)

    def messages_since(self, t):
        with self.lock:
            return [m for m in self.msgs if m[0] >= t]

    def wait_for(self, predicate, timeout, what):
        deadline = time.time() + timeout
        while time.time() < deadline:
            if predicate():
                return
            time.sleep(0.05)
        self.fail('timed out after %g s waiting for %s' % (timeout, what))

    def start_teleop(self):
        """Starts the node, waits for its window and its connection; focuses the window."""
        self.assertEqual(self.auto_repeat(), 'on', 'Xvfb should start with auto-repeat on')
        type(self).teleop = subprocess.Popen(['rosrun', 'racebot_gazebo', 'keyboard_teleop.py'], env=self.env)
        found = self.x('xdotool', 'search', '--sync', '--name', WINDOW_NAME, timeout=START_TIMEOUT)
        window = found.stdout.split()[0] if found.stdout.split() else None
        self.assertIsNotNone(window, 'no keyboard window appeared: %s' % found.stderr)
        self.wait_for(lambda: self.sub.get_num_connections() > 0, START_TIMEOUT,
                      'keyboard_teleop to connect to %s' % TOPIC)
        self.assertEqual(self.x('xdotool', 'windowfocus', '--sync', window).returncode, 0)
        time.sleep(0.5)
        self.assertEqual(self.auto_repeat(), 'on', 'the node switched the X session\'s auto-repeat off')
        return window

    def hold(self, key, seconds):
        t0 = time.time()
        self.x('xdotool', 'keydown', key)
        time.sleep(seconds)
        return t0

    def wait_exit(self):
        try:
            return self.teleop.wait(EXIT_TIMEOUT)
        except subprocess.TimeoutExpired:
            self.fail('keyboard_teleop still running %g s after being asked to quit' % EXIT_TIMEOUT)

    # -- tests ------------------------------------------------------------------------------------
    def test_1_hold_w_release_then_q(self):
        self.start_teleop()
        self.assertEqual(self.messages_since(0), [], 'published before any key was pressed')

        t0 = self.hold('w', 3.0)
        held = self.messages_since(t0)
        self.assertGreaterEqual(len(held), 20, 'holding W for 3 s gave %d commands' % len(held))
        for _, speed, steer in held:
            self.assertAlmostEqual(speed, SPEED, places=6)
            self.assertAlmostEqual(steer, 0.0, places=6)
        stamps = [m[0] for m in held]
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        self.assertTrue(8.0 <= rate <= 12.0, 'W held: %.1f Hz, expected about 10' % rate)

        t1 = self.hold('a', 1.0)  # W and A together: forward, steering left
        with_a = self.messages_since(t1)
        self.assertTrue(with_a and all(abs(m[1] - SPEED) < 1e-6 for m in with_a))
        self.assertAlmostEqual(with_a[-1][2], STEER, places=6)
        self.x('xdotool', 'keyup', 'a')
        time.sleep(0.5)

        t2 = time.time()
        self.x('xdotool', 'keyup', 'w')
        time.sleep(2.0)
        after = self.messages_since(t2)
        stops = [m for m in after if m[1] == 0.0 and m[2] == 0.0]
        self.assertEqual(len(stops), 1, 'releasing W: %d stop commands (%r)' % (len(stops), after))
        self.assertIs(after[-1], stops[0], 'the stop must be the last command: %r' % after)
        self.assertLessEqual(len(after), 2, 'after releasing W, only one command in flight, then the stop')
        self.assertLess(stops[0][0] - t2, 0.5, 'the stop came %.2f s after the release' % (stops[0][0] - t2))
        self.assertEqual(self.messages_since(t2 + 0.6), [], 'not silent after the stop')

        self.x('xdotool', 'key', 'q')
        self.assertEqual(self.wait_exit(), 0, 'keyboard_teleop exit status after Q')
        self.assertEqual(self.x('xdotool', 'search', '--name', WINDOW_NAME).stdout.strip(), '',
                         'the window is still there after Q')
        self.assertEqual(self.auto_repeat(), 'on', 'auto-repeat not restored after Q')

    def test_2_signals_stop_the_car_and_restore_repeat(self):
        for sig in (signal.SIGTERM, signal.SIGINT):
            self.start_teleop()
            t0 = self.hold('w', 1.0)
            self.assertTrue(self.messages_since(t0), 'no command while W is held')
            t1 = time.time()
            self.teleop.send_signal(sig)
            code = self.wait_exit()
            self.x('xdotool', 'keyup', 'w')
            self.assertEqual(code, 0, 'exit status after %s' % sig.name)
            self.assertEqual(self.auto_repeat(), 'on', 'auto-repeat not restored after %s' % sig.name)
            time.sleep(0.5)
            after = self.messages_since(t1)
            self.assertTrue(after and after[-1][1:] == (0.0, 0.0),
                            'after %s with W held the last command must be a stop: %r' % (sig.name, after))

    def test_4_sigkill_leaves_auto_repeat_on(self):
        self.start_teleop()
        t0 = self.hold('w', 1.0)
        self.assertTrue(self.messages_since(t0), 'no command while W is held')
        self.teleop.send_signal(signal.SIGKILL)
        self.assertEqual(self.wait_exit(), -signal.SIGKILL)
        self.x('xdotool', 'keyup', 'w')
        self.assertEqual(self.auto_repeat(), 'on', 'auto-repeat left off by a keyboard node killed with SIGKILL')

    def test_3_no_display_one_line_exit_0(self):
        for display in (None, ':%d' % (int(self.display[1:]) + 37)):  # unset; a display nobody serves
            env = dict(os.environ)
            env.pop('DISPLAY', None)
            if display:
                env['DISPLAY'] = display
            done = subprocess.run(['rosrun', 'racebot_gazebo', 'keyboard_teleop.py'], env=env, timeout=60,
                                  capture_output=True, text=True)
            lines = [line for line in done.stdout.splitlines() if line.strip()]
            self.assertEqual(done.returncode, 0, 'DISPLAY=%s: exit status %d' % (display, done.returncode))
            self.assertEqual(len(lines), 1, 'DISPLAY=%s: expected one line, got %r' % (display, done.stdout))
            self.assertIn('display', lines[0])
            self.assertNotIn('Traceback', done.stderr)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'keyboard_teleop_xdotool', KeyboardTeleopTest, sys.argv)
