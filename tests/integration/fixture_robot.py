"""What the rostests of the fixture robot packages (tests/fixtures/robots) share (not a test node itself).

FixtureRobotTest starts the packages' own launch files with one roslaunch in setUpClass and stops it in
tearDownClass, also when the start fails; a subclass says what to start and wait for in `start()`.
Commands go out at 20 Hz (Driver), waits are bounded in wall time and fail at once when roslaunch or one
of its nodes died (catkin_overlay.LaunchWatch), and the ground truth is read with physics paused (`paused`).
"""
import subprocess
import sys
import unittest
from pathlib import Path

import rospy
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

from catkin_overlay import fixture_launch
from integration_common import Latest

STARTUP_TIMEOUT = 90.0  # wall s
WALL_TIMEOUT = 30.0


class Driver:
    """The latest `command` (a Twist, or None to send nothing) published on each of `topics` at 20 Hz of wall time
    until stopped, by a process of its own (twist_driver.py: why there)."""

    def __init__(self, *topics):
        self._proc = subprocess.Popen([sys.executable, str(Path(__file__).with_name('twist_driver.py'))]
                                      + list(topics), stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        if self._proc.stdout.readline().strip() != 'ready':
            raise RuntimeError('twist_driver.py did not start (exit code %s)' % self._proc.wait(timeout=10))
        self._command = None

    @property
    def command(self):
        return self._command

    @command.setter
    def command(self, cmd):
        self._command = cmd
        line = 'none' if cmd is None else '%r %r %r' % (cmd.linear.x, cmd.linear.y, cmd.angular.z)
        self._proc.stdin.write(line + '\n')
        self._proc.stdin.flush()

    def stop(self):
        if self._proc.poll() is None:
            self._proc.stdin.close()
            try:
                self._proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait()


def twist(vx, vy, wz):
    t = Twist()
    t.linear.x, t.linear.y, t.angular.z = vx, vy, wz
    return t


def running_controllers(ns):
    """The names of the controllers running under /<ns>/controller_manager; empty while it is not up."""
    service = '/%s/controller_manager/list_controllers' % ns
    try:
        rospy.wait_for_service(service, timeout=0.1)
        res = rospy.ServiceProxy(service, ListControllers)()
    except (rospy.ROSException, rospy.ServiceException):
        return set()
    return {c.name for c in res.controller if c.state == 'running'}


class FixtureRobotTest(unittest.TestCase):
    """NODE: the test node's name (or node_name()). A subclass's `start()` subscribes, calls `launch_fixture`, and waits
    (self.watch) for what its tests need; /clock is subscribed before it is called."""
    NODE = None
    launch = None
    drivers = ()

    @classmethod
    def setUpClass(cls):
        try:
            rospy.init_node(cls.node_name())
            cls.clock = Latest('/clock', Clock)
            cls.drivers = []
            cls.start()
        except BaseException:
            cls.tearDownClass()
            raise

    @classmethod
    def node_name(cls):
        return cls.NODE

    @classmethod
    def start(cls):
        raise NotImplementedError

    @classmethod
    def tearDownClass(cls):
        for driver in cls.drivers:
            driver.stop()
        if cls.launch is not None:
            cls.launch.stop()

    @classmethod
    def launch_fixture(cls, args, name):
        """`roslaunch ARGS` with the fixture packages on ROS_PACKAGE_PATH (catkin_overlay.fixture_launch)."""
        cls.launch, cls.watch = fixture_launch(args, name)

    @classmethod
    def driver(cls, *topics):
        driver = Driver(*topics)
        cls.drivers.append(driver)
        return driver

    @classmethod
    def collect_tf(cls):
        """cls.tf: the latest transform on /tf of each (parent, child)."""
        cls.tf = {}
        rospy.Subscriber('/tf', TFMessage, cls._on_tf, queue_size=100)

    @classmethod
    def _on_tf(cls, msg):
        for t in msg.transforms:
            cls.tf[(t.header.frame_id, t.child_frame_id)] = t

    @classmethod
    def gazebo_services(cls):
        """get_state, pause and unpause: gazebo_ros's get_model_state, pause_physics, unpause_physics."""
        for name in ('get_model_state', 'pause_physics', 'unpause_physics'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)

    # -- helpers ------------------------------------------------------------------------------
    def wait_for(self, condition, what, timeout=WALL_TIMEOUT):
        return self.watch.wait(condition, what, timeout, period=0.01)

    def now(self):
        """The sim time of the latest /clock (waits for a first one)."""
        self.wait_for(lambda: self.clock.msg, '/clock')
        return self.clock.msg.clock.to_sec()

    def sim_wait(self, seconds):
        end = self.now() + seconds
        self.wait_for(lambda: self.now() >= end, '%.1f s of sim time' % seconds)

    def paused(self, read):
        """(sim time, read()) with physics paused, read once two /clock messages came after the pause: the
        time is then the paused world's."""
        self.pause()
        try:
            count = self.clock.count
            self.wait_for(lambda: self.clock.count >= count + 2, 'a /clock while paused')
            return self.now(), read()
        finally:
            self.unpause()

    def assertWithin(self, value, expected, fraction, what):
        self.assertLessEqual(abs(value - expected), fraction * abs(expected),
                             '%s: %.4f, expected %.4f within %.0f %%' % (what, value, expected, 100 * fraction))

    def assertClose(self, value, expected, tolerance, what):
        self.assertLessEqual(abs(value - expected), tolerance, '%s: %.4f, expected %.4f +- %.4f'
                             % (what, value, expected, tolerance))
