"""Exercises of chapter 1, "Frames, units and conventions" (notebooks/01_conventions/).

Each exercise converts one source's numbers into ours (SI, REP-103: x forward, y left,
heading and yaw rate counter-clockwise, a positive turning radius turns left), or computes a
quantity of our frame. The reference answers are the library's own converters.

>>> from wheelkin.exercises import check
>>> check("conventions.rover_radius", lambda radius_in: radius_in * 0.0254).kind
'specific'
>>> check("conventions.rover_radius", rover_radius).passed
True
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import frames, nonholonomic, sources, unified, units
from wheelkin.exercises import Case, Exercise

__all__ = ["encoder_steps_to_metres", "firmware_pose", "heading_error", "icr_of",
           "mecanum_twist", "rover_radius", "side_slip_row"]


# ------------------------------------------------------------------ 1. rover turning radius

def rover_radius(radius_in: float) -> float:
    """The rover document's turning radius (inches, > 0 turns right) as ours (m, > 0 left)."""
    return sources.rover_radius_to_ours(radius_in)


Exercise(
    "conventions.rover_radius",
    "Convert the rover document's turning radius radius_in (inches, r > 0 turns right) to our "
    "signed turning radius in metres (R > 0 turns left); an infinite radius stays infinite. "
    "It may use units.INCH, no other part of the library.",
    rover_radius,
    [Case((30.0,)), Case((-30.0,)), Case((250.0,)), Case((-17.754,)), Case((math.inf,))],
    library=("wheelkin.units.INCH",),
    mistakes=[
        (lambda radius_in: radius_in * 0.0254,
         "the size is right but not the side: the rover's r > 0 turns right, our R > 0 turns "
         "left, so the sign must flip."),
        (lambda radius_in: -radius_in / 39.37,
         "close, but an inch is exactly 0.0254 m; 1/39.37 is 2 parts per million off."),
        (lambda radius_in: -radius_in * 2.54,
         "that is centimetres: an inch is 0.0254 m."),
    ],
)


# ------------------------------------------------------------------ 2. firmware pose

def firmware_pose(X_mm: float, Y_mm: float, theta: float) -> NDArray[np.float64]:
    """The firmware's pose (mm, mm, rad; X right, Y forward, theta CCW from +Y) as our
    ``[x, y, theta]`` in metres and radians."""
    return sources.firmware_pose_to_ours(X_mm, Y_mm, theta).as_array()


Exercise(
    "conventions.firmware_pose",
    "Convert the Radon Ulzer firmware's pose (X_mm to the right, Y_mm along the start "
    "heading, theta in rad counter-clockwise from +Y) to our pose [x, y, theta] in metres and "
    "radians.",
    firmware_pose,
    [Case((0.0, 1000.0, 0.0)), Case((-100.0, 2000.0, 0.5)), Case((250.0, -40.0, -2.0)),
     Case((1234.0, 567.0, 3.0))],
    wheel_names=("x", "y", "theta"),
    mistakes=[
        (lambda X_mm, Y_mm, theta: [X_mm / 1000, Y_mm / 1000, theta],
         "the axes are not the same: the firmware's Y points forward (our x) and its X to the "
         "right (our -y)."),
        (lambda X_mm, Y_mm, theta: [Y_mm / 1000, X_mm / 1000, theta],
         "our y points left, the firmware's X points right: y = -X / 1000."),
        (lambda X_mm, Y_mm, theta: [Y_mm, -X_mm, theta],
         "the positions are still in millimetres: divide by 1000."),
        (lambda X_mm, Y_mm, theta: [Y_mm / 1000, -X_mm / 1000,
                                    theta + math.pi / 2],
         "the heading needs no offset: the firmware measures it from its +Y, which is our +x, "
         "and both count counter-clockwise."),
        (lambda X_mm, Y_mm, theta: [Y_mm / 1000, -X_mm / 1000, -theta],
         "both headings count counter-clockwise (a larger right-wheel distance increases "
         "either): theta passes through unchanged."),
    ],
)


# ------------------------------------------------------------------ 3. the ICR of a twist

def icr_of(vx: float, vy: float, omega: float) -> np.ndarray:
    """The ICR ``[x, y]`` (m, body frame) of the twist (vx, vy, omega), omega != 0."""
    return np.array(frames.icr(frames.Twist(vx, vy, omega)))


Exercise(
    "conventions.icr",
    "Return the instantaneous centre of rotation [x, y] (m, in the body frame) of the twist "
    "(vx, vy, omega) in m/s and rad/s, for omega != 0.",
    icr_of,
    [Case((1.0, 0.0, 0.5)), Case((1.0, 0.0, -0.5)), Case((0.3, 0.2, 1.5)),
     Case((-0.5, 0.4, -0.8)), Case((0.0, 0.0, 2.0))],
    wheel_names=("x", "y"),
    mistakes=[
        (lambda vx, vy, omega: [vx / omega, vy / omega],
         "that point lies along the velocity; the centre lies perpendicular to it: "
         "x = -vy / omega, y = vx / omega."),
        (lambda vx, vy, omega: [-vy * omega, vx * omega],
         "divide by omega, don't multiply: a slower turn has its centre further away."),
        (lambda vx, vy, omega: [vy / omega, -vx / omega],
         "that is the centre of the opposite rotation: for omega > 0 (counter-clockwise) and "
         "vx > 0 the centre is on the left, y > 0."),
    ],
)


