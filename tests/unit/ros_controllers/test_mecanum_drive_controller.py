"""mecanum_drive_controller/MecanumDriveController (ridgeback_control's): its kinematics (wheel rates of a body
twist and back, k from the joints' origins) and the controller over a recorded I/O (cmd_vel x, y, yaw -> four
wheel rates with the Ridgeback's geometry, odometry with linear.y, timeout, limits, init errors)."""
import math

import pytest
from geometry_msgs.msg import Twist, Vector3

from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.ros_controllers.mecanum_drive_controller import body_twist, k_from_origins, wheel_velocities

from controller_hw import make_hw
from fakes import FakeIO

TYPE = 'mecanum_drive_controller/MecanumDriveController'
WHEEL = """<link name="%(n)s_link"><collision><geometry><cylinder radius="0.0759" length="0.08"/></geometry>
  </collision></link>
  <joint name="%(n)s" type="continuous"><parent link="base_link"/><child link="%(n)s_link"/>
    <origin xyz="%(x)g %(y)g 0.0759"/><axis xyz="0 1 0"/></joint>
  <transmission name="%(n)s_t"><joint name="%(n)s">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>"""
# the Ridgeback's wheels: 0.638 m apart along x, 0.551 m along y (ridgeback_control/config/control.yaml)
BOT = '<robot name="ridgeback"><link name="base_link"/>%s</robot>' % ''.join(
    WHEEL % {'n': n, 'x': x, 'y': y} for n, x, y in (
    ('front_left_wheel', 0.319, 0.2755), ('rear_left_wheel', -0.319, 0.2755),
    ('rear_right_wheel', -0.319, -0.2755), ('front_right_wheel', 0.319, -0.2755)))
PARAMS = {'type': TYPE, 'front_left_wheel_joint': 'front_left_wheel', 'back_left_wheel_joint': 'rear_left_wheel',
          'front_right_wheel_joint': 'front_right_wheel', 'back_right_wheel_joint': 'rear_right_wheel',
          'publish_rate': 50, 'cmd_vel_timeout': 0.25, 'enable_odom_tf': False,
          'wheel_separation_x': 0.638, 'wheel_separation_y': 0.551,
          'pose_covariance_diagonal': [0.001, 0.001, 1000000.0, 1000000.0, 1000000.0, 0.03]}


def controller(**changes):
    params = dict(PARAMS, **changes)
    params = {k: v for k, v in params.items() if v is not None}
    hw, io = make_hw(BOT), FakeIO()
    return CONTROLLER_TYPES[TYPE]('ridgeback_velocity_controller', '/', params, hw, io), hw, io


def drive(c, hw, io, x, y, wz, until, start=0.0, dt=0.01, send=True):
    """Updates every dt until `until`, the command sent again every 0.1 s (cmd_vel_timeout is 0.25 s)."""
    t, sent = start, -math.inf
    while t < until - 1e-9:
        if send and t - sent >= 0.1 - 1e-9:
            io.subscribers['/ridgeback_velocity_controller/cmd_vel'].callback(
                Twist(linear=Vector3(x, y, 0.0), angular=Vector3(0.0, 0.0, wz)))
            sent = t
        t += dt
        for h in hw.handles.values():  # the wheels follow their velocity command exactly
            h.read(h.position + h.command * dt, h.command)
        c.update(t, dt)
    return t


def test_wheel_rates_and_body_twist_invert_each_other():
    k, r = 0.5945, 0.0759
    w = wheel_velocities(0.3, -0.2, 0.4, k, r)
    assert w == pytest.approx(((0.3 + 0.2 - k * 0.4) / r, (0.3 - 0.2 - k * 0.4) / r, (0.3 + 0.2 + k * 0.4) / r,
                               (0.3 - 0.2 + k * 0.4) / r))
    assert body_twist(w, k, r) == pytest.approx((0.3, -0.2, 0.4))


def test_k_from_the_joints_origins_is_half_the_two_separations():
    assert k_from_origins([(0.319, 0.2755), (-0.319, 0.2755), (-0.319, -0.2755), (0.319, -0.2755)]) == \
        pytest.approx((0.638 + 0.551) / 2)


def test_sideways_command_and_odometry():
    c, hw, io = controller()
    assert (c.k, c.radius) == pytest.approx((0.5945, 0.0759))  # radius from the wheel's collision cylinder
    assert c.claimed_resources() == [('hardware_interface/VelocityJointInterface', sorted(
        ['front_left_wheel', 'rear_left_wheel', 'rear_right_wheel', 'front_right_wheel']))]
    c.starting(0.0)
    drive(c, hw, io, 0.0, 0.55, 0.0, 2.0)
    rates = [hw.handles[n].command for n in ('front_left_wheel', 'rear_left_wheel', 'rear_right_wheel',
                                             'front_right_wheel')]
    assert rates == pytest.approx([-0.55 / 0.0759, 0.55 / 0.0759, -0.55 / 0.0759, 0.55 / 0.0759])
    odom = io.publishers['/ridgeback_velocity_controller/odom'].messages
    last = odom[-1]
    assert last.twist.twist.linear.y == pytest.approx(0.55) and abs(last.twist.twist.linear.x) < 1e-9
    assert last.pose.pose.position.y == pytest.approx(0.55 * 1.99, abs=0.02)
    assert last.pose.covariance[0] == 0.001 and last.pose.covariance[35] == 0.03
    assert '/tf' not in io.publishers  # enable_odom_tf false


def test_turning_integrates_in_the_new_heading():
    c, hw, io = controller()
    c.starting(0.0)
    drive(c, hw, io, 0.2, 0.0, 0.5, 2.0, dt=0.001)
    last = io.publishers['/ridgeback_velocity_controller/odom'].messages[-1]
    heading = 2.0 * math.atan2(last.pose.pose.orientation.z, last.pose.pose.orientation.w)
    assert heading == pytest.approx(0.5 * 1.98, abs=0.02)
    r = 0.2 / 0.5  # a circle of radius 0.4 m
    assert (last.pose.pose.position.x, last.pose.pose.position.y) == pytest.approx(
        (r * math.sin(heading), r * (1 - math.cos(heading))), abs=0.005)


def test_timeout_and_acceleration_limit():
    c, hw, io = controller(linear={'y': {'has_acceleration_limits': True, 'max_acceleration': 2.5}})
    c.starting(0.0)
    t = drive(c, hw, io, 0.0, 1.0, 0.0, 0.1)
    assert hw.handles['rear_left_wheel'].command == pytest.approx(0.25 / 0.0759)  # 2.5 m/s^2 for 0.1 s
    drive(c, hw, io, 0.0, 0.0, 0.0, 1.0, start=t, send=False)  # nothing new for longer than cmd_vel_timeout
    assert hw.handles['rear_left_wheel'].command == pytest.approx(0.0)


def test_init_errors_name_the_parameter():
    with pytest.raises(ControllerInitError, match='Only one wheel separation'):
        controller(wheel_separation_y=None)
    with pytest.raises(ControllerInitError, match='front_left_wheel_joint'):
        controller(front_left_wheel_joint='no_such_wheel')
    c, _, _ = controller(wheel_separation_x=None, wheel_separation_y=None)  # k from the URDF
    assert c.k == pytest.approx(0.5945)
