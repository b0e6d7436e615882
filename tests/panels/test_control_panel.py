"""The control chapter's panel and helpers draw and drive what the library computes.

The panel's path ends where the kinematic closed loop of `wheelkin.control.simulate` ends
(recomputed here from the law), its text gives the start's polar coordinates and the roots of
the characteristic polynomial (against numpy's roots of the hand-written quadratic), and it
says "refused" for gains the library refuses; the animation is legible and short. The run
helpers are checked against independent values: the unicycle limit keeps the curvature and
the wheel speeds within the cap; the car limit clips the curvature at tan(delta_max)/L; the
figure eight's twist is the derivative of its poses (finite differences); the many-robot
sandbox run equals single-robot runs of the same starts (the robots do not interact).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from wheelkin import control, style
from wheelkin.sandbox import RADON_ULZER
from wheelkin.widgets import all_panels
from wheelkin.widgets import control as W


def test_the_panel_draws_the_closed_loop():
    panel = all_panels()["control.pose"]()
    try:
        panel.redraw(k_rho=3.0, k_alpha=8.0, k_beta=-3.0, x=-0.6, y=0.5, heading_deg=90.0)
        view = panel.state
        start = (-0.6, 0.5, math.radians(90.0))

        def law(t, poses):
            return W.unicycle_commands(control.move_to_pose(poses, W.GOAL, 3.0, 8.0, -3.0))

        path = control.simulate(law, start, 12.0, 0.02)
        xs = np.concatenate([np.asarray(view.path.get_xdata(), float),
                             np.asarray(view.back.get_xdata(), float)])
        assert np.nanmax(np.abs(xs - np.concatenate([path[:, 0], path[:, 0]]))) < 1e-12
        text = view.text.get_text()
        rho = math.hypot(0.6, 0.5)
        assert f"ρ = {rho:.2f} m" in text
        roots = np.roots([1.0, 5.0, 9.0])
        assert f"{roots[0].real:+.2f} ± {abs(roots[0].imag):.2f}j" in text
        assert "at the goal" in text
        panel.redraw(k_rho=3.0, k_alpha=2.0, k_beta=-3.0, x=-0.6, y=0.5, heading_deg=90.0)
        assert "refused" in view.text.get_text()
    finally:
        panel.close()


def test_the_animation_is_legible_and_short():
    style.setup()
    anim = W.pose_animation()
    assert anim._save_count <= 40
    for k in (0, anim._save_count // 2, anim._save_count - 1):
        anim._func(k)
        assert style.check_figure(anim._fig) == []


def test_the_unicycle_limit_keeps_the_curvature():
    twists = np.array([[1.0, 0.0, 10.0], [0.1, 0.0, 0.2], [-2.0, 0.0, 1.0]])
    out = W.unicycle_commands(twists, 0.085, 0.3)
    left = out[:, 0] - out[:, 2] * 0.0425
    right = out[:, 0] + out[:, 2] * 0.0425
    assert np.all(np.maximum(np.abs(left), np.abs(right)) <= 0.3 + 1e-12)
    np.testing.assert_allclose(out[:, 2] / out[:, 0], twists[:, 2] / twists[:, 0])
    np.testing.assert_array_equal(out[1], twists[1])  # within the cap: unchanged


def test_the_car_limit_clips_the_curvature():
    out = W.car_commands([[0.5, 0.0, 5.0], [0.5, 0.0, 0.1], [0.0, 0.0, 1.0]], 0.33, 0.4, 1.0)
    kappa_max = math.tan(0.4) / 0.33
    assert out[0, 2] / out[0, 0] == pytest.approx(kappa_max)
    assert out[1, 2] == pytest.approx(0.1)
    assert out[2, 2] == 0.0  # a car at rest cannot turn


def test_the_figure_eight_twist_is_the_derivative_of_its_poses():
    t = np.linspace(0.0, 40.0, 4001)
    poses, twists = W.figure_eight(t)
    dt = t[1] - t[0]
    speed = np.hypot(np.gradient(poses[:, 0], dt), np.gradient(poses[:, 1], dt))
    rate = np.gradient(np.unwrap(poses[:, 2]), dt)
    np.testing.assert_allclose(twists[1:-1, 0], speed[1:-1], rtol=1e-4)
    np.testing.assert_allclose(twists[1:-1, 2], rate[1:-1], atol=1e-3)


def test_many_robots_in_one_world_drive_as_they_would_alone():
    starts = np.array([[-0.4, 0.2, 0.3], [0.3, -0.3, 2.0], [0.0, 0.4, -1.0]])

    def law(t, poses):
        return W.unicycle_commands(control.move_to_pose(poses, W.GOAL, 3.0, 8.0, -3.0,
                                                        stop_distance=0.005))

    together = W.sandbox_runs(RADON_ULZER, starts, law, 3.0)
    for start, run in zip(starts, together, strict=True):
        alone = W.sandbox_runs(RADON_ULZER, start[None], law, 3.0)[0]
        np.testing.assert_allclose(run.pose, alone.pose, atol=1e-9)
    assert W.converged(np.zeros((1, 3))).all()
    assert not W.converged([[0.011, 0.0, 0.0]]).any()
