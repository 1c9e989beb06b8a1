#!/usr/bin/env python3
"""The drive plugins through the topics gazebo_plugins would give, on robot packages of our own.

tests/fixtures/robots/skid_steer_bot (skid_steer_drive, p3d, joint_state_publisher; spawned with
-robot_namespace /skid, heading 0.7 rad) and planar_move_bot (planar_move, <robotNamespace>planar,
cmdTimeout 0.5) are launched in one world by one roslaunch of the skid-steer package's world launch
(empty_world.launch and its spawn) and the planar package's spawn launch (3 m to the left), started
here with tests/fixtures/robots on ROS_PACKAGE_PATH.
Ground truth is gazebo_ros's get_model_state read with physics paused, at the sim time of the /clock
that follows the pause. Motion is judged against the kinematics (racebot_sim_bridge.kinematics):
- planar move: body-frame vx, vy and wz within 5 % of the command, instantaneous and over 1 s;
- skid steer straight: speed within 5 % (no side slip when both sides turn alike); turning: each
  wheel at its side's commanded speed within 5 %, the base turning in the commanded sense and moving
  ahead, its yaw rate between 25 % and 105 % of the command. A skid-steer turn drags the wheels
  sideways, so friction, not the plugin, sets the yaw rate: below the differential formula's (the
  effective track is 1.5-2 times the wheel separation for a wheelbase/track of 0.75: 50-67 %). This
  window of this turn measured 0.398 rad/s for 0.8 (50 %) in each of 5 runs; the bound leaves half of
  it, as stick and slip make longer turns wander (0.09 to 0.5 rad/s in 0.5 s windows, measured).
Odometry, TF and p3d are compared with the ground truth at rest (poses) and while driving (twists).
"""
import math
import os

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState

from catkin_overlay import FIXTURE_ROBOTS
from fixture_robot import STARTUP_TIMEOUT, FixtureRobotTest, twist
from integration_common import Latest, yaw_of
from racebot_sim_bridge.kinematics import skid_steer
from racebot_sim_bridge.kinematics.planar import integrate, world_to_base

SKID, PLANAR = 'skid_steer_bot', 'planar_move_bot'
WHEELS = ['left_front_wheel_joint', 'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint']
WHEEL_RADIUS = 0.1
SEPARATION = 0.4
P3D_SIGMA = 0.01


class State:
    """A model's ground truth at sim time t: x, y, yaw and its world twist."""

    def __init__(self, t, res):
        p, q = res.pose.position, res.pose.orientation
        self.t, self.x, self.y, self.z, self.yaw = t, p.x, p.y, p.z, yaw_of(q)
        self.q = (q.x, q.y, q.z, q.w)
        self.linear = (res.twist.linear.x, res.twist.linear.y, res.twist.linear.z)
        self.wz = res.twist.angular.z

    def body_velocity(self):
        return world_to_base(self.linear[0], self.linear[1], self.yaw)


