"""diff_drive_controller/DiffDriveController: its kinematics (odometry, speed limiter, wheel geometry
from the URDF) and the controller over a recorded I/O (cmd_vel -> wheel velocities, timeout, NaN,
odom and TF at publish_rate, init errors)."""
import math

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
from racebot_sim_bridge.kinematics.controller_odometry import Odometry, SpeedLimiter, wheel_params_from_urdf

from controller_hw import make_hw
from fakes import FakeIO

TYPE = 'diff_drive_controller/DiffDriveController'
BOT = """<robot name="bot">
  <link name="base_link"/>
  <link name="left"><collision><geometry>%(wheel)s</geometry></collision></link>
  <link name="right"><collision><geometry>%(wheel)s</geometry></collision></link>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left"/>
    <origin xyz="0.1 0.2 0.05" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right"/>
    <origin xyz="0.1 -0.2 0.05" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <transmission name="t1"><joint name="left_wheel_joint">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>
  <transmission name="t2"><joint name="right_wheel_joint">
    <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint></transmission>
</robot>"""
CYLINDER = '<cylinder radius="0.05" length="0.02"/>'


# -- kinematics -------------------------------------------------------------------------------------
def test_odometry_of_a_circle_is_exact():
    odo = Odometry()
    odo.set_wheel_params(0.4, 0.05, 0.05)
    odo.init(0.0)
    # v = 0.3 m/s, w = 0.5 rad/s for 2 s in 0.01 s steps: wheels turn (v -+ w*s/2)/r rad/s
    wl, wr = (0.3 - 0.5 * 0.2) / 0.05, (0.3 + 0.5 * 0.2) / 0.05
    for k in range(1, 201):
        assert odo.update(wl * k * 0.01, wr * k * 0.01, k * 0.01)
    r = 0.3 / 0.5
    assert odo.heading == pytest.approx(1.0)
    assert (odo.x, odo.y) == pytest.approx((r * math.sin(1.0), r * (1 - math.cos(1.0))))
    assert (odo.linear, odo.angular) == pytest.approx((0.3, 0.5))


def test_odometry_velocity_is_the_rolling_mean_and_a_tiny_interval_is_skipped():
    odo = Odometry(window=2)
    odo.set_wheel_params(0.4, 1.0, 1.0)
    odo.init(0.0)
    odo.update(1.0, 1.0, 1.0)  # 1 m/s
    odo.update(4.0, 4.0, 2.0)  # 3 m/s
    odo.update(9.0, 9.0, 3.0)  # 5 m/s: the window keeps 3 and 5
    assert odo.linear == pytest.approx(4.0)
    assert not odo.update(10.0, 10.0, 3.00001)
    assert odo.x == pytest.approx(10.0) and odo.linear == pytest.approx(4.0)


def test_speed_limiter_velocity_acceleration_and_jerk():
    assert SpeedLimiter().limit(9.0, 0.0, 0.0, 0.1) == 9.0
    lim = SpeedLimiter(True, True, False, -1.0, 2.0, -0.5, 1.0)
    assert lim.limit(9.0, 0.0, 0.0, 0.1) == pytest.approx(0.1)   # acceleration 1 m/s^2 over 0.1 s
    assert lim.limit(9.0, 1.95, 1.9, 0.1) == pytest.approx(2.0)  # then the velocity limit
    assert lim.limit(-9.0, 0.0, 0.0, 0.1) == pytest.approx(-0.05)
    jerk = SpeedLimiter(False, False, True, max_jerk=10.0, min_jerk=-10.0)
    assert jerk.limit(5.0, 0.0, 0.0, 0.1) == pytest.approx(0.2)  # da <= jerk * 2 dt^2


@pytest.mark.parametrize('wheel,radius', [(CYLINDER, 0.05), ('<sphere radius="0.07"/>', 0.07)])
def test_wheel_geometry_from_the_urdf(wheel, radius):
    model = urdf_reader.parse_urdf(BOT % {'wheel': wheel})
    assert wheel_params_from_urdf(model, 'left_wheel_joint', 'right_wheel_joint', True, True) == \
        pytest.approx((0.4, radius))
    assert wheel_params_from_urdf(model, 'left_wheel_joint', 'right_wheel_joint', False, False) == (None, None)


def test_wheel_geometry_errors_say_what_to_set():
    model = urdf_reader.parse_urdf(BOT % {'wheel': '<box size="0.1 0.1 0.1"/>'})
    with pytest.raises(ValueError, match='NOT modeled as a cylinder or sphere.*set wheel_radius'):
        wheel_params_from_urdf(model, 'left_wheel_joint', 'right_wheel_joint', False, True)
    with pytest.raises(ValueError, match="nope couldn't be retrieved from model description"):
        wheel_params_from_urdf(model, 'nope', 'right_wheel_joint', True, False)


