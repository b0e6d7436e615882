r"""Frames: poses, twists, the instantaneous centre of rotation, and each source's frame.

Our frame (REP-103, :cite:`rep103`)
-----------------------------------
Body frame: x forward, y left, z up; the reference point is the origin of the body frame.
World frame: x east, y north, z up. A pose is :math:`(x, y, \theta)` in the world frame, in
metres and radians, with the heading :math:`\theta` measured counter-clockwise from world +x
and wrapped to :math:`(-\pi, \pi]` where a wrapped angle is meant. A twist is
:math:`(v_x, v_y, \omega)` in the body frame, in m/s and rad/s, with :math:`\omega`
counter-clockwise positive. A positive turning radius :math:`R` is a left turn.

The velocity of a point :math:`p = (p_x, p_y)` fixed to the body is

.. math:: \dot p = v + \omega \times p = (v_x - \omega p_y,\; v_y + \omega p_x),

which vanishes at the instantaneous centre of rotation (ICR)
:math:`p_{\mathrm{ICR}} = (-v_y / \omega,\; v_x / \omega)` when :math:`\omega \ne 0`.

The sources' frames
-------------------
Each source keeps its own frame and units; these functions convert explicitly.

========  ==========================================  =========================================
source    its convention                              converters
========  ==========================================  =========================================
rover     inches; signed turning radius r > 0 turns   :func:`rover_radius_to_ours`,
          right; unsigned "horizontal" (lateral) and  :func:`ours_to_rover_radius`,
          "vertical" (longitudinal) offsets           :func:`rover_twist`
mecanum   feet, ft/s; body X right, Y forward; world  :func:`mecanum_doc_twist_to_ours`,
          X right (east), Y up (north); headings      :func:`ours_to_mecanum_doc_twist`,
          clockwise from +Y; omega counter-clockwise  :func:`mecanum_doc_heading_to_ours`,
          positive (so the heading rate is -omega)    :func:`mecanum_doc_pose_to_ours` ...
firmware  mm, mrad; world X right, Y forward (the     :func:`firmware_pose_to_ours`,
          start heading); theta counter-clockwise     :func:`ours_to_firmware_pose`
          from +Y: dX = -d sin(theta), dY = d cos
lab       metres; x east, y north, theta counter-     :func:`lab_pose_to_ours`,
          clockwise from +x: the same as ours         :func:`ours_to_lab_pose`
========  ==========================================  =========================================

Scalars in, Pose/Twist out; arrays in, arrays out
-------------------------------------------------
A function taking components (``x, y, theta``) returns a :class:`Pose` or :class:`Twist` when
every component is a scalar, and an array of shape ``(..., 3)`` (columns in our order) when any
is an array. A function taking a :class:`Pose`/:class:`Twist` returns one (or the source's
own NamedTuple: :class:`FirmwarePose`, :class:`MecanumDocPose`, :class:`MecanumDocTwist`, fields
in the source's order); given an array of shape ``(..., 3)`` it returns an array of shape
``(..., 3)``. Pose and Twist are NamedTuples, so they unpack (``x, y, theta = pose``).
Bad input (NaN, infinity, a wrong shape) raises ``ValueError`` naming the parameter.

>>> firmware_pose_to_ours(-100.0, 2000.0, 0.5)
Pose(x=2.0, y=0.1, theta=0.5)
>>> mecanum_doc_twist_to_ours(1.0, 0.0, 0.0)  # 1 ft/s to the right = -0.3048 m/s along y
Twist(vx=0.0, vy=-0.3048, omega=0.0)
"""

from __future__ import annotations

import functools
import math
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as v
from wheelkin._kernels import arc_factors
from wheelkin.units import FOOT, INCH, MM

__all__ = [
    "FirmwarePose",
    "HalfTurn",
    "MecanumDocPose",
    "MecanumDocTwist",
    "Pose",
    "PoseRate",
    "Twist",
    "compose",
    "firmware_pose_to_ours",
    "fold_half_turn",
    "icr",
    "icr_array",
    "integrate_twist",
    "inverse",
    "lab_pose_to_ours",
    "mecanum_doc_heading_to_ours",
    "mecanum_doc_pose_to_ours",
    "mecanum_doc_twist_to_ours",
    "ours_to_firmware_pose",
    "ours_to_lab_pose",
    "ours_to_mecanum_doc_heading",
    "ours_to_mecanum_doc_pose",
    "ours_to_mecanum_doc_twist",
    "ours_to_rover_radius",
    "point_velocity",
    "pose_rate",
    "relative",
    "rover_radius_to_ours",
    "rover_twist",
    "se2_exp",
    "se2_log",
    "transform_points",
    "wrap_angle",
]



