r"""Differential drive and skid steer: wheel speeds <-> body twist, in SI and in encoder units.

A differential drive has two driven wheels on one axle, a distance :math:`W` apart (the
*track width*; the Radon Ulzer firmware calls it the *wheel base*), and a passive caster.
Symbols, as in the chapter "Differential drive in encoder units":

========================  ============================================  ================
symbol                    meaning                                       SI / firmware
========================  ============================================  ================
:math:`v`                 forward speed of the axle midpoint            m/s / steps/s
:math:`\omega`            yaw rate, counter-clockwise positive          rad/s / mrad/s
:math:`W`                 track width, wheel centre to wheel centre     m / mm
:math:`v_L,\ v_R`         ground speeds of the left and right wheels    m/s / steps/s
:math:`\mathrm{ENC}`      encoder steps per metre of wheel travel       steps/m
========================  ============================================  ================

In SI, with the REP-103 frame (x forward, y left):

.. math::

    v_L = v - \omega \frac{W}{2}, \qquad v_R = v + \omega \frac{W}{2}, \qquad
    v = \frac{v_L + v_R}{2}, \qquad \omega = \frac{v_R - v_L}{W}.

In the firmware's units (speeds in steps/s, :math:`\omega` in mrad/s, :math:`W` in mm):

.. math::

    v_{L,R} = v \mp \omega \, \frac{W}{2} \, \frac{\mathrm{ENC}}{10^6}.

The module also holds what a microcontroller does with these formulas: the firmware README's
formula as printed (:func:`wheel_speeds_steps_as_printed`, which halves the forward speed),
a faithful 32-bit integer model of the firmware's computation
(:func:`wheel_speeds_steps_int32`, with C's wraparound and truncating division), and the
speedometer that turns encoder counts into speeds (:func:`speed_from_counts`).

Sign convention: the firmware and this module agree, :math:`\omega > 0` turns left
(counter-clockwise seen from above) and makes the right wheel the faster one.

>>> wheel_speeds(0.2, 1.0, 0.085)
WheelSpeeds(left=0.1575, right=0.2425)
>>> v, omega = body_twist(0.1575, 0.2425, 0.085)
>>> v, omega
(0.2, 1.0)

Functions that return several named quantities return a :class:`typing.NamedTuple`
(:class:`WheelSpeeds`, :class:`BodyTwist`, ...): they unpack as before and also have names.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as V
from wheelkin._kernels import c_div, diff_drive_wheel_speeds
from wheelkin._records import Stack, Twist, _components, _pack, _unpack
from wheelkin.units import RADON_ULZER_STEPS_PER_M

__all__ = [
    "INT16_MAX",
    "INT16_MIN",
    "INT32_MAX",
    "INT32_METHODS",
    "INT32_MIN",
    "RADON_ULZER_CONSTANTS",
    "BodyTwist",
    "BodyTwistSteps",
    "CountSpeeds",
    "DiffDriveConstants",
    "FixedPointWheelSpeeds",
    "SkidSteerWheelSpeeds",
    "WheelSpeeds",
    "WheelSpeedsSteps",
    "body_twist",
    "body_twist_steps",
    "c_divide",
    "desaturate",
    "int32_omega_limit",
    "q16_turn_factor",
    "skid_steer_body_twist",
    "skid_steer_wheel_speeds",
    "speed_from_counts",
    "speed_resolution",
    "time_to_count",
    "wheel_speeds",
    "wheel_speeds_steps",
    "wheel_speeds_steps_as_printed",
    "wheel_speeds_steps_int32",
    "wrap_int",
]

INT32_MIN = -(2**31)
INT32_MAX = 2**31 - 1
INT16_MIN = -(2**15)
INT16_MAX = 2**15 - 1

#: Methods of :func:`wheel_speeds_steps_int32`.
INT32_METHODS = ("readme_order", "firmware", "corrected", "q16")


@dataclass(frozen=True)
class DiffDriveConstants:
    r"""The integer constants a differential-drive firmware computes with.

    Parameters
    ----------
    track_width_mm : int
        Track width :math:`W`, wheel centre to wheel centre, in millimetres (> 0).
    steps_per_m : int
        :math:`\mathrm{ENC}`, encoder steps per metre of wheel travel (> 0).

    Examples
    --------
    >>> RADON_ULZER_CONSTANTS.track_width
    0.085
    >>> round(RADON_ULZER_CONSTANTS.metres_per_step * 1e6, 2)  # micrometres per step
    124.33
    """

    track_width_mm: int
    steps_per_m: int

    def __post_init__(self) -> None:
        for name in ("track_width_mm", "steps_per_m"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | np.integer) or value <= 0:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
            object.__setattr__(self, name, int(value))  # a Python int, never a NumPy scalar

    @property
    def track_width(self) -> float:
        """:math:`W` in metres."""
        return self.track_width_mm * 1e-3

    @property
    def metres_per_step(self) -> float:
        r"""Wheel travel per encoder step, in metres (:math:`1/\mathrm{ENC}`)."""
        return 1.0 / self.steps_per_m


#: The Radon Ulzer robot (Pololu Zumo 32U4) as its firmware sees it: W = 85 mm,
#: ENC = 8043 steps/m (12 counts per motor revolution x 75.81 / 0.113097 m = 8043.7,
#: truncated by the firmware's integer arithmetic).
RADON_ULZER_CONSTANTS = DiffDriveConstants(track_width_mm=85, steps_per_m=RADON_ULZER_STEPS_PER_M)


# --------------------------------------------------------------------------------------------
# Helpers
# --------------------------------------------------------------------------------------------

_out = V.scalar_or_array  # one quantity: a float for 0-d, else the array


def _broadcast(**arrays) -> list[np.ndarray]:
    return V.broadcast(**{name: V.finite_array(name, value)
                           for name, value in arrays.items()})


# --------------------------------------------------------------------------------------------
# SI
# --------------------------------------------------------------------------------------------

class WheelSpeeds(NamedTuple):
    """Left and right wheel ground speeds (m/s), each a float or an array."""

    left: Any
    right: Any


class BodyTwist(NamedTuple):
    """A differential drive's twist: forward speed ``v`` (m/s) and yaw rate ``omega`` (rad/s,
    counter-clockwise positive), each a float or an array.

    Two components, not the three of a :class:`~wheelkin.frames.Twist`, on purpose: a
    differential drive's wheels cannot slide sideways, so its sideways speed is zero by
    construction, and a record with a ``vy`` would invite a value the vehicle cannot have.
    :meth:`to_twist` gives the :class:`~wheelkin.frames.Twist` (``vy = 0``) the frame
    functions take; :meth:`from_twist` takes one back and refuses a sideways speed.

    >>> BodyTwist(0.5, 0.2).to_twist()
    Twist(vx=0.5, vy=0.0, omega=0.2)
    >>> BodyTwist.from_twist(Twist(0.5, 0.0, 0.2))
    BodyTwist(v=0.5, omega=0.2)
    >>> BodyTwist.from_twist(Twist(0.5, 0.1, 0.2))
    Traceback (most recent call last):
    ...
    ValueError: twist must have vy = 0 (a differential drive cannot move sideways), got vy = 0.1
    """

    v: Any
    omega: Any

    def to_twist(self) -> Twist | NDArray[np.float64]:
        """The :class:`~wheelkin.frames.Twist` ``(v, 0, omega)``; an array (..., 3) for
        arrays."""
        (v, w), scalar = _components(("v", "omega"), (self.v, self.omega))
        return _pack(Twist, (v, np.zeros_like(v), w), scalar)

    @classmethod
    def from_twist(cls, twist: Twist | ArrayLike) -> BodyTwist:
        """``(vx, omega)`` of a twist whose ``vy`` is zero (a ValueError naming ``twist``
        otherwise); floats for a Twist, arrays for an array (..., 3)."""
        return cls(*_planar(twist))


def _planar(twist: Twist | ArrayLike) -> tuple[Any, Any]:
    """(vx, omega) of a twist without a sideways speed, refusing one that has it."""
    (vx, vy, w), is_record = _unpack("twist", twist, Twist)
    sideways = np.asarray(vy, dtype=float)
    if np.any(sideways != 0.0):
        shown = float(sideways) if sideways.ndim == 0 else f"up to {np.max(np.abs(sideways)):g}"
        raise ValueError(f"twist must have vy = 0 (a differential drive cannot move sideways), "
                         f"got vy = {shown}")
    if is_record:
        return float(vx), float(w)
    return np.asarray(vx, dtype=float), np.asarray(w, dtype=float)


class WheelSpeedsSteps(NamedTuple):
    """Left and right wheel speeds in the firmware's unit, encoder steps/s (floats or
    arrays)."""

    left: Any
    right: Any


class BodyTwistSteps(NamedTuple):
    """A differential drive's twist in the firmware's units: forward speed in steps/s, yaw rate
    in mrad/s (counter-clockwise positive), floats or arrays."""

    v_steps_per_s: Any
    omega_mrad_per_s: Any


class CountSpeeds(NamedTuple):
    """Speeds estimated from encoder counts, and where each estimate was made (see
    :func:`speed_from_counts`)."""

    #: steps/s at each sample.
    speed: np.ndarray
    #: True where a new estimate was made.
    updated: np.ndarray


class SkidSteerWheelSpeeds(NamedTuple):
    """Ground speeds (m/s) of a skid steer's four wheels, FL, FR, RL, RR."""

    fl: Any
    fr: Any
    rl: Any
    rr: Any


