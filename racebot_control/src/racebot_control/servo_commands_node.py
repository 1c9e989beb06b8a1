"""The servo_commands node: Ackermann drive commands to the racebot's six joint controllers.

Subscribes
    /ackermann_cmd_mux/output (ackermann_msgs/AckermannDriveStamped): speed [m/s] of the rear
    axle middle and bicycle steering angle [rad].
Publishes (std_msgs/Float64), under ~namespace:
    left_rear_wheel_velocity_controller/command, right_rear_wheel_velocity_controller/command,
    left_front_wheel_velocity_controller/command, right_front_wheel_velocity_controller/command
    (wheel speeds, rad/s); left_steering_hinge_position_controller/command,
    right_steering_hinge_position_controller/command (hinge angles, rad).
Parameters (read once at start)
    ~wheel_radius (0.032 m: the tutorial's 31.25 = 1 / 0.032), ~wheelbase (0.26 m), ~track
    (0.18 m), ~wheel_hinge_offset (0.025 m, front wheel centre outboard of its hinge axis),
    ~max_steering_angle (0.6 rad, the hinge limit), ~steering_mode (parallel: the tutorial's
    mapping; ackermann: own angle and speed per wheel, see racebot_control.wheel_commands),
    ~command_timeout (s, 0 = off: when no command has arrived for that long, one command with
    speed 0 and the last steering angle is sent; ROS time, i.e. /clock under sim time),
    ~namespace (/racebot, the controllers' namespace).

Every command is forwarded, in order: one subscriber thread (queue of QUEUE_SIZE), synchronous
publishers, TCP_NODELAY.
Commands with a non-finite speed or angle are skipped with a throttled warning; a steering angle
beyond half a turn is clamped like any other, with a throttled warning. Speeds are not limited here:
the wheel controllers clamp commands beyond the joints' URDF velocity limit, with their own warning.
"""

import math
import threading
import warnings

import rospy
from ackermann_msgs.msg import AckermannDriveStamped
from std_msgs.msg import Float64

from racebot_control.wheel_commands import STEERING_MODES, CarGeometry, wheel_commands

COMMAND_TOPIC = '/ackermann_cmd_mux/output'
# In WheelCommands order.
CONTROLLERS = (
    'left_rear_wheel_velocity_controller',
    'right_rear_wheel_velocity_controller',
    'left_front_wheel_velocity_controller',
    'right_front_wheel_velocity_controller',
    'left_steering_hinge_position_controller',
    'right_steering_hinge_position_controller',
)
# Enough that a burst of commands (50 Hz teleop, navigation) is never dropped.
QUEUE_SIZE = 100
WARN_PERIOD_S = 5.0
# Beyond this |steering_angle| [rad] (half a turn) a command is warned about (still clamped to the
# hinge limit, as every angle beyond it is): such a number is a unit or a wiring mistake, while
# angles a little past the limit are everyday (transform passes yaw rates through).
ABSURD_STEERING_ANGLE = math.pi


