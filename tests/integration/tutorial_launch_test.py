#!/usr/bin/env python3
"""The tutorial's own launch files, as printed, drive the car (issue 16, point 2).

tests/fixtures/tutorial_launch holds the seed's racebot.launch and its final racebot_control.launch byte
for byte (tests/unit/tutorial/test_tutorial_launch_fixtures.py), each in an overlay package named like ours. This
node links both into a catkin workspace under /tmp, builds it on top of racebot's devel space, and runs
the tutorial's command there from a shell: `roslaunch racebot_gazebo racebot.launch gui:=false` (with no
DISPLAY: the keyboard node says so in one line and exits). Then, as a user would:
- roslaunch read exactly the two tutorial files, and gazebo_ros's empty_world.launch;
- the seven controllers run, servo_commands.py and transform.py (the tutorial's node names) are up;
- AckermannDriveStamped on /ackermann_cmd_mux/output drives the car forward, and steering left turns it
  left (/gazebo/get_model_state).
Waits are bounded in wall time; nothing is asserted after a fixed sleep.
"""
import glob
import math
import os
import re
import sys
import threading
import unittest

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist

from catkin_overlay import LaunchWatch, ShellCommand, Workspace
from integration_common import yaw_of

FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'fixtures', 'tutorial_launch')
CMD_TOPIC = '/ackermann_cmd_mux/output'
CONTROLLERS = 7  # racebot_control.yaml: joint_state_controller, four wheels, two hinges
STARTUP_TIMEOUT = 180.0  # wall s: world server, spawn and spawner on a busy 2-core machine
DRIVE_TIMEOUT = 120.0    # wall s for a drive that takes a few s of sim time


