#!/usr/bin/env python3
"""racebot.launch itself, headless (gui:=false teleop:=false): the chapter's promises, under sim time.

- the seven controllers of racebot_control.yaml are loaded, of their types, and running;
- /racebot/joint_states at 50 Hz (header stamps, sim time) with the six joints;
- tf from base_footprint to every wheel, where the model puts it;
- `rostopic pub` style on /ackermann_cmd_mux/output: speed 0.5 for 4 s of sim time moves the car
  >= 1.8 m forward; steering 0.3 with speed 0.5 turns it left (yaw grows); speed -0.5 drives it back;
- the keyboard: keyboard_teleop in a private Xvfb, W held by xdotool, moves the car; releasing stops it;
- cmd_vel through transform moves the car (racebot_launch_yaw_rate.test: the converted mode).
Before each drive the car is stopped and put (/gazebo/set_model_state) where the room is free ahead:
its spawn point (0, 0) faces the warehouse robot 1.85 m away.
Every wait has a wall-clock limit (a stalled simulator fails the test, it does not hang it); every
duration and rate asserted is sim time.
"""
import math
import os
import subprocess
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
import tf2_ros
from ackermann_msgs.msg import AckermannDriveStamped
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetModelState, SetModelState
from geometry_msgs.msg import Twist
from sensor_msgs.msg import JointState

PKG = 'racebot_tests'
MODEL = 'racebot'
CMD_TOPIC = '/ackermann_cmd_mux/output'
CONTROLLERS = {  # racebot_control/config/racebot_control.yaml (the tutorial's)
    'joint_state_controller': 'joint_state_controller/JointStateController',
    'left_rear_wheel_velocity_controller': 'effort_controllers/JointVelocityController',
    'right_rear_wheel_velocity_controller': 'effort_controllers/JointVelocityController',
    'left_front_wheel_velocity_controller': 'effort_controllers/JointVelocityController',
    'right_front_wheel_velocity_controller': 'effort_controllers/JointVelocityController',
    'left_steering_hinge_position_controller': 'effort_controllers/JointPositionController',
    'right_steering_hinge_position_controller': 'effort_controllers/JointPositionController',
}
JOINTS = {'left_steering_hinge_joint', 'right_steering_hinge_joint', 'left_front_wheel_joint',
          'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint'}
# wheel frame -> its origin in base_footprint with the hinges straight (racecar.xacro: base_link at
# z 0.032, rear wheels at (-0.13, +-0.09), front wheels 0.025 outside the hinges at (0.13, +-0.065))
WHEELS = {'left_front_wheel': (0.13, 0.09, 0.032), 'right_front_wheel': (0.13, -0.09, 0.032),
          'left_rear_wheel': (-0.13, 0.09, 0.032), 'right_rear_wheel': (-0.13, -0.09, 0.032)}
STARTUP_TIMEOUT = 180.0  # wall s: simulator, spawn and spawner on a busy 2-core machine
SIM_STALL_TIMEOUT = 60.0  # wall s allowed per second of sim time before a wait gives up
COMMAND_PERIOD = 0.1      # sim s between repeated commands (`rostopic pub -r 10`)
WINDOW_NAME = '^racebot keyboard teleop$'


