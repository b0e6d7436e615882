"""The odometry chapter's exercises: references pass, stubs fail kindly, and the firmware
README's mistakes are named."""

from __future__ import annotations

import math

import pytest

from wheelkin.exercises import get

EXERCISES = ["odometry.center_and_turn", "odometry.midpoint_step", "odometry.exact_step",
             "odometry.alpha_mrad"]


@pytest.mark.parametrize("name", EXERCISES)
def test_exercise_reference_passes_and_stub_says_not_written(name):
    ex = get(name)
    assert ex.check(ex.reference).passed

    def stub(*args):
        raise NotImplementedError

    result = ex.check(stub)
    assert not result.passed
    assert result.kind == "not-written"


def test_exercise_mistakes_are_named():
    def readme_center(n_left, n_right, steps_per_mm, track_width_mm):
        return ((n_left - n_right) / 2 / steps_per_mm,
                (n_right - n_left) / steps_per_mm / track_width_mm)

    assert "(L + R)" in get("odometry.center_and_turn").check(readme_center).message

    def end_heading(x, y, theta, distance, dtheta):
        t = theta + dtheta
        return (x + distance * math.cos(t), y + distance * math.sin(t), t)

    assert "end" in get("odometry.midpoint_step").check(end_heading).message

    def rounded(n_left, n_right, steps_per_mm, track_width_mm):
        return round(1000 * (n_right - n_left) / (steps_per_mm * track_width_mm))

    assert "toward zero" in get("odometry.alpha_mrad").check(rounded).message

    def naive_exact(x, y, theta, distance, dtheta):
        r = distance / dtheta
        return (x + r * (math.sin(theta + dtheta) - math.sin(theta)),
                y - r * (math.cos(theta + dtheta) - math.cos(theta)), theta + dtheta)

    res = get("odometry.exact_step").check(naive_exact)
    assert not res.passed
    assert res.kind in ("raised", "nan")
