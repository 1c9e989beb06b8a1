"""What interactive_marker_twist_server's marker_server computes, free of ROS: its settings from the private
parameters, the marker's controls, and the Twist for a dragged marker pose.

Upstream (1.2.2, marker_server.cpp): `linear_scale` either a map of axes ({x: 1, y: 1}: a move axis per key) or a
number (x only, with the max_*_linear_velocity numbers, defaults 1 and -1); an axis the max maps lack clamps to 0,
as std::map's operator[] gives. angular_scale and max_angular_velocity default to 2.2, marker_size_scale to 1.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

AXES = ('x', 'y', 'z')
# (control name, orientation (w, x, y, z)) of each move axis, as upstream's FIXED MOVE_AXIS controls
MOVE_CONTROLS = {'x': ('move_x', (1.0, 1.0, 0.0, 0.0)),
                 'y': ('move_y', (1.0, 0.0, 0.0, 1.0)),
                 'z': ('move_z', (1.0, 0.0, 1.0, 0.0))}
ROTATE_CONTROL = ('rotate_z', (1.0, 0.0, 1.0, 0.0))


@dataclass
class Settings:
    link_name: str = 'base_link'
    robot_name: str = 'robot'
    linear_scale: dict[str, float] = field(default_factory=lambda: {'x': 1.0})
    max_positive: dict[str, float] = field(default_factory=lambda: {'x': 1.0})
    max_negative: dict[str, float] = field(default_factory=lambda: {'x': -1.0})
    angular_scale: float = 2.2
    max_angular_velocity: float = 2.2
    marker_size_scale: float = 1.0

    @property
    def marker_name(self) -> str:
        return self.robot_name + '_twist_marker'

    @property
    def description(self) -> str:
        return 'twist controller for ' + self.robot_name


def _axis_map(value) -> dict[str, float]:
    return {str(k): float(v) for k, v in value.items()} if isinstance(value, dict) else {}


def settings_from_params(get) -> Settings:
    """`get(name, default)` reads a private parameter (rospy.get_param('~' + name, default))."""
    s = Settings(link_name=str(get('link_name', 'base_link')), robot_name=str(get('robot_name', 'robot')))
    scale = get('linear_scale', None)
    if isinstance(scale, dict):
        s.linear_scale = _axis_map(scale)
        s.max_positive = _axis_map(get('max_positive_linear_velocity', {}))
        s.max_negative = _axis_map(get('max_negative_linear_velocity', {}))
    else:
        s.linear_scale = {'x': float(1.0 if scale is None else scale)}
        s.max_positive = {'x': float(get('max_positive_linear_velocity', 1.0))}
        s.max_negative = {'x': float(get('max_negative_linear_velocity', -1.0))}
    s.angular_scale = float(get('angular_scale', 2.2))
    s.max_angular_velocity = float(get('max_angular_velocity', 2.2))
    s.marker_size_scale = float(get('marker_size_scale', 1.0))
    return s


def controls(s: Settings) -> list[tuple[str, tuple[float, float, float, float], bool]]:
    """(name, orientation (w, x, y, z), is a move axis) of the marker's controls, in upstream's order."""
    out = [MOVE_CONTROLS[a] + (True,) for a in AXES if a in s.linear_scale]
    return out + [ROTATE_CONTROL + (False,)]


def yaw(w: float, x: float, y: float, z: float) -> float:
    """tf::getYaw: the yaw of Matrix3x3(q).getRPY (0 at the pitch singularity, as tf)."""
    d = w * w + x * x + y * y + z * z
    if d == 0.0:
        return 0.0
    s = 2.0 / d
    m20 = x * z * s - w * y * s
    if abs(m20) >= 1.0:
        return 0.0
    return math.atan2(x * y * s + w * z * s, 1.0 - (y * y + z * z) * s)


def _clamp(v: float, low: float, high: float) -> float:
    return max(min(v, high), low)


def twist(s: Settings, position: tuple[float, float, float], orientation: tuple[float, float, float, float]):
    """((vx, vy, vz), wz) for the marker dragged to `position` (x, y, z) and turned to `orientation` (w, x, y, z)
    in link_name's frame: each axis scaled and clamped to [max_negative, max_positive], the yaw scaled and
    clamped to +-max_angular_velocity."""
    wz = _clamp(s.angular_scale * yaw(*orientation), -s.max_angular_velocity, s.max_angular_velocity)
    linear = []
    for i, a in enumerate(AXES):
        if a in s.linear_scale:
            linear.append(_clamp(s.linear_scale[a] * position[i], s.max_negative.get(a, 0.0),
                                 s.max_positive.get(a, 0.0)))
        else:
            linear.append(0.0)
    return tuple(linear), wz
