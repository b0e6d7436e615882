"""Tests for wheelkin.frames, each against an independent derivation or a property.

Independent references used here: a sympy derivation of the rigid-body velocity field and its
ICR; the matrix exponential of se(2) (scipy.linalg.expm) for exact integration; a fine RK4
integration of the world-frame ODE; homogeneous 3x3 matrices for composition; each source's own
update equations and printed numbers for the converters.
"""

import math
import pickle

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from scipy.linalg import expm

from wheelkin import frames
from wheelkin.frames import (
    Pose,
    Twist,
    compose,
    firmware_pose_to_ours,
    icr,
    icr_array,
    integrate_twist,
    inverse,
    lab_pose_to_ours,
    mecanum_doc_heading_to_ours,
    mecanum_doc_pose_to_ours,
    mecanum_doc_twist_to_ours,
    ours_to_firmware_pose,
    ours_to_lab_pose,
    ours_to_mecanum_doc_heading,
    ours_to_mecanum_doc_pose,
    ours_to_mecanum_doc_twist,
    ours_to_rover_radius,
    point_velocity,
    relative,
    rover_radius_to_ours,
    rover_twist,
    se2_exp,
    transform_points,
    wrap_angle,
)

PI = math.pi
val = st.floats(min_value=-100.0, max_value=100.0, allow_nan=False, allow_infinity=False)
angle = st.floats(min_value=-50.0, max_value=50.0, allow_nan=False, allow_infinity=False)
any_angle = st.floats(min_value=-1e9, max_value=1e9, allow_nan=False, allow_infinity=False)
nonzero_rate = st.floats(min_value=0.01, max_value=10.0).flatmap(
    lambda w: st.sampled_from([w, -w]))


def homogeneous(x, y, th):
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]])


def from_homogeneous(m):
    return np.array([m[0, 2], m[1, 2], math.atan2(m[1, 0], m[0, 0])])


def same_angle(a, b, tol=1e-9):
    d = (a - b) / (2 * PI)
    return abs(d - round(d)) < tol


# --------------------------------------------------------------------------------------------
# Pose and Twist
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("cls", [Pose, Twist])
def test_pose_and_twist_validate_freeze_and_unpack(cls):
    names = list(cls._fields)
    obj = cls(1, 2, 3)
    assert obj.as_array().tolist() == [1.0, 2.0, 3.0]
    assert np.asarray(obj).tolist() == [1.0, 2.0, 3.0]
    assert all(type(getattr(obj, n)) is float for n in names)
    a, b, c = obj  # a NamedTuple unpacks
    assert (a, b, c) == (1.0, 2.0, 3.0)
    assert cls.from_array(obj.as_array()) == obj
    with pytest.raises(AttributeError):
        setattr(obj, names[0], 5.0)
    with pytest.raises(ValueError, match=rf"^{names[1]} must be a finite number"):
        obj._replace(**{names[1]: math.nan})
    assert obj._replace(**{names[2]: 4.0}) == cls(1, 2, 4)
    assert pickle.loads(pickle.dumps(obj)) == obj
    for i, name in enumerate(names):
        for bad in (math.nan, math.inf, "x", "1", None, True):
            args = [0.0, 0.0, 0.0]
            args[i] = bad
            # not a number at all (a string, even "1", None, a flag) is a TypeError
            error = ValueError if isinstance(bad, float) else TypeError
            with pytest.raises(error, match=rf"^{name} must be a (finite|real) number"):
                cls(*args)
    with pytest.raises(ValueError, match="must have shape"):
        cls.from_array([1.0, 2.0])
    with pytest.raises(ValueError, match=r"must have shape \(3,\)"):
        cls.from_array(np.zeros((2, 3)))


# --------------------------------------------------------------------------------------------
# wrap_angle
# --------------------------------------------------------------------------------------------


@given(any_angle)
def test_wrap_in_range_idempotent_and_congruent(a):
    w = wrap_angle(a)
    assert -PI < w <= PI
    assert wrap_angle(w) == w  # bit for bit
    # Congruent modulo 2 pi (to the precision the size of a allows).
    assert same_angle(w, a, tol=1e-15 * max(1.0, abs(a)) + 1e-15)


@given(st.lists(any_angle, min_size=1, max_size=20))
def test_wrap_vectorised_matches_scalar(values):
    out = wrap_angle(np.array(values))
    assert out.shape == (len(values),)
    assert [wrap_angle(x) for x in values] == out.tolist()


def test_wrap_boundaries():
    assert wrap_angle(PI) == PI
    assert wrap_angle(-PI) == PI
    assert wrap_angle(3 * PI) == pytest.approx(PI)
    assert wrap_angle(0.0) == 0.0
    assert wrap_angle(2 * PI) == pytest.approx(0.0, abs=1e-15)
    assert wrap_angle(np.nextafter(-PI, 0.0)) == np.nextafter(-PI, 0.0)
    assert wrap_angle(np.nextafter(-PI, -4.0)) <= PI
    assert wrap_angle(-1e-20) == -1e-20
    assert wrap_angle(np.zeros((2, 2))).shape == (2, 2)


