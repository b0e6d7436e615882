"""Tests of wheelkin.unified against independent values.

Independent means: a sympy derivation of each wheel kind's constraints from the rigid-body
velocity of its contact point (a 3-D cross product, rotation matrices, and for a Swedish
wheel the roller condition solved for the wheel rate); the chapter modules (wheelkin.rover,
wheelkin.mecanum, wheelkin.diffdrive), which were derived and tested separately; the
sandbox's own contact rows and ideal commands; textbook mobility numbers (Siegwart et al.,
section 3.3) with their null spaces checked directly; and properties (inverse after forward,
linearity, mirror symmetry).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import diffdrive, mecanum, rover
from wheelkin.frames import Twist
from wheelkin.mecanum import MecanumGeometry
from wheelkin.rover import RoverGeometry
from wheelkin.unified import (
    WheelConstraint,
    admissible_twists,
    body_twist,
    constraint_matrix,
    diff_drive_wheels,
    mecanum_wheels,
    mobility,
    rolling_matrix,
    rolling_row,
    rover_wheels,
    skid_steer_wheels,
    sliding_matrix,
    sliding_row,
    slip_residual,
    steer_for_twist,
    wheel_rates,
)
from wheelkin.units import INCH

SETTINGS = settings(deadline=None, max_examples=120)
speeds = st.floats(-3.0, 3.0, allow_nan=False)
rates = st.floats(-4.0, 4.0, allow_nan=False)
lengths = st.floats(0.02, 1.0)
angles = st.floats(-math.pi, math.pi)
twists = st.tuples(speeds, speeds, rates)


# --- the sympy derivation ---------------------------------------------------------------------

def _sympy_rows():
    """Rolling (rim speed r*phi) and sliding rows of each kind, derived symbolically.

    The contact point's velocity is v + omega z x p (a 3-D cross product); the rolling
    direction is the body x axis rotated by psi; a Swedish wheel's hub moves its rim at r*phi
    along e, and only the component along the roller axis u (the axle rotated by gamma) must
    match: u . (v_p - r phi e) = 0, solved for phi.
    """
    vx, vy, w, x, y, psi, gamma, r = sp.symbols("v_x v_y omega x y psi gamma r", real=True)
    phi = sp.Symbol("phi")
    v_p = (sp.Matrix([vx, vy, 0]) + sp.Matrix([0, 0, w]).cross(sp.Matrix([x, y, 0])))[:2, 0]

    def rot(a):
        return sp.Matrix([[sp.cos(a), -sp.sin(a)], [sp.sin(a), sp.cos(a)]])

    e = rot(psi) * sp.Matrix([1, 0])
    n = rot(psi) * sp.Matrix([0, 1])
    u = rot(gamma) * n
    twist = (vx, vy, w)
    conventional = [sp.diff(e.dot(v_p), s) for s in twist]
    sliding = [sp.diff(n.dot(v_p), s) for s in twist]
    rim_speed = r * sp.solve(sp.Eq(u.dot(v_p - r * phi * e), 0), phi)[0]
    swedish = [sp.simplify(sp.diff(rim_speed, s)) for s in twist]
    args = (x, y, psi, gamma)
    return (sp.lambdify(args, conventional), sp.lambdify(args, sliding),
            sp.lambdify(args, swedish))


CONVENTIONAL, SLIDING, SWEDISH = _sympy_rows()


@SETTINGS
@given(x=st.floats(-1, 1), y=st.floats(-1, 1), heading=angles,
       delta=st.floats(-math.pi, math.pi),
       kind=st.sampled_from(["fixed", "steered", "caster"]))
def test_conventional_rows_match_the_sympy_derivation(x, y, heading, delta, kind):
    steering = 0.0 if kind == "fixed" else delta
    w = WheelConstraint("W", (x, y), heading, 0.05, kind, steering=steering)
    psi = heading + steering
    np.testing.assert_allclose(rolling_row(w), CONVENTIONAL(x, y, psi, 0.0), atol=1e-12)
    if kind != "caster":
        np.testing.assert_allclose(sliding_row(w), SLIDING(x, y, psi, 0.0), atol=1e-12)


@SETTINGS
@given(x=st.floats(-1, 1), y=st.floats(-1, 1), heading=angles,
       gamma=st.floats(0.05, math.pi / 2) | st.floats(-math.pi / 2, -0.05))
def test_swedish_rows_match_the_sympy_derivation(x, y, heading, gamma):
    w = WheelConstraint("S", (x, y), heading, 0.05, "swedish", roller_angle=gamma)
    np.testing.assert_allclose(rolling_row(w), SWEDISH(x, y, heading, gamma),
                               rtol=1e-9, atol=1e-9)


def test_an_omni_wheel_rolls_like_a_fixed_wheel_and_has_no_sliding_row():
    omni = WheelConstraint("O", (0.1, 0.2), 0.7, 0.03, "swedish", roller_angle=math.pi / 2)
    fixed = WheelConstraint("F", (0.1, 0.2), 0.7, 0.03, "fixed")
    np.testing.assert_allclose(rolling_row(omni), rolling_row(fixed), atol=1e-15)
    assert sliding_matrix([omni]).shape == (0, 3)
    with pytest.raises(ValueError, match="no-side-slip row"):
        sliding_row(omni)


def test_constraint_matrix_stacks_rolling_then_sliding_rows_in_wheel_order():
    wheels = (*diff_drive_wheels(0.1, 0.02), WheelConstraint("S", (0.3, 0.0), kind="steered"))
    m = constraint_matrix(wheels)
    assert m.shape == (4 + 3, 3)
    np.testing.assert_array_equal(m[:4], rolling_matrix(wheels))
    np.testing.assert_array_equal(m[4:], sliding_matrix(wheels))
    # hand: L at (0, .05): rolling (1, 0, -.05), sliding (0, 1, 0); S at (.3, 0): (0, 1, .3)
    np.testing.assert_allclose(m[[0, 4, 6]], [[1, 0, -0.05], [0, 1, 0], [0, 1, 0.3]],
                               atol=1e-15)


# --- the four vehicles against their chapters ---------------------------------------------------

@SETTINGS
@given(v=speeds, omega=rates, track=lengths, radius=st.floats(0.01, 0.2))
def test_diff_drive_rates_are_the_diffdrive_chapter(v, omega, track, radius):
    wheels = diff_drive_wheels(track, radius)
    left, right = diffdrive.wheel_speeds(v, omega, track)
    rim = wheel_rates(wheels, (v, 0.0, omega))[:2] * radius
    np.testing.assert_allclose(rim, [left, right], atol=1e-12)
    np.testing.assert_allclose(slip_residual(wheels, (v, 0.0, omega)), 0.0, atol=1e-15)


@SETTINGS
@given(v=speeds, omega=rates, half_track=lengths, half_wheelbase=lengths,
       radius=st.floats(0.01, 0.2))
def test_skid_steer_rates_are_the_diffdrive_chapter_with_the_geometric_track(
        v, omega, half_track, half_wheelbase, radius):
    wheels = skid_steer_wheels(half_track=half_track, half_wheelbase=half_wheelbase, wheel_radius=radius)
    expected = diffdrive.skid_steer_wheel_speeds(v, omega, 2 * half_track)
    np.testing.assert_allclose(wheel_rates(wheels, (v, 0.0, omega)) * radius, expected,
                               atol=1e-12)


@SETTINGS
@given(twist=twists, a=lengths, b=lengths, radius=st.floats(0.01, 0.2),
       gamma=st.floats(0.1, math.pi / 2 - 0.1))
def test_mecanum_rates_are_the_mecanum_chapter(twist, a, b, radius, gamma):
    g = MecanumGeometry(wheel_radius=radius, half_wheelbase=a, half_track=b, roller_angle=gamma)
    np.testing.assert_allclose(wheel_rates(mecanum_wheels(g), twist),
                               mecanum.inverse_kinematics(*twist, g), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(rolling_matrix(mecanum_wheels(g)),
                               mecanum.inverse_matrix(g) * radius, rtol=1e-12, atol=1e-12)


def _radius_in(geometry: RoverGeometry):
    r_min = rover.min_turning_radius(geometry)
    return st.one_of(st.floats(r_min, 400.0), st.floats(-400.0, -r_min),
                     st.sampled_from([math.inf, -math.inf]))


@SETTINGS
@given(data=st.data(), speed=st.floats(-30.0, 30.0), wheel_radius=st.floats(0.02, 0.2),
       dims=st.tuples(st.floats(3, 15), st.floats(3, 15), st.floats(3, 15), st.floats(3, 15)))
def test_rover_rates_are_the_rover_chapter(data, speed, wheel_radius, dims):
    g = RoverGeometry(*dims, unit="in")
    radius = data.draw(_radius_in(g))
    wheels = rover_wheels(g, wheel_radius, turning_radius=-radius * INCH)
    twist = rover.document_twist(radius, speed, g)
    rim_in_per_s = wheel_rates(wheels, twist) * wheel_radius / INCH
    np.testing.assert_allclose(rim_in_per_s, rover.wheel_speeds(radius, speed, g),
                               rtol=1e-9, atol=1e-9)
    # the document's corner angles are the ones that leave no side slip
    np.testing.assert_allclose(slip_residual(wheels, twist), 0.0, atol=1e-12)


def test_rover_steering_is_the_documents_corner_angles_with_our_sign():
    wheels = {w.name: w for w in rover_wheels(turning_radius=-30.0 * INCH)}
    doc = dict(zip(rover.CORNER_NAMES, rover.corner_angles(30.0), strict=True))
    for name, angle in doc.items():
        assert wheels[name].steering == pytest.approx(-angle)
        assert wheels[name].kind == "steered"
    assert wheels["LM"].kind == wheels["RM"].kind == "fixed"
    # a right turn (r > 0): the front corners point right, i.e. clockwise, negative in REP-103
    assert wheels["LF"].steering < 0 and wheels["RF"].steering < 0


@SETTINGS
@given(twist=twists)
def test_forward_after_inverse_is_the_identity_on_admissible_twists(twist):
    vx, _vy, w = twist
    mec = mecanum_wheels(MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15))
    np.testing.assert_allclose(body_twist(mec, wheel_rates(mec, twist)), twist, atol=1e-9)
    dd = diff_drive_wheels(0.085, 0.018)
    np.testing.assert_allclose(body_twist(dd, wheel_rates(dd, (vx, 0, w))), (vx, 0, w),
                               atol=1e-9)
    swerve = steer_for_twist(_swerve(), twist)
    # Near omega = 0 the steering angles come from an ICR millions of metres away: the round
    # trip is then conditioned ~1e7 times worse, so allow a few nm/s (twist magnitudes <= ~1).
    np.testing.assert_allclose(body_twist(swerve, wheel_rates(swerve, twist)), twist,
                               atol=1e-8)


def test_skid_steer_odometry_is_the_diffdrive_chapters_forward_kinematics():
    wheels = skid_steer_wheels(half_track=0.06, half_wheelbase=0.05, wheel_radius=0.04)
    phi = np.array([3.0, 5.0, 2.0, 7.0])
    v, w = diffdrive.skid_steer_body_twist(*(phi * 0.04), 0.12)
    np.testing.assert_allclose(body_twist(wheels, phi), [v, 0.0, w], atol=1e-12)


@SETTINGS
@given(twist=twists, k=st.floats(-3, 3))
def test_wheel_rates_are_linear_in_the_twist(twist, k):
    wheels = rover_wheels(turning_radius=45.0 * INCH)
    np.testing.assert_allclose(wheel_rates(wheels, np.multiply(k, twist)),
                               k * wheel_rates(wheels, twist), atol=1e-9)


def test_batches_of_twists_give_batches_of_rates():
    wheels = mecanum_wheels(MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15))
    batch = np.arange(24.0).reshape(2, 4, 3) / 10
    out = wheel_rates(wheels, batch)
    assert out.shape == (2, 4, 4)
    np.testing.assert_allclose(out[1, 2], wheel_rates(wheels, batch[1, 2]))
    assert slip_residual(wheels, batch).shape == (2, 4, 4)
    assert body_twist(wheels, out).shape == (2, 4, 3)
    np.testing.assert_allclose(wheel_rates(wheels, Twist(0, 1, 0)), [-20, 20, 20, -20])


def test_a_left_turn_mirrors_a_right_turn():
    right = wheel_rates(rover_wheels(turning_radius=-40.0 * INCH), rover.document_twist(40.0, 10.0))
    left = wheel_rates(rover_wheels(turning_radius=40.0 * INCH), rover.document_twist(-40.0, 10.0))
    np.testing.assert_allclose(left, right[[3, 4, 5, 0, 1, 2]], atol=1e-12)


# --- the sandbox's contact imposes these rows: checked from first principles -----------------

@pytest.mark.parametrize("name", ["diff drive", "skid steer", "mecanum", "rover", "car"])
def test_sandbox_contact_rows_are_the_contact_velocities_by_hand(name):
    """J xi, per row, is the velocity of the wheel's contact point (v - w y, vy + w x) along
    the row's direction, computed here by hand from the angles; B phi is the rim speed r phi
    along e (r phi (u . e) along a roller axis u, at 90 deg + gamma from e)."""
    from wheelkin.sandbox import (
        LAB_ROBOT,
        MECANUM_ROBOT,
        OPEN_SOURCE_ROVER,
        RADON_ULZER,
        RC_CAR,
    )
    from wheelkin.sandbox.contact import constraint_rows

    spec, steering = {"diff drive": (RADON_ULZER, ()), "skid steer": (LAB_ROBOT, ()),
                      "mecanum": (MECANUM_ROBOT, ()),
                      "rover": (OPEN_SOURCE_ROVER, (0.3, -0.2, 0.1, -0.4)),
                      "car": (RC_CAR, (0.25, 0.2))}[name]
    J, B, owner = constraint_rows(spec, steering)
    xi = np.array([0.3, -0.2, 0.7])
    phi = np.array([1.5, -2.0, 0.5, 3.0, -1.0, 2.5])[:len(spec.wheel_names)]
    angle_of = dict(zip(spec.steered_names, steering, strict=True))
    expected_rows, expected_b = [], []
    for j, w in enumerate(spec.driven_wheels):
        x, y = w.position
        contact = np.array([xi[0] - xi[2] * y, xi[1] + xi[2] * x])
        psi = w.heading + angle_of.get(w.name, 0.0)
        e = np.array([math.cos(psi), math.sin(psi)])
        n = np.array([math.cos(psi + math.pi / 2), math.sin(psi + math.pi / 2)])
        r = w.wheel_radius
        if w.kind == "swedish":
            a = psi + math.pi / 2 + w.roller_angle
            u = np.array([math.cos(a), math.sin(a)])
            expected_rows.append(u @ contact)
            expected_b.append(r * phi[j] * (u @ e))
        elif w.name in spec.free_rolling:
            expected_rows += [0.0, n @ contact]
            expected_b += [0.0, 0.0]
        else:
            expected_rows += [e @ contact, n @ contact]
            expected_b += [r * phi[j], 0.0]
    np.testing.assert_allclose(J @ xi, expected_rows, atol=1e-12)
    np.testing.assert_allclose(B @ phi, expected_b, atol=1e-12)
    rows_per_wheel = 1 if spec.is_swedish else 2
    assert owner.tolist() == [j for j in range(len(phi)) for _ in range(rows_per_wheel)]


# --- mobility -----------------------------------------------------------------------------------

def _tricycle():
    """Siegwart et al.'s tricycle: a fixed rear axle and one steered front wheel."""
    return (WheelConstraint("RL", (0.0, 0.2)), WheelConstraint("RR", (0.0, -0.2)),
            WheelConstraint("F", (0.5, 0.0), kind="steered", steering=0.3))