def yaw_of(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


class RacebotDriving(unittest.TestCase):
    """Helpers to place the car, command it and measure how it moved (no tests of its own)."""

    @classmethod
    def setUpClass(cls):
        rospy.init_node('racebot_launch_test')
        cls.twist_pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        cls.cmd_pub = rospy.Publisher(CMD_TOPIC, AckermannDriveStamped, queue_size=10)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.set_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)

    # -- helpers ----------------------------------------------------------------------------------
    def wait_wall(self, predicate, timeout, what):
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            if predicate():
                return
            time.sleep(0.05)
        self.fail('timed out after %g s (wall) waiting for %s' % (timeout, what))

    def sim_sleep(self, seconds, every=None, action=None):
        """Waits `seconds` of sim time (calling `action` every `every` sim s); fails if the sim stalls."""
        start = rospy.get_time()
        next_action = start
        deadline = time.time() + SIM_STALL_TIMEOUT * max(1.0, seconds)
        while rospy.get_time() - start < seconds:
            if action is not None and rospy.get_time() >= next_action:
                action()
                next_action += every
            if time.time() > deadline or rospy.is_shutdown():
                self.fail('sim time did not advance %g s within %g s (wall)'
                          % (seconds, SIM_STALL_TIMEOUT * max(1.0, seconds)))
            time.sleep(0.005)

    def wait_for_simulation(self):
        self.wait_wall(lambda: rospy.get_time() > 0.0, STARTUP_TIMEOUT, '/clock from the simulator')
        self.wait_wall(lambda: self.get_state(MODEL, '').success if self._has_service() else False,
                       STARTUP_TIMEOUT, 'model %s in the simulator' % MODEL)
        self.wait_wall(lambda: self.cmd_pub.get_num_connections() > 0, STARTUP_TIMEOUT,
                       'servo_commands to subscribe to %s' % CMD_TOPIC)
        self.wait_wall(self._controllers_running, STARTUP_TIMEOUT, 'the seven controllers running')

    def _has_service(self):
        try:
            rospy.wait_for_service('/gazebo/get_model_state', timeout=1.0)
            return True
        except rospy.ROSException:
            return False

    def list_controllers(self):
        rospy.wait_for_service('/racebot/controller_manager/list_controllers', timeout=STARTUP_TIMEOUT)
        return rospy.ServiceProxy('/racebot/controller_manager/list_controllers', ListControllers)().controller

    def _controllers_running(self):
        try:
            return {c.name for c in self.list_controllers() if c.state == 'running'} >= set(CONTROLLERS)
        except (rospy.ROSException, rospy.ServiceException):
            return False

    def command(self, speed, steering_angle=0.0):
        msg = AckermannDriveStamped()
        msg.header.stamp = rospy.Time.now()
        msg.header.frame_id = 'base_link'
        msg.drive.speed = speed
        msg.drive.steering_angle = steering_angle
        self.cmd_pub.publish(msg)

    def pose(self):
        """(x, y, yaw, sim time) of the car."""
        res = self.get_state(MODEL, '')
        self.assertTrue(res.success, res.status_message)
        p = res.pose
        return p.position.x, p.position.y, yaw_of(p.orientation), res.header.stamp.to_sec()

    def place(self, x, y, yaw):
        """Stops the car, puts it at (x, y, yaw) at rest, lets it settle; returns its pose."""
        self.wait_for_simulation()
        self.sim_sleep(0.5, COMMAND_PERIOD, lambda: self.command(0.0))
        state = ModelState()
        state.model_name = MODEL
        state.reference_frame = 'world'
        state.pose.position.x, state.pose.position.y, state.pose.position.z = x, y, 0.002
        state.pose.orientation.z, state.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
        res = self.set_state(state)
        self.assertTrue(res.success, res.status_message)
        self.sim_sleep(1.0, COMMAND_PERIOD, lambda: self.command(0.0))
        start = self.pose()
        self.assertLess(math.hypot(start[0] - x, start[1] - y), 0.05, 'the car did not stay where it was put')
        return start

    def drive(self, speed, steering_angle, seconds):
        """Publishes the command every 0.1 s of sim time for `seconds` of sim time; -> pose at the end."""
        self.sim_sleep(seconds, COMMAND_PERIOD, lambda: self.command(speed, steering_angle))
        end = self.pose()
        self.command(0.0)
        return end

    @staticmethod
    def moved(start, end):
        """(forward, left, yaw change) of `end` in the frame of `start`."""
        dx, dy = end[0] - start[0], end[1] - start[1]
        c, s = math.cos(start[2]), math.sin(start[2])
        result = c * dx + s * dy, -s * dx + c * dy, wrap(end[2] - start[2])
        print('moved %.3f m forward, %.3f m left, turned %.3f rad in %.2f s of sim time'
              % (result + (end[3] - start[3],)), flush=True)
        return result