@pytest.mark.parametrize("bad", [math.nan, math.inf, [0.0, -math.inf], "north"])
def test_wrap_rejects_bad_input(bad):
    with pytest.raises(ValueError, match=r"^angle "):
        wrap_angle(bad)


# --------------------------------------------------------------------------------------------
# Point velocities and the ICR, against a sympy derivation
# --------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def sympy_velocity_field():
    vx, vy, w, px, py = sp.symbols("v_x v_y omega p_x p_y", real=True)
    v3 = sp.Matrix([vx, vy, 0]) + sp.Matrix([0, 0, w]).cross(sp.Matrix([px, py, 0]))
    sol = sp.solve([v3[0], v3[1]], [px, py], dict=True)
    assert len(sol) == 1
    field = sp.lambdify((vx, vy, w, px, py), [v3[0], v3[1]], "numpy")
    centre = sp.lambdify((vx, vy, w), [sol[0][px], sol[0][py]], "numpy")
    return field, centre


def test_point_velocity_and_icr_match_sympy(sympy_velocity_field):
    field, centre = sympy_velocity_field
    rng = np.random.default_rng(1)
    tw = rng.uniform(-3, 3, size=(200, 3))
    pts = rng.uniform(-2, 2, size=(200, 2))
    for t, p in zip(tw, pts, strict=True):
        np.testing.assert_allclose(point_velocity(t, p), field(*t, *p), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(icr(Twist(*t)), centre(*t), rtol=1e-12)
    np.testing.assert_allclose(point_velocity(tw, pts),
                               np.array(field(*tw.T, *pts.T)).T, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(icr_array(tw), np.array(centre(*tw.T)).T, rtol=1e-12)


@given(val, val, nonzero_rate)
def test_the_icr_does_not_move(vx, vy, w):
    c = icr(Twist(vx, vy, w))
    np.testing.assert_allclose(point_velocity(Twist(vx, vy, w), c), [0.0, 0.0], atol=1e-9)


def test_icr_examples_and_signs():
    assert icr(Twist(1.0, 0.0, 0.5)).tolist() == [0.0, 2.0]  # left turn: ICR on the left
    assert icr(Twist(1.0, 0.0, -0.5)).tolist() == [0.0, -2.0]  # right turn: on the right
    assert icr(Twist(0.0, 0.0, 1.0)).tolist() == [0.0, 0.0]  # spin in place
    assert icr(Twist(1.0, 0.0, 0.0)) is None
    assert icr(Twist(0.0, 0.0, 0.0)) is None
    assert icr([1.0, 0.0, 0.5]).tolist() == [0.0, 2.0]
    out = icr_array(np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 2.0, 1.0]]))
    assert np.all(np.isinf(out[:2]))
    np.testing.assert_allclose(out[2], [-2.0, 1.0])
    assert icr_array(np.zeros((4, 2, 3))).shape == (4, 2, 2)


@pytest.mark.parametrize("bad", [[1.0, 2.0], [1.0, math.nan, 0.0], "fast"])
def test_icr_rejects_bad_twists(bad):
    with pytest.raises(ValueError, match=r"^twist"):
        icr(bad)
    with pytest.raises(ValueError, match=r"^twists"):
        icr_array(bad)


def test_point_velocity_rejects_bad_points():
    with pytest.raises(ValueError, match=r"^point must have shape"):
        point_velocity(Twist(1, 0, 0), [1.0, 2.0, 3.0])


# --------------------------------------------------------------------------------------------
# Exact integration, against the matrix exponential and a fine RK4
# --------------------------------------------------------------------------------------------


def expm_step(t, dt):
    vx, vy, w = t
    xi = np.array([[0.0, -w, vx], [w, 0.0, vy], [0.0, 0.0, 0.0]]) * dt
    return expm(xi)


@given(val, val, st.floats(min_value=-20, max_value=20), st.floats(min_value=0.0, max_value=5.0))
def test_se2_exp_matches_matrix_exponential(vx, vy, w, dt):
    d = se2_exp(Twist(vx, vy, w), dt)
    m = expm_step((vx, vy, w), dt)
    np.testing.assert_allclose([d.x, d.y], m[:2, 2], rtol=1e-9, atol=1e-9)
    assert same_angle(d.theta, math.atan2(m[1, 0], m[0, 0]), tol=1e-9)
    assert d.theta == pytest.approx(w * dt)