def wheel_speeds(v: ArrayLike, omega: ArrayLike, track_width: float) -> WheelSpeeds:
    r"""Left and right wheel ground speeds of a differential drive, from a body twist.

    .. math:: v_L = v - \omega \frac{W}{2}, \qquad v_R = v + \omega \frac{W}{2}

    Parameters
    ----------
    v : float or array_like
        Forward speed :math:`v` of the axle midpoint, m/s.
    omega : float or array_like
        Yaw rate :math:`\omega`, rad/s, counter-clockwise (left turn) positive.
        Broadcasts with ``v``.
    track_width : float
        :math:`W`, distance between the wheel centres, m (> 0).

    Returns
    -------
    WheelSpeeds
        ``(left, right)``: ground speeds of the left and right wheel, m/s (floats for scalar
        input).

    Examples
    --------
    Turning on the spot to the left at 1 rad/s, W = 85 mm:

    >>> wheel_speeds(0.0, 1.0, 0.085)
    WheelSpeeds(left=-0.0425, right=0.0425)
    >>> left, right = wheel_speeds([0.1, 0.2], [0.0, -2.0], 0.085)
    >>> right
    array([0.1  , 0.115])
    """
    v_arr, w_arr = _broadcast(v=v, omega=omega)
    W = V.positive("track_width", track_width)
    with np.errstate(all="ignore"):  # an overflow is refused below, naming the inputs
        left, right = diff_drive_wheel_speeds(v_arr, w_arr, W)
    V.finite_result("v, omega and track_width", left, right)
    return WheelSpeeds(_out(left), _out(right))