class CmdVelDrive:
    """cmd_vel through transform moves the car: linear.x 0.5, angular.z 0.3 for 3 s of sim time.
    The yaw rate (over the last 2 s, once the car drives at its speed and angle) tells the conversion apart:
    the tutorial's transform passes angular.z through as a steering angle (0.3 rad: a bicycle turns at
    0.5 tan(0.3) / 0.26 = 0.59 rad/s, the car under parallel steering at about 0.43 rad/s); convert_yaw_rate
    turns it into the angle that gives that yaw rate (atan(0.26 * 0.3 / 0.5), so 0.3 rad/s)."""
    CONVERT_YAW_RATE = '--convert-yaw-rate' in sys.argv

    def twist(self, linear, angular):
        msg = Twist()
        msg.linear.x, msg.angular.z = linear, angular
        self.twist_pub.publish(msg)

    def test_8_cmd_vel_through_transform_moves_the_car(self):
        self.wait_wall(lambda: self.twist_pub.get_num_connections() > 0, STARTUP_TIMEOUT, 'transform on /cmd_vel')
        start = self.place(0.0, 0.0, 0.0)
        # the yaw rate is read over the last 2 s: the first second holds the commands' way through the transform
        # and the mux (later in sim time under load), the steering's travel and the car's speeding up
        self.sim_sleep(1.0, COMMAND_PERIOD, lambda: self.twist(0.5, 0.3))
        steady = self.pose()
        self.sim_sleep(2.0, COMMAND_PERIOD, lambda: self.twist(0.5, 0.3))
        end = self.pose()
        self.twist(0.0, 0.0)
        forward, left, _ = self.moved(start, end)
        rate = self.moved(steady, end)[2] / (end[3] - steady[3])
        self.assertGreater(forward, 0.3, 'cmd_vel 0.5 m/s: the car moved %.2f m forward' % forward)
        self.assertGreater(left, 0.1, 'cmd_vel angular.z 0.3 (left): the car moved %.2f m to its left' % left)
        if self.CONVERT_YAW_RATE:
            self.assertAlmostEqual(rate, 0.3, delta=0.06, msg='convert_yaw_rate: yaw rate %.3f rad/s, asked 0.3' % rate)
        else:  # the tutorial's angle 0.3 under parallel steering, which understeers (see make bench): 0.43 rad/s
            # where a bicycle would turn at 0.59; the bound lies halfway between it and convert_yaw_rate's 0.3
            self.assertGreater(rate, 0.37, 'tutorial transform: yaw rate %.3f rad/s, a 0.3 rad angle gives '
                                           '~0.43 here (convert_yaw_rate would give 0.3)' % rate)