def test_se2_exp_is_accurate_for_tiny_turns():
    # No cancellation for small omega dt, and a straight line at omega = 0.
    for phi in (9.999e-5, 1.0001e-4, 1e-8, 1e-300, 0.0, -1e-6):
        d = se2_exp(Twist(1.3, -0.4, phi), 1.0)
        m = expm_step((1.3, -0.4, phi), 1.0)
        np.testing.assert_allclose([d.x, d.y], m[:2, 2], rtol=1e-13, atol=1e-15)


def test_se2_exp_vectorised_and_validated():
    tw = np.array([[1.0, 0.0, 0.0], [1.0, 0.5, 2.0]])
    out = se2_exp(tw, 0.5)
    assert out.shape == (2, 3)
    np.testing.assert_allclose(out[1], se2_exp(Twist(1.0, 0.5, 2.0), 0.5).as_array())
    with pytest.raises(ValueError, match=r"^dt must be a finite number"):
        se2_exp(tw, math.nan)
    with pytest.raises(ValueError, match=r"^twist must have shape"):
        se2_exp([1.0, 2.0], 1.0)


def rk4_world(twists, dt, pose0, substeps=200):
    pose = np.array(pose0, dtype=float)
    out = [pose.copy()]

    def f(p, t):
        c, s = math.cos(p[2]), math.sin(p[2])
        return np.array([c * t[0] - s * t[1], s * t[0] + c * t[1], t[2]])

    h = dt / substeps
    for t in twists:
        for _ in range(substeps):
            k1 = f(pose, t)
            k2 = f(pose + h / 2 * k1, t)
            k3 = f(pose + h / 2 * k2, t)
            k4 = f(pose + h * k3, t)
            pose = pose + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(pose.copy())
    return np.array(out)


def test_integrate_twist_matches_rk4():
    rng = np.random.default_rng(7)
    twists = rng.uniform([-1, -0.5, -2], [1, 0.5, 2], size=(20, 3))
    twists[3, 2] = 0.0  # a straight step
    poses = integrate_twist(twists, 0.1, Pose(0.5, -0.2, 3.0))
    ref = rk4_world(twists, 0.1, [0.5, -0.2, 3.0])
    np.testing.assert_allclose(poses[:, :2], ref[:, :2], atol=1e-9)
    assert all(same_angle(a, b, 1e-9) for a, b in zip(poses[:, 2], ref[:, 2], strict=True))
    # not wrapped: the start heading (3 rad, near pi) plus the summed turns
    turns = np.concatenate([[0.0], np.cumsum(twists[:, 2] * 0.1)])
    np.testing.assert_allclose(poses[:, 2], 3.0 + turns, atol=1e-12)


def test_integrate_twist_matches_matrix_products():
    rng = np.random.default_rng(3)
    twists = rng.uniform(-2, 2, size=(30, 3))
    poses = integrate_twist(twists, 0.2, [1.0, 2.0, -0.5])
    m = homogeneous(1.0, 2.0, -0.5)
    for k, t in enumerate(twists):
        m = m @ expm_step(t, 0.2)
        got = poses[k + 1]
        np.testing.assert_allclose(got[:2], m[:2, 2], atol=1e-10)
        assert same_angle(got[2], math.atan2(m[1, 0], m[0, 0]))


def test_a_circle_closes_and_stays_on_its_circle():
    n = 48
    poses = integrate_twist(np.tile([0.5, 0.0, 0.5 / 1.5], (n, 1)), 2 * PI * 1.5 / 0.5 / n)
    np.testing.assert_allclose(poses[-1], [0.0, 0.0, 2 * PI], atol=1e-12)  # one whole turn
    np.testing.assert_allclose(np.hypot(poses[:, 0], poses[:, 1] - 1.5), 1.5, rtol=1e-12)


@pytest.mark.parametrize(
    ("twists", "dt", "pose0", "match"),
    [
        ([1.0, 0.0, 0.0], 0.1, None, r"^twists must have shape \(N, 3\)"),
        ([[1.0, 0.0]], 0.1, None, "^twists must have shape"),
        ([[1.0, math.nan, 0.0]], 0.1, None, "^twists must not contain NaN"),
        ([[1.0, 0.0, 0.0]], 0.0, None, "^dt must be a finite number > 0"),
        ([[1.0, 0.0, 0.0]], 0.1, [0.0, 0.0], "^pose0 must have shape"),
        ([[1.0, 0.0, 0.0]], 0.1, np.zeros((2, 3)), r"^pose0 must have shape \(3,\)"),
    ],
)
def test_integrate_twist_rejects_bad_input(twists, dt, pose0, match):
    with pytest.raises(ValueError, match=match):
        integrate_twist(twists, dt, pose0)


# --------------------------------------------------------------------------------------------
# compose, inverse, relative, transform_points, against homogeneous matrices
# --------------------------------------------------------------------------------------------


