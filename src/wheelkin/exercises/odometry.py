"""Exercises of the chapter "Odometry: where am I?" (checked against wheelkin.odometry).

- ``odometry.center_and_turn``: Δs and Δθ of one update from the encoder increments.
- ``odometry.midpoint_step``: one midpoint update of the pose (our frame).
- ``odometry.exact_step``: one exact (arc) update, which must also work for Δθ = 0.
- ``odometry.alpha_mrad``: the README's "improvement" in whole mrad, as a naive C port
  computes it (a cast, which truncates toward zero).
- ``odometry.choose_update``: a design: the cheapest update rule (1 Euler, 2 midpoint,
  3 exact arc) that keeps the error after half a circle within a budget.
- ``odometry.motion_split``: Thrun's turn, line and turn between two poses.
- ``odometry.gyro_correction``: the wheel-and-gyro filter's correction of one update.
"""

from __future__ import annotations

import math

from numpy.typing import ArrayLike, NDArray

from wheelkin import odometry as odo
from wheelkin.exercises import Case, Exercise

__all__ = ["alpha_mrad", "center_and_turn", "choose_update", "exact_step", "midpoint_step"]

_K = 8.043  # Radon Ulzer: steps per mm
_W = 85.0  # Radon Ulzer: track width W (wheel to wheel, side to side), mm


def center_and_turn(n_left: float, n_right: float, steps_per_mm: float,
                    track_mm: float) -> tuple[float, float]:
    """(Δs in mm, Δθ in rad) for one update with ``n_left``, ``n_right`` encoder steps."""
    ds, dth = odo.body_increments([[n_left, n_right]], steps_per_mm, track_mm)
    return (float(ds[0]), float(dth[0]))


def midpoint_step(x: float, y: float, theta: float, distance: float,
                  dtheta: float) -> tuple[float, ...]:
    """(x', y', θ') after one midpoint update (our frame, x forward, θ counter-clockwise)."""
    return tuple(odo.pose_update([x, y, theta], distance, dtheta, "midpoint").tolist())


def exact_step(x: float, y: float, theta: float, distance: float,
               dtheta: float) -> tuple[float, ...]:
    """(x', y', θ') after one exact arc update; Δθ may be zero."""
    return tuple(odo.pose_update([x, y, theta], distance, dtheta, "exact").tolist())


def alpha_mrad(n_left: float, n_right: float, steps_per_mm: float, track_mm: float) -> int:
    """The README's alpha in whole mrad, truncated toward zero as a C cast does."""
    return math.trunc(1000.0 * (n_right - n_left) / (steps_per_mm * track_mm))


def _readme_center(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left - n_right) / 2 / steps_per_mm,
            (n_right - n_left) / (steps_per_mm * track_width_mm))


def _sum_not_halved(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left + n_right) / steps_per_mm,
            (n_right - n_left) / (steps_per_mm * track_width_mm))


def _half_base(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            2 * (n_right - n_left) / (steps_per_mm * track_width_mm))


def _turn_sign(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            (n_left - n_right) / (steps_per_mm * track_width_mm))


def _turn_mrad(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            1000 * (n_right - n_left) / (steps_per_mm * track_width_mm))


def _no_mm(n_left, n_right, steps_per_mm, track_width_mm):
    return ((n_left + n_right) / 2, (n_right - n_left) / track_width_mm)


Exercise(
    "odometry.center_and_turn",
    "Given the encoder step increments n_left and n_right of one update, steps_per_mm and the "
    "track width W in mm, return (Δs in mm, Δθ in rad): the travel of the mid-point between the "
    "wheels and the change of heading (counter-clockwise positive).",
    center_and_turn,
    [Case((80, 100, _K, _W)), Case((100, 80, _K, _W)), Case((-50, 50, _K, _W)),
     Case((120, 120, _K, _W)), Case((-30, -70, 10.0, 120.0))],
    wheel_names=("Δs", "Δθ"),
    mistakes=[
        (_readme_center, "Δs is the mean of the two wheels, (L + R)/2, not the README's "
                         "(L − R)/2: with the difference, driving straight goes nowhere."),
        (_sum_not_halved, "Δs is twice too large: the mid-point travels the mean of the two "
                          "wheels, (Δs_L + Δs_R)/2."),
        (_half_base, "Δθ is twice too large: divide by the whole track width W (wheel to "
                     "wheel), not W/2."),
        (_turn_sign, "Δθ has the wrong sign: the right wheel going further turns the robot to "
                     "the left, which is counter-clockwise and positive (right minus left)."),
        (_turn_mrad, "Δθ is in mrad: the answer is wanted in rad."),
        (_no_mm, "divide the steps by steps_per_mm first: both results need wheel travel in mm, "
                 "not encoder steps."),
    ],
)


