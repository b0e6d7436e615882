r"""Car-like vehicles: Ackermann steering, the bicycle model, linkages and pure pursuit.

A car-like vehicle has a fixed rear axle and steered front wheels. Its reference point is the
*rear-axle midpoint*; all quantities are SI and REP-103 (x forward, y left, z up):

========= ===================================================== ======= ====================
symbol    meaning                                               unit    sign
========= ===================================================== ======= ====================
``L``     wheelbase: front axle to rear axle                    m       > 0
``W``     track width: left to right contact line               m       > 0
``delta`` steering angle (of the bicycle's one front wheel)     rad     > 0 turns left
``R``     turning radius of the rear-axle midpoint              m       > 0 left, inf straight
``kappa`` curvature 1/R                                         1/m     > 0 left
========= ===================================================== ======= ====================

The one no-side-slip fact behind every function here: a wheel that rolls without sliding
sideways moves along its own rolling direction, so the instantaneous centre of rotation (ICR)
lies on the line of its axle. The rear axle puts the ICR on the rear axle line, at
``(0, R)``; a front wheel at ``(L, y_i)`` then has to point at

.. math:: \tan\delta_i = \frac{L}{R - y_i},

which for the two front wheels at :math:`y = \pm W/2` is the Ackermann condition
:math:`\cot\delta_R - \cot\delta_L = W/L` (for a left turn).

The check against the ROS 2 steering controllers (``steering_controllers_library``,
``steering_odometry.cpp`` of ros-controls/ros2_controllers) is in ``tests/library/test_carlike.py``.
"""

from __future__ import annotations

import functools
import inspect
import math
from collections.abc import Callable
from typing import NamedTuple, ParamSpec, TypeVar, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin._records import Stack
from wheelkin.frames import Twist

__all__ = [
    "AckermannAngles",
    "ArmAngle",
    "CentreOfMassTwist",
    "LinkageAngles",
    "ackermann_angles",
    "ackermann_outer_angle",
    "bicycle_twist",
    "bicycle_twist_com",
    "jeantaud_arm_angle",
    "linkage_angles",
    "linkage_error",
    "minimum_radius",
    "optimal_arm_angle",
    "pure_pursuit_curvature",
    "side_slip_angle",
    "steering_angle",
    "steering_from_curvature",
    "tricycle_twist",
]

_HALF_PI = 0.5 * math.pi
_P = ParamSpec("_P")
_R = TypeVar("_R")


