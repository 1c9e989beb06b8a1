"""The path a drive check's robot took, from its ground-truth poses sampled along the drive. No ROS here.

A turning drive's speed is its path's length over the time, not the chord from the first pose to the last: the
racecar turning at 0.26 rad/s for 5 s covers a chord 7 % shorter than its arc, which read as 7 % too slow.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

from corpus import angles


def travelled(poses: Sequence[tuple[float, float, float]]) -> tuple[float, float]:
    """(length of the path through the (x, y, yaw) poses, the yaw turned along it): segment by segment, each
    segment's yaw change wrapped to (-pi, pi], so a turn beyond half a circle is counted whole when the poses are
    close enough together."""
    length = turned = 0.0
    for (x0, y0, th0), (x1, y1, th1) in zip(poses, poses[1:]):
        length += math.hypot(x1 - x0, y1 - y0)
        turned += angles.wrap(th1 - th0)
    return length, turned