def desaturate(v_left: ArrayLike, v_right: ArrayLike, max_speed: float) -> WheelSpeeds:
    r"""Scale both wheel speeds together so that neither exceeds ``max_speed`` in size.

    .. math:: (v_L', v_R') = (v_L, v_R)\,\min\left(1,
              \frac{v_{max}}{\max(|v_L|, |v_R|)}\right)

    WPILib's ``DifferentialDriveWheelSpeeds.desaturate``: the ratio of the two speeds, and so
    the curvature :math:`\omega/v` of the path, is kept; the robot drives the same arc,
    slower. Works as well on wheel rates (rad/s) with a rate limit.

    Parameters
    ----------
    v_left, v_right : float or array_like
        Wheel ground speeds, m/s (broadcast together).
    max_speed : float
        The largest allowed size, m/s (> 0).

    Returns
    -------
    WheelSpeeds
        ``(left, right)``, m/s (floats for scalar input).

    Examples
    --------
    >>> desaturate(1.0, 3.0, 2.0)
    WheelSpeeds(left=0.6666666666666666, right=2.0)
    >>> desaturate(0.5, -1.0, 2.0)  # within the limit: unchanged
    WheelSpeeds(left=0.5, right=-1.0)
    """
    left, right = _broadcast(v_left=v_left, v_right=v_right)
    out = _kernels.desaturate(np.stack([left, right], axis=-1),
                              V.positive("max_speed", max_speed))
    return WheelSpeeds(_out(out[..., 0]), _out(out[..., 1]))


def body_twist(v_left: ArrayLike, v_right: ArrayLike, track_width: float) -> BodyTwist:
    r"""Body twist of a differential drive from its wheel ground speeds; inverse of
    :func:`wheel_speeds`.

    .. math:: v = \frac{v_L + v_R}{2}, \qquad \omega = \frac{v_R - v_L}{W}

    Parameters
    ----------
    v_left, v_right : float or array_like
        Ground speeds of the left and right wheel, m/s (broadcast together).
    track_width : float
        :math:`W`, m (> 0).

    Returns
    -------
    BodyTwist
        ``(v, omega)``: forward speed of the axle midpoint (m/s) and yaw rate (rad/s,
        counter-clockwise +).

    Examples
    --------
    >>> body_twist(0.1, 0.3, 0.1)
    BodyTwist(v=0.2, omega=2.0)
    """
    left, right = _broadcast(v_left=v_left, v_right=v_right)
    w = V.positive("track_width", track_width)
    return BodyTwist(_out(0.5 * (left + right)), _out((right - left) / w))


def skid_steer_wheel_speeds(v: ArrayLike, omega: ArrayLike,
                            track_width: float) -> SkidSteerWheelSpeeds:
    r"""Wheel ground speeds of an ideal skid steer (four wheels, two per side).

    Kinematically a skid steer is a differential drive whose left pair (FL, RL) and right pair
    (FR, RR) each turn together:

    .. math:: v_{FL} = v_{RL} = v - \omega \frac{W}{2}, \qquad
              v_{FR} = v_{RR} = v + \omega \frac{W}{2}

    To turn, the wheels must slide sideways, so on real ground the *effective* :math:`W`
    (fitted from a measured turn) is larger than the geometric track width, by a factor that
    depends on the surface and the load; pass the effective value.

    Parameters
    ----------
    v, omega : float or array_like
        Forward speed (m/s) and yaw rate (rad/s, counter-clockwise +), broadcast together.
    track_width : float
        Effective track width :math:`W`, m (> 0).

    Returns
    -------
    SkidSteerWheelSpeeds
        ``(fl, fr, rl, rr)``: ground speeds front-left, front-right, rear-left, rear-right,
        m/s.

    Examples
    --------
    >>> tuple(skid_steer_wheel_speeds(0.5, 1.0, 0.12))
    (0.44, 0.56, 0.44, 0.56)
    """
    left, right = wheel_speeds(v, omega, track_width)
    return SkidSteerWheelSpeeds(left, right, left, right)


def skid_steer_body_twist(fl: ArrayLike, fr: ArrayLike, rl: ArrayLike, rr: ArrayLike,
                          track_width: float) -> BodyTwist:
    r"""Body twist of an ideal skid steer from its four wheel ground speeds.

    Each side's speed is the mean of its two wheels, then :func:`body_twist`:
    :math:`v_L = (v_{FL} + v_{RL})/2`, :math:`v_R = (v_{FR} + v_{RR})/2`.

    Parameters
    ----------
    fl, fr, rl, rr : float or array_like
        Ground speeds front-left, front-right, rear-left, rear-right, m/s.
    track_width : float
        Effective track width :math:`W`, m (> 0).

    Examples
    --------
    >>> skid_steer_body_twist(0.44, 0.56, 0.44, 0.56, 0.12)
    BodyTwist(v=0.5, omega=1.0)
    """
    a_fl, a_fr, a_rl, a_rr = _broadcast(fl=fl, fr=fr, rl=rl, rr=rr)
    return body_twist(0.5 * (a_fl + a_rl), 0.5 * (a_fr + a_rr), track_width)


# --------------------------------------------------------------------------------------------
# Encoder units, exact (floats)
# --------------------------------------------------------------------------------------------

