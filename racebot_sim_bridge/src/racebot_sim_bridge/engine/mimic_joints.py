"""URDF <mimic> joints driven in PyBullet: each mimic joint held at ``multiplier * leader + offset``.

Beyond Gazebo: Gazebo 11 (sdformat 9) drops <mimic> when it reads a URDF, and gazebo_ros_control does not drive
it (gazebo_ros_control issue #3), so there a mimic joint hangs free unless a plugin moves it. Here each one is
a Bullet gear constraint between the two joints of the body (btMultiBodyGearConstraint): two-way, as a linkage
is, so the leader feels the mimic joint's load and a blocked mimic joint holds its leader back. Its rows keep
``q_mimic + ratio * q_leader = target`` (measured: the constraint's parent link is the first term), so
ratio = -multiplier and target = offset, with position correction (erp) so no drift builds up. A plugin that
moves the joint itself (the roboticsgroup mimic joint plugin) takes it over with release().
"""
from __future__ import annotations

from collections import namedtuple
from typing import TYPE_CHECKING

import pybullet as pb

if TYPE_CHECKING:
    from racebot_sim_bridge.description.urdf_model import RobotModel
    from racebot_sim_bridge.engine.pybullet_client import PybulletClient

# A body is given as its PyBullet id and its Model.joints ({name: joint.Joint}); model.py and joint.py import this.

# The gear's force bound: far above any joint effort a URDF gives, so the joints move as one (a linkage), yet
# finite, as Bullet wants. Its position correction: measured to hold the rule to 1e-4 under gravity loads.
MAX_FORCE = 1e6
ERP = 0.2

Coupling = namedtuple('Coupling', 'leader multiplier offset constraint')


def couple(client: PybulletClient, body_id: int, joints: dict, model: RobotModel) -> dict[str, Coupling]:
    """Gear constraints for the <mimic> joints of `model` (RobotModel.mimics) on its PyBullet body, the joints
    put where the rule says; {mimic joint: Coupling} (a Model's `mimics`), leaders before their followers."""
    mimics = model.mimics()
    couplings = {}
    for name in _leaders_first(mimics):
        mimic = mimics[name]
        joint, leader = joints.get(name), joints.get(mimic.joint)
        if joint is None or leader is None:
            continue  # moving joints only; RobotModel.mimics already leaves fixed ones out
        constraint = client.createConstraint(body_id, joint.index, body_id, leader.index, pb.JOINT_GEAR, (0, 0, 1),
                                             (0, 0, 0), (0, 0, 0))
        client.changeConstraint(constraint, gearRatio=-mimic.multiplier, relativePositionTarget=mimic.offset,
                                maxForce=MAX_FORCE, erp=ERP)
        couplings[name] = Coupling(mimic.joint, mimic.multiplier, mimic.offset, constraint)
    settle(client, body_id, joints, couplings)
    return couplings


def settle(client: PybulletClient, body_id: int, joints: dict, mimics: dict[str, Coupling]) -> None:
    """Puts every mimic joint of `mimics` where its leader says (position and velocity): after joints were set
    from outside (spawn, reset, set_model_configuration), so the gears have nothing to pull back."""
    for name, c in mimics.items():  # leaders first: a chain settles in one pass
        position, velocity = client.getJointState(body_id, joints[c.leader].index)[:2]
        client.resetJointState(body_id, joints[name].index, c.multiplier * position + c.offset,
                               c.multiplier * velocity)


def release(client: PybulletClient, mimics: dict[str, Coupling], name: str) -> Coupling | None:
    """Takes the gear off mimic joint `name` (a plugin drives it instead) and out of `mimics`; its Coupling, or
    None if it had none."""
    coupling = mimics.pop(name, None)
    if coupling is not None:
        client.removeConstraint(coupling.constraint)
    return coupling


def _leaders_first(mimics):
    order, seen = [], set()

    def visit(name):
        if name in seen:
            return
        seen.add(name)
        if name in mimics:
            visit(mimics[name].joint)
            order.append(name)
    for name in mimics:
        visit(name)
    return order
