"""Exercises of the mecanum chapter (notebooks/04_mecanum.ipynb).

Wheel order FL, FR, RL, RR; our frame (x forward, y left, omega counter-clockwise); SI.

>>> from wheelkin.exercises import check
>>> import numpy as np
>>> def strafe_rates(speed, wheel_radius):
...     return np.array([-1.0, 1.0, 1.0, -1.0]) * speed   # forgot the wheel radius
>>> print(check("mecanum.strafe_rates", strafe_rates).message)  # doctest: +ELLIPSIS
✘ mecanum.strafe_rates: for speed=1, wheel_radius=0.05 ...: these are rim speeds (m/s)...
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from wheelkin.exercises import Case, Exercise
from wheelkin.mecanum import MecanumGeometry, forward_kinematics, inverse_kinematics

__all__ = ["choose_roller_angle", "max_spin_rate", "rates_60", "strafe_rates",
           "twist_from_rates"]

WHEELS = ("FL", "FR", "RL", "RR")
_ROLLERS = np.array([-1.0, 1.0, 1.0, -1.0])


# --- 1. a pure strafe ---------------------------------------------------------------------

def strafe_rates(speed: float, wheel_radius: float) -> np.ndarray:
    """Wheel rates (FL, FR, RL, RR), rad/s, that strafe left at ``speed`` m/s (45° rollers)."""
    # The half wheelbase and half track do not matter for a pure strafe (omega = 0).
    return inverse_kinematics(0.0, speed, 0.0, MecanumGeometry(
        half_wheelbase=1.0, half_track=1.0, wheel_radius=wheel_radius))


Exercise(
    "mecanum.strafe_rates",
    "Return the wheel rates (FL, FR, RL, RR) in rad/s that move the vehicle straight to the "
    "left at `speed` m/s (negative: to the right) without turning; 45-degree rollers, X "
    "arrangement, wheel radius `wheel_radius` m.",
    strafe_rates,
    [Case((1.0, 0.05)), Case((-0.5, 0.0762)), Case((2.0, 0.1))],
    wheel_names=WHEELS,
    mistakes=[
        (lambda speed, wheel_radius: _ROLLERS * speed,
         "these are rim speeds (m/s): divide by the wheel radius to get rad/s."),
        (lambda speed, wheel_radius: -_ROLLERS * speed / wheel_radius,
         "that strafes to the right. In our frame y points left, so a left strafe is vy > 0 "
         "(in the document's frame it would be X < 0: X points right)."),
        (lambda speed, wheel_radius: np.full(4, speed / wheel_radius),
         "all four wheels turning the same way drive forwards, not sideways: on a strafe "
         "the wheels on each diagonal turn together, against the other diagonal."),
    ],
)


# --- 2. the twist from four wheel rates ------------------------------------------------------

def twist_from_rates(rates: ArrayLike, wheel_radius: float, half_wheelbase: float,
                     half_track: float) -> np.ndarray:
    """The body twist (vx m/s, vy m/s, omega rad/s) from wheel rates FL, FR, RL, RR (rad/s)."""
    g = MecanumGeometry(half_wheelbase=half_wheelbase, half_track=half_track,
                        wheel_radius=wheel_radius)
    return np.asarray(forward_kinematics(rates, g))


def _twist_full_dims(rates, wheel_radius, half_wheelbase, half_track):
    g = MecanumGeometry(half_wheelbase=2 * half_wheelbase, half_track=2 * half_track,
                        wheel_radius=wheel_radius)
    return np.asarray(forward_kinematics(rates, g))


def _twist_no_quarter(rates, wheel_radius, half_wheelbase, half_track):
    return 4.0 * twist_from_rates(rates, wheel_radius, half_wheelbase, half_track)


def _twist_k_times(rates, wheel_radius, half_wheelbase, half_track):
    out = twist_from_rates(rates, wheel_radius, half_wheelbase, half_track)
    k = half_wheelbase + half_track
    return np.array([out[0], out[1], out[2] * k * k])


Exercise(
    "mecanum.twist_from_rates",
    "Given the four wheel rates `rates` = (FL, FR, RL, RR) in rad/s, return the body twist "
    "(vx, vy, omega) in m/s and rad/s (least squares when the rates are inconsistent).",
    twist_from_rates,
    [
        Case((np.array([10.0, 10.0, 10.0, 10.0]), 0.05, 0.2, 0.15)),
        Case((np.array([-20.0, 20.0, 20.0, -20.0]), 0.05, 0.2, 0.15)),
        Case((np.array([-7.0, 7.0, -7.0, 7.0]), 0.05, 0.2, 0.15)),
        Case((np.array([3.0, 11.0, 5.0, 1.0]), 0.0762, 0.3048, 0.2286)),
        Case((np.array([12.0, 10.0, -8.0, -10.0]), 0.0762, 0.3048, 0.2286)),
    ],
    mistakes=[
        (_twist_full_dims,
         "omega is half the right value: the lever arm k is half_wheelbase + half_track, "
         "not the full length plus the full width."),
        (_twist_no_quarter,
         "4 times too large: each of the four wheels contributes a quarter (r/4)."),
        (_twist_k_times,
         "omega is off by k squared: the forward map divides by k = a + b (the inverse "
         "multiplies)."),
    ],
)


# --- 3. 60-degree rollers --------------------------------------------------------------------

def rates_60(vx: float, vy: float, omega: float, wheel_radius: float, half_wheelbase: float,
             half_track: float) -> np.ndarray:
    """Wheel rates FL, FR, RL, RR (rad/s) for rollers at 60 degrees to the axle."""
    g = MecanumGeometry(half_wheelbase=half_wheelbase, half_track=half_track,
                        wheel_radius=wheel_radius, roller_angle=math.pi / 3)
    return inverse_kinematics(vx, vy, omega, g)


def _rates_45(vx, vy, omega, wheel_radius, half_wheelbase, half_track):
    return inverse_kinematics(vx, vy, omega,
                              MecanumGeometry(half_wheelbase=half_wheelbase,
                                              half_track=half_track,
                                              wheel_radius=wheel_radius))


def _rates_tan(vx, vy, omega, wheel_radius, half_wheelbase, half_track):
    g = MecanumGeometry(half_wheelbase=half_wheelbase, half_track=half_track,
                        wheel_radius=wheel_radius, roller_angle=math.pi / 6)
    return inverse_kinematics(vx, vy, omega, g)


def _rates_k_plain(vx, vy, omega, wheel_radius, half_wheelbase, half_track):
    c = 1.0 / math.tan(math.pi / 3)
    k = half_wheelbase + half_track
    sig = np.array([-1.0, 1.0, -1.0, 1.0])
    return (vx + _ROLLERS * c * vy + sig * k * omega) / wheel_radius


Exercise(
    "mecanum.rates_60",
    "Return the wheel rates (FL, FR, RL, RR) in rad/s for the twist (vx, vy, omega) when the "
    "rollers sit at 60 degrees to the wheel's axle (X arrangement).",
    rates_60,
    [
        Case((1.0, 0.0, 0.0, 0.05, 0.2, 0.15)),
        Case((0.0, 1.0, 0.0, 0.05, 0.2, 0.15)),
        Case((0.0, 0.0, 1.0, 0.05, 0.2, 0.15)),
        Case((0.5, -0.3, 0.8, 0.0762, 0.3048, 0.2286)),
    ],
    wheel_names=WHEELS,
    mistakes=[
        (_rates_k_plain, "the sideways term is right, but the lever arm is k = b + a cot(gamma) "
                         "(the front-back offset a reaches the wheel through the rollers "
                         "too), not a + b."),
        (_rates_45, "that is the 45-degree answer: the sideways term is multiplied by "
                    "cot(gamma), which is 1/sqrt(3) at 60 degrees, not 1."),
        (_rates_tan, "you used tan(60°) where cot(60°) belongs: gamma is measured from the "
                     "axle, not from the wheel's rolling direction."),
    ],
)


# --- 4. the fastest spin ---------------------------------------------------------------------

def max_spin_rate(max_rim_speed: float, half_wheelbase: float, half_track: float) -> float:
    """The fastest spin on the spot (rad/s) if no wheel rim may exceed ``max_rim_speed`` m/s."""
    return max_rim_speed / (half_wheelbase + half_track)


Exercise(
    "mecanum.max_spin_rate",
    "With every wheel's rim speed limited to `max_rim_speed` m/s, how fast (rad/s) can the "
    "vehicle spin on the spot? (45-degree rollers)",
    max_spin_rate,
    [Case((4.572, 0.3048, 0.2286)), Case((1.0, 0.2, 0.15)), Case((2.0, 0.1, 0.3))],
    mistakes=[
        (lambda max_rim_speed, half_wheelbase, half_track:
         max_rim_speed / math.hypot(half_wheelbase, half_track),
         "you divided by the distance from the centre to a wheel, sqrt(a² + b²): right for a "
         "wheel that rolls along the circle, but a mecanum wheel rolls along x and its rollers "
         "take the rest, so the lever arm is k = a + b."),
    ],
)


# --- 5. a design: which roller angle? ---------------------------------------------------------

ROLLER_CHOICES_DEG = (30.0, 45.0, 60.0)


def _uses(angle_deg, strafe_speed, side_accel, max_rim_speed, mu, gravity=9.81):
    """(share of the rim-speed limit, share of the grip) a pure strafe needs at this angle.

    Checked against the library's fastest rim and grip usage:

    >>> from wheelkin.mecanum import MecanumGeometry, grip_usage, max_rim_speed
    >>> g = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05,
    ...                     roller_angle=math.radians(60))
    >>> speed, grip = _uses(60.0, 2.0, 1.5, 3.0, 0.8)
    >>> bool(np.isclose(speed, max_rim_speed(0.0, 2.0, 0.0, g) / 3.0))
    True
    >>> bool(np.isclose(grip, grip_usage(0.0, 1.5, 0.8, math.radians(60))))
    True
    """
    gamma = math.radians(angle_deg)
    speed_use = abs(strafe_speed) / math.tan(gamma) / max_rim_speed  # rim: |vy| cot(gamma)
    grip_use = abs(side_accel) / (math.cos(gamma) * mu * gravity)  # eq. (mecanum-grip)
    return speed_use, grip_use


def choose_roller_angle(strafe_speed: float, side_accel: float, max_rim_speed: float,
                        mu: float) -> float:
    """The roller angle (deg) among 30, 45, 60 that strafes at ``strafe_speed`` m/s and
    accelerates sideways at ``side_accel`` m/s² with the most margin (the smallest of the
    larger of its two uses); 0 if none can."""
    best, best_use = 0.0, 1.0
    for angle in ROLLER_CHOICES_DEG:
        use = max(_uses(angle, strafe_speed, side_accel, max_rim_speed, mu))
        if use <= best_use:
            best, best_use = angle, use
    return best


def _speed_only(strafe_speed, side_accel, max_rim_speed, mu):
    ok = [a for a in ROLLER_CHOICES_DEG
          if _uses(a, strafe_speed, side_accel, max_rim_speed, mu)[0] <= 1.0]
    return max(ok) if ok else 0.0


def _grip_only(strafe_speed, side_accel, max_rim_speed, mu):
    ok = [a for a in ROLLER_CHOICES_DEG
          if _uses(a, strafe_speed, side_accel, max_rim_speed, mu)[1] <= 1.0]
    return min(ok) if ok else 0.0


def _first_that_works(strafe_speed, side_accel, max_rim_speed, mu):
    for a in ROLLER_CHOICES_DEG:
        if max(_uses(a, strafe_speed, side_accel, max_rim_speed, mu)) <= 1.0:
            return a
    return 0.0


Exercise(
    "mecanum.choose_roller_angle",
    "Choose the roller angle (30, 45 or 60 degrees, or 0 if none works) for a vehicle that "
    "must strafe at `strafe_speed` m/s with rims limited to `max_rim_speed` m/s and "
    "accelerate sideways at `side_accel` m/s² on a floor of friction `mu`; of the angles "
    "that work, the one with the most margin.",
    choose_roller_angle,
    [
        Case((3.0, 1.0, 2.0, 0.8)),    # only 60 is fast enough
        Case((1.0, 4.5, 3.0, 0.8)),    # 60 slides; 30 has the most margin
        Case((2.0, 3.2, 3.2, 0.8)),    # 45 balances the two
        Case((2.0, 1.0, 3.0, 0.8)),    # 45 works, 60 has more margin
        Case((3.0, 5.0, 2.0, 0.8)),    # none: too fast and too hard at once
    ],
    mistakes=[
        (_speed_only,
         "you chose by wheel speed alone: a steeper roller strafes more cheaply "
         "(rim speed |vy| cot γ), but pushes sideways with only cos γ of its force. Check "
         "the grip too: |a_y| / cos γ must stay within μg."),
        (_grip_only,
         "you chose by grip alone: a shallow roller pushes sideways well, but its rim must "
         "turn at |vy| cot γ to strafe. Check that this stays within the rim-speed limit."),
        (_first_that_works,
         "that angle works, but another one has more margin: compare, for each angle, the "
         "larger of its two uses (speed and grip) and take the smallest."),
    ],
)