@given(val, val, angle, val, val, angle)
def test_compose_matches_matrix_product(x, y, th, dx, dy, dth):
    got = compose(Pose(x, y, th), Pose(dx, dy, dth))
    ref = from_homogeneous(homogeneous(x, y, th) @ homogeneous(dx, dy, dth))
    np.testing.assert_allclose([got.x, got.y], ref[:2], atol=1e-9)
    assert same_angle(got.theta, ref[2])
    assert got.theta == pytest.approx(th + dth, abs=1e-12)  # not wrapped: the turns add


@given(val, val, angle, val, val, angle)
def test_inverse_and_relative(x, y, th, x2, y2, th2):
    a, b = Pose(x, y, th), Pose(x2, y2, th2)
    ident = compose(a, inverse(a))
    np.testing.assert_allclose(ident.as_array(), [0.0, 0.0, 0.0], atol=1e-9)
    back = compose(a, relative(a, b))
    np.testing.assert_allclose([back.x, back.y], [b.x, b.y], atol=1e-9)
    assert same_angle(back.theta, b.theta)


def test_pose_functions_vectorised():
    rng = np.random.default_rng(5)
    a = rng.uniform(-2, 2, size=(10, 3))
    b = rng.uniform(-2, 2, size=(10, 3))
    c = compose(a, b)
    assert c.shape == (10, 3)
    for k in range(10):
        np.testing.assert_allclose(c[k], compose(Pose(*a[k]), Pose(*b[k])).as_array(),
                                   atol=1e-12)
    np.testing.assert_allclose(compose(a, relative(a, b))[:, :2], b[:, :2], atol=1e-12)
    np.testing.assert_allclose(inverse(inverse(a)), np.column_stack([a[:, :2],
                                                                     wrap_angle(a[:, 2])]),
                               atol=1e-12)
    pts = transform_points(Pose(*a[0]), rng.uniform(-1, 1, size=(5, 2)))
    assert pts.shape == (5, 2)


def test_transform_points_matches_matrix():
    m = homogeneous(1.0, -2.0, 0.7)
    pts = np.array([[0.3, 0.4], [-1.0, 2.0]])
    ref = (m @ np.column_stack([pts, np.ones(2)]).T).T[:, :2]
    np.testing.assert_allclose(transform_points(Pose(1.0, -2.0, 0.7), pts), ref, atol=1e-12)


def test_pose_functions_reject_bad_input():
    with pytest.raises(ValueError, match=r"^delta must have shape"):
        compose(Pose(0, 0, 0), [1.0, 2.0])
    with pytest.raises(ValueError, match=r"^pose must not contain NaN"):
        inverse([0.0, math.nan, 0.0])
    with pytest.raises(ValueError, match=r"^pose_to must have shape"):
        relative(Pose(0, 0, 0), [[1.0]])
    with pytest.raises(ValueError, match=r"^points must have shape"):
        transform_points(Pose(0, 0, 0), [1.0, 2.0, 3.0])


# --------------------------------------------------------------------------------------------
# Rover: inches, r > 0 = right turn
# --------------------------------------------------------------------------------------------

# The rover document's base dimensions (inches) and its table for r = 30 in, X = 100.
D1, D2, D3, D4 = 7.254, 10.5, 10.5, 10.073
OSR_TABLE_30IN = [96.59, 100.0, 96.59, 62.52, 49.73, 62.52]


def test_rover_radius_examples():
    assert rover_radius_to_ours(30.0) == pytest.approx(-0.762)
    assert rover_radius_to_ours(-30.0) == pytest.approx(0.762)
    assert rover_radius_to_ours(math.inf) == -math.inf
    assert rover_radius_to_ours(-math.inf) == math.inf
    assert math.copysign(1.0, rover_radius_to_ours(0.0)) == 1.0  # no negative zero
    assert ours_to_rover_radius(math.inf) == -math.inf
    np.testing.assert_allclose(rover_radius_to_ours([30.0, -250.0]), [-0.762, 6.35])


@given(st.floats(allow_nan=False, min_value=-1e6, max_value=1e6) | st.sampled_from(
    [math.inf, -math.inf]))
def test_rover_radius_round_trip(r):
    assert ours_to_rover_radius(rover_radius_to_ours(r)) == pytest.approx(r, rel=1e-14)


def test_rover_table_from_our_icr():
    # Wheels in our body frame (metres), in the document's motor order 1..6 =
    # front-left, middle-left, rear-left, front-right, middle-right, rear-right (x fwd, y left).
    wheels = np.array([[D3, D1], [0.0, D4], [-D2, D1], [D3, -D1], [0.0, -D4], [-D2, -D1]]) * 0.0254
    tw = rover_twist(30.0, 10.0)
    centre = np.array(icr(tw))
    assert centre[1] < 0  # r > 0 turns right: the ICR is on our right (y < 0)
    dist = np.hypot(*(wheels - centre).T)
    pct = 100 * dist / dist.max()
    np.testing.assert_allclose(pct, OSR_TABLE_30IN, atol=0.006)
    # Every wheel's velocity is perpendicular to its arm from the ICR (rolls without slip).
    vel = point_velocity(tw, wheels)
    np.testing.assert_allclose(np.sum(vel * (wheels - centre), axis=1), 0.0, atol=1e-12)