def _firmware_constants(track_width_mm, steps_per_m) -> tuple[float, float]:
    return (V.positive("track_width_mm", track_width_mm),
            V.positive("steps_per_m", steps_per_m))


def wheel_speeds_steps(
        v_steps_per_s: ArrayLike, omega_mrad_per_s: ArrayLike, track_width_mm: float,
        steps_per_m: float) -> WheelSpeedsSteps:
    r"""Wheel speeds in encoder steps/s from a twist in the firmware's units (exact, floats).

    .. math:: v_L = v - \omega \, \frac{W}{2} \, \frac{\mathrm{ENC}}{10^6}, \qquad
              v_R = v + \omega \, \frac{W}{2} \, \frac{\mathrm{ENC}}{10^6}

    with :math:`v` in steps/s, :math:`\omega` in mrad/s, :math:`W` in mm and ENC in steps/m.
    The :math:`10^6` is :math:`10^3` (mrad -> rad) times :math:`10^3` (mm -> m). This is the
    correct formula; compare :func:`wheel_speeds_steps_as_printed`.

    Parameters
    ----------
    v_steps_per_s : float or array_like
        Forward speed of the axle midpoint, steps/s.
    omega_mrad_per_s : float or array_like
        Yaw rate, mrad/s, counter-clockwise +. Broadcasts with ``v_steps_per_s``.
    track_width_mm : float
        :math:`W`, mm (> 0).
    steps_per_m : float
        ENC, encoder steps per metre (> 0).

    Returns
    -------
    WheelSpeedsSteps
        ``(left, right)`` wheel speeds, steps/s (not rounded), floats or arrays.

    Examples
    --------
    The Radon Ulzer (W = 85 mm, ENC = 8043 steps/m) at 1000 steps/s turning left at
    1 rad/s:

    >>> left, right = wheel_speeds_steps(1000, 1000, 85, 8043)
    >>> print(f"{left:.4f} {right:.4f}")
    658.1725 1341.8275
    """
    v_arr, w_arr = _broadcast(v_steps_per_s=v_steps_per_s, omega_mrad_per_s=omega_mrad_per_s)
    w_mm, enc = _firmware_constants(track_width_mm, steps_per_m)
    turn = w_arr * (0.5 * w_mm * enc / 1e6)
    return WheelSpeedsSteps(_out(v_arr - turn), _out(v_arr + turn))


def body_twist_steps(
        left: ArrayLike, right: ArrayLike, track_width_mm: float,
        steps_per_m: float) -> BodyTwistSteps:
    r"""Twist in the firmware's units from wheel speeds in steps/s; inverse of
    :func:`wheel_speeds_steps`.

    .. math:: v = \frac{v_L + v_R}{2}, \qquad
              \omega = \frac{(v_R - v_L) \cdot 10^6}{W \, \mathrm{ENC}}

    Parameters
    ----------
    left, right : float or array_like
        Left and right wheel speeds :math:`v_L, v_R`, steps/s (broadcast together).
    track_width_mm : float
        :math:`W`, mm (> 0).
    steps_per_m : float
        ENC, steps/m (> 0).

    Returns
    -------
    BodyTwistSteps
        ``(v_steps_per_s, omega_mrad_per_s)``: forward speed of the axle midpoint (steps/s)
        and yaw rate (mrad/s, counter-clockwise +).

    Examples
    --------
    >>> v, omega = body_twist_steps(658.1725, 1341.8275, 85, 8043)
    >>> print(f"{v:.4f} {omega:.4f}")
    1000.0000 1000.0000
    """
    l_arr, r_arr = _broadcast(left=left, right=right)
    w_mm, enc = _firmware_constants(track_width_mm, steps_per_m)
    return BodyTwistSteps(_out(0.5 * (l_arr + r_arr)), _out((r_arr - l_arr) * 1e6 / (w_mm * enc)))


def wheel_speeds_steps_as_printed(
        v_linear_steps_per_s: ArrayLike, omega_mrad_per_s: ArrayLike, track_width_mm: float,
        steps_per_m: float) -> WheelSpeedsSteps:
    r"""The firmware README's wheel-speed formula, as printed. **Wrong**: kept to show the error.

    .. math:: v_{L,R} = \frac{v_{Linear}}{2} \mp
              \frac{\omega \, W}{2 \cdot 1000} \, \frac{\mathrm{ENC}}{1000}

    The unit factors are right, but the forward term is :math:`v_{Linear}/2` instead of
    :math:`v_{Linear}`: the axle midpoint then moves at :math:`(v_L + v_R)/2 = v_{Linear}/2`,
    half the commanded speed. The yaw rate comes out right. Use :func:`wheel_speeds_steps`.

    Parameters
    ----------
    v_linear_steps_per_s : float or array_like
        The commanded forward speed :math:`v_{Linear}` (the README's "linear speed center"),
        steps/s.
    omega_mrad_per_s : float or array_like
        Yaw rate, mrad/s, counter-clockwise +.
    track_width_mm, steps_per_m : float
        :math:`W` (mm) and ENC (steps/m), both > 0.

    Returns
    -------
    WheelSpeedsSteps
        ``(left, right)``: the wheel speeds the printed formula gives, steps/s.

    Examples
    --------
    Commanding 1000 steps/s straight ahead gives wheels at 500 steps/s:

    >>> wheel_speeds_steps_as_printed(1000, 0, 85, 8043)
    WheelSpeedsSteps(left=500.0, right=500.0)
    """
    v_arr, w_arr = _broadcast(v_linear_steps_per_s=v_linear_steps_per_s,
                              omega_mrad_per_s=omega_mrad_per_s)
    w_mm, enc = _firmware_constants(track_width_mm, steps_per_m)
    turn = w_arr * w_mm / (2 * 1000) * enc / 1000
    return WheelSpeedsSteps(_out(v_arr / 2 - turn), _out(v_arr / 2 + turn))


