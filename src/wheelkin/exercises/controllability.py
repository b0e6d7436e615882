"""Exercises of chapter 10, "Nonholonomy and controllability" (notebooks/10_controllability/).

Lie brackets by hand, the exact end of the car's parallel-parking manoeuvre, and a design: a
parking plan (move length and number of repetitions) that reaches a sideways shift within a
given room. SI units and the book's signs: y to the left, counter-clockwise positive; the
bracket is [f1, f2] = D f2 f1 - D f1 f2; the car's full-lock fields are per metre driven.

The plan is not compared with one right answer: :class:`PlanExercise` drives the student's plan
(the library's exact arcs) and checks where it ends and how far ahead it goes.

>>> from wheelkin.exercises import check
>>> check("controllability.unicycle_bracket", unicycle_bracket).passed
True
>>> check("controllability.parking_plan", lambda shift, room, k: (room, 1)).kind
'wrong'
>>> check("controllability.parking_plan", parking_plan).passed
True
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from wheelkin import frames, nonholonomic
from wheelkin.exercises import UNIT_FACTORS, Case, CheckResult, Exercise

__all__ = ["PlanExercise", "parking_plan", "parking_pose", "turn_bracket", "unicycle_bracket"]

#: The 1/10 car of the sandbox at full lock: tan(0.4189 rad) / 0.33 m, 1/m.
CAR_CURVATURE = math.tan(0.4189) / 0.33
#: How close to the asked shift a parking plan must end, m.
SHIFT_TOLERANCE = 0.005
#: The most repetitions a plan may ask for.
MAX_REPETITIONS = 1000


# ------------------------------------------------------------------ 1. the unicycle's bracket

def unicycle_bracket(theta: float) -> NDArray[np.float64]:
    """[f1, f2] of the unicycle's drive field f1 = (cos theta, sin theta, 0) and turn field
    f2 = (0, 0, 1), at heading theta (rad)."""
    bracket = nonholonomic.lie_bracket(nonholonomic.unicycle_drive,
                                       nonholonomic.unicycle_turn, [0.0, 0.0, theta])
    return np.round(bracket, 12) + 0.0  # the finite difference's 1e-14 noise off the zeros


def _reversed_order(theta):
    return -unicycle_bracket(theta)


def _body_frame(theta):
    return np.array([0.0, -1.0, 0.0])


Exercise(
    "controllability.unicycle_bracket",
    "The Lie bracket [f1, f2] = D f2 f1 - D f1 f2 of the unicycle's drive field "
    "f1 = (cos theta, sin theta, 0) and turn field f2 = (0, 0, 1), at heading theta (rad).",
    unicycle_bracket,
    [Case((0.5,)), Case((2.0,)), Case((-1.2,)), Case((0.0,))],
    wheel_names=("x", "y", "theta"),
    mistakes=[
        (_reversed_order, "that is [f2, f1] = -[f1, f2]: the bracket is antisymmetric. "
                          "With the book's convention the derivative of f2 along f1 comes "
                          "first: D f2 f1 - D f1 f2."),
        (_body_frame, "that is the bracket at theta = 0 (straight to the right of a robot "
                      "facing +x). The fields depend on theta, and so does their bracket: "
                      "differentiate f1 with respect to theta."),
    ],
    atol=1e-8,
)


# ------------------------------------------------------------------ 2. the car's turn on the spot

def turn_bracket(theta: float, steering: float, wheelbase: float) -> NDArray[np.float64]:
    """[f1, f2] of the car's drive field f1 = (cos theta, sin theta, tan(delta)/L, 0) and
    steer field f2 = (0, 0, 0, 1), at q = (x, y, theta, delta): the turn on the spot about
    the rear-axle midpoint (Nelson's wriggle is the opposite, [f2, f1])."""
    def drive(q):
        return nonholonomic.car_fields(q, wheelbase)[:, 0]

    def steer(q):
        return nonholonomic.car_fields(q, wheelbase)[:, 1]

    bracket = nonholonomic.lie_bracket(drive, steer, [0.0, 0.0, theta, steering])
    return np.round(bracket, 12) + 0.0  # the finite difference's 1e-14 noise off the zeros


def _nelsons_order(theta, steering, wheelbase):
    return -turn_bracket(theta, steering, wheelbase)


def _no_secant(theta, steering, wheelbase):
    return np.array([0.0, 0.0, -1.0 / wheelbase, 0.0])


def _tangent_kept(theta, steering, wheelbase):
    return np.array([0.0, 0.0, -math.tan(steering) / wheelbase, 0.0])


Exercise(
    "controllability.turn_bracket",
    "The Lie bracket [f1, f2] of the car's drive field f1 = (cos theta, sin theta, "
    "tan(delta)/L, 0) and steer field f2 = (0, 0, 0, 1), at q = (x, y, theta, delta); "
    "wheelbase L (m).",
    turn_bracket,
    [Case((0.3, 0.2, 0.33)), Case((1.0, -0.35, 2.5)), Case((-2.0, 0.6, 2.8)),
     Case((0.0, 0.0, 0.33))],
    wheel_names=("x", "y", "theta", "delta"),
    mistakes=[
        (_nelsons_order, "that is [f2, f1] = -[f1, f2], Nelson's wriggle: the bracket is "
                         "antisymmetric. With the book's convention the derivative of f2 "
                         "along f1 comes first: D f2 f1 - D f1 f2."),
        (_no_secant, "the derivative of tan(delta) is 1/cos(delta)^2, not 1: only at "
                     "delta = 0 are they equal."),
        (_tangent_kept, "only the derivative of f1 with respect to delta enters (f2 points "
                        "along delta): d/d delta of tan(delta)/L is 1/(L cos(delta)^2)."),
    ],
    atol=1e-8,
)


# ------------------------------------------------------------------ 3. the exact parking pose

def parking_pose(epsilon: float, max_curvature: float) -> NDArray[np.float64]:
    """The pose (x, y, theta) after the car's four full-lock moves of epsilon metres each
    (forward left, forward right, back left, back right) from the origin facing +x."""
    return nonholonomic.parallel_parking([0.0, 0.0, 0.0], epsilon, max_curvature)[-1]


def _leading_order(epsilon, max_curvature):
    return np.array([0.0, 2.0 * max_curvature * epsilon**2, 0.0])


def _forward_only(epsilon, max_curvature):
    twists = [[1.0, 0.0, max_curvature], [1.0, 0.0, -max_curvature]]
    return frames.integrate_twist(twists, epsilon)[-1]


Exercise(
    "controllability.parking_pose",
    "The exact pose (x, y, theta) (m, m, rad) of the car after four full-lock moves of "
    "epsilon metres each (forward at left lock, forward at right lock, back at left lock, "
    "back at right lock), curvature max_curvature (1/m) at lock, from the origin facing +x.",
    parking_pose,
    [Case((0.2, CAR_CURVATURE)), Case((0.05, CAR_CURVATURE)), Case((0.4, 0.5)),
     Case((0.3, 2.0))],
    wheel_names=("x", "y", "theta"),
    mistakes=[
        (_leading_order, "that is the leading order, epsilon^2 [f_L, f_R]: the exact arcs end "
                         "a little short of it. Compose the four arcs (each a constant twist "
                         "held for epsilon, an arc about its ICR)."),
        (_forward_only, "that is where the two forward moves end; the two backward moves "
                        "(twists (-1, 0, -kappa) then (-1, 0, kappa)) follow."),
    ],
)


# ------------------------------------------------------------------ 4. design: a parking plan

def _excursion(epsilon: float, max_curvature: float) -> float:
    """How far ahead of its start the rear-axle midpoint goes during one manoeuvre, m."""
    k = max_curvature
    twists = ([[1.0, 0.0, k]] * 50 + [[1.0, 0.0, -k]] * 50 + [[-1.0, 0.0, -k]] * 50
              + [[-1.0, 0.0, k]] * 50)
    path = frames.integrate_twist(twists, epsilon / 50)
    return float(path[:, 0].max())


def parking_plan(shift: float, room: float, max_curvature: float) -> NDArray[np.float64]:
    """Design: a move length epsilon (m) and a whole number of repetitions, count, of the car's
    four-move manoeuvre that shift it ``shift`` metres to its left (within 5 mm), while its
    rear-axle midpoint never goes more than ``room`` metres ahead of its start.

    One plan (the fewest repetitions): the longest move that fits, 2 sin(k eps)/k <= room,
    sets count = ceil(shift / s(eps)); then eps is shortened until count exact shifts
    s(eps) = 8 sin(k eps / 2)^2 / k add up to ``shift``.
    """
    k = max_curvature
    longest = math.asin(min(1.0, k * room / 2)) / k
    count = max(1, math.ceil(shift / nonholonomic.parking_shift(longest, k) - 1e-12))
    epsilon = 2.0 / k * math.asin(math.sqrt(k * shift / (8 * count)))
    return np.array([epsilon, float(count)])


def _leading_order_plan(shift, room, max_curvature):
    k = max_curvature
    longest = math.asin(min(1.0, k * room / 2)) / k
    n = max(1, math.ceil(shift / (2 * k * longest**2)))
    return np.array([math.sqrt(shift / (2 * k * n)), float(n)])


def _room_as_move(shift, room, max_curvature):
    k = max_curvature
    n = max(1, math.ceil(shift / nonholonomic.parking_shift(room, k)))
    return np.array([2.0 / k * math.asin(math.sqrt(k * shift / (8 * n))), float(n)])


class PlanExercise(Exercise):
    """A parking plan (epsilon, count) is judged by driving it, not by comparing numbers: it
    passes a case when count is a whole number in [1, 1000], one manoeuvre's rear-axle
    excursion fits the room, and count exact shifts end within 5 mm of the asked shift. The
    reference (the plan with the fewest repetitions) serves the diagnoses of unit and order
    mistakes."""

    def _passed(self) -> str:
        return (f"✔ {self.name}: every plan ends within {1000 * SHIFT_TOLERANCE:g} mm of the "
                f"asked shift and stays in its room, on all {len(self.cases)} cases.")

    def _judge(self, case: Case, where: str, raw: Any) -> CheckResult | None:
        try:
            got = np.asarray(raw, dtype=float)
        except (TypeError, ValueError):
            return self._fail("shape", f"for {where} you returned {raw!r}: a plan is two "
                              "numbers, (epsilon, count)")
        if got.shape != (2,):
            return self._fail("shape", f"for {where} you returned shape {got.shape}: a plan "
                              "is two numbers, (epsilon, count)")
        if not np.all(np.isfinite(got)):
            return self._fail("nan", f"for {where} your plan contains NaN or infinity: "
                              f"{got.tolist()}")
        shift, room, k = (float(a) for a in case.args)
        expected = np.asarray(self.reference(*case.args), dtype=float)
        epsilon, count = float(got[0]), float(got[1])
        head = f"for {where} you returned epsilon = {epsilon:.6g} m, count = {count:g}"
        if epsilon <= 0 or count <= 0:
            return self._fail("sign", f"{head}: both must be positive (moves of epsilon "
                              "metres forward first, then back; count manoeuvres).")
        if np.allclose(got, expected[::-1], rtol=1e-6):
            return self._fail("swapped", f"{head}: epsilon and count are swapped; "
                              "return (epsilon, count).")
        for factor, text in UNIT_FACTORS:
            if np.allclose(got, factor * expected, rtol=1e-4):
                return self._fail("units", f"{head}: {text}")
        why = self._mistake(case, got)
        if count != round(count) or not 1 <= count <= MAX_REPETITIONS:
            return self._fail("wrong", f"{head}: count must be a whole number of manoeuvres, "
                              f"from 1 to {MAX_REPETITIONS}.")
        ahead = _excursion(epsilon, k)
        if ahead > room + 1e-9:
            return self._fail("specific" if why else "wrong",
                              f"{head}: each manoeuvre takes the rear axle {ahead:.3f} m "
                              f"ahead, more than the room of {room:g} m"
                              + (f": {why}" if why else "."))
        reached = count * nonholonomic.parking_shift(epsilon, k)
        if abs(reached - shift) > SHIFT_TOLERANCE:
            return self._fail("specific" if why else "wrong",
                              f"{head}: the plan shifts the car {reached:.4f} m, "
                              f"{1000 * (reached - shift):+.1f} mm from the asked {shift:g} m"
                              + (f": {why}" if why else "."))
        return None

    def _mistake(self, case: Case, got: np.ndarray) -> str | None:
        for wrong, text in self.mistakes:
            try:
                candidate = np.asarray(wrong(*case.args, **case.kwargs), dtype=float)
            except Exception:  # a mistake model that cannot run on this case is skipped
                continue
            if candidate.shape == got.shape and np.allclose(got, candidate, rtol=1e-6):
                return text
        return None


PlanExercise(
    "controllability.parking_plan",
    "Design: (epsilon, count), a move length epsilon (m) and a whole number, count, of "
    "the car's four-move full-lock manoeuvres (curvature max_curvature, 1/m) that shift it "
    "`shift` metres to its left within 5 mm, its rear axle never more than `room` metres "
    "ahead of its start.",
    parking_plan,
    [Case((0.45, 1.00, CAR_CURVATURE)), Case((0.50, 0.30, CAR_CURVATURE)),
     Case((0.25, 0.40, CAR_CURVATURE)), Case((1.00, 1.50, 0.4))],
    mistakes=[
        (_leading_order_plan, "the plan trusts the leading order, a shift of "
                              "2 kappa epsilon^2 per manoeuvre. With long moves the exact "
                              "shift, 8 sin(kappa epsilon / 2)^2 / kappa, is noticeably "
                              "shorter: use it."),
        (_room_as_move, "the room is not the length of one move: the two forward moves take "
                        "the rear axle 2 sin(kappa epsilon)/kappa ahead, about twice "
                        "epsilon."),
    ],
)
