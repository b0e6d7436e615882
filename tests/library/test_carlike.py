"""wheelkin.carlike against sympy, hand values, properties, bad input, and the ROS 2 steering
controllers' odometry formulas.

The independent reference of the last group is ros2_controllers,
``steering_controllers_library/src/steering_odometry.cpp`` (ros-controls/ros2_controllers,
commit 0209540e): its Ackermann inverse kinematics (``get_commands``: front angles
``atan2(2 L sin phi, 2 L cos phi +- W sin phi)`` and rear traction speeds ``Ws (R +- W/2) / R``),
its bicycle odometry (``update_from_velocity``: ``omega = tan(steer) v / L``), its two-wheel
traction speed (``get_lin_velocity_double_traction_axle``) and its estimate of the bicycle
angle from one front wheel. The formulas are restated here in our own code from their published
form, in our sign convention (left positive, as theirs).
"""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import carlike as C
from wheelkin._kernels import arc_step

L, W = 2.5, 1.5

angles = st.floats(-1.45, 1.45).filter(lambda d: abs(d) > 1e-6)
radii = st.floats(0.8, 500.0) | st.floats(-500.0, -0.8)


# ------------------------------------------------------------------ sympy


def test_ackermann_condition_from_no_side_slip_rows():
    """The sliding rows of chapter 8 (n . (v + omega x p) = 0) of the two front wheels and the
    rear axle give the Ackermann condition and the library's angles."""
    R, Ls, Ws, v = sp.symbols("R L W v", positive=True)
    dl, dr = sp.symbols("delta_L delta_R")
    omega = v / R
    # Rear-axle midpoint twist (v, 0, omega); a wheel at (x, y) with angle d slides along
    # n = (-sin d, cos d) at n . (v - omega y, omega x).
    def slide(x, y, d):
        return -sp.sin(d) * (v - omega * y) + sp.cos(d) * (omega * x)

    sol_l = sp.solve(sp.Eq(sp.tan(dl), sp.solve(slide(Ls, Ws / 2, dl).subs(
        sp.sin(dl), sp.tan(dl) * sp.cos(dl)) / sp.cos(dl), sp.tan(dl))[0]), sp.tan(dl))
    tan_l = sp.simplify(sol_l[0])
    tan_r = sp.simplify(sp.solve(sp.expand(slide(Ls, -Ws / 2, dr).subs(
        sp.sin(dr), sp.tan(dr) * sp.cos(dr)) / sp.cos(dr)), sp.tan(dr))[0])
    assert sp.simplify(tan_l - Ls / (R - Ws / 2)) == 0
    assert sp.simplify(tan_r - Ls / (R + Ws / 2)) == 0
    assert sp.simplify(1 / tan_r - 1 / tan_l - Ws / Ls) == 0
    f = sp.lambdify((R, Ls, Ws), (sp.atan(tan_l), sp.atan(tan_r)))
    for r in (1.0, 3.0, 7.5, 40.0):
        got = C.ackermann_angles(r, wheelbase=L, track_width=W)
        assert np.allclose(got, f(r, L, W), rtol=0, atol=1e-14)


def test_pure_pursuit_from_the_circle_geometry():
    """The circle through the origin, tangent to x, through (x, y): centre (0, R) with
    x^2 + (y - R)^2 = R^2."""
    x, y, R = sp.symbols("x y R", real=True)
    sol = sp.solve(sp.Eq(x**2 + (y - R) ** 2, R**2), R)[0]
    kappa = sp.lambdify((x, y), 1 / sol)
    rng = np.random.default_rng(1)
    for px, py in rng.uniform(-3, 3, size=(50, 2)):
        assert C.pure_pursuit_curvature(px, py) == pytest.approx(kappa(px, py), rel=1e-12)


def test_com_twist_against_rigid_body_velocity():
    """The CoM twist is the rear-axle twist moved to (l_r, 0), rescaled to the CoM's speed."""
    for d, lr in ((0.3, 1.0), (-0.6, 2.0), (0.0, 0.7), (1.2, 2.5)):
        beta = C.side_slip_angle(d, wheelbase=L, rear_to_com=lr)
        rear_speed = 1.0
        omega = rear_speed * math.tan(d) / L
        vcom = np.array([rear_speed, omega * lr])  # v + omega x (lr, 0)
        speed = float(np.hypot(*vcom))
        tw = C.bicycle_twist_com(speed, d, wheelbase=L, rear_to_com=lr)
        assert tw.beta == pytest.approx(beta, abs=1e-15)
        assert np.allclose([tw.vx, tw.vy, tw.omega], [*vcom, omega], atol=1e-12)


