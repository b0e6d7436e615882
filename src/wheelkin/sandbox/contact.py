r"""Wheel-ground contact: friction-limited impulses that make the body roll on its wheels.

The model, in plain words
-------------------------
Each step, every driven wheel asks the ground for a velocity at its contact point: along its
rolling direction ``e``, the wheel's surface speed r_w * phi; across it (``n``), zero. A
Swedish (mecanum or omni) wheel asks only along the axis ``u`` of its ground roller, for
r_w * phi * (u . e); the roller spins freely in the other direction. The ground answers with
an *impulse* at the contact point (a force times the step dt) that changes the body's velocity
towards what the wheels ask, and friction caps it: a conventional wheel's impulse lies in a
disc of radius mu * N_i * dt (the Coulomb friction circle, N_i the wheel's normal load), a
Swedish wheel's in the interval of that half-width. Where every wheel gets what it asks within
its cap, the vehicle moves exactly as its kinematic model says; where one cannot, it *slips*,
and it is flagged.

The maths
---------
Work in the body frame with the twist xi = (vx, vy, w) and the mass matrix M = diag(m, m, I)
(the reference point is the mass centre). Row i of the constraint Jacobian J is the direction
d_i of one constraint at its wheel's contact point p_i, acting on the twist:
J_i = (d_x, d_y, p_x d_y - p_y d_x). The requested contact velocities are b = B phi (phi the
wheel rates; B holds r_w on rolling rows, 0 on lateral rows, r_w (u . e) on roller rows). For
a given steering, J is constant, and so is the effective mass A = J M^-1 J^T.

Let xi_p be the twist the body would have after the step with no wheel forces (its world
velocity kept, its frame turned by w dt: this is how the centripetal impulse of a turn is
charged to the tyres). The impulses j (one per row; the book's symbol) give xi' = xi_p + M^-1 J^T j.

1. *Stick*: j = A^+ (b - J xi_p). If the commands are consistent (b lies in the range of
   J) this gives J xi' = b exactly: xi' is the kinematic twist, whatever xi_p was. If also every
   wheel's impulse is within its cap, that is the answer. Because J has full column rank,
   A^+ = J^+T M J^+ with J^+ = (J^T J)^-1 J^T, so xi' = J^+ b = P phi and
   j = J (J^T J)^-1 M (xi' - xi_p): the least impulses that make the momentum change.
   (J^T J) is the same for every steering (a wheel's rolling and lateral directions are
   orthonormal), so a steering change costs only P: a few dozen float operations per step.
2. *Slip*: otherwise xi' minimises the convex function

   F(xi) = 1/2 (xi - xi_p)^T M (xi - xi_p) + sum_w mu N_w dt * norm(J_w xi - b_w)

   (kinetic energy of the correction plus the work friction does on the slip: the principle of
   maximum dissipation), whose optimality conditions are exactly the Coulomb law: a sticking
   wheel has zero slip and an impulse inside its disc; a slipping wheel's impulse has the full
   magnitude mu N_w dt and opposes its slip velocity. It is solved by an active-set method: a
   guess of which wheels slip (last step's, else the stick solution's over-cap wheels, else from
   projected Gauss-Seidel sweeps), Newton's method on the twist within the subspace where the
   sticking wheels do not slip, and corrections of the guess until the Coulomb conditions hold
   (to 1e-9 m/s and 1e-9 of the cap). A slipping wheel is one whose friction is at its cap.

The friction cap is a circle, not a box: the same tyre cannot give its full friction forward
and sideways at once. This matters for a skid steer: turning, its wheels slide sideways, the
sideways friction uses up their grip, the forward forces that would turn the body fall short,
and it turns *slower* than the ideal differential-drive model with its geometric track (a box
would let it turn at the ideal rate). For the lab robot the yaw rate is about 0.59 of the ideal,
whatever mu or the command: an effective track 1.7 times the geometric one. A skid steer cannot
satisfy its lateral constraints while turning at all: it always slips in a turn. That is
physics, and the waypoint chapter relies on it.

Normal loads are static, N_i = load_fraction_i * m * g; a caster carries its share and exerts
no force. Rolling resistance, motor torque limits and load transfer are not modelled: a wheel
turns at its commanded rate (after the optional first-order motor lag) whatever the load.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from wheelkin import _validate as V
from wheelkin import unified
from wheelkin._kernels import point_row, roller_axis

from .vehicles import VehicleSpec

# ContactModel and ContactResult are the world's engine (World.step calls them with values it
# has checked, every step); the public functions are the rows and the objective.
__all__ = ["ConstraintRows", "constraint_rows", "dissipation_objective"]

#: A constraint whose contact velocity misses its request by more than this slips (m/s).
SLIP_TOLERANCE = 1e-9
#: Relative tolerance on the friction cap.
CAP_TOLERANCE = 1e-9


class ConstraintRows(NamedTuple):
    """The contact constraints of a vehicle (see :func:`constraint_rows`)."""

    #: Constraint Jacobian, shape (m, 3): row i is the row's direction applied to the twist.
    J: np.ndarray
    #: Rate map, shape (m, n): the requested contact velocity is ``B @ phi``.
    B: np.ndarray
    #: The index (in ``spec.wheel_names``) of the wheel each row belongs to, shape (m,).
    owner: np.ndarray


def constraint_rows(spec: VehicleSpec, steering: Sequence[float] = ()) -> ConstraintRows:
    """Constraint Jacobian J, rate map B and the driven wheel of each row.

    The rows are those of :mod:`wheelkin.unified` for ``spec.wheels_at(steering)``, grouped by
    wheel in ``spec.wheel_names`` order: (:func:`~wheelkin.unified.rolling_row`,
    :func:`~wheelkin.unified.sliding_row`) for a conventional wheel (an empty rolling row for
    a free-rolling one), (:func:`~wheelkin.unified.roller_row`) for a Swedish wheel. Each is
    J_i = (d_x, d_y, p_x d_y - p_y d_x), d the row's unit direction and p the wheel's contact
    point; the requested contact velocity is b = B @ phi.

    Parameters
    ----------
    spec : VehicleSpec
    steering : sequence of float
        Steering angles of ``spec.steered_names``, rad.

    Examples
    --------
    >>> from wheelkin.sandbox.vehicles import diff_drive
    >>> J, B, wheel = constraint_rows(diff_drive(0.1, 0.02))
    >>> J.round(3).tolist()
    [[1.0, 0.0, -0.05], [0.0, 1.0, 0.0], [1.0, 0.0, 0.05], [0.0, 1.0, 0.0]]
    >>> B.round(3).tolist(), wheel.tolist()
    ([[0.02, 0.0], [0.0, 0.0], [0.0, 0.02], [0.0, 0.0]], [0, 0, 1, 1])
    """
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    k = len(spec.steered_names)
    steer = V.shaped("steering", steering, (k,)) if k else V.finite_array("steering", steering)
    if steer.shape != (k,):
        raise ValueError(f"steering must have {k} angles "
                         f"({', '.join(spec.steered_names) or 'none'}), got shape {steer.shape}")
    if np.any(np.abs(steer) > math.pi):
        raise ValueError(f"steering must be in [-pi, pi] rad, got {steering!r}")
    steer = steer.tolist()
    n = len(spec.wheel_names)
    J, B, owner = [], [], []
    for j, wheel in enumerate(spec.wheels_at(steer)):
        if wheel.kind == "swedish":
            rows = [(unified.roller_row(wheel),
                     wheel.wheel_radius * float(wheel.roller_axis @ wheel.rolling_direction))]
        elif wheel.name in spec.free_rolling:  # rolls freely: an empty rolling row, sliding
            rows = [(np.zeros(3), 0.0), (unified.sliding_row(wheel), 0.0)]
        else:
            rows = [(unified.rolling_row(wheel), wheel.wheel_radius),
                    (unified.sliding_row(wheel), 0.0)]
        for row, coeff in rows:
            J.append(row)
            brow = [0.0] * n
            brow[j] = coeff
            B.append(brow)
            owner.append(j)
    return ConstraintRows(np.array(J), np.array(B), np.array(owner))


def dissipation_objective(xi: npt.ArrayLike, xi_pred: npt.ArrayLike, J: npt.ArrayLike,
                          b: npt.ArrayLike, mass_diag: npt.ArrayLike, caps: npt.ArrayLike,
                          rows_per_wheel: int) -> float:
    """F(xi) = 1/2 (xi - xi_p)^T M (xi - xi_p) + sum_w c_w norm(J_w xi - b_w) (see module doc).

    The contact solution minimises it; tests use it to check optimality independently of the
    solver. ``caps`` are per wheel (mu N_w dt), ``rows_per_wheel`` is 1 or 2.
    """
    if isinstance(rows_per_wheel, bool) or rows_per_wheel not in (1, 2):
        raise ValueError(f"rows_per_wheel must be 1 or 2, got {rows_per_wheel!r}")
    x = V.twist("xi", xi)
    xp = V.twist("xi_pred", xi_pred)
    jac = V.shaped("J", J, (3,))
    if jac.ndim != 2 or len(jac) == 0 or len(jac) % rows_per_wheel:
        raise ValueError(f"J must have shape (m, 3) with m a multiple of rows_per_wheel "
                         f"({rows_per_wheel}), got shape {jac.shape}")
    m = len(jac)
    rhs = V.finite_array("b", b)
    if rhs.shape != (m,):
        raise ValueError(f"b must have shape ({m},), one per row of J, got shape {rhs.shape}")
    mass = V.finite_array("mass_diag", mass_diag)
    if mass.shape != (3,) or np.any(mass <= 0):
        raise ValueError(f"mass_diag must be 3 positive numbers (m, m, I), got {mass_diag!r}")
    c = V.finite_array("caps", caps)
    if c.shape != (m // rows_per_wheel,) or np.any(c < 0):
        raise ValueError(f"caps must be {m // rows_per_wheel} numbers >= 0, one per wheel, "
                         f"got {caps!r}")
    with np.errstate(all="ignore"):
        dx = x - xp
        s = (jac @ x - rhs).reshape(-1, rows_per_wheel)
        value = float(0.5 * dx @ (mass * dx) + c @ np.sqrt((s * s).sum(1)))
    return float(V.finite_result("xi, xi_pred, J, b, mass_diag and caps", value))


@dataclass(slots=True)
class ContactResult:
    """Outcome of one contact solve."""

    twist: list  # (vx, vy, w) after the impulses
    slipping: tuple  # bool per driven wheel
    slip_speed: tuple  # |slip velocity| per driven wheel, m/s
    method: str  # "stick", "active-set" or "pgs"


@dataclass
class _Warm:
    """What the previous step leaves for the next one's slip solve."""

    partition: tuple | None = None
    xi: np.ndarray | None = None
    lam: np.ndarray | None = None
    consistent_key: object = None
    consistent_rates: list | None = None
    consistent: bool = False
    counts: dict = field(default_factory=dict)


