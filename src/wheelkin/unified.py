r"""One model for every wheel: rolling and no-side-slip constraints acting on the body twist.

Every wheel of the book's four vehicles is one instance of a single description, a
:class:`WheelConstraint`, and every vehicle is a tuple of them. Each wheel contributes rows to
one matrix acting on the body twist :math:`\xi = (v_x, v_y, \omega)` (body frame, REP-103:
x forward, y left, :math:`\omega` counter-clockwise; SI), following the constraint
formulation of Siegwart et al. :cite:`siegwart2011` (section 3.2) in Cartesian form.

Symbols (as in the chapter "One model for every wheel")
-------------------------------------------------------
==========================  ===================================================  ============
symbol                      meaning                                              name here
==========================  ===================================================  ============
:math:`p_i = (x_i, y_i)`    wheel *i*'s contact point in the body frame, m       ``position``
:math:`\psi_i^0`            angle of its rolling direction at zero steering,     ``heading``
                            from the body x axis, rad
:math:`\delta_i`            steering angle (steered wheels and casters), rad,    ``steering``
                            counter-clockwise positive
:math:`\psi_i`              rolling direction :math:`\psi_i^0 + \delta_i`        ``direction``
:math:`r_w`                 wheel radius, m                                      ``wheel_radius``
:math:`\gamma_i`            Swedish wheels: signed angle from the wheel's axle   ``roller_angle``
                            to the axis of the roller touching the ground,
                            counter-clockwise seen from above, rad
:math:`\dot\varphi_i`       wheel angular rate, rad/s, positive rolling along
                            :math:`\mathbf e_i`
==========================  ===================================================  ============

Unit vectors: the rolling direction :math:`\mathbf e_i = (\cos\psi_i, \sin\psi_i)`, the
lateral (sliding) direction :math:`\mathbf n_i = (-\sin\psi_i, \cos\psi_i)` (the axle) and a
Swedish wheel's roller axis :math:`\mathbf u_i = (-\sin(\psi_i+\gamma_i),
\cos(\psi_i+\gamma_i))`, i.e. :math:`\mathbf n_i` turned by :math:`\gamma_i`.

The constraints
---------------
The contact point moves at :math:`\dot p_i = P_i\,\xi` with

.. math:: P_i = \begin{bmatrix} 1 & 0 & -y_i \\ 0 & 1 & x_i \end{bmatrix},

so a direction :math:`\mathbf d` at wheel *i* gives the row
:math:`\mathbf d^T P_i = (d_x,\ d_y,\ x_i d_y - y_i d_x)`. Then

- *rolling* (every wheel, one row of :math:`J_1`): the contact velocity along the rolling
  direction is the rim speed, :math:`\mathbf e_i^T P_i\,\xi = r_w\dot\varphi_i`; for a Swedish
  wheel only the velocity along the roller axis must come from the hub,
  :math:`\mathbf u_i^T P_i\,\xi = r_w\dot\varphi_i\,(\mathbf u_i\cdot\mathbf e_i)`, so its row is
  :math:`\mathbf u_i^T P_i / (\mathbf u_i\cdot\mathbf e_i)` with
  :math:`\mathbf u_i\cdot\mathbf e_i = -\sin\gamma_i`. We scale every row so that
  :math:`J_1\,\xi = r_w\,\dot\varphi` (wheel rim speeds, m/s).
- *no side slip* (fixed and steered wheels, one row of :math:`C_1`):
  :math:`\mathbf n_i^T P_i\,\xi = 0`. A Swedish wheel's rollers and a caster's swivel absorb
  any sideways velocity: they give no row.

The kinds
---------
``"fixed"``: conventional wheel at a fixed angle (:math:`\delta_i = 0`); ``"steered"``: a
conventional wheel turned about a vertical axis through its contact point; ``"swedish"``: a
hub with passive rollers at :math:`\gamma_i` (mecanum :math:`|\gamma_i| = 45°`, omni
:math:`|\gamma_i| = 90°`); ``"caster"``: a passive off-centre swivel wheel, whose rolling row
uses its current swivel angle :math:`\delta_i` (it trails along its contact velocity).

Mobility :cite:`siegwart2011` (section 3.3): the degree of mobility
:math:`\delta_m = 3 - \operatorname{rank} C_1(\delta)`, the degree of steerability
:math:`\delta_s` (independent steering freedoms) and the degree of manoeuvrability
:math:`\delta_M = \delta_m + \delta_s`; see :func:`mobility`.

The book's vehicles: :func:`rover_wheels` (from :class:`wheelkin.rover.RoverGeometry`),
:func:`mecanum_wheels` (from :class:`wheelkin.mecanum.MecanumGeometry`),
:func:`diff_drive_wheels`, :func:`skid_steer_wheels`, :func:`car_wheels`. The sandbox
(:class:`wheelkin.sandbox.VehicleSpec`) builds its vehicles from these wheels, and its contact
model imposes these rows (:func:`roller_row` for a Swedish wheel: its rolling row in unit form).

Conventions elsewhere: :mod:`wheelkin.mecanum`'s :math:`\gamma` is our :math:`|\gamma_i|`
(X arrangement: :math:`\gamma_i = +\gamma` for FL and RR, :math:`-\gamma` for FR and RL);
Siegwart's :math:`\gamma` is measured from the wheel plane, :math:`\gamma_S = \gamma_i + 90°`
(the same roller axis up to its sign).

Examples
--------
>>> wheels = diff_drive_wheels(0.085, 0.018, caster=False)
>>> wheel_rates(wheels, (0.2, 0.0, 1.0)) * 0.018   # rim speeds L, R (m/s)
array([0.1575, 0.2425])
>>> m = mobility(wheels)
>>> m.degree_of_mobility, m.degree_of_steerability, m.degree_of_manoeuvrability
(2, 0, 2)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from wheelkin import _validate as V
from wheelkin import rover
from wheelkin._kernels import point_row, roller_axis, shift_twist
from wheelkin.frames import Twist, fold_half_turn
from wheelkin.mecanum import ROLLER_SIGNS, MecanumGeometry
from wheelkin.mecanum import WHEEL_NAMES as MECANUM_WHEEL_NAMES
from wheelkin.units import INCH

__all__ = [
    "WHEEL_KINDS",
    "Mobility",
    "WheelConstraint",
    "admissible_twists",
    "body_twist",
    "car_wheels",
    "constraint_matrix",
    "diff_drive_wheels",
    "mecanum_wheels",
    "mobility",
    "roller_row",
    "rolling_matrix",
    "rolling_row",
    "rover_wheels",
    "skid_steer_wheels",
    "sliding_matrix",
    "sliding_row",
    "slip_residual",
    "steer_for_twist",
    "wheel_rates",
]

#: The kinds of wheel, in the order the chapter introduces them.
WHEEL_KINDS = ("fixed", "steered", "swedish", "caster")
#: Relative tolerance of the rank decisions (singular values below it count as zero).
RANK_TOLERANCE = 1e-9


@dataclass(frozen=True)
class WheelConstraint:
    r"""One wheel, as the constraints it puts on the body twist (body frame, SI).

    Parameters
    ----------
    name : str
        Unique within a vehicle, e.g. ``"FL"``.
    position : (float, float)
        Contact point :math:`(x_i, y_i)`, m.
    heading : float
        :math:`\psi_i^0`, angle of the rolling direction at zero steering, rad (finite).
    wheel_radius : float
        :math:`r_w`, m (> 0).
    kind : {"fixed", "steered", "swedish", "caster"}
    roller_angle : float
        Swedish wheels only: :math:`\gamma_i`, signed, :math:`0 < |\gamma_i| \le \pi/2` rad
        (0 for every other kind).
    steering : float
        Steered wheels and casters only: :math:`\delta_i` in :math:`[-\pi, \pi]` rad
        (0 for fixed and Swedish wheels).

    Examples
    --------
    >>> w = WheelConstraint("FL", (0.2, 0.15), wheel_radius=0.05, kind="swedish",
    ...                     roller_angle=math.pi / 4)
    >>> np.round(w.roller_axis, 4)  # n turned by +45 degrees
    array([-0.7071,  0.7071])
    >>> WheelConstraint("L", (0.0, 0.1), kind="fixed", steering=0.2)
    Traceback (most recent call last):
    ...
    ValueError: steering must be 0 for a 'fixed' wheel (it cannot steer), got 0.2
    """

    name: str
    position: tuple[float, float]
    heading: float = 0.0
    wheel_radius: float = 0.05
    kind: str = "fixed"
    roller_angle: float = 0.0
    steering: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"name must be a non-empty string, got {self.name!r}")
        p = V.shaped("position", self.position, (2,))
        if p.shape != (2,):
            raise ValueError(f"position must be one point (x, y), got shape {p.shape}")
        object.__setattr__(self, "position", (float(p[0]), float(p[1])))
        object.__setattr__(self, "heading", V.finite("heading", self.heading))
        object.__setattr__(self, "wheel_radius", V.positive("wheel_radius", self.wheel_radius))
        if not isinstance(self.kind, str):
            raise ValueError(f"kind must be one of {', '.join(map(repr, WHEEL_KINDS))}; "
                             f"got {self.kind!r}")
        V.choice("kind", self.kind, WHEEL_KINDS)
        gamma = V.finite("roller_angle", self.roller_angle)
        if self.kind == "swedish":
            if not 0.0 < abs(gamma) <= math.pi / 2:
                raise ValueError("roller_angle must satisfy 0 < |roller_angle| <= pi/2 for a "
                                 f"swedish wheel, got {self.roller_angle!r}")
        elif gamma != 0.0:
            raise ValueError(f"roller_angle must be 0 for a {self.kind!r} wheel (only swedish "
                             f"wheels have rollers), got {self.roller_angle!r}")
        object.__setattr__(self, "roller_angle", gamma)
        delta = V.finite("steering", self.steering)
        if self.kind in ("fixed", "swedish") and delta != 0.0:
            raise ValueError(f"steering must be 0 for a {self.kind!r} wheel (it cannot steer), "
                             f"got {self.steering!r}")
        if abs(delta) > math.pi:
            raise ValueError(f"steering must be in [-pi, pi], got {self.steering!r}")
        object.__setattr__(self, "steering", delta)

    @property
    def direction(self) -> float:
        r""":math:`\psi_i = \psi_i^0 + \delta_i`, the rolling direction's angle, rad."""
        return self.heading + self.steering

    @property
    def rolling_direction(self) -> np.ndarray:
        r""":math:`\mathbf e_i = (\cos\psi_i, \sin\psi_i)`."""
        return np.array([math.cos(self.direction), math.sin(self.direction)])

    @property
    def lateral_direction(self) -> np.ndarray:
        r""":math:`\mathbf n_i = (-\sin\psi_i, \cos\psi_i)`, along the axle."""
        return np.array([-math.sin(self.direction), math.cos(self.direction)])

    @property
    def roller_axis(self) -> np.ndarray:
        r""":math:`\mathbf u_i`, the ground roller's axis (Swedish wheels; ``ValueError``
        otherwise)."""
        if self.kind != "swedish":
            raise ValueError(f"roller_axis is defined for swedish wheels only, got a "
                             f"{self.kind!r} wheel ({self.name})")
        return np.array(roller_axis(self.direction, self.roller_angle))

    def steered_to(self, steering: float) -> WheelConstraint:
        """A copy with the steering angle ``steering`` (rad), validated again."""
        return replace(self, steering=steering)


