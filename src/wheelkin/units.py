"""Units: lengths, angles, speeds and encoder steps, converted explicitly to and from SI.

Inside wheelkin every quantity is SI: metres, seconds, radians. The sources the book reads use
inches (the Open Source Rover), feet (the mecanum simulator), millimetres, milliradians and
encoder steps (the Radon Ulzer firmware) and metres (the Webots lab). Nothing here converts
implicitly: a value enters the library through :func:`to_si` (or a constant such as
:data:`INCH`) and leaves it through :func:`from_si`.

Constants are the size of one unit in SI, so ``30 * INCH`` is 30 inches in metres and
``0.762 / INCH`` is 0.762 m in inches.

>>> to_si(30.0, "in")
0.762
>>> from_si(1.0, "ft/s")
3.280839895013123
>>> to_si(1.0, "furlong")
Traceback (most recent call last):
...
ValueError: unit must be one of 'm', 'mm', 'in', 'ft', 'rad', 'mrad', 'deg', 'm/s', 'mm/s',
'in/s', 'ft/s', 'rad/s', 'mrad/s', 'deg/s', 'rpm'; got 'furlong'

A motor's speed in revolutions per minute is a rate like any other:

>>> round(to_si(3000.0, "rpm"), 4)  # rad/s
314.1593
>>> round(from_si(1.0, "rpm"), 4)  # 1 rad/s in rpm
9.5493
"""

from __future__ import annotations

import math
from typing import overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin._records import Stack

__all__ = [
    "DEG",
    "FOOT",
    "INCH",
    "MM",
    "MRAD",
    "RADON_ULZER_COUNTS_PER_MOTOR_REV",
    "RADON_ULZER_GEAR_RATIO",
    "RADON_ULZER_STEPS_PER_M",
    "RADON_ULZER_WHEEL_CIRCUMFERENCE",
    "RPM",
    "UNITS",
    "convert",
    "distance_to_steps",
    "from_si",
    "steps_per_m_from",
    "steps_to_distance",
    "to_si",
]

#: One inch in metres (exact, by the 1959 international yard).
INCH = 0.0254
#: One foot in metres (exact: 12 inches).
FOOT = 0.3048
#: One millimetre in metres.
MM = 1e-3
#: One degree in radians.
DEG = math.pi / 180.0
#: One milliradian in radians.
MRAD = 1e-3
#: One revolution per minute in rad/s: :math:`2\pi/60`.
RPM = 2.0 * math.pi / 60.0

#: Every unit string the library accepts: its size in SI and the SI unit it converts to.
UNITS: dict[str, tuple[float, str]] = {
    "m": (1.0, "m"),
    "mm": (MM, "m"),
    "in": (INCH, "m"),
    "ft": (FOOT, "m"),
    "rad": (1.0, "rad"),
    "mrad": (MRAD, "rad"),
    "deg": (DEG, "rad"),
    "m/s": (1.0, "m/s"),
    "mm/s": (MM, "m/s"),
    "in/s": (INCH, "m/s"),
    "ft/s": (FOOT, "m/s"),
    "rad/s": (1.0, "rad/s"),
    "mrad/s": (MRAD, "rad/s"),
    "deg/s": (DEG, "rad/s"),
    "rpm": (RPM, "rad/s"),
}

#: Radon Ulzer (Pololu Zumo 32U4): encoder counts per revolution of the motor shaft.
RADON_ULZER_COUNTS_PER_MOTOR_REV = 12
#: Radon Ulzer: gear ratio between motor shaft and wheel.
RADON_ULZER_GEAR_RATIO = 75.81
#: Radon Ulzer: wheel circumference in metres (a 36 mm wheel: 36 mm x pi, truncated to 1 um).
RADON_ULZER_WHEEL_CIRCUMFERENCE = 0.113097
#: Radon Ulzer: the firmware's encoder steps per metre. The firmware computes
#: 12 x 75.81 / 0.113097 m = 8043.7 in unsigned integer arithmetic, which truncates to 8043.
RADON_ULZER_STEPS_PER_M = 8043


