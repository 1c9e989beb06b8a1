"""Link: one link of a model, as gazebo::physics::Link is one (pose, velocities, forces and torques, mass).

No ROS here. A Link is made by its Model (model.py) and found by name in `Model.links`. In PyBullet a link
is addressed (body id, link index): a URDF robot's links are one body's (its root link index -1), an SDF
model's links are a body each (all index -1; the first is the model's own body, `Model.id`).
"""
from __future__ import annotations

from typing import Any

import pybullet as pb

from racebot_sim_bridge.engine.physics_types import LinkDynamics, PhysicsError, Pose, Twist
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3


class Link:
    """A link: `name`, `body_id` and `index` (its PyBullet address), `model` (the engine.model.Model it belongs
    to; not annotated by class: model.py imports this module). `applied`: the world's accumulator of the
    wrenches applied since the last step, {(body id, link index): [fx, fy, fz, tx, ty, tz]} (Gazebo's Link
    force and torque accumulators, which ODE clears after each step as PyBullet its external forces; the
    world clears it)."""

    __slots__ = ('model', 'name', 'body_id', 'index', 'applied')

    def __init__(self, model: Any, name: str, body_id: int, index: int, applied: dict) -> None:
        self.model = model
        self.name = name
        self.body_id = body_id
        self.index = index
        self.applied = applied

    def __repr__(self):
        return '<Link %s (body %d, index %d) of %s>' % (self.name, self.body_id, self.index, self.model.name)

    @property
    def address(self) -> tuple[int, int]:
        """(PyBullet body id, link index)."""
        return self.body_id, self.index

    # -- pose and velocity ------------------------------------------------------------------------
    def state(self) -> tuple[Pose, Twist]:
        """World pose and twist (Link::WorldPose, WorldLinearVel, WorldAngularVel). A URDF root link: its
        frame's pose (Model.frame_pose); an SDF model's other links: their body's base."""
        client, index = self.model.client, self.index
        if index >= 0:
            s = client.getLinkState(self.body_id, index, computeLinkVelocity=1, computeForwardKinematics=1)
            return Pose(tuple(s[4]), tuple(s[5])), Twist(tuple(s[6]), tuple(s[7]))
        if self.body_id == self.model.id:
            return self.model.frame_pose(), self.model.twist()
        pos, orn = client.getBasePositionAndOrientation(self.body_id)
        lin, ang = client.getBaseVelocity(self.body_id)
        return Pose(tuple(pos), tuple(orn)), Twist(tuple(lin), tuple(ang))

    def set_base_state(self, position: Vec3, orientation: Quat, linear: Vec3 = (0, 0, 0),
                       angular: Vec3 = (0, 0, 0)) -> None:
        """Puts the link's body base (a link of index -1: a root link, or an SDF model's link) at a pose (its
        centre of mass) with a twist. PhysicsError for a link inside an articulated body: move its model or
        set its joints instead."""
        if self.index >= 0:
            raise PhysicsError("link '%s' of '%s' is not a body's base: move the model or set its joints"
                               % (self.name, self.model.name))
        self.model.client.resetBasePositionAndOrientation(self.body_id, position, orientation)
        self.model.client.resetBaseVelocity(self.body_id, linear, angular)

    def com_position(self) -> Vec3:
        """World position of the link's centre of mass."""
        if self.index < 0:
            return tuple(self.model.client.getBasePositionAndOrientation(self.body_id)[0])
        return tuple(self.model.client.getLinkState(self.body_id, self.index, computeForwardKinematics=1)[0])

    # -- dynamics ---------------------------------------------------------------------------------
    def dynamics(self) -> LinkDynamics:
        """Mass, inertia diagonal, inertial frame in the link frame."""
        d = self.model.client.getDynamicsInfo(self.body_id, self.index)
        return LinkDynamics(d[0], tuple(d[2]), tuple(d[3]), tuple(d[4]))

    def set_mass(self, mass: float, inertia_diagonal: Vec3) -> None:
        """Mass and inertia diagonal (Link::SetInertial)."""
        # Two calls: PyBullet recomputes the inertia from the collision shapes when the mass changes.
        self.model.client.changeDynamics(self.body_id, self.index, mass=mass)
        self.model.client.changeDynamics(self.body_id, self.index, localInertiaDiagonal=list(inertia_diagonal))

    # -- forces -----------------------------------------------------------------------------------
    def apply_wrench(self, force: Vec3, torque: Vec3, accumulate: bool = True) -> None:
        """A world-frame force at the link's centre of mass and a world-frame torque, for one step.
        `accumulate`: it counts in applied_wrench (False: a stand-in for what Gazebo does otherwise)."""
        if accumulate and (any(force) or any(torque)):
            total = self.applied.setdefault((self.body_id, self.index), [0.0] * 6)
            for i in range(3):
                total[i] += force[i]
                total[3 + i] += torque[i]
        if any(force):
            self.model.client.applyExternalForce(self.body_id, self.index, list(force), self.com_position(),
                                                 pb.WORLD_FRAME)
        if any(torque):
            self.model.client.applyExternalTorque(self.body_id, self.index, list(torque), pb.WORLD_FRAME)

    def applied_wrench(self) -> tuple[Vec3, Vec3]:
        """(force, torque), world axes, applied with apply_wrench since the last step: Gazebo's
        Link::WorldForce/WorldTorque (the torque about its centre of mass)."""
        total = self.applied.get((self.body_id, self.index), (0.0,) * 6)
        return tuple(total[:3]), tuple(total[3:])

    def enable_parent_wrench(self) -> None:
        """Has PyBullet measure the wrench through the joint above this link (parent_wrench)."""
        self.model.client.enableJointForceTorqueSensor(self.body_id, self.index, True)

    def parent_wrench(self) -> tuple[Vec3, Vec3]:
        """(force, torque) the parent applies to this link (and what hangs below it) through its joint, fixed
        or movable, in the last step: PyBullet's default feedback, in the link's inertial-frame axes, the
        torque about its centre of mass. Zero unless enable_parent_wrench was called."""
        reaction = self.model.client.getJointState(self.body_id, self.index)[2]
        return tuple(reaction[:3]), tuple(reaction[3:])
