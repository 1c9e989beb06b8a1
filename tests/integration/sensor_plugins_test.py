#!/usr/bin/env python3
"""The range, bumper, multicamera and openni_kinect plugins through the topics gazebo_ros would publish.

The robot (tests/fixtures/sensor_plugins/robot.urdf) stands at the origin of empty_world; this node
spawns a static 0.4 m box whose near face is 1 m ahead of the sonar. In order: the sonar's Range,
the stereo pair, the Kinect's topics and cloud, then the bumper free, then pushed into the box
with /gazebo/apply_body_wrench. Expected values come from the fixture's geometry and the pinhole
model; waits are bounded in wall time, stamps are sim time.
"""
import functools
import math
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
from gazebo_msgs.msg import ContactsState, ModelStates
from gazebo_msgs.srv import ApplyBodyWrench, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Vector3, Wrench
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, Range

import integration_common  # next to this file
from integration_common import Latest

WALL_TIMEOUT = 60.0
SONAR_X = 0.22     # sonar_joint
KINECT_X = 0.1     # kinect_joint
BOX_FACE = 1.22    # the box's near face, 1 m ahead of the sonar
BOX_SIZE = 0.4
BUMPER = 'sensor_robot::base_link::base_link_fixed_joint_lump__bumper_link_collision_1'
BOX_SDF = """<sdf version="1.6"><model name="obstacle"><static>true</static><link name="link">
<collision name="collision"><geometry><box><size>{s} {s} {s}</size></box></geometry></collision>
<visual name="visual"><geometry><box><size>{s} {s} {s}</size></box></geometry></visual>
</link></model></sdf>""".format(s=BOX_SIZE)

wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.01)


class SensorPluginsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('sensor_plugins_test')
        cls.clock = None
        cls.models = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        rospy.Subscriber('/gazebo/model_states', ModelStates, cls._on_models, queue_size=1)
        for name in ('spawn_sdf_model', 'apply_body_wrench'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        wait_for(lambda: cls.models is not None and 'sensor_robot' in cls.models.name, 'the robot to be spawned')
        box = Pose(position=Point(BOX_FACE + BOX_SIZE / 2, 0.0, BOX_SIZE / 2), orientation=Quaternion(0, 0, 0, 1))
        res = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)('obstacle', BOX_SDF, '', box, 'world')
        assert res.success, res.status_message
        cls.box_time = wait_for(lambda: cls.clock, '/clock')

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    @classmethod
    def _on_models(cls, msg):
        cls.models = msg

    def test_1_sonar_reads_the_distance_to_the_box(self):
        m = Latest('/sonar', Range).after(self.box_time + 0.1, 'a Range after the box appeared', WALL_TIMEOUT)
        self.assertEqual(m.header.frame_id, 'sonar_link')
        self.assertEqual(m.radiation_type, Range.ULTRASOUND)
        self.assertAlmostEqual(m.field_of_view, 0.5, places=6)
        self.assertAlmostEqual(m.min_range, 0.02, places=6)
        self.assertAlmostEqual(m.max_range, 4.0, places=6)
        self.assertAlmostEqual(m.range, BOX_FACE - SONAR_X, delta=0.01)  # the ray sensor's resolution

    def test_2_stereo_pair_with_the_baseline(self):
        latest = {(side, kind): Latest('/stereo/%s/%s' % (side, topic), cls)
                  for side in ('left', 'right') for kind, topic, cls in (('image', 'image_raw', Image),
                                                                        ('info', 'camera_info', CameraInfo))}
        msgs = {key: sub.after(self.box_time, '/stereo/%s %s' % key, WALL_TIMEOUT) for key, sub in latest.items()}
        f = 64 / (2 * math.tan(0.5))
        self.assertEqual(msgs['left', 'info'].P[3], 0.0)
        self.assertAlmostEqual(msgs['right', 'info'].P[3], -f * 0.07, places=4)  # Tx = -f * hackBaseline
        for side in ('left', 'right'):
            image = msgs[side, 'image']
            self.assertEqual((image.width, image.height, image.header.frame_id), (64, 48, 'stereo_link'))
            self.assertEqual(msgs[side, 'info'].header.frame_id, 'stereo_link')

    def test_3_kinect_topics_and_a_cloud_of_the_box(self):
        expected = {'/kinect/rgb/image_raw': 'sensor_msgs/Image', '/kinect/rgb/camera_info': 'sensor_msgs/CameraInfo',
                    '/kinect/depth/image_raw': 'sensor_msgs/Image',
                    '/kinect/depth/camera_info': 'sensor_msgs/CameraInfo',
                    '/kinect/depth/points': 'sensor_msgs/PointCloud2'}
        types = dict(rosgraph.Master('/sensor_plugins_test').getTopicTypes())
        self.assertEqual({t: types.get(t) for t in expected}, expected)
        cloud = Latest('/kinect/depth/points', PointCloud2).after(self.box_time + 0.1, 'a point cloud', WALL_TIMEOUT)
        self.assertEqual((cloud.width, cloud.height, cloud.header.frame_id), (64, 48, 'kinect_link'))
        xyz = np.frombuffer(cloud.data, np.uint8).reshape(-1, cloud.point_step)[:, :12].copy().view('<f4')
        finite = xyz[np.isfinite(xyz).all(axis=1)]
        self.assertGreater(len(finite), 100)
        self.assertTrue(((finite[:, 2] > 0.5) & (finite[:, 2] < 3.0)).all())  # pointCloudCutoff .. CutoffMax
        centre = xyz.reshape(48, 64, 3)[23:25, 31:33, 2]
        np.testing.assert_allclose(centre, BOX_FACE - KINECT_X, atol=0.03)

    def test_4_bumper_free_then_pushed_into_the_box(self):
        bumper = Latest('/bumper', ContactsState)
        free = bumper.after(self.clock + 0.1, 'a ContactsState', WALL_TIMEOUT)
        self.assertEqual(free.header.frame_id, 'bumper_link')
        self.assertEqual(free.states, [])  # the base stands on the ground; the bumper touches nothing
        push = rospy.ServiceProxy('/gazebo/apply_body_wrench', ApplyBodyWrench)
        res = push(body_name='sensor_robot::base_link', reference_frame='world', reference_point=Point(0, 0, 0),
                   wrench=Wrench(force=Vector3(30.0, 0.0, 0.0)), start_time=rospy.Time(0),
                   duration=rospy.Duration(-1))
        self.assertTrue(res.success, res.status_message)
        hit = wait_for(lambda: bumper.msg if bumper.msg is not None and bumper.msg.states else None,
                       'the bumper to touch the box')
        # a state per step since the last update (Gazebo's ContactSensor keeps them): one pair throughout
        self.assertEqual({(s.collision1_name, s.collision2_name) for s in hit.states},
                         {(BUMPER, 'obstacle::link::collision')})
        state = hit.states[-1]
        self.assertTrue(all(n.x < -0.9 for n in state.contact_normals), state.contact_normals)
        self.assertTrue(all(abs(p.x - BOX_FACE) < 0.02 for p in state.contact_positions), state.contact_positions)
        self.assertEqual(len(state.wrenches), len(state.depths))
        # The box pushes back once the robot presses on it: half a second of sim time into the push.
        # (The first touch can carry no force yet, touching is not pushing; or the impact's, -2500 N.)
        pressed = bumper.after(hit.header.stamp.to_sec() + 0.5, 'a ContactsState 0.5 s into the push', WALL_TIMEOUT)
        self.assertEqual([(s.collision1_name, s.collision2_name) for s in pressed.states],
                         [(BUMPER, 'obstacle::link::collision')] * 20)  # the sensor's 50 Hz: 20 steps of 1 ms
        # It holds the robot against the 30 N push less what the ground's friction takes (seen: -24.25 N).
        self.assertTrue(-31.0 < pressed.states[-1].total_wrench.force.x < -10.0, pressed.states[-1].total_wrench)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'sensor_plugins', SensorPluginsTest)
