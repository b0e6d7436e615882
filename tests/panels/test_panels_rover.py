"""The rover chapter's panel draws the model's wheel speeds and shows a model error instead of
raising; the sweep animation has every frame."""

from __future__ import annotations

import re

import numpy as np

from wheelkin.rover import RoverGeometry, command_to_radius, wheel_speeds


def test_panel_never_raises_and_draws_the_model():
    import matplotlib

    matplotlib.use("Agg")
    from wheelkin.widgets import rover as rw

    panel = rw.steering_panel()
    try:
        view = panel.state
        for command, speed in ((-100, 100), (0, 100), (1, 35), (37, 0), (100, 100)):
            panel.redraw(command=command, speed=speed)
            assert not view.message.get_visible()
            heights = [bar.get_height() for bar in view.bars]
            np.testing.assert_allclose(heights, wheel_speeds(command_to_radius(command), speed))
        # A model error is shown in the figure, never raised.
        view.geometry = RoverGeometry(7.254, 200.0, 200.0, 10.073, unit="in")  # r_min far above 20 in
        view.update(100, 50)
        assert view.message.get_visible() and "radius" in view.message.get_text()
    finally:
        panel.close()


def test_sweep_animation_renders_every_frame():
    import matplotlib

    matplotlib.use("Agg")
    from wheelkin.animation import to_html
    from wheelkin.widgets import rover as rw

    html = to_html(rw.sweep_animation(frames=5), name="test-rover-sweep", alt="sweep")
    assert len(re.findall(r"frames\[\d+\]", html)) == 5


def test_corner_angles_never_print_a_negative_zero():
    """Driving straight, every corner is at zero: its label reads +0.0°, never −0.0°; a turn
    still prints the sign of each corner (the book's delta, left positive)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from wheelkin.style import fixed_layout
    from wheelkin.widgets.rover import RoverView

    view = RoverView(Figure(layout=fixed_layout()))
    view.update(0.0, 100.0)
    corners = [view.labels[i].get_text() for i in (0, 2, 3, 5)]
    assert all("+0.0°" in t and "−0.0" not in t for t in corners), corners
    view.update(100.0, 100.0)  # a right turn: front corners steer right (−), back ones left
    corners = [view.labels[i].get_text() for i in (0, 2, 3, 5)]
    assert sum("−" in t for t in corners) == 2 and sum("+" in t for t in corners) == 2, corners
