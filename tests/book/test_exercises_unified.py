"""The unified chapter's exercises: references against hand calculations and textbook
mobility numbers; every mistake named."""

from __future__ import annotations

import math

import numpy as np


def test_exercise_references_agree_with_hand_calculations():
    from wheelkin.exercises import unified as ex

    # a wheel at (0.2, 0.1) rolling along x: contact velocity (vx - 0.1 w, vy + 0.2 w)
    np.testing.assert_allclose(ex.wheel_rows(0.2, 0.1, 0.0), [[1, 0, -0.1], [0, 1, 0.2]],
                               atol=1e-15)
    # rolling along y (psi = 90 deg) at (0.3, 0): e = (0, 1), n = (-1, 0)
    np.testing.assert_allclose(ex.wheel_rows(0.3, 0.0, math.pi / 2), [[0, 1, 0.3], [-1, 0, 0]],
                               atol=1e-15)
    # Siegwart et al.'s tricycle (steered front: delta_M = 2); a caster front leaves a
    # differential drive; a fixed front wheel off the rear axle leaves straight driving only
    assert tuple(ex.tricycle_mobility("steered")) == (1, 1, 2)
    assert tuple(ex.tricycle_mobility("caster")) == (2, 0, 2)
    assert tuple(ex.tricycle_mobility("swedish")) == (2, 0, 2)
    assert tuple(ex.tricycle_mobility("fixed")) == (1, 0, 1)
    # omni wheel at angle alpha rolling along alpha + 90 deg: phi = (-sin a vx + cos a vy + L w)/r
    alpha = np.array([0.0, 2 * math.pi / 3, 4 * math.pi / 3])
    vx, vy, w, r, L = 0.3, -0.2, 0.8, 0.04, 0.25
    np.testing.assert_allclose(ex.omni_rates(vx, vy, w, r, L),
                               (-np.sin(alpha) * vx + np.cos(alpha) * vy + L * w) / r, atol=1e-12)
    np.testing.assert_allclose(ex.skid_steer_slip(0.3, 2.0, 0.06, 0.05), [0.1, 0.1, -0.1, -0.1],
                               atol=1e-15)
    # the design exercise, counted by hand: the omni base (3, 0) with 3 motors can do all a
    # swerve base (1, 2) does; a differential drive (2, 0) all a tricycle (1, 1) does, with 2
    names = [text.split(":")[0] for text, _, _ in ex.CANDIDATES]
    assert names[ex.choose_design(3, 0)] == names[ex.choose_design(1, 2)] == "omni base"
    assert names[ex.choose_design(2, 0)] == names[ex.choose_design(1, 1)] == "differential drive"
    assert ex.choose_design(3, 1) == -1  # no design reaches four twist directions


def test_exercises_pass_their_references_and_name_each_mistake():
    from wheelkin.exercises import all_exercises

    exercises = {n: e for n, e in all_exercises().items() if n.startswith("unified.")}
    assert len(exercises) >= 3
    for name, exercise in exercises.items():
        assert exercise.check(exercise.reference).passed, name
        for wrong, text in exercise.mistakes:
            result = exercise.check(wrong)
            assert not result.passed and result.kind == "specific", (name, result.message)
            assert text in result.message

        def stub(*args):
            raise NotImplementedError

        assert exercise.check(stub).kind == "not-written"