def _car():
    """Ackermann car: fixed rear axle, front wheels steered about a common ICR."""
    wheels = (WheelConstraint("RL", (0.0, 0.3)), WheelConstraint("RR", (0.0, -0.3)),
              WheelConstraint("FL", (1.0, 0.3), kind="steered"),
              WheelConstraint("FR", (1.0, -0.3), kind="steered"))
    return steer_for_twist(wheels, (1.0, 0.0, 0.5))


def _swerve():
    """Three independently steered wheels, no fixed wheel (an omni-steer base)."""
    return tuple(WheelConstraint(f"S{k}", (0.3 * math.cos(2 * math.pi * k / 3),
                                           0.3 * math.sin(2 * math.pi * k / 3)), kind="steered")
                 for k in range(3))


def _kiwi():
    """Three omni wheels 120 degrees apart, rolling tangentially."""
    return tuple(WheelConstraint(f"O{k}", (0.2 * math.cos(a), 0.2 * math.sin(a)), a + math.pi / 2,
                                 0.03, "swedish", roller_angle=math.pi / 2)
                 for k, a in enumerate(2 * math.pi * np.arange(3) / 3))


@pytest.mark.parametrize(
    "name, wheels, expected",
    [
        # (degree of mobility, steerability, manoeuvrability), Siegwart et al. section 3.3
        ("differential drive", diff_drive_wheels(0.3, 0.05), (2, 0, 2)),
        ("mecanum", mecanum_wheels(MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)), (3, 0, 3)),
        ("omni (kiwi)", _kiwi(), (3, 0, 3)),
        ("rover, straight", rover_wheels(), (1, 1, 2)),
        ("rover, turning", rover_wheels(turning_radius=25.0 * INCH), (1, 1, 2)),
        ("skid steer", skid_steer_wheels(half_track=0.06, half_wheelbase=0.05, wheel_radius=0.04), (1, 0, 1)),
        ("tricycle", _tricycle(), (1, 1, 2)),
        ("car", _car(), (1, 1, 2)),
        ("swerve", steer_for_twist(_swerve(), (0.3, 0.2, 0.5)), (1, 2, 3)),
    ],
)
def test_mobility_numbers(name, wheels, expected):
    m = mobility(wheels)
    assert m[:3] == expected, name
    # delta_m is the dimension of the twists that leave every wheel without side slip:
    basis = admissible_twists(wheels)
    assert basis.shape == (3, m.degree_of_mobility)
    np.testing.assert_allclose(sliding_matrix(wheels) @ basis, 0.0, atol=1e-12)
    np.testing.assert_allclose(basis.T @ basis, np.eye(basis.shape[1]), atol=1e-12)


