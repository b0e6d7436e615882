r"""Dead reckoning for a differential drive: from encoder increments to a pose.

The chapter "Odometry: where am I?" derives every formula here and checks it. Symbols (the
same in the chapter):

- :math:`\mathrm{ENC}` encoder steps per metre of wheel travel; the functions take
  ``steps_per_mm`` :math:`= \mathrm{ENC}/1000`.
- :math:`W` the track width (parameter ``track_width_mm``, the firmware README's
  *wheelBase*): wheel to wheel, side to side, in mm.
- :math:`n_L, n_R` encoder step increments of the left and right wheel in one update, and
  :math:`\Delta s_L = 1000\,n_L/\mathrm{ENC}`, :math:`\Delta s_R = 1000\,n_R/\mathrm{ENC}`
  the wheel travel (mm) in that update.
- :math:`\Delta s = (\Delta s_R + \Delta s_L)/2` the travel of the mid-point between the
  wheels, :math:`\Delta\theta = (\Delta s_R - \Delta s_L)/W` the change of heading.
- :math:`(x, y, \theta)` the pose: in our frame (REP-103) x forward at the start, y to the
  left, heading :math:`\theta` counter-clockwise from +x, in mm and rad (the firmware's units;
  multiply by 1e-3 for the library's metres).

An increment array always has shape (N, 2) with the columns in the order (left, right).

Three updates of the pose over one step, all with :math:`\theta' = \theta + \Delta\theta`:

.. list-table::
   :header-rows: 1

   * - method
     - position update
     - order
   * - ``euler``
     - :math:`\Delta s\,(\cos\theta, \sin\theta)`
     - first
   * - ``midpoint``
     - :math:`\Delta s\,(\cos\bar\theta, \sin\bar\theta)`,
       :math:`\bar\theta = \theta + \Delta\theta/2`
     - second
   * - ``exact``
     - :math:`\Delta s\,\dfrac{\sin(\Delta\theta/2)}{\Delta\theta/2}
       (\cos\bar\theta, \sin\bar\theta)`
     - exact on arcs

The exact update assumes the curvature is constant within a step (both wheel speeds constant,
or at least in a constant ratio), which makes the path of the mid-point an arc whose chord is
shorter than the arc by the factor :func:`chord_factor`.

The firmware's scheme
---------------------
The Radon Ulzer firmware README (cited as ``radonulzer_architecture``) prints an odometry
scheme in its own convention: positions X, Y in mm with **Y forward** at the start and X to
the right, and the orientation counter-clockwise from +Y, in rad (or mrad in its "improvement").
Its pose converts to ours by ``x = Y``, ``y = -X``, ``theta = orientation`` (in metres:
:func:`wheelkin.sources.firmware_pose_to_ours`). :func:`firmware_as_printed` runs the scheme as
printed, **with its mistakes** (the centre distance from the difference of the wheels, and an
orientation update whose wrap overwrites it); :func:`firmware_corrected` is the same scheme with
those mistakes fixed; :func:`firmware_scheme` chooses every variant separately, and
:func:`firmware_fixed_point` models the "improvement" with whole millimetres and milliradians.
"""

from __future__ import annotations

import math
from typing import Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as v
from wheelkin._kernels import arc_factors, arc_step, c_div
from wheelkin.frames import Pose, wrap_angle

__all__ = [
    "FIRMWARE_TWO_PI_MRAD",
    "METHODS",
    "SERIES_THRESHOLD",
    "BodyIncrements",
    "BodyMotion",
    "body_increments",
    "body_motion",
    "chord_factor",
    "encoder_increments",
    "firmware_as_printed",
    "firmware_corrected",
    "firmware_fixed_point",
    "firmware_scheme",
    "integrate",
    "integrate_si",
    "plan_wheel_travel",
    "pose_update",
]

#: The pose updates :func:`integrate` and :func:`pose_update` know.
METHODS = ("exact", "midpoint", "euler")

#: Below this :math:`|\Delta\theta|` (rad) :func:`chord_factor` evaluates
#: :math:`\sin(u)/u` by its series :math:`1 - u^2/6 + u^4/120` (:math:`u = \Delta\theta/2`):
#: twice the arc kernel's threshold on :math:`u` (:data:`wheelkin._kernels.SERIES_THRESHOLD`);
#: the truncation error there is below :math:`u^6/5040 < 10^{-28}`, far under round-off.
SERIES_THRESHOLD = 2.0 * _kernels.SERIES_THRESHOLD

#: 2π in whole milliradians as the firmware computes it (2000 π cast to an integer): 6283,
#: which is 0.185 mrad short of 2π.
FIRMWARE_TWO_PI_MRAD = 6283


# --------------------------------------------------------------------------------------------
# validation helpers (thin wrappers of wheelkin._validate)

def _increments(value) -> np.ndarray:
    arr = v.finite_array("increments", value)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError("increments must have shape (N, 2): one (left, right) pair of encoder "
                         f"step increments per update, got shape {arr.shape}")
    return arr


def _pose(value, name: str = "pose") -> np.ndarray:
    arr = v.finite_array(name, value)
    if arr.shape != (3,):
        raise ValueError(f"{name} must have shape (3,): (x_mm, y_mm, theta_rad), "
                         f"got shape {arr.shape}")
    return arr


def _whole(name: str, arr: np.ndarray) -> np.ndarray:
    if np.any(arr != np.round(arr)):
        raise ValueError(f"{name} must hold whole numbers (encoder steps, mm, mrad), "
                         f"got {arr!r}")
    if np.any(np.abs(arr) > 2**31 - 1):
        raise ValueError(f"{name} must fit a 32-bit signed integer, got {arr!r}")
    return arr.astype(np.int64)


# --------------------------------------------------------------------------------------------
# the kinematics of one update

class BodyIncrements(NamedTuple):
    r"""The motion of the mid-point between the wheels in each update, in the firmware's
    units: travel ``distance_mm`` :math:`\Delta s` (mm, positive forward) and heading change
    ``dtheta`` :math:`\Delta\theta` (rad, counter-clockwise positive), arrays of shape (N,)."""

    distance_mm: np.ndarray
    dtheta: np.ndarray


def body_increments(increments: ArrayLike, steps_per_mm: float,
                    track_width_mm: float) -> BodyIncrements:
    r"""Travel of the mid-point and change of heading in each update, from encoder increments.

    .. math::
        \Delta s = \frac{n_L + n_R}{2\,\mathrm{ENC}_{mm}}, \qquad
        \Delta\theta = \frac{n_R - n_L}{\mathrm{ENC}_{mm}\, W}

    with :math:`\mathrm{ENC}_{mm}` = ``steps_per_mm`` and :math:`W` = ``track_width_mm``.

    Parameters
    ----------
    increments : array_like, shape (N, 2)
        Encoder step increments per update, columns (left, right).
    steps_per_mm : float
        Encoder steps per mm of wheel travel (> 0).
    track_width_mm : float
        Track width W (the README's wheelBase), wheel to wheel, in mm (> 0).

    Returns
    -------
    BodyIncrements
        ``(distance_mm, dtheta)``, arrays of shape (N,): :math:`\Delta s` (mm, positive
        forward) and :math:`\Delta\theta` (rad,
        counter-clockwise positive).

    Examples
    --------
    The right wheel 85 steps further than the left, 10 steps per mm, an 85 mm track width:
    the mid-point moves 4.25 mm and the robot turns 0.1 rad to the left.

    >>> ds, dth = body_increments([[0, 85]], 10.0, 85.0)
    >>> print(f"{ds[0]:.3f} mm, {dth[0]:.4f} rad")
    4.250 mm, 0.1000 rad
    """
    inc = _increments(increments)
    k = v.positive("steps_per_mm", steps_per_mm)
    w = v.positive("track_width_mm", track_width_mm)
    left, right = inc[:, 0], inc[:, 1]
    return BodyIncrements((left + right) / (2.0 * k), (right - left) / (k * w))


