"""What a level 2D lidar must read in a world, computed from the world file alone.

Independent of the simulator's physics: the SDF world is parsed with sdf_reader, and each beam is
intersected analytically with the horizontal slice of every shape at the scan height (upright
boxes become rectangles, upright cylinders and spheres circles; planes are the floor). Used by
the sensors rostest and its unit-level twin. Needs numpy only.
"""
import math

import numpy as np
from racebot_sim_bridge.description import sdf_reader


def _yaw_only(q, tol=1e-6):
    """True when the rotation q (x, y, z, w) is about z only (the shape stays upright)."""
    return abs(q[0]) < tol and abs(q[1]) < tol


def _yaw(q):
    return 2.0 * math.atan2(q[2], q[3])


def slices(world, height):
    """[(kind, centre xy, yaw, size)] of the shapes a horizontal plane at `height` cuts:
    ('rect', c, yaw, (sx, sy)) or ('circle', c, 0, r)."""
    found = []
    for model in world.models:
        for link in model.links:
            for col in link.collisions:
                shape = col.shape
                if shape.kind == 'plane':
                    continue
                (x, y, z), q = model.world_pose_of(link, col)
                if not _yaw_only(q):
                    raise ValueError('%s::%s: only upright shapes are supported' % (model.name, link.name))
                if shape.kind == 'box':
                    sx, sy, sz = shape.size
                    if abs(height - z) <= sz / 2.0:
                        found.append(('rect', (x, y), _yaw(q), (sx, sy)))
                elif shape.kind == 'cylinder':
                    if abs(height - z) <= shape.length / 2.0:
                        found.append(('circle', (x, y), 0.0, shape.radius))
                elif shape.kind == 'sphere':
                    dz = abs(height - z)
                    if dz < shape.radius:
                        found.append(('circle', (x, y), 0.0, math.sqrt(shape.radius ** 2 - dz ** 2)))
    return found


def cast(shapes, origin, angles):
    """Distance from `origin` (x, y) along each world angle to the nearest shape (inf if none)."""
    ox, oy = origin
    d = np.stack([np.cos(angles), np.sin(angles)], axis=-1)
    best = np.full(len(angles), np.inf)
    for kind, (cx, cy), yaw, size in shapes:
        if kind == 'rect':
            c, s = math.cos(-yaw), math.sin(-yaw)
            px, py = c * (ox - cx) - s * (oy - cy), s * (ox - cx) + c * (oy - cy)
            dx, dy = c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]
            t_near = np.full(len(angles), -np.inf)
            t_far = np.full(len(angles), np.inf)
            for p, v, half in ((px, dx, size[0] / 2.0), (py, dy, size[1] / 2.0)):
                with np.errstate(divide='ignore', invalid='ignore'):
                    t1, t2 = (-half - p) / v, (half - p) / v
                parallel = np.abs(v) < 1e-12
                inside = abs(p) <= half
                lo = np.where(parallel, np.where(inside, -np.inf, np.inf), np.minimum(t1, t2))
                hi = np.where(parallel, np.where(inside, np.inf, -np.inf), np.maximum(t1, t2))
                t_near, t_far = np.maximum(t_near, lo), np.minimum(t_far, hi)
            hit = (t_near <= t_far) & (t_near > 0)
            best = np.where(hit, np.minimum(best, t_near), best)
        else:
            fx, fy = ox - cx, oy - cy
            b = d[:, 0] * fx + d[:, 1] * fy
            disc = b * b - (fx * fx + fy * fy - size * size)
            t = -b - np.sqrt(np.maximum(disc, 0.0))
            hit = (disc >= 0) & (t > 0)
            best = np.where(hit, np.minimum(best, t), best)
    return best


def expected_scan(world_path, origin_xyz, yaw, angle_min, angle_increment, count):
    """Ranges a noise-free lidar at `origin_xyz` (world) facing `yaw` reads, by geometry alone."""
    world = sdf_reader.load_world(world_path)
    angles = yaw + angle_min + angle_increment * np.arange(count)
    return cast(slices(world, origin_xyz[2]), origin_xyz[:2], angles)


def compare(measured, expected, range_min, range_max, tolerance, edge_jump=0.1):
    """(number of beams checked, [(index, measured, expected)] beyond `tolerance`). Beams at a
    depth edge (a neighbour's expected range differs by more than `edge_jump`) are not checked:
    there a beam grazes a corner and a hair of angle decides what it hits."""
    measured = np.asarray(measured, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)
    jump = np.zeros(len(expected), dtype=bool)
    diff = np.abs(np.diff(np.where(np.isfinite(expected), expected, 1e6)))
    jump[:-1] |= diff > edge_jump
    jump[1:] |= diff > edge_jump
    bad, checked = [], 0
    for i, (m, e) in enumerate(zip(measured, expected)):
        if jump[i]:
            continue
        checked += 1
        if e >= range_max:
            if not (math.isinf(m) and m > 0):
                bad.append((i, m, e))
        elif e <= range_min:
            continue
        elif not abs(m - e) <= tolerance:
            bad.append((i, m, e))
    return checked, bad
