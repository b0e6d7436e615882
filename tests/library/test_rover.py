"""Tests of wheelkin.rover against independent values.

Independent means: the document's printed table and r_min (hand-checked numbers from the
source), a rigid-body simulation of the wheel contact points (the velocity of a point of a body
turning about a centre, v = omega x (p - c), with no use of the module's formulas), a sympy
derivation, and properties (mirror symmetry, linearity in speed, inverse after forward).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import rover
from wheelkin.rover import (
    OSR_GEOMETRY,
    RoverGeometry,
    centre_speed,
    command_to_radius,
    corner_angles,
    min_turning_radius,
    outer_middle_is_fastest_above,
    radius_to_command,
    sandbox_commands,
    wheel_distances,
    wheel_speeds,
)

SETTINGS = settings(deadline=None, max_examples=150)
R_MIN = 7.254 + 10.5  # hand: d1 + d3 / tan(45 deg)

# Wheel contact points written out by hand from the document's figure 6 (x forward, y left),
# wheels LF, LM, LB, RF, RM, RB.
OSR_POINTS = np.array([[10.5, 7.254], [0.0, 10.073], [-10.5, 7.254],
                       [10.5, -7.254], [0.0, -10.073], [-10.5, -7.254]])


def rigid_body(radius: float, speed: float, points: np.ndarray, d4: float):
    """Velocities of ``points`` for a body turning about (0, -radius) (document sign) so that
    the outer middle wheel moves forward at ``speed``. Returns (omega, velocities (n, 2))."""
    centre = np.array([0.0, -radius])
    omega = -np.sign(radius) * speed / (abs(radius) + d4)  # right turn forward: clockwise
    rel = points - centre
    vel = omega * np.column_stack([-rel[:, 1], rel[:, 0]])  # omega z x rel
    return omega, vel


radii = st.floats(min_value=R_MIN, max_value=249.0).flatmap(
    lambda m: st.sampled_from([m, -m]))
speeds = st.floats(min_value=-200.0, max_value=200.0)


# ---------------------------------------------------------------- the document's numbers

def test_document_table_at_30_inches():
    # The document's table (percent of the commanded 100), printed to two decimals.
    table = [96.59, 100.0, 96.59, 62.52, 49.73, 62.52]
    np.testing.assert_allclose(wheel_speeds(30.0, 100.0), table, atol=0.005)


def test_document_min_radius():
    assert min_turning_radius() == pytest.approx(17.754, abs=5e-4)
    assert min_turning_radius() == pytest.approx(R_MIN)


def test_document_equation_16_inner_front_angle():
    for r in (20.0, 30.0, 100.0, 240.0):
        inner_front = corner_angles(r)[1]  # RF is inner in a right turn
        assert inner_front == pytest.approx(math.atan(10.5 / (r - 7.254)))


def test_hand_values():
    # R2 = r + d4, R5 = r - d4, body centre at r: hand arithmetic at r = 30.
    np.testing.assert_allclose(wheel_distances(30.0)[[1, 4]], [40.073, 19.927])
    assert float(centre_speed(30.0, 100.0)) == pytest.approx(100 * 30 / 40.073)


# ---------------------------------------------------------------- first principles

@SETTINGS
@given(radius=radii, speed=speeds)
def test_wheel_speeds_match_rigid_body(radius, speed):
    _, vel = rigid_body(radius, speed, OSR_POINTS, 10.073)
    got = wheel_speeds(radius, speed)
    # Every wheel rolls at the speed of its contact point (no slip) ...
    np.testing.assert_allclose(np.abs(got), np.hypot(vel[:, 0], vel[:, 1]), atol=1e-9)
    # ... forwards, for every wheel of the OSR in its whole turning range.
    np.testing.assert_allclose(got, np.sign(vel[:, 0]) * np.hypot(*vel.T), atol=1e-9)
    # The outer middle wheel (LM in a right turn) gets exactly the command.
    outer = 1 if radius > 0 else 4
    assert got[outer] == pytest.approx(speed, abs=1e-12)


@SETTINGS
@given(radius=radii)
def test_corner_wheels_roll_along_their_velocity(radius):
    _, vel = rigid_body(radius, 1.0, OSR_POINTS, 10.073)
    angles = corner_angles(radius)  # LF, RF, LB, RB; positive = clockwise
    corners = [0, 3, 2, 5]
    for angle, i in zip(angles, corners, strict=True):
        heading = np.array([math.cos(-angle), math.sin(-angle)])  # REP-103 direction
        v = vel[i]
        cross = heading[0] * v[1] - heading[1] * v[0]
        assert abs(cross) < 1e-9 * max(1.0, np.hypot(*v))  # no sideways component
        assert heading @ v > 0  # rolling forwards


@SETTINGS
@given(radius=radii, speed=speeds)
def test_centre_speed_is_the_body_centre(radius, speed):
    omega, _ = rigid_body(radius, speed, OSR_POINTS, 10.073)
    # The body centre is |r| from the ICR.
    assert float(centre_speed(radius, speed)) == pytest.approx(abs(omega) * abs(radius)
                                                               * np.sign(speed), abs=1e-9)


def test_sympy_derivation_agrees():
    r, X, d1, d2, d3, d4 = sp.symbols("r X d1 d2 d3 d4", positive=True)
    pts = [(d3, d1), (0, d4), (-d2, d1), (d3, -d1), (0, -d4), (-d2, -d1)]
    icr = sp.Matrix([0, -r])
    dist = [sp.sqrt((sp.Matrix(p) - icr).dot(sp.Matrix(p) - icr)) for p in pts]
    speeds_sym = [X * R / dist[1] for R in dist]
    f = sp.lambdify((r, X, d1, d2, d3, d4), speeds_sym)
    rng = np.random.default_rng(3)
    for _ in range(50):
        g = RoverGeometry(*rng.uniform([3, 5, 5, 8], [9, 15, 15, 14]), unit="in")
        rr = rng.uniform(min_turning_radius(g), 240)
        x = rng.uniform(1, 100)
        want = np.array(f(rr, x, g.d1, g.d2, g.d3, g.d4), dtype=float)
        np.testing.assert_allclose(wheel_speeds(rr, x, g), want, rtol=1e-12)


# ---------------------------------------------------------------- properties

@SETTINGS
@given(radius=radii, speed=speeds)
def test_left_turn_mirrors_right_turn(radius, speed):
    right = wheel_speeds(radius, speed)
    left = wheel_speeds(-radius, speed)
    np.testing.assert_allclose(left, np.concatenate([right[3:], right[:3]]), atol=1e-12)
    a_right = corner_angles(radius)
    a_left = corner_angles(-radius)  # LF <-> RF, LB <-> RB, angles change sign
    np.testing.assert_allclose(a_left, -a_right[[1, 0, 3, 2]], atol=1e-15)


@SETTINGS
@given(radius=radii, speed=speeds, k=st.floats(-5, 5))
def test_linear_in_speed(radius, speed, k):
    np.testing.assert_allclose(wheel_speeds(radius, k * speed),
                               k * wheel_speeds(radius, speed), atol=1e-9)


def test_vectorised_matches_scalar():
    r = np.array([[20.0, -35.0], [np.inf, 260.0]])
    x = np.array([10.0, -3.0])
    got = wheel_speeds(r, x)
    assert got.shape == (2, 2, 6)
    for idx in np.ndindex(r.shape):
        np.testing.assert_array_equal(got[idx], wheel_speeds(r[idx], x[idx[1]]))
    ang = corner_angles(r)
    assert ang.shape == (2, 2, 4)
    for idx in np.ndindex(r.shape):
        np.testing.assert_array_equal(ang[idx], corner_angles(r[idx]))


def test_straight_threshold():
    for r in (250.0, -250.0, 1e6, np.inf, -np.inf):
        np.testing.assert_array_equal(wheel_speeds(r, 42.0), np.full(6, 42.0))
        np.testing.assert_array_equal(corner_angles(r), np.zeros(4))
    assert not np.allclose(wheel_speeds(249.9, 42.0), 42.0)
    # A larger threshold turns where the default drives straight.
    assert corner_angles(300.0, straight_threshold=np.inf)[1] == pytest.approx(
        math.atan(10.5 / (300 - 7.254)))


def test_inner_corners_hit_the_stop_at_r_min():
    for stop_deg in (30.0, 35.0, 45.0, 60.0):
        stop = math.radians(stop_deg)
        r = min_turning_radius(max_corner_angle=stop)
        a = corner_angles(r, straight_threshold=np.inf, max_corner_angle=stop)
        assert np.max(np.abs(a)) == pytest.approx(stop)
        with pytest.raises(ValueError, match="radius"):
            corner_angles(r * (1 - 1e-9), max_corner_angle=stop)


def test_min_radius_uses_the_longer_corner():
    g = RoverGeometry(d1=7.0, d2=14.0, d3=10.0, d4=10.0, unit="in")
    assert min_turning_radius(g) == pytest.approx(7.0 + 14.0)  # back corners bind
    a = corner_angles(min_turning_radius(g), g)
    assert abs(a[3]) == pytest.approx(math.pi / 4)  # inner back corner (RB) at the stop
    assert abs(a[1]) < math.pi / 4


def test_outer_middle_fastest_boundary():
    # OSR: the boundary (10.89 in) is inside the hard stops, so the outer middle wheel is
    # always the fastest: no wheel ever exceeds the command.
    assert outer_middle_is_fastest_above() < min_turning_radius()
    r = np.linspace(min_turning_radius(), 249, 500)
    assert np.all(np.max(np.abs(wheel_speeds(r, 1.0)), axis=-1) <= 1 + 1e-12)
    # A long rover: a corner wheel outruns the outer middle wheel below the boundary.
    long = RoverGeometry(d1=7.254, d2=25.0, d3=25.0, d4=10.073, unit="in")
    boundary = outer_middle_is_fastest_above(long)
    hand = 0.5 * (25.0**2 / (10.073 - 7.254) - 10.073 - 7.254)
    assert boundary == pytest.approx(hand)
    assert min_turning_radius(long) < boundary
    below = wheel_speeds(boundary - 1, 100.0, long)
    above = wheel_speeds(boundary + 1, 100.0, long)
    assert below.max() > 100.0 and np.argmax(below) in (0, 2)
    assert above.max() == pytest.approx(100.0)
    at = wheel_speeds(boundary, 100.0, long)
    assert at[0] == pytest.approx(100.0)


def test_inner_middle_wheel_reverses_inside_d4():
    # A rover whose middle wheels stick out beyond the turning centre: the inner middle
    # wheel turns backwards (its contact point moves backwards).
    g = RoverGeometry(d1=4.0, d2=5.0, d3=5.0, d4=15.0, unit="in")
    r = min_turning_radius(g)  # 9 < d4
    _, vel = rigid_body(r, 10.0, wheel_positions_of(g), g.d4)
    got = wheel_speeds(r, 10.0, g)
    assert got[4] < 0
    np.testing.assert_allclose(got, np.sign(vel[:, 0]) * np.hypot(*vel.T), atol=1e-9)


def wheel_positions_of(g: RoverGeometry) -> np.ndarray:
    return np.array([[g.d3, g.d1], [0, g.d4], [-g.d2, g.d1],
                     [g.d3, -g.d1], [0, -g.d4], [-g.d2, -g.d1]], dtype=float)


def test_wheel_positions():
    np.testing.assert_array_equal(rover.wheel_positions(), OSR_POINTS)


# ---------------------------------------------------------------- the steering command

def test_command_to_radius_linear_in_radius():
    assert command_to_radius(100) == pytest.approx(20.0)
    assert command_to_radius(-100) == pytest.approx(-20.0)
    assert command_to_radius(1) == pytest.approx(247.7)
    assert command_to_radius(-50) == pytest.approx(-135.0)
    assert command_to_radius(0) == math.inf
    c = np.linspace(1, 100, 100)
    r = command_to_radius(c)
    np.testing.assert_allclose(np.diff(r), -2.3, atol=1e-12)  # linear in radius


@SETTINGS
@given(c=st.floats(-100, 100))
def test_command_round_trip(c):
    assert radius_to_command(command_to_radius(c)) == pytest.approx(c, abs=1e-9)


def test_other_mappings():
    c = np.linspace(1, 100, 100)
    for mapping in ("radius", "curvature", "angle"):
        assert command_to_radius(100, mapping=mapping) == pytest.approx(20.0)
        assert command_to_radius(-100, mapping=mapping) == pytest.approx(-20.0)
        assert command_to_radius(0, mapping=mapping) == math.inf
        r = command_to_radius(c, mapping=mapping)
        assert np.all(np.diff(r) < 0)  # more command, tighter turn
        np.testing.assert_allclose(command_to_radius(-c, mapping=mapping), -r)
    kappa = 1 / command_to_radius(c, mapping="curvature")
    np.testing.assert_allclose(np.diff(kappa), np.diff(kappa)[0])  # linear in curvature
    r = command_to_radius(c, mapping="angle")
    inner = corner_angles(r, straight_threshold=np.inf)[:, 1]
    np.testing.assert_allclose(np.diff(inner), np.diff(inner)[0])  # linear in corner angle


# ---------------------------------------------------------------- conversions to ours

def test_sandbox_commands_are_rep103_and_rolling():
    wheel_radius = 2.35
    for radius in (20.0, -20.0, 30.0, -77.0, 240.0, np.inf):
        rates, steering = sandbox_commands(radius, 10.0, wheel_radius)
        if np.isfinite(radius) and abs(radius) < 250:
            _, vel = rigid_body(radius, 10.0, OSR_POINTS, 10.073)
        else:
            vel = np.tile([10.0, 0.0], (6, 1))
        # Rates: rolling speed / wheel radius, order LF, LM, LB, RF, RM, RB.
        np.testing.assert_allclose(rates * wheel_radius, np.hypot(*vel.T), atol=1e-9)
        # Steering, REP-103 sign (counter-clockwise positive), order LF, RF, LB, RB:
        # each corner's rolling direction is its contact point's velocity direction.
        for psi, i in zip(steering, [0, 3, 2, 5], strict=True):
            want = math.atan2(vel[i, 1], vel[i, 0])
            assert psi == pytest.approx(want, abs=1e-12)


def test_body_twist_is_rep103():
    frames = pytest.importorskip("wheelkin.frames")
    units = pytest.importorskip("wheelkin.units")
    inch = units.INCH
    assert inch == pytest.approx(0.0254)
    for radius, x in ((30.0, 10.0), (-30.0, 10.0), (20.0, -5.0), (np.inf, 7.0), (260.0, 7.0)):
        vx, vy, omega = rover.document_twist(radius, x).as_array()
        if np.isfinite(radius) and abs(radius) < 250:
            w, _ = rigid_body(radius, x, OSR_POINTS, 10.073)
            v = abs(w) * abs(radius) * np.sign(x)
        else:
            w, v = 0.0, x
        assert vx == pytest.approx(v * inch)
        assert vy == 0.0
        assert omega == pytest.approx(w, abs=1e-15)  # rad/s is rad/s
    # frames.rover_twist directly: REP-103 radius is minus the document's.
    vx, vy, omega = frames.rover_twist(40.0, 12.0).as_array()
    assert vx == pytest.approx(12 * inch)
    assert vx / omega == pytest.approx(-40 * inch)  # right turn: clockwise, radius < 0
    assert frames.ours_to_rover_radius(frames.rover_radius_to_ours(40.0)) == pytest.approx(40)
    assert frames.rover_radius_to_ours(40.0) == pytest.approx(-40 * inch)


# ---------------------------------------------------------------- bad inputs

@pytest.mark.parametrize(("call", "name"), [
    (lambda: wheel_speeds(float("nan"), 1.0), "radius"),
    (lambda: wheel_speeds(10.0, 1.0), "radius"),
    (lambda: wheel_speeds(-17.0, 1.0), "radius"),
    (lambda: wheel_speeds(0.0, 1.0), "radius"),
    (lambda: wheel_speeds([30.0, 5.0], 1.0), "radius"),
    (lambda: wheel_speeds(30.0, float("nan")), "speed"),
    (lambda: wheel_speeds(30.0, np.inf), "speed"),
    (lambda: wheel_speeds(30.0, "fast"), "speed"),
    (lambda: wheel_speeds(30.0, 1.0, straight_threshold=-1), "straight_threshold"),
    (lambda: wheel_speeds(30.0, 1.0, geometry=(1, 2, 3, 4)), "geometry"),
    (lambda: corner_angles(float("nan")), "radius"),
    (lambda: corner_angles(12.0), "radius"),
    (lambda: corner_angles(30.0, straight_threshold=float("nan")), "straight_threshold"),
    (lambda: min_turning_radius(max_corner_angle=math.pi / 2), "max_corner_angle"),
    (lambda: min_turning_radius(max_corner_angle=0.0), "max_corner_angle"),
    (lambda: min_turning_radius(max_corner_angle=float("nan")), "max_corner_angle"),
    (lambda: command_to_radius(100.5), "command"),
    (lambda: command_to_radius(-101), "command"),
    (lambda: command_to_radius(float("nan")), "command"),
    (lambda: command_to_radius([0, 200]), "command"),
    (lambda: command_to_radius(10, mapping="log"), "mapping"),
    (lambda: radius_to_command(10.0), "radius"),
    (lambda: radius_to_command(300.0), "radius"),
    (lambda: RoverGeometry(0.0, 1, 1, 1, unit="in"), "d1"),
    (lambda: RoverGeometry(1, 1, float("nan"), 1, unit="in"), "d3"),
    (lambda: RoverGeometry(1, 1, 1, np.inf, unit="in"), "d4"),
    (lambda: sandbox_commands(30.0, 1.0, 0.0), "wheel_radius_in"),
])
def test_bad_inputs_name_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        call()


def test_radius_message_gives_the_range():
    with pytest.raises(ValueError, match=r"\|radius\| >= 17.754"):
        wheel_speeds(10.0, 1.0)
    with pytest.raises(ValueError, match=r"\[-100, 100\]"):
        command_to_radius(120)


def test_geometry_is_frozen():
    with pytest.raises(AttributeError):
        OSR_GEOMETRY.d1 = 3.0  # type: ignore[misc]


# --------------------------------------------------------------------------------------------
# the SI, REP-103 entry point

@given(st.floats(0.46, 20.0), st.sampled_from([-1.0, 1.0]),
       st.one_of(st.floats(-2.0, -0.01), st.floats(0.01, 2.0)))
def test_wheel_commands_are_the_documents_in_metres_with_the_books_signs(radius_m, side,
                                                                         centre_speed):
    from wheelkin import rover as rv
    from wheelkin.units import INCH

    big_r = side * radius_m  # REP-103: > 0 turns left
    omega = centre_speed / big_r
    cmd = rv.wheel_commands(centre_speed, omega)
    r_doc = -big_r / INCH  # the document's radius: inches, > 0 turns right
    # the document gives the outer middle wheel X; the centre then moves at X |r|/(|r| + d4)
    x_doc = centre_speed / INCH * (abs(r_doc) + rv.OSR_GEOMETRY.d4) / abs(r_doc)
    want_speeds = rv.wheel_speeds(r_doc, x_doc, straight_threshold=math.inf) * INCH
    want_angles = -rv.corner_angles(r_doc, straight_threshold=math.inf)
    np.testing.assert_allclose(cmd.wheel_speeds, want_speeds, atol=1e-12)
    np.testing.assert_allclose(cmd.steering_angles, want_angles, atol=1e-12)


def test_wheel_commands_roll_every_wheel_at_right_angles_to_the_icr():
    from wheelkin import rover as rv

    v, omega = 0.4, 0.5  # R = 0.8 m to the left
    cmd = rv.wheel_commands(v, omega)
    pos = rv.wheel_positions(rv.OSR_GEOMETRY_SI)
    steer = np.zeros(6)
    steer[[0, 3, 2, 5]] = cmd.steering_angles
    heading = np.stack([np.cos(steer), np.sin(steer)], axis=1)
    to_icr = np.array([0.0, v / omega]) - pos
    np.testing.assert_allclose(np.sum(heading * to_icr, axis=1), 0.0, atol=1e-12)
    # each wheel's speed is omega times its distance to the ICR (S = R theta)
    np.testing.assert_allclose(cmd.wheel_speeds, omega * np.linalg.norm(to_icr, axis=1),
                               atol=1e-12)
    assert np.all(cmd.steering_angles[:2] > 0)  # a left turn steers the fronts left


def test_wheel_commands_straight_vectorised_and_bad_input():
    from wheelkin import rover as rv

    cmd = rv.wheel_commands([0.5, -0.2], 0.0)
    np.testing.assert_array_equal(cmd.wheel_speeds, [[0.5] * 6, [-0.2] * 6])
    np.testing.assert_array_equal(cmd.steering_angles, np.zeros((2, 4)))
    speeds, angles = rv.wheel_commands(0.0, 0.0)
    assert not np.any(speeds) and not np.any(angles)
    with pytest.raises(ValueError, match="omega"):
        rv.wheel_commands(0.0, 1.0)  # on the spot: the corners would need 55 degrees
    with pytest.raises(ValueError, match="omega"):
        rv.wheel_commands(0.1, math.nan)
    with pytest.raises(ValueError, match=r"^v "):
        rv.wheel_commands("fast", 0.1)
    with pytest.raises(ValueError, match="max_corner_angle"):
        rv.wheel_commands(0.1, 0.0, max_corner_angle=2.0)


def test_a_geometry_in_metres_and_in_inches_is_the_same_rover():
    """Each geometry carries its unit; the SI functions convert, so no mix-up is silent."""
    from wheelkin import unified
    from wheelkin.sandbox import rover as sandbox_rover

    metric = rover.RoverGeometry(7.254 * 0.0254, 10.5 * 0.0254, 10.5 * 0.0254,
                                 10.073 * 0.0254, unit="m")
    for geometry in (rover.OSR_GEOMETRY, metric):
        cmd = rover.wheel_commands(0.2, 0.004, geometry)
        # omega x / (v - omega y) for the left front corner at (10.5 in, 7.254 in), by hand
        x, y = 10.5 * 0.0254, 7.254 * 0.0254
        assert cmd.steering_angles[0] == pytest.approx(math.atan(0.004 * x / (0.2 - 0.004 * y)))
        wheels = unified.rover_wheels(geometry, 0.06, turning_radius=-30.0 * rover.INCH)
        assert wheels[0].position == pytest.approx((x, y), abs=1e-15)
        assert sandbox_rover(geometry).wheels[0].position == pytest.approx((x, y), abs=1e-15)
    inches = metric.in_unit("in")
    assert inches.unit == "in" and rover.OSR_GEOMETRY.in_unit("in") is rover.OSR_GEOMETRY
    for d in ("d1", "d2", "d3", "d4"):
        assert getattr(inches, d) == pytest.approx(getattr(rover.OSR_GEOMETRY, d), rel=1e-15)
    with pytest.raises(ValueError, match="unit"):
        rover.RoverGeometry(1.0, 1.0, 1.0, 1.0, unit="ft")


def test_a_metric_geometry_gives_the_same_command_radii_and_straight_threshold():
    """The joystick's radii are inches whatever the geometry's unit, and the straight-ahead
    threshold (250 in) is converted for a metric geometry (a robot builder's review found
    both mixed with metres)."""
    si = rover.OSR_GEOMETRY_SI
    for mapping in ("radius", "curvature", "angle"):
        assert rover.command_to_radius(50, mapping=mapping, geometry=si) == pytest.approx(
            rover.command_to_radius(50, mapping=mapping), rel=1e-12)
    inch = rover.INCH
    for r in (30.0, 200.0, 249.0, 251.0, 1000.0):  # turns below 250 in, straight above
        np.testing.assert_allclose(rover.wheel_speeds(r * inch, 10.0, si),
                                   rover.wheel_speeds(r, 10.0), rtol=1e-12)
        np.testing.assert_allclose(rover.corner_angles(r * inch, si), rover.corner_angles(r),
                                   atol=1e-12)
    assert np.all(rover.corner_angles(251.0 * inch, si) == 0.0)
    assert np.all(rover.corner_angles(249.0 * inch, si) != 0.0)
