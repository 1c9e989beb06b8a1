#!/usr/bin/env python3
"""ackermann_steering_controller/AckermannSteeringController on a robot package of our own
(tests/fixtures/robots/steer_bot), as odometry_drive_test.OdometryDriveTest drives it. The YAML gives no
wheel_separation_h or wheel_radius: the controller reads them from the URDF (0.4 m, 0.05 m). As upstream
reads cmd_vel, angular.z is the steering angle: 0.3 m/s at 0.3 rad must turn at the bicycle model's
v * tan(steer) / L = 0.232 rad/s. base_footprint is under the rear axle, the point the odometry tracks."""
import math

import rostest

from odometry_drive_test import OdometryDriveTest

WHEELBASE = 0.4  # m, urdf/steer_bot.urdf.xacro


class AckermannSteeringControllerTest(OdometryDriveTest):
    PACKAGE, LAUNCH = 'steer_bot', 'steer_bot_world.launch'
    NS, MODEL, CONTROLLER = 'steer_bot', 'steer_bot', 'ackermann_steering_controller'
    COMMAND = (0.3, 0.3)  # m/s, rad of steering
    YAW_RATE = COMMAND[0] * math.tan(COMMAND[1]) / WHEELBASE


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'ackermann_steering_controller', AckermannSteeringControllerTest)