def chord_factor(dtheta: ArrayLike) -> float | NDArray[np.float64]:
    r"""Ratio of the chord to the arc for a turn of :math:`\Delta\theta`: sin(u)/u, u = Δθ/2.

    .. math:: c(\Delta\theta) = \frac{\sin(\Delta\theta/2)}{\Delta\theta/2}
              \approx 1 - \frac{\Delta\theta^2}{24} + \frac{\Delta\theta^4}{1920}
              \quad (|\Delta\theta| < \text{SERIES\_THRESHOLD})

    The closed form is 0/0 at :math:`\Delta\theta = 0`; below :data:`SERIES_THRESHOLD` the
    series is used instead (its truncation error there is under 1e-28, so the switch is
    seamless; ros2_controllers' diff-drive odometry switches in the same spirit).

    Parameters
    ----------
    dtheta : float or array_like
        Change of heading over the step, rad.

    Returns
    -------
    float or numpy.ndarray
        The factor, 1 at :math:`\Delta\theta = 0`, :math:`2/\pi` at a half turn.

    Examples
    --------
    >>> print(f"{chord_factor(0.0):.6f} {chord_factor(math.pi):.6f}")
    1.000000 0.636620
    """
    d = v.finite_array("dtheta", dtheta)
    out = np.asarray(arc_factors(0.5 * d)[0], dtype=float)
    return float(out) if out.ndim == 0 else out


def pose_update(
        pose: ArrayLike, distance: ArrayLike, dtheta: ArrayLike,
        method: Literal["exact", "midpoint", "euler"] = "exact") -> Pose | NDArray[np.float64]:
    r"""The pose after one update that moved the mid-point by Δs and turned it by Δθ.

    .. math::
        \theta' = \theta + \Delta\theta, \qquad
        \begin{pmatrix} x' \\ y' \end{pmatrix} =
        \begin{pmatrix} x \\ y \end{pmatrix} + \Delta s\, c
        \begin{pmatrix} \cos\varphi \\ \sin\varphi \end{pmatrix}

    with :math:`(c, \varphi)` = :math:`(1, \theta)` for ``"euler"``,
    :math:`(1, \theta + \Delta\theta/2)` for ``"midpoint"`` and
    :math:`(` :func:`chord_factor` :math:`(\Delta\theta), \theta + \Delta\theta/2)` for
    ``"exact"`` (the chord of the arc of constant curvature).

    Parameters
    ----------
    pose : array_like, shape (..., 3)
        (x, y, θ): position in any length unit, heading in rad, our frame (counter-clockwise).
    distance : float or array_like
        Δs, travel of the mid-point in the same length unit (broadcast against ``pose[..., 0]``).
    dtheta : float or array_like
        Δθ, rad.
    method : {"exact", "midpoint", "euler"}

    Returns
    -------
    Pose (for a Pose and scalar steps) or numpy.ndarray, shape (..., 3)

    Examples
    --------
    A quarter circle of radius 100 mm in one step: the exact update lands on (100, 100).

    >>> p = pose_update([0.0, 0.0, 0.0], 50 * math.pi, math.pi / 2)
    >>> print(np.round(p, 6))
    [100.       100.         1.570796]
    >>> print(np.round(pose_update([0.0, 0.0, 0.0], 50 * math.pi, math.pi / 2, "euler"), 3))
    [157.08    0.      1.571]
    """
    p = v.shaped("pose", pose, (3,))
    ds = v.finite_array("distance", distance)
    dth = v.finite_array("dtheta", dtheta)
    v.choice("method", method, METHODS)
    try:
        ds, dth, _ = np.broadcast_arrays(ds, dth, p[..., 0])
    except ValueError:
        raise ValueError(f"distance (shape {ds.shape}) and dtheta (shape {dth.shape}) must "
                         f"broadcast against pose[..., 0] (shape {p.shape[:-1]})") from None
    with np.errstate(all="ignore"):
        out = _step(p, ds, dth, method)
    out = v.finite_result("pose, distance and dtheta", out)
    return Pose(*out.tolist()) if isinstance(pose, Pose) and out.ndim == 1 else out


def _step(p: np.ndarray, ds: np.ndarray, dth: np.ndarray, method: str) -> np.ndarray:
    """One update of poses ``p`` (..., 3) by ``ds``, ``dth`` (validated, broadcast)."""
    theta = p[..., 2]
    if method == "exact":  # the library's one arc kernel
        return np.stack(arc_step(p[..., 0], p[..., 1], theta, ds, dth), axis=-1)
    if method == "euler":
        phi, length = theta, ds
    else:
        phi, length = theta + 0.5 * dth, ds
    return np.stack([p[..., 0] + length * np.cos(phi), p[..., 1] + length * np.sin(phi),
                     theta + dth], axis=-1)


def integrate(increments: ArrayLike, steps_per_mm: float, track_width_mm: float,
              method: Literal["exact", "midpoint", "euler"] = "exact",
              pose: ArrayLike = (0.0, 0.0, 0.0)) -> NDArray[np.float64]:
    r"""Dead-reckon a differential drive from its per-update encoder increments.

    Applies :func:`pose_update` once per row of ``increments``, with the Δs and Δθ of
    :func:`body_increments`. The heading is the running sum
    :math:`\theta_k = \theta_0 + \sum_{j \le k} \Delta\theta_j` (not wrapped), and each
    position step depends only on the heading before it, so the whole run is computed with
    cumulative sums (10^5 updates take a few milliseconds).

    Parameters
    ----------
    increments : array_like, shape (N, 2)
        Encoder step increments per update, columns (left, right); may be fractional (an
        ideal, unquantised encoder).
    steps_per_mm : float
        Encoder steps per mm of wheel travel (> 0); ENC/1000.
    track_width_mm : float
        W, wheel to wheel, mm (> 0).
    method : {"exact", "midpoint", "euler"}
        See the module docstring: exact on arcs, second order, first order.
    pose : array_like, shape (3,)
        Start pose (x_mm, y_mm, theta_rad) in our frame.

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        The pose (x_mm, y_mm, theta_rad) after each update, our frame (x forward at the start
        when ``pose`` is zero, θ counter-clockwise, not wrapped).

    Raises
    ------
    ValueError
        NaN or infinity, a shape other than (N, 2), a non-positive constant, an unknown method.

    Examples
    --------
    Straight ahead 8043 steps on each wheel (1 m at 8.043 steps/mm), then a quarter turn on the
    spot:

    >>> quarter = 8.043 * 85.0 * math.pi / 4
    >>> poses = integrate([[8043, 8043], [-quarter, quarter]], 8.043, 85.0)
    >>> print(np.round(poses, 4))
    [[1000.         0.         0.    ]
     [1000.         0.         1.5708]]
    """
    ds, dth = body_increments(increments, steps_per_mm, track_width_mm)
    v.choice("method", method, METHODS)
    p0 = _pose(pose)
    theta = p0[2] + np.cumsum(dth)
    start = np.concatenate(([p0[2]], theta))[:-1]
    steps = _step(np.stack([np.zeros_like(ds), np.zeros_like(ds), start], axis=-1), ds, dth,
                  method)
    return np.column_stack([p0[0] + np.cumsum(steps[:, 0]), p0[1] + np.cumsum(steps[:, 1]),
                            theta])


# --------------------------------------------------------------------------------------------
# the same in SI: wheel travels in metres, the track width W in metres

class BodyMotion(NamedTuple):
    r"""The motion of the mid-point between the wheels in each update: travel ``distance``
    :math:`\Delta s` (m, positive forward) and heading change ``dtheta`` :math:`\Delta\theta`
    (rad, counter-clockwise positive)."""

    distance: np.ndarray
    dtheta: np.ndarray


def _travel_pair(delta_left, delta_right) -> tuple[np.ndarray, np.ndarray]:
    left = v.finite_array("delta_left", delta_left)
    right = v.finite_array("delta_right", delta_right)
    if left.ndim != 1 or left.size == 0:
        raise ValueError("delta_left must be a 1-D array of N >= 1 wheel travels (m), "
                         f"got shape {left.shape}")
    if right.shape != left.shape:
        raise ValueError(f"delta_right must have the shape of delta_left {left.shape}, "
                         f"got shape {right.shape}")
    return left, right


def body_motion(delta_left: ArrayLike, delta_right: ArrayLike,
                track_width: float) -> BodyMotion:
    r"""Travel of the mid-point and change of heading in each update, from wheel travels (SI).

    .. math::
        \Delta s = \frac{\Delta s_L + \Delta s_R}{2}, \qquad
        \Delta\theta = \frac{\Delta s_R - \Delta s_L}{W}

    (ros2_controllers' ``diff_drive_controller`` uses the same two lines, and so does
    WPILib's ``DifferentialDriveKinematics.toTwist2d``; WPILib's ``DifferentialDriveOdometry``
    instead takes the heading change from a gyro). The SI twin of :func:`body_increments`.

    Parameters
    ----------
    delta_left, delta_right : array_like, shape (N,)
        Travel of the left and right wheel's contact point in each update, m.
    track_width : float
        :math:`W`, the distance between the left and right wheel contact lines, m (> 0).

    Returns
    -------
    BodyMotion
        ``(distance, dtheta)``: arrays of shape (N,), m and rad.

    Examples
    --------
    >>> body_motion([0.0], [0.0425], 0.085)
    BodyMotion(distance=array([0.02125]), dtheta=array([0.5]))
    """
    left, right = _travel_pair(delta_left, delta_right)
    w = v.positive("track_width", track_width)
    return BodyMotion(0.5 * (left + right), (right - left) / w)


