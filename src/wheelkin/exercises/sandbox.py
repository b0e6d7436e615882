"""Exercises of the chapter "The sandbox" (checked by running the sandbox itself).

``sandbox.grip_ramp_time``: the Radon Ulzer starts at rest and must reach the body twist
``(v, 0, omega)`` by a linear ramp of length ``T`` (the command ``(v, 0, omega) * min(t/T, 1)``)
on a floor of friction coefficient ``mu``, with no wheel slipping at any step. The student's
function returns a ``T`` that grips and is at most 1.5 times the shortest ramp that grips, or
``math.inf`` when no ramp grips. The check does not compare with a formula: it runs the
sandbox with the student's ramp (no wheel may slip) and with a ramp 1.5 times shorter (a wheel
must slip), and decides "no ramp grips" by whether the steady turn itself slips.

>>> import math
>>> from wheelkin.exercises import check
>>> check("sandbox.grip_ramp_time", lambda v, omega, mu: 1.0).passed
False
>>> check("sandbox.grip_ramp_time", grip_ramp_time).passed
True
"""

from __future__ import annotations

import math
from typing import Any

from wheelkin.exercises import UNIT_FACTORS, Case, CheckResult, Exercise, _fmt
from wheelkin.sandbox import RADON_ULZER, World
from wheelkin.sandbox.vehicles import GRAVITY

__all__ = ["RampExercise", "grip_ramp_time"]

#: The Radon Ulzer's track width W (m): its driven wheels are W/2 either side of the centre.
TRACK = 0.085
#: Share of the weight on each driven wheel: the sandbox's Zumo rests on its two tracks alone.
DRIVEN_SHARE = 0.5
#: How much shorter a ramp the check tries to show that the answer is not needlessly long.
SLACK = 1.5
#: How long the check keeps the final command after the ramp, s.
HOLD = 0.5


def _check_inputs(v: float, omega: float, mu: float) -> None:
    if not (math.isfinite(v) and v >= 0):
        raise ValueError(f"v must be a finite speed >= 0 m/s, got {v!r}")
    if not math.isfinite(omega):
        raise ValueError(f"omega must be a finite yaw rate in rad/s, got {omega!r}")
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"mu must be a finite friction coefficient > 0, got {mu!r}")


def _ramp_time(v: float, omega: float, mu: float, share: float = DRIVEN_SHARE,
               inertia: bool = True, turn: bool = True) -> float:
    """The shortest ramp by the friction circle of one driven wheel at the ramp's end (the
    closed form; the keyword arguments switch parts off to model the usual mistakes)."""
    m, inertia_ = RADON_ULZER.mass, RADON_ULZER.inertia
    cap = share * mu * m * GRAVITY  # the largest push of one driven wheel, N
    side = m * v * abs(omega) / 2 if turn else 0.0  # its share of the centripetal push, N
    if side >= cap:
        return math.inf
    ahead = m * v / 2 + (inertia_ * abs(omega) / TRACK if inertia else 0.0)  # N s
    return ahead / math.sqrt(cap**2 - side**2)


def grip_ramp_time(v: float, omega: float, mu: float) -> float:
    """The shortest linear ramp (s) that takes the Radon Ulzer from rest to the body twist
    ``(v, 0, omega)`` on friction ``mu`` without a wheel slipping; ``math.inf`` if none does.

    At the end of the ramp each driven wheel (one track, half the weight) must push forward
    ``m v/(2T) + I|omega|/(T W)`` and sideways ``m v |omega| / 2``, together inside its friction
    circle of radius ``0.5 mu m g``:
    ``T = (m v/2 + I|omega|/W) / sqrt((0.5 mu m g)^2 - (m v omega/2)^2)``.

    >>> round(grip_ramp_time(0.5, 3.0, 0.8), 3)
    0.076
    >>> grip_ramp_time(0.4, 2.5, 0.1)
    inf
    """
    v, omega, mu = float(v), float(omega), float(mu)
    _check_inputs(v, omega, mu)
    return _ramp_time(v, omega, mu)


def _slips(v: float, omega: float, mu: float, ramp: float) -> bool:
    """Whether a wheel of the Radon Ulzer slips at any step of the ramp ``ramp`` (s) from rest
    to ``(v, 0, omega)`` on friction ``mu``, or in the ``HOLD`` seconds after it."""
    world = World()
    robot = world.add(RADON_ULZER.replace(mu=mu))

    def command(t, _world):
        s = 1.0 if ramp <= 0 else min(t / ramp, 1.0)
        robot.command_twist(v * s, 0.0, omega * s)

    return bool(world.run(ramp + HOLD, command, record_every=1).slipping.any())


def _steady_turn_slips(v: float, omega: float, mu: float) -> bool:
    """Whether the steady turn ``(v, 0, omega)`` itself slips (then no ramp can grip)."""
    world = World()
    robot = world.add(RADON_ULZER.replace(mu=mu), twist=(v, 0.0, omega))
    robot.command_twist(v, 0.0, omega)
    return bool(world.run(HOLD, record_every=1).slipping.any())