def _end_heading(x, y, theta, distance, dtheta):
    t = theta + dtheta
    return (x + distance * math.cos(t), y + distance * math.sin(t), t)


def _start_heading(x, y, theta, distance, dtheta):
    return (x + distance * math.cos(theta), y + distance * math.sin(theta), theta + dtheta)


def _firmware_frame(x, y, theta, distance, dtheta):
    t = theta + dtheta / 2
    return (x - distance * math.sin(t), y + distance * math.cos(t), theta + dtheta)


def _midpoint_no_turn(x, y, theta, distance, dtheta):
    t = theta + dtheta / 2
    return (x + distance * math.cos(t), y + distance * math.sin(t), theta)


Exercise(
    "odometry.midpoint_step",
    "Return the pose (x', y', θ') after one update that moved the mid-point by `distance` and "
    "turned the robot by `dtheta` (rad), using the heading half-way through the step; our frame: "
    "x forward, y left, θ counter-clockwise from +x.",
    midpoint_step,
    [Case((0.0, 0.0, 0.0, 10.0, 0.2)), Case((100.0, -50.0, 1.0, 12.0, -0.3)),
     Case((5.0, 5.0, -2.5, -8.0, 0.1)), Case((0.0, 0.0, 3.0, 20.0, 0.0))],
    wheel_names=("x'", "y'", "θ'"),
    mistakes=[
        (_end_heading, "you used the heading at the end of the step (θ + Δθ), as the README "
                       "does: that is first order. Use θ + Δθ/2."),
        (_start_heading, "you used the heading at the start of the step (Euler, first order). "
                         "Use θ + Δθ/2."),
        (_firmware_frame, "that is the firmware's Y-forward frame (dX = −Δs sin, dY = Δs cos); in "
                          "ours x is forward: x' = x + Δs cos(θ + Δθ/2)."),
        (_midpoint_no_turn, "the position is right but θ' must be θ + Δθ."),
    ],
)


def _midpoint_as_exact(x, y, theta, distance, dtheta):
    return midpoint_step(x, y, theta, distance, dtheta)


def _naive_arc(x, y, theta, distance, dtheta):
    r = distance / dtheta
    return (x + r * (math.sin(theta + dtheta) - math.sin(theta)),
            y - r * (math.cos(theta + dtheta) - math.cos(theta)), theta + dtheta)


def _arc_not_halved(x, y, theta, distance, dtheta):
    c = math.sin(dtheta) / dtheta if dtheta else 1.0
    t = theta + dtheta / 2
    return (x + distance * c * math.cos(t), y + distance * c * math.sin(t), theta + dtheta)


Exercise(
    "odometry.exact_step",
    "Return the pose (x', y', θ') after one update in which the mid-point travelled `distance` "
    "along an arc of constant curvature while the heading changed by `dtheta` (rad). It must "
    "also work when dtheta is 0 or tiny (1e-12).",
    exact_step,
    [Case((0.0, 0.0, 0.0, 50.0 * math.pi, math.pi / 2)), Case((10.0, 20.0, 0.5, 30.0, -0.8)),
     Case((0.0, 0.0, -1.0, -25.0, 0.3)), Case((1.0, 2.0, 0.3, 10.0, 0.0)),
     Case((1.0, 2.0, 0.3, 10.0, 1e-12))],
    wheel_names=("x'", "y'", "θ'"),
    mistakes=[
        (_midpoint_as_exact, "that is the midpoint update: along an arc the chord is shorter "
                             "than Δs by the factor sin(Δθ/2)/(Δθ/2)."),
        (_arc_not_halved, "the chord factor is sin(Δθ/2)/(Δθ/2), with half the turn."),
        (_naive_arc, "R (sin(θ + Δθ) − sin θ) with R = Δs/Δθ loses its digits when Δθ is tiny "
                     "(and divides by zero at 0): write it as Δs · sin(Δθ/2)/(Δθ/2) · "
                     "cos(θ + Δθ/2) and use the series 1 − Δθ²/24 when |Δθ| is small."),
    ],
    rtol=1e-9,
)


