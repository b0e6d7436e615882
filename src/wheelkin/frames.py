r"""Frames: poses, twists, the instantaneous centre of rotation, SE(2).

Our frame (REP-103, :cite:`rep103`)
-----------------------------------
Body frame: x forward, y left, z up; the reference point is the origin of the body frame.
World frame: x east, y north, z up. A pose is :math:`(x, y, \theta)` in the world frame, in
metres and radians, with the heading :math:`\theta` measured counter-clockwise from world +x
and never wrapped in a pose the library returns (it keeps the turns, as odometry does; use
:func:`wrap_angle` where a wrapped angle is meant). A twist is
:math:`(v_x, v_y, \omega)` in the body frame, in m/s and rad/s, with :math:`\omega`
counter-clockwise positive. A positive turning radius :math:`R` is a left turn.

The velocity of a point :math:`p = (p_x, p_y)` fixed to the body is

.. math:: \dot p = v + \omega \times p = (v_x - \omega p_y,\; v_y + \omega p_x),

which vanishes at the instantaneous centre of rotation (ICR)
:math:`p_{\mathrm{ICR}} = (-v_y / \omega,\; v_x / \omega)` when :math:`\omega \ne 0`.

The sources' frames
-------------------
The four sources' conventions and their converters are in :mod:`wheelkin.sources`. Its names
(``firmware_pose_to_ours``, ``rover_twist``, ``mecanum_doc_twist_to_ours``, ``FirmwarePose``,
...) stay importable from this module, where they were first: ``wheelkin.frames.rover_twist``
is ``wheelkin.sources.rover_twist``.

A Pose/Twist in, a Pose/Twist out; arrays in, arrays out
--------------------------------------------------------
A function taking a :class:`Pose`/:class:`Twist` returns one; given an array of shape
``(..., 3)`` it returns an array of shape ``(..., 3)``. Pose and Twist are NamedTuples, so they
unpack (``x, y, theta = pose``). Bad input (NaN, infinity, a wrong shape) raises
``ValueError`` naming the parameter.

>>> compose(Pose(1.0, 0.0, 0.0), Pose(1.0, 0.0, 0.5))
Pose(x=2.0, y=0.0, theta=0.5)
>>> se2_log(Pose(1.0, 0.0, 0.0))
Twist(vx=1.0, vy=0.0, omega=0.0)
"""

from __future__ import annotations

import math
from typing import NamedTuple, TypeAlias, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as V
from wheelkin._kernels import arc_factors
from wheelkin._records import Pose, Stack, Twist, _is_one, _no_negative_zero, _pack

# The sources' converters moved to wheelkin.sources; importable from here as before.
from wheelkin.sources import FirmwarePose as FirmwarePose
from wheelkin.sources import MecanumDocPose as MecanumDocPose
from wheelkin.sources import MecanumDocTwist as MecanumDocTwist
from wheelkin.sources import firmware_pose_to_ours as firmware_pose_to_ours
from wheelkin.sources import lab_pose_to_ours as lab_pose_to_ours
from wheelkin.sources import mecanum_doc_heading_to_ours as mecanum_doc_heading_to_ours
from wheelkin.sources import mecanum_doc_pose_to_ours as mecanum_doc_pose_to_ours
from wheelkin.sources import mecanum_doc_twist_to_ours as mecanum_doc_twist_to_ours
from wheelkin.sources import ours_to_firmware_pose as ours_to_firmware_pose
from wheelkin.sources import ours_to_lab_pose as ours_to_lab_pose
from wheelkin.sources import ours_to_mecanum_doc_heading as ours_to_mecanum_doc_heading
from wheelkin.sources import ours_to_mecanum_doc_pose as ours_to_mecanum_doc_pose
from wheelkin.sources import ours_to_mecanum_doc_twist as ours_to_mecanum_doc_twist
from wheelkin.sources import ours_to_rover_radius as ours_to_rover_radius
from wheelkin.sources import rover_radius_to_ours as rover_radius_to_ours
from wheelkin.sources import rover_twist as rover_twist

__all__ = [
    "HalfTurn",
    "Pose",
    "PoseRate",
    "Twist",
    "compose",
    "field_relative",
    "fold_half_turn",
    "icr",
    "icr_array",
    "integrate_twist",
    "inverse",
    "point_velocity",
    "pose_rate",
    "relative",
    "se2_exp",
    "se2_log",
    "to_field_relative",
    "transform_points",
    "wrap_angle",
]


