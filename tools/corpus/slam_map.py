"""A SLAM map judged against the world it was made in. Pure (no ROS): the corpus's `map` check hands it an
occupancy grid (nav_msgs/OccupancyGrid's numbers), the transform from the map frame to the world, and the world's
collision geometry (floor.WorldCollisions, read from the world file, its models and meshes).

What is measured, at the height of the robot's laser (where a 2D scan sees the world):
- the world's outline there: where its collision surfaces cross that horizontal plane (triangles of meshes, boxes,
  cylinders and spheres cut by the plane; planes left out), as points every OUTLINE_STEP m;
- `on_walls`: the share of the map's occupied cells whose centre lies within a tolerance of that outline, i.e. how
  much of what the map calls a wall is a wall of the world;
- `explored`: the map's free area over the area the outline encloses (its convex hull: an arena's outer walls).
"""
import math

import numpy as np

OCCUPIED = 65  # map_server's occupied_thresh 0.65: a cell this likely or more is a wall
OUTLINE_STEP = 0.01  # m between the outline's points
_CHUNK = 2048


def cells(data, width, height, resolution, origin, world_from_map, occupied=True):
    """World (x, y) of the centres of the grid's occupied cells (value >= OCCUPIED), or of its free ones (value 0)
    with occupied=False. `data`: the grid's row-major values; `origin`: the grid's (x, y, yaw) in the map frame;
    `world_from_map`: (x, y, yaw) of the map frame in the world."""
    grid = np.asarray(data, dtype=np.int16).reshape(height, width)
    rows, cols = np.nonzero(grid >= OCCUPIED) if occupied else np.nonzero(grid == 0)
    local = np.stack([(cols + 0.5) * resolution, (rows + 0.5) * resolution], axis=1)
    in_map = _apply(origin, local)
    return _apply(world_from_map, in_map)


def _apply(pose, points):
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    return np.stack([c * points[:, 0] - s * points[:, 1] + x, s * points[:, 0] + c * points[:, 1] + y], axis=1)


def outline(world, z, step=OUTLINE_STEP):
    """Points (N x 2) every `step` m along where the world's collision surfaces cross the plane at height z."""
    segments = [_cut(_triangles(kind, at, data), z) for _, kind, at, data in world.shapes]
    segments = [s for s in segments if len(s)]
    if not segments:
        return np.zeros((0, 2))
    seg = np.concatenate(segments)
    points = []
    for a, b in seg:
        n = max(1, int(math.ceil(np.linalg.norm(b - a) / step)))
        t = np.linspace(0.0, 1.0, n + 1)[:, None]
        points.append(a + (b - a) * t)
    return np.concatenate(points)


def _triangles(kind, at, data):
    """World-space triangles (N x 3 x 3) of one of floor.WorldCollisions' shapes; none for a plane."""
    import trimesh
    if kind == 'mesh':
        return data
    if kind == 'box':
        mesh = trimesh.creation.box(extents=data, transform=at)
    elif kind == 'cylinder':
        mesh = trimesh.creation.cylinder(radius=data[0], height=data[1], sections=64, transform=at)
    elif kind == 'sphere':
        mesh = trimesh.creation.icosphere(subdivisions=3, radius=data)
        mesh.apply_transform(at)
    else:
        return np.zeros((0, 3, 3))
    return np.asarray(mesh.triangles)


def _cut(tri, z):
    """Segments (N x 2 x 2, xy) where triangles cross the plane at height z (a triangle with exactly two of its
    edges crossing it)."""
    if not len(tri):
        return np.zeros((0, 2, 2))
    d = tri[:, :, 2] - z
    crossing, points = [], []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        across = (d[:, i] * d[:, j]) < 0
        t = np.where(across, d[:, i] / np.where(across, d[:, i] - d[:, j], 1.0), 0.0)
        crossing.append(across)
        points.append(tri[:, i, :2] + (tri[:, j, :2] - tri[:, i, :2]) * t[:, None])
    crossing, points = np.stack(crossing, axis=1), np.stack(points, axis=1)
    two = crossing.sum(axis=1) == 2
    first = np.argsort(~crossing[two], axis=1, kind='stable')[:, :2]  # the two crossing edges
    return np.take_along_axis(points[two], first[:, :, None], axis=1)


def nearest(points, targets):
    """For each point (N x 2), the distance to the nearest of `targets` (M x 2); inf when there are none."""
    if not len(targets):
        return np.full(len(points), np.inf)
    best = np.empty(len(points))
    for start in range(0, len(points), _CHUNK):
        chunk = points[start:start + _CHUNK]
        d2 = ((chunk[:, None, :] - targets[None, :, :]) ** 2).sum(axis=2)
        best[start:start + _CHUNK] = np.sqrt(d2.min(axis=1))
    return best


def hull_area(points):
    """The area of the convex hull of 2D points (Andrew's monotone chain, then the shoelace formula)."""
    pts = sorted(set(map(tuple, np.round(points, 6))))
    if len(pts) < 3:
        return 0.0

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    hull = np.asarray(lower[:-1] + upper[:-1])
    x, y = hull[:, 0], hull[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def judge(occupied, free, resolution, walls, tolerance):
    """(share of occupied cells within `tolerance` of the walls' outline, explored free area in m^2, the outline's
    enclosed area in m^2)."""
    on_walls = float((nearest(occupied, walls) <= tolerance).mean()) if len(occupied) else 0.0
    return on_walls, len(free) * resolution * resolution, hull_area(walls) if len(walls) else 0.0
