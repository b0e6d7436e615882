r"""Nonholonomic constraints and controllability: Pfaffian constraints, drift-free vector
fields, Lie brackets and the four-move manoeuvre that parallel-parks a car.

A wheel that rolls without sliding sideways constrains the *velocity* of the vehicle, not its
position. Written for the configuration :math:`q` (the pose :math:`(x, y, \theta)` in the world
frame, extended where said by the steering angle :math:`\delta` or the wheel angles
:math:`\varphi_L, \varphi_R`), every such constraint is linear in :math:`\dot q`: the
*Pfaffian form*

.. math:: A(q)\,\dot q = 0,

one row of :math:`A(q)` per constraint. The velocities it allows are combinations of a few
*vector fields* :math:`\mathbf f_i(q)` (the columns of a basis of the null space of
:math:`A(q)`), driven by the inputs :math:`u_i` (speeds and rates); with no input the vehicle
does not move (a *drift-free* system):

.. math:: \dot q = \mathbf f_1(q)\,u_1 + \dots + \mathbf f_m(q)\,u_m .

The *Lie bracket* of two fields is the field

.. math:: [\mathbf f_1, \mathbf f_2](q) = D\mathbf f_2(q)\,\mathbf f_1(q)
          - D\mathbf f_1(q)\,\mathbf f_2(q)

(:math:`D` the Jacobian; the convention of :cite:`lynch2017` and :cite:`murray1994`). Follow
:math:`\mathbf f_1` for a time :math:`\varepsilon`, then :math:`\mathbf f_2`, then
:math:`-\mathbf f_1`, then :math:`-\mathbf f_2`: the vehicle ends at
:math:`q + \varepsilon^2[\mathbf f_1, \mathbf f_2](q) + O(\varepsilon^3)`, a direction that
none of the fields gives directly. Chow's theorem: when the fields and their iterated
brackets span every direction of :math:`q` (:func:`bracket_ranks`), every configuration near
:math:`q` can be reached.

Symbols and sign conventions are the book's (``book/notation.md``): SI units, REP 103
(:math:`x` forward, :math:`y` left, counter-clockwise positive), :math:`\delta > 0` turns left,
:math:`\kappa_{max} = \tan\delta_{max}/L` the largest curvature of a car. A constraint row is
written so that :math:`A(q)\,\dot q` is the sideways velocity of a wheel's contact point (m/s),
or a rim speed minus a ground speed: the no-side-slip rows are :math:`C_1 R(\theta)^T`, the
body-frame rows of :func:`wheelkin.unified.sliding_matrix` turned into the world frame.

Examples
--------
The differential drive cannot move sideways, yet the bracket of its two fields is the
sideways direction (here, to its right):

>>> lie_bracket(unicycle_drive, unicycle_turn, [0.0, 0.0, 0.0]).round(9) + 0.0
array([ 0., -1.,  0.])
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin import frames, unified
from wheelkin._records import Stack

__all__ = [
    "bracket_manoeuvre",
    "bracket_prediction",
    "bracket_ranks",
    "car_constraints",
    "car_fields",
    "car_lock_fields",
    "diff_drive_constraints",
    "flow",
    "lie_bracket",
    "parallel_parking",
    "parking_shift",
    "pfaffian_matrix",
    "unicycle_constraint",
    "unicycle_drive",
    "unicycle_fields",
    "unicycle_turn",
    "wheel_angle_fields",
]

#: A vector field: a configuration (shape (n,)) to a velocity of the configuration (n,).
VectorField = Callable[[NDArray[np.float64]], ArrayLike]

#: Relative size of the finite-difference step of :func:`lie_bracket` (a fourth-order
#: central difference: truncation and rounding errors both near 1e-12 at this step).
BRACKET_STEP = 2e-4
#: The most RK4 steps one flow may take.
MAX_STEPS = 1_000_000
#: The deepest bracket :func:`bracket_ranks` builds (the book's vehicles need at most 3).
MAX_DEPTH = 5
_HALF_PI = 0.5 * math.pi


# --------------------------------------------------------------------------------------------
# Validation helpers
# --------------------------------------------------------------------------------------------

def _vector(name: str, value: ArrayLike, size: int | None = None) -> NDArray[np.float64]:
    """One configuration: a finite float array of shape (n,), n >= 1 (or exactly ``size``)."""
    arr = V.finite_array(name, value)
    if arr.ndim != 1 or arr.size == 0 or (size is not None and arr.size != size):
        want = f"({size},)" if size is not None else "(n,) with n >= 1"
        raise ValueError(f"{name} must be one configuration of shape {want}, got shape "
                         f"{arr.shape}")
    return arr


def _stack(name: str, value: ArrayLike, size: int) -> NDArray[np.float64]:
    """Configurations of shape (..., size): one or a stack."""
    return V.shaped(name, value, (size,))


def _field(name: str, value: object) -> VectorField:
    if not callable(value):
        raise TypeError(f"{name} must be a callable vector field (configuration -> velocity), "
                        f"got {type(value).__name__}")
    return value


def _evaluate(name: str, field: VectorField, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """``field(q)`` as a finite float array of q's shape; ``ValueError`` naming ``name``."""
    try:
        with np.errstate(all="ignore"):  # a NaN or an overflow is reported below, by name
            out = np.asarray(field(q.copy()), dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} could not be evaluated at the configuration "
                         f"{q.tolist()}: {exc}") from None
    if out.shape != q.shape:
        raise ValueError(f"{name} must return a velocity of shape {q.shape} (the "
                         f"configuration's), got shape {out.shape}")
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{name} is not finite at (or next to) the configuration "
                         f"{q.tolist()}: got {out.tolist()}")
    return out