class HalfTurn(NamedTuple):
    """A steering angle folded into (-pi/2, pi/2], and its rolling sign (see
    :func:`fold_half_turn`)."""

    #: rad, in (-pi/2, pi/2].
    angle: float
    #: +1.0, or -1.0 when the wheel was turned by half a turn (it then rolls backwards).
    sign: float



#: One pose or twist as a record: a Pose (Twist) or a plain tuple of three numbers; the
#: functions below return a record for it (their overloads say so to a type checker).
OnePose: TypeAlias = Pose | tuple[float, float, float]
OneTwist: TypeAlias = Twist | tuple[float, float, float]

# --------------------------------------------------------------------------------------------
# Angles, ICR, point velocities
# --------------------------------------------------------------------------------------------


@overload
def wrap_angle(angle: float) -> float: ...
@overload
def wrap_angle(angle: Stack | tuple[float, ...]) -> NDArray[np.float64]: ...
def wrap_angle(angle: ArrayLike) -> float | NDArray[np.float64]:
    r"""Wrap an angle (rad) to :math:`(-\pi, \pi]`; vectorised.

    An angle already in :math:`(-\pi, \pi]` is returned unchanged (bit for bit), so wrapping
    is idempotent; :math:`-\pi` maps to :math:`\pi`.

    Parameters
    ----------
    angle : float or array_like
        Finite angle(s) in radians.

    Examples
    --------
    >>> wrap_angle(3 * math.pi / 2)
    -1.5707963267948966
    >>> wrap_angle([-math.pi, 0.0, 7.0])
    array([3.14159265, 0.        , 0.71681469])
    """
    out = _kernels.wrap_angle(V.finite_array("angle", angle))
    return float(out) if out.ndim == 0 else out


def fold_half_turn(angle: float) -> HalfTurn:
    r"""A wheel's steering ``angle`` folded into :math:`(-\pi/2, \pi/2]`, and the sign its
    rolling rate takes: a wheel turned half a turn rolls the same line backwards.

    Used wherever a steered wheel is aimed along a direction (the sandbox's ideal commands,
    the unified wheel model), so that no wheel is ever steered past a quarter turn.

    Examples
    --------
    >>> fold_half_turn(0.5)
    HalfTurn(angle=0.5, sign=1.0)
    >>> a, sign = fold_half_turn(math.pi - 0.5)
    >>> round(a, 12), sign
    (-0.5, -1.0)
    """
    a = math.remainder(V.finite("angle", angle), 2 * math.pi)
    if a > math.pi / 2:
        return HalfTurn(a - math.pi, -1.0)
    if a <= -math.pi / 2:
        return HalfTurn(a + math.pi, -1.0)
    return HalfTurn(a, 1.0)


def point_velocity(twist: Twist | ArrayLike, point: ArrayLike) -> NDArray[np.float64]:
    r"""Velocity (m/s, body frame) of a point fixed to the body: :math:`v + \omega \times p`.

    .. math:: \dot p = (v_x - \omega p_y,\; v_y + \omega p_x)

    Parameters
    ----------
    twist : Twist or array_like, shape (3,)
        The body's twist :math:`(v_x, v_y, \omega)`.
    point : array_like, shape (..., 2)
        Point(s) :math:`p` in the body frame, metres.

    Returns
    -------
    numpy.ndarray, shape (..., 2)

    Examples
    --------
    Turning left at 1 rad/s while moving forward at 1 m/s, the point 1 m to the left is still:

    >>> point_velocity(Twist(1.0, 0.0, 1.0), [0.0, 1.0])
    array([0., 0.])
    """
    vx, vy, w = _twist_columns("twist", twist)
    p = V.shaped("point", point, (2,))
    return np.stack([vx - w * p[..., 1], vy + w * p[..., 0]], axis=-1)


def _twist_columns(name: str, twist):
    if isinstance(twist, Twist):
        return twist.vx, twist.vy, twist.omega
    arr = V.shaped(name, twist, (3,))
    return arr[..., 0], arr[..., 1], arr[..., 2]


