"""The sandbox chapter's exercise (wheelkin.exercises.sandbox) and its live panel's grip edge.

The exercise's reference is a closed form; it is checked here against the sandbox itself (the
shortest gripping ramp found by bisection on sandbox runs), and the check is tried on a right
answer, on the usual wrong ones and on answers that are right by a margin.
"""

from __future__ import annotations

import math

import pytest

from wheelkin.exercises import check, get
from wheelkin.exercises.sandbox import _ramp_time, _slips, grip_ramp_time
from wheelkin.sandbox.vehicles import GRAVITY

NAME = "sandbox.grip_ramp_time"


def shortest_gripping_ramp(v, omega, mu):
    """The shortest ramp (s) that the sandbox drives without a slip, by bisection."""
    lo, hi = 0.0, 5.0
    assert not _slips(v, omega, mu, hi)
    for _ in range(20):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _slips(v, omega, mu, mid) else (lo, mid)
    return hi


@pytest.mark.parametrize("case", [(0.5, 3.0, 0.8), (0.4, 0.0, 0.1), (0.0, 6.0, 0.3),
                                  (0.4, -2.0, 0.3)])
def test_closed_form_grips_and_is_close_to_the_sandboxs_shortest_ramp(case):
    simulated = shortest_gripping_ramp(*case)
    formula = grip_ramp_time(*case)
    # The friction circle at the ramp's end is the tightest moment: the closed form may be a
    # little long (the sandbox's wheels share the load dynamically), never short.
    assert simulated * (1 - 1e-3) <= formula <= 1.05 * simulated


def test_straight_ramp_is_the_friction_limit_by_hand():
    # v = 0.4 m/s straight on mu = 0.1: each track pushes m v / (2 T) <= 0.5 mu m g.
    assert grip_ramp_time(0.4, 0.0, 0.1) == pytest.approx(0.4 / (2 * 0.5 * 0.1 * GRAVITY))


def test_no_ramp_grips_beyond_the_steady_turns_edge():
    edge = 0.1 * GRAVITY / 0.4  # v |omega| = mu g: the two tracks carry the whole weight
    assert grip_ramp_time(0.4, 0.99 * edge, 0.1) < math.inf
    assert grip_ramp_time(0.4, 1.01 * edge, 0.1) == math.inf
    assert grip_ramp_time(0.4, -1.01 * edge, 0.1) == math.inf


@pytest.mark.parametrize(("args", "name"), [((0.4, 1.0, 0.0), "mu"), ((0.4, 1.0, -0.1), "mu"),
                                            ((-0.1, 1.0, 0.5), "v"),
                                            ((0.4, math.nan, 0.5), "omega")])
def test_bad_input_names_the_parameter(args, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        grip_ramp_time(*args)


def test_right_answers_pass_including_a_modest_margin():
    assert check(NAME, grip_ramp_time).passed
    assert check(NAME, lambda v, omega, mu: 1.3 * grip_ramp_time(v, omega, mu)).passed


@pytest.mark.parametrize(("wrong", "words"), [
    (lambda v, omega, mu: _ramp_time(v, omega, mu, turn=False), "share one friction circle"),

    (lambda v, omega, mu: _ramp_time(v, omega, mu, share=1.0), "carries half"),
    (lambda v, omega, mu: _ramp_time(v, omega, mu, inertia=False), "yaw acceleration"),
    (lambda v, omega, mu: 2.0 * grip_ramp_time(v, omega, mu), "longer than needed"),
    (lambda v, omega, mu: 0.5 * grip_ramp_time(v, omega, mu), "too short"),
])
def test_wrong_answers_fail_with_the_likely_mistake(wrong, words):
    result = check(NAME, wrong)
    assert not result.passed
    assert NAME in result.message and words in result.message, result.message


def test_infinity_is_judged_both_ways():
    always_inf = check(NAME, lambda v, omega, mu: math.inf)
    assert not always_inf.passed and "a ramp grips here" in always_inf.message

    def never_inf(v, omega, mu):
        t = grip_ramp_time(v, omega, mu)
        return 10.0 if t == math.inf else t

    result = check(NAME, never_inf)
    assert not result.passed and "return math.inf" in result.message


def test_stub_and_non_numbers_get_a_message():
    def stub(v, omega, mu):
        raise NotImplementedError

    assert check(NAME, stub).kind == "not-written"
    assert check(NAME, lambda v, omega, mu: None).kind == "shape"
    assert check(NAME, lambda v, omega, mu: "1 s").kind == "shape"
    assert check(NAME, lambda v, omega, mu: -1.0).kind == "sign"


def test_exercise_is_registered_with_a_prompt():
    exercise = get(NAME)
    assert "math.inf" in exercise.prompt and len(exercise.cases) == 8


@pytest.mark.parametrize(("omega", "slips"), [(0.0, False), (2.25, False), (2.5, True)])
def test_slip_panel_edge_is_the_steady_turns_friction_limit(omega, slips):
    # v omega <= mu g grips: at v = 0.4 m/s, mu = 0.1 the edge is 2.45 rad/s (the sandbox's
    # Zumo rests on its two tracks alone, so all of its weight gives grip).
    from wheelkin.widgets.sandbox import SPEED, _run

    assert (SPEED * omega > 0.1 * GRAVITY) == slips
    _, _, slipping, _, title = _run(0.1, omega)
    assert bool(slipping.any()) == slips
    assert ("off the model by 0.0 cm" in title) == (not slips)