def _factor(name: str, unit) -> tuple[float, str]:
    if not isinstance(unit, str) or unit not in UNITS:
        V.choice(name, unit, list(UNITS))
    return UNITS[unit]


def _number_or_array(name: str, value):
    arr = V.finite_array(name, value)
    return arr


def _out(arr: np.ndarray):
    return float(arr) if arr.ndim == 0 else arr


@overload
def to_si(value: float, unit: str) -> float: ...
@overload
def to_si(value: Stack, unit: str) -> NDArray[np.float64]: ...
def to_si(value: ArrayLike, unit: str) -> float | NDArray[np.float64]:
    """Convert ``value`` from ``unit`` to SI (m, rad, m/s or rad/s).

    Parameters
    ----------
    value : float or array_like
        Finite number(s) in ``unit``.
    unit : str
        One of the keys of :data:`UNITS`: ``"m"``, ``"mm"``, ``"in"``, ``"ft"``, ``"rad"``,
        ``"mrad"``, ``"deg"``, the same over ``"/s"``, and ``"rpm"`` (revolutions per minute).

    Returns
    -------
    float or numpy.ndarray
        ``value`` times the size of ``unit`` in SI (a float for a scalar input).

    Examples
    --------
    >>> to_si(90.0, "deg")
    1.5707963267948966
    >>> to_si([1000.0, -250.0], "mm/s")
    array([ 1.  , -0.25])
    """
    factor, _ = _factor("unit", unit)
    return _out(_number_or_array("value", value) * factor)


@overload
def from_si(value: float, unit: str) -> float: ...
@overload
def from_si(value: Stack, unit: str) -> NDArray[np.float64]: ...
def from_si(value: ArrayLike, unit: str) -> float | NDArray[np.float64]:
    """Convert ``value`` from SI (m, rad, m/s or rad/s) to ``unit``; inverse of :func:`to_si`.

    Examples
    --------
    >>> from_si(0.762, "in")
    30.0
    >>> from_si(math.pi, "deg")
    180.0
    """
    factor, _ = _factor("unit", unit)
    return _out(_number_or_array("value", value) / factor)


@overload
def convert(value: float, from_unit: str, to_unit: str) -> float: ...
@overload
def convert(value: Stack, from_unit: str, to_unit: str) -> NDArray[np.float64]: ...
def convert(value: ArrayLike, from_unit: str, to_unit: str) -> float | NDArray[np.float64]:
    """Convert ``value`` between two units of the same kind (``ValueError`` if they differ).

    Examples
    --------
    >>> convert(1.0, "ft", "in")
    12.0
    >>> convert(1.0, "ft", "rad")
    Traceback (most recent call last):
    ...
    ValueError: to_unit must be a unit of the same kind as from_unit='ft' (m), got 'rad' (rad)
    """
    f_from, si_from = _factor("from_unit", from_unit)
    f_to, si_to = _factor("to_unit", to_unit)
    if si_from != si_to:
        raise ValueError(f"to_unit must be a unit of the same kind as from_unit={from_unit!r} "
                         f"({si_from}), got {to_unit!r} ({si_to})")
    return _out(_number_or_array("value", value) * (f_from / f_to))