def _steering(name: str, value: ArrayLike) -> NDArray[np.float64]:
    arr = V.finite_array(name, value)
    if np.any(np.abs(arr) >= _HALF_PI):
        raise ValueError(f"{name} must be in (-pi/2, pi/2) rad, got {value!r}")
    return arr


# --------------------------------------------------------------------------------------------
# Pfaffian constraints A(q) q_dot = 0
# --------------------------------------------------------------------------------------------

def pfaffian_matrix(pose: ArrayLike, wheels: Sequence[unified.WheelConstraint]
                    ) -> NDArray[np.float64]:
    r"""The no-side-slip constraints of a vehicle's wheels in Pfaffian form,
    :math:`A(q)\,\dot q = 0` with :math:`q = (x, y, \theta)`.

    Each fixed or steered wheel at :math:`\mathbf p_i = (x_i, y_i)` rolling along
    :math:`\psi_i` gives one row, its body-frame row :math:`C_{1,i}`
    (:func:`wheelkin.unified.sliding_row`) turned into the world frame:

    .. math::
        A(q) = C_1\,R(\theta)^T,\qquad
        A_i(q) = \bigl(-\sin(\theta + \psi_i),\ \cos(\theta + \psi_i),\
                       x_i\cos\psi_i + y_i\sin\psi_i\bigr)

    with :math:`R(\theta)^T` the world-to-body rotation of the velocity
    (:math:`(\dot x, \dot y)` to :math:`(v_x, v_y)`, :math:`\dot\theta = \omega`).
    :math:`A_i(q)\,\dot q` is the sideways velocity of wheel *i*'s contact point (m/s).
    Swedish wheels and casters give no row (their rollers or swivel absorb it).

    Parameters
    ----------
    pose : array_like, shape (3,)
        :math:`(x, y, \theta)`, m, m, rad (only :math:`\theta` enters).
    wheels : sequence of WheelConstraint
        The vehicle's wheels at their present steering.

    Returns
    -------
    numpy.ndarray, shape (m, 3)
        One row per fixed or steered wheel, in the given order (m may be 0).

    Examples
    --------
    >>> wheels = unified.diff_drive_wheels(0.3, 0.05, caster=False)
    >>> pfaffian_matrix([0.0, 0.0, math.pi / 2], wheels).round(12) + 0.0  # rows L, R
    array([[-1.,  0.,  0.],
           [-1.,  0.,  0.]])
    """
    p = _vector("pose", pose, 3)
    body_rows = unified.sliding_matrix(wheels)
    c, s = math.cos(p[2]), math.sin(p[2])
    world_to_body = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return body_rows @ world_to_body + 0.0


def unicycle_constraint(pose: ArrayLike) -> NDArray[np.float64]:
    r"""The differential drive's (the unicycle's) no-side-slip constraint, :math:`q = (x, y,
    \theta)` with the reference point on the axle:

    .. math:: A(q) = (-\sin\theta,\ \cos\theta,\ 0),\qquad
              A(q)\,\dot q = -\dot x\sin\theta + \dot y\cos\theta = v_y = 0 .

    Parameters
    ----------
    pose : array_like, shape (..., 3)
        :math:`(x, y, \theta)`, m, m, rad; a stack gives a stack.

    Returns
    -------
    numpy.ndarray, shape (..., 1, 3)

    Examples
    --------
    >>> unicycle_constraint([0.0, 0.0, 0.0])
    array([[0., 1., 0.]])
    """
    p = _stack("pose", pose, 3)
    th = p[..., 2]
    row = np.stack([-np.sin(th), np.cos(th), np.zeros_like(th)], axis=-1)
    return row[..., None, :] + 0.0


