"""What the rostests of odometry drive controllers share (diff_drive_controller_test,
ackermann_steering_controller_test): a robot package of our own (tests/fixtures/robots/...) launched as such
a package is, through its world launch file (gazebo_ros's empty_world.launch, spawn_model, the controller
YAML under the robot's namespace, controller_manager's spawner), with the fixtures on ROS_PACKAGE_PATH.

Driven through <ns>/<controller>/cmd_vel: once the limits' ramp is done, the ground truth (get_model_state,
physics paused, at the sim time of the /clock that follows the pause) moves at the commanded speed and the
expected yaw rate within 5 % over 1 s of sim time; the controller's odometry (odom -> base_footprint, in the
message and on /tf) stays within 5 % of the distance travelled of the true pose. Then the publisher stops and
cmd_vel_timeout (0.25 s) stops the robot.
"""
import math

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from fixture_robot import STARTUP_TIMEOUT, FixtureRobotTest, running_controllers
from integration_common import Latest, yaw_of


class OdometryDriveTest(FixtureRobotTest):
    """A base on an odometry drive controller, driven through its cmd_vel. A subclass names the robot package
    and what to expect: PACKAGE and LAUNCH (the package's world launch file), NS (the robot's namespace),
    MODEL, CONTROLLER (its name), COMMAND (linear.x, angular.z published) and YAW_RATE (what the robot must
    turn at)."""
    PACKAGE = LAUNCH = NS = MODEL = CONTROLLER = None
    COMMAND = YAW_RATE = None

    @classmethod
    def topic(cls, leaf):
        return '/%s/%s/%s' % (cls.NS, cls.CONTROLLER, leaf)

    @classmethod
    def node_name(cls):
        return '%s_test' % cls.CONTROLLER

    @classmethod
    def start(cls):
        cls.collect_tf()
        cls.odom = Latest(cls.topic('odom'), Odometry)
        cls.cmd = cls.driver(cls.topic('cmd_vel'))
        cls.launch_fixture('%s %s gui:=false' % (cls.PACKAGE, cls.LAUNCH), cls.CONTROLLER)
        cls.watch.wait(lambda: running_controllers(cls.NS) >= {'joint_state_controller', cls.CONTROLLER},
                       'the two controllers to run', STARTUP_TIMEOUT, period=0.2)
        cls.gazebo_services()

    def snapshot(self):
        """(sim time, x, y, yaw, forward speed, yaw rate) of the robot with physics paused, and the odometry."""
        t, (res, odom) = self.paused(lambda: (self.get_state(self.MODEL, ''), self.odom.msg))
        p, q = res.pose.position, res.pose.orientation
        yaw = yaw_of(q)
        speed = res.twist.linear.x * math.cos(yaw) + res.twist.linear.y * math.sin(yaw)
        return (t, p.x, p.y, yaw, speed, res.twist.angular.z), odom

    # -- the test -------------------------------------------------------------------------------
    def test_drive_odometry_tf_and_timeout(self):
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = self.COMMAND
        self.cmd.command = cmd
        self.wait_for(lambda: self.odom.msg and self.odom.msg.twist.twist.angular.z > 0.95 * self.YAW_RATE
                      and self.odom.msg.twist.twist.linear.x > 0.95 * self.COMMAND[0], 'the ramp to end')
        self.sim_wait(0.2)
        (t0, x0, y0, yaw0, _, _), _ = self.snapshot()
        self.sim_wait(1.0)
        (t1, x1, y1, yaw1, speed, _), odom = self.snapshot()
        dt, turned = t1 - t0, math.remainder(yaw1 - yaw0, 2 * math.pi)
        chord = math.hypot(x1 - x0, y1 - y0)
        arc = chord * (turned / 2) / math.sin(turned / 2)  # the length of the circular arc through both poses
        rospy.loginfo('over %.3f s: yaw rate %.4f, speed along the arc %.4f, instantaneous %.4f',
                      dt, turned / dt, arc / dt, speed)
        self.assertWithin(turned / dt, self.YAW_RATE, 0.05, 'yaw rate (ground truth)')
        self.assertWithin(arc / dt, self.COMMAND[0], 0.05, 'mean speed along the arc (ground truth)')
        self.assertWithin(speed, self.COMMAND[0], 0.05, 'forward speed (ground truth)')
        # the controller's odometry: its frames (odom_frame_id default, base_frame_id from the YAML), near the truth
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('odom', 'base_footprint'))
        travelled = self.COMMAND[0] * t1
        p = odom.pose.pose
        self.assertLess(math.hypot(p.position.x - x1, p.position.y - y1), 0.05 * travelled,
                        'odometry (%.3f, %.3f), truth (%.3f, %.3f)' % (p.position.x, p.position.y, x1, y1))
        self.assertLess(abs(math.remainder(yaw_of(p.orientation) - yaw1, 2 * math.pi)), 0.05 * self.YAW_RATE * t1,
                        'odometry yaw')
        self.assertWithin(odom.twist.twist.linear.x, self.COMMAND[0], 0.05, 'odometry speed')
        self.assertWithin(odom.twist.twist.angular.z, self.YAW_RATE, 0.05, 'odometry yaw rate')
        self.assertEqual(odom.pose.covariance[0], 0.001)
        tf = self.wait_for(lambda: self.tf.get(('odom', 'base_footprint')), 'TF odom -> base_footprint')
        self.assertLess(math.hypot(tf.transform.translation.x - x1, tf.transform.translation.y - y1),
                        0.05 * travelled)
        # the publisher goes quiet: cmd_vel_timeout (0.25 s) brakes the wheels, the robot stops
        self.cmd.command = None
        self.sim_wait(1.5)
        (_, _, _, _, speed, yaw_rate), _ = self.snapshot()
        self.assertLess(abs(speed), 0.02, 'still moving %.3f m/s after the timeout' % speed)
        self.assertLess(abs(yaw_rate), 0.05, 'still turning %.3f rad/s after the timeout' % yaw_rate)

