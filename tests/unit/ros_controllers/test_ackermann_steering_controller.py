"""ackermann_steering_controller/AckermannSteeringController: geometry from the URDF, cmd_vel's
angular.z as the steering angle (upstream's convention), the bicycle-model odometry, init errors."""
import math

import pytest
from geometry_msgs.msg import Twist, Vector3

from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.kinematics.controller_odometry import AckermannOdometry, ackermann_params_from_urdf

from controller_hw import make_hw
from fakes import FakeIO

TYPE = 'ackermann_steering_controller/AckermannSteeringController'
CAR = """<robot name="car">
  <link name="base_link"/>
  <link name="rear"><collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>
  <link name="steer_link"/>
  <joint name="rear_wheel_joint" type="continuous"><parent link="base_link"/><child link="rear"/>
    <origin xyz="-0.2 0 0.1" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="front_steer_joint" type="revolute"><parent link="base_link"/><child link="steer_link"/>
    <origin xyz="0.3 0 0.1"/><axis xyz="0 0 1"/><limit lower="-0.6" upper="0.6" effort="5" velocity="5"/></joint>
  <transmission name="t1"><joint name="rear_wheel_joint">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="front_steer_joint">
    <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint></transmission>
</robot>"""


def test_geometry_from_the_urdf():
    model = urdf_reader.parse_urdf(CAR)
    assert ackermann_params_from_urdf(model, 'rear_wheel_joint', 'front_steer_joint', True, True) == \
        pytest.approx((0.5, 0.1))
    with pytest.raises(ValueError, match="nope couldn't be retrieved"):
        ackermann_params_from_urdf(model, 'nope', 'front_steer_joint', True, True)


def test_bicycle_odometry_turns_at_v_tan_delta_over_l():
    odo = AckermannOdometry()
    odo.set_wheel_params(0.5, 0.1)
    odo.init(0.0)
    delta, v = 0.3, 0.4
    for k in range(1, 101):
        odo.update(v / 0.1 * k * 0.01, delta, k * 0.01)
    assert odo.angular == pytest.approx(v * math.tan(delta) / 0.5)
    assert odo.heading == pytest.approx(v * math.tan(delta) / 0.5 * 1.0)
    assert odo.linear == pytest.approx(v)


def controller(**params):
    hw = make_hw(CAR)
    io = FakeIO()
    c = CONTROLLER_TYPES[TYPE]('ackermann_steering_controller', '/car', dict({'type': TYPE}, **params), hw, io)
    return c, hw, io


def test_cmd_vel_speed_to_the_rear_wheel_and_angular_z_to_the_steering_angle():
    c, hw, io = controller()
    assert (c.separation_h, c.radius) == pytest.approx((0.5, 0.1))
    assert c.claimed_resources() == [('hardware_interface/PositionJointInterface', ['front_steer_joint']),
                                     ('hardware_interface/VelocityJointInterface', ['rear_wheel_joint'])]
    c.starting(0.0)
    io.subscribers['/car/ackermann_steering_controller/cmd_vel'].callback(
        Twist(linear=Vector3(0.5, 0, 0), angular=Vector3(0, 0, 0.25)))
    t = 0.0
    for _ in range(30):
        t += 0.01
        rear, steer = hw.handles['rear_wheel_joint'], hw.handles['front_steer_joint']
        rear.read(rear.position + rear.command * 0.01, rear.command)
        steer.read(steer.command, 0.0)
        c.update(t, 0.01)
    assert hw.handles['rear_wheel_joint'].command == pytest.approx(0.5 / 0.1)
    assert hw.handles['front_steer_joint'].command == pytest.approx(0.25)
    odom = io.publishers['/car/ackermann_steering_controller/odom'].messages[-1]
    assert odom.twist.twist.angular.z == pytest.approx(0.5 * math.tan(0.25) / 0.5, rel=0.02)


@pytest.mark.parametrize('params,words', [
    ({'rear_wheel': 'nope'}, "nope couldn't be retrieved from model description"),
    ({'wheel_separation_h': 0}, 'wheel_separation_h must be a number > 0'),
    ({'front_steer': 'rear_wheel_joint', 'wheel_separation_h': 1.0},
     "Could not find resource 'rear_wheel_joint' in 'hardware_interface::PositionJointInterface'"),
])
def test_bad_parameters_fail_init_with_the_reason(params, words):
    with pytest.raises(ControllerInitError) as err:
        controller(**params)
    assert words in str(err.value)
