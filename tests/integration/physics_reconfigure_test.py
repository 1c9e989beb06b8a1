#!/usr/bin/env python3
"""gazebo_ros's physics dynamic_reconfigure server, black box, against a running world server.

As gazebo_ros_api_plugin (noetic): /gazebo/set_parameters, parameter_descriptions and
parameter_updates describe Physics.cfg's 15 parameters (names, types, defaults, limits); the first
configuration is the world's; a reconfigure changes the world as set_physics_properties does;
`rosrun dynamic_reconfigure dynparam get /gazebo` reads it. racebot's on-purpose difference: a
set_physics_properties call is published on parameter_updates (upstream's server would keep stale
numbers and put them back at the next reconfigure), and a refused value is not kept.
"""
import subprocess
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from gazebo_msgs.srv import GetPhysicsProperties, SetPhysicsProperties
from geometry_msgs.msg import Vector3

from integration_common import wait_for

WALL_TIMEOUT = 60.0
# gazebo_ros/cfg/Physics.cfg (noetic): name -> (type, default, min, max)
PHYSICS_CFG = {
    'time_step': ('double', 0.001, 0.0, 10.0),
    'max_update_rate': ('double', 60.0, 0.0, 1000.0),
    'gravity_x': ('double', 0.0, -100.0, 100.0),
    'gravity_y': ('double', 0.0, -100.0, 100.0),
    'gravity_z': ('double', -9.8, -100.0, 100.0),
    'auto_disable_bodies': ('bool', False, False, True),
    'sor_pgs_precon_iters': ('int', 0, 0, 10000),
    'sor_pgs_iters': ('int', 20, 0, 10000),
    'sor_pgs_w': ('double', 1.3, 0.0, 5.0),
    'sor_pgs_rms_error_tol': ('double', -1.0, -1.0, 10000.0),
    'cfm': ('double', 0.0, 0.0, 10.0),
    'erp': ('double', 0.2, 0.0, 10.0),
    'contact_surface_layer': ('double', 0.001, 0.0, 10.0),
    'contact_max_correcting_vel': ('double', 100.0, 0.0, 10000000.0),
    'max_contacts': ('int', 100, 0, 10000000),
}


class PhysicsReconfigureTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('physics_reconfigure_test')
        for name in ('get_physics_properties', 'set_physics_properties', 'set_parameters'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        cls.get = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        cls.set = rospy.ServiceProxy('/gazebo/set_physics_properties', SetPhysicsProperties)
        cls.updates = []
        cls.client = Client('/gazebo', timeout=WALL_TIMEOUT, config_callback=cls.updates.append)

    def world(self):
        return self.get()

    def latest(self):
        return self.client.get_configuration(timeout=WALL_TIMEOUT)

    def test_1_descriptions_are_physics_cfg(self):
        described = {}
        for group in self.client.get_group_descriptions(timeout=WALL_TIMEOUT)['parameters']:
            name = group['name']
            described[name] = (group['type'], group['default'], group['min'], group['max'])
        self.assertEqual(described, PHYSICS_CFG)

    def test_2_first_configuration_is_the_worlds(self):
        w, c = self.world(), self.latest()
        self.assertEqual((c['time_step'], c['max_update_rate']), (w.time_step, w.max_update_rate))
        self.assertEqual((c['gravity_x'], c['gravity_y'], c['gravity_z']), (w.gravity.x, w.gravity.y, w.gravity.z))
        self.assertEqual((c['sor_pgs_iters'], c['max_contacts'], c['erp']),
                         (w.ode_config.sor_pgs_iters, w.ode_config.max_contacts, w.ode_config.erp))

    def test_3_a_reconfigure_changes_the_world(self):
        before = self.world()
        c = self.client.update_configuration({'gravity_z': -2.5, 'sor_pgs_iters': 30})
        self.assertEqual((c['gravity_z'], c['sor_pgs_iters']), (-2.5, 30))
        w = self.world()
        self.assertEqual((w.gravity.z, w.ode_config.sor_pgs_iters), (-2.5, 30))
        self.assertEqual((w.time_step, w.max_update_rate, w.gravity.x), (before.time_step, before.max_update_rate,
                                                                         before.gravity.x))

    def test_4_set_physics_properties_is_published_and_not_undone(self):
        w = self.world()
        res = self.set(time_step=w.time_step, max_update_rate=w.max_update_rate, gravity=Vector3(0.5, 0, -4.0),
                       ode_config=w.ode_config)
        self.assertTrue(res.success, res.status_message)
        wait_for(lambda: self.updates and self.updates[-1]['gravity_z'] == -4.0,
                 'parameter_updates to show gravity_z -4.0', WALL_TIMEOUT)
        self.assertEqual(self.updates[-1]['gravity_x'], 0.5)
        self.client.update_configuration({'erp': 0.3})  # one parameter: the others stay the world's
        w = self.world()
        self.assertEqual((w.gravity.x, w.gravity.z, w.ode_config.erp), (0.5, -4.0, 0.3))

    def test_5_refused_and_clamped_values(self):
        step = self.world().time_step
        c = self.client.update_configuration({'time_step': 0.0})  # within Physics.cfg's limits; no step here
        self.assertEqual(c['time_step'], step, 'a refused time_step must not stay in the configuration')
        self.assertEqual(self.world().time_step, step)
        c = self.client.update_configuration({'sor_pgs_iters': 20000})  # above Physics.cfg's max: clamped
        self.assertEqual((c['sor_pgs_iters'], self.world().ode_config.sor_pgs_iters), (10000, 10000))

    def test_6_dynparam_get(self):
        done = subprocess.run(['rosrun', 'dynamic_reconfigure', 'dynparam', 'get', '/gazebo'], timeout=WALL_TIMEOUT,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.assertEqual(done.returncode, 0, done.stdout)
        for name in PHYSICS_CFG:
            self.assertIn("'%s'" % name, done.stdout)
        self.assertIn("'gravity_z': %r" % self.world().gravity.z, done.stdout)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'physics_reconfigure', PhysicsReconfigureTest)