# --------------------------------------------------------------------------------------------
# Validation helpers
# --------------------------------------------------------------------------------------------

def _wheel(wheel) -> WheelConstraint:
    if not isinstance(wheel, WheelConstraint):
        raise ValueError(f"wheel must be a WheelConstraint, got {type(wheel).__name__}")
    return wheel


def _wheels(wheels) -> tuple[WheelConstraint, ...]:
    if isinstance(wheels, WheelConstraint) or not isinstance(wheels, Sequence) or not wheels:
        raise ValueError("wheels must be a non-empty sequence of WheelConstraint, got "
                         f"{type(wheels).__name__}")
    if not all(isinstance(w, WheelConstraint) for w in wheels):
        bad = next(type(w).__name__ for w in wheels if not isinstance(w, WheelConstraint))
        raise ValueError(f"wheels must be a non-empty sequence of WheelConstraint, got an "
                         f"element of type {bad}")
    names = [w.name for w in wheels]
    if len(set(names)) != len(names):
        raise ValueError(f"wheels must have unique names, got {names}")
    return tuple(wheels)


def _twist(twist) -> np.ndarray:
    if isinstance(twist, Twist):
        return twist.as_array()
    return V.shaped("twist", twist, (3,))


def _row(direction: np.ndarray, position: tuple[float, float]) -> np.ndarray:
    return np.array(point_row(*position, float(direction[0]), float(direction[1]))) + 0.0


