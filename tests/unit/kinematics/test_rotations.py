"""rotations: the package's quaternion, roll-pitch-yaw and transform maths, checked against PyBullet's own
(getQuaternionFromEuler, getEulerFromQuaternion, multiplyTransforms, invertTransform, getMatrixFromQuaternion)
on random inputs drawn from a fixed seed."""
import math
import random

import pybullet as pb
import pytest
from hypothesis import given, settings, strategies as st

from racebot_sim_bridge.kinematics import rotations

TOL = 1e-9  # our own round trips, in double precision
PB = 1e-5  # against multiplyTransforms and friends: PyBullet computes them in single precision
N = 500
HALF_PI = math.pi / 2


def _random_rpy(rng):
    # pitch kept off +-pi/2, where roll and yaw are not separable (gimbal lock)
    return (rng.uniform(-math.pi, math.pi), rng.uniform(-1.5, 1.5), rng.uniform(-math.pi, math.pi))


def _random_quaternion(rng):
    q = [rng.gauss(0.0, 1.0) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def _random_vector(rng, scale=5.0):
    return tuple(rng.uniform(-scale, scale) for _ in range(3))


def _same_rotation(a, b, tol=TOL):
    """q and -q are the same rotation."""
    sign = 1.0 if sum(x * y for x, y in zip(a, b)) >= 0.0 else -1.0
    return all(abs(x - sign * y) < tol for x, y in zip(a, b))


def _close(a, b, tol=TOL):
    return all(abs(x - y) < tol for x, y in zip(a, b))


@pytest.fixture(name='rng')
def _rng():
    return random.Random(20261123)


def test_rpy_to_quaternion_is_pybullets(rng):
    for _ in range(N):
        rpy = _random_rpy(rng)
        assert _same_rotation(rotations.rpy_to_quaternion(*rpy), pb.getQuaternionFromEuler(rpy)), rpy


def test_quaternion_to_rpy_is_pybullets_and_inverts_rpy_to_quaternion(rng):
    for _ in range(N):
        rpy = _random_rpy(rng)
        q = pb.getQuaternionFromEuler(rpy)
        assert _close(rotations.quaternion_to_rpy(q), pb.getEulerFromQuaternion(q), 1e-7), rpy
        assert _close(rotations.quaternion_to_rpy(rotations.rpy_to_quaternion(*rpy)), rpy), rpy
        assert rotations.yaw_of(q) == pytest.approx(rpy[2], abs=TOL)


def test_quaternion_to_rpy_at_gimbal_lock_stays_a_number():
    # rounding puts 2 (w y - z x) just above 1 for a pitch of exactly pi/2
    q = rotations.rpy_to_quaternion(0.0, math.pi / 2, 0.0)
    q = tuple(c * (1.0 + 1e-15) for c in q)
    assert rotations.quaternion_to_rpy(q)[1] == pytest.approx(math.pi / 2)


def test_quaternion_multiply_is_pybullets_composition(rng):
    for _ in range(N):
        a, b = _random_quaternion(rng), _random_quaternion(rng)
        expected = pb.multiplyTransforms((0, 0, 0), a, (0, 0, 0), b)[1]
        assert _same_rotation(rotations.quaternion_multiply(a, b), expected, PB)


def test_rotate_and_rotate_back_are_pybullets(rng):
    for _ in range(N):
        q, v = _random_quaternion(rng), _random_vector(rng)
        turned = pb.multiplyTransforms((0, 0, 0), q, v, (0, 0, 0, 1))[0]
        assert _close(rotations.rotate(q, v), turned, PB)
        assert _close(rotations.rotate_back(q, turned), v, PB)
        assert _close(rotations.rotate_back(q, rotations.rotate(q, v)), v)
        assert _same_rotation(rotations.conjugate(q), pb.invertTransform((0, 0, 0), q)[1], PB)


def test_matrix_is_pybullets(rng):
    for _ in range(N):
        q = _random_quaternion(rng)
        rows = rotations.matrix(q)
        assert _close([c for row in rows for c in row], pb.getMatrixFromQuaternion(q), PB)  # row-major
        v = _random_vector(rng)
        assert _close([sum(r * c for r, c in zip(row, v)) for row in rows], rotations.rotate(q, v))


def test_compose_and_inverse_are_pybullets(rng):
    for _ in range(N):
        a = (_random_vector(rng), _random_quaternion(rng))
        b = (_random_vector(rng), _random_quaternion(rng))
        p, q = rotations.compose(a, b)
        ep, eq = pb.multiplyTransforms(a[0], a[1], b[0], b[1])
        assert _close(p, ep, PB) and _same_rotation(q, eq, PB)
        ip, iq = rotations.inverse(a)
        ep, eq = pb.invertTransform(*a)
        assert _close(ip, ep, PB) and _same_rotation(iq, eq, PB)
        p, q = rotations.compose(rotations.inverse(a), a)
        assert _close(p, (0, 0, 0)) and _same_rotation(q, rotations.IDENTITY)


def test_six_tuple_poses_are_taken_as_xyz_rpy(rng):
    for _ in range(N):
        xyz, rpy = _random_vector(rng), _random_rpy(rng)
        b = (_random_vector(rng), _random_quaternion(rng))
        six = xyz + rpy
        p, q = rotations.as_transform(six)
        assert p == xyz and _same_rotation(q, pb.getQuaternionFromEuler(rpy))
        assert _close(rotations.as_xyz_rpy((p, q)), six)
        p, q = rotations.compose(six, b)
        ep, eq = pb.multiplyTransforms(xyz, pb.getQuaternionFromEuler(rpy), b[0], b[1])
        assert _close(p, ep, PB) and _same_rotation(q, eq, PB)


def test_as_transform_gives_floats():
    p, q = rotations.as_transform(((1, 2, 3), (0, 0, 0, 1)))
    assert all(type(c) is float for c in p + q)


def test_rpy_is_fixed_axis_xyz():
    # R = Rz(yaw) Ry(pitch) Rx(roll): roll 90 then yaw 90 sends y to z, then z stays z.
    q = rotations.rpy_to_quaternion(HALF_PI, 0.0, HALF_PI)
    assert rotations.rotate(q, (0.0, 1.0, 0.0)) == pytest.approx((0.0, 0.0, 1.0), abs=1e-12)
    assert rotations.rotate(q, (1.0, 0.0, 0.0)) == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)


def test_compose_of_six_tuples_by_hand():
    xyz, _ = rotations.compose((1, 0, 0, 0, 0, HALF_PI), (1, 0, 0, 0, 0, 0))
    assert xyz == pytest.approx((1.0, 1.0, 0.0))
    # Rotations do not commute: roll 90 of the parent, then yaw 90 of the child.
    _, quat = rotations.compose((0, 0, 0, HALF_PI, 0, 0), (0, 0, 0, 0, 0, HALF_PI))
    assert rotations.rotate(quat, (1.0, 0.0, 0.0)) == pytest.approx((0.0, 0.0, 1.0), abs=1e-12)


@settings(max_examples=200, deadline=None)
@given(st.floats(-3.1, 3.1), st.floats(-1.5, 1.5), st.floats(-3.1, 3.1))
def test_rpy_round_trip(roll, pitch, yaw):
    # Angles are unique for |pitch| < pi/2 and roll, yaw in (-pi, pi).
    back = rotations.quaternion_to_rpy(rotations.rpy_to_quaternion(roll, pitch, yaw))
    assert back == pytest.approx((roll, pitch, yaw), abs=1e-9)
