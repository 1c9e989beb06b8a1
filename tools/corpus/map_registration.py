"""Where a map lies in the world it was made in. Pure (no ROS): the corpus's `navigation` check hands it the map
map_server serves (or reads map_server's own yaml + image here, as map_server does) and the world's wall outline at
the laser's height (slam_map.outline, from floor.WorldCollisions), and gets back the map frame's pose in the world:
the transform (x, y, yaw) that puts the most occupied cells on the walls.

How: a coarse search over every yaw (YAW_STEP) and every translation at once (the occupied cells, turned about
their centre, counted in COARSE_CELL cells and cross-correlated with the cells near the walls by FFT), then around
the best few a finer search in ROUNDS of the mean distance from the cells to the walls, capped at the tolerance,
read off a distance field of FINE_CELL. A map whose best placement puts fewer than `min_share` of its occupied
cells on the walls matches nothing, and says so (NoMatch).
"""
from __future__ import annotations

import math
import os
from typing import NamedTuple

import numpy as np

from corpus import angles, slam_map

COARSE_CELL = 0.1    # m: the coarse search's cells
YAW_STEP = math.radians(2.0)
FINE_CELL = 0.01     # m: the distance field's cells
# the fine search's rounds: (translation step m, yaw step rad), each about the last one's best, one step of the
# last round (the coarse search's cell and yaw step) and one of its own either side
ROUNDS = ((0.04, math.radians(0.5)), (0.01, math.radians(0.1)))
CANDIDATES = 4       # coarse placements refined
DISTINCT = 0.5       # m (or DISTINCT rad): candidates this far apart are different placements


class Grid(NamedTuple):
    """An occupancy grid as nav_msgs/OccupancyGrid has it: row-major values (100 occupied, 0 free, -1 unknown),
    row 0 at the origin's y; origin (x, y, yaw) in the map frame."""
    data: np.ndarray
    width: int
    height: int
    resolution: float
    origin: tuple


class Registration(NamedTuple):
    """The map frame's pose in the world (x, y, yaw), the share of occupied cells within `tolerance` of the walls
    there, their mean distance to the walls (capped at the tolerance), and the best placement that is a different
    one (None when there was no other candidate): how close the world's symmetries come."""
    x: float
    y: float
    yaw: float
    on_walls: float
    mean_distance: float
    tolerance: float
    cells: int
    runner_up: Registration | None = None


class NoMatch(ValueError):
    """No placement puts enough of the map's occupied cells on the world's walls; `best` is the best there was."""

    def __init__(self, message: str, best: Registration) -> None:
        super().__init__(message)
        self.best = best


def read_map(yaml_path: str) -> Grid:
    """A map_server map file (yaml: image, resolution, origin, negate, occupied_thresh, free_thresh, mode trinary)
    as map_server serves it: a pixel's occupancy is (255 - mean of its channels) / 255 (negated: without the
    255 -), occupied (100) above occupied_thresh, free (0) below free_thresh, else unknown (-1); the image's top
    row is the grid's last."""
    import yaml
    from PIL import Image
    with open(yaml_path) as f:
        meta = yaml.safe_load(f)
    mode = meta.get('mode', 'trinary')
    if mode != 'trinary':
        raise ValueError('%s: map mode %r: only trinary is read here' % (yaml_path, mode))
    image = os.path.join(os.path.dirname(os.path.abspath(yaml_path)), meta['image'])
    with Image.open(image) as img:
        pixels = np.asarray(img.convert('RGB') if img.mode not in ('L', 'RGB') else img, dtype=float)
    value = pixels.mean(axis=2) if pixels.ndim == 3 else pixels
    occupancy = value / 255.0 if int(meta.get('negate', 0)) else (255.0 - value) / 255.0
    grid = np.full(occupancy.shape, -1, dtype=np.int8)
    grid[occupancy > float(meta['occupied_thresh'])] = 100
    grid[occupancy < float(meta['free_thresh'])] = 0
    height, width = grid.shape
    return Grid(grid[::-1].ravel(), width, height, float(meta['resolution']),
                tuple(float(v) for v in meta['origin'][:3]))


