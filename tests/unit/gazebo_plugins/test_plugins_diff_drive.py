"""gazebo_ros_diff_drive and the gazebo_ros_imu model plugin on a real Simulator
(tests/fixtures/robots/diffbot_plugins, spawned at the root as spawn_model does there): topics, wheel
speeds and the ramp, encoder and world odometry, TF, joint states, the IMU's message, refusals and
warnings for bad parameters."""
import math

import pytest

from racebot_sim_bridge.kinematics import differential as kin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace
from racebot_sim_bridge.gazebo_plugins import gazebo_ros_imu as imu_plugin
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion, yaw_of

from model_plugin_sim import ROBOTS
from diff_drive_world import command, spawn

DRIVE = 'differential_drive_controller'
RADIUS, SEPARATION = 0.075, 0.34


@pytest.fixture(scope='module')
def urdf():
    import xacro
    path = ROBOTS / 'diffbot_plugins' / 'urdf' / 'diffbot_plugins.urdf.xacro'
    return xacro.process_file(str(path), mappings={}).toxml()  # its xacro:arg needs an argument context


def replace(urdf, old, new):
    assert urdf.count(old) == 1, old
    return urdf.replace(old, new)


def with_param(urdf, tag, text):
    """The drive plugin with <tag>text</tag> first (the first element of a tag is the one read)."""
    first = '<commandTopic>cmd_vel</commandTopic>'
    return replace(urdf, first, '<%s>%s</%s>' % (tag, text, tag) + first)


def wheel_velocities(w, robot):
    names = ('left_wheel_joint', 'right_wheel_joint')
    return [s[1] for s in robot.body.joint_states_raw([robot.body.joints[n].index for n in names])]


def quaternion(msg):
    return msg.x, msg.y, msg.z, msg.w


def base_twist(robot):
    """The base's (forward speed, yaw rate) from PyBullet's ground truth."""
    frame = robot.body.frame_pose()
    linear, angular = robot.body.twist()
    yaw = yaw_of(frame.orientation)
    return linear[0] * math.cos(yaw) + linear[1] * math.sin(yaw), angular[2]


def test_gazebo_ros_namespace_rule():
    """GazeboRos (gazebo_ros_utils.cpp): no element or an empty one -> the model's name; then + '/'."""
    assert model_plugin_namespace('gazebo_ros', None, '', 'bot') == '/bot'
    assert model_plugin_namespace('gazebo_ros', '', '/x', 'bot') == '/bot'
    assert model_plugin_namespace('gazebo_ros', None, '/', 'bot') == '/'  # spawn_model at the root
    assert model_plugin_namespace('gazebo_ros', None, '/fleet', 'bot') == '/fleet'


