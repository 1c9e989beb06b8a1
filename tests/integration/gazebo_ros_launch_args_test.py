#!/usr/bin/env python3
"""gazebo_ros's empty_world.launch arguments that change what the world server offers or says
(issue 16, row 10 and the launch file's arguments).

The test node runs `roslaunch` of a launch file including $(find gazebo_ros)/launch/empty_world.launch
at the root namespace with enable_ros_network:=false, use_clock_frequency:=true pub_clock_frequency:=50,
debug:=true, recording:=true, physics:=bullet, extra_gazebo_args:=--lockstep and verbose:=true, and reads
its output:
  enable_ros_network false: the gazebo node offers only /clock (and rospy's logger services), as
    gazebo_ros_api_plugin does (no /gazebo/* services or state topics);
  pub_clock_frequency 50: /clock every 0.02 s of sim time, not at every 1 ms update;
  debug, recording, physics, verbose, an unknown gzserver option: each said once in the log;
  world_name's default worlds/empty.world: gazebo_ros's, found through GAZEBO_RESOURCE_PATH.
"""
import os
import shutil
import tempfile
import unittest

import rosgraph
import rospkg
import rospy
import rostest
from rosgraph_msgs.msg import Clock

from robustness_common import Process, wait_for

WORLD_LAUNCH = """<launch>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="gui" value="false"/>
    <arg name="enable_ros_network" value="false"/>
    <arg name="use_clock_frequency" value="true"/>
    <arg name="pub_clock_frequency" value="50"/>
    <arg name="debug" value="true"/>
    <arg name="recording" value="true"/>
    <arg name="physics" value="bullet"/>
    <arg name="extra_gazebo_args" value="--lockstep"/>
    <arg name="verbose" value="true"/>
  </include>
</launch>
"""
CLOCK_PERIOD = 1.0 / 50


class GazeboRosLaunchArgsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('gazebo_ros_launch_args_test', disable_rostime=True)
        cls.tmp = tempfile.mkdtemp(prefix='gazebo_ros_launch_args_')
        path = os.path.join(cls.tmp, 'world.launch')
        with open(path, 'w') as f:
            f.write(WORLD_LAUNCH)
        cls.stamps = []
        cls.clock_sub = rospy.Subscriber('/clock', Clock, lambda m: cls.stamps.append(m.clock.to_sec()),
                                         queue_size=200)
        cls.world = Process(['roslaunch', '--disable-title', path])
        try:  # the services would be advertised before the first /clock and the "loaded" line
            cls.world.wait_output('world ', ' loaded: ')
            wait_for(lambda: len(cls.stamps) > 0, 'the first /clock')
        except AssertionError:
            cls.tearDownClass()  # unittest skips it when setUpClass fails: the world would outlive the test
            raise

    @classmethod
    def tearDownClass(cls):
        cls.world.stop()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_enable_ros_network_false_leaves_only_the_clock(self):
        publishers, _, services = rosgraph.Master('/gazebo_ros_launch_args_test').getSystemState()
        offered = sorted(s for s, nodes in services if '/gazebo' in nodes)
        self.assertEqual(offered, ['/gazebo/get_loggers', '/gazebo/set_logger_level'])
        published = sorted(t for t, nodes in publishers if '/gazebo' in nodes)
        self.assertEqual(published, ['/clock', '/rosout'])

    def test_pub_clock_frequency_throttles_the_clock_in_sim_time(self):
        start = len(self.stamps)
        wait_for(lambda: len({round(t, 6) for t in self.stamps[start:]}) >= 20, '20 /clock stamps')
        distinct = sorted({round(t, 6) for t in self.stamps[start:]})
        gaps = [b - a for a, b in zip(distinct, distinct[1:])]
        self.assertGreaterEqual(min(gaps), CLOCK_PERIOD - 1e-6, gaps)
        self.assertLessEqual(min(gaps), CLOCK_PERIOD + 0.001 + 1e-6, gaps)  # the first update past the period

    def test_what_cannot_apply_is_said_once(self):
        text = self.world.text
        for says in ('debug:=true starts gzserver under gdb in Gazebo',
                     'recording:=true: there are no Gazebo state logs here',
                     '-e bullet (the physics engine is always PyBullet here)',
                     'gzserver option --lockstep has no meaning here',
                     '--verbose (verbose:=true): this world server logs all it has to say',
                     'ROS gazebo topics/services are disabled'):
            self.assertEqual(text.count(says), 1, '%r said %d times in:\n%s' % (says, text.count(says), text[-3000:]))

    def test_default_world_is_gazebo_ros_empty_world(self):
        expected = os.path.join(rospkg.RosPack().get_path('gazebo_ros'), 'worlds', 'empty.world')
        self.assertIn('world %s loaded: ' % os.path.realpath(expected), self.world.text)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'gazebo_ros_launch_args', GazeboRosLaunchArgsTest)