def integrate_si(delta_left: ArrayLike, delta_right: ArrayLike, track_width: float,
                 method: str = "exact", pose: ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
    r"""Dead-reckon a differential drive from its wheel travels in metres: the SI twin of
    :func:`integrate`.

    Per update, :func:`body_motion` gives :math:`\Delta s, \Delta\theta`, and the pose moves
    by the update of ``method`` (see the module docstring); for ``"exact"``, the arc of
    constant curvature

    .. math::
        x' = x + \Delta s\,\frac{\sin\Delta\theta}{\Delta\theta}\cos\theta
               - \Delta s\,\frac{1-\cos\Delta\theta}{\Delta\theta}\sin\theta,\quad
        y' = y + \Delta s\,\frac{\sin\Delta\theta}{\Delta\theta}\sin\theta
               + \Delta s\,\frac{1-\cos\Delta\theta}{\Delta\theta}\cos\theta,\quad
        \theta' = \theta + \Delta\theta

    (the library's arc kernel; ros2_controllers' ``integrateExact`` and WPILib's
    ``Pose2d.exp`` compute the same pose).

    Parameters
    ----------
    delta_left, delta_right : array_like, shape (N,)
        Wheel travel of the left and right wheel in each update, m (wheel radius times the
        change of wheel angle).
    track_width : float
        :math:`W`, m (> 0).
    method : {"exact", "midpoint", "euler"}
    pose : array_like, shape (3,)
        Start pose (x, y, θ) in m, m, rad, world frame (REP-103).

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        The pose (x, y, θ) after each update (m, m, rad; θ not wrapped).

    Examples
    --------
    One metre straight, then a quarter turn on the spot with W = 0.5 m:

    >>> quarter = 0.5 * math.pi / 4
    >>> print(np.round(integrate_si([1.0, -quarter], [1.0, quarter], 0.5), 6))
    [[1.       0.       0.      ]
     [1.       0.       1.570796]]
    """
    ds, dth = body_motion(delta_left, delta_right, track_width)
    v.choice("method", method, METHODS)
    p0 = v.finite_array("pose", pose)
    if p0.shape != (3,):
        raise ValueError(f"pose must have shape (3,): (x_m, y_m, theta_rad), got shape "
                         f"{p0.shape}")
    theta = p0[2] + np.cumsum(dth)
    start = np.concatenate(([p0[2]], theta))[:-1]
    steps = _step(np.stack([np.zeros_like(ds), np.zeros_like(ds), start], axis=-1), ds, dth,
                  method)
    return np.column_stack([p0[0] + np.cumsum(steps[:, 0]), p0[1] + np.cumsum(steps[:, 1]),
                            theta])


# --------------------------------------------------------------------------------------------
# encoder sequences for experiments

def plan_wheel_travel(segments: ArrayLike, track_width_mm: float,
                      max_step_mm: float) -> NDArray[np.float64]:
    r"""Cumulative wheel travel (left, right) along a path of arcs, sampled in small updates.

    Each segment ``(distance_mm, turn_rad)`` moves the mid-point by ``distance_mm`` along an arc
    of constant curvature while the heading changes by ``turn_rad`` (distance 0: a turn on the
    spot). The wheels then travel

    .. math:: s_L = \Delta s - \tfrac{W}{2}\Delta\theta, \qquad
              s_R = \Delta s + \tfrac{W}{2}\Delta\theta

    and each segment is split into the fewest equal updates in which no wheel moves more than
    ``max_step_mm``.

    Parameters
    ----------
    segments : array_like, shape (M, 2)
        (distance_mm, turn_rad) per segment, driven in order.
    track_width_mm : float
        W in mm (> 0).
    max_step_mm : float
        Largest wheel travel per update, mm (> 0).

    Returns
    -------
    numpy.ndarray, shape (K + 1, 2)
        Cumulative travel of the (left, right) wheels in mm, starting with (0, 0).

    Examples
    --------
    >>> print(plan_wheel_travel([[100.0, 0.0]], 85.0, 30.0))
    [[  0.   0.]
     [ 25.  25.]
     [ 50.  50.]
     [ 75.  75.]
     [100. 100.]]
    """
    seg = v.finite_array("segments", segments)
    if seg.ndim != 2 or seg.shape[1] != 2:
        raise ValueError("segments must have shape (M, 2): (distance_mm, turn_rad) per segment, "
                         f"got shape {seg.shape}")
    w = v.positive("track_width_mm", track_width_mm)
    h = v.positive("max_step_mm", max_step_mm)
    with np.errstate(all="ignore"):
        wheel_travel = np.abs(seg[:, :1]) + 0.5 * w * np.abs(seg[:, 1:])
        steps = np.sum(np.ceil(wheel_travel / h))
    if not np.isfinite(steps) or steps > 1e8:
        raise ValueError(f"segments, track_width_mm and max_step_mm ask for {steps:.3g} steps "
                         "(more than 1e8): make max_step_mm larger")
    pieces = [np.zeros((1, 2))]
    start = np.zeros(2)
    for distance, turn in seg:
        wheels = np.array([distance - 0.5 * w * turn, distance + 0.5 * w * turn])
        n = max(1, math.ceil(np.max(np.abs(wheels)) / h - 1e-12))
        frac = np.arange(1, n + 1)[:, None] / n
        pieces.append(start + frac * wheels)
        start = start + wheels
    return np.concatenate(pieces)


def encoder_increments(travel_mm: ArrayLike, steps_per_mm: float) -> NDArray[np.int64]:
    r"""The per-update increments of an ideal quantising encoder for a cumulative wheel travel.

    .. math:: n_k = \lfloor \mathrm{ENC}_{mm}\, s_k \rfloor
                  - \lfloor \mathrm{ENC}_{mm}\, s_{k-1} \rfloor

    (the counter counts the step edges crossed; the travel is measured from an edge).

    Parameters
    ----------
    travel_mm : array_like, shape (K + 1, 2)
        Cumulative travel of the (left, right) wheels in mm, first row the start (e.g. from
        :func:`plan_wheel_travel`).
    steps_per_mm : float
        Encoder steps per mm (> 0).

    Returns
    -------
    numpy.ndarray of int64, shape (K, 2)
        Whole encoder steps per update, columns (left, right).

    Examples
    --------
    >>> print(encoder_increments([[0.0, 0.0], [1.0, 1.3], [2.0, 2.6]], 8.043))
    [[ 8 10]
     [ 8 10]]
    """
    s = v.finite_array("travel_mm", travel_mm)
    if s.ndim != 2 or s.shape[1] != 2 or s.shape[0] < 1:
        raise ValueError("travel_mm must have shape (K + 1, 2): cumulative (left, right) travel, "
                         f"first row the start, got shape {s.shape}")
    k = v.positive("steps_per_mm", steps_per_mm)
    # A tiny tolerance so that a travel of exactly n steps (up to round-off) counts n.
    with np.errstate(all="ignore"):
        exact = np.floor(s * k + 1e-9)
    if not np.all(np.abs(exact) < 2.0**62):
        raise ValueError("travel_mm times steps_per_mm must stay below 2**62 encoder steps, "
                         f"got up to {np.max(np.abs(exact)):.3g}")
    counts = exact.astype(np.int64)
    return np.diff(counts, axis=0)


# --------------------------------------------------------------------------------------------
# the firmware README's scheme (its frame: Y forward, X right, orientation counter-clockwise
# from +Y; X, Y in mm)

CENTERS = ("difference", "sum")
WRAPS = ("literal", "fmod", "pi", "none")
POSITION_HEADINGS = ("end", "midpoint")


def firmware_scheme(
        increments: ArrayLike, steps_per_mm: float, track_width_mm: float,
        pose: ArrayLike = (0.0, 0.0, 0.0), *, center: Literal["sum", "difference"] = "sum",
        wrap: Literal["pi", "fmod", "literal", "none"] = "pi",
        position_heading: Literal["midpoint", "end"] = "midpoint") -> NDArray[np.float64]:
    """The firmware README's odometry scheme, with each printed choice selectable.

    Per update, in the README's names (our symbols in brackets):

    - distanceLeft = L / encoderStepsPerMM [Δs_L], distanceRight likewise [Δs_R];
    - stepsCenter = (L + R)/2 (``center="sum"``; the README prints (L − R)/2,
      ``center="difference"``), distanceCenter = stepsCenter / encoderStepsPerMM [Δs];
    - alpha = (distanceRight − distanceLeft) / wheelBase [Δθ];
    - orientation' = orientation + alpha, then wrapped by ``wrap``:

      ``"literal"``: orientation' = fmod(orientation, 2π), the printed line read literally:
      it overwrites the sum with the *old* orientation, so alpha is discarded;
      ``"fmod"``: orientation' = fmod(orientation + alpha, 2π), the sign-keeping C remainder
      the README describes (values in (−2π, 2π), two representations of most headings);
      ``"pi"``: wrapped into (−π, π]; ``"none"``: not wrapped;
    - dX = −distanceCenter · sin φ, dY = distanceCenter · cos φ, with φ the orientation
      after the update (``position_heading="end"``, as printed) or the mean of the orientations
      before and after (``"midpoint"``, the same cost and second order).

    Parameters
    ----------
    increments : array_like, shape (N, 2)
        Encoder step increments (L, R) per update.
    steps_per_mm : float
        encoderStepsPerMM (> 0).
    track_width_mm : float
        wheelBase, mm (> 0).
    pose : array_like, shape (3,)
        Start (X_mm, Y_mm, orientation_rad) in the firmware's frame.
    center : {"sum", "difference"}
    wrap : {"pi", "fmod", "literal", "none"}
    position_heading : {"midpoint", "end"}

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        (X_mm, Y_mm, orientation_rad) after each update, firmware frame (Y forward at the
        start, X right, orientation counter-clockwise from +Y), orientation wrapped by ``wrap``.

    Examples
    --------
    Straight ahead 100 steps per wheel at 10 steps/mm: 10 mm along +Y with the sum, nothing
    with the printed difference.

    >>> print(firmware_scheme([[100, 100]], 10.0, 85.0))
    [[ 0. 10.  0.]]
    >>> print(firmware_scheme([[100, 100]], 10.0, 85.0, center="difference"))
    [[0. 0. 0.]]
    """
    inc = _increments(increments)
    k = v.positive("steps_per_mm", steps_per_mm)
    w = v.positive("track_width_mm", track_width_mm)
    p0 = _pose(pose)
    v.choice("center", center, CENTERS)
    v.choice("wrap", wrap, WRAPS)
    v.choice("position_heading", position_heading, POSITION_HEADINGS)
    left, right = inc[:, 0], inc[:, 1]
    steps_center = (left + right) / 2.0 if center == "sum" else (left - right) / 2.0
    distance_center = steps_center / k
    alpha = (right / k - left / k) / w
    n = len(alpha)
    if wrap in ("pi", "none"):
        # A running sum, wrapped (or not) afterwards: independent of the history.
        unwrapped = p0[2] + np.cumsum(alpha)
        after = wrap_angle(unwrapped) if wrap == "pi" and n else unwrapped
        before = np.concatenate(([p0[2]], after))[:-1]
    else:
        # The sign-keeping fmod makes the stored value depend on the history (and "literal"
        # drops alpha), so the orientation is updated in a loop, as the firmware would.
        before, after = np.empty(n), np.empty(n)
        orientation = float(p0[2])
        two_pi = 2.0 * math.pi
        for i, a in enumerate(alpha.tolist()):
            before[i] = orientation
            if wrap == "literal":
                orientation = math.fmod(orientation, two_pi)  # alpha is lost
            else:
                orientation = math.fmod(orientation + a, two_pi)
            after[i] = orientation
    if position_heading == "end" or wrap == "literal":
        phi = after
    else:
        # before + alpha/2, the heading half-way through the step (a wrap of `after` must not
        # leak into it, so it is built from `before`).
        phi = before + 0.5 * alpha
    dx = -distance_center * np.sin(phi)
    dy = distance_center * np.cos(phi)
    return np.column_stack([p0[0] + np.cumsum(dx), p0[1] + np.cumsum(dy), after])


def firmware_as_printed(
        increments: ArrayLike, steps_per_mm: float, track_width_mm: float,
        pose: ArrayLike = (0.0, 0.0, 0.0), *,
        wrap: Literal["pi", "fmod", "literal", "none"] = "literal") -> NDArray[np.float64]:
    """The firmware README's odometry scheme exactly as printed. **Wrong**: do not port it.

    As printed (see :func:`firmware_scheme` for the per-update equations):

    - **wrong**: stepsCenter = (L − R)/2. Driving straight gives zero distance; a turn on the
      spot moves the robot. It must be (L + R)/2.
    - **wrong** if read literally (``wrap="literal"``, the default): orientation' =
      orientation % 2π wraps the *old* orientation, overwriting the update, so the heading
      never changes. ``wrap="fmod"`` reads it as intended, wrapping the updated value with the
      sign-keeping C remainder into (−2π, 2π).
    - first order: the position step uses the orientation after the update (orientation').

    Parameters and return value as :func:`firmware_scheme` (firmware frame: Y forward at the
    start, X right, orientation counter-clockwise from +Y; mm and rad).

    Examples
    --------
    A turn on the spot (left wheel back, right wheel forward) moves the printed robot 10 mm
    backwards (along −Y) and, read literally, does not turn it:

    >>> print(firmware_as_printed([[-100, 100]], 10.0, 85.0))
    [[  0. -10.   0.]]
    """
    v.choice("wrap", wrap, ("literal", "fmod"))
    return firmware_scheme(increments, steps_per_mm, track_width_mm, pose, center="difference",
                           wrap=wrap, position_heading="end")


def firmware_corrected(
        increments: ArrayLike, steps_per_mm: float, track_width_mm: float,
        pose: ArrayLike = (0.0, 0.0, 0.0), *,
        position_heading: Literal["midpoint", "end"] = "midpoint") -> NDArray[np.float64]:
    """The firmware README's odometry scheme with its mistakes corrected.

    stepsCenter = (L + R)/2; orientation' = orientation + alpha, wrapped into (−π, π];
    dX = −distanceCenter · sin φ, dY = distanceCenter · cos φ with φ = orientation + alpha/2
    (``position_heading="midpoint"``, second order at the cost of the printed first-order
    update) or φ = orientation' (``"end"``, as printed). In our frame the midpoint version is
    :func:`integrate` with ``method="midpoint"``.

    Parameters and return value as :func:`firmware_scheme` (firmware frame and units).

    Examples
    --------
    A turn on the spot: no translation, 100 steps / 10 steps/mm / 85 mm · 2 = 0.2353 rad.

    >>> print(np.round(firmware_corrected([[-100, 100]], 10.0, 85.0), 4))
    [[0.     0.     0.2353]]
    """
    return firmware_scheme(increments, steps_per_mm, track_width_mm, pose, center="sum",
                           wrap="pi", position_heading=position_heading)


def _c_mod(a: int, b: int) -> int:
    """The remainder of C's integer division (keeps the sign of ``a``), as C's ``%``."""
    return a - b * c_div(a, b)


def _div_round_up(a: int, b: int) -> int:
    """The firmware source's ``Util::divRoundUp(int32_t, int32_t)``, line for line.

    C's quotient (toward zero), plus one step away from zero when the remainder's magnitude
    is at least ``|b / 2|``; a quotient of 0 always steps to +1, whatever the sign of ``a``.
    """
    result = c_div(a, b)
    if abs(a - b * result) >= abs(c_div(b, 2)):
        result += -1 if result < 0 else 1
    return result


def firmware_fixed_point(increments: ArrayLike, steps_per_mm: float, track_width_mm: float,
                         pose: ArrayLike = (0, 0, 0), *, carry: bool = False,
                         alpha_rounding: Literal["truncate", "source"] = "truncate",
                         ) -> NDArray[np.int64]:
    """A fixed-point model of the README's "improvement": whole mm, whole mrad, C truncation.

    A direct port to C with 32-bit integer state, the centre distance corrected to the sum
    and the position update as printed (orientation after the update). Per update:

    - stepsCenter = (L + R) / 2 in integer division (toward zero);
    - alpha_mrad = trunc(1000 · (R − L) / (encoderStepsPerMM · wheelBase));
    - orientation_mrad = (orientation_mrad + alpha_mrad) % 6283 (C remainder; 6283 =
      :data:`FIRMWARE_TWO_PI_MRAD`, the firmware's integer 2π);
    - distanceCenter_mm = trunc(stepsCenter / encoderStepsPerMM);
    - X += trunc(−distanceCenter · sin(orientation_mrad/1000)),
      Y += trunc(distanceCenter · cos(orientation_mrad/1000)).

    With ``carry=True`` the fractions that truncation drops (half steps, fractions of a mrad
    and of a mm) are kept in accumulators and added to the next update, so rounding no
    longer accumulates; the stored state is still whole mm and mrad (the firmware's source
    code keeps its position in 1/1000 steps for the same reason). The 0.185 mrad lost at every
    wrap by 6283 is kept in both modes.

    With ``alpha_rounding="source"`` alpha is rounded as the firmware's source code
    (``Odometry::calculateOrientation``, BlueAndi/RadonUlzer) does it, in two stages with
    its ``Util::divRoundUp``: the wheel-travel difference to whole mm,
    ``a = divRoundUp(1000 (R − L), ENC)``, then ``alpha_mrad = divRoundUp(1000 a, wheelBase)``.
    Every turn is then a multiple of about 1000/wheelBase mrad, no fraction is carried, and a
    difference between −1 and −1/2 mm is rounded to +1 mm (``divRoundUp`` steps a quotient of
    0 up). It needs ENC = 1000 ``steps_per_mm`` and ``track_width_mm`` to be whole numbers, as
    in the firmware; ``carry`` then applies to the distance and the position only.

    Parameters
    ----------
    increments : array_like of whole numbers, shape (N, 2)
        Encoder step increments (L, R) per update.
    steps_per_mm : float
        encoderStepsPerMM (> 0), used as a real number.
    track_width_mm : float
        wheelBase, mm (> 0).
    pose : array_like of whole numbers, shape (3,)
        Start (X_mm, Y_mm, orientation_mrad), firmware frame.
    carry : bool
        Carry the truncated fractions to the next update.
    alpha_rounding : {"truncate", "source"}
        How alpha becomes whole mrad: a C cast (toward zero), or the source code's two-stage
        rounding (whole mm, then whole mrad).

    Returns
    -------
    numpy.ndarray of int64, shape (N, 3)
        (X_mm, Y_mm, orientation_mrad) after each update, firmware frame, orientation in
        (−6283, 6283).

    Examples
    --------
    Ten updates of 80 steps per wheel (9.95 mm each at 8.043 steps/mm): truncation counts 9 mm
    per update, carrying counts the 99 mm driven.

    >>> inc = np.full((10, 2), 80)
    >>> print(firmware_fixed_point(inc, 8.043, 85.0)[-1], firmware_fixed_point(inc, 8.043, 85.0,
    ...       carry=True)[-1])
    [ 0 90  0] [ 0 99  0]

    On a left circle of 1 m radius the wheels differ by 6 to 8 steps (0.75 to 1 mm) per update,
    8.8 to 11.7 mrad: truncated, 8 to 11 mrad; the source rounds each difference to 1 mm and
    turns 1000/85 = 11.8, so 12 mrad; and on the mirrored right circle also +12 mrad:

    >>> left = [[80, 87], [80, 86], [80, 88]]
    >>> right = [[87, 80], [86, 80], [88, 80]]
    >>> for rule in ("truncate", "source"):
    ...     print(rule, [int(firmware_fixed_point(inc, 8.043, 85.0, alpha_rounding=rule)[-1, 2])
    ...                  for inc in (left, right)])
    truncate [29, -29]
    source [36, 36]
    """
    inc = _whole("increments", _increments(increments))
    k = v.positive("steps_per_mm", steps_per_mm)
    w = v.positive("track_width_mm", track_width_mm)
    p0 = _whole("pose", _pose(pose))
    if not isinstance(carry, bool | np.bool_):
        raise ValueError(f"carry must be True or False, got {carry!r}")
    v.choice("alpha_rounding", alpha_rounding, ("truncate", "source"))
    enc, base = round(1000.0 * k), round(w)
    if alpha_rounding == "source" and (abs(1000.0 * k - enc) > 1e-6 or abs(w - base) > 1e-9):
        raise ValueError("alpha_rounding='source' needs whole numbers, as in the firmware: "
                         f"1000 * steps_per_mm (ENC, got {1000.0 * k!r}) and track_width_mm "
                         f"(got {w!r})")
    x, y, orientation = (int(c) for c in p0)
    out = np.empty((len(inc), 3), dtype=np.int64)
    rest_alpha = rest_x = rest_y = 0.0
    alpha_scale = 1000.0 / (k * w)
    for i, (left, right) in enumerate(inc.tolist()):
        if carry:
            distance = (left + right) / 2.0 / k
            exact_alpha = rest_alpha + (right - left) * alpha_scale
            alpha = math.trunc(exact_alpha)
            rest_alpha = exact_alpha - alpha
        else:
            distance = math.trunc(c_div(left + right, 2) / k)
            alpha = math.trunc((right - left) * alpha_scale)
        if alpha_rounding == "source":
            alpha = _div_round_up(_div_round_up(1000 * (right - left), enc) * 1000, base)
        orientation = _c_mod(orientation + alpha, FIRMWARE_TWO_PI_MRAD)
        heading = orientation / 1000.0
        dx = -distance * math.sin(heading)
        dy = distance * math.cos(heading)
        if carry:
            dx += rest_x
            dy += rest_y
            step_x, step_y = math.trunc(dx), math.trunc(dy)
            rest_x, rest_y = dx - step_x, dy - step_y
        else:
            step_x, step_y = math.trunc(dx), math.trunc(dy)
        x += step_x
        y += step_y
        out[i] = (x, y, orientation)
    return out


# ============================================================================================
# Uncertainty
# ============================================================================================
# How wrong, and how sure: the covariance of a dead-reckoned pose under random wheel errors
# (propagated to first order, or sampled by Monte Carlo), and Borenstein and Feng's UMBmark
# correction of the two systematic errors. SI units (m, rad), REP-103 frame. W is the track
# width (``track_width``): the side-to-side distance between the wheels' contact lines.

from typing import NamedTuple  # noqa: E402

from wheelkin import _validate as _checks  # noqa: E402
from wheelkin._kernels import SERIES_THRESHOLD as _ARC_THRESHOLD  # noqa: E402
from wheelkin._kernels import arc_factors as _arc_factors  # noqa: E402
from wheelkin._kernels import arc_step as _arc_step  # noqa: E402

__all__ += [
    "PathCovariance",
    "PoseCovariance",
    "StepJacobians",
    "UmbmarkCorrection",
    "monte_carlo_poses",
    "propagate_covariance",
    "propagate_path",
    "step_jacobians",
    "umbmark_correction",
]


class StepJacobians(NamedTuple):
    """The Jacobians of one exact-arc update (see :func:`step_jacobians`)."""

    #: :math:`F_p = \partial(x', y', \theta')/\partial(x, y, \theta)`, shape (3, 3).
    wrt_pose: np.ndarray
    #: :math:`F_w = \partial(x', y', \theta')/\partial(\Delta s_L, \Delta s_R)`, shape (3, 2).
    wrt_wheels: np.ndarray


class PoseCovariance(NamedTuple):
    """A pose (x, y, θ) in m, m, rad and its 3 x 3 covariance (m², m·rad, rad²)."""

    pose: Pose | np.ndarray
    covariance: np.ndarray


class PathCovariance(NamedTuple):
    """Poses (N + 1, 3) along a path, the start first, and their covariances (N + 1, 3, 3)."""

    poses: np.ndarray
    covariances: np.ndarray


class UmbmarkCorrection(NamedTuple):
    """Borenstein and Feng's two correction factors (see :func:`umbmark_correction`)."""

    #: :math:`E_d = D_R/D_L`, the ratio of the right to the left wheel's true diameter.
    diameter_ratio: float
    #: :math:`E_b = W_{true}/W_{assumed}`, the true track width over the assumed one.
    track_ratio: float


def _pose_si(value, name: str = "pose") -> np.ndarray:
    arr = _checks.finite_array(name, value)
    if arr.shape != (3,):
        raise ValueError(f"{name} must have shape (3,): (x_m, y_m, theta_rad), "
                         f"got shape {arr.shape}")
    return arr


def _covariance(value, name: str = "covariance") -> np.ndarray:
    arr = _checks.finite_array(name, value)
    if arr.shape != (3, 3):
        raise ValueError(f"{name} must have shape (3, 3) (over x, y, theta), got shape "
                         f"{arr.shape}")
    scale = max(1.0, float(np.max(np.abs(arr))))
    if np.max(np.abs(arr - arr.T)) > 1e-9 * scale:
        raise ValueError(f"{name} must be symmetric, got {arr.tolist()!r}")
    sym = 0.5 * (arr + arr.T)
    if np.min(np.linalg.eigvalsh(sym)) < -1e-12 * scale:
        raise ValueError(f"{name} must be positive semi-definite (no negative eigenvalue), "
                         f"got eigenvalues {np.linalg.eigvalsh(sym).tolist()!r}")
    return sym


def _arc_derivatives(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r""":math:`(a'(\varphi), b'(\varphi))` of the kernel's arc factors, exact at 0."""
    small = np.abs(phi) < _ARC_THRESHOLD
    safe = np.where(small, 1.0, phi)
    a, b = _arc_factors(safe)
    p2 = phi * phi
    da = np.where(small, phi * (-1.0 / 3.0 + p2 / 30.0), (np.cos(safe) - a) / safe)
    db = np.where(small, 0.5 - p2 / 8.0 + p2 * p2 / 144.0, a - b / safe)
    return da, db


def _jacobians(theta, ds, dth, track_width: float) -> tuple[np.ndarray, np.ndarray]:
    """F_pose (..., 3, 3) and F_wheels (..., 3, 2) for validated, broadcast arrays."""
    theta, ds, dth = np.broadcast_arrays(*(np.asarray(q, dtype=float) for q in
                                           (theta, ds, dth)))
    a, b = _arc_factors(dth)
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    da, db = _arc_derivatives(dth)
    c, s = np.cos(theta), np.sin(theta)
    dx = ds * (a * c - b * s)
    dy = ds * (a * s + b * c)
    shape = theta.shape
    f_pose = np.zeros((*shape, 3, 3))
    f_pose[..., 0, 0] = f_pose[..., 1, 1] = f_pose[..., 2, 2] = 1.0
    f_pose[..., 0, 2] = -dy
    f_pose[..., 1, 2] = dx
    f_wheels = np.empty((*shape, 3, 2))
    for column, sign in ((0, -1.0), (1, 1.0)):  # left, right
        d_a = 0.5 * a + sign * ds * da / track_width
        d_b = 0.5 * b + sign * ds * db / track_width
        f_wheels[..., 0, column] = d_a * c - d_b * s
        f_wheels[..., 1, column] = d_a * s + d_b * c
        f_wheels[..., 2, column] = sign / track_width
    return f_pose, f_wheels


def _body(delta_left, delta_right, track_width: float):
    return 0.5 * (delta_left + delta_right), (delta_right - delta_left) / track_width


def step_jacobians(pose: ArrayLike, delta_left: float, delta_right: float,
                   track_width: float) -> StepJacobians:
    r"""The Jacobians of one exact-arc update with respect to the pose and the wheel travels.

    The update (the chord form of :func:`pose_update`, ``method="exact"``) is

    .. math::
        \Delta s = \frac{\Delta s_L + \Delta s_R}{2},\quad
        \Delta\theta = \frac{\Delta s_R - \Delta s_L}{W},\quad
        \begin{aligned}
        x' &= x + \Delta s\,(a\cos\theta - b\sin\theta)\\
        y' &= y + \Delta s\,(a\sin\theta + b\cos\theta)\\
        \theta' &= \theta + \Delta\theta
        \end{aligned}

    with :math:`a = \sin\Delta\theta/\Delta\theta` and
    :math:`b = (1 - \cos\Delta\theta)/\Delta\theta`. Its Jacobians are

    .. math::
        F_p = \begin{pmatrix} 1 & 0 & -(y' - y)\\ 0 & 1 & x' - x\\ 0 & 0 & 1\end{pmatrix},
        \qquad
        F_w = \begin{pmatrix}
        A_L\cos\theta - B_L\sin\theta & A_R\cos\theta - B_R\sin\theta\\
        A_L\sin\theta + B_L\cos\theta & A_R\sin\theta + B_R\cos\theta\\
        -1/W & 1/W \end{pmatrix}

    with :math:`A_{L,R} = a/2 \mp \Delta s\,a'/W` and :math:`B_{L,R} = b/2 \mp \Delta s\,b'/W`
    (upper sign: left), :math:`a' = (\cos\Delta\theta - a)/\Delta\theta`,
    :math:`b' = a - b/\Delta\theta`. Below :data:`wheelkin._kernels.SERIES_THRESHOLD`
    (:math:`|\Delta\theta| < 10^{-4}`, the arc kernel's switch) :math:`a'` and :math:`b'` come
    from their series :math:`-\Delta\theta/3 + \Delta\theta^3/30` and
    :math:`1/2 - \Delta\theta^2/8 + \Delta\theta^4/144`, so a straight step is exact.

    Parameters
    ----------
    pose : array_like, shape (3,)
        (x, y, θ) before the step: m, m, rad, REP-103 (θ counter-clockwise from +x).
    delta_left, delta_right : float
        Travel of the left and right wheel in the step, m (negative: backwards).
    track_width : float
        W, the side-to-side distance between the wheels' contact lines, m (> 0).

    Returns
    -------
    StepJacobians
        ``wrt_pose`` (3, 3) and ``wrt_wheels`` (3, 2), columns (left, right).

    Examples
    --------
    A straight step of 0.1 m at heading 0 on a 0.085 m track: the heading changes by
    :math:`\pm 1/W` per metre of wheel travel, and a wheel moves the robot sideways by
    :math:`\Delta s/(2W)` per metre.

    >>> jac = step_jacobians([0.0, 0.0, 0.0], 0.1, 0.1, 0.085)
    >>> print(np.round(jac.wrt_pose, 4) + 0.0)  # + 0.0: no "-0."
    [[1.  0.  0. ]
     [0.  1.  0.1]
     [0.  0.  1. ]]
    >>> print(np.round(jac.wrt_wheels, 4))
    [[  0.5      0.5   ]
     [ -0.5882   0.5882]
     [-11.7647  11.7647]]
    """
    p = _pose_si(pose)
    left = _travel("delta_left", delta_left)
    right = _travel("delta_right", delta_right)
    w = _checks.positive("track_width", track_width)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    f_pose, f_wheels = _jacobians(p[2], ds, dth, w)
    return StepJacobians(f_pose, f_wheels)


#: The largest wheel travel of one update (m) and error variance per metre (m) accepted.
_MAX_TRAVEL, _MAX_K = 1e6, 1.0


def _wheel_noise(name: str, value) -> float:
    k = _checks.nonnegative(name, value)
    if k > _MAX_K:
        raise ValueError(f"{name} must be in [0, {_MAX_K:g}] m (an error variance per metre "
                         f"rolled), got {value!r}")
    return k


def _travel(name: str, value) -> float:
    travel = _checks.finite(name, value)
    if abs(travel) > _MAX_TRAVEL:
        raise ValueError(f"{name} must be a wheel travel in [-{_MAX_TRAVEL:g}, "
                         f"{_MAX_TRAVEL:g}] m, got {value!r}")
    return travel


def _turns(dth, track_width: float) -> None:
    if np.any(np.abs(dth) > _MAX_TRAVEL):
        raise ValueError("delta_left, delta_right and track_width give a turn of more than "
                         f"{_MAX_TRAVEL:g} rad in one update (track_width = "
                         f"{track_width!r} m): check the units")


def propagate_covariance(pose: ArrayLike, covariance: ArrayLike, delta_left: float,
                         delta_right: float, track_width: float, k_left: float,
                         k_right: float) -> PoseCovariance:
    r"""One exact-arc update of a pose and of its covariance, with random wheel errors.

    Each wheel's travel in the step has an independent, zero-mean error whose variance grows
    with the distance it rolled (the error model of :cite:t:`siegwart2011`):

    .. math::
        Q = \begin{pmatrix} k_L\,|\Delta s_L| & 0\\ 0 & k_R\,|\Delta s_R| \end{pmatrix},
        \qquad
        \Sigma' = F_p\,\Sigma\,F_p^\mathsf{T} + F_w\,Q\,F_w^\mathsf{T}

    with the Jacobians :math:`F_p, F_w` of :func:`step_jacobians` (first order: exact for
    a linear update, an approximation where the update bends the distribution). The pose
    comes from the library's arc kernel. ``k_left`` and ``k_right`` are in m (variance in m²
    per m rolled): a wheel's error after 1 m has the standard deviation :math:`\sqrt{k}`.

    Parameters
    ----------
    pose : array_like, shape (3,)
        (x, y, θ) in m, m, rad (REP-103).
    covariance : array_like, shape (3, 3)
        Covariance of the pose over (x, y, θ), symmetric, positive semi-definite.
    delta_left, delta_right : float
        Wheel travels of the step, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).

    Returns
    -------
    PoseCovariance
        ``pose`` after the step (a Pose for a Pose, else an array (3,)) and its
        ``covariance`` (3, 3), symmetric.

    Examples
    --------
    A 1 m straight step from a certain pose with 1 mm per metre on each wheel (k = 1e-6 m):
    the distance error is the mean of the two wheels' errors, the heading error their
    difference over W.

    >>> new = propagate_covariance([0, 0, 0], np.zeros((3, 3)), 1.0, 1.0, 0.085, 1e-6, 1e-6)
    >>> print(new.pose)
    [1. 0. 0.]
    >>> print(f"{np.sqrt(new.covariance[0, 0]) * 1e3:.4f} mm, "
    ...       f"{np.sqrt(new.covariance[2, 2]) * 1e3:.3f} mrad")
    0.7071 mm, 16.638 mrad
    """
    p = _pose_si(pose)
    sigma = _covariance(covariance)
    left = _travel("delta_left", delta_left)
    right = _travel("delta_right", delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    f_pose, f_wheels = _jacobians(p[2], ds, dth, w)
    q = np.diag([kl * abs(left), kr * abs(right)])
    new = _covariance_step(f_pose, sigma, f_wheels @ q @ f_wheels.T)
    x, y, theta = _arc_step(float(p[0]), float(p[1]), float(p[2]), ds, dth)
    after = Pose(x, y, theta) if isinstance(pose, Pose) else np.array([x, y, theta])
    return PoseCovariance(after, new)


def _noise_model(track_width, k_left, k_right) -> tuple[float, float, float]:
    """The validated track width and the two wheels' error variances per metre."""
    return (_checks.positive("track_width", track_width), _wheel_noise("k_left", k_left),
            _wheel_noise("k_right", k_right))


def _covariance_step(f_pose: np.ndarray, sigma: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """One propagation step, F Σ Fᵀ + noise, made exactly symmetric."""
    step = f_pose @ sigma @ f_pose.T + noise
    return 0.5 * (step + step.T)


def _increment_pair(delta_left, delta_right) -> tuple[np.ndarray, np.ndarray]:
    left = _checks.finite_array("delta_left", delta_left)
    right = _checks.finite_array("delta_right", delta_right)
    if left.ndim != 1 or right.ndim != 1 or left.shape != right.shape or left.size == 0:
        raise ValueError("delta_left and delta_right must be 1-D arrays of the same length "
                         "N >= 1 (one wheel travel per update, m), got shapes "
                         f"{left.shape} and {right.shape}")
    for name, arr in (("delta_left", left), ("delta_right", right)):
        if np.any(np.abs(arr) > _MAX_TRAVEL):
            raise ValueError(f"{name} must hold wheel travels in [-{_MAX_TRAVEL:g}, "
                             f"{_MAX_TRAVEL:g}] m, got a largest of {np.abs(arr).max():g}")
    return left, right


def _path_poses(p0: np.ndarray, ds: np.ndarray, dth: np.ndarray) -> np.ndarray:
    """Poses after every update (..., N, 3) from Δs, Δθ (..., N): cumulative arc steps."""
    theta_after = p0[2] + np.cumsum(dth, axis=-1)
    theta_before = np.concatenate(
        [np.full((*dth.shape[:-1], 1), p0[2]), theta_after[..., :-1]], axis=-1)
    dx, dy, _ = _arc_step(0.0, 0.0, theta_before, ds, dth)
    return np.stack([p0[0] + np.cumsum(dx, axis=-1), p0[1] + np.cumsum(dy, axis=-1),
                     theta_after], axis=-1)


def propagate_path(pose: ArrayLike, covariance: ArrayLike, delta_left: ArrayLike,
                   delta_right: ArrayLike, track_width: float, k_left: float,
                   k_right: float) -> PathCovariance:
    r"""Propagate a pose and its covariance along a sequence of wheel increments.

    :func:`propagate_covariance` applied once per update:
    :math:`\Sigma_{k+1} = F_{p,k}\Sigma_k F_{p,k}^\mathsf{T} + F_{w,k} Q_k F_{w,k}^\mathsf{T}`,
    with the poses of the exact arc update (heading not wrapped).

    On a straight run of length :math:`s` in :math:`N` equal updates of :math:`h = s/N`
    from a certain start at heading 0, this gives exactly (derived in the chapter)

    .. math::
        \sigma_\theta^2 = \frac{(k_L + k_R)\,s}{W^2},\qquad
        \sigma_y^2 = \frac{k_L + k_R}{W^2}\Big(\frac{s^3}{3} - \frac{s h^2}{12}\Big),
        \qquad \sigma_x^2 = \frac{(k_L + k_R)\,s}{4}:

    the lateral variance grows with the cube of the distance.

    Parameters
    ----------
    pose : array_like, shape (3,)
        Start pose (x, y, θ): m, m, rad.
    covariance : array_like, shape (3, 3)
        Covariance of the start pose (zeros for a known start).
    delta_left, delta_right : array_like, shape (N,)
        Wheel travel of each update, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).

    Returns
    -------
    PathCovariance
        ``poses`` (N + 1, 3) and ``covariances`` (N + 1, 3, 3), the start first.

    Examples
    --------
    10 m straight ahead in 1000 updates, 1 mm per metre on each wheel, a 0.085 m track: the
    lateral standard deviation is :math:`\sqrt{2k s^3/(3W^2)}`, 30 cm.

    >>> h = np.full(1000, 0.01)
    >>> run = propagate_path([0, 0, 0], np.zeros((3, 3)), h, h, 0.085, 1e-6, 1e-6)
    >>> print(f"{np.sqrt(run.covariances[-1, 1, 1]):.4f} m")
    0.3038 m
    """
    p0 = _pose_si(pose)
    sigma = _covariance(covariance)
    left, right = _increment_pair(delta_left, delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    after = _path_poses(p0, ds, dth)
    poses = np.vstack([p0[None, :], after])
    f_pose, f_wheels = _jacobians(poses[:-1, 2], ds, dth, w)
    q = np.stack([kl * np.abs(left), kr * np.abs(right)], axis=-1)  # (N, 2) diagonals
    noise = np.einsum("nik,nk,njk->nij", f_wheels, q, f_wheels)
    out = np.empty((len(poses), 3, 3))
    out[0] = sigma
    for k in range(len(ds)):
        out[k + 1] = _covariance_step(f_pose[k], out[k], noise[k])
    return PathCovariance(poses, out)


#: Runs per block of :func:`monte_carlo_poses` (memory bound; the result does not depend on it).
_MC_BLOCK = 256


def monte_carlo_poses(pose: ArrayLike, delta_left: ArrayLike, delta_right: ArrayLike,
                      track_width: float, k_left: float, k_right: float, runs: int,
                      rng: np.random.Generator, *, at: ArrayLike | None = None) -> np.ndarray:
    r"""Poses of ``runs`` noisy repetitions of a drive: the sampled counterpart of
    :func:`propagate_path`.

    Each run integrates the wheel increments with independent errors drawn per update and
    per wheel, :math:`\Delta s_{L,k} + \sqrt{k_L|\Delta s_{L,k}|}\,z`, :math:`z \sim N(0, 1)`
    (the same model :func:`propagate_covariance` propagates), with the exact arc update of
    the library's kernel, vectorised over runs and updates (cumulative sums, as
    :func:`integrate`). The draws come from ``rng`` in a fixed order, so a seeded generator
    gives the same poses every time.

    Parameters
    ----------
    pose : array_like, shape (3,)
        Start pose (x, y, θ): m, m, rad (the same for every run).
    delta_left, delta_right : array_like, shape (N,)
        The nominal wheel travel of each update, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).
    runs : int
        Number of runs (>= 1).
    rng : numpy.random.Generator
        The source of the errors, e.g. ``np.random.default_rng(7)``.
    at : array_like of int, optional
        Numbers of updates (0 .. N) after which to report the poses; default: only the end.

    Returns
    -------
    numpy.ndarray
        Shape (runs, 3), the final poses; or (len(at), runs, 3) with ``at``.

    Examples
    --------
    >>> h = np.full(100, 0.01)
    >>> ends = monte_carlo_poses([0, 0, 0], h, h, 0.085, 1e-6, 1e-6, 2000,
    ...                          np.random.default_rng(1))
    >>> ends.shape
    (2000, 3)
    >>> print(f"{ends[:, 2].std() * 1e3:.2f} mrad (propagated: "
    ...       f"{np.sqrt(2e-6 * 1.0) / 0.085 * 1e3:.2f})")
    16.67 mrad (propagated: 16.64)
    """
    p0 = _pose_si(pose)
    left, right = _increment_pair(delta_left, delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    if isinstance(runs, bool) or not isinstance(runs, int | np.integer) or runs < 1:
        raise ValueError(f"runs must be a whole number >= 1, got {runs!r}")
    if not isinstance(rng, np.random.Generator):
        raise TypeError("rng must be a numpy.random.Generator (np.random.default_rng(seed)), "
                        f"got {type(rng).__name__}")
    _turns(_body(left, right, w)[1] + 6.0 * np.sqrt(kl + kr) * np.sqrt(
        np.abs(left) + np.abs(right)) / w, w)
    n = left.size
    if at is None:
        steps = np.array([n])
    else:
        steps = _checks.finite_array("at", at)
        if steps.ndim != 1 or steps.size == 0 or np.any(steps != np.round(steps)) or np.any(
                (steps < 0) | (steps > n)):
            raise ValueError(f"at must be a 1-D list of whole numbers of updates in [0, {n}], "
                             f"got {at!r}")
        steps = steps.astype(np.int64)
    sd = np.sqrt(np.array([kl, kr]) * np.abs(np.stack([left, right], axis=-1)))  # (N, 2)
    out = np.empty((len(steps), int(runs), 3))
    for start in range(0, int(runs), _MC_BLOCK):
        count = min(_MC_BLOCK, int(runs) - start)
        z = rng.standard_normal((count, n, 2))
        noisy_left = left + sd[:, 0] * z[..., 0]
        noisy_right = right + sd[:, 1] * z[..., 1]
        ds, dth = _body(noisy_left, noisy_right, w)
        poses = _path_poses(p0, ds, dth)
        full = np.concatenate([np.broadcast_to(p0, (count, 1, 3)), poses], axis=1)
        out[:, start:start + count] = np.moveaxis(full[:, steps], 1, 0)
    return out[0] if at is None else out


def umbmark_correction(cw_end: ArrayLike, ccw_end: ArrayLike, side: float, track_width: float, *,
                       components: str = "xy") -> UmbmarkCorrection:
    r"""Borenstein and Feng's correction factors from the returns of the bidirectional square.

    UMBmark :cite:p:`borenstein1996umbmark`: the robot drives a square of side :math:`L`,
    steered by its own odometry, once clockwise (CW, right turns on the spot) and once
    counter-clockwise (CCW, left turns), several times each. At the end the true position
    is measured; the *return error* is true minus odometry,
    :math:`\varepsilon = (x_{true} - x_{odo},\; y_{true} - y_{odo})`, and its mean over the
    runs of one direction (the paper's "centre of gravity") is ``cw_end`` or ``ccw_end``.

    **The paper's conventions, and ours.** The paper calls the track "the wheelbase
    :math:`b`"; in this book the wheelbase is the front-to-back distance, so its :math:`b` is
    our track width :math:`W` (``track_width``). Its equations take :math:`x` along the
    robot's heading at the start and :math:`y` to its left (the CCW square lies on the
    :math:`+y` side): the REP-103 frame of the start pose. If the robot starts at a heading
    :math:`\theta_0` in a world frame, rotate the errors by :math:`-\theta_0` first. Two
    error types:

    - *type A*, the track: the robot turns :math:`90^\circ - \alpha` at every corner in both
      directions (:math:`\alpha > 0`: less than it believes), :math:`E_b = W_{true}/W =
      (\pi/2)/(\pi/2 - \alpha)`;
    - *type B*, unequal wheel diameters: every straight leg bends by :math:`\beta`
      (:math:`\beta > 0`: to the left), the arc of radius :math:`R = (L/2)/\sin(\beta/2)`,
      and :math:`E_d = D_R/D_L = (R + E_b W/2)/(R - E_b W/2)`.

    To first order in :math:`\alpha, \beta` the returns are
    :math:`\varepsilon_{CW} = -2L(\alpha + \beta)\,(1, 1)` and
    :math:`\varepsilon_{CCW} = 2L(\alpha - \beta)\,(-1, 1)`, so

    .. math::
        \alpha = -\frac{x_{CW} + x_{CCW}}{4L} = -\frac{y_{CW} - y_{CCW}}{4L},\qquad
        \beta = -\frac{x_{CW} - x_{CCW}}{4L} = -\frac{y_{CW} + y_{CCW}}{4L}.

    The paper states these in degrees; here they are in radians. ``components="x"`` uses
    the :math:`x` forms, ``"y"`` the :math:`y` forms, ``"xy"`` (default) their mean, the
    least-squares solution of all four equations. To apply the correction, scale the
    distance per encoder count of the left and right wheel by :math:`2/(E_d + 1)` and
    :math:`2/(1/E_d + 1)` (their mean diameter unchanged) and use the track :math:`E_b W`.

    Parameters
    ----------
    cw_end, ccw_end : array_like, shape (2,)
        Mean return errors (x, y), true minus odometry, m, in the start pose's frame.
    side : float
        L, the side of the square, m (> 0).
    track_width : float
        W assumed by the odometry during the test, m (> 0).
    components : {"xy", "x", "y"}
        Which of the paper's equations give :math:`\alpha` and :math:`\beta`.

    Returns
    -------
    UmbmarkCorrection
        ``diameter_ratio`` :math:`E_d` and ``track_ratio`` :math:`E_b`.

    Raises
    ------
    ValueError
        Bad input, or returns so large (:math:`|\alpha|` or :math:`|\beta| \ge \pi/4`, or
        :math:`W|\sin(\beta/2)| \ge L`) that the first-order model does not apply.

    Examples
    --------
    A 4 m square, a 0.34 m track; both runs return 8 cm off, CW at (-0.08, -0.08) m and CCW
    at (-0.08, 0.08) m: a pure type A error (the robot turns too little in both
    directions), the true track 0.32 % larger.

    >>> E_d, E_b = umbmark_correction([-0.08, -0.08], [-0.08, 0.08], 4.0, 0.34)
    >>> print(f"E_d = {E_d:.6f}, E_b = {E_b:.6f}")
    E_d = 1.000000, E_b = 1.006407
    """
    cw = _checks.finite_array("cw_end", cw_end)
    ccw = _checks.finite_array("ccw_end", ccw_end)
    for name, arr in (("cw_end", cw), ("ccw_end", ccw)):
        if arr.shape != (2,):
            raise ValueError(f"{name} must have shape (2,): the mean return error (x, y) in m, "
                             f"got shape {arr.shape}")
    length = _checks.positive("side", side)
    w = _checks.positive("track_width", track_width)
    _checks.choice("components", components, ("xy", "x", "y"))
    alpha_x = -(cw[0] + ccw[0]) / (4.0 * length)
    alpha_y = -(cw[1] - ccw[1]) / (4.0 * length)
    beta_x = -(cw[0] - ccw[0]) / (4.0 * length)
    beta_y = -(cw[1] + ccw[1]) / (4.0 * length)
    if components == "x":
        alpha, beta = alpha_x, beta_x
    elif components == "y":
        alpha, beta = alpha_y, beta_y
    else:
        alpha, beta = 0.5 * (alpha_x + alpha_y), 0.5 * (beta_x + beta_y)
    limit = 0.25 * math.pi
    if abs(alpha) >= limit or abs(beta) >= limit:
        raise ValueError(
            f"cw_end and ccw_end are too large for UMBmark's first-order model: alpha = "
            f"{alpha:.3g} rad, beta = {beta:.3g} rad (each must be below pi/4 in size); "
            "check the units (m) and the side of the square")
    track_ratio = (0.5 * math.pi) / (0.5 * math.pi - alpha)
    half_bend = track_ratio * w * math.sin(0.5 * beta)
    if abs(half_bend) >= length:
        raise ValueError(
            f"cw_end and ccw_end give a leg bent to a radius ({0.5 * length:.3g} m / "
            f"sin({0.5 * beta:.3g})) smaller than half the track: the first-order model "
            "does not apply")
    # E_d = (R + b/2)/(R - b/2) with R = (L/2)/sin(beta/2), multiplied through by sin(beta/2)
    diameter_ratio = (length + half_bend) / (length - half_bend)
    return UmbmarkCorrection(float(diameter_ratio), float(track_ratio))