def _rank(matrix: np.ndarray) -> int:
    if matrix.size == 0:
        return 0
    s = np.linalg.svd(matrix, compute_uv=False)
    return int(np.sum(s > RANK_TOLERANCE * max(1.0, float(s[0]))))


# --------------------------------------------------------------------------------------------
# Rows and matrices
# --------------------------------------------------------------------------------------------

def rolling_row(wheel: WheelConstraint) -> np.ndarray:
    r"""The wheel's rolling-constraint row :math:`J_{1,i}`, with :math:`J_{1,i}\,\xi =
    r_w\dot\varphi_i` (the rim speed, m/s).

    .. math::

        J_{1,i} = \mathbf e_i^T P_i
        = (\cos\psi_i,\ \sin\psi_i,\ x_i\sin\psi_i - y_i\cos\psi_i)

    for fixed and steered wheels and casters, and for a Swedish wheel

    .. math::

        J_{1,i} = \frac{\mathbf u_i^T P_i}{\mathbf u_i\cdot\mathbf e_i}
        = \frac{(\sin(\psi_i+\gamma_i),\ -\cos(\psi_i+\gamma_i),\
          -x_i\cos(\psi_i+\gamma_i) - y_i\sin(\psi_i+\gamma_i))}{\sin\gamma_i}.

    Parameters
    ----------
    wheel : WheelConstraint

    Returns
    -------
    numpy.ndarray, shape (3,)
        Coefficients of :math:`(v_x, v_y, \omega)`: dimensionless, dimensionless, m.

    Examples
    --------
    A mecanum front-left wheel at (0.2, 0.15) with 45-degree rollers: the row of
    :func:`wheelkin.mecanum.inverse_matrix` times r_w, (1, -1, -(a + b)).

    >>> w = WheelConstraint("FL", (0.2, 0.15), kind="swedish", roller_angle=math.pi / 4)
    >>> np.round(rolling_row(w), 12) + 0.0
    array([ 1.  , -1.  , -0.35])
    """
    w = _wheel(wheel)
    if w.kind == "swedish":
        return roller_row(w) / float(w.roller_axis @ w.rolling_direction)
    return _row(w.rolling_direction, w.position)


def roller_row(wheel: WheelConstraint) -> np.ndarray:
    r"""A Swedish wheel's roller row :math:`\mathbf u_i^T P_i`: the velocity of the contact
    point along the ground roller's axis, the one velocity the wheel constrains.

    .. math::

        \mathbf u_i^T P_i\,\xi = r_w\dot\varphi_i\,(\mathbf u_i\cdot\mathbf e_i), \qquad
        \mathbf u_i^T P_i = (-\sin(\psi_i+\gamma_i),\ \cos(\psi_i+\gamma_i),\
        x_i\cos(\psi_i+\gamma_i) + y_i\sin(\psi_i+\gamma_i))

    Its direction is a unit vector, so it is the row along which the ground pushes the wheel
    (the sandbox's contact uses it); :func:`rolling_row` is the same row divided by
    :math:`\mathbf u_i\cdot\mathbf e_i = -\sin\gamma_i`.

    Parameters
    ----------
    wheel : WheelConstraint
        A ``"swedish"`` wheel (``ValueError`` for any other kind).

    Returns
    -------
    numpy.ndarray, shape (3,)
        Coefficients of :math:`(v_x, v_y, \omega)`: dimensionless, dimensionless, m.

    Examples
    --------
    >>> w = WheelConstraint("FL", (0.2, 0.15), kind="swedish", roller_angle=math.pi / 4)
    >>> np.round(roller_row(w) * math.sqrt(2), 12) + 0.0   # (-1, 1, a + b) / sqrt(2)
    array([-1.  ,  1.  ,  0.35])
    """
    w = _wheel(wheel)
    return _row(w.roller_axis, w.position)


