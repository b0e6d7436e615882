"""wheelkin.nonholonomic against independent values: sympy's constraints and brackets, closed
forms of the flows, the order of the bracket manoeuvre's remainder measured, and bad input.

Independent means: the constraint rows are derived here from the wheels' contact-point
velocities in sympy (not from the library's formulas), the brackets are sympy Jacobians, the
flows of the full-lock car are circular arcs written out by hand, and the manoeuvre is
integrated twice (the library's exact arcs and its Runge-Kutta flows, two separate code paths).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import mecanum, unified
from wheelkin import nonholonomic as nh

KAPPA = math.tan(0.4189) / 0.33  # the 1/10 car at full lock, 1/m

x, y, th, d, phl, phr = sp.symbols("x y theta delta phi_L phi_R", real=True)
Ls, Ws, rs = sp.symbols("L W r", positive=True)


# ------------------------------------------------------------------ sympy: the constraints

def _contact_velocity(px, py, q_dot):
    """World velocity of the body point (px, py) for pose rates q_dot = (x', y', theta')."""
    c, s = sp.cos(th), sp.sin(th)
    return sp.Matrix([q_dot[0] - q_dot[2] * (s * px + c * py),
                      q_dot[1] + q_dot[2] * (c * px - s * py)])


def _lateral(angle):
    """The world direction of a wheel's axle when its rolling direction is at ``angle``."""
    return sp.Matrix([-sp.sin(angle), sp.cos(angle)])


def _row(expr, rates):
    return [sp.simplify(sp.diff(expr, r)) for r in rates]


def test_unicycle_and_car_rows_from_contact_velocities():
    rng = np.random.default_rng(1)
    xd, yd, thd, dd = sp.symbols("xd yd thd dd", real=True)
    rear = _lateral(th).dot(_contact_velocity(0, 0, (xd, yd, thd)))
    front = _lateral(th + d).dot(_contact_velocity(Ls, 0, (xd, yd, thd)))
    uni = sp.lambdify((th,), _row(rear, (xd, yd, thd)))
    car = sp.lambdify((th, d, Ls), [_row(rear, (xd, yd, thd, dd)),
                                    _row(front, (xd, yd, thd, dd))])
    for _ in range(200):
        t, delta, L = rng.uniform(-4, 4), rng.uniform(-1.5, 1.5), rng.uniform(0.1, 5)
        pose = [rng.normal(), rng.normal(), t]
        np.testing.assert_allclose(nh.unicycle_constraint(pose), [uni(t)], atol=1e-14)
        np.testing.assert_allclose(nh.car_constraints([*pose[:2], t, delta], L),
                                   car(t, delta, L), atol=1e-13)


def _diff_drive_rows():
    """The differential drive's three constraint rows in q = (x, y, theta, phi_L, phi_R),
    derived in sympy from its contact velocities, as a function of (theta, W, r)."""
    xd, yd, thd, pld, prd = sp.symbols("xd yd thd pld prd", real=True)
    rates = (xd, yd, thd, pld, prd)
    forward = sp.Matrix([sp.cos(th), sp.sin(th)])
    rows = [_row(_lateral(th).dot(_contact_velocity(0, 0, rates[:3])), rates),
            _row(forward.dot(_contact_velocity(0, Ws / 2, rates[:3])) - rs * pld, rates),
            _row(forward.dot(_contact_velocity(0, -Ws / 2, rates[:3])) - rs * prd, rates)]
    return sp.lambdify((th, Ws, rs), rows)


def test_diff_drive_rows_from_contact_velocities():
    rng = np.random.default_rng(2)
    f = _diff_drive_rows()
    for _ in range(100):
        t, W, r = rng.uniform(-4, 4), rng.uniform(0.05, 2), rng.uniform(0.01, 0.5)
        got = nh.diff_drive_constraints([0.3, -0.2, t, 1.0, 2.0], W, r)
        np.testing.assert_allclose(got, f(t, W, r), atol=1e-14)


def test_pfaffian_matrix_of_any_wheel_from_its_contact_velocity():
    rng = np.random.default_rng(3)
    xd, yd, thd = sp.symbols("xd yd thd", real=True)
    xi, yi, psi = sp.symbols("x_i y_i psi_i", real=True)
    row = _row(_lateral(th + psi).dot(_contact_velocity(xi, yi, (xd, yd, thd))),
               (xd, yd, thd))
    f = sp.lambdify((th, xi, yi, psi), row)
    for _ in range(200):
        t, px, py, angle = rng.uniform(-4, 4), *rng.uniform(-1, 1, 2), rng.uniform(-3, 3)
        wheel = unified.WheelConstraint("w", (px, py), angle)
        np.testing.assert_allclose(nh.pfaffian_matrix([0.0, 0.0, t], [wheel])[0],
                                   f(t, px, py, angle), atol=1e-14)


def test_pfaffian_matrix_of_the_books_vehicles():
    t = 0.7
    diff = nh.pfaffian_matrix([1.0, 2.0, t], unified.diff_drive_wheels(0.3, 0.05))
    np.testing.assert_allclose(diff, np.vstack([nh.unicycle_constraint([0, 0, t])[0]] * 2),
                               atol=1e-15)
    geometry = mecanum.MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    assert nh.pfaffian_matrix([0, 0, t], unified.mecanum_wheels(geometry)).shape == (0, 3)
    # The Ackermann car's four rows: rank 2, and the bicycle's drive field satisfies them.
    for radius in (0.8, -1.5, 4.0):
        wheels = unified.car_wheels(wheelbase=0.33, track_width=0.27, wheel_radius=0.05,
                                    turning_radius=radius)
        rows = nh.pfaffian_matrix([0.0, 0.0, t], wheels)
        drive = nh.car_fields([0.0, 0.0, t, math.atan(0.33 / radius)], 0.33)[:3, 0]
        assert np.linalg.matrix_rank(rows) == 2
        np.testing.assert_allclose(rows @ drive, 0.0, atol=1e-14)


def test_fields_span_the_null_space_of_the_constraints():
    rng = np.random.default_rng(4)
    for _ in range(100):
        t, delta = rng.uniform(-4, 4), rng.uniform(-1.4, 1.4)
        A = nh.unicycle_constraint([0, 0, t])
        G = nh.unicycle_fields([0, 0, t])
        np.testing.assert_allclose(A @ G, 0.0, atol=1e-15)
        assert np.linalg.matrix_rank(G) == 2
        A = nh.car_constraints([0, 0, t, delta], 2.5)
        G = nh.car_fields([0, 0, t, delta], 2.5)
        np.testing.assert_allclose(A @ G, 0.0, atol=1e-14)
        assert np.linalg.matrix_rank(np.vstack([A, G.T])) == 4
        G = nh.car_lock_fields([0, 0, t], KAPPA)
        np.testing.assert_allclose(A[:1, :3] @ G, 0.0, atol=1e-15)
    stack = nh.unicycle_fields(rng.uniform(-3, 3, (7, 3)))
    assert stack.shape == (7, 3, 2)


def test_rolling_difference_is_holonomic_and_side_slip_is_not():
    """The one-form W dtheta - r dphi_R + r dphi_L is exact (the gradient of a function);
    the no-side-slip form fails the integrability condition a . curl a = 0 everywhere."""
    A = nh.diff_drive_constraints([0, 0, 0.4, 0, 0], 0.3, 0.05)
    np.testing.assert_allclose(A[2] - A[1], [0, 0, 0.3, 0.05, -0.05], atol=1e-15)
    h = Ws * th - rs * (phr - phl)
    assert [sp.diff(h, v) for v in (x, y, th, phl, phr)] == [0, 0, Ws, rs, -rs]
    a = sp.Matrix([-sp.sin(th), sp.cos(th), 0])
    curl = sp.Matrix([sp.diff(a[2], y) - sp.diff(a[1], th), sp.diff(a[0], th) - sp.diff(a[2], x),
                      sp.diff(a[1], x) - sp.diff(a[0], y)])
    assert sp.simplify(a.dot(curl)) == -1


# ------------------------------------------------------------------ sympy: the brackets

def _sym_bracket(f1, f2, q):
    return sp.simplify(f2.jacobian(q) * f1 - f1.jacobian(q) * f2)


def _lambdified(fields, q, *params):
    return [sp.lambdify((q, *params), list(f)) for f in fields]


def test_brackets_of_the_vehicles_against_sympy():
    rng = np.random.default_rng(5)
    q3 = sp.Matrix([x, y, th])
    q4 = sp.Matrix([x, y, th, d])
    k = sp.symbols("kappa", positive=True)
    uni = (sp.Matrix([sp.cos(th), sp.sin(th), 0]), sp.Matrix([0, 0, 1]))
    car = (sp.Matrix([sp.cos(th), sp.sin(th), sp.tan(d) / Ls, 0]), sp.Matrix([0, 0, 0, 1]))
    lock = (sp.Matrix([sp.cos(th), sp.sin(th), k]), sp.Matrix([sp.cos(th), sp.sin(th), -k]))
    assert list(_sym_bracket(*uni, q3)) == [sp.sin(th), -sp.cos(th), 0]
    assert list(_sym_bracket(*lock, q3)) == [-2 * k * sp.sin(th), 2 * k * sp.cos(th), 0]
    wriggle = _sym_bracket(*car, q4)
    assert sp.simplify(wriggle[2] + 1 / (Ls * sp.cos(d) ** 2)) == 0
    slide = _sym_bracket(car[0], wriggle, q4)
    cases = [(uni, q3, (), lambda p: nh.unicycle_fields(p)),
             (car, q4, (Ls,), lambda p, L: nh.car_fields(p, L)),
             (lock, q3, (k,), lambda p, kk: nh.car_lock_fields(p, kk))]
    for fields, q, params, lib in cases:
        exact = sp.lambdify((q, *params), list(_sym_bracket(*fields, q)))
        for _ in range(50):
            point = rng.uniform(-2, 2, len(q))
            if len(q) == 4:
                point[3] = rng.uniform(-1.2, 1.2)
            values = [rng.uniform(0.2, 3.0) for _ in params]

            def f1(p, values=values, lib=lib):
                return lib(p, *values)[:, 0]

            def f2(p, values=values, lib=lib):
                return lib(p, *values)[:, 1]

            np.testing.assert_allclose(nh.lie_bracket(f1, f2, point),
                                       exact(point, *values), rtol=1e-9, atol=1e-10)
    slide_f = sp.lambdify((q4, Ls), list(slide))
    for _ in range(20):
        point = np.array([*rng.uniform(-2, 2, 3), rng.uniform(-1, 1)])

        def drive(p):
            return nh.car_fields(p, 2.0)[:, 0]

        def wriggle_num(p):
            return nh.lie_bracket(drive, lambda z: nh.car_fields(z, 2.0)[:, 1], p)

        np.testing.assert_allclose(nh.lie_bracket(drive, wriggle_num, point),
                                   slide_f(point, 2.0), rtol=1e-7, atol=1e-8)


def test_bracket_of_general_nonlinear_fields_against_sympy():
    rng = np.random.default_rng(6)
    q = sp.Matrix([x, y, th])
    f1 = sp.Matrix([sp.sin(y) * th, x**2 - th, sp.exp(x / 3) * sp.cos(th)])
    f2 = sp.Matrix([y * th, sp.cos(x + th), x * y - 1])
    exact = sp.lambdify((q,), list(_sym_bracket(f1, f2, q)))
    g1, g2 = (sp.lambdify((q,), list(f)) for f in (f1, f2))
    for _ in range(100):
        point = rng.uniform(-2, 2, 3)
        got = nh.lie_bracket(lambda p: g1(p), lambda p: g2(p), point)
        np.testing.assert_allclose(got, exact(point), rtol=1e-9, atol=1e-9)


@settings(max_examples=60)
@given(st.lists(st.floats(-3, 3), min_size=3, max_size=3), st.floats(0.1, 5.0),
       st.floats(-2, 2))
def test_bracket_is_antisymmetric_and_bilinear(point, kappa, scale):
    def left(p):
        return nh.car_lock_fields(p, kappa)[:, 0]

    def right(p):
        return nh.car_lock_fields(p, kappa)[:, 1]

    ab = nh.lie_bracket(left, right, point)
    np.testing.assert_allclose(nh.lie_bracket(right, left, point), -ab, atol=1e-10)
    np.testing.assert_allclose(nh.lie_bracket(left, left, point), 0.0, atol=1e-10)
    scaled = nh.lie_bracket(lambda p: scale * left(p), right, point)
    np.testing.assert_allclose(scaled, scale * ab, atol=1e-9)


# ------------------------------------------------------------------ flows and the manoeuvre

def _arc(pose, length, curvature):
    """Hand-written: the pose after driving ``length`` on a circle of ``curvature``."""
    x0, y0, t0 = pose
    t1 = t0 + curvature * length
    return np.array([x0 + (math.sin(t1) - math.sin(t0)) / curvature,
                     y0 - (math.cos(t1) - math.cos(t0)) / curvature, t1])


def test_flow_against_closed_forms():
    rng = np.random.default_rng(7)
    for _ in range(20):
        pose = rng.uniform(-2, 2, 3)
        length = rng.uniform(-1, 1)

        def left(p):
            return nh.car_lock_fields(p, KAPPA)[:, 0]

        np.testing.assert_allclose(nh.flow(left, pose, length, steps=200),
                                   _arc(pose, length, KAPPA), atol=1e-11)
        straight = nh.flow(nh.unicycle_drive, pose, length, steps=1)
        np.testing.assert_allclose(straight[:2] - pose[:2],
                                   length * np.array([math.cos(pose[2]), math.sin(pose[2])]),
                                   atol=1e-15)


def test_parallel_parking_against_hand_arcs_and_runge_kutta():
    def left(p):
        return nh.car_lock_fields(p, KAPPA)[:, 0]

    def right(p):
        return nh.car_lock_fields(p, KAPPA)[:, 1]

    for eps in (0.02, 0.1, 0.3, -0.2):
        pose = np.array([0.4, -1.0, 0.6])
        hand = [pose]
        for sign, curvature in ((1, KAPPA), (1, -KAPPA), (-1, KAPPA), (-1, -KAPPA)):
            hand.append(_arc(hand[-1], sign * eps, curvature))
        exact = nh.parallel_parking(pose, eps, KAPPA)
        np.testing.assert_allclose(exact, np.array(hand), atol=1e-13)
        rk = nh.bracket_manoeuvre(left, right, pose, eps, steps=400)
        np.testing.assert_allclose(rk, exact, atol=1e-11)
        shift = np.array([-math.sin(pose[2]), math.cos(pose[2]), 0.0]) * nh.parking_shift(
            eps, KAPPA)
        np.testing.assert_allclose(exact[-1] - pose, shift, atol=1e-14)
    np.testing.assert_array_equal(nh.parallel_parking([1.0, 2.0, 3.0], 0.0, KAPPA),
                                  [[1.0, 2.0, 3.0]] * 5)


def test_parking_shift_series_from_sympy():
    eps, k = sp.symbols("epsilon kappa", positive=True)
    series = sp.series(4 * (1 - sp.cos(k * eps)) / k, eps, 0, 6).removeO()
    assert sp.simplify(series - (2 * k * eps**2 - k**3 * eps**4 / 6)) == 0
    with mpmath.workdps(40):  # 1 - cos loses digits in floats; not in 40-digit arithmetic
        for e in (1e-4, 1e-3, 0.05, 0.4, 2.0):
            exact = 4 * (1 - mpmath.cos(mpmath.mpf(KAPPA) * e)) / KAPPA
            assert math.isclose(nh.parking_shift(e, KAPPA), float(exact), rel_tol=1e-14)
    arr = nh.parking_shift(np.array([0.1, 0.2]), KAPPA)
    assert isinstance(arr, np.ndarray) and arr.shape == (2,)
    assert isinstance(nh.parking_shift(0.1, KAPPA), float)


def _order(f1, f2, start, epsilons):
    """The slope of log |net motion - eps^2 [f1, f2]| against log eps."""
    errors = []
    for eps in epsilons:
        path = nh.bracket_manoeuvre(f1, f2, start, eps, steps=200)
        errors.append(np.linalg.norm(path[-1] - path[0]
                                     - nh.bracket_prediction(f1, f2, start, eps)))
    return np.polyfit(np.log(epsilons), np.log(errors), 1)[0]


def test_remainder_order_measured():
    """Generic fields: the remainder is O(eps^3); at full lock the eps^3 term,
    1/2 [f_L + f_R, [f_L, f_R]], vanishes and the remainder is O(eps^4)."""
    epsilons = np.geomspace(0.01, 0.08, 6)
    start = [0.2, 0.1, 0.5]
    assert abs(_order(nh.unicycle_drive, nh.unicycle_turn, start, epsilons) - 3.0) < 0.05

    def left(p):
        return nh.car_lock_fields(p, KAPPA)[:, 0]

    def right(p):
        return nh.car_lock_fields(p, KAPPA)[:, 1]

    assert abs(_order(left, right, start, epsilons) - 4.0) < 0.05
    # and the leading term itself: net / eps^2 tends to the bracket
    small = nh.bracket_manoeuvre(left, right, start, 1e-3)
    np.testing.assert_allclose((small[-1] - small[0]) / 1e-6,
                               nh.lie_bracket(left, right, start), rtol=1e-5, atol=1e-6)


def test_bracket_ranks_of_the_vehicles():
    def lock(i):
        return lambda p: nh.car_lock_fields(p, KAPPA)[:, i]

    def car(i):
        return lambda p: nh.car_fields(p, 0.33)[:, i]

    def omni(i):
        return lambda p: np.array([[math.cos(p[2]), -math.sin(p[2]), 0.0],
                                   [math.sin(p[2]), math.cos(p[2]), 0.0],
                                   [0.0, 0.0, 1.0]])[:, i]

    pose = [0.1, -0.3, 0.9]
    assert nh.bracket_ranks([nh.unicycle_drive, nh.unicycle_turn], pose).tolist() == [2, 3, 3]
    assert nh.bracket_ranks([lock(0), lock(1)], pose).tolist() == [2, 3, 3]
    assert nh.bracket_ranks([car(0), car(1)], [*pose, 0.3]).tolist() == [2, 3, 4]
    assert nh.bracket_ranks([omni(0), omni(1), omni(2)], pose, depth=2).tolist() == [3, 3]
    assert nh.bracket_ranks([nh.unicycle_drive], pose).tolist() == [1, 1, 1]
    # Two translations: integrable (holonomic), the brackets add nothing.
    planar = [lambda p: np.array([1.0, 0.0, 0.0]), lambda p: np.array([0.0, 1.0, 0.0])]
    assert nh.bracket_ranks(planar, pose, depth=4).tolist() == [2, 2, 2, 2]


# ------------------------------------------------------------------ wheel angles: Frobenius

MECANUM = mecanum.MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)


