"""Exercises of the chapter "Differential drive in encoder units" (checked against
:mod:`wheelkin.diffdrive`).

>>> from wheelkin.exercises import check
>>> check("diffdrive.wheel_speeds", lambda v, omega, track_width: (v, v)).passed
False
"""

from __future__ import annotations

import math

from wheelkin import diffdrive as dd
from wheelkin.exercises import Case, Exercise

__all__: list[str] = []

_WHEELS = ("v_left", "v_right")


def wheel_speeds(v, omega, track_width):
    return dd.wheel_speeds(v, omega, track_width)


Exercise(
    "diffdrive.wheel_speeds",
    "Left and right wheel ground speeds (m/s) of a differential drive moving at v (m/s) "
    "and turning at omega (rad/s, counter-clockwise +), wheels track_width (m) apart.",
    wheel_speeds,
    [Case((0.2, 1.0, 0.085)), Case((0.0, -2.0, 0.085)), Case((0.3, 0.5, 0.2)),
     Case((-0.1, 0.7, 0.15))],
    wheel_names=_WHEELS,
    mistakes=[
        (lambda v, omega, track_width: (v / 2 - omega * track_width / 2,
                                        v / 2 + omega * track_width / 2),
         "the forward term is halved, as in the firmware README: each wheel must carry the "
         "whole forward speed v, not v/2, or the robot drives at half speed."),
        (lambda v, omega, track_width: (v - omega * track_width, v + omega * track_width),
         "the turn term is twice too large: each wheel is W/2 from the axle midpoint, so it "
         "moves at omega * W/2 relative to it (omega * W is one wheel relative to the other)."),
    ],
)


def wheel_speeds_steps(v_steps_per_s, omega_mrad_per_s, track_mm, steps_per_m):
    return dd.wheel_speeds_steps(v_steps_per_s, omega_mrad_per_s, track_mm, steps_per_m)


def _turn(omega, base, enc, factor):
    return omega * base / 2 * enc * factor


Exercise(
    "diffdrive.wheel_speeds_steps",
    "Left and right wheel speeds (steps/s) from v (steps/s) and omega (mrad/s), with the "
    "track width W in mm and the encoder's steps per metre.",
    wheel_speeds_steps,
    [Case((1000, 1000, 85, 8043)), Case((0, -2500, 85, 8043)), Case((-400, 300, 120, 5000))],
    # Firmware units are whole numbers: draw them, in the ranges the visible cases span.
    hidden=lambda rng: [Case((int(rng.integers(-2500, 2501)), int(rng.integers(-2500, 2501)),
                              int(rng.integers(60, 151)), int(rng.integers(4000, 9001))))
                        for _ in range(4)],
    wheel_names=_WHEELS,
    mistakes=[
        (lambda v, w, b, e: (v / 2 - _turn(w, b, e, 1e-6), v / 2 + _turn(w, b, e, 1e-6)),
         "the forward term is halved, as in the firmware README: use v, not v/2."),
        (lambda v, w, b, e: (v - _turn(w, b, e, 1e-3), v + _turn(w, b, e, 1e-3)),
         "the turn term is 1000 times too large: mrad -> rad and mm -> m are two factors of "
         "1/1000, so the turn term needs 1/10**6."),
        (lambda v, w, b, e: (v - _turn(w, b, e, 1.0), v + _turn(w, b, e, 1.0)),
         "the turn term is 10**6 times too large: divide by 1000 for mrad and by 1000 for mm."),
        (lambda v, w, b, e: (v - _turn(w, b, e, 1e-9), v + _turn(w, b, e, 1e-9)),
         "the turn term is 1000 times too small: one factor of 1/1000 too many."),
    ],
)


def omega_limit(track_mm, steps_per_m):
    return dd.int32_omega_limit(track_mm, steps_per_m)


