"""wheelkin.odometry, section "Uncertainty": Jacobians, covariance propagation, Monte Carlo,
UMBmark.

Independent references: the Jacobians against sympy's derivatives of the exact-arc update
(evaluated in 50-digit arithmetic near a straight step) and against central differences;
the covariance of a straight run against the closed form derived by hand (below); the
propagated covariance against the sample covariance of Monte Carlo runs, with tolerances
from the sampling distributions; the UMBmark factors against a kinematic simulation of the
square, written here, of a robot with known wheel diameters and track.
"""

from __future__ import annotations

import cmath
import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from wheelkin import odometry as odo

W = 0.085  # the Radon Ulzer's track width, m


# ------------------------------------------------------------------------------------------
# the exact-arc update in sympy (the chapter's derivation, written out again here)

_x, _y, _th, _sl, _sr, _w = sp.symbols("x y theta s_L s_R W", real=True)
_ds = (_sl + _sr) / 2
_dth = (_sr - _sl) / _w
_STATE = sp.Matrix([
    _x + _ds / _dth * (sp.sin(_th + _dth) - sp.sin(_th)),
    _y - _ds / _dth * (sp.cos(_th + _dth) - sp.cos(_th)),
    _th + _dth,
])
_F_POSE = _STATE.jacobian([_x, _y, _th])
_F_WHEELS = _STATE.jacobian([_sl, _sr])
_ARGS = (_x, _y, _th, _sl, _sr, _w)
_f_pose = sp.lambdify(_ARGS, _F_POSE, "numpy")
_f_wheels = sp.lambdify(_ARGS, _F_WHEELS, "numpy")


def _random_steps(rng, n, min_turn=1e-3):
    """Random (pose, left, right) with |Δθ| >= min_turn (the sympy form divides by Δθ)."""
    out = []
    while len(out) < n:
        pose = rng.uniform([-2, -2, -7], [2, 2, 7])
        left, right = rng.uniform(-0.2, 0.2, size=2)
        if abs(right - left) / W >= min_turn:
            out.append((pose, float(left), float(right)))
    return out