def diff_drive_constraints(configuration: ArrayLike, track_width: float,
                           wheel_radius: float) -> NDArray[np.float64]:
    r"""The differential drive's three constraints with its wheel angles in the configuration,
    :math:`q = (x, y, \theta, \varphi_L, \varphi_R)`: no side slip, then the left and the
    right wheel rolling.

    .. math::
        A(q) = \begin{bmatrix}
            -\sin\theta & \cos\theta & 0 & 0 & 0 \\
            \cos\theta & \sin\theta & -W/2 & -r & 0 \\
            \cos\theta & \sin\theta & W/2 & 0 & -r
        \end{bmatrix}

    (wheels at :math:`(0, \pm W/2)` of the axle midpoint; a rolling row is the contact point's
    forward speed minus the rim speed :math:`r\dot\varphi`). The difference of the two rolling
    rows, :math:`W\dot\theta = r(\dot\varphi_R - \dot\varphi_L)`, integrates to
    :math:`W\theta - r(\varphi_R - \varphi_L) = \text{const}`: holonomic. The no-side-slip
    row does not integrate.

    Parameters
    ----------
    configuration : array_like, shape (5,)
        :math:`(x, y, \theta, \varphi_L, \varphi_R)`, m, m, rad, rad, rad.
    track_width, wheel_radius : float
        :math:`W`, :math:`r`, m (> 0).

    Returns
    -------
    numpy.ndarray, shape (3, 5)

    Examples
    --------
    >>> diff_drive_constraints([0, 0, 0, 0, 0], 0.3, 0.05)
    array([[ 0.  ,  1.  ,  0.  ,  0.  ,  0.  ],
           [ 1.  ,  0.  , -0.15, -0.05,  0.  ],
           [ 1.  ,  0.  ,  0.15,  0.  , -0.05]])
    """
    q = _vector("configuration", configuration, 5)
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    c, s = math.cos(q[2]), math.sin(q[2])
    return np.array([[-s, c, 0.0, 0.0, 0.0],
                     [c, s, -W / 2, -r, 0.0],
                     [c, s, W / 2, 0.0, -r]]) + 0.0


def car_constraints(configuration: ArrayLike, wheelbase: float) -> NDArray[np.float64]:
    r"""The car's (the kinematic bicycle's) two no-side-slip constraints,
    :math:`q = (x, y, \theta, \delta)` with the reference point at the rear-axle midpoint:
    the rear wheel, then the front wheel at :math:`(L, 0)` steered by :math:`\delta`.

    .. math::
        A(q) = \begin{bmatrix}
            -\sin\theta & \cos\theta & 0 & 0 \\
            -\sin(\theta + \delta) & \cos(\theta + \delta) & L\cos\delta & 0
        \end{bmatrix}

    Parameters
    ----------
    configuration : array_like, shape (4,)
        :math:`(x, y, \theta, \delta)`, m, m, rad, rad; :math:`|\delta| < \pi/2`.
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    numpy.ndarray, shape (2, 4)

    Examples
    --------
    >>> car_constraints([0.0, 0.0, 0.0, 0.0], 2.5)
    array([[0. , 1. , 0. , 0. ],
           [0. , 1. , 2.5, 0. ]])
    """
    q = _vector("configuration", configuration, 4)
    L = V.positive("wheelbase", wheelbase)
    _steering("configuration[3] (the steering angle delta)", q[3])
    th, d = q[2], q[3]
    return np.array([[-math.sin(th), math.cos(th), 0.0, 0.0],
                     [-math.sin(th + d), math.cos(th + d), L * math.cos(d), 0.0]]) + 0.0


# --------------------------------------------------------------------------------------------
# Drift-free vector fields q_dot = G(q) u
# --------------------------------------------------------------------------------------------

def unicycle_fields(pose: ArrayLike) -> NDArray[np.float64]:
    r"""The unicycle's (a differential drive's) two vector fields, as the columns of
    :math:`G(q)` in :math:`\dot q = G(q)\,(v, \omega)`:

    .. math:: \mathbf f_1(q) = (\cos\theta,\ \sin\theta,\ 0)\ \text{(drive)},\qquad
              \mathbf f_2(q) = (0,\ 0,\ 1)\ \text{(turn on the spot)}.

    Both satisfy :func:`unicycle_constraint`: :math:`A(q)\,G(q) = 0`.

    Parameters
    ----------
    pose : array_like, shape (..., 3)
        :math:`(x, y, \theta)`, m, m, rad.

    Returns
    -------
    numpy.ndarray, shape (..., 3, 2)
        Columns: drive (per m/s of :math:`v`), turn (per rad/s of :math:`\omega`).

    Examples
    --------
    >>> unicycle_fields([1.0, 2.0, math.pi / 2]).round(12) + 0.0
    array([[0., 0.],
           [1., 0.],
           [0., 1.]])
    """
    p = _stack("pose", pose, 3)
    th = p[..., 2]
    zero, one = np.zeros_like(th), np.ones_like(th)
    drive = np.stack([np.cos(th), np.sin(th), zero], axis=-1)
    turn = np.stack([zero, zero, one], axis=-1)
    return np.stack([drive, turn], axis=-1) + 0.0


def unicycle_drive(pose: ArrayLike) -> NDArray[np.float64]:
    r"""The unicycle's drive field :math:`\mathbf f_1(q) = (\cos\theta, \sin\theta, 0)`: the
    first column of :func:`unicycle_fields` (a vector field for :func:`lie_bracket`).

    Examples
    --------
    >>> unicycle_drive([0.0, 0.0, 0.0])
    array([1., 0., 0.])
    """
    return unicycle_fields(pose)[..., 0]