@given(st.floats(min_value=1.0, max_value=1e4), st.floats(min_value=-50, max_value=50))
def test_rover_twist_mirror_and_icr(r, speed):
    right, left = rover_twist(r, speed), rover_twist(-r, speed)
    assert right.vx == left.vx == pytest.approx(speed * 0.0254)
    assert right.omega == pytest.approx(-left.omega)
    if abs(speed) > 1e-6:
        assert icr(right) == pytest.approx((0.0, -r * 0.0254))
        assert icr(left) == pytest.approx((0.0, r * 0.0254))


def test_rover_twist_straight_vectorised_and_validated():
    assert rover_twist(math.inf, 20.0) == Twist(0.508, 0.0, 0.0)
    assert rover_twist(-math.inf, 20.0) == Twist(0.508, 0.0, 0.0)
    out = rover_twist(np.array([30.0, math.inf]), 10.0)
    assert out.shape == (2, 3)
    np.testing.assert_allclose(out[1], [0.254, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^radius_in must be non-zero"):
        rover_twist(0.0, 10.0)
    with pytest.raises(ValueError, match=r"^radius_in must not contain NaN"):
        rover_twist(math.nan, 10.0)
    with pytest.raises(ValueError, match=r"^centre_speed_in_per_s must not contain NaN"):
        rover_twist(30.0, math.inf)
    with pytest.raises(ValueError, match="must have the same shape"):
        rover_twist([30.0, 40.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"^radius_m must not contain NaN"):
        ours_to_rover_radius(math.nan)


# --------------------------------------------------------------------------------------------
# Mecanum simulator: feet, body X right / Y forward, headings clockwise from +Y
# --------------------------------------------------------------------------------------------


def test_mecanum_inverse_matrix_is_ours_with_ccw_omega_and_fl_fr_rl_rr():
    """Derive our mecanum inverse kinematics from the roller geometry, then compare rows."""
    vx, vy, w, r, lx, ly, k = sp.symbols("v_x v_y omega r l_x l_y k", real=True)
    # Our wheel layout (x forward, y left) and the direction of each roller's axis at the
    # contact, for the usual X pattern seen from above; FL, FR, RL, RR.
    layout = {"FL": ((lx, ly), (1, -1)), "FR": ((lx, -ly), (1, 1)),
              "RL": ((-lx, ly), (1, 1)), "RR": ((-lx, -ly), (1, -1))}
    ours = []
    for (px, py), (ax, ay) in layout.values():
        contact = sp.Matrix([vx - w * py, vy + w * px])  # v + omega x p
        axis = sp.Matrix([ax, ay]) / sp.sqrt(2)
        # The roller is free to roll across its axis; along it the wheel must carry the motion:
        # contact . axis = r * phi * (e_x . axis).
        phi = sp.simplify(contact.dot(axis) / (r * axis[0]))
        ours.append(sp.expand(phi.subs(lx + ly, k).subs(lx, k - ly)))
    # The document's matrix, with its k = (L + H), acting on ITS (Vx, Vy, omega_doc).
    doc = sp.Matrix([[1, 1, -k], [-1, 1, k], [-1, 1, -k], [1, 1, k]]) / r
    vx_doc, vy_doc, w_doc = -vy, vx, w  # our twist seen in its frame (units cancel here)
    psi = doc * sp.Matrix([vx_doc, vy_doc, w_doc])
    for i in range(4):
        assert sp.simplify(psi[i] - ours[i]) == 0
    # With a clockwise-positive omega the rows would not match.
    psi_cw = doc * sp.Matrix([vx_doc, vy_doc, -w])
    assert any(sp.simplify(psi_cw[i] - ours[i]) != 0 for i in range(4))
    # And the document's forward matrix inverts its inverse matrix: F @ I = identity.
    fwd = r / 4 * sp.Matrix([[1, -1, -1, 1], [1, 1, 1, 1], [-1 / k, 1 / k, -1 / k, 1 / k]])
    assert sp.simplify(fwd * doc) == sp.eye(3)


def test_mecanum_twist_examples():
    assert mecanum_doc_twist_to_ours(0.0, 15.0, 0.0) == Twist(4.572, 0.0, 0.0)  # top speed fwd
    assert mecanum_doc_twist_to_ours(1.0, 0.0, 0.0) == Twist(0.0, -0.3048, 0.0)  # strafe right
    assert mecanum_doc_twist_to_ours(0.0, 0.0, 0.5).omega == 0.5


@given(val, val, val)
def test_mecanum_twist_round_trip(a, b, c):
    back = ours_to_mecanum_doc_twist(mecanum_doc_twist_to_ours(a, b, c))
    np.testing.assert_allclose(back, (a, b, c), rtol=1e-12, atol=1e-12)
    t = Twist(a, b, c)
    np.testing.assert_allclose(mecanum_doc_twist_to_ours(*ours_to_mecanum_doc_twist(t))
                               .as_array(), t.as_array(), rtol=1e-12, atol=1e-12)


@given(angle)
def test_mecanum_heading_round_trip(psi):
    back = ours_to_mecanum_doc_heading(mecanum_doc_heading_to_ours(psi))
    assert same_angle(back, psi)
    assert -PI < back <= PI


@given(val, val, angle, val, val, val)
def test_mecanum_world_velocity_agrees(X, Y, psi, Vx, Vy, w):
    """The document's world velocity equals ours, for any pose and body twist."""
    # Its body axes in its world at heading psi (clockwise from +Y): forward (sin, cos),
    # right (cos, -sin).
    fwd = np.array([math.sin(psi), math.cos(psi)])
    right = np.array([math.cos(psi), -math.sin(psi)])
    doc_world_v = (Vx * right + Vy * fwd) * 0.3048
    pose = mecanum_doc_pose_to_ours(X, Y, psi)
    tw = mecanum_doc_twist_to_ours(Vx, Vy, w)
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    ours_world_v = np.array([c * tw.vx - s * tw.vy, s * tw.vx + c * tw.vy])
    np.testing.assert_allclose(ours_world_v, doc_world_v, atol=1e-9)
    np.testing.assert_allclose([pose.x, pose.y], [X * 0.3048, Y * 0.3048], rtol=1e-12)


def test_mecanum_heading_rate_is_minus_omega():
    # Turn CCW at omega for dt in our frame; the document's heading (clockwise) decreases.
    theta0 = mecanum_doc_heading_to_ours(0.3)
    dt, w = 0.01, 0.5
    psi1 = ours_to_mecanum_doc_heading(theta0 + w * dt)
    assert (psi1 - 0.3) / dt == pytest.approx(-w)


@given(val, val, angle)
def test_mecanum_pose_round_trip(X, Y, psi):
    back = ours_to_mecanum_doc_pose(mecanum_doc_pose_to_ours(X, Y, psi))
    np.testing.assert_allclose(back[:2], (X, Y), rtol=1e-12, atol=1e-12)
    assert same_angle(back[2], psi)


def test_mecanum_vectorised_and_validated():
    out = mecanum_doc_pose_to_ours(np.array([1.0, 2.0]), np.array([3.0, 4.0]), 0.0)
    assert out.shape == (2, 3)
    np.testing.assert_allclose(ours_to_mecanum_doc_pose(out)[:, :2], [[1.0, 3.0], [2.0, 4.0]])
    assert mecanum_doc_twist_to_ours([1.0], [2.0], [0.0]).shape == (1, 3)
    for fn, args, name in [
        (mecanum_doc_twist_to_ours, (math.nan, 0.0, 0.0), "Vx_ftps"),
        (mecanum_doc_twist_to_ours, (0.0, math.inf, 0.0), "Vy_ftps"),
        (mecanum_doc_twist_to_ours, (0.0, 0.0, "fast"), "omega"),
        (mecanum_doc_pose_to_ours, (0.0, math.nan, 0.0), "Y_ft"),
        (mecanum_doc_heading_to_ours, (math.nan,), "psi"),
        (ours_to_mecanum_doc_heading, (math.inf,), "theta"),
    ]:
        with pytest.raises(ValueError, match=rf"^{name} "):
            fn(*args)
    with pytest.raises(ValueError, match=r"^twist must have shape"):
        ours_to_mecanum_doc_twist([1.0, 2.0])
    with pytest.raises(ValueError, match=r"^twist must be a Twist"):
        ours_to_mecanum_doc_twist(Pose(0, 0, 0))
    with pytest.raises(ValueError, match=r"^pose must be a Pose"):
        ours_to_mecanum_doc_pose(Twist(0, 0, 0))


# --------------------------------------------------------------------------------------------
# Firmware: mm, X right / Y forward, theta CCW from +Y
# --------------------------------------------------------------------------------------------


@given(val, val, angle, st.floats(min_value=-500, max_value=500))
def test_firmware_step_is_our_step_along_our_heading(X, Y, th, d):
    """The firmware's own update, dX = -d sin(theta), dY = d cos(theta), is a step of d along
    our heading theta once both poses are converted."""
    before = firmware_pose_to_ours(X * 1000, Y * 1000, th)
    after = firmware_pose_to_ours(X * 1000 - d * math.sin(th), Y * 1000 + d * math.cos(th), th)
    step = np.array([after.x - before.x, after.y - before.y])
    np.testing.assert_allclose(step, d / 1000 * np.array([math.cos(th), math.sin(th)]),
                               atol=1e-9)
    assert after.theta == th


def test_firmware_turn_sense():
    # alpha = (distanceRight - distanceLeft) / wheelBase > 0 when the right wheel goes further:
    # a left (CCW) turn, which must increase our theta too.
    alpha = (110.0 - 90.0) / 85.0
    assert firmware_pose_to_ours(0.0, 0.0, alpha).theta > 0
    assert firmware_pose_to_ours(0.0, 1000.0, 0.0) == Pose(1.0, 0.0, 0.0)
    assert firmware_pose_to_ours(1000.0, 0.0, 0.0) == Pose(0.0, -1.0, 0.0)  # X right = -y


@given(val, val, angle)
def test_firmware_round_trip(X, Y, th):
    back = ours_to_firmware_pose(firmware_pose_to_ours(X, Y, th))
    np.testing.assert_allclose(back, (X, Y, th), rtol=1e-12, atol=1e-12)
    p = Pose(X, Y, th)
    np.testing.assert_allclose(firmware_pose_to_ours(*ours_to_firmware_pose(p)).as_array(),
                               p.as_array(), rtol=1e-12, atol=1e-12)


def test_firmware_vectorised_and_validated():
    arr = np.array([[0.0, 1000.0, 0.0], [-100.0, 2000.0, 0.5]])
    ours = firmware_pose_to_ours(*arr.T)
    np.testing.assert_allclose(ours, [[1.0, 0.0, 0.0], [2.0, 0.1, 0.5]])
    np.testing.assert_allclose(ours_to_firmware_pose(ours), arr)
    with pytest.raises(ValueError, match=r"^X_mm must not contain NaN"):
        firmware_pose_to_ours(math.nan, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"^theta must not contain NaN"):
        firmware_pose_to_ours(0.0, 0.0, math.inf)
    with pytest.raises(ValueError, match=r"^pose must have shape"):
        ours_to_firmware_pose([1.0, 2.0])


# --------------------------------------------------------------------------------------------
# Lab: the same frame as ours
# --------------------------------------------------------------------------------------------


@given(val, val, angle)
def test_lab_identity_round_trip(x, y, th):
    assert lab_pose_to_ours(x, y, th) == Pose(x, y, th)
    assert ours_to_lab_pose(Pose(x, y, th)) == (x, y, th)


def test_lab_update_matches_ours():
    # The lab's x = x0 + d cos(theta), y = y0 + d sin(theta) is our straight step.
    p = lab_pose_to_ours(1.5, -1.5, PI / 2)
    step = se2_exp(Twist(2.5, 0.0, 0.0), 1.0)
    q = compose(p, step)
    np.testing.assert_allclose([q.x, q.y], [1.5 + 2.5 * math.cos(PI / 2),
                                            -1.5 + 2.5 * math.sin(PI / 2)], atol=1e-12)


def test_lab_validated_and_vectorised():
    with pytest.raises(ValueError, match=r"^y must not contain NaN"):
        lab_pose_to_ours(0.0, math.nan, 0.0)
    with pytest.raises(ValueError, match=r"^pose must have shape"):
        ours_to_lab_pose([[1.0, 2.0]])
    assert lab_pose_to_ours([1.0, 2.0], [3.0, 4.0], [0.0, 0.1]).shape == (2, 3)


def test_module_lists_its_public_names():
    for name in frames.__all__:
        assert hasattr(frames, name)


# --------------------------------------------------------------------------------------------
# se2_log (the inverse of se2_exp) and pose_rate, against scipy's matrix logarithm and a
# sympy derivative

def _homogeneous(x, y, th):
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]])