# --------------------------------------------------------------------------------------------
# Integer arithmetic, as a microcontroller does it
# --------------------------------------------------------------------------------------------

@overload
def wrap_int(values: float, bits: int = 32) -> int: ...
@overload
def wrap_int(values: Stack, bits: int = 32) -> NDArray[np.int64]: ...
def wrap_int(values: ArrayLike, bits: int = 32) -> int | NDArray[np.int64]:
    """Two's-complement wraparound of integers to ``bits`` bits, as a C signed integer wraps.

    (Signed overflow is undefined behaviour in the C standard; on the microcontrollers this
    book is about, compiled code wraps exactly like this.)

    Parameters
    ----------
    values : int or array_like of int
        Whole numbers (any size).
    bits : int
        Width of the signed integer: 8, 16, 32 or 64.

    Returns
    -------
    int or numpy.ndarray of int64
        ``values`` reduced into :math:`[-2^{b-1}, 2^{b-1} - 1]`.

    Examples
    --------
    >>> wrap_int(2**31)          # INT32_MAX + 1
    -2147483648
    >>> wrap_int(2 * 1000 * 1000, bits=16)
    -31616
    """
    if isinstance(bits, bool) or not isinstance(bits, int | np.integer) or bits not in (8, 16,
                                                                                     32, 64):
        raise ValueError(f"bits must be one of 8, 16, 32, 64; got {bits!r}")
    arr = _integers("values", values, None)
    m = 1 << bits
    half = 1 << (bits - 1)
    flat = [((int(x) + half) % m) - half for x in arr.ravel()]  # exact Python integers
    out = np.array(flat, dtype=np.int64).reshape(arr.shape)
    return int(out) if out.ndim == 0 else out


@overload
def c_divide(numerator: float, denominator: float) -> int: ...  # type: ignore[overload-overlap]
@overload
def c_divide(numerator: float | Stack, denominator: float | Stack) -> NDArray[np.int64]: ...
def c_divide(numerator: ArrayLike, denominator: ArrayLike) -> int | NDArray[np.int64]:
    """Integer division truncating toward zero, as C's ``/`` on integers does.

    Python's ``//`` floors instead: ``-7 // 2 == -4`` but C gives ``-7 / 2 == -3``.

    Parameters
    ----------
    numerator, denominator : int or array_like of int
        Whole numbers; ``denominator`` must not be 0.

    Returns
    -------
    int or numpy.ndarray of int64

    Examples
    --------
    >>> c_divide(-7, 2), -7 // 2
    (-3, -4)
    >>> c_divide([7, -7, 7, -7], [2, 2, -2, -2])
    array([ 3, -3, -3,  3])
    """
    num = _integers("numerator", numerator, None).astype(object)
    den = _integers("denominator", denominator, None).astype(object)
    try:
        num, den = np.broadcast_arrays(num, den)
    except ValueError:
        raise ValueError("numerator and denominator must have shapes that broadcast together, "
                         f"got {num.shape} and {den.shape}") from None
    if np.any(den == 0):
        raise ValueError("denominator must not be 0")
    flat = [c_div(int(a), int(b)) for a, b in zip(num.ravel(), den.ravel(), strict=True)]
    out = np.array(flat, dtype=np.int64).reshape(num.shape)
    return int(out) if out.ndim == 0 else out


def _integers(name: str, values, limits: tuple[int, int] | None) -> np.ndarray:
    """Whole numbers as an int64 (or, if larger, object) array; ValueError otherwise."""
    if isinstance(values, bool):
        raise ValueError(f"{name} must be whole numbers, got {values!r}")
    if isinstance(values, int | np.integer):
        whole = int(values)
        arr = np.array(whole, dtype=np.int64 if abs(whole) < 2**62 else object)
    else:
        raw = np.asarray(values)
        if raw.dtype == object or raw.dtype.kind == "b":
            if not all(isinstance(x, int | np.integer) and not isinstance(x, bool)
                       for x in raw.ravel()):
                raise ValueError(f"{name} must be whole numbers, got {values!r}")
            arr = raw.astype(object)
        elif raw.dtype.kind in "iu":
            arr = raw.astype(np.int64)
        elif raw.dtype.kind == "f":
            if not np.all(np.isfinite(raw)) or np.any(raw != np.round(raw)):
                raise ValueError(f"{name} must be whole numbers, got {values!r}")
            if np.any(np.abs(raw) >= 2**62):
                raise ValueError(f"{name} must be whole numbers below 2**62, got {values!r}")
            arr = raw.astype(np.int64)
        else:
            raise ValueError(f"{name} must be whole numbers, got {values!r}")
    if limits is not None:
        lo, hi = limits
        if np.any(arr < lo) or np.any(arr > hi):
            raise ValueError(f"{name} must be whole numbers in [{lo}, {hi}], got {values!r}")
    return arr