# ------------------------------------------------------------------ hand values


def test_hand_values():
    # L = R: 45 degrees; Jeantaud rule for L = 2.5, W = 1.5: atan(0.3) = 16.699 deg.
    assert C.steering_angle(2.5, wheelbase=2.5) == pytest.approx(math.pi / 4)
    assert C.steering_angle(-2.5, wheelbase=2.5) == pytest.approx(-math.pi / 4)
    assert C.jeantaud_arm_angle(wheelbase=L, track_width=W) == pytest.approx(math.atan(0.3))
    # R = 5, L = 2.5, W = 1.5: tan dL = 2.5 / 4.25, tan dR = 2.5 / 5.75.
    left, right = C.ackermann_angles(5.0, wheelbase=L, track_width=W)
    assert math.tan(left) == pytest.approx(2.5 / 4.25)
    assert math.tan(right) == pytest.approx(2.5 / 5.75)
    # Straight ahead.
    assert tuple(C.ackermann_angles(math.inf, wheelbase=L, track_width=W)) == (0.0, 0.0)
    # Minimum radius: 45 deg on the inner wheel of a 2.5 m x 1.5 m car: 2.5 + 0.75.
    assert C.minimum_radius(math.pi / 4, wheelbase=L, track_width=W) == pytest.approx(3.25)
    # Tricycle at 60 deg: rear speed v cos 60 = v / 2.
    assert C.tricycle_twist(2.0, math.pi / 3, wheelbase=L)[0] == pytest.approx(1.0)
    # Parallel linkage (arm angle 0): both wheels equal.
    assert np.allclose(C.linkage_angles(0.4, track_width=W, arm_length=0.2, arm_angle=0.0), (0.4, 0.4), atol=1e-14)


# ------------------------------------------------------------------ properties


@settings(max_examples=200, deadline=None)
@given(radii)
def test_ackermann_condition_holds(radius):
    left, right = C.ackermann_angles(radius, wheelbase=L, track_width=W)
    # ICR on the rear axle line: both wheel axes pass through (0, R).
    for (x, y), d in (((L, W / 2), left), ((L, -W / 2), right)):
        n = np.array([-math.sin(d), math.cos(d)])
        to_icr = np.array([0.0 - x, radius - y])
        assert abs(n[0] * to_icr[1] - n[1] * to_icr[0]) < 1e-9 * (1 + abs(radius))
    assert 1 / math.tan(right) - 1 / math.tan(left) == pytest.approx(W / L, rel=1e-9)
    inner, outer = (left, right) if radius > 0 else (right, left)
    assert abs(inner) > abs(outer)
    assert C.ackermann_outer_angle(inner, wheelbase=L, track_width=W) == pytest.approx(outer, abs=1e-12)


@settings(max_examples=200, deadline=None)
@given(angles)
def test_steering_radius_round_trip(d):
    R = L / math.tan(d)
    assert C.steering_angle(R, wheelbase=L) == pytest.approx(d, abs=1e-12)
    assert C.steering_from_curvature(1 / R, wheelbase=L) == pytest.approx(d, abs=1e-12)
    # The bicycle's front wheel points across the line to the ICR (0, R).
    tw = C.bicycle_twist(1.0, d, wheelbase=L)
    vfront = np.array([tw[0], tw[2] * L])  # v + omega x (L, 0)
    assert math.atan2(vfront[1], vfront[0]) == pytest.approx(d, abs=1e-12)


@settings(max_examples=100, deadline=None)
@given(st.floats(0.01, 0.7), st.floats(0.0, 0.45))
def test_linkage_is_a_rigid_mechanism(inner, beta):
    """The tie rod keeps its length, and mirror symmetry holds."""
    a = 0.2
    left, right = C.linkage_angles(inner, track_width=W, arm_length=a, arm_angle=beta)
    pl = np.array([a * math.cos(math.pi + beta + left), W / 2 + a * math.sin(math.pi + beta + left)])
    pr = np.array([a * math.cos(math.pi - beta + right),
                   -W / 2 + a * math.sin(math.pi - beta + right)])
    assert np.hypot(*(pl - pr)) == pytest.approx(W - 2 * a * math.sin(beta), rel=1e-12)
    ml, mr = C.linkage_angles(-inner, track_width=W, arm_length=a, arm_angle=beta)
    assert (ml, mr) == pytest.approx((-right, -left), abs=1e-12)


