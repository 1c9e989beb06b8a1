"""raycast.cast_rays splits what PyBullet's rayTestBatch takes at once: a VLP-16's 1875 x 16 = 30000 rays all
come back, each with its hit."""
import functools

import numpy as np
import pybullet as pb

from racebot_sim_bridge.sensors.raycast import MAX_RAYS_PER_BATCH, cast_rays


class Client:
    """The physics client as cast_rays uses it (world.client.rayTestBatch), on a connection of its own."""

    def __init__(self, cid):
        self.rayTestBatch = functools.partial(pb.rayTestBatch, physicsClientId=cid)


class World:
    def __init__(self, cid):
        self.client = Client(cid)


def test_more_rays_than_one_batch_all_hit_a_box():
    cid = pb.connect(pb.DIRECT)
    try:
        pb.createMultiBody(0, pb.createCollisionShape(pb.GEOM_BOX, halfExtents=[1, 1, 1], physicsClientId=cid),
                           basePosition=[3, 0, 0], physicsClientId=cid)
        for n in (MAX_RAYS_PER_BATCH, MAX_RAYS_PER_BATCH + 1, 30000):
            starts = np.zeros((n, 3))
            ends = np.tile([5.0, 0.0, 0.0], (n, 1))
            fractions, hit = cast_rays(World(cid), starts, ends)
            assert hit.all() and len(fractions) == n
            assert np.allclose(fractions, 0.4)  # the box's near face at x = 2 of 5
    finally:
        pb.disconnect(physicsClientId=cid)
