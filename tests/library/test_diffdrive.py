"""Tests for wheelkin.diffdrive against independent values: a sympy rigid-body derivation,
C integer semantics from ctypes and exact fractions, hand calculations and properties."""

from __future__ import annotations

import ctypes
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import diffdrive as dd

W_MM, ENC = 85, 8043
finite = st.floats(-5.0, 5.0, allow_nan=False)
widths = st.floats(0.01, 2.0, allow_nan=False)
int16 = st.integers(-(2**15), 2**15 - 1)


# ------------------------------------------------------------------ sympy, independent


def _sympy_wheel_speeds():
    """Ground speed of each wheel contact point of a rigid body: v_P = v_c + omega x r_P."""
    v, w, W = sp.symbols("v omega W", real=True)
    v_c = sp.Matrix([v, 0, 0])
    omega = sp.Matrix([0, 0, w])
    r_left = sp.Matrix([0, W / 2, 0])  # y is left (REP-103)
    r_right = sp.Matrix([0, -W / 2, 0])
    left = (v_c + omega.cross(r_left))[0]
    right = (v_c + omega.cross(r_right))[0]
    return sp.lambdify((v, w, W), (left, right), "numpy")


SYMPY_SPEEDS = _sympy_wheel_speeds()


@settings(max_examples=60, deadline=None)
@given(finite, finite, widths)
def test_wheel_speeds_match_rigid_body_derivation(v, omega, width):
    expected = SYMPY_SPEEDS(v, omega, width)
    np.testing.assert_allclose(dd.wheel_speeds(v, omega, width), expected, atol=1e-12)


def test_wheel_speeds_steps_match_unit_derivation():
    """Derive the encoder-unit formula from SI with explicit unit factors in sympy."""
    v_steps, w_mrad, W_mm, enc = sp.symbols("v_s omega_m W_mm ENC", positive=True)
    v_si = v_steps / enc            # steps/s -> m/s
    w_si = w_mrad / 1000            # mrad/s -> rad/s
    W_si = W_mm / 1000              # mm -> m
    right_si = v_si + w_si * W_si / 2
    right_steps = sp.simplify(right_si * enc)
    assert sp.simplify(right_steps - (v_steps + w_mrad * W_mm / 2 * enc / 10**6)) == 0
    f = sp.lambdify((v_steps, w_mrad, W_mm, enc), right_steps)
    rng = np.random.default_rng(1)
    for _ in range(50):
        args = rng.uniform(-3000, 3000), rng.uniform(-5000, 5000), rng.uniform(50, 300), \
            rng.uniform(1000, 20000)
        _, right = dd.wheel_speeds_steps(*args)
        assert math.isclose(right, f(*args), rel_tol=1e-12, abs_tol=1e-9)


def test_hand_calculation_radon_ulzer():
    # 1 rad/s, W = 0.085 m: each wheel 0.0425 m/s relative to the midpoint = 341.8275 steps/s
    left, right = dd.wheel_speeds_steps(1000, 1000, W_MM, ENC)
    assert math.isclose(right - 1000, 0.0425 * 8043, rel_tol=1e-12)
    assert math.isclose(1000 - left, 0.0425 * 8043, rel_tol=1e-12)


# ------------------------------------------------------------------ properties


@settings(max_examples=60, deadline=None)
@given(finite, finite, widths)
def test_body_twist_inverts_wheel_speeds(v, omega, width):
    back = dd.body_twist(*dd.wheel_speeds(v, omega, width), width)
    np.testing.assert_allclose(back, (v, omega), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.floats(-3e4, 3e4), st.floats(-3e4, 3e4), st.floats(10, 500), st.floats(100, 5e4))
def test_body_twist_steps_inverts_wheel_speeds_steps(v, omega, w_mm, enc):
    back = dd.body_twist_steps(*dd.wheel_speeds_steps(v, omega, w_mm, enc), w_mm, enc)
    np.testing.assert_allclose(back, (v, omega), rtol=1e-9, atol=1e-6)


@settings(max_examples=40, deadline=None)
@given(finite, finite, widths)
def test_left_turn_mirrors_right_turn(v, omega, width):
    left, right = dd.wheel_speeds(v, omega, width)
    m_left, m_right = dd.wheel_speeds(v, -omega, width)
    assert math.isclose(left, m_right, abs_tol=1e-12)
    assert math.isclose(right, m_left, abs_tol=1e-12)