def icr(twist: Twist | ArrayLike) -> NDArray[np.float64] | None:
    r"""The instantaneous centre of rotation of a planar twist, in the body frame (m).

    .. math:: p_{\mathrm{ICR}} = \left(-\frac{v_y}{\omega},\; \frac{v_x}{\omega}\right)

    the one point of the body (extended) whose velocity :math:`v + \omega \times p` is zero.

    Parameters
    ----------
    twist : Twist or array_like, shape (3,)
        :math:`(v_x, v_y, \omega)` in m/s and rad/s.

    Returns
    -------
    numpy.ndarray, shape (2,), or None
        ``(x, y)`` of the ICR (a point, like :func:`point_velocity`'s); ``None`` when
        :math:`\omega = 0` (a pure translation: the ICR is
        at infinity, perpendicular to :math:`(v_x, v_y)`; at rest it is undefined). For arrays
        of twists use :func:`icr_array`.

    Examples
    --------
    A left turn of radius 2 m (forward at 1 m/s, 0.5 rad/s): the ICR is 2 m to the left.

    >>> icr(Twist(1.0, 0.0, 0.5))
    array([0., 2.])
    >>> icr(Twist(1.0, 0.0, 0.0)) is None
    True
    """
    if not isinstance(twist, Twist):
        twist = Twist.from_array(twist)
    if twist.omega == 0.0:
        return None
    return np.array([-twist.vy / twist.omega, twist.vx / twist.omega]) + 0.0


def icr_array(twists: ArrayLike) -> np.ndarray:
    r"""Vectorised :func:`icr`: shape (..., 3) twists to shape (..., 2) ICRs (m).

    Where :math:`\omega = 0` both coordinates are ``inf`` (the ICR is at infinity).

    Examples
    --------
    >>> icr_array([[1.0, 0.0, 0.5], [1.0, 0.0, 0.0], [0.0, 1.0, -1.0]])
    array([[ 0.,  2.],
           [inf, inf],
           [ 1.,  0.]])
    """
    arr = V.shaped("twists", twists, (3,))
    w = arr[..., 2]
    moving = w != 0.0
    safe = np.where(moving, w, 1.0)
    out = np.stack([-arr[..., 1] / safe, arr[..., 0] / safe], axis=-1) + 0.0
    return np.where(moving[..., None], out, np.inf)


# --------------------------------------------------------------------------------------------
# SE(2): exact integration of a constant twist, composition
# --------------------------------------------------------------------------------------------


@overload
def se2_exp(twist: OneTwist, dt: float = 1.0) -> Pose: ...
@overload
def se2_exp(twist: Stack, dt: float = 1.0) -> NDArray[np.float64]: ...
def se2_exp(twist: Twist | ArrayLike, dt: float = 1.0) -> Pose | NDArray[np.float64]:
    r"""The body-frame displacement after holding ``twist`` constant for ``dt`` seconds.

    Exact (the body moves on a circular arc about the ICR, or straight when
    :math:`\omega = 0`). With :math:`\varphi = \omega\,\Delta t`:

    .. math::
        \Delta x = \Delta t \left(v_x \frac{\sin\varphi}{\varphi}
                    - v_y \frac{1-\cos\varphi}{\varphi}\right),\quad
        \Delta y = \Delta t \left(v_x \frac{1-\cos\varphi}{\varphi}
                    + v_y \frac{\sin\varphi}{\varphi}\right),\quad
        \Delta\theta = \varphi

    (the fractions tend to 1 and 0 as :math:`\varphi \to 0`; they come from
    :func:`wheelkin._kernels.arc_factors`, the library's one small-angle strategy, within a
    few units in the last place of the exact values).

    Parameters
    ----------
    twist : Twist or array_like, shape (..., 3)
        :math:`(v_x, v_y, \omega)` in m/s and rad/s.
    dt : float
        Duration in seconds (finite; negative integrates backwards); 1 s by default, as
        :func:`se2_log`'s, so that ``se2_exp(se2_log(delta))`` is ``delta``.

    Returns
    -------
    Pose or numpy.ndarray, shape (..., 3)
        The displacement :math:`(\Delta x, \Delta y, \Delta\theta)` in the body frame at the
        start (a Pose for a Twist; ``Δθ`` not wrapped).

    Examples
    --------
    A quarter circle of radius 1 m to the left:

    >>> d = se2_exp(Twist(math.pi / 2, 0.0, math.pi / 2), 1.0)
    >>> print(f"{d.x:.6f} {d.y:.6f} {d.theta:.6f}")
    1.000000 1.000000 1.570796
    """
    is_twist = _is_one(twist, Twist)
    vx, vy, w = _twist_columns("twist", twist)
    t = V.finite("dt", dt)
    with np.errstate(all="ignore"):
        a, b = arc_factors(np.asarray(w * t, dtype=float))
        dx = t * (vx * a - vy * b)
        dy = t * (vx * b + vy * a)
        dth = np.asarray(w * t, dtype=float)
    V.finite_result("twist and dt", dx, dy, dth)
    return _pack(Pose, (dx, dy, dth), is_twist)


