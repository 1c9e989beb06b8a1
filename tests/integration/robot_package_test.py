#!/usr/bin/env python3
"""A robot package written the way ROS 1 packages are runs unchanged on racebot (issue 16, point 5).

examples/demo_diffbot (racebot's worked example, examples/README.md) is such a package: its world launch
includes `$(find gazebo_ros)/launch/empty_world.launch` with a world that includes `model://marker_post` from the
package's own `gazebo_model_path` export, spawns its xacro description with `spawn_model -urdf -param
robot_description -model demo_diffbot`, loads a ros_control YAML (joint_state_controller and two
velocity_controllers/JointVelocityController) started by controller_manager's spawner, and drives with
`scripts/drive.py`, a `#!/usr/bin/env python` node run from the source space (no catkin relay).

As a user would, from a login shell with nothing but the user's own environment: `source` racebot's
devel space, `catkin_make` a new workspace under /tmp holding a copy of the package, then `source` its
devel space and `roslaunch demo_diffbot demo_world.launch gui:=false`. Checked: the world's included
model is where the world puts it, the three controllers run, drive.py runs under `python`, and the
robot drives straight ahead. Waits are bounded in wall time.
"""
import math
import os
import shutil
import subprocess
import sys
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from std_msgs.msg import Float64

from catkin_overlay import BUILD_TIMEOUT, LaunchWatch, ShellCommand, Workspace, user_environment

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
PACKAGE = os.path.join(REPO, 'examples', 'demo_diffbot')
RACEBOT_SETUP = os.path.join(REPO, 'devel', 'setup.bash')
MODEL = 'demo_diffbot'
CONTROLLERS = {'joint_state_controller': 'joint_state_controller/JointStateController',
               'left_wheel_controller': 'velocity_controllers/JointVelocityController',
               'right_wheel_controller': 'velocity_controllers/JointVelocityController'}
STARTUP_TIMEOUT = 180.0  # wall s: world server, spawn and spawner on a busy 2-core machine
DRIVE_TIMEOUT = 120.0



class RobotPackageTest(unittest.TestCase):
    launch = workspace = None  # set by start(); tearDownClass also runs after a failed start

    @classmethod
    def setUpClass(cls):
        try:
            cls.start()
        except BaseException:
            cls.tearDownClass()  # unittest does not call it when setUpClass fails
            raise

    @classmethod
    def start(cls):
        rospy.init_node('robot_package_test')
        cls.commands = []
        cls.command_sub = rospy.Subscriber('/%s/left_wheel_controller/command' % MODEL, Float64,
                                           cls.commands.append, queue_size=10)
        cls.workspace = Workspace('racebot-robot-ws-')
        shutil.copytree(PACKAGE, os.path.join(cls.workspace.src, 'demo_diffbot'))
        env = user_environment()
        build = ShellCommand('source %s && catkin_make -C %s' % (RACEBOT_SETUP, cls.workspace.root), env,
                             os.path.join(cls.workspace.root, 'catkin_make.log'), login=True)
        try:
            built = build.process.wait(BUILD_TIMEOUT)
        except subprocess.TimeoutExpired:
            built = 'timed out after %.0f s' % BUILD_TIMEOUT
        log = build.output()
        build.stop()
        assert built == 0, 'catkin_make of the robot package failed (%s):\n%s' % (built, log[-3000:])
        cls.launch = ShellCommand('source %s && command -v python && exec roslaunch demo_diffbot demo_world.launch '
                                  'gui:=false' % cls.workspace.setup, env,
                                  os.path.join(cls.workspace.root, 'roslaunch.log'), login=True)
        cls.watch = LaunchWatch(cls.launch)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)

    @classmethod
    def tearDownClass(cls):
        if cls.launch is not None:
            cls.launch.stop()
            sys.stdout.write('--- roslaunch output ---\n%s\n' % cls.launch.output()[-6000:])
        if cls.workspace is not None:
            cls.workspace.remove()

    def launched(self, condition, what, timeout=STARTUP_TIMEOUT):
        return self.watch.wait(condition, what, timeout)

    def state(self, model):
        try:
            rospy.wait_for_service('/gazebo/get_model_state', timeout=0.5)
            state = self.get_state(model, '')
        except (rospy.ServiceException, rospy.ROSException):
            return None
        return state if state.success else None

    def running_controllers(self):
        try:
            rospy.wait_for_service('/%s/controller_manager/list_controllers' % MODEL, timeout=0.5)
            listed = rospy.ServiceProxy('/%s/controller_manager/list_controllers' % MODEL, ListControllers)()
        except (rospy.ServiceException, rospy.ROSException):
            return None
        running = {c.name: c.type for c in listed.controller if c.state == 'running'}
        return running if len(running) == len(CONTROLLERS) else None

    def test_1_the_world_includes_the_packages_model(self):
        post = self.launched(lambda: self.state('post'), 'model "post" (model://marker_post) in the world')
        self.assertAlmostEqual(post.pose.position.x, 1.0, delta=1e-3)
        self.assertAlmostEqual(post.pose.position.y, 1.0, delta=1e-3)

    def test_2_the_spawner_starts_the_yaml_controllers(self):
        self.assertEqual(self.launched(self.running_controllers, 'the three controllers running'), CONTROLLERS)

    def test_3_drive_py_runs_under_python(self):
        master = rosgraph.Master('/robot_package_test')
        pid = self.launched(lambda: self._pid(master, '/drive'), 'node /drive to answer getPid')
        with open('/proc/%d/cmdline' % pid, 'rb') as f:
            argv = f.read().decode().split('\0')
        # `#!/usr/bin/env python`: env runs `python` (found on PATH) with the script from the source space
        self.assertEqual(argv[0], 'python', argv)
        self.assertEqual(os.path.basename(argv[1]), 'drive.py', argv)
        self.assertIn('/src/demo_diffbot/scripts/', argv[1], argv)
        # the sender: rospy has no public accessor; its own rospy_tutorials read the connection header
        self.launched(lambda: any(m._connection_header['callerid'] == '/drive' and m.data == 4.0
                                  for m in list(self.commands)), 'drive.py\'s wheel command (4.0 rad/s)')

    @staticmethod
    def _pid(master, name):
        """The pid of node `name`, or None while it is not registered or does not answer."""
        try:
            code, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(name)).getPid('/robot_package_test')
        except (rosgraph.MasterError, OSError, xmlrpc.client.Error):
            return None
        return pid if code == 1 else None

    def test_4_the_robot_drives_straight_ahead(self):
        self.launched(lambda: self.state(MODEL), 'model %s spawned' % MODEL)
        moved = self.launched(lambda: (lambda s: s if s and s.pose.position.x > 0.5 else None)(self.state(MODEL)),
                              'the robot to drive 0.5 m ahead (+x)', DRIVE_TIMEOUT).pose.position
        self.assertLess(abs(moved.y), 0.15 * moved.x, 'not straight ahead: (%.2f, %.2f)' % (moved.x, moved.y))
        self.assertTrue(math.isfinite(moved.z) and abs(moved.z - 0.1) < 0.05, 'off the ground: z %.3f' % moved.z)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'robot_package', RobotPackageTest, sys.argv)
