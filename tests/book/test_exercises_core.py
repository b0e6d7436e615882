"""Tests for the exercise machinery (wheelkin.exercises) and chapter 1's exercises.

Every diagnosis kind is provoked on purpose by a wrong answer written for it, and the message
is checked to say the right thing in plain words. The checker must never raise.
"""

import math

import numpy as np
import pytest

from wheelkin.exercises import (
    UNIT_FACTORS,
    Case,
    CheckResult,
    Exercise,
    all_exercises,
    check,
    get,
)
from wheelkin.frames import Pose


def scale(x, y):
    return 2.0 * x + y


def wheels(v, w):
    """Four 'wheel speeds' FL, FR, RL, RR of a made-up vehicle (distinct for the cases)."""
    return [v - w, v + w, v - 2 * w, v + 2 * w]


def make(reference=scale, cases=None, **kwargs):
    cases = cases or [Case((1.0, 0.5)), Case((3.0, -1.0))]
    return Exercise("test.demo", "Demo.", reference, cases, register=False, **kwargs)


def not_written(*args):
    raise NotImplementedError


# --------------------------------------------------------------------------------------------
# One test per diagnosis kind
# --------------------------------------------------------------------------------------------


def test_pass():
    r = make().check(lambda x, y: 2 * x + y)
    assert r.passed and bool(r) and r.kind == "pass"
    assert r.message == "✔ test.demo: correct on all 2 cases."
    r.assert_passed()


def test_not_written():
    r = make().check(not_written)
    assert not r.passed and r.kind == "not-written"
    assert "not written yet" in r.message and "NotImplementedError" in r.message


def test_raised_names_the_case_and_the_error():
    r = make().check(lambda x, y: [1, 2][5])
    assert r.kind == "raised"
    assert "for x=1, y=0.5 your function raised IndexError" in r.message
    assert make().check("not a function").kind == "raised"


@pytest.mark.parametrize(
    ("answer", "text"),
    [
        (lambda x, y: [2 * x + y, 0.0], "you returned shape (2,)"),
        (lambda x, y: "three", "which is not a number"),
        (lambda x, y: None, "forget the 'return'"),
        (lambda x, y: {"a": 1}, "which is not a number"),
    ],
)
def test_shape(answer, text):
    r = make().check(answer)
    assert r.kind == "shape"
    assert text in r.message


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_nan_or_infinity(bad):
    r = make().check(lambda x, y: bad)
    assert r.kind == "nan"
    assert "NaN or infinity" in r.message


def test_infinity_is_right_where_the_reference_is_infinite():
    ex = make(reference=lambda r: -r, cases=[Case((math.inf,)), Case((2.0,))])
    assert ex.check(lambda r: -r).passed
    wrong = ex.check(lambda r: r)
    assert wrong.kind == "sign"


def test_sign_scalar_and_vector():
    assert make().check(lambda x, y: -(2 * x + y)).kind == "sign"
    ex = make(reference=wheels, wheel_names=("FL", "FR", "RL", "RR"))
    r = ex.check(lambda v, w: [-s for s in wheels(v, w)])
    assert r.kind == "sign" and "the sign is wrong" in r.message


def test_sign_of_some_elements_is_named():
    ex = make(reference=wheels, wheel_names=("FL", "FR", "RL", "RR"))
    r = ex.check(lambda v, w: [s if i != 2 else -s for i, s in enumerate(wheels(v, w))])
    assert r.kind == "sign"
    assert "the sign of RL is wrong" in r.message


def test_swapped_pair_is_named():
    ex = make(reference=wheels, wheel_names=("FL", "FR", "RL", "RR"))

    def swap_fl_fr(v, w):
        s = wheels(v, w)
        return [s[1], s[0], s[2], s[3]]

    r = ex.check(swap_fl_fr)
    assert r.kind == "swapped"
    assert "FL and FR are swapped" in r.message


def test_swapped_halves_and_reversed_order():
    ex = make(reference=lambda a: [a, 2 * a, 3 * a, 5 * a], cases=[Case((1.0,))])
    halves = ex.check(lambda a: [3 * a, 5 * a, a, 2 * a])
    assert halves.kind == "swapped" and "two halves" in halves.message
    ex3 = make(reference=lambda a: [a, 2 * a, 4 * a], cases=[Case((1.0,))])
    rev = ex3.check(lambda a: [4 * a, 2 * a, a])
    assert rev.kind == "swapped" and "swapped" in rev.message  # a reversal of 3 is a pair swap
    ex5 = make(reference=lambda a: [a, 2 * a, 4 * a, 8 * a, 16 * a], cases=[Case((1.0,))])
    rev5 = ex5.check(lambda a: [16 * a, 8 * a, 4 * a, 2 * a, a])
    assert rev5.kind == "swapped" and "the order is reversed" in rev5.message


@pytest.mark.parametrize(("factor", "text"), UNIT_FACTORS)
def test_units_every_factor(factor, text):
    r = make().check(lambda x, y: factor * (2 * x + y))
    assert r.kind == "units"
    assert r.message.endswith(text)