def _solve_small(H: list, g: list) -> list:
    """Solve H x = g for a small symmetric positive definite H (lists; Gaussian elimination)."""
    d = len(g)
    a = [[*row, g[i]] for i, row in enumerate(H)]
    for c in range(d):
        p = max(range(c, d), key=lambda r: abs(a[r][c]))
        if p != c:
            a[c], a[p] = a[p], a[c]
        piv = a[c][c]
        for r in range(c + 1, d):
            f = a[r][c] / piv
            if f:
                ar, ac = a[r], a[c]
                for j in range(c, d + 1):
                    ar[j] -= f * ac[j]
    x = [0.0] * d
    for c in range(d - 1, -1, -1):
        acc = a[c][d]
        for j in range(c + 1, d):
            acc -= a[c][j] * x[j]
        x[c] = acc / a[c][c]
    return x


def _newton(Mn: list, hq: list, G: list, s0: list, caps: list, k: int, y: list,
            y_alt: list) -> list:
    """Minimise f(y) = 1/2 y'Mn y + hq'y + sum_w caps_w |s0_w + G_w y| by damped Newton.

    The reduced slip problem of one partition (plain floats: d <= 3 unknowns, a few wheels).
    Slipping wheels add curvature caps_w / |s_w| across their slip direction (k = 2 rows per
    wheel); along it (and for one-row wheels) their term is linear. Newton starts at ``y``,
    or at ``y_alt`` if a slipping wheel has no slip at ``y`` (a kink of f).
    """
    d = len(y)
    rows = len(s0)
    rng = range(d)

    def slips(y):
        s = [s0[i] + sum(G[i][j] * y[j] for j in rng) for i in range(rows)]
        if k == 2:
            nrm = [math.hypot(s[2 * w], s[2 * w + 1]) for w in range(len(caps))]
        else:
            nrm = [abs(v) for v in s]
        return s, nrm

    def value(y, nrm):
        quad = sum(y[i] * (0.5 * sum(Mn[i][j] * y[j] for j in rng) + hq[i]) for i in rng)
        return quad + sum(c * v for c, v in zip(caps, nrm, strict=True))

    s, nrm = slips(y)
    if nrm and min(nrm) <= 1e-15:
        y = y_alt
        s, nrm = slips(y)
    for _it in range(60):
        if nrm and min(nrm) <= 1e-15:
            break  # at a kink: the caller decides whether that wheel sticks
        g = [sum(Mn[i][j] * y[j] for j in rng) + hq[i] for i in rng]
        H = [row[:] for row in Mn]
        for w, c in enumerate(caps):
            inv = 1.0 / nrm[w]
            if k == 2:
                r0, r1 = G[2 * w], G[2 * w + 1]
                a0, a1 = s[2 * w] * inv, s[2 * w + 1] * inv
                q = [a0 * r1[j] - a1 * r0[j] for j in rng]  # J_w^T t, t perpendicular to slip
                cw = c * inv
                for i in rng:
                    g[i] += c * (a0 * r0[i] + a1 * r1[i])
                    hi = H[i]
                    for j in rng:
                        hi[j] += cw * q[i] * q[j]
            else:
                sg = c if s[w] > 0 else -c
                for i in rng:
                    g[i] += sg * G[w][i]
        try:
            step = _solve_small(H, [-v for v in g])
        except ZeroDivisionError:  # pragma: no cover - H is positive definite
            break
        if max(abs(v) for v in step) <= 1e-12 * (1.0 + max(abs(v) for v in y)):
            return [a + b for a, b in zip(y, step, strict=True)]
        f0 = value(y, nrm)
        slope = sum(a * b for a, b in zip(g, step, strict=True))
        # Fraction to the apex: no slip may shrink below a tenth in one step, so a slip that
        # is small but not zero at the optimum is approached, not jumped over to the kink.
        t = 1.0
        for w in range(len(caps)):
            if k == 2:
                s_w = (s[2 * w], s[2 * w + 1])
                rw = (G[2 * w], G[2 * w + 1])
            else:
                s_w, rw = (s[w],), (G[w],)
            a = [sum(r[j] * step[j] for j in rng) for r in rw]
            aa = sum(v * v for v in a)
            sa = sum(u * v for u, v in zip(s_w, a, strict=True))
            ss = nrm[w] * nrm[w]
            disc = sa * sa - aa * 0.99 * ss
            if aa > 0 and disc >= 0:
                root = (-sa - math.sqrt(disc)) / aa
                if 0 < root < t:
                    t = root
        for _ls in range(40):
            y1 = [a + t * b for a, b in zip(y, step, strict=True)]
            s1, nrm1 = slips(y1)
            if value(y1, nrm1) <= f0 + 1e-4 * t * slope + 1e-15 * abs(f0):
                break
            t *= 0.5
        else:
            break
        y, s, nrm = y1, s1, nrm1
    return y