class FixedPointWheelSpeeds(NamedTuple):
    """Result of :func:`wheel_speeds_steps_int32`.

    Attributes
    ----------
    left, right : int or numpy.ndarray of int64
        Wheel speeds in steps/s, as the firmware would store them (int16).
    overflow : bool or numpy.ndarray of bool
        True where an intermediate product left the int32 range, or a result the int16 range,
        and wrapped around: the value in ``left``/``right`` is then garbage, as on the robot.
    """

    left: int | np.ndarray
    right: int | np.ndarray
    overflow: bool | np.ndarray


def q16_turn_factor(track_width_mm: int, steps_per_m: int) -> int:
    r"""The turn term's constant in Q16 fixed point: :math:`K = \mathrm{round}\!\left(2^{16}
    \, \frac{W \, \mathrm{ENC}}{2 \cdot 10^6}\right)`.

    Computed once, exactly, at compile time (in 64-bit or by hand), so that at run time
    :math:`\omega \, W \, \mathrm{ENC} / (2 \cdot 10^6) \approx (\omega K) / 2^{16}` needs
    one 32-bit product and a shift.

    Examples
    --------
    >>> q16_turn_factor(85, 8043)
    22402
    """
    w = _positive_int("track_width_mm", track_width_mm)
    enc = _positive_int("steps_per_m", steps_per_m)
    num = w * enc * (1 << 16)
    den = 2 * 10**6
    return (2 * num + den) // (2 * den)  # round half up, exact integer arithmetic


