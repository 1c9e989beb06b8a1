#!/usr/bin/env python3
"""Issue 29 item 5 over ROS, each robot spawned through /gazebo/spawn_urdf_model (tests/fixtures/world_plugins):

- gripper: its leader joint under a position_controllers/JointPositionController; 'mirror', a URDF <mimic> of it
  (-0.5 x + 0.3), follows it (beyond Gazebo, which ignores <mimic>) and is in /gripper/joint_states through its
  transmission; 'twin', under roboticsgroup's mimic joint plugin (multiplier 2), follows too. Read with
  /gazebo/get_joint_properties while paused;
- elevator: std_msgs/String '1' on /elevator takes the car to floor 1 (3.075 m: it rests m g / p = 0.078 m short);
- box: hung by the harness at its spawn height until std_msgs/Bool true on /box/harness/detach drops it;
- cart: the wheel slip plugin's dynamic_reconfigure server at /cart/wheel_slip takes a compliance.
"""
import os
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import LoadController, SwitchController
from gazebo_msgs.srv import GetJointProperties, GetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool, Float64, String
from std_srvs.srv import Empty

from integration_common import Latest, wait_for

TIMEOUT = 90.0


class MimicAndWorldPluginsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('mimic_and_world_plugins_test')
        for name in ('spawn_urdf_model', 'get_joint_properties', 'get_model_state', 'pause_physics',
                     'unpause_physics'):
            rospy.wait_for_service('/gazebo/' + name, timeout=TIMEOUT)
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        fixtures = rospy.get_param('~fixtures')
        for name, filename, (x, y, z) in (('gripper', 'gripper', (0, 0, 0)), ('elevator', 'elevator', (10, 0, 0)),
                                          ('box', 'harness_box', (-10, 0, 1.5)), ('cart', 'slip_cart', (0, 10, 0.16))):
            with open(os.path.join(fixtures, filename + '.urdf')) as f:
                res = spawn(name, f.read(), '', Pose(Point(x, y, z), Quaternion(0, 0, 0, 1)), '')
            assert res.success, res.status_message
        cls.joint = rospy.ServiceProxy('/gazebo/get_joint_properties', GetJointProperties)
        cls.model = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)

    def paused(self, read):
        self.pause()
        try:
            return read()
        finally:
            self.unpause()

    def positions(self, *names):
        return [self.joint(n).position[0] for n in names]

    def test_gripper_mimics_follow_the_leader(self):
        cm = '/gripper/controller_manager/'
        rospy.wait_for_service(cm + 'load_controller', timeout=TIMEOUT)
        load = rospy.ServiceProxy(cm + 'load_controller', LoadController)
        for controller in ('joint_state_controller', 'leader_position_controller'):
            self.assertTrue(load(controller).ok, controller)
        switch = rospy.ServiceProxy(cm + 'switch_controller', SwitchController)
        self.assertTrue(switch(['joint_state_controller', 'leader_position_controller'], [], 2, False, 0.0).ok)
        states = Latest('/gripper/joint_states', JointState)
        command = rospy.Publisher('/gripper/leader_position_controller/command', Float64, queue_size=1, latch=True)
        for target in (0.8, -0.6):
            command.publish(Float64(target))
            wait_for(lambda: abs(self.positions('leader')[0] - target) < 1e-3, 'the leader at %g' % target,
                     TIMEOUT)
            rospy.sleep(0.5)
            leader, mirror, twin = self.paused(lambda: self.positions('leader', 'mirror', 'twin'))
            self.assertAlmostEqual(mirror, -0.5 * leader + 0.3, delta=2e-3)
            self.assertAlmostEqual(twin, 2 * leader, delta=5e-3)
        msg = wait_for(lambda: states.msg, '/gripper/joint_states', TIMEOUT)
        self.assertEqual(sorted(msg.name), ['leader', 'mirror'])

    def test_the_elevator_goes_to_floor_1(self):
        pub = rospy.Publisher('/elevator', String, queue_size=1, latch=True)
        wait_for(lambda: pub.get_num_connections() > 0, 'the elevator plugin to subscribe', TIMEOUT)
        pub.publish(String('1'))
        rest = 3.075 - 800 * 9.8 / 1e5  # p = 1e5 holds 800 kg that far below the floor
        wait_for(lambda: abs(self.positions('lift')[0] - rest) < 0.005, 'the car at rest at floor 1', TIMEOUT)

    def test_the_harness_holds_then_detaches(self):
        z = self.model('box', '').pose.position.z
        self.assertAlmostEqual(z, 1.5, delta=1e-3)
        pub = rospy.Publisher('/box/harness/detach', Bool, queue_size=1, latch=True)
        wait_for(lambda: pub.get_num_connections() > 0, 'the harness plugin to subscribe', TIMEOUT)
        pub.publish(Bool(True))
        wait_for(lambda: abs(self.model('box', '').pose.position.z - 0.5) < 0.01, 'the box on the ground', TIMEOUT)

    def test_the_wheel_slip_reconfigure_server(self):
        from dynamic_reconfigure.client import Client
        client = Client('/cart/wheel_slip', timeout=TIMEOUT)
        self.assertEqual(client.get_configuration(timeout=TIMEOUT)['slip_compliance_unitless_lateral'], -1.0)
        config = client.update_configuration({'slip_compliance_unitless_lateral': 2.5})
        self.assertEqual(config['slip_compliance_unitless_lateral'], 2.5)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'mimic_and_world_plugins', MimicAndWorldPluginsTest)
