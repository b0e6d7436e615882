"""The differential-drive chapter's exercises: each reference passes, a stub says it is not
written yet, and the anticipated mistakes are named."""

from __future__ import annotations

import pytest

from wheelkin import diffdrive as dd
from wheelkin.exercises import check, get

EXERCISES = ["diffdrive.wheel_speeds", "diffdrive.wheel_speeds_steps", "diffdrive.omega_limit",
             "diffdrive.count_time"]


@pytest.mark.parametrize("name", EXERCISES)
def test_exercise_reference_passes_and_stub_is_friendly(name):
    ex = get(name)
    assert check(name, ex.reference).passed

    def stub(*args):
        raise NotImplementedError

    result = check(name, stub)
    assert not result.passed and result.kind == "not-written"


@pytest.mark.parametrize("name", EXERCISES)
def test_exercise_mistakes_are_diagnosed(name):
    ex = get(name)
    assert len(ex.mistakes) >= 2
    for wrong, text in ex.mistakes:
        result = check(name, wrong)
        assert not result.passed
        assert text in result.message


def test_exercise_swapped_wheels_are_named():
    def swapped(v, omega, track_width):
        left, right = dd.wheel_speeds(v, omega, track_width)
        return right, left

    result = check("diffdrive.wheel_speeds", swapped)
    assert result.kind == "swapped" and "v_left and v_right" in result.message
