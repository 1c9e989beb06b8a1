"""gazebo_ros_p3d: upstream's arithmetic (relative_state) and, on a real Simulator with the skid-steer
fixture, its topic, rate, frames, world-frame velocities, noise and refusals."""
import math
import statistics

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_p3d import relative_state
from racebot_sim_bridge.kinematics.rotations import (conjugate, quaternion_multiply, rotate, rotate_back,
                                                     rpy_to_quaternion, yaw_of)

from model_plugin_sim import PluginWorld, fixture_urdf

TOPIC = '/skid/ground_truth/state'
P3D_START = '<updateRate>50.0</updateRate><bodyName>'


@pytest.fixture(scope='module')
def urdf():
    text = fixture_urdf('skid_steer_bot')
    assert text.count(P3D_START) == 1
    return text


def with_p3d(urdf, **tags):
    """The fixture with p3d's tags replaced (None removes one) or added."""
    import re
    for tag, value in tags.items():
        pattern = re.compile(r'<%s>[^<]*</%s>' % (tag, tag))
        start = urdf.index(P3D_START)
        end = urdf.index('</plugin>', start)
        part = urdf[start:end]
        new = '' if value is None else '<%s>%s</%s>' % (tag, value, tag)
        part = pattern.sub(new, part) if pattern.search(part) else part + new
        urdf = urdf[:start] + part + urdf[end:]
    return urdf


def spawn(tmp_path, urdf, yaw=0.0):
    w = PluginWorld(tmp_path)
    robot = w.spawn('skid_steer_bot', urdf, '/skid', (0.0, 0.0, 0.1))
    if yaw:
        frame = robot.body.com_pose_for_frame((0.0, 0.0, 0.1), rpy_to_quaternion(0, 0, yaw))
        robot.body.set_pose(frame.position, frame.orientation)
    return w, robot


def drive(w, vx, wz=0.0):
    msg = Twist()
    msg.linear.x, msg.angular.z = vx, wz
    w.fake.subscribers['/skid/cmd_vel'](msg)