# --------------------------------------------------------------------------------------------
# Dataclasses
# --------------------------------------------------------------------------------------------


class Pose(NamedTuple):
    """A planar pose in our world frame: position ``x``, ``y`` (m), heading ``theta`` (rad).

    ``theta`` is counter-clockwise from world +x. It is stored as given (not wrapped); use
    :func:`wrap_angle` where a wrapped heading is meant. A NamedTuple: ``x, y, theta = pose``
    unpacks it, ``pose.x`` names a field, ``np.asarray(pose)`` (or :meth:`as_array`) is the
    array ``[x, y, theta]`` (use the array for arithmetic: ``pose * 2`` repeats a tuple).

    >>> x, y, theta = Pose(1.0, 2.0, 0.5)
    >>> Pose(1.0, 2.0, 0.5).as_array()
    array([1. , 2. , 0.5])
    >>> Pose(1.0, float("nan"), 0.0)
    Traceback (most recent call last):
    ...
    ValueError: y must be a finite number, got nan
    """

    #: m, world +x (east).
    x: float
    #: m, world +y (north).
    y: float
    #: rad, counter-clockwise from world +x (not wrapped).
    theta: float

    def as_array(self) -> np.ndarray:
        """``[x, y, theta]`` as a float array of shape (3,)."""
        return np.array(self, dtype=float)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Pose:
        """A Pose from an array_like ``[x, y, theta]`` of shape (3,)."""
        arr = v.shaped("pose", values, (3,))
        if arr.ndim != 1:
            raise ValueError(f"pose must have shape (3,), got shape {arr.shape}")
        return cls(*arr.tolist())


class Twist(NamedTuple):
    """A planar twist in our body frame: ``vx``, ``vy`` (m/s), ``omega`` (rad/s, CCW +).

    A NamedTuple, like :class:`Pose`: ``vx, vy, omega = twist`` unpacks it, and
    ``np.asarray(twist)`` (or :meth:`as_array`) is the array for arithmetic.

    >>> Twist(0.5, 0.0, 0.25).as_array()
    array([0.5 , 0.  , 0.25])
    >>> Twist(0.5, 0.0, float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: omega must be a finite number, got inf
    """

    #: m/s, forward (body +x).
    vx: float
    #: m/s, to the left (body +y).
    vy: float
    #: rad/s, counter-clockwise positive.
    omega: float

    def as_array(self) -> np.ndarray:
        """``[vx, vy, omega]`` as a float array of shape (3,)."""
        return np.array(self, dtype=float)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Twist:
        """A Twist from an array_like ``[vx, vy, omega]`` of shape (3,)."""
        arr = v.shaped("twist", values, (3,))
        if arr.ndim != 1:
            raise ValueError(f"twist must have shape (3,), got shape {arr.shape}")
        return cls(*arr.tolist())


def _validating_new(cls: Any) -> None:
    """Make a NamedTuple's constructor check that every field is a finite number, naming the
    field (a NamedTuple may not define ``__new__`` in its body; it is replaced here)."""
    plain_new = cls.__new__
    fields = cls._fields

    @functools.wraps(plain_new)  # the signature (x, y, theta) for help() and the docs
    def __new__(klass, *args: float, **kwargs: float):
        values = plain_new(klass, *args, **kwargs)
        return plain_new(klass, *(v.finite(n, x) for n, x in zip(fields, values, strict=True)))

    def _replace(self, **changes: float):  # checked too (the generated one is not)
        return type(self)(**(self._asdict() | changes))

    cls.__new__ = __new__
    cls._replace = _replace
    cls._make = classmethod(lambda klass, iterable: klass(*iterable))
    cls.validates = True  # marks a record the bad-input sweep calls, not only reads