def _alpha_rounded(n_left, n_right, steps_per_mm, track_width_mm):
    return round(1000.0 * (n_right - n_left) / (steps_per_mm * track_width_mm))


def _alpha_floor(n_left, n_right, steps_per_mm, track_width_mm):
    return math.floor(1000.0 * (n_right - n_left) / (steps_per_mm * track_width_mm))


def _alpha_float(n_left, n_right, steps_per_mm, track_width_mm):
    return 1000.0 * (n_right - n_left) / (steps_per_mm * track_width_mm)


Exercise(
    "odometry.alpha_mrad",
    "The README's improvement: return alpha = 1000 (R − L)/(steps_per_mm · wheelBase) as a whole "
    "number of mrad, converted to an integer as a naive C port does (a cast: int32_t alpha = "
    "...); wheelBase "
    "is the README's name for the track width W.",
    alpha_mrad,
    [Case((0, 100, 10.0, _W)), Case((100, 0, 10.0, _W)), Case((80, 90, _K, _W)),
     Case((95, 80, _K, _W)), Case((-40, 40, _K, _W))],
    mistakes=[
        (_alpha_float, "the firmware stores whole mrad: convert the quotient to an integer."),
        (_alpha_rounded, "C converts a float to an integer by truncating toward zero, not by "
                         "rounding to the nearest."),
        (_alpha_floor, "math.floor rounds negative values down (−117.6 → −118); C truncates "
                       "toward zero (−117)."),
    ],
    atol=1e-9,
)


# ------------------------------------------------------------------ a design: the update rule

def choose_update(update_mm: float, radius_mm: float, tolerance_mm: float) -> int:
    """The cheapest rule (1 Euler, 2 midpoint, 3 exact arc) whose end-point error after half a
    circle of ``radius_mm``, in updates of ``update_mm``, stays within ``tolerance_mm``.

    The errors are Euler's h sin(Φ/2) and the midpoint rule's h² sin(Φ/2)/(12 R) at Φ = π
    (the book's sympy derivation, checked against odometry.integrate); the exact arc has none.
    """
    if update_mm <= tolerance_mm:
        return 1
    if update_mm**2 / (12.0 * radius_mm) <= tolerance_mm:
        return 2
    return 3


def _choose_local_euler(update_mm, radius_mm, tolerance_mm):
    if update_mm**2 / (2.0 * radius_mm) <= tolerance_mm:
        return 1
    return choose_update(update_mm, radius_mm, tolerance_mm)


def _choose_24(update_mm, radius_mm, tolerance_mm):
    if update_mm <= tolerance_mm:
        return 1
    return 2 if update_mm**2 / (24.0 * radius_mm) <= tolerance_mm else 3


Exercise(
    "odometry.choose_update",
    "Odometry updates every update_mm of centre travel; the tightest curve has radius "
    "radius_mm; after half a circle on it the integration error must stay within "
    "tolerance_mm. Return the cheapest rule that meets it: 1 Euler, 2 midpoint, 3 exact arc.",
    choose_update,
    [Case((0.05, 100.0, 0.1)), Case((10.0, 100.0, 0.1)), Case((10.0, 50.0, 0.1)),
     Case((1.0, 100.0, 0.1)), Case((20.0, 1000.0, 0.05)), Case((5.0, 100.0, 0.01))],
    mistakes=[
        (_choose_local_euler, "you judged Euler by its error in one step, h²/(2R); the budget "
                              "is for the end of half a circle, where the steps' errors add "
                              "up to h sin(Φ/2) = h."),
        (_choose_24, "you used a one-step factor (1/24); the midpoint rule's error at the end "
                     "of half a circle is h² sin(Φ/2)/(12 R) = h²/(12 R)."),
        (lambda update_mm, radius_mm, tolerance_mm: 3,
         "the exact arc always meets the budget, but the cheapest rule that meets it is "
         "wanted: try Euler (h ≤ tolerance) and the midpoint rule (h²/(12 R) ≤ tolerance) "
         "first."),
        (lambda update_mm, radius_mm, tolerance_mm: min(
            choose_update(update_mm, radius_mm, tolerance_mm) + 1, 3),
         "that rule meets the budget, but a cheaper one does too."),
        (lambda update_mm, radius_mm, tolerance_mm: max(
            choose_update(update_mm, radius_mm, tolerance_mm) - 1, 1),
         "that rule is too coarse for the budget: compare its error after half a circle "
         "(Euler h, midpoint h²/(12 R)) with the tolerance."),
    ],
    atol=1e-9,
)


