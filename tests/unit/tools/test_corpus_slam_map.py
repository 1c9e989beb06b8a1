"""make corpus's `map` check (tools/corpus/slam_map.py): a SLAM map's occupied cells against the walls of the world
it was made in, at the laser's height, and its free area against the area the walls enclose. A world written here:
a 4 m square room of box walls with a round pillar; maps drawn here, right and wrong. No ROS."""
import math

import numpy as np
import pytest

from corpus import slam_map
from corpus.floor import pose_matrix

RES = 0.05


class World:
    """What slam_map reads of floor.WorldCollisions: its shapes (name, kind, world-from-shape, data)."""

    def __init__(self):
        wall = 'wall'
        self.shapes = [('ground', 'plane', np.eye(4), (0.0, 0.0, 1.0)),
                       (wall, 'box', pose_matrix('2 0 0.25 0 0 0'), np.array([0.1, 4.1, 0.5])),
                       (wall, 'box', pose_matrix('-2 0 0.25 0 0 0'), np.array([0.1, 4.1, 0.5])),
                       (wall, 'box', pose_matrix('0 2 0.25 0 0 0'), np.array([4.1, 0.1, 0.5])),
                       (wall, 'box', pose_matrix('0 -2 0.25 0 0 0'), np.array([4.1, 0.1, 0.5])),
                       ('pillar', 'cylinder', pose_matrix('1 1 0.25 0 0 0'), (0.15, 0.5))]


def grid_of(points, size=100, origin=(-2.5, -2.5)):
    """An occupancy grid (row-major values) of size x size cells of RES m, occupied (100) where `points` fall, free
    (0) inside the room, unknown (-1) elsewhere."""
    data = np.full((size, size), -1, dtype=np.int16)
    xs = origin[0] + (np.arange(size) + 0.5) * RES
    inside = (np.abs(xs)[None, :] < 1.9) & (np.abs(xs)[:, None] < 1.9)
    data[inside] = 0
    for x, y in points:
        data[int((y - origin[1]) / RES), int((x - origin[0]) / RES)] = 100
    return data.ravel().tolist()


def wall_points():
    along = np.linspace(-1.9, 1.9, 60)
    return [(1.95, v) for v in along] + [(-1.95, v) for v in along] + [(v, 1.95) for v in along] + \
        [(v, -1.95) for v in along]


def test_the_outline_at_the_lasers_height_is_the_rooms_walls_and_the_pillar():
    walls = slam_map.outline(World(), 0.17)
    assert len(walls) > 1000
    # in a wall's band: 1.95 to 2.05 m out on one axis, within 2.05 on both
    on_room = (np.abs(walls) >= 1.95 - 1e-6).any(axis=1) & (np.abs(walls) <= 2.05 + 1e-6).all(axis=1)
    on_pillar = np.isclose(np.hypot(walls[:, 0] - 1, walls[:, 1] - 1), 0.15, atol=0.002)
    assert (on_room | on_pillar).all()
    assert on_pillar.any()
    assert slam_map.outline(World(), 0.7).shape == (0, 2)  # above the walls: nothing


def test_a_map_drawn_on_the_walls_is_on_them_and_explores_the_room():
    world = World()
    data = grid_of(wall_points())
    occupied = slam_map.cells(data, 100, 100, RES, (-2.5, -2.5, 0.0), (0.0, 0.0, 0.0))
    free = slam_map.cells(data, 100, 100, RES, (-2.5, -2.5, 0.0), (0.0, 0.0, 0.0), occupied=False)
    on_walls, area, enclosed = slam_map.judge(occupied, free, RES, slam_map.outline(world, 0.17), 0.1)
    assert on_walls == 1.0
    assert enclosed == pytest.approx(4.1 * 4.1, rel=0.01)
    assert area == pytest.approx(3.8 * 3.8, rel=0.05)


def test_a_map_placed_wrong_in_the_world_is_off_the_walls():
    """The same map, its frame 0.5 m and 10 degrees off where it lies in the world: its walls are not the world's."""
    data = grid_of(wall_points())
    occupied = slam_map.cells(data, 100, 100, RES, (-2.5, -2.5, 0.0), (0.5, 0.0, math.radians(10)))
    on_walls, _, _ = slam_map.judge(occupied, np.zeros((0, 2)), RES, slam_map.outline(World(), 0.17), 0.1)
    assert on_walls < 0.5


def test_cells_take_the_grids_origin_and_the_maps_place_in_the_world():
    data = [-1] * 12
    data[1 * 4 + 2] = 100  # row 1, column 2
    (x, y), = slam_map.cells(data, 4, 3, 1.0, (10.0, 0.0, 0.0), (0.0, 0.0, math.pi / 2))
    assert (x, y) == pytest.approx((-1.5, 12.5))  # (12.5, 1.5) in the map, turned a quarter about the world's origin


def test_hull_area_of_a_square_and_of_too_few_points():
    square = np.array([[0, 0], [2, 0], [2, 2], [0, 2], [1, 1]], dtype=float)
    assert slam_map.hull_area(square) == pytest.approx(4.0)
    assert slam_map.hull_area(square[:2]) == 0.0
