"""The library a `<plugin filename=...>` names: the one place a filename becomes a library name (pure text).

urdf_model asks it which plugin is gazebo_ros_control's; gazebo_plugins/registry.py finds each library's class by
it; the sensor configuration asks it which plugin a `<sensor>` names.
"""
from __future__ import annotations

import os


def library_key(filename: str | None) -> str:
    """The library a plugin's filename names: 'libgazebo_ros_diff_drive.so', '/opt/x/libgazebo_ros_diff_drive.so'
    and 'gazebo_ros_diff_drive' all give 'gazebo_ros_diff_drive' (as Gazebo, which adds lib and .so to a bare
    name)."""
    base = os.path.basename(filename or '')
    if base.endswith('.so'):
        base = base[:-3]
    if base.startswith('lib'):
        base = base[3:]
    return base
