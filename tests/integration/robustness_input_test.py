#!/usr/bin/env python3
"""Bad input against the running simulator, car, controllers, servo_commands and transform.

Every case feeds one kind of bad input and checks (a) the text that reports it says what was wrong
and what to do (read from /rosout, a service's status_message or a process's output) and (b) the
simulator still serves afterwards (a query answers, /clock advances) with the car's state finite.
"""
import math
import time
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest
from ackermann_msgs.msg import AckermannDriveStamped
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import ListControllers, LoadController, SwitchController, SwitchControllerRequest
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose, Twist
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from robustness_common import WALL_TIMEOUT, Rosout, SimProbe, rosrun, wait_for

CM = '/racebot/controller_manager/'
WHEELS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
          'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller']
HINGES = ['left_steering_hinge_position_controller', 'right_steering_hinge_position_controller']
CONTROLLERS = WHEELS + HINGES + ['joint_state_controller']
HINGE_JOINTS = ['left_steering_hinge_joint', 'right_steering_hinge_joint']
HINGE_LIMIT = 0.6
BAD_VALUES = [math.nan, math.inf, -math.inf]
ABSURD = 1e9
THROTTLE_S = 5.5  # the nodes throttle each warning to one per 5 s


class RobustnessInputTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('robustness_input_test')
        cls.sim = SimProbe()
        cls.rosout = Rosout(clock=lambda: cls.sim.clock)
        cls.joint_state = None
        rospy.Subscriber('/racebot/joint_states', JointState, cls._on_joints, queue_size=1)
        cls.ackermann = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=100)
        cls.cmd_vel = rospy.Publisher('/cmd_vel', Twist, queue_size=100)
        cls.cmd = {c: rospy.Publisher('/racebot/%s/command' % c, Float64, queue_size=100) for c in WHEELS + HINGES}
        cls.sim.wait_ready()
        rospy.wait_for_service(CM + 'list_controllers', timeout=WALL_TIMEOUT)
        cls.list_controllers = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)
        cls.load_controller = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        cls.switch_controller = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        cls.spawn_urdf = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.delete_model = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.reset_world = rospy.ServiceProxy('/gazebo/reset_world', Empty)
        wait_for(lambda: cls.running() == set(CONTROLLERS), 'the seven controllers to run')
        wait_for(lambda: cls.ackermann.get_num_connections() > 0, 'servo_commands to subscribe')
        wait_for(lambda: cls.cmd_vel.get_num_connections() > 0, 'transform to subscribe')
        wait_for(lambda: all(p.get_num_connections() > 0 for p in cls.cmd.values()), 'the controllers to subscribe')
        cls.robot_description = rospy.get_param('/robot_description')

    last_flood = (0.0, 0.0)

    @classmethod
    def _on_joints(cls, msg):
        cls.joint_state = msg

    @classmethod
    def running(cls):
        return {c.name for c in cls.list_controllers().controller if c.state == 'running'}

    def tearDown(self):
        self.drive(0.0, 0.0)

    # -- helpers ------------------------------------------------------------------------------
    def drive(self, speed, steering):
        msg = AckermannDriveStamped()
        msg.drive.speed, msg.drive.steering_angle = speed, steering
        self.ackermann.publish(msg)

    def hold(self, send, value, sim_seconds):
        """Send `value` again every 0.1 s wall for `sim_seconds` of sim time: messages of two publishers
        (this test, servo_commands) to one controller are not ordered, the last repeat wins."""
        start = wait_for(lambda: self.sim.clock is not None, '/clock') and self.sim.clock

        def again():
            send(value)
            return self.sim.clock >= start + sim_seconds
        wait_for(again, '%g s of sim time' % sim_seconds, period=0.1)

    def twist(self, linear, angular):
        msg = Twist()
        msg.linear.x, msg.angular.z = linear, angular
        self.cmd_vel.publish(msg)

    def hinge_positions(self):
        msg = wait_for(lambda: self.joint_state, '/racebot/joint_states')
        return [msg.position[msg.name.index(j)] for j in HINGE_JOINTS]

    def flood(self, send, values, times=20):
        """Each bad value `times` times, fast: the warnings must be throttled, not one per message.
        The values take turns: a subscriber that falls behind keeps only its queue's newest messages
        (rospy drops the older), and any window of them holds every value."""
        for _ in range(times):
            for value in values:
                send(value)
                time.sleep(0.002)
        RobustnessInputTest.last_flood = (time.time(), self.sim.clock)

    def fresh_warnings(self):
        """Wait until the throttle period (5 s; wall time in the simulator, sim time in rospy nodes)
        since the last flood and the last warning is over, so the next bad input warns again. A
        node that falls behind warns after the flood has ended: its warning's arrival here bounds
        when it was written."""
        (flood_wall, flood_sim), (warn_wall, warn_sim) = self.last_flood, self.rosout.last_warning
        wall, sim = max(flood_wall, warn_wall), max(flood_sim, warn_sim)
        wait_for(lambda: time.time() > wall + THROTTLE_S and self.sim.clock > sim + THROTTLE_S,
                 'the warning throttle period to pass')

    def assert_throttled(self, since, *needles):
        """At least one warning with these words, and far fewer than the messages that caused it."""
        warning = self.rosout.find(*needles, level=Log.WARN, since=since)
        time.sleep(0.5)  # late copies, if any, arrive
        count = len(self.rosout.matching(*needles, level=Log.WARN, since=since))
        self.assertLessEqual(count, 3, 'the warning %r came %d times: it must be throttled' % (needles, count))
        return warning

    def assert_survived(self):
        """The simulator serves, the car's state is finite, the controllers still run."""
        self.sim.assert_serving(self)
        self.sim.assert_state_finite(self)
        self.assertEqual(self.running(), set(CONTROLLERS))

    def settle(self):
        """Back to the spawn pose (after a wild drive). As in Gazebo, the controllers keep running with
        their last commands, so callers zero the commands first."""
        self.reset_world()
        self.sim.sim_sleep(0.3)

    # -- NaN, inf, 1e9 on every command topic ----------------------------------------------------
    def test_01_ackermann_nan_and_inf_are_skipped_with_a_throttled_warning(self):
        mark = self.rosout.mark()
        self.flood(lambda v: self.drive(v, 0.0), BAD_VALUES)
        w = self.assert_throttled(mark, 'servo_commands: skipping a command that is not finite')
        self.assertIn('speed nan', w.msg)
        self.flood(lambda v: self.drive(0.2, v), BAD_VALUES)
        self.sim.sim_sleep(1.0)
        self.assert_survived()

    def test_02_ackermann_absurd_values_are_clamped_with_warnings(self):
        mark = self.rosout.mark()
        self.flood(lambda v: self.drive(0.0, v), [ABSURD, -ABSURD], times=5)
        w = self.assert_throttled(mark, 'servo_commands: steering_angle', 'not a steering angle')
        self.assertIn('clamped to the hinge limit', w.msg)
        self.sim.sim_sleep(0.5)
        for position in self.hinge_positions():
            self.assertLessEqual(abs(position), HINGE_LIMIT + 0.02)
        self.flood(lambda v: self.drive(v, 0.0), [ABSURD], times=5)
        w = self.assert_throttled(mark, 'left_rear_wheel_velocity_controller: command', 'beyond the velocity limit')
        self.assertIn('clamped to 1000', w.msg)
        self.assertIn('Publish a value within the URDF <limit>', w.msg)
        self.sim.sim_sleep(1.0)
        self.assert_survived()
        self.drive(0.0, 0.0)
        self.settle()

    def test_03_cmd_vel_nan_inf_absurd(self):
        mark = self.rosout.mark()
        self.flood(lambda v: self.twist(v, 0.0), BAD_VALUES)
        self.flood(lambda v: self.twist(0.1, v), BAD_VALUES)
        w = self.assert_throttled(mark, 'transform: skipping a Twist that is not finite')
        self.assertIn('linear.x nan', w.msg)
        self.sim.sim_sleep(0.5)
        self.assert_survived()
        self.fresh_warnings()
        mark = self.rosout.mark()
        self.flood(lambda v: self.twist(v, ABSURD), [ABSURD], times=5)
        self.assert_throttled(mark, 'servo_commands: steering_angle', 'not a steering angle')
        self.assert_throttled(mark, 'left_rear_wheel_velocity_controller: command', 'beyond the velocity limit')
        self.sim.sim_sleep(1.0)
        self.assert_survived()
        # The absurd steering reaches the hinges clamped: their set points stay within the limit. Not
        # their positions: the flood drives the car at the wheels' 1000 rad/s limit (32 m/s) at full
        # lock, and the tyres' contact forces then push a hinge past PyBullet's soft joint limit
        # (0.633-0.647 rad seen within 3 s; 0.600 standing, 0.601 at 3 m/s), by how much depends on
        # the instant joint_states is read, which moves with the machine's load.
        for name, set_point in zip(HINGES, self.set_points()):
            self.assertLessEqual(abs(set_point), HINGE_LIMIT + 1e-9, '%s: set point %g' % (name, set_point))
        for position in self.hinge_positions():
            self.assertTrue(math.isfinite(position))
        self.twist(0.0, 0.0)
        self.settle()

    def test_04_every_controller_command_topic_nan_inf_absurd(self):
        self.fresh_warnings()
        mark = self.rosout.mark()
        for name in WHEELS + HINGES:
            self.flood(self.cmd[name].publish, [Float64(v) for v in BAD_VALUES + [ABSURD, -ABSURD]], times=5)
        for name in WHEELS + HINGES:
            w = self.assert_throttled(mark, '/racebot/%s: ignored a non-finite command' % name)
            self.assertIn('Publish a finite number', w.msg)
            w = self.assert_throttled(mark, '/racebot/%s: command' % name, 'beyond the')
            # +ABSURD and -ABSURD take turns: the first warning is for either
            self.assertRegex(w.msg, r'clamped to -?%s\.' % ('1000' if name in WHEELS else r'0\.6'))
        self.sim.sim_sleep(1.0)
        self.assert_survived()
        self.hold(lambda v: [self.cmd[n].publish(Float64(v)) for n in WHEELS + HINGES], 0.0, 0.3)
        self.settle()

    def set_points(self):
        """The hinge controllers' set points (their state topics): the clamped targets."""
        return [rospy.wait_for_message('/racebot/%s/state' % name, JointControllerState,
                                       timeout=WALL_TIMEOUT).set_point for name in HINGES]

    def assert_clamped(self, sign, what):
        for name, set_point in zip(HINGES, self.set_points()):
            self.assertAlmostEqual(set_point, sign * HINGE_LIMIT, places=9,
                                   msg='%s: set point %g for %s must be the hinge limit' % (name, set_point, what))
        for joint, position in zip(HINGE_JOINTS, self.hinge_positions()):
            # at the limit, give or take what the tyres' friction holds back; never beyond it
            self.assertLessEqual(abs(position), HINGE_LIMIT + 0.02, '%s at %.3f for %s' % (joint, position, what))
            self.assertGreater(sign * position, HINGE_LIMIT - 0.15, '%s at %.3f for %s' % (joint, position, what))

    def test_05_steering_beyond_the_hinge_limits_is_clamped(self):
        for steering in (0.9, -0.9, 3.0):
            self.hold(lambda v: self.drive(0.0, v), steering, 1.0)
            self.assert_clamped(math.copysign(1.0, steering), 'steering %g' % steering)
        # straight to the controllers, past servo_commands: the controller clamps its set point to the
        # URDF limits (ros_control's enforceJointLimits)
        self.hold(lambda v: [self.cmd[n].publish(Float64(v)) for n in HINGES], 1.2, 1.0)
        self.assert_clamped(1.0, 'a command of 1.2 to the controllers')
        self.assert_survived()

    # -- robot_description -----------------------------------------------------------------------
    def variant(self, strip_transmissions=False, strip_plugin=False, bad_joint=False, own_namespace=True):
        """The racebot URDF without its sensors, altered as asked. own_namespace=False drops the control
        plugin's <robotNamespace>/racebot</robotNamespace>: a plugin's own namespace wins over spawn's
        -robot_namespace, as in Gazebo, so only then does -robot_namespace place the controller manager."""
        root = ET.fromstring(self.robot_description)
        if not own_namespace:
            for plugin in root.findall('gazebo/plugin'):
                for ns in plugin.findall('robotNamespace'):
                    plugin.remove(ns)
        for gz in list(root.findall('gazebo')):
            if gz.find('sensor') is not None or (strip_plugin and gz.find('plugin') is not None):
                root.remove(gz)
        if strip_transmissions:
            for t in list(root.findall('transmission')):
                root.remove(t)
        if bad_joint:
            root.find('transmission/joint').set('name', 'no_such_joint')
        return ET.tostring(root, encoding='unicode')

    def spawn_cli(self, *args):
        p = rosrun('gazebo_ros', 'spawn_model', *args)
        code = p.wait_exit()
        return code, p.text

    def delete(self, name):
        if name in self.sim.world_properties().model_names:
            self.assertTrue(self.delete_model(name).success)

    def test_10_robot_description_missing(self):
        code, text = self.spawn_cli('-urdf', '-model', 'ghost', '-param', '/no_such_description', '-timeout', '30')
        self.assertEqual(code, 1, text)
        self.assertIn("parameter '/no_such_description' does not exist", text)
        self.assertIn('load the model first', text)
        self.assertNotIn('ghost', self.sim.world_properties().model_names)
        self.assert_survived()

    def test_11_robot_description_empty(self):
        rospy.set_param('/empty_description', '')
        code, text = self.spawn_cli('-urdf', '-model', 'ghost', '-param', '/empty_description', '-timeout', '30')
        self.assertEqual(code, 1, text)
        self.assertIn('Error: param does not exist or is empty (-param /empty_description)', text)
        self.assertNotIn('ghost', self.sim.world_properties().model_names)
        self.assert_survived()

    def test_12_robot_description_not_xml(self):
        rospy.set_param('/broken_description', '<robot name="x"><link name="a"></robot')
        code, text = self.spawn_cli('-urdf', '-model', 'ghost', '-param', '/broken_description', '-timeout', '30')
        self.assertEqual(code, 1, text)
        self.assertIn('Invalid XML: ', text)  # spawn_model parses the XML before sending it, as upstream
        res = self.spawn_urdf('ghost', 'not xml at all', '', Pose(), '')
        self.assertFalse(res.success)
        # gazebo_ros's words, then why
        self.assertEqual(res.status_message, 'SpawnModel: Failure - entity format is invalid. The model_xml is not '
                                             'XML (syntax error: line 1, column 0)')
        self.assertNotIn('ghost', self.sim.world_properties().model_names)
        self.assert_survived()

    def test_13_urdf_without_transmissions_spawns_with_an_empty_controller_manager(self):
        # gazebo_ros_control loads with no transmissions: a controller manager with no joints.
        rospy.set_param('/notrans_description', self.variant(strip_transmissions=True, own_namespace=False))
        mark = self.rosout.mark()
        code, text = self.spawn_cli('-urdf', '-model', 'notrans', '-param', '/notrans_description',
                                    '-robot_namespace', '/notrans', '-y', '3', '-timeout', '30')
        self.assertEqual(code, 0, text)
        w = self.rosout.find('notrans', 'has no <transmission>', level=Log.WARN, since=mark)
        self.assertIn('add a <transmission> per actuated joint', w.msg)
        rospy.set_param('/notrans/wheel', {'type': 'effort_controllers/JointVelocityController',
                                           'joint': 'left_rear_wheel_joint', 'pid': {'p': 1.0}})
        rospy.wait_for_service('/notrans/controller_manager/load_controller', timeout=WALL_TIMEOUT)
        load = rospy.ServiceProxy('/notrans/controller_manager/load_controller', LoadController)
        mark = self.rosout.mark()
        self.assertFalse(load('wheel').ok)
        e = self.rosout.find("Could not find resource 'left_rear_wheel_joint'", level=Log.ERROR, since=mark)
        self.assertIn('this robot offers: none', e.msg)
        self.delete('notrans')
        self.assert_survived()

    def test_14_urdf_without_the_control_plugin_spawns_without_a_controller_manager(self):
        # Gazebo: the model is spawned; nothing serves <ns>/controller_manager.
        rospy.set_param('/noplugin_description', self.variant(strip_plugin=True))
        mark = self.rosout.mark()
        code, text = self.spawn_cli('-urdf', '-model', 'noplugin', '-param', '/noplugin_description',
                                    '-robot_namespace', '/noplugin', '-y', '-3', '-timeout', '30')
        self.assertEqual(code, 0, text)
        w = self.rosout.find('noplugin has <transmission>s but declares no libgazebo_ros_control.so plugin',
                             level=Log.WARN, since=mark)
        self.assertIn('add <gazebo><plugin', w.msg)
        self.assertIn('noplugin', self.sim.world_properties().model_names)
        with self.assertRaises(rospy.ROSException):
            rospy.wait_for_service('/noplugin/controller_manager/list_controllers', timeout=2.0)
        self.delete('noplugin')
        self.assert_survived()

    def test_15_transmission_naming_a_missing_joint(self):
        # gazebo_ros_control: "Could not initialize robot simulation interface"; the model stays,
        # without a controller manager.
        rospy.set_param('/badjoint_description', self.variant(bad_joint=True))
        mark = self.rosout.mark()
        code, text = self.spawn_cli('-urdf', '-model', 'badjoint', '-param', '/badjoint_description',
                                    '-robot_namespace', '/badjoint', '-x', '3', '-timeout', '30')
        self.assertEqual(code, 0, text)
        e = self.rosout.find('badjoint', "names joint 'no_such_joint', which does not exist", level=Log.ERROR,
                             since=mark)
        self.assertIn('spawned without a controller manager', e.msg)
        self.assertIn('Fix the URDF', e.msg)
        with self.assertRaises(rospy.ROSException):
            rospy.wait_for_service('/badjoint/controller_manager/list_controllers', timeout=2.0)
        self.delete('badjoint')
        self.assert_survived()

    # -- spawn_model -----------------------------------------------------------------------------
    def test_20_spawn_model_duplicate_name(self):
        code, text = self.spawn_cli('-urdf', '-model', 'racebot', '-param', '/robot_description', '-timeout', '30')
        self.assertEqual(code, 1, text)
        self.assertIn('SpawnModel: Failure - entity already exists.', text)  # gazebo_ros's status message
        self.assertEqual(self.sim.world_properties().model_names.count('racebot'), 1)
        self.assert_survived()

    def test_21_spawn_model_unknown_option(self):
        code, text = self.spawn_cli('-urdf', '-model', 'x', '-param', '/robot_description', '-speed', '3')
        self.assertEqual(code, 2, text)
        self.assertIn('unrecognized arguments: -speed 3', text)
        self.assertIn('usage:', text)
        self.assert_survived()

    def test_22_spawn_model_without_a_model_name(self):
        code, text = self.spawn_cli('-urdf', '-param', '/robot_description')
        self.assertEqual(code, 2, text)
        self.assertIn('the following arguments are required: -model', text)
        res = self.spawn_urdf('', self.variant(), '/nameless', Pose(), '')
        self.assertFalse(res.success)
        self.assertIn('no model name given; pass -model NAME', res.status_message)
        self.assert_survived()

    # -- load_controller / switch_controller -------------------------------------------------------
    def refused_load(self, name, params, *needles):
        if params is not None:
            rospy.set_param('/racebot/%s' % name, params)
        mark = self.rosout.mark()
        self.assertFalse(self.load_controller(name).ok, '%s must be refused' % name)
        e = self.rosout.find(*needles, level=Log.ERROR, since=mark)
        self.assert_survived()
        return e

    def test_30_load_controller_unknown_type(self):
        e = self.refused_load('typo_controller', {'type': 'effort_controllers/JointVelocityControler',
                                                  'joint': 'left_rear_wheel_joint', 'pid': {'p': 1.0}},
                              "controller type 'effort_controllers/JointVelocityControler' does not exist")
        self.assertIn('list_controller_types', e.msg)

    def test_31_load_controller_without_type(self):
        e = self.refused_load('untyped_controller', {'joint': 'left_rear_wheel_joint'},
                              "Could not load controller 'untyped_controller' because the type was not specified")
        self.assertIn('rosparam load', e.msg)
        e = self.refused_load('unconfigured_controller', None, "'unconfigured_controller'",
                              'type was not specified')
        self.assertIn("namespace: '/racebot/unconfigured_controller'", e.msg)

    def test_32_load_controller_unknown_joint(self):
        e = self.refused_load('ghost_joint_controller', {'type': 'effort_controllers/JointPositionController',
                                                         'joint': 'left_steering_joint', 'pid': {'p': 1.0}},
                              "Could not find resource 'left_steering_joint'")
        self.assertIn('left_steering_hinge_joint', e.msg)  # lists what the robot offers

    def test_33_load_controller_duplicate_name(self):
        e = self.refused_load('joint_state_controller', None, "'joint_state_controller' was already loaded")
        self.assertIn('unload it first', e.msg)

    def test_34_switch_unknown_controller_strict(self):
        mark = self.rosout.mark()
        req = SwitchControllerRequest(start_controllers=['no_such_controller'], stop_controllers=[WHEELS[0]],
                                      strictness=SwitchControllerRequest.STRICT)
        self.assertFalse(self.switch_controller(req).ok)
        e = self.rosout.find("Could not start controller with name 'no_such_controller'", level=Log.ERROR, since=mark)
        self.assertIn('STRICT switch refused; nothing was changed', e.msg)
        self.assert_survived()  # WHEELS[0] still running: nothing changed

    def test_35_switch_unknown_controller_best_effort(self):
        mark = self.rosout.mark()
        req = SwitchControllerRequest(start_controllers=['no_such_controller'], stop_controllers=['also_missing'],
                                      strictness=SwitchControllerRequest.BEST_EFFORT)
        self.assertTrue(self.switch_controller(req).ok)
        w = self.rosout.find("'no_such_controller'", 'BEST_EFFORT: skipped', level=Log.WARN, since=mark)
        self.assertIn('no controller with this name exists', w.msg)
        self.rosout.find("'also_missing'", 'BEST_EFFORT: skipped', level=Log.WARN, since=mark)
        self.assert_survived()


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'robustness_input', RobustnessInputTest)
