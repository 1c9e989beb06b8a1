"""racebot_control: the racebot's command path, Twist -> AckermannDrive -> six joint commands.

The pure logic (`wheel_commands`, `twist_to_ackermann`) imports no rospy and is unit-tested on its
own; `servo_commands_node` and `transform_node` wrap it in ROS nodes.
"""
