#!/usr/bin/env python3
"""Faults while the car drives: a node killed and respawned, the spawner killed, resets, pauses.

  servo_commands killed (SIGKILL) mid-drive -> the controllers keep its last command, roslaunch
      respawns it (respawn="true"), the car follows the new node's commands;
  the spawner killed (SIGINT)    -> it stops and unloads its controllers, as ros_control's does; a
      new spawner loads and starts them again;
  reset_world / reset_simulation mid-drive -> the car at its spawn pose, time going on / back to 0,
      and ros_control left as it was, as gazebo_ros_control leaves it (its Reset() only sets its
      last update time to 0): every controller still running with its command and PID state (the
      left rear wheel's PID has an integral gain here, wound up before the reset: its integral term
      is still there after it), so the car drives off again with no new command; after
      reset_simulation, joint_state_controller says nothing until sim time passes the time it last
      published (its next publish time is not reset: gazebo_ros_pkgs issue #1368);
  pause / unpause under load (sensors subscribed, driving) -> sim time and the car frozen while
      paused, then going on with the same speed and a control period of one step (no catch-up).
"""
import math
import os
import signal
import threading
import time
import unittest

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import ListControllers
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Image, Imu, JointState, LaserScan
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from robustness_common import WALL_TIMEOUT, Rosout, SimProbe, node_pid, pid_alive, rosrun, wait_for, yaw_of

CM = '/racebot/controller_manager/'
CONTROLLERS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller',
               'joint_state_controller']
PID_WHEEL = 'left_rear_wheel_velocity_controller'  # given i: 5, i_clamp: 5 by faults.test
I_CLAMP = 5.0
CONTROL_PERIOD = 0.001
SENSOR_TYPES = {'sensor_msgs/LaserScan': LaserScan, 'sensor_msgs/Imu': Imu, 'sensor_msgs/Image': Image}


def sensor_topics():
    """The simulator's sensor topics that exist (laser, IMU, images): {topic: message class}."""
    return {t: SENSOR_TYPES[kind] for t, kind in rospy.get_published_topics() if kind in SENSOR_TYPES}


class FaultsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('faults_test')
        cls.rosout = Rosout()
        cls.sim = SimProbe()
        cls.lock = threading.Lock()
        cls.pid_states = []  # (stamp, effort, time_step, i gain, set point, integral term) of PID_WHEEL's state topic
        cls.joint_stamps = []
        cls.sensor_stamps = {}
        cls.processes = []
        rospy.Subscriber('/racebot/%s/state' % PID_WHEEL, JointControllerState, cls._on_pid_state, queue_size=100)
        rospy.Subscriber('/racebot/joint_states', JointState, cls._on_joints, queue_size=100)
        cls.ackermann = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=10)
        cls.wheel_cmd = rospy.Publisher('/racebot/%s/command' % PID_WHEEL, Float64, queue_size=10)
        cls.sim.wait_ready()
        rospy.wait_for_service(CM + 'list_controllers', timeout=WALL_TIMEOUT)
        cls.list_controllers = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)
        cls.reset_world = rospy.ServiceProxy('/gazebo/reset_world', Empty)
        cls.reset_simulation = rospy.ServiceProxy('/gazebo/reset_simulation', Empty)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        wait_for(lambda: cls.running() == set(CONTROLLERS), 'the seven controllers to run')
        wait_for(lambda: cls.ackermann.get_num_connections() > 0, 'servo_commands to subscribe')
        wait_for(lambda: cls.wheel_cmd.get_num_connections() > 0, 'the wheel controller to subscribe')
        wait_for(lambda: cls.pid_states, 'the state of %s' % PID_WHEEL)
        assert cls.pid_states[-1][3] == 5.0, 'faults.test must give %s an i gain of 5' % PID_WHEEL

    @classmethod
    def tearDownClass(cls):
        for p in cls.processes:
            p.stop()

    @classmethod
    def _on_pid_state(cls, msg):
        with cls.lock:
            cls.pid_states.append((msg.header.stamp.to_sec(), msg.command, msg.time_step, msg.i, msg.set_point,
                                   msg.command - msg.p * msg.error))  # the last: the PID's integral term

    @classmethod
    def _on_joints(cls, msg):
        with cls.lock:
            cls.joint_stamps.append(msg.header.stamp.to_sec())

    @classmethod
    def running(cls):
        return {c.name for c in cls.list_controllers().controller if c.state == 'running'}

    def tearDown(self):
        self.hold_drive(0.0, 0.0, 0.2)

    # -- helpers ------------------------------------------------------------------------------
    def drive(self, speed, steering):
        msg = AckermannDriveStamped()
        msg.drive.speed, msg.drive.steering_angle = speed, steering
        self.ackermann.publish(msg)

    def hold_drive(self, speed, steering, sim_seconds):
        """The command again every 0.1 s of wall time for `sim_seconds` of sim time."""
        start = wait_for(lambda: self.sim.clock is not None, '/clock') and self.sim.clock

        def again():
            self.drive(speed, steering)
            return self.sim.clock >= start + sim_seconds
        wait_for(again, '%g s of sim time' % sim_seconds, period=0.1)

    def forward_speed(self):
        """The car's speed along its heading [m/s]."""
        res = self.sim.state()
        self.assertTrue(res.success, res.status_message)
        yaw = yaw_of(res.pose.orientation)
        v = res.twist.linear
        return v.x * math.cos(yaw) + v.y * math.sin(yaw)

    def pose(self):
        p = self.sim.state().pose
        return p.position.x, p.position.y, yaw_of(p.orientation)

    def pid_states_after(self, t, since=0):
        """The states stamped after sim time t, of those received from index `since` on."""
        with self.lock:
            return [s for s in self.pid_states[since:] if s[0] > t]

    def wind_up(self):
        """Drive the PID wheel far beyond what it can reach: its integral term saturates at i_clamp."""
        start = self.sim.clock

        def wound():  # i * error saturates the i term within milliseconds; 0.3 s makes sure
            self.wheel_cmd.publish(Float64(300.0))
            states = self.pid_states_after(start + 0.3)
            return states and states[-1][1] >= I_CLAMP
        wait_for(wound, 'the integral term of %s to wind up' % PID_WHEEL, period=0.1)
        return self.pid_states_after(start)[-1]

    def after_reset(self):
        """(index into pid_states, sim time) from which on everything is after a reset that just returned."""
        time.sleep(0.1)  # a /clock or state message from before the reset, still in flight, arrives
        with self.lock:
            return len(self.pid_states), self.sim.clock

    def assert_windup_kept_after(self, index, t_reset):
        """The PID wheel right after a reset: the same set point, and its integral term still at the
        clamp (gazebo_ros_control restarts nothing), so its effort is at least that."""
        def first():
            with self.lock:
                return next((st for st in self.pid_states[index:] if st[0] >= t_reset), None)
        state = wait_for(first, 'a PID state after the reset')
        self.assertEqual(state[4], 300.0, 'the wheel command must stay in force across the reset')
        self.assertAlmostEqual(state[5], I_CLAMP, delta=1e-6, msg='the integral term right after the reset is '
                               '%.3f: it was wound up to %g, and nothing clears it' % (state[5], I_CLAMP))

    def reset_paused(self, reset):
        """`reset` (a reset service) with physics paused, the car's pose read at the spawn pose, then
        unpaused. The commands stay in force across a reset, so a running car drives off again at once:
        read unpaused, the pose depends on how much sim time a loaded machine lets pass first."""
        self.pause()
        try:
            reset()
            x, y, _ = self.pose()
            self.assertLess(math.hypot(x, y), 0.01, 'the car is not at its spawn pose after the reset')
        finally:
            self.unpause()

    def assert_driving_off(self):
        """Moving away from the spawn pose with no new command."""
        wait_for(lambda: math.hypot(*self.pose()[:2]) > 0.1,
                 'the car to drive off again with its commands still in force')

    # -- faults ---------------------------------------------------------------------------------
    def test_1_servo_commands_killed_mid_drive_keeps_the_last_command_then_follows_the_respawned_node(self):
        self.hold_drive(0.4, 0.0, 1.5)
        self.assertGreater(self.forward_speed(), 0.3)
        old = node_pid('/servo_commands')
        self.assertIsNotNone(old)
        os.kill(old, signal.SIGKILL)
        wait_for(lambda: not pid_alive(old), 'servo_commands to die')
        # Nobody commands now: the controllers keep servo_commands' last command.
        for _ in range(2):
            self.sim.sim_sleep(0.5)
            self.assertGreater(self.forward_speed(), 0.3, 'the car must keep its last command')
        new = wait_for(lambda: (node_pid('/servo_commands') or old) != old and node_pid('/servo_commands'),
                       'roslaunch to respawn servo_commands')
        self.assertNotEqual(new, old)
        self.rosout.find('servo_commands: parallel steering', node='/servo_commands')

        def reversing():
            self.drive(-0.3, 0.0)
            return self.forward_speed() < -0.2
        wait_for(reversing, 'the car to follow the respawned servo_commands (reverse)', period=0.1)
        self.hold_drive(0.0, 0.0, 0.5)
        self.sim.assert_serving(self)
        self.reset_world()

    def test_2_reset_world_mid_drive(self):
        self.hold_drive(0.4, 0.3, 1.0)
        wound = self.wind_up()
        self.assertGreaterEqual(wound[1], I_CLAMP)
        before = self.sim.clock
        self.reset_paused(self.reset_world)
        index, t_reset = self.after_reset()
        self.assertGreaterEqual(t_reset, before, 'reset_world must not send time back')
        self.assertEqual(self.running(), set(CONTROLLERS), 'controllers must keep running after reset_world')
        self.assert_windup_kept_after(index, t_reset)
        self.assert_driving_off()
        self.hold_drive(0.3, 0.0, 1.0)  # the controllers still follow new commands
        self.assertGreater(self.forward_speed(), 0.2)
        self.hold_drive(0.0, 0.0, 1.0)
        self.reset_world()

    def test_3_reset_simulation_mid_drive(self):
        self.hold_drive(0.4, -0.3, 1.0)
        self.wind_up()
        before = self.sim.clock
        self.assertGreater(before, 2.0)
        self.reset_paused(self.reset_simulation)
        index, _ = self.after_reset()
        back = wait_for(lambda: self.sim.clock < before and self.sim.clock, 'time to go back to 0')
        self.assertLess(back, 1.0)
        self.assertEqual(self.running(), set(CONTROLLERS), 'controllers must keep running after reset_simulation')
        with self.lock:
            joints_mark = len(self.joint_stamps)
        self.assert_windup_kept_after(index, 0.0)  # stamps of the new time line, from 0
        self.assert_driving_off()
        # joint_state_controller was not restarted: silent until sim time passes its last publish time,
        # then publishing again
        self.sim.sim_sleep(0.5)
        with self.lock:
            self.assertEqual(self.joint_stamps[joints_mark:], [], 'joint_states after reset_simulation, before '
                             'sim time caught up: joint_state_controller was restarted')
        wait_for(lambda: self.joint_stamps[-1] > before, 'joint_states again once sim time passed %.2f s' % before)
        self.hold_drive(0.0, 0.0, 1.0)
        self.reset_world()

    def test_4_pause_and_unpause_under_load(self):
        topics = sensor_topics()
        self.sensor_stamps.update({t: [] for t in topics})
        subs = [rospy.Subscriber(t, cls, lambda m, t=t: self.sensor_stamps[t].append(m.header.stamp.to_sec()),
                                 queue_size=5) for t, cls in topics.items()]
        try:
            wait_for(lambda: all(self.sensor_stamps.values()), 'a message on each sensor topic %s' % list(topics))
            self.hold_drive(0.4, 0.2, 1.0)
            for _ in range(3):
                speed = self.forward_speed()
                self.pause()
                time.sleep(0.5)  # what was in flight arrives
                clock, pose = self.sim.clock, self.pose()
                with self.lock:  # states kept from before test_3's reset_simulation can be stamped later
                    mark = len(self.pid_states)
                time.sleep(1.5)  # wall time: nothing may move
                self.assertEqual(self.sim.clock, clock, '/clock advanced while paused')
                for a, b in zip(pose, self.pose()):
                    self.assertAlmostEqual(a, b, places=6)
                for topic, stamps in self.sensor_stamps.items():
                    self.assertLessEqual(stamps[-1], clock + 1e-6, '%s published a stamp after the pause' % topic)
                self.unpause()
                self.sim.sim_sleep(0.2)
                self.assertAlmostEqual(self.forward_speed(), speed, delta=0.15,
                                       msg='the speed jumped across pause/unpause')
                steps = [s[2] for s in self.pid_states_after(clock, since=mark)]
                self.assertTrue(steps)
                self.assertAlmostEqual(max(steps), CONTROL_PERIOD, delta=1e-6,
                                       msg='a control period longer than one step after unpause: %r' % max(steps))
                self.drive(0.4, 0.2)
            self.assertEqual(self.running(), set(CONTROLLERS))
            self.sim.assert_serving(self)
            self.sim.assert_state_finite(self)
        finally:
            for s in subs:
                s.unregister()
        self.reset_world()

    def test_5_spawner_killed_unloads_its_controllers_and_a_new_spawner_starts_them(self):
        mark = self.rosout.mark()
        pid = node_pid('/racebot/controller_manager')
        self.assertIsNotNone(pid, 'the spawner node /racebot/controller_manager is not running')
        os.kill(pid, signal.SIGINT)
        wait_for(lambda: not pid_alive(pid), 'the spawner to exit')
        wait_for(lambda: not self.list_controllers().controller, 'the controllers to be unloaded')
        self.rosout.find('Stopping and unloading controllers', since=mark)
        for name in CONTROLLERS:
            self.rosout.find("Unloaded '%s'" % name, since=mark)
        self.sim.assert_serving(self)
        spawner = rosrun('controller_manager', 'spawner', *(CONTROLLERS + ['__ns:=/racebot', '__name:=spawner_again']))
        self.processes.append(spawner)
        wait_for(lambda: self.running() == set(CONTROLLERS), 'a new spawner to start the seven controllers')
        self.assertFalse(self.rosout.matching('Controller Spawner', level=Log.ERROR, since=mark))
        wait_for(lambda: self.ackermann.get_num_connections() > 0, 'servo_commands')
        self.hold_drive(0.3, 0.0, 1.5)
        self.assertGreater(self.forward_speed(), 0.2, 'the car must drive again under the new spawner')


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'faults', FaultsTest)