def test_jacobians_match_sympy_at_random_steps():
    rng = np.random.default_rng(14)
    for pose, left, right in _random_steps(rng, 300):
        jac = odo.step_jacobians(pose, left, right, W)
        args = (*pose, left, right, W)
        np.testing.assert_allclose(jac.wrt_pose, np.array(_f_pose(*args), dtype=float),
                                   rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(jac.wrt_wheels, np.array(_f_wheels(*args), dtype=float),
                                   rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("turn", [0.0, 1e-9, 3e-6, 9.9e-5, 1.01e-4, 3e-4, 1e-2])
def test_jacobians_near_a_straight_step_match_sympy_in_50_digits(turn):
    """Both sides of the series switch at |Δθ| = 1e-4, against 50-digit sympy values."""
    pose, left = (0.3, -0.2, 0.7), 0.05
    right = left + turn * W
    jac = odo.step_jacobians(pose, left, right, W)
    if turn == 0.0:  # the sympy form is 0/0: take its limit
        subs = {_x: pose[0], _y: pose[1], _th: sp.Rational(7, 10), _sl: sp.Rational(1, 20),
                _w: sp.Rational(85, 1000)}
        expected = np.array([[float(sp.limit(e.subs(subs), _sr, sp.Rational(1, 20)))
                              for e in row] for row in _F_WHEELS.tolist()])
    else:
        with mpmath.workdps(50):
            subs = {_x: pose[0], _y: pose[1], _th: mpmath.mpf("0.7"), _sl: mpmath.mpf("0.05"),
                    _w: mpmath.mpf("0.085")}
            subs[_sr] = subs[_sl] + mpmath.mpf(repr(turn)) * subs[_w]
            expected = np.array(_F_WHEELS.evalf(50, subs=subs).tolist(), dtype=float)
    np.testing.assert_allclose(jac.wrt_wheels, expected, rtol=1e-9, atol=1e-10)


def _numeric(pose, left, right, h=1e-6):
    def f(v):
        return np.array(odo.propagate_covariance(v[:3], np.zeros((3, 3)), v[3], v[4], W, 0.0,
                                                 0.0).pose)
    v0 = np.array([*pose, left, right], dtype=float)
    cols = []
    for i in range(5):
        e = np.zeros(5)
        e[i] = h
        cols.append((f(v0 + e) - f(v0 - e)) / (2 * h))
    full = np.column_stack(cols)
    return full[:, :3], full[:, 3:]


def test_jacobians_match_central_differences_including_straight_steps():
    rng = np.random.default_rng(41)
    cases = [*_random_steps(rng, 100), ((0.1, 0.2, 1.0), 0.1, 0.1),
             ((0, 0, -2.0), -0.05, -0.05), ((0, 0, 0.0), -0.03, 0.03)]
    for pose, left, right in cases:
        jac = odo.step_jacobians(pose, left, right, W)
        f_pose, f_wheels = _numeric(pose, left, right)
        np.testing.assert_allclose(jac.wrt_pose, f_pose, atol=1e-8)
        np.testing.assert_allclose(jac.wrt_wheels, f_wheels, atol=1e-6, rtol=1e-7)


def test_step_pose_is_the_closed_form_arc():
    for pose, left, right in _random_steps(np.random.default_rng(5), 50):
        new = odo.propagate_covariance(pose, np.zeros((3, 3)), left, right, W, 0, 0).pose
        ds, dth = (left + right) / 2, (right - left) / W
        radius = ds / dth
        x = pose[0] + radius * (math.sin(pose[2] + dth) - math.sin(pose[2]))
        y = pose[1] - radius * (math.cos(pose[2] + dth) - math.cos(pose[2]))
        np.testing.assert_allclose(new, [x, y, pose[2] + dth], rtol=1e-11, atol=1e-12)


# ------------------------------------------------------------------------------------------
# properties of the propagation

def _random_path(rng, n=400):
    ds = rng.uniform(-0.01, 0.03, n)
    dth = rng.uniform(-0.2, 0.2, n) * (rng.random(n) < 0.7)
    return ds - dth * W / 2, ds + dth * W / 2


@pytest.mark.parametrize("seed", range(5))
def test_covariance_stays_symmetric_positive_semidefinite(seed):
    rng = np.random.default_rng(seed)
    left, right = _random_path(rng)
    root = rng.normal(size=(3, 3)) * 1e-3
    run = odo.propagate_path(rng.normal(size=3), root @ root.T, left, right, W,
                             rng.uniform(0, 1e-4), rng.uniform(0, 1e-4))
    for sigma in run.covariances:
        assert np.array_equal(sigma, sigma.T)
        assert np.linalg.eigvalsh(sigma).min() >= -1e-15 * max(1.0, np.abs(sigma).max())
    # each step's covariance is the start's plus only non-negative added noise: the variance
    # of the heading (a sum of independent errors) never decreases
    assert np.all(np.diff(run.covariances[:, 2, 2]) >= 0)


def test_zero_noise_keeps_a_known_pose_known():
    left, right = _random_path(np.random.default_rng(9))
    run = odo.propagate_path([0.5, -1, 2], np.zeros((3, 3)), left, right, W, 0.0, 0.0)
    assert np.all(run.covariances == 0.0)


def test_path_equals_repeated_single_steps():
    rng = np.random.default_rng(11)
    left, right = _random_path(rng, 60)
    run = odo.propagate_path([0, 0, 0.3], np.eye(3) * 1e-6, left, right, W, 2e-5, 5e-5)
    pose, sigma = np.array([0, 0, 0.3]), np.eye(3) * 1e-6
    for k in range(60):
        pose, sigma = odo.propagate_covariance(pose, sigma, left[k], right[k], W, 2e-5, 5e-5)
        np.testing.assert_allclose(run.poses[k + 1], pose, atol=1e-12)
        np.testing.assert_allclose(run.covariances[k + 1], sigma, rtol=1e-10, atol=1e-18)


@pytest.mark.parametrize(("n", "k_left", "k_right"), [(1000, 1e-6, 1e-6), (37, 3e-5, 1e-5),
                                                       (1, 1e-4, 0.0)])
def test_straight_run_matches_the_hand_derived_closed_form(n, k_left, k_right):
    """A straight run of length s in N updates of h = s/N, linearised by hand.

    Per update j the errors are d_j = (e_R + e_L)/2 (distance) and t_j = (e_R - e_L)/W
    (heading), with Var d = K h/4, Var t = K h/W², Cov(d, t) = (k_R - k_L) h/(2W),
    K = k_L + k_R. At heading 0, x_N = sum d_j, θ_N = sum t_j, and the lateral position moves
    h θ per update with the heading half-way through it: y_N = h sum_j t_j (N - j - 1/2),
    j = 0 .. N-1. Summing: Var y = h² (K h/W²) sum_{m=1..N} (m - 1/2)² = K (s³/3 - s h²/12)/W²,
    Cov(y, θ) = K s²/(2W²), Cov(x, y) = (k_R - k_L) s²/(4W), Cov(x, θ) = (k_R - k_L) s/(2W).
    """
    s = 10.0
    h = s / n
    steps = np.full(n, h)
    run = odo.propagate_path([0, 0, 0], np.zeros((3, 3)), steps, steps, W, k_left, k_right)
    K, D = k_left + k_right, k_right - k_left
    expected = np.array([
        [K * s / 4, D * s**2 / (4 * W), D * s / (2 * W)],
        [D * s**2 / (4 * W), K * (s**3 / 3 - s * h**2 / 12) / W**2, K * s**2 / (2 * W**2)],
        [D * s / (2 * W), K * s**2 / (2 * W**2), K * s / W**2],
    ])
    np.testing.assert_allclose(run.covariances[-1], expected, rtol=1e-9, atol=1e-15)


def test_lateral_variance_grows_with_the_cube_of_distance():
    steps = np.full(4000, 0.005)
    run = odo.propagate_path([0, 0, 0], np.zeros((3, 3)), steps, steps, W, 1e-6, 1e-6)
    distance = np.arange(4001) * 0.005
    pick = [400, 800, 1600, 3200]
    slope = np.polyfit(np.log(distance[pick]), np.log(run.covariances[pick, 1, 1]), 1)[0]
    assert abs(slope - 3.0) < 1e-3


# ------------------------------------------------------------------------------------------
# Monte Carlo against the propagation

def test_monte_carlo_matches_the_propagated_covariance_in_the_linear_regime():
    """4,000 runs of a 2 m drive with a turn, errors small enough to stay linear.

    Sample variances: (n-1) S/σ² ~ χ²(n-1), standard error sqrt(2/(n-1)) = 0.022; allowed 4
    of them. The mean squared Mahalanobis distance of 3-D Gaussian errors is 3 with standard
    error sqrt(6/n) = 0.039; allowed 4 of them. The 2-D (x, y) fractions inside the 1, 2, 3
    sigma ellipses follow a binomial law around 1 - exp(-m²/2); allowed 4 standard errors.
    """
    runs = 4000
    left = np.concatenate([np.full(100, 0.01), np.full(100, 0.01 - 0.005 * W)])
    right = np.concatenate([np.full(100, 0.01), np.full(100, 0.01 + 0.005 * W)])
    k = 1e-9
    run = odo.propagate_path([0, 0, 0], np.zeros((3, 3)), left, right, W, k, 2 * k)
    ends = odo.monte_carlo_poses([0, 0, 0], left, right, W, k, 2 * k, runs,
                                 np.random.default_rng(2024))
    sigma = run.covariances[-1]
    err = ends - run.poses[-1]
    sample = np.cov(err.T)
    se = math.sqrt(2 / (runs - 1))
    assert np.all(np.abs(np.diag(sample) / np.diag(sigma) - 1) < 4 * se)
    d2 = np.einsum("ni,ij,nj->n", err, np.linalg.inv(sigma), err)
    assert abs(d2.mean() - 3) < 4 * math.sqrt(6 / runs)
    d2_xy = np.einsum("ni,ij,nj->n", err[:, :2], np.linalg.inv(sigma[:2, :2]), err[:, :2])
    for m in (1, 2, 3):
        p = 1 - math.exp(-m * m / 2)
        assert abs(np.mean(d2_xy <= m * m) - p) < 4 * math.sqrt(p * (1 - p) / runs)


def test_monte_carlo_is_reproducible_and_reports_at_the_asked_updates():
    h = np.full(50, 0.02)
    a = odo.monte_carlo_poses([0, 0, 0], h, h, W, 1e-5, 1e-5, 300, np.random.default_rng(3))
    b = odo.monte_carlo_poses([0, 0, 0], h, h, W, 1e-5, 1e-5, 300, np.random.default_rng(3),
                              at=[0, 25, 50])
    assert b.shape == (3, 300, 3)
    assert np.array_equal(a, b[2])
    assert np.all(b[0] == 0.0)
    quiet = odo.monte_carlo_poses([0, 0, 0], h, h, W, 0.0, 0.0, 4, np.random.default_rng(3))
    np.testing.assert_allclose(quiet, np.tile([1.0, 0.0, 0.0], (4, 1)), atol=1e-12)


# ------------------------------------------------------------------------------------------
# UMBmark against a simulation with known errors

def _arc(z, heading, distance, turn):
    """Exact arc in complex form: position z, heading; returns the new (z, heading)."""
    if turn == 0.0:
        return z + distance * cmath.exp(1j * heading), heading
    radius = distance / turn
    centre = z + 1j * radius * cmath.exp(1j * heading)
    return centre - 1j * radius * cmath.exp(1j * (heading + turn)), heading + turn


def _square(diameter_ratio, track_ratio, side, track, clockwise, scales=None):
    """True end (x, y) of a robot that believes it drives the square exactly.

    The odometry assumes equal wheels and the track ``track``; the true right and left wheels
    roll 2 E_d/(E_d + 1) and 2/(E_d + 1) of what the odometry counts (or ``scales`` =
    (left, right) if given), the true track is E_b W. Legs: equal counts (believed straight);
    corners: opposite counts for a believed 90 degree turn on the spot.
    """
    if scales is None:
        scales = (2 / (diameter_ratio + 1), 2 * diameter_ratio / (diameter_ratio + 1))
    c_left, c_right = scales
    true_track = track_ratio * track
    sign = -1.0 if clockwise else 1.0
    z, heading = 0j, 0.0
    for _ in range(4):
        left, right = c_left * side, c_right * side
        z, heading = _arc(z, heading, (left + right) / 2, (right - left) / true_track)
        spin = sign * track * math.pi / 4  # believed: each wheel rolls W π/4 for 90 degrees
        left, right = -c_left * spin, c_right * spin
        z, heading = _arc(z, heading, (left + right) / 2, (right - left) / true_track)
    return np.array([z.real, z.imag])


def _angles(diameter_ratio, track_ratio, side, track):
    """(α, β) of the paper for known factors: the corner deficit and the bend of a leg."""
    alpha = 0.5 * math.pi * (1 - 1 / track_ratio)
    # a leg of chord ~ L on an arc of radius R = (E_b W/2)(E_d + 1)/(E_d - 1)
    beta = 2 * math.asin(side * (diameter_ratio - 1)
                         / (track_ratio * track * (diameter_ratio + 1)))
    return alpha, beta


@pytest.mark.parametrize(("e_d", "e_b"), [(1.002, 1.0), (1.0, 1.02), (1.001, 0.985),
                                          (0.9985, 1.012), (0.9995, 0.995)])
def test_umbmark_recovers_known_errors_to_first_order(e_d, e_b):
    side, track = 4.0, 0.34
    cw = _square(e_d, e_b, side, track, clockwise=True)
    ccw = _square(e_d, e_b, side, track, clockwise=False)
    got = odo.umbmark_correction(cw, ccw, side, track)
    alpha, beta = _angles(e_d, e_b, side, track)
    got_alpha, got_beta = _angles(got.diameter_ratio, got.track_ratio, side, track)
    # first order: what is left is second order in the angles
    second = alpha**2 + beta**2
    assert abs(got_alpha - alpha) < second and abs(got_beta - beta) < second
    # and it shrinks quadratically: errors ten times smaller, residual ~100 times smaller
    small_d, small_b = 1 + (e_d - 1) / 10, 1 + (e_b - 1) / 10
    small = odo.umbmark_correction(_square(small_d, small_b, side, track, True),
                                   _square(small_d, small_b, side, track, False), side, track)
    residual = max(abs(got.diameter_ratio - e_d), abs(got.track_ratio - e_b))
    residual_small = max(abs(small.diameter_ratio - small_d), abs(small.track_ratio - small_b))
    assert residual_small < residual / 30


def test_umbmark_correction_reduces_the_return_error_tenfold_or_more():
    side, track, e_d, e_b = 4.0, 0.34, 1.0015, 1.01
    before = [_square(e_d, e_b, side, track, cw) for cw in (True, False)]
    corr = odo.umbmark_correction(*before, side, track)
    # the corrected odometry counts c_L, c_R per nominal unit and uses the track E_b W; the
    # true wheels roll t_L, t_R: relative to the corrected odometry they roll t/c
    c_left, c_right = 2 / (corr.diameter_ratio + 1), 2 / (1 / corr.diameter_ratio + 1)
    t_left, t_right = 2 / (e_d + 1), 2 * e_d / (e_d + 1)
    new_track = corr.track_ratio * track
    after = [_square(None, e_b * track / new_track, side, new_track, cw,
                     scales=(t_left / c_left, t_right / c_right)) for cw in (True, False)]
    worst_before = max(np.hypot(*e) for e in before)
    worst_after = max(np.hypot(*e) for e in after)
    assert worst_after < worst_before / 10


def test_umbmark_docstring_conventions_pure_errors():
    side, track = 4.0, 0.34
    # type A only: both returns mirror each other about the x axis, E_d = 1 exactly
    a = odo.umbmark_correction([-0.08, -0.08], [-0.08, 0.08], side, track)
    assert a.diameter_ratio == 1.0 and a.track_ratio > 1
    # type B only (right wheel larger, legs bend left): E_b = 1, E_d > 1
    b = odo.umbmark_correction([-0.08, -0.08], [0.08, -0.08], side, track)
    assert b.track_ratio == 1.0 and b.diameter_ratio > 1
    cw = _square(1.003, 1.0, side, track, True)
    ccw = _square(1.003, 1.0, side, track, False)
    assert cw[0] < 0 and cw[1] < 0 and ccw[0] > 0 and ccw[1] < 0
    for components in ("x", "y", "xy"):
        got = odo.umbmark_correction(cw, ccw, side, track, components=components)
        assert abs(got.diameter_ratio - 1.003) < 3e-4


# ------------------------------------------------------------------------------------------
# bad input

Z = np.zeros((3, 3))


@pytest.mark.parametrize(("call", "match"), [
    (lambda: odo.step_jacobians([0, 0], 0.1, 0.1, W), "pose must have shape"),
    (lambda: odo.step_jacobians([0, 0, math.nan], 0.1, 0.1, W), "pose must not contain"),
    (lambda: odo.step_jacobians([0, 0, 0], "a", 0.1, W), "delta_left"),
    (lambda: odo.step_jacobians([0, 0, 0], 0.1, math.inf, W), "delta_right"),
    (lambda: odo.step_jacobians([0, 0, 0], 0.1, 0.1, 0.0), "track_width must be"),
    (lambda: odo.propagate_covariance([0, 0, 0], np.eye(2), 0.1, 0.1, W, 0, 0),
     "covariance must have shape"),
    (lambda: odo.propagate_covariance([0, 0, 0], [[0, 1, 0], [0, 0, 0], [0, 0, 0]], 0.1, 0.1,
                                      W, 0, 0), "covariance must be symmetric"),
    (lambda: odo.propagate_covariance([0, 0, 0], -np.eye(3), 0.1, 0.1, W, 0, 0),
     "positive semi-definite"),
    (lambda: odo.propagate_covariance([0, 0, 0], Z, 0.1, 0.1, W, -1e-6, 0), "k_left"),
    (lambda: odo.propagate_covariance([0, 0, 0], Z, 0.1, 0.1, W, 0, math.nan), "k_right"),
    (lambda: odo.propagate_path([0, 0, 0], Z, [0.1, 0.1], [0.1], W, 0, 0), "same length"),
    (lambda: odo.propagate_path([0, 0, 0], Z, [], [], W, 0, 0), "N >= 1"),
    (lambda: odo.propagate_path([0, 0, 0], Z, [[0.1]], [[0.1]], W, 0, 0), "1-D"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 0,
                                   np.random.default_rng(0)), "runs must be"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 2.5,
                                   np.random.default_rng(0)), "runs must be"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, True,
                                   np.random.default_rng(0)), "runs must be"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 5, 0,
                                   at=[0, 2]), "rng must be"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 5,
                                   np.random.default_rng(0), at=[2]), "at must be"),
    (lambda: odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 5,
                                   np.random.default_rng(0), at=[0.5]), "at must be"),
    (lambda: odo.umbmark_correction([0, 0, 0], [0, 0], 4, 0.3), "cw_end must have shape"),
    (lambda: odo.umbmark_correction([0, 0], [0, math.nan], 4, 0.3), "ccw_end must not"),
    (lambda: odo.umbmark_correction([0, 0], [0, 0], -4, 0.3), "side must be"),
    (lambda: odo.umbmark_correction([0, 0], [0, 0], 4, 0), "track_width must be"),
    (lambda: odo.umbmark_correction([0, 0], [0, 0], 4, 0.3, components="z"), "components"),
    (lambda: odo.umbmark_correction([-8, -8], [-8, 8], 4, 0.3), "too large"),
    (lambda: odo.umbmark_correction([-3, -3], [3, -3], 4, 30.0), "smaller than half the track"),
])
def test_bad_input_is_refused_with_a_message_naming_it(call, match):
    with pytest.raises((ValueError, TypeError), match=match):
        call()


def test_rng_must_be_a_generator_type_error():
    with pytest.raises(TypeError, match=r"numpy\.random\.Generator"):
        odo.monte_carlo_poses([0, 0, 0], [0.1], [0.1], W, 0, 0, 5, np.random.RandomState(0))
