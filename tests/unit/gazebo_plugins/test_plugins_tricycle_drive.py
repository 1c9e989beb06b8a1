"""gazebo_ros_tricycle_drive on a real Simulator: a three-wheeled base (steered, driven front wheel; two free
encoder wheels 0.5 m apart) spawned at the root. The driven wheel's speed is linear.x / r and the steering angle
angular.z; encoder odometry is upstream's integration of the encoder wheels' travel (its yaw grows with
left - right travel); world odometry is the true pose; the wheel ramp, steering by speed, joint states, wheel TFs,
refusals."""
import math

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.kinematics import tricycle
from racebot_sim_bridge.kinematics.rotations import yaw_of

from model_plugin_sim import PluginWorld

R = 0.075  # every wheel's radius (the plugin's default diameters, 0.15)
WHEEL = """<link name="{name}"><inertial><mass value="0.5"/>
  <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.075" length="0.04"/></geometry></collision>
 </link>"""


def tricycle_urdf(params=''):
    return """<robot name="trike">
 <link name="base_link"><inertial><mass value="5"/>
  <inertia ixx="0.1" iyy="0.2" izz="0.2" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><origin xyz="0.2 0 0.1"/><geometry><box size="0.6 0.4 0.05"/></geometry></collision></link>
 <link name="steering_link"><inertial><mass value="0.2"/>
  <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="front_steering_joint" type="revolute"><parent link="base_link"/><child link="steering_link"/>
  <origin xyz="0.45 0 0"/><axis xyz="0 0 1"/><limit lower="-1.6" upper="1.6" effort="100" velocity="10"/></joint>
 {front}
 <joint name="front_wheel_joint" type="continuous"><parent link="steering_link"/><child link="front_wheel"/>
  <axis xyz="0 1 0"/></joint>
 {left}
 <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left_wheel"/>
  <origin xyz="0 0.25 0"/><axis xyz="0 1 0"/></joint>
 {right}
 <joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right_wheel"/>
  <origin xyz="0 -0.25 0"/><axis xyz="0 1 0"/></joint>
 <gazebo><plugin name="trike_drive" filename="libgazebo_ros_tricycle_drive.so">%s</plugin></gazebo>
</robot>""".format(front=WHEEL.format(name='front_wheel'), left=WHEEL.format(name='left_wheel'),
                   right=WHEEL.format(name='right_wheel')) % params


def spawn(tmp_path, params='', namespace='/', ros_params=None):
    w = PluginWorld(tmp_path, ros_params)
    robot = w.spawn('trike', tricycle_urdf(params), namespace, (0.0, 0.0, R))
    return w, robot


def command(w, vx, angle, topic='/cmd_vel'):
    msg = Twist()
    msg.linear.x, msg.angular.z = vx, angle
    w.fake.subscribers[topic](msg)


def joints(w, robot, *names):
    return [robot.body.joint_states_raw([robot.body.joints[n].index])[0] for n in names]


