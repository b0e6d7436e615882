"""Exercises of the rover chapter (notebooks/03_rover/): the Open Source Rover's wheel speeds,
corner angles, tightest turn and a design question. Lengths in inches; wheels LF, LM, LB, RF,
RM, RB; corners LF, RF, LB, RB. The speed and tightest-turn exercises take the document's
radius r_OSR (> 0 turns right); the corner-angle exercise works in the book's convention
(signed radius R > 0 turns left, steering angle delta > 0 turns the wheel left).

The design answer is checked against the library by a property: at the longest corner offset
the outer corner and the outer middle wheel are equally far from the turning centre exactly
at the tightest turn.

>>> from wheelkin.rover import RoverGeometry, min_turning_radius, outer_middle_is_fastest_above
>>> d = longest_corner_offset(7.254, 10.073, 45.0)
>>> round(d, 2)
12.7
>>> g = RoverGeometry(7.254, d, d, 10.073, unit="in")
>>> abs(outer_middle_is_fastest_above(g) - min_turning_radius(g)) < 1e-9
True

>>> from wheelkin.exercises import check
>>> result = check("rover.tightest_turn", lambda d1, d2, d3, max_corner_angle_deg: 0.0)
>>> result.passed, result.kind
(False, 'wrong')
>>> check("rover.tightest_turn", tightest_turn).passed
True
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from wheelkin.exercises import Case, Exercise
from wheelkin.rover import (
    OSR_GEOMETRY,
    RoverGeometry,
    corner_angles,
    min_turning_radius,
    wheel_speeds,
)

__all__ = ["corner_angles_general", "longest_corner_offset", "normalised_wheel_speeds",
           "outer_back_speed", "tightest_turn"]

_G = OSR_GEOMETRY


# ------------------------------------------------------------------ 1. outer back wheel

def outer_back_speed(radius: float, speed: float) -> float:
    """Speed of the OSR's outer back wheel (LB in a right turn, RB in a left turn) when the
    outer middle wheel gets ``speed``; ``radius`` in inches, > 0 turns right."""
    return float(wheel_speeds(radius, speed)[2 if radius > 0 else 5])


def _inner_back(radius, speed):
    return float(wheel_speeds(radius, speed)[5 if radius > 0 else 2])


def _centre_reference(radius, speed):
    a = abs(radius) + _G.d1
    return speed * math.hypot(_G.d2, a) / abs(radius)


def _right_turn_formula(radius, speed):
    return speed * math.hypot(_G.d2, _G.d1 + radius) / (radius + _G.d4)


def _lateral_only(radius, speed):
    return speed * (abs(radius) + _G.d1) / (abs(radius) + _G.d4)


Exercise(
    "rover.outer_back_speed",
    "The speed of the outer back wheel (LB in a right turn, RB in a left one) of the Open "
    "Source Rover, in the unit of speed, when the outer middle wheel gets speed; radius in "
    "inches, > 0 turns right.",
    outer_back_speed,
    [Case((30.0, 100.0)), Case((-30.0, 100.0)), Case((45.0, 60.0)), Case((-120.0, 25.0)),
     Case((200.0, -40.0))],
    mistakes=[
        (_inner_back, "that is the inner back wheel; the outer one is on the side away from "
                      "the turning centre (LB when r > 0, RB when r < 0)."),
        (_centre_reference, "you scaled by the body centre's radius |r|, but the command goes "
                            "to the outer middle wheel, at |r| + d4 from the turning centre."),
        (_right_turn_formula, "the document's equation 9 is written for right turns (r > 0); "
                              "for a left turn mirror it: use |r| (and the outer side changes)."),
        (_lateral_only, "you used only the lateral distance |r| + d1; the back wheel is also "
                        "d2 behind the middle axle: R3 = sqrt(d2^2 + (|r| + d1)^2)."),
    ],
)


# ------------------------------------------------------------------ 2. corner angles, d2 != d3

def corner_angles_general(R: float, d1: float, d2: float, d3: float) -> NDArray[np.float64]:
    """The four corner angles delta (rad), corners LF, RF, LB, RB, positive = turned to the
    LEFT (the book's sign), for a rover whose back corners are d2 behind and front corners d3
    ahead of the middle axle, d1 to each side; ``R`` the signed turning radius of the body
    centre in inches, > 0 turns left. The library's corner_angles uses the document's sign
    (delta_OSR = -delta) and radius (r_OSR = -R)."""
    return -corner_angles(-R, RoverGeometry(d1, d2, d3, d1, unit="in"), straight_threshold=math.inf)


def _document_sign(R, d1, d2, d3):
    return corner_angles(R, RoverGeometry(d1, d2, d3, d1, unit="in"), straight_threshold=math.inf)


def _swapped_d2_d3(radius, d1, d2, d3):
    return corner_angles_general(radius, d1, d3, d2)


def _back_same_sign(radius, d1, d2, d3):
    a = corner_angles_general(radius, d1, d2, d3)
    return np.concatenate([a[:2], -a[2:]])


def _inner_only(radius, d1, d2, d3):
    a = corner_angles_general(radius, d1, d2, d3)
    inner = (1, 3) if radius > 0 else (0, 2)
    return np.array([a[inner[0]], a[inner[0]], a[inner[1]], a[inner[1]]])


Exercise(
    "rover.corner_angles",
    "The four corner angles delta in radians (LF, RF, LB, RB; positive = turned to the left) "
    "for a rover with back corners d2 behind and front corners d3 ahead of the middle axle, "
    "d1 to each side; R in inches, > 0 turns left.",
    corner_angles_general,
    [Case((40.0, 6.0, 14.0, 9.0)), Case((-40.0, 6.0, 14.0, 9.0)), Case((25.0, 5.0, 8.0, 12.0)),
     Case((-60.0, 8.0, 12.0, 16.0)), Case((30.0, 7.254, 10.5, 10.5))],
    wheel_names=("LF", "RF", "LB", "RB"),
    mistakes=[
        (_document_sign, "these are the document's angles for a turn to the other side: with "
                         "R > 0 the turn is to the LEFT, and delta > 0 turns a wheel left; "
                         "use delta = atan(x / (R - y)) with y positive to the left."),
        (_swapped_d2_d3, "d2 and d3 are swapped: the front corners are d3 ahead of the middle "
                         "axle, the back corners d2 behind it."),
        (_back_same_sign, "the back corners must turn the other way from the front ones: they "
                          "are behind the turning centre's line, so their angle has the "
                          "opposite sign."),
        (_inner_only, "every corner got the inner wheel's angle (equation 16); the outer "
                      "corners are farther from the turning centre: use |R| + d1 there."),
    ],
)


# ------------------------------------------------------------------ 3. tightest turn

def tightest_turn(d1: float, d2: float, d3: float, max_corner_angle_deg: float) -> float:
    """The smallest turning radius (in) of the body centre that keeps every corner within
    ``max_corner_angle_deg`` degrees of straight."""
    return min_turning_radius(RoverGeometry(d1, d2, d3, d1, unit="in"),
                              math.radians(max_corner_angle_deg))


def _front_only(d1, d2, d3, max_corner_angle_deg):
    return d1 + d3 / math.tan(math.radians(max_corner_angle_deg))


def _times_tan(d1, d2, d3, max_corner_angle_deg):
    return d1 + max(d2, d3) * math.tan(math.radians(max_corner_angle_deg))


def _no_d1(d1, d2, d3, max_corner_angle_deg):
    return max(d2, d3) / math.tan(math.radians(max_corner_angle_deg))


def _tan_of_degrees(d1, d2, d3, max_corner_angle_deg):
    return d1 + max(d2, d3) / math.tan(max_corner_angle_deg)


Exercise(
    "rover.tightest_turn",
    "The tightest turning radius (in) of the body centre for a rover with corners d1 to the "
    "side, d2 behind and d3 ahead of the middle axle, when the corner motors stop at "
    "max_corner_angle_deg degrees.",
    tightest_turn,
    [Case((7.254, 10.5, 10.5, 35.0)), Case((7.254, 10.5, 10.5, 45.0)),
     Case((6.0, 9.0, 14.0, 35.0)), Case((6.0, 14.0, 9.0, 30.0))],
    mistakes=[
        (_front_only, "you used the front corners only (d3); here the back corners are farther "
                      "from the middle axle (d2 > d3), so they reach the stop first."),
        (_times_tan, "tan(angle) = d / x, so x = d / tan(angle), not d * tan(angle)."),
        (_no_d1, "that is the distance from the corner's line to the turning centre; the "
                 "radius is measured from the body centre, d1 farther: add d1."),
        (_tan_of_degrees, "math.tan takes radians: convert the angle with math.radians first."),
    ],
)


# ------------------------------------------------------------------ 4. the fastest wheel

def normalised_wheel_speeds(radius: float, speed: float, d1: float, d2: float, d3: float,
                            d4: float) -> NDArray[np.float64]:
    """The six wheel speeds (wheels LF, LM, LB, RF, RM, RB) scaled so that the fastest wheel
    gets exactly ``speed`` (no motor is asked for more than the command)."""
    v = wheel_speeds(radius, 1.0, RoverGeometry(d1, d2, d3, d4, unit="in"))
    return speed * v / np.max(np.abs(v))


def _document_rule(radius, speed, d1, d2, d3, d4):
    return wheel_speeds(radius, speed, RoverGeometry(d1, d2, d3, d4, unit="in"))


Exercise(
    "rover.normalised_wheel_speeds",
    "The six wheel speeds (LF, LM, LB, RF, RM, RB) of a rover with dimensions d1..d4, scaled "
    "so that the fastest wheel gets exactly speed; radius in inches, > 0 turns right.",
    normalised_wheel_speeds,
    [Case((30.0, 100.0, 7.254, 10.5, 10.5, 10.073)),
     Case((40.0, 100.0, 7.254, 25.0, 25.0, 10.073)),
     Case((-40.0, 100.0, 7.254, 25.0, 25.0, 10.073)),
     Case((60.0, 80.0, 7.254, 18.0, 25.0, 10.073)),
     Case((200.0, 50.0, 7.254, 25.0, 25.0, 10.073))],
    wheel_names=("LF", "LM", "LB", "RF", "RM", "RB"),
    mistakes=[
        (_document_rule, "that is the document's rule (the outer middle wheel gets the "
                         "command); for this long rover a corner wheel is farther from the "
                         "turning centre and would be asked for more than speed."),
    ],
)


# ------------------------------------------------------------------ 5. design: a longer rover

def longest_corner_offset(d1: float, d4: float, max_corner_angle_deg: float) -> float:
    """The largest corner offset d = d2 = d3 (in) for which the document's rule (the outer
    middle wheel gets the command) never asks a corner motor for more than the command in any
    turn the hard stops allow: r*(d) <= r_min(d), with r*(d) = (d^2 + d1^2 - d4^2) /
    (2 (d4 - d1)) and r_min(d) = d1 + d / tan(stop). Requires d4 > d1."""
    if not d4 > d1 > 0:
        raise ValueError(f"need d4 > d1 > 0 (in), got d1={d1!r}, d4={d4!r}")
    t = math.tan(math.radians(max_corner_angle_deg))
    k = d4 - d1
    # d^2 - (2 k / t) d - (2 k d1 + d4^2 - d1^2) = 0: the positive root
    b = 2 * k / t
    c = 2 * k * d1 + d4**2 - d1**2
    return (b + math.sqrt(b * b + 4 * c)) / 2


def _tan_of_degrees_design(d1, d4, max_corner_angle_deg):
    k, t = d4 - d1, math.tan(max_corner_angle_deg)
    c = 2 * k * d1 + d4**2 - d1**2
    return (2 * k / t + math.sqrt((2 * k / t) ** 2 + 4 * c)) / 2


def _r_min_without_d1(d1, d4, max_corner_angle_deg):
    k, t = d4 - d1, math.tan(math.radians(max_corner_angle_deg))
    c = d4**2 - d1**2
    return (2 * k / t + math.sqrt((2 * k / t) ** 2 + 4 * c)) / 2


def _r_min_times_tan(d1, d4, max_corner_angle_deg):
    k, t = d4 - d1, math.tan(math.radians(max_corner_angle_deg))
    c = 2 * k * d1 + d4**2 - d1**2
    return (2 * k * t + math.sqrt((2 * k * t) ** 2 + 4 * c)) / 2


Exercise(
    "rover.longest_corner_offset",
    "Design: the largest corner offset d = d2 = d3 (in) of a rover with sideways dimensions "
    "d1 and d4 (in) for which the outer middle wheel is the fastest wheel in every turn that "
    "corner hard stops at max_corner_angle_deg allow.",
    longest_corner_offset,
    [Case((7.254, 10.073, 45.0)), Case((7.254, 10.073, 35.0)), Case((6.0, 12.0, 45.0)),
     Case((5.0, 9.0, 60.0))],
    mistakes=[
        (_tan_of_degrees_design, "math.tan takes radians: convert the hard stop with "
                                 "math.radians first."),
        (_r_min_without_d1, "the tightest turn is measured from the body centre: "
                            "r_min = d1 + d / tan(stop), not d / tan(stop)."),
        (_r_min_times_tan, "tan(stop) = d / (r_min - d1), so r_min = d1 + d / tan(stop), not "
                           "d1 + d * tan(stop)."),
    ],
)