def test_in_the_world_the_state_passes_through_with_offsets():
    q = rpy_to_quaternion(0.1, 0.2, 0.3)
    body = ((1.0, 2.0, 3.0), q, (0.4, 0.5, 0.6), (0.01, 0.02, 0.03))
    pos, orn, lin, ang = relative_state(body, None, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert (pos, lin, ang) == ((1.0, 2.0, 3.0), (0.4, 0.5, 0.6), (0.01, 0.02, 0.03))
    assert orn == pytest.approx(q)
    pos, orn, _, _ = relative_state(body, None, (1.0, 0.0, -1.0), (0.0, 0.0, 0.5))
    assert pos == (2.0, 2.0, 2.0)
    assert orn == pytest.approx(quaternion_multiply(rpy_to_quaternion(0, 0, 0.5), q))  # offset applied first


def test_relative_to_a_link_as_upstream_computes_it():
    qb, qf = rpy_to_quaternion(0.1, 0.0, 1.0), rpy_to_quaternion(0.0, 0.2, 0.5)
    body = ((1.0, 2.0, 0.0), qb, (1.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    frame = ((0.5, 0.5, 0.0), qf, (0.0, 1.0, 0.0), (0.0, 0.0, 0.25))
    pos, orn, lin, ang = relative_state(body, frame, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert pos == pytest.approx(rotate_back(qf, (0.5, 1.5, 0.0)))  # into the frame's axes
    assert orn == pytest.approx(quaternion_multiply(qb, conjugate(qf)))  # q_body * q_frame^-1, as upstream
    assert lin == pytest.approx(rotate(qf, (1.0, -1.0, 0.0)))  # turned BY the frame's rotation, as upstream
    assert ang == pytest.approx(rotate(qf, (0.0, 0.0, 0.75)))


def test_publishes_only_with_a_subscriber_at_its_rate(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf)
    try:
        w.run(0.1)
        pub = w.fake.publishers[TOPIC]
        assert pub.messages == []
        pub.connections = 1
        w.run(0.1)
        stamps = [m.header.stamp.to_sec() for m in pub.messages]
        assert stamps == pytest.approx([0.101, 0.121, 0.141, 0.161, 0.181])  # first at once, then 50 Hz
    finally:
        w.close()


def test_pose_and_world_frame_velocity_of_the_body_with_noise(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf, yaw=0.7)
    try:
        pub = w.fake.publishers[TOPIC]
        pub.connections = 1
        drive(w, 0.4)
        w.run(1.0)
        frame = robot.body.frame_pose()
        w.run(0.02)
        msg = pub.messages[-1]
        assert (msg.header.frame_id, msg.child_frame_id) == ('world', 'base_link')
        p = msg.pose.pose
        assert (p.position.x, p.position.y, p.position.z) == pytest.approx(frame.position, abs=0.01)
        assert yaw_of((p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)) == \
            pytest.approx(yaw_of(frame.orientation), abs=0.01)
        # world axes: 0.4 m/s along a heading of 0.7 rad, noise sigma 0.01
        recent = pub.messages[-20:]
        vx = statistics.mean(m.twist.twist.linear.x for m in recent)
        vy = statistics.mean(m.twist.twist.linear.y for m in recent)
        assert (vx, vy) == pytest.approx((0.4 * math.cos(0.7), 0.4 * math.sin(0.7)), abs=0.02)
        assert list(msg.pose.covariance[0:36:7]) == pytest.approx([1e-4] * 6)
        assert list(msg.twist.covariance[0:36:7]) == pytest.approx([1e-4] * 6)
    finally:
        w.close()


@pytest.mark.parametrize('sigma', ['0.05', '-0.05'])  # upstream's Box-Muller takes a negative sigma as well
def test_noise_is_on_the_twist_only_with_its_standard_deviation(tmp_path, urdf, sigma):
    w, robot = spawn(tmp_path, with_p3d(urdf, gaussianNoise=sigma, updateRate='0'))
    try:
        pub = w.fake.publishers[TOPIC]
        pub.connections = 1
        w.run(0.5)
        msgs = pub.messages[-400:]
        assert len(msgs) == 400  # updateRate 0: every world update
        for part in ('linear', 'angular'):
            for axis in 'xyz':
                spread = statistics.pstdev(getattr(getattr(m.twist.twist, part), axis) for m in msgs)
                assert spread == pytest.approx(0.05, rel=0.2), (part, axis)
        assert statistics.pstdev(m.pose.pose.position.x for m in msgs) < 1e-4
        assert msgs[-1].twist.covariance[35] == pytest.approx(0.0025) and w.warnings() == []
    finally:
        w.close()


def test_a_link_as_reference_frame(tmp_path, urdf):
    w, robot = spawn(tmp_path, with_p3d(urdf, frameName='left_front_wheel', xyzOffset='0 0 1'))
    try:
        pub = w.fake.publishers[TOPIC]
        pub.connections = 1
        w.run(0.05)
        msg = pub.messages[-1]
        assert msg.header.frame_id == 'left_front_wheel'
        p = msg.pose.pose.position
        assert (p.x, p.y, p.z) == pytest.approx((-0.15, -0.2, 1.0), abs=0.01)  # base from the wheel, + offset
    finally:
        w.close()


@pytest.mark.parametrize('tags, reason', [
    ({'bodyName': None}, '<bodyName> is missing'),
    ({'bodyName': 'chassis'}, '<bodyName>chassis</bodyName> is not a link of the model'),
    ({'topicName': None}, '<topicName> is missing'),
    ({'frameName': 'map_link'}, '<frameName>map_link</frameName> is not a link'),
])
def test_refusals_with_the_reason(tmp_path, urdf, tags, reason):
    w, robot = spawn(tmp_path, with_p3d(urdf, **tags))
    try:
        errors = w.errors('p3d_base_controller')
        assert len(errors) == 1 and reason in errors[0] and 'refused' in errors[0]
        assert TOPIC not in w.fake.publishers
    finally:
        w.close()


def test_a_link_gazebo_lumps_away_is_read_as_its_parent_with_the_joint_as_offset(tmp_path, urdf):
    # as sdformat rewrites it: bodyName base_link, xyzOffset J * 0 = the joint's 0 0 0.5 (added to the position)
    lumped = urdf.replace('</robot>', '<link name="imu_link"/><joint name="imu_joint" type="fixed">'
                          '<parent link="base_link"/><child link="imu_link"/><origin xyz="0 0 0.5"/></joint></robot>')
    w, robot = spawn(tmp_path, with_p3d(lumped, bodyName='imu_link'))  # its xyzOffset 0 0 0: composed with J
    try:
        assert w.errors('p3d_base_controller') == []
        pub = w.fake.publishers[TOPIC]
        pub.connections = 1
        w.run(0.02)
        msg = pub.messages[-1]
        assert msg.child_frame_id == 'base_link'
        assert msg.pose.pose.position.z == pytest.approx(robot.body.frame_pose().position[2] + 0.5, abs=0.01)
    finally:
        w.close()


def test_the_old_plural_offset_tags_are_named_and_ignored(tmp_path, urdf):
    w, robot = spawn(tmp_path, with_p3d(urdf, xyzOffset=None, xyzOffsets='0 0 5'))
    try:
        assert len(w.warnings('<xyzOffsets> is not read')) == 1
        pub = w.fake.publishers[TOPIC]
        pub.connections = 1
        w.run(0.02)
        assert pub.messages[-1].pose.pose.position.z == pytest.approx(0.1, abs=0.01)
    finally:
        w.close()