def unicycle_turn(pose: ArrayLike) -> NDArray[np.float64]:
    r"""The unicycle's turn field :math:`\mathbf f_2(q) = (0, 0, 1)`: the second column of
    :func:`unicycle_fields`.

    Examples
    --------
    >>> unicycle_turn([0.0, 0.0, 0.0])
    array([0., 0., 1.])
    """
    return unicycle_fields(pose)[..., 1]


def car_fields(configuration: ArrayLike, wheelbase: float) -> NDArray[np.float64]:
    r"""The car's two vector fields with its steering in the configuration,
    :math:`q = (x, y, \theta, \delta)`, :math:`\dot q = G(q)\,(v, \dot\delta)`:

    .. math:: \mathbf f_1(q) = \bigl(\cos\theta,\ \sin\theta,\ \tfrac{\tan\delta}{L},\
              0\bigr)\ \text{(drive)},\qquad
              \mathbf f_2(q) = (0,\ 0,\ 0,\ 1)\ \text{(steer)}.

    Both satisfy :func:`car_constraints`. Their bracket :math:`[\mathbf f_1, \mathbf f_2] =
    (0, 0, -1/(L\cos^2\delta), 0)` turns the car on the spot about its rear-axle midpoint
    (Nelson's *wriggle* is the same bracket the other way round, :math:`[\mathbf f_2,
    \mathbf f_1]`); the next, :math:`[\mathbf f_1, [\mathbf f_1, \mathbf f_2]]`, moves it
    sideways (Nelson's *slide*).

    Parameters
    ----------
    configuration : array_like, shape (..., 4)
        :math:`(x, y, \theta, \delta)`, m, m, rad, rad; :math:`|\delta| < \pi/2`.
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 4, 2)
        Columns: drive (per m/s of the rear-axle speed :math:`v`), steer (per rad/s of
        :math:`\dot\delta`).

    Examples
    --------
    >>> car_fields([0.0, 0.0, 0.0, math.pi / 4], 2.0).round(12) + 0.0
    array([[1. , 0. ],
           [0. , 0. ],
           [0.5, 0. ],
           [0. , 1. ]])
    """
    q = _stack("configuration", configuration, 4)
    L = V.positive("wheelbase", wheelbase)
    _steering("configuration[..., 3] (the steering angle delta)", q[..., 3])
    th, d = q[..., 2], q[..., 3]
    zero, one = np.zeros_like(th), np.ones_like(th)
    drive = np.stack([np.cos(th), np.sin(th), np.tan(d) / L, zero], axis=-1)
    steer = np.stack([zero, zero, zero, one], axis=-1)
    return np.stack([drive, steer], axis=-1) + 0.0


def car_lock_fields(pose: ArrayLike, max_curvature: float) -> NDArray[np.float64]:
    r"""The car's two vector fields at full lock (the steering at its limit, left or right),
    :math:`q = (x, y, \theta)`, per metre driven by the rear-axle midpoint:

    .. math:: \mathbf f_L(q) = (\cos\theta,\ \sin\theta,\ \kappa_{max}),\qquad
              \mathbf f_R(q) = (\cos\theta,\ \sin\theta,\ -\kappa_{max})

    with :math:`\kappa_{max} = \tan\delta_{max}/L`. Driven forwards or backwards (a negative
    input), they are the car's tightest turns; every turn in between is a mix of the two.
    Their bracket :math:`[\mathbf f_L, \mathbf f_R] = 2\kappa_{max}(-\sin\theta, \cos\theta,
    0)` points to the car's left: the direction of :func:`parallel_parking`.

    Parameters
    ----------
    pose : array_like, shape (..., 3)
        :math:`(x, y, \theta)`, m, m, rad.
    max_curvature : float
        :math:`\kappa_{max}`, 1/m (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 3, 2)
        Columns: left lock, right lock (per metre of rear-axle travel).

    Examples
    --------
    >>> car_lock_fields([0.0, 0.0, 0.0], 1.5)
    array([[ 1. ,  1. ],
           [ 0. ,  0. ],
           [ 1.5, -1.5]])
    """
    p = _stack("pose", pose, 3)
    kappa = V.positive("max_curvature", max_curvature)
    th = p[..., 2]
    c, s, k = np.cos(th), np.sin(th), np.full_like(th, kappa)
    left = np.stack([c, s, k], axis=-1)
    right = np.stack([c, s, -k], axis=-1)
    return np.stack([left, right], axis=-1) + 0.0