class _Partition:
    """Matrices of one stick/slip partition, as maps of the requested velocities b."""

    def __init__(self, model: ContactModel, sliding: tuple) -> None:
        k, n, m = model.k, model.n, model.m
        self.sliding = sliding
        self.stuck = np.array([w for w in range(n) if not sliding[w]], dtype=int)
        self.slide = np.array([w for w in range(n) if sliding[w]], dtype=int)
        self.krows = np.array([w * k + i for w in self.stuck for i in range(k)], dtype=int)
        self.srows = np.array([w * k + i for w in self.slide for i in range(k)], dtype=int)
        self.kr, self.ns = len(self.krows), len(self.slide)
        J = model.J
        JK, JS = J[self.krows], J[self.srows]
        eye = np.eye(m)
        PK, PS = eye[self.krows], eye[self.srows]
        if self.kr:
            JKp = np.linalg.pinv(JK, rcond=1e-10)
            _, sv, vt = np.linalg.svd(JK)
            rank = int((sv > 1e-10 * sv.max()).sum())
            N = vt[rank:].T
        else:
            JKp = np.zeros((3, 0))
            N = np.eye(3)
        self.JK, self.JS, self.JKp, self.N, self.Nt = JK, JS, JKp, N, N.T
        self.d = N.shape[1]
        Md = model.mass_diag
        self.NtM = N.T * Md
        self.Mn = (self.NtM @ N).tolist()
        self.x0_map = JKp @ PK  # xi0 = J_K^+ b_K
        self.res_map = JK @ self.x0_map - PK  # J_K xi0 - b_K (zero when consistent)
        self.s0_map = JS @ self.x0_map - PS  # slip of the sliding rows at xi0
        self.G = (JS @ N).tolist()
        self.caps = model.caps[self.slide]
        self.caps_list = self.caps.tolist()

    def toggled(self, wheel: int) -> tuple:
        new = list(self.sliding)
        new[wheel] = not new[wheel]
        return tuple(new)