def sliding_row(wheel: WheelConstraint) -> np.ndarray:
    r"""The wheel's no-side-slip row :math:`C_{1,i}`, with :math:`C_{1,i}\,\xi = 0` when the
    wheel does not slide sideways (fixed and steered wheels only).

    .. math::

        C_{1,i} = \mathbf n_i^T P_i
        = (-\sin\psi_i,\ \cos\psi_i,\ x_i\cos\psi_i + y_i\sin\psi_i)

    Parameters
    ----------
    wheel : WheelConstraint
        A ``"fixed"`` or ``"steered"`` wheel; a Swedish wheel or a caster has no such row
        (``ValueError``).

    Returns
    -------
    numpy.ndarray, shape (3,)
        Coefficients of :math:`(v_x, v_y, \omega)`; :math:`C_{1,i}\,\xi` is the sideways
        sliding speed of the contact point, m/s.

    Examples
    --------
    >>> sliding_row(WheelConstraint("FL", (0.05, 0.06)))  # a skid steer's front-left wheel
    array([0.  , 1.  , 0.05])
    """
    w = _wheel(wheel)
    if w.kind not in ("fixed", "steered"):
        raise ValueError(f"wheel {w.name!r} is a {w.kind!r} wheel: only fixed and steered "
                         "wheels have a no-side-slip row")
    return _row(w.lateral_direction, w.position)


def rolling_matrix(wheels: Sequence[WheelConstraint]) -> np.ndarray:
    r""":math:`J_1`: the rolling rows of all wheels, in the given order, shape (n, 3).

    :math:`J_1\,\xi = \operatorname{diag}(r_w)\,\dot\varphi` (rim speeds, m/s).

    Examples
    --------
    >>> rolling_matrix(diff_drive_wheels(0.1, 0.02, caster=False))  # rows L, R
    array([[ 1.  ,  0.  , -0.05],
           [ 1.  ,  0.  ,  0.05]])
    """
    return np.array([rolling_row(w) for w in _wheels(wheels)])


def sliding_matrix(wheels: Sequence[WheelConstraint]) -> np.ndarray:
    r""":math:`C_1`: the no-side-slip rows of the fixed and steered wheels, in the given order,
    shape (m, 3) (m may be 0: no row for Swedish wheels and casters).

    Examples
    --------
    >>> skid = skid_steer_wheels(half_wheelbase=0.05, half_track=0.06,
    ...                   wheel_radius=0.04)
    >>> sliding_matrix(skid)  # rows FL, FR, RL, RR
    array([[ 0.  ,  1.  ,  0.05],
           [ 0.  ,  1.  ,  0.05],
           [ 0.  ,  1.  , -0.05],
           [ 0.  ,  1.  , -0.05]])
    >>> geometry = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> sliding_matrix(mecanum_wheels(geometry)).shape
    (0, 3)
    """
    rows = [sliding_row(w) for w in _wheels(wheels) if w.kind in ("fixed", "steered")]
    return np.array(rows).reshape(len(rows), 3)


def constraint_matrix(wheels: Sequence[WheelConstraint]) -> np.ndarray:
    r"""The whole constraint matrix :math:`\begin{bmatrix} J_1 \\ C_1 \end{bmatrix}`, shape
    (n + m, 3): first one rolling row per wheel, then one sliding row per fixed or steered
    wheel, each group in the given wheel order, with

    .. math:: \begin{bmatrix} J_1 \\ C_1 \end{bmatrix} \xi =
              \begin{bmatrix} \operatorname{diag}(r_w)\,\dot\varphi \\ 0 \end{bmatrix}

    (Siegwart et al.'s combined constraint equation, in the body frame).

    Examples
    --------
    >>> constraint_matrix(diff_drive_wheels(0.1, 0.02, caster=False))  # L, R, then L, R
    array([[ 1.  ,  0.  , -0.05],
           [ 1.  ,  0.  ,  0.05],
           [ 0.  ,  1.  ,  0.  ],
           [ 0.  ,  1.  ,  0.  ]])
    """
    w = _wheels(wheels)
    return np.vstack([rolling_matrix(w), sliding_matrix(w)])


# --------------------------------------------------------------------------------------------
# Using the model
# --------------------------------------------------------------------------------------------

def wheel_rates(wheels: Sequence[WheelConstraint], twist: Twist | npt.ArrayLike, *,
                centre_of_rotation: npt.ArrayLike | None = None) -> np.ndarray:
    r"""Wheel angular rates :math:`\dot\varphi_i` (rad/s) for a body twist, from the rolling rows.

    .. math:: \dot\varphi_i = \frac{J_{1,i}\,\xi}{r_{w,i}}

    With a ``centre_of_rotation`` :math:`c` (as WPILib's mecanum kinematics have, and
    ros2_controllers' mecanum controller through its ``base_frame_offset`` when that offset
    is not rotated), :math:`(v_x, v_y)` is the velocity of :math:`c` and the body turns
    about it: the twist of the body origin is then
    :math:`\xi = (v_x + \omega c_y,\; v_y - \omega c_x,\; \omega)`.

    Steered wheels and casters roll along their *current* steering; whether the twist also
    respects the no-side-slip rows is :func:`slip_residual`'s question (steer them first with
    :func:`steer_for_twist`).

    Parameters
    ----------
    wheels : sequence of WheelConstraint
    twist : Twist or array_like, shape (..., 3)
        :math:`(v_x, v_y, \omega)`, m/s, m/s, rad/s.
    centre_of_rotation : array_like, shape (2,), optional
        :math:`(c_x, c_y)` in the body frame, m; default the origin.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        rad/s, in the wheels' order.

    Examples
    --------
    The mecanum strafe of :func:`wheelkin.mecanum.inverse_kinematics`, FL, FR, RL, RR:

    >>> geometry = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> wheel_rates(mecanum_wheels(geometry), (0.0, 1.0, 0.0))
    array([-20.,  20.,  20., -20.])
    """
    w = _wheels(wheels)
    xi = _twist(twist)
    if centre_of_rotation is not None:
        c = V.finite_array("centre_of_rotation", centre_of_rotation)
        if c.shape != (2,):
            raise ValueError("centre_of_rotation must have shape (2,): (c_x, c_y) in m, got "
                             f"shape {c.shape}")
        xi = np.stack(shift_twist(xi[..., 0], xi[..., 1], xi[..., 2], c[0], c[1]), axis=-1)
    radii = np.array([wh.wheel_radius for wh in w])
    return (xi @ rolling_matrix(w).T) / radii