# --------------------------------------------------------------------------------------------
# Uncertainty and UMBmark (sections "How sure?", "Monte Carlo", "UMBmark"): SI units, the
# track width W in m.
#
# - ``odometry.pose_jacobian``: F_p of one exact arc step.
# - ``odometry.covariance_step``: the covariance after one straight step with wheel errors.
# - ``odometry.umbmark_correction``: E_d and E_b from the returns of the square both ways.
# - ``odometry.blind_distance``: a design: how far the robot may drive straight without a
#   fix before the sideways standard deviation reaches a tolerance.

import numpy as np  # noqa: E402

__all__ += ["blind_distance", "covariance_step", "pose_jacobian", "umbmark_correction"]


def pose_jacobian(theta: float, distance: float, dtheta: float) -> NDArray[np.float64]:
    """F_p = d(x', y', θ')/d(x, y, θ) of one exact arc step (Δs = distance, Δθ = dtheta)."""
    return odo.step_jacobians([0.0, 0.0, theta], distance - dtheta / 2,
                              distance + dtheta / 2, 1.0).wrt_pose


def _jacobian_euler(theta, distance, dtheta):
    return np.array([[1, 0, -distance * math.sin(theta)], [0, 1, distance * math.cos(theta)],
                     [0, 0, 1]])


def _jacobian_no_chord(theta, distance, dtheta):
    mid = theta + dtheta / 2
    return np.array([[1, 0, -distance * math.sin(mid)], [0, 1, distance * math.cos(mid)],
                     [0, 0, 1]])


def _jacobian_flipped(theta, distance, dtheta):
    f = pose_jacobian(theta, distance, dtheta)
    f[0, 2], f[1, 2] = -f[0, 2], -f[1, 2]
    return f


def _jacobian_zero_diagonal(theta, distance, dtheta):
    f = pose_jacobian(theta, distance, dtheta)
    return f - np.eye(3)


Exercise(
    "odometry.pose_jacobian",
    "Return the 3 x 3 Jacobian F_p = ∂(x', y', θ')/∂(x, y, θ) of one exact arc step that "
    "moves the mid-point `distance` (m) along an arc turning by `dtheta` (rad), starting at "
    "heading `theta`.",
    pose_jacobian,
    [Case((0.0, 1.0, 0.5)), Case((0.7, 0.2, -1.0)), Case((-2.0, 0.5, 0.0)),
     Case((3.0, -0.3, 0.4))],
    mistakes=[
        (_jacobian_euler, "that is the Jacobian of the Euler update (start heading, no "
                          "chord): the exact step's last column is (−(y' − y), x' − x)."),
        (_jacobian_no_chord, "the heading is right but the length is not: the chord is "
                             "shorter than Δs by sin(Δθ/2)/(Δθ/2)."),
        (_jacobian_flipped, "the last column has the wrong sign: a heading error swings the "
                            "step counter-clockwise, ∂x'/∂θ = −(y' − y), ∂y'/∂θ = x' − x."),
        (_jacobian_zero_diagonal, "the diagonal is missing: x' depends on x with slope 1, "
                                  "F_p is the identity plus one column."),
    ],
    rtol=1e-9,
)


def covariance_step(covariance: ArrayLike, theta: float, distance: float, track_width: float,
                    k_left: float, k_right: float) -> NDArray[np.float64]:
    """Σ' after one straight step (both wheels roll `distance`, m) at heading `theta`."""
    return odo.propagate_covariance([0.0, 0.0, theta], covariance, distance, distance,
                                    track_width, k_left, k_right).covariance


def _straight_jacobians(theta, distance, track_width, sideways=True):
    c, s = math.cos(theta), math.sin(theta)
    f_pose = np.array([[1, 0, -distance * s], [0, 1, distance * c], [0, 0, 1]])
    e = distance / (2 * track_width) if sideways else 0.0
    f_wheels = np.array([[c / 2 + e * s, c / 2 - e * s], [s / 2 - e * c, s / 2 + e * c],
                         [-1 / track_width, 1 / track_width]])
    return f_pose, f_wheels


