#!/usr/bin/env python3
"""hector_gazebo_plugins' IMU and GPS on a robot package of our own (tests/fixtures/robots/skid_steer_bot with
hector:=true, the two plugins as Husky's description declares them), launched through its world launch file
(gazebo_ros's empty_world.launch and spawn_model -robot_namespace /skid), and used as a user would: the
topics; `set_accel_bias` (hector_gazebo_plugins/SetBias) seen on the bias topic; the accelerometer's
dynamic_reconfigure server read and changed with dynamic_reconfigure's own Client (the offset shows in the
acceleration); `set_reference_geopose` (hector_gazebo_plugins/SetReferenceGeoPose) moving the fix; the GPS
status server switching the fix off.
"""
import math

import rospy
import rostest
from dynamic_reconfigure.client import Client
from geographic_msgs.msg import GeoPoint, GeoPose
from geometry_msgs.msg import Quaternion, Vector3
from hector_gazebo_plugins.srv import SetBias, SetReferenceGeoPose
from sensor_msgs.msg import Imu, NavSatFix

from fixture_robot import STARTUP_TIMEOUT, WALL_TIMEOUT, FixtureRobotTest
from integration_common import Latest

IMU, FIX = '/skid/imu/data', '/skid/navsat/fix'


class HectorPluginsTest(FixtureRobotTest):
    NODE = 'hector_plugins_test'

    @classmethod
    def start(cls):
        cls.imu = Latest(IMU, Imu)
        cls.bias = Latest(IMU + '/bias', Imu)
        cls.fix = Latest(FIX, NavSatFix)
        cls.launch_fixture('skid_steer_bot skid_steer_bot_world.launch gui:=false hector:=true', 'hector_plugins')
        cls.watch.wait(lambda: cls.imu.msg is not None and cls.fix.msg is not None, 'the IMU and the fix',
                       STARTUP_TIMEOUT)

    def test_imu_bias_service_and_reconfigure(self):
        self.assertEqual(self.imu.msg.header.frame_id, 'base_link')
        self.assertAlmostEqual(self.imu.msg.linear_acceleration.z, 9.8, delta=0.3)  # at rest: gravity up
        rospy.wait_for_service(IMU + '/set_accel_bias', WALL_TIMEOUT)
        rospy.ServiceProxy(IMU + '/set_accel_bias', SetBias)(bias=Vector3(0.0, 0.7, 0.0))
        self.wait_for(lambda: self.bias.msg and abs(self.bias.msg.linear_acceleration.y - 0.7) < 0.05,
                      'the bias topic to show the accelerometer bias set')
        client = Client(IMU + '/accel', timeout=WALL_TIMEOUT)
        config = client.get_configuration(timeout=WALL_TIMEOUT)
        self.assertAlmostEqual(config['drift'], 0.005)  # the URDF's accelDrift, the mean of its axes
        self.assertAlmostEqual(config['gaussian_noise'], 0.005)
        client.update_configuration({'offset': 2.0, 'gaussian_noise': 0.0})
        self.wait_for(lambda: abs(self.imu.msg.linear_acceleration.x - 2.0) < 0.2,
                      'the acceleration to show the offset set through dynamic_reconfigure')

    def test_gps_reference_and_status(self):
        fix = self.fix.msg
        self.assertEqual((fix.header.frame_id, fix.status.status), ('base_link', 0))
        self.assertAlmostEqual(fix.latitude, 49.9, delta=1e-5)
        rospy.wait_for_service(FIX + '/set_reference_geopose', WALL_TIMEOUT)
        yaw = math.pi / 6
        rospy.ServiceProxy(FIX + '/set_reference_geopose', SetReferenceGeoPose)(geo_pose=GeoPose(
            GeoPoint(-33.9, 151.2, 50.0), Quaternion(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))))
        self.wait_for(lambda: abs(self.fix.msg.latitude + 33.9) < 1e-4 and abs(self.fix.msg.longitude - 151.2) < 1e-4
                      and abs(self.fix.msg.altitude - 50.0) < 0.5, 'the fix at the new reference')
        Client(FIX + '/status', timeout=WALL_TIMEOUT).update_configuration({'STATUS_FIX': False})
        self.wait_for(lambda: self.fix.msg.status.status == -1, 'the fix status to say no fix')


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'hector_plugins', HectorPluginsTest)