def test_the_differential_drive_cannot_strafe_and_the_rover_cannot_either():
    for wheels in (diff_drive_wheels(0.3, 0.05), rover_wheels()):
        strafe = np.array([0.0, 0.3, 0.0])
        wheels = steer_for_twist(wheels, strafe)
        assert np.abs(slip_residual(wheels, strafe)).max() == pytest.approx(0.3)
    # the mecanum vehicle can, without any residual
    assert not np.any(slip_residual(mecanum_wheels(MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)),
                                    (0.0, 0.3, 0.0)))


@SETTINGS
@given(v=speeds, omega=rates.filter(lambda w: abs(w) > 1e-3), a=lengths, b=lengths)
def test_the_skid_steer_must_slip_to_turn(v, omega, a, b):
    """Only straight motion is admissible; a turn leaves each wheel sliding at a|omega|."""
    wheels = skid_steer_wheels(half_track=b, half_wheelbase=a, wheel_radius=0.04)
    residual = slip_residual(wheels, (v, 0.0, omega))
    np.testing.assert_allclose(np.abs(residual), a * abs(omega), rtol=1e-12)
    np.testing.assert_allclose(residual, omega * np.array([a, a, -a, -a]), rtol=1e-12)
    np.testing.assert_allclose(admissible_twists(wheels).ravel(), [1.0, 0.0, 0.0], atol=1e-12)


