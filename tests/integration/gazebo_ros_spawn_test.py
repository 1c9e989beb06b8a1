#!/usr/bin/env python3
"""gazebo_ros as a robot package uses it: `empty_world.launch` included under a group namespace,
models spawned with `rosrun gazebo_ros spawn_model` (issue 16, rows 9 and 10).

The test node writes a launch file that includes $(find gazebo_ros)/launch/empty_world.launch in
<group ns="sim"> (paused:=true) and runs it with roslaunch, with GAZEBO_MODEL_PATH on a folder made
here (a model for -database, a mesh for -package_to_model). Then, in order:
  services and topics under the gazebo node's namespace (/sim/gazebo/...), none under /gazebo;
  /clock at every world update (use_clock_frequency false);
  -J twice + -unpause: both joints set, the world running after;
  -wait: the spawn waits until the named model exists;
  -database: the model folder's SDF, found in the Gazebo model path;
  -package_to_model: package:// meshes found as model:// (and not found without the flag);
  -robot_namespace: the caller's namespace by default, the option's when given (where the model's
   gazebo_ros_control serves its controller manager);
  -b: the model is deleted when spawn_model is shut down;
  -stdin; a missing file or a folder given to -file: exit 1 with upstream's message.
"""
import math
import os
import shutil
import subprocess
import tempfile
import unittest

import rosgraph
import rospy
import rostest
from gazebo_msgs.srv import GetLinkState, GetPhysicsProperties, GetWorldProperties
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from robustness_common import WALL_TIMEOUT, Process, wait_for

GZ = '/sim/gazebo'

# A base on the ground and two links turning about vertical axes (gravity leaves their angles alone),
# with gazebo_ros_control (no robotNamespace of its own) and a transmission: a controller manager.
ARM_URDF = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial><mass value="20"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision>
  </link>
  <link name="l1">
    <inertial><origin xyz="0.1 0 0"/><mass value="0.2"/>
      <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="l2">
    <inertial><origin xyz="0.1 0 0"/><mass value="0.2"/>
      <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="5"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.2 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="5"/></joint>
  <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
</robot>
"""

# A box whose collision shape is a mesh given as package://h1_mesh_pkg/... (no such ROS package, but a
# folder h1_mesh_pkg in the model path): found, it rests on the ground; left out, the box falls through.
MESH_URDF = """<?xml version="1.0"?>
<robot name="meshbox">
  <link name="body">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="package://h1_mesh_pkg/meshes/cube.obj"/></geometry></collision>
  </link>
</robot>
"""

CUBE_OBJ = """v -0.1 -0.1 -0.1
v 0.1 -0.1 -0.1
v 0.1 0.1 -0.1
v -0.1 0.1 -0.1
v -0.1 -0.1 0.1
v 0.1 -0.1 0.1
v 0.1 0.1 0.1
v -0.1 0.1 0.1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""

BOX_SDF = """<?xml version="1.0"?>
<sdf version="1.6"><model name="%s"><pose>0 0 0.1 0 0 0</pose><link name="link">
  <inertial><mass>1</mass></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
</link></model></sdf>
"""

CRATE_CONFIG = """<?xml version="1.0"?>
<model><name>h1 crate</name><version>1.0</version><sdf version="1.6">crate.sdf</sdf></model>
"""

WORLD_LAUNCH = """<launch>
  <group ns="sim">
    <include file="$(find gazebo_ros)/launch/empty_world.launch">
      <arg name="paused" value="true"/>
      <arg name="gui" value="false"/>
    </include>
  </group>
</launch>
"""


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def angle_between(a, b):
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


class GazeboRosSpawnTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('gazebo_ros_spawn_test', disable_rostime=True)
        cls.tmp = tempfile.mkdtemp(prefix='gazebo_ros_spawn_')
        models = os.path.join(cls.tmp, 'models')
        os.makedirs(os.path.join(models, 'h1_crate'))
        with open(os.path.join(models, 'h1_crate', 'model.config'), 'w') as f:
            f.write(CRATE_CONFIG)
        with open(os.path.join(models, 'h1_crate', 'crate.sdf'), 'w') as f:
            f.write(BOX_SDF % 'crate')
        os.makedirs(os.path.join(models, 'h1_mesh_pkg', 'meshes'))
        with open(os.path.join(models, 'h1_mesh_pkg', 'meshes', 'cube.obj'), 'w') as f:
            f.write(CUBE_OBJ)
        cls.files = {}
        for name, text in (('arm.urdf', ARM_URDF), ('mesh.urdf', MESH_URDF), ('box.sdf', BOX_SDF % 'box'),
                           ('world.launch', WORLD_LAUNCH)):
            cls.files[name] = os.path.join(cls.tmp, name)
            with open(cls.files[name], 'w') as f:
                f.write(text)
        env = dict(os.environ, GAZEBO_MODEL_PATH=models)
        cls.world = Process(['roslaunch', '--disable-title', cls.files['world.launch']], env=env)
        cls.processes = [cls.world]
        cls.clock_stamps = []
        cls.clock_sub = rospy.Subscriber('/clock', Clock, lambda m: cls.clock_stamps.append(m.clock.to_sec()),
                                         queue_size=100)
        try:
            # gazebo_ros advertises reset_world last (one master call each): with it, every service is there
            rospy.wait_for_service(GZ + '/reset_world', timeout=WALL_TIMEOUT)
        except rospy.ROSException:
            cls.tearDownClass()  # unittest skips it when setUpClass fails: the world would outlive the test
            raise AssertionError('%s/reset_world did not appear; roslaunch said:\n%s'
                                 % (GZ, cls.world.text[-3000:]))
        cls.world_properties = rospy.ServiceProxy(GZ + '/get_world_properties', GetWorldProperties)
        cls.physics = rospy.ServiceProxy(GZ + '/get_physics_properties', GetPhysicsProperties)
        cls.link_state = rospy.ServiceProxy(GZ + '/get_link_state', GetLinkState)

    @classmethod
    def tearDownClass(cls):
        for p in reversed(cls.processes):
            p.stop()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def spawn(self, *args, **kw):
        """rosrun gazebo_ros spawn_model ARGS (with env overrides in kw['env'])."""
        argv = ['rosrun', 'gazebo_ros', 'spawn_model'] + list(args)
        env = dict(os.environ, **kw.get('env', {}))
        p = Process(argv, env=env)
        self.processes.append(p)
        return p

    def models(self):
        return self.world_properties().model_names

    def run_world(self):
        rospy.ServiceProxy(GZ + '/unpause_physics', Empty)()
        wait_for(lambda: not self.physics().pause, 'the world running')

    def sim_time(self):
        return self.clock_stamps[-1] if self.clock_stamps else 0.0

    def link_yaw(self, link):
        res = self.link_state(link, '')
        self.assertTrue(res.success, res.status_message)
        return yaw_of(res.link_state.pose.orientation)

    # -- row 10: the namespace of the gazebo node ----------------------------------------------------
    def test_00_services_and_topics_live_under_the_gazebo_nodes_namespace(self):
        master = rosgraph.Master('/gazebo_ros_spawn_test')
        publishers, _, services = master.getSystemState()
        names = {s for s, _ in services}
        for service in ('spawn_urdf_model', 'spawn_sdf_model', 'delete_model', 'get_world_properties',
                        'set_model_configuration', 'pause_physics', 'unpause_physics'):
            self.assertIn('%s/%s' % (GZ, service), names)
        self.assertFalse([s for s in names if s.startswith('/gazebo/')], 'nothing may stay under /gazebo')
        topics = {t for t, _ in publishers}
        self.assertIn(GZ + '/model_states', topics)
        self.assertIn(GZ + '/link_states', topics)
        self.assertIn('/clock', topics)

    def test_01_clock_at_every_update_without_use_clock_frequency(self):
        rospy.ServiceProxy(GZ + '/unpause_physics', Empty)()
        start = len(self.clock_stamps)
        wait_for(lambda: len({round(t, 6) for t in self.clock_stamps[start:]}) >= 30, '30 /clock stamps')
        stamps = sorted({round(t, 6) for t in self.clock_stamps[start:]})
        self.assertAlmostEqual(min(b - a for a, b in zip(stamps, stamps[1:])), 0.001, delta=1e-6)
        rospy.ServiceProxy(GZ + '/pause_physics', Empty)()
        wait_for(lambda: self.physics().pause, 'the world paused again')

    # -- row 9: spawn_model's command line ----------------------------------------------------------
    def test_10_j_twice_and_unpause(self):
        self.assertTrue(self.physics().pause, 'the world starts paused (paused:=true)')
        p = self.spawn('-urdf', '-file', self.files['arm.urdf'], '-model', 'arm', '-gazebo_namespace', GZ,
                       '-z', '0.05', '-J', 'j1', '0.5', '-J', 'j2', '-0.3', '-unpause')
        self.assertEqual(p.wait_exit(), 0, p.text)
        self.assertIn('Unpausing physics', p.text)
        self.assertFalse(self.physics().pause, '-unpause leaves the world running')
        base = self.link_yaw('arm::base')
        self.assertLess(angle_between(self.link_yaw('arm::l1') - base, 0.5), 0.02)
        self.assertLess(angle_between(self.link_yaw('arm::l2') - base, 0.2), 0.02)

    def test_11_robot_namespace_is_the_callers_namespace_by_default(self):
        # spawn_model run in namespace /team1 (as in <group ns="team1">): robot_namespace '/team1/', so the
        # model's gazebo_ros_control (no <robotNamespace> of its own) serves /team1/controller_manager
        p = self.spawn('-urdf', '-file', self.files['arm.urdf'], '-model', 'arm_team1', '-gazebo_namespace', GZ,
                       '-x', '2', '-z', '0.05', env={'ROS_NAMESPACE': '/team1'})
        self.assertEqual(p.wait_exit(), 0, p.text)
        rospy.wait_for_service('/team1/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        p = self.spawn('-urdf', '-file', self.files['arm.urdf'], '-model', 'arm_team2', '-gazebo_namespace', GZ,
                       '-x', '-2', '-z', '0.05', '-robot_namespace', '/team2', env={'ROS_NAMESPACE': '/team1'})
        self.assertEqual(p.wait_exit(), 0, p.text)
        rospy.wait_for_service('/team2/controller_manager/list_controllers', timeout=WALL_TIMEOUT)

    def test_20_wait_holds_the_spawn_until_the_model_exists(self):
        self.run_world()  # model_states come with world updates
        waiter = self.spawn('-sdf', '-file', self.files['box.sdf'], '-model', 'waiter', '-gazebo_namespace', GZ,
                            '-x', '4', '-wait', 'late_box')
        waiter.wait_output('Waiting for model late_box before proceeding.')
        self.assertNotIn('waiter', self.models())
        self.assertTrue(waiter.alive(), waiter.text)
        late = self.spawn('-sdf', '-file', self.files['box.sdf'], '-model', 'late_box', '-gazebo_namespace', GZ,
                          '-x', '5')
        self.assertEqual(late.wait_exit(), 0, late.text)
        self.assertEqual(waiter.wait_exit(), 0, waiter.text)
        self.assertIn('waiter', self.models())

    def test_30_database_spawns_a_model_from_the_model_path(self):
        p = self.spawn('-sdf', '-database', 'h1_crate', '-model', 'crate7', '-gazebo_namespace', GZ, '-y', '3')
        self.assertEqual(p.wait_exit(), 0, p.text)
        self.assertIn('Loading model XML from Gazebo Model Database', p.text)
        self.assertIn('crate7', self.models())
        res = self.link_state('crate7::link', '')
        self.assertTrue(res.success, res.status_message)
        self.assertAlmostEqual(res.link_state.pose.position.y, 3.0, delta=0.05)
        missing = self.spawn('-sdf', '-database', 'h1_no_such_model', '-model', 'ghost', '-gazebo_namespace', GZ)
        self.assertEqual(missing.wait_exit(), 1, missing.text)
        self.assertIn('Spawn service failed. Exiting.', missing.text)
        self.assertNotIn('ghost', self.models())

    def test_40_package_to_model(self):
        self.run_world()
        plain = self.spawn('-urdf', '-file', self.files['mesh.urdf'], '-model', 'meshbox0', '-gazebo_namespace', GZ,
                           '-y', '-3', '-z', '0.5')
        # package://h1_mesh_pkg is no ROS package: gazebo_ros refuses the spawn and spawn_model exits 1
        self.assertEqual(plain.wait_exit(), 1, plain.text)
        self.assertIn('Spawn status: urdf reference package name does not exist: h1_mesh_pkg', plain.text)
        self.assertIn('Spawn service failed. Exiting.', plain.text)
        self.assertNotIn('meshbox0', self.models())
        p = self.spawn('-urdf', '-file', self.files['mesh.urdf'], '-model', 'meshbox', '-gazebo_namespace', GZ,
                       '-y', '-5', '-z', '0.5', '-package_to_model')
        self.assertEqual(p.wait_exit(), 0, p.text)
        start = self.sim_time()
        wait_for(lambda: self.sim_time() > start + 2.0, '2 s of sim time')
        self.assertAlmostEqual(self.link_state('meshbox::body', '').link_state.pose.position.z, 0.1, delta=0.03)

    def test_50_bond_deletes_the_model_on_shutdown(self):
        p = self.spawn('-sdf', '-file', self.files['box.sdf'], '-model', 'bonded', '-gazebo_namespace', GZ,
                       '-x', '-4', '-b')
        p.wait_output('Waiting for shutdown to delete model bonded')
        self.assertIn('bonded', self.models())
        self.assertTrue(p.alive(), '-b keeps spawn_model running')
        self.assertEqual(p.stop(), 0, p.text)
        self.assertIn('Deleting model bonded', p.text)
        self.assertNotIn('bonded', self.models())

    def test_60_stdin_and_unreadable_sources(self):
        with open(self.files['box.sdf']) as f:
            done = subprocess.run(['rosrun', 'gazebo_ros', 'spawn_model', '-sdf', '-stdin', '-model', 'piped',
                                   '-gazebo_namespace', GZ, '-x', '6'], stdin=f, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, timeout=WALL_TIMEOUT, text=True)
        self.assertEqual(done.returncode, 0, done.stdout)
        self.assertIn('Loading model XML from stdin', done.stdout)
        self.assertIn('piped', self.models())
        missing = os.path.join(self.tmp, 'no_such.urdf')
        p = self.spawn('-urdf', '-file', missing, '-model', 'ghost', '-gazebo_namespace', GZ)
        self.assertEqual(p.wait_exit(), 1, p.text)
        self.assertIn('Error: specified file %s does not exist' % missing, p.text)
        p = self.spawn('-urdf', '-file', self.tmp, '-model', 'ghost', '-gazebo_namespace', GZ)
        self.assertEqual(p.wait_exit(), 1, p.text)
        self.assertIn('Error: specified file %s is not a file' % self.tmp, p.text)
        self.assertNotIn('ghost', self.models())


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'gazebo_ros_spawn', GazeboRosSpawnTest)
