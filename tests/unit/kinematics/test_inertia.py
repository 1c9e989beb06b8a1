"""kinematics/inertia.py: ODE's positive-definiteness test (dInvertPDMatrix's Cholesky) and PyBullet's importer's."""
import math

import numpy as np
import pytest

from racebot_sim_bridge.kinematics import inertia


@pytest.mark.parametrize('six, ode, bullet_zeroes', [
    ((1e-3, 0, 0, 1e-3, 0, 1e-3), True, False),
    ((1e-3, 0, 0, 1e-3, 0, 5e-3), True, True),      # a moment larger than the other two: ODE takes it
    ((1e-3, 0, 0, -1e-3, 0, 1e-3), False, True),    # negative
    ((0, 0, 0, 0, 0, 0), False, False),             # zero: PyBullet keeps 0, ODE falls back to the identity
    ((1e-3, 0, 5e-3, 1e-3, 0, 1e-3), False, True),  # products too large: indefinite
    ((1, 1, 0, 1, 0, 1), False, True),              # singular (eigenvalues 0, 1, 2)
    ((1e-9, 0, 0, 1e-9, 0, 1e-9), True, False),     # tiny is fine
])
def test_ode_and_bullet_verdicts(six, ode, bullet_zeroes):
    rows = inertia.tensor(*six)
    assert inertia.ode_positive_definite(rows) is ode
    assert inertia.bullet_importer_zeroes(rows) is bullet_zeroes


def test_principal_axes_give_the_tensor_back():
    c, s = math.cos(0.4), math.sin(0.4)
    turn = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    rows = turn @ np.diag([1e-3, 2e-3, 7e-3]) @ turn.T
    moments, (roll, pitch, yaw) = inertia.principal_axes(rows)
    assert moments == pytest.approx((1e-3, 2e-3, 7e-3))
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    r = (np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]) @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
         @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]]))
    assert r @ np.diag(moments) @ r.T == pytest.approx(rows, abs=1e-15)
