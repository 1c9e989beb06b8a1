#!/usr/bin/env python3
"""A Gazebo user's robot and world with meshes: package:// meshes on the car, a model:// mesh model in the
world, materials in the camera images.

Everything is written by this node into a temporary folder before it starts the simulator itself (as
robustness_world_test does), so that the simulator sees them in its environment:
  - a Gazebo model library (GAZEBO_MODEL_PATH) with `mesh_wall`: a static 0.2 x 1.0 x 0.6 m wall whose
    collision is an STL and whose visual is a DAE drawn in Gazebo/Blue;
  - a ROS package (on ROS_PACKAGE_PATH) holding the racebot's every box and cylinder as a mesh (STL wheels,
    OBJ chassis scaled by 0.5, DAE visuals): the racebot URDF rewritten to name them by package:// URIs;
  - a world including ground_plane, mesh_wall 2 m ahead of the car, and a model that exists nowhere.
Expected values come from the geometry written here and the URDF (sensor poses), never from the simulator.
"""
import math
import os
import shutil
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose
from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix as rotation
from sensor_msgs.msg import Image, LaserScan
from std_msgs.msg import Float64

import mesh_fixtures
from integration_common import Latest
from robustness_common import WALL_TIMEOUT, Process, SimProbe, wait_for

CONTROLLERS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller',
               'joint_state_controller']
WALL_X, WALL_SIZE = 2.0, (0.2, 1.0, 0.6)  # the wall's centre x and size; its face is at WALL_X - 0.1
WALL_FACE_X = WALL_X - WALL_SIZE[0] / 2
MISSING = 'racebot_no_such_model'
SCAN_TOLERANCE = 0.03   # m (the lidar's resolution is 0.01 m, noise is off)
DEPTH_TOLERANCE = 0.02  # m
WHEEL_RADIUS = 0.032

WALL_SDF = '''<model name="mesh_wall"><static>true</static><link name="link">
  <collision name="collision"><geometry><mesh><uri>model://mesh_wall/meshes/wall.stl</uri></mesh></geometry></collision>
  <visual name="visual"><geometry><mesh><uri>model://mesh_wall/meshes/wall.dae</uri></mesh></geometry>
    <material><script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Blue</name></script>
    </material></visual></link></model>'''
WORLD = '''<?xml version="1.0"?><sdf version="1.6"><world name="default">
  <physics type="ode"><max_step_size>0.001</max_step_size><real_time_update_rate>1000</real_time_update_rate></physics>
  <include><uri>model://ground_plane</uri></include>
  <include><uri>model://mesh_wall</uri><pose>%g 0 %g 0 0 0</pose></include>
  <include><uri>model://%s</uri></include>
</world></sdf>''' % (WALL_X, WALL_SIZE[2] / 2, MISSING)
# A URDF box whose <gazebo> material (green) must win over its URDF colour (red), and one with a URDF colour only.
COLOUR_BOX = '''<robot name="{name}"><link name="box"><inertial><mass value="0.5"/>
  <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  <visual><geometry><box size="0.12 0.12 0.12"/></geometry><material name="m"><color rgba="{rgba}"/></material></visual>
  <collision><geometry><box size="0.12 0.12 0.12"/></geometry></collision></link>{gazebo}</robot>'''


class MeshesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('meshes_test')
        cls.tmp = tempfile.mkdtemp(prefix='racebot_meshes_')
        cls.processes = []
        models = os.path.join(cls.tmp, 'models')
        folder = mesh_fixtures.write_model(models, 'mesh_wall', WALL_SDF)
        for ext in ('stl', 'dae'):
            mesh_fixtures.write_mesh(mesh_fixtures.box(WALL_SIZE), os.path.join(folder, 'meshes', 'wall.' + ext))
        world = os.path.join(cls.tmp, 'meshes.world')
        with open(world, 'w') as f:
            f.write(WORLD)
        cls.models_dir = models
        packages = os.path.join(cls.tmp, 'packages')
        urdf, cls.replaced = mesh_fixtures.meshify_urdf(rospy.get_param('/robot_description'), packages)
        rospy.set_param('/robot_description', urdf)
        cls.model = urdf_reader.parse_urdf(urdf)
        cls.specs = {s.type: s for s in cls.model.sensors}
        env = dict(os.environ, GAZEBO_MODEL_PATH=models, RACEBOT_MESH_CACHE=os.path.join(cls.tmp, 'cache'),
                   ROS_PACKAGE_PATH=os.pathsep.join([packages, os.environ.get('ROS_PACKAGE_PATH', '')]))
        cls.sim = SimProbe()
        cls.server = cls.start(env, 'racebot_sim_bridge', 'world_server', world, '__name:=gazebo')
        cls.sim.wait_ready()
        spawn = Process(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-model', 'racebot', '-param',
                         '/robot_description', '-timeout', '60'], env)
        assert spawn.wait_exit() == 0, spawn.text
        cls.start(env, 'controller_manager', 'spawner', *(CONTROLLERS + ['__ns:=/racebot']))
        rospy.wait_for_service('/racebot/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        listing = rospy.ServiceProxy('/racebot/controller_manager/list_controllers', ListControllers)
        wait_for(lambda: {c.name for c in listing().controller if c.state == 'running'} == set(CONTROLLERS),
                 'the seven controllers running on the mesh car')
        cls.sim.sim_sleep(1.5)  # the car settles on its wheels

    @classmethod
    def start(cls, env, *args):
        p = Process(['rosrun'] + list(args), env)
        cls.processes.append(p)
        return p

    @classmethod
    def tearDownClass(cls):
        for p in reversed(cls.processes):
            p.stop()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def now(self):
        return wait_for(lambda: self.sim.clock, '/clock')

    def latest(self, topic, cls):
        latest = Latest(topic, cls)
        self.addCleanup(latest.sub.unregister)
        return latest

    def car(self):
        res = self.sim.state('racebot')
        self.assertTrue(res.success, res.status_message)
        p, q = res.pose.position, res.pose.orientation
        return np.array([p.x, p.y, p.z]), (q.x, q.y, q.z, q.w)

    def sensor_pose(self, spec):
        position, q = self.car()
        offset = rotations.compose(self.model.pose_in_lumped_link(spec.reference), spec.pose)
        p, o = rotations.compose((tuple(position), q), offset)
        return np.array(p), o

    # -- the world ------------------------------------------------------------------------------------
    def test_1_a_missing_model_is_one_warning_naming_the_places_searched_and_the_rest_loads(self):
        names = self.sim.world_properties().model_names
        self.assertEqual(sorted(names), ['ground_plane', 'mesh_wall', 'racebot'])
        lines = [line for line in self.server.text.splitlines() if 'model://%s' % MISSING in line]
        self.assertEqual(len(lines), 1, self.server.text[-3000:])
        self.assertIn('[WARN]', lines[0])
        for needle in ("model '%s' not found; searched" % MISSING, self.models_dir,
                       os.path.join(os.path.expanduser('~'), '.gazebo', 'models'), 'GAZEBO_MODEL_PATH'):
            self.assertIn(needle, lines[0])
        self.assertNotIn('Traceback', self.server.text)
        self.assertNotIn('left out', self.server.text, 'a mesh of the car was not loaded')

    def test_2_the_car_rests_on_its_mesh_wheels(self):
        self.assertGreaterEqual(self.replaced, 10)
        position, q = self.car()
        # base_footprint is at the wheels' contact level: without wheel collisions the chassis would lie lower
        self.assertLess(abs(position[2]), 0.005, 'the car stands at z = %.4f' % position[2])
        self.assertLess(abs(rotation(q)[2, 2] - 1.0), 1e-3, 'the car is not upright')

    # -- sensors see the model:// mesh ----------------------------------------------------------------
    def test_3_the_lidar_sees_the_mesh_wall_at_its_range(self):
        scan = self.latest('/scan', LaserScan).after(self.now() + 0.1, 'a /scan')
        position, q = self.sensor_pose(self.specs['ray'])
        yaw = rotations.quaternion_to_rpy(q)[2]
        checked = []
        for i, r in enumerate(scan.ranges):
            a = scan.angle_min + i * scan.angle_increment + yaw
            if abs(a) > math.radians(8):  # well inside the wall's width
                continue
            expected = (WALL_FACE_X - position[0]) / math.cos(a)
            checked.append((i, r, expected))
        self.assertGreater(len(checked), 50)
        errors = [abs(r - e) for _, r, e in checked]
        rospy.loginfo('lidar on the mesh wall: %d beams, max error %.4f m, mean %.4f m'
                      % (len(errors), max(errors), float(np.mean(errors))))
        self.assertLess(max(errors), SCAN_TOLERANCE, [c for c in checked if abs(c[1] - c[2]) >= SCAN_TOLERANCE][:5])

    def test_4_the_depth_camera_sees_the_mesh_wall_at_its_depth(self):
        spec = self.specs['depth']
        d = self.latest('/real_sense/depth/image_raw', Image).after(self.now() + 0.1, 'a depth image')
        position, q = self.sensor_pose(spec)
        forward = rotation(q)[:, 0]
        self.assertAlmostEqual(forward[0], 1.0, delta=1e-3)
        expected = WALL_FACE_X - position[0]
        depth = np.frombuffer(d.data, dtype='<f4').reshape(d.height, d.width)
        face = depth[d.height // 2 - 10:d.height // 2 + 10, d.width // 2 - 10:d.width // 2 + 10]
        rospy.loginfo('depth of the mesh wall: %.4f m measured (mean), %.4f m expected, max error %.4f m'
                      % (face.mean(), expected, np.abs(face - expected).max()))
        self.assertLess(np.abs(face - expected).max(), DEPTH_TOLERANCE,
                        'depth at the image centre %.3f, the wall face is %.3f m away' % (face.mean(), expected))

    # -- colours ---------------------------------------------------------------------------------------
    def test_5_materials_show_in_the_camera_image(self):
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        boxes = [('gazebo_green', '1 0 0 1', '<gazebo reference="box"><material>Gazebo/Green</material></gazebo>',
                  0.25), ('urdf_magenta', '1 0 1 1', '', -0.25)]
        for name, rgba, gazebo, y in boxes:
            pose = Pose()
            pose.position.x, pose.position.y, pose.position.z = 1.0, y, 0.061
            pose.orientation.w = 1.0
            res = spawn(name, COLOUR_BOX.format(name=name, rgba=rgba, gazebo=gazebo), '', pose, 'world')
            self.assertTrue(res.success, res.status_message)
            self.addCleanup(delete, name)
        img = self.latest('/rrbot/camera1/image_raw', Image).after(self.now() + 0.2, 'a camera image with the boxes')
        rgb = np.frombuffer(img.data, dtype=np.uint8).reshape(img.height, img.width, 3).astype(int)
        r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
        green = (g > 100) & (r < 60) & (b < 60)
        magenta = (r > 100) & (b > 100) & (g < 60)
        blue = (b > 100) & (r < 60) & (g < 60)
        red = (r > 100) & (g < 60) & (b < 60)
        counts = dict(green=int(green.sum()), magenta=int(magenta.sum()), blue=int(blue.sum()), red=int(red.sum()))
        rospy.loginfo('camera pixels by colour: %s' % counts)
        self.assertGreater(counts['green'], 300, 'the <gazebo> material Gazebo/Green is not shown: %s' % counts)
        self.assertLess(counts['red'], 20, 'the URDF colour shows where the <gazebo> material must win: %s' % counts)
        self.assertGreater(counts['magenta'], 300, 'the URDF <material><color> is not shown: %s' % counts)
        self.assertGreater(counts['blue'], 2000, 'the mesh wall (Gazebo/Blue) is not shown: %s' % counts)
        # the green box stands left of the centre (y > 0), the magenta one right
        self.assertLess(np.nonzero(green)[1].mean(), img.width / 2)
        self.assertGreater(np.nonzero(magenta)[1].mean(), img.width / 2)

    # -- driving ---------------------------------------------------------------------------------------
    def test_6_the_mesh_car_drives(self):
        pubs = [rospy.Publisher('/racebot/%s_rear_wheel_velocity_controller/command' % side, Float64, queue_size=1)
                for side in ('left', 'right')]
        start, _ = self.car()
        begin = self.now()
        omega = 10.0  # rad/s: 0.32 m/s on 0.032 m wheels
        while self.now() < begin + 2.0:
            for p in pubs:
                p.publish(Float64(omega))
            rospy.sleep(0.05)
        for p in pubs:
            p.publish(Float64(0.0))
        end, q = self.car()
        moved = end - start
        rospy.loginfo('the mesh car drove %.3f m in 2 s (commanded %.3f m/s)' % (moved[0], omega * WHEEL_RADIUS))
        self.assertGreater(moved[0], 0.2, 'the car did not drive forward: moved %s' % moved)
        self.assertLess(abs(moved[1]), 0.1, 'the car veered: moved %s' % moved)
        self.assertLess(abs(end[2]), 0.01, 'the car left the ground or sank: z = %.4f' % end[2])


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'meshes', MeshesTest)