def _columns(fields_of, wheels):
    return [lambda q, j=j: fields_of(q, wheels)[:, j]
            for j in range(fields_of(np.zeros(3 + len(wheels)), wheels).shape[1])]


def test_wheel_angle_fields_of_the_diff_drive_from_its_contact_velocities():
    """The fields satisfy the five-variable constraints derived in sympy from the wheels'
    contact velocities, and are the hand-written drive and turn columns."""
    rng = np.random.default_rng(8)
    constraints = _diff_drive_rows()
    for _ in range(50):
        t, W, r = rng.uniform(-4, 4), rng.uniform(0.05, 2), rng.uniform(0.01, 0.5)
        q = [*rng.normal(size=2), t, *rng.normal(size=2)]
        got = nh.wheel_angle_fields(q, unified.diff_drive_wheels(W, r, caster=False))
        hand = np.array([[math.cos(t), 0.0], [math.sin(t), 0.0], [0.0, 1.0],
                         [1 / r, -W / (2 * r)], [1 / r, W / (2 * r)]])
        np.testing.assert_allclose(got, hand, atol=1e-12)
        np.testing.assert_allclose(np.array(constraints(t, W, r), dtype=float) @ got, 0.0,
                                   atol=1e-12)


def test_wheel_angle_fields_of_the_mecanum_platform_turn_its_wheels_as_its_kinematics():
    t = 0.9
    got = nh.wheel_angle_fields([1.0, -2.0, t, 0.1, 0.2, 0.3, 0.4],
                                unified.mecanum_wheels(MECANUM))
    rotation = np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0],
                         [0.0, 0.0, 1.0]])
    np.testing.assert_allclose(got[:3], rotation, atol=1e-14)  # forward, sideways, turn
    for j, twist in enumerate(np.eye(3)):
        np.testing.assert_allclose(got[3:, j], mecanum.inverse_kinematics(*twist, MECANUM),
                                   atol=1e-12)