class RampExercise(Exercise):
    """An exercise whose answer is judged by running the sandbox, not by comparing numbers.

    The answer ``T`` passes a case when the ramp of length ``T`` grips and the ramp of length
    ``T / SLACK`` slips (so ``T`` is no more than ``SLACK`` times the shortest gripping ramp);
    when the steady turn slips, only ``math.inf`` passes. ``reference`` (the closed form)
    and ``mistakes`` serve the messages only. Each case runs the sandbox for the ramp asked,
    so the grader grants this judge more time than a comparison needs.
    """

    judge_seconds = 30.0

    def _passed(self) -> str:
        return (f"✔ {self.name}: every ramp grips and none is more than {SLACK:g}× longer "
                f"than needed, on all {len(self.cases)} cases (each run in the sandbox).")

    def _judge(self, case: Case, where: str, raw: Any) -> CheckResult | None:
        try:
            ramp = float(raw)
        except (TypeError, ValueError):
            return self._fail("shape", f"for {where} you returned {raw!r}, which is not a "
                              "number (a ramp time in seconds)")
        v, omega, mu = (float(x) for x in case.args)
        head = f"for {where} you returned T = {_fmt(ramp)}"
        if math.isnan(ramp):
            return self._fail("nan", f"{head}: a ramp time must be a number, not NaN.")
        if ramp < 0:
            return self._fail("sign", f"{head}: a ramp time cannot be negative.")
        side, grip = v * abs(omega), 2 * DRIVEN_SHARE * mu * GRAVITY
        if _steady_turn_slips(v, omega, mu):
            if ramp == math.inf:
                return None
            return self._fail("specific", f"{head}, but no ramp grips here: even the steady "
                              f"turn needs v|ω| = {side:.3g} m/s² sideways, more than the "
                              f"{grip:.3g} m/s² the driven wheels can give; return math.inf.")
        if ramp == math.inf:
            return self._fail("nan", f"{head}, but a ramp grips here: the steady turn "
                              f"needs v|ω| = {side:.3g} m/s² sideways, less than the "
                              f"{grip:.3g} m/s² the driven wheels can give.")
        shortest = float(self.reference(v, omega, mu))
        for factor, text in UNIT_FACTORS:  # a factor of 2 is left to the sandbox's verdict
            if (abs(math.log(factor)) > math.log(3) and shortest > 0
                    and math.isclose(ramp, factor * shortest, rel_tol=1e-3)):
                return self._fail("units", f"{head}: {text}")
        if _slips(v, omega, mu, ramp):
            why = self._mistake(case, ramp)
            return self._fail("specific" if why else "wrong",
                              f"{head}, and a wheel slips during that ramp in the sandbox"
                              + (f": {why}" if why else ": the ramp is too short."))
        if not _slips(v, omega, mu, ramp / SLACK):
            return self._fail("specific", f"{head}: it grips, but so does a ramp {SLACK:g}× "
                              f"shorter, so yours is more than {SLACK:g}× longer than needed "
                              f"(the shortest is about {_fmt(self.reference(v, omega, mu))} s).")
        return None

    def _mistake(self, case: Case, ramp: float) -> str | None:
        for wrong, text in self.mistakes:
            try:
                candidate = float(wrong(*case.args, **case.kwargs))
            except Exception:  # a mistake model that cannot run on this case is skipped
                continue
            if math.isclose(ramp, candidate, rel_tol=1e-3, abs_tol=1e-9):
                return text
        return None


RampExercise(
    "sandbox.grip_ramp_time",
    "The length T (s) of a linear ramp from rest to the twist (v, 0, omega) that the Radon "
    "Ulzer drives on friction mu without a wheel slipping, at most 1.5 times the shortest "
    "such ramp; math.inf when no ramp grips. It may use RADON_ULZER (its mass and inertia), "
    "no other part of the library.",
    grip_ramp_time,
    [Case((0.5, 3.0, 0.8)), Case((0.4, 1.0, 0.1)), Case((0.4, 0.0, 0.1)),
     Case((0.4, -2.0, 0.3)), Case((0.0, 6.0, 0.3)), Case((0.6, 4.0, 0.5)),
     Case((0.4, 2.5, 0.1)), Case((0.5, 2.98, 0.2))],
    library=("wheelkin.sandbox.RADON_ULZER",),
    mistakes=[
        (lambda v, omega, mu: _ramp_time(v, omega, mu, turn=False),
         "the turn is ignored. Driving and turning share one friction circle: the sideways "
         "push m v ω / 2 of each driven wheel leaves less grip for speeding up."),
        (lambda v, omega, mu: _ramp_time(v, omega, mu, inertia=False),
         "the yaw acceleration is forgotten. Spinning the body up to ω needs a torque: each "
         "driven wheel pushes an extra I|ω|/(T W) along its rolling direction (a spin on the "
         "spot needs a ramp too)."),
        (lambda v, omega, mu: _ramp_time(v, omega, mu, share=1.0),
         "the whole weight is given to each wheel. Each of the two driven wheels carries half "
         "the weight, so its circle has radius 0.5 μ m g."),
    ],
)