# ------------------------------------------------------------------ 4. encoder steps

def encoder_steps_to_metres(steps: float) -> float:
    """Distance (m) of ``steps`` encoder steps of the Radon Ulzer (12 counts per motor
    revolution, 75.81:1 gear, 0.113097 m wheel circumference), without rounding."""
    per_m = units.steps_per_m_from(units.RADON_ULZER_COUNTS_PER_MOTOR_REV,
                                   units.RADON_ULZER_GEAR_RATIO,
                                   units.RADON_ULZER_WHEEL_CIRCUMFERENCE)
    return units.steps_to_distance(steps, steps_per_m=per_m)


Exercise(
    "conventions.encoder_steps",
    "Convert steps of a Radon Ulzer wheel encoder (12 counts per motor revolution, gear "
    "75.81:1, wheel circumference 0.113097 m) to metres, using the exact steps per metre.",
    encoder_steps_to_metres,
    [Case((8043.7,)), Case((100000.0,)), Case((-2500.0,)), Case((1.0,))],
    mistakes=[
        (lambda steps: steps / 8043.0,
         "close: that is the firmware's rounded 8043 steps/m; use the exact "
         "12 x 75.81 / 0.113097 m = 8043.7."),
        (lambda steps: steps / 12.0 * 0.113097,
         "you left out the gearbox: the encoder sits on the motor, which turns 75.81 times per "
         "wheel revolution."),
        (lambda steps: steps / (12.0 * 75.81) * 0.113097 * 1000,
         "that is millimetres: the answer is in metres."),
        (lambda steps: steps / (12.0 * 75.81) * 2 * math.pi * 0.113097,
         "0.113097 m is already the circumference (2 pi r), not the radius."),
    ],
)


# ------------------------------------------------------------------ 5. mecanum twist

def mecanum_twist(Vx_ftps: float, Vy_ftps: float, omega: float) -> NDArray[np.float64]:
    """The mecanum simulator's body twist (ft/s right, ft/s forward, rad/s) as our
    ``[vx, vy, omega]`` (m/s, m/s, rad/s)."""
    return sources.mecanum_doc_twist_to_ours(Vx_ftps, Vy_ftps, omega).as_array()


Exercise(
    "conventions.mecanum_twist",
    "Convert the mecanum simulator's body twist (Vx_ftps to the right, Vy_ftps forward, in "
    "ft/s; omega in rad/s) to our twist [vx, vy, omega] in m/s and rad/s. It may use "
    "units.FOOT, no other part of the library.",
    mecanum_twist,
    [Case((0.0, 10.0, 0.0)), Case((2.0, 0.0, 0.0)), Case((1.0, 3.0, 0.5)),
     Case((-2.0, 1.5, -1.2))],
    library=("wheelkin.units.FOOT",),
    wheel_names=("vx", "vy", "omega"),
    mistakes=[
        (lambda Vx_ftps, Vy_ftps, omega: [Vx_ftps * 0.3048, Vy_ftps * 0.3048,
                                          omega],
         "the simulator's X is to the right and Y forward; ours is x forward, y left."),
        (lambda Vx_ftps, Vy_ftps, omega: [Vy_ftps * 0.3048, Vx_ftps * 0.3048,
                                          omega],
         "its X points right, our y points left: vy = -Vx."),
        (lambda Vx_ftps, Vy_ftps, omega: [Vy_ftps * 0.3048, -Vx_ftps * 0.3048,
                                          -omega],
         "the simulator's headings are clockwise, but its omega is counter-clockwise (check "
         "its inverse matrix against the wheel layout): omega passes through unchanged."),
        (lambda Vx_ftps, Vy_ftps, omega: [Vy_ftps, -Vx_ftps, omega],
         "the speeds are still in feet per second: multiply by 0.3048."),
    ],
)


# ------------------------------------------------------------------ 6. a heading error (judgement)

def heading_error(theta_odometry: ArrayLike, theta_true: ArrayLike) -> float:
    """The signed error (rad) of the final heading, keeping whole turns: both series (wrapped
    to (-pi, pi], sampled so that no step exceeds a quarter turn) are unwrapped, then the
    last samples subtracted, odometry minus truth.

    >>> t = np.linspace(0.0, 4 * np.pi, 200)   # two left turns
    >>> o = 1.5 * t                             # odometry says three
    >>> round(heading_error(frames.wrap_angle(o), frames.wrap_angle(t)) / (2 * np.pi), 6)
    1.0
    """
    o = np.unwrap(np.asarray(theta_odometry, dtype=float))
    t = np.unwrap(np.asarray(theta_true, dtype=float))
    return float(o[-1] - t[-1])