@given(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0), st.floats(-3.1, 3.1), st.floats(0.1, 5.0))
def test_se2_log_is_the_matrix_logarithm(dx, dy, dth, dt):
    from scipy.linalg import logm

    twist = frames.se2_log([dx, dy, dth], dt)
    xi = np.real(logm(_homogeneous(dx, dy, dth))) / dt  # principal log: |dth| < pi here
    np.testing.assert_allclose(twist, [xi[0, 2], xi[1, 2], xi[1, 0]], atol=1e-9)


@given(st.floats(-2.0, 2.0), st.floats(-2.0, 2.0), st.floats(-6.2, 6.2), st.floats(0.05, 3.0))
def test_se2_log_inverts_se2_exp(vx, vy, phi, dt):
    twist = np.array([vx, vy, phi / dt])
    back = frames.se2_log(frames.se2_exp(twist, dt), dt)
    np.testing.assert_allclose(back, twist, atol=1e-9 * (1 + 1 / abs(2 * math.pi - abs(phi))))


def test_se2_log_by_hand():
    # straight ahead 3 m in 2 s: 1.5 m/s, no turn
    assert frames.se2_log(Pose(3.0, 0.0, 0.0), 2.0) == Twist(1.5, 0.0, 0.0)
    # a turn on the spot
    assert frames.se2_log(Pose(0.0, 0.0, 1.0)) == Twist(0.0, 0.0, 1.0)
    # a half circle of radius 1 to the left: from (0, 0) to (0, 2), pi/1 s of travel
    tw = frames.se2_log(Pose(0.0, 2.0, math.pi))
    assert (tw.vx, tw.vy, tw.omega) == pytest.approx((math.pi, 0.0, math.pi), abs=1e-15)
    # arrays: one row per displacement
    out = frames.se2_log([[3.0, 0.0, 0.0], [0.0, 0.0, 1.0]], 1.0)
    np.testing.assert_allclose(out, [[3.0, 0.0, 0.0], [0.0, 0.0, 1.0]], atol=1e-15)
    # the default duration is one second in both directions: exp(log(delta)) is delta
    delta = Pose(0.3, -0.2, 1.1)
    np.testing.assert_allclose(frames.se2_exp(frames.se2_log(delta)), delta, atol=1e-15)