def test_linkage_against_brute_force():
    """The outer angle found by scanning the tie-rod constraint on a fine grid."""
    a, beta, inner = 0.18, 0.3, 0.5
    lk = C.linkage_angles(inner, track_width=W, arm_length=a, arm_angle=beta)
    pl = np.array([a * math.cos(math.pi + beta + inner),
                   W / 2 + a * math.sin(math.pi + beta + inner)])
    grid = np.linspace(0.0, 0.8, 800001)
    px = a * np.cos(math.pi - beta + grid)
    py = -W / 2 + a * np.sin(math.pi - beta + grid)
    miss = np.abs(np.hypot(px - pl[0], py - pl[1]) - (W - 2 * a * math.sin(beta)))
    assert lk.right == pytest.approx(grid[np.argmin(miss)], abs=2e-6)


def test_second_order_arm_angle():
    """Expanding the tie-rod constraint to second order in delta gives the outer angle
    delta - tan(beta) W / l delta^2 (l the tie rod), and Ackermann's is delta - W/L delta^2:
    they agree when tan(beta) = l / L. There the error shrinks like delta^3; at the rule of
    thumb's angle (arms aimed at the rear axle's centre) like delta^2."""
    a = 0.2
    beta = 0.5
    for _ in range(60):  # fixed point of tan(beta) = (W - 2 a sin(beta)) / L
        beta = math.atan((W - 2 * a * math.sin(beta)) / L)
    small = np.array([0.01, 0.005])
    e = np.abs(C.linkage_error(small, wheelbase=L, track_width=W, arm_length=a, arm_angle=beta))
    assert e[0] / e[1] > 7.5  # third order or better
    rule = C.jeantaud_arm_angle(wheelbase=L, track_width=W)
    e2 = C.linkage_error(small, wheelbase=L, track_width=W, arm_length=a, arm_angle=rule)
    assert e2[0] / e2[1] == pytest.approx(4.0, rel=0.05)
    k = math.tan(rule) * W / (W - 2 * a * math.sin(rule)) - W / L  # predicted coefficient
    assert -e2[1] / small[1] ** 2 == pytest.approx(k, rel=0.02)


def test_optimal_arm_angle_beats_a_scan():
    best = C.optimal_arm_angle(wheelbase=L, track_width=W, arm_length=0.2, max_inner_angle=math.radians(35))
    grid = np.linspace(0.0, 0.6, 601)
    d = np.linspace(0.0, math.radians(35), 181)
    worst = [np.max(np.abs(C.linkage_error(d, wheelbase=L, track_width=W, arm_length=0.2, arm_angle=b))) for b in grid]
    assert best.worst_error <= min(worst) + 1e-9
    assert best.arm_angle == pytest.approx(grid[int(np.argmin(worst))], abs=2e-3)
    assert best.worst_error < np.max(np.abs(C.linkage_error(d, wheelbase=L, track_width=W, arm_length=0.2,
                                                             arm_angle=C.jeantaud_arm_angle(wheelbase=L, track_width=W))))


def test_vectorised_matches_scalar():
    R = np.array([1.0, -2.0, 10.0, np.inf])
    left, right = C.ackermann_angles(R, wheelbase=L, track_width=W)
    for i, r in enumerate(R):
        assert (left[i], right[i]) == tuple(C.ackermann_angles(r, wheelbase=L, track_width=W))
    tw = C.bicycle_twist([1.0, 2.0], [0.1, -0.2], wheelbase=L)
    assert tw.shape == (2, 3)


# ------------------------------------------------------------------ ros2_controllers


def _ros_ackermann_commands(v, omega, wheelbase, track, wheel_radius):
    """ros2_controllers get_commands, ACKERMANN_CONFIG (restated): returns the rear wheel
    rates (right, left) and the front angles (right, left)."""
    phi = math.atan(omega * wheelbase / v)
    ws = v / wheel_radius
    R = wheelbase / math.tan(phi)
    wr, wl = ws * (R + track / 2) / R, ws * (R - track / 2) / R
    num = 2 * wheelbase * math.sin(phi)
    ar = math.atan2(num, 2 * wheelbase * math.cos(phi) + track * math.sin(phi))
    al = math.atan2(num, 2 * wheelbase * math.cos(phi) - track * math.sin(phi))
    return (wr, wl), (ar, al)


