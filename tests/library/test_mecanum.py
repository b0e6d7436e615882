"""Tests of wheelkin.mecanum against independent values: a sympy derivation from the roller
constraint, the document's own matrices through the frame converters, hand calculations, and
properties (round trips, mirror symmetry, linearity, closed-loop simulations)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import frames, mecanum
from wheelkin.mecanum import (
    DOCUMENT_MAX_SPEED,
    EXAMPLE_GEOMETRY,
    FIGHTING_PATTERN,
    WHEEL_NAMES,
    MecanumGeometry,
    circle_speed,
    circle_twist,
    fighting_component,
    forward_kinematics,
    forward_matrix,
    go_to_point_twist,
    grip_usage,
    inverse_kinematics,
    inverse_matrix,
    limit_speed,
    max_rim_speed,
)
from wheelkin.units import FOOT

G = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
finite = st.floats(-10, 10, allow_nan=False)
dims = st.floats(0.01, 2.0)
angles = st.floats(0.1, math.pi / 2 - 0.1)


# --- an independent derivation: the rolling constraint of each wheel, solved by sympy ------

def _sympy_rows():
    """phi_i from 'contact velocity along the roller axis = hub velocity along it'."""
    vx, vy, w, a, b, r, g = sp.symbols("v_x v_y omega a b r gamma", real=True)
    phi = sp.Symbol("phi")
    # wheel positions and the roller axis at the contact point, X arrangement (seen from
    # below the contact rollers form an X... i.e. from above an X of the upper rollers)
    layout = {"FL": (a, b, -1), "FR": (a, -b, 1), "RL": (-a, b, 1), "RR": (-a, -b, -1)}
    rows = []
    for name in WHEEL_NAMES:
        x, y, s = layout[name]
        contact = sp.Matrix([vx - w * y, vy + w * x])
        axis = sp.Matrix([sp.sin(g), s * sp.cos(g)])  # roller axis, angle gamma to the axle
        hub = sp.Matrix([r * phi, 0])                 # hub surface velocity (rolls along x)
        rows.append(sp.solve(sp.Eq(contact.dot(axis), hub.dot(axis)), phi)[0])
    return sp.lambdify((vx, vy, w, a, b, r, g), rows, "numpy")


SYMPY_ROWS = _sympy_rows()


def test_inverse_matches_sympy_derivation_at_many_points():
    rng = np.random.default_rng(4)
    for _ in range(200):
        vx, vy, w = rng.uniform(-3, 3, 3)
        a, b, r = rng.uniform(0.02, 1.0, 3)
        gamma = rng.uniform(0.2, 1.4)
        g = MecanumGeometry(wheel_radius=r, half_wheelbase=a, half_track=b, roller_angle=gamma)
        expected = np.array(SYMPY_ROWS(vx, vy, w, a, b, r, gamma), dtype=float)
        np.testing.assert_allclose(inverse_kinematics(vx, vy, w, g), expected,
                                   rtol=1e-12, atol=1e-9)


def test_contract_formulas_by_hand():
    # FL = (vx - vy - k w)/r, FR = (vx + vy + k w)/r, RL = (vx + vy - k w)/r,
    # RR = (vx - vy + k w)/r, k = 0.35, r = 0.05
    vx, vy, w = 0.3, -0.2, 0.7
    hand = np.array([vx - vy - 0.35 * w, vx + vy + 0.35 * w, vx + vy - 0.35 * w,
                     vx - vy + 0.35 * w]) / 0.05
    np.testing.assert_allclose(inverse_kinematics(vx, vy, w, G), hand, rtol=1e-12)


def test_forward_left_needs_fl_rr_slower():
    fl, fr, rl, rr = inverse_kinematics(1.0, 1.0, 0.0, G)
    assert fl < fr and fl < rl and rr < fr and rr < rl


def test_forward_matrix_is_numpy_pseudo_inverse():
    for gamma in (math.pi / 4, math.pi / 3, 0.3):
        g = MecanumGeometry(wheel_radius=0.07, half_wheelbase=0.3, half_track=0.2, roller_angle=gamma)
        np.testing.assert_allclose(forward_matrix(g), np.linalg.pinv(inverse_matrix(g)),
                                   rtol=1e-12, atol=1e-15)


@settings(max_examples=60, deadline=None)
@given(finite, finite, finite, dims, dims, dims, angles)
def test_forward_after_inverse_is_identity(vx, vy, w, r, a, b, gamma):
    g = MecanumGeometry(wheel_radius=r, half_wheelbase=a, half_track=b, roller_angle=gamma)
    np.testing.assert_allclose(forward_kinematics(inverse_kinematics(vx, vy, w, g), g),
                               [vx, vy, w], atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.lists(finite, min_size=4, max_size=4), angles)
def test_rates_split_into_motion_and_fighting(rates, gamma):
    g = MecanumGeometry(wheel_radius=0.06, half_wheelbase=0.25, half_track=0.2, roller_angle=gamma)
    rates = np.array(rates)
    moving = inverse_kinematics(*forward_kinematics(rates, g), g)
    np.testing.assert_allclose(rates - moving, fighting_component(rates) * FIGHTING_PATTERN,
                               atol=1e-9)


def test_fighting_pattern_is_the_null_space():
    for gamma in (math.pi / 4, math.pi / 3):
        g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=gamma)
        np.testing.assert_allclose(inverse_matrix(g).T @ FIGHTING_PATTERN, 0.0, atol=1e-12)
        np.testing.assert_allclose(forward_kinematics(5 * FIGHTING_PATTERN, g), 0.0,
                                   atol=1e-12)
        assert np.linalg.matrix_rank(inverse_matrix(g)) == 3


@settings(max_examples=40, deadline=None)
@given(finite, finite, finite)
def test_mirror_left_right_swaps_wheels(vx, vy, w):
    # mirroring in the x axis maps (vx, vy, w) to (vx, -vy, -w) and FL<->FR, RL<->RR
    rates = inverse_kinematics(vx, vy, w, G)
    mirrored = inverse_kinematics(vx, -vy, -w, G)
    np.testing.assert_allclose(mirrored, rates[[1, 0, 3, 2]], atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(finite, finite, finite, st.floats(-5, 5))
def test_linear_in_the_twist(vx, vy, w, c):
    np.testing.assert_allclose(inverse_kinematics(c * vx, c * vy, c * w, G),
                               c * inverse_kinematics(vx, vy, w, G), atol=1e-9)


def test_sixty_degree_rollers_by_hand():
    g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=math.pi / 3)
    c = 1 / math.sqrt(3)
    k = 0.15 + 0.2 * c
    np.testing.assert_allclose(g.k, k)
    np.testing.assert_allclose(inverse_kinematics(0.0, 1.0, 0.0, g),
                               np.array([-c, c, c, -c]) / 0.05)
    np.testing.assert_allclose(inverse_kinematics(0.0, 0.0, 1.0, g),
                               np.array([-k, k, -k, k]) / 0.05)


def test_vectorised_shapes():
    out = inverse_kinematics(np.zeros((5, 2)), 1.0, np.linspace(0, 1, 2), G)
    assert out.shape == (5, 2, 4)
    back = forward_kinematics(out, G)
    assert back.shape == (5, 2, 3)
    np.testing.assert_allclose(back[..., 1], 1.0)
    assert fighting_component(out).shape == (5, 2)


# --- the document's matrices, through wheelkin.frames -----------------------------------------

def _doc_inverse(r_ft, k_ft):
    return np.array([[1, 1, -k_ft], [-1, 1, k_ft], [-1, 1, -k_ft], [1, 1, k_ft]]) / r_ft


def _doc_forward(r_ft, k_ft):
    return r_ft / 4 * np.array([[1, -1, -1, 1], [1, 1, 1, 1],
                                [-1 / k_ft, 1 / k_ft, -1 / k_ft, 1 / k_ft]])


def test_document_inverse_equals_ours_through_frames_converter():
    # With wheels 1..4 = FL, FR, RL, RR and omega counter-clockwise, L + H = a + b.
    g = EXAMPLE_GEOMETRY
    r_ft, k_ft = g.wheel_radius / FOOT, g.k / FOOT
    rng = np.random.default_rng(7)
    doc = rng.uniform(-10, 10, (50, 3))  # (Vx ft/s right, Vy ft/s forward, omega rad/s)
    ours = frames.mecanum_doc_twist_to_ours(doc[:, 0], doc[:, 1], doc[:, 2])
    np.testing.assert_allclose(inverse_kinematics(ours[:, 0], ours[:, 1], ours[:, 2], g),
                               doc @ _doc_inverse(r_ft, k_ft).T, rtol=1e-12, atol=1e-9)
    rates = doc @ _doc_inverse(r_ft, k_ft).T
    back = frames.ours_to_mecanum_doc_twist(forward_kinematics(rates, g))
    np.testing.assert_allclose(back, doc, atol=1e-9)
    np.testing.assert_allclose(rates @ _doc_forward(r_ft, k_ft).T, doc, atol=1e-9)


def test_frames_converters_from_our_side():
    t = frames.mecanum_doc_twist_to_ours(2.0, 10.0, 0.5)  # right 2 ft/s, forward 10 ft/s
    assert math.isclose(t.vx, 10 * FOOT) and math.isclose(t.vy, -2 * FOOT)
    assert t.omega == 0.5
    assert frames.ours_to_mecanum_doc_twist(t) == pytest.approx((2.0, 10.0, 0.5))
    # heading: the document's psi is clockwise from +Y; moving forward at psi, the world
    # velocity is (sin psi, cos psi) in the document and (cos theta, sin theta) in ours.
    for psi in np.linspace(-3, 3, 13):
        theta = frames.mecanum_doc_heading_to_ours(psi)
        assert math.isclose(math.cos(theta), math.sin(psi), abs_tol=1e-12)
        assert math.isclose(math.sin(theta), math.cos(psi), abs_tol=1e-12)
        assert math.isclose(frames.ours_to_mecanum_doc_heading(theta),
                            frames.wrap_angle(psi), abs_tol=1e-12)
    p = frames.mecanum_doc_pose_to_ours(10.0, -5.0, math.pi / 2)
    assert (p.x, p.y, p.theta) == pytest.approx((10 * FOOT, -5 * FOOT, 0.0))


# --- speed limit -------------------------------------------------------------------------------

def test_limit_speed_within_scaled_refused():
    ok = limit_speed((1.0, 1.0, 0.0), DOCUMENT_MAX_SPEED)
    assert ok.scale == 1.0 and ok.twist == (1.0, 1.0, 0.0) and "within" in ok.reason
    out = limit_speed((6.0, -3.0, 0.5), DOCUMENT_MAX_SPEED)
    assert math.isclose(math.hypot(*out.twist[:2]), 4.572)
    assert math.isclose(out.twist[0] / out.twist[1], -2.0)  # direction kept
    assert math.isclose(out.twist[2], 0.5 * out.scale)      # path shape kept
    assert "scaled" in out.reason and "6.708" in out.reason
    no = limit_speed((6.0, -3.0, 0.5), DOCUMENT_MAX_SPEED, refuse=True)
    assert no.twist == (0.0, 0.0, 0.0) and no.scale == 0.0 and "refused" in no.reason


def test_limit_speed_wheel_rule_is_stricter_on_diagonals_and_spins():
    g = EXAMPLE_GEOMETRY
    diag = 15 * FOOT / math.sqrt(2)
    assert limit_speed((diag, diag, 0.0), DOCUMENT_MAX_SPEED).scale == 1.0  # doc rule passes
    out = limit_speed((diag, diag, 0.0), DOCUMENT_MAX_SPEED, g)
    assert math.isclose(out.scale, 1 / math.sqrt(2))  # rim speed was 15 * sqrt(2) ft/s
    rates = inverse_kinematics(*out.twist, g)
    assert math.isclose(np.max(np.abs(rates)) * g.wheel_radius, DOCUMENT_MAX_SPEED)
    spin = limit_speed((0.0, 0.0, 20.0), DOCUMENT_MAX_SPEED, g)
    assert math.isclose(spin.twist[2], DOCUMENT_MAX_SPEED / g.k)
    assert "rim speed" in spin.reason
    assert limit_speed(frames.Twist(1.0, 0.0, 0.0), 4.572).scale == 1.0


def test_limit_speed_within_names_each_speed():
    """A twist within both limits: the reason gives the body speed and the fastest rim speed
    each with its own value (hand calculation: a 1.5 m circle in 3.6 s with the heading held,
    at the moment it moves along the body's diagonal: body speed 2 pi 1.5 / 3.6 m/s, and at
    45 deg the fastest rim moves at |vx| + |vy| = sqrt(2) times that)."""
    speed = 2 * math.pi * 1.5 / 3.6
    twist = (speed / math.sqrt(2), speed / math.sqrt(2), 0.0)
    out = limit_speed(twist, DOCUMENT_MAX_SPEED, EXAMPLE_GEOMETRY)
    assert out.scale == 1.0
    assert f"body speed {speed:.3f} m/s," in out.reason
    assert f"rim speed {math.sqrt(2) * speed:.3f} m/s <= 4.572 m/s" in out.reason
    assert "2.618" in out.reason and "3.702" in out.reason


@settings(max_examples=40, deadline=None)
@given(finite, finite, finite)
def test_limit_speed_output_never_exceeds_either_limit(vx, vy, w):
    out = limit_speed((vx, vy, w), 2.0, G)
    assert math.hypot(*out.twist[:2]) <= 2.0 + 1e-9
    assert float(max_rim_speed(*out.twist, G)) <= 2.0 + 1e-9
    assert out.reason


def test_max_rim_speed_is_the_fastest_wheel():
    rng = np.random.default_rng(1)
    tw = rng.uniform(-2, 2, (100, 3))
    for gamma in (math.pi / 4, 1.0):
        g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=gamma)
        rates = inverse_kinematics(tw[:, 0], tw[:, 1], tw[:, 2], g)
        np.testing.assert_allclose(max_rim_speed(tw[:, 0], tw[:, 1], tw[:, 2], g),
                                   np.max(np.abs(rates), axis=-1) * 0.05, rtol=1e-12)


# --- circle and go-to-point ---------------------------------------------------------------------

@pytest.mark.parametrize("heading", ["rotating", "held"])
@pytest.mark.parametrize("radius", [2.0, -1.5])
def test_circle_twist_drives_the_circle(heading, radius):
    lap = 8.0
    n = 4000
    dt = lap / n
    t = (np.arange(n) + 0.5) * dt  # midpoint of each step
    poses = frames.integrate_twist(circle_twist(radius, lap, t, heading=heading), dt)
    centre = np.array([0.0, radius])
    np.testing.assert_allclose(np.hypot(*(poses[:, :2] - centre).T), abs(radius), rtol=1e-5)
    np.testing.assert_allclose(poses[-1, :2], [0.0, 0.0], atol=1e-5)  # back after one lap
    if heading == "held":
        np.testing.assert_allclose(poses[:, 2], 0.0, atol=1e-12)
    assert math.isclose(float(circle_speed(radius, lap)), 2 * math.pi * abs(radius) / lap)


def _drive_to(start, goal, dt, *, sampled):
    """Closed loop: the twist is re-evaluated every dt and held constant over the step."""
    pose = np.array(start, dtype=float)
    direction = (goal[:2] - pose[:2]) / np.linalg.norm(goal[:2] - pose[:2])
    worst = 0.0
    for _ in range(100_000):
        tw = go_to_point_twist(pose, goal, 1.0, 0.5, dt=dt if sampled else None)
        if not np.any(tw):
            break
        ttg = max(np.linalg.norm(goal[:2] - pose[:2]) / 1.0,
                  abs(frames.wrap_angle(goal[2] - pose[2])) / 0.5)
        hold = dt if sampled else min(dt, ttg)  # the continuous law must not overshoot
        pose = frames.compose(pose, frames.se2_exp(tw, hold))
        offset = pose[:2] - np.asarray(start[:2])
        worst = max(worst, abs(offset[0] * direction[1] - offset[1] * direction[0]))
        if np.allclose(pose, [goal[0], goal[1], frames.wrap_angle(goal[2])], rtol=0, atol=1e-12):
            break
    return pose, worst


START = np.array([0.5, -1.0, 2.5])
GOAL = np.array([3.0, 2.0, -2.8])  # heading error wraps: -2.8 - 2.5 + 2 pi = +0.983 rad


def test_go_to_point_continuous_law_arrives_and_its_drift_vanishes_with_dt():
    pose, cross = _drive_to(START, GOAL, 0.01, sampled=False)
    np.testing.assert_allclose(pose[:2], GOAL[:2], atol=1e-9)
    assert abs(frames.wrap_angle(pose[2] - GOAL[2])) < 1e-9
    assert cross < 3e-3  # holding a rotating-frame command for 10 ms bends the path
    _, cross_fine = _drive_to(START, GOAL, 0.0025, sampled=False)
    assert cross_fine < cross / 3  # O(dt)
    # the heading turns the short way (+0.983 rad), not through -5.3 rad
    assert go_to_point_twist(START, GOAL, 1.0, 0.5)[2] > 0


def test_go_to_point_sampled_law_stays_on_the_segment():
    pose, cross = _drive_to(START, GOAL, 0.01, sampled=True)
    np.testing.assert_allclose(pose[:2], GOAL[:2], atol=1e-9)
    assert abs(frames.wrap_angle(pose[2] - GOAL[2])) < 1e-9
    assert cross < 1e-9
    # one big step when the goal is closer than dt: arrives exactly
    tw = go_to_point_twist(START, GOAL, 100.0, 100.0, dt=1.0)
    end = frames.compose(START, frames.se2_exp(tw, 1.0))
    # the goal's heading reached by the shorter turn (compose keeps the turns, unwrapped)
    np.testing.assert_allclose([end[0], end[1], frames.wrap_angle(end[2])],
                               [3.0, 2.0, frames.wrap_angle(-2.8)], atol=1e-12)


def test_go_to_point_at_goal_and_vectorised():
    np.testing.assert_array_equal(go_to_point_twist((1, 2, 3), (1, 2, 3), 1.0, 1.0), 0.0)
    out = go_to_point_twist(np.zeros((4, 3)), [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]],
                            2.0, 1.0)
    np.testing.assert_allclose(out, [[2, 0, 0], [0, 2, 0], [0, 0, 1], [0, 0, 0]])


# --- bad input -----------------------------------------------------------------------------------

@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: MecanumGeometry(wheel_radius=0.0, half_wheelbase=0.2, half_track=0.15), "wheel_radius"),
        (lambda: MecanumGeometry(wheel_radius=0.05, half_wheelbase=float("nan"), half_track=0.15), "half_wheelbase"),
        (lambda: MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=-1), "half_track"),
        (lambda: MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=math.pi / 2), "roller_angle"),
        (lambda: inverse_kinematics(float("nan"), 0, 0, G), "vx"),
        (lambda: inverse_kinematics(0, [1, 2], [1, 2, 3], G), "vy and omega"),
        (lambda: inverse_kinematics(0, 0, float("inf"), G), "omega"),
        (lambda: inverse_kinematics(0, 0, 0, (0.05, 0.2, 0.15)), "geometry"),
        (lambda: forward_kinematics([1, 2, 3], G), "wheel_rates"),
        (lambda: forward_kinematics([1, 2, 3, float("nan")], G), "wheel_rates"),
        (lambda: fighting_component(np.zeros((2, 3))), "wheel_rates"),
        (lambda: limit_speed((1, 2), 1.0), "twist"),
        (lambda: limit_speed(np.zeros((2, 3)), 1.0), "twist"),
        (lambda: limit_speed((1, 2, 3), 0.0), "max_speed"),
        (lambda: circle_twist(0.0, 1.0), "radius"),
        (lambda: circle_twist(1.0, -1.0), "lap_time"),
        (lambda: circle_twist(1.0, 1.0, heading="spinning"), "heading"),
        (lambda: go_to_point_twist((0, 0), (1, 1, 1), 1.0, 1.0), "pose"),
        (lambda: go_to_point_twist((0, 0, 0), (1, 1, 1), -1.0, 1.0), "speed"),
        (lambda: go_to_point_twist((0, 0, 0), (1, 1, 1), 1.0, 0.0), "max_omega"),
        (lambda: go_to_point_twist((0, 0, 0), (1, 1, 1), 1.0, 1.0, dt=0.0), "dt"),
        (lambda: grip_usage(float("nan"), 0.0, 0.8), "accel_x"),
        (lambda: grip_usage(0.0, 1.0, -0.8), "mu"),
        (lambda: grip_usage(0.0, 1.0, 0.8, roller_angle=0.0), "roller_angle"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# --- grip and the sandbox ---------------------------------------------------------------------

def _min_max_wheel_force(ax, ay, gamma, a=0.3, b=0.2, mass=1.0):
    """Independent: the smallest max |f_i| with sum f_i u_i = m a and zero torque (1-D search)."""
    s_sign = np.array([-1.0, 1.0, 1.0, -1.0])
    pos = np.array([[a, b], [a, -b], [-a, b], [-a, -b]])
    u = np.column_stack([np.full(4, math.sin(gamma)), s_sign * math.cos(gamma)])
    torque = pos[:, 0] * u[:, 1] - pos[:, 1] * u[:, 0]
    A = np.vstack([u.T, torque])
    rhs = np.array([mass * ax, mass * ay, 0.0])
    f0 = np.linalg.lstsq(A, rhs, rcond=None)[0]
    n = np.linalg.svd(A)[2][-1]
    # max_i |f0_i + t n_i| is convex and piecewise linear in t: its minimum is at a crossing
    candidates = [0.0]
    for i in range(4):
        for j in range(4):
            for sgn in (1.0, -1.0):
                den = n[i] - sgn * n[j]
                if abs(den) > 1e-12:
                    candidates.append((sgn * f0[j] - f0[i]) / den)
    return min(np.max(np.abs(f0 + t * n)) for t in candidates)


@pytest.mark.parametrize("gamma", [math.pi / 4, math.pi / 3, 0.4])
def test_grip_usage_matches_a_min_max_force_solve(gamma):
    rng = np.random.default_rng(5)
    for ax, ay in rng.uniform(-6, 6, (40, 2)):
        needed = _min_max_wheel_force(ax, ay, gamma)  # N per kg
        cap = 0.7 * 9.81 / 4
        np.testing.assert_allclose(grip_usage(ax, ay, 0.7, gamma), needed / cap, rtol=1e-9)


def test_sandbox_commands_equal_inverse_kinematics():
    from wheelkin import sandbox

    rng = np.random.default_rng(9)
    for gamma in (math.pi / 4, math.pi / 3):
        spec = sandbox.mecanum(half_wheelbase=0.3048, half_track=0.2286, wheel_radius=0.0762,
                            roller_angle=gamma)
        g = MecanumGeometry(wheel_radius=0.0762, half_wheelbase=0.3048, half_track=0.2286, roller_angle=gamma)
        for twist in rng.uniform(-2, 2, (20, 3)):
            rates, _ = sandbox.ideal_commands(spec, twist)
            np.testing.assert_allclose(rates, inverse_kinematics(*twist, g), rtol=1e-12,
                                       atol=1e-12)


def test_sandbox_follows_the_kinematics_within_friction():
    from wheelkin import sandbox

    spec = sandbox.mecanum(half_wheelbase=0.3048, half_track=0.2286, wheel_radius=0.0762,
                            mass=20.0)
    twist = np.array([1.0, 0.5, 0.4])
    world = sandbox.World(dt=1 / 240)
    robot = world.add(spec, twist=twist)
    robot.set_wheel_rates(inverse_kinematics(*twist, EXAMPLE_GEOMETRY))
    traj = world.run(9.0)
    predicted = frames.compose(np.zeros(3), frames.se2_exp(np.outer(traj.t, twist), 1.0))
    assert traj.distance[-1] > 10.0
    assert not traj.slipping.any()
    assert np.max(np.hypot(*(traj.pose[:, :2] - predicted[:, :2]).T)) < 1e-5  # 0.01 mm


@pytest.mark.parametrize(("heading", "usage_per_a"), [("held", 2.0), ("rotating", math.sqrt(2))])
def test_sandbox_slips_where_grip_usage_passes_one(heading, usage_per_a):
    # circle of radius 1.5 m: held heading needs (|cos| + |sin|) sqrt2 a <= mu g at worst 2a;
    # rotating heading needs sqrt2 a (sideways)
    from wheelkin import sandbox

    spec = sandbox.mecanum(half_wheelbase=0.3048, half_track=0.2286, wheel_radius=0.0762,
                            mass=20.0)
    radius, mu_g = 1.5, spec.mu * 9.81
    for usage, slips in ((0.97, False), (1.03, True)):
        accel = usage * mu_g / usage_per_a
        lap = 2 * math.pi * math.sqrt(radius / accel)
        world = sandbox.World(dt=1 / 240)
        robot = world.add(spec, twist=circle_twist(radius, lap, 0.0, heading=heading))
        traj = world.run(lap, controller=lambda t, w, lap=lap, robot=robot:
                         robot.set_wheel_rates(inverse_kinematics(
                             *circle_twist(radius, lap, t, heading=heading), EXAMPLE_GEOMETRY)))
        assert traj.slipping.any() == slips, (heading, usage)


# --------------------------------------------------------------------------------------------
# desaturation and the centre of rotation, against WPILib's published formulas

def _wpilib_mecanum_wheel_speeds(vx, vy, omega, fl, fr, rl, rr, cor):
    """MecanumDriveKinematics.toWheelSpeeds (WPILib): rows (1, -1, -(x + y)) for FL,
    (1, 1, x - y) for FR, (1, 1, x - y) for RL, (1, -1, -(x + y)) for RR, with (x, y) each
    wheel's position minus the centre of rotation; wheel surface speeds in m/s."""
    rows = []
    for (x, y), sign in zip((fl, fr, rl, rr), ("m", "p", "p", "m"), strict=True):
        x, y = x - cor[0], y - cor[1]
        rows.append([1, -1, -(x + y)] if sign == "m" else [1, 1, x - y])
    return np.array(rows) @ np.array([vx, vy, omega])


