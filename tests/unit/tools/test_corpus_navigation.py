"""make corpus's `navigation` check, its pure part (tools/corpus/navigation.py): what a row must give, its goals in
the map, which goal tolerances hold, and the verdicts on localisation and on a reached goal. No ROS."""
import math

import numpy as np
import pytest

from corpus import manifest, navigation
from corpus.map_registration import Grid


def good_check(**changes):
    check = {'kind': 'navigation', 'world': '$(find w)/worlds/w.world', 'height': 0.18, 'cmd_topic': '/cmd_vel',
             'route': [[0.0, 0.4, 16.0], [0.1, 0.0, 3.0]], 'goals': [[-0.6, -1.8, 0.0], [-2.0, 0.0, 1.5708]],
             'goal_timeout': 120, 'localisation_tolerance': 0.1, 'xy_goal_tolerance': 0.05,
             'yaw_goal_tolerance': 0.17, 'initial_pose': 'publish', 'from': 'the package'}
    check.update(changes)
    return check


def test_a_good_check_has_no_problems_and_validates_in_a_row():
    assert navigation.input_problems(good_check()) == []
    row = {'name': 'nav', 'covers': ['navigation'], 'commands': ['roslaunch a b.launch'],
           'repos': [{'repo': 'o/n', 'branch': 'noetic', 'commit': 'e9d809ca8e3bf889c0275e4103b15a341ffab888',
                      'packages': ['a']}], 'checks': [good_check()]}
    assert manifest.validate([row]) == []
    row['checks'] = [dict(good_check(), goals='north')]
    assert any('goals must be a list' in e for e in manifest.validate([row]))


@pytest.mark.parametrize('change, words', [
    ({'goals': None}, 'goals must be a list'),
    ({'goals': []}, 'goals must be a list'),
    ({'goals': [[1.0, 2.0]]}, 'goals must be a list'),
    ({'goals': [[1.0, 2.0, 'east']]}, 'goals must be a list'),
    ({'route': [[0.0, 0.4]]}, 'route must be a list'),
    ({'route': [[0.0, 0.4, 0.0]]}, 'route must be a list'),
    ({'initial_pose': 'rviz'}, 'initial_pose must be one of publish, launch_default'),
    ({'localisation_tolerance': 0}, 'localisation_tolerance must be a positive number'),
    ({'goal_timeout': '2 min'}, 'goal_timeout must be a positive number'),
    ({'xy_goal_tolerance': True}, 'xy_goal_tolerance must be a positive number'),
])
def test_a_bad_field_is_refused_with_a_reason(change, words):
    problems = navigation.input_problems(good_check(**change))
    assert problems and any(words in p for p in problems), problems


def test_a_missing_field_is_named():
    check = good_check()
    del check['goals'], check['initial_pose']
    problems = navigation.input_problems(check)
    assert 'navigation check without goals' in problems and 'navigation check without initial_pose' in problems


def small_map():
    """A 10 x 10 map of 0.5 m cells from (-2, -2): free inside, a wall along column 9 (x 2.5 to 3), unknown row 0."""
    data = np.zeros((10, 10), dtype=np.int8)
    data[:, 9] = 100
    data[0, :] = -1
    return Grid(data.ravel(), 10, 10, 0.5, (-2.0, -2.0, 0.0))


def test_goals_must_be_in_free_cells_away_from_the_walls():
    grid = small_map()
    problems, clearances = navigation.goal_problems(grid, [(0.1, 0.1, 0.0)], 1.0)
    assert problems == [] and clearances[0] == pytest.approx(math.hypot(2.75 - 0.1, 0.25 - 0.1))
    problems, _ = navigation.goal_problems(grid, [(2.1, 0.25, 0.0)], 1.0)
    assert 'is 0.65 m from the nearest wall of the map (at least 1.00 asked)' in problems[0]
    for goal, words in (((2.8, 0.1, 0.0), 'on an occupied cell'), ((0.1, -1.8, 0.0), 'on an unknown cell'),
                        ((9.0, 0.0, 0.0), 'outside the map')):
        problems, _ = navigation.goal_problems(grid, [goal], 0.0)
        assert problems and words + ', not on a free cell' in problems[0], (goal, problems)