@settings(max_examples=40, deadline=None)
@given(finite, finite, widths)
def test_doubling_the_twist_doubles_the_wheel_speeds(v, omega, width):
    np.testing.assert_allclose(dd.wheel_speeds(2 * v, 2 * omega, width),
                               2 * np.array(dd.wheel_speeds(v, omega, width)), atol=1e-12)


def test_positive_omega_turns_left_right_wheel_faster():
    left, right = dd.wheel_speeds(0.1, 0.5, 0.085)
    assert right > left


def test_relative_speed_of_wheels_is_omega_times_W():
    left, right = dd.wheel_speeds(0.3, 2.0, 0.085)
    assert math.isclose(right - left, 2.0 * 0.085)          # one wheel relative to the other
    assert math.isclose(right - 0.3, 2.0 * 0.085 / 2)       # one wheel relative to the midpoint


def test_vectorised_and_broadcast():
    v = np.array([[0.1], [0.2]])
    omega = np.array([0.0, 1.0, -1.0])
    left, right = dd.wheel_speeds(v, omega, 0.1)
    assert left.shape == right.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            assert math.isclose(left[i, j], dd.wheel_speeds(v[i, 0], omega[j], 0.1)[0])
    assert isinstance(dd.wheel_speeds(0.1, 0.2, 0.1)[0], float)


# ------------------------------------------------------------------ the README as printed


@settings(max_examples=40, deadline=None)
@given(st.floats(-3e4, 3e4), st.floats(-3e4, 3e4))
def test_as_printed_halves_the_forward_speed_but_keeps_the_yaw_rate(v, omega):
    left, right = dd.wheel_speeds_steps_as_printed(v, omega, W_MM, ENC)
    v_got, w_got = dd.body_twist_steps(left, right, W_MM, ENC)
    assert math.isclose(v_got, v / 2, rel_tol=1e-9, abs_tol=1e-6)
    assert math.isclose(w_got, omega, rel_tol=1e-9, abs_tol=1e-6)


def test_as_printed_agrees_with_correct_formula_when_v_is_zero():
    np.testing.assert_allclose(dd.wheel_speeds_steps_as_printed(0, 1234, W_MM, ENC),
                               dd.wheel_speeds_steps(0, 1234, W_MM, ENC))


# ------------------------------------------------------------------ C integer semantics


def _c_int32(x: int) -> int:
    return ctypes.c_int32(x & 0xFFFFFFFF).value


def _c_int16(x: int) -> int:
    return ctypes.c_int16(x & 0xFFFF).value


def _c_div(a: int, b: int) -> int:
    return math.trunc(Fraction(a, b))


def _reference_int32(v: int, w: int, method: str, base=W_MM, enc=ENC):
    """An independent C-semantics model: ctypes wraparound, Fraction truncation."""
    overflow = False

    def mul(a, b):
        nonlocal overflow
        p = _c_int32(a * b)
        overflow |= p != a * b
        return p

    if method == "q16":
        k = round(Fraction(base * enc * 65536, 2_000_000))
        turn = (mul(abs(w), k) + 32768) >> 16
        turn = -turn if w < 0 else turn
        centre = v
    elif method == "readme_order":
        turn = _c_div(_c_div(mul(w, base), 2000) * enc, 1000)  # no overflow possible here
        centre = _c_div(v, 2)
    else:
        turn = _c_div(mul(mul(w, base), enc), 2_000_000)
        centre = _c_div(v, 2) if method == "firmware" else v
    left, right = centre - turn, centre + turn
    overflow |= _c_int16(left) != left or _c_int16(right) != right
    return _c_int16(left), _c_int16(right), overflow


@settings(max_examples=200, deadline=None)
@given(int16, int16, st.sampled_from(dd.INT32_METHODS))
def test_int32_model_matches_independent_c_model(v, w, method):
    got = dd.wheel_speeds_steps_int32(v, w, method=method)
    assert tuple(got) == _reference_int32(v, w, method)


def test_int32_overflow_bound_is_exact():
    limit = dd.int32_omega_limit(W_MM, ENC)
    assert limit * W_MM * ENC <= 2**31 - 1 < (limit + 1) * W_MM * ENC
    assert limit == 3141
    for method in ("firmware", "corrected"):
        assert not dd.wheel_speeds_steps_int32(0, limit, method=method).overflow
        assert not dd.wheel_speeds_steps_int32(0, -limit, method=method).overflow
        assert dd.wheel_speeds_steps_int32(0, limit + 1, method=method).overflow
        assert dd.wheel_speeds_steps_int32(0, -limit - 1, method=method).overflow
    # just past the bound the wrapped product flips the sign: the robot turns the wrong way
    left, right, _ = dd.wheel_speeds_steps_int32(0, limit + 1, method="corrected")
    assert right < 0 < left


