"""Exercises of the waypoint-lab chapter (notebooks/07_waypoints): the lab's four-wheeled
skid steer in our convention (SI, x forward, y left, counter-clockwise positive; wheels FL, FR,
RL, RR; a positive radius turns left).

>>> from wheelkin.exercises import check
>>> check("waypoints.quarter_circle_duration", quarter_circle_duration).passed
True
>>> r = check("waypoints.curve_wheel_rates", lambda radius, half_axle, wheel_radius,
...           wheel_rate: curve_wheel_rates(radius, half_axle, wheel_radius, wheel_rate)[::-1])
>>> r.kind
'specific'
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from wheelkin.diffdrive import body_twist
from wheelkin.exercises import Case, Exercise
from wheelkin.waypoints import plan_segments, schedule

__all__ = ["curve_wheel_rates", "effective_track_width", "heading_after",
           "quarter_circle_duration", "skid_curve_rates"]


def _arc_command(radius, half_axle, wheel_radius, wheel_rate):
    """The library's schedule for one quarter circle of signed ``radius`` (left if > 0)."""
    side = math.copysign(abs(radius), radius)
    segs = plan_segments([[0.0, 0.0], [abs(radius), side]], arc_radius=abs(radius),
                         initial_heading=0.0)
    return schedule(segs, wheel_radius, half_axle, wheel_rate)[0]


# ------------------------------------------------------------------ 1. duration of a curve

def quarter_circle_duration(radius: float, half_axle: float, wheel_radius: float,
                            wheel_rate: float) -> float:
    """Seconds for a quarter circle of radius ``radius`` (m, the centre's path) when the outer
    wheel turns at ``wheel_rate`` (rad/s); ``half_axle`` and ``wheel_radius`` in m."""
    return _arc_command(radius, half_axle, wheel_radius, wheel_rate).duration


Exercise(
    "waypoints.quarter_circle_duration",
    "The duration (s) of a quarter circle of radius R (m, described by the robot's centre) "
    "when the outer wheel turns at wheel_rate (rad/s); half_axle d and wheel_radius r_w in m.",
    quarter_circle_duration,
    [Case((0.5, 0.06, 0.04, 7.5)), Case((0.3, 0.1, 0.05, 5.0)), Case((1.2, 0.06, 0.04, 10.0))],
    mistakes=[
        (lambda R, d, r, w: (math.pi / 2) * R / (r * w),
         "that is the time for the centre's path at the outer wheel's speed; the centre is "
         "slower: the outer wheel, on the circle of radius R + d, sets the yaw rate "
         "V/(R + d)."),
        (lambda R, d, r, w: (math.pi / 2) * (R - d) / (r * w),
         "you used the inner wheel's circle, R - d; the wheel at wheel_rate is the outer one, "
         "on R + d."),
        (lambda R, d, r, w: 2 * math.pi * (R + d) / (r * w),
         "that is a whole circle: a quarter circle is a quarter of it."),
        (lambda R, d, r, w: (math.pi / 2) * (R + d) / w,
         "wheel_rate is an angular rate (rad/s): the rim speed is wheel_radius * wheel_rate."),
        (lambda R, d, r, w: (math.pi / 2) * (R + 2 * d) / (r * w),
         "half_axle is already half the axle: the outer wheel is at R + d, not R + 2d."),
    ],
)


# ------------------------------------------------------------------ 2. wheel rates on a curve

def curve_wheel_rates(radius: float, half_axle: float, wheel_radius: float,
                      wheel_rate: float) -> tuple[float, float]:
    """Left and right wheel rates (rad/s) for a curve of signed ``radius`` (m, > 0 turns left),
    the outer wheel at ``wheel_rate`` (rad/s); returned as (left, right)."""
    c = _arc_command(radius, half_axle, wheel_radius, wheel_rate)
    return c.left_rate, c.right_rate


def _lab_inner_right(R, d, r, w):
    inner = w * (abs(R) - d) / (abs(R) + d)
    return w, inner


def _yaw_rate_as_wheel(R, d, r, w):
    yaw = r * w / (abs(R) + d)
    return (yaw, w) if R > 0 else (w, yaw)


Exercise(
    "waypoints.curve_wheel_rates",
    "The (left, right) wheel angular rates (rad/s) for a curve of signed radius R (m, > 0 "
    "turns left, counter-clockwise), the outer wheel at wheel_rate; half_axle d, "
    "wheel_radius r_w in m.",
    curve_wheel_rates,
    [Case((0.5, 0.06, 0.04, 7.5)), Case((-0.5, 0.06, 0.04, 7.5)), Case((0.25, 0.06, 0.04, 6.0)),
     Case((-0.2, 0.08, 0.05, 4.0)), Case((0.05, 0.06, 0.04, 7.5))],
    wheel_names=("left", "right"),
    mistakes=[
        (_lab_inner_right,
         "you slowed the right wheel on every curve, as the lab does; on a left turn "
         "(R > 0, counter-clockwise) the left wheel is the inner one."),
        (_yaw_rate_as_wheel,
         "V/(R + d) is the robot's yaw rate about the centre of the circle (rad/s of the "
         "body), not a wheel's rate; the inner wheel's rim speed is that yaw rate times "
         "(R - d)."),
        (lambda R, d, r, w: tuple(np.array(curve_wheel_rates(R, d, r, w)) * r),
         "those are rim speeds (m/s); divide by the wheel radius for rad/s."),
    ],
)


# ------------------------------------------------------------------ 3. heading from encoders