def _wpilib_desaturate(speeds, limit):
    """MecanumDriveWheelSpeeds.desaturate: if the largest |speed| exceeds the limit, every
    speed is multiplied by limit / largest."""
    real_max = max(abs(s) for s in speeds)
    if real_max > limit:
        return [s / real_max * limit for s in speeds]
    return list(speeds)


@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(-0.5, 0.5),
       st.floats(-0.5, 0.5))
def test_centre_of_rotation_is_wpilibs(vx, vy, omega, cx, cy):
    g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    got = mecanum.inverse_kinematics(vx, vy, omega, g, centre_of_rotation=(cx, cy))
    want = _wpilib_mecanum_wheel_speeds(vx, vy, omega, (0.2, 0.15), (0.2, -0.15),
                                        (-0.2, 0.15), (-0.2, -0.15), (cx, cy))
    np.testing.assert_allclose(got * g.wheel_radius, want, atol=1e-12)
    # the default centre is the origin
    np.testing.assert_allclose(mecanum.inverse_kinematics(vx, vy, omega, g),
                               mecanum.inverse_kinematics(vx, vy, omega, g,
                                                          centre_of_rotation=(0.0, 0.0)))


def test_turning_about_a_wheel_leaves_it_still_for_any_roller_angle():
    for gamma in (0.3, math.pi / 4, 1.2):
        g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=gamma)
        for k, (x, y) in enumerate([(0.2, 0.15), (0.2, -0.15), (-0.2, 0.15), (-0.2, -0.15)]):
            rates = mecanum.inverse_kinematics(0.0, 0.0, 1.3, g, centre_of_rotation=(x, y))
            assert abs(rates[k]) < 1e-12


