"""Exercises of the chapter "Odometry: where am I?" (checked against wheelkin.odometry).

- ``odometry.center_and_turn``: Δs and Δθ of one update from the encoder increments.
- ``odometry.midpoint_step``: one midpoint update of the pose (our frame).
- ``odometry.exact_step``: one exact (arc) update, which must also work for Δθ = 0.
- ``odometry.alpha_mrad``: the README's "improvement", whole mrad with C truncation.
"""

from __future__ import annotations

import math

from wheelkin import odometry as odo
from wheelkin.exercises import Case, Exercise

__all__ = ["alpha_mrad", "center_and_turn", "exact_step", "midpoint_step"]

_K = 8.043  # Radon Ulzer: steps per mm
_W = 85.0  # Radon Ulzer: wheel base, mm


def center_and_turn(n_left, n_right, steps_per_mm, wheel_base_mm):
    """(Δs in mm, Δθ in rad) for one update with ``n_left``, ``n_right`` encoder steps."""
    ds, dth = odo.body_increments([[n_left, n_right]], steps_per_mm, wheel_base_mm)
    return (float(ds[0]), float(dth[0]))


def midpoint_step(x, y, theta, distance, dtheta):
    """(x', y', θ') after one midpoint update (our frame, x forward, θ counter-clockwise)."""
    return tuple(odo.pose_update([x, y, theta], distance, dtheta, "midpoint").tolist())


def exact_step(x, y, theta, distance, dtheta):
    """(x', y', θ') after one exact arc update; Δθ may be zero."""
    return tuple(odo.pose_update([x, y, theta], distance, dtheta, "exact").tolist())


def alpha_mrad(n_left, n_right, steps_per_mm, wheel_base_mm):
    """The README's alpha in whole mrad, truncated toward zero as a C cast does."""
    return math.trunc(1000.0 * (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _readme_center(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left - n_right) / 2 / steps_per_mm,
            (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _sum_not_halved(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left + n_right) / steps_per_mm,
            (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _half_base(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            2 * (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _turn_sign(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            (n_left - n_right) / (steps_per_mm * wheel_base_mm))


def _turn_mrad(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left + n_right) / 2 / steps_per_mm,
            1000 * (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _no_mm(n_left, n_right, steps_per_mm, wheel_base_mm):
    return ((n_left + n_right) / 2, (n_right - n_left) / wheel_base_mm)


Exercise(
    "odometry.center_and_turn",
    "Given the encoder step increments n_left and n_right of one update, steps_per_mm and the "
    "wheel base in mm, return (Δs in mm, Δθ in rad): the travel of the mid-point between the "
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
        (_half_base, "Δθ is twice too large: divide by the whole wheel base W (wheel to wheel), "
                     "not W/2."),
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


def _alpha_rounded(n_left, n_right, steps_per_mm, wheel_base_mm):
    return round(1000.0 * (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _alpha_floor(n_left, n_right, steps_per_mm, wheel_base_mm):
    return math.floor(1000.0 * (n_right - n_left) / (steps_per_mm * wheel_base_mm))


def _alpha_float(n_left, n_right, steps_per_mm, wheel_base_mm):
    return 1000.0 * (n_right - n_left) / (steps_per_mm * wheel_base_mm)


Exercise(
    "odometry.alpha_mrad",
    "The README's improvement: return alpha = 1000 (R − L)/(steps_per_mm · wheelBase) as a whole "
    "number of mrad, converted to an integer the way C does (int32_t alpha = ...).",
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