def slip_residual(wheels: Sequence[WheelConstraint],
                  twist: Twist | npt.ArrayLike) -> np.ndarray:
    r"""How fast each wheel would have to slide sideways to follow the twist, m/s.

    .. math:: s_i = C_{1,i}\,\xi = \mathbf n_i \cdot (v_x - \omega y_i,\ v_y + \omega x_i)

    for fixed and steered wheels (signed, along :math:`\mathbf n_i`), and 0 for Swedish wheels
    and casters, which have no such constraint. All zeros means the twist is admissible: the
    wheels can follow it by rolling alone.

    Parameters
    ----------
    wheels : sequence of WheelConstraint
    twist : Twist or array_like, shape (..., 3)

    Returns
    -------
    numpy.ndarray, shape (..., n)
        m/s, one per wheel in the wheels' order.

    Examples
    --------
    A skid steer spinning on the spot at 1 rad/s: every wheel slides sideways at a = 0.05 m/s.

    >>> skid = skid_steer_wheels(half_wheelbase=0.05, half_track=0.06,
    ...                   wheel_radius=0.04)
    >>> slip_residual(skid, (0.0, 0.0, 1.0))
    array([ 0.05,  0.05, -0.05, -0.05])
    """
    w = _wheels(wheels)
    xi = _twist(twist)
    rows = np.array([sliding_row(wh) if wh.kind in ("fixed", "steered") else np.zeros(3)
                     for wh in w])
    return xi @ rows.T + 0.0


def body_twist(wheels: Sequence[WheelConstraint], rates: npt.ArrayLike) -> np.ndarray:
    r"""The body twist that best explains measured wheel rates (forward kinematics, odometry).

    Least squares on the rolling rows of the wheels that are not casters (a caster is not
    measured):

    .. math:: \xi = J_1^{+}\,\operatorname{diag}(r_w)\,\dot\varphi

    with :math:`J_1^{+}` the Moore-Penrose pseudo-inverse: exact when the rates are those of a
    twist; of several twists that explain them equally well (a differential drive cannot
    measure :math:`v_y`), the smallest. The sliding rows are not used, so a skid steer is
    read as a differential drive of its geometric track.

    Parameters
    ----------
    wheels : sequence of WheelConstraint
    rates : array_like, shape (..., n)
        :math:`\dot\varphi`, rad/s, in the wheels' order (casters' entries are ignored).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        :math:`(v_x, v_y, \omega)`, m/s, m/s, rad/s.

    Examples
    --------
    >>> wheels = diff_drive_wheels(0.1, 0.02)           # L, R, caster C
    >>> body_twist(wheels, [7.5, 12.5, 123.0])          # the caster's entry is ignored
    array([0.2, 0. , 1. ])
    """
    w = _wheels(wheels)
    phi = V.shaped("rates", rates, (len(w),))
    measured = [i for i, wh in enumerate(w) if wh.kind != "caster"]
    if not measured:
        raise ValueError("wheels must include at least one wheel that is not a caster")
    J = rolling_matrix([w[i] for i in measured])
    radii = np.array([w[i].wheel_radius for i in measured])
    pinv = np.linalg.pinv(J, rcond=RANK_TOLERANCE)
    return (phi[..., measured] * radii) @ pinv.T + 0.0


def steer_for_twist(wheels: Sequence[WheelConstraint],
                    twist: Twist | npt.ArrayLike) -> tuple[WheelConstraint, ...]:
    r"""The wheels with every steered wheel and caster turned to roll along its contact
    velocity, so that the twist leaves them no sideways slip.

    .. math:: \delta_i = \operatorname{atan2}(v_y + \omega x_i,\ v_x - \omega y_i) - \psi_i^0

    A steered wheel takes the angle folded into :math:`(-\pi/2, \pi/2]` (it rolls backwards
    rather than turning round); a caster trails, so it takes the angle in
    :math:`(-\pi, \pi]`. A wheel whose contact point is at rest (at the ICR) keeps its
    steering. Fixed and Swedish wheels are returned unchanged.

    Parameters
    ----------
    wheels : sequence of WheelConstraint
    twist : Twist or array_like, shape (3,)
        One twist, m/s, m/s, rad/s.

    Returns
    -------
    tuple of WheelConstraint

    Examples
    --------
    A single steered wheel 1 m ahead of the reference point, turning left about it:

    >>> (w,) = steer_for_twist([WheelConstraint("F", (1.0, 0.0), kind="steered")],
    ...                        (1.0, 0.0, 1.0))
    >>> round(math.degrees(w.steering), 6)
    45.0
    """
    w = _wheels(wheels)
    xi = V.twist("twist", twist)
    vx, vy, omega = (float(c) for c in xi)
    out = []
    for wh in w:
        if wh.kind in ("steered", "caster"):
            x, y = wh.position
            cx, cy = vx - omega * y, vy + omega * x
            if math.hypot(cx, cy) > 1e-12:
                angle = math.atan2(cy, cx) - wh.heading
                if wh.kind == "steered":
                    delta = fold_half_turn(angle)[0]
                else:
                    delta = math.remainder(angle, 2 * math.pi)
                    delta = math.pi if delta <= -math.pi else delta
                wh = wh.steered_to(delta)
        out.append(wh)
    return tuple(out)


