"""ridgeback_ros_force_based_move on a real Simulator: a box on frictionless feet pushed towards cmd_vel by
upstream's P forces reaches the commanded sideways and forward speed and yaw rate (its own axes), stops after
cmdVelTimeOut, and publishes odometry integrated from the forward speed and yaw rate only, as upstream."""
import math

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.gazebo_plugins.ridgeback_ros_force_based_move import force_and_torque, motion
from racebot_sim_bridge.kinematics.rotations import rotate_back

from model_plugin_sim import PluginWorld

MOVE = """<plugin name="move" filename="libridgeback_ros_force_based_move.so"><robotNamespace>/</robotNamespace>
<commandTopic>cmd_vel</commandTopic><odometryTopic>odom</odometryTopic><odometryRate>25.0</odometryRate>
<robotBaseFrame>base_link</robotBaseFrame><cmdVelTimeOut>0.25</cmdVelTimeOut><publishOdometryTf>0</publishOdometryTf>
<yaw_velocity_p_gain>500.0</yaw_velocity_p_gain><x_velocity_p_gain>10000.0</x_velocity_p_gain>
<y_velocity_p_gain>10000.0</y_velocity_p_gain></plugin>"""
ROBOT = """<robot name="base">
 <link name="base_link"><inertial><mass value="100"/><inertia ixx="5" iyy="5" izz="5" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="0.8 0.6 0.2"/></geometry></collision></link>
 <gazebo reference="base_link"><mu1>0.0</mu1><mu2>0.0</mu2></gazebo>
 <gazebo>%s</gazebo>
</robot>""" % MOVE


def command(w, x=0.0, y=0.0, wz=0.0):
    msg = Twist()
    msg.linear.x, msg.linear.y, msg.angular.z = x, y, wz
    w.fake.subscribers['/cmd_vel'](msg)


def velocities(robot):
    frame, twist = robot.body.frame_pose(), robot.body.twist()
    return rotate_back(frame.orientation, twist.linear), twist.angular


def test_the_p_law_is_upstreams():
    force, torque = force_and_torque((0.5, -0.2, 1.0), (0.3, 0.1, 0.0), 0.25, (10000.0, 20000.0, 500.0))
    assert force == pytest.approx((2000.0, -6000.0, 0.0)) and torque == pytest.approx((0.0, 0.0, 375.0))


def test_odometry_integrates_forward_speed_and_yaw_rate():
    assert motion((0.0, 0.0, 0.0), 1.0, 0.0, 2.0) == pytest.approx((2.0, 0.0, 0.0))
    x, y, yaw = motion((1.0, 1.0, math.pi / 2), 1.0, math.pi / 2, 1.0)  # a quarter circle of radius 2/pi
    assert (x, y, yaw) == pytest.approx((1.0 - 2 / math.pi, 1.0 + 2 / math.pi, math.pi))


def test_sideways_and_forward_and_turning(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        robot = w.spawn('base', ROBOT, '/', (0.0, 0.0, 0.1))
        w.run(0.3)
        for _ in range(10):  # 1 s, the command renewed within cmdVelTimeOut
            command(w, y=0.55)
            w.run(0.1)
        (vx, vy, _), (_, _, wz) = velocities(robot)
        assert vy == pytest.approx(0.55, abs=0.01) and abs(vx) < 0.01 and abs(wz) < 0.01
        odom = w.fake.publishers['/odom'].messages
        assert odom and abs(odom[-1].pose.pose.position.y) < 1e-3  # upstream's odometry leaves y out
        for _ in range(10):
            command(w, x=0.3, wz=0.5)
            w.run(0.1)
        (vx, vy, _), (_, _, wz) = velocities(robot)
        assert vx == pytest.approx(0.3, abs=0.02) and wz == pytest.approx(0.5, abs=0.02)
        w.run(1.0)  # no command for longer than cmdVelTimeOut: pushed to a stop
        (vx, vy, _), (_, _, wz) = velocities(robot)
        assert abs(vx) < 0.01 and abs(vy) < 0.01 and abs(wz) < 0.01
    finally:
        w.close()
