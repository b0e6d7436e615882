"""Exercises of the car-like chapter (notebooks/09_carlike/): Ackermann angles, the tightest
turn, pure-pursuit steering, the rover against a car, and the design of a steering linkage.
SI units and the book's signs: R > 0 and delta > 0 turn left; the wheelbase L is front axle to
rear axle, the track W left contact line to right.

>>> from wheelkin.exercises import check
>>> check("carlike.front_wheel_angles", lambda R, L, W: (0.0, 0.0)).passed
False
>>> check("carlike.front_wheel_angles", front_wheel_angles).passed
True
>>> check("carlike.best_arm_angle", best_arm_angle).passed
True
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from wheelkin import carlike
from wheelkin.exercises import Case, Exercise

__all__ = ["best_arm_angle", "front_wheel_angles", "pursuit_steering", "rover_radius_ratio",
           "tightest_radius"]


# ------------------------------------------------------------------ 1. Ackermann angles

def front_wheel_angles(R: float, L: float, W: float) -> NDArray[np.float64]:
    """(left, right) front wheel angles (rad) of an ideal Ackermann car turning with radius R
    (m, > 0 left) of its rear-axle midpoint."""
    return np.array(carlike.ackermann_angles(R, wheelbase=L, track_width=W))


def _swapped_sides(R, L, W):
    return front_wheel_angles(R, L, W)[::-1]


def _full_track(R, L, W):
    return np.array([math.atan(L / (R - W)), math.atan(L / (R + W))])


def _bicycle_both(R, L, W):
    d = math.atan(L / R)
    return np.array([d, d])


Exercise(
    "carlike.front_wheel_angles",
    "The left and right front wheel angles (rad, > 0 turns left) of an ideal Ackermann car "
    "whose rear-axle midpoint turns with radius R (m, > 0 left); wheelbase L, track W (m).",
    front_wheel_angles,
    [Case((2.0, 0.33, 0.27)), Case((-1.5, 0.33, 0.27)), Case((5.0, 2.5, 1.5)),
     Case((-8.0, 2.8, 1.6))],
    wheel_names=("left", "right"),
    mistakes=[
        (_swapped_sides, "left and right are swapped: in a left turn (R > 0) the left wheel is "
                         "the inner one, nearer the centre, and turns more: "
                         "tan(delta_L) = L / (R - W/2)."),
        (_full_track, "each front wheel is W/2 from the centre line, not W: "
                      "tan(delta) = L / (R -+ W/2)."),
        (_bicycle_both, "that is the bicycle angle for both wheels (parallel steering); each "
                        "wheel must point across the line to the turning centre from its own "
                        "position."),
    ],
)


# ------------------------------------------------------------------ 2. tightest turn

def tightest_radius(max_inner_deg: float, L: float, W: float) -> float:
    """Smallest turning radius (m) of the rear-axle midpoint of an Ackermann car whose inner
    front wheel can turn at most max_inner_deg degrees."""
    return float(carlike.minimum_radius(math.radians(max_inner_deg), wheelbase=L, track_width=W))


def _no_track(max_inner_deg, L, W):
    return L / math.tan(math.radians(max_inner_deg))


def _outer_limited(max_inner_deg, L, W):
    return L / math.tan(math.radians(max_inner_deg)) - W / 2


Exercise(
    "carlike.tightest_radius",
    "The smallest turning radius (m) of the rear-axle midpoint of an Ackermann car whose inner "
    "front wheel turns at most max_inner_deg degrees; wheelbase L, track W (m).",
    tightest_radius,
    [Case((24.0, 0.33, 0.27)), Case((35.0, 2.5, 1.5)), Case((45.0, 2.5, 1.5)),
     Case((30.0, 2.8, 1.6))],
    mistakes=[
        (_no_track, "that is the inner wheel's own distance to the centre line's turning "
                    "point: the rear-axle midpoint is W/2 further out: R = L/tan + W/2."),
        (_outer_limited, "the inner wheel is nearer the centre: the midpoint is W/2 further "
                         "from the centre than the inner wheel, so add W/2."),
    ],
)


# ------------------------------------------------------------------ 3. pure pursuit

def pursuit_steering(x: float, y: float, L: float) -> float:
    """The bicycle steering angle (rad) that pure pursuit commands for the look-ahead point
    (x, y) (m, rear-axle frame, y left); wheelbase L (m)."""
    return float(carlike.steering_from_curvature(carlike.pure_pursuit_curvature(x, y),
                                                 wheelbase=L))


def _y_over_l2(x, y, L):
    return math.atan(L * y / (x * x + y * y))


def _curvature_only(x, y, L):
    return 2 * y / (x * x + y * y)


def _aim_at_point(x, y, L):
    return math.atan2(y, x)


Exercise(
    "carlike.pursuit_steering",
    "The steering angle (rad) pure pursuit commands for the look-ahead point (x, y) in the "
    "rear-axle frame (m); wheelbase L (m).",
    pursuit_steering,
    [Case((1.0, 0.2, 0.33)), Case((0.8, -0.3, 0.33)), Case((2.0, 0.5, 2.5)),
     Case((0.5, 0.5, 0.33))],
    mistakes=[
        (_y_over_l2, "the curvature is 2 y / L_d^2: the factor 2 comes from the isosceles "
                     "triangle of the centre, the car and the point."),
        (_curvature_only, "that is the curvature kappa; the steering angle is "
                          "atan(L * kappa)."),
        (_aim_at_point, "that steers the wheels straight at the point; pure pursuit steers "
                        "onto the circle through the car and the point, tangent to its "
                        "heading."),
    ],
)


# ------------------------------------------------------------------ 4. rover against car

def rover_radius_ratio(max_deg: float, length: float, half_track: float) -> float:
    """Ratio of the tightest turn of a four-corner-steered vehicle (turning centre on the
    middle axle line, corners length/2 ahead and behind) to that of a car of the same
    wheelbase (length) and track (2 * half_track), both radii of the body's centre line on
    the middle (rover) or rear (car) axle, the inner steered wheel limited to max_deg."""
    t = math.tan(math.radians(max_deg))
    rover_r = half_track + (length / 2) / t
    car_r = half_track + length / t
    return rover_r / car_r


def _inverse_ratio(max_deg, length, half_track):
    return 1 / rover_radius_ratio(max_deg, length, half_track)


def _half_exactly(max_deg, length, half_track):
    return 0.5


Exercise(
    "carlike.rover_radius_ratio",
    "The ratio (rover / car) of the tightest turning radii of a four-corner-steered vehicle "
    "and a front-steered car of the same wheelbase and track, steering limit max_deg on the "
    "inner wheel.",
    rover_radius_ratio,
    [Case((45.0, 0.5334, 0.1843)), Case((30.0, 0.5334, 0.1843)), Case((35.0, 2.5, 0.75))],
    mistakes=[
        (_inverse_ratio, "that is car / rover; the rover turns tighter, so the ratio is "
                         "below 1."),
        (_half_exactly, "half the wheelbase halves only the L / tan term; both radii also "
                        "carry the half track."),
    ],
)


# ------------------------------------------------------------------ 5. design: linkage

def best_arm_angle(L: float, W: float, arm_length: float, max_inner_deg: float) -> float:
    """Design: the arm angle (rad) of a trapezoidal linkage that makes the worst Ackermann
    error over inner angles 0..max_inner_deg as small as possible."""
    return carlike.optimal_arm_angle(wheelbase=L, track_width=W, arm_length=arm_length,
                                     max_inner_angle=math.radians(max_inner_deg)).arm_angle


def _rule_of_thumb(L, W, arm_length, max_inner_deg):
    return math.atan(W / (2 * L))


def _second_order(L, W, arm_length, max_inner_deg):
    beta = 0.3
    for _ in range(60):
        beta = math.atan((W - 2 * arm_length * math.sin(beta)) / L)
    return beta


Exercise(
    "carlike.best_arm_angle",
    "Design: the arm angle (rad) of a trapezoidal steering linkage (kingpins W apart, arms "
    "arm_length long, wheelbase L) whose worst Ackermann error for inner wheel angles from 0 "
    "to max_inner_deg degrees is as small as possible; it may use carlike.linkage_error, no "
    "other part of the library.",
    best_arm_angle,
    [Case((0.33, 0.27, 0.04, 24.0)), Case((2.5, 1.5, 0.15, 35.0)),
     Case((2.5, 1.5, 0.2, 40.0))],
    mistakes=[
        (_rule_of_thumb, "that is the rule of thumb (arms aimed at the rear axle's centre): it "
                         "is not the best arm angle for any steering range."),
        (_second_order, "that arm angle is exact for small steering angles only; over the "
                        "whole range a compromise does better: minimise the largest error."),
    ],
    atol=2e-3,
    rtol=0.0,
    library=("wheelkin.carlike.linkage_error",),
)
