"""make corpus's `navigation` check places the map map_server serves in the world (tools/corpus/map_registration.py):
the map frame's pose that puts the most occupied cells on the world's walls at the laser's height. A world written
here: a 4 m square room of box walls with one round pillar (which tells the room's four quarter turns apart); maps
drawn here from its outline, placed where the test says, and a map of another room. No ROS."""
import math

import numpy as np
import pytest
from PIL import Image

from corpus import angles
from corpus import map_registration as reg
from corpus import slam_map
from corpus.floor import pose_matrix

RES = 0.05


class World:
    """What slam_map.outline reads of floor.WorldCollisions: its shapes (name, kind, world-from-shape, data)."""

    def __init__(self):
        self.shapes = [('ground', 'plane', np.eye(4), (0.0, 0.0, 1.0)),
                       ('wall', 'box', pose_matrix('2 0 0.25 0 0 0'), np.array([0.1, 4.1, 0.5])),
                       ('wall', 'box', pose_matrix('-2 0 0.25 0 0 0'), np.array([0.1, 4.1, 0.5])),
                       ('wall', 'box', pose_matrix('0 2 0.25 0 0 0'), np.array([4.1, 0.1, 0.5])),
                       ('wall', 'box', pose_matrix('0 -2 0.25 0 0 0'), np.array([4.1, 0.1, 0.5])),
                       ('pillar', 'cylinder', pose_matrix('1 1 0.25 0 0 0'), (0.15, 0.5))]


@pytest.fixture(scope='module')
def walls():
    return slam_map.outline(World(), 0.17)


def apply(pose, points):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return np.stack([c * points[:, 0] - s * points[:, 1] + pose[0], s * points[:, 0] + c * points[:, 1] + pose[1]],
                    axis=1)


def drawn(world_points, world_from_map, size=120, origin=(-3.0, -3.0)):
    """A map (reg.Grid) whose frame lies at `world_from_map` in the world, occupied in the cells the world points
    (the walls' surfaces, as a laser sees them: the room's inner faces and the pillar) fall in."""
    in_map = apply(reg.inverse(world_from_map), world_points)
    data = np.full((size, size), -1, dtype=np.int8)
    cols = ((in_map[:, 0] - origin[0]) / RES).astype(int)
    rows = ((in_map[:, 1] - origin[1]) / RES).astype(int)
    data[rows, cols] = 100
    return reg.Grid(data.ravel(), size, size, RES, (origin[0], origin[1], 0.0))


def inner_faces(walls):
    """The outline's points a robot inside the room sees: the walls' inner faces and the pillar."""
    inside = (np.abs(walls) <= 1.95 + 1e-6).all(axis=1)
    return walls[inside]


@pytest.mark.parametrize('placed', [(0.63, -0.41, math.radians(7.0)), (-0.2, 0.35, math.radians(-100.0))])
def test_a_map_drawn_in_the_room_is_placed_where_it_was_drawn_within_a_cell(walls, placed):
    grid = drawn(inner_faces(walls), placed)
    found = reg.register(reg.occupied(grid), walls, tolerance=0.1)
    assert math.hypot(found.x - placed[0], found.y - placed[1]) < RES
    assert abs(angles.wrap(found.yaw - placed[2])) < math.radians(1.0)
    assert found.on_walls > 0.95
    # every cell of the map lands within a cell of where it was drawn
    cells = reg.occupied(grid)
    assert np.hypot(*(apply(found[:3], cells) - apply(placed, cells)).T).max() < RES
    # the room turned a quarter (the pillar elsewhere) is a placement too, and a worse one
    assert found.runner_up is not None and found.runner_up.mean_distance > found.mean_distance


def test_a_map_that_matches_nothing_says_so(walls):
    """A round room of 3 m radius: nowhere in the square room are most of its walls on the square's."""
    turn = np.linspace(0, 2 * math.pi, 400, endpoint=False)
    grid = drawn(np.stack([2.9 * np.cos(turn), 2.9 * np.sin(turn)], axis=1), (0.0, 0.0, 0.0), size=130,
                 origin=(-3.2, -3.2))
    with pytest.raises(reg.NoMatch, match='matches nothing') as err:
        reg.register(reg.occupied(grid), walls, tolerance=0.1)
    assert err.value.best.on_walls < 0.5


def test_nothing_to_match_says_so(walls):
    with pytest.raises(reg.NoMatch, match='nothing to match'):
        reg.register(np.zeros((0, 2)), walls)


def test_read_map_reads_map_servers_trinary_map_with_its_top_row_last(tmp_path):
    pixels = np.array([[0, 254, 205],
                       [254, 254, 0]], dtype=np.uint8)  # top row first, as the image has it
    Image.fromarray(pixels, mode='L').save(tmp_path / 'map.pgm')
    (tmp_path / 'map.yaml').write_text('image: map.pgm\nresolution: 0.5\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n'
                                       'occupied_thresh: 0.65\nfree_thresh: 0.196\n')
    grid = reg.read_map(str(tmp_path / 'map.yaml'))
    assert (grid.width, grid.height, grid.resolution, grid.origin) == (3, 2, 0.5, (-1.0, 2.0, 0.0))
    assert list(grid.data) == [0, 0, 100, 100, 0, -1]  # the image's bottom row first; 205 is unknown
    (x, y), (x2, y2) = reg.occupied(grid)
    assert (x, y) == pytest.approx((0.25, 2.25)) and (x2, y2) == pytest.approx((-0.75, 2.75))
    (tmp_path / 'negated.yaml').write_text('image: map.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 1\n'
                                           'occupied_thresh: 0.65\nfree_thresh: 0.196\n')
    negated = reg.read_map(str(tmp_path / 'negated.yaml'))
    assert list(negated.data) == [100, 100, 0, 0, 100, 100]  # 205 reads 0.80 negated: occupied


def test_compose_and_inverse_are_the_poses_of_frames():
    a, b = (1.0, 2.0, math.pi / 2), (0.5, 0.0, 0.3)
    assert reg.compose(a, b) == pytest.approx((1.0, 2.5, math.pi / 2 + 0.3))
    assert reg.compose(reg.inverse(a), reg.compose(a, b)) == pytest.approx(b)
    assert reg.compose(a, reg.inverse(a)) == pytest.approx((0.0, 0.0, 0.0))


def test_the_wall_field_is_the_distance_to_the_nearest_wall_capped():
    field = reg.WallField(np.array([[0.0, 0.0], [1.0, 0.0]]), 0.01, 0.3)
    d = field.distance(np.array([[0.0, 0.2], [0.5, 0.0], [0.8, 0.05], [5.0, 5.0]]))
    assert d == pytest.approx([0.2, 0.3, math.hypot(0.2, 0.05), 0.3], abs=0.011)
