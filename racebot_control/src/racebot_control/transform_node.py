"""The transform node: navigation's Twist to the car's AckermannDriveStamped (chapter 6, part 4).

Subscribes
    cmd_vel (geometry_msgs/Twist, relative name as in the tutorial): linear.x [m/s], angular.z.
Publishes
    /ackermann_cmd_mux/output (ackermann_msgs/AckermannDriveStamped): stamped now, frame_id
    base_link, speed = linear.x, acceleration = jerk = steering_angle_velocity = 1, and the steering
    angle per ~convert_yaw_rate.
Parameters (read once at start)
    ~convert_yaw_rate (false: steering_angle = angular.z, the tutorial's pass-through; true:
    steering_angle = atan(wheelbase * angular.z / linear.x) clamped to the hinge limit, and at
    linear.x = 0 the previous angle; see racebot_control.twist_to_ackermann), ~wheelbase (0.26 m),
    ~max_steering_angle (0.6 rad).

Twists with a non-finite linear.x or angular.z are skipped with a throttled warning.
"""

import rospy
from ackermann_msgs.msg import AckermannDriveStamped
from geometry_msgs.msg import Twist

from racebot_control.twist_to_ackermann import FRAME_ID, TwistToAckermann

INPUT_TOPIC = 'cmd_vel'
OUTPUT_TOPIC = '/ackermann_cmd_mux/output'
QUEUE_SIZE = 100
WARN_PERIOD_S = 5.0


class Transform:
    """Converts every Twist on cmd_vel into one AckermannDriveStamped (module docstring)."""

    def __init__(self):
        self.converter = TwistToAckermann(
            convert_yaw_rate=rospy.get_param('~convert_yaw_rate', False),
            wheelbase=rospy.get_param('~wheelbase', 0.26),
            max_steering_angle=rospy.get_param('~max_steering_angle', 0.6))
        self._publisher = rospy.Publisher(OUTPUT_TOPIC, AckermannDriveStamped, queue_size=QUEUE_SIZE,
                                          tcp_nodelay=True)
        self._subscriber = rospy.Subscriber(INPUT_TOPIC, Twist, self._on_twist, queue_size=QUEUE_SIZE,
                                            tcp_nodelay=True)
        rospy.loginfo('transform: %s -> %s, %s', rospy.resolve_name(INPUT_TOPIC), OUTPUT_TOPIC,
                      'yaw rate converted to a steering angle (wheelbase %.3f m, limit %.3f rad)'
                      % (self.converter.wheelbase, self.converter.max_steering_angle)
                      if self.converter.convert_yaw_rate else 'angular.z passed through as the steering angle')

    def _on_twist(self, twist):
        command = self.converter.convert(twist.linear.x, twist.angular.z)
        if command is None:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'transform: skipping a Twist that is not finite '
                                   '(linear.x %r, angular.z %r)' % (twist.linear.x, twist.angular.z))
            return
        msg = AckermannDriveStamped()
        msg.header.stamp = rospy.Time.now()
        msg.header.frame_id = FRAME_ID
        msg.drive.speed = command.speed
        msg.drive.steering_angle = command.steering_angle
        msg.drive.steering_angle_velocity = command.steering_angle_velocity
        msg.drive.acceleration = command.acceleration
        msg.drive.jerk = command.jerk
        self._publisher.publish(msg)


def main():
    rospy.init_node('transform')
    try:
        Transform()
    except ValueError as err:
        rospy.logfatal('transform: bad parameter: %s' % err)
        raise SystemExit(1)
    rospy.spin()
