"""The arc kernel, the angle wrap and C's integer division against independent values.

The reference for the arc factors and the arc step is 50-digit arithmetic (mpmath) at the
exact binary value of each float input; for C's division, exact rational arithmetic; for the
wrap, 50-digit reduction modulo 2π.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import _kernels as k

EPS = float(np.finfo(float).eps)
#: The bound stated in wheelkin._kernels: both arc factors within 2 eps (relative) of the
#: exact values for every normal float turn, on both branches and on both code paths.
BOUND = 2 * EPS


def _turns() -> np.ndarray:
    rng = np.random.default_rng(12)
    t = k.SERIES_THRESHOLD
    phis = np.concatenate([
        np.geomspace(1e-300, 1e3, 1500),
        rng.uniform(-60.0, 60.0, 1500),
        t * (1 + np.linspace(-1e-6, 1e-6, 41)),
        [t, np.nextafter(t, 0.0), np.nextafter(t, 1.0), math.pi, 2 * math.pi, 1e-4, 1.0],
    ])
    return np.concatenate([phis, -phis])


def _exact_factors(p: float) -> tuple[mpmath.mpf, mpmath.mpf]:
    big = mpmath.mpf(p)  # the float's exact binary value
    return mpmath.sin(big) / big, 2 * mpmath.sin(big / 2) ** 2 / big


def _rel(got: float, want: mpmath.mpf) -> float:
    return float(abs((mpmath.mpf(got) - want) / want))


def test_arc_factors_within_the_stated_bound_of_50_digit_values():
    mpmath.mp.dps = 50
    phis = _turns()
    a_arr, b_arr = k.arc_factors(phis)  # the array path
    worst = 0.0
    for p, a2, b2 in zip(phis.tolist(), a_arr.tolist(), b_arr.tolist(), strict=True):
        a1, b1 = k.arc_factors(p)  # the float path
        assert type(a1) is float and type(b1) is float
        wa, wb = _exact_factors(p)
        worst = max(worst, _rel(a1, wa), _rel(b1, wb), _rel(a2, wa), _rel(b2, wb))
    assert worst <= BOUND, f"worst relative error {worst / EPS:.2f} eps"


def test_arc_factors_at_zero_and_below_the_normal_range():
    assert k.arc_factors(0.0) == (1.0, 0.0)
    a, b = k.arc_factors(np.array([0.0, -0.0]))
    assert a.tolist() == [1.0, 1.0] and b.tolist() == [0.0, 0.0]
    # a subnormal turn: a is 1, b is phi/2 rounded (no NaN, no division by zero)
    a, b = k.arc_factors(5e-324)
    assert a == 1.0 and abs(b) <= 5e-324


def test_series_and_closed_form_meet_at_the_threshold():
    t = k.SERIES_THRESHOLD
    below, above = k.arc_factors(np.nextafter(t, 0.0)), k.arc_factors(t)
    assert abs(below[0] - above[0]) <= 2 * EPS
    assert abs(below[1] - above[1]) <= 2 * EPS * above[1] + 1e-20  # b ~ t/2, its slope 1/2


def _exact_step(x, y, th, ds, dth):
    """The end of the circle about the ICR, in enough digits that its cancellation (of about
    -log10|dth| digits) leaves 50."""
    digits = 60 + (0 if dth == 0 else max(0, int(-math.log10(abs(dth)))))
    with mpmath.workdps(digits):
        X, Y, T, S, D = (mpmath.mpf(float(z)) for z in (x, y, th, ds, dth))
        if D == 0:
            return X + S * mpmath.cos(T), Y + S * mpmath.sin(T), T
        r = S / D  # the circle of radius ds/dth about the ICR
        return (X + r * (mpmath.sin(T + D) - mpmath.sin(T)),
                Y - r * (mpmath.cos(T + D) - mpmath.cos(T)), T + D)


@settings(max_examples=300, deadline=None)
@given(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(-20.0, 20.0),
       st.floats(-100.0, 100.0),
       st.one_of(st.floats(-7.0, 7.0), st.floats(-3e-4, 3e-4), st.just(0.0)))
def test_arc_step_is_the_circle_of_50_digit_arithmetic(x, y, th, ds, dth):
    mpmath.mp.dps = 50
    want = _exact_step(x, y, th, ds, dth)
    for got in (k.arc_step(x, y, th, ds, dth),
                tuple(float(g) for g in k.arc_step(np.array(x), np.array(y), np.array(th),
                                                    np.array(ds), np.array(dth)))):
        tol = 8 * EPS * (abs(ds) + abs(x) + abs(y)) + 1e-300
        assert abs(got[0] - float(want[0])) <= tol
        assert abs(got[1] - float(want[1])) <= tol
        assert got[2] == th + dth


def test_arc_step_quarter_circle_by_hand():
    # radius 1 m, a quarter turn to the left from the origin facing +x: (1, 1), heading pi/2
    x, y, th = k.arc_step(0.0, 0.0, 0.0, math.pi / 2, math.pi / 2)
    assert (x, y, th) == pytest.approx((1.0, 1.0, math.pi / 2), abs=1e-15)
    # facing +y, the same turn ends at (-1, 1)
    x, y, _ = k.arc_step(0.0, 0.0, math.pi / 2, math.pi / 2, math.pi / 2)
    assert (x, y) == pytest.approx((-1.0, 1.0), abs=1e-15)


@settings(max_examples=500)
@given(st.integers(-2**70, 2**70), st.integers(-2**70, 2**70).filter(lambda d: d != 0))
def test_c_div_truncates_toward_zero_as_c_does(a, b):
    want = math.trunc(Fraction(a, b))  # exact: C99 6.5.5 "truncation toward zero"
    assert k.c_div(a, b) == want
    assert a - b * k.c_div(a, b) == a - b * want  # C's % keeps the sign of a


@pytest.mark.parametrize(("a", "b", "q"), [
    (7, 2, 3), (-7, 2, -3), (7, -2, -3), (-7, -2, 3), (0, -5, 0), (-1, 2, 0),
    (-32768, 2, -16384), (-32768, -1, 32768), (-(2**31), 7, -306783378),
])
def test_c_div_by_hand(a, b, q):
    assert k.c_div(a, b) == q


@settings(max_examples=400)
@given(st.one_of(st.floats(-1e6, 1e6),
                 st.sampled_from([j * math.pi for j in range(-9, 10)]),
                 st.sampled_from([math.nextafter(j * math.pi, d) for j in (-3, -1, 1, 3)
                                  for d in (-math.inf, math.inf)])))
def test_wrap_angle_is_the_50_digit_reduction(angle):
    mpmath.mp.dps = 50
    got_float = k.wrap_angle(angle)
    got_array = float(k.wrap_angle(np.array(angle)))
    assert got_float == got_array
    assert -math.pi < got_float <= math.pi
    if -math.pi < angle <= math.pi:
        assert got_float == angle  # unchanged, bit for bit
        return
    a = mpmath.mpf(angle)
    two_pi = 2 * mpmath.pi
    exact = a - two_pi * mpmath.floor((a + mpmath.pi) / two_pi)  # in [-pi, pi)
    # equal to the exact reduction, up to the rounding of the float 2*pi multiples
    diff = abs(mpmath.mpf(got_float) - exact)
    diff = min(diff, abs(diff - two_pi))  # -pi and pi are the same angle
    assert float(diff) <= 4 * EPS * max(1.0, abs(angle))


def test_diff_drive_wheel_speeds_by_hand():
    assert k.diff_drive_wheel_speeds(0.0, 1.0, 0.085) == (-0.0425, 0.0425)
    assert k.diff_drive_wheel_speeds(1.0, 0.0, 0.3) == (1.0, 1.0)
    left, right = k.diff_drive_wheel_speeds(np.array([0.2]), np.array([-2.0]), 0.1)
    assert left.tolist() == pytest.approx([0.3]) and right.tolist() == pytest.approx([0.1])
