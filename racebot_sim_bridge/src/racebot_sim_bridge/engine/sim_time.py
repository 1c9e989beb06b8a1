"""Sim time (float seconds) on Gazebo's clock: common::Time counts whole nanoseconds, so sim times are
compared (`to_ns`) and stamped (`ros_time`, every message and /clock) as integer nanoseconds."""
from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

NS = 1000000000

_Time = TypeVar('_Time')  # a time class such as rospy.Time


def to_ns(seconds: float) -> int:
    return int(round(seconds * NS))


def ros_time(time_class: Callable[[int, int], _Time], t: float) -> _Time:
    """`time_class` (rospy.Time) of sim time `t`, to the nearest nanosecond. rospy.Time.from_sec
    truncates: the float nearest 2.134 is a hair below it, so from_sec gives 2 s 133999999 ns, and
    35 % of the 1 ms updates of a world came out 1 ns early. Gazebo's common::Time counts whole
    nanoseconds: its update at 2.134 s is stamped 2 s 134000000 ns, and so is ours."""
    ns = to_ns(t)
    return time_class(ns // NS, ns % NS)