class Mobility(NamedTuple):
    r"""Result of :func:`mobility`: Siegwart et al.'s degrees and the ranks behind them."""

    #: :math:`\delta_m = 3 - \operatorname{rank} C_1`: independent motions without steering.
    degree_of_mobility: int
    #: :math:`\delta_s`: independent steering freedoms.
    degree_of_steerability: int
    #: :math:`\delta_M = \delta_m + \delta_s`.
    degree_of_manoeuvrability: int
    #: :math:`\operatorname{rank} C_1` at the current steering.
    rank_sliding: int
    #: :math:`\operatorname{rank} C_{1f}` (fixed wheels).
    rank_fixed: int
    #: Generic :math:`\operatorname{rank} C_{1s}` (steered wheels, over their steering).
    rank_steered: int


#: Steering angles (rad) at which the generic rank of the steered rows is evaluated: any
#: steering outside a set of measure zero gives the generic rank; three unrelated sets make a
#: coincidence impossible in practice.
_GENERIC_STEERING = ((0.3183, -0.8776, 1.1348, 0.5403, -0.2322, 1.3817, -0.6536, 0.9129),
                     (-1.2107, 0.4161, 0.7568, -0.9589, 0.2794, -0.1455, 1.0462, -0.5064),
                     (0.8415, 1.4142, -0.3010, -1.1071, 0.6931, -0.7854, 0.1107, 1.2490))


