"""The waypoint lab's exercises: references pass, and the lab's own mistakes are explained."""

from __future__ import annotations

import math

import pytest


def test_exercises_pass_with_the_reference_and_explain_the_labs_mistakes():
    from wheelkin.exercises import check
    from wheelkin.exercises import waypoints as ex

    for name, fn in [("quarter_circle_duration", ex.quarter_circle_duration),
                     ("curve_wheel_rates", ex.curve_wheel_rates),
                     ("heading_after", ex.heading_after),
                     ("effective_track_width", ex.effective_track_width)]:
        check(f"waypoints.{name}", fn).assert_passed()

        def stub(*args):
            raise NotImplementedError

        assert check(f"waypoints.{name}", stub).kind == "not-written"
    # the lab's rule (slow the right wheel on every curve) is named as such
    lab_rule = check("waypoints.curve_wheel_rates",
                     lambda R, d, r, w: (w, w * (abs(R) - d) / (abs(R) + d)))
    assert lab_rule.kind == "specific" and "left wheel is the inner one" in lab_rule.message
    # the hand value of the lab's quarter circle: (pi/2)(0.5 + 0.06)/(0.04 * 7.5)
    assert ex.quarter_circle_duration(0.5, 0.06, 0.04, 7.5) == pytest.approx(
        math.pi / 2 * 0.56 / 0.3)
