#!/usr/bin/env python3
"""Black-box test of the racebot's simulated sensors through the topics gazebo_ros would publish.

The car stands at its spawn pose in room_mini with its controllers holding it; sensor noise is
off (/gazebo/sensors/noise false in sensors.test). Expected values come from elsewhere than the
simulator: the world file's geometry (sensors_geometry), the URDF in /robot_description (sizes,
offsets, fields of view) and the pinhole model. Waits are in wall time, judgements in sim time.
"""
import functools
import math
import unittest

import numpy as np
import rospy
import rostest

import integration_common  # next to this file
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import DeleteModel, GetPhysicsProperties, SpawnModel
from geometry_msgs.msg import Pose
from integration_common import Latest
from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix as rotation
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2

import sensors_geometry

WALL_TIMEOUT = 90.0
SCAN_TOLERANCE = 0.03   # m, lidar against the world's geometry
DEPTH_TOLERANCE = 0.02  # m, depth camera against a box's known distance

BOX_SDF = """<sdf version="1.6"><model name="box"><static>true</static><link name="link">
<collision name="c"><geometry><box><size>{s} {s} {s}</size></box></geometry></collision>
<visual name="v"><geometry><box><size>{s} {s} {s}</size></box></geometry>
<material><ambient>{rgb} 1</ambient><diffuse>{rgb} 1</diffuse></material></visual>
</link></model></sdf>"""


wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.01)


class SensorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('sensors_test')
        cls.clock = None
        cls.models = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        rospy.Subscriber('/gazebo/model_states', ModelStates, cls._on_models, queue_size=1)
        # each service it calls: the world server advertises them one after another, as Gazebo does
        for name in ('spawn_sdf_model', 'delete_model', 'get_physics_properties'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        cls.spawn = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.gravity = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)().gravity
        cls.model = urdf_reader.parse_urdf(rospy.get_param('/robot_description'))
        cls.specs = {s.type: s for s in cls.model.sensors}
        wait_for(lambda: cls.models is not None and 'racebot' in cls.models.name, 'the racebot to be spawned')
        wait_for(lambda: rospy.get_param('/racebot/joint_state_controller/type', None), 'the controller config')
        cls.sim_sleep_until(2.0)  # the car settles on its wheels

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    @classmethod
    def _on_models(cls, msg):
        cls.models = msg

    @classmethod
    def sim_sleep_until(cls, t):
        wait_for(lambda: cls.clock is not None and cls.clock >= t, 'sim time %.1f s' % t)

    def sim_now(self):
        return wait_for(lambda: self.clock, '/clock')

    def car_pose(self):
        i = self.models.name.index('racebot')
        p, q = self.models.pose[i].position, self.models.pose[i].orientation
        return np.array([p.x, p.y, p.z]), (q.x, q.y, q.z, q.w)

    def sensor_pose(self, spec):
        """World pose of a sensor: car pose, the fixed joints to the sensor's link, its <pose>."""
        position, q = self.car_pose()
        link = self.model.lumped_link(spec.reference)
        self.assertEqual(link, self.model.root_link, 'the sensor links hang on fixed joints from the root')
        offset = rotations.compose(self.model.pose_in_lumped_link(spec.reference), spec.pose)
        p, o = rotations.compose((tuple(position), q), offset)
        return np.array(p), o

    def latest(self, topic, cls):
        """A Latest for this test only: its subscription (and so the sensor's work) ends with it."""
        latest = Latest(topic, cls)
        self.addCleanup(latest.sub.unregister)
        return latest

    def add_box(self, name, xyz, size, rgb):
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = xyz
        pose.orientation.w = 1.0
        res = self.spawn(name, BOX_SDF.format(s=size, rgb=rgb), '', pose, 'world')
        self.assertTrue(res.success, res.status_message)
        self.addCleanup(self.delete, name)

    # -- lidar ------------------------------------------------------------------------------
    def test_1_scan_matches_the_room_geometry(self):
        scans = self.latest('/scan', LaserScan)
        scan = scans.after(self.sim_now() + 0.1, 'a /scan')
        ray = self.specs['ray'].ray
        self.assertEqual(len(scan.ranges), ray.samples)
        self.assertEqual(scan.header.frame_id, 'lidar')
        self.assertAlmostEqual(scan.angle_min, ray.min_angle, places=6)
        self.assertAlmostEqual(scan.angle_max, ray.max_angle, places=6)
        self.assertAlmostEqual(scan.angle_increment, (ray.max_angle - ray.min_angle) / (ray.samples - 1), places=8)
        self.assertEqual((scan.range_min, scan.range_max), (np.float32(ray.range_min), np.float32(ray.range_max)))
        position, q = self.sensor_pose(self.specs['ray'])
        yaw = rotations.quaternion_to_rpy(q)[2]
        expected = sensors_geometry.expected_scan(rospy.get_param('~world'), position, yaw, scan.angle_min,
                                                  scan.angle_increment, len(scan.ranges))
        checked, bad = sensors_geometry.compare(scan.ranges, expected, scan.range_min, scan.range_max,
                                                SCAN_TOLERANCE)
        self.assertGreater(checked, 0.95 * len(scan.ranges))
        self.assertFalse(bad, 'beams off the geometry by more than %g m (index, measured, expected): %s'
                         % (SCAN_TOLERANCE, bad[:10]))
        finite = np.isfinite(scan.ranges)
        self.assertGreater(finite.sum(), 1000, 'the room walls are all within 10 m')

    # -- IMU --------------------------------------------------------------------------------
    def test_2_imu_at_rest_reads_gravity_and_no_rotation(self):
        samples = []
        sub = rospy.Subscriber('/imu', Imu, samples.append, queue_size=200)
        start = self.sim_now()
        self.sim_sleep_until(start + 1.0)
        sub.unregister()
        self.assertGreater(len(samples), 50)
        self.assertEqual(samples[-1].header.frame_id, 'imu')
        acc = np.array([[m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z] for m in samples])
        gyro = np.array([[m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z] for m in samples])
        g = math.sqrt(self.gravity.x ** 2 + self.gravity.y ** 2 + self.gravity.z ** 2)
        self.assertAlmostEqual(acc[:, 2].mean(), g, delta=0.05)
        self.assertLess(np.abs(acc[:, :2].mean(axis=0)).max(), 0.05)
        self.assertLess(np.abs(gyro).max(), 0.02)
        o = samples[-1].orientation
        self.assertAlmostEqual(abs(o.w), 1.0, delta=0.01)

    # -- camera -----------------------------------------------------------------------------
    def test_3_camera_sees_a_red_box_where_the_pinhole_model_says(self):
        spec = self.specs['camera']
        images = self.latest('/rrbot/camera1/image_raw', Image)
        infos = self.latest('/rrbot/camera1/camera_info', CameraInfo)
        target = np.array([1.2, 0.25, 0.12])
        self.add_box('red_box', target, 0.1, '1 0 0')
        t = self.sim_now() + 0.1
        img = images.after(t, 'a camera image with the box')
        info = infos.after(t, 'camera_info')
        cam = spec.camera
        self.assertEqual((img.width, img.height, img.encoding), (cam.width, cam.height, 'rgb8'))
        self.assertEqual(img.step, 3 * cam.width)
        self.assertEqual(img.header.frame_id, 'camera')
        self.assertEqual((info.width, info.height, info.header.frame_id), (cam.width, cam.height, 'camera'))
        f = cam.width / (2 * math.tan(cam.horizontal_fov / 2))
        self.assertAlmostEqual(info.K[0], f, places=3)
        self.assertAlmostEqual(info.K[4], f, places=3)
        # gazebo_ros_camera_utils' principal point, one pixel off the centre of the image it renders
        self.assertAlmostEqual(info.K[2], (cam.width + 1) / 2.0, places=3)
        self.assertAlmostEqual(info.K[5], (cam.height + 1) / 2.0, places=3)
        rgb = np.frombuffer(img.data, dtype=np.uint8).reshape(img.height, img.width, 3).astype(int)
        red = (rgb[..., 0] > 120) & (rgb[..., 1] < 60) & (rgb[..., 2] < 60)
        self.assertGreater(red.sum(), 200, 'the red box is not in the image')
        vs, us = np.nonzero(red)
        position, q = self.sensor_pose(spec)
        p = rotation(q).T @ (target - position)  # sensor frame: x forward, y left, z up
        u = info.K[0] * (-p[1] / p[0]) + info.K[2]
        v = info.K[4] * (-p[2] / p[0]) + info.K[5]
        self.assertAlmostEqual(us.mean(), u, delta=8, msg='box centre column %.1f, pinhole says %.1f' % (us.mean(), u))
        self.assertAlmostEqual(vs.mean(), v, delta=15, msg='box centre row %.1f, pinhole says %.1f' % (vs.mean(), v))

    # -- depth camera -----------------------------------------------------------------------
    def test_4_depth_of_a_box_in_front_equals_its_distance(self):
        spec = self.specs['depth']
        depths = self.latest('/real_sense/depth/image_raw', Image)
        clouds = self.latest('/real_sense/depth/points', PointCloud2)
        infos = self.latest('/real_sense/depth/camera_info', CameraInfo)
        position, q = self.sensor_pose(spec)
        forward = rotation(q)[:, 0]
        distance = 1.5
        centre = position + (distance + 0.25) * forward
        self.add_box('grey_box', (centre[0], centre[1], 0.25), 0.5, '0.5 0.5 0.5')
        t = self.sim_now() + 0.1
        d = depths.after(t, 'a depth image with the box')
        cam = spec.camera
        self.assertEqual((d.width, d.height, d.encoding, d.header.frame_id),
                         (cam.width, cam.height, '32FC1', 'realsense_depth'))
        depth = np.frombuffer(d.data, dtype='<f4').reshape(d.height, d.width)
        face = depth[d.height // 2 - 5:d.height // 2 + 5, d.width // 2 - 5:d.width // 2 + 5]
        self.assertLess(np.abs(face - distance).max(), DEPTH_TOLERANCE,
                        'depth at the image centre %s, the box face is %.3f m away' % (face.mean(), distance))
        info = infos.after(t, 'depth camera_info')
        self.assertEqual((info.width, info.height), (cam.width, cam.height))
        cloud = clouds.after(t, 'a point cloud')
        self.assertEqual((cloud.width, cloud.height, cloud.header.frame_id), (cam.width, cam.height, 'realsense_depth'))
        self.assertEqual([f.name for f in cloud.fields], ['x', 'y', 'z', 'rgb'])
        pts = np.frombuffer(cloud.data, dtype=np.uint8).reshape(cloud.height, cloud.width, cloud.point_step)
        xyz = pts[:, :, :12].copy().view('<f4')
        self.assertLess(np.abs(xyz[cloud.height // 2, cloud.width // 2] - [0.0, 0.0, distance]).max(), DEPTH_TOLERANCE)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'sensors', SensorsTest)