@overload
def se2_log(delta: OnePose, dt: float = 1.0) -> Twist: ...
@overload
def se2_log(delta: Stack, dt: float = 1.0) -> NDArray[np.float64]: ...
def se2_log(delta: Pose | ArrayLike, dt: float = 1.0) -> Twist | np.ndarray:
    r"""The constant body twist that moves the body by ``delta`` in ``dt`` seconds: the inverse
    of :func:`se2_exp`.

    With :math:`\varphi = \Delta\theta` and :math:`h = (\varphi/2)\cot(\varphi/2)` (1 at
    :math:`\varphi = 0`):

    .. math::
        v_x = \frac{h\,\Delta x + \tfrac{\varphi}{2}\,\Delta y}{\Delta t},\quad
        v_y = \frac{-\tfrac{\varphi}{2}\,\Delta x + h\,\Delta y}{\Delta t},\quad
        \omega = \frac{\varphi}{\Delta t}

    (the arc about the ICR that ends at :math:`(\Delta x, \Delta y)` after turning by
    :math:`\varphi`). :math:`\Delta\theta` is taken as given, not wrapped: a displacement
    that turned by more than half a turn has a different twist than its wrapped heading
    suggests, and a whole turn (:math:`|\Delta\theta| \ge 2\pi`) has none that is unique.

    Parameters
    ----------
    delta : Pose or array_like, shape (..., 3)
        Body-frame displacement :math:`(\Delta x, \Delta y, \Delta\theta)` (m, m, rad),
        :math:`|\Delta\theta| < 2\pi`.
    dt : float
        Duration in seconds (> 0).

    Returns
    -------
    Twist or numpy.ndarray, shape (..., 3)
        :math:`(v_x, v_y, \omega)` (m/s, m/s, rad/s); a Twist for a Pose.

    Examples
    --------
    The quarter circle of radius 1 m of :func:`se2_exp`'s example, back to its twist:

    >>> se2_log(Pose(1.0, 1.0, math.pi / 2))
    Twist(vx=1.5707963267948966, vy=0.0, omega=1.5707963267948966)
    """
    is_pose = _is_one(delta, Pose)
    dx, dy, phi = (np.asarray(c, dtype=float) for c in _pose_columns("delta", delta))
    t = V.positive("dt", dt)
    if np.any(np.abs(phi) >= 2 * math.pi):
        raise ValueError(f"delta's heading change must be in (-2 pi, 2 pi), got {phi!r}")
    half = 0.5 * phi
    h = np.cos(half) / arc_factors(half)[0]  # (phi/2) cot(phi/2) = cos(u) / (sin(u)/u)
    out = ((h * dx + half * dy) / t, (-half * dx + h * dy) / t, phi / t)
    return _pack(Twist, [_no_negative_zero(o) for o in out], is_pose)


