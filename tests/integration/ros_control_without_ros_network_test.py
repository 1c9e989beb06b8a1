#!/usr/bin/env python3
"""A world-file robot's controller manager with enable_ros_network:=false (issue 28).

upstream (gazebo_ros_pkgs noetic-devel): only gazebo_ros_api_plugin reads enable_ros_network, and leaves
out its own /gazebo services; gazebo_ros_control_plugin.cpp reads no such flag and makes its
ControllerManager, which advertises <ns>/controller_manager/*, whatever it says. The world
(fixtures/ros_control/control_bot.world) holds wbot, an SDF model with the plugin in /wbot.
"""
import unittest

import rosgraph
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers, LoadController

WALL_TIMEOUT = 60
CM = '/wbot/controller_manager/'
CM_SERVICES = ['list_controller_types', 'list_controllers', 'load_controller', 'reload_controller_libraries',
               'switch_controller', 'unload_controller']


class RosControlWithoutRosNetworkTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('ros_control_without_ros_network_test')
        rospy.wait_for_service(CM + 'list_controllers', timeout=WALL_TIMEOUT)

    def test_the_world_file_robot_offers_its_controller_manager(self):
        self.assertEqual(rospy.ServiceProxy(CM + 'list_controllers', ListControllers)().controller, [])
        self.assertTrue(rospy.ServiceProxy(CM + 'load_controller', LoadController)('joint_state_controller').ok)
        (state,) = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)().controller
        self.assertEqual((state.name, state.state), ('joint_state_controller', 'initialized'))

    def test_the_gazebo_node_offers_no_gazebo_services(self):
        _, _, services = rosgraph.Master('/ros_control_without_ros_network_test').getSystemState()
        offered = sorted(s for s, nodes in services if '/gazebo' in nodes)
        self.assertEqual(offered, sorted(['/gazebo/get_loggers', '/gazebo/set_logger_level'] +
                                         [CM + name for name in CM_SERVICES]))


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'ros_control_without_ros_network', RosControlWithoutRosNetworkTest)