def test_topics_in_the_gazebo_ros_namespace_and_the_defaults_said_once(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        assert {'/odom', '/tf'} == set(w.fake.publishers) and {'/cmd_vel'} == set(w.fake.subscribers)
        assert w.warnings() == [] and w.errors() == []
        said = [m for level, m in w.fake.logs if level == 'info' and 'defaults used' in m]
        assert len(said) == 1 and '<robotBaseFrame> base_link' in said[0]
    finally:
        w.close()
    w, robot = spawn(tmp_path, '<robotNamespace></robotNamespace><publishWheelJointState>true</publishWheelJointState>')
    try:  # GazeboRos: an empty robotNamespace is the model's name
        assert {'/trike/odom', '/trike/joint_states'} <= set(w.fake.publishers)
        assert {'/trike/cmd_vel'} == set(w.fake.subscribers)
    finally:
        w.close()


def test_straight_drive_world_odometry_and_the_wheel_speed(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        command(w, 0.3, 0.0)
        w.run(2.0)
        (front,) = joints(w, robot, 'front_wheel_joint')
        assert front[1] == pytest.approx(0.3 / R, rel=0.01)  # linear.x / (actuatedWheelDiameter / 2)
        odom = w.fake.publishers['/odom'].messages
        last = odom[-1]
        assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_link')
        assert last.twist.twist.linear.x == pytest.approx(0.3, rel=0.03)
        frame = robot.body.frame_pose()
        w.run(0.01)  # the next update reads the pose the last step left
        p = w.fake.publishers['/odom'].messages[-1].pose.pose.position
        assert (p.x, p.y, p.z) == pytest.approx(frame.position, abs=2e-3)  # z too: the model's pose
        assert p.z == pytest.approx(R, abs=0.01)
        assert list(last.pose.covariance[0:36:7]) == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
        stamps = [m.header.stamp.to_sec() for m in odom[:3]]  # 100 Hz: more than 10 ms since the last
        assert stamps == pytest.approx([0.011, 0.021, 0.031])
        tf = [t for m in w.fake.publishers['/tf'].messages for t in m.transforms]
        assert {(t.header.frame_id, t.child_frame_id) for t in tf} == {('odom', 'base_link')}
    finally:
        w.close()


def test_encoder_odometry_integrates_the_encoder_wheels_with_upstreams_yaw_sign(tmp_path):
    w, robot = spawn(tmp_path, '<odometrySource>encoder</odometrySource>')
    try:
        left0, right0 = (s[0] for s in joints(w, robot, 'left_wheel_joint', 'right_wheel_joint'))
        command(w, 0.3, 0.4)  # steered left: the robot turns left (its true yaw grows)
        w.run(0.010)
        assert joints(w, robot, 'front_steering_joint')[0][0] == pytest.approx(0.0, abs=1e-6)  # no update yet
        w.run(0.001)
        assert joints(w, robot, 'front_steering_joint')[0][0] == pytest.approx(0.4, abs=1e-6)  # set: kinematic
        w.run(3.0)  # its last step ends at 3.011 s: an update, the encoders integrated up to the step before
        left, right = (s[0] for s in joints(w, robot, 'left_wheel_joint', 'right_wheel_joint'))
        sl, sr = (left - left0) * R, (right - right0) * R
        assert sr > sl > 0.3  # a left turn: the right wheel is the outer one
        odom = w.fake.publishers['/odom'].messages[-1]
        theta = 2 * math.atan2(odom.pose.pose.orientation.z, odom.pose.pose.orientation.w)
        assert theta == pytest.approx((sl - sr) / 0.5, abs=2e-3)  # upstream's sign: (left - right) / separation
        true_yaw = yaw_of(robot.body.frame_pose().orientation)
        assert true_yaw == pytest.approx((sr - sl) / 0.5, rel=0.05)  # the wheels roll without slipping
        assert odom.pose.pose.position.y < -0.05 and robot.body.frame_pose().position[1] > 0.05  # mirrored
        t = odom.twist.twist
        assert t.angular.z == pytest.approx(-robot.body.twist().angular[2], rel=0.15)  # one step's wheel rates
        # the twist in odom axes: its direction is the encoder heading, not the base's x
        assert math.atan2(t.linear.y, t.linear.x) == pytest.approx(theta, abs=0.05) and abs(t.linear.y) > 0.05
        assert odom.pose.pose.position.z == 0.0
    finally:
        w.close()


def test_wheel_ramp_raises_at_deceleration_and_lowers_at_acceleration(tmp_path):
    w, robot = spawn(tmp_path, '<wheelAcceleration>8</wheelAcceleration><wheelDeceleration>2</wheelDeceleration>')
    try:
        command(w, 0.3, 0.0)  # 4 rad/s
        # 101 updates, each raising the speed by wheelDeceleration (upstream's quirk) * 11 ms: the time since the
        # last update is read before it moves on by the 10 ms period, so an update is 11 ms after the last one's
        w.run(1.011)
        speed = joints(w, robot, 'front_wheel_joint')[0][1]
        assert speed == pytest.approx(101 * 2 * 0.011, rel=0.03)
        w.run(1.5)
        assert joints(w, robot, 'front_wheel_joint')[0][1] == pytest.approx(4.0, abs=0.02)
        command(w, 0.0, 0.0)
        w.run(0.25)  # 25 updates lowering it by wheelAcceleration * 0.011
        assert joints(w, robot, 'front_wheel_joint')[0][1] == pytest.approx(4.0 - 25 * 8 * 0.011, abs=0.1)
    finally:
        w.close()


def test_steering_speed_drives_the_steering_joint_at_that_speed(tmp_path):
    w, robot = spawn(tmp_path, '<steeringSpeed>1.0</steeringSpeed><wheelTorque>20</wheelTorque>')
    try:
        command(w, 0.0, 0.5)
        w.run(0.211)
        steer = joints(w, robot, 'front_steering_joint')[0]
        assert steer[1] == pytest.approx(1.0, rel=0.02) and steer[0] == pytest.approx(0.2, abs=0.02)
        w.run(0.5)
        steer = joints(w, robot, 'front_steering_joint')[0]
        assert abs(steer[0] - 0.5) < 0.02 and abs(steer[1]) < 0.05  # stopped within the tolerance
        command(w, 0.0, 3.0)  # clamped to pi / 2
        assert tricycle.steering(3.0, 0.0, 0.0, 0.0, 0.01, 0.01) == ('position', math.pi / 2)
    finally:
        w.close()


def test_joint_states_and_wheel_tfs_named_after_the_joints(tmp_path):
    w, robot = spawn(tmp_path, '<publishWheelJointState>true</publishWheelJointState>'
                               '<publishWheelTF>true</publishWheelTF><updateRate>50</updateRate>',
                     ros_params={'/tf_prefix': 'trike1'})
    try:
        command(w, 0.2, -0.3)
        w.run(0.5)
        js = w.fake.publishers['/joint_states'].messages[-1]
        assert list(js.name) == ['front_steering_joint', 'front_wheel_joint', 'left_wheel_joint', 'right_wheel_joint']
        assert js.position[0] == pytest.approx(-0.3, abs=1e-6) and js.velocity[1] == pytest.approx(0.2 / R, rel=0.05)
        assert list(js.effort) == [0.0] * 4
        tf = {(t.header.frame_id, t.child_frame_id): t.transform for m in w.fake.publishers['/tf'].messages
              for t in m.transforms}
        assert set(tf) == {('trike1/odom', 'trike1/base_link'), ('trike1/base_link', 'trike1/front_steering_joint'),
                           ('trike1/steering_link', 'trike1/front_wheel_joint'),
                           ('trike1/base_link', 'trike1/left_wheel_joint'),
                           ('trike1/base_link', 'trike1/right_wheel_joint')}
        front = tf[('trike1/steering_link', 'trike1/front_wheel_joint')]  # the child's pose in the MODEL frame
        assert (front.translation.x, front.translation.y) == pytest.approx((0.45, 0.0), abs=2e-3)
        steer = tf[('trike1/base_link', 'trike1/front_steering_joint')].rotation
        assert 2 * math.atan2(steer.z, steer.w) == pytest.approx(-0.3, abs=1e-3)
    finally:
        w.close()


@pytest.mark.parametrize('params, said', [
    ('<steeringJoint>nope</steeringJoint>', '<steeringJoint>nope</steeringJoint> is not a movable joint'),
    ('<encoderWheelLeftJoint>front_steering</encoderWheelLeftJoint>', 'is not a movable joint'),
])
def test_an_unknown_joint_refuses_the_plugin(tmp_path, params, said):
    w, robot = spawn(tmp_path, params)
    try:
        errors = w.errors('refused')
        assert len(errors) == 1 and said in errors[0], w.fake.logs
        assert '/odom' not in w.fake.publishers
        w.run(0.02)
    finally:
        w.close()


def test_encoder_step_is_diff_drives_with_the_sides_exchanged():
    pose, twist = tricycle.encoder_step((0.0, 0.0, 0.0), 2.0, 4.0, 0.15, 0.5, 0.1)
    sl, sr = 2.0 * 0.075 * 0.1, 4.0 * 0.075 * 0.1
    assert pose[2] == pytest.approx((sl - sr) / 0.5)
    assert pose[0] == pytest.approx((sl + sr) / 2 * math.cos((sl - sr) / 1.0))
    assert pose[1] == pytest.approx((sl + sr) / 2 * math.sin((sl - sr) / 1.0))
    assert twist == pytest.approx((pose[0] / 0.1, pose[1] / 0.1, pose[2] / 0.1))
    assert tricycle.wheel_speed(4.0, 1.0, 8.0, 2.0, 0.01, 0.01) == pytest.approx(1.02)
    assert tricycle.wheel_speed(0.0, 4.0, 8.0, 2.0, 0.01, 0.01) == pytest.approx(3.92)
    assert tricycle.wheel_speed(4.0, 3.995, 8.0, 2.0, 0.01, 0.01) == 3.995  # within the tolerance: kept
    assert tricycle.steering(0.5, 0.6, 5.0, 1.0, 0.01, 0.01) == ('velocity', 1.0)  # upstream's angle-vs-speed test