def wheel_angle_fields(configuration: ArrayLike, wheels: Sequence[unified.WheelConstraint]
                       ) -> NDArray[np.float64]:
    r"""A vehicle's vector fields with its wheel angles in the configuration,
    :math:`q = (x, y, \theta, \varphi_1, \varphi_2, \dots)`, one wheel angle per wheel.

    Each column belongs to one twist :math:`\xi_j` of the orthonormal basis of the twists the
    wheels allow without sliding sideways (:func:`wheelkin.unified.admissible_twists`, at the
    wheels' present steering, held): the pose moves with :math:`\xi_j` turned into the world
    frame and each wheel turns at the rate its rolling constraint sets,

    .. math::
        \mathbf f_j(q) = \bigl(R(\theta)\,\xi_j,\ \ J_1\,\xi_j / r\bigr),\qquad
        \dot\varphi_i = \frac{J_{1,i}\,\xi_j}{r_i}

    (the rates of :func:`wheelkin.unified.wheel_rates`). Every field satisfies all the
    wheels' constraints, rolling and no side slip (a Swedish wheel rolls on its rollers).
    With the wheel angles in :math:`q` the rolling constraints join :math:`A(q)`, and
    Frobenius's theorem counts how many combinations of them integrate: the dimension of
    :math:`q` less the rank of the fields and their brackets (:func:`bracket_ranks`). For
    the differential drive that is one, :math:`W\theta - r(\varphi_R - \varphi_L)`
    (:func:`diff_drive_constraints`).

    Parameters
    ----------
    configuration : array_like, shape (3 + number of wheels,)
        :math:`(x, y, \theta, \varphi_1, \varphi_2, \dots)`, m, m, rad, rad, ...; the wheel
        angles in the order of ``wheels`` (only :math:`\theta` enters).
    wheels : sequence of WheelConstraint
        The vehicle's wheels, fixed, steered (at their present steering) or Swedish; no
        caster (its swivel angle would be one more coordinate).

    Returns
    -------
    numpy.ndarray, shape (3 + number of wheels, m)
        One column per admissible twist, per unit of it (m/s or rad/s); m is the degree of
        mobility :math:`\delta_m`.

    Examples
    --------
    A differential drive (track 0.3 m, wheels of radius 0.05 m), q = (x, y, θ, φ_L, φ_R):
    driving turns both wheels alike, turning on the spot turns them against each other:

    >>> wheels = unified.diff_drive_wheels(0.3, 0.05, caster=False)
    >>> wheel_angle_fields([0.0, 0.0, 0.0, 0.0, 0.0], wheels).round(12) + 0.0
    array([[ 1.,  0.],
           [ 0.,  0.],
           [ 0.,  1.],
           [20., -3.],
           [20.,  3.]])
    """
    basis = unified.admissible_twists(wheels)  # (3, m); validates the wheels
    casters = [w.name for w in wheels if w.kind == "caster"]
    if casters:
        raise ValueError(f"wheels must not include a caster (its swivel angle would be one "
                         f"more coordinate of q): got the caster(s) {casters}")
    q = _vector("configuration", configuration, 3 + len(wheels))
    c, s = math.cos(q[2]), math.sin(q[2])
    body_to_world = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    rates = unified.wheel_rates(wheels, basis.T)  # (m, k)
    return np.vstack([body_to_world @ basis, rates.T]) + 0.0


# --------------------------------------------------------------------------------------------
# Lie brackets and flows
# --------------------------------------------------------------------------------------------

def _directional(field: VectorField, name: str, q: NDArray[np.float64],
                 direction: NDArray[np.float64], step: float) -> NDArray[np.float64]:
    r""":math:`D\mathbf f(q)\,\mathbf d`: a fourth-order central difference along ``direction``."""
    size = float(np.max(np.abs(direction)))
    if size == 0.0:
        return np.zeros_like(q)
    t = step * max(1.0, float(np.max(np.abs(q)))) / size
    values = [_evaluate(name, field, q + k * t * direction) for k in (-2, -1, 1, 2)]
    return (values[0] - 8.0 * values[1] + 8.0 * values[2] - values[3]) / (12.0 * t)


def _bracket(f1: VectorField, f2: VectorField, q: NDArray[np.float64], step: float,
             names: tuple[str, str] = ("f1", "f2")) -> NDArray[np.float64]:
    a = _evaluate(names[0], f1, q)
    b = _evaluate(names[1], f2, q)
    return _directional(f2, names[1], q, a, step) - _directional(f1, names[0], q, b, step)


def lie_bracket(f1: VectorField, f2: VectorField, configuration: ArrayLike, *,
                step: float = BRACKET_STEP) -> NDArray[np.float64]:
    r"""The Lie bracket of two vector fields at a configuration, numerically:

    .. math:: [\mathbf f_1, \mathbf f_2](q) = D\mathbf f_2(q)\,\mathbf f_1(q)
              - D\mathbf f_1(q)\,\mathbf f_2(q).

    Each directional derivative :math:`D\mathbf f(q)\,\mathbf d` is a fourth-order central
    difference along :math:`\mathbf d` (four evaluations of :math:`\mathbf f`), with a
    displacement of ``step`` times :math:`\max(1, \|q\|_\infty)` in the largest coordinate:
    about 1e-12 from the exact bracket for fields whose derivatives are of order one
    (the tests compare with sympy's). The bracket is antisymmetric,
    :math:`[\mathbf f_2, \mathbf f_1] = -[\mathbf f_1, \mathbf f_2]`.

    Parameters
    ----------
    f1, f2 : callable
        Vector fields: a configuration, shape (n,), to a velocity, shape (n,), finite at and
        near ``configuration``.
    configuration : array_like, shape (n,)
        The configuration :math:`q`.
    step : float, keyword-only
        Relative finite-difference step, in [1e-8, 0.1].

    Returns
    -------
    numpy.ndarray, shape (n,)

    Examples
    --------
    The car at full lock (:func:`car_lock_fields`, :math:`\kappa_{max}` = 1.5 /m), facing
    :math:`+y`: the bracket of left and right lock points to its left, :math:`-x`:

    >>> def left(q):
    ...     return car_lock_fields(q, 1.5)[:, 0]
    >>> def right(q):
    ...     return car_lock_fields(q, 1.5)[:, 1]
    >>> lie_bracket(left, right, [0.0, 0.0, math.pi / 2]).round(9) + 0.0
    array([-3.,  0.,  0.])
    """
    a = _field("f1", f1)
    b = _field("f2", f2)
    q = _vector("configuration", configuration)
    h = V.in_range("step", step, 1e-8, 0.1)
    return _bracket(a, b, q, h) + 0.0


