#!/usr/bin/env python3
"""ROS 1 C++ builds and runs unchanged on Debian 12 (issue 38, points 1 and 5): upstream_compat's pluginlib,
class_loader and roscpp overlays.

tests/fixtures/ros1_cpp_workspace holds four packages written the way ROS 1 packages are: fixture_shapes (a
pluginlib base class and a loader using pluginlib::ClassLoader from <pluginlib/class_loader.h>),
fixture_shape_plugins (two plugins from <pluginlib/class_list_macros.h>, one with PLUGINLIB_EXPORT_CLASS, one with
the older PLUGINLIB_DECLARE_CLASS, exported in package.xml), fixture_relay_nodelet (a nodelet whose subscriber
callback is boost::bind(..., _1) with a bare placeholder), fixture_echo_node (a plain roscpp node, finding only
roscpp and std_msgs, with the same kind of callback). As a user would, from a login shell that sourced
racebot's devel space: catkin_make the workspace once (shared by every test here), then in shells that sourced
its devel space: the loader finds both plugins through rospack's exports and creates them; Debian's nodelet
manager loads the nodelet, whose callback relays a message; the plain node echoes one.
"""
import os
import sys
import tempfile
import time
import unittest

import rospy
import rostest
from std_msgs.msg import String

from catkin_overlay import BUILD_TIMEOUT, ShellCommand, Workspace, in_user_shell, user_environment

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FIXTURE = os.path.join(REPO, 'tests', 'fixtures', 'ros1_cpp_workspace')
RACEBOT_SETUP = os.path.join(REPO, 'devel', 'setup.bash')
COMMAND_TIMEOUT = 60.0  # wall s for the loader on a busy machine
RELAY_TIMEOUT = 60.0    # wall s for the nodelet manager to start, load the nodelet and relay
SIDE = 2.0              # the side length shape_loader gives each shape
AREAS = {'fixture_shape_plugins/Square': SIDE * SIDE,
         'fixture_shape_plugins/Triangle': SIDE * SIDE * 3 ** 0.5 / 4}


class Ros1CppTest(unittest.TestCase):
    workspace = None

    @classmethod
    def setUpClass(cls):
        rospy.init_node('ros1_cpp_test')
        cls.workspace = Workspace('racebot-ros1-cpp-ws-')
        cls.workspace.copy_packages(FIXTURE)
        cls.built, cls.build_output = in_user_shell(RACEBOT_SETUP, 'catkin_make -C %s' % cls.workspace.root,
                                               BUILD_TIMEOUT)

    @classmethod
    def tearDownClass(cls):
        if cls.workspace is not None:
            cls.workspace.remove()

    def assert_built(self):
        self.assertEqual(self.built, 0, 'catkin_make of the ROS 1 C++ packages failed:\n%s' % self.build_output[-4000:])

    def test_1_the_ros1_packages_build(self):
        self.assert_built()
        for path in ('lib/fixture_shapes/shape_loader', 'lib/libfixture_shape_plugins.so',
                     'lib/libfixture_relay_nodelet.so', 'lib/fixture_echo_node/echo_node'):
            self.assertTrue(os.path.exists(os.path.join(self.workspace.root, 'devel', path)), 'no devel/%s' % path)

    def test_2_the_loader_finds_and_creates_the_plugins_through_package_exports(self):
        self.assert_built()
        code, output = in_user_shell(self.workspace.setup, 'rosrun fixture_shapes shape_loader', COMMAND_TIMEOUT)
        self.assertEqual(code, 0, output)
        found = {}
        for line in output.splitlines():
            words = line.split()
            if len(words) == 6 and words[0] == 'shape' and words[2] == 'area':
                found[words[1]] = (float(words[3]), words[5])
        self.assertEqual(sorted(found), sorted(AREAS), output)
        library = os.path.join(self.workspace.root, 'devel', 'lib', 'libfixture_shape_plugins.so')
        for name, area in AREAS.items():
            self.assertAlmostEqual(found[name][0], area, places=3, msg=output)
            self.assertEqual(os.path.realpath(found[name][1]), os.path.realpath(library), output)
        self.assertIn('shapes declared 2', output)

    def relays(self, namespace, command, answer):
        """Runs `command` (after sourcing the workspace) in `namespace`, publishes 'hello' on <namespace>/in until
        <namespace>/out answers; the answer must be `answer`."""
        self.assert_built()
        received = []
        rospy.Subscriber(namespace + '/out', String, lambda message: received.append(message.data), queue_size=10)
        publisher = rospy.Publisher(namespace + '/in', String, queue_size=10)
        handle, log = tempfile.mkstemp(prefix='ros1_cpp%s-' % namespace.replace('/', '_'), suffix='.log',
                                       dir=os.environ.get('ROS_LOG_DIR'))
        os.close(handle)
        shell = ShellCommand('source %s && ROS_NAMESPACE=%s exec %s' % (self.workspace.setup, namespace, command),
                             user_environment(), log, login=True)
        try:
            deadline = time.time() + RELAY_TIMEOUT
            while not received and time.time() < deadline and shell.running() and not rospy.is_shutdown():
                publisher.publish(String(data='hello'))
                time.sleep(0.2)
            self.assertTrue(received, 'nothing on %s/out (%s); the output of %s:\n%s' % (
                namespace, 'it ended' if not shell.running() else 'timed out', command, shell.output()[-3000:]))
            self.assertEqual(received[0], answer)
        finally:
            shell.stop()

    def test_3_debians_nodelet_manager_runs_the_nodelet_and_its_bound_callback_relays(self):
        # the nodelet in a manager of its own, in the namespace /relay (its topics: /relay/in, /relay/out)
        self.relays('/relay', 'rosrun nodelet nodelet standalone fixture_relay_nodelet/Relay', 'relayed: hello')

    def test_4_a_plain_roscpp_node_with_a_bare_placeholder_echoes(self):
        self.relays('/echo', 'rosrun fixture_echo_node echo_node', 'echoed: hello')


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'ros1_cpp', Ros1CppTest, sys.argv)
