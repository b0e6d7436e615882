"""The unified chapter's panels: the tour's twists, and the constraint view marks exactly the
wheels that must slide (every slider value of every panel: tests/panels/test_panel_sweep.py)."""

from __future__ import annotations

import numpy as np
import pytest


def test_the_tour_animations_have_their_frames():
    import matplotlib

    matplotlib.use("Agg")
    from wheelkin.widgets import unified as panels

    twists = panels.tour_twists(40)
    assert twists.shape == (40, 3)
    np.testing.assert_allclose(np.hypot(twists[:20, 0], twists[:20, 1]), 0.3)
    np.testing.assert_allclose(twists[-1], [0.0, 0.0, 1.5])
    with pytest.raises(ValueError, match="frames"):
        panels.tour_twists(3)
    with pytest.raises(ValueError, match="frames"):
        panels.manoeuvre_animation({"strafe": {}}, frames=41)  # more than a page may hold


def test_constraint_view_marks_exactly_the_wheels_that_must_slide():
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from wheelkin.sandbox.render import SLIP_COLOUR
    from wheelkin.widgets.unified import ConstraintView

    view = ConstraintView(Figure(layout="none"))  # as the panel makes it
    view.update(0.0, 0.3, 0.0, steer=True)  # strafe left
    red = {}
    for name, item in zip(view.vehicles, view.items, strict=True):
        colours = [matplotlib.colors.to_hex(p.get_facecolor()) for p in item["drawing"].wheels]
        red[name] = [w.name for w, c in zip(item["spec"].wheels, colours, strict=True)
                     if c == SLIP_COLOUR]
    assert red == {"differential drive": ["L", "R"], "skid steer": ["FL", "FR", "RL", "RR"],
                   "mecanum": [], "rover": ["LM", "RM"]}


def test_the_tour_never_shows_a_twist_twice():
    """Consecutive frames differ (the spin starts one step after the turn ends), and the tour
    still ends on the spin asked for."""
    from wheelkin.widgets import unified as panels

    for frames in (8, 32, 40):
        twists = panels.tour_twists(frames)
        steps = np.abs(np.diff(twists, axis=0)).max(axis=1)
        assert steps.min() > 0, frames


def test_contact_arrows_start_at_the_wheel_edge():
    """A spinning differential drive's slow contact points (1.5 rad/s x 43 mm) are drawn from
    the edge of each wheel's outline (half-length = wheel radius), forward on the right wheel,
    backward on the left: outside the wheel, each pointing its own way."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from wheelkin.widgets.unified import ConstraintView

    view = ConstraintView(Figure(layout="none"), arrow_speeds={"differential drive": 0.4})
    view.update(0.0, 0.0, 1.5)
    item = view.items[0]
    spec = item["spec"]
    bases = item["velocity"].get_offsets()
    for wheel, base, u in zip(spec.wheels, bases, item["velocity"].U, strict=True):
        x, y = wheel.position
        # the contact velocity is -omega y along x; the base lies one wheel radius that way
        assert np.sign(u) == np.sign(-1.5 * y)
        assert base[0] == pytest.approx(x + np.sign(-y) * wheel.wheel_radius)
        assert base[1] == pytest.approx(y)
    assert item["scale"] == pytest.approx(0.8 * 0.061 / 0.4, rel=0.02)
    with pytest.raises(ValueError, match="arrow_speeds"):
        ConstraintView(Figure(layout="none"), arrow_speeds={"rover": 0.0})