def _positive_int(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value <= 0:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def int32_omega_limit(track_width_mm: int, steps_per_m: int) -> int:
    r"""Largest :math:`|\omega|` (whole mrad/s) for which :math:`\omega \, W \, \mathrm{ENC}`
    fits in a signed 32-bit integer.

    .. math:: |\omega|_{max} = \left\lfloor \frac{2^{31} - 1}{W \, \mathrm{ENC}} \right\rfloor

    (The negative side could go one further, to :math:`-2^{31}`, only if the product hit it
    exactly; the symmetric bound is the useful one.)

    Examples
    --------
    >>> int32_omega_limit(85, 8043)   # 3.141 rad/s: the Radon Ulzer cannot turn faster than pi
    3141
    """
    w = _positive_int("track_width_mm", track_width_mm)
    enc = _positive_int("steps_per_m", steps_per_m)
    return INT32_MAX // (w * enc)


def wheel_speeds_steps_int32(v_steps_per_s: ArrayLike, omega_mrad_per_s: ArrayLike,
                             track_width_mm: int = 85,
                             steps_per_m: int = RADON_ULZER_STEPS_PER_M, *,
                             method: str = "firmware") -> FixedPointWheelSpeeds:
    r"""Wheel speeds (steps/s) computed in 32-bit integers, as the firmware's C code does.

    Every product is wrapped to int32 (two's complement, like the hardware), every division
    truncates toward zero (like C's ``/``), and the results are stored in int16 as the
    firmware stores them. Inputs are the firmware's int16 set points.

    ``method`` chooses the computation:

    ``"readme_order"``
        The README's mrad/s formula evaluated literally, left to right, as C would:
        :math:`v_{L,R} = v/2 \mp (((\omega W) / 2000)\,\mathrm{ENC}) / 1000`. The first
        division truncates the turn to whole mm/s: no turn at all for
        :math:`|\omega W| < 2000` (:math:`|\omega| \le 23` mrad/s on the Radon Ulzer), and
        steps of ENC/1000 steps/s above.
    ``"firmware"``
        What the firmware's source does with the README's formula: the forward term is
        halved, :math:`v/2`, and the turn term is evaluated left to right in int32,
        :math:`T = ((\omega W)\,\mathrm{ENC}) / (2\cdot 10^6)`;
        :math:`v_{L,R} = v/2 \mp T`. Wrong forward speed (the README's erratum) and the
        product overflows for :math:`|\omega| >` :func:`int32_omega_limit`.
    ``"corrected"``
        The same order of operations with the correct forward term:
        :math:`v_{L,R} = v \mp T`. Still overflows for large :math:`|\omega|`.
    ``"q16"``
        Correct forward term, and the turn term in Q16 fixed point with a precomputed
        constant :math:`K` (:func:`q16_turn_factor`), rounded to nearest, symmetric in
        :math:`\omega`: :math:`T = \mathrm{sign}(\omega)\,((|\omega| K + 2^{15}) \gg 16)`.
        :math:`|\omega K| < 2^{31}` for every int16 :math:`\omega` with realistic constants,
        and the error is at most half a step per second.

    Parameters
    ----------
    v_steps_per_s : int or array_like of int
        Forward speed set point, steps/s, whole numbers in [-32768, 32767].
    omega_mrad_per_s : int or array_like of int
        Yaw-rate set point, mrad/s, whole numbers in [-32768, 32767]; broadcasts with ``v``.
    track_width_mm : int
        :math:`W`, mm (positive integer). Default: the Radon Ulzer's 85 mm.
    steps_per_m : int
        ENC, steps/m (positive integer). Default: the Radon Ulzer's 8043.
    method : {"readme_order", "firmware", "corrected", "q16"}
        The computation (see above).

    Returns
    -------
    FixedPointWheelSpeeds
        ``(left, right, overflow)``: int16 wheel speeds (steps/s) and where something wrapped.

    Examples
    --------
    >>> wheel_speeds_steps_int32(0, 20, method="readme_order")     # 20 * 85 / 2000 == 0
    FixedPointWheelSpeeds(left=0, right=0, overflow=False)
    >>> wheel_speeds_steps_int32(1000, 1000)                       # the firmware: v halved
    FixedPointWheelSpeeds(left=159, right=841, overflow=False)
    >>> wheel_speeds_steps_int32(1000, 1000, method="corrected")   # exact: 658.17, 1341.83
    FixedPointWheelSpeeds(left=659, right=1341, overflow=False)
    >>> wheel_speeds_steps_int32(0, 3142, method="corrected")      # 3142 * 85 * 8043 > 2**31
    FixedPointWheelSpeeds(left=1073, right=-1073, overflow=True)
    >>> wheel_speeds_steps_int32(0, 3142, method="q16")            # exact: -1074.02, 1074.02
    FixedPointWheelSpeeds(left=-1074, right=1074, overflow=False)
    """
    V.choice("method", method, INT32_METHODS)
    v_int = _integers("v_steps_per_s", v_steps_per_s, (INT16_MIN, INT16_MAX))
    w_int = _integers("omega_mrad_per_s", omega_mrad_per_s, (INT16_MIN, INT16_MAX))
    try:
        v_int, w_int = np.broadcast_arrays(v_int, w_int)
    except ValueError:
        raise ValueError("v_steps_per_s and omega_mrad_per_s must have shapes that broadcast "
                         f"together, got {v_int.shape} and {w_int.shape}") from None
    base = _positive_int("track_width_mm", track_width_mm)
    enc = _positive_int("steps_per_m", steps_per_m)
    if base > INT32_MAX or enc > INT32_MAX:
        raise ValueError("track_width_mm and steps_per_m must fit in int32")

    shape = v_int.shape
    lefts, rights, flags = [], [], []
    k16 = q16_turn_factor(base, enc) if method == "q16" else 0
    for v_i, w_i in zip(v_int.ravel().tolist(), w_int.ravel().tolist(), strict=True):
        overflow = False

        def mul(a: int, b: int) -> int:
            nonlocal overflow
            p = a * b
            if not INT32_MIN <= p <= INT32_MAX:
                overflow = True
                p = ((p - INT32_MIN) % (1 << 32)) + INT32_MIN
            return p

        if method == "q16":
            mag = mul(abs(w_i), k16) + (1 << 15)
            if mag > INT32_MAX:
                overflow = True
            turn = mag >> 16
            turn = -turn if w_i < 0 else turn
            centre = v_i
        elif method == "readme_order":
            turn = c_div(mul(c_div(mul(w_i, base), 2 * 1000), enc), 1000)
            centre = c_div(v_i, 2)
        else:
            turn = c_div(mul(mul(w_i, base), enc), 2 * 1000 * 1000)
            centre = c_div(v_i, 2) if method == "firmware" else v_i
        left, right = centre - turn, centre + turn
        for value in (left, right):
            if not INT16_MIN <= value <= INT16_MAX:
                overflow = True
        lefts.append(((left - INT16_MIN) % (1 << 16)) + INT16_MIN)
        rights.append(((right - INT16_MIN) % (1 << 16)) + INT16_MIN)
        flags.append(overflow)
    if len(shape) == 0:
        return FixedPointWheelSpeeds(lefts[0], rights[0], flags[0])
    return FixedPointWheelSpeeds(np.array(lefts, dtype=np.int64).reshape(shape),
                                 np.array(rights, dtype=np.int64).reshape(shape),
                                 np.array(flags, dtype=bool).reshape(shape))


# --------------------------------------------------------------------------------------------
# Speedometer
# --------------------------------------------------------------------------------------------

@overload
def speed_resolution(window: float, steps_per_m: float) -> float: ...
@overload
def speed_resolution(window: Stack, steps_per_m: float) -> NDArray[np.float64]: ...
def speed_resolution(window: ArrayLike, steps_per_m: float) -> float | NDArray[np.float64]:
    r"""Speed resolution of counting encoder steps over a time window: one step per window.

    .. math:: \Delta v = \frac{1}{T \, \mathrm{ENC}} \quad \text{m/s}
              \qquad \left(= \frac{1}{T} \text{ steps/s}\right)

    Parameters
    ----------
    window : float or array_like
        Counting window :math:`T`, s (> 0).
    steps_per_m : float
        ENC, steps/m (> 0).

    Examples
    --------
    A 10 ms window on the Radon Ulzer resolves 100 steps/s, 12.4 mm/s:

    >>> print(f"{speed_resolution(0.010, 8043) * 1000:.2f} mm/s")
    12.43 mm/s
    """
    t = V.finite_array("window", window)
    if np.any(t <= 0):
        raise ValueError(f"window must be > 0 s, got {window!r}")
    k = V.positive("steps_per_m", steps_per_m)
    with np.errstate(all="ignore"):
        out = 1.0 / (t * k)
    return _out(V.finite_result("window and steps_per_m", out))


@overload
def time_to_count(min_steps: float, speed: float,
                  steps_per_m: float) -> float: ...
@overload
def time_to_count(min_steps: float, speed: Stack,
                  steps_per_m: float) -> NDArray[np.float64]: ...
def time_to_count(min_steps: float, speed: ArrayLike,
                  steps_per_m: float) -> float | NDArray[np.float64]:
    r"""Time a wheel at ``speed`` takes to turn ``min_steps`` encoder steps.

    .. math:: T_{min} = \frac{m}{\mathrm{ENC} \, |v|}

    This is how long a speedometer that waits for :math:`m` steps must wait (its latency).

    Parameters
    ----------
    min_steps : float
        :math:`m`, steps (> 0).
    speed : float or array_like
        Wheel ground speed, m/s (non-zero).
    steps_per_m : float
        ENC, steps/m (> 0).

    Examples
    --------
    Six steps at 0.05 m/s on the Radon Ulzer take 14.9 ms:

    >>> print(f"{time_to_count(6, 0.05, 8043) * 1000:.1f} ms")
    14.9 ms
    """
    m = V.positive("min_steps", min_steps)
    s = V.finite_array("speed", speed)
    if np.any(s == 0):
        raise ValueError(f"speed must be non-zero (a wheel at rest never counts), got {speed!r}")
    k = V.positive("steps_per_m", steps_per_m)
    with np.errstate(all="ignore"):
        out = m / (k * np.abs(s))
    return _out(V.finite_result("speed and steps_per_m", out))


def speed_from_counts(
        counts: ArrayLike, times: ArrayLike, window: float, min_steps: int = 0,
        timeout: float | None = None, *, return_updates: bool = False,
) -> NDArray[np.float64] | CountSpeeds:
    r"""Wheel speed (steps/s) from cumulative encoder counts, as a firmware speedometer does.

    The estimator keeps an *anchor* sample :math:`a` (where it last made an estimate). At each
    later sample :math:`i` it makes a new estimate

    .. math:: \hat v_i = \frac{c_i - c_a}{t_i - t_a}, \qquad a \leftarrow i

    once both :math:`t_i - t_a \ge T` (the ``window``) and :math:`|c_i - c_a| \ge m` (the
    ``min_steps``); otherwise it holds the previous estimate. If ``timeout`` is given and
    :math:`t_i - t_a \ge` ``timeout`` it estimates anyway (so a stopped wheel reads 0).

    - ``min_steps=0``: a fixed window (gate time) :math:`T`. Resolution one step per window,
      :math:`1/T` steps/s (:func:`speed_resolution`), however slow the wheel.
    - ``window=0, min_steps=m``: a minimum step count: every estimate rests on at least
      :math:`m` steps, so its relative error stays below about :math:`1/m`, and the window
      stretches at low speed (:func:`time_to_count`). The Radon Ulzer firmware waits for 6
      steps too, but it reads the counts on every pass of its main loop and stamps them in
      whole milliseconds, so at speed its time stamps, not the count, limit it; sampled
      every 10 ms, this function is a different scheme.

    Parameters
    ----------
    counts : array_like, shape (N,) or (N, k)
        Cumulative encoder counts at each sample (one column per wheel, e.g. L, R).
    times : array_like, shape (N,)
        Sample times, s, strictly increasing.
    window : float
        Minimum time between estimates :math:`T`, s (>= 0).
    min_steps : int
        Minimum :math:`|\Delta c|` for an estimate :math:`m` (>= 0).
    timeout : float, optional
        Longest time without an estimate, s (> 0, >= ``window``); None: hold forever.
    return_updates : bool
        Also return where a new estimate was made.

    Returns
    -------
    numpy.ndarray, same shape as ``counts``, or CountSpeeds
        Estimated speed at each sample, steps/s (0 until the first estimate); with
        ``return_updates=True`` a :class:`CountSpeeds` ``(speed, updated)``, ``updated``
        True at the samples where a new estimate was made (elsewhere the previous one is
        held).

    Examples
    --------
    A wheel counting 4 steps per 10 ms sample, then 5, read with a 20 ms window:

    >>> counts = [0, 4, 8, 13, 18]
    >>> times = [0.00, 0.01, 0.02, 0.03, 0.04]
    >>> speed_from_counts(counts, times, window=0.02)
    array([  0.,   0., 400., 400., 500.])
    """
    c = V.finite_array("counts", counts)
    t = V.finite_array("times", times)
    if c.ndim not in (1, 2) or c.shape[0] < 1:
        raise ValueError(f"counts must have shape (N,) or (N, k) with N >= 1, got {c.shape}")
    if t.shape != (c.shape[0],):
        raise ValueError(f"times must have shape ({c.shape[0]},) to match counts, got {t.shape}")
    if t.size > 1 and np.any(np.diff(t) <= 0):
        raise ValueError("times must be strictly increasing")
    win = V.nonnegative("window", window)
    if not isinstance(return_updates, bool):
        raise ValueError(f"return_updates must be True or False, got {return_updates!r}")
    if isinstance(min_steps, bool) or not float(V.nonnegative("min_steps", min_steps)
                                                ).is_integer():
        raise ValueError(f"min_steps must be a whole number >= 0, got {min_steps!r}")
    m = float(min_steps)
    if timeout is not None:
        tmo = V.positive("timeout", timeout)
        if tmo < win:
            raise ValueError(f"timeout must be >= window ({win:g} s), got {timeout!r}")
    else:
        tmo = math.inf
    cols = c.reshape(c.shape[0], -1)
    out = np.zeros_like(cols)
    updated = np.zeros(cols.shape, dtype=bool)
    eps = 1e-9 * max(1.0, float(np.max(np.abs(t))))  # float times: 0.03 - 0.01 < 0.02
    for j in range(cols.shape[1]):
        col = cols[:, j]
        anchor = 0
        estimate = 0.0
        for i in range(1, t.size):
            dt = t[i] - t[anchor]
            dc = col[i] - col[anchor]
            due = dt >= win - eps and abs(dc) >= m
            if due or dt >= tmo - eps:
                estimate = dc / dt
                anchor = i
                updated[i, j] = True
            out[i, j] = estimate
    if return_updates:
        return CountSpeeds(out.reshape(c.shape), updated.reshape(c.shape))
    return out.reshape(c.shape)
