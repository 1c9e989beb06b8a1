#!/usr/bin/env python3
"""diff_drive_controller/DiffDriveController on a robot package of our own (tests/fixtures/robots/diffbot_control),
as odometry_drive_test.OdometryDriveTest drives it. The YAML gives no wheel_separation or wheel_radius: the
controller reads them from the URDF (0.34 m, 0.075 m). 0.3 m/s and 0.5 rad/s asked, 0.3 m/s and 0.5 rad/s
expected."""
import rostest

from odometry_drive_test import OdometryDriveTest


class DiffDriveControllerTest(OdometryDriveTest):
    PACKAGE, LAUNCH = 'diffbot_control', 'diffbot_world.launch'
    NS, MODEL, CONTROLLER = 'diffbot', 'diffbot', 'mobile_base_controller'
    COMMAND = (0.3, 0.5)  # m/s, rad/s
    YAW_RATE = COMMAND[1]


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'diff_drive_controller', DiffDriveControllerTest)