class TutorialLaunchTest(unittest.TestCase):
    launch = workspace = None  # set by start(); tearDownClass also runs after a failed start

    @classmethod
    def setUpClass(cls):
        try:
            cls.start()
        except BaseException:
            cls.tearDownClass()  # unittest does not call it when setUpClass fails
            raise

    @classmethod
    def start(cls):
        rospy.init_node('tutorial_launch_test')
        cls.workspace = Workspace('racebot-tutorial-ws-')
        for package in ('racebot_gazebo', 'racebot_control'):
            cls.workspace.link(os.path.realpath(os.path.join(FIXTURES, package)))
        setup = cls.workspace.build()
        env = dict(os.environ)
        env.pop('DISPLAY', None)
        command = 'source %s && exec roslaunch %%s racebot_gazebo racebot.launch gui:=false' % setup
        files = ShellCommand(command % '--files', env, os.path.join(cls.workspace.root, 'files.log'))
        try:
            files.process.wait(120)
        finally:
            files.stop()
        cls.files = files.output()
        cls.launch = ShellCommand(command % '', env, os.path.join(cls.workspace.root, 'roslaunch.log'))
        cls.watch = LaunchWatch(cls.launch)
        cls.pub = rospy.Publisher(CMD_TOPIC, AckermannDriveStamped, queue_size=10)
        cls.twist = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)

    @classmethod
    def tearDownClass(cls):
        if cls.launch is not None:
            cls.launch.stop()
            sys.stdout.write('--- roslaunch output ---\n%s\n' % cls.launch.output()[-6000:])
        if cls.workspace is not None:
            cls.workspace.remove()

    def launched(self, condition, what, timeout=STARTUP_TIMEOUT):
        return self.watch.wait(condition, what, timeout)

    def model_state(self):
        try:
            state = self.get_state('racebot', '')
        except (rospy.ServiceException, rospy.ROSException):
            return None
        return state if state.success else None

    def controllers_running(self):
        try:
            rospy.wait_for_service('/racebot/controller_manager/list_controllers', timeout=0.5)
            listed = rospy.ServiceProxy('/racebot/controller_manager/list_controllers', ListControllers)()
        except (rospy.ServiceException, rospy.ROSException):
            return False
        return sum(c.state == 'running' for c in listed.controller) == CONTROLLERS

    def ready(self):
        self.launched(self.model_state, 'the racebot in the world (/gazebo/get_model_state)')
        self.launched(self.controllers_running, 'the %d controllers running' % CONTROLLERS)
        self.launched(lambda: self.pub.get_num_connections() > 0, 'servo_commands.py on %s' % CMD_TOPIC)

    def drive(self, speed, steering, done, what):
        """Publishes the command at 10 Hz (wall) until done(pose) is true; then a stop command."""
        stop = threading.Event()

        def publish():
            msg = AckermannDriveStamped()
            msg.drive.speed, msg.drive.steering_angle = speed, steering
            while not stop.wait(0.1):
                self.pub.publish(msg)
        thread = threading.Thread(target=publish)
        thread.start()
        try:
            return self.launched(lambda: (lambda s: s if s and done(s.pose) else None)(self.model_state()),
                                 what, DRIVE_TIMEOUT)
        finally:
            stop.set()
            thread.join()
            self.pub.publish(AckermannDriveStamped())

    def test_1_roslaunch_reads_the_tutorial_files(self):
        files = [os.path.realpath(f) for f in self.files.split() if f.endswith('.launch')]
        self.assertIn(os.path.realpath(os.path.join(FIXTURES, 'racebot_gazebo', 'launch', 'racebot.launch')),
                      files, self.files)
        self.assertIn(os.path.realpath(os.path.join(FIXTURES, 'racebot_control', 'launch',
                                                    'racebot_control.launch')), files, self.files)
        self.assertTrue(any(f.endswith('/gazebo_ros/launch/empty_world.launch') for f in files), self.files)

    def test_2_the_tutorial_nodes_run(self):
        self.ready()
        self.launched(lambda: self.twist.get_num_connections() > 0, 'transform.py on /cmd_vel')
        # The verbatim racebot_control.launch gives servo_commands no parameters; ours would.
        self.assertFalse(rospy.has_param('/servo_commands/steering_mode'),
                         'racebot\'s own racebot_control.launch ran, not the tutorial\'s')

    def test_3_the_keyboard_node_without_display_says_so_and_exits(self):
        found = self.launched(lambda: re.search(r'\[(keyboard_teleop-\d+)\] process has (finished cleanly|died.*)'
                                                r'\nlog file: (\S+)\*\.log', self.launch.output()),
                              'the keyboard node to exit (no DISPLAY)')
        self.assertEqual(found.group(2), 'finished cleanly', found.group(0))
        stdout = glob.glob(found.group(3) + '*stdout*.log')
        self.assertTrue(stdout, 'no stdout log of %s' % found.group(1))
        with open(stdout[0]) as f:
            lines = [line for line in f.read().splitlines() if line.strip()]
        self.assertEqual(len(lines), 1, lines)
        self.assertIn('no display', lines[0])

    def test_4_ackermann_commands_drive_the_car(self):
        self.ready()
        start = self.model_state().pose
        x0, y0, yaw0 = start.position.x, start.position.y, yaw_of(start.orientation)
        ahead = self.drive(0.5, 0.0, lambda p: math.hypot(p.position.x - x0, p.position.y - y0) > 0.3,
                           'the car to drive 0.3 m (speed 0.5)').pose
        heading = math.atan2(ahead.position.y - y0, ahead.position.x - x0)
        self.assertLess(abs(math.atan2(math.sin(heading - yaw0), math.cos(heading - yaw0))), 0.2,
                        'speed 0.5 moved the car at %.2f rad from where it faced (%.2f): not forward'
                        % (heading, yaw0))
        yaw1 = yaw_of(ahead.orientation)
        turned = self.drive(0.5, 0.3, lambda p: abs(math.atan2(math.sin(yaw_of(p.orientation) - yaw1),
                                                               math.cos(yaw_of(p.orientation) - yaw1))) > 0.3,
                            'the car to turn 0.3 rad (speed 0.5, steering 0.3)').pose
        change = math.atan2(math.sin(yaw_of(turned.orientation) - yaw1), math.cos(yaw_of(turned.orientation) - yaw1))
        self.assertGreater(change, 0.0, 'steering +0.3 turned the car right (yaw %.2f rad)' % change)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'tutorial_launch', TutorialLaunchTest, sys.argv)