def mobility(wheels: Sequence[WheelConstraint]) -> Mobility:
    r"""Degrees of mobility, steerability and manoeuvrability of a wheel arrangement.

    Following Siegwart et al. :cite:`siegwart2011` (section 3.3):

    - degree of mobility, at the wheels' current steering:
      :math:`\delta_m = 3 - \operatorname{rank} C_1(\delta)`, the dimension of the twists
      :math:`\xi` with :math:`C_1\xi = 0`, which the wheels can follow by rolling alone;
    - degree of steerability: the independent steering freedoms,
      :math:`\delta_s = \min(\operatorname{rank} C_{1s},\ 2 - \operatorname{rank} C_{1f})`
      (at least 0), with :math:`\operatorname{rank} C_{1s}` the rank of the steered wheels'
      rows for generic steering angles. Steering moves the instantaneous centre of rotation
      (ICR), which has 2 coordinates; fixed wheels pin it to their axle line
      (:math:`\operatorname{rank} C_{1f} = 1`) or to a point (rank 2), leaving
      :math:`2 - \operatorname{rank} C_{1f}` freedoms for the steering to use. This is
      Siegwart et al.'s count for the designs they discuss: coordinated (Ackermann-like)
      steered wheels beside a fixed axle give :math:`\delta_s = 1`, two or more independent
      steered wheels and no fixed wheel give 2;
    - degree of manoeuvrability :math:`\delta_M = \delta_m + \delta_s`.

    Swedish wheels and casters add no rows: a vehicle on them alone has :math:`\delta_m = 3`.

    Parameters
    ----------
    wheels : sequence of WheelConstraint

    Returns
    -------
    Mobility
        ``(degree_of_mobility, degree_of_steerability, degree_of_manoeuvrability,
        rank_sliding, rank_fixed, rank_steered)``.

    Examples
    --------
    >>> geometry = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> mobility(mecanum_wheels(geometry))[:3]
    (3, 0, 3)
    >>> mobility(rover_wheels())[:3]   # like a car: one motion, one steering freedom
    (1, 1, 2)
    >>> skid = skid_steer_wheels(half_wheelbase=0.05, half_track=0.06,
    ...                   wheel_radius=0.04)
    >>> mobility(skid)[:3]   # straight ahead only
    (1, 0, 1)
    """
    w = _wheels(wheels)
    rank_c1 = _rank(sliding_matrix(w))
    fixed = [wh for wh in w if wh.kind == "fixed"]
    steered = [wh for wh in w if wh.kind == "steered"]
    rank_f = _rank(np.array([sliding_row(wh) for wh in fixed]).reshape(len(fixed), 3))
    rank_s = 0
    if steered:
        trials = [steered]
        for angles in _GENERIC_STEERING:
            n = len(angles)
            trials.append([wh.steered_to(angles[i % n] + 0.1 * (i // n))
                           for i, wh in enumerate(steered)])
        rank_s = max(_rank(np.array([sliding_row(wh) for wh in t])) for t in trials)
    delta_m = 3 - rank_c1
    delta_s = max(0, min(rank_s, 2 - rank_f))
    return Mobility(delta_m, delta_s, delta_m + delta_s, rank_c1, rank_f, rank_s)


def admissible_twists(wheels: Sequence[WheelConstraint]) -> np.ndarray:
    r"""An orthonormal basis of the twists the wheels can follow without sliding sideways:
    the null space of :math:`C_1` at the current steering, shape (3, :math:`\delta_m`).

    Examples
    --------
    A differential drive can move forward and turn, not sideways:

    >>> admissible_twists(diff_drive_wheels(0.1, 0.02)).round(12) + 0.0
    array([[1., 0.],
           [0., 0.],
           [0., 1.]])
    >>> skid = skid_steer_wheels(half_wheelbase=0.05, half_track=0.06,
    ...                   wheel_radius=0.04)
    >>> admissible_twists(skid).round(12).T + 0.0
    array([[1., 0., 0.]])
    """
    w = _wheels(wheels)
    c1 = sliding_matrix(w)
    rank = _rank(c1)
    if rank == 0:
        return np.eye(3)
    _, _, vt = np.linalg.svd(c1)
    basis = vt[rank:].T
    # A readable basis: reduced row echelon form of the basis' transpose, orthonormalised.
    q, _ = np.linalg.qr(_echelon(basis.T).T)
    for j in range(q.shape[1]):  # sign: first non-zero entry positive
        col = q[:, j]
        k = int(np.argmax(np.abs(col) > 1e-12))
        if col[k] < 0:
            q[:, j] = -col
    return q + 0.0


def _echelon(m: np.ndarray) -> np.ndarray:
    """Reduced row echelon form (rows span the same space, pivots of 1)."""
    a = np.array(m, dtype=float)
    rows, cols = a.shape
    r = 0
    for c in range(cols):
        if r == rows:
            break
        p = r + int(np.argmax(np.abs(a[r:, c])))
        if abs(a[p, c]) < 1e-12:
            continue
        a[[r, p]] = a[[p, r]]
        a[r] /= a[r, c]
        for i in range(rows):
            if i != r:
                a[i] -= a[i, c] * a[r]
        r += 1
    return a


# --------------------------------------------------------------------------------------------
# The book's vehicles
# --------------------------------------------------------------------------------------------

def diff_drive_wheels(track_width: float, wheel_radius: float, *, caster: bool = True,
                      caster_offset: float | None = None) -> tuple[WheelConstraint, ...]:
    r"""A differential drive: fixed wheels ("L", "R") at :math:`(0, \pm W/2)` and, if
    ``caster``, a caster "C" at (-caster_offset, 0) (radius 0.4 :math:`r_w`, trailing
    straight).

    Parameters
    ----------
    track_width : float
        :math:`W`, wheel to wheel, m (> 0).
    wheel_radius : float
        :math:`r_w`, m (> 0).
    caster : bool
        Include the caster.
    caster_offset : float, optional
        Distance of the caster behind the axle, m (> 0; default :math:`W/2`, as the sandbox).

    Examples
    --------
    >>> [(w.name, w.kind, w.position) for w in diff_drive_wheels(0.1, 0.02)]
    [('L', 'fixed', (0.0, 0.05)), ('R', 'fixed', (0.0, -0.05)), ('C', 'caster', (-0.05, 0.0))]
    """
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    if not isinstance(caster, bool):
        raise ValueError(f"caster must be True or False, got {caster!r}")
    wheels = [WheelConstraint("L", (0.0, W / 2), 0.0, r, "fixed"),
              WheelConstraint("R", (0.0, -W / 2), 0.0, r, "fixed")]
    if caster:
        d = 0.5 * W if caster_offset is None else V.positive("caster_offset", caster_offset)
        wheels.append(WheelConstraint("C", (-d, 0.0), 0.0, 0.4 * r, "caster"))
    return tuple(wheels)


def skid_steer_wheels(*, half_wheelbase: float, half_track: float,
                      wheel_radius: float) -> tuple[WheelConstraint, ...]:
    r"""A four-wheel skid steer: fixed wheels FL :math:`(a, b)`, FR :math:`(a, -b)`, RL
    :math:`(-a, b)`, RR :math:`(-a, -b)`, :math:`a` = half wheelbase, :math:`b` = half track
    (m), all rolling along x. Keyword-only, like
    :class:`~wheelkin.mecanum.MecanumGeometry`.

    Examples
    --------
    >>> skid = skid_steer_wheels(half_wheelbase=0.05, half_track=0.06,
    ...                   wheel_radius=0.04)
    >>> [w.position for w in skid]
    [(0.05, 0.06), (0.05, -0.06), (-0.05, 0.06), (-0.05, -0.06)]
    """
    b = V.positive("half_track", half_track)
    a = V.positive("half_wheelbase", half_wheelbase)
    r = V.positive("wheel_radius", wheel_radius)
    return tuple(WheelConstraint(name, (sx * a, sy * b), 0.0, r, "fixed")
                 for name, sx, sy in (("FL", 1, 1), ("FR", 1, -1), ("RL", -1, 1),
                                      ("RR", -1, -1)))


def mecanum_wheels(geometry: MecanumGeometry) -> tuple[WheelConstraint, ...]:
    r"""The mecanum vehicle of :class:`wheelkin.mecanum.MecanumGeometry`: Swedish wheels FL,
    FR, RL, RR at :math:`(\pm a, \pm b)`, rollers in the X arrangement.

    The chapter's :math:`\gamma` (between roller axis and axle, unsigned) becomes the signed
    :math:`\gamma_i = -s_i\gamma` with :math:`s = (-1, +1, +1, -1)`
    (:data:`wheelkin.mecanum.ROLLER_SIGNS`): :math:`+\gamma` for FL and RR, :math:`-\gamma` for
    FR and RL. Then :func:`wheel_rates` is :func:`wheelkin.mecanum.inverse_kinematics`.

    Examples
    --------
    >>> geometry = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> wheels = mecanum_wheels(geometry)
    >>> [round(math.degrees(w.roller_angle)) for w in wheels]
    [45, -45, -45, 45]
    """
    if not isinstance(geometry, MecanumGeometry):
        raise ValueError(f"geometry must be a MecanumGeometry, got {type(geometry).__name__}")
    a, b, r = geometry.half_wheelbase, geometry.half_track, geometry.wheel_radius
    signs = {"FL": (1, 1), "FR": (1, -1), "RL": (-1, 1), "RR": (-1, -1)}
    return tuple(WheelConstraint(name, (signs[name][0] * a, signs[name][1] * b), 0.0, r,
                                 "swedish", roller_angle=-float(s) * geometry.roller_angle)
                 for name, s in zip(MECANUM_WHEEL_NAMES, ROLLER_SIGNS, strict=True))


def rover_wheels(geometry: rover.RoverGeometry | None = None, wheel_radius: float = 0.06, *,
                 turning_radius: float = math.inf) -> tuple[WheelConstraint, ...]:
    r"""The six-wheel rover of :class:`wheelkin.rover.RoverGeometry`, in metres and REP-103.

    Wheels LF, LM, LB, RF, RM, RB at the document's positions
    (:func:`wheelkin.rover.wheel_positions`, in metres); the middle wheels fixed, the corners
    steered for a turn of signed radius ``turning_radius`` about a centre on the middle
    wheels' axle (the document's corner angles, :func:`wheelkin.rover.corner_angles`, with
    our sign: :math:`\delta_i = -\delta_i^{doc}`, positive to the left).

    Parameters
    ----------
    geometry : RoverGeometry, optional
        In inches or metres (its ``unit``); default :data:`wheelkin.rover.OSR_GEOMETRY`.
    wheel_radius : float
        :math:`r_w`, m (> 0); the document gives none: 0.06 m is the sandbox's estimate.
    turning_radius : float
        m, > 0 for a left turn (REP-103), :math:`\pm\infty` straight; at least the corner
        stops' :func:`wheelkin.rover.min_turning_radius` in size. Keyword-only: it is a
        length, like ``wheel_radius`` beside it.

    Examples
    --------
    The document's right turn of 30 in (0.762 m):

    >>> wheels = rover_wheels(turning_radius=-0.762)
    >>> [round(math.degrees(w.steering), 3) for w in wheels]
    [-15.74, 0.0, 15.74, -24.779, 0.0, 24.779]
    """
    g = rover.OSR_GEOMETRY if geometry is None else geometry
    if not isinstance(g, rover.RoverGeometry):
        raise ValueError(f"geometry must be a RoverGeometry, got {type(g).__name__}")
    g = g.in_unit("in")  # the document's corner angles are in inches; positions in metres
    r = V.positive("wheel_radius", wheel_radius)
    turn = V.finite_array("turning_radius", turning_radius, allow_inf=True)
    smallest = rover.min_turning_radius(g) * INCH
    if turn.ndim != 0 or abs(float(turn)) < smallest * (1 - 1e-12):
        raise ValueError(f"turning_radius must be one number with |turning_radius| >= "
                         f"{smallest:.6g} m (the corner stops), or +-inf; "
                         f"got {turning_radius!r}")
    turn_doc = -float(turn) / INCH  # the document's radius: inches, positive to the right
    corners = dict(zip(rover.CORNER_NAMES, -np.asarray(rover.corner_angles(turn_doc, g)),
                       strict=True))
    positions = rover.wheel_positions(g) * INCH
    return tuple(
        WheelConstraint(name, tuple(positions[i]), 0.0, r,
                        "steered" if name in corners else "fixed",
                        steering=float(corners.get(name, 0.0)) + 0.0)
        for i, name in enumerate(rover.WHEEL_NAMES))


def car_wheels(*, wheelbase: float, track_width: float, wheel_radius: float,
               turning_radius: float = math.inf) -> tuple[WheelConstraint, ...]:
    r"""A car-like vehicle: steered FL :math:`(L, W/2)`, FR :math:`(L, -W/2)`, fixed RL
    :math:`(0, W/2)`, RR :math:`(0, -W/2)` (the rear-axle midpoint is the origin), the front
    wheels steered to the ideal Ackermann angles of a turn of signed radius ``turning_radius``
    (:func:`wheelkin.carlike.ackermann_angles`; ``inf`` straight).

    Its sliding rows have rank 2 for any radius: one degree of mobility, one of steering
    (the car of :mod:`wheelkin.carlike`).

    Examples
    --------
    >>> wheels = car_wheels(wheelbase=0.33, track_width=0.27, wheel_radius=0.05,
    ...                     turning_radius=1.0)
    >>> [round(math.degrees(w.steering), 3) for w in wheels]
    [20.882, 16.212, 0.0, 0.0]
    """
    from wheelkin import carlike

    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    if V.finite_array("turning_radius", turning_radius, allow_inf=True).ndim != 0:
        raise ValueError("turning_radius must be one number (inf: straight), got "
                         f"{turning_radius!r}")
    try:
        left, right = carlike.ackermann_angles(turning_radius, wheelbase=L, track_width=W)
    except ValueError as exc:
        raise ValueError(str(exc).replace("radius", "turning_radius", 1)) from None
    return (WheelConstraint("FL", (L, W / 2), 0.0, r, "steered", steering=float(left)),
            WheelConstraint("FR", (L, -W / 2), 0.0, r, "steered", steering=float(right)),
            WheelConstraint("RL", (0.0, W / 2), 0.0, r, "fixed"),
            WheelConstraint("RR", (0.0, -W / 2), 0.0, r, "fixed"))