def _cov_no_sideways(covariance, theta, distance, track_width, k_left, k_right):
    f_pose, f_wheels = _straight_jacobians(theta, distance, track_width, sideways=False)
    q = np.diag([k_left * abs(distance), k_right * abs(distance)])
    return f_pose @ np.asarray(covariance) @ f_pose.T + f_wheels @ q @ f_wheels.T


def _cov_squared(covariance, theta, distance, track_width, k_left, k_right):
    f_pose, f_wheels = _straight_jacobians(theta, distance, track_width)
    q = np.diag([k_left * distance**2, k_right * distance**2])
    return f_pose @ np.asarray(covariance) @ f_pose.T + f_wheels @ q @ f_wheels.T


def _cov_no_transport(covariance, theta, distance, track_width, k_left, k_right):
    _, f_wheels = _straight_jacobians(theta, distance, track_width)
    q = np.diag([k_left * abs(distance), k_right * abs(distance)])
    return np.asarray(covariance) + f_wheels @ q @ f_wheels.T


def _cov_wheels_swapped(covariance, theta, distance, track_width, k_left, k_right):
    return covariance_step(covariance, theta, distance, track_width, k_right, k_left)


_SIGMA0 = [[4e-6, 1e-6, 2e-5], [1e-6, 9e-6, -1e-5], [2e-5, -1e-5, 4e-4]]

Exercise(
    "odometry.covariance_step",
    "Return the 3 x 3 covariance Σ' of the pose after one straight step in which both "
    "wheels roll `distance` (m) at heading `theta`, from the covariance `covariance`, with "
    "wheel error variances k_left·|Δs_L| and k_right·|Δs_R| (k in m) and a track width "
    "`track_width` (m).",
    covariance_step,
    [Case((_SIGMA0, 0.3, 0.1, 0.085, 1e-6, 3e-6)), Case((_SIGMA0, -2.0, 0.05, 0.12, 4e-6, 1e-6)),
     Case(([[0.0] * 3] * 3, 1.0, 0.2, 0.085, 1e-6, 2e-6))],
    mistakes=[
        (_cov_no_sideways, "F_w is missing its sideways part ±Δs/(2W): a wheel error turns "
                           "the robot during the step, which drives half of it on the new "
                           "heading."),
        (_cov_squared, "the wheel error variance is k·|Δs|, proportional to the distance "
                       "(not k·Δs², which would make short updates too certain)."),
        (_cov_no_transport, "the old covariance must be carried through the step: "
                            "F_p Σ F_pᵀ, not Σ (a heading error swings the step)."),
        (_cov_wheels_swapped, "k_left and k_right are swapped: column 0 of F_w is the left "
                              "wheel."),
    ],
    rtol=1e-9,
    atol=1e-15,
)


def umbmark_correction(cw_end: ArrayLike, ccw_end: ArrayLike, side: float,
                       track_width: float) -> tuple[float, ...]:
    """(E_d, E_b) from the mean return errors (x, y), m, of the CW and CCW squares, with
    α and β from the x errors (the paper's equations)."""
    return tuple(odo.umbmark_correction(cw_end, ccw_end, side, track_width, components="x"))


def _returns(alpha, beta, side):
    """First-order return errors (CW, CCW) for the paper's angles (tested in the library)."""
    cw = [-2 * side * (alpha + beta)] * 2
    ccw = [-2 * side * (alpha - beta), 2 * side * (alpha - beta)]
    return cw, ccw


def _umb_swapped(cw_end, ccw_end, side, track_width):
    return umbmark_correction(ccw_end, cw_end, side, track_width)


def _umb_degrees(cw_end, ccw_end, side, track_width):
    alpha = -(cw_end[0] + ccw_end[0]) / (4 * side)
    beta = -(cw_end[0] - ccw_end[0]) / (4 * side)
    e_b = 90 / (90 - alpha)
    radius = (side / 2) / math.sin(beta / 2)
    return ((radius + e_b * track_width / 2) / (radius - e_b * track_width / 2), e_b)


