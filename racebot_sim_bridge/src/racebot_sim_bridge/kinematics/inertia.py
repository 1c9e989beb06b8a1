"""Inertia tensors as Gazebo classic's ODE and PyBullet's URDF importer take them. Plain maths: no rospy, no PyBullet.

Gazebo 11 hands ODE a link's inertia unchecked (physics/Inertial.cc keeps the six numbers; ode/ODELink.cc
UpdateMass calls dMassSetParameters, whose dMassCheck answer nobody reads, then dBodySetMass). dBodySetMass
(deps/opende/src/ode.cpp) keeps the tensor and inverts it with dInvertPDMatrix, a Cholesky factorisation
(matrix.cpp _dFactorCholesky); when a pivot is <= 0 the inverse inertia is set to the identity: the body turns
as if its inertia were 1 kg m^2 about every axis. PyBullet's URDF importer (BulletUrdfImporter.cpp
getMassAndInertia2) instead zeroes every principal moment when one is negative or larger than the sum of the
other two ("Bad inertia tensor properties"), which also zeroes tensors ODE takes as they are.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ['IDENTITY', 'KEYS', 'tensor', 'ode_positive_definite', 'not_positive_definite', 'bullet_importer_zeroes',
           'principal_axes']

KEYS = ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')
IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)  # in KEYS' order: what ODE's inverse falls back to


def tensor(ixx: float, ixy: float, ixz: float, iyy: float, iyz: float, izz: float) -> list[list[float]]:
    """The symmetric 3x3 tensor (rows) of the six numbers, as dMassSetParameters fills it."""
    return [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]


def ode_positive_definite(rows) -> bool:
    """Whether ODE's dInvertPDMatrix inverts the symmetric 3x3 `rows`: _dFactorCholesky's pivots, in its order,
    reading the lower triangle, all > 0. When not, dBodySetMass uses the identity as the inverse inertia.
    (A NaN pivot counts as a failure here; ODE would carry it on.)"""
    low = [[0.0] * 3 for _ in range(3)]
    for i in range(3):
        for j in range(i):
            low[i][j] = (float(rows[i][j]) - sum(low[i][k] * low[j][k] for k in range(j))) / low[j][j]
        pivot = float(rows[i][i]) - sum(low[i][k] * low[i][k] for k in range(i))
        if not pivot > 0.0:
            return False
        low[i][i] = math.sqrt(pivot)
    return True


def not_positive_definite(model: str, link: str, values, mass: float) -> str:
    """The one warning for a link whose inertia (`values`, in KEYS' order) ODE cannot invert."""
    return ("model '%s' link '%s': its inertia (%s; mass %g kg) is not positive definite (a moment about some axis is "
            "zero or negative). Gazebo/ODE uses the identity inertia (1 kg m^2 about each axis) for such a link "
            "(dBodySetMass), and so does racebot; give the link a real inertia"
            % (model, link, ', '.join('%s %g' % kv for kv in zip(KEYS, values)), mass))


def bullet_importer_zeroes(rows) -> bool:
    """Whether PyBullet's URDF importer would zero this inertia: a principal moment negative or larger than the
    sum of the other two (it diagonalises the tensor first when it has products of inertia)."""
    a, b, c = np.linalg.eigvalsh(np.array(rows, dtype=float))
    return bool(min(a, b, c) < 0.0 or a > b + c or b > a + c or c > a + b)


def principal_axes(rows) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """(principal moments, roll-pitch-yaw of the axes that carry them) of a symmetric 3x3 tensor: R diag R^T,
    R a proper rotation (URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll))."""
    moments, axes = np.linalg.eigh(np.array(rows, dtype=float))
    if np.linalg.det(axes) < 0.0:
        axes[:, 2] = -axes[:, 2]
    roll = math.atan2(axes[2, 1], axes[2, 2])
    pitch = math.asin(max(-1.0, min(1.0, -axes[2, 0])))
    yaw = math.atan2(axes[1, 0], axes[0, 0])
    return tuple(float(m) for m in moments), (roll, pitch, yaw)
