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