class _Base:
    """What does not depend on the steering: masses, caps, and C = (J^T J)^-1.

    For a conventional wheel the rolling and lateral rows are orthonormal in (x, y), so their
    contribution to J^T J does not depend on the steering angle; a Swedish wheel is not
    steered. So C is one constant 3x3 matrix per vehicle.
    """

    def __init__(self, spec: VehicleSpec, dt: float) -> None:
        self.spec, self.dt = spec, dt
        J, _, _ = constraint_rows(spec, [0.0] * len(spec.steered_names))
        JtJ = J.T @ J
        self.C = np.linalg.inv(JtJ)
        self.C_list = self.C.tolist()
        self.n = len(spec.wheel_names)
        self.k = len(J) // self.n
        self.mass_diag = np.array([spec.mass, spec.mass, spec.inertia])
        self.caps = spec.mu * spec.normal_loads * dt  # impulse cap per wheel, N s
        self.stick_flags = (False,) * self.n
        self.stick_speeds = (0.0,) * self.n
        where = {name: i for i, name in enumerate(spec.steered_names)}
        self.table = tuple(
            (w.position[0], w.position[1], w.heading, w.wheel_radius, w.kind == "swedish",
             w.roller_angle, where.get(w.name, -1),
             (float(cap) * (1.0 + CAP_TOLERANCE)) ** 2, w.name in spec.free_rolling)
            for w, cap in zip(spec.driven_wheels, self.caps, strict=True))
        self.C_flat = tuple(v for row in self.C_list for v in row)
        # Free-rolling wheels have one row each (lateral), so J^T J depends on their steering:
        # keep the part of the other wheels, and add theirs per steering (_free_gram_inverse).
        self.has_free = any(entry[8] for entry in self.table)
        if self.has_free:
            rest = np.zeros((3, 3))
            for j, entry in enumerate(self.table):
                if not entry[8]:
                    rows = J[j * self.k:(j + 1) * self.k]
                    rest += rows.T @ rows
            self.gram_rest = tuple(rest.reshape(-1).tolist())
            self.free = tuple(entry for entry in self.table if entry[8])
        # An unsteered wheel's stick data does not change: computed once here.
        self.fixed = tuple(None if entry[6] >= 0 else _wheel_data(entry, 0.0, self.C_flat)
                           for entry in self.table)