Exercise(
    "diffdrive.omega_limit",
    "The largest whole yaw rate |omega| (mrad/s) for which omega * track_mm * "
    "steps_per_m still fits in a signed 32-bit integer.",
    omega_limit,
    [Case((85, 8043)), Case((150, 4000)), Case((100, 20000)), Case((60, 1000))],
    hidden=lambda rng: [Case((int(rng.integers(60, 151)), int(rng.integers(1000, 20001))))
                        for _ in range(4)],
    rtol=0.0,
    atol=0.0,
    mistakes=[
        (lambda b, e: (2**32 - 1) // (b * e),
         "2**32 - 1 is the largest *unsigned* 32-bit integer; a signed int32 stops at "
         "2**31 - 1."),
        (lambda b, e: (2**15 - 1) // (b * e),
         "2**15 - 1 is the int16 limit; the product is computed in int32 (2**31 - 1)."),
        (lambda b, e: (2**31 - 1) / (b * e),
         "round down to a whole number of mrad/s (the set point is an integer): use //."),
        (lambda b, e: round((2**31 - 1) / (b * e)),
         "round down, not to nearest: one more mrad/s would already overflow."),
    ],
)


def count_time(min_steps, speed, steps_per_m):
    return dd.time_to_count(min_steps, speed, steps_per_m)


Exercise(
    "diffdrive.count_time",
    "How long (s) a wheel moving at speed (m/s, either sign) takes to turn min_steps encoder "
    "steps, with steps_per_m steps per metre.",
    count_time,
    [Case((6, 0.05, 8043)), Case((6, -0.2, 8043)), Case((10, 0.01, 4000))],
    mistakes=[
        (lambda m, s, e: m / (e * s),
         "a wheel turning backwards (negative speed) also counts steps: use |speed|."),
        (lambda m, s, e: m * e / abs(s),
         "the steps per metre belong in the denominator: the wheel covers min_steps / "
         "steps_per_m metres, at |speed| metres per second."),
        (lambda m, s, e: abs(s) * e / m,
         "that is a rate (estimates per second), not a time: invert it."),
    ],
)



# ------------------------------------------------------------------ a design: the step count

def choose_min_steps(min_speed, max_latency, max_error, steps_per_m):
    """The smallest whole minimum step count m whose error, about 1/m, is at most
    ``max_error``, if waiting for m steps at ``min_speed`` (m/s) takes at most ``max_latency``
    (s); 0 if no m meets both (the chapter's speedometer section)."""
    steps = math.ceil(1.0 / max_error - 1e-9)
    wait = steps / (steps_per_m * abs(min_speed))
    return steps if wait <= max_latency else 0


Exercise(
    "diffdrive.choose_min_steps",
    "The smallest minimum step count m (error about 1/m <= max_error) for a speedometer "
    "that must read min_speed (m/s) within max_latency (s); 0 if none meets both.",
    choose_min_steps,
    [Case((0.05, 0.1, 0.2, 8043)), Case((0.01, 0.1, 0.1, 8043)), Case((0.02, 0.2, 0.1, 8043)),
     Case((0.1, 0.05, 0.05, 8043)), Case((-0.05, 0.1, 0.25, 8043))],
    mistakes=[
        (lambda v, lat, err, enc: math.ceil(1.0 / err - 1e-9),
         "that step count meets the error, but the wait at the slowest speed, "
         "m / (ENC |v|), is longer than max_latency: then no m works, return 0."),
        (lambda v, lat, err, enc: math.floor(lat * enc * abs(v)),
         "that is the largest m the latency allows; the smallest m that meets the error is "
         "wanted (fewer steps, fresher readings), or 0 if even that one is too slow."),
        (lambda v, lat, err, enc: (math.ceil(1.0 / err - 1e-9)
                                   if math.ceil(1.0 / err - 1e-9) / (enc * v) <= lat else 0),
         "a wheel running backwards has a negative speed: use |v| for the wait."),
    ],
    atol=1e-9,
)