def test_unified_model_has_the_same_centre_of_rotation():
    from wheelkin import unified

    g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=0.6)
    got = unified.wheel_rates(unified.mecanum_wheels(g), (0.3, -0.2, 0.7),
                              centre_of_rotation=(0.1, -0.4))
    want = mecanum.inverse_kinematics(0.3, -0.2, 0.7, g, centre_of_rotation=(0.1, -0.4))
    np.testing.assert_allclose(got, want, atol=1e-12)
    with pytest.raises(ValueError, match="centre_of_rotation"):
        unified.wheel_rates(unified.mecanum_wheels(g), (0.3, -0.2, 0.7),
                            centre_of_rotation=(0.1,))


@given(st.lists(st.floats(-100, 100), min_size=4, max_size=4), st.floats(0.1, 50))
def test_desaturate_is_wpilibs(rates, limit):
    got = mecanum.desaturate(rates, limit)
    np.testing.assert_allclose(got, _wpilib_desaturate(rates, limit), rtol=1e-15, atol=1e-300)
    assert np.max(np.abs(got)) <= limit * (1 + 1e-15) or np.allclose(got, rates)


def test_desaturate_keeps_the_motion_direction_and_vectorises():
    g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    rates = mecanum.inverse_kinematics(3.0, 1.0, 2.0, g)
    out = mecanum.desaturate(rates, 20.0)
    twist_in = mecanum.forward_kinematics(rates, g)
    twist_out = mecanum.forward_kinematics(out, g)
    s = 20.0 / np.max(np.abs(rates))
    np.testing.assert_allclose(twist_out, s * np.asarray(twist_in), atol=1e-12)  # slower
    batch = mecanum.desaturate([[1.0, 2.0, 3.0, 4.0], [10.0, 0.0, 0.0, -20.0]], 5.0)
    np.testing.assert_allclose(batch, [[1.0, 2.0, 3.0, 4.0], [2.5, 0.0, 0.0, -5.0]])
    for bad, name in (([1.0, 2.0, 3.0], 5.0), ([1.0, math.nan, 0, 0], 5.0)):
        with pytest.raises(ValueError, match="wheel_rates"):
            mecanum.desaturate(bad, name)
    with pytest.raises(ValueError, match="max_rate"):
        mecanum.desaturate([1.0, 2.0, 3.0, 4.0], 0.0)
    with pytest.raises(ValueError, match="centre_of_rotation"):
        mecanum.inverse_kinematics(1.0, 0.0, 0.0, g, centre_of_rotation=(0.0, math.inf))
