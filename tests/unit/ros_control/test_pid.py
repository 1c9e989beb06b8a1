"""Unit tests of racebot_sim_bridge.ros_control.pid (control_toolbox semantics)."""

import math

import pytest
from hypothesis import given, settings, strategies as st

from racebot_sim_bridge.ros_control.pid import Pid

WHERE = '/racebot/left_rear_wheel_velocity_controller/pid'


def test_p_only():
    pid = Pid(2.0)
    assert pid.compute(1.5, 0.01) == pytest.approx(3.0)
    assert pid.compute(-0.5, 0.01) == pytest.approx(-1.0)
    assert pid.command == pytest.approx(-1.0)
    assert pid.p_error == -0.5


def test_derivative_is_zero_on_first_step_then_difference_quotient():
    pid = Pid(0.0, d=1.0)
    assert pid.compute(5.0, 0.1) == 0.0
    assert pid.d_error == 0.0
    assert pid.compute(6.0, 0.1) == pytest.approx(10.0)
    assert pid.d_error == pytest.approx(10.0)


@pytest.mark.parametrize('dt', [0.0, -0.01, math.nan, math.inf])
def test_non_positive_or_non_finite_dt_returns_zero_and_keeps_state(dt):
    pid = Pid(1.0, i=1.0, d=1.0, i_clamp_min=-10.0, i_clamp_max=10.0)
    pid.compute(1.0, 0.5)
    before = (pid.p_error, pid.i_error, pid.d_error, pid.command)
    assert pid.compute(3.0, dt) == 0.0
    assert (pid.p_error, pid.i_error, pid.d_error, pid.command) == before


@pytest.mark.parametrize('error', [math.nan, math.inf, -math.inf])
def test_non_finite_error_returns_zero_and_keeps_state(error):
    pid = Pid(1.0, i=1.0, d=1.0, i_clamp_min=-10.0, i_clamp_max=10.0)
    pid.compute(1.0, 0.5)
    before = (pid.p_error, pid.i_error, pid.d_error, pid.command)
    assert pid.compute(error, 0.5) == 0.0
    assert (pid.p_error, pid.i_error, pid.d_error, pid.command) == before
    # The previous error is untouched too: the next derivative uses 1.0.
    pid.compute(2.0, 0.5)
    assert pid.d_error == pytest.approx(2.0)


def test_integral_accumulates_inside_the_clamp():
    pid = Pid(0.0, i=2.0, i_clamp_min=-100.0, i_clamp_max=100.0)
    pid.compute(1.0, 0.5)
    assert pid.compute(1.0, 0.5) == pytest.approx(2.0)  # 2 * (0.5 + 0.5)
    assert pid.i_error == pytest.approx(1.0)


def test_integral_term_clamped_without_antiwindup_state_keeps_growing():
    pid = Pid(0.0, i=1.0, i_clamp_min=-0.5, i_clamp_max=0.5)
    for _ in range(10):
        out = pid.compute(1.0, 1.0)
    assert out == pytest.approx(0.5)
    assert pid.i_error == pytest.approx(10.0)  # wound up
    # Winding down takes as long as winding up did: still at the clamp after 9 steps back.
    for _ in range(9):
        out = pid.compute(-1.0, 1.0)
    assert out == pytest.approx(0.5)
    assert pid.i_error == pytest.approx(1.0)


def test_integral_state_clamped_with_antiwindup():
    pid = Pid(0.0, i=2.0, i_clamp_min=-1.0, i_clamp_max=1.0, antiwindup=True)
    for _ in range(10):
        out = pid.compute(1.0, 1.0)
    assert out == pytest.approx(1.0)
    assert pid.i_error == pytest.approx(0.5)  # i_clamp_max / i
    # No wind-up: one step back leaves the clamp at once.
    assert pid.compute(-0.25, 1.0) == pytest.approx(2.0 * 0.25)


@pytest.mark.parametrize('error', [1.0, -1.0])
def test_antiwindup_bounds_are_sorted_for_a_negative_i_gain(error):
    pid = Pid(0.0, i=-2.0, i_clamp_min=-1.0, i_clamp_max=1.0, antiwindup=True)
    for _ in range(10):
        out = pid.compute(error, 1.0)
    assert pid.i_error == pytest.approx(0.5 * error)  # bounds (1 / -2, -1 / -2), sorted
    assert out == pytest.approx(-1.0 * error)