def test_a_turned_map_origin_is_followed():
    grid = small_map()._replace(origin=(0.0, 0.0, math.pi / 2))  # columns run along +y, rows along -x
    value, clearance = navigation.cell_at(grid, -0.75, 4.75)  # row 1, column 9: the wall
    assert value == 100 and clearance == pytest.approx(0.0)
    assert navigation.cell_at(grid, -0.25, 4.75) == (-1, pytest.approx(0.5))  # row 0: unknown, a row from the wall


def test_move_bases_own_tolerances_come_first_and_the_rows_are_the_fallback():
    check = good_check(xy_goal_tolerance=0.3, yaw_goal_tolerance=0.5)
    assert navigation.goal_tolerances(0.05, 0.17, check) == (0.05, 0.17, 'move_base parameters')
    xy, yaw, source = navigation.goal_tolerances(None, 0.17, check)
    assert (xy, yaw) == (0.3, 0.17) and 'xy_goal_tolerance missing from the parameter server' in source
    xy, yaw, source = navigation.goal_tolerances(None, None, check)
    assert (xy, yaw) == (0.3, 0.5) and 'xy_goal_tolerance and yaw_goal_tolerance missing' in source


def test_localisation_is_judged_in_xy_and_the_yaw_said():
    problems, numbers = navigation.judge_localisation((1.05, 2.0, 0.3), (1.0, 2.03, 0.0), 0.1)
    assert problems == [] and '0.058 m off (tolerance 0.10)' in numbers and 'yaw 17.2 deg off' in numbers
    problems, _ = navigation.judge_localisation((1.2, 2.0, 0.0), (1.0, 2.0, 0.0), 0.1)
    assert problems == ['amcl 0.200 m from the ground truth (tolerance 0.10)']


def test_the_ground_truth_nearest_in_time_to_amcls_stamp():
    history = [(0.0, 0.0, 0.0, 10.0), (0.1, 0.0, 0.0, 10.1), (0.2, 0.0, 0.0, 10.2)]
    assert navigation.nearest_in_time(history, 10.13) == history[1]


def test_a_reached_goal_within_move_bases_tolerances_and_the_robot_within_them_plus_amcls_error():
    goal = (1.0, 1.0, math.pi)
    problems, numbers = navigation.judge_goal(goal, (1.03, 1.02, -math.pi + 0.1), (1.1, 1.0, math.pi), 0.05, 0.17,
                                              0.1)
    assert problems == []  # yaw across +-pi: 0.1 rad; the robot 0.1 m off, within 0.05 + 0.1
    assert 'amcl 0.036 m (xy tolerance 0.050) and 0.100 rad (yaw tolerance 0.170)' in numbers
    assert 'ground truth 0.100 m (xy + localisation tolerance 0.150)' in numbers


@pytest.mark.parametrize('localised, truth, words', [
    ((1.06, 1.0, 0.0), (1.0, 1.0, 0.0), 'amcl says 0.060 m from the goal, xy tolerance 0.050'),
    ((1.0, 1.0, 0.2), (1.0, 1.0, 0.0), 'amcl says 0.200 rad from the goal yaw, yaw tolerance 0.170'),
    ((1.0, 1.0, 0.0), (1.0, 1.2, 0.0), 'the robot is 0.200 m from the goal, more than xy + localisation tolerance'),
])
def test_a_goal_missed_says_by_how_much(localised, truth, words):
    problems, _ = navigation.judge_goal((1.0, 1.0, 0.0), localised, truth, 0.05, 0.17, 0.1)
    assert len(problems) == 1 and words in problems[0], problems