def _free_gram_inverse(base: _Base, steering: tuple) -> tuple:
    """C = (J^T J)^-1 (flat, 9 floats) of a vehicle with free-rolling wheels at a steering."""
    a, b, c, d, e, f, gg, h, k = base.gram_rest
    for entry in base.free:
        px, py, heading, slot = entry[0], entry[1], entry[2], entry[6]
        ang = heading + (steering[slot] if slot >= 0 else 0.0)
        ch, sh = math.cos(ang), math.sin(ang)
        r0, r1, r2 = point_row(px, py, -sh, ch)
        a += r0 * r0
        b += r0 * r1
        c += r0 * r2
        e += r1 * r1
        f += r1 * r2
        k += r2 * r2
    d, gg, h = b, c, f  # symmetric
    co = (e * k - f * h, -(b * k - c * h), b * f - c * e,
          -(d * k - f * gg), a * k - c * gg, -(a * f - c * d),
          d * h - e * gg, -(a * h - b * gg), a * e - b * d)
    det = a * co[0] + b * co[3] + c * co[6]
    return tuple(v / det for v in co)


def _wheel_data(entry: tuple, steer: float, C: tuple) -> tuple:
    """A driven wheel's column of P = J^+ B and its stick-check data at a steering angle."""
    px, py, heading, radius, is_swedish, gamma, _slot, cap2, is_free = entry
    c0, c1, c2, c3, c4, c5, c6, c7, c8 = C
    h = heading + steer
    ex, ey = math.cos(h), math.sin(h)
    if is_free:  # only the lateral row: no column in P, the impulse along n is checked
        return (0.0, 0.0, 0.0), (px, py, -ey, ex, 0.0, cap2, False)
    if is_swedish:
        dx, dy = roller_axis(h, gamma)
        coef = radius * (dx * ex + dy * ey)
    else:
        dx, dy, coef = ex, ey, radius
    r2 = point_row(px, py, dx, dy)[2]
    col = (coef * (c0 * dx + c1 * dy + c2 * r2), coef * (c3 * dx + c4 * dy + c5 * r2),
           coef * (c6 * dx + c7 * dy + c8 * r2))
    return col, (px, py, dx, dy, coef, cap2, not is_swedish)


def _disc_step(Ainv: list, t0: float, t1: float, cap: float) -> tuple[float, float]:
    """The impulse of a two-row wheel's exact block step when the unconstrained one, ``t``,
    is outside the friction disc: the minimiser of (l - t)^T A (l - t) over |l| <= cap, with
    A = Ainv^-1 the block's effective inverse mass.

    Not the plain projection t cap / |t|, which is the minimiser only when A is a multiple of
    the identity. On the disc's edge the optimum is l(mu) = (A + mu I)^-1 A t with mu > 0 and
    |l(mu)| = cap; Newton's method on 1/|l(mu)| - 1/cap (Moré and Sorensen's secular
    equation, concave and increasing in mu) converges to it from mu = 0.
    """
    det = Ainv[0][0] * Ainv[1][1] - Ainv[0][1] * Ainv[1][0]
    scale = Ainv[0][0] * Ainv[0][0] + Ainv[1][1] * Ainv[1][1] + 2 * Ainv[0][1] * Ainv[0][1]
    if abs(det) <= 1e-12 * scale:  # one row of the pair is empty (a free-rolling wheel):
        norm = math.hypot(t0, t1)   # t has no component along it, and the plain projection
        return t0 * cap / norm, t1 * cap / norm  # of t is the exact step
    a00, a01, a11 = Ainv[1][1] / det, -Ainv[0][1] / det, Ainv[0][0] / det  # A = Ainv^-1
    c0, c1 = a00 * t0 + a01 * t1, a01 * t0 + a11 * t1  # A t
    mu = 0.0
    l0, l1 = t0, t1
    for _ in range(60):
        d = (a00 + mu) * (a11 + mu) - a01 * a01
        l0 = ((a11 + mu) * c0 - a01 * c1) / d
        l1 = (-a01 * c0 + (a00 + mu) * c1) / d
        norm = math.hypot(l0, l1)
        m0 = ((a11 + mu) * l0 - a01 * l1) / d  # (A + mu I)^-1 l
        m1 = (-a01 * l0 + (a00 + mu) * l1) / d
        psi = 1.0 / norm - 1.0 / cap
        step = psi * norm ** 3 / (l0 * m0 + l1 * m1)
        mu -= step
        if abs(psi) <= 1e-15 / cap or mu < 0.0:
            break
    norm = math.hypot(l0, l1)
    return l0 * cap / norm, l1 * cap / norm  # on the edge exactly (to rounding)


