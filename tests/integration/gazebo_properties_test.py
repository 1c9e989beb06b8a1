#!/usr/bin/env python3
"""gazebo_ros's property, physics, light and force services, black box, on a paused empty world.

The test spawns a probe (a base with a plate fixed to it, lumped as Gazebo lumps it, and an arm on a
revolute hinge) and a puck (one box) high above the ground, and judges motion over sim-time intervals
it measures itself: it pauses the world, reads the state (stamped), unpauses for an interval, pauses
again and reads again. Bad requests must be answered with success false and gazebo_ros's message.
"""
import functools
import unittest

import rospy
import rostest

import integration_common  # next to this file
from gazebo_msgs.msg import ModelState, ODEJointProperties, PerformanceMetrics
from gazebo_msgs.srv import (ApplyBodyWrench, ApplyJointEffort, BodyRequest, DeleteLight, DeleteModel,
                             GetJointProperties,
                             GetLightProperties, GetLinkProperties, GetModelProperties, GetModelState,
                             GetPhysicsProperties, JointRequest, SetJointProperties, SetLightProperties,
                             SetLinkProperties, SetModelConfiguration, SetModelState, SetPhysicsProperties,
                             SpawnModel)
from geometry_msgs.msg import Point, Pose, Quaternion, Wrench, Vector3
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty

WALL_TIMEOUT = 60.0
wait_for = functools.partial(integration_common.wait_for, timeout=WALL_TIMEOUT, period=0.005)

PROBE = """<robot name="probe">
  <link name="base">
    <inertial><origin xyz="0 0 0.05"/><mass value="2.0"/>
      <inertia ixx="0.02" iyy="0.03" izz="0.04" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.3 0.3 0.1"/></geometry></collision>
  </link>
  <link name="plate">
    <inertial><mass value="0.3"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.01"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.002" izz="0.003" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="plate_fixed" type="fixed"><parent link="base"/><child link="plate"/></joint>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="5" velocity="10"/></joint>
</robot>"""

PUCK = """<robot name="puck"><link name="body">
  <inertial><mass value="1.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>"""

IMU_PROBE = """<robot name="imu_probe"><link name="body">
  <inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <gazebo reference="body"><sensor name="imu_sensor" type="imu"><always_on>true</always_on>
    <update_rate>50</update_rate>
    <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"><topicName>/probe_imu</topicName>
      <updateRateHZ>50.0</updateRateHZ><frameName>body</frameName></plugin></sensor></gazebo></robot>"""

HIGH = 60.0  # m: where the bodies are put before each measurement (no ground within a few seconds)


def pose(x, y, z):
    return Pose(position=Point(x, y, z), orientation=Quaternion(0, 0, 0, 1))


class GazeboPropertiesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('gazebo_properties_test')
        cls.clock = None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)
        services = dict(
            spawn_urdf_model=SpawnModel, delete_model=DeleteModel, get_model_state=GetModelState,
            set_model_configuration=SetModelConfiguration, set_model_state=SetModelState,
            pause_physics=Empty, unpause_physics=Empty, get_model_properties=GetModelProperties,
            get_joint_properties=GetJointProperties, get_link_properties=GetLinkProperties,
            set_link_properties=SetLinkProperties, set_joint_properties=SetJointProperties,
            get_physics_properties=GetPhysicsProperties, set_physics_properties=SetPhysicsProperties,
            get_light_properties=GetLightProperties, set_light_properties=SetLightProperties,
            delete_light=DeleteLight, reset_world=Empty, apply_body_wrench=ApplyBodyWrench,
            apply_joint_effort=ApplyJointEffort,
            clear_body_wrenches=BodyRequest, clear_joint_forces=JointRequest)
        cls.srv = {}
        for name, cls_ in services.items():
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
            cls.srv[name] = rospy.ServiceProxy('/gazebo/' + name, cls_)
        for name, xml, x in (('probe', PROBE, 0.0), ('puck', PUCK, 5.0)):
            res = cls.srv['spawn_urdf_model'](name, xml, '', pose(x, 0, HIGH), 'world')
            assert res.success, res.status_message
        physics = cls.srv['get_physics_properties']()
        cls.gravity = physics.gravity.z
        # The empty world's pace, kept throughout (see run_for).
        cls.max_update_rate = physics.max_update_rate
        assert abs(cls.max_update_rate * physics.time_step - 1.0) < 1e-9, 'the test needs a world paced at real time'

    @classmethod
    def _on_clock(cls, msg):
        cls.clock = msg.clock.to_sec()

    def call(self, name, *args, **kwargs):
        return self.srv[name](*args, **kwargs)

    def refused(self, res, message):
        self.assertFalse(res.success, 'a bad request must fail')
        self.assertEqual(res.status_message, message)

    # -- time ---------------------------------------------------------------------------------------
    def state(self, model):
        res = self.call('get_model_state', model, 'world')
        self.assertTrue(res.success, res.status_message)
        return res

    def place(self, model, x):
        """`model` at rest at (x, 0, HIGH), joints as they are; the world paused."""
        self.call('pause_physics')
        self.assertTrue(self.call('set_model_state', ModelState(model_name=model, pose=pose(x, 0, HIGH),
                                                                reference_frame='world')).success)

    def run_for(self, seconds):
        """Unpauses for about `seconds` of sim time, pauses; returns the sim time at the pause.

        The run ends when the test has seen the time pass and paused: it lasts longer by the test's
        reaction time in sim time. In real time, as the empty world runs, that is what a busy machine
        makes of it (a few ms to some tenths of a second); as fast as possible (~20 x real time) a 0.5 s
        run lasted 14 s on a busy machine, so the falling bodies hit the ground and a spinning arm
        its joint limit. The tests measure the sim time each run lasted and judge with that.
        """
        start = self.state('probe').header.stamp.to_sec()
        self.call('unpause_physics')
        wait_for(lambda: self.clock is not None and self.clock >= start + seconds, '%g s of sim time' % seconds)
        self.call('pause_physics')
        return self.state('probe').header.stamp.to_sec()

    def fall(self, model, x, seconds):
        """(drop in z, sim time elapsed) of `model` released at rest."""
        self.place(model, x)
        t0 = self.state(model).header.stamp.to_sec()
        t1 = self.run_for(seconds)
        return HIGH - self.state(model).pose.position.z, t1 - t0

    def masses(self, model):
        names = self.call('get_model_properties', model).body_names
        return {n: self.call('get_link_properties', '%s::%s' % (model, n)).mass for n in names}

    # -- properties -----------------------------------------------------------------------------------
    def test_01_model_properties_are_the_urdfs_after_lumping(self):
        res = self.call('get_model_properties', 'probe')
        self.assertTrue(res.success)
        self.assertEqual(res.status_message, 'GetModelProperties: got properties')
        self.assertEqual(list(res.body_names), ['base', 'arm'])
        self.assertEqual(list(res.joint_names), ['hinge'])
        self.assertEqual(list(res.geom_names), ['base_collision', 'base_fixed_joint_lump__plate_collision_1',
                                                'arm_collision'])
        self.assertFalse(res.is_static)
        ground = self.call('get_model_properties', 'ground_plane')  # an SDF model of the world file
        self.assertEqual((list(ground.body_names), list(ground.geom_names), ground.is_static),
                         (['link'], ['collision'], True))
        self.refused(self.call('get_model_properties', 'nope'), 'GetModelProperties: model does not exist')

    def test_02_link_properties_are_the_urdfs(self):
        arm = self.call('get_link_properties', 'probe::arm')
        self.assertTrue(arm.success)
        self.assertEqual(arm.status_message, 'GetLinkProperties: got properties')
        self.assertAlmostEqual(arm.mass, 0.5, places=9)
        for field, value in zip(('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz'), (0.001, 0.002, 0.003, 0, 0, 0)):
            self.assertAlmostEqual(getattr(arm, field), value, places=9, msg=field)
        self.assertTrue(arm.gravity_mode)
        base = self.call('get_link_properties', 'probe::base')
        self.assertAlmostEqual(base.mass, 2.3, places=9)  # the plate is lumped into it, as Gazebo does
        self.assertAlmostEqual(base.com.position.z, 2.0 * 0.05 / 2.3, places=6)
        ground = self.call('get_link_properties', 'ground_plane::link')  # static: the SDF's inertial, as Gazebo
        self.assertEqual((ground.success, ground.mass), (True, 1.0))
        self.refused(self.call('get_link_properties', 'probe::nope'),
                     'GetLinkProperties: link not found, did you forget to scope the link by model name?')
        self.refused(self.call('get_link_properties', 'probe'),  # a model is not a link
                     'GetLinkProperties: link not found, did you forget to scope the link by model name?')

    def test_03_joint_properties(self):
        res = self.call('get_joint_properties', 'hinge')
        self.assertTrue(res.success)
        self.assertEqual(res.status_message, 'GetJointProperties: got properties')
        self.assertEqual((res.type, len(res.position), len(res.rate)), (res.REVOLUTE, 1, 1))
        self.assertTrue(self.call('get_joint_properties', 'probe::hinge').success)
        self.refused(self.call('get_joint_properties', 'nope'), 'GetJointProperties: joint not found')

    # -- physics --------------------------------------------------------------------------------------
    def physics_request(self, **changes):
        now = self.call('get_physics_properties')
        req = dict(time_step=now.time_step, max_update_rate=now.max_update_rate, gravity=now.gravity,
                   ode_config=now.ode_config)
        req.update(changes)
        return self.call('set_physics_properties', **req)

    def test_04_max_update_rate_paces_the_world(self):
        metrics = integration_common.Latest('/gazebo/performance_metrics', PerformanceMetrics)
        res = self.physics_request(max_update_rate=100.0)
        self.assertEqual((res.success, res.status_message), (True, 'physics engine updated'))
        self.assertEqual(self.call('get_physics_properties').max_update_rate, 100.0)
        self.call('unpause_physics')
        try:
            seen = metrics.count
            # the second message after the change covers an interval paced at 100 updates/s: 0.1 x real time
            msg = wait_for(lambda: metrics.msg if metrics.count >= seen + 2 else None, 'two performance metrics')
            self.assertLess(msg.real_time_factor, 0.3)
            self.assertGreater(msg.real_time_factor, 0.0)
            self.assertEqual(list(msg.sensors), [])  # no sensor in this world
        finally:
            self.call('pause_physics')
            metrics.sub.unregister()
            self.assertTrue(self.physics_request(max_update_rate=self.max_update_rate).success)

    def test_05_set_gravity_changes_the_fall(self):
        self.assertTrue(self.physics_request(gravity=Vector3(0, 0, -2.0)).success)
        try:
            self.assertEqual(self.call('get_physics_properties').gravity.z, -2.0)
            drop, t = self.fall('puck', 5.0, 0.5)
            self.assertAlmostEqual(drop, 0.5 * 2.0 * t * t, delta=0.02 * drop)
        finally:
            self.assertTrue(self.physics_request(gravity=Vector3(0, 0, self.gravity)).success)
        drop, t = self.fall('puck', 5.0, 0.5)
        self.assertAlmostEqual(drop, 0.5 * -self.gravity * t * t, delta=0.02 * drop)

    def test_06_time_step_changes_and_time_goes_on(self):
        self.call('pause_physics')
        before = self.state('probe').header.stamp.to_sec()
        self.assertTrue(self.physics_request(time_step=0.002).success)
        try:
            self.assertEqual(self.call('get_physics_properties').time_step, 0.002)
            after = self.run_for(0.1)
            self.assertGreater(after, before)
            # every update is now 2 ms: the time stays on the 2 ms grid counted from the change
            steps = (after - before) / 0.002
            self.assertAlmostEqual(steps, round(steps), delta=1e-3)
        finally:
            self.assertTrue(self.physics_request(time_step=0.001).success)

    def test_07_bad_physics_requests(self):
        res = self.physics_request(time_step=0.0)
        self.assertFalse(res.success)
        self.assertIn('time_step must be a positive number', res.status_message)
        self.assertFalse(self.physics_request(gravity=Vector3(0, 0, float('nan'))).success)
        self.assertFalse(self.physics_request(max_update_rate=-1.0).success)
        self.assertEqual(self.call('get_physics_properties').time_step, 0.001)  # nothing changed

    def test_07b_ode_config_is_kept(self):
        ode = self.call('get_physics_properties').ode_config
        self.assertEqual(ode.sor_pgs_iters, 50)
        ode.sor_pgs_iters, ode.erp = 30, 0.3
        self.assertTrue(self.physics_request(ode_config=ode).success)
        try:
            now = self.call('get_physics_properties').ode_config
            self.assertEqual((now.sor_pgs_iters, now.erp), (30, 0.3))
        finally:
            ode.sor_pgs_iters, ode.erp = 50, 0.2
            self.assertTrue(self.physics_request(ode_config=ode).success)

    # -- forces ---------------------------------------------------------------------------------------
    def wrench(self, body, force, reference_frame='', point=(0, 0, 0), duration=-1.0, torque=(0, 0, 0)):
        return self.call('apply_body_wrench', body_name=body, reference_frame=reference_frame,
                         reference_point=Point(*point), wrench=Wrench(force=Vector3(*force), torque=Vector3(*torque)),
                         start_time=rospy.Time(0), duration=rospy.Duration.from_sec(duration))

    def test_08_m_g_up_cancels_gravity_until_cleared(self):
        weight = sum(self.masses('probe').values()) * -self.gravity
        self.place('probe', 0.0)
        res = self.wrench('probe::base', (0, 0, weight))
        self.assertEqual((res.success, res.status_message), (True, ''))
        self.run_for(1.0)
        self.assertAlmostEqual(self.state('probe').pose.position.z, HIGH, delta=1e-3)
        self.call('clear_body_wrenches', 'probe::base')
        drop, t = self.fall('probe', 0.0, 0.3)
        self.assertAlmostEqual(drop, 0.5 * -self.gravity * t * t, delta=0.02 * drop)

    def test_09_a_wrench_lasts_its_duration(self):
        weight = sum(self.masses('probe').values()) * -self.gravity
        self.place('probe', 0.0)
        t0 = self.state('probe').header.stamp.to_sec()
        self.assertTrue(self.wrench('probe::base', (0, 0, 2 * weight), duration=0.2).success)
        t1 = self.run_for(0.5)
        # net +g for 0.2 s (200 updates), then free fall: v = g 0.2 - g (T - 0.2)
        v = self.state('probe').twist.linear.z
        self.assertAlmostEqual(v, -self.gravity * (0.4 - (t1 - t0)), delta=0.01)

    def test_10_a_wrench_in_a_reference_frame(self):
        self.place('probe', 0.0)
        # the model's own frame, which is where its base link is: the wrench is unchanged
        res = self.wrench('probe::base', (0, 0, 1.0), reference_frame='probe', duration=0.0)
        self.assertEqual((res.success, res.status_message), (True, ''))
        res = self.wrench('base', (0, 0, 1.0), reference_frame='probe::arm', duration=0.0)  # plain link name
        self.assertTrue(res.success)

    def test_11_bad_wrenches(self):
        self.refused(self.wrench('probe::nope', (1, 0, 0)), 'ApplyBodyWrench: body does not exist')
        self.refused(self.wrench('probe', (1, 0, 0)), 'ApplyBodyWrench: body does not exist')  # a model
        self.refused(self.wrench('probe::base', (1, 0, 0), reference_frame='nope'),
                     'ApplyBodyWrench: reference_frame not found')
        res = self.wrench('probe::base', (float('inf'), 0, 0))
        self.assertFalse(res.success)
        self.assertIn('must be finite', res.status_message)
        res = self.wrench('probe::base', (1, 0, 0), point=(float('nan'), 0, 0))
        self.assertFalse(res.success)

    def effort(self, joint, value, duration=-1.0):
        return self.call('apply_joint_effort', joint_name=joint, effort=value, start_time=rospy.Time(0),
                         duration=rospy.Duration.from_sec(duration))

    def rate(self, joint='hinge'):
        return self.call('get_joint_properties', joint).rate[0]

    def pushed(self, seconds):
        """(sim time, change of the hinge's rate) over a run of about `seconds`."""
        t0, r0 = self.state('probe').header.stamp.to_sec(), self.rate()
        t1 = self.run_for(seconds)
        return t1 - t0, self.rate() - r0

    def test_12_an_effort_of_duration_minus_one_lasts_until_cleared(self):
        # The probe falls freely: the effort turns the arm one way and the base (plate lumped in) the
        # other, both about the hinge's axis, which holds both centres of mass: the rate grows at
        # effort x (1/izz_arm + 1/izz_base).
        effort = 0.003
        accel = effort * (1 / 0.003 + 1 / (0.04 + 0.001))
        self.place('probe', 0.0)
        res = self.effort('hinge', effort)
        self.assertEqual((res.success, res.status_message), (True, 'ApplyJointEffort: effort set'))
        try:
            for _ in range(2):  # still pushing after the first run
                dt, dv = self.pushed(0.3)
                self.assertAlmostEqual(dv, accel * dt, delta=0.02 * accel * dt)
            self.call('reset_world')  # as upstream, a reset leaves the job alone
            self.assertAlmostEqual(self.rate(), 0.0, delta=1e-9)  # the joint back at rest
            dt, dv = self.pushed(0.3)
            self.assertAlmostEqual(dv, accel * dt, delta=0.02 * accel * dt)
            self.call('clear_joint_forces', 'hinge')
            for _ in range(2):  # cleared: no more push, and no damping either
                _, dv = self.pushed(0.3)
                self.assertAlmostEqual(dv, 0.0, delta=1e-3)
        finally:
            self.call('clear_joint_forces', 'hinge')  # a failure leaves no push to the tests after

    def test_13_bad_efforts(self):
        self.refused(self.effort('nope', 1.0), 'ApplyJointEffort: joint not found')
        res = self.effort('hinge', float('nan'))
        self.assertFalse(res.success)
        self.assertIn('finite', res.status_message)

    def test_14_joint_limits_and_motor(self):
        self.place('probe', 0.0)
        self.assertTrue(self.call('set_model_configuration', 'probe', '', ['hinge'], [0.0]).success)
        res = self.call('set_joint_properties', 'hinge', ODEJointProperties(hiStop=[0.2], loStop=[-0.2]))
        self.assertEqual((res.success, res.status_message), (True, 'SetJointProperties: properties set'))
        try:
            self.assertTrue(self.effort('hinge', 0.01).success)
            self.run_for(1.0)
            position = self.call('get_joint_properties', 'hinge').position[0]
            self.assertLess(position, 0.21)
            self.assertGreater(position, 0.15)
        finally:
            self.call('clear_joint_forces', 'hinge')
            self.assertTrue(self.call('set_joint_properties', 'hinge',
                                      ODEJointProperties(hiStop=[3.0], loStop=[-3.0])).success)
        # ODE's joint motor: vel held with at most fmax
        self.assertTrue(self.call('set_joint_properties', 'hinge', ODEJointProperties(vel=[-0.5], fmax=[10.0])).success)
        try:
            self.run_for(0.2)
            self.assertAlmostEqual(self.rate(), -0.5, delta=0.01)
        finally:
            self.assertTrue(self.call('set_joint_properties', 'hinge',
                                      ODEJointProperties(vel=[0.0], fmax=[0.0])).success)
        # a model deleted and spawned again has its joint motor off, whatever the old one's was
        self.assertTrue(self.call('set_joint_properties', 'hinge', ODEJointProperties(vel=[-0.5], fmax=[10.0])).success)
        self.assertTrue(self.call('delete_model', 'probe').success)
        self.assertTrue(self.call('spawn_urdf_model', 'probe', PROBE, '', pose(0, 0, HIGH), 'world').success)
        self.place('probe', 0.0)
        self.assertTrue(self.call('set_joint_properties', 'hinge', ODEJointProperties(vel=[0.3])).success)
        self.run_for(0.2)
        self.assertAlmostEqual(self.rate(), 0.0, delta=1e-3)  # vel without fmax: a motor without force
        self.refused(self.call('set_joint_properties', 'nope', ODEJointProperties()),
                     'SetJointProperties: joint not found')
        res = self.call('set_joint_properties', 'hinge', ODEJointProperties(loStop=[1.0], hiStop=[0.5]))
        self.assertFalse(res.success)

    def link_request(self, link, **changes):
        now = self.call('get_link_properties', link)
        req = dict(link_name=link, com=now.com, gravity_mode=now.gravity_mode, mass=now.mass, ixx=now.ixx,
                   ixy=now.ixy, ixz=now.ixz, iyy=now.iyy, iyz=now.iyz, izz=now.izz)
        req.update(changes)
        return self.call('set_link_properties', **req)

    def test_15_set_link_properties(self):
        res = self.link_request('puck::body', mass=3.0, ixx=0.02, iyy=0.03, izz=0.04)
        self.assertEqual((res.success, res.status_message), (True, 'SetLinkProperties: properties set'))
        try:
            now = self.call('get_link_properties', 'puck::body')
            self.assertEqual((now.mass, now.ixx, now.iyy, now.izz), (3.0, 0.02, 0.03, 0.04))
            # the new mass is what a force acts on: 3 kg pushed by 3 g up hovers
            self.place('puck', 5.0)
            self.assertTrue(self.wrench('puck::body', (0, 0, 3.0 * -self.gravity)).success)
            self.run_for(0.5)
            self.assertAlmostEqual(self.state('puck').pose.position.z, HIGH, delta=1e-3)
        finally:
            self.call('clear_body_wrenches', 'puck::body')
            self.assertTrue(self.link_request('puck::body', mass=1.5, ixx=0.01, iyy=0.01, izz=0.01).success)

    def test_16_gravity_mode_off_floats(self):
        self.assertTrue(self.link_request('puck::body', gravity_mode=False).success)
        try:
            self.assertFalse(self.call('get_link_properties', 'puck::body').gravity_mode)
            drop, _ = self.fall('puck', 5.0, 0.5)
            self.assertAlmostEqual(drop, 0.0, delta=1e-3)
        finally:
            self.assertTrue(self.link_request('puck::body', gravity_mode=True).success)
        drop, t = self.fall('puck', 5.0, 0.3)
        self.assertAlmostEqual(drop, 0.5 * -self.gravity * t * t, delta=0.02 * drop)

    def test_17_bad_link_properties(self):
        self.refused(self.link_request('puck::body', link_name='puck::nope'),
                     'SetLinkProperties: link not found, did you forget to scope the link by model name?')
        com = Pose(position=Point(0.1, 0, 0), orientation=Quaternion(0, 0, 0, 1))
        res = self.link_request('puck::body', com=com)
        self.assertFalse(res.success)
        self.assertIn('centre of mass', res.status_message)
        self.assertFalse(self.link_request('puck::body', mass=-1.0).success)
        self.assertFalse(self.link_request('puck::body', ixy=0.005).success)  # would turn the principal axes
        self.assertEqual(self.call('get_link_properties', 'puck::body').mass, 1.5)

    # -- lights ---------------------------------------------------------------------------------------
    def test_18_lights(self):
        sun = self.call('get_light_properties', 'sun')
        self.assertTrue(sun.success)
        self.assertAlmostEqual(sun.diffuse.r, 0.8, places=6)  # ColorRGBA is float32
        self.assertEqual((sun.diffuse.a, sun.attenuation_constant), (1.0, 0.9))
        req = dict(light_name='sun', cast_shadows=False, diffuse=sun.diffuse, specular=sun.diffuse,
                   attenuation_constant=0.5, attenuation_linear=0.1, attenuation_quadratic=0.0,
                   direction=Vector3(0, 0, -1), pose=pose(0, 0, 10))
        req['diffuse'].r = 0.25
        self.assertTrue(self.call('set_light_properties', **req).success)
        now = self.call('get_light_properties', 'sun')
        self.assertEqual((now.diffuse.r, now.attenuation_constant, now.attenuation_linear), (0.25, 0.5, 0.1))
        self.refused(self.call('get_light_properties', 'lamp'), 'getLightProperties: Requested light lamp not found!')
        req['light_name'] = 'lamp'
        self.refused(self.call('set_light_properties', **req), 'setLightProperties: Requested light lamp not found!')
        self.refused(self.call('delete_light', 'lamp'), 'DeleteLight: Requested light lamp not found!')
        req['light_name'] = 'sun'
        req['attenuation_linear'] = float('nan')
        self.assertFalse(self.call('set_light_properties', **req).success)
        self.assertEqual(self.call('get_light_properties', 'sun').attenuation_linear, 0.1)
        res = self.call('delete_light', 'sun')
        self.assertEqual((res.success, res.status_message), (True, 'DeleteLight: sun successfully deleted'))
        self.refused(self.call('get_light_properties', 'sun'), 'getLightProperties: Requested light sun not found!')

    def test_19_the_world_still_runs(self):
        before = self.run_for(0.0)
        self.assertGreater(self.run_for(0.1), before)

    def test_20_performance_metrics_name_the_sensors_and_their_rates(self):
        self.assertTrue(self.call('spawn_urdf_model', 'imu_probe', IMU_PROBE, '', pose(10, 0, HIGH), 'world').success)
        imu = integration_common.Latest('/probe_imu', Imu)  # a sensor measures while it is read
        metrics = integration_common.Latest('/gazebo/performance_metrics', PerformanceMetrics)
        name = 'default::imu_probe::body::imu_sensor'  # world::model::link::sensor, as Gazebo scopes it
        self.call('unpause_physics')
        try:
            msg = wait_for(lambda: metrics.msg if metrics.msg is not None and
                           any(s.name == name for s in metrics.msg.sensors) else None, 'the IMU in the metrics')
            seen = metrics.count
            msg = wait_for(lambda: metrics.msg if metrics.count >= seen + 1 else None, 'one more message')
        finally:
            self.call('pause_physics')
            imu.sub.unregister()
            metrics.sub.unregister()
        (sensor,) = [s for s in msg.sensors if s.name == name]
        self.assertAlmostEqual(sensor.sim_update_rate, 50.0, delta=5.0)
        self.assertGreater(sensor.real_update_rate, 0.0)
        self.assertEqual(sensor.fps, -1.0)  # not a camera


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'gazebo_properties', GazeboPropertiesTest)