@pytest.mark.parametrize('antiwindup', [False, True])
def test_zero_i_clamp_kills_the_integral_term(antiwindup):
    pid = Pid.from_params({'p': 0.0, 'i': 5.0, 'antiwindup': antiwindup}, WHERE)
    for _ in range(5):
        assert pid.compute(1.0, 0.1) == 0.0


def test_reset_clears_integral_previous_error_and_command():
    pid = Pid(1.0, i=1.0, d=1.0, i_clamp_min=-10.0, i_clamp_max=10.0)
    pid.compute(1.0, 1.0)
    pid.compute(3.0, 1.0)
    pid.reset()
    assert (pid.p_error, pid.i_error, pid.d_error, pid.command) == (0.0, 0.0, 0.0, 0.0)
    # First step after reset: no derivative, integral starts from zero.
    assert pid.compute(2.0, 1.0) == pytest.approx(2.0 + 2.0)


def test_compute_with_error_dot_uses_the_given_derivative():
    pid = Pid(1.0, d=0.5)
    assert pid.compute_with_error_dot(1.0, -4.0, 0.01) == pytest.approx(1.0 - 2.0)
    assert pid.d_error == -4.0
    assert pid.compute_with_error_dot(1.0, math.nan, 0.01) == 0.0
    assert pid.d_error == -4.0


def test_from_params_i_clamp_sets_symmetric_bounds():
    pid = Pid.from_params({'p': 1, 'i': 2, 'd': 3, 'i_clamp': -4.0}, WHERE)
    assert (pid.p, pid.i, pid.d) == (1.0, 2.0, 3.0)
    assert (pid.i_clamp_min, pid.i_clamp_max, pid.i_clamp) == (-4.0, 4.0, 4.0)
    assert pid.antiwindup is False


def test_from_params_min_max_override_i_clamp_and_are_forced_to_sign():
    pid = Pid.from_params({'p': 1, 'i_clamp': 4.0, 'i_clamp_min': 2.0}, WHERE)
    assert (pid.i_clamp_min, pid.i_clamp_max) == (-2.0, 4.0)
    pid = Pid.from_params({'p': 1, 'i_clamp': 4.0, 'i_clamp_max': -1.0, 'antiwindup': True},
                          WHERE)
    assert (pid.i_clamp_min, pid.i_clamp_max, pid.antiwindup) == (-4.0, 1.0, True)


def test_from_params_missing_p_names_the_namespace():
    with pytest.raises(ValueError, match=r"^/racebot/left_rear_wheel_velocity_controller/pid: "
                                         r"no 'p' gain given; set pid: \{p: \.\.\.\}"):
        Pid.from_params({'i': 1.0}, WHERE)


@pytest.mark.parametrize('params, key', [
    ({'p': 'fast'}, 'p'),
    ({'p': 1.0, 'd': math.nan}, 'd'),
    ({'p': 1.0, 'i': math.inf}, 'i'),
    ({'p': True}, 'p'),
    ({'p': 1.0, 'i_clamp_max': None}, 'i_clamp_max'),
    ({'p': 1.0, 'antiwindup': 'yes'}, 'antiwindup'),
])
def test_from_params_rejects_bad_values_naming_the_key(params, key):
    with pytest.raises(ValueError, match='^%s/%s: ' % (WHERE, key)):
        Pid.from_params(params, WHERE)


def test_from_params_rejects_a_non_dictionary():
    with pytest.raises(ValueError, match=WHERE):
        Pid.from_params(3.0, WHERE)


def test_constructor_rejects_inverted_clamp():
    with pytest.raises(ValueError, match='i_clamp_min'):
        Pid(1.0, i_clamp_min=1.0, i_clamp_max=-1.0)


_finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)
_gain = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(gains=st.tuples(_gain, _gain, _gain), clamp=st.floats(0, 1e3), antiwindup=st.booleans(),
       steps=st.lists(st.tuples(_finite, st.floats(min_value=1e-6, max_value=1.0)), max_size=30))
def test_output_is_finite_for_finite_inputs(gains, clamp, antiwindup, steps):
    pid = Pid(*gains, i_clamp_min=-clamp, i_clamp_max=clamp, antiwindup=antiwindup)
    for error, dt in steps:
        assert math.isfinite(pid.compute(error, dt))
        assert abs(pid.i_term) <= clamp * (1 + 1e-12)  # rounding of i * (clamp / i)