def _lengths_by_name(func: Callable[_P, _R]) -> Callable[_P, _R]:
    """``func`` with a clear TypeError when its keyword-only lengths are passed by position.

    A car's lengths are keyword-only: ``ackermann_angles(2, 0.25, 0.33)`` with the wheelbase
    and the track swapped would return plausible angles. Python's own message ("takes 1
    positional argument but 3 were given") does not say what to write instead; this one names
    the parameters.
    """
    params = inspect.signature(func).parameters.values()
    positional = [p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD]
    named = [p.name for p in params if p.kind is p.KEYWORD_ONLY]

    @functools.wraps(func)
    def call(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        if len(args) > len(positional):
            extra = named[:len(args) - len(positional)]
            takes = f"takes {', '.join(positional)} by position and " if positional else "takes "
            raise TypeError(
                f"{func.__name__}() {takes}the car's dimensions by name only: write "
                f"{', '.join(f'{n}=...' for n in extra)} (got {len(args)} positional "
                "arguments; lengths in the wrong order would give plausible wrong answers)")
        return func(*args, **kwargs)

    return call


class AckermannAngles(NamedTuple):
    """Front wheel steering angles (rad, positive turns left)."""

    left: float | np.ndarray
    right: float | np.ndarray


class LinkageAngles(NamedTuple):
    """Front wheel angles of a steering linkage (rad, positive turns left)."""

    left: float | np.ndarray
    right: float | np.ndarray


class CentreOfMassTwist(NamedTuple):
    """Body twist at the centre of mass, and its side-slip angle beta (rad)."""

    vx: float | np.ndarray
    vy: float | np.ndarray
    omega: float | np.ndarray
    beta: float | np.ndarray


class ArmAngle(NamedTuple):
    """A steering-arm angle (rad) and the worst Ackermann error over the range (rad)."""

    arm_angle: float
    worst_error: float


_out = V.scalar_or_array  # one quantity: a float for 0-d, else the array


def _twist(columns: np.ndarray) -> Twist | np.ndarray:
    """One twist (shape (3,)) as a Twist; a stack of them (shape (..., 3)) as the array."""
    return Twist(*columns.tolist()) if columns.ndim == 1 else columns


def _steer(name: str, value) -> np.ndarray:
    arr = V.finite_array(name, value)
    if np.any(np.abs(arr) >= _HALF_PI):
        raise ValueError(f"{name} must be in (-pi/2, pi/2) rad, got {value!r}")
    return arr


def _radius(name: str, value) -> np.ndarray:
    arr = V.finite_array(name, value, allow_inf=True)
    if np.any(arr == 0):
        raise ValueError(f"{name} must be non-zero (+-inf for straight ahead), got {value!r}")
    return arr


@_lengths_by_name
def steering_angle(radius: ArrayLike, *, wheelbase: float) -> float | NDArray[np.float64]:
    r"""The bicycle model's front steering angle for a turning radius of the rear axle.

    .. math:: \delta = \arctan\frac{L}{R}

    Parameters
    ----------
    radius : float or array_like
        :math:`R`, signed turning radius of the rear-axle midpoint, m (> 0 left, < 0 right,
        ``inf`` straight; not 0).
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    float or ndarray
        :math:`\delta`, rad, in (-pi/2, pi/2), positive turns left (REP-103).

    Examples
    --------
    >>> round(math.degrees(steering_angle(1.0, wheelbase=1.0)), 6)
    45.0
    >>> steering_angle(np.inf, wheelbase=0.3)
    0.0
    >>> steering_angle(0.0, wheelbase=0.3)
    Traceback (most recent call last):
    ...
    ValueError: radius must be non-zero (+-inf for straight ahead), got 0.0
    """
    R = _radius("radius", radius)
    L = V.positive("wheelbase", wheelbase)
    with np.errstate(all="ignore"):
        delta = np.arctan(L / R) + 0.0
    if np.any(np.abs(delta) >= _HALF_PI):  # L/R overflowed: a radius of a few 1e-308 m
        raise ValueError(f"radius is too small for the wheelbase: the steering angle rounds to "
                         f"90 degrees, got {radius!r}")
    return _out(delta)


@_lengths_by_name
def steering_from_curvature(curvature: ArrayLike, *,
                            wheelbase: float) -> float | NDArray[np.float64]:
    r"""The bicycle model's front steering angle for a path curvature of the rear axle.

    .. math:: \delta = \arctan(L\,\kappa)

    Parameters
    ----------
    curvature : float or array_like
        :math:`\kappa = 1/R`, 1/m (> 0 left, 0 straight).
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    float or ndarray
        :math:`\delta`, rad.

    Examples
    --------
    >>> round(steering_from_curvature(2.0, wheelbase=0.5), 12) == round(math.pi / 4, 12)
    True
    >>> steering_from_curvature([0.0, -1.0], wheelbase=1.0).round(4).tolist()
    [0.0, -0.7854]
    """
    k = V.finite_array("curvature", curvature)
    L = V.positive("wheelbase", wheelbase)
    return _out(np.arctan(L * k) + 0.0)


@_lengths_by_name
def ackermann_outer_angle(inner_angle: ArrayLike, *, wheelbase: float,
                          track_width: float) -> float | NDArray[np.float64]:
    r"""The outer front wheel's angle that satisfies the Ackermann condition.

    .. math:: \cot\delta_o = \cot\delta_i + \frac{W}{L}
              \quad\Longrightarrow\quad
              \delta_o = \arctan\frac{L\tan\delta_i}{L + W\tan\delta_i}

    for a left turn (:math:`\delta_i > 0`, inner = left); a right turn is its mirror image
    (the formula holds with :math:`|\delta_i|` and the sign restored).

    Parameters
    ----------
    inner_angle : float or array_like
        :math:`\delta_i`, the inner wheel's angle, rad, in (-pi/2, pi/2).
    wheelbase, track_width : float
        :math:`L`, :math:`W`, m (> 0).

    Returns
    -------
    float or ndarray
        :math:`\delta_o`, rad, of the same sign, smaller in magnitude.

    Examples
    --------
    >>> round(math.degrees(ackermann_outer_angle(math.radians(30), wheelbase=2.5,
    ...                                          track_width=1.5)), 4)
    23.21
    """
    d = _steer("inner_angle", inner_angle)
    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    t = np.tan(np.abs(d))
    return _out(np.sign(d) * np.arctan(L * t / (L + W * t)) + 0.0)


@_lengths_by_name
def ackermann_angles(radius: ArrayLike, *, wheelbase: float, track_width: float) -> AckermannAngles:
    r"""Left and right front wheel angles of an ideal Ackermann car for a turning radius.

    The ICR is on the rear axle line at :math:`(0, R)` (rear-axle midpoint frame); the left
    wheel at :math:`(L, W/2)` and the right at :math:`(L, -W/2)` must each roll across the
    line to it:

    .. math:: \delta_L = \arctan\frac{L}{R - W/2},\qquad
              \delta_R = \arctan\frac{L}{R + W/2},

    so that :math:`\cot\delta_R - \cot\delta_L = W/L` whatever :math:`R`.

    Parameters
    ----------
    radius : float or array_like
        :math:`R` of the rear-axle midpoint, m, signed (> 0 left), :math:`|R| > W/2`
        (``inf`` straight).
    wheelbase : float
        :math:`L`, m (> 0).
    track_width : float
        :math:`W`, m (> 0).

    Returns
    -------
    AckermannAngles
        ``(left, right)``, rad; the inner wheel turns more.

    Examples
    --------
    >>> left, right = ackermann_angles(5.0, wheelbase=2.5, track_width=1.5)
    >>> round(math.degrees(left), 4), round(math.degrees(right), 4)
    (30.4655, 23.4986)
    >>> ackermann_angles(0.5, wheelbase=2.5, track_width=1.5)
    Traceback (most recent call last):
    ...
    ValueError: radius must satisfy |radius| > track_width/2 = 0.75 m, got 0.5
    """
    R = _radius("radius", radius)
    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    if np.any(np.abs(R) <= W / 2):
        raise ValueError(f"radius must satisfy |radius| > track_width/2 = {W / 2:g} m, "
                         f"got {radius!r}")
    return AckermannAngles(_out(np.arctan(L / (R - W / 2)) + 0.0),
                           _out(np.arctan(L / (R + W / 2)) + 0.0))


@_lengths_by_name
def bicycle_twist(speed: ArrayLike, steering_angle: ArrayLike, *,
                  wheelbase: float) -> Twist | NDArray[np.float64]:
    r"""Body twist of the rear-axle midpoint of the kinematic bicycle model.

    .. math:: v_x = v,\qquad v_y = 0,\qquad \omega = \frac{v\tan\delta}{L}

    Parameters
    ----------
    speed : float or array_like
        :math:`v`, speed of the rear-axle midpoint, m/s (negative: reversing).
    steering_angle : float or array_like
        :math:`\delta`, rad, in (-pi/2, pi/2), positive left.
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    Twist, or ndarray of shape (..., 3) for array input
        ``(vx, vy, omega)`` in m/s, m/s, rad/s (body frame, REP-103).

    Examples
    --------
    >>> [round(c, 6) for c in bicycle_twist(2.0, math.pi / 4, wheelbase=0.5)]
    [2.0, 0.0, 4.0]
    >>> bicycle_twist(1.0, 2.0, wheelbase=0.5)
    Traceback (most recent call last):
    ...
    ValueError: steering_angle must be in (-pi/2, pi/2) rad, got 2.0
    """
    v = V.finite_array("speed", speed)
    d = _steer("steering_angle", steering_angle)
    L = V.positive("wheelbase", wheelbase)
    v, d = V.broadcast(speed=v, steering_angle=d)
    return _twist(np.stack([v + 0.0, np.zeros_like(v), v * np.tan(d) / L + 0.0], axis=-1))


@_lengths_by_name
def tricycle_twist(front_speed: ArrayLike, steering_angle: ArrayLike, *,
                   wheelbase: float) -> Twist | NDArray[np.float64]:
    r"""Body twist of the rear-axle midpoint of a tricycle driven by its steered front wheel.

    The front wheel rolls at :math:`v_f` along its own direction, at angle :math:`\delta`;
    the rear axle forbids a sideways velocity at the rear midpoint, so

    .. math:: v_x = v_f\cos\delta,\qquad v_y = 0,\qquad \omega = \frac{v_f\sin\delta}{L}.

    It is :func:`bicycle_twist` with :math:`v = v_f\cos\delta`.

    Parameters
    ----------
    front_speed : float or array_like
        :math:`v_f`, m/s.
    steering_angle : float or array_like
        :math:`\delta`, rad, in [-pi/2, pi/2] (at pi/2 the tricycle turns on the spot about
        the rear-axle midpoint).
    wheelbase : float
        :math:`L`, m (> 0).

    Returns
    -------
    Twist, or ndarray of shape (..., 3) for array input
        ``(vx, vy, omega)``.

    Examples
    --------
    >>> tricycle_twist(1.0, math.pi / 2, wheelbase=0.5)
    Twist(vx=0.0, vy=0.0, omega=2.0)
    """
    v = V.finite_array("front_speed", front_speed)
    d = V.finite_array("steering_angle", steering_angle)
    if np.any(np.abs(d) > _HALF_PI):
        raise ValueError(f"steering_angle must be in [-pi/2, pi/2] rad, got {steering_angle!r}")
    L = V.positive("wheelbase", wheelbase)
    v, d = V.broadcast(front_speed=v, steering_angle=d)
    vx = np.where(np.abs(np.abs(d) - _HALF_PI) < 1e-15, 0.0, v * np.cos(d))
    return _twist(np.stack([vx + 0.0, np.zeros_like(v), v * np.sin(d) / L + 0.0], axis=-1))


@_lengths_by_name
def side_slip_angle(steering_angle: ArrayLike, *, wheelbase: float,
                    rear_to_com: float) -> float | NDArray[np.float64]:
    r"""Side-slip angle :math:`\beta` of a point on the centre line at :math:`l_r` ahead of
    the rear axle.

    .. math:: \tan\beta = \frac{l_r\tan\delta}{L}

    Parameters
    ----------
    steering_angle : float or array_like
        :math:`\delta`, rad, in (-pi/2, pi/2).
    wheelbase : float
        :math:`L`, m (> 0).
    rear_to_com : float
        :math:`l_r`, distance from the rear axle to the centre of mass, m, in [0, L].

    Returns
    -------
    float or ndarray
        :math:`\beta`, rad: the angle from the body x axis to the velocity of that point.

    Examples
    --------
    >>> round(math.degrees(side_slip_angle(math.pi / 4, wheelbase=2.0, rear_to_com=1.0)), 4)
    26.5651
    """
    d = _steer("steering_angle", steering_angle)
    L = V.positive("wheelbase", wheelbase)
    lr = V.in_range("rear_to_com", rear_to_com, 0.0, L)
    return _out(np.arctan(lr * np.tan(d) / L) + 0.0)


@_lengths_by_name
def bicycle_twist_com(speed: ArrayLike, steering_angle: ArrayLike, *, wheelbase: float,
                      rear_to_com: float) -> CentreOfMassTwist:
    r"""Body twist at the centre of mass (:math:`l_r` ahead of the rear axle), given its speed.

    The velocity of the centre of mass makes the side-slip angle :math:`\beta`
    (:func:`side_slip_angle`) with the body x axis; the yaw rate follows from the rear axle's
    speed :math:`v\cos\beta`:

    .. math:: v_x = v\cos\beta,\quad v_y = v\sin\beta,\quad
              \omega = \frac{v\cos\beta\,\tan\delta}{L}

    (the kinematic bicycle model of Rajamani, ch. 2, with the front steering only).

    Parameters
    ----------
    speed : float or array_like
        :math:`v`, speed of the centre of mass, m/s.
    steering_angle : float or array_like
        :math:`\delta`, rad, in (-pi/2, pi/2).
    wheelbase : float
        :math:`L`, m (> 0).
    rear_to_com : float
        :math:`l_r`, m, in [0, L].

    Returns
    -------
    CentreOfMassTwist
        ``(vx, vy, omega, beta)`` in m/s, m/s, rad/s, rad.

    Examples
    --------
    >>> tw = bicycle_twist_com(1.0, math.pi / 4, wheelbase=2.0, rear_to_com=1.0)
    >>> [round(float(x), 6) for x in tw]
    [0.894427, 0.447214, 0.447214, 0.463648]
    """
    v = V.finite_array("speed", speed)
    beta = np.asarray(side_slip_angle(steering_angle, wheelbase=wheelbase, rear_to_com=rear_to_com))
    d = np.asarray(steering_angle, dtype=float)
    L = float(wheelbase)
    v, d, beta = V.broadcast(speed=v, steering_angle=d, side_slip=beta)
    cb = np.cos(beta)
    return CentreOfMassTwist(_out(v * cb + 0.0), _out(v * np.sin(beta) + 0.0),
                             _out(v * cb * np.tan(d) / L + 0.0), _out(beta + 0.0))


@_lengths_by_name
def minimum_radius(max_steering_angle: ArrayLike, *, wheelbase: float,
                   track_width: float = 0.0) -> float | NDArray[np.float64]:
    r"""Smallest turning radius of the rear-axle midpoint for a steering limit.

    With the limit on the inner front wheel of an Ackermann car (its ICR on the rear axle
    line, the inner wheel at :math:`W/2` from the centre line):

    .. math:: R_{min} = \frac{L}{\tan\delta_{max}} + \frac{W}{2};

    ``track_width = 0`` is the bicycle model, :math:`R_{min} = L/\tan\delta_{max}`.

    Parameters
    ----------
    max_steering_angle : float or array_like
        :math:`\delta_{max}`, rad, in (0, pi/2).
    wheelbase : float
        :math:`L`, m (> 0).
    track_width : float
        :math:`W`, m (>= 0).

    Returns
    -------
    float or ndarray
        :math:`R_{min}`, m (> 0).

    Examples
    --------
    >>> round(minimum_radius(math.pi / 4, wheelbase=2.5), 6)
    2.5
    >>> round(minimum_radius(math.pi / 4, wheelbase=2.5, track_width=1.5), 6)
    3.25
    """
    d = _steer("max_steering_angle", max_steering_angle)
    if np.any(d <= 0):
        raise ValueError(f"max_steering_angle must be in (0, pi/2) rad, got "
                         f"{max_steering_angle!r}")
    L = V.positive("wheelbase", wheelbase)
    W = V.nonnegative("track_width", track_width)
    with np.errstate(all="ignore"):
        out = L / np.tan(d) + W / 2
    return _out(V.finite_result("max_steering_angle, wheelbase and track_width", out))


@overload
def pure_pursuit_curvature(x: float, y: float) -> float: ...  # type: ignore[overload-overlap]
@overload
def pure_pursuit_curvature(x: float | Stack, y: float | Stack) -> NDArray[np.float64]: ...
def pure_pursuit_curvature(x: ArrayLike, y: ArrayLike) -> float | NDArray[np.float64]:
    r"""Curvature of the circle through the rear-axle midpoint, tangent to the heading, that
    passes through the look-ahead point ``(x, y)`` (rear-axle frame).

    .. math:: \kappa = \frac{2y}{L_d^2},\qquad L_d^2 = x^2 + y^2

    Parameters
    ----------
    x, y : float or array_like
        The look-ahead point in the vehicle frame (x forward, y left), m; not both zero.

    Returns
    -------
    float or ndarray
        :math:`\kappa`, 1/m (> 0: turn left).

    Examples
    --------
    >>> pure_pursuit_curvature(1.0, 1.0)
    1.0
    >>> pure_pursuit_curvature([2.0, 0.0], [0.0, -0.5]).tolist()
    [0.0, -4.0]
    >>> pure_pursuit_curvature(0.0, 0.0)
    Traceback (most recent call last):
    ...
    ValueError: (x, y) must not be the origin (the look-ahead point is where the vehicle is)
    """
    px = V.finite_array("x", x)
    py = V.finite_array("y", y)
    px, py = V.broadcast(x=px, y=py)
    if np.any((px == 0) & (py == 0)):
        raise ValueError("(x, y) must not be the origin (the look-ahead point is where the "
                         "vehicle is)")
    with np.errstate(all="ignore"):  # far points: 0; tiny ones overflow and are refused
        out = 2.0 * py / (px * px + py * py) + 0.0
    return _out(V.finite_result("x and y", out))


# ---------------------------------------------------------------------------- linkages


def _linkage_geometry(track_width, arm_length, arm_angle):
    W = V.positive("track_width", track_width)
    a = V.positive("arm_length", arm_length)
    b = V.finite("arm_angle", arm_angle)
    if not 0.0 <= b < _HALF_PI:
        raise ValueError(f"arm_angle must be in [0, pi/2) rad, got {arm_angle!r}")
    tie = W - 2.0 * a * math.sin(b)
    if tie <= 0:
        raise ValueError(f"arm_length must be < track_width / (2 sin(arm_angle)) = "
                         f"{W / (2 * math.sin(b)):g} m so that the tie rod has a length, "
                         f"got {arm_length!r}")
    return W, a, b, tie


def _follower(driver, W, a, b, tie):
    """Right (follower) wheel angle for left (driver) wheel angles, rad (arrays)."""
    # Kingpins: left (0, W/2), right (0, -W/2); arms point back and inward at b.
    ang = math.pi + b + driver
    plx, ply = a * np.cos(ang), W / 2 + a * np.sin(ang)
    dx, dy = plx, ply + W / 2  # from the right kingpin to the left arm's end
    d = np.hypot(dx, dy)
    with np.errstate(all="ignore"):
        c = (a * a + d * d - tie * tie) / (2.0 * a * d)
    V.finite_result("track_width and arm_length", c)
    if np.any(np.abs(c) > 1.0):
        return None
    psi = np.arctan2(dy, dx) + np.arccos(c)
    return psi - (math.pi - b)


@_lengths_by_name
def linkage_angles(inner_angle: ArrayLike, *, track_width: float, arm_length: float,
                   arm_angle: float) -> LinkageAngles:
    r"""Front wheel angles of a trapezoidal (Jeantaud) steering linkage.

    Kingpins at :math:`(0, \pm W/2)`; each carries a steering arm of length :math:`a`
    pointing backward and inward, at the arm angle :math:`\beta` from the x axis; a tie rod of
    length :math:`l = W - 2a\sin\beta` joins the arms' ends. Turning the inner wheel by
    :math:`\delta_i` turns its arm with it; the outer wheel's arm end is then the intersection
    of the circle of radius :math:`a` about its kingpin with the circle of radius :math:`l`
    about the inner arm's end (the branch through the straight-ahead position).

    Parameters
    ----------
    inner_angle : float or array_like
        :math:`\delta_i`, the inner wheel's angle, rad, in (-pi/2, pi/2): > 0 a left turn
        (inner = left wheel), < 0 a right turn (inner = right wheel).
    track_width : float
        :math:`W`, distance between the kingpins, m (> 0).
    arm_length : float
        :math:`a`, m (> 0, with :math:`2a\sin\beta < W`).
    arm_angle : float
        :math:`\beta`, rad, in [0, pi/2) (0: a parallelogram, both wheels at the same angle).

    Returns
    -------
    LinkageAngles
        ``(left, right)``, rad.

    Raises
    ------
    ValueError
        If the linkage cannot reach ``inner_angle`` (the rods would have to stretch).

    Examples
    --------
    >>> left, right = linkage_angles(math.radians(30), track_width=1.5, arm_length=0.15,
    ...                              arm_angle=math.radians(16.7))
    >>> round(math.degrees(left), 4), round(math.degrees(right), 4)
    (30.0, 25.2212)
    >>> parallel = linkage_angles(0.3, track_width=1.5, arm_length=0.15, arm_angle=0.0)
    >>> [round(float(x), 12) for x in parallel]
    [0.3, 0.3]
    """
    d = _steer("inner_angle", inner_angle)
    W, a, b, tie = _linkage_geometry(track_width, arm_length, arm_angle)
    mag = np.abs(d)
    outer = _follower(mag, W, a, b, tie)
    if outer is None:
        raise ValueError(f"inner_angle is beyond the linkage's reach (the tie rod of "
                         f"{tie:g} m cannot join the arms), got {inner_angle!r}")
    left = np.where(d < 0, -outer, mag)
    right = np.where(d < 0, -mag, outer)
    return LinkageAngles(_out(left + 0.0), _out(right + 0.0))


@_lengths_by_name
def linkage_error(inner_angle: ArrayLike, *, wheelbase: float, track_width: float,
                  arm_length: float, arm_angle: float) -> float | NDArray[np.float64]:
    r"""The linkage's Ackermann error: its outer wheel angle minus the Ackermann one.

    .. math:: e(\delta_i) = \delta_o^{link}(\delta_i) - \delta_o^{Ack}(\delta_i)

    with :math:`\delta_o^{Ack}` from :func:`ackermann_outer_angle` and
    :math:`\delta_o^{link}` from :func:`linkage_angles`, signed like the turn (> 0: the
    outer wheel turns too much, towards parallel steering).

    Parameters
    ----------
    inner_angle : float or array_like
        :math:`\delta_i`, rad, in (-pi/2, pi/2).
    wheelbase : float
        :math:`L`, m (> 0).
    track_width, arm_length, arm_angle
        As in :func:`linkage_angles`.

    Returns
    -------
    float or ndarray
        rad.

    Examples
    --------
    >>> round(linkage_error(0.0, wheelbase=2.5, track_width=1.5, arm_length=0.15,
    ...                     arm_angle=0.3), 12)
    0.0
    >>> e = linkage_error(math.radians(30), wheelbase=2.5, track_width=1.5,
    ...                   arm_length=0.15, arm_angle=0.0)   # parallel steering
    >>> round(math.degrees(e), 4)
    6.79
    """
    d = _steer("inner_angle", inner_angle)
    L = V.positive("wheelbase", wheelbase)
    left, right = linkage_angles(d, track_width=track_width, arm_length=arm_length,
                                 arm_angle=arm_angle)
    outer = np.where(d < 0, left, right)
    ideal = ackermann_outer_angle(d, wheelbase=L, track_width=track_width)
    return _out(outer - np.asarray(ideal) + 0.0)


@_lengths_by_name
def jeantaud_arm_angle(*, wheelbase: float, track_width: float) -> float:
    r"""The classic rule's arm angle: the arms' lines meet at the rear axle's midpoint.

    .. math:: \tan\beta_J = \frac{W}{2L}

    Exact only for small steering angles.

    Examples
    --------
    >>> round(math.degrees(jeantaud_arm_angle(wheelbase=2.5, track_width=1.5)), 4)
    16.6992
    """
    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    return math.atan2(W / 2, L)


@_lengths_by_name
def optimal_arm_angle(*, wheelbase: float, track_width: float, arm_length: float,
                      max_inner_angle: float, samples: int = 181,
                      tolerance: float = 1e-7) -> ArmAngle:
    r"""The arm angle that minimises the worst Ackermann error over a steering range.

    Minimises :math:`\max_{\delta_i \in [0, \delta_{max}]} |e(\delta_i)|`
    (:func:`linkage_error`, sampled at ``samples`` evenly spaced inner angles; the linkage is
    mirror-symmetric, so right turns add nothing) over :math:`\beta` by golden-section search
    on :math:`[0, 2\beta_J]` (:func:`jeantaud_arm_angle`), within the angles the linkage can
    be assembled for and can reach :math:`\delta_{max}` with.

    Parameters
    ----------
    wheelbase, track_width, arm_length : float
        :math:`L`, :math:`W`, :math:`a`, m (> 0).
    max_inner_angle : float
        :math:`\delta_{max}`, rad, in (0, pi/2).
    samples : int
        Inner angles at which the error is evaluated (>= 3).
    tolerance : float
        Width of the final bracket of :math:`\beta`, rad (> 0).

    Returns
    -------
    ArmAngle
        ``(arm_angle, worst_error)``, rad.

    Examples
    --------
    >>> best = optimal_arm_angle(wheelbase=2.5, track_width=1.5, arm_length=0.15,
    ...                          max_inner_angle=math.radians(35))
    >>> round(math.degrees(best.arm_angle), 2), round(math.degrees(best.worst_error), 3)
    (23.67, 0.356)
    """
    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    a = V.positive("arm_length", arm_length)
    dmax = V.finite("max_inner_angle", max_inner_angle)
    if not 0 < dmax < _HALF_PI:
        raise ValueError(f"max_inner_angle must be in (0, pi/2) rad, got {max_inner_angle!r}")
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 3:
        raise ValueError(f"samples must be an integer >= 3, got {samples!r}")
    tol = V.positive("tolerance", tolerance)
    grid = np.linspace(0.0, dmax, int(samples))
    t = np.tan(grid)
    ideal = np.arctan(L * t / (L + W * t))

    def worst(beta: float) -> float:
        tie = W - 2.0 * a * math.sin(beta)
        if tie <= 0:
            return math.inf
        outer = _follower(grid, W, a, beta, tie)
        if outer is None:
            return math.inf
        return float(np.max(np.abs(outer - ideal)))

    hi = min(2.0 * math.atan2(W / 2, L), 0.999 * _HALF_PI)
    if 2 * a >= W:
        hi = min(hi, 0.999 * math.asin(W / (2 * a)))
    lo = 0.0
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = worst(x1), worst(x2)
    while hi - lo > tol:
        if f1 <= f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = worst(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = worst(x2)
    beta = 0.5 * (lo + hi)
    err = worst(beta)
    if not math.isfinite(err):
        raise ValueError("arm_length is too long for this track_width and max_inner_angle: "
                         "no arm angle lets the linkage reach max_inner_angle")
    return ArmAngle(beta, err)