def test_int32_corrected_is_within_one_step_below_the_bound():
    v = np.arange(-3000, 3001, 250)[:, None]
    w = np.arange(-3141, 3142, 17)[None, :]
    left, right, overflow = dd.wheel_speeds_steps_int32(v, w, method="corrected")
    exact_l, exact_r = dd.wheel_speeds_steps(v, w, W_MM, ENC)
    assert not overflow.any()
    assert np.max(np.abs(left - exact_l)) < 1 and np.max(np.abs(right - exact_r)) < 1


def test_int32_q16_never_overflows_and_rounds_to_nearest():
    w = np.arange(-(2**15), 2**15, 7)
    left, right, overflow = dd.wheel_speeds_steps_int32(0, w, method="q16")
    _, exact_r = dd.wheel_speeds_steps(0, w, W_MM, ENC)
    assert not overflow.any()
    k_error = abs(22402 - Fraction(W_MM * ENC * 65536, 2_000_000)) / 65536  # K is rounded
    assert np.max(np.abs(right - exact_r)) <= 0.5 + float(k_error) * 2**15 + 1e-9
    np.testing.assert_array_equal(left, -right)           # symmetric in omega


def test_int32_readme_order_dead_band_and_steps():
    w = np.arange(-200, 201)
    _, right, _ = dd.wheel_speeds_steps_int32(0, w, method="readme_order")
    assert np.all(right[np.abs(w) <= 23] == 0) and np.all(right[np.abs(w) >= 24] != 0)
    assert set(np.unique(np.abs(right))) <= {8 * k + k * 43 // 1000 for k in range(10)}


def test_int32_firmware_halves_v():
    left, right, _ = dd.wheel_speeds_steps_int32(1001, 0, method="firmware")
    assert left == right == 500  # C: 1001 / 2 == 500


def test_int32_result_narrowed_to_int16():
    _, right, overflow = dd.wheel_speeds_steps_int32(32767, 3000, method="corrected")
    assert overflow  # 32767 + 1025 does not fit int16
    assert right == _c_int16(32767 + 1025)


@settings(max_examples=100, deadline=None)
@given(st.integers(-(2**70), 2**70), st.sampled_from([8, 16, 32, 64]))
def test_wrap_int_matches_ctypes(x, bits):
    ctype = {8: ctypes.c_int8, 16: ctypes.c_int16, 32: ctypes.c_int32, 64: ctypes.c_int64}[bits]
    assert dd.wrap_int(x, bits) == ctype(x & ((1 << bits) - 1)).value


@settings(max_examples=100, deadline=None)
@given(st.integers(-(10**12), 10**12), st.integers(-(10**6), 10**6).filter(bool))
def test_c_divide_truncates_toward_zero(a, b):
    assert dd.c_divide(a, b) == math.trunc(Fraction(a, b))


def test_c_divide_vectorised():
    np.testing.assert_array_equal(dd.c_divide([-7, 7, -1], 2), [-3, 3, 0])


def test_q16_factor_by_hand():
    assert dd.q16_turn_factor(85, 8043) == 22402  # 85 * 8043 * 65536 / 2e6 = 22402.007


# ------------------------------------------------------------------ speedometer


def _encoder(speed_steps_per_s, times, phase=0.3):
    return np.floor(speed_steps_per_s * times + phase)


def test_speedometer_fixed_window_within_one_step_per_window():
    t = np.arange(0, 2.0, 0.001)
    true = 402.15  # 0.05 m/s on the Radon Ulzer
    est = dd.speed_from_counts(_encoder(true, t), t, window=0.010)
    settled = est[t > 0.02]
    assert np.max(np.abs(settled - true)) <= 100 + 1e-6     # 1 step / 10 ms
    assert set(np.round(np.unique(settled))) <= {400.0, 500.0}
    assert abs(np.mean(settled) - true) < 5                 # unbiased on average


def test_speedometer_min_steps_bounds_relative_error():
    t = np.arange(0, 3.0, 0.010)  # a 10 ms task, as on a microcontroller
    true = 80.43  # 0.01 m/s: under one step per 10 ms
    fixed = dd.speed_from_counts(_encoder(true, t), t, window=0.010)
    waiting = dd.speed_from_counts(_encoder(true, t), t, window=0.0, min_steps=6)
    late = t > 0.5
    assert np.max(np.abs(fixed[late] - true)) / true > 0.5       # reads 0 or 100 steps/s
    assert np.max(np.abs(waiting[late] - true)) / true < 1 / 6 + 0.02


def test_speedometer_every_estimate_uses_min_steps():
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.005, 0.015, 400))
    counts = np.cumsum(rng.integers(0, 3, 400))
    est, updated = dd.speed_from_counts(counts, t, window=0.0, min_steps=5,
                                        return_updates=True)
    assert updated.shape == est.shape and updated.sum() > 20
    assert np.all(np.diff(est)[~updated[1:]] == 0)  # held between updates
    last = 0
    for i in np.flatnonzero(updated):
        assert counts[i] - counts[last] >= 5
        assert math.isclose(est[i], (counts[i] - counts[last]) / (t[i] - t[last]))
        last = i


