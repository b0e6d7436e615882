r"""The four sources' frames and units, to ours and back.

Each source keeps its own frame and units; these functions convert explicitly. Ours is
REP-103 in SI (:mod:`wheelkin.frames`): x forward, y left, heading counter-clockwise from +x,
metres and radians.

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
firmware  its architecture notes: mm, mrad; world     :func:`firmware_pose_to_ours`,
          X right, Y forward (the start heading);     :func:`ours_to_firmware_pose`
          theta counter-clockwise from +Y: dX = -d
          sin(theta), dY = d cos (its code since
          2023: ours in mm, mrad; see the warning)
lab       metres; x east, y north, theta counter-     :func:`lab_pose_to_ours`,
          clockwise from +x: the same as ours         :func:`ours_to_lab_pose`
========  ==========================================  =========================================

Components in (``X_mm, Y_mm, theta``): a :class:`~wheelkin.frames.Pose` or
:class:`~wheelkin.frames.Twist` when every component is a scalar, an array of shape ``(..., 3)``
(columns in our order) when any is an array. A Pose/Twist in: the source's own NamedTuple out
(:class:`FirmwarePose`, :class:`MecanumDocPose`, :class:`MecanumDocTwist`, fields in the
source's order); an array ``(..., 3)`` in, an array out. Bad input (NaN, infinity, a wrong
shape) raises ``ValueError`` naming the parameter.

Every name here is importable from :mod:`wheelkin.frames` too, where it was first (and where
the chapters' notebooks import it from).

>>> firmware_pose_to_ours(-100.0, 2000.0, 0.5)
Pose(x=2.0, y=0.1, theta=0.5)
>>> mecanum_doc_twist_to_ours(1.0, 0.0, 0.0)  # 1 ft/s to the right = -0.3048 m/s along y
Twist(vx=0.0, vy=-0.3048, omega=0.0)
"""

from __future__ import annotations

import math
from typing import NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as V
from wheelkin._records import (
    Pose,
    Stack,
    Twist,
    _components,
    _no_negative_zero,
    _pack,
    _unpack,
    _unpack_out,
)
from wheelkin.units import FOOT, INCH, MM

__all__ = [
    "FirmwarePose",
    "MecanumDocPose",
    "MecanumDocTwist",
    "firmware_pose_to_ours",
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
    "rover_radius_to_ours",
    "rover_twist",
]


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


def _wrap(angle: np.ndarray) -> float | NDArray[np.float64]:
    """A validated angle wrapped to (-pi, pi] (as :func:`wheelkin.frames.wrap_angle`)."""
    return V.scalar_or_array(_kernels.wrap_angle(np.asarray(angle, dtype=float)))


# --------------------------------------------------------------------------------------------
# Rover (JPL Open Source Rover controls walkthrough): inches, r > 0 = right turn
# --------------------------------------------------------------------------------------------


@overload
def rover_radius_to_ours(radius_in: float) -> float: ...
@overload
def rover_radius_to_ours(radius_in: Stack) -> NDArray[np.float64]: ...
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
    r = V.finite_array("radius_in", radius_in, allow_inf=True)
    out = _no_negative_zero(-r * INCH)
    return float(out) if out.ndim == 0 else out


@overload
def ours_to_rover_radius(radius_m: float) -> float: ...
@overload
def ours_to_rover_radius(radius_m: Stack) -> NDArray[np.float64]: ...
def ours_to_rover_radius(radius_m: ArrayLike) -> float | NDArray[np.float64]:
    """Our turning radius (m, R > 0 = left) as the rover document's (inches, r > 0 = right).

    .. math:: r = -R / 0.0254

    Examples
    --------
    >>> ours_to_rover_radius(-0.762)
    30.0
    """
    r = V.finite_array("radius_m", radius_m, allow_inf=True)
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
    r = V.finite_array("radius_in", radius_in, allow_inf=True)
    speed = V.finite_array("centre_speed_in_per_s", centre_speed_in_per_s)
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
    V.finite_result("radius_in", omega)
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


@overload
def mecanum_doc_heading_to_ours(psi: float) -> float: ...
@overload
def mecanum_doc_heading_to_ours(psi: Stack) -> NDArray[np.float64]: ...
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
    p = V.finite_array("psi", psi)
    return _wrap(_no_negative_zero(math.pi / 2 - p))


@overload
def ours_to_mecanum_doc_heading(theta: float) -> float: ...
@overload
def ours_to_mecanum_doc_heading(theta: Stack) -> NDArray[np.float64]: ...
def ours_to_mecanum_doc_heading(theta: ArrayLike) -> float | NDArray[np.float64]:
    r"""Our heading (rad, CCW from +x) as the mecanum simulator's (clockwise from +Y).

    .. math:: \psi = \operatorname{wrap}(\pi/2 - \theta)

    Examples
    --------
    >>> ours_to_mecanum_doc_heading(math.pi)  # facing west is 270 deg clockwise from north
    -1.5707963267948966
    """
    t = V.finite_array("theta", theta)
    return _wrap(_no_negative_zero(math.pi / 2 - t))


def mecanum_doc_pose_to_ours(X_ft: ArrayLike, Y_ft: ArrayLike,
                             psi: ArrayLike) -> Pose | NDArray[np.float64]:
    r"""The mecanum simulator's world pose (ft, ft, rad clockwise from +Y) as ours.

    .. math:: x = 0.3048\, X,\quad y = 0.3048\, Y,\quad
              \theta = \pi/2 - \psi

    (not wrapped, as every pose the library returns). Its world X is to the right (east) and
    Y up the page (north), as ours; only the unit and the heading convention differ.

    Examples
    --------
    >>> mecanum_doc_pose_to_ours(10.0, -5.0, 0.0)
    Pose(x=3.048, y=-1.524, theta=1.5707963267948966)
    """
    (x_doc, y_doc, p), scalar = _components(("X_ft", "Y_ft", "psi"), (X_ft, Y_ft, psi))
    return _pack(Pose, (x_doc * FOOT, y_doc * FOOT, _no_negative_zero(math.pi / 2 - p)),
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
    r"""A pose in the Radon Ulzer notes' convention (mm, mm, rad) as ours (m, m, rad).

    .. math:: x = Y / 1000,\quad y = -X / 1000,\quad \theta = \theta_{fw}

    The firmware's architecture notes :cite:`radonulzer_architecture` put Y along the start
    heading and X to its right, and measure the orientation counter-clockwise from +Y, so a
    step :math:`d` moves it by :math:`dX = -d \sin\theta`, :math:`dY = d \cos\theta`.
    Turning that frame so that its +Y becomes our +x leaves the heading angle unchanged; it
    is passed through as given (not wrapped: the notes keep it in :math:`(-2\pi, 2\pi)`).
    The firmware stores the orientation in mrad: convert with
    ``wheelkin.units.to_si(theta_mrad, "mrad")`` first.

    .. warning::
       This is the notes' convention, not the current firmware code's. Since March 2023
       (commit b6de7d1 of BlueAndi/RadonUlzer, "Following the REP-103") the firmware's
       odometry puts X along the start heading and Y to its left, with the orientation
       counter-clockwise from +X: our frame in mm and mrad. Convert a pose read off that
       firmware with ``units.to_si(X, "mm")``, ``units.to_si(Y, "mm")`` and
       ``units.to_si(orientation, "mrad")``, not with this function.

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
