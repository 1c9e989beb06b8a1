"""A link of a spawned body held to the world by a PyBullet constraint at an anchor: a slider along an axis, a
fixed joint or a ball joint (what libgazebo_ros_harness's joints to the world become).

PyBullet takes a constraint's frames in the link's centre-of-mass frame, so the anchor and axis given in the world
are carried there; the other end is the world, at the anchor, in the centre of mass's orientation at that moment,
so the link keeps the orientation it has.
"""
from __future__ import annotations

import pybullet as pb

from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3, compose, inverse, rotate

KINDS = {'prismatic': pb.JOINT_PRISMATIC, 'fixed': pb.JOINT_FIXED, 'ball': pb.JOINT_POINT2POINT}
MAX_FORCE = 1e7  # far above any load a harness carries: the joint holds as a simulator's joint does


def hold(client: PybulletClient, body_id: int, index: int, kind: str, frame: tuple[Vec3, Quat], anchor: Vec3,
         axis: Vec3) -> int:
    """A constraint of `kind` (KINDS) between link `index` of body `body_id` (its frame now `frame`, world pose
    (xyz, quaternion)) and the world at `anchor` (world), sliding along `axis` (world) for a prismatic one; its id."""
    com_in_link = tuple(client.getDynamicsInfo(body_id, index)[3:5])
    com = compose(frame, com_in_link)
    to_com = inverse(com)
    pivot = compose(to_com, (anchor, (0.0, 0.0, 0.0, 1.0)))[0]
    constraint = client.createConstraint(body_id, index, -1, -1, KINDS[kind], list(rotate(to_com[1], axis)),
                                         list(pivot), list(anchor), (0.0, 0.0, 0.0, 1.0), list(com[1]))
    client.changeConstraint(constraint, maxForce=MAX_FORCE)
    return constraint


def release(client: PybulletClient, constraint: int) -> None:
    client.removeConstraint(constraint)