@pytest.mark.parametrize("delta, dt, match", [
    (Pose(0.0, 0.0, 2 * math.pi), 1.0, "delta"),
    ([0.0, 0.0, -7.0], 1.0, "delta"),
    ([0.0, math.nan, 0.0], 1.0, "delta"),
    ([0.0, 0.0], 1.0, "delta"),
    (Pose(1.0, 0.0, 0.0), 0.0, "dt"),
    (Pose(1.0, 0.0, 0.0), True, "dt"),
])
def test_se2_log_rejects_bad_input(delta, dt, match):
    with pytest.raises(ValueError, match=match):
        frames.se2_log(delta, dt)


def test_pose_rate_is_the_derivative_of_the_exact_motion():
    t, th0, vx, vy, w = sp.symbols("t theta0 v_x v_y omega", real=True)
    # the exact motion under a constant twist: heading th0 + w t, velocity rotated into the
    # world; its derivative at t = 0 is the pose rate
    theta = th0 + w * t
    xdot = vx * sp.cos(theta) - vy * sp.sin(theta)
    ydot = vx * sp.sin(theta) + vy * sp.cos(theta)
    x = sp.integrate(xdot, (t, 0, t))
    y = sp.integrate(ydot, (t, 0, t))
    rates = [sp.diff(e, t).subs(t, 0) for e in (x, y, theta)]
    f = sp.lambdify((th0, vx, vy, w), rates)
    rng = np.random.default_rng(4)
    for th, a, b, c in rng.uniform(-4, 4, size=(50, 4)):
        got = frames.pose_rate(th, Twist(a, b, c))
        assert isinstance(got, frames.PoseRate)
        np.testing.assert_allclose(got, [float(r) for r in f(th, a, b, c)], atol=1e-12)