class ServoCommands:
    """Forwards each AckermannDriveStamped as six Float64 joint commands (module docstring)."""

    def __init__(self):
        try:
            self.geometry = CarGeometry(
                wheel_radius=rospy.get_param('~wheel_radius', 0.032),
                wheelbase=rospy.get_param('~wheelbase', 0.26),
                track=rospy.get_param('~track', 0.18),
                max_steering_angle=rospy.get_param('~max_steering_angle', 0.6),
                wheel_hinge_offset=rospy.get_param('~wheel_hinge_offset', 0.025))
        except ValueError as err:
            raise ValueError('servo_commands: bad geometry parameter: %s' % err)
        self.mode = rospy.get_param('~steering_mode', 'parallel')
        if self.mode not in STEERING_MODES:
            raise ValueError('servo_commands: ~steering_mode must be one of %s, got %r'
                             % (', '.join(STEERING_MODES), self.mode))
        self.command_timeout = float(rospy.get_param('~command_timeout', 0.0))
        if not self.command_timeout >= 0.0:
            raise ValueError('servo_commands: ~command_timeout must be >= 0, got %r' % self.command_timeout)
        namespace = rospy.get_param('~namespace', '/racebot').rstrip('/')

        # The subscriber callback and the timeout timer both publish: one lock keeps each set of
        # six commands together and in order.
        self._lock = threading.Lock()
        self._last_command_time = None   # ROS time of the last command; None once stopped
        self._last_steering_angle = 0.0
        # Synchronous publishers (queue_size=None): each command is written to the controllers' sockets
        # in this callback, in order, with no hand-off to a writer thread (which cost milliseconds of
        # latency under load) and no queue that could overflow and drop a command.
        with warnings.catch_warnings():  # rospy warns that queue_size=None means synchronous: it is meant
            warnings.simplefilter('ignore', SyntaxWarning)
            self._publishers = [
                rospy.Publisher('%s/%s/command' % (namespace, name), Float64, queue_size=None, tcp_nodelay=True)
                for name in CONTROLLERS]
        self._timer = None
        if self.command_timeout > 0.0:
            period = min(0.05, self.command_timeout / 5.0)
            self._timer = rospy.Timer(rospy.Duration(period), self._check_timeout)
        self._subscriber = rospy.Subscriber(COMMAND_TOPIC, AckermannDriveStamped, self._on_command,
                                            queue_size=QUEUE_SIZE, tcp_nodelay=True)
        rospy.on_shutdown(self.shutdown)
        rospy.loginfo('servo_commands: %s steering, wheel radius %.4f m, wheelbase %.3f m, track %.3f m, '
                      'steering limit %.3f rad, command timeout %s', self.mode, self.geometry.wheel_radius,
                      self.geometry.wheelbase, self.geometry.track, self.geometry.max_steering_angle,
                      '%.3f s' % self.command_timeout if self.command_timeout else 'off')

    def _publish(self, speed, steering_angle):
        """Publishes the six commands; False if the command was not finite."""
        commands = wheel_commands(speed, steering_angle, self.mode, self.geometry)
        if commands is None:
            return False
        for publisher, value in zip(self._publishers, commands):
            publisher.publish(Float64(value))
        return True

    def _on_command(self, msg):
        with self._lock:
            if not self._publish(msg.drive.speed, msg.drive.steering_angle):
                rospy.logwarn_throttle(WARN_PERIOD_S, 'servo_commands: skipping a command that is not '
                                       'finite (speed %r, steering_angle %r)'
                                       % (msg.drive.speed, msg.drive.steering_angle))
                return
            if abs(msg.drive.steering_angle) > ABSURD_STEERING_ANGLE:
                rospy.logwarn_throttle(WARN_PERIOD_S, 'servo_commands: steering_angle %g rad is more than half a '
                                       'turn, not a steering angle; clamped to the hinge limit +-%g rad. Send an '
                                       'angle in radians within the limit.'
                                       % (msg.drive.steering_angle, self.geometry.max_steering_angle))
            self._last_steering_angle = msg.drive.steering_angle
            self._last_command_time = rospy.get_rostime()

    def _check_timeout(self, _event):
        with self._lock:
            if self._last_command_time is None:
                return
            now = rospy.get_rostime()
            if now < self._last_command_time:  # time went backwards (sim reset): start over
                self._last_command_time = now
                return
            if (now - self._last_command_time).to_sec() >= self.command_timeout:
                rospy.loginfo('servo_commands: no command for %.3f s, stopping the car', self.command_timeout)
                self._publish(0.0, self._last_steering_angle)
                self._last_command_time = None

    def shutdown(self):
        if self._timer is not None:
            self._timer.shutdown()


def main():
    rospy.init_node('servo_commands')
    try:
        ServoCommands()
    except ValueError as err:
        rospy.logfatal(str(err))
        raise SystemExit(1)
    rospy.spin()