def bracket_prediction(f1: VectorField, f2: VectorField, configuration: ArrayLike,
                       epsilon: float) -> NDArray[np.float64]:
    r"""The leading-order net motion of the four-move manoeuvre of size :math:`\varepsilon`
    (:func:`bracket_manoeuvre`): :math:`\varepsilon^2\,[\mathbf f_1, \mathbf f_2](q)`.

    Parameters
    ----------
    f1, f2 : callable
        Vector fields (see :func:`lie_bracket`).
    configuration : array_like, shape (n,)
        The start :math:`q`.
    epsilon : float
        :math:`\varepsilon`, the duration of each move (finite; for fields per metre, the
        distance of each move).

    Returns
    -------
    numpy.ndarray, shape (n,)
        The predicted change of the configuration.

    Examples
    --------
    Drive 0.1 m, turn 0.1 rad, back 0.1 m, turn back: about 1 cm to the right:

    >>> p = bracket_prediction(unicycle_drive, unicycle_turn, [0.0, 0.0, 0.0], 0.1)
    >>> p.round(12) + 0.0
    array([ 0.  , -0.01,  0.  ])
    """
    eps = V.finite("epsilon", epsilon)
    with np.errstate(all="ignore"):
        out = eps * eps * lie_bracket(f1, f2, configuration)
    V.finite_result("epsilon", out)
    return out + 0.0


def _rk4(field: VectorField, name: str, q: NDArray[np.float64], duration: float,
         steps: int) -> NDArray[np.float64]:
    h = duration / steps
    x = q.copy()
    for _ in range(steps):
        k1 = _evaluate(name, field, x)
        k2 = _evaluate(name, field, x + 0.5 * h * k1)
        k3 = _evaluate(name, field, x + 0.5 * h * k2)
        k4 = _evaluate(name, field, x + h * k3)
        x = x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return x


def _steps(steps: object) -> int:
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer):
        raise TypeError(f"steps must be an int, got {type(steps).__name__}")
    if not 1 <= int(steps) <= MAX_STEPS:
        raise ValueError(f"steps must be in [1, {MAX_STEPS}], got {steps!r}")
    return int(steps)


def flow(field: VectorField, configuration: ArrayLike, duration: float, *,
         steps: int = 100) -> NDArray[np.float64]:
    r"""Where the flow of a vector field carries a configuration in ``duration``:
    :math:`q(t)` with :math:`\dot q = \mathbf f(q)`, :math:`q(0) = q_0`, by ``steps`` steps of
    the classical fourth-order Runge-Kutta method (global error :math:`O(h^4)`,
    :math:`h` = ``duration / steps``). A negative duration follows :math:`-\mathbf f`.

    Parameters
    ----------
    field : callable
        The vector field (see :func:`lie_bracket`).
    configuration : array_like, shape (n,)
        :math:`q_0`.
    duration : float
        :math:`t` (finite; negative runs the flow backwards).
    steps : int, keyword-only
        In [1, 1e6].

    Returns
    -------
    numpy.ndarray, shape (n,)

    Examples
    --------
    Half a turn of the unicycle's turn field, then 1 m of its drive field:

    >>> q = flow(unicycle_turn, [0.0, 0.0, 0.0], math.pi)
    >>> flow(unicycle_drive, q, 1.0).round(9) + 0.0
    array([-1.        ,  0.        ,  3.14159265])
    """
    f = _field("field", field)
    q = _vector("configuration", configuration)
    t = V.finite("duration", duration)
    n = _steps(steps)
    with np.errstate(all="ignore"):
        out = _rk4(f, "field", q, t, n)
    V.finite_result("duration", out)
    return out + 0.0


