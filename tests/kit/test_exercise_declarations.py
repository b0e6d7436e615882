"""What every exercise declares for the grader (``wheelkin.exercises.Exercise``): hidden cases
that a memorised table of the visible answers fails, library parts that exist and that its
prompt names, and a check that never raises, whatever the answer."""

from __future__ import annotations

import copy
import importlib

import numpy as np
import pytest

from wheelkin.exercises import Case, all_exercises, get

EXERCISES = sorted(all_exercises())


def _graded(exercise, cases):
    graded = copy.copy(exercise)
    graded.cases = list(cases)
    return graded


#: Exercises whose inputs are a finite set the visible cases nearly cover: their hidden
#: cases are the rest of the set, the same every run.
FINITE = {"unified.tricycle_mobility": "four kinds of front wheel: three visible, one hidden"}


@pytest.mark.parametrize("name", EXERCISES)
def test_every_exercise_has_hidden_cases_drawn_anew_each_run(name):
    """Hidden cases exist, repeat no visible case, and depend on the run's random draw (the
    grader seeds it with a secret), so they cannot be computed in advance."""
    exercise = get(name)
    first = exercise.hidden_cases(np.random.default_rng(1))
    second = exercise.hidden_cases(np.random.default_rng(2))
    assert first, f"{name} has no hidden case"
    visible = {repr(c) for c in exercise.cases}
    assert not visible & {repr(c) for c in first + second}
    if name not in FINITE:
        assert {repr(c) for c in first} != {repr(c) for c in second}


@pytest.mark.parametrize("name", EXERCISES)
def test_a_memorised_answer_fails_the_hidden_cases(name):
    """A function that returns the visible cases' answers from a table passes the notebook's
    check and fails the grader's."""
    exercise = get(name)
    table = {repr(c): exercise.reference(*c.args, **c.kwargs) for c in exercise.cases}
    zero = np.zeros_like(np.asarray(next(iter(table.values())), dtype=float))

    def memorised(*args, **kwargs):
        return table.get(repr(Case(tuple(args), kwargs)), zero)

    assert exercise.check(memorised).passed, "the memorised table passes the visible cases"
    hidden = exercise.hidden_cases(np.random.default_rng(7))
    assert not _graded(exercise, list(exercise.cases) + hidden).check(memorised).passed


@pytest.mark.parametrize("name", [n for n in EXERCISES if get(n).library])
def test_declared_library_parts_exist_and_the_prompt_names_them(name):
    exercise = get(name)
    for part in exercise.library:
        module, _, attr = part.rpartition(".")
        assert hasattr(importlib.import_module(module), attr), part
        assert attr in exercise.prompt, f"{name}'s prompt does not name {attr}"


def test_a_bad_declaration_is_refused():
    with pytest.raises(ValueError, match="library must name parts of wheelkin"):
        from wheelkin.exercises import Exercise

        Exercise("demo.x", "x", lambda x: x, [Case((1.0,))], library=("numpy.sin",),
                 register=False)


def test_the_check_never_raises_even_when_its_judge_cannot_handle_the_answer():
    """The ramp's judge cannot simulate a ramp of a billion seconds (the sandbox refuses the
    duration): the check says so instead of raising."""
    result = get("sandbox.grip_ramp_time").check(lambda v, omega, mu: 1e9)
    assert not result.passed and "could not be checked" in result.message