@pytest.mark.parametrize("radius", [0.9, 2.0, 7.0, -1.2, -30.0])
def test_ros2_ackermann_inverse_kinematics(radius):
    wheelbase, track, r = 0.33, 0.27, 0.05
    v = 1.3
    (wr, wl), (ar, al) = _ros_ackermann_commands(v, v / radius, wheelbase, track, r)
    left, right = C.ackermann_angles(radius, wheelbase=wheelbase, track_width=track)
    assert (left, right) == pytest.approx((al, ar), abs=1e-12)
    # The rear wheels: the rigid-body speed of (0, +-W/2) in our bicycle twist.
    vx, _, om = C.bicycle_twist(v, C.steering_angle(radius, wheelbase=wheelbase), wheelbase=wheelbase)
    assert ((vx - om * track / 2) / r, (vx + om * track / 2) / r) == pytest.approx(
        (wl, wr), rel=1e-12)


@pytest.mark.parametrize("steer", [0.0, 0.05, 0.3, -0.4])
def test_ros2_bicycle_odometry(steer):
    """Their bicycle odometry: omega = tan(steer) v / L, integrated by the exact arc; ours:
    bicycle_twist and the library's one arc kernel."""
    wheelbase, dt, v = 0.33, 0.02, 0.8
    ros = np.zeros(3)
    ours = (0.0, 0.0, 0.0)
    for _ in range(200):
        omega = math.tan(steer) * v / wheelbase
        dth = omega * dt
        if abs(dth) < 1e-6:
            mid = ros[2] + 0.5 * dth
            ros += (v * math.cos(mid) * dt, v * math.sin(mid) * dt, dth)
        else:
            R = v * dt / dth
            old = ros[2]
            ros[2] += dth
            ros[0] += R * (math.sin(ros[2]) - math.sin(old))
            ros[1] += -R * (math.cos(ros[2]) - math.cos(old))
        vx, _, om = C.bicycle_twist(v, steer, wheelbase=wheelbase)
        ours = arc_step(*ours, vx * dt, om * dt)
    assert np.allclose(ours, ros, atol=1e-12)


def test_ros2_double_traction_speed_and_front_wheel_estimate():
    wheelbase, track, r = 0.33, 0.27, 0.05
    for radius in (1.0, -2.5, 6.0):
        d = C.steering_angle(radius, wheelbase=wheelbase)
        v = 0.7
        vx, _, om = C.bicycle_twist(v, d, wheelbase=wheelbase)
        wl, wr = (vx - om * track / 2) / r, (vx + om * track / 2) / r
        R = wheelbase / math.tan(d)
        ros_v = 0.5 * (wr * r * R / (R + track / 2) + wl * r * R / (R - track / 2))
        assert ros_v == pytest.approx(v, rel=1e-12)
        # Their bicycle angle from one front wheel's angle (right and left) agrees with ours.
        left, right = C.ackermann_angles(radius, wheelbase=wheelbase, track_width=track)
        est_r = math.atan(wheelbase * math.tan(right)
                          / (wheelbase - track / 2 * math.tan(right)))
        est_l = math.atan(wheelbase * math.tan(left)
                          / (wheelbase + track / 2 * math.tan(left)))
        assert est_r == pytest.approx(d, abs=1e-12)
        assert est_l == pytest.approx(d, abs=1e-12)


