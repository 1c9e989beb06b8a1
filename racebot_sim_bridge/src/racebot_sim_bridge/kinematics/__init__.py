"""The kinematics of drives and controllers as plain functions: no rospy, no PyBullet, unit-tested
(tests/unit/test_kinematics_*.py). The plugins and controllers wrap them with their ROS plumbing."""