def steps_per_m_from(counts_per_motor_rev: float, gear_ratio: float,
                     wheel_circumference: float) -> float:
    r"""Encoder steps per metre of wheel travel, from the encoder and the drive train.

    .. math:: \mathrm{ENC} = \frac{n_c \, g}{C_w}

    with :math:`n_c` encoder counts per revolution of the motor shaft, :math:`g` the gear ratio
    (motor revolutions per wheel revolution) and :math:`C_w = 2 \pi r_w` the wheel
    circumference in metres. The result is exact (not rounded): firmware that stores it as an
    integer loses the fraction (see :data:`RADON_ULZER_STEPS_PER_M`).

    Parameters
    ----------
    counts_per_motor_rev : float
        Encoder counts per motor revolution (> 0), e.g. 12 for the Zumo 32U4.
    gear_ratio : float
        Motor revolutions per wheel revolution (> 0), e.g. 75.81.
    wheel_circumference : float
        Wheel circumference in metres (> 0).

    Examples
    --------
    The Radon Ulzer robot (12 counts, 75.81:1, a 36 mm wheel):

    >>> round(steps_per_m_from(12, 75.81, 0.113097), 1)
    8043.7
    """
    n = V.positive("counts_per_motor_rev", counts_per_motor_rev)
    g = V.positive("gear_ratio", gear_ratio)
    c = V.positive("wheel_circumference", wheel_circumference)
    return n * g / c


def _metres_per_step(steps_per_m, steps_per_rev, wheel_radius) -> float:
    by_metre = steps_per_m is not None
    by_rev = steps_per_rev is not None or wheel_radius is not None
    if by_metre == by_rev:
        raise ValueError("give exactly one of steps_per_m, or steps_per_rev together with "
                         "wheel_radius")
    if by_metre:
        return 1.0 / V.positive("steps_per_m", steps_per_m)
    if steps_per_rev is None or wheel_radius is None:
        missing = "wheel_radius" if wheel_radius is None else "steps_per_rev"
        raise ValueError(f"{missing} must be given together with "
                         f"{'steps_per_rev' if missing == 'wheel_radius' else 'wheel_radius'}")
    n = V.positive("steps_per_rev", steps_per_rev)
    r = V.positive("wheel_radius", wheel_radius)
    return 2.0 * math.pi * r / n


@overload
def steps_to_distance(steps: float, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> float: ...
@overload
def steps_to_distance(steps: Stack, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> NDArray[np.float64]: ...
def steps_to_distance(steps: ArrayLike, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> float | NDArray[np.float64]:
    r"""Distance in metres travelled by a wheel for ``steps`` encoder steps.

    .. math:: d = \frac{s}{\mathrm{ENC}} \quad\text{or}\quad
              d = \frac{s}{n_r} \, 2 \pi r_w

    Give exactly one description of the encoder: ``steps_per_m`` (:math:`\mathrm{ENC}`, steps
    per metre), or ``steps_per_rev`` (:math:`n_r`, steps per wheel revolution) together with
    ``wheel_radius`` (:math:`r_w`, metres).

    Parameters
    ----------
    steps : float or array_like
        Encoder steps (signed: negative is backwards).

    Returns
    -------
    float or numpy.ndarray
        Distance in metres, same sign as ``steps``.

    Examples
    --------
    >>> steps_to_distance(8043, steps_per_m=8043.7)
    0.999912
    >>> steps_to_distance(909.72, steps_per_rev=909.72, wheel_radius=0.018)
    0.113097
    """
    per_step = _metres_per_step(steps_per_m, steps_per_rev, wheel_radius)
    return _out(V.finite_array("steps", steps) * per_step)


@overload
def distance_to_steps(distance: float, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> float: ...
@overload
def distance_to_steps(distance: Stack, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> NDArray[np.float64]: ...
def distance_to_steps(distance: ArrayLike, *, steps_per_m: float | None = None,
                      steps_per_rev: float | None = None,
                      wheel_radius: float | None = None) -> float | NDArray[np.float64]:
    """Encoder steps (not rounded) for a wheel travel of ``distance`` metres.

    Inverse of :func:`steps_to_distance`, with the same ways to describe the encoder. A real
    encoder counts whole steps: round or floor the result as your firmware does.

    Examples
    --------
    >>> distance_to_steps(10.0, steps_per_m=8043.7)
    80437.0
    >>> distance_to_steps([-0.5, 1.0], steps_per_rev=360, wheel_radius=0.05)
    array([-572.957795, 1145.915590])
    """
    per_step = _metres_per_step(steps_per_m, steps_per_rev, wheel_radius)
    return _out(V.finite_array("distance", distance) / per_step)