def test_ros2_four_argument_odometry_uses_the_small_angle_form():
    """Their update_from_velocity with two steering angles computes omega = steer * v / L (no
    tangent): at 0.4 rad that is 5.5 % less than tan(steer) v / L, which ours and their own
    one-angle form give. Documented here as a known difference."""
    d, v = 0.4, 1.0
    theirs = d * v / 0.33
    ours = C.bicycle_twist(v, d, wheelbase=0.33)[2]
    assert ours / theirs == pytest.approx(math.tan(d) / d)
    assert ours / theirs - 1 > 0.05


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize("call, match", [
    (lambda: C.steering_angle(0.0, wheelbase=1.0), "radius must be non-zero"),
    (lambda: C.steering_angle(1.0, wheelbase=-1.0), "wheelbase must be a finite number > 0"),
    (lambda: C.steering_angle(float("nan"), wheelbase=1.0), "radius must not contain NaN"),
    (lambda: C.ackermann_angles(0.5, wheelbase=2.5, track_width=1.5), r"\|radius\| > track_width/2"),
    (lambda: C.ackermann_angles(5.0, wheelbase=2.5, track_width=0.0), "track_width must be a finite number > 0"),
    (lambda: C.bicycle_twist(1.0, math.pi / 2, wheelbase=1.0), r"steering_angle must be in \(-pi/2"),
    (lambda: C.bicycle_twist("fast", 0.1, wheelbase=1.0), "speed must be numeric"),
    (lambda: C.tricycle_twist(1.0, 2.0, wheelbase=1.0), "steering_angle must be in"),
    (lambda: C.side_slip_angle(0.1, wheelbase=1.0, rear_to_com=2.0), r"rear_to_com must be in \[0, 1\]"),
    (lambda: C.minimum_radius(0.0, wheelbase=1.0), "max_steering_angle must be in"),
    (lambda: C.minimum_radius(0.3, wheelbase=1.0, track_width=-0.1), "track_width must be a finite number >= 0"),
    (lambda: C.pure_pursuit_curvature(0.0, 0.0), "must not be the origin"),
    (lambda: C.pure_pursuit_curvature(1.0, float("inf")), "y must not contain"),
    (lambda: C.steering_from_curvature(1.0, wheelbase=0.0), "wheelbase"),
    (lambda: C.linkage_angles(0.3, track_width=1.5, arm_length=0.2, arm_angle=math.pi / 2), "arm_angle must be in"),
    (lambda: C.linkage_angles(0.3, track_width=1.5, arm_length=5.0, arm_angle=0.4), "arm_length must be <"),
    (lambda: C.linkage_angles(1.5, track_width=1.5, arm_length=0.7, arm_angle=0.9), "beyond the linkage's reach"),
    (lambda: C.linkage_error(0.3, wheelbase=-2.5, track_width=1.5, arm_length=0.2, arm_angle=0.3), "wheelbase"),
    (lambda: C.optimal_arm_angle(wheelbase=2.5, track_width=1.5, arm_length=0.2, max_inner_angle=0.0), "max_inner_angle must be in"),
    (lambda: C.optimal_arm_angle(wheelbase=2.5, track_width=1.5, arm_length=0.2, max_inner_angle=0.5, samples=2), "samples must be"),
    (lambda: C.optimal_arm_angle(wheelbase=2.5, track_width=1.5, arm_length=0.2, max_inner_angle=0.5, tolerance=0), "tolerance"),
    # where the formula overflows: a refusal naming the inputs, never a warning or 90 degrees
    (lambda: C.steering_angle(5e-324, wheelbase=1.0), "radius is too small for the wheelbase"),
    (lambda: C.minimum_radius(5e-324, wheelbase=1.0), "max_steering_angle, wheelbase and track_width"),
    (lambda: C.pure_pursuit_curvature(1e-170, 1e-170), "x and y is out of range"),
    (lambda: C.linkage_angles(0.3, track_width=1e300, arm_length=0.15, arm_angle=0.3), "track_width and arm_length"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ------------------------------------------------------------------ lengths by name

#: A car's dimensions: what a port could swap silently if they were positional (issue 23).
CAR_DIMENSIONS = {"wheelbase", "track_width", "rear_to_com", "arm_length", "arm_angle",
                  "max_inner_angle"}
CAR_FUNCTIONS = [name for name in C.__all__ if inspect.isfunction(getattr(C, name))]


@pytest.mark.parametrize("name", CAR_FUNCTIONS)
def test_a_cars_dimensions_are_keyword_only(name):
    params = inspect.signature(getattr(C, name)).parameters.values()
    positional = [p.name for p in params if p.kind is not p.KEYWORD_ONLY]
    assert not CAR_DIMENSIONS & set(positional), f"{name} takes {positional} by position"


def test_the_swapped_lengths_of_the_issue_are_refused():
    """``ackermann_angles(2, 0.25, 0.33)``: wheelbase and track swapped gave plausible angles."""
    with pytest.raises(TypeError, match=r"ackermann_angles\(\).*wheelbase=\.\.\., "
                                        r"track_width=\.\.\."):
        C.ackermann_angles(2, 0.25, 0.33)  # positional on purpose
    left, right = C.ackermann_angles(2.0, wheelbase=0.33, track_width=0.25)
    # by hand: each front wheel points at the ICR (0, R) from (L, +-W/2)
    assert left == pytest.approx(math.atan(0.33 / (2.0 - 0.125)), rel=1e-15)
    assert right == pytest.approx(math.atan(0.33 / (2.0 + 0.125)), rel=1e-15)


def test_named_lengths_in_any_order_give_the_same_answer():
    a = C.linkage_error(0.4, wheelbase=2.5, track_width=1.5, arm_length=0.15, arm_angle=0.3)
    b = C.linkage_error(0.4, arm_angle=0.3, arm_length=0.15, track_width=1.5, wheelbase=2.5)
    assert a == b


def test_a_far_look_ahead_point_is_straight_ahead():
    assert C.pure_pursuit_curvature(1e300, 0.0) == 0.0
    assert C.pure_pursuit_curvature(0.0, 1e300) == 0.0  # 2/1e300 underflows to 0