def test_frobenius_counts_the_holonomic_combinations():
    """Rank of fields and brackets against the dimension of q: the differential drive with its
    wheel angles keeps one function constant (W theta - r (phi_R - phi_L)), the mecanum
    platform two (a diagonal pair's angle difference against the heading), the skid steer six;
    each such function is constant along any sequence of flows, found here by hand."""
    W, r = 0.3, 0.05
    diff = unified.diff_drive_wheels(W, r, caster=False)
    wheels = unified.mecanum_wheels(MECANUM)
    skid = unified.skid_steer_wheels(half_wheelbase=0.1, half_track=0.12, wheel_radius=0.04)
    q5, q7 = [0.1, 0.2, 0.3, 0.4, 0.5], [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]
    assert nh.bracket_ranks(_columns(nh.wheel_angle_fields, diff), q5, depth=4).tolist() == \
        [2, 3, 4, 4]
    assert nh.bracket_ranks(_columns(nh.wheel_angle_fields, wheels), q7).tolist() == [3, 5, 5]
    assert nh.bracket_ranks(_columns(nh.wheel_angle_fields, skid), q7).tolist() == [1, 1, 1]
    k = MECANUM.half_wheelbase + MECANUM.half_track  # the rotation lever at 45 degrees
    rm = MECANUM.wheel_radius
    conserved = {  # q = (x, y, theta, phi_L, phi_R) and (x, y, theta, FL, FR, RL, RR)
        "diff": (diff, q5, [lambda q: W * q[2] - r * (q[4] - q[3])]),
        "mecanum": (wheels, q7, [lambda q: rm * (q[3] - q[6]) + 2 * k * q[2],
                                 lambda q: rm * (q[4] - q[5]) - 2 * k * q[2]]),
    }
    rng = np.random.default_rng(9)
    for vehicle, start, functions in conserved.values():
        fields = _columns(nh.wheel_angle_fields, vehicle)
        q = np.array(start, dtype=float)
        for _ in range(8):
            q = nh.flow(fields[rng.integers(len(fields))], q, rng.uniform(-0.5, 0.5), steps=20)
        for function in functions:
            assert math.isclose(function(q), function(start), abs_tol=1e-12)
        assert np.linalg.norm(q - start) > 0.1  # it did move