def _heading_series(turns_true, scale, offset, n=25):
    """(odometry, truth), both wrapped: the truth turns ``turns_true`` turns at a steady rate
    with a wiggle; the odometry over-counts by ``scale`` and drifts by ``offset`` rad."""
    s = np.linspace(0.0, 1.0, n)
    truth = 2 * np.pi * turns_true * s + 0.3 * np.sin(5 * np.pi * s)
    odometry = scale * truth + offset * s
    return (np.round(frames.wrap_angle(odometry), 2), np.round(frames.wrap_angle(truth), 2))


def _wrapped_error(theta_odometry, theta_true):
    return float(frames.wrap_angle(heading_error(theta_odometry, theta_true)))


def _last_samples(theta_odometry, theta_true):
    return float(np.asarray(theta_odometry)[-1] - np.asarray(theta_true)[-1])


def _absolute(theta_odometry, theta_true):
    return abs(heading_error(theta_odometry, theta_true))


Exercise(
    "conventions.heading_error",
    "The signed error (rad) of the final heading, odometry minus truth, keeping whole turns, "
    "from two series of headings wrapped to (-pi, pi] and sampled finely.",
    heading_error,
    [Case(_heading_series(2.0, 1.5, 0.0)), Case(_heading_series(-1.0, 1.02, 0.4)),
     Case(_heading_series(3.0, 0.9, -0.2)), Case(_heading_series(0.25, 1.0, 0.05))],
    hidden=lambda rng: [Case(_heading_series(rng.uniform(-3.0, 3.0), rng.uniform(0.85, 1.5),
                                             rng.uniform(-0.4, 0.4))) for _ in range(4)],
    mistakes=[
        (_wrapped_error, "you wrapped the error: a robot that counted a whole turn too many "
                         "would show an error of 0. Report the difference of the unwrapped "
                         "headings, not wrapped again."),
        (_last_samples, "you subtracted the last wrapped samples: whole turns (and the jump "
                        "at +-pi) are lost. Unwrap each series first (np.unwrap), then "
                        "subtract."),
        (_absolute, "the error is signed: odometry ahead of the truth (to the left) is "
                    "positive, behind is negative."),
    ],
)


# ------------------------------------------------------------------ 7. a no-side-slip row

def side_slip_row(theta: float, x: float, y: float, psi: float) -> NDArray[np.float64]:
    """The Pfaffian row (coefficients of x_dot, y_dot, theta_dot) of the no-side-slip
    constraint of a wheel at (x, y) in the body frame (m) rolling along psi (rad), on a body
    with heading theta (rad)."""
    wheel = unified.WheelConstraint("wheel", (x, y), psi)
    return nonholonomic.pfaffian_matrix([0.0, 0.0, theta], [wheel])[0]


def _body_frame_row(theta, x, y, psi):
    return np.array([-math.sin(psi), math.cos(psi), x * math.cos(psi) + y * math.sin(psi)])


def _rolling_row(theta, x, y, psi):
    return np.array([math.cos(theta + psi), math.sin(theta + psi),
                     x * math.sin(psi) - y * math.cos(psi)])


def _lever_sign(theta, x, y, psi):
    return np.array([-math.sin(theta + psi), math.cos(theta + psi),
                     -(x * math.cos(psi) + y * math.sin(psi))])


def _lever_in_world(theta, x, y, psi):
    return np.array([-math.sin(theta + psi), math.cos(theta + psi),
                     x * math.cos(theta + psi) + y * math.sin(theta + psi)])


Exercise(
    "conventions.side_slip_row",
    "The row A_i(q) of the no-side-slip constraint A_i(q) q_dot = 0, coefficients of "
    "(x_dot, y_dot, theta_dot), of a wheel at (x, y) in the body frame (m) rolling along psi "
    "(rad from body +x), on a body with heading theta (rad).",
    side_slip_row,
    [Case((0.3, 0.2, 0.1, 0.5)), Case((-1.2, 0.33, 0.0, 0.3)), Case((2.0, 0.0, -0.15, 0.0)),
     Case((0.7, -0.2, 0.15, -0.4))],
    wheel_names=("x_dot", "y_dot", "theta_dot"),
    mistakes=[
        (_body_frame_row, "that is the row in the body frame, for (v_x, v_y, omega). In "
                          "world rates the axle direction turns with the body: its first "
                          "two entries are -sin(theta + psi) and cos(theta + psi)."),
        (_rolling_row, "that is the rolling direction's row (e_i). No side slip is the "
                       "velocity along the axle, n_i = (-sin psi, cos psi) in the body."),
        (_lever_sign, "the turning term has the wrong sign: the contact point moves at "
                      "v + omega x p = (v_x - omega y, v_y + omega x), and n_i . (omega x p) "
                      "= omega (x cos psi + y sin psi)."),
        (_lever_in_world, "the turning term does not depend on the heading: omega x p is "
                          "taken in the body frame, where p and n_i are fixed, so it is "
                          "x cos psi + y sin psi."),
    ],
)
