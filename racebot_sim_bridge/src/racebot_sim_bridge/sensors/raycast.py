"""The laser's measurement: one PyBullet rayTestBatch for all beams, on the physics client."""
import numpy as np

MAX_RAYS_PER_BATCH = 16384  # PyBullet's limit for one rayTestBatch call


def cast_rays(world, starts, ends):
    """(fractions along each segment, hit flags) for segments starts[i] -> ends[i] (N x 3)."""
    starts = np.asarray(starts, dtype=np.float64)
    ends = np.asarray(ends, dtype=np.float64)
    fractions = np.ones(len(starts))
    hit = np.zeros(len(starts), dtype=bool)
    for first in range(0, len(starts), MAX_RAYS_PER_BATCH):
        last = first + MAX_RAYS_PER_BATCH
        results = world.client.rayTestBatch(starts[first:last], ends[first:last], numThreads=1)
        fractions[first:last] = [r[2] for r in results]
        hit[first:last] = [r[0] >= 0 for r in results]
    return fractions, hit