def test_a_closed_loop_of_the_mecanum_chassis_can_leave_its_wheels_turned():
    """Holonomic in (x, y, theta), not with its wheel angles: forward, turn, back, turn back,
    then a straight move home leaves the chassis where it was and the wheels turned."""
    wheels = unified.mecanum_wheels(MECANUM)
    forward, sideways, turn = _columns(nh.wheel_angle_fields, wheels)
    start = np.zeros(7)
    q = nh.flow(forward, start, 0.3)
    q = nh.flow(turn, q, 0.5)
    q = nh.flow(forward, q, -0.3)
    q = nh.flow(turn, q, -0.5)
    home = -q[:2]  # heading 0 again: body and world axes agree
    np.testing.assert_allclose(q[2], 0.0, atol=1e-12)
    q = nh.flow(lambda p: home[0] * forward(p) + home[1] * sideways(p), q, 1.0)
    np.testing.assert_allclose(q[:3], 0.0, atol=1e-12)
    assert np.abs(q[3:]).max() > 0.5  # rad: the wheels did not come back


# ------------------------------------------------------------------ bad input

def _left(p):
    return nh.car_lock_fields(p, 1.0)[:, 0]


BAD = [
    (lambda: nh.unicycle_constraint([0.0, 0.0]), ValueError, "pose"),
    (lambda: nh.unicycle_constraint([0.0, math.nan, 0.0]), ValueError, "pose"),
    (lambda: nh.pfaffian_matrix([0.0, 0.0, math.inf], unified.diff_drive_wheels(0.3, 0.05)),
     ValueError, "pose"),
    (lambda: nh.pfaffian_matrix([0.0, 0.0, 0.0], []), ValueError, "wheels"),
    (lambda: nh.diff_drive_constraints([0, 0, 0], 0.3, 0.05), ValueError, "configuration"),
    (lambda: nh.diff_drive_constraints([0] * 5, -0.3, 0.05), ValueError, "track_width"),
    (lambda: nh.diff_drive_constraints([0] * 5, 0.3, 0.0), ValueError, "wheel_radius"),
    (lambda: nh.car_constraints([0, 0, 0, 1.6], 2.5), ValueError, "delta"),
    (lambda: nh.car_constraints([0, 0, 0, 0.1], math.nan), ValueError, "wheelbase"),
    (lambda: nh.car_fields([0, 0, 0, -2.0], 2.5), ValueError, "delta"),
    (lambda: nh.car_fields([0, 0, 0], 2.5), ValueError, "configuration"),
    (lambda: nh.car_lock_fields([0, 0, 0], 0.0), ValueError, "max_curvature"),
    (lambda: nh.car_lock_fields([0, 0, 0], True), ValueError, "max_curvature"),
    (lambda: nh.lie_bracket(3.0, _left, [0, 0, 0]), TypeError, "f1"),
    (lambda: nh.lie_bracket(_left, None, [0, 0, 0]), TypeError, "f2"),
    (lambda: nh.lie_bracket(_left, _left, [[0, 0, 0]]), ValueError, "configuration"),
    (lambda: nh.lie_bracket(_left, _left, []), ValueError, "configuration"),
    (lambda: nh.lie_bracket(_left, _left, [0, 0, 0], step=0.0), ValueError, "step"),
    (lambda: nh.lie_bracket(_left, lambda p: p[:2], [0, 0, 0]), ValueError, "f2"),
    (lambda: nh.lie_bracket(lambda p: p / 0.0, _left, [0, 0, 0]), ValueError, "f1"),
    (lambda: nh.lie_bracket(lambda p: "fast", _left, [0, 0, 0]), ValueError, "f1"),
    (lambda: nh.bracket_prediction(_left, _left, [0, 0, 0], math.inf), ValueError, "epsilon"),
    (lambda: nh.bracket_prediction(_left, _left, [0, 0, 0], 1e300), ValueError, "epsilon"),
    (lambda: nh.flow(_left, [0, 0, 0], math.nan), ValueError, "duration"),
    (lambda: nh.flow(_left, [0, 0, 0], 1.0, steps=0), ValueError, "steps"),
    (lambda: nh.flow(_left, [0, 0, 0], 1.0, steps=2.5), TypeError, "steps"),
    (lambda: nh.flow(_left, [0, 0, 0], 1.0, steps=True), TypeError, "steps"),
    (lambda: nh.flow("left", [0, 0, 0], 1.0), TypeError, "field"),
    (lambda: nh.flow(lambda p: np.exp(p * 1e3), [1.0, 0, 0], 10.0), ValueError, "field"),
    (lambda: nh.bracket_manoeuvre(_left, _left, [0, 0, 0], "fast"), ValueError, "epsilon"),
    (lambda: nh.bracket_manoeuvre(_left, 1, [0, 0, 0], 0.1), TypeError, "f2"),
    (lambda: nh.bracket_ranks(_left, [0, 0, 0]), TypeError, "fields"),
    (lambda: nh.bracket_ranks([], [0, 0, 0]), TypeError, "fields"),
    (lambda: nh.bracket_ranks([_left, 2], [0, 0, 0]), TypeError, r"fields\[1\]"),
    (lambda: nh.bracket_ranks([_left], [0, 0, 0], depth=0), ValueError, "depth"),
    (lambda: nh.bracket_ranks([_left], [0, 0, 0], depth=2.0), TypeError, "depth"),
    (lambda: nh.bracket_ranks([_left], [0, 0, 0], tolerance=1.0), ValueError, "tolerance"),
    (lambda: nh.parallel_parking([0, 0, 0], 0.1, -1.0), ValueError, "max_curvature"),
    (lambda: nh.parallel_parking([0, 0], 0.1, 1.0), ValueError, "pose"),
    (lambda: nh.parallel_parking([0, 0, 0], None, 1.0), ValueError, "epsilon"),
    (lambda: nh.parallel_parking([0, 0, 0], math.inf, 1.0), ValueError, "epsilon"),
    (lambda: nh.parking_shift([0.1, math.nan], 1.0), ValueError, "epsilon"),
    (lambda: nh.parking_shift(0.1, 5e-324), ValueError, "max_curvature"),
    (lambda: nh.wheel_angle_fields([0.0] * 6, unified.diff_drive_wheels(0.3, 0.05)),
     ValueError, "caster"),
    (lambda: nh.wheel_angle_fields([0.0] * 4, unified.diff_drive_wheels(0.3, 0.05,
                                                                        caster=False)),
     ValueError, "configuration"),
    (lambda: nh.wheel_angle_fields([0.0] * 3, []), ValueError, "wheels"),
    (lambda: nh.wheel_angle_fields([0.0, 0.0, math.nan, 0.0, 0.0],
                                   unified.diff_drive_wheels(0.3, 0.05, caster=False)),
     ValueError, "configuration"),
]


@pytest.mark.parametrize(("call", "error", "name"), BAD, ids=range(len(BAD)))
def test_bad_input(call, error, name):
    with pytest.raises(error, match=name):
        call()
