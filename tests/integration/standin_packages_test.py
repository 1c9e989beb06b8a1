#!/usr/bin/env python3
"""The ROS packages robot packages name are there, as racebot's stand-ins (issue 29, point 4).

tests/fixtures/standin_workspace holds three packages written the way community Gazebo packages are:
sim_robot_gazebo names gazebo_ros, gazebo_plugins, gazebo_ros_control, ros_control's and ros_controllers'
packages and tf as catkin components, calls find_package(gazebo REQUIRED) and builds a plain roscpp node;
sim_robot_plugins compiles a Gazebo C++ world plugin; sim_robot_hw a C++ ros_control RobotHW. As a user would,
from a login shell that sourced racebot's devel space: catkin_make the workspace, and when it stops, run the
catkin_make line its message gives. Checked: the world plugin builds against racebot's Gazebo plugin API (issue
39); the RobotHW builds against racebot's hardware_interface but its node runs
ros_control's C++ controller manager, which racebot does not have: it is refused with a message naming it, its
file and how to leave it out; with it left out the workspace builds; `rospack find` gives every stand-in; a
launch file's `$(find joint_state_controller)/joint_state_controller.yaml` loads into the parameter server;
`roslaunch joint_state_controller joint_state_controller.launch` resolves.
"""
import os
import re
import sys
import unittest

import rospy
import rostest

from catkin_overlay import BUILD_TIMEOUT, Workspace, in_user_shell

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FIXTURE = os.path.join(REPO, 'tests', 'fixtures', 'standin_workspace')
RACEBOT_SETUP = os.path.join(REPO, 'devel', 'setup.bash')
STANDINS = ('joint_state_controller', 'effort_controllers', 'position_controllers', 'velocity_controllers',
            'forward_command_controller', 'diff_drive_controller', 'ackermann_steering_controller',
            'joint_trajectory_controller', 'gripper_action_controller', 'controller_interface', 'hardware_interface',
            'transmission_interface', 'joint_limits_interface', 'control_toolbox', 'realtime_tools',
            'gazebo_plugins', 'gazebo_ros_control', 'gazebo_dev')
# what each C++ package includes first of what racebot does not have
REFUSED = {'sim_robot_hw': 'src/sim_robot_hw_node.cpp: #include <controller_manager/controller_manager.h>'}
SUGGESTED = re.compile(r'catkin_make -DCATKIN_BLACKLIST_PACKAGES="([^"]*)"')
COMMAND_TIMEOUT = 60.0  # wall s for rospack and roslaunch on a busy machine



class StandinPackagesTest(unittest.TestCase):
    workspace = None

    @classmethod
    def setUpClass(cls):
        rospy.init_node('standin_packages_test')
        cls.workspace = Workspace('racebot-standin-ws-')
        cls.workspace.copy_packages(FIXTURE)
        # catkin_make; while it stops with racebot's advice, the catkin_make line the advice gives
        cls.refusals = []  # (output, the CATKIN_BLACKLIST_PACKAGES it suggests)
        arguments = ''
        for _ in range(len(REFUSED) + 1):
            cls.built, cls.build_output = cls.in_racebot_shell('catkin_make -C %s %s' % (cls.workspace.root, arguments),
                                                               BUILD_TIMEOUT)
            suggested = SUGGESTED.search(cls.build_output)
            if cls.built == 0 or not suggested:
                break
            cls.refusals.append((cls.build_output, suggested.group(1)))
            arguments = suggested.group(0)[len('catkin_make '):]

    @classmethod
    def tearDownClass(cls):
        if cls.workspace is not None:
            cls.workspace.remove()

    @classmethod
    def in_racebot_shell(cls, command, timeout, setup=RACEBOT_SETUP):
        return in_user_shell(setup, command, timeout)

    def in_workspace_shell(self, command):
        return self.in_racebot_shell(command, COMMAND_TIMEOUT, setup=self.workspace.setup)

    def test_1_each_cpp_package_is_refused_naming_it(self):
        refused = []
        for output, suggested in self.refusals:
            output = ' '.join(output.split())  # CMake wraps a message's lines
            skipped = suggested.split(';')
            package = skipped[-1]
            self.assertIn(package, REFUSED, output[-3000:])
            self.assertEqual(skipped[:-1], refused, 'the advice keeps the packages left out before')
            self.assertIn("racebot: package '%s' compiles C++ against" % package, output, output[-3000:])
            self.assertIn(REFUSED[package], output, output[-3000:])
            refused.append(package)
        self.assertEqual(sorted(refused), sorted(REFUSED), self.build_output[-3000:])

    def test_2_the_rest_builds_with_the_advice(self):
        self.assertEqual(self.built, 0, 'catkin_make failed:\n%s' % self.build_output[-3000:])
        node = os.path.join(self.workspace.root, 'devel', 'lib', 'sim_robot_gazebo', 'sim_robot_drive')
        self.assertTrue(os.access(node, os.X_OK), 'no %s' % node)
        plugin = os.path.join(self.workspace.root, 'devel', 'lib', 'libsim_robot_world_plugin.so')
        self.assertTrue(os.path.isfile(plugin), 'the world plugin did not build: no %s' % plugin)

    def test_3_rospack_finds_every_standin(self):
        self.assertEqual(self.built, 0, 'the workspace did not build')
        code, output = self.in_workspace_shell('for p in %s; do echo "$p=$(rospack find $p)"; done'
                                               % ' '.join(STANDINS))
        self.assertEqual(code, 0, output)
        found = dict(line.split('=', 1) for line in output.splitlines() if '=' in line)
        for package in STANDINS:
            self.assertEqual(found.get(package), os.path.join(REPO, 'upstream_compat', package), output)

    def test_4_find_loads_joint_state_controllers_yaml(self):
        self.assertEqual(self.built, 0, 'the workspace did not build')
        # a launch file of only parameters: roslaunch loads them into this test's master and ends
        code, output = self.in_workspace_shell('roslaunch sim_robot_gazebo control_params.launch')
        self.assertEqual(code, 0, output)
        self.assertEqual(rospy.get_param('/sim_robot/joint_state_controller'),
                         {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50})
        self.assertEqual(rospy.get_param('/sim_robot/left_wheel_controller/type'),
                         'velocity_controllers/JointVelocityController')

    def test_5_roslaunch_pkg_file_of_a_standin(self):
        self.assertEqual(self.built, 0, 'the workspace did not build')
        code, output = self.in_workspace_shell('roslaunch --dump-params joint_state_controller '
                                               'joint_state_controller.launch && '
                                               'roslaunch --nodes joint_state_controller joint_state_controller.launch')
        self.assertEqual(code, 0, output)
        self.assertIn('/joint_state_controller/type: joint_state_controller/JointStateController', output)
        self.assertIn('/joint_state_controller/publish_rate: 50', output)
        self.assertIn('/joint_state_controller_spawner', output)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'standin_packages', StandinPackagesTest, sys.argv)