_validating_new(Pose)
_validating_new(Twist)


class FirmwarePose(NamedTuple):
    """A pose in the Radon Ulzer firmware's convention (see :func:`ours_to_firmware_pose`)."""

    #: mm, to the right of the start heading.
    X_mm: float
    #: mm, along the start heading.
    Y_mm: float
    #: rad, counter-clockwise from +Y.
    theta: float


class MecanumDocPose(NamedTuple):
    """A world pose in the mecanum simulator's convention (see
    :func:`ours_to_mecanum_doc_pose`)."""

    #: ft, east.
    X_ft: float
    #: ft, north.
    Y_ft: float
    #: rad, clockwise from +Y.
    psi: float


class MecanumDocTwist(NamedTuple):
    """A body twist in the mecanum simulator's convention (see
    :func:`ours_to_mecanum_doc_twist`)."""

    #: ft/s, to the right.
    Vx_ftps: float
    #: ft/s, forward.
    Vy_ftps: float
    #: rad/s, counter-clockwise positive.
    omega: float


class HalfTurn(NamedTuple):
    """A steering angle folded into (-pi/2, pi/2], and its rolling sign (see
    :func:`fold_half_turn`)."""

    #: rad, in (-pi/2, pi/2].
    angle: float
    #: +1.0, or -1.0 when the wheel was turned by half a turn (it then rolls backwards).
    sign: float


# --------------------------------------------------------------------------------------------
# Helpers: scalars in -> Pose/Twist out, arrays in -> arrays out
# --------------------------------------------------------------------------------------------


def _components(names: tuple[str, ...], values: tuple, *, allow_inf: bool = False):
    """Validate components; return (list of arrays broadcast together, all_scalar)."""
    arrays = [v.finite_array(n, x, allow_inf=allow_inf) for n, x in zip(names, values,
                                                                        strict=True)]
    scalar = all(a.ndim == 0 for a in arrays)
    try:
        arrays = list(np.broadcast_arrays(*arrays))
    except ValueError:
        shapes = ", ".join(f"{n}: {a.shape}" for n, a in zip(names, arrays, strict=True))
        raise ValueError(f"{', '.join(names)} must have the same shape, got {shapes}") from None
    return arrays, scalar


def _pack(cls, columns, scalar: bool):
    if scalar:
        return cls(*(float(c) for c in columns))
    return np.stack([np.asarray(c, dtype=float) for c in columns], axis=-1)


def _unpack(name: str, value, cls):
    """(columns, is_record) from a Pose/Twist or an array (..., 3)."""
    if isinstance(value, cls):
        return list(value.as_array()), True
    if isinstance(value, Pose | Twist):
        raise ValueError(f"{name} must be a {cls.__name__} or an array of shape (..., 3), "
                         f"got a {type(value).__name__}")
    arr = v.shaped(name, value, (3,))
    return [arr[..., 0], arr[..., 1], arr[..., 2]], False


def _unpack_out(columns, is_record: bool, cls):
    if is_record:
        return cls(*(float(c) for c in columns))
    return np.stack(columns, axis=-1)


def _no_negative_zero(a):
    return a + 0.0


# --------------------------------------------------------------------------------------------
# Angles, ICR, point velocities
# --------------------------------------------------------------------------------------------


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
    out = _kernels.wrap_angle(v.finite_array("angle", angle))
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
    a = math.remainder(v.finite("angle", angle), 2 * math.pi)
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
    p = v.shaped("point", point, (2,))
    return np.stack([vx - w * p[..., 1], vy + w * p[..., 0]], axis=-1)


def _twist_columns(name: str, twist):
    if isinstance(twist, Twist):
        return twist.vx, twist.vy, twist.omega
    arr = v.shaped(name, twist, (3,))
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
    arr = v.shaped("twists", twists, (3,))
    w = arr[..., 2]
    moving = w != 0.0
    safe = np.where(moving, w, 1.0)
    out = np.stack([-arr[..., 1] / safe, arr[..., 0] / safe], axis=-1) + 0.0
    return np.where(moving[..., None], out, np.inf)


