"""wheelkin.control: the pose controller, line following, trajectory tracking, the simulator.

Independent references: the closed loops derived here again in sympy from the unicycle's
kinematics (chain rule on the polar and error coordinates), their linearisations and
eigenvalues; the gain conditions of Astolfi and of Siegwart et al. (the local condition
k_rho > 0, k_beta < 0, k_alpha - k_rho > 0 and Siegwart's strong-stability margin, with the
two published gain sets (3, 8, -1.5) and Corke's (3, 8, -3)); hand values; the Lyapunov
functions of the chapter, decreasing along simulated runs; the backwards law built from the
forward law on a robot and goal turned half a turn (via wheelkin.frames); the simulator
against frames.se2_exp compositions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from wheelkin import control as C
from wheelkin import frames

CORKE = (3.0, 8.0, -3.0)
SIEGWART = (3.0, 8.0, -1.5)


# ------------------------------------------------------------------------------ sympy models

_x, _y, _th, _v, _w = sp.symbols("x y theta v omega", real=True)
_kr, _ka, _kb = sp.symbols("k_rho k_alpha k_beta", real=True)
_rho_s, _al_s, _be_s = sp.symbols("rho alpha beta", real=True)


def _polar_rates():
    """(rho', alpha', beta') of a unicycle at (x, y, theta) in the goal frame, by the chain
    rule (valid where the polar coordinates are smooth: rho > 0, no wrap)."""
    rho = sp.sqrt(_x**2 + _y**2)
    alpha = sp.atan2(-_y, -_x) - _th
    beta = -_th - alpha
    xdot, ydot, thdot = _v * sp.cos(_th), _v * sp.sin(_th), _w
    rates = [sp.diff(q, _x) * xdot + sp.diff(q, _y) * ydot + sp.diff(q, _th) * thdot
             for q in (rho, alpha, beta)]
    return [sp.simplify(r) for r in rates]


def _closed_loop():
    """The closed loop in (rho, alpha, beta), written in those coordinates."""
    v = _kr * _rho_s
    w = _ka * _al_s + _kb * _be_s
    return sp.Matrix([-v * sp.cos(_al_s), -w + v * sp.sin(_al_s) / _rho_s,
                      -v * sp.sin(_al_s) / _rho_s])


def test_polar_kinematics_by_the_chain_rule_match_the_closed_loop_forms():
    rates = sp.lambdify((_x, _y, _th, _v, _w), _polar_rates())
    rng = np.random.default_rng(1)
    for _ in range(100):
        x, y = rng.uniform(-2, 2, 2)
        th = rng.uniform(-1, 1)
        v, w = rng.uniform(-1, 1, 2)
        rho, alpha, _ = C.polar_coordinates((x, y, th), (0, 0, 0))
        want = (-v * math.cos(alpha), -w + v * math.sin(alpha) / rho,
                -v * math.sin(alpha) / rho)
        assert np.allclose(rates(x, y, th, v, w), want, atol=1e-9)


def test_the_law_closes_the_loop_the_chapter_states():
    # finite difference of the polar coordinates along a short exact step of the twist
    rng = np.random.default_rng(2)
    h = 1e-6
    for _ in range(50):
        pose = np.array([*rng.uniform(-2, 2, 2), rng.uniform(-math.pi, math.pi)])
        goal = rng.uniform(-1, 1, 3)
        rho, alpha, beta = C.polar_coordinates(pose, goal)
        if abs(alpha) > 1.4 or abs(abs(beta) - math.pi) < 0.1 or rho < 0.1:
            continue
        tw = C.move_to_pose(pose, goal, *CORKE, direction="forward")
        after = frames.compose(frames.Pose(*pose), frames.se2_exp(tw, h))
        r2, a2, b2 = C.polar_coordinates(after, goal)
        kr, ka, kb = CORKE
        want = (-kr * rho * math.cos(alpha), kr * math.sin(alpha) - ka * alpha - kb * beta,
                -kr * math.sin(alpha))
        got = ((r2 - rho) / h, (a2 - alpha) / h, (b2 - beta) / h)
        assert np.allclose(got, want, rtol=1e-4, atol=1e-4)


def _linear_matrix():
    f = _closed_loop().subs({_kr * _rho_s * sp.sin(_al_s) / _rho_s: _kr * sp.sin(_al_s)})
    f = sp.simplify(f)
    return f.jacobian([_rho_s, _al_s, _be_s]).subs({_rho_s: 0, _al_s: 0, _be_s: 0})


def test_linearised_closed_loop_and_its_characteristic_polynomial():
    a = sp.simplify(_linear_matrix())
    assert a == sp.Matrix([[-_kr, 0, 0], [0, -(_ka - _kr), -_kb], [0, -_kr, 0]])
    lam = sp.Symbol("lambda")
    poly = sp.factor(a.charpoly(lam).as_expr())
    assert sp.simplify(poly - (lam + _kr) * (lam**2 + (_ka - _kr) * lam - _kr * _kb)) == 0


def test_the_library_refuses_exactly_the_gains_the_eigenvalues_refuse():
    a = sp.lambdify((_kr, _ka, _kb), _linear_matrix())
    rng = np.random.default_rng(3)
    for _ in range(400):
        gains = rng.uniform(-5, 5, 3)
        stable = np.all(np.linalg.eigvals(np.array(a(*gains), dtype=float)).real < -1e-9)
        try:
            C.move_to_pose((0, 1, 0), (0, 0, 0), *gains)
            accepted = True
        except ValueError:
            accepted = False
        assert accepted == stable, gains


@pytest.mark.parametrize(("gains", "name"), [((0.0, 8.0, -3.0), "k_rho"),
                                              ((-1.0, 8.0, -3.0), "k_rho"),
                                              ((3.0, 8.0, 0.0), "k_beta"),
                                              ((3.0, 8.0, 1.0), "k_beta"),
                                              ((3.0, 3.0, -1.0), "k_alpha - k_rho"),
                                              ((3.0, 2.0, -1.0), "k_alpha - k_rho")])
def test_bad_gains_name_the_condition(gains, name):
    with pytest.raises(ValueError, match=name.replace("-", r"\-")):
        C.move_to_pose((0, 1, 0), (0, 0, 0), *gains)


def test_published_gains_and_siegwart_strong_stability():
    for gains in (CORKE, SIEGWART):
        C.move_to_pose((1, 1, 0), (0, 0, 0), *gains)  # accepted
    # k_alpha + 5/3 k_beta - 2/pi k_rho, by hand
    assert C.strong_stability_margin(*CORKE) == pytest.approx(8 - 5 - 6 / math.pi)
    assert C.strong_stability_margin(*SIEGWART) == pytest.approx(8 - 2.5 - 6 / math.pi)
    assert C.strong_stability_margin(3, 4, -3) < 0  # locally stable, not strongly


def test_hand_values():
    # behind the goal, facing it: straight at it
    assert C.move_to_pose((-2.0, 0.0, 0.0), (0, 0, 0), *CORKE) == frames.Twist(6.0, 0.0, 0.0)
    # beside the goal, facing along it: alpha = +90 deg (left), beta = -90 deg, forwards
    rho, alpha, beta = C.polar_coordinates((0.0, -1.0, 0.0), (0.0, 0.0, 0.0))
    assert (rho, alpha, beta) == pytest.approx((1.0, math.pi / 2, -math.pi / 2))
    tw = C.move_to_pose((0.0, -1.0, 0.0), (0.0, 0.0, 0.0), *CORKE)
    assert (tw.vx, tw.omega) == pytest.approx((3.0, 8 * math.pi / 2 - 3 * -math.pi / 2))
    # a goal elsewhere in the world: the same as moving everything into its frame
    goal = frames.Pose(2.0, -1.0, 0.7)
    pose = frames.compose(goal, frames.Pose(-1.0, 0.3, 0.2))
    assert C.move_to_pose(pose, goal, *CORKE) == pytest.approx(
        C.move_to_pose((-1.0, 0.3, 0.2), (0, 0, 0), *CORKE))


def test_at_the_goal_the_robot_turns_in_place_to_its_heading():
    tw = C.move_to_pose((1.0, 1.0, 0.3), (1.0, 1.0, 0.0), *CORKE)
    assert tw.vx == 0.0 and tw.omega == pytest.approx(-8 * 0.3)


def test_backwards_is_the_forward_law_on_the_half_turned_robot_and_goal():
    rng = np.random.default_rng(4)
    checked = 0
    for _ in range(200):
        pose = np.array([*rng.uniform(-2, 2, 2), rng.uniform(-math.pi, math.pi)])
        goal = np.array([*rng.uniform(-1, 1, 2), rng.uniform(-math.pi, math.pi)])
        if abs(C.polar_coordinates(pose, goal).alpha) <= math.pi / 2:
            continue
        back = C.move_to_pose(pose, goal, *SIEGWART)
        half = np.array([0.0, 0.0, math.pi])
        turned = C.move_to_pose(pose + half, goal + half, *SIEGWART,
                                direction="forward")
        assert back.vx == pytest.approx(-turned.vx) and back.vx < 0
        assert back.omega == pytest.approx(turned.omega, abs=1e-9)
        checked += 1
    assert checked > 50


def test_within_the_stop_distance_it_turns_to_the_goal_heading_as_at_the_goal():
    near = C.move_to_pose((0.003, -0.002, 0.4), (0, 0, 0), *CORKE, stop_distance=0.005)
    at_goal = C.move_to_pose((0.0, 0.0, 0.4), (0, 0, 0), *CORKE)
    assert near == pytest.approx(at_goal) and near == pytest.approx((0.0, 0.0, -8 * 0.4))
    far = C.move_to_pose((0.3, -0.2, 0.4), (0, 0, 0), *CORKE, stop_distance=0.005)
    assert far == C.move_to_pose((0.3, -0.2, 0.4), (0, 0, 0), *CORKE)
    behind = C.move_to_pose((0.003, 0.0, 0.0), (0, 0, 0), *CORKE, stop_distance=0.005)
    assert behind == (0.0, 0.0, 0.0)  # not backwards: it has arrived


def test_measurement_noise_at_the_goal_spins_the_published_law_and_not_the_stopping_one():
    rng = np.random.default_rng(8)
    starts = _grid(3, 4)
    ends = {}
    for stop in (0.0, 0.005):
        def law(t, p, stop=stop):
            seen = p + rng.normal(0.0, 5e-4, p.shape) * [1.0, 1.0, 0.0]
            return C.move_to_pose(seen, (0, 0, 0), *CORKE, stop_distance=stop)

        ends[stop] = C.simulate(law, starts, 12.0, 0.01, max_speed=0.5)[-1]
    turned = np.abs(frames.wrap_angle(ends[0.0][:, 2]))
    assert np.median(turned) > math.radians(10)  # the bearing is noise: the heading too
    assert np.all(np.abs(frames.wrap_angle(ends[0.005][:, 2])) < math.radians(0.5))
    assert np.all(np.hypot(ends[0.005][:, 0], ends[0.005][:, 1]) < 0.006)


def test_direction_can_be_imposed():
    fwd = C.move_to_pose((1.0, 0.0, 0.0), (0, 0, 0), *CORKE, direction="forward")
    assert fwd.vx == 3.0  # drives away first: alpha = pi
    back = C.move_to_pose((-1.0, 0.0, 0.0), (0, 0, 0), *CORKE, direction="backward")
    assert back.vx == -3.0


def test_stacks_give_arrays_and_one_pose_a_twist():
    poses = np.array([[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])
    out = C.move_to_pose(poses, (0, 0, 0), *CORKE)
    assert out.shape == (2, 3)
    for row, pose in zip(out, poses, strict=True):
        assert tuple(row) == pytest.approx(tuple(C.move_to_pose(pose, (0, 0, 0), *CORKE)))
    assert isinstance(C.move_to_pose([0.0, -1.0, 0.0], (0, 0, 0), *CORKE), frames.Twist)


def _grid(n=5, headings=8):
    xs = np.linspace(-1.0, 1.0, n)
    return np.array([(x, y, th) for x in xs for y in xs
                     for th in np.linspace(-math.pi, math.pi, headings, endpoint=False)
                     if math.hypot(x, y) > 0.05])


def test_every_start_of_a_grid_converges_with_corke_gains():
    law = lambda t, p: C.move_to_pose(p, (0, 0, 0), *CORKE)  # noqa: E731
    path = C.simulate(law, _grid(), 12.0, 0.01, max_speed=1.0, max_yaw_rate=8.0)
    end = path[-1]
    assert np.all(np.hypot(end[:, 0], end[:, 1]) < 0.01)
    assert np.all(np.abs(frames.wrap_angle(end[:, 2])) < math.radians(1))


def test_the_lyapunov_function_of_the_angles_decreases():
    kr, _, kb = SIEGWART
    starts = _grid(4, 6)
    law = lambda t, p: C.move_to_pose(p, (0, 0, 0), *SIEGWART, direction="forward")  # noqa
    path = C.simulate(law, starts, 0.5, 1e-3)
    pol = C.polar_coordinates(path.reshape(-1, 3), (0, 0, 0))
    alpha = pol.alpha.reshape(path.shape[:2])
    beta = pol.beta.reshape(path.shape[:2])
    lyap = 1 - np.cos(alpha) - kb / (2 * kr) * beta**2
    inside = lyap[0] < 1.5  # a sublevel set that keeps |alpha| < pi and |beta| < pi
    assert inside.sum() > 20
    dv = np.diff(lyap[:, inside], axis=0)
    # the law is sampled every millisecond: where the continuous V' is zero (alpha = 0) the
    # held command can raise V by O(T^2) = 1e-6 of a step's change; no more
    assert np.all(dv < 1e-8)
    assert np.all(lyap[-1, inside] < lyap[0, inside])


def test_line_error_and_following_hand_values():
    assert C.line_error((1.0, 2.0, 0.5), (0.0, 1.0), math.pi / 2) == pytest.approx(
        (-1.0, 0.5 - math.pi / 2))
    tw = C.follow_line((0.0, 0.5, 0.2), (0.0, 0.0), 0.0, 0.4, 4.0, 3.0)
    want = -4.0 * 0.4 * 0.5 * math.sin(0.2) / 0.2 - 3.0 * 0.4 * 0.2
    assert tw == pytest.approx((0.4, 0.0, want))
    back = C.follow_line((0.0, 0.5, 0.2), (0.0, 0.0), 0.0, -0.4, 4.0, 3.0)
    assert back.omega == pytest.approx(4.0 * 0.4 * 0.5 * math.sin(0.2) / 0.2 - 3.0 * 0.4 * 0.2)


def test_line_following_linearised_in_distance_does_not_depend_on_speed():
    ky, kt, v = sp.symbols("k_y k_theta v", positive=True)
    e_y, e_th = sp.symbols("e_y e_theta", real=True)
    omega = -ky * v * e_y * sp.sin(e_th) / e_th - kt * v * e_th
    rates = sp.Matrix([v * sp.sin(e_th), omega]) / v  # d/ds = (d/dt) / v
    a = rates.jacobian([e_y, e_th]).subs({e_y: 0}).limit(e_th, 0)
    assert sp.simplify(a - sp.Matrix([[0, 1], [-ky, -kt]])) == sp.zeros(2, 2)
    # and the simulated paths coincide when driven at two speeds over the same distance
    start = (0.0, 0.4, 0.6)
    paths = []
    for speed in (0.2, 0.5):
        law = lambda t, p, sp_=speed: C.follow_line(p, (0, 0), 0.0, sp_, 4.0, 4.0)  # noqa
        paths.append(C.simulate(law, start, 4.0 / speed, 0.002 / speed))
    assert np.allclose(paths[0], paths[1], atol=1e-9)


def test_line_following_lyapunov_decreases_for_both_directions():
    rng = np.random.default_rng(5)
    starts = np.column_stack([rng.uniform(-1, 1, 30), rng.uniform(-1, 1, 30),
                              rng.uniform(-3, 3, 30)])
    for speed in (0.3, -0.3):
        law = lambda t, p, s=speed: C.follow_line(p, (0, 0), 0.3, s, 4.0, 4.0)  # noqa
        path = C.simulate(law, starts, 20.0, 0.002)
        err = C.line_error(path.reshape(-1, 3), (0, 0), 0.3)
        lyap = (0.5 * 4.0 * err.offset**2 + 0.5 * err.heading**2).reshape(path.shape[:2])
        assert np.all(np.diff(lyap, axis=0) < 1e-6)
        assert np.all(lyap[-1] < 1e-4)


def test_tracking_error_dynamics_by_finite_differences():
    rng = np.random.default_rng(6)
    h = 1e-6
    for _ in range(50):
        pose = np.array([*rng.uniform(-1, 1, 2), rng.uniform(-3, 3)])
        ref = pose + rng.uniform(-0.3, 0.3, 3)
        v_r, w_r = rng.uniform(0.1, 1.0), rng.uniform(-1, 1)
        tw = C.track_trajectory(pose, ref, (v_r, 0, w_r), 1.0, 10.0, 5.0)
        e = C.tracking_error(pose, ref)
        pose2 = frames.compose(frames.Pose(*pose), frames.se2_exp(tw, h))
        ref2 = frames.compose(frames.Pose(*ref), frames.se2_exp((v_r, 0.0, w_r), h))
        e2 = C.tracking_error(pose2, ref2)
        v, w = tw.vx, tw.omega
        want = (w * e.y - v + v_r * math.cos(e.theta), -w * e.x + v_r * math.sin(e.theta),
                w_r - w)
        got = ((e2.x - e.x) / h, (e2.y - e.y) / h, (e2.theta - e.theta) / h)
        assert np.allclose(got, want, rtol=1e-4, atol=1e-5)


def test_tracking_linearisation_eigenvalues():
    ex, ey, et, vr, wr = sp.symbols("e_x e_y e_theta v_r omega_r", real=True)
    kx, ky, kt = sp.symbols("k_x k_y k_theta", positive=True)
    v = vr * sp.cos(et) + kx * ex
    w = wr + vr * (ky * ey + kt * sp.sin(et))
    f = sp.Matrix([w * ey - v + vr * sp.cos(et), -w * ex + vr * sp.sin(et), wr - w])
    a = f.jacobian([ex, ey, et]).subs({ex: 0, ey: 0, et: 0, wr: 0})
    lam = sp.Symbol("lambda")
    want = (lam + kx) * (lam**2 + vr * kt * lam + vr**2 * ky)
    assert sp.expand(a.charpoly(lam).as_expr() - want) == 0


def test_tracking_on_the_reference_and_convergence_on_a_circle():
    assert C.track_trajectory((1, 2, 0.5), (1, 2, 0.5), (0.3, 0.0, -0.2), 1, 10, 5) == \
        pytest.approx((0.3, 0.0, -0.2))
    v_r, w_r = 0.3, 0.5

    def reference(t):
        return np.array([math.sin(w_r * t) / w_r * v_r, (1 - math.cos(w_r * t)) / w_r * v_r,
                          w_r * t])

    def law(t, p):
        return C.track_trajectory(p, reference(t), (v_r, 0.0, w_r), 2.0, 25.0, 10.0)

    starts = np.array([[-0.3, 0.2, 0.5], [0.2, -0.3, -0.5], [0.0, 0.0, 1.2]])
    path = C.simulate(law, starts, 25.0, 0.005)
    final = path[-1] - reference(25.0)
    assert np.all(np.hypot(final[:, 0], final[:, 1]) < 1e-3)
    # Kanayama's Lyapunov function decreases (the law is sampled: within a hair)
    lyap = []
    for k in range(0, len(path), 20):
        e = C.tracking_error(path[k], reference(k * 0.005))
        lyap.append(0.5 * (e.x**2 + e.y**2) + (1 - np.cos(e.theta)) / 25.0)
    assert np.all(np.diff(np.array(lyap), axis=0) < 1e-7)


def test_tracking_refuses_a_sideways_reference():
    with pytest.raises(ValueError, match="reference_twist"):
        C.track_trajectory((0, 0, 0), (0, 0, 0), (0.3, 0.1, 0.0), 1, 1, 1)


def test_simulate_is_exact_for_a_constant_twist():
    tw = (0.4, 0.0, 0.7)
    path = C.simulate(lambda t, p: np.tile(tw, (len(p), 1)), (0.1, 0.2, 0.3), 1.0, 0.1)
    pose = frames.Pose(0.1, 0.2, 0.3)
    for k in range(1, 11):
        pose = frames.compose(pose, frames.se2_exp(tw, 0.1))
        assert path[k] == pytest.approx(tuple(pose), abs=1e-12)


def test_simulate_limits_keep_the_curvature():
    def law(t, p):
        return np.tile([2.0, 0.0, 4.0], (len(p), 1))

    fast = C.simulate(law, (0, 0, 0), 0.1, 0.01)
    slow = C.simulate(law, (0, 0, 0), 1.0, 0.01, max_speed=0.2)
    # the same arc: the slow run reaches at 1 s where the fast one is at 0.1 s
    assert slow[-1] == pytest.approx(fast[-1], abs=1e-9)
    capped = C.simulate(law, (0, 0, 0), 1.0, 0.01, max_yaw_rate=0.4)
    assert capped[-1] == pytest.approx(fast[-1], abs=1e-9)


def test_simulate_rejects_a_bad_law():
    with pytest.raises(ValueError, match="law"):
        C.simulate(lambda t, p: np.full((len(p), 3), np.nan), (0, 0, 0), 1.0, 0.1)
    with pytest.raises(ValueError, match="law"):
        C.simulate(42, (0, 0, 0), 1.0, 0.1)
