"""The rover chapter's exercises: references pass and agree with hand values independent of
the library's shortcuts; stubs fail kindly; mistakes are named."""

from __future__ import annotations

import math

import numpy as np
import pytest

EXERCISES = ("rover.outer_back_speed", "rover.corner_angles", "rover.tightest_turn",
             "rover.normalised_wheel_speeds")


@pytest.mark.parametrize("name", EXERCISES)
def test_exercise_solution_passes_stub_fails_mistakes_named(name):
    from wheelkin.exercises import check, get

    ex = get(name)
    assert check(name, ex.reference).passed

    def stub(*args, **kwargs):
        raise NotImplementedError

    assert check(name, stub).kind == "not-written"
    assert ex.mistakes
    for wrong, text in ex.mistakes:
        result = check(name, wrong)
        assert not result.passed
        assert result.kind == "specific" and text in result.message


def test_exercise_references_are_independent_of_the_shortcuts():
    from wheelkin.exercises import rover as ex

    # Outer back wheel by hand at r = +-30: sqrt(10.5^2 + 37.254^2) / 40.073 * 100.
    hand = 100 * math.hypot(10.5, 37.254) / 40.073
    assert ex.outer_back_speed(30.0, 100.0) == pytest.approx(hand)
    assert ex.outer_back_speed(-30.0, 100.0) == pytest.approx(hand)
    # Tightest turn at 35 degrees, by hand.
    assert ex.tightest_turn(7.254, 10.5, 10.5, 35.0) == pytest.approx(
        7.254 + 10.5 / math.tan(math.radians(35)))
    # Corner angles with d2 != d3, by hand, in the book's sign (R = +40 in turns left, so
    # the left corners are inner: 40 - 6 = 34 in from the turning centre; d1 = 6, d2 = 14,
    # d3 = 9; order LF, RF, LB, RB; positive = turned left).
    want = [math.atan(9 / 34), math.atan(9 / 46), -math.atan(14 / 34), -math.atan(14 / 46)]
    np.testing.assert_allclose(ex.corner_angles_general(40.0, 6.0, 14.0, 9.0), want)
    # Normalised speeds: the fastest wheel gets the command, the ratios are kept.
    v = ex.normalised_wheel_speeds(40.0, 100.0, 7.254, 25.0, 25.0, 10.073)
    assert np.max(np.abs(v)) == pytest.approx(100.0)
    assert v[0] == pytest.approx(100.0)  # the outer front corner is the fastest here
