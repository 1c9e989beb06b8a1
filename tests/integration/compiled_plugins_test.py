#!/usr/bin/env python3
"""A lab's own compiled Gazebo plugin with a ROS interface runs in racebot's world server (issue 39, points 2 and 7).

tests/fixtures/gazebo_plugin_workspace/fixture_ros_gazebo_plugins is written the way community plugin packages are:
find_package(catkin COMPONENTS roscpp gazebo_ros ...) and find_package(gazebo), a model plugin that makes a
ros::NodeHandle in its Load, subscribes a velocity command (its callback on roscpp's spinner), drives a joint at
every worldUpdateBegin (boost::bind with a bare _1), publishes the joint's velocity and serves a std_srvs/Trigger
that moves the joint from roscpp's thread. As a user would, from a login shell: source racebot's devel space,
catkin_make a workspace under /tmp holding the package, source its devel space and roslaunch its world launch
(gazebo_ros's empty_world.launch, spawn_model -urdf). Checked: roscpp's node runs beside the world server's rospy
node without a name clash; the command drives the joint (its velocity topic reads it back); the service moves the
joint from roscpp's thread while the world steps; ROS_INFO from Load reaches the log. The launch also names the
package's system plugin on gzserver's command line (-s): it meets the world at worldCreated and serves what it
counts of the world's updates.

The same workspace holds tests/fixtures/gazebo_plugin_workspace/fixture_cpp_controllers, a lab's own ros_control
controllers in C++ (issue 39, point 3): find_package(catkin COMPONENTS controller_interface hardware_interface
pluginlib realtime_tools), PLUGINLIB_EXPORT_CLASS and a plugin XML. Its launch file spawns a robot into the running
world and starts them with ros_control's spawner beside a Python controller; checked: list_controllers and
list_controller_types as ros_control reports them, the C++ velocity forwarder's realtime buffer and publisher, a
MultiInterfaceController holding a joint with an effort while it reads another joint, a Python controller on the
next joint in the same updates, a bad joint refused at load with the controller's own error, stop, start, unload.

And tests/fixtures/gazebo_plugin_workspace/fixture_robot_hw_sim, a lab's own gazebo_ros_control RobotHWSim
(issue 39, point 3): its <robotSimType> is made through pluginlib and gets the model, URDF and transmissions in
initSim; checked: its joints, a virtual one of its own included, reach the Python joint_state_controller; a C++
controller on its handles and a Python one through the mirror both drive their wheels through its writeSim.

And tests/fixtures/gazebo_plugin_workspace/fixture_ray_sensor_plugins, a lab's own ray sensor plugins (issue 39,
points 1, 2 and 7): a RayPlugin in velodyne_gazebo_plugins' pattern (sensor off at load, a Gazebo transport
subscription to its scan and SetActive(true) when its ROS topic gets a subscriber) built twice, for a ray and a
gpu_ray sensor, and one that reads the updated event and the laser shape's raw rays at a rate it sets. Checked:
the scans' size, angles, frame, stamp and ranges against the walls they see; the rate the plugin set; the sensor
moving with its body.
"""
import math
import os
import subprocess
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from controller_manager_msgs.srv import (ListControllers, ListControllerTypes, LoadController, SwitchController,
                                         UnloadController)
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetWorldProperties, SetModelState
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState, LaserScan
from std_msgs.msg import Bool, Float64
from std_srvs.srv import Trigger

from catkin_overlay import BUILD_TIMEOUT, LaunchWatch, ShellCommand, Workspace, user_environment

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FIXTURES = os.path.join(REPO, 'tests', 'fixtures', 'gazebo_plugin_workspace')
RACEBOT_SETUP = os.path.join(REPO, 'devel', 'setup.bash')
STARTUP_TIMEOUT = 180.0  # wall s: world server, spawn and the plugin's first message on a busy 2-core machine
COMMAND_TIMEOUT = 60.0


