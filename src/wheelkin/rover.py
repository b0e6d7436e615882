r"""The six-wheel, corner-steered rover of JPL's Open Source Rover (OSR).

This module reproduces the rover's controller maths :cite:`osr_controls` in **the document's
own convention**, so that its numbers can be checked one for one. The one exception is
:func:`wheel_commands` (with :class:`RoverCommand`): the rover in SI and REP-103, for a
robot builder.

- lengths in **inches**: the geometry's unit (:class:`RoverGeometry` carries it; the
  defaults are the OSR's inches) for the wheel functions (:func:`wheel_speeds`,
  :func:`corner_angles`, :func:`wheel_distances`, :func:`centre_speed`,
  :func:`min_turning_radius`), always inches for the joystick command
  (:func:`command_to_radius`, :func:`radius_to_command`), :func:`document_twist` and
  :func:`sandbox_commands`;
- a turning radius ``r > 0`` turns **right**, ``r < 0`` turns left (REP-103, and the rest of
  this library, use the opposite sign: :func:`document_twist` converts);
- wheels numbered 1..6 = LF, LM, LB, RF, RM, RB (left front, left middle, left back, right
  front, right middle, right back), the order of every six-element array here;
- corners in the order LF, RF, LB, RB; a corner angle ``delta > 0`` means the wheel's front
  edge is turned toward the rover's **right** (clockwise seen from above).

Geometry (the document's d1..d4, body frame x forward, y left, origin at the body centre, the
middle of the rover)::

    wheel   1 LF       2 LM     3 LB        4 RF        5 RM      6 RB
    x       +d3        0        -d2         +d3         0         -d2
    y       +d1        +d4      +d1         -d1         -d4       -d1

The turning centre (instantaneous centre of rotation, ICR) lies on the line through the two
middle wheels (they cannot steer), at ``(0, -r)``: a distance ``|r|`` to the right of the body
centre when ``r > 0``. Every point of the rigid body turns through the same angle ``theta``
about it, so by S = R theta each wheel's speed is proportional to its distance ``R_i`` to the
ICR. With ``a_i = |r| + s y_i`` (``s`` = sign of r) the lateral distance from the ICR to
wheel i,

.. math::

    R_i = \sqrt{x_i^2 + a_i^2}, \qquad
    V_i = X \, \operatorname{sgn}(a_i) \frac{R_i}{|r| + d_4}, \qquad
    \delta_i = \arctan\frac{x_i}{r + y_i}

where ``X`` is the commanded speed, given to the outer middle wheel (``R = |r| + d4``). For
``r = 30`` in and ``X = 100`` this is the document's table, 96.59, 100, 96.59, 62.52, 49.73,
62.52. The corner hard stops (45 degrees) bound the tightest turn,
``r_min = d1 + max(d2, d3) / tan(45 deg) = 17.754`` in.

The document never says how the joystick's -100..100 steering command becomes a radius;
:func:`command_to_radius` implements the mapping linear in radius (``|r| = 250 - 2.3 |c|``,
so that 100 gives the 20 in software limit) and, for comparison, mappings linear in curvature
and in corner angle.

Examples
--------
>>> import numpy as np
>>> np.round(wheel_speeds(30.0, 100.0), 2)
array([ 96.59, 100.  ,  96.59,  62.52,  49.73,  62.52])
>>> round(min_turning_radius(), 3)
17.754
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, NamedTuple, cast, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin import sources
from wheelkin._records import Stack
from wheelkin.frames import Twist
from wheelkin.units import INCH

__all__ = [
    "CORNER_NAMES",
    "HARD_STOP",
    "OSR_GEOMETRY",
    "OSR_GEOMETRY_SI",
    "OSR_PARAMS_GEOMETRY",
    "OSR_PARAMS_WHEEL_RADIUS",
    "SOFTWARE_MIN_RADIUS",
    "STRAIGHT_THRESHOLD",
    "WHEEL_NAMES",
    "RoverCommand",
    "RoverGeometry",
    "SandboxCommand",
    "centre_speed",
    "command_to_radius",
    "corner_angles",
    "document_twist",
    "min_turning_radius",
    "outer_middle_is_fastest_above",
    "radius_to_command",
    "sandbox_commands",
    "wheel_commands",
    "wheel_distances",
    "wheel_positions",
    "wheel_speeds",
]

#: Order of the six drive wheels in every array of this module (the document's 1..6).
WHEEL_NAMES = ("LF", "LM", "LB", "RF", "RM", "RB")
#: Order of the four steered corners in every array of this module.
CORNER_NAMES = ("LF", "RF", "LB", "RB")
#: The corner motors' physical hard stop (rad): 45 degrees either way.
HARD_STOP = math.radians(45.0)
#: The tightest turn the OSR software allows (in), kept clear of the hard stops.
SOFTWARE_MIN_RADIUS = 20.0
#: Radii at or above this (in) are driven straight by the OSR software.
STRAIGHT_THRESHOLD = 250.0
#: Largest magnitude of the joystick's steering command.
COMMAND_LIMIT = 100.0
#: Radius change per unit of command in the linear-in-radius mapping (in).
_RADIUS_PER_COMMAND = (STRAIGHT_THRESHOLD - SOFTWARE_MIN_RADIUS) / COMMAND_LIMIT  # 2.3 in
_MAPPINGS = ("radius", "curvature", "angle")

# Which corner of the four (LF, RF, LB, RB) is which of the six wheels (1..6).
_CORNER_WHEELS = (0, 3, 2, 5)


@dataclass(frozen=True)
class RoverGeometry:
    """Where the rover's six wheels are, in the document's symbols (any length unit, inches
    for the OSR).

    Parameters
    ----------
    d1 : float
        Lateral distance from the body centre to the four corner wheels (> 0).
    d2 : float
        Longitudinal distance from the body centre back to the back corner wheels (> 0).
    d3 : float
        Longitudinal distance from the body centre forward to the front corner wheels (> 0).
    d4 : float
        Lateral distance from the body centre to the two middle wheels (> 0).
    unit : {"in", "m"}
        The unit of d1..d4, keyword-only and required: inches (the document's) or metres
        (there is no default: a geometry in metres read as inches gave a rover 0.04 times
        its size without an error). The SI functions
        (:func:`wheel_commands`, :func:`wheelkin.unified.rover_wheels`) convert with
        :meth:`in_unit`, so a geometry in either unit gives the same rover; the document's
        functions (:func:`corner_angles`, :func:`wheel_speeds`, ...) work in the geometry's
        unit.

    Examples
    --------
    >>> RoverGeometry(7.254, 10.5, 10.5, 10.073, unit="in") == OSR_GEOMETRY
    True
    >>> round(OSR_GEOMETRY.in_unit("m").d1, 6), OSR_GEOMETRY_SI.unit
    (0.184252, 'm')
    >>> RoverGeometry(7.0, -1.0, 10.0, 10.0, unit="in")
    Traceback (most recent call last):
    ...
    ValueError: d2 must be a finite number > 0, got -1.0
    """

    d1: float
    d2: float
    d3: float
    d4: float
    unit: Literal["in", "m"] = field(kw_only=True)

    def __post_init__(self) -> None:
        for name in ("d1", "d2", "d3", "d4"):
            object.__setattr__(self, name, V.positive(name, getattr(self, name)))
        V.choice("unit", self.unit, ("in", "m"))

    def in_unit(self, unit: Literal["in", "m"]) -> RoverGeometry:
        """The same geometry in ``unit`` ("in" or "m"); itself if already in it."""
        V.choice("unit", unit, ("in", "m"))
        if unit == self.unit:
            return self
        k = INCH if unit == "m" else 1.0 / INCH
        return RoverGeometry(self.d1 * k, self.d2 * k, self.d3 * k, self.d4 * k, unit=unit)


#: The Open Source Rover's base model (inches), from the document's equation 5.
OSR_GEOMETRY = RoverGeometry(d1=7.254, d2=10.5, d3=10.5, d4=10.073, unit="in")
#: The same rover in metres, for the SI functions (:func:`wheel_commands`).
OSR_GEOMETRY_SI = RoverGeometry(d1=7.254 * INCH, d2=10.5 * INCH, d3=10.5 * INCH,
                                d4=10.073 * INCH, unit="m")
#: The OSR as its current software configures it (metres): ``rover_dimensions`` of
#: ``ROS/osr_bringup/config/osr_params.yaml`` in nasa-jpl/osr-rover-code (commit 40f88e78),
#: d1 = 0.184, d2 = d3 = 0.267, d4 = 0.2556 m: the document's inches rounded to the millimetre
#: (within 0.6 mm of :data:`OSR_GEOMETRY_SI`).
OSR_PARAMS_GEOMETRY = RoverGeometry(d1=0.184, d2=0.267, d3=0.267, d4=0.2556, unit="m")
#: The OSR's wheel radius in the same file, m.
OSR_PARAMS_WHEEL_RADIUS = 0.075


def _geometry(geometry) -> RoverGeometry:
    if not isinstance(geometry, RoverGeometry):
        raise ValueError(f"geometry must be a RoverGeometry, got {type(geometry).__name__}")
    return geometry


def wheel_positions(geometry: RoverGeometry = OSR_GEOMETRY) -> np.ndarray:
    """The six wheels' contact points (x forward, y left) in the body frame, wheels LF, LM,
    LB, RF, RM, RB, shape (6, 2), in the geometry's unit.

    Examples
    --------
    >>> wheel_positions()
    array([[ 10.5  ,   7.254],
           [  0.   ,  10.073],
           [-10.5  ,   7.254],
           [ 10.5  ,  -7.254],
           [  0.   , -10.073],
           [-10.5  ,  -7.254]])
    """
    g = _geometry(geometry)
    return np.array([[g.d3, g.d1], [0.0, g.d4], [-g.d2, g.d1],
                     [g.d3, -g.d1], [0.0, -g.d4], [-g.d2, -g.d1]])


def min_turning_radius(geometry: RoverGeometry = OSR_GEOMETRY,
                       max_corner_angle: float = HARD_STOP) -> float:
    r"""The tightest turn the corner hard stops allow (the geometry's unit).

    The inner corners steer the most; an inner corner at longitudinal distance ``d`` reaches
    the stop ``delta_max`` when ``tan(delta_max) = d / (r - d1)``, so

    .. math:: r_{min} = d_1 + \frac{\max(d_2, d_3)}{\tan \delta_{max}}

    (the document's equation 14 has ``d3`` only: there ``d2 = d3``).

    Parameters
    ----------
    geometry : RoverGeometry
    max_corner_angle : float
        The hard stop (rad), in (0, pi/2).

    Examples
    --------
    >>> round(min_turning_radius(), 3)
    17.754
    >>> round(min_turning_radius(max_corner_angle=math.radians(35)), 4)
    22.2496
    """
    g = _geometry(geometry)
    angle = V.in_range("max_corner_angle", max_corner_angle, 0.0, math.pi / 2,
                               inclusive=False)
    with np.errstate(all="ignore"):
        out = g.d1 + max(g.d2, g.d3) / np.tan(angle)
    return float(V.finite_result("max_corner_angle", out))


def outer_middle_is_fastest_above(geometry: RoverGeometry = OSR_GEOMETRY) -> float:
    r"""The radius above which the outer middle wheel is the fastest of the six (the
    geometry's unit; 0 if it always is).

    The outer corner at ``d`` (the larger of d2, d3) is farther from the ICR than the outer
    middle wheel when ``d^2 + (d1 + r)^2 > (d4 + r)^2``, that is (for ``d4 > d1``) when

    .. math:: r < r^* = \frac{1}{2}\left(\frac{d^2}{d_4 - d_1} - d_4 - d_1\right)

    For ``d4 <= d1`` the outer corners are always farther: ``inf`` is returned.

    Examples
    --------
    >>> round(outer_middle_is_fastest_above(), 3)
    10.892
    >>> outer_middle_is_fastest_above(RoverGeometry(7.254, 10.5, 10.5, 7.0, unit="in"))
    inf
    """
    g = _geometry(geometry)
    if g.d4 <= g.d1:
        return math.inf
    d = max(g.d2, g.d3)
    return max(0.0, 0.5 * (d * d / (g.d4 - g.d1) - g.d4 - g.d1))


def _radius(radius, geometry: RoverGeometry, max_corner_angle: float) -> np.ndarray:
    """Validated turning radius (inf allowed, meaning straight)."""
    r = V.finite_array("radius", radius, allow_inf=True)
    r_min = min_turning_radius(geometry, max_corner_angle)
    bad = np.abs(r) < r_min * (1.0 - 1e-12)  # tan(pi/4) rounds below 1: accept 17.754 itself
    if np.any(bad):
        first = float(r[bad].flat[0]) if r.ndim else float(r)
        raise ValueError(
            f"radius must satisfy |radius| >= {r_min:.6g} (the tightest turn the "
            f"{math.degrees(max_corner_angle):.6g} degree corner stops allow), or be +-inf to "
            f"drive straight; got {first!r}")
    return r


def _scalar_radius(radius) -> float:
    """One turning radius (inf allowed, meaning straight) as a float."""
    r = V.finite_array("radius", radius, allow_inf=True)
    if r.ndim != 0:
        raise ValueError(f"radius must be one number (inf allowed), got shape {r.shape}")
    return float(r)


def _threshold(straight_threshold, geometry: RoverGeometry) -> float:
    """The straight-ahead threshold in the geometry's unit (None: the OSR's 250 in)."""
    if straight_threshold is None:
        return STRAIGHT_THRESHOLD * (1.0 if geometry.unit == "in" else INCH)
    t = V.finite_array("straight_threshold", straight_threshold, allow_inf=True)
    if t.ndim != 0 or not t > 0:
        raise ValueError(f"straight_threshold must be a number > 0 (inf allowed), got "
                         f"{straight_threshold!r}")
    return float(t)


def wheel_distances(radius: ArrayLike, geometry: RoverGeometry = OSR_GEOMETRY, *,
                    max_corner_angle: float = HARD_STOP) -> np.ndarray:
    r"""Each wheel's distance ``R_i`` to the turning centre, wheels LF, LM, LB, RF, RM, RB.

    .. math:: R_i = \sqrt{x_i^2 + (|r| + s\,y_i)^2}, \quad s = \operatorname{sgn} r

    For ``r > 0`` (right turn) these are the document's equations 4 and 7-12:
    ``R1 = sqrt(d3^2 + (d1 + r)^2)``, ``R2 = r + d4``, ``R3 = sqrt(d2^2 + (d1 + r)^2)``,
    ``R4 = sqrt(d3^2 + (r - d1)^2)``, ``R5 = |r - d4|``, ``R6 = sqrt(d2^2 + (r - d1)^2)``.

    Parameters
    ----------
    radius : float or array
        Turning radius of the body centre (document sign: > 0 turns right), ``|radius| >=
        min_turning_radius(geometry, max_corner_angle)``; ``inf`` gives infinite distances.
    geometry : RoverGeometry
    max_corner_angle : float
        The corner hard stop (rad) that sets the smallest radius accepted.

    Returns
    -------
    ndarray, shape ``radius.shape + (6,)``, in the geometry's unit.

    Examples
    --------
    >>> np.round(wheel_distances(30.0), 3)
    array([38.705, 40.073, 38.705, 25.053, 19.927, 25.053])
    >>> np.round(wheel_distances(-30.0), 3)  # a left turn mirrors it
    array([25.053, 19.927, 25.053, 38.705, 40.073, 38.705])
    """
    g = _geometry(geometry)
    r = _radius(radius, g, max_corner_angle)
    pos = wheel_positions(g)
    finite = np.isfinite(r)
    rr = np.where(finite, r, 0.0)[..., None]
    a = np.abs(rr) + np.sign(rr) * pos[:, 1]
    dist = np.hypot(pos[:, 0], a)
    return np.where(finite[..., None], dist, np.inf)


def wheel_speeds(radius: ArrayLike, speed: ArrayLike, geometry: RoverGeometry = OSR_GEOMETRY,
                 straight_threshold: float | None = None, *,
                 max_corner_angle: float = HARD_STOP) -> np.ndarray:
    r"""The six drive wheels' speeds, wheels LF, LM, LB, RF, RM, RB (the document's 1..6).

    The outer middle wheel (LM in a right turn, RM in a left turn) gets ``speed``; every other
    wheel scales by its distance to the turning centre (S = R theta, the same theta for all):

    .. math:: V_i = X \operatorname{sgn}(a_i) \frac{R_i}{|r| + d_4},
              \qquad a_i = |r| + s\,y_i

    which for ``r > 0`` are the document's equations 7-12. The sign factor only matters for
    an inner middle wheel on the far side of the ICR (``|r| < d4``, possible for geometries
    other than the OSR's): it then turns backwards. At ``|radius| >= straight_threshold``
    (or infinite) the rover drives straight and every wheel gets ``speed``.

    Parameters
    ----------
    radius : float or array
        Turning radius of the body centre (document sign: > 0 turns right; +-inf straight).
    speed : float or array
        The commanded speed ``X`` (any unit: the document's percent, or in/s); broadcast with
        ``radius``. Negative drives backwards.
    geometry : RoverGeometry
    straight_threshold : float, optional
        Radii at or beyond this are driven straight, in the geometry's unit (default: the
        document's 250 in, converted for a metric geometry).
    max_corner_angle : float
        The corner hard stop (rad); a tighter radius raises ``ValueError``.

    Returns
    -------
    ndarray, shape ``broadcast(radius, speed).shape + (6,)``, in the unit of ``speed``.

    Examples
    --------
    >>> np.round(wheel_speeds(30.0, 100.0), 2)  # the document's table
    array([ 96.59, 100.  ,  96.59,  62.52,  49.73,  62.52])
    >>> np.round(wheel_speeds(-30.0, 100.0), 2)  # left turn: the sides swap
    array([ 62.52,  49.73,  62.52,  96.59, 100.  ,  96.59])
    >>> wheel_speeds(300.0, 50.0)  # beyond 250 in: straight
    array([50., 50., 50., 50., 50., 50.])
    >>> wheel_speeds(10.0, 50.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: radius must satisfy |radius| >= 17.754 (the tightest turn the 45 degree ...
    """
    g = _geometry(geometry)
    r = _radius(radius, g, max_corner_angle)
    x = V.finite_array("speed", speed)
    threshold = _threshold(straight_threshold, g)
    r, x = V.broadcast(radius=r, speed=x)
    straight = np.abs(r) >= threshold
    rr = np.where(straight, 1.0e9, r)[..., None]  # placeholder, replaced below
    pos = wheel_positions(g)
    a = np.abs(rr) + np.sign(rr) * pos[:, 1]
    ratio = np.sign(a) * np.hypot(pos[:, 0], a) / (np.abs(rr) + g.d4)
    return x[..., None] * np.where(straight[..., None], 1.0, ratio)


def corner_angles(radius: ArrayLike, geometry: RoverGeometry = OSR_GEOMETRY,
                  straight_threshold: float | None = None, *,
                  max_corner_angle: float = HARD_STOP) -> np.ndarray:
    r"""The four corner wheels' steering angles (rad), corners LF, RF, LB, RB.

    Each corner wheel rolls at right angles to the line from the ICR to it:

    .. math:: \delta_i = \arctan\frac{x_i}{r + y_i}

    so for ``r > 0`` the inner front corner (RF) is the document's equation 16,
    ``arctan(d3 / (r - d1))``; the outer front is ``arctan(d3 / (r + d1))``, and the back
    corners turn the other way, ``-arctan(d2 / (r -+ d1))``. Sign (the document's): positive
    means the wheel's front edge is turned toward the rover's right (clockwise seen from
    above). At ``|radius| >= straight_threshold`` all four are 0.

    Parameters
    ----------
    radius : float or array
        Turning radius of the body centre (document sign: > 0 turns right; +-inf straight).
    geometry : RoverGeometry
    straight_threshold : float, optional
        Radii at or beyond this are driven straight, in the geometry's unit (default: the
        document's 250 in, converted for a metric geometry).
    max_corner_angle : float
        The corner hard stop (rad); a tighter radius raises ``ValueError``.

    Returns
    -------
    ndarray, shape ``radius.shape + (4,)``, rad.

    Examples
    --------
    >>> np.round(np.degrees(corner_angles(30.0)), 3)
    array([ 15.74 ,  24.779, -15.74 , -24.779])
    >>> np.round(np.degrees(corner_angles(-min_turning_radius())), 3)  # inner corners at the stop
    array([-45.   , -22.776,  45.   ,  22.776])
    """
    g = _geometry(geometry)
    r = _radius(radius, g, max_corner_angle)
    threshold = _threshold(straight_threshold, g)
    straight = np.abs(r) >= threshold
    rr = np.where(straight, 1.0e9, r)[..., None]
    pos = wheel_positions(g)[list(_CORNER_WHEELS)]
    with np.errstate(divide="ignore"):  # a corner on the ICR's line: x/0 = inf, 90 degrees
        angles = np.arctan(pos[:, 0] / (rr + pos[:, 1]))
    return np.where(straight[..., None], 0.0, angles)


@overload
def centre_speed(radius: float, speed: float, geometry: RoverGeometry = OSR_GEOMETRY,  # type: ignore[overload-overlap]
                 straight_threshold: float | None = None, *,
                 max_corner_angle: float = HARD_STOP) -> float: ...
@overload
def centre_speed(radius: float | Stack, speed: float | Stack,
                 geometry: RoverGeometry = OSR_GEOMETRY, straight_threshold: float | None = None, *,
                 max_corner_angle: float = HARD_STOP) -> NDArray[np.float64]: ...
def centre_speed(radius: ArrayLike, speed: ArrayLike, geometry: RoverGeometry = OSR_GEOMETRY,
                 straight_threshold: float | None = None, *,
                 max_corner_angle: float = HARD_STOP) -> float | NDArray[np.float64]:
    r"""Speed of the body centre (the "middle of the rover") when the outer middle wheel gets
    ``speed``.

    The body centre is at distance ``|r|`` from the ICR, the outer middle wheel at
    ``|r| + d4``, so

    .. math:: v = X \frac{|r|}{|r| + d_4}

    and ``v = X`` when driving straight. At r = 30 in it is 74.86 % of the command, not 100 %.

    Examples
    --------
    >>> round(centre_speed(30.0, 100.0), 2)
    74.86
    >>> centre_speed(np.inf, 100.0)
    100.0
    """
    g = _geometry(geometry)
    r = _radius(radius, g, max_corner_angle)
    x = V.finite_array("speed", speed)
    threshold = _threshold(straight_threshold, g)
    r, x = V.broadcast(radius=r, speed=x)
    straight = np.abs(r) >= threshold
    rr = np.where(straight, 1.0, np.abs(r))
    return V.scalar_or_array(x * np.where(straight, 1.0, rr / (rr + g.d4)))


@overload
def command_to_radius(command: float, *, mapping: str = "radius",
                      geometry: RoverGeometry = OSR_GEOMETRY) -> float: ...
@overload
def command_to_radius(command: Stack, *, mapping: str = "radius",
                      geometry: RoverGeometry = OSR_GEOMETRY) -> NDArray[np.float64]: ...
def command_to_radius(command: ArrayLike, *, mapping: str = "radius",
                      geometry: RoverGeometry = OSR_GEOMETRY) -> float | NDArray[np.float64]:
    """The turning radius (in, document sign: > 0 right) for a joystick steering command.

    The document says only that the command runs from -100 to 100, negative turning left,
    and that a larger magnitude turns tighter. Three mappings that all give 20 in (the
    software limit) at +-100 and straight (``inf``) at 0:

    - ``"radius"`` (the default, linear in radius): ``|r| = 250 - 2.3 |c|`` in, so 1 gives
      247.7 in and 100 gives 20 in;
    - ``"curvature"`` (linear in curvature ``1/r``): ``|r| = 20 * 100 / |c|`` in;
    - ``"angle"`` (linear in the inner front corner's angle): ``delta = |c|/100 * delta_20``
      with ``delta_20 = arctan(d3 / (20 - d1))``, and ``|r| = d1 + d3 / tan(delta)``.

    The sign of ``c`` is the sign of ``r``; ``c = 0`` gives ``+inf`` (straight).

    Parameters
    ----------
    command : float or array
        In [-100, 100].
    mapping : {"radius", "curvature", "angle"}
    geometry : RoverGeometry
        Used by ``"angle"`` only (in either unit; the result is in inches).

    Returns
    -------
    float (for a scalar command) or ndarray, in inches.

    Examples
    --------
    >>> command_to_radius(100), command_to_radius(-100), command_to_radius(1)
    (20.0, -20.0, 247.7)
    >>> command_to_radius(0)
    inf
    >>> command_to_radius(50, mapping="curvature")
    40.0
    >>> command_to_radius(101)
    Traceback (most recent call last):
    ...
    ValueError: command must be in [-100, 100], got 101
    """
    c = V.finite_array("command", command)
    if np.any(np.abs(c) > COMMAND_LIMIT):
        bad = c[np.abs(c) > COMMAND_LIMIT].flat[0] if c.ndim else command
        raise ValueError(f"command must be in [-100, 100], got {bad!r}")
    V.choice("mapping", mapping, _MAPPINGS)
    g = _geometry(geometry).in_unit("in")  # the command's radii are the document's inches
    mag = np.abs(c)
    safe = np.where(mag > 0, mag, 1.0)
    if mapping == "radius":
        r = STRAIGHT_THRESHOLD - _RADIUS_PER_COMMAND * safe
    elif mapping == "curvature":
        r = SOFTWARE_MIN_RADIUS * COMMAND_LIMIT / safe
    else:
        delta_max = math.atan(g.d3 / (SOFTWARE_MIN_RADIUS - g.d1))
        r = g.d1 + g.d3 / np.tan(safe / COMMAND_LIMIT * delta_max)
    out = np.where(mag > 0, np.where(c < 0, -r, r), np.inf)
    return float(out) if out.ndim == 0 else out


@overload
def radius_to_command(radius: float) -> float: ...
@overload
def radius_to_command(radius: Stack) -> NDArray[np.float64]: ...
def radius_to_command(radius: ArrayLike) -> float | NDArray[np.float64]:
    r"""The joystick command whose linear-in-radius mapping gives ``radius`` (inverse of
    :func:`command_to_radius` with ``mapping="radius"``).

    .. math:: c = \operatorname{sgn}(r) \frac{250 - |r|}{2.3}

    Parameters
    ----------
    radius : float or array
        ``20 <= |radius| <= 250`` in, or ``+-inf`` (command 0).

    Examples
    --------
    >>> round(radius_to_command(135.0), 6), radius_to_command(-20.0), radius_to_command(np.inf)
    (50.0, -100.0, 0.0)
    """
    r = V.finite_array("radius", radius, allow_inf=True)
    mag = np.abs(r)
    finite = np.isfinite(r)
    bad = finite & ((mag < SOFTWARE_MIN_RADIUS) | (mag > STRAIGHT_THRESHOLD))
    if np.any(bad):
        first = float(r[bad].flat[0]) if r.ndim else float(r)
        raise ValueError(f"radius must satisfy 20 <= |radius| <= 250 (in), or be +-inf; "
                         f"got {first!r}")
    c = np.where(finite, np.sign(r) * (STRAIGHT_THRESHOLD - np.where(finite, mag, 0.0))
                 / _RADIUS_PER_COMMAND, 0.0)
    return float(c) if c.ndim == 0 else c


def document_twist(radius: float, speed_in_per_s: float, geometry: RoverGeometry = OSR_GEOMETRY,
               straight_threshold: float | None = None, *,
               max_corner_angle: float = HARD_STOP) -> Twist:
    """The body twist in **our** convention (SI, REP-103: x forward, y left, omega
    counter-clockwise) for a turn commanded in the document's convention.

    The body centre moves at ``v = X |r| / (|r| + d4)`` (:func:`centre_speed`) on a circle of
    radius ``|r|``, clockwise for ``r > 0``; :func:`wheelkin.sources.rover_twist` turns that
    into ``(vx, vy, omega) = (v, 0, -v / r)`` in m/s and rad/s.

    Parameters
    ----------
    radius : float
        Document sign, inches (> 0 right; +-inf straight).
    speed_in_per_s : float
        The speed ``X`` given to the outer middle wheel, in inches per second.

    Returns
    -------
    wheelkin.frames.Twist
        ``(vx, vy, omega)`` in m/s, m/s, rad/s.

    Examples
    --------
    >>> tw = document_twist(30.0, 10.0)  # right turn: omega < 0 in REP-103
    >>> print(f"{tw.vx:.5f} {tw.vy:.1f} {tw.omega:.5f}")
    0.19015 0.0 -0.24954
    """
    g = _geometry(geometry).in_unit("in")  # the document's command is in inches
    threshold = _threshold(straight_threshold, g)
    r = _scalar_radius(radius)
    x = V.finite("speed_in_per_s", speed_in_per_s)
    v = float(centre_speed(r, x, g, threshold, max_corner_angle=max_corner_angle))
    if abs(r) >= threshold:
        r = math.inf
    return cast(Twist, sources.rover_twist(r, v))  # scalars in: a Twist


class SandboxCommand(NamedTuple):
    """What :func:`sandbox_commands` gives the sandbox's rover: wheel rates and steering."""

    #: rad/s, wheels LF, LM, LB, RF, RM, RB, shape (6,).
    rates: np.ndarray
    #: rad, corners LF, RF, LB, RB, REP-103 sign (positive to the left), shape (4,).
    steering: np.ndarray


def sandbox_commands(radius: float, speed_in_per_s: float, wheel_radius_in: float,
                     geometry: RoverGeometry = OSR_GEOMETRY,
                     straight_threshold: float | None = None, *,
                     max_corner_angle: float = HARD_STOP) -> SandboxCommand:
    """Wheel rates and steering angles for ``wheelkin.sandbox.rover``, from a command in
    the document's convention.

    Returns
    -------
    SandboxCommand
        ``rates`` (rad/s, shape (6,), wheels LF, LM, LB, RF, RM, RB): ``V_i / r_w``,
        :func:`wheel_speeds` in in/s divided by the wheel radius in inches; ``steering``
        (rad, shape (4,), corners LF, RF, LB, RB) in **REP-103** sign (positive = turned
        counter-clockwise, to the left): the negative of :func:`corner_angles`.

    Examples
    --------
    >>> rates, steering = sandbox_commands(30.0, 10.0, 2.35)
    >>> np.round(rates, 3)
    array([4.11 , 4.255, 4.11 , 2.66 , 2.116, 2.66 ])
    >>> np.round(np.degrees(steering), 3)
    array([-15.74 , -24.779,  15.74 ,  24.779])
    """
    w = V.positive("wheel_radius_in", wheel_radius_in)
    r = _scalar_radius(radius)
    x = V.finite("speed_in_per_s", speed_in_per_s)
    geometry = _geometry(geometry).in_unit("in")  # the command is in inches
    speeds = wheel_speeds(r, x, geometry, straight_threshold, max_corner_angle=max_corner_angle)
    angles = corner_angles(r, geometry, straight_threshold, max_corner_angle=max_corner_angle)
    return SandboxCommand(speeds / w, -angles)


# --------------------------------------------------------------------------------------------
# SI and REP-103: metres, m/s, and a steering angle positive to the left


class RoverCommand(NamedTuple):
    """What the rover's motors are told: six wheel ground speeds and four steering angles."""

    #: Ground speeds (m/s) of the wheels LF, LM, LB, RF, RM, RB, shape (..., 6); positive
    #: rolls the wheel forward along its steered direction.
    wheel_speeds: np.ndarray
    #: Steering angles :math:`\delta` (rad) of the corners LF, RF, LB, RB, shape (..., 4);
    #: positive turns the wheel's front edge to the left (counter-clockwise, REP-103), the
    #: opposite of the document's :func:`corner_angles`.
    steering_angles: np.ndarray


def wheel_commands(v: ArrayLike, omega: ArrayLike,
                   geometry: RoverGeometry = OSR_GEOMETRY_SI, *,
                   max_corner_angle: float = HARD_STOP) -> RoverCommand:
    r"""Wheel speeds and corner steering angles for a body twist, in SI and REP-103.

    The rover is a rigid body moving with forward speed :math:`v` and yaw rate
    :math:`\omega` (no sideways velocity: the middle wheels cannot steer). A wheel at
    :math:`(x_i, y_i)` (the body frame, x forward, y left) moves with

    .. math::
        \dot p_i = (v - \omega y_i,\; \omega x_i), \qquad
        \delta_i = \arctan\frac{\omega x_i}{v - \omega y_i}, \qquad
        V_i = \frac{v - \omega y_i}{\cos\delta_i},

    so each wheel rolls at right angles to the line from the turning centre
    :math:`(0, R)`, :math:`R = v/\omega` (positive: a left turn). This is the document's
    maths (:func:`wheel_speeds`, :func:`corner_angles`) with the body centre's speed given
    instead of the outer middle wheel's, lengths in metres, and the book's signs: :math:`R`
    and :math:`\delta` positive to the left (:math:`\delta = -\delta_{OSR}`). The OSR
    software's straight-ahead threshold is not applied.

    Parameters
    ----------
    v : float or array_like
        Forward speed of the body centre, m/s.
    omega : float or array_like
        Yaw rate, rad/s, counter-clockwise positive; broadcast with ``v``.
    geometry : RoverGeometry
        In metres (default :data:`OSR_GEOMETRY_SI`).
    max_corner_angle : float
        The corner hard stop (rad), in (0, pi/2); a twist that needs more raises
        ``ValueError``.

    Returns
    -------
    RoverCommand
        ``(wheel_speeds, steering_angles)``: m/s, shape (..., 6), wheels LF, LM, LB, RF,
        RM, RB; rad, shape (..., 4), corners LF, RF, LB, RB.

    Examples
    --------
    The document's right turn of r = 30 in, outer middle wheel (LM) at 10 in/s, as a twist:

    >>> tw = document_twist(30.0, 10.0)
    >>> cmd = wheel_commands(tw.vx, tw.omega)
    >>> np.round(cmd.wheel_speeds / INCH, 3)  # in/s, the document's table at X = 10
    array([ 9.659, 10.   ,  9.659,  6.252,  4.973,  6.252])
    >>> np.round(np.degrees(cmd.steering_angles), 3)  # right turn: negative, to the right
    array([-15.74 , -24.779,  15.74 ,  24.779])
    """
    g = _geometry(geometry).in_unit("m")
    stop = V.in_range("max_corner_angle", max_corner_angle, 0.0, math.pi / 2,
                              inclusive=False)
    v_a = V.finite_array("v", v)
    w_a = V.finite_array("omega", omega)
    try:
        v_a, w_a = np.broadcast_arrays(v_a, w_a)
    except ValueError:
        raise ValueError(f"v and omega must have shapes that broadcast together, got "
                         f"{v_a.shape} and {w_a.shape}") from None
    pos = wheel_positions(g)
    along = v_a[..., None] - w_a[..., None] * pos[:, 1]  # (..., 6)
    across = w_a[..., None] * pos[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        delta = np.where(along == 0.0, np.where(across == 0.0, 0.0, math.pi / 2),
                         np.arctan(across / np.where(along == 0.0, 1.0, along)))
    corners = delta[..., list(_CORNER_WHEELS)]
    if np.any(np.abs(corners) > stop * (1.0 + 1e-12)):
        worst = float(np.max(np.abs(corners)))
        raise ValueError(f"omega: the turn needs a corner angle of {math.degrees(worst):.6g} "
                         f"degrees, beyond the {math.degrees(stop):.6g} degree stop (v and "
                         f"omega give R = v/omega too tight a turn); got v={v!r}, "
                         f"omega={omega!r}")
    speeds = np.where(along == 0.0, across, along / np.cos(delta)) + 0.0
    return RoverCommand(speeds, corners + 0.0)
