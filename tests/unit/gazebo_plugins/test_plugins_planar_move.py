"""gazebo_ros_planar_move on a real Simulator (tests/fixtures/robots/planar_move_bot): the model moves at
cmd_vel's velocity in its own axes, odometry at odometryRate as upstream times and computes it, TF,
cmdTimeout."""
import math

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.kinematics.planar import integrate, world_to_base
from racebot_sim_bridge.kinematics.rotations import yaw_of

from model_plugin_sim import PluginWorld, fixture_urdf


@pytest.fixture(scope='module')
def urdf():
    return fixture_urdf('planar_move_bot')


@pytest.fixture
def world(tmp_path, urdf):
    w = PluginWorld(tmp_path)
    robot = w.spawn('planar_move_bot', urdf)
    yield w, robot
    w.close()


def command(w, vx, vy, wz):
    msg = Twist()
    msg.linear.x, msg.linear.y, msg.angular.z = vx, vy, wz
    w.fake.subscribers['/planar/cmd_vel'](msg)


def drive(w, cmd, seconds):
    """Sends `cmd` every 0.1 s of sim time (as a teleop would; cmdTimeout is 0.5 s) for `seconds`."""
    for _ in range(int(round(seconds / 0.1))):
        command(w, *cmd)
        w.run(0.1)


def state(robot):
    frame = robot.body.frame_pose()
    linear, angular = robot.body.twist()
    return frame.position[0], frame.position[1], yaw_of(frame.orientation), linear, angular


def test_follows_the_command_in_its_own_axes(world):
    w, robot = world
    drive(w, (0.3, 0.2, 0.5), 0.2)
    x0, y0, yaw0, _, _ = state(robot)
    drive(w, (0.3, 0.2, 0.5), 1.0)
    x1, y1, yaw1, linear, angular = state(robot)
    assert world_to_base(linear[0], linear[1], yaw1) == pytest.approx((0.3, 0.2), rel=0.01)
    assert angular[2] == pytest.approx(0.5, rel=0.01)
    assert (x1, y1, yaw1) == pytest.approx(integrate((x0, y0, yaw0), (0.3, 0.2, 0.5), 1.0), abs=0.005)


def test_odometry_at_the_upstream_rate_in_the_robot_axes(world):
    w, robot = world
    drive(w, (0.3, 0.2, 0.5), 1.0)
    w.run(0.05)
    odom = w.fake.publishers['/planar/odom'].messages
    stamps = [m.header.stamp.to_sec() for m in odom]
    assert stamps[:3] == pytest.approx([0.051, 0.102, 0.153])  # more than 1/20 s apart: 19.6 Hz
    assert len(odom) == 20
    last = odom[-1]
    assert (last.header.frame_id, last.child_frame_id) == ('planar_odom', 'planar_base')
    t = last.twist.twist
    assert (t.linear.x, t.linear.y, t.angular.z) == pytest.approx((0.3, 0.2, 0.5), rel=0.05)
    assert list(last.pose.covariance[0:36:7]) == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
    assert list(last.twist.covariance) == [0.0] * 36
    assert last.pose.pose.position.z == 0.0
    tf = w.fake.publishers['/tf'].messages[-1].transforms[0]
    assert (tf.header.frame_id, tf.child_frame_id) == ('planar_odom', 'planar_base')
    assert tf.transform.translation.x == pytest.approx(last.pose.pose.position.x)


def test_cmd_timeout_stops_the_model(world):
    w, robot = world
    command(w, 0.3, 0.0, 0.0)
    w.run(0.4)
    assert math.hypot(*state(robot)[3][:2]) == pytest.approx(0.3, rel=0.01)
    w.run(0.2)  # 0.6 s since the command, cmdTimeout 0.5
    assert math.hypot(*state(robot)[3][:2]) < 1e-3


def test_without_a_command_timeout_the_command_lasts(tmp_path, urdf):
    w = PluginWorld(tmp_path)
    robot = w.spawn('planar_move_bot', urdf.replace('<cmdTimeout>0.5</cmdTimeout>', ''))
    try:
        command(w, 0.3, 0.0, 0.0)
        w.run(1.0)
        assert math.hypot(*state(robot)[3][:2]) == pytest.approx(0.3, rel=0.01)
    finally:
        w.close()


def test_odometry_rate_zero_publishes_nothing(tmp_path, urdf):
    w = PluginWorld(tmp_path)
    w.spawn('planar_move_bot', urdf.replace('<odometryRate>20.0</odometryRate>', '<odometryRate>0</odometryRate>'))
    try:
        command(w, 0.3, 0.0, 0.0)
        w.run(0.3)
        assert w.fake.publishers['/planar/odom'].messages == [] and w.fake.publishers['/tf'].messages == []
    finally:
        w.close()