class CompiledPluginsTest(unittest.TestCase):
    launch = workspace = turntable = rover = hover = ranger = None

    @classmethod
    def setUpClass(cls):
        try:
            cls.start()
        except BaseException:
            cls.tearDownClass()
            raise

    @classmethod
    def start(cls):
        rospy.init_node('compiled_plugins_test')
        cls.velocities = []
        cls.velocity_sub = rospy.Subscriber('/spinner/joint_velocity', Float64, lambda m: cls.velocities.append(m.data),
                                            queue_size=100)
        cls.cmd = rospy.Publisher('/spinner/cmd', Float64, queue_size=1, latch=True)
        cls.log = []
        cls.log_sub = rospy.Subscriber('/rosout', Log, cls.log.append, queue_size=1000)
        cls.joints = {}
        cls.joint_sub = rospy.Subscriber('/turntable/joint_states', JointState, cls._on_joints, queue_size=10)
        cls.wheel_state, cls.watched = [], []
        rospy.Subscriber('/turntable/wheel_controller/state', Float64, lambda m: cls.wheel_state.append(m.data))
        rospy.Subscriber('/turntable/arm_controller/watched_position', Float64, lambda m: cls.watched.append(m.data))
        cls.rover_joints = {}
        rospy.Subscriber('/rover/joint_states', JointState, cls._on_rover_joints, queue_size=10)
        cls.hover_joints = {}
        rospy.Subscriber('/joint_states', JointState, cls._on_hover_joints, queue_size=10)
        cls.left_cmd = rospy.Publisher('/rover/left_controller/command', Float64, queue_size=1, latch=True)
        cls.right_cmd = rospy.Publisher('/rover/right_controller/command', Float64, queue_size=1, latch=True)
        cls.wheel_cmd = rospy.Publisher('/turntable/wheel_controller/command', Float64, queue_size=1, latch=True)
        cls.wheel2_cmd = rospy.Publisher('/turntable/wheel2_controller/command', Float64, queue_size=1, latch=True)
        cls.workspace = Workspace('racebot-plugin-ws-')
        cls.workspace.copy_packages(FIXTURES)
        env = user_environment()
        build = ShellCommand('source %s && catkin_make -C %s' % (RACEBOT_SETUP, cls.workspace.root), env,
                             os.path.join(cls.workspace.root, 'catkin_make.log'), login=True)
        try:
            built = build.process.wait(BUILD_TIMEOUT)
        except subprocess.TimeoutExpired:
            built = 'timed out after %.0f s' % BUILD_TIMEOUT
        log = build.output()
        build.stop()
        assert built == 0, 'catkin_make of the plugin package failed (%s):\n%s' % (built, log[-3000:])
        cls.launch = cls.roslaunch('fixture_ros_gazebo_plugins spinner_world.launch', 'roslaunch.log')
        cls.watch = LaunchWatch(cls.launch)

    @classmethod
    def _on_joints(cls, msg):
        cls.joints = {name: (p, v) for name, p, v in zip(msg.name, msg.position, msg.velocity)}

    @classmethod
    def _on_rover_joints(cls, msg):
        cls.rover_joints = {name: (p, v) for name, p, v in zip(msg.name, msg.position, msg.velocity)}

    @classmethod
    def _on_hover_joints(cls, msg):
        cls.hover_joints = {name: (p, v) for name, p, v in zip(msg.name, msg.position, msg.velocity)}

    @classmethod
    def tearDownClass(cls):
        for name in ('ranger', 'hover', 'rover', 'turntable'):  # the launches into the world, newest first
            launch = getattr(cls, name)
            if launch is not None:
                launch.stop()
                sys.stdout.write('--- %s roslaunch output ---\n%s\n' % (name, launch.output()[-4000:]))
        if cls.launch is not None:
            cls.launch.stop()
            sys.stdout.write('--- roslaunch output ---\n%s\n' % cls.launch.output()[-6000:])
        if cls.workspace is not None:
            cls.workspace.remove()

    @classmethod
    def roslaunch(cls, args, log):
        """`roslaunch ARGS` from a login shell with the built workspace sourced, as a user types it; output in LOG."""
        return ShellCommand('source %s && exec roslaunch %s' % (cls.workspace.setup, args), user_environment(),
                            os.path.join(cls.workspace.root, log), login=True)

    def launched(self, condition, what, timeout=STARTUP_TIMEOUT):
        return self.watch.wait(condition, what, timeout)

    def test_1_roscpp_runs_beside_the_world_servers_node(self):
        self.launched(lambda: self.velocities, "the plugin's first /spinner/joint_velocity")
        nodes = rosgraph.Master('/compiled_plugins_test').getSystemState()
        publishers = {topic: names for topic, names in nodes[0]}
        self.assertEqual(publishers.get('/spinner/joint_velocity'), ['/gazebo_cpp'], publishers)
        services = {name: providers for name, providers in nodes[2]}
        self.assertEqual(services.get('/spinner/zero'), ['/gazebo_cpp'])
        self.assertIn('/gazebo/spawn_urdf_model', services)  # the rospy node is still there, not replaced
        self.launched(lambda: 'RosJointPlugin drives spinner::spin_joint in namespace /spinner'
                      in self.launch.output(), "the plugin's ROS_INFO on the world server's screen")
        # NodeHandle("~") is /gazebo_cpp's: what the launch file loaded under /gazebo was copied there
        self.launched(lambda: "RosJointPlugin: ~ros_joint_plugin/greeting is 'hello from the launch file'"
                      in self.launch.output(), "the launch file's parameter read through NodeHandle(\"~\")")

    def test_2_the_topic_drives_the_joint(self):
        self.launched(lambda: self.velocities, "the plugin's first /spinner/joint_velocity")
        self.cmd.publish(Float64(3.0))
        self.launched(lambda: self.velocities and abs(self.velocities[-1] - 3.0) < 1e-3,
                      'the joint at the commanded 3.0 rad/s', COMMAND_TIMEOUT)

    def test_3_a_service_moves_the_joint_from_roscpps_thread(self):
        rospy.wait_for_service('/spinner/zero', timeout=STARTUP_TIMEOUT)
        answer = rospy.ServiceProxy('/spinner/zero', Trigger)()
        self.assertTrue(answer.success)
        self.assertAlmostEqual(float(answer.message), 0.0, places=6)
        self.launched(lambda: self.velocities and abs(self.velocities[-1]) < 1e-6,
                      'the joint stopped by the service', COMMAND_TIMEOUT)

    def test_3a_a_system_plugin_from_the_command_line_serves_what_it_counts(self):
        # spinner_world.launch: extra_gazebo_args:="-s libfixture_world_stats_plugin.so"; its ros::init gave way
        # to the world server's roscpp, and its service waited for worldCreated
        rospy.wait_for_service('/world_stats/describe', timeout=STARTUP_TIMEOUT)
        services = {name: providers for name, providers in rosgraph.Master('/compiled_plugins_test')
                    .getSystemState()[2]}
        self.assertEqual(services.get('/world_stats/describe'), ['/gazebo_cpp'])
        describe = rospy.ServiceProxy('/world_stats/describe', Trigger)
        self.launched(lambda: ' models 1 ' in describe().message, 'the spinner in the system plugin\'s world')
        first = describe().message.split()
        self.assertEqual(first[:4], ['world', 'default', 'models', '1'], first)
        self.launched(lambda: int(describe().message.split()[5]) > int(first[5]) + 10,
                      'the system plugin counting updates', COMMAND_TIMEOUT)
        words = describe().message.split()
        # every update it counted is one of the world's (it connected at worldCreated, before the first)
        self.assertLessEqual(int(words[5]), int(words[7]))
        self.assertGreater(int(words[5]), 0)

    # -- a lab's C++ ros_control controllers (fixture_cpp_controllers) -------------------------------------------
    @classmethod
    def start_turntable(cls):
        """roslaunch fixture_cpp_controllers turntable.launch into the running world, once, and wait for its four
        controllers to run."""
        if cls.turntable is None:
            rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=STARTUP_TIMEOUT)
            cls.turntable = cls.roslaunch('fixture_cpp_controllers turntable.launch', 'turntable.log')
            rospy.wait_for_service(CM + 'list_controllers', timeout=STARTUP_TIMEOUT)
            LaunchWatch(cls.turntable).wait(lambda: len(cls.running()) == 4, 'the four controllers to run',
                                            STARTUP_TIMEOUT)

    @staticmethod
    def running():
        controllers = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)().controller
        return {c.name: c for c in controllers if c.state == 'running'}

    def joint(self, name):
        return self.joints.get(name, (math.nan, math.nan))

    def test_4_cpp_controllers_are_listed_as_ros_control_lists_them(self):
        self.start_turntable()
        claimed = {name: [(r.hardware_interface, list(r.resources)) for r in c.claimed_resources]
                   for name, c in self.running().items()}
        self.assertEqual(claimed, {
            'joint_state_controller': [('hardware_interface::JointStateInterface', [])],
            'wheel_controller': [('hardware_interface::VelocityJointInterface', ['wheel_joint'])],
            'wheel2_controller': [('hardware_interface::VelocityJointInterface', ['wheel2_joint'])],
            'arm_controller': [('hardware_interface::EffortJointInterface', ['arm_joint']),
                               ('hardware_interface::JointStateInterface', [])]})
        self.assertEqual(self.running()['wheel_controller'].type, 'fixture_cpp_controllers/VelocityForwardController')
        types = rospy.ServiceProxy(CM + 'list_controller_types', ListControllerTypes)()
        listed = dict(zip(types.types, types.base_classes))
        for cpp in ('VelocityForwardController', 'HoldPositionController'):
            cpp = 'fixture_cpp_controllers/' + cpp
            self.assertEqual(listed.get(cpp), 'controller_interface::ControllerBase', types)
        self.assertIn('velocity_controllers/JointVelocityController', listed)

    def test_5_cpp_and_python_controllers_drive_their_joints_in_the_same_updates(self):
        self.start_turntable()
        self.wheel_cmd.publish(Float64(2.0))
        self.wheel2_cmd.publish(Float64(-1.0))
        self.launched(lambda: abs(self.joint('wheel_joint')[1] - 2.0) < 1e-6
                      and abs(self.joint('wheel2_joint')[1] + 1.0) < 1e-6,
                      'wheel_joint at 2 rad/s (C++) and wheel2_joint at -1 rad/s (Python)', COMMAND_TIMEOUT)
        # the realtime publisher sends what the C++ controller reads from its handle
        del self.wheel_state[:]
        self.launched(lambda: self.wheel_state and abs(self.wheel_state[-1] - 2.0) < 1e-6,
                      "the C++ controller's state topic at 2 rad/s", COMMAND_TIMEOUT)
        # the MultiInterfaceController holds arm_joint at its target (effort) and reads wheel_joint (state only)
        self.launched(lambda: abs(self.joint('arm_joint')[0] - 0.5) < 0.01 and abs(self.joint('arm_joint')[1]) < 0.01,
                      'arm_joint held at 0.5 rad', COMMAND_TIMEOUT)
        del self.watched[:]
        self.launched(lambda: len(self.watched) > 10, 'watched positions', COMMAND_TIMEOUT)
        self.assertGreater(self.watched[-1], self.watched[0], 'wheel_joint turns, as read by the arm controller')

    def test_6_a_bad_joint_is_refused_at_load_with_the_controllers_own_error(self):
        self.start_turntable()
        mark = len(self.log)
        self.assertFalse(rospy.ServiceProxy(CM + 'load_controller', LoadController)('bad_controller').ok)
        self.launched(lambda: any("Could not find resource 'no_such_joint'" in m.msg and m.name == '/gazebo_cpp'
                                  for m in self.log[mark:]), "the C++ controller's ROS_ERROR, from /gazebo_cpp",
                      COMMAND_TIMEOUT)
        self.launched(lambda: any("Initializing controller 'bad_controller' failed" in m.msg and m.level == Log.ERROR
                                  for m in self.log[mark:]), "the controller manager's error", COMMAND_TIMEOUT)
        self.assertEqual(len(self.running()), 4)

    def test_7_a_cpp_controller_stops_starts_and_unloads(self):
        self.start_turntable()
        switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        self.wheel_cmd.publish(Float64(2.0))
        self.launched(lambda: abs(self.joint('wheel_joint')[1] - 2.0) < 1e-6, 'wheel_joint at 2 rad/s', COMMAND_TIMEOUT)
        self.assertTrue(switch([], ['wheel_controller'], 2, False, 0.0).ok)  # STRICT
        self.launched(lambda: abs(self.joint('wheel_joint')[1]) < 1e-6, 'the stopped joint at rest', COMMAND_TIMEOUT)
        self.assertTrue(switch(['wheel_controller'], [], 2, False, 0.0).ok)
        self.wheel_cmd.publish(Float64(-3.0))
        self.launched(lambda: abs(self.joint('wheel_joint')[1] + 3.0) < 1e-6, 'wheel_joint at -3 rad/s again',
                      COMMAND_TIMEOUT)
        self.assertTrue(switch([], ['wheel_controller'], 2, False, 0.0).ok)
        self.assertTrue(rospy.ServiceProxy(CM + 'unload_controller', UnloadController)('wheel_controller').ok)
        self.launched(lambda: '/turntable/wheel_controller/state' not in
                      [t for t, _ in rosgraph.Master('/compiled_plugins_test').getSystemState()[0]],
                      "the unloaded controller's publisher gone from the master", COMMAND_TIMEOUT)
        self.assertNotIn('wheel_controller', self.running())
        self.assertIn('arm_controller', self.running())

    def test_8_a_cpp_controller_that_throws_is_stopped_and_the_world_goes_on(self):
        self.start_turntable()
        load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        mark = len(self.log)
        self.assertFalse(load('unknown_joint_controller').ok)  # its init lets HardwareInterfaceException out
        self.launched(lambda: any("Initializing controller 'unknown_joint_controller' failed" in m.msg
                                  and "its init threw: Could not find resource 'no_such_joint'" in m.msg
                                  for m in self.log[mark:]), "the manager's error quoting the exception",
                      COMMAND_TIMEOUT)
        self.assertTrue(load('failing_controller').ok)
        switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        self.assertTrue(switch(['failing_controller'], [], 2, False, 0.0).ok)
        self.assertIn('failing_controller', self.running())
        fail = rospy.Publisher('/turntable/failing_controller/fail', Bool, queue_size=1, latch=True)
        fail.publish(Bool(True))
        self.launched(lambda: any("Controller 'failing_controller' raised RuntimeError in its update (C++ exception: "
                                  "joint wheel_joint read past the end of a table)" in m.msg for m in self.log[mark:]),
                      'the error naming the controller and its exception', COMMAND_TIMEOUT)
        self.assertNotIn('failing_controller', self.running())
        self.assertIn('arm_controller', self.running())
        del self.watched[:]
        self.launched(lambda: len(self.watched) > 10, 'the other C++ controller still publishing', COMMAND_TIMEOUT)

    # -- a lab's C++ RobotHWSim (fixture_robot_hw_sim) ----------------------------------------------------------
    def test_9_a_packages_robot_hw_sim_carries_cpp_and_python_controllers(self):
        rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=STARTUP_TIMEOUT)
        type(self).rover = self.roslaunch('fixture_robot_hw_sim rover.launch', 'rover.log')
        self.launched(lambda: 'WheelHWSim in /rover: 2 driven wheels, 1 joints reported, on model rover'
                      in self.launch.output(), "the RobotHWSim's ROS_INFO from its initSim")
        rospy.wait_for_service('/rover/controller_manager/list_controllers', timeout=STARTUP_TIMEOUT)
        listed = rospy.ServiceProxy('/rover/controller_manager/list_controllers', ListControllers)
        LaunchWatch(self.rover).wait(lambda: len([c for c in listed().controller if c.state == 'running']) == 3,
                                     "the rover's three controllers to run", STARTUP_TIMEOUT)
        # the Python joint_state_controller reports every joint of the RobotHWSim, its virtual mean_wheel too
        self.launched(lambda: set(self.rover_joints) == {'left_wheel_joint', 'right_wheel_joint', 'flag_joint',
                                                          'mean_wheel'}, "the RobotHWSim's joints on joint_states",
                      COMMAND_TIMEOUT)
        self.left_cmd.publish(Float64(2.0))  # C++ controller, on the RobotHWSim's own handle
        self.right_cmd.publish(Float64(-1.0))  # Python controller, through the mirror
        self.launched(lambda: abs(self.rover_joints['left_wheel_joint'][1] - 2.0) < 1e-6
                      and abs(self.rover_joints['right_wheel_joint'][1] + 1.0) < 1e-6
                      and abs(self.rover_joints['mean_wheel'][1] - 0.5) < 1e-6,
                      'left wheel at 2 rad/s, right at -1 rad/s, their mean at 0.5', COMMAND_TIMEOUT)

    def test_9a_a_robot_hw_sim_at_the_root_namespace_reads_a_relative_robot_param(self):
        # hector_quadrotor's case: no robotNamespace (spawn_model gives the plugin "/", whose NodeHandle searches
        # from ''), a relative robotParam, no <transmission> (the RobotHWSim has interfaces of its own: Gazebo
        # warns of no missing transmission, nor do we)
        rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=STARTUP_TIMEOUT)
        type(self).hover = self.roslaunch('fixture_robot_hw_sim hover.launch', 'hover.log')
        self.launched(lambda: 'WheelHWSim in /: 0 driven wheels, 1 joints reported, on model hover'
                      in self.launch.output(), "the root RobotHWSim's ROS_INFO from its initSim")
        rospy.wait_for_service('/controller_manager/list_controllers', timeout=STARTUP_TIMEOUT)
        listed = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)
        LaunchWatch(self.hover).wait(lambda: [(c.name, c.state) for c in listed().controller]
                                     == [('hover_state_controller', 'running')],
                                     'the hover_state_controller to run at the root namespace', STARTUP_TIMEOUT)
        self.launched(lambda: set(self.hover_joints) == {'rotor_joint', 'mean_wheel'},
                      "the root RobotHWSim's joints on /joint_states", COMMAND_TIMEOUT)
        said = self.launch.output() + '\n'.join(m.msg for m in self.log)
        self.assertNotIn('has no <transmission>', said)

    # -- a lab's compiled ray sensor plugins (fixture_ray_sensor_plugins) ----------------------------------------
    @classmethod
    def start_ranger(cls):
        """roslaunch fixture_ray_sensor_plugins ranger.launch into the running world, once: the ranger at (0, 10)
        between two walls, whose faces are 1.9 m ahead of its lasers and 2.9 m behind them."""
        if cls.ranger is None:
            rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=STARTUP_TIMEOUT)
            cls.clock = []
            rospy.Subscriber('/clock', Clock, lambda m: cls.clock.append(m.clock.to_sec()), queue_size=100)
            cls.nearest, cls.nearest_raw = [], []
            rospy.Subscriber('/ranger/nearest', Float64,
                             lambda m: cls.nearest.append((cls.clock[-1] if cls.clock else None, m.data)))
            rospy.Subscriber('/ranger/nearest_raw', Float64, lambda m: cls.nearest_raw.append(m.data))
            cls.ranger = cls.roslaunch('fixture_ray_sensor_plugins ranger.launch', 'ranger.log')
            LaunchWatch(cls.launch).wait(lambda: 'scan relay on gpu_laser' in cls.launch.output(),
                                         "the sensor plugins' ROS_INFO from their Load", STARTUP_TIMEOUT)
            # the walls come from spawners of their own, which may finish after the ranger's (and roslaunch ends
            # once its spawners have: the world server's answer is what counts)
            properties = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
            deadline = time.time() + STARTUP_TIMEOUT
            while not {'front_wall', 'back_wall'} <= set(properties().model_names):
                assert time.time() < deadline, 'the walls were not spawned within %.0f s:\n%s' % (
                    STARTUP_TIMEOUT, cls.ranger.output()[-3000:])
                time.sleep(0.1)

    def scans(self, topic, count=3):
        """The next `count` LaserScans on `topic` (subscribed only for them: the relay's sensor runs on demand)."""
        got = []
        sub = rospy.Subscriber(topic, LaserScan, got.append, queue_size=10)
        try:
            self.launched(lambda: len(got) >= count, '%d scans on %s' % (count, topic), COMMAND_TIMEOUT)
        finally:
            sub.unregister()
        return got[:count]

    def test_9b_a_ray_plugin_reads_its_sensors_scan_through_transport_on_demand(self):
        self.start_ranger()
        scan = self.scans('/ranger/scan')[-1]
        self.assertEqual(len(scan.ranges), 61)
        self.assertAlmostEqual(scan.angle_min, -0.5, places=6)
        self.assertAlmostEqual(scan.angle_increment, 1.0 / 60, places=6)
        self.assertEqual(scan.header.frame_id, 'laser_link')
        self.assertGreater(scan.header.stamp.to_sec(), 0.0)  # the measurement's sim time
        self.assertAlmostEqual(scan.ranges[30], 1.9, delta=0.01)  # straight ahead to the wall's face
        self.assertAlmostEqual(scan.ranges[0], 1.9 / math.cos(0.5), delta=0.01)

    def test_9c_a_gpu_ray_plugin_from_the_same_source_reads_its_gpu_ray_sensor(self):
        self.start_ranger()
        scan = self.scans('/ranger/gpu_scan')[-1]
        self.assertEqual(len(scan.ranges), 31)
        self.assertAlmostEqual(scan.ranges[15], 2.9, delta=0.01)  # it looks back, to the other wall

    def test_9d_a_plugin_reads_the_updated_event_and_raw_rays_at_the_rate_it_sets(self):
        self.start_ranger()
        del self.nearest[:], self.nearest_raw[:]  # from now on: both walls stand
        self.launched(lambda: len(self.nearest) > 12 and self.nearest_raw, 'the nearest obstacle published',
                      COMMAND_TIMEOUT)
        self.assertAlmostEqual(self.nearest[-1][1], 1.9, delta=0.01)
        self.assertAlmostEqual(self.nearest_raw[-1], 1.9, delta=0.01)
        # the sensor declares 50 Hz, its plugin sets 5 Hz (SetUpdateRate): the messages' sim times say which
        times = [t for t, _ in self.nearest[-11:] if t is not None]
        self.assertGreaterEqual(len(times), 10)
        rate = (len(times) - 1) / (times[-1] - times[0])
        self.assertGreater(rate, 3.0, rate)
        self.assertLess(rate, 8.0, rate)

    def test_9e_the_sensor_follows_its_body(self):
        self.start_ranger()
        moved = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)(ModelState(
            model_name='ranger', pose=Pose(position=Point(0.5, 10.0, 0.0), orientation=Quaternion(0, 0, 0, 1))))
        self.assertTrue(moved.success, moved.status_message)
        scan = self.scans('/ranger/scan', 3)[-1]
        self.assertAlmostEqual(scan.ranges[30], 1.4, delta=0.02)


CM = '/turntable/controller_manager/'

if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'compiled_plugins', CompiledPluginsTest, sys.argv)