def test_topics_at_the_root_and_no_warning(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        assert {'/odom', '/joint_states', '/tf', '/imu'} <= set(w.fake.publishers)
        assert {'/cmd_vel'} == set(w.fake.subscribers)
        assert '/imu_service' in w.fake.services
        assert w.warnings() == [] and w.errors() == []
    finally:
        w.close()


def test_unsubscribed_outputs_are_not_made_and_the_encoders_go_on_meanwhile(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf, listen=False)
    try:
        command(w, 0.3, 0.5)
        w.run(0.5)
        assert [len(w.fake.publishers[t].messages) for t in ('/odom', '/tf', '/joint_states')] == [0, 0, 0]
        assert max(abs(v) for v in wheel_velocities(w, robot)) > 1.0  # it drives all the same
        w.fake.publishers['/odom'].connections = 1
        w.run(0.1)
        odom = w.fake.publishers['/odom'].messages
        assert len(odom) == 5 and not w.fake.publishers['/tf'].messages  # 50 Hz; /tf still unsubscribed
        assert odom[-1].pose.pose.position.x > 0.05  # integrated from the start, not from the subscription
    finally:
        w.close()


def test_drives_the_twist_after_the_ramp_and_integrates_the_encoders(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        command(w, 0.3, 0.5)
        w.run(0.1)
        # wheelAcceleration 1 m/s^2: after 0.1 s no rim is faster than 0.1 m/s (+ one update of slack)
        assert max(abs(v) * RADIUS for v in wheel_velocities(w, robot)) < 0.13
        w.run(1.4)
        left, right = kin.wheel_speeds(0.3, 0.5, SEPARATION)
        assert wheel_velocities(w, robot) == pytest.approx([left / RADIUS, right / RADIUS], rel=0.02)
        vx, wz = base_twist(robot)
        assert vx == pytest.approx(0.3, rel=0.05) and wz == pytest.approx(0.5, rel=0.05)
        odom = w.fake.publishers['/odom'].messages
        last = odom[-1]
        assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_footprint')
        assert last.twist.twist.linear.x == pytest.approx(0.3, rel=0.03)
        assert last.twist.twist.angular.z == pytest.approx(0.5, rel=0.03)
        assert list(last.pose.covariance[0:36:7]) == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
        assert list(last.twist.covariance) == [0.0] * 36
        frame = robot.body.frame_pose()
        p = last.pose.pose
        travelled = 0.3 * 1.5
        assert math.hypot(p.position.x - frame.position[0], p.position.y - frame.position[1]) < 0.05 * travelled
        assert yaw_of(quaternion(p.orientation)) == pytest.approx(yaw_of(frame.orientation), abs=0.03)
        assert p.position.z == 0.0
        # updateRate 50 at a 1 ms step: an update every 20 ms, stamped with the sim time
        stamps = [m.header.stamp.to_sec() for m in odom]
        assert stamps[:3] == pytest.approx([0.021, 0.041, 0.061]) and len(odom) == 74
        tf = [t for m in w.fake.publishers['/tf'].messages for t in m.transforms]
        odom_tf = [t for t in tf if (t.header.frame_id, t.child_frame_id) == ('odom', 'base_footprint')]
        assert len(odom_tf) == 74 and odom_tf[-1].transform.translation.x == p.position.x
    finally:
        w.close()


def test_wheel_tf_and_joint_states_right_wheel_first(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        command(w, 0.2, 0.0)
        w.run(0.5)
        tf = {(t.header.frame_id, t.child_frame_id): t for m in w.fake.publishers['/tf'].messages
              for t in m.transforms}
        # the joints' parent is base_link, merged into base_footprint: Gazebo's parent link
        left = tf[('base_footprint', 'left_wheel')].transform
        right = tf[('base_footprint', 'right_wheel')].transform
        assert (left.translation.x, left.translation.y, left.translation.z) == pytest.approx((0, 0.17, 0.075), abs=2e-3)
        assert right.translation.y == pytest.approx(-0.17, abs=2e-3)
        js = w.fake.publishers['/joint_states'].messages[-1]
        assert list(js.name) == ['right_wheel_joint', 'left_wheel_joint']
        assert js.position[0] > 0.5 and js.velocity == [] and js.effort == []
        # the wheel's TF turns with its joint: about y by the joint's angle
        angle = 2 * math.atan2(left.rotation.y, left.rotation.w)
        assert math.remainder(angle - js.position[1], 2 * math.pi) == pytest.approx(0.0, abs=0.05)
    finally:
        w.close()


def test_world_odometry_is_the_true_pose_and_no_ramp_without_acceleration(tmp_path, urdf):
    text = with_param(with_param(urdf, 'odometrySource', 'world'), 'wheelAcceleration', '0')
    w, robot = spawn(tmp_path, text)
    try:
        command(w, 0.3, 0.0)
        w.run(0.1)
        assert min(abs(v) * RADIUS for v in wheel_velocities(w, robot)) > 0.25
        w.run(0.4)
        frame = robot.body.frame_pose()
        w.run(0.02)  # the next odometry reads the pose the last step left
        p = w.fake.publishers['/odom'].messages[-1].pose.pose
        assert (p.position.x, p.position.y, p.position.z) == pytest.approx(frame.position, abs=1e-3)
        assert w.fake.publishers['/odom'].messages[-1].twist.twist.linear.x == pytest.approx(0.3, rel=0.03)
    finally:
        w.close()


def test_without_publish_tf_there_is_no_odometry_and_frames_go_under_tf_prefix(tmp_path, urdf):
    w, robot = spawn(tmp_path, replace(urdf, '<publishTf>true<', '<publishTf>false<'))
    try:
        assert '/odom' not in w.fake.publishers
        w.run(0.05)
        frames = {(t.header.frame_id, t.child_frame_id) for m in w.fake.publishers['/tf'].messages
                  for t in m.transforms}
        assert frames == {('base_footprint', 'left_wheel'), ('base_footprint', 'right_wheel')}
    finally:
        w.close()
    w, robot = spawn(tmp_path, urdf, params={'/tf_prefix': 'bot1'}, namespace='/fleet')
    try:
        w.run(0.03)
        odom = w.fake.publishers['/fleet/odom'].messages[-1]
        assert (odom.header.frame_id, odom.child_frame_id) == ('bot1/odom', 'bot1/base_footprint')
    finally:
        w.close()


@pytest.mark.parametrize('tag, text, used', [
    ('wheelSeparation', '-0.34', 'using 0.34'), ('wheelDiameter', '0', 'using 0.15'),
    ('wheelTorque', 'strong', 'using 5.0'), ('publishWheelTF', 'yes', 'using False'),
    ('odometrySource', '1', 'not the enum numbers 0 and 1); using world'),
    ('odometrySource', 'gps', 'must be encoder or world; using world')])
def test_bad_values_warn_naming_the_parameter_and_the_value_used(tmp_path, urdf, tag, text, used):
    w, robot = spawn(tmp_path, with_param(urdf, tag, text))
    try:
        warnings = w.warnings('<%s>%s</%s>' % (tag, text, tag))
        assert len(warnings) == 1 and used in warnings[0] and DRIVE in warnings[0], w.fake.logs
        command(w, 0.3, 0.0)
        w.run(0.6)
        assert base_twist(robot)[0] == pytest.approx(0.3, rel=0.05)  # the defaults match this robot
    finally:
        w.close()


def test_legacy_mode_true_is_said_to_be_ignored_and_rosdebuglevel_error_hides_warnings(tmp_path, urdf):
    w, robot = spawn(tmp_path, replace(urdf, '<legacyMode>false<', '<legacyMode>true<'))
    try:
        warnings = w.warnings('<legacyMode>true</legacyMode> is not read')
        assert len(warnings) == 1 and 'exchange <leftJoint> and <rightJoint>' in warnings[0]
        command(w, 0.0, 0.5)
        w.run(0.8)
        assert base_twist(robot)[1] == pytest.approx(0.5, rel=0.05)  # a left turn all the same (noetic)
    finally:
        w.close()
    text = with_param(replace(urdf, '<rosDebugLevel>na<', '<rosDebugLevel>Error<'), 'wheelSeparation', '-1')
    w, robot = spawn(tmp_path, text)
    try:
        assert w.warnings(DRIVE) == []
    finally:
        w.close()


@pytest.mark.parametrize('old, new, said', [
    ('<leftJoint>left_wheel_joint<', '<leftJoint>left_axle<', '<leftJoint>left_axle</leftJoint> is not a movable'),
    ('<rightJoint>right_wheel_joint</rightJoint>', '', "<rightJoint> is missing and the default right wheel joint "
                                                      "'right_joint'")])
def test_an_unknown_joint_refuses_the_plugin_and_the_world_goes_on(tmp_path, urdf, old, new, said):
    w, robot = spawn(tmp_path, replace(urdf, old, new))
    try:
        errors = w.errors('refused')
        assert len(errors) == 1 and said in errors[0] and DRIVE in errors[0], errors
        assert 'left_wheel_joint' in errors[0]  # the joints it could name
        assert '/odom' not in w.fake.publishers and '/imu' in w.fake.publishers
        w.run(0.05)
    finally:
        w.close()


def test_reset_zeroes_the_encoder_odometry_and_the_command(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        command(w, 0.3, 0.0)
        w.run(0.5)
        w.sim.reset_world()
        w.run(0.3)
        p = w.fake.publishers['/odom'].messages[-1].pose.pose
        assert abs(p.position.x) < 0.01
        assert abs(base_twist(robot)[0]) < 0.01
    finally:
        w.close()


# -- gazebo_ros_imu (the model plugin) ------------------------------------------------------------
def test_imu_vectors_are_turned_by_the_orientation_as_upstream():
    q = rpy_to_quaternion(0, 0, math.pi / 2)
    orientation, w, a = imu_plugin.imu_vectors(q, rpy_to_quaternion(0, 0, 0), (0.2, 0, 0.5), (1, 0, 0), lambda: 0.0)
    assert orientation == pytest.approx(q)
    assert w == pytest.approx((0, 0.2, 0.5)) and a == pytest.approx((0, 1, 0))  # BY q: x -> y
    offset = rpy_to_quaternion(0, 0, -math.pi / 2)
    orientation, _, a = imu_plugin.imu_vectors(q, offset, (0, 0, 0), (1, 0, 0), lambda: 0.1)
    assert orientation == pytest.approx((0, 0, 0, 1))
    assert a == pytest.approx((1.1, 0.1, 0.1))
    assert imu_plugin.acceleration((1, 2, 3), (2, 2, 1), 0.5) == (2, 0, -4)
    assert imu_plugin.acceleration((1, 2, 3), (2, 2, 1), 0) is None


def test_imu_publishes_with_subscribers_at_its_rate_without_gravity(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        pub = w.fake.publishers['/imu']
        w.run(0.3)
        assert pub.messages == []  # nobody listens
        pub.connections = 1
        w.run(0.5)
        msgs = pub.messages
        assert len(msgs) == 25  # updateRate 50: at least 20 ms apart
        assert msgs[-1].header.frame_id == 'imu_link'
        assert msgs[-1].header.stamp.to_sec() - msgs[-2].header.stamp.to_sec() == pytest.approx(0.02)
        acc = msgs[-1].linear_acceleration
        assert abs(acc.z) < 0.05 and abs(acc.x) < 0.05  # at rest: no gravity in it, as upstream
        command(w, 0.3, 0.0)
        w.run(0.1)  # ramping at 1 m/s^2
        assert pub.messages[-1].linear_acceleration.x == pytest.approx(1.0, abs=0.3)
        w.run(1.0)
        command(w, 0.0, 0.5)
        w.run(1.0)
        last = pub.messages[-1]
        frame = robot.body.frame_pose()
        assert yaw_of(quaternion(last.orientation)) == pytest.approx(yaw_of(frame.orientation), abs=0.02)
        assert last.angular_velocity.z == pytest.approx(0.5, rel=0.05)
        assert list(last.orientation_covariance) == [0.0] * 9
        cls, handler = w.fake.services['/imu_service']
        assert handler(cls._request_class()) is not None  # answers at once
    finally:
        w.close()


def test_imu_noise_and_its_covariance(tmp_path, urdf):
    w, robot = spawn(tmp_path, replace(urdf, '<gaussianNoise>0.0<', '<gaussianNoise>0.1<'))
    try:
        w.fake.publishers['/imu'].connections = 1
        w.run(1.0)
        msgs = w.fake.publishers['/imu'].messages
        zs = [m.angular_velocity.z for m in msgs]
        spread = math.sqrt(sum(z * z for z in zs) / len(zs))
        assert 0.06 < spread < 0.14
        assert msgs[-1].angular_velocity_covariance[4] == pytest.approx(0.01)
        assert msgs[-1].linear_acceleration_covariance[8] == pytest.approx(0.01)
    finally:
        w.close()


@pytest.mark.parametrize('old, new, said', [
    ('<bodyName>base_footprint</bodyName>', '', '<bodyName> is missing'),
    ('<bodyName>base_footprint<', '<bodyName>chassis<', '<bodyName>chassis</bodyName> is not a link')])
def test_imu_refused_without_a_body(tmp_path, urdf, old, new, said):
    w, robot = spawn(tmp_path, replace(urdf, old, new))
    try:
        errors = w.errors('refused')
        assert len(errors) == 1 and said in errors[0] and 'imu_plugin' in errors[0], errors
        assert '/imu' not in w.fake.publishers and '/odom' in w.fake.publishers
    finally:
        w.close()


def test_imu_defaults_and_old_offset_names(tmp_path, urdf):
    text = replace(replace(replace(urdf, '<topicName>imu</topicName>', '<rpyOffsets>0 0 1</rpyOffsets>'),
                           '<serviceName>imu_service</serviceName>', ''), '<frameName>imu_link</frameName>', '')
    w, robot = spawn(tmp_path, text)
    try:
        assert len(w.warnings('<rpyOffsets> is not read')) == 1
        assert '/default_imu' in w.fake.publishers and '/default_imu' in w.fake.services
        w.fake.publishers['/default_imu'].connections = 1
        w.run(0.03)  # updateRate 50
        msg = w.fake.publishers['/default_imu'].messages[-1]
        assert msg.header.frame_id == 'base_footprint'
        assert yaw_of(quaternion(msg.orientation)) == pytest.approx(0.0, abs=1e-3)
    finally:
        w.close()
    w, robot = spawn(tmp_path, replace(urdf, '<topicName>imu</topicName>', '<topicName></topicName>'))
    try:
        assert '/imu' not in w.fake.publishers and '/imu_service' not in w.fake.services
        w.run(0.01)
    finally:
        w.close()
