#!/usr/bin/env python3
"""A link kept by <gazebo reference="lidar_joint"><preserveFixedJoint> is a frame of its own.

The racebot (preserved_lidar.xacro) stands in room_mini. Gazebo keeps the lidar link instead of
lumping it into base_footprint, so /gazebo/get_link_state answers for racebot::lidar, at the car's
pose moved by the two fixed joints' origins of the URDF; /gazebo/link_states lists it (and not the
camera, still lumped); the laser on it scans the room's walls where the world file puts them.
"""
import functools
import unittest

import rospy
import rostest

import integration_common  # next to this file
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import GetLinkState, GetModelState
from integration_common import Latest
from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.description import urdf_reader
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty

import sensors_geometry

WALL_TIMEOUT = 60.0
POSITION_TOLERANCE = 1e-4  # m: both read with the physics paused
SCAN_TOLERANCE = 0.03      # m, lidar against the world's geometry (as sensors_test)

wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.01)


def as_pair(pose):
    p, q = pose.position, pose.orientation
    return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)


class PreservedLinkTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('preserved_link_test')
        cls.clock = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        for name in ('get_link_state', 'get_model_state', 'pause_physics', 'unpause_physics'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        cls.link_state = rospy.ServiceProxy('/gazebo/get_link_state', GetLinkState)
        cls.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        cls.model = urdf_reader.parse_urdf(rospy.get_param('/robot_description'))
        wait_for(lambda: cls.model_state('racebot', '').success, 'the racebot to be spawned')
        wait_for(lambda: cls.clock is not None and cls.clock >= 1.0, 'sim time 1 s')  # settled on its wheels

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    def paused_states(self):
        """(model pose, lidar link pose) read with the physics paused, so both are of one instant."""
        self.pause()
        try:
            model = self.model_state('racebot', '')
            link = self.link_state('racebot::lidar', '')
        finally:
            self.unpause()
        self.assertTrue(model.success, model.status_message)
        self.assertTrue(link.success, link.status_message)
        return as_pair(model.pose), as_pair(link.link_state.pose)

    def expected_lidar(self, model_pose):
        """The lidar frame from the URDF: the model's (base_footprint's) pose, then the origin of each
        fixed joint down to the lidar (base_link2base_footprint, lidar_joint)."""
        chain, joint = [], self.model.parent_joint('lidar')
        while joint is not None:
            self.assertEqual(joint.type, 'fixed')
            chain.append(joint)
            joint = self.model.parent_joint(joint.parent)
        pose = model_pose
        for joint in reversed(chain):
            pose = rotations.compose(pose, joint.origin_xyz + joint.origin_rpy)
        return pose

    def test_1_the_preserved_link_has_a_state_at_its_urdf_place(self):
        self.assertEqual(self.model.lumped_link('lidar'), 'lidar')
        model_pose, lidar_pose = self.paused_states()
        expected = self.expected_lidar(model_pose)
        for got, want in zip(lidar_pose[0], expected[0]):
            self.assertAlmostEqual(got, want, delta=POSITION_TOLERANCE)
        for got, want in zip(lidar_pose[1], expected[1]):
            self.assertAlmostEqual(got, want, delta=1e-4)

    def test_2_link_states_list_it_and_not_a_lumped_link(self):
        states = Latest('/gazebo/link_states', LinkStates)
        msg = wait_for(lambda: states.msg, '/gazebo/link_states')
        self.assertIn('racebot::lidar', msg.name)
        self.assertNotIn('racebot::camera', msg.name)  # still lumped into base_footprint, as Gazebo does

    def test_3_the_laser_on_it_scans_the_room(self):
        scans = Latest('/scan', LaserScan)
        _, lidar_pose = self.paused_states()
        after = wait_for(lambda: self.clock, '/clock') + 0.1
        scan = wait_for(lambda: scans.msg if scans.msg is not None and scans.msg.header.stamp.to_sec() >= after
                        else None, 'a /scan')
        self.assertEqual(scan.header.frame_id, 'lidar')
        spec = next(s for s in self.model.sensors if s.reference == 'lidar')
        position, orientation = rotations.compose(lidar_pose, spec.pose)
        yaw = rotations.quaternion_to_rpy(orientation)[2]
        expected = sensors_geometry.expected_scan(rospy.get_param('~world'), position, yaw, scan.angle_min,
                                                  scan.angle_increment, len(scan.ranges))
        checked, bad = sensors_geometry.compare(scan.ranges, expected, scan.range_min, scan.range_max,
                                                SCAN_TOLERANCE)
        self.assertGreater(checked, 0.95 * len(scan.ranges))
        self.assertFalse(bad, bad[:10])


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'preserved_link', PreservedLinkTest)