def bracket_manoeuvre(f1: VectorField, f2: VectorField, configuration: ArrayLike,
                      epsilon: float, *, steps: int = 100) -> NDArray[np.float64]:
    r"""The four-move manoeuvre that the Lie bracket describes: follow :math:`\mathbf f_1`
    for :math:`\varepsilon`, then :math:`\mathbf f_2`, then :math:`-\mathbf f_1`, then
    :math:`-\mathbf f_2` (each by :func:`flow`).

    The net motion is :math:`\varepsilon^2[\mathbf f_1, \mathbf f_2](q) + O(\varepsilon^3)`
    (:func:`bracket_prediction`); the :math:`\varepsilon^3` term is
    :math:`\tfrac12[\mathbf f_1 + \mathbf f_2, [\mathbf f_1, \mathbf f_2]]`, so where that
    bracket vanishes (the car at full lock) the remainder is :math:`O(\varepsilon^4)`.

    Parameters
    ----------
    f1, f2 : callable
        Vector fields (see :func:`lie_bracket`).
    configuration : array_like, shape (n,)
        The start :math:`q`.
    epsilon : float
        :math:`\varepsilon`, the duration of each move (finite).
    steps : int, keyword-only
        Runge-Kutta steps per move, in [1, 1e6].

    Returns
    -------
    numpy.ndarray, shape (5, n)
        The configuration at the start and after each move.

    Examples
    --------
    >>> path = bracket_manoeuvre(unicycle_drive, unicycle_turn, [0.0, 0.0, 0.0], 0.1)
    >>> (path[-1] - path[0]).round(6) + 0.0  # about (0, -0.01, 0): to the right
    array([ 0.0005  , -0.009983,  0.      ])
    """
    a = _field("f1", f1)
    b = _field("f2", f2)
    q = _vector("configuration", configuration)
    eps = V.finite("epsilon", epsilon)
    n = _steps(steps)
    out = [q]
    with np.errstate(all="ignore"):
        for field, name, sign in ((a, "f1", 1.0), (b, "f2", 1.0), (a, "f1", -1.0),
                                  (b, "f2", -1.0)):
            out.append(_rk4(field, name, out[-1], sign * eps, n))
    result = np.array(out)
    V.finite_result("epsilon", result)
    return result + 0.0


def bracket_ranks(fields: Sequence[VectorField], configuration: ArrayLike, *,
                  depth: int = 3, tolerance: float = 1e-6) -> NDArray[np.int64]:
    r"""The dimension of the span of the fields and their brackets, depth by depth: the
    *growth vector* at :math:`q`; its last entry is the rank that Chow's condition asks to
    equal :math:`n`.

    Depth 1 is the fields themselves, depth 2 adds :math:`[\mathbf f_i, \mathbf f_j]`, depth
    :math:`k` adds the brackets of a field with those of depth :math:`k - 1` (these span all
    brackets of depth :math:`k`). A rank is the number of singular values of the stacked
    vectors above ``tolerance`` times the largest (or 1).

    Parameters
    ----------
    fields : sequence of callable
        One or more vector fields (see :func:`lie_bracket`).
    configuration : array_like, shape (n,)
        The configuration :math:`q`.
    depth : int, keyword-only
        The deepest bracket, in [1, 5].
    tolerance : float, keyword-only
        Relative threshold of the rank decision, in [1e-12, 0.1].

    Returns
    -------
    numpy.ndarray of int, shape (depth,)

    Examples
    --------
    The car with its steering (:func:`car_fields`): two fields, the turn on the spot, the
    slide:

    >>> def drive(q):
    ...     return car_fields(q, 2.5)[:, 0]
    >>> def steer(q):
    ...     return car_fields(q, 2.5)[:, 1]
    >>> bracket_ranks([drive, steer], [0.0, 0.0, 0.3, 0.2]).tolist()
    [2, 3, 4]
    """
    if isinstance(fields, str) or not isinstance(fields, Sequence) or not fields:
        raise TypeError("fields must be a non-empty sequence of callable vector fields, got "
                        f"{type(fields).__name__}")
    given = [_field(f"fields[{i}]", f) for i, f in enumerate(fields)]
    q = _vector("configuration", configuration)
    if isinstance(depth, bool) or not isinstance(depth, int | np.integer):
        raise TypeError(f"depth must be an int, got {type(depth).__name__}")
    if not 1 <= int(depth) <= MAX_DEPTH:
        raise ValueError(f"depth must be in [1, {MAX_DEPTH}], got {depth!r}")
    tol = V.in_range("tolerance", tolerance, 1e-12, 0.1)
    # Nested differences lose accuracy: a coarser step keeps a depth-5 bracket near 1e-8.
    step = 1e-2 if depth > 2 else BRACKET_STEP
    named: list[tuple[str, VectorField]] = [(f"fields[{i}]", f) for i, f in enumerate(given)]
    level = named
    vectors = [_evaluate(name, f, q) for name, f in named]
    ranks = [_span_rank(vectors, tol)]
    for _ in range(int(depth) - 1):
        level = [(f"[{name_a}, {name_b}]", _bracket_field(a, b, (name_a, name_b), step))
                 for name_a, a in named for name_b, b in level]
        vectors += [_evaluate(name, f, q) for name, f in level]
        ranks.append(_span_rank(vectors, tol))
    return np.array(ranks, dtype=np.int64)


