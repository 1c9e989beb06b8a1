"""gazebo_ros_joint_state_publisher: jointName split as upstream, and on a real Simulator (the skid-steer
fixture) the message, its namespace, rate and refusals."""
import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_joint_state_publisher import joint_names

from model_plugin_sim import PluginWorld, fixture_urdf

WHEELS = ['left_front_wheel_joint', 'right_front_wheel_joint', 'left_rear_wheel_joint', 'right_rear_wheel_joint']
JOINT_NAME = '<jointName>%s</jointName>' % ', '.join(WHEELS)


@pytest.fixture(scope='module')
def urdf():
    text = fixture_urdf('skid_steer_bot')
    assert text.count(JOINT_NAME) == 1
    return text


def test_joint_names_drop_spaces_and_split_at_commas():
    assert joint_names(' a, b ,c ') == ['a', 'b', 'c']
    assert joint_names('left wheel,right') == ['leftwheel', 'right']
    assert joint_names('a,,b') == ['a', '', 'b']


def spawn(tmp_path, urdf, namespace='/skid'):
    w = PluginWorld(tmp_path)
    return w, w.spawn('skid_steer_bot', urdf, namespace, (0.0, 0.0, 0.1))


def test_named_joints_in_order_at_the_update_rate(tmp_path, urdf):
    reordered = urdf.replace(JOINT_NAME, '<jointName>right_rear_wheel_joint,left_front_wheel_joint</jointName>')
    w, robot = spawn(tmp_path, reordered)
    try:
        msg = Twist()
        msg.linear.x = 0.4
        w.fake.subscribers['/skid/cmd_vel'](msg)
        w.run(0.5)
        msgs = w.fake.publishers['/skid/joint_states'].messages
        assert len(msgs) == 24  # 50 Hz from 0.021 s
        assert msgs[0].header.stamp.to_sec() == pytest.approx(0.021)
        last = msgs[-1]
        assert list(last.name) == ['right_rear_wheel_joint', 'left_front_wheel_joint']
        assert list(last.velocity) == pytest.approx([4.0, 4.0], rel=0.05)
        states = robot.body.joint_states_raw([robot.body.joints['right_rear_wheel_joint'].index])
        # read before the step that ends at its stamp, then turning at 4 rad/s until now (0.5 s)
        age = 0.5 - (last.header.stamp.to_sec() - 0.001)
        assert last.position[0] == pytest.approx(states[0][0] - 4.0 * age, abs=0.01)
        assert list(last.effort) == []
    finally:
        w.close()


@pytest.mark.parametrize('own, spawn_ns, topic', [
    (None, '', '/skid_steer_bot/joint_states'),  # no element, nothing requested: the model's name
    ('', '/skid', '/skid_steer_bot/joint_states'),  # an empty element: the model's name too
    ('arm', '/skid', '/arm/joint_states')])
def test_namespace(tmp_path, urdf, own, spawn_ns, topic):
    text = urdf if own is None else urdf.replace(JOINT_NAME, JOINT_NAME + '<robotNamespace>%s</robotNamespace>' % own)
    w, robot = spawn(tmp_path, text, spawn_ns)
    try:
        assert topic in w.fake.publishers
    finally:
        w.close()


@pytest.mark.parametrize('names', ['left_front_wheel_joint,steering', 'left_front_wheel_joint,'])
def test_a_name_that_is_no_joint_refuses_the_plugin(tmp_path, urdf, names):
    w, robot = spawn(tmp_path, urdf.replace(JOINT_NAME, '<jointName>%s</jointName>' % names))
    try:
        errors = w.errors('joint_state_publisher')
        assert len(errors) == 1 and 'refused' in errors[0] and 'not movable joints' in errors[0]
        assert '/skid/joint_states' not in w.fake.publishers
    finally:
        w.close()


def test_without_joint_names_it_warns_and_publishes_empty_states(tmp_path, urdf):
    w, robot = spawn(tmp_path, urdf.replace(JOINT_NAME, ''))
    try:
        assert len(w.warnings('<jointName> is missing')) == 1
        w.run(0.05)
        msgs = w.fake.publishers['/skid/joint_states'].messages
        assert msgs and list(msgs[-1].name) == [] and list(msgs[-1].position) == []
    finally:
        w.close()
