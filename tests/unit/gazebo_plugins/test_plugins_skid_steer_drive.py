"""gazebo_ros_skid_steer_drive on a real Simulator (tests/fixtures/robots/skid_steer_bot, spawned under
/skid as spawn_model -robot_namespace /skid does): topics, wheel speeds, odometry and TF, refusals and
warnings for bad parameters."""
import math

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion, yaw_of

from model_plugin_sim import PluginWorld, fixture_urdf

WHEELS = ['left_front_wheel_joint', 'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint']
PLUGIN_END = '<broadcastTF>true</broadcastTF>'


@pytest.fixture(scope='module')
def urdf():
    return fixture_urdf('skid_steer_bot')


def spawn(tmp_path, urdf, params=None, yaw=0.0):
    w = PluginWorld(tmp_path, params)
    robot = w.spawn('skid_steer_bot', urdf, '/skid', (0.0, 0.0, 0.1))
    if yaw:
        frame = robot.body.com_pose_for_frame((0.0, 0.0, 0.1), rpy_to_quaternion(0, 0, yaw))
        robot.body.set_pose(frame.position, frame.orientation)
    return w, robot


def command(w, vx, wz, topic='/skid/cmd_vel'):
    msg = Twist()
    msg.linear.x, msg.angular.z = vx, wz
    w.fake.subscribers[topic](msg)


def wheel_velocities(w, robot):
    return [s[1] for s in robot.body.joint_states_raw([robot.body.joints[n].index for n in WHEELS])]