def _bracket_field(a: VectorField, b: VectorField, names: tuple[str, str],
                   step: float) -> VectorField:
    """The vector field [a, b] (numerical), for brackets of brackets."""
    def bracket(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return _bracket(a, b, np.asarray(x, dtype=float), step, names)
    return bracket


def _span_rank(vectors: list[NDArray[np.float64]], tolerance: float) -> int:
    s = np.linalg.svd(np.array(vectors), compute_uv=False)
    return int(np.sum(s > tolerance * max(1.0, float(s[0]))))


# --------------------------------------------------------------------------------------------
# The car's parallel-parking manoeuvre, exactly
# --------------------------------------------------------------------------------------------

def parallel_parking(pose: ArrayLike, epsilon: float, max_curvature: float
                     ) -> NDArray[np.float64]:
    r"""The car's four full-lock moves of length :math:`\varepsilon`, exactly: forward at
    left lock, forward at right lock, backward at left lock, backward at right lock (the flows
    of :math:`\mathbf f_L, \mathbf f_R, -\mathbf f_L, -\mathbf f_R` of
    :func:`car_lock_fields`).

    Each move is an arc of radius :math:`1/\kappa_{max}` (:func:`wheelkin.frames.se2_exp`),
    so the poses are exact. The heading comes back exactly and the net motion is exactly
    sideways, to the left, by :func:`parking_shift`:
    :math:`4(1 - \cos\kappa_{max}\varepsilon)/\kappa_{max}
    = 2\kappa_{max}\varepsilon^2 + O(\varepsilon^4)`, the bracket
    :math:`\varepsilon^2[\mathbf f_L, \mathbf f_R]` to leading order.

    Parameters
    ----------
    pose : array_like, shape (3,)
        The start :math:`(x, y, \theta)`, m, m, rad.
    epsilon : float
        :math:`\varepsilon`, the distance the rear-axle midpoint drives in each move, m
        (finite; a negative one runs the manoeuvre backwards, to the right).
    max_curvature : float
        :math:`\kappa_{max} = \tan\delta_{max}/L`, 1/m (> 0).

    Returns
    -------
    numpy.ndarray, shape (5, 3)
        The pose at the start and after each move (headings wrapped to :math:`(-\pi, \pi]`).

    Examples
    --------
    The 1/10 car (:math:`\kappa_{max}` = 1.35 /m), moves of 0.2 m: 10.7 cm to the left:

    >>> parallel_parking([0.0, 0.0, 0.0], 0.2, 1.35)[-1].round(6) + 0.0
    array([0.      , 0.107345, 0.      ])
    """
    p = _vector("pose", pose, 3)
    eps = V.finite("epsilon", epsilon)
    kappa = V.positive("max_curvature", max_curvature)
    twists = [[1.0, 0.0, kappa], [1.0, 0.0, -kappa], [-1.0, 0.0, -kappa], [-1.0, 0.0, kappa]]
    if abs(eps) < np.finfo(float).tiny:  # zero (or subnormal): no motion at all
        return np.repeat(p[None, :], 5, axis=0) + 0.0
    with np.errstate(all="ignore"):
        if eps > 0:
            out = frames.integrate_twist(twists, eps, p)
        else:  # the same moves run backwards in time: each twist reversed
            out = frames.integrate_twist([[-a, b, -c] for a, b, c in twists], -eps, p)
    V.finite_result("epsilon and max_curvature", out)
    return out + 0.0


@overload
def parking_shift(epsilon: float, max_curvature: float) -> float: ...
@overload
def parking_shift(epsilon: Stack, max_curvature: float) -> NDArray[np.float64]: ...
def parking_shift(epsilon: ArrayLike, max_curvature: float) -> float | NDArray[np.float64]:
    r"""How far :func:`parallel_parking` moves the car sideways (to its left), exactly:

    .. math:: s(\varepsilon) = \frac{4\,(1 - \cos\kappa_{max}\varepsilon)}{\kappa_{max}}
              = \frac{8}{\kappa_{max}}\sin^2\frac{\kappa_{max}\varepsilon}{2}
              = 2\kappa_{max}\varepsilon^2 - \frac{\kappa_{max}^3\varepsilon^4}{6}
              + O(\varepsilon^6).

    Parameters
    ----------
    epsilon : float or array_like
        :math:`\varepsilon`, the length of each move, m (finite; the shift is even in it).
    max_curvature : float
        :math:`\kappa_{max}`, 1/m (> 0).

    Returns
    -------
    float or numpy.ndarray
        m, of ``epsilon``'s shape.

    Examples
    --------
    >>> round(parking_shift(0.2, 1.35), 6)
    0.107345
    """
    eps = V.finite_array("epsilon", epsilon)
    kappa = V.positive("max_curvature", max_curvature)
    with np.errstate(all="ignore"):
        half = np.sin(0.5 * kappa * eps)
        out = 8.0 * half * half / kappa
    V.finite_result("max_curvature", out)
    return V.scalar_or_array(out + 0.0)
