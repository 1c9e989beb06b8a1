"""Sim time (float seconds) as the ROS time every message, /clock included, is stamped with."""


def ros_time(time_class, t):
    """`time_class` (rospy.Time) of sim time `t`, to the nearest nanosecond. rospy.Time.from_sec
    truncates: the float nearest 2.134 is a hair below it, so from_sec gives 2 s 133999999 ns, and
    35 % of the 1 ms updates of a world came out 1 ns early. Gazebo's common::Time counts whole
    nanoseconds: its update at 2.134 s is stamped 2 s 134000000 ns, and so is ours."""
    ns = int(round(t * 1e9))
    return time_class(ns // 1000000000, ns % 1000000000)