# -- the controller -----------------------------------------------------------------------------------
def controller(**params):
    hw = make_hw(BOT % {'wheel': CYLINDER})
    io = FakeIO()
    base = {'type': TYPE, 'left_wheel': 'left_wheel_joint', 'right_wheel': 'right_wheel_joint',
            'pose_covariance_diagonal': [0.001, 0.001, 1e6, 1e6, 1e6, 0.03]}
    base.update(params)
    c = CONTROLLER_TYPES[TYPE]('diff_drive_controller', '/bot', base, hw, io)
    return c, hw, io


def drive(c, hw, io, lin, ang, until, start=0.0, dt=0.01, send=True):
    t = start
    if send:
        io.subscribers['/bot/diff_drive_controller/cmd_vel'].callback(Twist(linear=_v(lin), angular=_v(0, ang)))
    while t < until - 1e-9:
        t += dt
        for h in hw.handles.values():  # the wheels follow their velocity command exactly
            h.read(h.position + h.command * dt, h.command)
        c.update(t, dt)
    return t


def _v(x=0.0, z=0.0):
    from geometry_msgs.msg import Vector3
    return Vector3(x, 0.0, z)


def test_cmd_vel_gives_wheel_velocities_from_the_urdf_geometry_and_odometry_follows():
    c, hw, io = controller()
    assert (c.separation, c.radius) == pytest.approx((0.4, 0.05))
    assert c.claimed_resources() == [('hardware_interface/VelocityJointInterface',
                                      ['left_wheel_joint', 'right_wheel_joint'])]
    c.starting(0.0)
    drive(c, hw, io, 0.3, 0.5, 0.4)
    assert hw.handles['left_wheel_joint'].command == pytest.approx((0.3 - 0.5 * 0.2) / 0.05)
    assert hw.handles['right_wheel_joint'].command == pytest.approx((0.3 + 0.5 * 0.2) / 0.05)
    odom = io.publishers['/bot/diff_drive_controller/odom'].messages
    assert 15 <= len(odom) <= 21  # 50 Hz over 0.4 s
    last = odom[-1]
    assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_link')
    assert last.twist.twist.linear.x == pytest.approx(0.3, rel=0.02)
    assert last.twist.twist.angular.z == pytest.approx(0.5, rel=0.02)
    assert last.pose.covariance[0] == 0.001 and last.pose.covariance[35] == 0.03
    tf = io.publishers['/tf'].messages[-1].transforms[0]
    assert (tf.header.frame_id, tf.child_frame_id) == ('odom', 'base_link')
    assert tf.transform.translation.x == pytest.approx(last.pose.pose.position.x)


def test_a_stale_command_times_out_and_nan_is_ignored():
    c, hw, io = controller(cmd_vel_timeout=0.25)
    c.starting(0.0)
    t = drive(c, hw, io, 0.2, 0.0, 0.2)
    assert hw.handles['left_wheel_joint'].command == pytest.approx(4.0)
    io.subscribers['/bot/diff_drive_controller/cmd_vel'].callback(Twist(linear=_v(float('nan'))))
    assert any('NaN' in w for w in io.warnings)
    drive(c, hw, io, 0, 0, 0.5, start=t, send=False)
    assert hw.handles['left_wheel_joint'].command == 0.0


def test_commands_before_start_are_refused_and_limits_apply():
    c, hw, io = controller(linear={'x': {'has_acceleration_limits': True, 'max_acceleration': 1.0}})
    io.subscribers['/bot/diff_drive_controller/cmd_vel'].callback(Twist(linear=_v(1.0)))
    assert "Can't accept new commands. Controller is not running." in io.warnings[-1]
    c.starting(0.0)
    drive(c, hw, io, 1.0, 0.0, 0.1)
    assert hw.handles['left_wheel_joint'].command == pytest.approx(0.1 / 0.05)  # 1 m/s^2 for 0.1 s


@pytest.mark.parametrize('params,words', [
    ({'left_wheel': None}, "Couldn't retrieve wheel param 'left_wheel'"),
    ({'left_wheel': []}, "Wheel param 'left_wheel' is an empty list"),
    ({'left_wheel': ['left_wheel_joint', 'x']}, '#left wheels (2) != #right wheels (1)'),
    ({'left_wheel': 3}, 'neither a list of strings nor a string'),
    ({'wheel_separation': -0.4}, 'wheel_separation must be a number > 0'),
    ({'publish_rate': 0}, 'publish_rate must be a positive number'),
    ({'pose_covariance_diagonal': [1, 2]}, 'must be a list of 6 numbers'),
    ({'left_wheel': 'nope'}, "nope couldn't be retrieved from model description"),
])
def test_bad_parameters_fail_init_with_the_reason(params, words):
    with pytest.raises(ControllerInitError) as err:
        controller(**params)
    assert words in str(err.value)


def test_given_geometry_and_multipliers_win_over_the_urdf():
    c, hw, io = controller(wheel_separation=0.5, wheel_radius=0.1, wheel_radius_multiplier=2.0)
    c.starting(0.0)
    drive(c, hw, io, 0.4, 0.0, 0.05)
    assert hw.handles['left_wheel_joint'].command == pytest.approx(0.4 / 0.2)
