#!/usr/bin/env python3
"""World files that cannot be used, and the simulator's lifecycle under a running spawner.

This test starts the simulators itself (rosrun world_server ...) so that it can read their output,
stop and restart them. Cases:
  missing / not-XML world file  -> the world server exits 1 with a fatal log naming the file and
                                   saying what to do;
  degenerate / unsupported geometry -> one warning per element, the element skipped, the model kept and
                                   listed (Gazebo's loader keeps it: a missing mesh, a link without
                                   shapes), the world loads and serves;
  a spawner started long before the simulator -> it waits (saying why), then loads and starts;
  the simulator restarted under a running spawner -> the new controller manager starts empty (as with
                                   ros_control); our spawner notices, says what to do and forgets its
                                   controllers; a new spawner starts them; nothing crashes.
"""
import os
import tempfile
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers

from robustness_common import WALL_TIMEOUT, SimProbe, rosrun, wait_for

CONTROLLERS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller',
               'joint_state_controller']
# The spawner's --timeout: short, so that the test sees it wait past it. The simulator starts paused and
# the car's spawn unpauses it, so the car's services are there when the clock starts (then the spawner's
# wait is a normal timeout again, and a slow spawn_model under load cannot use it up).
SPAWNER_TIMEOUT = 10.0

GOOD_BOX = '''<model name="good_box"><static>true</static><pose>3 0 0.5 0 0 0</pose><link name="link">
  <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link></model>'''
DEGENERATE = {
    'flat_box': '<box><size>1 0 1</size></box>',
    'negative_ball': '<sphere><radius>-0.5</radius></sphere>',
    'nan_cylinder': '<cylinder><radius>0.2</radius><length>nan</length></cylinder>',
    'mesh_thing': '<mesh><uri>model://thing/meshes/thing.dae</uri></mesh>',
}
# a link with neither collision nor visual: Gazebo keeps and lists its model
BARE = ('<model name="bare"><pose>0 -3 0.5 0 0 0</pose><link name="link"><inertial><mass>2</mass></inertial>'
        '</link></model>')


def world(body):
    return ('<?xml version="1.0"?><sdf version="1.6"><world name="default">'
            '<physics type="ode"><max_step_size>0.001</max_step_size>'
            '<real_time_update_rate>1000</real_time_update_rate></physics>'
            '<include><uri>model://ground_plane</uri></include>%s</world></sdf>' % body)


def bad_model(name, geometry):
    return ('<model name="%s"><pose>0 3 0.5 0 0 0</pose><link name="link"><collision name="c"><geometry>%s'
            '</geometry></collision></link></model>' % (name, geometry))


class RobustnessWorldTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('robustness_world_test')
        cls.sim = SimProbe()
        cls.tmp = tempfile.mkdtemp(prefix='robustness_world_')
        cls.processes = []

    @classmethod
    def tearDownClass(cls):
        for p in reversed(cls.processes):
            p.stop()

    def start(self, package, executable, *args):
        p = rosrun(package, executable, *args)
        self.processes.append(p)
        return p

    def write(self, name, text):
        path = os.path.join(self.tmp, name)
        with open(path, 'w') as f:
            f.write(text)
        return path

    def assert_no_crash(self, process):
        self.assertNotIn('Traceback', process.text, 'a Python exception in %s:\n%s'
                         % (' '.join(process.args), process.text[-3000:]))

    def list_controllers(self):
        rospy.wait_for_service('/racebot/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        return rospy.ServiceProxy('/racebot/controller_manager/list_controllers', ListControllers)().controller

    def running(self):
        try:
            return {c.name for c in self.list_controllers() if c.state == 'running'}
        except (rospy.ServiceException, rospy.ROSException):  # between two simulators
            return set()

    def start_simulator(self, world_file):
        """The world server and the car in it, as empty_world.launch paused:=true + spawn_model -unpause
        start them: the clock starts with the car's controller manager there, so the spawner's short
        --timeout counts from a spawned car, not from however long spawn_model takes to start under load."""
        server = self.start('racebot_sim_bridge', 'world_server', '-u', world_file, '__name:=gazebo')
        self.sim.clock = None
        self.sim.wait_ready()
        spawn = rosrun('gazebo_ros', 'spawn_model', '-urdf', '-model', 'racebot', '-param',
                       '/robot_description', '-timeout', '60', '-unpause')
        self.assertEqual(spawn.wait_exit(), 0, spawn.text)
        return server

    def start_spawner(self, name, *extra):
        return self.start('controller_manager', 'spawner', *(list(extra) + CONTROLLERS +
                                                             ['__ns:=/racebot', '__name:=%s' % name]))

    # -- world files ------------------------------------------------------------------------------
    def test_1_missing_world_file_is_fatal_naming_the_file(self):
        path = os.path.join(self.tmp, 'no_such_dir', 'missing.world')
        p = self.start('racebot_sim_bridge', 'world_server', path, '__name:=gazebo_missing')
        self.assertEqual(p.wait_exit(), 1, p.text)
        self.assertIn('[FATAL]', p.text)
        self.assertIn("world file '%s' not found" % path, p.text)
        self.assertIn('pass an existing file', p.text)
        self.assert_no_crash(p)

    def test_2_world_file_not_xml_is_fatal_naming_the_file(self):
        path = self.write('broken.world', '<sdf version="1.6"><world name="x"><model name="m"></world>')
        p = self.start('racebot_sim_bridge', 'world_server', path, '__name:=gazebo_broken')
        self.assertEqual(p.wait_exit(), 1, p.text)
        self.assertIn('[FATAL]', p.text)
        self.assertIn('%s is not valid XML' % path, p.text)
        self.assertIn('line 1', p.text)
        self.assertIn('check it with xmllint', p.text)
        self.assert_no_crash(p)

    def test_3_degenerate_geometry_is_skipped_with_a_warning_its_model_kept_and_the_world_loads(self):
        # a mesh named in other capitals than the file on disk (a model made on Windows): kept, 'did you mean'
        on_disk = self.write('Lamp_Shade.DAE', 'not read: the name is what matters')
        capitals = {'mesh_capitals': '<mesh><uri>file://%s</uri></mesh>' % os.path.join(self.tmp, 'lamp_shade.DAE')}
        path = self.write('degenerate.world', world(GOOD_BOX + BARE + ''.join(
            bad_model(name, geometry) for name, geometry in sorted(dict(DEGENERATE, **capitals).items()))))
        p = self.start('racebot_sim_bridge', 'world_server', path, '__name:=gazebo')
        self.sim.clock = None
        self.sim.wait_ready()
        res = self.sim.assert_serving(self, sim_seconds=0.5)
        self.assertIn('good_box', res.model_names)
        self.assertIn('ground_plane', res.model_names)
        self.assertIn('bare', res.model_names)
        for name in list(DEGENERATE) + list(capitals):
            self.assertIn(name, res.model_names)  # as Gazebo: the model stays, its link without the shape
            warnings = [line for line in p.text.splitlines() if '[WARN]' in line and "model '%s'" % name in line]
            self.assertTrue(warnings, 'no warning names %s:\n%s' % (name, p.text[-3000:]))
        self.assertIn('box size must be > 0, got 1 0 1', p.text)
        self.assertIn('sphere radius must be > 0', p.text)
        self.assertIn('cylinder length must be finite', p.text)
        self.assertIn('model://thing/meshes/thing.dae not found; searched', p.text)  # a mesh that is nowhere
        self.assertIn('did you mean %s?' % on_disk, p.text)
        self.assertTrue(p.alive())
        self.assertEqual(p.stop(), 0, p.text[-3000:])
        self.assert_no_crash(p)

    # -- the spawner and the simulator's lifecycle --------------------------------------------------
    def test_4_spawner_started_long_before_the_simulator_waits_then_succeeds(self):
        spawner = self.start_spawner('early_spawner', '--timeout', str(SPAWNER_TIMEOUT))
        spawner.wait_output('is not there after', 'the simulator is probably still starting')
        time.sleep(5.0)  # well past its timeout: it must still be waiting
        self.assertTrue(spawner.alive(), spawner.text)
        RobustnessWorldTest.early_spawner = spawner
        RobustnessWorldTest.server = self.start_simulator('worlds/empty.world')
        try:
            wait_for(lambda: self.running() == set(CONTROLLERS), 'the early spawner to start the seven controllers')
        except AssertionError:
            raise AssertionError('the early spawner did not start the controllers; its output:\n' + spawner.text)
        spawner.wait_output('Started controllers')
        self.assertTrue(spawner.alive())
        self.sim.assert_serving(self)
        self.assert_no_crash(spawner)

    def test_5_simulator_restarted_under_a_running_spawner(self):
        spawner = self.early_spawner
        self.assertEqual(self.server.stop(), 0, self.server.text[-3000:])
        warning = spawner.wait_output('the controller manager this spawner loaded', 'is gone')
        self.assertTrue(warning)
        self.assertIn('start a new spawner', spawner.text)
        self.assertTrue(spawner.alive(), 'the spawner must survive its simulator:\n' + spawner.text)
        RobustnessWorldTest.server = self.start_simulator('worlds/empty.world')
        # A new controller manager starts empty, as with ros_control: the old spawner loads nothing.
        time.sleep(3.0)
        self.assertEqual(self.list_controllers(), [])
        self.assertTrue(spawner.alive())
        second = self.start_spawner('second_spawner')
        wait_for(lambda: self.running() == set(CONTROLLERS), 'a new spawner to start the seven controllers')
        # The old spawner's shutdown must not take down what the new one started.
        self.assertEqual(spawner.stop(), 0, spawner.text[-3000:])
        time.sleep(2.0)
        self.assertEqual(self.running(), set(CONTROLLERS))
        self.sim.assert_serving(self)
        for p in (spawner, second, self.server):
            self.assert_no_crash(p)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'robustness_world', RobustnessWorldTest)
