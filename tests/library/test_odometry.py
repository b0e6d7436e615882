"""Tests of wheelkin.odometry against independent references.

References: circle geometry (an arc of radius R is known in closed form), a sympy integration
of the unicycle ODE, mpmath at 50 digits, plain sequential loops written from the equations,
wheelkin.frames (SE(2) exponential, the firmware frame converter), hand calculations, and
properties (mirror symmetry, rotation and translation invariance, convergence orders).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import frames
from wheelkin import odometry as odo

K = 8.043  # steps per mm
W = 85.0  # wheel base, mm

finite = st.floats(-500.0, 500.0, allow_nan=False, allow_infinity=False)
inc_rows = st.lists(st.tuples(finite, finite), min_size=1, max_size=30)


def arc_increments(radius_mm, angle_rad, n):
    """Fractional (ideal) increments driving an arc of the mid-point in ``n`` equal updates."""
    s_l = (radius_mm - W / 2) * angle_rad / n
    s_r = (radius_mm + W / 2) * angle_rad / n
    return np.tile([s_l * K, s_r * K], (n, 1))


def arc_truth(radius_mm, angle_rad):
    """Closed-form pose after turning ``angle_rad`` on a left arc of radius R from the origin."""
    return np.array([radius_mm * math.sin(angle_rad),
                     radius_mm * (1 - math.cos(angle_rad)), angle_rad])


def loop_reference(increments, method, pose=(0.0, 0.0, 0.0)):
    """A plain sequential loop written from the equations (not from the library)."""
    x, y, th = pose
    out = []
    for n_l, n_r in increments:
        s_l, s_r = n_l / K, n_r / K
        ds, dth = (s_l + s_r) / 2, (s_r - s_l) / W
        if method == "euler":
            x, y = x + ds * math.cos(th), y + ds * math.sin(th)
        elif method == "midpoint":
            x, y = x + ds * math.cos(th + dth / 2), y + ds * math.sin(th + dth / 2)
        elif method == "end":
            x, y = x + ds * math.cos(th + dth), y + ds * math.sin(th + dth)
        th += dth
        out.append((x, y, th))
    return np.array(out)


# --- the exact update --------------------------------------------------------------------------

@pytest.mark.parametrize("radius", [60.0, 200.0, -150.0, 1e6])
@pytest.mark.parametrize("n", [1, 3, 50])
def test_exact_is_exact_on_an_arc(radius, n):
    angle = 2.0 if radius < 1e5 else 1e-4
    poses = odo.integrate(arc_increments(radius, angle, n), K, W)
    np.testing.assert_allclose(poses[-1], arc_truth(radius, angle), rtol=1e-10, atol=1e-9)


def test_exact_matches_sympy_integration_of_the_unicycle():
    t, tau, v, w, x0, y0, th0 = sp.symbols("t tau v omega x0 y0 theta0", real=True)
    theta = th0 + w * t
    x1 = x0 + sp.integrate(v * sp.cos(theta), (t, 0, tau), conds="none")
    y1 = y0 + sp.integrate(v * sp.sin(theta), (t, 0, tau), conds="none")
    ds, dth = sp.symbols("Delta_s Delta_theta", real=True)
    # piecewise in omega: take the omega != 0 branch, then substitute v tau = ds, w tau = dth
    x1 = sp.simplify(x1.args[0][0] if isinstance(x1, sp.Piecewise) else x1)
    y1 = sp.simplify(y1.args[0][0] if isinstance(y1, sp.Piecewise) else y1)
    subs = {v: ds / tau, w: dth / tau}
    fx = sp.lambdify((x0, y0, th0, ds, dth, tau), sp.simplify(x1.subs(subs)))
    fy = sp.lambdify((x0, y0, th0, ds, dth, tau), sp.simplify(y1.subs(subs)))
    rng = np.random.default_rng(3)
    for _ in range(200):
        p = rng.uniform(-100, 100, 3)
        d, a = rng.uniform(-50, 50), rng.uniform(-3, 3)
        got = odo.pose_update(p, d, a)
        np.testing.assert_allclose(got[:2], [fx(*p, d, a, 1.0), fy(*p, d, a, 1.0)],
                                   rtol=1e-9, atol=1e-9)
        assert got[2] == pytest.approx(p[2] + a)


def test_exact_agrees_with_the_se2_exponential():
    rng = np.random.default_rng(5)
    inc = rng.uniform(-200, 400, size=(300, 2))
    ds, dth = odo.body_increments(inc, K, W)
    twists = np.column_stack([ds, np.zeros_like(ds), dth])  # mm per "second", dt = 1
    ref = frames.integrate_twist(twists, 1.0)[1:]
    got = odo.integrate(inc, K, W)
    np.testing.assert_allclose(got[:, :2], ref[:, :2], atol=1e-8)
    np.testing.assert_allclose(frames.wrap_angle(got[:, 2] - ref[:, 2]), 0.0, atol=1e-12)


def test_chord_factor_against_mpmath_on_both_sides_of_the_switch():
    t = odo.SERIES_THRESHOLD
    angles = np.concatenate([np.geomspace(1e-12, 10, 400), t * (1 + np.linspace(-1e-6, 1e-6, 21)),
                             [t, np.nextafter(t, 0), np.nextafter(t, 1)]])
    got = odo.chord_factor(np.concatenate([angles, -angles]))
    mpmath.mp.dps = 50
    want = [float(mpmath.sin(mpmath.mpf(a) / 2) / (mpmath.mpf(a) / 2))
            for a in np.concatenate([angles, -angles])]
    np.testing.assert_allclose(got, want, rtol=2e-16, atol=0)
    assert odo.chord_factor(0.0) == 1.0


def test_exact_update_is_continuous_across_the_series_switch():
    t = odo.SERIES_THRESHOLD
    below = odo.pose_update([3.0, -2.0, 0.7], 12.0, np.nextafter(t, 0))
    above = odo.pose_update([3.0, -2.0, 0.7], 12.0, np.nextafter(t, 1))
    np.testing.assert_allclose(below, above, rtol=0, atol=1e-14)
    # ... and the series branch really is used below it (exact zero stays finite)
    assert np.all(np.isfinite(odo.pose_update([0, 0, 0], 10.0, 0.0)))


def test_naive_radius_form_loses_digits_but_ours_does_not():
    """Why the chord form: R (sin(th + dth) - sin th) cancels catastrophically for tiny dth."""
    ds, dth, th = 10.0, 1e-9, 0.3
    naive = ds / dth * (math.sin(th + dth) - math.sin(th))
    exact = float(mpmath.mpf(ds) / dth * (mpmath.sin(th + mpmath.mpf(dth)) - mpmath.sin(th)))
    ours = odo.pose_update([0, 0, th], ds, dth)[0]
    assert abs(ours - exact) < 1e-14
    assert abs(naive - exact) > 1e-9  # the fallback is not decoration


# --- euler and midpoint ------------------------------------------------------------------------

@pytest.mark.parametrize("method", ["euler", "midpoint"])
def test_euler_and_midpoint_equal_a_plain_loop(method):
    rng = np.random.default_rng(11)
    inc = rng.integers(-50, 120, size=(400, 2))
    pose = (10.0, -5.0, 2.5)
    np.testing.assert_allclose(odo.integrate(inc, K, W, method, pose),
                               loop_reference(inc, method, pose), rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize(("method", "order"), [("euler", 1), ("midpoint", 2)])
def test_convergence_order_on_an_arc(method, order):
    radius, angle = 150.0, 3.0
    errors = []
    for n in (40, 80, 160, 320):
        end = odo.integrate(arc_increments(radius, angle, n), K, W, method)[-1]
        errors.append(np.hypot(*(end[:2] - arc_truth(radius, angle)[:2])))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    np.testing.assert_allclose(np.log2(ratios), order, atol=0.05)


def test_all_methods_agree_on_straight_lines_and_turns_on_the_spot():
    inc = np.array([[100, 100], [-50, 50], [80, 80], [30, -30], [-40, -40]])
    results = [odo.integrate(inc, K, W, m) for m in odo.METHODS]
    for r in results[1:]:
        np.testing.assert_allclose(r, results[0], atol=1e-12)
    assert results[0][1, 0] == pytest.approx(results[0][0, 0])  # turning on the spot: no move


# --- properties --------------------------------------------------------------------------------

@settings(max_examples=60, deadline=None)
@given(inc_rows, st.sampled_from(odo.METHODS))
def test_mirror_swapping_the_wheels_mirrors_the_path(rows, method):
    inc = np.array(rows)
    a = odo.integrate(inc, K, W, method)
    b = odo.integrate(inc[:, ::-1], K, W, method)
    np.testing.assert_allclose(b, a * [1, -1, -1], atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(inc_rows, st.sampled_from(odo.METHODS), finite, finite, st.floats(-7, 7))
def test_start_pose_rotates_and_translates_the_path(rows, method, x0, y0, th0):
    inc = np.array(rows)
    base = odo.integrate(inc, K, W, method)
    moved = odo.integrate(inc, K, W, method, pose=(x0, y0, th0))
    c, s = math.cos(th0), math.sin(th0)
    want = np.column_stack([x0 + c * base[:, 0] - s * base[:, 1],
                            y0 + s * base[:, 0] + c * base[:, 1], base[:, 2] + th0])
    np.testing.assert_allclose(moved, want, atol=1e-7)


@settings(max_examples=40, deadline=None)
@given(inc_rows)
def test_heading_depends_only_on_the_total_step_difference(rows):
    inc = np.array(rows)
    theta = odo.integrate(inc, K, W)[-1, 2]
    assert theta == pytest.approx((inc[:, 1].sum() - inc[:, 0].sum()) / (K * W), abs=1e-9)


def test_empty_run_and_broadcast_pose_update():
    assert odo.integrate(np.zeros((0, 2)), K, W).shape == (0, 3)
    assert odo.firmware_scheme(np.zeros((0, 2)), K, W).shape == (0, 3)
    assert odo.firmware_scheme(np.zeros((0, 2)), K, W, wrap="fmod").shape == (0, 3)
    assert odo.firmware_fixed_point(np.zeros((0, 2)), K, W).shape == (0, 3)
    out = odo.pose_update(np.zeros((4, 3)), [1.0, 2.0, 3.0, 4.0], 0.0, "midpoint")
    np.testing.assert_allclose(out[:, 0], [1, 2, 3, 4])


# --- encoder sequences --------------------------------------------------------------------------

def test_plan_and_encoder_increments():
    travel = odo.plan_wheel_travel([[100.0, 0.0], [0.0, math.pi / 2]], W, 10.0)
    # straight: 10 updates; a quarter turn on the spot moves each wheel W pi / 4 = 66.8 mm: 7
    assert len(travel) == 1 + 10 + 7
    np.testing.assert_allclose(travel[-1], [100 - W * math.pi / 4, 100 + W * math.pi / 4])
    inc = odo.encoder_increments(travel, K)
    np.testing.assert_array_equal(inc.sum(axis=0), np.floor(travel[-1] * K + 1e-9))
    pose = odo.integrate(inc, K, W)[-1]
    np.testing.assert_allclose(pose, [100, 0, math.pi / 2], atol=0.3)  # within a step or two


# --- the firmware's scheme -----------------------------------------------------------------------

def to_ours_mm(fw):
    """Firmware (X, Y, orientation) rows to our (x, y, theta) in mm via wheelkin.frames."""
    ours = frames.firmware_pose_to_ours(fw[:, 0], fw[:, 1], fw[:, 2])
    return np.column_stack([1000 * ours[:, 0], 1000 * ours[:, 1], ours[:, 2]])


def test_as_printed_straight_drive_goes_nowhere_and_turn_on_spot_moves():
    straight = odo.firmware_as_printed([[800, 800]] * 5, K, W)
    np.testing.assert_allclose(straight[-1, :2], 0.0)
    spin = odo.firmware_as_printed([[-100, 100]] * 4, K, W, wrap="fmod")
    assert spin[-1, 2] == pytest.approx(4 * 200 / K / W)  # it turns (fmod reading) ...
    assert np.hypot(*spin[-1, :2]) > 40  # ... and it moves: 4 x 100 steps / K = 49.7 mm


def test_literal_wrap_discards_the_turn():
    out = odo.firmware_as_printed([[0, 100]] * 10, K, W, pose=(0, 0, 7.0))
    np.testing.assert_allclose(out[:, 2], math.fmod(7.0, 2 * math.pi))


def test_fmod_wrap_keeps_sign_and_matches_unwrapped_on_sin_cos():
    rng = np.random.default_rng(2)
    inc = rng.integers(-300, 300, size=(2000, 2))
    fm = odo.firmware_scheme(inc, K, W, wrap="fmod", position_heading="end")
    raw = odo.firmware_scheme(inc, K, W, wrap="none", position_heading="end")
    assert np.all(np.abs(fm[:, 2]) < 2 * math.pi)
    np.testing.assert_allclose(np.cos(fm[:, 2]), np.cos(raw[:, 2]), atol=1e-9)
    np.testing.assert_allclose(fm[:, :2], raw[:, :2], atol=1e-6)
    # two representations: the same heading is stored both as a and as a - 2 pi
    wrapped = frames.wrap_angle(fm[:, 2])
    assert np.any((fm[:, 2] > math.pi) & (wrapped < 0)) or np.any(fm[:, 2] < -math.pi)


def test_corrected_in_our_frame_is_midpoint_integration():
    rng = np.random.default_rng(8)
    inc = rng.integers(-50, 150, size=(500, 2))
    fw = odo.firmware_corrected(inc, K, W)
    ours = to_ours_mm(fw)
    ref = odo.integrate(inc, K, W, "midpoint")
    np.testing.assert_allclose(ours[:, :2], ref[:, :2], atol=1e-8)
    np.testing.assert_allclose(ours[:, 2], frames.wrap_angle(ref[:, 2]), atol=1e-9)
    assert np.all(np.abs(fw[:, 2]) <= math.pi)


def test_printed_position_update_is_end_heading_euler_in_our_frame():
    rng = np.random.default_rng(9)
    inc = rng.integers(-50, 150, size=(300, 2))
    fw = odo.firmware_corrected(inc, K, W, position_heading="end")
    np.testing.assert_allclose(to_ours_mm(fw)[:, :2], loop_reference(inc, "end")[:, :2],
                               atol=1e-8)


def test_firmware_start_pose_is_honoured():
    fw = odo.firmware_corrected([[100, 100]], 10.0, W, pose=(5.0, 7.0, math.pi / 2))
    np.testing.assert_allclose(fw[0], [5.0 - 10.0, 7.0, math.pi / 2])  # facing -X: moves left


# --- the fixed-point model -----------------------------------------------------------------------

def test_fixed_point_hand_calculations():
    # alpha = trunc(1000 * 100 / (10 * 85)) = trunc(117.6) = 117, and -117 backwards (toward 0)
    out = odo.firmware_fixed_point([[0, 100], [100, 0]], 10.0, W)
    np.testing.assert_array_equal(out[:, 2], [117, 0])
    # centre: (0 + 100) / 2 = 50 steps = 5 mm at heading 0.117 rad: dX = trunc(-0.583) = 0,
    # dY = trunc(4.966) = 4
    assert tuple(out[0, :2]) == (0, 4)
    # backwards: -80 steps per wheel -> trunc(-9.95) = -9 mm (toward zero, not -10)
    back = odo.firmware_fixed_point([[-80, -80]], K, W)
    assert tuple(back[0]) == (0, -9, 0)
    # odd sum: (3 + 4) / 2 = 3 in C, and (-3 - 4) / 2 = -3; at 0.5 steps/mm: 6 mm (a wheel
    # base of 1 km makes alpha = trunc(0.002) = 0)
    assert tuple(odo.firmware_fixed_point([[3, 4]], 0.5, 1e6)[0]) == (0, 6, 0)
    assert tuple(odo.firmware_fixed_point([[-3, -4]], 0.5, 1e6)[0]) == (0, -6, 0)


def test_fixed_point_wrap_is_c_remainder_by_6283():
    # 117 mrad per update from 6200: 6317 % 6283 = 34; from -6200 going the other way: -34
    up = odo.firmware_fixed_point([[0, 100]], 10.0, W, pose=(0, 0, 6200))
    down = odo.firmware_fixed_point([[100, 0]], 10.0, W, pose=(0, 0, -6200))
    assert up[0, 2] == 34
    assert down[0, 2] == -34


def test_fixed_point_carry_stays_close_to_floating_point_over_a_long_run():
    travel = odo.plan_wheel_travel([[3000.0, 2 * math.pi], [3000.0, -2 * math.pi]] * 5, W, 10.0)
    inc = odo.encoder_increments(travel, K)
    ref = to_ours_mm(odo.firmware_corrected(inc, K, W, position_heading="end"))
    carry = odo.firmware_fixed_point(inc, K, W, carry=True)
    trunc = odo.firmware_fixed_point(inc, K, W)
    err_carry = np.hypot(carry[-1, 1] - ref[-1, 0], -carry[-1, 0] - ref[-1, 1])
    err_trunc = np.hypot(trunc[-1, 1] - ref[-1, 0], -trunc[-1, 0] - ref[-1, 1])
    assert err_carry < 50  # 30 m driven: heading quantised to 1 mrad, but nothing accumulates
    assert err_trunc > 10 * err_carry
    # heading: the carried integer heading is the truncated exact heading (ten wraps by 6283)
    exact_mrad = 1000 * (inc[:, 1].sum() - inc[:, 0].sum()) / (K * W)
    assert abs(carry[-1, 2] - exact_mrad) <= 1 + 10 * 0.2


def test_fixed_point_source_rounding_by_hand():
    # Util::divRoundUp read from the firmware's Util.cpp: C quotient, then one step away from 0
    # when |remainder| >= |b / 2| (a quotient of 0 steps to +1).
    # 100 steps: 100000 / 8043 = 12 r 3484 < 4021 -> 12 mm; 12000 / 85 = 141 r 15 -> 141 mrad
    assert odo.firmware_fixed_point([[0, 100]], 8.043, W, alpha_rounding="source")[0, 2] == 141
    # -100 steps: -12 r -3484 -> -12 mm -> -141 mrad (symmetric when the quotient is not 0)
    assert odo.firmware_fixed_point([[100, 0]], 8.043, W, alpha_rounding="source")[0, 2] == -141
    # 5 steps: 5000 / 8043 = 0 r 5000 >= 4021 -> 1 mm -> 1000 / 85 = 11 r 65 >= 42 -> 12 mrad
    assert odo.firmware_fixed_point([[0, 5]], 8.043, W, alpha_rounding="source")[0, 2] == 12
    # -5 steps: 0 r -5000, |r| >= 4021 and the quotient 0 is stepped UP: +1 mm -> +12 mrad
    assert odo.firmware_fixed_point([[5, 0]], 8.043, W, alpha_rounding="source")[0, 2] == 12
    # 3 steps: 3000 < 4021 -> 0 mm -> no turn at all (truncation gives 1000*3/683.655 -> 4)
    assert odo.firmware_fixed_point([[0, 3]], 8.043, W, alpha_rounding="source")[0, 2] == 0
    assert odo.firmware_fixed_point([[0, 3]], 8.043, W)[0, 2] == 4


def test_fixed_point_source_rounding_on_one_lap_of_a_1_m_circle():
    # 1 cm updates on a 1 m circle: every update's wheel difference is 6 to 8 steps, which the
    # source rounds to 1 mm = 12 mrad; 656 updates count 7872 mrad instead of 6283 (+25 %),
    # and the mirrored right-hand lap counts the same +7872 (the stepped-up quotient of 0).
    for turn in (2 * math.pi, -2 * math.pi):
        inc = odo.encoder_increments(odo.plan_wheel_travel([[2000 * math.pi, turn]], W, 10.0), K)
        diff = np.abs(inc[:, 1] - inc[:, 0])
        assert len(inc) == 656 and diff.min() >= 6 and diff.max() <= 8
        out = odo.firmware_fixed_point(inc, K, W, alpha_rounding="source")
        assert out[-1, 2] == 7872 % 6283
        assert np.all(np.diff(np.concatenate([[0], out[:, 2]])) % 6283 == 12)


def test_fixed_point_returns_integers():
    out = odo.firmware_fixed_point([[10, 12]] * 3, K, W, pose=(1, 2, 3))
    assert out.dtype == np.int64


# --- bad input ----------------------------------------------------------------------------------

@pytest.mark.parametrize(("call", "name"), [
    (lambda: odo.integrate([[1.0, np.nan]], K, W), "increments"),
    (lambda: odo.integrate([1.0, 2.0], K, W), "increments"),
    (lambda: odo.integrate(np.ones((3, 3)), K, W), "increments"),
    (lambda: odo.integrate([["a", "b"]], K, W), "increments"),
    (lambda: odo.integrate([[1, 2]], 0.0, W), "steps_per_mm"),
    (lambda: odo.integrate([[1, 2]], -K, W), "steps_per_mm"),
    (lambda: odo.integrate([[1, 2]], K, 0.0), "track_width_mm"),
    (lambda: odo.integrate([[1, 2]], K, np.inf), "track_width_mm"),
    (lambda: odo.integrate([[1, 2]], K, W, "rk4"), "method"),
    (lambda: odo.integrate([[1, 2]], K, W, pose=(0, 0)), "pose"),
    (lambda: odo.integrate([[1, 2]], K, W, pose=(0, np.nan, 0)), "pose"),
    (lambda: odo.pose_update([0, 0], 1.0, 0.0), "pose"),
    (lambda: odo.pose_update(np.zeros((2, 3)), [1.0, 2.0, 3.0], 0.0), "distance"),
    (lambda: odo.pose_update([0, 0, 0], 1.0, 0.0, "exactly"), "method"),
    (lambda: odo.chord_factor(np.nan), "dtheta"),
    (lambda: odo.firmware_scheme([[1, 2]], K, W, wrap="mod"), "wrap"),
    (lambda: odo.firmware_scheme([[1, 2]], K, W, center="mean"), "center"),
    (lambda: odo.firmware_scheme([[1, 2]], K, W, position_heading="start"), "position_heading"),
    (lambda: odo.firmware_as_printed([[1, 2]], K, W, wrap="pi"), "wrap"),
    (lambda: odo.firmware_fixed_point([[1.5, 2]], K, W), "increments"),
    (lambda: odo.firmware_fixed_point([[1, 2]], K, W, pose=(0.5, 0, 0)), "pose"),
    (lambda: odo.firmware_fixed_point([[1, 2]], K, W, carry="yes"), "carry"),
    (lambda: odo.firmware_fixed_point([[2**40, 2]], K, W), "increments"),
    (lambda: odo.firmware_fixed_point([[1, 2]], K, W, alpha_rounding="round"), "alpha_rounding"),
    (lambda: odo.firmware_fixed_point([[1, 2]], 8.0435, W, alpha_rounding="source"),
     "steps_per_mm"),
    (lambda: odo.firmware_fixed_point([[1, 2]], K, 85.5, alpha_rounding="source"),
     "track_width_mm"),
    (lambda: odo.plan_wheel_travel([[1.0, 2.0, 3.0]], W, 10.0), "segments"),
    (lambda: odo.plan_wheel_travel([[1.0, 2.0]], W, 0.0), "max_step_mm"),
    (lambda: odo.encoder_increments([1.0, 2.0], K), "travel_mm"),
])
def test_bad_input_raises_value_error_naming_it(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# --------------------------------------------------------------------------------------------
def test_pose_update_validates_every_argument():
    for args, name in ((([math.nan, 0.0, 0.0], 1.0, 0.0), "pose"),
                       (([0.0, 0.0, 0.0], math.nan, 0.0), "distance"),
                       (([0.0, 0.0, 0.0], 1.0, math.inf), "dtheta")):
        with pytest.raises(ValueError, match=name):
            odo.pose_update(*args)


# --------------------------------------------------------------------------------------------
# SI odometry: against ros2_controllers' and WPILib's published update formulas

def _ros2_integrate_exact(deltas_left, deltas_right, track_width):
    """diff_drive_controller/src/odometry.cpp (ros2_controllers): updateFromVelocity /
    integrateExact, written out from its published source: runge-kutta 2 below 1e-6 rad,
    else the circle r = ds / dtheta."""
    x = y = heading = 0.0
    out = []
    for dl, dr in zip(deltas_left, deltas_right, strict=True):
        linear = 0.5 * (dl + dr)
        angular = (dr - dl) / track_width
        if abs(angular) < 1e-6:
            direction = heading + 0.5 * angular
            x += linear * math.cos(direction)
            y += linear * math.sin(direction)
            heading += angular
        else:
            heading_old = heading
            r = linear / angular
            heading += angular
            x += r * (math.sin(heading) - math.sin(heading_old))
            y += -r * (math.cos(heading) - math.cos(heading_old))
        out.append((x, y, heading))
    return np.array(out)


def _wpilib_twist_exp(deltas_left, deltas_right, track_width):
    """WPILib DifferentialDriveOdometry.update: Twist2d(ds, 0, dtheta) through Pose2d.exp,
    whose sin(theta)/theta and (1 - cos(theta))/theta switch to 1 - theta^2/6 and theta/2
    below 1e-9 rad."""
    x = y = heading = 0.0
    out = []
    for dl, dr in zip(deltas_left, deltas_right, strict=True):
        dx = 0.5 * (dl + dr)
        dtheta = (dr - dl) / track_width
        if abs(dtheta) < 1e-9:
            s, c = 1.0 - dtheta**2 / 6.0, 0.5 * dtheta
        else:
            s, c = math.sin(dtheta) / dtheta, (1 - math.cos(dtheta)) / dtheta
        tx, ty = dx * s, dx * c  # the body-frame displacement, then rotated by the heading
        x += tx * math.cos(heading) - ty * math.sin(heading)
        y += tx * math.sin(heading) + ty * math.cos(heading)
        heading += dtheta
        out.append((x, y, heading))
    return np.array(out)


def test_integrate_si_is_ros2_and_wpilib_odometry():
    rng = np.random.default_rng(7)
    left = rng.uniform(-0.02, 0.05, 500)
    right = left + rng.normal(0.0, 0.01, 500)
    right[::7] = left[::7]  # straight updates too (the small-angle branches)
    w = 0.287
    got = odo.integrate_si(left, right, w)
    np.testing.assert_allclose(got, _ros2_integrate_exact(left, right, w), atol=1e-12)
    np.testing.assert_allclose(got, _wpilib_twist_exp(left, right, w), atol=1e-12)


def test_integrate_si_methods_and_start_pose_by_hand():
    # a quarter circle of radius 1 m (W = 0.5 m) in one update, from (1, 2) facing +y
    w, r = 0.5, 1.0
    left, right = (r - w / 2) * math.pi / 2, (r + w / 2) * math.pi / 2
    start = (1.0, 2.0, math.pi / 2)
    exact = odo.integrate_si([left], [right], w, pose=start)[0]
    np.testing.assert_allclose(exact, [0.0, 3.0, math.pi], atol=1e-15)
    euler = odo.integrate_si([left], [right], w, "euler", pose=start)[0]
    np.testing.assert_allclose(euler, [1.0, 2.0 + math.pi / 2, math.pi], atol=1e-15)
    mid = odo.integrate_si([left], [right], w, "midpoint", pose=start)[0]
    h = math.pi / 2 * (math.sqrt(0.5))  # the arc length along the chord's direction
    np.testing.assert_allclose(mid, [1.0 - h, 2.0 + h, math.pi], atol=1e-15)


def test_body_motion_by_hand():
    m = odo.body_motion([0.1, -0.2], [0.3, 0.2], 0.4)
    assert isinstance(m, odo.BodyMotion)
    np.testing.assert_allclose(m.distance, [0.2, 0.0])
    np.testing.assert_allclose(m.dtheta, [0.5, 1.0])


@pytest.mark.parametrize("call, name", [
    (lambda: odo.integrate_si([0.1], [0.1, 0.2], 0.3), "delta_right"),
    (lambda: odo.integrate_si([], [], 0.3), "delta_left"),
    (lambda: odo.integrate_si([[0.1]], [[0.1]], 0.3), "delta_left"),
    (lambda: odo.integrate_si([math.nan], [0.1], 0.3), "delta_left"),
    (lambda: odo.integrate_si([0.1], [0.1], 0.0), "track_width"),
    (lambda: odo.integrate_si([0.1], [0.1], True), "track_width"),
    (lambda: odo.integrate_si([0.1], [0.1], 0.3, "rk4"), "method"),
    (lambda: odo.integrate_si([0.1], [0.1], 0.3, pose=(0, 0)), "pose"),
    (lambda: odo.body_motion([0.1], ["a"], 0.3), "delta_right"),
])
def test_integrate_si_rejects_bad_input(call, name):
    with pytest.raises(ValueError, match=name):
        call()