def test_mis_steered_rover_cannot_move_at_all():
    wheels = list(rover_wheels(turning_radius=-30.0 * INCH))
    wheels[0] = wheels[0].steered_to(wheels[0].steering + 0.05)  # LF 3 degrees off
    m = mobility(wheels)
    assert m.degree_of_mobility == 0 and m.rank_sliding == 3
    assert m.degree_of_steerability == 1  # the design still has its one steering freedom


@SETTINGS
@given(twist=twists)
def test_steering_for_a_twist_removes_all_side_slip_of_steered_wheels(twist):
    wheels = steer_for_twist(_swerve(), twist)
    np.testing.assert_allclose(slip_residual(wheels, twist), 0.0, atol=1e-12)
    assert all(-math.pi / 2 < w.steering <= math.pi / 2 for w in wheels)


def test_a_caster_trails_along_its_contact_velocity():
    wheels = steer_for_twist(diff_drive_wheels(0.2, 0.05), (-0.5, 0.0, 0.0))  # reversing
    caster = wheels[2]
    assert abs(caster.steering) == pytest.approx(math.pi)  # turned round, rolling forward
    assert wheel_rates(wheels, (-0.5, 0.0, 0.0))[2] == pytest.approx(0.5 / caster.wheel_radius)
    # a wheel at the ICR keeps its steering
    (w,) = steer_for_twist([WheelConstraint("S", (0.0, 1.0), kind="steered", steering=0.4)],
                           (1.0, 0.0, 1.0))
    assert w.steering == 0.4