def test_speedometer_plain_difference_and_columns():
    t = np.array([0.0, 0.1, 0.3, 0.4])
    c = np.array([[0, 0], [2, -1], [6, -3], [7, -3]])
    est = dd.speed_from_counts(c, t, window=0.0)
    np.testing.assert_allclose(est[1:], np.diff(c, axis=0) / np.diff(t)[:, None])
    assert est.shape == c.shape


def test_speedometer_timeout_reads_zero_when_stopped():
    t = np.arange(0, 1.0, 0.01)
    counts = np.where(t < 0.5, np.floor(400 * t), 200)
    held = dd.speed_from_counts(counts, t, window=0.0, min_steps=6)
    timed = dd.speed_from_counts(counts, t, window=0.0, min_steps=6, timeout=0.1)
    assert held[-1] > 300          # without a timeout the last speed is held
    assert timed[-1] == 0.0


def test_speed_resolution_and_time_to_count_by_hand():
    assert math.isclose(dd.speed_resolution(0.01, 8043), 1 / 80.43)
    assert math.isclose(dd.time_to_count(6, 0.05, 8043), 6 / 402.15)
    assert math.isclose(dd.time_to_count(6, -0.05, 8043), 6 / 402.15)


# ------------------------------------------------------------------ skid steer, constants


def test_skid_steer_pairs_and_inverse():
    fl, fr, rl, rr = dd.skid_steer_wheel_speeds(0.3, -1.5, 0.12)
    assert fl == rl and fr == rr and fl > fr  # a right turn: left side faster
    np.testing.assert_allclose(dd.skid_steer_body_twist(fl, fr, rl, rr, 0.12), (0.3, -1.5))