def _umb_alpha_beta_swapped(cw_end, ccw_end, side, track_width):
    beta = -(cw_end[0] + ccw_end[0]) / (4 * side)
    alpha = -(cw_end[0] - ccw_end[0]) / (4 * side)
    e_b = (math.pi / 2) / (math.pi / 2 - alpha)
    radius = (side / 2) / math.sin(beta / 2)
    return ((radius + e_b * track_width / 2) / (radius - e_b * track_width / 2), e_b)


Exercise(
    "odometry.umbmark_correction",
    "Return (E_d, E_b): Borenstein and Feng's diameter ratio D_R/D_L and track ratio "
    "W_true/W from the mean return errors (x, y) in m (true minus odometry, the start "
    "pose's frame) of the clockwise run `cw_end` and the counter-clockwise run `ccw_end` "
    "of a square of side `side` (m) driven by a robot whose odometry assumes the track "
    "`track_width` (m); take α and β from the x errors, as the paper does.",
    umbmark_correction,
    [Case((*_returns(0.02, 0.01, 4.0), 4.0, 0.34)), Case((*_returns(-0.015, 0.004, 4.0), 4.0,
                                                          0.34)),
     Case((*_returns(0.03, -0.02, 1.0), 1.0, 0.085)), Case(([-0.1095, -0.1335],
                                                            [-0.0262, 0.0266], 1.0, 0.085))],
    wheel_names=("E_d", "E_b"),
    mistakes=[
        (_umb_swapped, "cw_end and ccw_end are swapped: the clockwise run turns right."),
        (_umb_degrees, "α and β are in radians here: use π/2 in E_b = (π/2)/(π/2 − α), not "
                       "90 (the paper writes degrees)."),
        (_umb_alpha_beta_swapped, "α and β are swapped: the sum x_CW + x_CCW measures the "
                                  "turn error α (type A), their difference the bend β "
                                  "(type B)."),
    ],
    rtol=1e-4,
    atol=0.0,
)


def blind_distance(tolerance: float, track_width: float, k_left: float, k_right: float) -> float:
    """The longest straight run (m) whose sideways standard deviation stays <= tolerance."""
    return (3.0 * track_width**2 * tolerance**2 / (k_left + k_right)) ** (1.0 / 3.0)


def _blind_square_law(tolerance, track_width, k_left, k_right):
    return math.sqrt(track_width**2 * tolerance**2 / (k_left + k_right))


def _blind_no_three(tolerance, track_width, k_left, k_right):
    return (track_width**2 * tolerance**2 / (k_left + k_right)) ** (1.0 / 3.0)


def _blind_one_wheel(tolerance, track_width, k_left, k_right):
    return (3.0 * track_width**2 * tolerance**2 / k_left) ** (1.0 / 3.0)


Exercise(
    "odometry.blind_distance",
    "A design: return the longest distance (m) the robot may drive straight from a known "
    "pose before the standard deviation of its sideways position reaches `tolerance` (m), "
    "for a track width `track_width` (m) and wheel errors k_left, k_right (m), with short "
    "updates.",
    blind_distance,
    [Case((0.05, 0.085, 1e-6, 1e-6)), Case((0.01, 0.3, 4e-6, 1e-6)),
     Case((0.2, 0.12, 1e-5, 3e-5))],
    mistakes=[
        (_blind_square_law, "the sideways variance grows with the cube of the distance, "
                            "σ_y² = (k_L + k_R) s³/(3W²), not with its square."),
        (_blind_no_three, "σ_y² = (k_L + k_R) s³/(3 W²): the factor 3 is missing."),
        (_blind_one_wheel, "both wheels' errors add: use k_left + k_right."),
    ],
    rtol=1e-9,
)


# ------------------------------------------------------------------ motion models and the gyro

__all__ += ["gyro_correction", "motion_split"]


def motion_split(previous_pose: ArrayLike, pose: ArrayLike) -> NDArray[np.float64]:
    """(rot1 rad, trans m, rot2 rad): Thrun's turn, line and turn from ``previous_pose`` to
    ``pose`` (each (x, y, theta) in m, m, rad), both turns wrapped to (-pi, pi]."""
    return np.array(odo.odometry_motion(previous_pose, pose))


def _split_unwrapped(previous_pose, pose):
    x0, y0, th0 = previous_pose
    x1, y1, th1 = pose
    rot1 = math.atan2(y1 - y0, x1 - x0) - th0
    return np.array([rot1, math.hypot(x1 - x0, y1 - y0), th1 - th0 - rot1])


