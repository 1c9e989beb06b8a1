"""hector_gazebo_plugins' IMU (libhector_gazebo_ros_imu.so) on a real Simulator with the skid-steer fixture:
at rest it reads gravity up and no rate, every world update by default; its biases tilt and turn the reported
orientation as upstream's Update() does; the bias topic and the calibrate service; turning shows as yaw rate."""
import math

import pytest
from geometry_msgs.msg import Twist
from std_srvs.srv import EmptyRequest

from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_imu import rate_from_rotation
from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy, rpy_to_quaternion

from model_plugin_sim import PluginWorld, fixture_urdf

IMU = ('<gazebo><plugin name="imu_controller" filename="libhector_gazebo_ros_imu.so">%s<bodyName>base_link'
       '</bodyName><topicName>imu/data</topicName></plugin></gazebo></robot>')


def spawn(tmp_path, extra=''):
    w = PluginWorld(tmp_path)
    w.spawn('skid_steer_bot', fixture_urdf('skid_steer_bot').replace('</robot>', IMU % extra), '/skid',
            (0.0, 0.0, 0.1))
    assert not w.errors(), w.errors()
    return w


def test_rate_from_a_change_of_orientation():
    a, b = rpy_to_quaternion(0, 0, 0.3), rpy_to_quaternion(0, 0, 0.31)
    assert rate_from_rotation(a, b, 0.01) == pytest.approx((0.0, 0.0, 1.0))
    assert rate_from_rotation(a, a, 0.01) == (0.0, 0.0, 0.0)


def test_at_rest_gravity_up_every_world_update(tmp_path):
    w = spawn(tmp_path)
    try:
        w.run(1.0)
        msgs = w.fake.publishers['/skid/imu/data'].messages
        assert len(msgs) == pytest.approx(1000, abs=2)  # updateRate 0: every world update, as hector
        m = msgs[-1]
        assert m.header.frame_id == 'base_link'
        assert (m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z) == \
            (pytest.approx(0.0, abs=0.05), pytest.approx(0.0, abs=0.05), pytest.approx(9.8, abs=0.05))
        assert abs(m.angular_velocity.z) < 1e-3 and m.orientation.w == pytest.approx(1.0, abs=1e-3)
        assert '/skid/imu/data/bias' in w.fake.publishers
    finally:
        w.close()


def test_biases_tilt_and_turn_the_orientation_and_calibrate_clears_the_rate_drift(tmp_path):
    w = spawn(tmp_path, '<updateRate>100</updateRate><accelOffset>0.98 0 0</accelOffset><yawOffset>0.2</yawOffset>'
                        '<rateOffset>0 0 0.01</rateOffset><rateDrift>0 0 0.5</rateDrift>')
    try:
        w.run(0.5)
        msgs = w.fake.publishers['/skid/imu/data'].messages
        assert len(msgs) == pytest.approx(50, abs=1)
        m = msgs[-1]
        roll, pitch, yaw = quaternion_to_rpy((m.orientation.x, m.orientation.y, m.orientation.z, m.orientation.w))
        assert yaw == pytest.approx(0.2, abs=0.01)  # the yaw bias
        assert pitch == pytest.approx(-0.1, abs=0.01)  # x accel bias 0.98 on g 9.8: tilted by about 0.1 rad
        assert m.linear_acceleration.x == pytest.approx(0.98, abs=0.05)
        bias = w.fake.publishers['/skid/imu/data/bias'].messages[-1]
        assert bias.linear_acceleration.x == pytest.approx(0.98)
        w.fake.services['/skid/imu/data/calibrate'](EmptyRequest())
        w.run(0.02)
        bias = w.fake.publishers['/skid/imu/data/bias'].messages[-1]
        assert bias.angular_velocity.z == pytest.approx(0.01, abs=0.01)  # drift reset to 0: the offset is left
    finally:
        w.close()


def test_set_bias_services_and_the_reconfigure_servers(tmp_path):
    from geometry_msgs.msg import Vector3
    from hector_gazebo_plugins.srv import SetBias, SetBiasRequest
    w = spawn(tmp_path, '<rateGaussianNoise>0.1 0.2 0.3</rateGaussianNoise><yawOffset>0.25</yawOffset>')
    try:
        assert SetBias._type == 'hector_gazebo_plugins/SetBias'
        w.fake.services['/skid/imu/data/set_accel_bias'](SetBiasRequest(bias=Vector3(0.5, 0.0, 0.0)))
        w.fake.services['/skid/imu/data/set_rate_bias'](SetBiasRequest(bias=Vector3(0.0, 0.0, 0.05)))
        w.run(0.01)
        bias = w.fake.publishers['/skid/imu/data/bias'].messages[-1]
        assert (bias.linear_acceleration.x, bias.angular_velocity.z) == (pytest.approx(0.5, abs=1e-3),
                                                                          pytest.approx(0.05, abs=1e-3))
        assert sorted(w.servers) == ['/skid/imu/data/accel', '/skid/imu/data/rate', '/skid/imu/data/yaw']
        # first call: the configuration shows the model (a 3-axis model: the mean of its axes; the yaw its own)
        assert w.servers['/skid/imu/data/rate'].config['gaussian_noise'] == pytest.approx(0.2)
        assert w.servers['/skid/imu/data/yaw'].config['offset'] == pytest.approx(0.25)
        assert w.servers['/skid/imu/data/accel'].config['scale_error'] == 1.0
        # a change sets all three axes
        w.servers['/skid/imu/data/accel'].change(offset=1.0, gaussian_noise=0.0)
        w.run(0.01)
        m = w.fake.publishers['/skid/imu/data'].messages[-1]
        assert m.linear_acceleration.x == pytest.approx(1.5, abs=0.05)  # offset 1 + the bias set above
        assert m.linear_acceleration.y == pytest.approx(1.0, abs=0.05)
    finally:
        w.close()


def test_turning_shows_as_yaw_rate(tmp_path):
    w = spawn(tmp_path)
    try:
        cmd = Twist()
        cmd.angular.z = 1.0
        w.fake.subscribers['/skid/cmd_vel'](cmd)
        w.run(2.0)
        m = w.fake.publishers['/skid/imu/data'].messages[-1]
        assert m.angular_velocity.z > 0.2 and math.isfinite(m.angular_velocity.z)
    finally:
        w.close()
