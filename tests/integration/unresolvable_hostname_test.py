#!/usr/bin/env python3
"""The suite passes on a machine whose host name does not resolve (a common container set-up).

A small rostest (hostname/racebot_publishes.test: master, roslaunch, the world server, the spawner,
the C++ robot_state_publisher, publishtest) runs in a UTS namespace whose host name resolves nowhere:
- with the ROS networking the test runner gives the suite (tools/run_tests.py), it must pass;
- without it (no ROS_HOSTNAME or ROS_IP, as in such a container), roslaunch cannot reach its own
  server and the rostest must fail: that shows the host name really does not resolve, and that the
  first case tests the runner's networking rather than nothing.
The namespace is made with unshare(1) (util-linux); as root, or else in a user namespace.
"""
import os
import socket
import subprocess
import sys
import tempfile
import unittest

import rosunit

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, 'tools'))
from run_tests import use_loopback_ros_networking  # noqa: E402

INNER_TEST = os.path.join(HERE, 'hostname', 'racebot_publishes.test')
# Sets the host name inside the new namespace, then becomes the command (no `hostname` binary needed).
SET_HOSTNAME_AND_EXEC = 'import os, socket, sys; socket.sethostname(sys.argv[1]); os.execvp(sys.argv[2], sys.argv[2:])'


class UnresolvableHostName(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.hostname = 'racebot-unresolvable-%d' % os.getpid()
        try:
            socket.getaddrinfo(cls.hostname, None)
            raise AssertionError('host name %s resolves here; the test needs one that does not' % cls.hostname)
        except socket.gaierror:
            pass
        cls.unshare = ['unshare', '--uts'] if os.geteuid() == 0 else ['unshare', '--user', '--map-root-user', '--uts']

    def rostest(self, env):
        """(exit status, output) of the inner rostest under the unresolvable host name."""
        with tempfile.TemporaryDirectory(prefix='racebot_hostname_') as results:
            cmd = self.unshare + [sys.executable, '-c', SET_HOSTNAME_AND_EXEC, self.hostname,
                                  'rostest', '--results-base-dir', results, INNER_TEST]
            run = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                 text=True, timeout=240)
        return run.returncode, run.stdout

    def test_1_without_ros_networking_rostest_fails(self):
        env = dict(os.environ)
        for name in ('ROS_HOSTNAME', 'ROS_IP', 'ROS_IPV6'):
            env.pop(name, None)
        code, out = self.rostest(env)
        self.assertNotEqual(code, 0, 'rostest passed although the host name %s does not resolve and no ROS '
                                     'networking was set; this test no longer tests anything:\n%s'
                                     % (self.hostname, out[-3000:]))

    def test_2_with_the_runners_networking_rostest_passes(self):
        code, out = self.rostest(use_loopback_ros_networking(dict(os.environ)))
        self.assertEqual(code, 0, 'rostest failed under host name %s with the runner\'s ROS networking:\n%s'
                                  % (self.hostname, out[-4000:]))
        self.assertIn('SUMMARY', out)
        self.assertIn('* RESULT: SUCCESS', out)


if __name__ == '__main__':
    rosunit.unitrun('racebot_tests', 'unresolvable_hostname', UnresolvableHostName)
