r"""The four-wheel mecanum vehicle: inverse and forward kinematics, for any roller angle.

Frame and units: our frame (REP-103: x forward, y left, yaw rate :math:`\omega`
counter-clockwise positive), SI (m, s, rad). Wheel order is always **FL, FR, RL, RR**
(front-left, front-right, rear-left, rear-right).

Geometry (the chapter's symbols)

- :math:`r_w` wheel radius (``wheel_radius``);
- :math:`a` half wheelbase, from the centre to the front and rear axles along x
  (``half_wheelbase``); the wheels sit at :math:`x_i = \pm a`;
- :math:`b` half track, from the centre to each wheel's mid-plane along y (``half_track``);
  the wheels sit at :math:`y_i = \pm b`;
- :math:`\gamma` the angle between a roller's axis and its wheel's axle (``roller_angle``,
  :math:`\pi/4` for the common mecanum wheel; an omni wheel would be :math:`\pi/2`).

The rollers are in the "X" arrangement: seen from above, the (upper) rollers of the four wheels
point towards the vehicle's centre, so the rollers touching the ground form an "O". Then a
forward-and-left twist needs FL and RR slower than FR and RL.

Rolling constraint of wheel *i*, at :math:`(x_i, y_i)`, whose contact point moves at
:math:`(v_x - \omega y_i,\ v_y + \omega x_i)`: the rollers absorb any velocity across their
axes; the component along a roller's axis must come from the hub. That gives

.. math::

    \dot\varphi_i = \frac{1}{r_w}\left[(v_x - \omega y_i) + s_i \cot\gamma\,(v_y + \omega x_i)
    \right],\qquad s = (-1, +1, +1, -1)\ \text{for (FL, FR, RL, RR)}

and, with :math:`k = b + a\cot\gamma` (:math:`k = a + b` at 45 degrees),

.. math::

    \begin{aligned}
    \dot\varphi_{FL} &= (v_x - v_y\cot\gamma - k\,\omega)/r_w, &
    \dot\varphi_{FR} &= (v_x + v_y\cot\gamma + k\,\omega)/r_w, \\
    \dot\varphi_{RL} &= (v_x + v_y\cot\gamma - k\,\omega)/r_w, &
    \dot\varphi_{RR} &= (v_x - v_y\cot\gamma + k\,\omega)/r_w.
    \end{aligned}

The 4x3 matrix :math:`J` of this map has orthogonal columns, so its pseudo-inverse (the
forward map) is a scaled transpose, and the one wheel combination it cannot produce,
:math:`(+1, +1, -1, -1)` (front wheels against rear wheels), is its null space: wheels
turning that way fight each other and the vehicle does not move.

The mecanum simulator document :cite:`florida2014mecanum` uses X right, Y forward and feet;
the converters between its frame and ours live in :mod:`wheelkin.frames`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as V
from wheelkin._kernels import arc_factors, shift_twist
from wheelkin._records import Stack, _is_one
from wheelkin.frames import Pose, Twist, wrap_angle
from wheelkin.units import FOOT

__all__ = [
    "DOCUMENT_MAX_SPEED",
    "EXAMPLE_GEOMETRY",
    "FIGHTING_PATTERN",
    "ROLLER_SIGNS",
    "SPIN_SIGNS",
    "WHEEL_NAMES",
    "MecanumGeometry",
    "SpeedLimit",
    "circle_speed",
    "circle_twist",
    "desaturate",
    "fighting_component",
    "forward_kinematics",
    "forward_matrix",
    "go_to_point_twist",
    "grip_usage",
    "inverse_kinematics",
    "inverse_matrix",
    "limit_speed",
    "max_rim_speed",
]

#: Wheel order of every array in this module.
WHEEL_NAMES: tuple[str, ...] = ("FL", "FR", "RL", "RR")
#: :math:`s_i`, the sign of the :math:`v_y` term of each wheel (FL, FR, RL, RR), X arrangement.
ROLLER_SIGNS = np.array([-1.0, 1.0, 1.0, -1.0])
#: :math:`\sigma_i`, the sign of the :math:`\omega` term of each wheel (FL, FR, RL, RR).
SPIN_SIGNS = np.array([-1.0, 1.0, -1.0, 1.0])
#: Wheel rates (FL, FR, RL, RR) that produce no motion: the null space of the inverse matrix.
FIGHTING_PATTERN = np.array([1.0, 1.0, -1.0, -1.0])
#: The document's top speed, 15 ft/s, in m/s (4.572 m/s).
DOCUMENT_MAX_SPEED = 15.0 * FOOT


@dataclass(frozen=True, kw_only=True)
class MecanumGeometry:
    r"""Dimensions of a four-wheel mecanum vehicle (m, rad), validated on construction.

    Keyword-only, like every set of three vehicle lengths in the library (a port cannot
    swap two of them silently); the fields come front-to-back, side-to-side, wheel radius.

    Parameters
    ----------
    half_wheelbase : float
        :math:`a`, centre to the front (and rear) axle along x, m, > 0.
    half_track : float
        :math:`b`, centre to each wheel's mid-plane along y, m, > 0.
    wheel_radius : float
        :math:`r_w`, m, > 0.
    roller_angle : float
        :math:`\gamma`, angle between a roller's axis and the wheel's axle, rad, in
        (0, pi/2); default pi/4.

    Examples
    --------
    >>> g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    >>> round(g.k, 6)
    0.35
    >>> MecanumGeometry(wheel_radius=0.05, half_wheelbase=-0.2, half_track=0.15)
    Traceback (most recent call last):
    ...
    ValueError: half_wheelbase must be a finite number > 0, got -0.2
    """

    half_wheelbase: float
    half_track: float
    wheel_radius: float
    roller_angle: float = math.pi / 4

    def __post_init__(self) -> None:
        for name in ("half_wheelbase", "half_track", "wheel_radius"):
            object.__setattr__(self, name, V.positive(name, getattr(self, name)))
        gamma = V.finite("roller_angle", self.roller_angle)
        if not 0.0 < gamma < math.pi / 2:
            raise ValueError(
                f"roller_angle must be in (0, pi/2) rad (exclusive), got {self.roller_angle!r}"
            )
        object.__setattr__(self, "roller_angle", gamma)

    @property
    def lateral_factor(self) -> float:
        r""":math:`\cot\gamma`: how much a sideways velocity turns the wheels (1 at 45 deg)."""
        return 1.0 / math.tan(self.roller_angle)

    @property
    def k(self) -> float:
        r""":math:`k = b + a\cot\gamma`, m: the yaw lever arm (:math:`a + b` at 45 deg)."""
        return self.half_track + self.half_wheelbase * self.lateral_factor


#: The vehicle the chapter uses (our choice; the document gives no dimensions): 6-inch wheels
#: (r_w = 3 in), axles 1 ft ahead of and behind the centre, wheels 9 in either side of it.
EXAMPLE_GEOMETRY = MecanumGeometry(
    half_wheelbase=1.0 * FOOT, half_track=0.75 * FOOT, wheel_radius=0.25 * FOOT
)


def _geometry(geometry) -> MecanumGeometry:
    if not isinstance(geometry, MecanumGeometry):
        raise ValueError(
            f"geometry must be a MecanumGeometry, got {type(geometry).__name__}"
        )
    return geometry


def _twist_or_components(vx, vy, omega, geometry, function: str = "inverse_kinematics"):
    """(vx, vy, omega, geometry) from either form of :func:`inverse_kinematics` (or of
    :func:`max_rim_speed`, named by ``function``).

    ``(twist, geometry)``: the twist's columns; ``(vx, vy, omega, geometry)``: as given. A twist
    where a component is meant, a missing argument or one too many is a ``TypeError`` (also a
    ``ValueError``) naming the parameter.
    """
    forms = f"{function}(twist, geometry) or {function}(vx, vy, omega, geometry)"
    if omega is None and geometry is None and vy is not None:  # (twist, geometry)
        if isinstance(vx, Pose):
            raise V.InputTypeError(f"twist must be a Twist, a tuple (vx, vy, omega) or an array "
                                   f"of shape (..., 3), got a Pose; use {forms}")
        if isinstance(vx, Twist):
            arr = vx.as_array()
        else:
            arr = V.finite_array("twist", vx)
            if arr.ndim == 0 or arr.shape[-1] != 3:
                raise V.InputTypeError(
                    f"twist must be a Twist, a tuple (vx, vy, omega) or an array of shape "
                    f"(..., 3), got shape {arr.shape}; use {forms}")
        return arr[..., 0], arr[..., 1], arr[..., 2], vy
    for name, value in (("vx", vx), ("vy", vy), ("omega", omega)):
        if isinstance(value, Twist | Pose | MecanumGeometry):
            raise V.InputTypeError(f"{name} must be a number or an array of numbers, got a "
                                   f"{type(value).__name__}; use {forms}")
    for name, value in (("vy", vy), ("omega", omega), ("geometry", geometry)):
        if value is None:
            raise V.InputTypeError(f"{name} is missing: use {forms}")
    return vx, vy, omega, geometry


def _broadcast(**arrays: np.ndarray) -> list[np.ndarray]:
    return V.broadcast(**arrays)


def inverse_matrix(geometry: MecanumGeometry) -> np.ndarray:
    r"""The 4x3 matrix :math:`J` with :math:`\dot{\boldsymbol\varphi} = J\,(v_x, v_y, \omega)^T`.

    Rows FL, FR, RL, RR; columns :math:`v_x, v_y, \omega`:

    .. math::

        J = \frac{1}{r_w}\begin{bmatrix}
        1 & -\cot\gamma & -k\\ 1 & \cot\gamma & k\\ 1 & \cot\gamma & -k\\ 1 & -\cot\gamma & k
        \end{bmatrix},\qquad k = b + a\cot\gamma .

    Parameters
    ----------
    geometry : MecanumGeometry

    Returns
    -------
    numpy.ndarray, shape (4, 3)
        Entries in 1/m (columns 1, 2) and 1 (column 3): rad/s of wheel per m/s or rad/s.

    Examples
    --------
    >>> inverse_matrix(MecanumGeometry(wheel_radius=0.5, half_wheelbase=0.2, half_track=0.3))
    array([[ 2., -2., -1.],
           [ 2.,  2.,  1.],
           [ 2.,  2., -1.],
           [ 2., -2.,  1.]])
    """
    g = _geometry(geometry)
    cols = np.column_stack(
        [np.ones(4), ROLLER_SIGNS * g.lateral_factor, SPIN_SIGNS * g.k]
    )
    return cols / g.wheel_radius


def forward_matrix(geometry: MecanumGeometry) -> np.ndarray:
    r"""The 3x4 pseudo-inverse :math:`J^+ = (J^TJ)^{-1}J^T` of :func:`inverse_matrix`.

    The columns of :math:`J` are orthogonal, so

    .. math::

        J^+ = \frac{r_w}{4}\begin{bmatrix}
        1 & 1 & 1 & 1\\
        -\tan\gamma & \tan\gamma & \tan\gamma & -\tan\gamma\\
        -1/k & 1/k & -1/k & 1/k
        \end{bmatrix}.

    Columns FL, FR, RL, RR; rows :math:`v_x` (m/s), :math:`v_y` (m/s), :math:`\omega`
    (rad/s) per rad/s of wheel.

    Examples
    --------
    >>> g = MecanumGeometry(wheel_radius=0.5, half_wheelbase=0.2, half_track=0.3)
    >>> forward_matrix(g)
    array([[ 0.125,  0.125,  0.125,  0.125],
           [-0.125,  0.125,  0.125, -0.125],
           [-0.25 ,  0.25 , -0.25 ,  0.25 ]])
    >>> np.allclose(forward_matrix(g) @ inverse_matrix(g), np.eye(3))
    True
    """
    g = _geometry(geometry)
    rows = np.vstack(
        [np.ones(4), ROLLER_SIGNS / g.lateral_factor, SPIN_SIGNS / g.k]
    )
    return rows * (g.wheel_radius / 4.0)


#: One body twist given as itself: a :class:`~wheelkin.frames.Twist` or a tuple of three numbers.
OneTwist = Twist | tuple[float, float, float]


@overload
def inverse_kinematics(twist: OneTwist | Stack, geometry: MecanumGeometry, /, *,
                       centre_of_rotation: ArrayLike | None = None) -> NDArray[np.float64]: ...
@overload
def inverse_kinematics(vx: ArrayLike, vy: ArrayLike, omega: ArrayLike,
                       geometry: MecanumGeometry, *,
                       centre_of_rotation: ArrayLike | None = None) -> NDArray[np.float64]: ...
def inverse_kinematics(vx: Any, vy: Any = None, omega: Any = None, geometry: Any = None, *,
                       centre_of_rotation: ArrayLike | None = None) -> NDArray[np.float64]:
    r"""Wheel angular rates (FL, FR, RL, RR), rad/s, that produce the body twist.

    .. math::

        \dot\varphi_{FL} = \frac{v_x - v_y\cot\gamma - k\omega}{r_w},\
        \dot\varphi_{FR} = \frac{v_x + v_y\cot\gamma + k\omega}{r_w},\
        \dot\varphi_{RL} = \frac{v_x + v_y\cot\gamma - k\omega}{r_w},\
        \dot\varphi_{RR} = \frac{v_x - v_y\cot\gamma + k\omega}{r_w}

    with :math:`k = b + a\cot\gamma`; at :math:`\gamma = 45^\circ`, :math:`\cot\gamma = 1` and
    :math:`k = a + b`. Positive rates roll the wheel forward (+x).

    With a ``centre_of_rotation`` :math:`c = (c_x, c_y)` (as WPILib's
    ``MecanumDriveKinematics.toWheelSpeeds`` has), :math:`(v_x, v_y)` is the velocity of the
    point :math:`c` and the body turns about it at :math:`\omega`; the centre's velocity is
    then :math:`(v_x + \omega c_y,\; v_y - \omega c_x)`, which goes into the equations above.

    Two forms: ``inverse_kinematics(twist, geometry)`` with a :class:`~wheelkin.frames.Twist`
    (or a tuple of three numbers, or an array of twists of shape (..., 3)), and
    ``inverse_kinematics(vx, vy, omega, geometry)`` with the components. Any other
    combination is a ``TypeError`` naming the parameter.

    Parameters
    ----------
    twist : Twist, tuple of three numbers or array_like of shape (..., 3)
        (vx m/s, vy m/s, omega rad/s), body frame; the first form's only twist argument.
    vx, vy : float or array_like
        Body velocity of the centre (or of ``centre_of_rotation``), m/s (x forward, y left).
    omega : float or array_like
        Yaw rate, rad/s, counter-clockwise positive.
        The three are broadcast together.
    geometry : MecanumGeometry
    centre_of_rotation : array_like, shape (2,), optional
        :math:`(c_x, c_y)`, m, in the body frame; default the centre (0, 0).

    Returns
    -------
    numpy.ndarray, shape (..., 4)
        Wheel rates in the order FL, FR, RL, RR, rad/s.

    Examples
    --------
    Strafe left at 1 m/s on wheels of radius 0.05 m:

    >>> g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    >>> inverse_kinematics(0.0, 1.0, 0.0, g)
    array([-20.,  20.,  20., -20.])
    >>> inverse_kinematics(Twist(vx=0.0, vy=1.0, omega=0.0), g)
    array([-20.,  20.,  20., -20.])
    >>> inverse_kinematics([1.0, 0.0], 0.0, [0.0, 1.0], g)
    array([[20., 20., 20., 20.],
           [-7.,  7., -7.,  7.]])

    Turning about the front-left wheel (a = 0.2 m ahead, b = 0.15 m left) leaves it still:

    >>> np.round(inverse_kinematics(0.0, 0.0, 1.0, g, centre_of_rotation=(0.2, 0.15)), 12) + 0
    array([ 0.,  6., -8., 14.])
    """
    is_twist = omega is None and geometry is None
    vx, vy, omega, geometry = _twist_or_components(vx, vy, omega, geometry)
    g = _geometry(geometry)
    vx_a, vy_a, w_a = _broadcast(vx=V.finite_array("vx", vx), vy=V.finite_array("vy", vy),
                                 omega=V.finite_array("omega", omega))
    given = "twist" if is_twist else "vx, vy, omega"
    names = f"{given} and the geometry"
    with np.errstate(all="ignore"):  # an overflow is refused below, naming the inputs
        if centre_of_rotation is not None:
            c = V.finite_array("centre_of_rotation", centre_of_rotation)
            if c.shape != (2,):
                raise ValueError("centre_of_rotation must have shape (2,): (c_x, c_y) in m, "
                                 f"got shape {c.shape}")
            vx_a, vy_a, w_a = shift_twist(vx_a, vy_a, w_a, c[0], c[1])
            names = f"{given}, centre_of_rotation and the geometry"
        twist = np.stack([vx_a, vy_a, w_a], axis=-1)
        rates = twist @ inverse_matrix(g).T
    return V.finite_result(names, rates)


@overload
def forward_kinematics(wheel_rates: tuple[float, float, float, float] | list[float],
                       geometry: MecanumGeometry) -> Twist: ...
@overload
def forward_kinematics(wheel_rates: list[list[float]], geometry: MecanumGeometry
                       ) -> NDArray[np.float64]: ...
@overload
def forward_kinematics(wheel_rates: NDArray[Any], geometry: MecanumGeometry
                       ) -> Twist | NDArray[np.float64]: ...
def forward_kinematics(wheel_rates: ArrayLike, geometry: MecanumGeometry
                       ) -> Twist | NDArray[np.float64]:
    r"""The body twist (vx, vy, omega) that best explains four wheel rates (least squares).

    .. math::

        \begin{aligned}
        v_x &= \tfrac{r_w}{4}(\dot\varphi_{FL} + \dot\varphi_{FR} + \dot\varphi_{RL}
               + \dot\varphi_{RR}),\\
        v_y &= \tfrac{r_w\tan\gamma}{4}(-\dot\varphi_{FL} + \dot\varphi_{FR} + \dot\varphi_{RL}
               - \dot\varphi_{RR}),\\
        \omega &= \tfrac{r_w}{4k}(-\dot\varphi_{FL} + \dot\varphi_{FR} - \dot\varphi_{RL}
               + \dot\varphi_{RR}).
        \end{aligned}

    Exact (the inverse of :func:`inverse_kinematics`) when the rates are consistent, i.e. when
    their :func:`fighting_component` is zero; otherwise that component is ignored (it moves
    nothing).

    Parameters
    ----------
    wheel_rates : array_like, shape (..., 4)
        Wheel angular rates FL, FR, RL, RR, rad/s.
    geometry : MecanumGeometry

    Returns
    -------
    Twist for one set of four rates (shape (4,)), numpy.ndarray of shape (..., 3) for a stack
        (vx m/s, vy m/s, omega rad/s) in the body frame. A Twist unpacks and indexes like the
        array did; take ``np.asarray(...)`` for arithmetic (``twist * 2`` repeats the tuple).
        The static type is ``Twist`` for a list or tuple of four numbers, an array for a
        nested list; an ``ndarray``'s shape is not known to a type checker, so its result
        is typed ``Twist | ndarray``.

    Examples
    --------
    >>> g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    >>> forward_kinematics([-20.0, 20.0, 20.0, -20.0], g)
    Twist(vx=0.0, vy=1.0, omega=0.0)
    >>> forward_kinematics([10.0, 10.0, -10.0, -10.0], g)  # the wheels fight: no motion
    Twist(vx=0.0, vy=0.0, omega=0.0)
    >>> np.round(forward_kinematics([[20.0, 20.0, 20.0, 20.0], [-7.0, 7.0, -7.0, 7.0]], g), 12) + 0
    array([[1., 0., 0.],
           [0., 0., 1.]])
    """
    g = _geometry(geometry)
    rates = V.shaped("wheel_rates", wheel_rates, (4,))
    out = rates @ forward_matrix(g).T + 0.0
    return Twist(*out.tolist()) if out.ndim == 1 else out


@overload
def fighting_component(wheel_rates: float) -> float: ...
@overload
def fighting_component(wheel_rates: Stack) -> NDArray[np.float64]: ...
def fighting_component(wheel_rates: ArrayLike) -> float | NDArray[np.float64]:
    r"""How much of the wheel rates is the no-motion pattern (+1, +1, -1, -1), rad/s.

    Any four rates split uniquely into a part that moves the vehicle and
    :math:`\nu\,(1, 1, -1, -1)` (FL, FR, RL, RR) with

    .. math:: \nu = \tfrac14(\dot\varphi_{FL} + \dot\varphi_{FR} - \dot\varphi_{RL}
              - \dot\varphi_{RR}).

    A non-zero :math:`\nu` cannot be satisfied by rolling: the rollers must slip (and the wheels
    push against each other). The pattern is the same for every roller angle and geometry.

    Parameters
    ----------
    wheel_rates : array_like, shape (..., 4)
        FL, FR, RL, RR, rad/s.

    Returns
    -------
    float, or numpy.ndarray of shape (...) for shape (..., 4)

    Examples
    --------
    >>> fighting_component([12.0, 10.0, -8.0, -10.0])
    10.0
    """
    rates = V.shaped("wheel_rates", wheel_rates, (4,))
    return V.scalar_or_array(rates @ FIGHTING_PATTERN / 4.0)


@overload
def max_rim_speed(twist: OneTwist | list[float], geometry: MecanumGeometry, /) -> float: ...
@overload
def max_rim_speed(twist: list[list[float]], geometry: MecanumGeometry, /
                  ) -> NDArray[np.float64]: ...
@overload
def max_rim_speed(twist: NDArray[Any], geometry: MecanumGeometry, /
                  ) -> float | NDArray[np.float64]: ...
@overload
def max_rim_speed(vx: float, vy: float, omega: float,  # type: ignore[overload-overlap]
                  geometry: MecanumGeometry) -> float: ...
@overload
def max_rim_speed(vx: float | Stack, vy: float | Stack, omega: float | Stack,
                  geometry: MecanumGeometry) -> NDArray[np.float64]: ...
def max_rim_speed(vx: Any, vy: Any = None, omega: Any = None,
                  geometry: Any = None) -> float | NDArray[np.float64]:
    r"""The fastest wheel's rim speed :math:`r_w\max_i|\dot\varphi_i|`, m/s, for a body twist.

    Every sign combination of the :math:`v_y` and :math:`\omega` terms occurs on one of the
    four wheels, so

    .. math:: r_w \max_i |\dot\varphi_i| = |v_x| + |v_y|\cot\gamma + k|\omega| .

    This, not the body speed :math:`\sqrt{v_x^2+v_y^2}`, is what the motors limit.

    Like :func:`inverse_kinematics`, it takes ``max_rim_speed(twist, geometry)`` (a Twist, a
    tuple of three numbers or an array of shape (..., 3)) or
    ``max_rim_speed(vx, vy, omega, geometry)``.

    Returns
    -------
    float for one twist (shape (3,), or scalar components), numpy.ndarray for a stack
        m/s. An ``ndarray`` twist's shape is not known to a type checker: its result is
        typed ``float | ndarray``.

    Examples
    --------
    >>> g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    >>> max_rim_speed(1.0, 1.0, 0.0, g)  # diagonal: body speed 1.414 m/s
    2.0
    >>> max_rim_speed(Twist(vx=1.0, vy=1.0, omega=0.0), g)
    2.0
    """
    vx, vy, omega, geometry = _twist_or_components(vx, vy, omega, geometry, "max_rim_speed")
    g = _geometry(geometry)
    vx_a, vy_a, w_a = _broadcast(vx=V.finite_array("vx", vx), vy=V.finite_array("vy", vy),
                                 omega=V.finite_array("omega", omega))
    return V.scalar_or_array(np.abs(vx_a) + np.abs(vy_a) * g.lateral_factor + np.abs(w_a) * g.k)


@overload
def grip_usage(accel_x: float, accel_y: float, mu: float, roller_angle: float = math.pi / 4,  # type: ignore[overload-overlap]
               gravity: float = 9.81) -> float: ...
@overload
def grip_usage(accel_x: float | Stack, accel_y: float | Stack, mu: float,
               roller_angle: float = math.pi / 4,
               gravity: float = 9.81) -> NDArray[np.float64]: ...
def grip_usage(accel_x: ArrayLike, accel_y: ArrayLike, mu: float, roller_angle: float = math.pi / 4,
               gravity: float = 9.81) -> float | NDArray[np.float64]:
    r"""Share of the tyres' grip that a body acceleration needs (above 1: the wheels slip).

    A mecanum wheel can push on the floor only along its floor roller's axis
    :math:`(\sin\gamma, s_i\cos\gamma)`, and at most with :math:`\mu N_i`. With the weight
    shared equally (:math:`N_i = mg/4`) and no angular acceleration, the smallest largest
    wheel force that gives the body the acceleration :math:`(a_x, a_y)` (body frame, any
    velocity) is :math:`\tfrac m4(|a_x|/\sin\gamma + |a_y|/\cos\gamma)`, so

    .. math:: U = \frac{|a_x|/\sin\gamma + |a_y|/\cos\gamma}{\mu g} \le 1 .

    At 45 degrees: :math:`|a_x| + |a_y| \le \mu g/\sqrt2`, a diamond, like the speed limit of
    :func:`max_rim_speed`. Straight ahead or sideways a mecanum vehicle can use only
    :math:`1/\sqrt2` of the grip of ordinary wheels, diagonally only half (two wheels push,
    the other two cannot). A circle of radius :math:`R_c` at speed :math:`v` needs
    :math:`v^2/R_c` towards the centre: sideways in the body with the heading rotating, in every
    body direction with the heading held.

    Parameters
    ----------
    accel_x, accel_y : float or array_like
        Body-frame acceleration of the centre, m/s^2.
    mu : float
        Friction coefficient, > 0.
    roller_angle : float
        :math:`\gamma`, rad, in (0, pi/2).
    gravity : float
        m/s^2, > 0 (the sandbox's 9.81 by default).

    Returns
    -------
    float or numpy.ndarray
        The grip usage :math:`u` (dimensionless), an array for array input.

    Examples
    --------
    >>> round(grip_usage(0.0, 5.0, 0.8), 4)  # sideways, 5 m/s^2 on mu = 0.8
    0.901
    >>> round(grip_usage(3.0, 3.0, 0.8), 4)  # diagonal, 4.24 m/s^2
    1.0812
    """
    ax_a, ay_a = _broadcast(accel_x=V.finite_array("accel_x", accel_x),
                            accel_y=V.finite_array("accel_y", accel_y))
    mu_f = V.positive("mu", mu)
    gamma = V.finite("roller_angle", roller_angle)
    if not 0.0 < gamma < math.pi / 2:
        raise ValueError(f"roller_angle must be in (0, pi/2) rad (exclusive), got {roller_angle!r}")
    g = V.positive("gravity", gravity)
    with np.errstate(all="ignore"):
        out = (np.abs(ax_a) / math.sin(gamma) + np.abs(ay_a) / math.cos(gamma)) / (mu_f * g)
    return V.scalar_or_array(V.finite_result("accel_x, accel_y, mu and roller_angle", out))


class SpeedLimit(NamedTuple):
    """Result of :func:`limit_speed`: the twist to execute, its scale factor, and why."""

    #: The twist to execute (m/s, m/s, rad/s).
    twist: Twist
    #: 1.0 within the limit; 0 < scale < 1 when scaled; 0.0 when refused.
    scale: float
    reason: str


def limit_speed(twist: Twist | ArrayLike, max_speed: float, geometry: MecanumGeometry | None = None,
                *, refuse: bool = False) -> SpeedLimit:
    r"""Check a body twist against a top speed; scale it down, or refuse it, saying why.

    Two limits are checked:

    - the body speed :math:`\sqrt{v_x^2+v_y^2} \le v_{max}` (the document's rule);
    - if ``geometry`` is given, also the fastest wheel's rim speed
      :math:`|v_x| + |v_y|\cot\gamma + k|\omega| \le v_{max}` (what a motor limits: the
      vehicle reaches :math:`v_{max}` driving straight ahead with every wheel at full speed).

    A twist over a limit is multiplied by :math:`s = v_{max}/\text{speed} < 1` (all three
    components, so the path keeps its shape and is only driven more slowly), or with
    ``refuse=True`` replaced by the zero twist. Nothing is ever clipped silently: ``reason``
    says what was checked and what was done.

    Parameters
    ----------
    twist : Twist or array_like, shape (3,)
        (vx m/s, vy m/s, omega rad/s), body frame. One command at a time.
    max_speed : float
        m/s, > 0 (the document's 15 ft/s is :data:`DOCUMENT_MAX_SPEED`).
    geometry : MecanumGeometry, optional
        Enables the wheel rim-speed check.
    refuse : bool
        Refuse (return zeros) instead of scaling.

    Returns
    -------
    SpeedLimit
        ``(twist, scale, reason)``.

    Examples
    --------
    >>> out = limit_speed((6.0, 0.0, 0.0), 4.572)
    >>> round(out.scale, 4), out.twist
    (0.762, Twist(vx=4.572, vy=0.0, omega=0.0))
    >>> print(out.reason)
    body speed 6.000 m/s exceeds the limit 4.572 m/s: scaled by 0.762 (same path, slower)
    >>> print(limit_speed((3.0, 0.0, 0.0), 4.572).reason)
    within the limit: body speed 3.000 m/s <= 4.572 m/s
    >>> g = MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    >>> print(limit_speed((0.0, 0.0, 20.0), 4.572, g, refuse=True).reason)
    fastest wheel (FL) rim speed 7.000 m/s exceeds the limit 4.572 m/s: refused (not driven)
    """
    vec = V.twist("twist", twist)
    vmax = V.positive("max_speed", max_speed)
    if not isinstance(refuse, bool):
        raise ValueError(f"refuse must be True or False, got {refuse!r}")
    vx, vy, w = (float(c) for c in vec)
    checks = [("body speed", math.hypot(vx, vy))]
    if geometry is not None:
        g = _geometry(geometry)
        rim = abs(vx) + abs(vy) * g.lateral_factor + abs(w) * g.k
        rates = inverse_kinematics(vx, vy, w, g)
        fastest = WHEEL_NAMES[int(np.argmax(np.abs(rates)))]
        checks.append((f"fastest wheel ({fastest}) rim speed", rim))
    what, speed = max(checks, key=lambda c: c[1])
    if speed <= vmax:
        each = ", ".join(f"{name} {value:.3f} m/s" for name, value in checks)
        return SpeedLimit(Twist(vx, vy, w), 1.0,
                          f"within the limit: {each} <= {vmax:.3f} m/s")
    head = f"{what} {speed:.3f} m/s exceeds the limit {vmax:.3f} m/s"
    if refuse:
        return SpeedLimit(Twist(0.0, 0.0, 0.0), 0.0, f"{head}: refused (not driven)")
    s = vmax / speed
    return SpeedLimit(Twist(vx * s, vy * s, w * s), s,
                      f"{head}: scaled by {s:.3f} (same path, slower)")


def desaturate(wheel_rates: ArrayLike, max_rate: float) -> np.ndarray:
    r"""Scale all four wheel rates together so that none exceeds ``max_rate`` in size.

    .. math:: \dot\varphi_i' = \dot\varphi_i\,\min\left(1, \frac{\dot\varphi_{max}}
              {\max_j |\dot\varphi_j|}\right)

    WPILib's ``MecanumDriveWheelSpeeds.desaturate``: the ratios of the wheel rates are kept,
    so the vehicle drives the same path (the same direction and curvature), only slower.
    Works as well on rim speeds (m/s) with a speed limit.

    Parameters
    ----------
    wheel_rates : array_like, shape (..., 4)
        FL, FR, RL, RR, rad/s (or m/s).
    max_rate : float
        The largest allowed size, same unit, > 0.

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Examples
    --------
    >>> desaturate([10.0, 20.0, -40.0, 5.0], 20.0)
    array([  5. ,  10. , -20. ,   2.5])
    """
    rates = V.shaped("wheel_rates", wheel_rates, (4,))
    return _kernels.desaturate(rates, V.positive("max_rate", max_rate))


@overload
def circle_speed(radius: float, lap_time: float) -> float: ...  # type: ignore[overload-overlap]
@overload
def circle_speed(radius: float | Stack, lap_time: float | Stack) -> NDArray[np.float64]: ...
def circle_speed(radius: ArrayLike, lap_time: ArrayLike) -> float | NDArray[np.float64]:
    r"""Speed along a circle driven once in ``lap_time``: :math:`v = 2\pi|R|/T`, m/s.

    Parameters
    ----------
    radius : float or array_like
        :math:`R`, m, non-zero; positive = counter-clockwise (left), negative = clockwise.
    lap_time : float or array_like
        :math:`T`, s, > 0.

    Examples
    --------
    >>> round(circle_speed(1.0, 2 * np.pi), 12)
    1.0
    """
    r_a, t_a = _circle_args(radius, lap_time)
    return V.scalar_or_array(2.0 * np.pi * np.abs(r_a) / t_a)


def _circle_args(radius, lap_time) -> tuple[np.ndarray, np.ndarray]:
    r_a = V.finite_array("radius", radius)
    t_a = V.finite_array("lap_time", lap_time)
    if np.any(r_a == 0):
        raise ValueError(f"radius must be a non-zero finite number (m), got {radius!r}")
    if np.any(t_a < np.finfo(float).tiny):  # not subnormal: 1/T must not overflow
        raise ValueError(f"lap_time must be a finite number > 0 (s), not subnormal, got "
                         f"{lap_time!r}")
    r_a, t_a = _broadcast(radius=r_a, lap_time=t_a)
    with np.errstate(all="ignore"):
        V.finite_result("radius and lap_time", 2.0 * np.pi * r_a / t_a)
    return r_a, t_a


def circle_twist(radius: ArrayLike, lap_time: ArrayLike, t: ArrayLike = 0.0, *,
                 heading: str = "rotating") -> Twist | NDArray[np.float64]:
    r"""Body twist that drives a circle of radius :math:`R` once every :math:`T` seconds.

    The vehicle starts at the origin facing +x, moving along +x, with the centre of the
    circle at :math:`(0, R)` (to its left for :math:`R > 0`). With
    :math:`\Omega = \operatorname{sign}(R)\,2\pi/T` and :math:`v = 2\pi|R|/T`:

    - ``heading="rotating"``: the vehicle turns with the path, facing along it; the twist is
      constant, :math:`(v, 0, \Omega)` (any vehicle can do this).
    - ``heading="held"``: the vehicle keeps facing +x while its velocity turns; the twist
      varies with time, :math:`(v\cos\Omega t,\ v\sin\Omega t,\ 0)` (only a holonomic
      vehicle can do this).

    Parameters
    ----------
    radius : float or array_like
        m, non-zero; positive = counter-clockwise.
    lap_time : float or array_like
        s, > 0.
    t : float or array_like
        Time since the start, s (matters only for ``heading="held"``).
    heading : {"rotating", "held"}

    Returns
    -------
    Twist, or numpy.ndarray of shape (..., 3) for array input
        (vx m/s, vy m/s, omega rad/s), body frame.

    Examples
    --------
    >>> circle_twist(2.0, 4 * np.pi)
    Twist(vx=1.0, vy=0.0, omega=0.5)
    >>> np.round(circle_twist(2.0, 4 * np.pi, t=[0.0, np.pi], heading="held"), 12)
    array([[1., 0., 0.],
           [0., 1., 0.]])
    """
    V.choice("heading", heading, ("rotating", "held"))
    r_a, t_a = _circle_args(radius, lap_time)
    t_arr = V.finite_array("t", t)
    r_a, t_a, t_arr = _broadcast(radius=r_a, lap_time=t_a, t=t_arr)
    speed = 2.0 * np.pi * np.abs(r_a) / t_a
    rate = np.sign(r_a) * 2.0 * np.pi / t_a
    if heading == "rotating":
        out = np.stack([speed, np.zeros_like(speed), rate], axis=-1)
    else:
        angle = rate * t_arr
        out = np.stack([speed * np.cos(angle), speed * np.sin(angle), np.zeros_like(speed)],
                       axis=-1) + 0.0
    return Twist(*out.tolist()) if out.ndim == 1 else out


def go_to_point_twist(pose: Pose | ArrayLike, goal: Pose | ArrayLike, speed: float,
                      max_omega: float, dt: float | None = None) -> Twist | NDArray[np.float64]:
    r"""Body twist that drives straight to ``goal`` while turning to its heading.

    "Where am I" is ``pose`` :math:`(x, y, \theta)`, "where am I going" is ``goal``
    :math:`(x_g, y_g, \theta_g)` (world frame, m and rad); "how do I get there": move along the
    straight segment and turn through the wrapped heading error
    :math:`\Delta\theta = \operatorname{wrap}(\theta_g - \theta)` so that both end together,
    after

    .. math:: T = \max\left(\frac{d}{v_{max}}, \frac{|\Delta\theta|}{\omega_{max}}\right),
              \quad d = \sqrt{(x_g-x)^2 + (y_g-y)^2}.

    The world velocity is :math:`(x_g - x, y_g - y)/T` and :math:`\omega = \Delta\theta/T`;
    rotated into the body frame by :math:`-\theta`:

    .. math::

        v_x = \frac{\cos\theta\,(x_g-x) + \sin\theta\,(y_g-y)}{T},\quad
        v_y = \frac{-\sin\theta\,(x_g-x) + \cos\theta\,(y_g-y)}{T},\quad
        \omega = \frac{\Delta\theta}{T}.

    This is the continuous-time answer: the world velocity is constant, so the body twist
    turns as the vehicle turns. A controller that holds each command for a step ``dt`` drives
    short arcs instead and drifts off the segment by O(dt) (about 2 mm over 4 m at 100 Hz while
    turning 0.25 rad/s). Pass ``dt`` to get the *sampled* answer instead: the constant twist
    that, held for ``dt``, lands exactly on the segment at the fraction
    :math:`f = \min(\Delta t/T, 1)` of the way (the SE(2) logarithm of that displacement,
    divided by :math:`\Delta t`); with :math:`T \le \Delta t` it arrives in this step.

    At the goal both return zeros.

    Parameters
    ----------
    pose, goal : Pose or array_like, shape (..., 3)
        (x m, y m, theta rad), world frame.
    speed : float
        :math:`v_{max}`, speed along the segment, m/s, > 0.
    max_omega : float
        :math:`\omega_{max}`, largest yaw rate, rad/s, > 0.
    dt : float, optional
        Control period, s, > 0: return the sampled twist (see above).

    Returns
    -------
    Twist (for two Poses) or numpy.ndarray, shape (..., 3)
        (vx m/s, vy m/s, omega rad/s), body frame.

    Examples
    --------
    Facing +y (theta = pi/2), a goal 2 m ahead in world +x is to the vehicle's right:

    >>> np.round(go_to_point_twist((0, 0, np.pi / 2), (2, 0, np.pi / 2), 1.0, 1.0), 12)
    array([ 0., -1.,  0.])
    """
    p = pose.as_array() if isinstance(pose, Pose) else V.shaped("pose", pose, (3,))
    q = goal.as_array() if isinstance(goal, Pose) else V.shaped("goal", goal, (3,))
    vmax = V.positive("speed", speed)
    wmax = V.positive("max_omega", max_omega)
    step = None if dt is None else V.positive("dt", dt)
    try:
        p, q = np.broadcast_arrays(p, q)
    except ValueError:
        raise ValueError(f"pose and goal must have broadcastable shapes, got {np.shape(p)} "
                         f"and {np.shape(q)}") from None
    dx = q[..., 0] - p[..., 0]
    dy = q[..., 1] - p[..., 1]
    dth = wrap_angle(q[..., 2] - p[..., 2])
    time_to_go = np.maximum(np.hypot(dx, dy) / vmax, np.abs(dth) / wmax)
    arrived = time_to_go == 0
    safe_t = np.where(arrived, 1.0, time_to_go)
    c, s = np.cos(p[..., 2]), np.sin(p[..., 2])
    bx, by = c * dx + s * dy, -s * dx + c * dy  # goal offset in the body frame
    if step is None:
        out = np.stack([bx / safe_t, by / safe_t, dth / safe_t], axis=-1)
    else:
        f = step / np.maximum(safe_t, step)  # min(dt / T, 1) without overflow
        phi = f * dth
        a, b = arc_factors(phi)  # sin(phi)/phi, (1 - cos(phi))/phi: the arc kernel's
        norm = a * a + b * b
        ex, ey = f * bx, f * by
        out = np.stack([(a * ex + b * ey) / norm / step, (-b * ex + a * ey) / norm / step,
                        phi / step], axis=-1)
    out = np.where(arrived[..., None], 0.0, out) + 0.0
    if _is_one(pose, Pose) and _is_one(goal, Pose):
        return Twist(*out.tolist())
    return out