def heading_after(wheel_angles: ArrayLike, wheel_radius: float, half_axle: float) -> float:
    """Heading change (rad, counter-clockwise +) after the wheels turned by ``wheel_angles``
    (rad, cumulative from zero, order FL, FR, RL, RR) on an ideal skid steer (no slip)."""
    fl, fr, rl, rr = (float(a) for a in wheel_angles)
    r = wheel_radius
    return float(body_twist(r * (fl + rl) / 2, r * (fr + rr) / 2, 2 * half_axle)[1])


def _heading_sign(phi, r, d):
    return -heading_after(phi, r, d)


def _heading_twice(phi, r, d):
    fl, fr, rl, rr = phi
    return r * ((fr + rr) - (fl + rl)) / (2 * d)


def _heading_no_radius(phi, r, d):
    fl, fr, rl, rr = phi
    return ((fr + rr) - (fl + rl)) / 2 / (2 * d)


Exercise(
    "waypoints.heading_after",
    "The heading change (rad) of an ideal skid steer whose wheels turned by wheel_angles "
    "(rad, FL, FR, RL, RR, from zero); wheel_radius and half_axle in m.",
    heading_after,
    [Case(([-2.0, 2.0, -2.0, 2.0], 0.04, 0.06)), Case(([10.0, 12.0, 10.0, 12.0], 0.04, 0.06)),
     Case(([30.0, 25.0, 29.0, 26.0], 0.05, 0.1)), Case(([5.0, 5.0, 5.0, 5.0], 0.04, 0.06))],
    mistakes=[
        (_heading_sign, "the sign is wrong: the right wheels ahead of the left turns the robot "
                        "left, counter-clockwise, which is positive."),
        (_heading_twice, "twice too large: either you added the two wheels of a side (average "
                         "them instead), or you divided the difference of the sides by d "
                         "(divide by the whole track, 2d)."),
        (_heading_no_radius, "the encoders give wheel angles (rad); multiply by the wheel "
                             "radius to get the distances the rims rolled."),
    ],
)


# ------------------------------------------------------------------ 4. effective track width

def effective_track_width(left_angle: float, right_angle: float, rotation: float,
                          wheel_radius: float) -> float:
    """Effective track width (m) from a spin test: the sides turned by ``left_angle`` and
    ``right_angle`` (rad, side averages) while the robot turned by ``rotation`` (rad,
    measured)."""
    return wheel_radius * (right_angle - left_angle) / rotation


Exercise(
    "waypoints.effective_track_width",
    "The effective track width (m) of a skid steer from a spin test: the left and right sides' "
    "wheels turned by left_angle and right_angle (rad) while the robot turned by rotation "
    "(rad, measured from outside); wheel_radius in m.",
    effective_track_width,
    [Case((-30.0, 30.0, 2 * math.pi, 0.04)), Case((-50.0, 50.0, 3.0 * math.pi, 0.04)),
     Case((40.0, -40.0, -4.0, 0.05))],
    mistakes=[
        (lambda left, right, rot, r: r * (right - left) / rot / 2,
         "that is half the effective track (an effective d): the track is r_w times the "
         "difference of the sides over the rotation."),
        (lambda left, right, rot, r: (right - left) / rot,
         "the wheel angles are in radians: multiply by the wheel radius for the distance "
         "the rims rolled."),
    ],
)


# ------------------------------------------------------------------ 5. a design: skid-steer curve

def skid_curve_rates(radius: float, half_axle: float, half_wheelbase: float, wheel_radius: float,
                     wheel_rate: float) -> tuple[float, float]:
    """(left, right) wheel rates (rad/s) that make a four-wheeled skid steer (wheels at
    x = ±``half_wheelbase``, y = ±``half_axle``, m) follow a curve of signed ``radius`` (m, > 0
    turns left) with the outer wheels at ``wheel_rate``: the two-wheel rates computed with the
    effective half track χ d, χ = 1 + (a/d)² (the Coulomb spin derivation of the lab chapter)."""
    chi = 1.0 + (half_wheelbase / half_axle) ** 2
    return curve_wheel_rates(radius, chi * half_axle, wheel_radius, wheel_rate)


Exercise(
    "waypoints.skid_curve_rates",
    "Design the (left, right) wheel rates (rad/s) that make a four-wheeled skid steer with "
    "half track half_axle and half wheelbase half_wheelbase (m) follow a curve of signed radius "
    "R (m, > 0 turns left), the outer wheels at wheel_rate; wheel_radius in m.",
    skid_curve_rates,
    [Case((0.5, 0.06, 0.05, 0.04, 7.5)), Case((-0.5, 0.06, 0.05, 0.04, 7.5)),
     Case((1.0, 0.1, 0.04, 0.05, 6.0)), Case((-0.8, 0.08, 0.08, 0.04, 5.0))],
    wheel_names=("left", "right"),
    mistakes=[
        (lambda R, d, a, r, w: curve_wheel_rates(R, d, r, w),
         "those are the rates of a two-wheeled robot: a skid steer turns only 1/χ as fast, "
         "so compute them with the effective half track χ d, χ = 1 + (a/d)²."),
        (lambda R, d, a, r, w: curve_wheel_rates(R, d / (1 + (a / d) ** 2), r, w),
         "χ goes the other way: the skid steer turns less than it is told, so it needs a "
         "wider effective track, χ d, not d/χ."),
        (lambda R, d, a, r, w: curve_wheel_rates(R, (1 + a / d) * d, r, w),
         "χ = 1 + (a/d)², with the ratio squared."),
        (lambda R, d, a, r, w: skid_curve_rates(R, d, a, r, w)[::-1],
         "the wheels are swapped: on a left turn (R > 0) the left wheels are the inner, "
         "slower ones."),
    ],
)
