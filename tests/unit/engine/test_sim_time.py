"""Stamps are whole nanoseconds of sim time, as Gazebo's common::Time: rospy.Time.from_sec truncates,
and the float of a time such as 2.134 s lies a hair below it."""
import rospy

from racebot_sim_bridge.engine.sim_time import ros_time


def test_every_millisecond_update_is_stamped_on_its_millisecond():
    steps = 200000  # 200 s of 1 ms updates, the time as Simulator counts it (t0 + steps x step)
    off = [k for k in range(steps) if ros_time(rospy.Time, k * 0.001).to_nsec() != k * 1000000]
    assert off == []


def test_whole_seconds_and_rounding_either_way():
    assert (ros_time(rospy.Time, 2.134).secs, ros_time(rospy.Time, 2.134).nsecs) == (2, 134000000)
    assert ros_time(rospy.Time, 0.9999999999).to_nsec() == 1000000000  # rounds up into the next second
    assert ros_time(rospy.Time, 5.0).to_nsec() == 5000000000
    assert ros_time(rospy.Time, 0.0) == rospy.Time(0)
    assert ros_time(rospy.Time, 1e6 + 0.001).to_nsec() == 1000000001000000  # ~12 days of sim time