class ContactModel:
    """The contact maps of one vehicle in one steering configuration.

    Parameters
    ----------
    spec : VehicleSpec
    steering : tuple of float
        Steering angles (``spec.steered_names`` order), rad.
    dt : float
        Step, s (the caps are impulses, mu N dt).
    base : optional
        The steering-independent part, shared between a robot's configurations.

    The stick path runs in plain floats: with P = J^+ B (3 x n) and C = (J^T J)^-1,
    xi' = P phi, h = C M (xi' - xi_p), and a wheel's impulse is j_w = J_w h, whose length
    for a conventional wheel is norm((h_x - p_y h_w, h_y + p_x h_w)) whatever its steering. The
    numpy matrices of the slip path are built on first use.
    """

    def __init__(self, spec: VehicleSpec, steering: tuple, dt: float, base: _Base | None = None
                 ) -> None:
        if base is None:
            base = _Base(spec, dt)
        self.base, self.spec, self.dt = base, spec, dt
        self.steering = tuple(steering)
        self.n, self.k = base.n, base.k
        self.m = self.n * self.k
        self.mass_diag, self.caps = base.mass_diag, base.caps
        self.stick_flags, self.stick_speeds = base.stick_flags, base.stick_speeds
        steer, C = self.steering, base.C_flat
        if base.has_free:
            C = _free_gram_inverse(base, steer)
            data = [_wheel_data(entry, steer[entry[6]] if entry[6] >= 0 else 0.0, C)
                    for entry in base.table]
        else:
            data = [fixed if fixed is not None else _wheel_data(entry, steer[entry[6]], C)
                    for entry, fixed in zip(base.table, base.fixed, strict=True)]
        self._cols = tuple(d[0] for d in data)
        self._fast = tuple(d[1] for d in data)
        self._C = C
        self._M = (spec.mass, spec.mass, spec.inertia)
        self._steered = tuple((j, entry) for j, entry in enumerate(base.table) if entry[6] >= 0)
        self._np_ready = False
        self._block_data = None
        self._partitions: dict = {}

    def retarget(self, steering: tuple) -> None:
        """Change the steering in place: only the steered wheels' data are recomputed, and the
        slip path's matrices are dropped (they are rebuilt when next needed)."""
        self.steering = steering
        cols, fast, C = list(self._cols), list(self._fast), self._C
        if self.base.has_free:  # C depends on the free wheels' steering: every column changes
            C = self._C = _free_gram_inverse(self.base, steering)
            for j, entry in enumerate(self.base.table):
                cols[j], fast[j] = _wheel_data(
                    entry, steering[entry[6]] if entry[6] >= 0 else 0.0, C)
        else:
            for j, entry in self._steered:
                cols[j], fast[j] = _wheel_data(entry, steering[entry[6]], C)
        self._cols, self._fast = tuple(cols), tuple(fast)
        self._np_ready = False
        self._block_data = None
        self._partitions = {}

    def _numpy(self) -> None:
        """Build the matrices of the slip path."""
        if self._np_ready:
            return
        J, B, owner = constraint_rows(self.spec, self.steering)
        self._J, self._B, self._owner = J, B, owner
        self._WJt = (J / self.mass_diag).T  # M^-1 J^T, (3, m)
        self._np_ready = True

    @property
    def J(self) -> np.ndarray:
        """Constraint Jacobian (m, 3), rows grouped by wheel (see :func:`constraint_rows`)."""
        self._numpy()
        return self._J

    @property
    def B(self) -> np.ndarray:
        """Requested contact velocities per wheel rate, b = B @ phi, (m, n)."""
        self._numpy()
        return self._B

    @property
    def WJt(self) -> np.ndarray:
        """M^-1 J^T, (3, m)."""
        self._numpy()
        return self._WJt

    # ---------------------------------------------------------------- fast path
    def solve(self, rates: Sequence[float], xi_pred: Sequence[float], warm: _Warm
              ) -> ContactResult:
        """Impulses for one step: the twist after them and the slip flags.

        ``rates`` are the wheel rates over the step (rad/s, a list), ``xi_pred`` the
        free-flight twist.
        """
        u = v = w = 0.0
        for (a, b, c), phi in zip(self._cols, rates, strict=True):
            u += a * phi
            v += b * phi
            w += c * phi
        mx, my, mw = self._M
        gx, gy, gw = mx * (u - xi_pred[0]), my * (v - xi_pred[1]), mw * (w - xi_pred[2])
        c0, c1, c2, c3, c4, c5, c6, c7, c8 = self._C
        hx = c0 * gx + c1 * gy + c2 * gw
        hy = c3 * gx + c4 * gy + c5 * gw
        hw = c6 * gx + c7 * gy + c8 * gw
        ok = True
        for px, py, dx, dy, _coef, cap2, conventional in self._fast:
            lx, ly = hx - py * hw, hy + px * hw
            if conventional:
                q = lx * lx + ly * ly
            else:
                q = dx * lx + dy * ly
                q *= q
            if q > cap2:
                ok = False
                break
        if warm.consistent_key is not self or warm.consistent_rates != rates:
            warm.consistent_key, warm.consistent_rates = self, list(rates)
            consistent = True
            for (px, py, dx, dy, coef, _cap2, conventional), phi in zip(self._fast, rates,
                                                                        strict=True):
                cx, cy = u - py * w, v + px * w
                if abs(dx * cx + dy * cy - coef * phi) > SLIP_TOLERANCE or (
                        conventional and abs(dx * cy - dy * cx) > SLIP_TOLERANCE):
                    consistent = False
                    break
            warm.consistent = consistent
        if ok and warm.consistent:
            warm.partition = None
            return ContactResult([u, v, w], self.stick_flags, self.stick_speeds, "stick")
        self._numpy()
        lam_rows = (self.J @ np.array((hx, hy, hw))).reshape(self.n, self.k)
        return self._solve_slip(np.asarray(rates, float), np.asarray(xi_pred, float), lam_rows,
                                warm)

    # ---------------------------------------------------------------- slip path
    def _solve_slip(self, rates, xp, lam_rows, warm: _Warm) -> ContactResult:
        b = self.B @ rates
        n = self.n

        def follow(guess, start):
            """Active set: solve a partition, correct it, until Coulomb's law holds."""
            memo: dict = {}
            seen = set()
            for _ in range(2 * n + 4):
                if guess in seen:
                    return None
                seen.add(guess)
                res = memo.get(guess)
                if res is None:
                    res = self._partition_solve(guess, b, xp, start)
                    memo[guess] = res
                if res[0] == "ok":
                    return guess, res
                guess = res[1]
            return None

        norms = np.sqrt((lam_rows ** 2).sum(1))
        guesses = []
        if warm.partition is not None:
            guesses.append((warm.partition, warm.xi))
        over = tuple(bool(x) for x in norms > self.caps * (1 + CAP_TOLERANCE))
        guesses.append((over, xp))  # (the stick twist would sit on every wheel's kink)
        for guess, start in guesses:
            found = follow(guess, start)
            if found is not None:
                return self._accept(found, warm, "active-set")
        # Projected Gauss-Seidel from the last impulses, then the active set from its answer.
        if warm.partition is not None and warm.lam is not None:
            lam = warm.lam
        else:  # the stick impulses, clamped into their discs
            scale = np.minimum(1.0, self.caps / np.maximum(norms, 1e-300))
            lam = (lam_rows * scale[:, None]).reshape(-1)
        for sweeps in (60, 400, 2000):
            xi, lam = self._pgs(b, xp, lam, sweeps)
            at_cap = np.sqrt((lam.reshape(n, self.k) ** 2).sum(1)) >= self.caps * (1 - 1e-7)
            found = follow(tuple(bool(x) for x in at_cap), xi)
            if found is not None:
                return self._accept(found, warm, "active-set")
        # Fallback: the projected Gauss-Seidel answer.
        s = (self.J @ xi - b).reshape(n, self.k)
        speeds = np.sqrt((s * s).sum(1)) * at_cap
        slipping = tuple(bool(x) for x in at_cap)
        warm.partition, warm.xi, warm.lam = slipping, xi, lam
        return ContactResult(xi.tolist(), slipping, tuple(speeds.tolist()), "pgs")

    def _accept(self, found, warm: _Warm, method: str) -> ContactResult:
        guess, (_, xi, lam, speeds) = found
        warm.partition, warm.xi, warm.lam = guess, xi, lam
        return ContactResult(xi.tolist(), guess, tuple(speeds.tolist()), method)

    def _partition(self, sliding: tuple) -> _Partition:
        """Cached matrices of one stick/slip partition."""
        data = self._partitions.get(sliding)
        if data is None:
            if len(self._partitions) > 256:
                self._partitions.clear()
            data = _Partition(self, sliding)
            self._partitions[sliding] = data
        return data

    def _partition_solve(self, sliding: tuple, b, xp, start):
        """Minimise F with the wheels ``sliding`` slipping and the others stuck.

        Returns ("ok", xi, j, slip speeds) if Coulomb's law holds, else ("retry", a
        corrected partition): a stuck wheel that cannot roll or whose impulse is over its cap
        is freed, a slipping wheel whose slip vanishes is stuck.
        """
        P = self._partition(sliding)
        k, M = self.k, self.mass_diag
        if P.kr:
            res = P.res_map @ b
            if np.abs(res).max() > SLIP_TOLERANCE:
                per = np.sqrt((res.reshape(-1, k) ** 2).sum(1))
                return ("retry", P.toggled(int(P.stuck[int(per.argmax())])))
            xi0 = P.x0_map @ b
        else:
            xi0 = np.zeros(3)
        if P.d:
            s0 = (P.s0_map @ b).tolist() if P.ns else []
            hq = (P.NtM @ (xi0 - xp)).tolist()
            y0 = (P.Nt @ (np.asarray(start, float) - xi0)).tolist()
            y_alt = (P.Nt @ (xp - xi0)).tolist()
            y = _newton(P.Mn, hq, P.G, s0, P.caps_list, k, y0, y_alt)
            xi = xi0 + P.N @ np.array(y)
        else:
            xi = xi0
        lam = np.zeros(self.m)
        rhs = M * (xi - xp)
        speeds = np.zeros(self.n)
        if P.ns:
            s = (P.JS @ xi - b[P.srows]).reshape(P.ns, k)
            nrm = np.sqrt((s * s).sum(1))
            vanishing = P.toggled(int(P.slide[int(nrm.argmin())]))
            if nrm.min() <= 1e-15:
                return ("retry", vanishing)
            friction = -(s * (P.caps / nrm)[:, None]).reshape(-1)  # opposes the slip
            lam[P.srows] = friction
            rhs = rhs - P.JS.T @ friction
            speeds[P.slide] = nrm
        if P.kr:
            lamK = P.JKp.T @ rhs
            per = np.sqrt((lamK.reshape(-1, k) ** 2).sum(1)) / self.caps[P.stuck]
            if per.max() > 1 + CAP_TOLERANCE:
                return ("retry", P.toggled(int(P.stuck[int(per.argmax())])))
            lam[P.krows] = lamK
            miss = P.JK.T @ lamK - rhs
        else:
            miss = rhs
        # The impulses must account for the whole momentum change (Newton converged). If not,
        # Newton stalled at a kink: the wheel whose slip vanishes should stick.
        if np.abs(miss).max() > 1e-9 * (1.0 + np.abs(M * (xi - xp)).max()):
            if P.ns and nrm.min() <= SLIP_TOLERANCE:
                return ("retry", vanishing)
            return ("retry", sliding)
        return ("ok", xi, lam, speeds)

    @property
    def _blocks(self) -> list:
        """Per-wheel data for projected Gauss-Seidel, in plain floats (built on first use)."""
        if self._block_data is None:
            J, WJt, blocks = self.J, self.WJt, []
            for w in range(self.n):
                rows = list(range(w * self.k, (w + 1) * self.k))
                Aw = J[rows] @ WJt[:, rows]
                blocks.append((rows, [tuple(J[i]) for i in rows],
                               [tuple(WJt[:, i]) for i in rows],
                               (np.linalg.pinv(Aw) if self.base.table[w][8]  # free: rank 1
                                else np.linalg.inv(Aw)).tolist(), float(self.caps[w])))
            self._block_data = blocks
        return self._block_data

    def _pgs(self, b, xp, lam0, sweeps: int):
        """Projected Gauss-Seidel over the wheels' impulse blocks (plain floats)."""
        lam = [float(x) for x in lam0]
        xi = list((xp + self.WJt @ np.asarray(lam0, float)).tolist())
        bl = b.tolist()
        for _sweep in range(sweeps):
            change = 0.0
            for rows, Jr, WJr, Ainv, cap in self._blocks:
                if len(rows) == 2:
                    i0, i1 = rows
                    j0, j1 = Jr
                    s0 = j0[0] * xi[0] + j0[1] * xi[1] + j0[2] * xi[2] - bl[i0]
                    s1 = j1[0] * xi[0] + j1[1] * xi[1] + j1[2] * xi[2] - bl[i1]
                    l0 = lam[i0] - (Ainv[0][0] * s0 + Ainv[0][1] * s1)
                    l1 = lam[i1] - (Ainv[1][0] * s0 + Ainv[1][1] * s1)
                    if math.hypot(l0, l1) > cap:
                        l0, l1 = _disc_step(Ainv, l0, l1, cap)
                    d0, d1 = l0 - lam[i0], l1 - lam[i1]
                    lam[i0], lam[i1] = l0, l1
                    w0, w1 = WJr
                    xi[0] += w0[0] * d0 + w1[0] * d1
                    xi[1] += w0[1] * d0 + w1[1] * d1
                    xi[2] += w0[2] * d0 + w1[2] * d1
                    change = max(change, abs(d0), abs(d1))
                else:
                    (i0,) = rows
                    (j0,) = Jr
                    s0 = j0[0] * xi[0] + j0[1] * xi[1] + j0[2] * xi[2] - bl[i0]
                    l0 = min(cap, max(-cap, lam[i0] - Ainv[0][0] * s0))
                    d0 = l0 - lam[i0]
                    lam[i0] = l0
                    (w0,) = WJr
                    xi[0] += w0[0] * d0
                    xi[1] += w0[1] * d0
                    xi[2] += w0[2] * d0
                    change = max(change, abs(d0))
            if change <= 1e-15 * (1.0 + max(self.caps)):
                break
        return np.array(xi), np.array(lam)