def test_units_on_a_vector():
    ex = make(reference=wheels)
    r = ex.check(lambda v, w: [1000 * s for s in wheels(v, w)])
    assert r.kind == "units" and "factor of 1000" in r.message


def test_specific_mistake_comes_first():
    ex = make(mistakes=[(lambda x, y: -(2 * x + y), "you measured x the other way.")])
    r = ex.check(lambda x, y: -(2 * x + y))
    assert r.kind == "specific"  # before the generic sign message
    assert r.message.endswith("you measured x the other way.")


def test_a_mistake_model_that_fails_is_skipped():
    ex = make(mistakes=[(lambda x, y: 1 / 0, "never shown")])
    r = ex.check(lambda x, y: 7.0)
    assert r.kind == "wrong"


def test_wrong():
    r = make().check(lambda x, y: x + y + 0.123)
    assert r.kind == "wrong"
    assert r.message == "✘ test.demo: for x=1, y=0.5 you returned 1.623, expected 2.5."


# --------------------------------------------------------------------------------------------
# Robustness
# --------------------------------------------------------------------------------------------


def test_dataclass_answers_are_accepted():
    ex = make(reference=lambda x: Pose(x, 0.0, 0.0).as_array(), cases=[Case((1.0,))])
    assert ex.check(lambda x: Pose(x, 0.0, 0.0)).passed
    assert ex.check(lambda x: (x, 0.0, 0.0)).passed


def test_student_cannot_corrupt_the_cases():
    data = np.array([1.0, 2.0])
    ex = make(reference=lambda a: float(np.sum(a)), cases=[Case((data,)), Case((data,))])

    def mutating(a):
        total = float(np.sum(a))
        a *= 100  # a student mutates the input in place
        return total

    assert ex.check(mutating).passed
    assert data.tolist() == [1.0, 2.0]


def test_kwargs_cases_are_described():
    ex = make(cases=[Case((1.0,), {"y": 2.0})])
    r = ex.check(lambda x, y: 0.0)
    assert "for x=1, y=2 you returned 0" in r.message


def test_check_never_raises_on_strange_returns():
    for answer in (lambda x, y: object(), lambda x, y: [[1, 2], [3]], lambda x, y: 1j,
                   lambda x, y: (i for i in range(3))):
        r = make().check(answer)
        assert isinstance(r, CheckResult) and not r.passed


def test_result_display():
    ok = make().check(lambda x, y: 2 * x + y)
    bad = make().check(lambda x, y: 0.0)
    assert repr(ok) == ok.message
    assert "#1a7f37" in ok._repr_html_() and "#b35900" in bad._repr_html_()
    assert "&lt;" in make(cases=[Case(("<",))], reference=lambda s: 1.0).check(
        lambda s: 2.0)._repr_html_()
    with pytest.raises(AssertionError, match=r"expected 2\.5"):
        bad.assert_passed()


def test_registry():
    with pytest.raises(ValueError, match=r"no exercise named 'nope\.none'; known: .*conventions"):
        get("nope.none")
    ex = get("conventions.icr")
    with pytest.raises(ValueError, match="already registered"):
        Exercise("conventions.icr", "again", ex.reference, ex.cases)
    with pytest.raises(ValueError, match="at least one Case"):
        Exercise("test.empty", "x", scale, [], register=False)
    assert "conventions.icr" in all_exercises()


# --------------------------------------------------------------------------------------------
# Chapter 1's exercises: the reference passes, a stub says "not written", each modelled
# mistake is recognised with its own message, and the answers are right by hand.
# --------------------------------------------------------------------------------------------

CONVENTIONS = ["conventions.rover_radius", "conventions.firmware_pose", "conventions.icr",
               "conventions.encoder_steps", "conventions.mecanum_twist"]


@pytest.mark.parametrize("name", CONVENTIONS)
def test_conventions_exercise(name):
    ex = get(name)
    assert check(name, ex.reference).passed
    assert check(name, not_written).kind == "not-written"
    assert len(ex.mistakes) >= 3
    for wrong, text in ex.mistakes:
        r = check(name, wrong)
        assert r.kind == "specific", (name, r.message)
        assert r.message.endswith(text)


def test_conventions_answers_by_hand():
    assert get("conventions.rover_radius").reference(30.0) == pytest.approx(-0.762)
    np.testing.assert_allclose(get("conventions.firmware_pose").reference(-100.0, 2000.0, 0.5),
                               [2.0, 0.1, 0.5])
    np.testing.assert_allclose(get("conventions.icr").reference(1.0, 0.0, 0.5), [0.0, 2.0])
    assert get("conventions.encoder_steps").reference(909.72) == pytest.approx(0.113097)
    np.testing.assert_allclose(get("conventions.mecanum_twist").reference(1.0, 3.0, 0.5),
                               [0.9144, -0.3048, 0.5])
