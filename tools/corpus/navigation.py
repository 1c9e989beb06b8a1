"""The corpus's `navigation` check, its pure part (no ROS): what a row must give, where its goals lie in the map,
which goal tolerances hold, and the verdicts on localisation and on a reached goal. checks.check_navigation does the
ROS side (amcl, map_server, move_base's action, the ground truth) and hands the numbers here.

Poses are (x, y, yaw) in the map frame unless said.
"""
from __future__ import annotations

import math

import numpy as np

from corpus import angles

# what a navigation check needs in its row (manifest.py and the check itself refuse a row without one)
KEYS = ('world', 'height', 'cmd_topic', 'route', 'goals', 'goal_timeout', 'localisation_tolerance',
        'xy_goal_tolerance', 'yaw_goal_tolerance', 'initial_pose')
POSITIVE = ('height', 'goal_timeout', 'localisation_tolerance', 'xy_goal_tolerance', 'yaw_goal_tolerance')
INITIAL_POSE = ('publish', 'launch_default')
# rviz's 2D Pose Estimate (rviz/default_plugin/tools/initial_pose_tool.cpp): x and y 0.5 m, yaw pi/12 rad (std dev)
RVIZ_COVARIANCE = {0: 0.25, 7: 0.25, 35: 0.06853891945200942}


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def input_problems(check: dict) -> list:
    """Every problem of a navigation check's fields, one line each (empty: it can run)."""
    problems = ['navigation check without %s' % key for key in KEYS if key not in check]
    for key in POSITIVE:
        if key in check and not (_number(check[key]) and check[key] > 0):
            problems.append('navigation check: %s must be a positive number (got %r)' % (key, check[key]))
    goals = check.get('goals')
    if 'goals' in check and (not isinstance(goals, list) or not goals or not all(
            isinstance(g, list) and len(g) == 3 and all(_number(v) for v in g) for g in goals)):
        problems.append('navigation check: goals must be a list of [x, y, yaw] map-frame poses (got %r)' % (goals,))
    route = check.get('route')
    if 'route' in check and (not isinstance(route, list) or not all(
            isinstance(s, list) and len(s) == 3 and all(_number(v) for v in s) and s[2] > 0 for s in route)):
        problems.append('navigation check: route must be a list of [vx, wz, sim seconds] (got %r)' % (route,))
    if 'initial_pose' in check and check['initial_pose'] not in INITIAL_POSE:
        problems.append('navigation check: initial_pose must be one of %s (got %r)' % (
            ', '.join(INITIAL_POSE), check['initial_pose']))
    return problems


def cell_at(grid, x: float, y: float) -> tuple:
    """(value of the grid's cell under map-frame (x, y), None outside the grid; distance from (x, y) to the nearest
    occupied cell's centre, inf when there is none). `grid`: map_registration.Grid or anything with its fields."""
    ox, oy, oyaw = grid.origin
    c, s = math.cos(oyaw), math.sin(oyaw)
    lx, ly = c * (x - ox) + s * (y - oy), -s * (x - ox) + c * (y - oy)
    col, row = int(math.floor(lx / grid.resolution)), int(math.floor(ly / grid.resolution))
    data = np.asarray(grid.data).reshape(grid.height, grid.width)
    value = int(data[row, col]) if 0 <= row < grid.height and 0 <= col < grid.width else None
    rows, cols = np.nonzero(data >= 65)
    if not len(rows):
        return value, math.inf
    cx, cy = (cols + 0.5) * grid.resolution, (rows + 0.5) * grid.resolution
    return value, float(np.sqrt((cx - lx) ** 2 + (cy - ly) ** 2).min())