def test_pose_rate_by_hand_and_vectorised():
    r = frames.pose_rate(0.0, Twist(1.0, 0.0, 0.0))
    assert r == (1.0, 0.0, 0.0) and r.x_dot == 1.0
    # an array twist in, an array out (the module's rule), even for one twist
    out = frames.pose_rate(0.0, [1.0, 0.0, 0.0])
    assert isinstance(out, np.ndarray) and out.tolist() == [1.0, 0.0, 0.0]
    out = frames.pose_rate([0.0, math.pi / 2], [[1.0, 0.0, 0.3], [1.0, 0.0, 0.3]])
    np.testing.assert_allclose(out, [[1.0, 0.0, 0.3], [0.0, 1.0, 0.3]], atol=1e-15)
    with pytest.raises(ValueError, match="theta"):
        frames.pose_rate(math.nan, Twist(1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="twist"):
        frames.pose_rate(0.0, [1.0, 0.0])


def test_relative_heading_is_the_unwrapped_difference():
    # from heading 3.0 to heading -3.0: -6 rad as given (wrap_angle gives the shorter +0.283)
    d = frames.relative(Pose(0.0, 0.0, 3.0), Pose(0.0, 0.0, -3.0))
    assert d.theta == pytest.approx(-6.0, abs=1e-15)
    assert frames.wrap_angle(d.theta) == pytest.approx(2 * math.pi - 6.0, abs=1e-15)
    out = frames.relative([[0.0, 0.0, -3.0]], [[0.0, 0.0, 3.0]])
    assert out[0, 2] == pytest.approx(6.0, abs=1e-15)