def test_constants():
    c = dd.RADON_ULZER_CONSTANTS
    assert (c.track_width_mm, c.steps_per_m) == (85, 8043)
    assert 12 * 75810 * 1000 // 113097 == c.steps_per_m  # the firmware's integer formula
    with pytest.raises(ValueError, match="track_width_mm"):
        dd.DiffDriveConstants(0, 8043)
    with pytest.raises(ValueError, match="steps_per_m"):
        dd.DiffDriveConstants(85, 8043.5)


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: dd.wheel_speeds(float("nan"), 0, 0.1), "v"),
        (lambda: dd.wheel_speeds(0, [1, float("inf")], 0.1), "omega"),
        (lambda: dd.wheel_speeds(0, 0, 0.0), "track_width"),
        (lambda: dd.wheel_speeds(0, 0, -1), "track_width"),
        (lambda: dd.wheel_speeds([1, 2], [1, 2, 3], 0.1), "v and omega"),
        (lambda: dd.body_twist("fast", 0, 0.1), "v_left"),
        (lambda: dd.body_twist(0, 0, float("nan")), "track_width"),
        (lambda: dd.wheel_speeds_steps(0, 0, 0, 8043), "track_width_mm"),
        (lambda: dd.wheel_speeds_steps(0, 0, 85, -1), "steps_per_m"),
        (lambda: dd.wheel_speeds_steps([1, 2], [1, 2, 3], 85, 8043), "v_steps_per_s"),
        (lambda: dd.body_twist_steps(float("nan"), 0, 85, 8043), "left"),
        (lambda: dd.wheel_speeds_steps_as_printed(0, 0, 85, 0), "steps_per_m"),
        (lambda: dd.wheel_speeds_steps_int32(0, 0, method="float"), "method"),
        (lambda: dd.wheel_speeds_steps_int32(0.5, 0), "v_steps_per_s"),
        (lambda: dd.wheel_speeds_steps_int32(0, 40000), "omega_mrad_per_s"),
        (lambda: dd.wheel_speeds_steps_int32(0, float("nan")), "omega_mrad_per_s"),
        (lambda: dd.wheel_speeds_steps_int32(0, 0, 85.5, 8043), "track_width_mm"),
        (lambda: dd.wheel_speeds_steps_int32(0, 0, 85, 0), "steps_per_m"),
        (lambda: dd.wheel_speeds_steps_int32([1, 2], [1, 2, 3]), "v_steps_per_s"),
        (lambda: dd.wrap_int(1.5), "values"),
        (lambda: dd.wrap_int(1, bits=12), "bits"),
        (lambda: dd.c_divide(1, 0), "denominator"),
        (lambda: dd.int32_omega_limit(0, 8043), "track_width_mm"),
        (lambda: dd.q16_turn_factor(85, -2), "steps_per_m"),
        (lambda: dd.speed_resolution(0, 8043), "window"),
        (lambda: dd.time_to_count(6, 0.0, 8043), "speed"),
        (lambda: dd.time_to_count(0, 0.1, 8043), "min_steps"),
        (lambda: dd.speed_from_counts([0, 1], [0.0, 0.0], 0.0), "times"),
        (lambda: dd.speed_from_counts([0, 1], [0.0, 0.1, 0.2], 0.0), "times"),
        (lambda: dd.speed_from_counts([[[0]]], [0.0], 0.0), "counts"),
        (lambda: dd.speed_from_counts([0, float("nan")], [0.0, 0.1], 0.0), "counts"),
        (lambda: dd.speed_from_counts([0, 1], [0.0, 0.1], -0.1), "window"),
        (lambda: dd.speed_from_counts([0, 1], [0.0, 0.1], 0.0, min_steps=1.5), "min_steps"),
        (lambda: dd.speed_from_counts([0, 1], [0.0, 0.1], 0.2, timeout=0.1), "timeout"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# --------------------------------------------------------------------------------------------
# named results and desaturation (WPILib's DifferentialDriveWheelSpeeds.desaturate)

def test_results_are_named_tuples_that_unpack_as_before():
    ws = dd.wheel_speeds(0.2, 1.0, 0.085)
    assert isinstance(ws, dd.WheelSpeeds) and isinstance(ws, tuple)
    left, right = ws
    assert (left, right) == (ws.left, ws.right) == pytest.approx((0.1575, 0.2425))
    tw = dd.body_twist(left, right, 0.085)
    assert tw.v == pytest.approx(0.2) and tw.omega == pytest.approx(1.0)
    four = dd.skid_steer_wheel_speeds(0.5, 1.0, 0.12)
    assert (four.fl, four.fr, four.rl, four.rr) == pytest.approx((0.44, 0.56, 0.44, 0.56))
    assert dd.skid_steer_body_twist(*four, 0.12).omega == pytest.approx(1.0)


@settings(max_examples=200)
@given(st.floats(-10, 10), st.floats(-10, 10), st.floats(0.01, 20))
def test_desaturate_is_wpilibs(left, right, limit):
    biggest = max(abs(left), abs(right))
    want = (left / biggest * limit, right / biggest * limit) if biggest > limit else (left,
                                                                                       right)
    got = dd.desaturate(left, right, limit)
    assert got == pytest.approx(want, rel=1e-15, abs=1e-300)
    assert max(abs(got.left), abs(got.right)) <= limit * (1 + 1e-15)
    if biggest > 0 and got.left != 0:  # the ratio (the curvature) is kept
        assert got.right / got.left == pytest.approx(right / left, rel=1e-12)


def test_desaturate_vectorised_and_bad_input():
    out = dd.desaturate([1.0, 4.0], [3.0, -1.0], 2.0)
    np.testing.assert_allclose(out.left, [2 / 3, 2.0])
    np.testing.assert_allclose(out.right, [2.0, -0.5])
    for args, name in (((math.nan, 1.0, 2.0), "v_left"), ((1.0, "x", 2.0), "v_right"),
                       ((1.0, 1.0, 0.0), "max_speed"), ((1.0, 1.0, True), "max_speed"),
                       (([1.0, 2.0], [1.0, 2.0, 3.0], 2.0), "v_left")):
        with pytest.raises(ValueError, match=name):
            dd.desaturate(*args)