def goal_problems(grid, goals: list, min_clearance: float) -> tuple:
    """([problem], [clearance]) of the goals in the map: each in a free cell (0) and at least min_clearance m from
    the nearest occupied cell."""
    problems, clearances = [], []
    for x, y, _ in goals:
        value, clearance = cell_at(grid, x, y)
        clearances.append(clearance)
        if value != 0:
            problems.append('goal (%.2f, %.2f) is %s, not on a free cell of the map' % (
                x, y, 'outside the map' if value is None else 'on an unknown cell' if value < 0 else
                'on an occupied cell'))
        elif clearance < min_clearance:
            problems.append('goal (%.2f, %.2f) is %.2f m from the nearest wall of the map (at least %.2f asked)' % (
                x, y, clearance, min_clearance))
    return problems, clearances


def goal_tolerances(xy_param, yaw_param, check: dict) -> tuple:
    """(xy m, yaw rad, where they come from): move_base's own (DWAPlannerROS's xy_goal_tolerance and
    yaw_goal_tolerance on the parameter server, None when absent), else the row's, and the source says which."""
    xy = float(xy_param) if _number(xy_param) and xy_param > 0 else None
    yaw = float(yaw_param) if _number(yaw_param) and yaw_param > 0 else None
    if xy is not None and yaw is not None:
        return xy, yaw, 'move_base parameters'
    source = 'the row (%s missing from the parameter server)' % ' and '.join(
        name for name, v in (('xy_goal_tolerance', xy), ('yaw_goal_tolerance', yaw)) if v is None)
    return (xy if xy is not None else float(check['xy_goal_tolerance']),
            yaw if yaw is not None else float(check['yaw_goal_tolerance']), source)


def nearest_in_time(history: list, stamp: float) -> tuple:
    """The (x, y, yaw, stamp) of `history` closest in time to `stamp`."""
    return min(history, key=lambda sample: abs(sample[3] - stamp))


def judge_localisation(amcl: tuple, truth: tuple, tolerance: float) -> tuple:
    """([problem], numbers): amcl's pose against the ground truth (both in the map frame), within `tolerance` m in
    x-y; the yaw is said, not judged."""
    off = math.hypot(amcl[0] - truth[0], amcl[1] - truth[1])
    turn = math.degrees(abs(angles.wrap(amcl[2] - truth[2])))
    numbers = 'amcl at (%.3f, %.3f), ground truth (%.3f, %.3f): %.3f m off (tolerance %.2f), yaw %.1f deg off' % (
        amcl[0], amcl[1], truth[0], truth[1], off, tolerance, turn)
    return (['amcl %.3f m from the ground truth (tolerance %.2f)' % (off, tolerance)] if off > tolerance else []), \
        numbers


def judge_goal(goal: tuple, localised: tuple, truth: tuple, xy_tolerance: float, yaw_tolerance: float,
               localisation_tolerance: float) -> tuple:
    """([problem], numbers) of one reached goal. move_base stops where amcl's pose (`localised`) is within its xy
    and yaw goal tolerances of the goal: that is judged with them. The robot itself (`truth`, the ground truth in
    the map frame) is where amcl is, give or take amcl's own error: within xy tolerance + localisation tolerance."""
    off = math.hypot(localised[0] - goal[0], localised[1] - goal[1])
    turn = abs(angles.wrap(localised[2] - goal[2]))
    true_off = math.hypot(truth[0] - goal[0], truth[1] - goal[1])
    allowed = xy_tolerance + localisation_tolerance
    numbers = ('amcl %.3f m (xy tolerance %.3f) and %.3f rad (yaw tolerance %.3f) from the goal; ground truth %.3f m '
               '(xy + localisation tolerance %.3f)' % (off, xy_tolerance, turn, yaw_tolerance, true_off, allowed))
    problems = []
    if off > xy_tolerance:
        problems.append('amcl says %.3f m from the goal, xy tolerance %.3f' % (off, xy_tolerance))
    if turn > yaw_tolerance:
        problems.append('amcl says %.3f rad from the goal yaw, yaw tolerance %.3f' % (turn, yaw_tolerance))
    if true_off > allowed:
        problems.append('the robot is %.3f m from the goal, more than xy + localisation tolerance %.3f' % (
            true_off, allowed))
    return problems, numbers
