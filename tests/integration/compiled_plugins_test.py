#!/usr/bin/env python3
"""A lab's own compiled Gazebo plugin with a ROS interface runs in racebot's world server (issue 39, points 2 and 7).

tests/fixtures/gazebo_plugin_workspace/fixture_ros_gazebo_plugins is written the way community plugin packages are:
find_package(catkin COMPONENTS roscpp gazebo_ros ...) and find_package(gazebo), a model plugin that makes a
ros::NodeHandle in its Load, subscribes a velocity command (its callback on roscpp's spinner), drives a joint at
every worldUpdateBegin (boost::bind with a bare _1), publishes the joint's velocity and serves a std_srvs/Trigger
that moves the joint from roscpp's thread. As a user would, from a login shell: source racebot's devel space,
catkin_make a workspace under /tmp holding the package, source its devel space and roslaunch its world launch
(gazebo_ros's empty_world.launch, spawn_model -urdf). Checked: roscpp's node runs beside the world server's rospy
node without a name clash; the command drives the joint (its velocity topic reads it back); the service moves the
joint from roscpp's thread while the world steps; ROS_INFO from Load reaches the log.
"""
import os
import shutil
import subprocess
import sys
import unittest

import rosgraph
import rospy
import rostest
from std_msgs.msg import Float64
from std_srvs.srv import Trigger

from catkin_overlay import BUILD_TIMEOUT, LaunchWatch, ShellCommand, Workspace, user_environment

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
PACKAGE = os.path.join(REPO, 'tests', 'fixtures', 'gazebo_plugin_workspace', 'fixture_ros_gazebo_plugins')
RACEBOT_SETUP = os.path.join(REPO, 'devel', 'setup.bash')
STARTUP_TIMEOUT = 180.0  # wall s: world server, spawn and the plugin's first message on a busy 2-core machine
COMMAND_TIMEOUT = 60.0


class CompiledPluginsTest(unittest.TestCase):
    launch = workspace = None

    @classmethod
    def setUpClass(cls):
        try:
            cls.start()
        except BaseException:
            cls.tearDownClass()
            raise

    @classmethod
    def start(cls):
        rospy.init_node('compiled_plugins_test')
        cls.velocities = []
        cls.velocity_sub = rospy.Subscriber('/spinner/joint_velocity', Float64, lambda m: cls.velocities.append(m.data),
                                            queue_size=100)
        cls.cmd = rospy.Publisher('/spinner/cmd', Float64, queue_size=1, latch=True)
        cls.workspace = Workspace('racebot-plugin-ws-')
        shutil.copytree(PACKAGE, os.path.join(cls.workspace.src, os.path.basename(PACKAGE)))
        env = user_environment()
        build = ShellCommand('source %s && catkin_make -C %s' % (RACEBOT_SETUP, cls.workspace.root), env,
                             os.path.join(cls.workspace.root, 'catkin_make.log'), login=True)
        try:
            built = build.process.wait(BUILD_TIMEOUT)
        except subprocess.TimeoutExpired:
            built = 'timed out after %.0f s' % BUILD_TIMEOUT
        log = build.output()
        build.stop()
        assert built == 0, 'catkin_make of the plugin package failed (%s):\n%s' % (built, log[-3000:])
        cls.launch = ShellCommand('source %s && exec roslaunch fixture_ros_gazebo_plugins spinner_world.launch'
                                  % cls.workspace.setup, env, os.path.join(cls.workspace.root, 'roslaunch.log'),
                                  login=True)
        cls.watch = LaunchWatch(cls.launch)

    @classmethod
    def tearDownClass(cls):
        if cls.launch is not None:
            cls.launch.stop()
            sys.stdout.write('--- roslaunch output ---\n%s\n' % cls.launch.output()[-6000:])
        if cls.workspace is not None:
            cls.workspace.remove()

    def launched(self, condition, what, timeout=STARTUP_TIMEOUT):
        return self.watch.wait(condition, what, timeout)

    def test_1_roscpp_runs_beside_the_world_servers_node(self):
        self.launched(lambda: self.velocities, "the plugin's first /spinner/joint_velocity")
        nodes = rosgraph.Master('/compiled_plugins_test').getSystemState()
        publishers = {topic: names for topic, names in nodes[0]}
        self.assertEqual(publishers.get('/spinner/joint_velocity'), ['/gazebo_cpp'], publishers)
        services = {name: providers for name, providers in nodes[2]}
        self.assertEqual(services.get('/spinner/zero'), ['/gazebo_cpp'])
        self.assertIn('/gazebo/spawn_urdf_model', services)  # the rospy node is still there, not replaced
        self.launched(lambda: 'RosJointPlugin drives spinner::spin_joint in namespace /spinner'
                      in self.launch.output(), "the plugin's ROS_INFO on the world server's screen")

    def test_2_the_topic_drives_the_joint(self):
        self.launched(lambda: self.velocities, "the plugin's first /spinner/joint_velocity")
        self.cmd.publish(Float64(3.0))
        self.launched(lambda: self.velocities and abs(self.velocities[-1] - 3.0) < 1e-3,
                      'the joint at the commanded 3.0 rad/s', COMMAND_TIMEOUT)

    def test_3_a_service_moves_the_joint_from_roscpps_thread(self):
        rospy.wait_for_service('/spinner/zero', timeout=STARTUP_TIMEOUT)
        answer = rospy.ServiceProxy('/spinner/zero', Trigger)()
        self.assertTrue(answer.success)
        self.assertAlmostEqual(float(answer.message), 0.0, places=6)
        self.launched(lambda: self.velocities and abs(self.velocities[-1]) < 1e-6,
                      'the joint stopped by the service', COMMAND_TIMEOUT)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'compiled_plugins', CompiledPluginsTest, sys.argv)
