"""Every exercise check against the usual wrong answers (``wheelkin.exercises.all_exercises``):
wrong answers are built from each exercise's own reference and cases, so a new exercise is
covered as soon as it is registered: the reference negated ("sign"), two distinct elements of a
vector answer swapped ("swapped"; only where the answer is a vector), scaled by 1000, 25.4 or
180/pi ("units"), NaN or infinity ("nan"), a function that raises ("raised"), returns None or
the wrong shape ("shape"), is not written yet ("not-written"). Each must get its own diagnosis
(``CheckResult.kind``) — or an exercise-specific one where the chapter's author anticipated
that very mistake — and the check must never raise or print.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from wheelkin.exercises import CheckResult, all_exercises

EXERCISES = all_exercises()


# ----------------------------------------------------------------------------- exercises

def _array(value) -> np.ndarray:
    if hasattr(value, "as_array") and callable(value.as_array):
        value = value.as_array()
    return np.asarray(value, dtype=float)


def _swap(out: np.ndarray) -> np.ndarray:
    """``out`` with its first pair of distinct elements swapped (not merely negated)."""
    for i in range(out.size):
        for j in range(i + 1, out.size):
            swapped = out.copy()
            swapped[[i, j]] = swapped[[j, i]]
            if not np.allclose(swapped, out) and not np.allclose(swapped, -out):
                return swapped
    return out


def _reference_outputs(exercise) -> list[np.ndarray]:
    return [_array(exercise.reference(*c.args, **c.kwargs)) for c in exercise.cases]


def _wrong_answers(exercise) -> dict:
    """(expected kind, wrong function) by label, derived from the reference and the cases."""

    def reference(*args, **kwargs) -> np.ndarray:
        return _array(exercise.reference(*args, **kwargs))

    def scaled(factor):
        return lambda *a, **k: factor * reference(*a, **k)

    def raises(*args, **kwargs):
        raise ZeroDivisionError("division by zero")

    def not_written(*args, **kwargs):
        raise NotImplementedError

    outputs = _reference_outputs(exercise)
    nonzero = any(np.any(o != 0) for o in outputs)
    wrong = {
        "NaN": ("nan", lambda *a, **k: np.full_like(reference(*a, **k), np.nan)),
        "infinity": ("nan", lambda *a, **k: np.full_like(reference(*a, **k), np.inf)),
        "raises": ("raised", raises),
        "wrong signature": ("raised", lambda: 0.0),
        "not a function": ("raised", 42.0),
        "returns None": ("shape", lambda *a, **k: None),
        "one element too many": ("shape", lambda *a, **k: np.append(reference(*a, **k), 0.0)),
        "a string": ("shape", lambda *a, **k: "forty-two"),
        "ragged": ("shape", lambda *a, **k: [1.0, [2.0, 3.0]]),
        "not written": ("not-written", not_written),
    }
    if nonzero:  # a zero answer has no sign and no unit to get wrong
        wrong["sign"] = ("sign", lambda *a, **k: -reference(*a, **k))
        wrong["mm for m (x1000)"] = ("units", scaled(1000.0))
        wrong["mm for inches (x25.4)"] = ("units", scaled(25.4))
        wrong["degrees for radians"] = ("units", scaled(180.0 / math.pi))
    if any(o.ndim == 1 and not np.array_equal(_swap(o), o) for o in outputs):
        wrong["swapped"] = ("swapped", lambda *a, **k: _swap(reference(*a, **k)))
    return wrong


CASES = [(name, label) for name in sorted(EXERCISES)
         for label in _wrong_answers(EXERCISES[name])]


@pytest.mark.parametrize(("name", "label"), CASES)
def test_exercise_diagnoses_the_usual_wrong_answer(name, label, capfd):
    exercise = EXERCISES[name]
    kind, wrong = _wrong_answers(exercise)[label]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = exercise.check(wrong)
    assert isinstance(result, CheckResult) and not result.passed
    assert result.message.startswith(f"✘ {name}: ")
    anticipated = result.kind == "specific" and any(text in result.message
                                                    for _, text in exercise.mistakes)
    assert result.kind == kind or anticipated, (label, result.kind, result.message)
    if result.kind == "units" and label == "degrees for radians":
        assert "degrees" in result.message
    if kind == "swapped" and result.kind == "swapped":
        assert "swapped" in result.message
    assert not caught, [f"{w.category.__name__}: {w.message}" for w in caught]
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_every_exercise_accepts_its_reference_in_any_container():
    for name, exercise in EXERCISES.items():
        assert exercise.check(exercise.reference).passed, name

        def as_list(*args, _exercise=exercise, **kwargs):
            return _array(_exercise.reference(*args, **kwargs)).tolist()

        assert exercise.check(as_list).passed, name


def test_scalar_answers_are_not_asked_about_swapped_wheels():
    for name, exercise in EXERCISES.items():
        outputs = _reference_outputs(exercise)
        if all(o.ndim == 0 for o in outputs):
            assert "swapped" not in _wrong_answers(exercise), name
    # and every kind is exercised somewhere
    kinds = {kind for name in EXERCISES for kind, _ in _wrong_answers(EXERCISES[name]).values()}
    assert {"sign", "swapped", "units", "nan", "raised", "shape", "not-written"} <= kinds