def field_relative(twist: Twist | tuple[float, float, float], heading: float) -> Twist:
    r"""A field-relative command (:math:`v_x, v_y` along the world's axes) as the body twist
    of a robot whose heading is :math:`\theta`: the velocity rotated by :math:`-\theta`.

    .. math:: v_x^b = v_x\cos\theta + v_y\sin\theta,\quad
              v_y^b = -v_x\sin\theta + v_y\cos\theta,\quad \omega^b = \omega

    WPILib's ``ChassisSpeeds.fromFieldRelativeSpeeds``: a driver pushes the stick "north" and
    the robot goes north whatever its heading (a holonomic base; a differential drive can
    follow only the part along its heading). The inverse is :func:`to_field_relative`.

    Parameters
    ----------
    twist : Twist or (float, float, float)
        :math:`(v_x, v_y, \omega)` with the velocity in the world frame, m/s and rad/s.
    heading : float
        The robot's heading :math:`\theta` (rad), counter-clockwise from world +x.

    Returns
    -------
    Twist
        The body-frame twist.

    Examples
    --------
    Facing north (+y), "go east at 1 m/s" is "slide right":

    >>> t = field_relative(Twist(1.0, 0.0, 0.0), math.pi / 2)
    >>> print(f"{t.vx:.6f} {t.vy:.6f} {t.omega:.6f}")
    0.000000 -1.000000 0.000000
    """
    vx, vy, w = (V.finite(n, c) for n, c in zip(("vx", "vy", "omega"), _one_twist(twist),
                                                  strict=True))
    th = V.finite("heading", heading)
    c, s = math.cos(th), math.sin(th)
    return Twist(vx * c + vy * s + 0.0, -vx * s + vy * c + 0.0, w)


def to_field_relative(twist: Twist | tuple[float, float, float], heading: float) -> Twist:
    r"""A body twist as a field-relative one (velocity along the world's axes): the inverse
    of :func:`field_relative`, the velocity rotated by :math:`+\theta`.

    Examples
    --------
    >>> t = to_field_relative(field_relative(Twist(1.0, 2.0, 0.5), 0.7), 0.7)
    >>> print(f"{t.vx:.6f} {t.vy:.6f} {t.omega:.6f}")
    1.000000 2.000000 0.500000
    """
    vx, vy, w = (V.finite(n, c) for n, c in zip(("vx", "vy", "omega"), _one_twist(twist),
                                                  strict=True))
    th = V.finite("heading", heading)
    c, s = math.cos(th), math.sin(th)
    return Twist(vx * c - vy * s + 0.0, vx * s + vy * c + 0.0, w)


def _one_twist(twist: object) -> tuple[object, object, object]:
    if isinstance(twist, tuple | list) and len(twist) == 3:
        return twist[0], twist[1], twist[2]
    raise V.InputTypeError(f"twist must be a Twist (vx, vy, omega), got the "
                           f"{type(twist).__name__} {twist!r}")


class PoseRate(NamedTuple):
    r"""The world-frame derivative of a pose: :math:`(\dot x, \dot y, \dot\theta)` in m/s,
    m/s, rad/s."""

    x_dot: float
    y_dot: float
    theta_dot: float


def pose_rate(theta: ArrayLike, twist: Twist | ArrayLike) -> PoseRate | np.ndarray:
    r"""The world-frame rate of change of the pose of a body with heading ``theta`` moving
    with the body-frame ``twist``.

    .. math::
        \dot x = v_x\cos\theta - v_y\sin\theta,\quad
        \dot y = v_x\sin\theta + v_y\cos\theta,\quad
        \dot\theta = \omega

    (the twist rotated into the world frame; integrating it over time with the twist held
    constant gives :func:`se2_exp` composed onto the pose).

    Parameters
    ----------
    theta : float or array_like
        Heading :math:`\theta` (rad), counter-clockwise from world +x.
    twist : Twist or array_like, shape (..., 3)
        :math:`(v_x, v_y, \omega)` in the body frame (m/s, m/s, rad/s); broadcast against
        ``theta``.

    Returns
    -------
    PoseRate or numpy.ndarray, shape (..., 3)
        :math:`(\dot x, \dot y, \dot\theta)` in the world frame; a :class:`PoseRate`
        (a NamedTuple) when ``theta`` is a number and ``twist`` a Twist, an array otherwise
        (as every function here: a Twist in, a record out; an array in, an array out).

    Examples
    --------
    Facing north (+y), driving forward at 2 m/s and sliding left at 1 m/s:

    >>> r = pose_rate(math.pi / 2, Twist(2.0, 1.0, 0.5))
    >>> print(f"{r.x_dot:.6f} {r.y_dot:.6f} {r.theta_dot:.6f}")
    -1.000000 2.000000 0.500000
    """
    th = V.finite_array("theta", theta)
    vx, vy, w = _twist_columns("twist", twist)
    V.broadcast(theta=th, twist=vx)  # names both when their shapes do not broadcast
    th, vx, vy, w = np.broadcast_arrays(th, vx, vy, w)
    c, s = np.cos(th), np.sin(th)
    out = [_no_negative_zero(np.asarray(o, dtype=float))
           for o in (vx * c - vy * s, vx * s + vy * c, w + 0.0 * th)]
    if out[0].ndim == 0 and _is_one(twist, Twist):
        return PoseRate(*(float(o) for o in out))
    return np.stack(out, axis=-1)