# --------------------------------------------------------------------------------------------
# SE(2): exact integration of a constant twist, composition
# --------------------------------------------------------------------------------------------


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
    is_twist = isinstance(twist, Twist)
    vx, vy, w = _twist_columns("twist", twist)
    t = v.finite("dt", dt)
    with np.errstate(all="ignore"):
        a, b = arc_factors(np.asarray(w * t, dtype=float))
        dx = t * (vx * a - vy * b)
        dy = t * (vx * b + vy * a)
        dth = np.asarray(w * t, dtype=float)
    v.finite_result("twist and dt", dx, dy, dth)
    return _pack(Pose, (dx, dy, dth), is_twist)


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
    is_pose = isinstance(delta, Pose)
    dx, dy, phi = (np.asarray(c, dtype=float) for c in _pose_columns("delta", delta))
    t = v.positive("dt", dt)
    if np.any(np.abs(phi) >= 2 * math.pi):
        raise ValueError(f"delta's heading change must be in (-2 pi, 2 pi), got {phi!r}")
    half = 0.5 * phi
    h = np.cos(half) / arc_factors(half)[0]  # (phi/2) cot(phi/2) = cos(u) / (sin(u)/u)
    out = ((h * dx + half * dy) / t, (-half * dx + h * dy) / t, phi / t)
    return _pack(Twist, [_no_negative_zero(o) for o in out], is_pose)


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
    th = v.finite_array("theta", theta)
    vx, vy, w = _twist_columns("twist", twist)
    v.broadcast(theta=th, twist=vx)  # names both when their shapes do not broadcast
    th, vx, vy, w = np.broadcast_arrays(th, vx, vy, w)
    c, s = np.cos(th), np.sin(th)
    out = [_no_negative_zero(np.asarray(o, dtype=float))
           for o in (vx * c - vy * s, vx * s + vy * c, w + 0.0 * th)]
    if out[0].ndim == 0 and isinstance(twist, Twist):
        return PoseRate(*(float(o) for o in out))
    return np.stack(out, axis=-1)


