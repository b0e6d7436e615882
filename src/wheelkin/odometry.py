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

How sure the pose is
--------------------
The uncertainty of a dead-reckoned pose (covariance propagation, Monte Carlo, UMBmark) is in
:mod:`wheelkin.odometry_uncertainty`. Its names stay importable from this module, where they
were first: ``wheelkin.odometry.propagate_covariance`` is
``wheelkin.odometry_uncertainty.propagate_covariance``, and so are ``step_jacobians``,
``propagate_path``, ``monte_carlo_poses``, ``umbmark_correction`` and their records.

Motion models
-------------
Thrun, Burgard and Fox's probabilistic motion models, which a localisation course uses, are
in :mod:`wheelkin.motion_models`; they are importable from here too, as the chapter names
them: ``wheelkin.odometry.motion_model_odometry`` (the density of table 5.5),
``wheelkin.odometry.sample_motion_model_odometry`` (its sampler, table 5.6),
``sample_motion_model_velocity`` (table 5.3), ``odometry_motion`` and ``OdometryMotion``.
"""

from __future__ import annotations

import math
from typing import Literal, NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _kernels
from wheelkin import _validate as V
from wheelkin._kernels import arc_factors, arc_step, c_div
from wheelkin._records import Stack, _is_one
from wheelkin.frames import Pose, wrap_angle

# Thrun's motion models live in wheelkin.motion_models; the chapter imports them from here.
from wheelkin.motion_models import OdometryMotion as OdometryMotion
from wheelkin.motion_models import motion_model_odometry as motion_model_odometry
from wheelkin.motion_models import odometry_motion as odometry_motion
from wheelkin.motion_models import sample_motion_model_odometry as sample_motion_model_odometry
from wheelkin.motion_models import sample_motion_model_velocity as sample_motion_model_velocity

# The uncertainty of a dead-reckoned pose moved to wheelkin.odometry_uncertainty; its names
# stay importable from here, as before.
from wheelkin.odometry_uncertainty import PathCovariance as PathCovariance
from wheelkin.odometry_uncertainty import PoseCovariance as PoseCovariance
from wheelkin.odometry_uncertainty import StepJacobians as StepJacobians
from wheelkin.odometry_uncertainty import UmbmarkCorrection as UmbmarkCorrection
from wheelkin.odometry_uncertainty import monte_carlo_poses as monte_carlo_poses
from wheelkin.odometry_uncertainty import propagate_covariance as propagate_covariance
from wheelkin.odometry_uncertainty import propagate_path as propagate_path
from wheelkin.odometry_uncertainty import step_jacobians as step_jacobians
from wheelkin.odometry_uncertainty import umbmark_correction as umbmark_correction

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
    arr = V.finite_array("increments", value)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError("increments must have shape (N, 2): one (left, right) pair of encoder "
                         f"step increments per update, got shape {arr.shape}")
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
    k = V.positive("steps_per_mm", steps_per_mm)
    w = V.positive("track_width_mm", track_width_mm)
    left, right = inc[:, 0], inc[:, 1]
    return BodyIncrements((left + right) / (2.0 * k), (right - left) / (k * w))


@overload
def chord_factor(dtheta: float) -> float: ...
@overload
def chord_factor(dtheta: Stack) -> NDArray[np.float64]: ...
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
    d = V.finite_array("dtheta", dtheta)
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
    p = V.shaped("pose", pose, (3,))
    ds = V.finite_array("distance", distance)
    dth = V.finite_array("dtheta", dtheta)
    V.choice("method", method, METHODS)
    try:
        ds, dth, _ = np.broadcast_arrays(ds, dth, p[..., 0])
    except ValueError:
        raise ValueError(f"distance (shape {ds.shape}) and dtheta (shape {dth.shape}) must "
                         f"broadcast against pose[..., 0] (shape {p.shape[:-1]})") from None
    with np.errstate(all="ignore"):
        out = _step(p, ds, dth, method)
    out = V.finite_result("pose, distance and dtheta", out)
    return Pose(*out.tolist()) if _is_one(pose, Pose) and out.ndim == 1 else out


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
    V.choice("method", method, METHODS)
    p0 = V.pose("pose", pose)
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
    left = V.finite_array("delta_left", delta_left)
    right = V.finite_array("delta_right", delta_right)
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
    w = V.positive("track_width", track_width)
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
    V.choice("method", method, METHODS)
    p0 = V.pose("pose", pose)
    with np.errstate(all="ignore"):  # an overflow is refused below, naming the inputs
        ds, dth = body_motion(delta_left, delta_right, track_width)
        theta = p0[2] + np.cumsum(dth)
        start = np.concatenate(([p0[2]], theta))[:-1]
        steps = _step(np.stack([np.zeros_like(ds), np.zeros_like(ds), start], axis=-1), ds, dth,
                      method)
        out = np.column_stack([p0[0] + np.cumsum(steps[:, 0]),
                               p0[1] + np.cumsum(steps[:, 1]), theta])
    return V.finite_result("delta_left, delta_right, track_width and pose", out)


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
    seg = V.finite_array("segments", segments)
    if seg.ndim != 2 or seg.shape[1] != 2:
        raise ValueError("segments must have shape (M, 2): (distance_mm, turn_rad) per segment, "
                         f"got shape {seg.shape}")
    w = V.positive("track_width_mm", track_width_mm)
    h = V.positive("max_step_mm", max_step_mm)
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
    s = V.finite_array("travel_mm", travel_mm)
    if s.ndim != 2 or s.shape[1] != 2 or s.shape[0] < 1:
        raise ValueError("travel_mm must have shape (K + 1, 2): cumulative (left, right) travel, "
                         f"first row the start, got shape {s.shape}")
    k = V.positive("steps_per_mm", steps_per_mm)
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
    k = V.positive("steps_per_mm", steps_per_mm)
    w = V.positive("track_width_mm", track_width_mm)
    p0 = V.pose("pose", pose)
    V.choice("center", center, CENTERS)
    V.choice("wrap", wrap, WRAPS)
    V.choice("position_heading", position_heading, POSITION_HEADINGS)
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
    V.choice("wrap", wrap, ("literal", "fmod"))
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
    k = V.positive("steps_per_mm", steps_per_mm)
    w = V.positive("track_width_mm", track_width_mm)
    p0 = _whole("pose", V.pose("pose", pose))
    if not isinstance(carry, bool | np.bool_):
        raise ValueError(f"carry must be True or False, got {carry!r}")
    V.choice("alpha_rounding", alpha_rounding, ("truncate", "source"))
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