def _split_world_angle(previous_pose, pose):
    x0, y0, _ = previous_pose
    x1, y1, th1 = pose
    rot1 = math.atan2(y1 - y0, x1 - x0)
    rot2 = th1 - rot1
    return np.array([rot1, math.hypot(x1 - x0, y1 - y0),
                     math.atan2(math.sin(rot2), math.cos(rot2))])


def _pose_pair(rng):
    start = rng.uniform(-2.0, 2.0, 2)
    step = rng.uniform(0.2, 1.5) * np.array([math.cos(a := rng.uniform(-math.pi, math.pi)),
                                             math.sin(a)])
    return ((float(start[0]), float(start[1]), float(rng.uniform(-math.pi, math.pi))),
            (float(start[0] + step[0]), float(start[1] + step[1]),
             float(rng.uniform(-math.pi, math.pi))))


Exercise(
    "odometry.motion_split",
    "Thrun's split (rot1 rad, trans m, rot2 rad) of the motion from previous_pose to pose, "
    "both turns wrapped to (-pi, pi].",
    motion_split,
    [Case(((0.0, 0.0, 0.0), (1.0, 1.0, math.pi / 2))),
     Case(((1.0, 2.0, 2.5), (0.2, 1.5, -2.9))),
     Case(((0.5, -0.5, -3.0), (0.6, -0.2, 2.9)))],
    wheel_names=("rot1", "trans", "rot2"),
    # poses are not floats: the grader's hidden cases are drawn here (two poses at least
    # 0.2 m apart, headings anywhere, so that both wraps are exercised)
    hidden=lambda rng: [Case(_pose_pair(rng)) for _ in range(3)],
    mistakes=[
        (_split_unwrapped, "wrap both turns to (-pi, pi]: the difference of two headings can "
                           "leave that range."),
        (_split_world_angle, "rot1 is measured from the robot's heading before the motion: "
                             "atan2(y' - y, x' - x) - theta, not the direction in the world."),
    ],
)


def gyro_correction(noise: ArrayLike, gyro_variance: float,
                    innovation: float) -> NDArray[np.float64]:
    """The EKF's correction (dx m, dy m, dtheta rad) of the predicted pose by one gyro turn:
    ``noise[:, 2] * innovation / (noise[2, 2] + gyro_variance)``, with ``noise`` the 3 x 3
    covariance of this update's wheel errors, ``innovation`` the gyro's turn minus the
    wheels' (rad) and ``gyro_variance`` its variance (rad^2)."""
    n = np.asarray(noise, dtype=float)
    return n[:, 2] * float(innovation) / (n[2, 2] + float(gyro_variance))


def _no_gyro_variance(noise, gyro_variance, innovation):
    n = np.asarray(noise, dtype=float)
    return n[:, 2] * float(innovation) / n[2, 2]


def _heading_only(noise, gyro_variance, innovation):
    n = np.asarray(noise, dtype=float)
    return np.array([0.0, 0.0, n[2, 2] * float(innovation) / (n[2, 2] + gyro_variance)])


_NOISE_A = [[2.5e-9, 1.1e-8, 2.9e-7], [1.1e-8, 5.2e-8, 1.3e-6], [2.9e-7, 1.3e-6, 3.0e-5]]
_NOISE_B = [[4.0e-9, -2.0e-8, -5.0e-7], [-2.0e-8, 1.2e-7, 2.4e-6], [-5.0e-7, 2.4e-6, 5.5e-5]]

Exercise(
    "odometry.gyro_correction",
    "The pose correction (dx m, dy m, dtheta rad) the wheel-and-gyro EKF adds for one update, "
    "from the update's wheel-noise covariance, the gyro's variance and the innovation.",
    gyro_correction,
    [Case((_NOISE_A, 7.4e-10, 0.01)), Case((_NOISE_B, 1e-5, -0.02)),
     Case((_NOISE_A, 3e-5, 0.003))],
    wheel_names=("dx", "dy", "dtheta"),
    mistakes=[
        (_no_gyro_variance, "the innovation's variance is the wheels' heading noise plus the "
                            "gyro's: S = N[2, 2] + gyro_variance."),
        (_heading_only, "the correction moves the position too, along N[:, 2]: the wheels' "
                        "heading error of this update also moved the robot sideways."),
    ],
    rtol=1e-6,
    atol=1e-15,
)