def compose(pose: Pose | ArrayLike, delta: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The pose reached from ``pose`` by the body-frame displacement ``delta``: pose ⊕ delta.

    .. math::
        x' = x + \Delta x\cos\theta - \Delta y \sin\theta,\quad
        y' = y + \Delta x \sin\theta + \Delta y \cos\theta,\quad
        \theta' = \operatorname{wrap}(\theta + \Delta\theta)

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
    both = isinstance(pose, Pose) and isinstance(delta, Pose)
    x, y, th = _pose_columns("pose", pose)
    dx, dy, dth = _pose_columns("delta", delta)
    c, s = np.cos(th), np.sin(th)
    out = (x + c * dx - s * dy, y + s * dx + c * dy, wrap_angle(th + dth))
    return _pack(Pose, [_no_negative_zero(np.asarray(o)) for o in out], both)


def _pose_columns(name: str, pose):
    if isinstance(pose, Pose):
        return pose.x, pose.y, pose.theta
    arr = v.shaped(name, pose, (3,))
    return arr[..., 0], arr[..., 1], arr[..., 2]


def inverse(pose: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    """The inverse pose: ``compose(pose, inverse(pose))`` is the identity.

    Examples
    --------
    >>> p = Pose(1.0, 2.0, 0.3)
    >>> np.round(compose(p, inverse(p)).as_array(), 12)
    array([0., 0., 0.])
    """
    is_pose = isinstance(pose, Pose)
    x, y, th = _pose_columns("pose", pose)
    c, s = np.cos(th), np.sin(th)
    out = (-c * x - s * y, s * x - c * y, wrap_angle(-np.asarray(th)))
    return _pack(Pose, [_no_negative_zero(np.asarray(o)) for o in out], is_pose)


def relative(pose_from: Pose | ArrayLike, pose_to: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    """The displacement of ``pose_to`` seen from ``pose_from`` (in its body frame).

    ``compose(pose_from, relative(pose_from, pose_to))`` equals ``pose_to``.

    Examples
    --------
    >>> d = relative(Pose(1.0, 1.0, math.pi / 2), Pose(1.0, 3.0, math.pi / 2))
    >>> print(f"{d.x:.6f} {d.y:.6f} {d.theta:.6f}")  # 2 m straight ahead
    2.000000 0.000000 0.000000
    """
    both = isinstance(pose_from, Pose) and isinstance(pose_to, Pose)
    x0, y0, th0 = _pose_columns("pose_from", pose_from)
    x1, y1, th1 = _pose_columns("pose_to", pose_to)
    c, s = np.cos(th0), np.sin(th0)
    dx, dy = x1 - x0, y1 - y0
    out = (c * dx + s * dy, -s * dx + c * dy, wrap_angle(np.asarray(th1) - th0))
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
    p = v.shaped("points", points, (2,))
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
        Poses :math:`(x, y, \theta)` at times 0, dt, ..., N dt (headings wrapped).

    Examples
    --------
    A full circle of radius 1 m in 4 steps comes back to the start:

    >>> poses = integrate_twist([[math.pi / 2, 0.0, math.pi / 2]] * 4, 1.0)
    >>> np.round(poses, 12) + 0.0
    array([[ 0.        ,  0.        ,  0.        ],
           [ 1.        ,  1.        ,  1.57079633],
           [ 0.        ,  2.        ,  3.14159265],
           [-1.        ,  1.        , -1.57079633],
           [ 0.        ,  0.        ,  0.        ]])
    """
    tw = v.shaped("twists", twists, (3,))
    if tw.ndim != 2:
        raise ValueError(f"twists must have shape (N, 3), got shape {tw.shape}")
    t = v.positive("dt", dt)
    start: np.ndarray
    if pose0 is None:
        start = np.zeros(3)
    elif isinstance(pose0, Pose):
        start = pose0.as_array()
    else:
        start = v.shaped("pose0", pose0, (3,))
        if start.ndim != 1:
            raise ValueError(f"pose0 must have shape (3,), got shape {start.shape}")
    steps = np.asarray(se2_exp(tw, t))  # (N, 3) body-frame displacements
    headings = start[2] + np.concatenate([[0.0], np.cumsum(steps[:, 2])])
    c, s = np.cos(headings[:-1]), np.sin(headings[:-1])
    world_dx = c * steps[:, 0] - s * steps[:, 1]
    world_dy = s * steps[:, 0] + c * steps[:, 1]
    out = np.empty((tw.shape[0] + 1, 3))
    out[:, 0] = start[0] + np.concatenate([[0.0], np.cumsum(world_dx)])
    out[:, 1] = start[1] + np.concatenate([[0.0], np.cumsum(world_dy)])
    out[:, 2] = wrap_angle(headings)
    return out + 0.0


# --------------------------------------------------------------------------------------------
# Rover (JPL Open Source Rover controls walkthrough): inches, r > 0 = right turn
# --------------------------------------------------------------------------------------------


def rover_radius_to_ours(radius_in: ArrayLike) -> float | NDArray[np.float64]:
    r"""The rover document's turning radius (inches, r > 0 = right) as ours (m, R > 0 = left).

    .. math:: R = -0.0254\, r

    The rover walkthrough :cite:`osr_controls` measures the turning radius from the rover's
    centre to the turning point in inches, positive for a right turn. Ours is in metres and
    positive for a left turn. An infinite radius (driving straight) stays infinite, with its
    sign flipped; NaN is rejected.

    Parameters
    ----------
    radius_in : float or array_like
        Rover turning radius in inches (may be ``±inf``).

    Returns
    -------
    float or numpy.ndarray
        Our signed turning radius :math:`R` in metres.

    Examples
    --------
    >>> rover_radius_to_ours(30.0)  # 30 in to the right
    -0.762
    >>> rover_radius_to_ours(-math.inf)
    inf
    """
    r = v.finite_array("radius_in", radius_in, allow_inf=True)
    out = _no_negative_zero(-r * INCH)
    return float(out) if out.ndim == 0 else out


def ours_to_rover_radius(radius_m: ArrayLike) -> float | NDArray[np.float64]:
    """Our turning radius (m, R > 0 = left) as the rover document's (inches, r > 0 = right).

    .. math:: r = -R / 0.0254

    Examples
    --------
    >>> ours_to_rover_radius(-0.762)
    30.0
    """
    r = v.finite_array("radius_m", radius_m, allow_inf=True)
    out = _no_negative_zero(-r / INCH)
    return float(out) if out.ndim == 0 else out


def rover_twist(radius_in: ArrayLike,
                centre_speed_in_per_s: ArrayLike) -> Twist | NDArray[np.float64]:
    r"""Our twist for the rover document's turning radius and the speed of the rover's centre.

    .. math:: v_x = 0.0254\, X,\quad v_y = 0,\quad \omega = v_x / R,\quad R = -0.0254\, r

    where :math:`r` (in) is the rover document's radius (> 0 right) and :math:`X` (in/s) the
    forward speed of the centre of the rover (the midpoint between the middle wheels). An
    infinite radius is straight driving (:math:`\omega = 0`). A radius of 0 (a spin in place)
    cannot be described by a centre speed and is rejected.

    Parameters
    ----------
    radius_in : float or array_like
        Turning radius in inches, > 0 right, ``±inf`` straight; non-zero.
    centre_speed_in_per_s : float or array_like
        Forward speed of the rover's centre in inches per second.

    Returns
    -------
    Twist, or numpy.ndarray of shape (..., 3) for array input

    Examples
    --------
    30 inches to the right at 10 in/s: clockwise, so omega < 0.

    >>> tw = rover_twist(30.0, 10.0)
    >>> print(f"{tw.vx:.4f} {tw.vy:.1f} {tw.omega:.6f}")
    0.2540 0.0 -0.333333
    """
    r = v.finite_array("radius_in", radius_in, allow_inf=True)
    speed = v.finite_array("centre_speed_in_per_s", centre_speed_in_per_s)
    scalar = r.ndim == 0 and speed.ndim == 0
    try:
        r, speed = np.broadcast_arrays(r, speed)
    except ValueError:
        raise ValueError("radius_in and centre_speed_in_per_s must have the same shape, got "
                         f"{r.shape} and {speed.shape}") from None
    if np.any(r == 0):
        raise ValueError("radius_in must be non-zero (a spin in place has no centre speed); "
                         f"got {radius_in!r}")
    vx = speed * INCH
    straight = np.isinf(r)
    big_r = np.where(straight, 1.0, -r * INCH)
    with np.errstate(all="ignore"):
        omega = np.where(straight, 0.0, vx / big_r)
    v.finite_result("radius_in", omega)
    return _pack(Twist, (vx, np.zeros_like(vx), _no_negative_zero(omega)), scalar)


# --------------------------------------------------------------------------------------------
# Mecanum simulator (T. Florida, JHU 2014): feet; body X right, Y forward; headings clockwise
# from +Y; omega counter-clockwise positive
# --------------------------------------------------------------------------------------------


def mecanum_doc_twist_to_ours(Vx_ftps: ArrayLike, Vy_ftps: ArrayLike,
                              omega: ArrayLike) -> Twist | NDArray[np.float64]:
    r"""The mecanum simulator's body twist (ft/s, X right, Y forward) as ours (SI).

    .. math:: v_x = 0.3048\, V_y,\quad v_y = -0.3048\, V_x,\quad \omega = \omega_{doc}

    The simulator :cite:`florida2014mecanum` writes its body velocities with X to the right and
    Y forward, in feet per second. Its rotation rate is counter-clockwise positive (its inverse
    kinematic matrix only matches the wheel layout FL, FR, RL, RR that way), in rad/s, so it
    passes through unchanged, although its headings are clockwise.

    Parameters
    ----------
    Vx_ftps, Vy_ftps : float or array_like
        Rightward and forward speed, ft/s.
    omega : float or array_like
        Yaw rate, rad/s, counter-clockwise positive.

    Returns
    -------
    Twist, or numpy.ndarray of shape (..., 3) for array input

    Examples
    --------
    >>> mecanum_doc_twist_to_ours(0.0, 10.0, 0.5)
    Twist(vx=3.048, vy=0.0, omega=0.5)
    """
    (vx_doc, vy_doc, w), scalar = _components(("Vx_ftps", "Vy_ftps", "omega"),
                                              (Vx_ftps, Vy_ftps, omega))
    return _pack(Twist, (_no_negative_zero(vy_doc * FOOT), _no_negative_zero(-vx_doc * FOOT),
                         w), scalar)


def ours_to_mecanum_doc_twist(twist: Twist | ArrayLike) -> MecanumDocTwist | NDArray[np.float64]:
    r"""Our twist (SI) as the mecanum simulator's ``(Vx_ftps, Vy_ftps, omega)``.

    .. math:: V_x = -v_y / 0.3048,\quad V_y = v_x / 0.3048,\quad \omega_{doc} = \omega

    Parameters
    ----------
    twist : Twist or array_like, shape (..., 3)

    Returns
    -------
    MecanumDocTwist (for a Twist) or numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> ours_to_mecanum_doc_twist(Twist(3.048, -0.6096, 0.5))
    MecanumDocTwist(Vx_ftps=2.0, Vy_ftps=10.0, omega=0.5)
    """
    (vx, vy, w), is_twist = _unpack("twist", twist, Twist)
    return _unpack_out([_no_negative_zero(-np.asarray(vy) / FOOT),
                        _no_negative_zero(np.asarray(vx) / FOOT), np.asarray(w)], is_twist,
                       MecanumDocTwist)


def mecanum_doc_heading_to_ours(psi: ArrayLike) -> float | NDArray[np.float64]:
    r"""The mecanum simulator's heading (rad, clockwise from +Y) as ours (CCW from +x).

    .. math:: \theta = \operatorname{wrap}(\pi/2 - \psi)

    The simulator's user interface gives angles in degrees: convert them first with
    ``wheelkin.units.to_si(psi_deg, "deg")``.

    Examples
    --------
    >>> mecanum_doc_heading_to_ours(0.0)  # facing +Y (north) is our pi/2
    1.5707963267948966
    >>> mecanum_doc_heading_to_ours(math.pi / 2)  # facing +X (east) is our 0
    0.0
    """
    p = v.finite_array("psi", psi)
    return wrap_angle(_no_negative_zero(math.pi / 2 - p))


def ours_to_mecanum_doc_heading(theta: ArrayLike) -> float | NDArray[np.float64]:
    r"""Our heading (rad, CCW from +x) as the mecanum simulator's (clockwise from +Y).

    .. math:: \psi = \operatorname{wrap}(\pi/2 - \theta)

    Examples
    --------
    >>> ours_to_mecanum_doc_heading(math.pi)  # facing west is 270 deg clockwise from north
    -1.5707963267948966
    """
    t = v.finite_array("theta", theta)
    return wrap_angle(_no_negative_zero(math.pi / 2 - t))


def mecanum_doc_pose_to_ours(X_ft: ArrayLike, Y_ft: ArrayLike,
                             psi: ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The mecanum simulator's world pose (ft, ft, rad clockwise from +Y) as ours.

    .. math:: x = 0.3048\, X,\quad y = 0.3048\, Y,\quad
              \theta = \operatorname{wrap}(\pi/2 - \psi)

    Its world X is to the right (east) and Y up the page (north), as ours; only the unit and
    the heading convention differ.

    Examples
    --------
    >>> mecanum_doc_pose_to_ours(10.0, -5.0, 0.0)
    Pose(x=3.048, y=-1.524, theta=1.5707963267948966)
    """
    (x_doc, y_doc, p), scalar = _components(("X_ft", "Y_ft", "psi"), (X_ft, Y_ft, psi))
    return _pack(Pose, (x_doc * FOOT, y_doc * FOOT, np.asarray(mecanum_doc_heading_to_ours(p))),
                 scalar)


def ours_to_mecanum_doc_pose(pose: Pose | ArrayLike) -> MecanumDocPose | NDArray[np.float64]:
    """Our world pose as the mecanum simulator's ``(X_ft, Y_ft, psi)`` (psi clockwise from +Y).

    Examples
    --------
    >>> ours_to_mecanum_doc_pose(Pose(3.048, -1.524, 0.0))
    MecanumDocPose(X_ft=10.0, Y_ft=-5.0, psi=1.5707963267948966)
    """
    (x, y, th), is_pose = _unpack("pose", pose, Pose)
    return _unpack_out([np.asarray(x) / FOOT, np.asarray(y) / FOOT,
                        np.asarray(ours_to_mecanum_doc_heading(th))], is_pose, MecanumDocPose)


# --------------------------------------------------------------------------------------------
# Firmware (Radon Ulzer): mm, mrad; X right, Y forward; theta CCW from +Y
# --------------------------------------------------------------------------------------------


def firmware_pose_to_ours(X_mm: ArrayLike, Y_mm: ArrayLike,
                          theta: ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The Radon Ulzer firmware's pose (mm, mm, rad) as ours (m, m, rad).

    .. math:: x = Y / 1000,\quad y = -X / 1000,\quad \theta = \theta_{fw}

    The firmware :cite:`radonulzer_architecture` puts Y along the start heading and X to its
    right, and measures its orientation counter-clockwise from +Y, so a step :math:`d` moves it
    by :math:`dX = -d \sin\theta`, :math:`dY = d \cos\theta`. Turning that frame so that its
    +Y becomes our +x leaves the heading angle unchanged; it is passed through as given (not
    wrapped: the firmware keeps it in :math:`(-2\pi, 2\pi)`). The firmware stores the
    orientation in mrad: convert with ``wheelkin.units.to_si(theta_mrad, "mrad")`` first.

    Parameters
    ----------
    X_mm, Y_mm : float or array_like
        Position in millimetres (X right of the start heading, Y along it).
    theta : float or array_like
        Orientation in radians, counter-clockwise from +Y.

    Returns
    -------
    Pose, or numpy.ndarray of shape (..., 3) for array input

    Examples
    --------
    >>> firmware_pose_to_ours(0.0, 1000.0, 0.0)  # 1 m straight ahead
    Pose(x=1.0, y=0.0, theta=0.0)
    """
    (x_fw, y_fw, th), scalar = _components(("X_mm", "Y_mm", "theta"), (X_mm, Y_mm, theta))
    return _pack(Pose, (y_fw * MM, _no_negative_zero(-x_fw * MM), th), scalar)


def ours_to_firmware_pose(pose: Pose | ArrayLike) -> FirmwarePose | NDArray[np.float64]:
    r"""Our pose as the Radon Ulzer firmware's ``(X_mm, Y_mm, theta)``.

    .. math:: X = -1000\, y,\quad Y = 1000\, x,\quad \theta_{fw} = \theta

    Examples
    --------
    >>> ours_to_firmware_pose(Pose(2.0, 0.1, 0.5))
    FirmwarePose(X_mm=-100.0, Y_mm=2000.0, theta=0.5)
    """
    (x, y, th), is_pose = _unpack("pose", pose, Pose)
    return _unpack_out([_no_negative_zero(-np.asarray(y) / MM), np.asarray(x) / MM,
                        np.asarray(th)], is_pose, FirmwarePose)


# --------------------------------------------------------------------------------------------
# Lab (Webots waypoint lab): metres, x east, y north, theta CCW from +x: the same as ours
# --------------------------------------------------------------------------------------------


def lab_pose_to_ours(x: ArrayLike, y: ArrayLike, theta: ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The Webots lab's pose as ours: the identity, validated.

    The lab :cite:`webots_waypoint_lab` works in metres with x east, y north and the heading
    counter-clockwise from +x (its position update is :math:`x = x_0 + \Delta x \cos\theta`,
    :math:`y = y_0 + \Delta x \sin\theta`): the same as ours. The converter exists so that
    code says where a number came from, and it still rejects NaN and infinity.

    Examples
    --------
    >>> lab_pose_to_ours(1.5, -1.5, math.pi / 2)
    Pose(x=1.5, y=-1.5, theta=1.5707963267948966)
    """
    (x_lab, y_lab, th), scalar = _components(("x", "y", "theta"), (x, y, theta))
    return _pack(Pose, (x_lab, y_lab, th), scalar)


def ours_to_lab_pose(pose: Pose | ArrayLike) -> Pose | NDArray[np.float64]:
    """Our pose as the Webots lab's ``(x, y, theta)``: the identity, validated.

    Examples
    --------
    >>> ours_to_lab_pose(Pose(1.5, -1.5, 0.25))
    Pose(x=1.5, y=-1.5, theta=0.25)
    """
    (x, y, th), is_pose = _unpack("pose", pose, Pose)
    return _unpack_out([np.asarray(x), np.asarray(y), np.asarray(th)], is_pose, Pose)
