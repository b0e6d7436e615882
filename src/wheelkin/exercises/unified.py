"""Exercises of the closing chapter, "One model for every wheel" (notebooks/08_one_model).

Our frame (x forward, y left, omega counter-clockwise); SI.

>>> from wheelkin.exercises import check
>>> import numpy as np
>>> def skid_steer_slip(v, omega, half_track, half_wheelbase):
...     return omega * half_track * np.array([1.0, 1.0, -1.0, -1.0])  # b instead of a
>>> print(check("unified.skid_steer_slip", skid_steer_slip).message)  # doctest: +ELLIPSIS
✘ unified.skid_steer_slip: for v=0.3, omega=1, ...: the wheels slide sideways because ...
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from wheelkin.exercises import Case, Exercise
from wheelkin.mecanum import MecanumGeometry
from wheelkin.unified import (
    WheelConstraint,
    diff_drive_wheels,
    mecanum_wheels,
    mobility,
    rolling_row,
    rover_wheels,
    skid_steer_wheels,
    sliding_row,
    slip_residual,
    steer_for_twist,
    wheel_rates,
)

__all__ = ["CANDIDATES", "choose_design", "omni_rates", "skid_steer_slip", "tricycle_mobility",
           "wheel_rows"]


# --- 1. the two rows of one wheel ----------------------------------------------------------------

def wheel_rows(x: float, y: float, psi: float) -> NDArray[np.float64]:
    """Rolling row and no-side-slip row (a 2x3 array) of a conventional wheel at (x, y) m
    rolling along the direction psi (rad) from the body x axis."""
    w = WheelConstraint("W", (x, y), psi, 1.0, "fixed")
    return np.array([rolling_row(w), sliding_row(w)])


def _rows_omega_sign(x, y, psi):
    rows = wheel_rows(x, y, psi)
    rows[:, 2] *= -1.0
    return rows


def _rows_clockwise_normal(x, y, psi):
    rows = wheel_rows(x, y, psi)
    rows[1] *= -1.0
    return rows


def _rows_swapped(x, y, psi):
    return wheel_rows(x, y, psi)[::-1]


def _rows_no_rotation(x, y, psi):
    rows = wheel_rows(x, y, psi)
    rows[:, 2] = 0.0
    return rows


Exercise(
    "unified.wheel_rows",
    "Return a 2x3 array: first the rolling row J1 (with J1 . (vx, vy, omega) = r_w phi), then "
    "the no-side-slip row C1, of a conventional wheel whose contact point is at (x, y) m and "
    "whose rolling direction is at the angle psi (rad) from the body x axis.",
    wheel_rows,
    [Case((0.2, 0.1, 0.0)), Case((0.0, -0.3, math.pi / 3)), Case((-0.4, 0.25, -2.0)),
     Case((0.3, 0.0, math.pi / 2))],
    mistakes=[
        (_rows_omega_sign,
         "the omega column has the wrong sign: the contact point moves at v + omega z x p = "
         "(vx - omega y, vy + omega x), so the third entry of the row for a direction d is "
         "x d_y - y d_x."),
        (_rows_clockwise_normal,
         "the sliding row has the wrong sign: take n as the rolling direction turned "
         "counter-clockwise by 90 degrees, n = (-sin psi, cos psi) (the row's sign does not "
         "change the constraint, but the chapter fixes it this way)."),
        (_rows_swapped, "the two rows are swapped: rolling row first, then the sliding row."),
        (_rows_no_rotation,
         "the omega column is missing: a turning body moves the contact point too "
         "(omega z x p), unless the wheel sits at the reference point."),
    ],
)


# --- 2. the mobility of a tricycle -------------------------------------------------------------

def _tricycle(front_kind: str):
    front = {"fixed": {}, "steered": {"steering": 0.3}, "caster": {},
             "swedish": {"roller_angle": math.pi / 4}}
    if front_kind not in front:
        raise ValueError(f"front_kind must be one of {', '.join(map(repr, front))}; "
                         f"got {front_kind!r}")
    return (WheelConstraint("RL", (0.0, 0.2)), WheelConstraint("RR", (0.0, -0.2)),
            WheelConstraint("F", (0.5, 0.0), kind=front_kind, **front[front_kind]))


def tricycle_mobility(front_kind: str) -> NDArray[np.float64]:
    """(degree of mobility, steerability, manoeuvrability) of a tricycle: a fixed rear axle
    (two fixed wheels) and one front wheel of the kind ``front_kind``."""
    m = mobility(_tricycle(front_kind))
    return np.array(m[:3], dtype=float)


def _steered_adds_motion(front_kind):
    m = tricycle_mobility(front_kind)
    if front_kind == "steered":
        return np.array([2.0, 1.0, 3.0])
    return m


def _caster_constrains(front_kind):
    if front_kind in ("caster", "swedish"):
        return np.array([1.0, 0.0, 1.0])
    return tricycle_mobility(front_kind)


def _steered_two(front_kind):
    if front_kind == "steered":
        return np.array([1.0, 2.0, 3.0])
    return tricycle_mobility(front_kind)


Exercise(
    "unified.tricycle_mobility",
    "A tricycle has a fixed rear axle (two fixed wheels at (0, +-0.2) m) and one front wheel "
    "at (0.5, 0) m of the kind `front_kind` ('fixed', 'steered', 'caster' or 'swedish'). "
    "Return (degree of mobility, degree of steerability, degree of manoeuvrability).",
    tricycle_mobility,
    [Case(("fixed",)), Case(("steered",)), Case(("caster",))],
    # Four front wheels in all: the notebook's check tries three, the grader the fourth.
    hidden=lambda rng: [Case(("swedish",))],
    mistakes=[
        (_steered_adds_motion,
         "a steered wheel still forbids sliding sideways at whatever angle it is turned to: "
         "its row joins C1 and takes a motion away (delta_m = 1); what it adds is a steering "
         "freedom (delta_s = 1)."),
        (_caster_constrains,
         "a caster's swivel (and a Swedish wheel's rollers) absorb any sideways velocity: such "
         "a wheel adds no row to C1, so the tricycle keeps the two motions of a differential "
         "drive."),
        (_steered_two,
         "the fixed rear axle already pins the ICR to its line: steering can only move the ICR "
         "along it, one freedom, delta_s = min(rank C1s, 2 - rank C1f) = 1."),
    ],
)


# --- 3. the wheel rates of an omni-wheel robot ----------------------------------------------------

#: How the check names the three wheels in its messages.
OMNI_NAMES = ("the wheel at 0°", "the wheel at 120°", "the wheel at 240°")


def _omni(wheel_radius, centre_distance):
    return tuple(
        WheelConstraint(name, (centre_distance * math.cos(a), centre_distance * math.sin(a)),
                        a + math.pi / 2, wheel_radius, "swedish", roller_angle=math.pi / 2)
        for name, a in zip(OMNI_NAMES, (0.0, 2 * math.pi / 3, 4 * math.pi / 3), strict=True))


def omni_rates(vx: float, vy: float, omega: float, wheel_radius: float,
               centre_distance: float) -> np.ndarray:
    """Wheel rates (rad/s) of three omni wheels at 0, 120 and 240 degrees around the centre,
    in that order, each rolling counter-clockwise around it (rollers along the rim)."""
    return wheel_rates(_omni(wheel_radius, centre_distance), (vx, vy, omega))


def _omni_radial(vx, vy, omega, wheel_radius, centre_distance):
    alpha = np.array([0.0, 2 * math.pi / 3, 4 * math.pi / 3])
    return (np.cos(alpha) * vx + np.sin(alpha) * vy) / wheel_radius


def _omni_no_distance(vx, vy, omega, wheel_radius, centre_distance):
    alpha = np.array([0.0, 2 * math.pi / 3, 4 * math.pi / 3])
    return (-np.sin(alpha) * vx + np.cos(alpha) * vy + omega) / wheel_radius


def _omni_rim(vx, vy, omega, wheel_radius, centre_distance):
    return omni_rates(vx, vy, omega, wheel_radius, centre_distance) * wheel_radius


Exercise(
    "unified.omni_rates",
    "Three omni wheels (rollers along the rim) sit at distance `centre_distance` m from the "
    "centre, at 0, 120 and 240 degrees from the body x axis, each rolling counter-clockwise "
    "around the centre. Return their rates (rad/s) in that order for the twist (vx, vy, omega).",
    omni_rates,
    [Case((0.0, 0.0, 1.0, 0.03, 0.2)), Case((0.5, 0.0, 0.0, 0.03, 0.2)),
     Case((0.0, 0.4, 0.0, 0.05, 0.15)), Case((0.3, -0.2, 0.8, 0.04, 0.25))],
    wheel_names=OMNI_NAMES,
    mistakes=[
        (_omni_radial,
         "those wheels roll outwards, along the line from the centre: each rolls along the "
         "tangent, at 90 degrees to it (psi_i = alpha_i + 90 degrees)."),
        (_omni_no_distance,
         "the spin term needs the lever arm: the rim moves at omega times the distance to the "
         "centre (centre_distance * omega), not at omega."),
        (_omni_rim, "these are rim speeds (m/s): divide by the wheel radius to get rad/s."),
    ],
)


# --- 4. how fast a skid steer's wheels slide ---------------------------------------------------

SKID_NAMES = ("FL", "FR", "RL", "RR")


def skid_steer_slip(v: float, omega: float, half_track: float, half_wheelbase: float) -> np.ndarray:
    """Sideways sliding speed (m/s, along each wheel's left) of a skid steer's wheels FL, FR,
    RL, RR driving the twist (v, 0, omega)."""
    wheels = skid_steer_wheels(half_wheelbase=half_wheelbase, half_track=half_track,
                               wheel_radius=0.05)
    return slip_residual(wheels, (v, 0.0, omega))


def _skid_track(v, omega, half_track, half_wheelbase):
    return omega * half_track * np.array([1.0, 1.0, -1.0, -1.0])


def _skid_with_speed(v, omega, half_track, half_wheelbase):
    return skid_steer_slip(v, omega, half_track, half_wheelbase) + v


Exercise(
    "unified.skid_steer_slip",
    "A skid steer has fixed wheels FL (a, b), FR (a, -b), RL (-a, b), RR (-a, -b) "
    "(a = half_wheelbase, b = half_track, m). Return each wheel's sideways sliding speed "
    "(m/s, positive to the vehicle's left) when it drives the twist (v, 0, omega).",
    skid_steer_slip,
    [Case((0.3, 1.0, 0.06, 0.05)), Case((0.0, -2.0, 0.2, 0.3)), Case((1.0, 0.5, 0.25, 0.1))],
    wheel_names=SKID_NAMES,
    mistakes=[
        (_skid_track,
         "the wheels slide sideways because the body turns about a point between the axles: "
         "the lateral speed is omega times the distance along x (the half wheelbase a), "
         "not across (the half track b)."),
        (_skid_with_speed,
         "the forward speed v is along each wheel's rolling direction: it adds nothing to the "
         "sideways slide."),
    ],
)


# --- 5. a design: which wheel set for a task? ----------------------------------------------------

def _omni_base():
    return tuple(WheelConstraint(f"O{k}", (0.2 * math.cos(q), 0.2 * math.sin(q)),
                                 q + math.pi / 2, 0.03, "swedish", roller_angle=math.pi / 2)
                 for k, q in enumerate(2 * np.pi * np.arange(3) / 3))


def _swerve():
    wheels = tuple(WheelConstraint(f"S{k}", (0.3 * math.cos(q), 0.3 * math.sin(q)),
                                   kind="steered")
                   for k, q in enumerate(2 * np.pi * np.arange(3) / 3))
    return steer_for_twist(wheels, (0.3, 0.2, 0.5))  # coordinated on one turning centre


def _rover():
    return rover_wheels()


#: The candidate designs of the exercise: (description, wheels builder, motors).
CANDIDATES = (
    ("differential drive: two fixed driven wheels on one axle and a caster",
     lambda: diff_drive_wheels(0.3, 0.05), 2),
    ("skid steer: four fixed driven wheels on two axles",
     lambda: skid_steer_wheels(half_track=0.15, half_wheelbase=0.2, wheel_radius=0.05), 4),
    ("mecanum: four 45-degree Swedish wheels", lambda: mecanum_wheels(MecanumGeometry(
        wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)), 4),
    ("omni base: three 90-degree Swedish wheels at 120 degrees", _omni_base, 3),
    ("tricycle: a fixed unpowered rear axle and a driven, steered front wheel",
     lambda: _tricycle("steered"), 2),
    ("rover: a fixed middle pair and four steered corners, all six driven", _rover, 10),
    ("swerve: three driven, steered wheels", _swerve, 6),
)


def _degrees(index):
    m = mobility(CANDIDATES[index][1]())
    return m.degree_of_mobility, m.degree_of_steerability


def _fits(index: int, delta_m: int, delta_s: int) -> bool:
    """Does design ``index`` do at least what (delta_m, delta_s) asks?"""
    m, s_ = _degrees(index)
    return m >= delta_m and m + s_ >= delta_m + delta_s


def choose_design(delta_m: int, delta_s: int) -> int:
    """Index into :data:`CANDIDATES` of the design with the fewest motors (on a tie, the first
    listed) that does at least what the degrees ask: its own degree of mobility at least
    ``delta_m`` (the motions it makes without steering first) and its degree of
    manoeuvrability at least ``delta_m + delta_s`` (the twist directions it reaches at all,
    steering first if it must); -1 if none does.

    The degrees are computed by :func:`wheelkin.unified.mobility` from each design's wheels:

    >>> [_degrees(k) for k in range(len(CANDIDATES))]
    [(2, 0), (1, 0), (3, 0), (3, 0), (1, 1), (1, 1), (1, 2)]
    >>> choose_design(1, 2), choose_design(1, 1), choose_design(3, 1)
    (3, 0, -1)
    """
    fits = [k for k in range(len(CANDIDATES)) if _fits(k, delta_m, delta_s)]
    return min(fits, key=lambda k: CANDIDATES[k][2]) if fits else -1


def _exact_degrees(delta_m, delta_s):
    fits = [k for k in range(len(CANDIDATES)) if _degrees(k) == (delta_m, delta_s)]
    return min(fits, key=lambda k: CANDIDATES[k][2]) if fits else -1


def _first_fit(delta_m, delta_s):
    fits = [k for k in range(len(CANDIDATES)) if _fits(k, delta_m, delta_s)]
    return fits[0] if fits else -1


def _most_motors(delta_m, delta_s):
    fits = [k for k in range(len(CANDIDATES)) if _fits(k, delta_m, delta_s)]
    return max(fits, key=lambda k: CANDIDATES[k][2]) if fits else -1


def _other_degrees(rng):
    """Four degrees (delta_m, delta_s) the visible cases do not ask about, drawn from all of
    0..3 x 0..3 (some of which no candidate has: the answer is then -1)."""
    pairs = [(m, s) for m in range(4) for s in range(4)
             if (m, s) not in {(1, 1), (3, 0), (2, 0), (1, 2), (2, 1), (3, 1)}]
    return [Case(pairs[k]) for k in rng.choice(len(pairs), size=4, replace=False)]


Exercise(
    "unified.choose_design",
    "Return the index in CANDIDATES of the design with the fewest motors (on a tie, the first "
    "listed) whose degree of mobility is at least delta_m and whose degree of "
    "manoeuvrability is at least delta_m + delta_s, or -1 if no candidate has them; it may "
    "use CANDIDATES and wheelkin.unified.mobility, no other part of the library.",
    choose_design,
    [Case((1, 1)), Case((3, 0)), Case((2, 0)), Case((1, 2)), Case((2, 1)), Case((3, 1))],
    library=("wheelkin.exercises.unified.CANDIDATES", "wheelkin.unified.mobility"),
    hidden=_other_degrees,
    mistakes=[
        (_exact_degrees,
         "that design has exactly the degrees asked, but a design that can do more may cost "
         "less: accept every design with at least delta_m motions of its own and at least "
         "delta_m + delta_s directions in all (a differential drive, (2, 0), does what a "
         "tricycle, (1, 1), does, with the same two motors; the omni base, (3, 0), does what "
         "a swerve base, (1, 2), does, with three motors instead of six)."),
        (_first_fit,
         "that design can do the task, but another can do it with fewer motors: the "
         "three-omni base is omnidirectional with 3 motors, the mecanum vehicle needs 4."),
        (_most_motors,
         "that design can do the task, but it is the most expensive one: compare the motor "
         "counts and take the fewest (the rover needs ten motors for what a tricycle does "
         "with two)."),
    ],
)
