#!/usr/bin/env python3
"""A robot written as a Gazebo model, not a URDF: tests/fixtures/robots/sdf_diffbot's model.sdf (revolute
wheel joints, one axis in the joint frame and one in the model frame, a caster, a laser on a fixed joint,
gazebo_ros_diff_drive as a model plugin and gazebo_ros_laser in the link's <sensor>), launched as such a
package is: its launch file includes gazebo_ros's empty_world.launch and runs spawn_model -sdf -database
sdf_diffbot, which the package's gazebo_model_path export puts on the model path, into the package's
world, which <include>s the same model as parked_bot.

The laser scans in its frame, the model's links and joints are what Gazebo lists for an SDF model (its
fixed joint and link kept), the model pose is the model frame (below the chassis link), and driven
through cmd_vel at 0.3 m/s and 0.5 rad/s the ground truth (get_model_state with physics paused) turns at
the commanded yaw rate within 5 % and its chassis, 0.1 m ahead of the wheel axle, moves at the speed that
puts the axle at 0.3 m/s, within 5 %. The world file's robot runs its plugins too, under its model name
(no robotNamespace): /parked_bot/cmd_vel drives it.
"""
import math

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import GetModelProperties
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState, LaserScan

from fixture_robot import STARTUP_TIMEOUT, WALL_TIMEOUT, FixtureRobotTest
from integration_common import Latest, yaw_of

MODEL = 'sdf_diffbot'
COMMAND = (0.3, 0.5)  # m/s, rad/s
CHASSIS_AHEAD = 0.1  # m: the chassis origin ahead of the wheel axle


class SdfRobotTest(FixtureRobotTest):
    NODE = 'sdf_robot_test'

    @classmethod
    def start(cls):
        cls.models = Latest('/gazebo/model_states', ModelStates)
        cls.odom = Latest('/odom', Odometry)
        cls.scan = Latest('/scan', LaserScan)
        cls.joint_states = Latest('/joint_states', JointState)
        cls.parked_odom = Latest('/parked_bot/odom', Odometry)
        cls.cmd = cls.driver('/cmd_vel', '/parked_bot/cmd_vel')  # both robots get the same command
        cls.launch_fixture('sdf_diffbot sdf_diffbot_world.launch gui:=false', 'sdf_robot')
        cls.watch.wait(lambda: cls.models.msg is not None and MODEL in cls.models.msg.name,
                       'the robot to be spawned', STARTUP_TIMEOUT)
        cls.gazebo_services()
        rospy.wait_for_service('/gazebo/get_model_properties', timeout=WALL_TIMEOUT)
        cls.get_properties = rospy.ServiceProxy('/gazebo/get_model_properties', GetModelProperties)

    def snapshot(self):
        """(sim time, x, y, yaw) of the model with physics paused."""
        t, res = self.paused(lambda: self.get_state(MODEL, ''))
        p = res.pose.position
        return t, p.x, p.y, yaw_of(res.pose.orientation)

    def test_links_laser_and_drive(self):
        props = self.get_properties(MODEL)
        self.assertTrue(props.success, props.status_message)
        self.assertEqual(sorted(props.body_names), ['chassis', 'laser_link', 'left_wheel', 'right_wheel'])
        self.assertEqual(sorted(props.joint_names), ['laser_joint', 'left_wheel_hinge', 'right_wheel_hinge'])
        # the model frame (Gazebo's model pose), on the ground: its chassis link is 0.1 m above it
        self.assertAlmostEqual(self.get_state(MODEL, '').pose.position.z, 0.0, delta=0.01)
        scan = self.wait_for(lambda: self.scan.msg, '/scan')
        self.assertEqual((len(scan.ranges), scan.header.frame_id), (360, 'laser_link'))
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = COMMAND
        self.cmd.command = cmd
        self.wait_for(lambda: self.odom.msg and self.odom.msg.twist.twist.angular.z > 0.95 * COMMAND[1],
                      'the robot to turn')
        self.sim_wait(0.3)
        t0, x0, y0, yaw0 = self.snapshot()
        self.sim_wait(1.0)
        t1, x1, y1, yaw1 = self.snapshot()
        self.cmd.command = Twist()
        dt, turned = t1 - t0, math.remainder(yaw1 - yaw0, 2 * math.pi)
        chord = math.hypot(x1 - x0, y1 - y0)
        arc = chord * (turned / 2) / math.sin(turned / 2)
        rospy.loginfo('over %.3f s: yaw rate %.4f, chassis speed along the arc %.4f', dt, turned / dt, arc / dt)
        self.assertWithin(turned / dt, COMMAND[1], 0.05, 'yaw rate (ground truth)')
        chassis_speed = COMMAND[1] * math.hypot(COMMAND[0] / COMMAND[1], CHASSIS_AHEAD)
        self.assertWithin(arc / dt, chassis_speed, 0.05, 'chassis speed along the arc (ground truth)')
        odom = self.odom.msg
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('odom', 'chassis'))
        js = self.wait_for(lambda: self.joint_states.msg, '/joint_states')
        self.assertEqual(sorted(js.name), ['left_wheel_hinge', 'right_wheel_hinge'])
        # the world file's robot got the same command on its own topic: it turned too, from where it was parked
        parked = self.get_state('parked_bot', '').pose
        self.assertGreater(math.hypot(parked.position.x, parked.position.y - 3.0), 0.3)
        self.assertAlmostEqual(parked.position.z, 0.0, delta=0.01)
        self.assertEqual(self.parked_odom.msg.header.frame_id, 'odom')  # frames are not namespaced (upstream)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'sdf_robot', SdfRobotTest)
