#!/usr/bin/env python3
"""gazebo_ros_block_laser, velodyne_gazebo_plugins' laser and hector's sonar through the topics a user reads.

The robot (tests/fixtures/ray_plugins/robot.urdf) stands at the origin of empty_world, its sensors 0.45 m up;
this node spawns a static wall whose near face is the plane x = 2 from y = -0.05 on (rays to the right of it
miss), laser_retro 200. Then: the sonar's Range and its SensorModel changed with dynamic_reconfigure's own
Client; the block laser's PointCloud; the velodyne's PointCloud2 (the pinned 1.0.9 layout). Expected values come
from the fixture's geometry; waits are bounded in wall time, stamps are sim time.
"""
import functools
import math
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud, PointCloud2, Range

import integration_common  # next to this file
from integration_common import Latest

WALL_TIMEOUT = 60.0
WALL_X, WALL_Y_MIN = 2.0, -0.05
WALL_SDF = """<sdf version="1.6"><model name="wall"><static>true</static><link name="link">
<collision name="collision"><laser_retro>200</laser_retro><geometry><box><size>1 {w} 2</size></box></geometry>
</collision></link></model></sdf>""".format(w=10.0 - WALL_Y_MIN)

wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.01)


class RayPluginsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('ray_plugins_test')
        cls.clock = None
        cls.models = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        rospy.Subscriber('/gazebo/model_states', ModelStates, cls._on_models, queue_size=1)
        rospy.wait_for_service('/gazebo/spawn_sdf_model', timeout=WALL_TIMEOUT)
        wait_for(lambda: cls.models is not None and 'ray_robot' in cls.models.name, 'the robot to be spawned')
        pose = Pose(position=Point(WALL_X + 0.5, (WALL_Y_MIN + 10.0) / 2, 1.0), orientation=Quaternion(0, 0, 0, 1))
        res = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)('wall', WALL_SDF, '', pose, 'world')
        assert res.success, res.status_message
        cls.wall_time = wait_for(lambda: cls.clock, '/clock')

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    @classmethod
    def _on_models(cls, msg):
        cls.models = msg

    def test_1_sonar_reads_the_wall_and_its_model_changes_through_dynamic_reconfigure(self):
        sonar = Latest('/sonar', Range)
        m = sonar.after(self.wall_time + 0.2, 'a Range after the wall appeared', WALL_TIMEOUT)
        self.assertEqual((m.header.frame_id, m.radiation_type), ('sonar_link', Range.ULTRASOUND))
        self.assertAlmostEqual(m.field_of_view, 0.1, places=6)
        self.assertAlmostEqual(m.range, WALL_X, delta=1e-3)
        client = Client('/sonar', timeout=WALL_TIMEOUT)
        self.assertAlmostEqual(client.get_configuration(timeout=WALL_TIMEOUT)['scale_error'], 1.0)
        client.update_configuration({'offset': 0.5})
        wait_for(lambda: sonar.msg is not None and abs(sonar.msg.range - WALL_X - 0.5) < 1e-3,
                 'the sonar to read the offset set through dynamic_reconfigure')

    def test_2_block_laser_cloud(self):
        m = Latest('/block_cloud', PointCloud).after(self.wall_time + 0.2, 'a PointCloud', WALL_TIMEOUT)
        self.assertEqual((m.header.frame_id, len(m.points), len(m.channels)), ('sensor_link', 15, 1))
        # the middle layer's third point: the straight-ahead ray's range (2 m), at upstream's mean angle
        p = m.points[1 * 5 + 2]
        self.assertAlmostEqual(math.hypot(p.x, p.y, p.z), WALL_X, delta=1e-3)
        self.assertAlmostEqual(math.atan2(p.y, p.x), 0.05, delta=1e-4)
        self.assertAlmostEqual(m.channels[0].values[1 * 5 + 2], 200.0)   # all four corners on the wall
        self.assertEqual(m.channels[0].values[1 * 5 + 0], 0.0)           # all four beside it

    def test_3_velodyne_cloud(self):
        m = Latest('/velodyne_points', PointCloud2).after(self.wall_time + 0.2, 'a PointCloud2', WALL_TIMEOUT)
        self.assertEqual([(f.name, f.offset) for f in m.fields],
                         [('x', 0), ('y', 4), ('z', 8), ('intensity', 16), ('ring', 20)])
        self.assertEqual((m.header.frame_id, m.height, m.width, m.point_step, m.row_step), ('velodyne', 1, 16, 32, 512))
        points = list(point_cloud2.read_points(m, field_names=('x', 'intensity', 'ring')))
        self.assertEqual([p[2] for p in points], [0, 1, 2, 3] * 4)
        self.assertTrue(all(abs(p[0] - WALL_X) < 1e-3 and p[1] == 200.0 for p in points), points)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'ray_plugins', RayPluginsTest)
