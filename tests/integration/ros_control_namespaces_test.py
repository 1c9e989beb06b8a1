#!/usr/bin/env python3
"""ros_control and sensor plugins as gazebo_ros puts them (issue 16, rows 1, 4 and 5), on a real world server.

Row 1, namespaces: one small robot (a box with a free wheel, a ros_control plugin, a laser and an
IMU), spawned four ways:
  fleet_car  spawn_model -robot_namespace /fleet; the IMU has its own robotNamespace /own_imu
             -> /fleet/controller_manager, /fleet/scan, /own_imu/imu (its own wins)
  mine_car   spawn request robot_namespace /fleet2; the control plugin says /mine
             -> /mine/controller_manager (the request no longer overrides it), /fleet2/scan, /fleet2/imu
  plain_car  spawn request with an empty robot_namespace
             -> /plain_car/controller_manager (the model name), /plain_car/imu (imu_sensor's default)
  root_car   spawn_model at the root (it sends '/')
             -> /controller_manager, /imu
Row 4: on fleet_car, a wheel velocity controller driven at 6 rad/s; reset_world and reset_simulation
mid-drive leave it running with its command: the wheel spins up again with no new command.
Row 5: switch_controller while the world is paused waits for an update: with a timeout it gives up
after timeout + 1 s of wall time (ok false, nothing switched); with timeout 0 it waits until unpaused.
"""
import os
import tempfile
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import (ListControllers, LoadController, SwitchController,
                                         SwitchControllerRequest)
from gazebo_msgs.srv import GetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from robustness_common import WALL_TIMEOUT, SimProbe, rosrun, wait_for

COMMAND = 6.0  # rad/s for the wheel
WHEEL = '/fleet/wheel_velocity'


def robot_urdf(control_ns=None, imu_ns=None):
    """A 1 kg box resting on the ground with a free wheel on top (it spins in the air; its inertia makes
    a spin-up take ~0.3 s), an effort transmission, gazebo_ros_control, a laser (topicName scan) and an
    IMU (topicName imu)."""
    def ns(value):
        return '' if value is None else '<robotNamespace>%s</robotNamespace>' % value
    inertia = '<inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/>'
    return ('<robot name="r"><link name="base"><inertial><mass value="1"/>' + inertia % (0.01, 0.01, 0.01) +
            '</inertial><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>'
            '<link name="wheel"><inertial><mass value="0.1"/>' + inertia % (0.02, 0.02, 0.02) +
            '</inertial><visual><geometry><cylinder radius="0.04" length="0.02"/></geometry></visual></link>'
            '<joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/>'
            '<origin xyz="0 0 0.12"/><axis xyz="0 1 0"/><limit effort="2" velocity="50"/></joint>'
            '<transmission name="t"><type>transmission_interface/SimpleTransmission</type><joint name="wheel_joint">'
            '<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>'
            '<actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>'
            '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">%s</plugin></gazebo>'
            '<gazebo reference="base"><sensor type="ray" name="laser"><update_rate>10</update_rate><ray><scan>'
            '<horizontal><samples>9</samples><min_angle>-0.5</min_angle><max_angle>0.5</max_angle></horizontal>'
            '</scan><range><min>0.2</min><max>5</max></range></ray><plugin name="l" filename="libgazebo_ros_laser.so">'
            '<topicName>scan</topicName><frameName>base</frameName></plugin></sensor>'
            '<sensor type="imu" name="imu"><update_rate>50</update_rate><plugin name="i" '
            'filename="libgazebo_ros_imu_sensor.so">%s<topicName>imu</topicName><frameName>base</frameName>'
            '<updateRateHZ>50</updateRateHZ></plugin></sensor></gazebo></robot>') % (ns(control_ns), ns(imu_ns))


def pose(x, y):
    return Pose(position=Point(x, y, 0.06), orientation=Quaternion(0, 0, 0, 1))


class RosControlNamespacesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('ros_control_namespaces_test')
        cls.sim = SimProbe()
        cls.sim.wait_ready()
        cls.master = rosgraph.Master('/ros_control_namespaces_test')
        cls.spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        for name in ('reset_world', 'reset_simulation', 'pause_physics', 'unpause_physics'):
            setattr(cls, name, rospy.ServiceProxy('/gazebo/' + name, Empty))
        cls.files = []
        cls.spawn_cli('fleet_car', robot_urdf(imu_ns='/own_imu'), '-robot_namespace', '/fleet', '-x', '0')
        res = cls.spawn('mine_car', robot_urdf(control_ns='/mine'), '/fleet2', pose(2, 0), '')
        assert res.success, res.status_message
        res = cls.spawn('plain_car', robot_urdf(), '', pose(-2, 0), '')
        assert res.success, res.status_message
        cls.spawn_cli('root_car', robot_urdf(), '-y', '2')

    @classmethod
    def tearDownClass(cls):
        for path in cls.files:
            os.unlink(path)

    @classmethod
    def spawn_cli(cls, name, xml, *args):
        with tempfile.NamedTemporaryFile('w', suffix='.urdf', delete=False) as f:
            f.write(xml)
        cls.files.append(f.name)
        p = rosrun('gazebo_ros', 'spawn_model', '-urdf', '-file', f.name, '-model', name, '-z', '0.06', *args)
        assert p.wait_exit() == 0, p.text

    def topics(self):
        return dict(self.master.getPublishedTopics(''))

    def services(self):
        return {name for name, _ in self.master.getSystemState()[2]}

    def test_1_plugins_land_where_gazebo_ros_puts_them(self):
        expected_services = ['/fleet/controller_manager/switch_controller',
                             '/mine/controller_manager/switch_controller',
                             '/plain_car/controller_manager/switch_controller',
                             '/controller_manager/switch_controller']
        wait_for(lambda: set(expected_services) <= self.services(), 'the four controller managers')
        expected_topics = {'/fleet/scan': 'sensor_msgs/LaserScan', '/own_imu/imu': 'sensor_msgs/Imu',
                           '/fleet2/scan': 'sensor_msgs/LaserScan', '/fleet2/imu': 'sensor_msgs/Imu',
                           '/scan': 'sensor_msgs/LaserScan', '/plain_car/imu': 'sensor_msgs/Imu',
                           '/imu': 'sensor_msgs/Imu'}
        topics = wait_for(lambda: (lambda t: t if all(k in t for k in expected_topics) else None)(self.topics()),
                          'the sensor topics %s' % sorted(expected_topics))
        for topic, kind in expected_topics.items():
            self.assertEqual(topics[topic], kind, topic)
        services = self.services()
        for wrong in ('/fleet2/controller_manager/switch_controller', '/r/controller_manager/switch_controller',
                      '/fleet_car/controller_manager/switch_controller'):
            self.assertNotIn(wrong, services)
        for wrong in ('/fleet/imu', '/mine/scan', '/mine/imu', '/fleet_car/imu'):
            self.assertNotIn(wrong, topics)

    # -- row 4 -------------------------------------------------------------------------------------
    def start_wheel(self):
        rospy.set_param(WHEEL, {'type': 'effort_controllers/JointVelocityController', 'joint': 'wheel_joint',
                                'pid': {'p': 0.05, 'i': 0.2, 'i_clamp': 0.1}})
        cm = '/fleet/controller_manager/'
        rospy.wait_for_service(cm + 'load_controller', timeout=WALL_TIMEOUT)
        self.assertTrue(rospy.ServiceProxy(cm + 'load_controller', LoadController)('wheel_velocity').ok)
        switch = rospy.ServiceProxy(cm + 'switch_controller', SwitchController)
        self.assertTrue(switch(SwitchControllerRequest(start_controllers=['wheel_velocity'],
                                                       strictness=SwitchControllerRequest.STRICT)).ok)
        self.states = []
        self.lock = threading.Lock()
        rospy.Subscriber(WHEEL + '/state', JointControllerState, self._on_state, queue_size=100)
        command = rospy.Publisher(WHEEL + '/command', Float64, queue_size=1, latch=True)
        wait_for(lambda: command.get_num_connections() > 0, 'the wheel controller to subscribe')
        command.publish(Float64(COMMAND))
        self.command = command  # kept alive; nothing is published again

    def _on_state(self, msg):
        with self.lock:
            self.states.append((msg.header.stamp.to_sec(), msg.set_point, msg.process_value))

    def spinning_after(self, mark, what):
        """The wheel's state after index `mark`: at the command's speed again, the set point unchanged."""
        def fast():
            with self.lock:
                later = self.states[mark:]
            return later and later[-1][2] > 0.8 * COMMAND and later[-1]
        state = wait_for(fast, 'the wheel to spin at %g rad/s again %s' % (COMMAND, what))
        self.assertEqual(state[1], COMMAND)
        return state

    def slowed_after(self, mark, what):
        def slow():
            with self.lock:
                return any(s[2] < 0.5 * COMMAND for s in self.states[mark:])
        wait_for(slow, 'the wheel at rest just after %s' % what)

    def running(self):
        res = rospy.ServiceProxy('/fleet/controller_manager/list_controllers', ListControllers)()
        return {c.name: c.state for c in res.controller}

    def test_2_reset_world_and_simulation_leave_controllers_and_commands(self):
        self.start_wheel()
        self.spinning_after(0, 'after the command')
        for reset in (self.reset_world, self.reset_simulation):
            before = self.sim.clock
            with self.lock:
                mark = len(self.states)
            reset()
            self.assertEqual(self.running(), {'wheel_velocity': 'running'}, reset.resolved_name)
            p = self.model_state('fleet_car', '').pose.position
            self.assertLess(abs(p.x) + abs(p.y), 0.05, 'fleet_car back at its spawn pose')
            self.slowed_after(mark, reset.resolved_name)  # the joint was reset: the wheel stood still
            self.spinning_after(mark, 'after %s, with no new command' % reset.resolved_name)
            if reset == self.reset_simulation:
                self.assertLess(self.sim.clock, before, 'time went back')

    # -- row 5 -------------------------------------------------------------------------------------
    def test_3_switch_waits_for_an_update(self):
        rospy.set_param('/plain_car/joints', {'type': 'joint_state_controller/JointStateController',
                                              'publish_rate': 10})
        cm = '/plain_car/controller_manager/'
        rospy.wait_for_service(cm + 'load_controller', timeout=WALL_TIMEOUT)
        self.assertTrue(rospy.ServiceProxy(cm + 'load_controller', LoadController)('joints').ok)
        switch = rospy.ServiceProxy(cm + 'switch_controller', SwitchController)
        listing = rospy.ServiceProxy(cm + 'list_controllers', ListControllers)
        start = SwitchControllerRequest(start_controllers=['joints'], strictness=SwitchControllerRequest.STRICT)
        self.pause_physics()
        try:
            start.timeout = 0.5
            begin = time.monotonic()
            self.assertFalse(switch(start).ok, 'no update while paused: the switch must time out')
            self.assertGreaterEqual(time.monotonic() - begin, 1.5 - 0.05)  # timeout + 1 s of wall time
            self.assertEqual([c.state for c in listing().controller], ['initialized'])
            start.timeout = 0.0  # no bound: it waits for the world to run
            answers = []
            caller = threading.Thread(target=lambda: answers.append(switch(start).ok), daemon=True)
            caller.start()
            caller.join(2.0)
            self.assertTrue(caller.is_alive(), 'switch_controller answered while the world was paused')
        finally:
            self.unpause_physics()
        caller.join(WALL_TIMEOUT)
        self.assertEqual(answers, [True])
        self.assertEqual([c.state for c in listing().controller], ['running'])


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'ros_control_namespaces', RosControlNamespacesTest)
