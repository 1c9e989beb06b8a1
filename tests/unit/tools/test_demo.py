"""make demo's map numbers (tools/demo.py): gmapping's map placed in the world by the tf map -> odom (the odom frame
is the world frame), and judged against the world's walls with tools/corpus/slam_map.py. No ROS."""
import math

import numpy as np
import pytest

import demo

RES = 0.05


def test_world_from_map_undoes_map_to_odom():
    map_from_odom = (0.3, -0.2, 0.4)
    x, y, yaw = demo.world_from_map(map_from_odom)
    # a point of the odom frame (= the world) taken into the map frame and back lands where it was
    px, py = 1.0, 2.0
    c, s = math.cos(0.4), math.sin(0.4)
    mx, my = 0.3 + c * px - s * py, -0.2 + s * px + c * py
    assert (x + math.cos(yaw) * mx - math.sin(yaw) * my, y + math.sin(yaw) * mx + math.cos(yaw) * my) == \
        pytest.approx((px, py))
    assert demo.world_from_map((0.0, 0.0, 0.0)) == pytest.approx((0.0, 0.0, 0.0))


def grid(occupied_cells, size=40, origin=(-1.0, -1.0, 0.0)):
    """A size x size map of RES cells, free inside, occupied at the (column, row) cells given."""
    data = np.zeros((size, size), dtype=int)
    for col, row in occupied_cells:
        data[row, col] = 100
    data[0, :] = -1  # a row nobody saw
    return {'data': data.ravel().tolist(), 'width': size, 'height': size, 'resolution': RES, 'origin': origin}


def test_map_numbers_counts_the_occupied_cells_on_the_walls():
    # a wall along x = 0.5 m in the world; the map's column 30 is x = -1 + 30.5 * 0.05 = 0.525
    walls = np.array([(0.5, y) for y in np.linspace(-1, 1, 201)])
    on_wall = [(30, row) for row in range(5, 35)]
    off_wall = [(10, row) for row in range(5, 15)]  # x = -0.475: a wall where the world has none
    numbers = demo.map_numbers(grid(on_wall + off_wall), (0.0, 0.0, 0.0), walls)
    assert (numbers['width'], numbers['height'], numbers['resolution']) == (40, 40, RES)
    assert numbers['occupied'] == 40
    assert numbers['on_walls'] == pytest.approx(30 / 40)
    assert numbers['free_m2'] == pytest.approx((40 * 39 - 40) * RES * RES)


def test_map_numbers_places_the_map_in_the_world_first():
    walls = np.array([(0.5, y) for y in np.linspace(-1, 1, 201)])
    on_wall = [(30, row) for row in range(5, 35)]
    # the same map, its frame 0.6 m along x in the world: its wall is at x = 1.125, off the world's
    assert demo.map_numbers(grid(on_wall), (0.6, 0.0, 0.0), walls)['on_walls'] == 0.0
    # the tf says the odom frame sits 0.6 m behind the map frame's origin (x -0.6 in the map): the map frame is at
    # x 0.6 in the world, and a wall 0.6 m short of the world's in the map is on it
    shifted = grid([(col - 12, row) for col, row in on_wall])
    assert demo.world_from_map((-0.6, 0.0, 0.0)) == pytest.approx((0.6, 0.0, 0.0))
    assert demo.map_numbers(shifted, demo.world_from_map((-0.6, 0.0, 0.0)), walls)['on_walls'] == 1.0


def test_without_gmapping_the_demo_finds_none(tmp_path, monkeypatch):
    # a shell where rospack knows only racebot, and a make deps cache with no underlay in it
    monkeypatch.setenv('ROS_PACKAGE_PATH', str(demo.REPO))
    monkeypatch.setenv('RACEBOT_DEPS_CACHE', str(tmp_path))
    monkeypatch.setenv('ROS_HOME', str(tmp_path / 'ros_home'))
    assert demo.gmapping_env() == (None, None)
    assert 'make deps ARGS=gmapping' in demo.GMAPPING_HINT
