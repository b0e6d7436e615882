"""The contact solver, checked against first principles (Coulomb friction, maximum dissipation).

Independent references: hand calculations of one step (a vehicle accelerating from rest on a
dry floor and on ice, the mecanum rollers' factor sqrt 2), the physics of rolling wheels (a
skid steer cannot turn without slipping; an over-driven mecanum wheel slips), and for any
state the *dual* of the contact problem, solved here with scipy's SLSQP: the impulses lambda,
one per wheel inside its friction disc (an interval for a roller), that maximise

    D(lambda) = -1/2 lambda' A lambda - lambda . (J xi_p - b),     A = J M^-1 J',

give the twist xi_p + M^-1 J' lambda. By weak duality every feasible lambda bounds the
primal objective F (the module's dissipation principle) from below, and F is strongly convex
(1/2 |xi - xi*|_M^2 <= F(xi) - F*), so F(solver's twist) - D(lambda) bounds the solver's error
whatever the accuracy of SLSQP. F is written out again here, not taken from the module.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import minimize

from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    RC_CAR,
)
from wheelkin.sandbox.contact import (
    ContactModel,
    _newton,
    _solve_small,
    _Warm,
    dissipation_objective,
)
from wheelkin.sandbox.vehicles import GRAVITY, diff_drive

DT = 1 / 240


# ----------------------------------------------------------------------------- references
def lopsided(spec):
    """``spec`` with its wheels moved so that no mirror (left-right or front-back) maps the
    vehicle onto itself."""
    shifts = [(0.031, 0.017), (-0.012, -0.029), (0.008, 0.041), (-0.027, 0.006)]
    wheels = []
    i = 0
    for w in spec.wheels:
        if w.kind == "caster":
            wheels.append(w)
            continue
        dx, dy = shifts[i % len(shifts)]
        i += 1
        wheels.append(dataclasses.replace(w, position=(w.position[0] + dx, w.position[1] + dy)))
    return spec.replace(wheels=tuple(wheels), name=spec.name + " (lopsided)")


def primal(model, rates, xp, xi):
    """F(xi) = 1/2 |xi - xi_p|_M^2 + sum_w cap_w |slip_w| (slip: J_w xi - b_w)."""
    J, b = model.J, model.B @ np.asarray(rates, float)
    d = np.asarray(xi, float) - np.asarray(xp, float)
    slip = (J @ xi - b).reshape(model.n, model.k)
    return 0.5 * float(d @ (model.mass_diag * d)) + float(model.caps @ np.linalg.norm(slip, axis=1))


def dual(model, rates, xp, enough=-np.inf):
    """The impulses of maximum dissipation (SLSQP on the dual), each wheel's inside its disc.

    Returns (lambda (n, k), twist xi_p + M^-1 J' lambda, dual value D(lambda)); a second start
    is tried unless the first reaches the value ``enough``."""
    J, b = model.J, model.B @ np.asarray(rates, float)
    n, k, caps = model.n, model.k, model.caps
    xp = np.asarray(xp, float)
    Minv = 1.0 / model.mass_diag
    c = np.repeat(caps, k)  # lambda = c * nu, |nu_w| <= 1
    A = (J * Minv) @ J.T
    g = J @ xp - b
    Q, q = c[:, None] * A * c[None, :], c * g
    scale = max(np.abs(Q).max(), np.abs(q).max(), 1e-300)
    Q, q = Q / scale, q / scale

    def D(nu):
        return 0.5 * nu @ Q @ nu + q @ nu, Q @ nu + q

    def cons(nu):
        return 1.0 - (nu.reshape(n, k) ** 2).sum(1)

    def cons_jac(nu):
        out = np.zeros((n, n * k))
        for w in range(n):
            out[w, w * k:(w + 1) * k] = -2.0 * nu[w * k:(w + 1) * k]
        return out

    best = None
    for start in (np.zeros(n * k), -np.clip(np.linalg.lstsq(Q, q, rcond=None)[0], -1, 1)):
        res = minimize(D, start, jac=True, method="SLSQP",
                       constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}],
                       options={"ftol": 1e-16, "maxiter": 1000})
        nu = res.x.reshape(n, k)
        nu = nu / np.maximum(1.0, np.linalg.norm(nu, axis=1))[:, None]  # feasible, exactly
        nu = nu.reshape(-1)
        if best is None or D(nu)[0] < D(best)[0]:
            best = nu
        if -D(best)[0] * scale >= enough:
            break
    lam = c * best
    xi = xp + Minv * (J.T @ lam)
    value = -0.5 * lam @ A @ lam - lam @ g
    return lam.reshape(n, k), xi, float(value)


def check_against_first_principles(model, rates, xp, res, *, gap=1e-11):
    """The solver's answer is the maximum-dissipation twist, and its flags and slip speeds
    say what Coulomb's law says of it."""
    xi = np.array(res.twist)
    F = primal(model, rates, xp, xi)
    lam, xi_ref, D = dual(model, rates, xp, enough=F - 0.5 * gap * (1.0 + abs(F)))
    scale = 1.0 + abs(D)
    assert F - D <= gap * scale, (F, D)
    # Strong convexity: |xi - xi*|_M <= sqrt(2 (F - D)); and the dual's own twist agrees.
    np.testing.assert_allclose(xi, xi_ref, atol=1e-6)
    slip = (model.J @ xi - model.B @ np.asarray(rates, float)).reshape(model.n, model.k)
    speed = np.linalg.norm(slip, axis=1)
    np.testing.assert_allclose(res.slip_speed, speed * np.array(res.slipping), atol=1e-9)
    for w in range(model.n):
        if speed[w] > 1e-7:  # a wheel that slips is flagged, and its friction is at its cap
            assert res.slipping[w], (w, speed[w])
            assert np.linalg.norm(lam[w]) == pytest.approx(model.caps[w], rel=1e-5)
        elif not res.slipping[w]:  # a wheel that rolls grips within its disc
            assert np.linalg.norm(lam[w]) <= model.caps[w] * (1 + 1e-6)


# ----------------------------------------------------------------------------- objective
def test_dissipation_objective_by_hand():
    # One two-row wheel: rows x and y of the body, asking for (0.7, 0.4) m/s; the body moves
    # at (1, 0, 0) from rest: kinetic 1/2 * 2 * 1^2 = 1, slip (0.3, -0.4) of length 0.5
    # costs 3 * 0.5 = 1.5 (a circle: not 3 * (0.3 + 0.4)).
    J = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    F = dissipation_objective([1.0, 0.0, 0.0], [0.0, 0.0, 0.0], J, np.array([0.7, 0.4]),
                              np.array([2.0, 2.0, 1.0]), np.array([3.0]), 2)
    assert F == pytest.approx(2.5, rel=1e-15)
    # Two one-row wheels (rollers): |1 - 0.7| * 3 + |0 - 0.4| * 5 = 0.9 + 2; kinetic as above
    # plus a spin 0.5 with inertia 4: 1/2 * 4 * 0.25 = 0.5.
    F = dissipation_objective([1.0, 0.0, 0.5], [0.0, 0.0, 0.0], J, np.array([0.7, 0.4]),
                              np.array([2.0, 2.0, 4.0]), np.array([3.0, 5.0]), 1)
    assert F == pytest.approx(1.0 + 0.5 + 0.9 + 2.0, rel=1e-15)


@pytest.mark.parametrize("spec", [RADON_ULZER, MECANUM_ROBOT], ids=["circles", "rollers"])
def test_dissipation_objective_is_the_written_out_objective(spec):
    model = ContactModel(spec, (), DT)
    rng = np.random.default_rng(3)
    for _ in range(5):
        rates, xp, xi = rng.normal(0, 5, model.n), rng.normal(0, 0.3, 3), rng.normal(0, 0.3, 3)
        F = dissipation_objective(xi, xp, model.J, model.B @ rates, model.mass_diag,
                                  model.caps, model.k)
        assert F == pytest.approx(primal(model, rates, xp, xi), rel=1e-13)


# ----------------------------------------------------------------------------- any state
def _vehicles():
    return {
        "diff drive": (RADON_ULZER, ()),
        "skid steer": (LAB_ROBOT, ()),
        "mecanum": (MECANUM_ROBOT, ()),
        "rover": (OPEN_SOURCE_ROVER, (0.31, -0.12, -0.25, 0.07)),
        "car": (RC_CAR, (0.22, 0.17)),
        "lopsided diff drive": (lopsided(RADON_ULZER), ()),
        "lopsided skid steer": (lopsided(LAB_ROBOT), ()),
        "lopsided mecanum": (lopsided(MECANUM_ROBOT), ()),
    }


VEHICLES = _vehicles()


@pytest.mark.parametrize("which", list(VEHICLES))
def test_every_state_gets_the_maximum_dissipation_answer(which):
    """From gentle to violent: rates near and far from the free-flight twist's, several
    frictions; one warm record carried from step to step as the world does."""
    spec, steering = VEHICLES[which]
    rng = np.random.default_rng(sum(map(ord, which)))
    warm, fallbacks = _Warm(), []
    for mu in (0.8, 0.1):
        model = ContactModel(spec.replace(mu=mu), steering, DT)
        dv = mu * GRAVITY * DT  # the most one step of friction can change a speed
        radius = np.abs(model.B).max(0)
        radius[radius == 0] = 1.0  # a free-rolling wheel: its rate asks for nothing
        for kick in (0.2, 1.0, 3.0):
            for noise in (0.0, 0.05, 0.5, 3.0):
                # Rates of a random twist (straight ahead: every vehicle can follow that),
                # the twist those rates ask for, and a free-flight twist a kick away from it.
                twist = rng.normal(0, 0.2, 3) * ((1, 0, 0) if noise == 0.0 else (1, 1, 1))
                rates = np.linalg.lstsq(model.B, model.J @ twist, rcond=None)[0]
                asked = np.linalg.lstsq(model.J, model.B @ rates, rcond=None)[0]
                xp = asked + rng.normal(0, kick * dv, 3) * (1, 1, 10)
                rates = (rates + rng.normal(0, noise * dv, model.n) / radius).tolist()
                for record in (warm, _Warm()):
                    res = model.solve(rates, tuple(xp.tolist()), record)
                    if res.method == "pgs":  # the fallback: checked all the same
                        fallbacks.append(res)
                    check_against_first_principles(model, rates, xp, res)
    assert len(fallbacks) <= 2  # of 48 answers: the active set answers almost all


@pytest.mark.parametrize("which, rates, xp", [
    ("rover", [-1.3211955450404562, -1.387324343926056, -1.3441957897715264,
               -1.3773475893800877, -1.387324343926056, -1.383926786959162],
     [-0.08293887800651091, -0.004049687867381245, -0.03710902221449555]),
], ids=["rover, middle wheels sharing their sideways load"])
def test_the_fallback_answer_is_the_maximum_dissipation_answer(which, rates, xp):
    spec, steering = VEHICLES[which]
    model = ContactModel(spec, steering, DT)
    res = model.solve(rates, tuple(xp), _Warm())
    check_against_first_principles(model, rates, np.array(xp), res)


# ----------------------------------------------------------------------------- by hand
# One step from rest, every wheel asked for the same forward speed dv. By symmetry each driven
# wheel takes an equal share of the momentum m dv: a conventional wheel along x; a mecanum
# wheel along its roller axis at 45 degrees, so its impulse is sqrt 2 times its share. The
# friction caps mu N dt then limit dv to mu g dt (skid steer, and the Zumo on its two tracks:
# all the weight on the driven wheels), (1 - caster share) mu g dt (a diff drive with a caster
# carrying a fifth of the weight), mu g dt / sqrt 2 (mecanum).
LIMITS = {
    "skid steer": (LAB_ROBOT, 1.0),
    "diff drive, two tracks": (RADON_ULZER, 1.0),
    "diff drive with a caster": (diff_drive(0.085, 0.018, caster_load=0.2), 0.8),
    "mecanum": (MECANUM_ROBOT, 1 / math.sqrt(2)),
}


@pytest.mark.parametrize("mu", [0.05, 0.8], ids=["ice", "dry floor"])
@pytest.mark.parametrize("which", list(LIMITS))
def test_the_most_a_step_can_accelerate_from_rest(which, mu):
    spec, factor = LIMITS[which]
    model = ContactModel(spec.replace(mu=mu), (), DT)
    limit = factor * mu * GRAVITY * DT
    forward = np.linalg.lstsq(model.B, model.J @ [1.0, 0.0, 0.0], rcond=None)[0]
    below = model.solve((forward * limit * (1 - 1e-6)).tolist(), (0.0, 0.0, 0.0), _Warm())
    assert below.method == "stick" and not any(below.slipping)
    np.testing.assert_allclose(below.twist, [limit * (1 - 1e-6), 0, 0], rtol=1e-12, atol=1e-15)
    above = model.solve((forward * limit * (1 + 1e-6)).tolist(), (0.0, 0.0, 0.0), _Warm())
    assert all(above.slipping)
    np.testing.assert_allclose(above.twist, [limit, 0, 0], rtol=1e-12, atol=1e-15)
    # Each contact point lags its wheel's rim by the speed friction could not give.
    rim_lag = 1e-6 * limit * np.linalg.norm(
        (model.B @ forward).reshape(model.n, model.k), axis=1)
    np.testing.assert_allclose(above.slip_speed, rim_lag, rtol=1e-6)


def test_ice_lets_a_skid_steer_gain_a_sixteenth_of_what_a_dry_floor_does():
    """The same hard launch (rims at 1 m/s from rest): friction-limited on both surfaces."""
    gained = []
    for mu in (0.05, 0.8):
        model = ContactModel(LAB_ROBOT.replace(mu=mu), (), DT)
        res = model.solve([25.0] * 4, (0.0, 0.0, 0.0), _Warm())
        assert all(res.slipping)
        gained.append(res.twist[0])
    assert gained[0] / gained[1] == pytest.approx(0.05 / 0.8, rel=1e-12)


# ----------------------------------------------------------------------------- stick path
STICKY = {  # vehicle, steering, a twist every wheel can follow
    "diff drive": (RADON_ULZER, (), (0.2, 0.0, 2.0)),
    "lopsided diff drive": (lopsided(RADON_ULZER), (), (0.25, 0.0, 0.0)),
    "lopsided skid steer": (lopsided(LAB_ROBOT), (), (0.25, 0.0, 0.0)),
    "lopsided mecanum": (lopsided(MECANUM_ROBOT), (), (0.25, 0.1, 0.8)),
    "car": (RC_CAR, (0.0, 0.0), (0.25, 0.0, 0.0)),
}


@pytest.mark.parametrize("which", list(STICKY))
def test_the_stick_shortcut_is_taken_exactly_when_the_least_impulses_fit(which):
    """Commands a rigid vehicle can follow (the rates of a twist the wheels allow), from a
    free-flight twist kicked in every direction by up to three steps' worth of friction: the
    least impulses that make the momentum change (numpy's least-norm solution of
    J' lambda = M (xi - xi_p)) decide, and the twist is the commanded one when they fit."""
    spec, steering, twist = STICKY[which]
    model = ContactModel(spec, steering, DT)
    rng = np.random.default_rng(11)
    dv = spec.mu * GRAVITY * DT
    twist = np.array(twist)
    rates = np.linalg.lstsq(model.B, model.J @ twist, rcond=None)[0].tolist()
    fits = overs = 0
    for direction in rng.normal(0, 1, (8, 3)) * (1, 1, 8):
        for size in (0.05, 0.2, 0.5, 0.8, 1.2, 3.0):
            xp = twist - size * dv * direction / np.linalg.norm(direction[:2])
            lam = np.linalg.lstsq(model.J.T, model.mass_diag * (twist - xp), rcond=None)[0]
            load = (np.linalg.norm(lam.reshape(model.n, model.k), axis=1) / model.caps).max()
            res = model.solve(rates, tuple(xp.tolist()), _Warm())
            if load < 1 - 1e-6:
                fits += 1
                assert res.method == "stick" and not any(res.slipping)
                np.testing.assert_allclose(res.twist, twist, atol=1e-12)
            elif load > 1 + 1e-6:
                overs += 1
                assert res.method != "stick"
            if res.method != "pgs":
                check_against_first_principles(model, rates, xp, res)
    assert fits > 8 and overs > 8


@pytest.mark.parametrize("wheel", range(4))
def test_a_mecanum_wheel_off_by_a_micrometre_per_second_slips(wheel):
    """Four rollers over-determine a three-dimensional twist: a rate that disagrees with the
    others by 2e-5 rad/s (contact speeds 1e-6 m/s apart) cannot be met by rolling alone."""
    model = ContactModel(MECANUM_ROBOT, (), DT)
    rates = np.linalg.lstsq(model.B, model.J @ [0.3, 0.1, 0.2], rcond=None)[0]
    rates[wheel] += 2e-5
    xp = np.linalg.lstsq(model.J, model.B @ rates, rcond=None)[0]
    res = model.solve(rates.tolist(), tuple(xp.tolist()), _Warm())
    assert res.method != "stick" and any(res.slipping)
    assert 1e-7 < max(res.slip_speed) < 1e-5
    check_against_first_principles(model, rates, xp, res)


@pytest.mark.parametrize("turn", [[4.9, 5.1, 4.9, 5.1], [4.99, 5.01, 4.99, 5.01]])
def test_a_skid_steer_cannot_turn_without_sliding_even_gently(turn):
    """However gentle the turn, its wheels slide sideways; also right after a straight step
    (the record of the last step must not vouch for new rates)."""
    model = ContactModel(LAB_ROBOT, (), DT)
    xp = np.linalg.lstsq(model.J, model.B @ turn, rcond=None)[0]  # the least-squares twist
    warm = _Warm()
    straight = model.solve([5.0] * 4, (0.2, 0.0, 0.0), warm)
    assert straight.method == "stick" and straight.twist == pytest.approx([0.2, 0, 0])
    for record in (_Warm(), warm):
        res = model.solve(turn, tuple(xp.tolist()), record)
        assert res.method != "stick" and any(res.slipping)
        check_against_first_principles(model, turn, xp, res)


def test_a_mecanum_robot_spinning_against_a_straight_command():
    """Rollers asked to drive straight at 4.5 cm/s while the body drifts and spins at
    0.44 rad/s the other way: three wheels slip, one grips. (Found by the mutation study:
    on the way, Newton stalls short of the minimum of one stick/slip partition, and only the
    momentum balance of its impulses tells.)"""
    model = ContactModel(MECANUM_ROBOT, (), DT)
    rates = [0.9011160805554622] * 4
    xp = np.array([0.06387827027213681, 0.13645158251336242, -0.43900363228037176])
    res = model.solve(rates, tuple(xp.tolist()), _Warm())
    assert res.slipping == (False, True, True, True)
    check_against_first_principles(model, rates, xp, res)


# ----------------------------------------------------------------------------- mirrors
def mirrored(spec):
    """The vehicle seen in a mirror along its x axis: y, headings and roller angles negated."""
    wheels = tuple(dataclasses.replace(w, position=(w.position[0], -w.position[1]),
                                       heading=-w.heading, roller_angle=-w.roller_angle)
                   for w in spec.wheels)
    return spec.replace(wheels=wheels)


@pytest.mark.parametrize("which", ["lopsided skid steer", "lopsided mecanum", "rover"])
def test_a_mirrored_vehicle_moves_as_the_mirror_image(which):
    spec, steering = VEHICLES[which]
    model = ContactModel(spec, steering, DT)
    image = ContactModel(mirrored(spec), tuple(-s for s in steering), DT)
    rng = np.random.default_rng(5)
    dv = spec.mu * GRAVITY * DT
    for size in (0.3, 1.0, 4.0):
        twist = rng.normal(0, 0.2, 3)
        rates = np.linalg.lstsq(model.B, model.J @ twist, rcond=None)[0]
        rates = (rates + rng.normal(0, 0.2 * size * dv, model.n) / 0.05).tolist()
        xp = twist + rng.normal(0, size * dv, 3) * (1, 1, 10)
        res = model.solve(rates, tuple(xp.tolist()), _Warm())
        mir = image.solve(rates, (xp[0], -xp[1], -xp[2]), _Warm())
        np.testing.assert_allclose(mir.twist, np.array(res.twist) * (1, -1, -1), atol=1e-10)
        assert mir.slipping == res.slipping
        np.testing.assert_allclose(mir.slip_speed, res.slip_speed, atol=1e-10)


# ----------------------------------------------------------------------------- fallback
def test_projected_gauss_seidel_finds_the_optimum_for_rollers():
    """The fallback on one-row (roller) wheels, from zero impulses: the dual's answer, each
    impulse within its interval, and the twist moved by exactly those impulses."""
    rng = np.random.default_rng(8)
    for spec in (MECANUM_ROBOT, lopsided(MECANUM_ROBOT)):
        model = ContactModel(spec.replace(mu=0.3), (), DT)
        for _ in range(6):
            rates = rng.normal(0, 6, model.n)
            xp = rng.normal(0, 0.2, 3)
            b = model.B @ rates
            xi, lam = model._pgs(b, xp, np.zeros(model.m), 2000)
            _, xi_ref, _ = dual(model, rates, xp)
            np.testing.assert_allclose(xi, xi_ref, atol=1e-9)
            assert np.all(np.abs(lam) <= model.caps * (1 + 1e-12))
            np.testing.assert_allclose(xi, xp + (model.J.T @ lam) / model.mass_diag,
                                       atol=1e-12)


def test_projected_gauss_seidel_caps_a_wheel_in_its_disc():
    """The fallback on two-row wheels: a diff drive asked for 1.5 or 30 times what friction
    can give in one step from rest gains 0.8 mu g dt when a caster carries a fifth of the weight
    (hand calculation above), each wheel's impulse on its circle."""
    spec = diff_drive(0.085, 0.018, caster_load=0.2)
    model = ContactModel(spec, (), DT)
    limit = 0.8 * spec.mu * GRAVITY * DT
    forward = np.linalg.lstsq(model.B, model.J @ [1.0, 0.0, 0.0], rcond=None)[0]
    for times in (1.5, 30.0):
        b = model.B @ (times * limit * forward)
        xi, lam = model._pgs(b, np.zeros(3), np.zeros(model.m), 400)
        np.testing.assert_allclose(xi, [limit, 0, 0], atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(lam.reshape(2, 2), axis=1), model.caps,
                                   rtol=1e-12)


# ----------------------------------------------------------------------------- Newton's parts
@pytest.mark.parametrize("d", [1, 2, 3])
def test_the_small_linear_solve_agrees_with_lapack(d):
    """Newton's step solves H x = g for the symmetric positive definite H of the reduced
    problem (any signs off the diagonal)."""
    rng = np.random.default_rng(d)
    for _ in range(20):
        R = rng.normal(0, 1, (d, d))
        H = R @ R.T + 0.1 * np.eye(d)
        g = rng.normal(0, 1, d)
        x = _solve_small(H.tolist(), g.tolist())
        np.testing.assert_allclose(x, np.linalg.solve(H, g), rtol=1e-9, atol=1e-12)


def _reduced_problem(rng, k, wheels, small_slip=False):
    """A reduced slip problem f(y) = 1/2 y'Mn y + hq'y + sum_w c_w |s0_w + G_w y| with its
    minimiser y* found by scipy (BFGS from y* of the smooth part, polished): every wheel
    slips at y*, so f is smooth there and its gradient vanishes."""
    d = 3
    R = rng.normal(0, 1, (d, d))
    Mn = R @ R.T + 0.5 * np.eye(d)
    hq = rng.normal(0, 1, d)
    G = rng.normal(0, 1, (wheels * k, d))
    s0 = rng.normal(0, 1, wheels * k)
    caps = rng.uniform(0.05, 0.3, wheels)

    def f(y):
        s = (s0 + G @ y).reshape(wheels, k)
        nrm = np.linalg.norm(s, axis=1)
        grad = Mn @ y + hq + G.T @ (np.repeat(caps / nrm, k) * s.reshape(-1))
        return 0.5 * y @ Mn @ y + hq @ y + caps @ nrm, grad

    if small_slip:  # move wheel 0's request so that it slips at only 1e-7 at the optimum
        y = minimize(lambda y: f(y)[0], np.zeros(d), method="Nelder-Mead").x
        s = (s0 + G @ y)[:k]
        s0[:k] -= s * (1 - 1e-7 / np.linalg.norm(s))
    return Mn, hq, G, s0, caps, f


@pytest.mark.parametrize("k", [1, 2], ids=["rollers", "circles"])
def test_newton_returns_the_minimum_or_a_kink(k):
    """Newton stops where a slipping wheel stops slipping (a kink, for the caller to decide);
    anywhere else it has found the minimum: the gradient vanishes and scipy finds no lower
    value nearby."""
    rng = np.random.default_rng(20 + k)
    smooth = 0
    for i in range(16):
        Mn, hq, G, s0, caps, f = _reduced_problem(rng, k, 2, small_slip=i % 2 == 1)
        y = np.array(_newton(Mn.tolist(), hq.tolist(), G.tolist(), s0.tolist(),
                             caps.tolist(), k, [0.0] * 3, [0.0] * 3))
        if np.linalg.norm((s0 + G @ y).reshape(2, k), axis=1).min() <= 1e-15:
            continue
        smooth += 1
        value, grad = f(y)
        assert np.abs(grad).max() < 1e-9
        ref = minimize(f, y + 0.01, jac=True, method="BFGS", options={"gtol": 1e-12})
        assert value <= ref.fun + 1e-14 * (1 + abs(ref.fun))
    assert smooth >= 5


def test_newton_started_on_a_kink_restarts_from_the_alternative():
    """At a point where a slipping wheel does not slip, f has a kink and no gradient: Newton
    starts from the alternative point instead and reaches the minimum (problems whose
    minimum lies well away from every kink)."""
    rng = np.random.default_rng(31)
    done = 0
    while done < 4:
        Mn, hq, G, s0, caps, f = _reduced_problem(rng, 2, 2)
        ref = minimize(f, np.zeros(3), jac=True, method="BFGS", options={"gtol": 1e-12})
        if np.linalg.norm((s0 + G @ ref.x).reshape(2, 2), axis=1).min() < 0.1:
            continue
        done += 1
        kink = rng.normal(0, 1, 3)
        s0[:2] = -G[:2] @ kink  # wheel 0 does not slip at `kink`
        ref = minimize(f, np.zeros(3), jac=True, method="BFGS", options={"gtol": 1e-12})
        y = np.array(_newton(Mn.tolist(), hq.tolist(), G.tolist(), s0.tolist(),
                             caps.tolist(), 2, kink.tolist(), [0.0] * 3))
        assert f(y)[0] <= ref.fun + 1e-12 * (1 + abs(ref.fun))
