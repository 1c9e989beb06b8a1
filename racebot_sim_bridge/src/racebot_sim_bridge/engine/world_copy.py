"""A copy of the simulated world in another PyBullet client, posed as the world was at an instant.

No rospy here. The render worker and the window (viewer_process) each hold such a copy. It is
built only from what physics.PhysicsWorld records of every body (`Model.source`, picklable) and
PhysicsWorld's own loaders, so whatever the loaders draw (shapes, meshes, colours) appears in the
copy too.
- snapshot(world): every body's base pose(s) and joint positions, taken on the physics thread at
  the sim time a frame is stamped with (a few microseconds a body);
- WorldCopy.sync(bodies) / .pose(snapshot): keeps the copy's bodies and poses equal to them.
"""
from __future__ import annotations

import itertools
from collections.abc import Collection, Mapping
from typing import TYPE_CHECKING, Dict, List, Tuple

from racebot_sim_bridge.kinematics.rotations import Transform

if TYPE_CHECKING:
    from racebot_sim_bridge.engine.physics import PhysicsWorld
    from racebot_sim_bridge.engine.model import Model
    from racebot_sim_bridge.engine.physics_types import BodySource

_SERIALS = itertools.count()

BodyKey = Tuple[str, int]  # (model name, serial): see body_key
# {name: (key, [(position, orientation) of the base and each extra body], (joint positions))}
Snapshot = Dict[str, Tuple[BodyKey, List[Transform], Tuple[float, ...]]]


def body_key(body: Model) -> BodyKey:
    """Identifies a body across a delete and respawn under the same name (PyBullet may even give
    the new body the old id): a serial number kept on the Model (its copy_key) the first time it is
    asked for."""
    if body.copy_key is None:
        body.copy_key = (body.name, next(_SERIALS))
    return body.copy_key


def snapshot(world: PhysicsWorld) -> Snapshot:
    """{name: (key, [(position, orientation) of the base and each extra body], (joint positions))}."""
    client = world.client
    shot = {}
    for name, body in world.bodies.items():
        ids = [body.id] + [extra for _, extra in body.extra_bodies]
        poses = [client.getBasePositionAndOrientation(i) for i in ids]
        joints = list(body.joints.values())
        positions = tuple(s[0] for s in client.getJointStates(body.id, [j.index for j in joints])) if joints else ()
        shot[name] = (body_key(body), poses, positions)
    return shot


def sources(world: PhysicsWorld) -> dict[str, tuple[BodyKey, BodySource]]:
    """{name: (key, Model.source)} of every body."""
    return {name: (body_key(body), body.source) for name, body in world.bodies.items()}


class WorldCopy:
    def __init__(self, world: PhysicsWorld) -> None:
        """`world`: the physics.PhysicsWorld holding the copy (its own client)."""
        self.world = world
        self.keys = {}  # name -> key of the simulated body the copy stands for

    def sync(self, bodies: Mapping[str, tuple[BodyKey, BodySource]]) -> None:
        """Adds the bodies of `bodies` ({name: (key, source)}) not in the copy yet and rebuilds those
        whose key changed. Bodies absent from it are not touched (see `prune`)."""
        for name, (key, source) in bodies.items():
            if self.keys.get(name) == key:
                continue
            if name in self.world.bodies:
                self.world.remove(name)
            self.keys.pop(name, None)
            self.world.add_copy(name, source)
            self.keys[name] = key

    def prune(self, names: Collection[str]) -> None:
        """Removes every body whose name is not in `names`."""
        for name in [n for n in self.world.bodies if n not in names]:
            self.world.remove(name)
            self.keys.pop(name, None)

    def pose(self, shot: Snapshot) -> None:
        """Puts every copied body where `shot` (snapshot()) says."""
        client = self.world.client
        for name, (key, poses, positions) in shot.items():
            copy = self.world.bodies.get(name)
            if copy is None or self.keys.get(name) != key:
                continue
            ids = [copy.id] + [extra for _, extra in copy.extra_bodies]
            for body_id, (position, orientation) in zip(ids, poses):
                client.resetBasePositionAndOrientation(body_id, position, orientation)
            if positions:  # one call for all joints: each call into a GUI client waits for its frame
                indices = [joint.index for joint in copy.joints.values()][:len(positions)]
                client.resetJointStatesMultiDof(copy.id, indices, [[p] for p in positions[:len(indices)]])