def occupied(grid: Grid) -> np.ndarray:
    """Map-frame (x, y) of the grid's occupied cells' centres (N x 2)."""
    return slam_map.cells(grid.data, grid.width, grid.height, grid.resolution, grid.origin, (0.0, 0.0, 0.0))


# --- poses (x, y, yaw) ---------------------------------------------------------------------------------

def compose(a: tuple, b: tuple) -> tuple:
    """The pose b given in frame a, in a's parent frame (a * b)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], angles.wrap(a[2] + b[2]))


def inverse(a: tuple) -> tuple:
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-(c * a[0] + s * a[1]), s * a[0] - c * a[1], angles.wrap(-a[2]))


def _turn(points, yaw):
    c, s = math.cos(yaw), math.sin(yaw)
    return np.stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]], axis=1)


# --- the walls' distance field ----------------------------------------------------------------------------

class WallField:
    """The distance from points to the nearest of the walls' outline points, capped at `reach`, read off a grid of
    `cell` m (exact at cell centres, off by at most a cell's half diagonal elsewhere)."""

    def __init__(self, walls: np.ndarray, cell: float, reach: float) -> None:
        self.cell, self.reach = cell, reach
        self.low = walls.min(axis=0) - reach - 2 * cell
        size = np.ceil((walls.max(axis=0) + reach + 2 * cell - self.low) / cell).astype(int) + 1
        self.field = np.full(tuple(size), reach)
        at = np.unique(np.floor((walls - self.low) / cell).astype(int), axis=0)
        k = int(math.ceil(reach / cell))
        for dx in range(-k, k + 1):
            for dy in range(-k, k + 1):
                d = math.hypot(dx, dy) * cell
                if d <= reach:
                    ix, iy = at[:, 0] + dx, at[:, 1] + dy
                    self.field[ix, iy] = np.minimum(self.field[ix, iy], d)
        self._flat = self.field.ravel()

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Capped distance of points (... x 2) to the walls; `reach` outside the grid (its border cells, more than
        `reach` from every wall point, stand for everything beyond)."""
        ix = np.clip(np.floor((points[..., 0] - self.low[0]) / self.cell).astype(np.intp), 0, self.field.shape[0] - 1)
        iy = np.clip(np.floor((points[..., 1] - self.low[1]) / self.cell).astype(np.intp), 0, self.field.shape[1] - 1)
        return self._flat.take(ix * self.field.shape[1] + iy)


# --- the search --------------------------------------------------------------------------------------------

def _coarse(points, near, low, yaws):
    """[(count of points on `near` cells, yaw, tx, ty)] per yaw, its best translation: `near` is a boolean grid of
    COARSE_CELL cells from `low`."""
    shape = np.array(near.shape)
    out = []
    spectrum_cache = {}
    for yaw in yaws:
        turned = _turn(points, yaw)
        base = turned.min(axis=0)
        at = np.floor((turned - base) / COARSE_CELL).astype(int)
        extent = at.max(axis=0) + 1
        size = tuple(int(n) for n in shape + extent)
        if size not in spectrum_cache:
            spectrum_cache[size] = np.fft.rfft2(near.astype(float), size)
        counts = np.zeros(tuple(extent))
        np.add.at(counts, (at[:, 0], at[:, 1]), 1.0)
        score = np.fft.irfft2(spectrum_cache[size] * np.conj(np.fft.rfft2(counts, size)), size)
        i, j = np.unravel_index(int(np.argmax(score)), size)
        shift = np.array([i if i < shape[0] else i - size[0], j if j < shape[1] else j - size[1]])
        # a point at base + (a + 0.5) cell lands in the near cell a + shift: t = low + shift * cell - base
        t = low + shift * COARSE_CELL - base
        out.append((float(score[i, j]), yaw, float(t[0]), float(t[1])))
    return out


def _distinct(ranked, count):
    """The first `count` of ranked (score, yaw, x, y) that are DISTINCT apart from each other."""
    kept = []
    for cand in ranked:
        if all(math.hypot(cand[2] - k[2], cand[3] - k[3]) > DISTINCT or abs(angles.wrap(cand[1] - k[1])) > DISTINCT
               for k in kept):
            kept.append(cand)
        if len(kept) == count:
            break
    return kept


def _refine(points, field, start, tolerance):
    """The (mean capped distance, yaw, x, y) near `start` (score, yaw, x, y) with the least mean distance to the
    walls, in ROUNDS."""
    best, (reach, yaw_reach) = start, (COARSE_CELL, YAW_STEP)
    for step, yaw_step in ROUNDS:
        steps = np.arange(-reach - step, reach + step + 1e-9, step)
        dx, dy = np.meshgrid(steps, steps, indexing='ij')
        shifts = np.stack([dx.ravel(), dy.ravel()], axis=1)
        _, yaw0, x0, y0 = best
        best = None
        for yaw in yaw0 + np.arange(-yaw_reach - yaw_step, yaw_reach + yaw_step + 1e-12, yaw_step):
            turned = _turn(points, yaw) + (x0, y0)
            d = np.minimum(field.distance(turned[None, :, :] + shifts[:, None, :]), tolerance).mean(axis=1)
            k = int(np.argmin(d))
            if best is None or d[k] < best[0]:
                best = (float(d[k]), float(yaw), x0 + shifts[k, 0], y0 + shifts[k, 1])
        reach, yaw_reach = step, yaw_step
    return best


def register(points: np.ndarray, walls: np.ndarray, tolerance: float = 0.1, min_share: float = 0.5,
             yaws: tuple | None = None) -> Registration:
    """The map frame's pose in the world that puts the most of the map's occupied cells (`points`, map frame,
    N x 2) within `tolerance` m of the walls' outline (`walls`, world, M x 2). `yaws`: (low, high) rad of the map's
    yaw searched, every yaw unless given. Raises NoMatch when the best puts fewer than `min_share` on the walls."""
    if not len(points) or not len(walls):
        raise NoMatch('%d occupied cells, %d wall points: nothing to match' % (len(points), len(walls)),
                      Registration(0.0, 0.0, 0.0, 0.0, tolerance, tolerance, len(points)))
    field = WallField(walls, FINE_CELL, tolerance + FINE_CELL)  # beyond the tolerance: more than it
    low = walls.min(axis=0) - tolerance - COARSE_CELL
    size = np.ceil((walls.max(axis=0) + tolerance + COARSE_CELL - low) / COARSE_CELL).astype(int)
    gx, gy = np.meshgrid(*(low[i] + (np.arange(size[i]) + 0.5) * COARSE_CELL for i in range(2)), indexing='ij')
    near = field.distance(np.stack([gx, gy], axis=-1)) <= tolerance
    lo, hi = yaws if yaws is not None else (-math.pi, math.pi - YAW_STEP / 2)
    centre = points.mean(axis=0)  # turned about their centre: a yaw step moves no cell far
    local = points - centre
    coarse = sorted(_coarse(local, near, low, np.arange(lo, hi + 1e-12, YAW_STEP)), reverse=True)
    fine = sorted(_refine(local, field, c, tolerance) for c in _distinct(coarse, CANDIDATES))
    placed = [_registration(points, field, _uncentred(f, centre), tolerance) for f in _distinct(fine, 2)]
    best = placed[0]._replace(runner_up=placed[1] if len(placed) > 1 else None)
    if best.on_walls < min_share:
        raise NoMatch('the map matches nothing: at best %.1f %% of its %d occupied cells within %.2f m of the walls '
                      '(at least %.0f %% asked)' % (100 * best.on_walls, len(points), tolerance, 100 * min_share), best)
    return best


def _uncentred(found, centre):
    """A placement (score, yaw, x, y) of the points less their centre, as one of the points themselves."""
    score, yaw, x, y = found
    turned = _turn(centre[None, :], yaw)[0]
    return score, yaw, x - turned[0], y - turned[1]


def _registration(points, field, found, tolerance):
    _, yaw, x, y = found
    d = field.distance(_turn(points, yaw) + (x, y))
    return Registration(float(x), float(y), angles.wrap(float(yaw)), float((d <= tolerance).mean()),
                        float(np.minimum(d, tolerance).mean()), tolerance, len(points))