class RacebotLaunchTest(CmdVelDrive, RacebotDriving):
    # -- tests ------------------------------------------------------------------------------------
    def test_1_seven_controllers_running(self):
        self.wait_for_simulation()
        found = {c.name: c for c in self.list_controllers()}
        self.assertEqual(set(found), set(CONTROLLERS))
        for name, kind in CONTROLLERS.items():
            self.assertEqual(found[name].state, 'running', name)
            self.assertEqual(found[name].type, kind, name)

    def test_2_joint_states_at_50_hz(self):
        self.wait_for_simulation()
        stamps, names = [], []
        lock = threading.Lock()

        def on_joint_states(msg):
            with lock:
                stamps.append(msg.header.stamp.to_sec())
                names.append(set(msg.name))
        sub = rospy.Subscriber('/racebot/joint_states', JointState, on_joint_states, queue_size=200)
        try:
            self.sim_sleep(3.0)
        finally:
            sub.unregister()
        with lock:
            stamps, names = list(stamps), list(names)
        self.assertGreater(len(stamps), 50, 'only %d joint_states in 3 s of sim time' % len(stamps))
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        self.assertAlmostEqual(rate, 50.0, delta=2.0, msg='joint_states at %.1f Hz (sim time)' % rate)
        self.assertTrue(all(n == JOINTS for n in names), 'joint names: %r' % names[0])

    def test_3_tf_from_base_footprint_to_every_wheel(self):
        self.place(0.0, 0.0, 0.0)
        buf = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buf)  # noqa: F841 (keeps the subscription alive)
        for wheel, expected in sorted(WHEELS.items()):
            self.wait_wall(lambda: buf.can_transform('base_footprint', wheel, rospy.Time(0)), 60.0,
                           'tf base_footprint -> %s' % wheel)
            t = buf.lookup_transform('base_footprint', wheel, rospy.Time(0)).transform.translation
            for got, want, axis in zip((t.x, t.y, t.z), expected, 'xyz'):
                self.assertAlmostEqual(got, want, delta=0.01, msg='%s %s: %.4f, expected %.3f'
                                       % (wheel, axis, got, want))

    def test_4_speed_0_5_for_4_s_moves_1_8_m_forward(self):
        start = self.place(-1.0, 0.0, 0.0)  # 2.85 m of free floor ahead
        forward, left, turned = self.moved(start, self.drive(0.5, 0.0, 4.0))
        self.assertGreaterEqual(forward, 1.8, 'speed 0.5 for 4 s: %.2f m forward' % forward)
        self.assertLess(forward, 2.3, 'speed 0.5 for 4 s: %.2f m forward, faster than commanded' % forward)
        self.assertLess(abs(left), 0.2, 'drifted %.2f m sideways' % left)
        self.assertLess(abs(turned), 0.15, 'turned %.2f rad driving straight' % turned)

    def test_5_steering_0_3_turns_left(self):
        start = self.place(0.0, 0.0, 0.0)
        mid = self.drive(0.5, 0.3, 1.5)
        end = self.drive(0.5, 0.3, 1.5)
        _, _, turned_mid = self.moved(start, mid)
        forward, left, turned = self.moved(start, end)
        # a bicycle with wheelbase 0.26 m: yaw rate 0.5 * tan(0.3) / 0.26 = 0.59 rad/s, 1.8 rad in 3 s
        self.assertGreater(turned_mid, 0.3, 'steering 0.3: yaw changed %.2f rad in 1.5 s' % turned_mid)
        self.assertGreater(turned, turned_mid + 0.3, 'yaw does not keep growing: %.2f then %.2f rad'
                           % (turned_mid, turned))
        self.assertGreater(left, 0.3, 'steering 0.3 (left) moved the car %.2f m to its left' % left)
        self.assertGreater(forward, 0.3)

    def test_6_speed_minus_0_5_drives_backwards(self):
        start = self.place(0.0, 0.0, 0.0)  # 8 m of free floor behind
        forward, left, turned = self.moved(start, self.drive(-0.5, 0.0, 4.0))
        self.assertLessEqual(forward, -1.8, 'speed -0.5 for 4 s: %.2f m (negative is backwards)' % forward)
        self.assertLess(abs(turned), 0.15, 'turned %.2f rad reversing straight' % turned)

    def test_7_keyboard_w_moves_the_car_release_stops_it(self):
        """keyboard_teleop (with racebot.launch's parameters) in a private Xvfb; W held by xdotool."""
        from keyboard_teleop_xvfb import start_xvfb, stop_xvfb  # next to this file
        start = self.place(-1.0, 0.0, 0.0)
        xvfb, display = start_xvfb()
        env = dict(os.environ, DISPLAY=display)

        def x(*args, timeout=60.0):
            return subprocess.run(list(args), env=env, capture_output=True, text=True, timeout=timeout)
        teleop = subprocess.Popen(['rosrun', 'racebot_gazebo', 'keyboard_teleop.py'], env=env)
        try:
            found = x('xdotool', 'search', '--sync', '--name', WINDOW_NAME).stdout.split()
            self.assertTrue(found, 'no keyboard window')
            self.wait_wall(lambda: '/keyboard_teleop' in self._publishers(CMD_TOPIC), 60.0,
                           'keyboard_teleop to advertise %s' % CMD_TOPIC)
            self.assertEqual(x('xdotool', 'windowfocus', '--sync', found[0]).returncode, 0)
            time.sleep(1.0)
            x('xdotool', 'keydown', 'w')
            self.sim_sleep(3.0)
            x('xdotool', 'keyup', 'w')
            held = self.pose()
            self.sim_sleep(1.5)
            rest = self.pose()
            self.sim_sleep(1.0)
            still = self.pose()
            x('xdotool', 'key', 'q')
            teleop.wait(30)
        finally:
            if teleop.poll() is None:
                teleop.kill()
                teleop.wait(10)
            stop_xvfb(xvfb)
        forward, _, _ = self.moved(start, held)
        self.assertGreater(forward, 0.9, 'W held for 3 s of sim time: the car moved %.2f m' % forward)
        coast = math.hypot(still[0] - rest[0], still[1] - rest[1])
        self.assertLess(coast, 0.05, 'after W was released the car still moved %.2f m in 1 s' % coast)

    @staticmethod
    def _publishers(topic):
        """Names of the nodes publishing `topic` (from the master)."""
        state = rosgraph.Master(rospy.get_name()).getSystemState()
        for name, nodes in state[0]:
            if name == topic:
                return nodes
        return []


class CmdVelOnlyTest(CmdVelDrive, RacebotDriving):
    """racebot.launch with convert_yaw_rate:=true (racebot_launch_yaw_rate.test): only the cmd_vel drive."""


if __name__ == '__main__':
    if CmdVelDrive.CONVERT_YAW_RATE:
        rostest.rosrun(PKG, 'racebot_launch_yaw_rate', CmdVelOnlyTest, sys.argv)
    else:
        rostest.rosrun(PKG, 'racebot_launch', RacebotLaunchTest, sys.argv)
