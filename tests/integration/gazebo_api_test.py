#!/usr/bin/env python3
"""gazebo_ros's state and spawn services as upstream (gazebo_ros_api_plugin.cpp, noetic) answers them,
against a running world server with real PyBullet. Issue 16: row 2 (set_model_state's reference frame,
zero quaternion), row 6 (model::link names resolve to links; a model name as a link reference), row 7
(set_model_configuration passes over unknown joints), row 8 (spawn_sdf_model's reference_frame and
robot_namespace), set_link_state and the /gazebo/set_model_state, /gazebo/set_link_state topics, and
bad input answered with upstream's status messages while the world keeps running.

Models: 'arm' (URDF: link base, revolute 'hinge' about z at x = 0.3 to link arm_link) and 'box' (SDF:
link 'link' 0.5 m above the model frame), spawned paused at poses chosen so that every expected
number below is worked out by hand.
"""
import math
import unittest

import rospy
import rostest
from gazebo_msgs import srv
from gazebo_msgs.msg import LinkState, ModelState
from geometry_msgs.msg import Pose, Quaternion, Twist
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

import integration_common
from integration_common import yaw_of

WALL_TIMEOUT = 60.0
TOL = 1e-4
YAW_90 = Quaternion(0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))

LINK = ('<link name="{name}"><inertial><mass value="{mass}"/><inertia ixx="0.01" iyy="0.01" izz="0.01" '
        'ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
        '</collision></link>')
ARM_URDF = ('<robot name="arm">' + LINK.format(name='base', mass=1.0) + LINK.format(name='arm_link', mass=0.5) +
            '<joint name="hinge" type="continuous"><parent link="base"/><child link="arm_link"/>'
            '<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/></joint>{extra}</robot>')
CONTROL = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type><joint name="hinge">'
           '<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>'
           '<actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>'
           '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>')
BOX_SDF = ('<?xml version="1.0"?><sdf version="1.6"><model name="{name}"><static>{static}</static>'
           '<link name="link"><pose>0 0 {dz} 0 0 0</pose><collision name="c"><geometry><box><size>0.2 0.2 0.2'
           '</size></box></geometry></collision></link></model></sdf>')

SPAWN_EXISTS = 'SpawnModel: Failure - entity already exists.'
SPAWN_NO_FRAME = 'SpawnModel: reference reference_frame not found, did you forget to scope the link by model name?'


def pose(x=0.0, y=0.0, z=0.0, q=None):
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation = q if q is not None else Quaternion(0, 0, 0, 1)
    return p


def twist(lx=0.0, ly=0.0, lz=0.0, ax=0.0, ay=0.0, az=0.0):
    t = Twist()
    t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z = lx, ly, lz, ax, ay, az
    return t


class GazeboApiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('gazebo_api_test')
        names = {'spawn_urdf_model': srv.SpawnModel, 'spawn_sdf_model': srv.SpawnModel,
                 'get_model_state': srv.GetModelState, 'set_model_state': srv.SetModelState,
                 'get_link_state': srv.GetLinkState, 'set_link_state': srv.SetLinkState,
                 'set_model_configuration': srv.SetModelConfiguration, 'delete_model': srv.DeleteModel,
                 'get_world_properties': srv.GetWorldProperties, 'pause_physics': Empty,
                 'unpause_physics': Empty, 'reset_world': Empty}
        for name, cls_ in names.items():
            if name != 'set_link_state':  # advertised before set_model_configuration; its tests fail without it
                rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
            setattr(cls, name, rospy.ServiceProxy('/gazebo/' + name, cls_))
        cls.pause_physics()  # nothing moves between a set and the get that checks it
        res = cls.spawn_urdf_model('arm', ARM_URDF.format(extra=''), '', pose(0, 0, 1), 'world')
        assert res.success, res.status_message
        res = cls.spawn_sdf_model('box', BOX_SDF.format(name='box', static='false', dz=0.5), '',
                                  pose(5, 5, 0, YAW_90), '')
        assert res.success, res.status_message

    def setUp(self):
        # each test starts from the same places
        self.assertTrue(self.set_model_state(ModelState('box', pose(5, 5, 0, YAW_90), Twist(), 'world')).success)
        self.assertTrue(self.set_model_state(ModelState('arm', pose(0, 0, 1), Twist(), 'world')).success)
        self.assertTrue(self.set_model_configuration('arm', '', ['hinge'], [0.0]).success)

    def assert_pose(self, p, xyz, yaw=None):
        self.assertTrue(all(abs(a - b) < TOL for a, b in zip((p.position.x, p.position.y, p.position.z), xyz)),
                        'position %s, expected %s' % ((p.position.x, p.position.y, p.position.z), xyz))
        if yaw is not None:
            self.assertAlmostEqual(yaw_of(p.orientation), yaw, delta=TOL)

    def assert_vector(self, v, xyz):
        self.assertTrue(all(abs(a - b) < TOL for a, b in zip((v.x, v.y, v.z), xyz)),
                        'vector %s, expected %s' % ((v.x, v.y, v.z), xyz))

    def model(self, name, frame=''):
        res = self.get_model_state(name, frame)
        self.assertTrue(res.success, res.status_message)
        return res

    def link(self, name, frame=''):
        res = self.get_link_state(name, frame)
        self.assertTrue(res.success, res.status_message)
        return res.link_state

    # -- row 2: set_model_state --------------------------------------------------------------------------
    def test_row2_set_model_state_in_a_model_frame(self):
        # box's frame: (5, 5, 0), yawed 90 degrees; 1 m ahead of it is +y in the world; twists rotate too
        res = self.set_model_state(ModelState('arm', pose(1, 0, 0), twist(lx=1.0, az=0.5), 'box'))
        self.assertEqual((res.success, res.status_message), (True, 'SetModelState: set model state done'))
        got = self.model('arm')
        self.assert_pose(got.pose, (5, 6, 0), yaw=math.pi / 2)
        self.assert_vector(got.twist.linear, (0, 1, 0))
        self.assert_vector(got.twist.angular, (0, 0, 0.5))

    def test_row2_set_model_state_in_a_link_frame(self):
        # box::link sits 0.5 m above the box's model frame
        self.assertTrue(self.set_model_state(ModelState('arm', pose(1, 0, 0), Twist(), 'box::link')).success)
        self.assert_pose(self.model('arm').pose, (5, 6, 0.5), yaw=math.pi / 2)

    def test_row2_zero_quaternion_is_the_identity(self):
        res = self.set_model_state(ModelState('arm', pose(2, 0, 1, Quaternion(0, 0, 0, 0)), Twist(), 'world'))
        self.assertTrue(res.success, res.status_message)
        q = self.model('arm').pose.orientation
        self.assertAlmostEqual(abs(q.w), 1.0, delta=TOL)

    def test_row2_unknown_frame_fails(self):
        res = self.set_model_state(ModelState('arm', pose(9, 9, 9), Twist(), 'box::no_such_link'))
        self.assertEqual((res.success, res.status_message),
                         (False, 'SetModelState: specified reference frame entity does not exist'))
        self.assert_pose(self.model('arm').pose, (0, 0, 1))

    # -- row 6: model::link names --------------------------------------------------------------------------
    def test_row6_get_model_state_relative_to_a_link(self):
        self.assertTrue(self.set_model_state(ModelState('arm', pose(5, 6, 0.5, YAW_90), Twist(), 'world')).success)
        got = self.model('arm', 'box::link')
        self.assert_pose(got.pose, (1, 0, 0), yaw=0.0)
        self.assertEqual(got.header.frame_id, 'box::link')
        self.assert_pose(self.model('arm', 'box').pose, (1, 0, 0.5), yaw=0.0)  # the model frame is lower

    def test_row6_get_link_state_with_a_model_as_reference(self):
        got = self.link('arm::arm_link', 'box')
        # arm_link at (0.3, 0, 1) in the world; in box's frame: x' = y - 5, y' = -(x - 5)
        self.assert_pose(got.pose, (-5, 4.7, 1), yaw=-math.pi / 2)
        self.assertEqual(got.reference_frame, 'box')
        self.assert_pose(self.link('arm_link', 'arm').pose, (0.3, 0, 0))  # a bare link name: the first having it

    def test_row6_spawn_relative_to_a_link(self):
        res = self.spawn_urdf_model('arm2', ARM_URDF.format(extra=''), '', pose(1, 0, 0), 'box::link')
        self.assertTrue(res.success, res.status_message)
        self.addCleanup(self.delete_model, 'arm2')
        self.assert_pose(self.model('arm2').pose, (5, 6, 0.5), yaw=math.pi / 2)

    def test_row6_unknown_references(self):
        res = self.get_model_state('arm', 'box::nothing')
        self.assertEqual((res.success, res.status_message), (False, 'GetModelState: reference relative_entity_name '
                                                                    'not found, did you forget to scope the body by '
                                                                    'model name?'))
        res = self.get_link_state('arm::arm_link', 'nothing')
        self.assertEqual((res.success, res.status_message), (False, 'GetLinkState: reference reference_frame not '
                                                                    'found, did you forget to scope the link by model '
                                                                    'name?'))
        res = self.get_link_state('arm::nothing', '')
        self.assertEqual((res.success, res.status_message),
                         (False, 'GetLinkState: link not found, did you forget to scope the link by model name?'))
        res = self.get_link_state('arm', '')  # a model is no link
        self.assertFalse(res.success)
        res = self.get_model_state('arm::base', '')  # a link is no model
        self.assertEqual((res.success, res.status_message), (False, 'GetModelState: model does not exist'))

    # -- row 7: set_model_configuration --------------------------------------------------------------------
    def test_row7_unknown_joints_are_passed_over(self):
        res = self.set_model_configuration('arm', '', ['no_such_joint', 'hinge'], [1.0, 0.5])
        self.assertEqual((res.success, res.status_message), (True, 'SetModelConfiguration: success'))
        self.assert_pose(self.link('arm::arm_link', 'arm').pose, (0.3, 0, 0), yaw=0.5)
        # a scoped joint name is the joint too
        self.assertTrue(self.set_model_configuration('arm', '', ['arm::hinge'], [-0.25]).success)
        self.assertAlmostEqual(yaw_of(self.link('arm::arm_link', 'arm').pose.orientation), -0.25, delta=TOL)

    def test_row7_bad_requests(self):
        res = self.set_model_configuration('nobody', '', ['hinge'], [0.5])
        self.assertEqual((res.success, res.status_message), (False, 'SetModelConfiguration: model does not exist'))
        res = self.set_model_configuration('arm', '', ['hinge'], [0.5, 1.0])
        self.assertEqual((res.success, res.status_message),
                         (False, 'SetModelConfiguration: joint name and position list have different lengths'))
        res = self.set_model_configuration('arm', '', ['hinge'], [math.nan])
        self.assertFalse(res.success)
        self.assertIn('must be finite', res.status_message)

    # -- row 8: spawn_sdf_model ----------------------------------------------------------------------------
    def test_row8_spawn_sdf_relative_to_a_model_and_a_link(self):
        for name, frame, z in (('marker', 'box', 0.0), ('marker2', 'box::link', 0.5)):
            res = self.spawn_sdf_model(name, BOX_SDF.format(name='m', static='true', dz=0.0), '/ns',
                                       pose(1, 0, 0), frame)
            self.assertEqual((res.success, res.status_message), (True, 'SpawnModel: Successfully spawned entity'))
            self.addCleanup(self.delete_model, name)
            self.assert_pose(self.model(name).pose, (5, 6, z), yaw=math.pi / 2)
        res = self.spawn_sdf_model('marker3', BOX_SDF.format(name='m', static='true', dz=0.0), '', pose(),
                                   'box::nothing')
        self.assertEqual((res.success, res.status_message), (False, SPAWN_NO_FRAME))
        self.assertNotIn('marker3', self.get_world_properties().model_names)

    def test_row8_spawn_sdf_model_takes_a_urdf_with_its_robot_namespace(self):
        res = self.spawn_sdf_model('ctl', ARM_URDF.format(extra=CONTROL), '/sdf_ns', pose(-3, 0, 1), '')
        self.assertTrue(res.success, res.status_message)
        self.addCleanup(self.delete_model, 'ctl')
        rospy.wait_for_service('/sdf_ns/controller_manager/list_controllers', timeout=WALL_TIMEOUT)

    def test_set_model_state_moves_every_link_of_a_static_sdf_model_and_reset_world_puts_it_back(self):
        shelf = ('<sdf version="1.6"><model name="shelf"><static>true</static>' + ''.join(
            '<link name="%s"><pose>0 0 %g 0 0 0</pose><collision name="c"><geometry><box><size>0.2 0.2 0.2</size>'
            '</box></geometry></collision></link>' % (name, z) for name, z in (('base', 0.1), ('top', 1.0))) +
            '</model></sdf>')
        self.assertTrue(self.spawn_sdf_model('shelf', shelf, '', pose(0, 3, 0), '').success)
        self.addCleanup(self.delete_model, 'shelf')
        res = self.set_model_state(ModelState('shelf', pose(0, 4, 0, YAW_90), Twist(), ''))
        self.assertTrue(res.success, res.status_message)  # Gazebo moves static models too
        self.assert_pose(self.model('shelf').pose, (0, 4, 0), yaw=math.pi / 2)
        self.assert_pose(self.link('shelf::top').pose, (0, 4, 1), yaw=math.pi / 2)
        self.reset_world()
        self.assert_pose(self.model('shelf').pose, (0, 3, 0), yaw=0.0)
        self.assert_pose(self.link('shelf::top').pose, (0, 3, 1), yaw=0.0)

    # -- set_link_state ---------------------------------------------------------------------------------
    def test_set_link_state_of_an_sdf_link(self):
        res = self.set_link_state(LinkState('box::link', pose(2, -3, 1), twist(lx=1.0), 'world'))
        self.assertEqual((res.success, res.status_message), (True, 'SetLinkState: success'))
        got = self.link('box::link')
        self.assert_pose(got.pose, (2, -3, 1), yaw=0.0)
        self.assert_vector(got.twist.linear, (1, 0, 0))
        self.assert_pose(self.model('box').pose, (2, -3, 0.5), yaw=0.0)

    def test_set_link_state_of_a_urdf_link_in_a_link_frame(self):
        self.assertTrue(self.set_link_state(LinkState('box::link', pose(2, -3, 1), Twist(), '')).success)
        res = self.set_link_state(LinkState('arm::arm_link', pose(0, 0, 1, YAW_90), Twist(), 'box::link'))
        self.assertTrue(res.success, res.status_message)
        self.assert_pose(self.link('arm::arm_link').pose, (2, -3, 2), yaw=math.pi / 2)
        # the model came along: base is 0.3 m behind arm_link along arm_link's x (world +y)
        self.assert_pose(self.model('arm').pose, (2, -3.3, 2), yaw=math.pi / 2)

    def test_set_link_state_bad_requests(self):
        res = self.set_link_state(LinkState('box::link', pose(1, 1, 1), Twist(), 'box'))  # a model: no link
        self.assertEqual((res.success, res.status_message), (False, 'SetLinkState: failed'))
        res = self.set_link_state(LinkState('box::nothing', pose(1, 1, 1), Twist(), ''))
        self.assertEqual((res.success, res.status_message), (False, 'SetLinkState: link does not exist'))
        res = self.set_link_state(LinkState('box::link', pose(math.inf, 1, 1), Twist(), ''))
        self.assertFalse(res.success)
        self.assertIn('not finite', res.status_message)
        self.assert_pose(self.model('box').pose, (5, 5, 0))

    # -- the topics ---------------------------------------------------------------------------------------
    def test_set_state_topics(self):
        models = rospy.Publisher('/gazebo/set_model_state', ModelState, queue_size=1)
        links = rospy.Publisher('/gazebo/set_link_state', LinkState, queue_size=1)
        self.addCleanup(models.unregister)
        self.addCleanup(links.unregister)
        for pub in (models, links):
            integration_common.wait_for(lambda: pub.get_num_connections() > 0, 'the world server to subscribe',
                                        timeout=WALL_TIMEOUT)
        models.publish(ModelState('arm', pose(1, 0, 0), Twist(), 'box'))
        integration_common.wait_for(lambda: abs(self.model('arm').pose.position.y - 6) < TOL,
                                    'arm moved by /gazebo/set_model_state', timeout=WALL_TIMEOUT)
        links.publish(LinkState('box::link', pose(7, 7, 1), Twist(), ''))
        integration_common.wait_for(lambda: abs(self.link('box::link').pose.position.x - 7) < TOL,
                                    'box::link moved by /gazebo/set_link_state', timeout=WALL_TIMEOUT)

    # -- point 6: bad input --------------------------------------------------------------------------------
    def test_bad_model_state_requests(self):
        res = self.set_model_state(ModelState('nobody', pose(), Twist(), ''))
        self.assertEqual((res.success, res.status_message), (False, 'SetModelState: model does not exist'))
        res = self.set_model_state(ModelState('arm', pose(math.nan, 0, 0), Twist(), ''))
        self.assertFalse(res.success)
        self.assertIn('pose of model [arm] is not finite', res.status_message)
        res = self.set_model_state(ModelState('arm', pose(), twist(az=math.inf), ''))
        self.assertFalse(res.success)
        self.assertIn('twist of model [arm] is not finite', res.status_message)
        res = self.get_model_state('nobody', '')
        self.assertEqual((res.success, res.status_message), (False, 'GetModelState: model does not exist'))
        res = self.delete_model('nobody')
        self.assertEqual((res.success, res.status_message), (False, 'DeleteModel: model does not exist'))
        self.assert_pose(self.model('arm').pose, (0, 0, 1))

    def test_bad_spawn_requests(self):
        bad = [
            (self.spawn_urdf_model, '', 'SpawnModel: Failure - entity format is invalid.'),
            (self.spawn_urdf_model, '<robot name="x"><link name="a"></robot', 'SpawnModel: Failure - entity format '
                                                                              'is invalid.'),
            (self.spawn_urdf_model, BOX_SDF.format(name='m', static='true', dz=0), 'SpawnModel: Failure - entity '
                                                                                   'format is invalid.'),
            (self.spawn_sdf_model, '', 'GazeboRosApiPlugin SpawnModel Failure: input model_xml not SDF or URDF, or '
                                       'cannot be converted to Gazebo compatible format.'),
            (self.spawn_sdf_model, '<sdf version="1.6"><model name="m"></model></sdf>',
             'SpawnModel: Entity pushed to spawn queue, but spawn service timed out waiting for entity to appear in '
             'simulation under the name ghost'),
            (self.spawn_urdf_model, '<robot name="x"/>', 'SpawnModel: Entity pushed to spawn queue, but spawn service '
                                                         'timed out waiting for entity to appear in simulation under '
                                                         'the name ghost'),
        ]
        # a package:// of a package that is not on the ROS package path refuses the URDF spawn (upstream's
        # spawnURDFModel checks every package:// before anything else, the model's name included)
        nopkg = ARM_URDF.format(extra='<link name="m"><visual><geometry><mesh filename="package://nopkg/m.stl"/>'
                                      '</geometry></visual></link><joint name="j" type="fixed"><parent link="base"/>'
                                      '<child link="m"/></joint>')
        bad += [(self.spawn_urdf_model, nopkg, 'urdf reference package name does not exist: nopkg')]
        res = self.spawn_urdf_model('arm', nopkg, '', pose(), '')
        self.assertEqual((res.success, res.status_message),
                         (False, 'urdf reference package name does not exist: nopkg'))
        for spawn, xml, status in bad:
            res = spawn('ghost', xml, '', pose(), '')
            self.assertFalse(res.success, xml)
            if 'package name' in status:
                self.assertEqual(res.status_message, status, xml)
            else:  # upstream's words, then the reason (upstream's is only in its log)
                self.assertTrue(res.status_message.startswith(status + (': ' if 'timed out' in status else ' ')),
                                res.status_message)
                self.assertGreater(len(res.status_message), len(status) + 10, res.status_message)
        res = self.spawn_urdf_model('ghost', ARM_URDF.format(extra=''), '', pose(math.nan), '')
        self.assertFalse(res.success)
        self.assertIn('not finite', res.status_message)
        for spawn, name, xml in ((self.spawn_urdf_model, 'arm', ARM_URDF.format(extra='')),
                                 (self.spawn_sdf_model, 'box', BOX_SDF.format(name='b', static='true', dz=0))):
            res = spawn(name, xml, '', pose(), '')
            self.assertEqual((res.success, res.status_message), (False, SPAWN_EXISTS))
        self.assertEqual(sorted(self.get_world_properties().model_names), ['arm', 'box', 'ground_plane'])

    def test_rendering_enabled_is_true_without_a_window(self):
        # gazebo_ros hard-codes it (its world->GetRenderEngineEnabled() is commented out); no window here
        res = self.get_world_properties()
        self.assertTrue(res.success)
        self.assertTrue(res.rendering_enabled)

    def test_zz_world_keeps_running(self):
        clock = integration_common.Latest('/clock', Clock)
        self.addCleanup(clock.sub.unregister)
        start = integration_common.wait_for(lambda: clock.msg, '/clock', timeout=WALL_TIMEOUT).clock.to_sec()
        self.unpause_physics()
        self.addCleanup(self.pause_physics)
        integration_common.wait_for(lambda: clock.msg.clock.to_sec() > start + 0.5, 'sim time to advance',
                                    timeout=WALL_TIMEOUT)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'gazebo_api', GazeboApiTest)
