"""Joint: one movable joint of a model, as gazebo::physics::Joint is one (position, velocity, effort, limits,
motor commands).

No ROS here. A Joint is made by its Model (model.py) from PyBullet's joint info, and is found by name in
`Model.joints`. The per-update paths (ros_control's read and write, the drive plugins) address many joints
at once through the Model's array calls (Model.joint_states_raw, apply_efforts, drive_velocities); a Joint's
own methods are for one joint at a time (services, plugins that move one joint).
"""
from __future__ import annotations

from typing import Any

import pybullet as pb

from racebot_sim_bridge.engine import mimic_joints
from racebot_sim_bridge.engine.physics_types import JointState
from racebot_sim_bridge.kinematics.rotations import Vec3

JOINT_TYPES = {pb.JOINT_REVOLUTE: 'revolute', pb.JOINT_PRISMATIC: 'prismatic',
               pb.JOINT_FIXED: 'fixed', pb.JOINT_SPHERICAL: 'spherical', pb.JOINT_PLANAR: 'planar'}


class Joint:
    """A movable joint: `index` (PyBullet's joint index, also its child link's), `name`, `type` ('revolute',
    'prismatic', ...), position limits `lower` and `upper`, `max_effort`, `max_velocity`, `child_link` (its
    child link's name) and `model`, the engine.model.Model it belongs to (not annotated by class: model.py
    imports this module)."""

    __slots__ = ('model', 'index', 'name', 'type', 'lower', 'upper', 'max_effort', 'max_velocity', 'child_link')

    def __init__(self, model: Any, info: tuple) -> None:
        """`info`: PyBullet's getJointInfo tuple of the joint."""
        self.model = model
        self.index = info[0]
        self.name = info[1].decode()
        self.type = JOINT_TYPES.get(info[2], 'unknown')
        self.lower, self.upper = info[8], info[9]
        self.max_effort, self.max_velocity = info[10], info[11]
        self.child_link = info[12].decode()

    def __repr__(self):
        return '<Joint %s (%s, index %d) of %s>' % (self.name, self.type, self.index, self.model.name)

    # -- state ------------------------------------------------------------------------------------
    def state(self) -> JointState:
        """Position and velocity now."""
        s = self.model.client.getJointState(self.model.id, self.index)
        return JointState(s[0], s[1])

    def set_position(self, position: float, velocity: float = 0.0) -> None:
        """Puts the joint at `position` moving at `velocity` (Joint::SetPosition); its URDF <mimic> followers
        are put where their rule says."""
        model = self.model
        model.client.resetJointState(model.id, self.index, position, velocity)
        if model.wheel_friction is not None:  # a wheel held at a rate: its friction along the wheel (wheel_friction.py)
            model.wheel_friction.hold(self.index)
        if model.mimics:
            mimic_joints.settle(model.client, model.id, model.joints, model.mimics)

    # -- commands (for one step) ------------------------------------------------------------------
    def apply_effort(self, effort: float) -> None:
        """A torque (or force) for the coming step (Joint::SetForce)."""
        self.model.apply_efforts([self.index], [effort])

    def drive_velocity(self, velocity: float, max_force: float) -> None:
        """PyBullet's velocity motor towards `velocity`, with at most `max_force` (held until changed)."""
        self.model.drive_velocities([self.index], [velocity], [max_force])

    # -- dynamics and limits ----------------------------------------------------------------------
    def set_dynamics(self, damping: float | None = None, lower: float | None = None,
                     upper: float | None = None) -> None:
        """Viscous damping and position limits (None: unchanged)."""
        model = self.model
        dampers = model.dampers
        if damping is not None and dampers is not None and self.index in dampers.joints:
            dampers.set_damping(self.index, damping)  # Gazebo's SetDamping keeps an implicit joint implicit
        elif damping is not None:
            model.client.changeDynamics(model.id, self.index, jointDamping=damping)
        if lower is not None or upper is not None:
            self.lower = self.lower if lower is None else lower
            self.upper = self.upper if upper is None else upper
            model.client.changeDynamics(model.id, self.index, jointLowerLimit=self.lower, jointUpperLimit=self.upper)

    def enable_wrench(self) -> None:
        """Has PyBullet measure the wrench through this joint (wrench())."""
        self.model.links[self.child_link].enable_parent_wrench()

    def wrench(self) -> tuple[Vec3, Vec3]:
        """(force, torque) through the joint in the last step (Joint::GetForceTorque): Link.parent_wrench of
        its child link."""
        return self.model.links[self.child_link].parent_wrench()