class DrivePluginsTest(FixtureRobotTest):
    NODE = 'drive_plugins_test'

    @classmethod
    def start(cls):
        files = [os.path.join(FIXTURE_ROBOTS, 'skid_steer_bot', 'launch', 'skid_steer_bot_world.launch'),
                 os.path.join(FIXTURE_ROBOTS, 'planar_move_bot', 'launch', 'spawn.launch')]
        cls.launch_fixture('%s gui:=false yaw:=0.7 y:=3' % ' '.join(files), 'drive_plugins')
        cls.models = Latest('/gazebo/model_states', ModelStates)
        cls.skid_odom = Latest('/skid/odom', Odometry)
        cls.ground_truth = Latest('/skid/ground_truth/state', Odometry)
        cls.joint_states = Latest('/skid/joint_states', JointState)
        cls.planar_odom = Latest('/planar/odom', Odometry)
        cls.collect_tf()
        cls.skid = cls.driver('/skid/cmd_vel')
        cls.planar = cls.driver('/planar/cmd_vel')
        cls.watch.wait(lambda: cls.models.msg is not None and {SKID, PLANAR} <= set(cls.models.msg.name),
                       'both robots to be spawned', STARTUP_TIMEOUT)
        cls.gazebo_services()

    def snapshot(self, model):
        """Ground truth of `model` with physics paused."""
        t, res = self.paused(lambda: self.get_state(model, ''))
        return State(t, res)

    def check_wheels(self, expected):
        """joint_state_publisher's latest message: the named joints in order, at these velocities (5 %)."""
        count = self.joint_states.count
        js = self.wait_for(lambda: self.joint_states.count > count and self.joint_states.msg, 'joint_states')
        self.assertEqual(list(js.name), WHEELS)
        for name, v, e in zip(js.name, js.velocity, expected):
            self.assertClose(v, e, 0.05 * abs(e), '%s velocity' % name)

    # -- planar move ---------------------------------------------------------------------------
    def test_1_planar_move_follows_cmd_vel_in_its_own_axes(self):
        command = (0.3, 0.2, 0.5)
        self.planar.command = twist(*command)
        self.wait_for(lambda: self.planar_odom.msg and self.planar_odom.msg.twist.twist.angular.z > 0.4,
                      'the planar base to turn')
        a = self.snapshot(PLANAR)
        self.sim_wait(1.0)
        b = self.snapshot(PLANAR)
        vx, vy = b.body_velocity()
        rospy.loginfo('planar move: truth vx %.4f vy %.4f wz %.4f for (0.3, 0.2, 0.5); over %.2f s yaw rate %.4f',
                      vx, vy, b.wz, b.t - a.t, (b.yaw - a.yaw) / (b.t - a.t))
        for value, expected, what in ((vx, command[0], 'vx'), (vy, command[1], 'vy'), (b.wz, command[2], 'wz')):
            self.assertClose(value, expected, 0.05 * abs(expected), 'ground-truth %s in the robot frame' % what)
        dt = b.t - a.t
        self.assertClose((b.yaw - a.yaw) / dt, command[2], 0.05 * command[2], 'mean yaw rate over %.2f s' % dt)
        x, y, _ = integrate((a.x, a.y, a.yaw), command, dt)
        travelled = math.hypot(command[0], command[1]) * dt
        self.assertLessEqual(math.hypot(b.x - x, b.y - y), 0.05 * travelled,
                             'end of the arc: (%.3f, %.3f), kinematics (%.3f, %.3f)' % (b.x, b.y, x, y))
        odom = self.planar_odom.msg
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('planar_odom', 'planar_base'))
        self.assertClose(odom.twist.twist.linear.x, command[0], 0.05 * command[0], 'odometry vx')
        self.assertClose(odom.twist.twist.linear.y, command[1], 0.05 * command[1], 'odometry vy')
        self.assertClose(odom.twist.twist.angular.z, command[2], 0.05 * command[2], 'odometry wz')
        self.assertEqual(odom.pose.covariance[0], 1e-5)
        # cmdTimeout 0.5: with no more commands the base stops; its odometry and TF then equal the truth
        self.planar.command = None
        self.sim_wait(0.6)
        self.wait_for(lambda: abs(self.planar_odom.msg.twist.twist.linear.x) < 1e-3, 'the planar base to stop')
        count = self.planar_odom.count
        self.wait_for(lambda: self.planar_odom.count > count, 'odometry at rest')
        rest = self.snapshot(PLANAR)
        self.assertLess(math.hypot(*rest.linear[:2]), 1e-3, 'the base still moves after cmdTimeout')
        pose = self.planar_odom.msg.pose.pose
        self.assertClose(pose.position.x, rest.x, 1e-3, 'odometry x')
        self.assertClose(pose.position.y, rest.y, 1e-3, 'odometry y')
        self.assertClose(yaw_of(pose.orientation), rest.yaw, 1e-3, 'odometry yaw')
        tf = self.wait_for(lambda: self.tf.get(('planar_odom', 'planar_base')), 'TF planar_odom -> planar_base')
        self.assertClose(tf.transform.translation.x, rest.x, 1e-3, 'TF x')
        self.assertClose(tf.transform.translation.y, rest.y, 1e-3, 'TF y')

    # -- skid steer, p3d, joint_state_publisher -------------------------------------------------
    def test_2_skid_steer_turns_drives_and_reports(self):
        # a left turn
        turn = (0.2, 0.8)
        self.skid.command = twist(turn[0], 0.0, turn[1])
        self.wait_for(lambda: self.skid_odom.msg and self.skid_odom.msg.twist.twist.angular.z > 0.1,
                      'the skid base to turn')
        self.sim_wait(0.3)
        a = self.snapshot(SKID)
        self.sim_wait(1.0)
        b = self.snapshot(SKID)
        dt = b.t - a.t
        rate = (b.yaw - a.yaw) / dt
        rospy.loginfo('skid steer turn: yaw rate %.4f rad/s over %.2f s for %.2f commanded', rate, dt, turn[1])
        self.assertGreater(rate, 0.25 * turn[1], 'yaw rate %.3f rad/s for a commanded %.2f' % (rate, turn[1]))
        self.assertLess(rate, 1.05 * turn[1], 'yaw rate %.3f rad/s for a commanded %.2f' % (rate, turn[1]))
        ahead = world_to_base(b.x - a.x, b.y - a.y, a.yaw)[0]
        self.assertGreater(ahead, 0.0, 'the base went backwards while turning')
        left, right = skid_steer.side_speeds(turn[0], turn[1], SEPARATION)
        self.check_wheels((left / WHEEL_RADIUS, right / WHEEL_RADIUS) * 2)
        # straight ahead, heading more than 0.7 rad from the world's x axis
        speed = 0.4
        self.skid.command = twist(speed, 0.0, 0.0)
        self.wait_for(lambda: abs(self.skid_odom.msg.twist.twist.angular.z) < 0.02
                      and self.skid_odom.msg.twist.twist.linear.x > 0.95 * speed, 'the skid base to drive straight')
        c = self.snapshot(SKID)
        self.sim_wait(1.0)
        d = self.snapshot(SKID)
        dt = d.t - c.t
        rospy.loginfo('skid steer straight: mean speed %.4f m/s over %.2f s for %.2f commanded',
                      math.hypot(d.x - c.x, d.y - c.y) / dt, dt, speed)
        self.assertClose(math.hypot(d.x - c.x, d.y - c.y) / dt, speed, 0.05 * speed, 'mean speed over %.2f s' % dt)
        self.assertClose(math.atan2(d.y - c.y, d.x - c.x), c.yaw, 0.05, 'direction of travel against the heading')
        self.assertGreater(abs(d.yaw), 0.5, 'the heading is too near the x axis to tell frames apart')
        odom = self.skid_odom.msg
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('odom', 'base_link'))
        self.assertClose(odom.twist.twist.linear.x, speed, 0.05 * speed, 'odometry vx (robot frame)')
        self.assertClose(odom.twist.twist.linear.y, 0.0, 0.02, 'odometry vy (robot frame)')
        self.assertEqual(list(odom.pose.covariance[0:36:7]), [1e-4, 1e-4, 1e12, 1e12, 1e12, 0.01])
        # p3d: world-frame velocities (not the robot's axes), noise of sigma 0.01
        truth = self.ground_truth.msg
        self.assertEqual((truth.header.frame_id, truth.child_frame_id), ('world', 'base_link'))
        noise = 5 * P3D_SIGMA + 0.01
        self.assertClose(truth.twist.twist.linear.x, d.linear[0], noise, 'p3d world vx')
        self.assertClose(truth.twist.twist.linear.y, d.linear[1], noise, 'p3d world vy')
        self.assertClose(truth.pose.covariance[0], P3D_SIGMA ** 2, 1e-12, 'p3d covariance')
        # joint_state_publisher: the named joints, in order, turning at speed / radius
        self.check_wheels([speed / WHEEL_RADIUS] * 4)
        # at rest: odometry, TF and p3d poses equal the ground truth
        self.skid.command = twist(0.0, 0.0, 0.0)
        self.wait_for(lambda: abs(self.skid_odom.msg.twist.twist.linear.x) < 0.002, 'the skid base to stop')
        self.sim_wait(0.2)
        rest = self.snapshot(SKID)
        for what, msg in (('odometry', self.skid_odom.msg), ('p3d', self.ground_truth.msg)):
            p = msg.pose.pose
            self.assertClose(p.position.x, rest.x, 2e-3, '%s x' % what)
            self.assertClose(p.position.y, rest.y, 2e-3, '%s y' % what)
            self.assertClose(yaw_of(p.orientation), rest.yaw, 2e-3, '%s yaw' % what)
        self.assertClose(self.ground_truth.msg.pose.pose.position.z, rest.z, 2e-3, 'p3d z')
        self.assertEqual(self.skid_odom.msg.pose.pose.position.z, 0.0)  # upstream leaves it 0
        tf = self.wait_for(lambda: self.tf.get(('odom', 'base_link')), 'TF odom -> base_link')
        self.assertClose(tf.transform.translation.x, rest.x, 2e-3, 'TF x')
        self.assertClose(tf.transform.translation.z, rest.z, 2e-3, 'TF z')  # the TF has it


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'drive_plugins', DrivePluginsTest)
