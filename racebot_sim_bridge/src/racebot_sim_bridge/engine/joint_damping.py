"""URDF joint damping as Gazebo classic's ODE applies it: explicit unless the joint asks for implicit.

sdformat (parser_urdf.cc) writes a URDF <dynamics damping> into the SDF joint's <axis><dynamics><damping>, and
<physics><ode><implicit_spring_damper> only when the joint's <gazebo reference> sets <implicitSpringDamper> (or
the older <cfmDamping>); joint.sdf's default is false, as is ODEJoint's constructor. ODEJoint::ApplyStiffnessDamping
then runs before every step:
- explicit (the default, ApplyExplicitStiffnessDamping): a torque -|damping| * velocity from the velocity before the
  step. PyBullet's URDF importer applies <dynamics damping> the same way (a torque -damping * velocity added before
  the step; measured: a 0.01 kg m^2 disc at 1 ms goes v -> v * (1 - damping * dt / I)), so those joints keep it;
  like Gazebo's, it overshoots and grows once damping * dt / I > 2.
- implicit (ApplyImplicitStiffnessDamping): an extra constraint row, hi_stop = lo_stop = the spring reference, with
  ERP/CFM from KpKdToCFMERP (kp = 0: ERP 0, CFM 1 / damping): the damping force is -damping * (the velocity after
  the step), solved with the step, so it never overshoots at any damping. Off while the joint is (predicted at
  angle + 2 * velocity * dt) beyond its limits, where the limit row takes that row over.

ImplicitDampers does the implicit case for one body: each step it predicts the damped joints' velocities after the
step from the joint-space mass matrix, the efforts applied this step and (fixed base) gravity and Coriolis, solves
(1 + dt * Minv_JJ * D) v' = v + dt * a for the damped joints together, and applies -D * v' as a joint torque.
Contacts and motors are not in the prediction (ODE solves them in the same LCP); they enter the next step. The mass
matrix's inverse is worked out again every MASS_MATRIX_STEPS steps, not every step (the Fetch's 15 joints: ~70 us each
time); any positive definite one keeps the update a contraction, so an older one costs accuracy, never stability.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

import numpy as np

from racebot_sim_bridge.engine.pybullet_client import PybulletClient

if TYPE_CHECKING:
    from racebot_sim_bridge.description.urdf_model import RobotModel

MASS_MATRIX_STEPS = 10


def implicit_damping(urdf_model: RobotModel, joint_name: str) -> float:
    """|<dynamics damping>| of a joint whose <gazebo reference> sets implicitSpringDamper (or cfmDamping, which
    sdformat reads as the same switch); 0 for every other joint, whose damping stays explicit."""
    refs = urdf_model.gazebo_refs.get(joint_name, {})
    if not (refs.get('implicitSpringDamper') is True or refs.get('cfmDamping') is True):
        return 0.0
    dynamics = getattr(urdf_model.joints.get(joint_name), 'dynamics', None)
    return abs(dynamics.damping) if dynamics is not None else 0.0


def implicit_joints(urdf_model: RobotModel, joints: Mapping[str, object]) -> list[tuple[int, float, float | None,
                                                                                      float | None]]:
    """(index, damping, lower, upper) of the implicitly damped joints among `joints` (name -> joint.Joint);
    limits None where the joint has none (continuous: sdformat writes it unlimited; PyBullet reports the URDF's
    numbers, or lower >= upper)."""
    result = []
    for name, joint in joints.items():
        damping = implicit_damping(urdf_model, name)
        if not damping:
            continue
        spec = urdf_model.joints.get(name)
        limited = joint.lower < joint.upper and getattr(spec, 'type', '') != 'continuous'
        result.append((joint.index, damping, joint.lower if limited else None, joint.upper if limited else None))
    return result


class ImplicitDampers:
    """The implicitly damped joints of one PyBullet body.

    joints: (index, damping, lower, upper) per damped joint, limits None for a continuous joint."""

    def __init__(self, client: PybulletClient, body_id: int, fixed_base: bool,
                 joints: Iterable[tuple[int, float, float | None, float | None]]) -> None:
        self.client = client
        self.body_id = body_id
        self.fixed_base = fixed_base
        self.joints = {index: (damping, lower, upper) for index, damping, lower, upper in joints}
        # every movable joint in PyBullet's velocity order (uIndex; its first movable joint has uIndex 6)
        infos = [client.getJointInfo(body_id, j) for j in range(client.getNumJoints(body_id))]
        movable = sorted((info[4], info[0]) for info in infos if info[4] >= 0)
        self.movable = [index for _, index in movable]
        self.dof = {index: k for k, index in enumerate(self.movable)}
        self.base_dofs = 0 if fixed_base else 6
        self._m_inv = None  # the joints' block of M^-1, MASS_MATRIX_STEPS steps old at most
        self._age = 0

    def set_damping(self, index: int, damping: float) -> None:
        _, lower, upper = self.joints[index]
        self.joints[index] = (abs(damping), lower, upper)

    def torques(self, dt: float, applied: Mapping[int, float]) -> tuple[list[int], list[float]]:
        """(joint indices, damping torques) to apply for the coming step of `dt`; `applied`: {joint index: effort}
        applied to this body for that step so far."""
        states = self.client.getJointStates(self.body_id, self.movable)
        q = [s[0] for s in states]
        v = np.array([s[1] for s in states])
        active = []
        for index, (damping, lower, upper) in self.joints.items():
            k = self.dof[index]
            ahead = q[k] + 2.0 * v[k] * dt
            if damping > 0.0 and not ((lower is not None and ahead <= lower) or (upper is not None and ahead >= upper)):
                active.append((index, k, damping))
        if not active:
            return [], []
        n = len(self.movable)
        if self._m_inv is None or self._age >= MASS_MATRIX_STEPS:
            mass = np.array(self.client.calculateMassMatrix(self.body_id, q))
            self._m_inv = np.linalg.inv(mass)[self.base_dofs:, self.base_dofs:]
            self._age = 0
        self._age += 1
        m_inv = self._m_inv
        effort = np.zeros(n)
        for index, value in applied.items():
            if index in self.dof:
                effort[self.dof[index]] += value
        if self.fixed_base:  # gravity and Coriolis (PyBullet's inverse dynamics takes no floating base)
            effort -= np.array(self.client.calculateInverseDynamics(self.body_id, q, list(v), [0.0] * n))
        free = v + dt * (m_inv @ effort) if effort.any() else v
        ks = [k for _, k, _ in active]
        damping = np.array([d for _, _, d in active])
        system = np.eye(len(ks)) + dt * m_inv[np.ix_(ks, ks)] * damping[np.newaxis, :]
        after = np.linalg.solve(system, free[ks])
        return [index for index, _, _ in active], list(-damping * after)
