"""The mecanum chapter's exercises: references pass, stubs fail kindly, mistakes are named."""

from __future__ import annotations

import pytest

from wheelkin.exercises import all_exercises, check

MECANUM_EXERCISES = sorted(n for n in all_exercises() if n.startswith("mecanum."))


def test_at_least_three_exercises():
    assert len(MECANUM_EXERCISES) >= 3


@pytest.mark.parametrize("name", MECANUM_EXERCISES)
def test_exercise_reference_passes_stub_fails_and_mistakes_are_named(name):
    ex = all_exercises()[name]
    assert check(name, ex.reference).passed

    def stub(*args):
        raise NotImplementedError

    result = check(name, stub)
    assert not result.passed and result.kind == "not-written"
    for wrong, text in ex.mistakes:
        got = check(name, wrong)
        assert not got.passed and text in got.message, (name, text, got.message)
