"""A wheel's friction along the wheel, as ODE's <fdir1> pyramid aligns it, where Bullet's stays with the world.

ODE (Gazebo classic's default engine) builds a contact's two friction rows from the collision's <fdir1> turned with
the link, and the normal's cross with it; each row is limited to its own mu (mu1 along fdir1, mu2 across) times the
normal force. For a wheel whose fdir1 lies square to its axle or along it, the two rows are the rolling direction and
the axle. Bullet builds its two rows from the contact normal alone (btPlaneSpace1: world x and y on flat ground), so
a wheel heading 45 degrees off a world axis that slides along its rolling direction (a car whose four wheels turn at
one rate, hunter's RobotHWSim) uses up both rows' limits and keeps no grip across: the car turns short, and by how
much depends on its heading. Bullet's anisotropic friction only rescales its rows, never turns them.

WheelFriction applies ODE's box itself to the wheels a plugin holds at a rate (Joint::SetVelocity, hunter's
steer_bot_hardware_gazebo; Joint.set_position here), for the steps it holds them: their contacts leave Bullet's
friction (lateralFriction 0: Bullet solves their normal forces only) and get a force at each contact for the coming
step:
- per contact, the rolling direction r (the normal's cross with the axle laid into the contact plane) and the axle
  a; the slip s, the contact point's velocity along each (the other body's, where it moves, subtracted);
- the impulses lambda that take the slip out, from the response W of every wheel's slip to every wheel's impulse:
  the model taken as one rigid body (its mass and inertia about its centre of mass, from its links, worked out
  again every RIGID_STEPS steps) plus each wheel's spin about its axle on the rolling rows. A held wheel responds
  less than W says (what turns it is taken out by the next SetVelocity), so the correction is slower, never
  unstable (below); W's redundant modes take no impulse (NULL_MODE);
- as a proportional and an integral term on W^-1 s (ALPHA, BETA): lambda = I - ALPHA W^-1 s, I -= BETA W^-1 s,
  each row held to mu times the last step's normal impulse. The integral term holds a standing load (a car parked
  across a slope, a wheel pulling) with no creep. Stable for a response up to (4 / (2 ALPHA + BETA)) = 3 times W;
- the equal and opposite force on the other body when it is not static.
A wheel turned by effort (a JointEffortController, racebot's and the MIT racecar's) stays with Bullet's friction:
its spin adapts to the ground, so it slides little, and a friction force applied from outside the solver, one step
late, on a wheel that light (racebot's: 0.66 kg at its rim) beside an effort controller's own explicit loop made
both ring and pump energy into the car (racebot accelerated to 7 m/s with its wheels at 0.3 m/s).
Normal forces are the last step's (the step before solves them), as ODE's are solved with the friction in one LCP:
a wheel's first step of contact has no friction. The cone model is not followed here (a box, as the pyramid).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pybullet as pb

from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.kinematics.rotations import rotate as _rotate
from racebot_sim_bridge.kinematics.rotations import rotate_back

ALPHA, BETA = 0.6, 0.15
RIGID_STEPS = 10
# W's modes (its rows scaled to a response of 1 each) below this share of its largest take no impulse: four wheels'
# lateral rows are redundant for a rigid body's three motions, and two wheels squeezing each other across move nothing
# (an inverse winds that up to the limits, where it pushes the car sideways)
NULL_MODE = 1e-2


class AlignedWheel(NamedTuple):
    """A wheel link of the body: its PyBullet link `index`, its continuous joint's unit `axle` in its URDF link
    frame, and its mu along the rolling direction and along the axle (bullet_urdf.WheelAxes, held to the ground's)."""
    index: int
    axle: tuple
    mu_roll: float
    mu_axle: float


class WheelFriction:
    """ODE's fdir1-aligned friction for the `wheels` of one free-based body while they are held (module docstring):
    hold(index) when a joint is set to a rate, apply(dt) before every step, reset() when the body is put back."""

    def __init__(self, client: PybulletClient, body_id: int, wheels: list[AlignedWheel]) -> None:
        self.client, self.body = client, body_id
        self.wheels = {w.index: w for w in wheels}
        self.bullet_mu = {w.index: client.getDynamicsInfo(body_id, w.index)[1] for w in wheels}  # given back
        self.held, self.active = set(), set()  # held for the coming step; whose friction this takes over now
        self.links = list(range(client.getNumJoints(body_id)))
        dyn = [client.getDynamicsInfo(body_id, i) for i in [-1] + self.links]
        self.masses = np.array([d[0] for d in dyn])
        self.moments = [np.diag(d[2]) for d in dyn]
        # each wheel's moment about its axle: the axle in its inertial frame, on the principal moments
        self.spin_inertia = {}
        for w in wheels:
            d = dyn[w.index + 1]
            local = rotate_back(d[4], w.axle)
            self.spin_inertia[w.index] = max(sum(m * c * c for m, c in zip(d[2], local)), 1e-12)
        self.impulse = {w.index: np.zeros(2) for w in wheels}  # the integral term of each wheel's rows
        # (body, link) -> (its lateral friction, whether it is static) of what the wheels touch (Bullet multiplies
        # frictions; the robot's is ODE's minimum already)
        self.others = {}
        self.solver = None
        self.steps = 0

    def hold(self, index: int) -> None:
        """Link (joint) `index` is held at its rate for the coming step (Joint::SetVelocity); not a wheel: nothing."""
        if index in self.wheels:
            self.held.add(index)

    def _take_over(self, held: set) -> None:
        """The held wheels' friction out of Bullet's solver, the others' back in it."""
        for index in held - self.active:
            self.client.changeDynamics(self.body, index, lateralFriction=0.0)
        for index in self.active - held:
            self.client.changeDynamics(self.body, index, lateralFriction=self.bullet_mu[index])
            self.impulse[index][:] = 0.0
        self.active = held

    def reset(self) -> None:
        for v in self.impulse.values():
            v[:] = 0.0
        self.solver = None

    def _rigid_body(self):
        """(mass, centre of mass, inverse inertia about it) of the whole body, in the world."""
        client = self.client
        pos, orn = client.getBasePositionAndOrientation(self.body)
        positions, orientations = [pos], [orn]
        if self.links:
            for s in client.getLinkStates(self.body, self.links, computeForwardKinematics=1):
                positions.append(s[0])
                orientations.append(s[1])
        p = np.array(positions)
        mass = float(self.masses.sum())
        cm = self.masses @ p / mass
        inertia = np.zeros((3, 3))
        for m, x, q, moments in zip(self.masses, p, orientations, self.moments):
            r = np.array(client.getMatrixFromQuaternion(q)).reshape(3, 3)
            d = x - cm
            inertia += r @ moments @ r.T + m * (d @ d * np.eye(3) - np.outer(d, d))
        return mass, cm, np.linalg.inv(inertia)

    def _other(self, body: int, link: int):
        """(lateral friction, static) of the body a wheel touches."""
        key = (body, link)
        if key not in self.others:
            info = self.client.getDynamicsInfo(body, link)
            self.others[key] = (info[1], info[0] == 0.0)
        return self.others[key]

    def _point_velocity(self, body: int, link: int, point: tuple) -> tuple:
        client = self.client
        if link < 0:
            pos, _ = client.getBasePositionAndOrientation(body)
            lin, ang = client.getBaseVelocity(body)
        else:
            s = client.getLinkState(body, link, computeLinkVelocity=1, computeForwardKinematics=1)
            pos, lin, ang = s[0], s[6], s[7]
        return _add(lin, _cross(ang, _sub(point, pos)))

    def _contacts(self):
        """[(wheel, contact point, unit normal, normal force, other body, other link)] of the last step."""
        touching = {}
        for c in self.client.getContactPoints(bodyA=self.body):
            if c[3] in self.active and c[9] > 0.0:
                touching.setdefault(c[3], []).append(c)
        found = []
        for index in sorted(touching):
            points = touching[index]
            force = sum(c[9] for c in points)
            point = tuple(sum(c[6][k] * c[9] for c in points) / force for k in range(3))
            normal = _unit(tuple(sum(c[7][k] * c[9] for c in points) for k in range(3)))
            main = max(points, key=lambda c: c[9])
            found.append((self.wheels[index], point, normal, force, main[2], main[4]))
        return found

    def _solver(self, key, rows, spin):
        """What takes a slip to its impulses, x = W^+ s as (pseudo-inverse of W scaled to unit rows, the scale), for
        the wheels in contact `key`; worked out again, with the rigid body, every RIGID_STEPS steps or when the wheels
        in contact change."""
        if self.solver is None or self.solver[0] != key or self.steps % RIGID_STEPS == 0:
            mass, cm, inverse_inertia = self._rigid_body()
            jac = np.array([list(d) + list(_cross(_sub(point, cm), d)) for point, d in rows])
            response = jac[:, :3] @ jac[:, :3].T / mass + jac[:, 3:] @ inverse_inertia @ jac[:, 3:].T
            response[0::2, 0::2] += np.diag(spin)  # an impulse along the rolling direction also turns the wheel
            scale = np.sqrt(np.diag(response))  # each row's own response 1: the modes compare as shares of it
            self.solver = (key, np.linalg.pinv(response / np.outer(scale, scale), rcond=NULL_MODE, hermitian=True),
                           scale)
        return self.solver[1], self.solver[2]

    def apply(self, dt: float) -> None:
        if not (self.held or self.active):  # no wheel held now or before: every step of a car driven by effort
            return
        held, self.held = self.held, set()
        if held != self.active:
            self._take_over(held)
        if not held:
            return
        contacts = self._contacts()  # of the active wheels, the held ones
        touching = {c[0].index for c in contacts}
        for index, v in self.impulse.items():
            if index not in touching:
                v[:] = 0.0
        if not contacts:
            return
        client = self.client
        states = client.getLinkStates(self.body, [c[0].index for c in contacts], computeLinkVelocity=1,
                                      computeForwardKinematics=1)
        rows, slip, limits, spin, others = [], [], [], [], []
        for (wheel, point, normal, force, other, other_link), s in zip(contacts, states):
            axle = _rotate(s[5], wheel.axle)
            across = _sub(axle, _scale(normal, _dot(normal, axle)))
            if _dot(across, across) < 1e-12:  # the wheel lies flat on its side: any two directions of the plane
                across = _cross(normal, (1.0, 0.0, 0.0) if abs(normal[0]) < 0.9 else (0.0, 1.0, 0.0))
            across = _unit(across)
            rolling = _cross(normal, across)
            arm = _sub(point, s[0])
            velocity = _add(s[6], _cross(s[7], arm))
            other_mu, other_static = self._other(other, other_link)
            if not other_static:
                velocity = _sub(velocity, self._point_velocity(other, other_link, point))
            others.append(None if other_static else (other, other_link))
            for direction, mu in ((rolling, wheel.mu_roll), (across, wheel.mu_axle)):
                rows.append((point, direction))
                slip.append(_dot(velocity, direction))
                limits.append(mu * other_mu * force * dt)
            spin.append(_dot(arm, arm) / self.spin_inertia[wheel.index])
        inverse, scale = self._solver(tuple(sorted(touching)), rows, spin)
        self.steps += 1
        x = inverse @ (np.array(slip) / scale) / scale
        limits = np.array(limits)
        integral = np.concatenate([self.impulse[c[0].index] for c in contacts]) - BETA * x
        integral = np.clip(integral, -limits, limits)
        impulses = (np.clip(integral - ALPHA * x, -limits, limits) / dt).tolist()
        for k, ((wheel, point, *_), other) in enumerate(zip(contacts, others)):
            self.impulse[wheel.index][:] = integral[2 * k:2 * k + 2]
            f = _add(_scale(rows[2 * k][1], impulses[2 * k]), _scale(rows[2 * k + 1][1], impulses[2 * k + 1]))
            client.applyExternalForce(self.body, wheel.index, f, point, pb.WORLD_FRAME)
            if other is not None:
                client.applyExternalForce(other[0], other[1], _scale(f, -1.0), point, pb.WORLD_FRAME)


# 3-vectors as tuples: numpy's call overhead (~3 us a cross product) would be most of a step's cost
def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(a, k):
    return (a[0] * k, a[1] * k, a[2] * k)


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _unit(a):
    n = _dot(a, a) ** 0.5
    return (a[0] / n, a[1] / n, a[2] / n)