@overload
def compose(pose: OnePose, delta: OnePose) -> Pose: ...
@overload
def compose(pose: OnePose | Stack, delta: Stack) -> NDArray[np.float64]: ...
@overload
def compose(pose: Stack, delta: OnePose | Stack) -> NDArray[np.float64]: ...
def compose(pose: Pose | ArrayLike, delta: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The pose reached from ``pose`` by the body-frame displacement ``delta``: pose ⊕ delta.

    .. math::
        x' = x + \Delta x\cos\theta - \Delta y \sin\theta,\quad
        y' = y + \Delta x \sin\theta + \Delta y \cos\theta,\quad
        \theta' = \theta + \Delta\theta

    Parameters
    ----------
    pose, delta : Pose or array_like, shape (..., 3)
        World pose and body-frame displacement (m, m, rad). Broadcast together.

    Returns
    -------
    Pose (if both are Poses) or numpy.ndarray, shape (..., 3)

    Examples
    --------
    Facing north (+y) at (1, 0), 2 m straight ahead is (1, 2):

    >>> p = compose(Pose(1.0, 0.0, math.pi / 2), Pose(2.0, 0.0, 0.0))
    >>> print(f"{p.x:.6f} {p.y:.6f} {p.theta:.6f}")
    1.000000 2.000000 1.570796
    """
    both = _is_one(pose, Pose) and _is_one(delta, Pose)
    x, y, th = _pose_columns("pose", pose)
    dx, dy, dth = _pose_columns("delta", delta)
    _together("pose", x, "delta", dx)
    c, s = np.cos(th), np.sin(th)
    out = (x + c * dx - s * dy, y + s * dx + c * dy, np.asarray(th + dth))
    return _pack(Pose, [_no_negative_zero(np.asarray(o)) for o in out], both)


def _together(name_a: str, a, name_b: str, b, width_b: int = 3) -> None:
    """``ValueError`` naming both parameters unless their stacks of poses (or points) broadcast
    together (shapes (N, 3) and (M, 3) with N != M, neither 1, do not)."""
    try:
        np.broadcast_shapes(np.shape(a), np.shape(b))
    except ValueError:
        raise ValueError(
            f"{name_a} and {name_b} must broadcast together (one and many, or as many of each): "
            f"{name_a} has shape {(*np.shape(a), 3)}, {name_b} shape "
            f"{(*np.shape(b), width_b)}") from None


def _pose_columns(name: str, pose):
    if isinstance(pose, Pose):
        return pose.x, pose.y, pose.theta
    arr = V.shaped(name, pose, (3,))
    return arr[..., 0], arr[..., 1], arr[..., 2]


@overload
def inverse(pose: OnePose) -> Pose: ...
@overload
def inverse(pose: Stack) -> NDArray[np.float64]: ...
def inverse(pose: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    """The inverse pose: ``compose(pose, inverse(pose))`` is the identity.

    Examples
    --------
    >>> p = Pose(1.0, 2.0, 0.3)
    >>> np.round(compose(p, inverse(p)).as_array(), 12)
    array([0., 0., 0.])
    """
    is_pose = _is_one(pose, Pose)
    x, y, th = _pose_columns("pose", pose)
    c, s = np.cos(th), np.sin(th)
    out = (-c * x - s * y, s * x - c * y, -np.asarray(th))
    return _pack(Pose, [_no_negative_zero(np.asarray(o)) for o in out], is_pose)


@overload
def relative(pose_from: OnePose, pose_to: OnePose) -> Pose: ...
@overload
def relative(pose_from: OnePose | Stack, pose_to: Stack) -> NDArray[np.float64]: ...
@overload
def relative(pose_from: Stack, pose_to: OnePose | Stack) -> NDArray[np.float64]: ...
def relative(pose_from: Pose | ArrayLike, pose_to: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    """The displacement of ``pose_to`` seen from ``pose_from`` (in its body frame).

    ``compose(pose_from, relative(pose_from, pose_to))`` equals ``pose_to``.

    Examples
    --------
    >>> d = relative(Pose(1.0, 1.0, math.pi / 2), Pose(1.0, 3.0, math.pi / 2))
    >>> print(f"{d.x:.6f} {d.y:.6f} {d.theta:.6f}")  # 2 m straight ahead
    2.000000 0.000000 0.000000
    """
    both = _is_one(pose_from, Pose) and _is_one(pose_to, Pose)
    x0, y0, th0 = _pose_columns("pose_from", pose_from)
    x1, y1, th1 = _pose_columns("pose_to", pose_to)
    _together("pose_from", x0, "pose_to", x1)
    c, s = np.cos(th0), np.sin(th0)
    dx, dy = x1 - x0, y1 - y0
    out = (c * dx + s * dy, -s * dx + c * dy, np.asarray(th1) - th0)
    return _pack(Pose, [_no_negative_zero(np.asarray(o)) for o in out], both)


def transform_points(pose: Pose | ArrayLike, points: ArrayLike) -> np.ndarray:
    """Body-frame points (m, shape (..., 2)) to world coordinates for a body at ``pose``.

    Examples
    --------
    >>> np.round(transform_points(Pose(1.0, 0.0, math.pi / 2), [[1.0, 0.0], [0.0, 1.0]]), 12)
    array([[1., 1.],
           [0., 0.]])
    """
    x, y, th = _pose_columns("pose", pose)
    p = V.shaped("points", points, (2,))
    _together("pose", x, "points", p[..., 0], 2)
    c, s = np.cos(th), np.sin(th)
    return np.stack([x + c * p[..., 0] - s * p[..., 1], y + s * p[..., 0] + c * p[..., 1]],
                    axis=-1)


def integrate_twist(twists: ArrayLike, dt: float,
                    pose0: Pose | ArrayLike | None = None) -> np.ndarray:
    r"""Poses of a body driven by a sequence of twists, each held constant for ``dt`` seconds.

    Exact for piecewise-constant twists (each step is :func:`se2_exp` composed onto the pose
    before it), and vectorised: the headings are a cumulative sum, and each body-frame step is
    rotated into the world by the heading at its start.

    Parameters
    ----------
    twists : array_like, shape (N, 3)
        Body-frame twists :math:`(v_x, v_y, \omega)`, m/s and rad/s, one per step.
    dt : float
        Step duration in seconds (> 0).
    pose0 : Pose or array_like, shape (3,), optional
        Start pose (default: the origin, heading 0).

    Returns
    -------
    numpy.ndarray, shape (N + 1, 3)
        Poses :math:`(x, y, \theta)` at times 0, dt, ..., N dt (headings not wrapped: the
        sum of the turns, as odometry keeps it).

    Examples
    --------
    A full circle of radius 1 m in 4 steps comes back to the start:

    >>> poses = integrate_twist([[math.pi / 2, 0.0, math.pi / 2]] * 4, 1.0)
    >>> np.round(poses, 12) + 0.0
    array([[ 0.        ,  0.        ,  0.        ],
           [ 1.        ,  1.        ,  1.57079633],
           [ 0.        ,  2.        ,  3.14159265],
           [-1.        ,  1.        ,  4.71238898],
           [ 0.        ,  0.        ,  6.28318531]])
    """
    tw = V.shaped("twists", twists, (3,))
    if tw.ndim != 2:
        raise ValueError(f"twists must have shape (N, 3), got shape {tw.shape}")
    t = V.positive("dt", dt)
    start = np.zeros(3) if pose0 is None else V.pose("pose0", pose0)
    steps = np.asarray(se2_exp(tw, t))  # (N, 3) body-frame displacements
    headings = start[2] + np.concatenate([[0.0], np.cumsum(steps[:, 2])])
    c, s = np.cos(headings[:-1]), np.sin(headings[:-1])
    world_dx = c * steps[:, 0] - s * steps[:, 1]
    world_dy = s * steps[:, 0] + c * steps[:, 1]
    out = np.empty((tw.shape[0] + 1, 3))
    out[:, 0] = start[0] + np.concatenate([[0.0], np.cumsum(world_dx)])
    out[:, 1] = start[1] + np.concatenate([[0.0], np.cumsum(world_dy)])
    out[:, 2] = headings
    return out + 0.0