def test_topics_under_the_spawn_namespace(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        assert '/skid/odom' in w.fake.publishers and '/tf' in w.fake.publishers
        assert '/skid/cmd_vel' in w.fake.subscribers
        assert w.warnings() == [] and w.errors() == []
    finally:
        w.close()


def test_drives_straight_and_publishes_odometry_of_the_true_pose(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf, yaw=0.7)
    try:
        command(w, 0.4, 0.0)
        w.run(1.0)
        assert wheel_velocities(w, robot) == pytest.approx([4.0] * 4, rel=0.02)  # 0.4 m/s / 0.1 m
        odom = w.fake.publishers['/skid/odom'].messages
        assert len(odom) == 99  # 100 Hz: at 0.011, 0.021, ... 0.991 s
        assert [m.header.stamp.to_sec() for m in odom[:3]] == pytest.approx([0.011, 0.021, 0.031])
        last = odom[-1]
        assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_link')
        # in the robot's axes although it heads 0.7 rad off the world's x axis
        assert last.twist.twist.linear.x == pytest.approx(0.4, rel=0.03)
        assert abs(last.twist.twist.linear.y) < 0.01
        assert last.pose.pose.position.z == 0.0
        assert list(last.pose.covariance[0:36:7]) == [1e-4, 1e-4, 1e12, 1e12, 1e12, 0.01]
        assert list(last.twist.covariance) == list(last.pose.covariance)
        frame = robot.body.frame_pose()
        w.run(0.01)  # the next odometry reads the pose the last step left
        p = w.fake.publishers['/skid/odom'].messages[-1].pose.pose
        assert (p.position.x, p.position.y) == pytest.approx(frame.position[:2], abs=1e-6)
        assert math.atan2(frame.position[1], frame.position[0]) == pytest.approx(0.7, abs=0.02)
        tf = w.fake.publishers['/tf'].messages[-1].transforms[0]
        assert (tf.header.frame_id, tf.child_frame_id) == ('odom', 'base_link')
        assert tf.transform.translation.z == pytest.approx(0.1, abs=0.01)  # the TF keeps z
    finally:
        w.close()


def test_a_left_turn_drives_the_sides_as_the_kinematics_say(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        command(w, 0.2, 0.8)
        w.run(1.0)
        assert wheel_velocities(w, robot) == pytest.approx([0.4, 3.6, 0.4, 3.6], rel=0.05)
        assert yaw_of(robot.body.frame_pose().orientation) > 0.05
    finally:
        w.close()


def test_without_broadcast_tf_no_transform_is_sent_and_defaults_name_the_frames(tmp_path, urdf):
    text = urdf.replace(PLUGIN_END, '').replace('<robotBaseFrame>base_link</robotBaseFrame>', '')
    w, robot = spawn(tmp_path, text)
    try:
        w.run(0.02)
        assert '/tf' not in w.fake.publishers
        assert w.fake.publishers['/skid/odom'].messages[-1].child_frame_id == 'base_footprint'
    finally:
        w.close()


def test_frames_go_under_tf_prefix(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf, params={'/skid/tf_prefix': 'robot1'})
    try:
        w.run(0.02)
        odom = w.fake.publishers['/skid/odom'].messages[-1]
        assert (odom.header.frame_id, odom.child_frame_id) == ('robot1/odom', 'robot1/base_link')
    finally:
        w.close()


def test_a_wheel_joint_that_is_not_there_refuses_the_plugin(tmp_path, urdf):
    text = urdf.replace('<leftRearJoint>left_rear_wheel_joint<', '<leftRearJoint>left_rear_axle<')
    w, robot = spawn(tmp_path, text)
    try:
        errors = w.errors('skid_steer_drive_controller')
        assert len(errors) == 1 and 'refused' in errors[0] and '<leftRearJoint>left_rear_axle' in errors[0]
        assert 'left_rear_wheel_joint' in errors[0]  # the joints it could name
        assert '/skid/odom' not in w.fake.publishers
        w.run(0.05)  # the world goes on
    finally:
        w.close()


def test_a_missing_wheel_tag_whose_default_joint_is_not_there_refuses_the_plugin(tmp_path, urdf):
    text = urdf.replace('<rightFrontJoint>right_front_wheel_joint</rightFrontJoint>', '')
    w, robot = spawn(tmp_path, text)
    try:
        errors = w.errors('refused')
        assert len(errors) == 1 and '<rightFrontJoint> is missing' in errors[0]
        assert "'right_front_joint'" in errors[0]
    finally:
        w.close()


@pytest.mark.parametrize('tag, text, used', [
    ('wheelSeparation', '-0.4', '0.4'), ('wheelDiameter', 'big', '0.15'), ('torque', '-3', '5.0'),
    ('broadcastTF', 'yes', 'False')])
def test_bad_values_warn_naming_the_parameter_and_the_value_used(tmp_path, urdf, tag, text, used):
    first = '<updateRate>100.0</updateRate>'  # the skid-steer plugin's first element
    assert urdf.count(first) == 1
    body = urdf.replace(first, '<%s>%s</%s>' % (tag, text, tag) + first)  # the first one of a tag wins
    w, robot = spawn(tmp_path, body)
    try:
        warnings = w.warnings('<%s>%s</%s>' % (tag, text, tag))
        assert len(warnings) == 1 and ('using %s' % used) in warnings[0], w.fake.logs
    finally:
        w.close()


def test_after_reset_simulation_it_goes_on_from_the_new_time_with_its_command(tmp_path, urdf):
    # upstream would wait until the sim time passed its last update again; racebot restarts its clock
    w, robot = spawn(tmp_path, urdf)
    try:
        command(w, 0.4, 0.0)
        w.run(0.5)
        w.sim.reset_simulation()
        pub = w.fake.publishers['/skid/odom']
        before = len(pub.messages)
        w.run(0.5)
        stamps = [m.header.stamp.to_sec() for m in pub.messages[before:]]
        assert stamps[:2] == pytest.approx([0.012, 0.022]) and len(stamps) == 49  # the clock restarts at 0.001
        assert wheel_velocities(w, robot) == pytest.approx([4.0] * 4, rel=0.02)  # cmd_vel kept, as upstream
    finally:
        w.close()
