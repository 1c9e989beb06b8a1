#!/usr/bin/env python3
"""The world server's own ROS time (world_server.init_clock_source): it publishes /clock and is not
subscribed to it (rospy's own /clock subscription is left out), and what it logs to /rosout is
stamped with the sim time of the moment, not wall time."""
import unittest

import rosgraph
import rospy
import rostest
from gazebo_msgs.srv import SpawnModel
from rosgraph_msgs.msg import Clock
from rosgraph_msgs.msg import Log

from integration_common import wait_for

URDF = ('<robot name="probe"><link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" '
        'iyy="0.01" iyz="0" izz="0.01"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
        '</collision></link></robot>')


class WorldServerTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('world_server_time_test', disable_rostime=True)
        cls.clock = None
        cls.logs = []
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        rospy.Subscriber('/rosout', Log, lambda m: cls.logs.append(m), queue_size=100)
        rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    def test_the_world_server_publishes_the_clock_without_subscribing_to_it(self):
        wait_for(lambda: self.clock is not None, '/clock', 60)
        publishers, subscribers, _ = rosgraph.Master('/world_server_time_test').getSystemState()
        self.assertIn('/gazebo', dict(publishers)['/clock'])
        self.assertNotIn('/gazebo', dict(subscribers).get('/clock', []),
                         'the world server subscribes to its own /clock')

    def test_its_log_messages_carry_sim_time(self):
        wait_for(lambda: self.clock is not None and self.clock > 1.0, '1 s of sim time', 60)
        before = self.clock
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        self.assertTrue(spawn(model_name='probe', model_xml=URDF, robot_namespace='').success)
        log = wait_for(lambda: [m for m in self.logs if m.name == '/gazebo' and 'probe declares no' in m.msg],
                       "the world server's log line about the probe", 60)[0]
        stamp = log.header.stamp.to_sec()
        self.assertGreaterEqual(stamp, before, 'the log stamp is older than the sim time before the spawn')
        wait_for(lambda: self.clock >= stamp, 'sim time to reach the log stamp %.3f (a wall-time stamp never does)'
                 % stamp, 20)

if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'world_server_time', WorldServerTimeTest)