# --- bad input ----------------------------------------------------------------------------------

@pytest.mark.parametrize(
    "kwargs, param",
    [
        ({"name": ""}, "name"),
        ({"position": (0.0, math.nan)}, "position"),
        ({"position": (0.0, 1.0, 2.0)}, "position"),
        ({"heading": math.inf}, "heading"),
        ({"wheel_radius": 0.0}, "wheel_radius"),
        ({"kind": "mecanum"}, "kind"),
        ({"kind": 3}, "kind"),
        ({"kind": "swedish", "roller_angle": 0.0}, "roller_angle"),
        ({"kind": "swedish", "roller_angle": 2.0}, "roller_angle"),
        ({"kind": "fixed", "roller_angle": 0.5}, "roller_angle"),
        ({"kind": "fixed", "steering": 0.5}, "steering"),
        ({"kind": "steered", "steering": 4.0}, "steering"),
        ({"kind": "steered", "steering": math.nan}, "steering"),
    ],
)
def test_bad_wheels_raise_value_error_naming_the_parameter(kwargs, param):
    base = {"name": "W", "position": (0.0, 0.0)}
    with pytest.raises(ValueError, match=param):
        WheelConstraint(**{**base, **kwargs})


@pytest.mark.parametrize(
    "call, param",
    [
        (lambda: wheel_rates([], (0, 0, 0)), "wheels"),
        (lambda: wheel_rates(WheelConstraint("A", (0, 0)), (0, 0, 0)), "wheels"),
        (lambda: wheel_rates([1, 2], (0, 0, 0)), "wheels"),
        (lambda: wheel_rates([WheelConstraint("A", (0, 0))] * 2, (0, 0, 0)), "unique"),
        (lambda: wheel_rates(diff_drive_wheels(0.1, 0.02), (0, 0)), "twist"),
        (lambda: wheel_rates(diff_drive_wheels(0.1, 0.02), (0, math.nan, 0)), "twist"),
        (lambda: slip_residual(diff_drive_wheels(0.1, 0.02), "fast"), "twist"),
        (lambda: body_twist(diff_drive_wheels(0.1, 0.02), [1.0, 2.0]), "rates"),
        (lambda: body_twist(diff_drive_wheels(0.1, 0.02)[2:], [1.0]), "caster"),
        (lambda: steer_for_twist(_swerve(), np.zeros((2, 3))), "twist"),
        (lambda: rolling_row("wheel"), "wheel"),
        (lambda: diff_drive_wheels(-0.1, 0.02), "track_width"),
        (lambda: diff_drive_wheels(0.1, 0.02, caster="yes"), "caster"),
        (lambda: diff_drive_wheels(0.1, 0.02, caster_offset=0.0), "caster_offset"),
        (lambda: skid_steer_wheels(half_track=0.06, half_wheelbase=math.nan, wheel_radius=0.04), "half_wheelbase"),
        (lambda: mecanum_wheels((0.05, 0.2, 0.15)), "geometry"),
        (lambda: rover_wheels((7, 10, 10, 10)), "geometry"),
        (lambda: rover_wheels(wheel_radius=0), "wheel_radius"),
        (lambda: rover_wheels(turning_radius=-10.0 * INCH), "radius"),
        (lambda: WheelConstraint("A", (0, 0)).roller_axis, "roller_axis"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, param):
    with pytest.raises(ValueError, match=param):
        call()
