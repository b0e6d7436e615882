"""The waypoint lab's panels: the lab panel shows the geometric track failing, every slider
redraws, and blitting gives the picture of a full draw."""

from __future__ import annotations

import numpy as np
import pytest

from wheelkin import follower as fo


def test_widgets_reexport_the_reduced_model():
    pytest.importorskip("pymunk")
    from wheelkin.widgets import waypoints as ww

    assert ww.KinematicSkidSteer is fo.KinematicSkidSteer


def test_lab_panel_builds_and_shows_the_geometric_track_failing():
    pytest.importorskip("wheelkin.sandbox")
    from wheelkin.widgets import waypoints as ww

    panel = ww.lab_panel()
    try:
        good = panel.state.text.get_text()
        assert "final error" in good
        panel.redraw(track=ww.TRACK_CHOICES[1][1])
        bad = panel.state.text.get_text()
        final = float(bad.split("final error")[1].split("cm")[0])
        assert final > 100  # the robot trusts its wheels and is lost by metres
    finally:
        panel.close()


def test_every_slider_value_of_the_waypoint_panels_redraws():
    pytest.importorskip("wheelkin.sandbox")
    from wheelkin.widgets import all_panels, slider_values

    panels = {k: f for k, f in all_panels().items() if k.startswith("waypoints.")}
    assert panels
    for factory in panels.values():
        panel = factory()
        try:
            for name, control in panel.controls.items():
                for value in slider_values(control, n=2):  # a lap each: the ends suffice
                    panel.redraw(**{name: value})
                    assert "lap time" in panel.state.text.get_text()
                panel.redraw(**{name: control.value})
        finally:
            panel.close()


def _png_pixels(panel) -> np.ndarray:
    import io

    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(panel.image.value)))


def _full_draw(setup, update, dpi=72, **values) -> np.ndarray:
    """The picture of a fresh figure drawn whole (no panel, nothing blitted)."""
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from wheelkin import style

    with plt.ioff(), plt.rc_context(style._RC):  # as the panel builds its figure
        fig, state = setup()
    plt.close(fig)
    FigureCanvasAgg(fig)
    fig.set_dpi(dpi)
    update(state, **values)
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba()).copy()


def test_lab_panel_blits_the_picture_of_a_full_draw():
    pytest.importorskip("wheelkin.sandbox")
    from wheelkin.widgets import waypoints as ww

    panel = ww.lab_panel()
    try:
        assert panel._blit  # the panel blits
        for values in ({}, {"speed": 0.5, "lookahead": 0.05, "heading_gain": 10.0},
                       {"encoder": 16, "track": ww.TRACK_CHOICES[1][1]},  # lost: off the map
                       {"speed": 0.1, "lookahead": 0.5, "heading_gain": 1.0, "encoder": 0,
                        "track": ww.EFFECTIVE_TRACK}):
            panel.redraw(**values)
            full = _full_draw(ww._setup, ww._update, dpi=panel.dpi, **panel.values())
            assert (full != 255).any()
            np.testing.assert_array_equal(_png_pixels(panel), full)
    finally:
        panel.close()


def test_lab_view_redraws_the_legend_only_over_a_path_that_runs_under_it():
    pytest.importorskip("wheelkin.sandbox")
    import ipywidgets
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from wheelkin.widgets import Panel
    from wheelkin.widgets import waypoints as ww

    fig, view = ww._setup()  # where the legend is, in data units
    plt.close(fig)
    FigureCanvasAgg(fig)
    fig.set_dpi(72)
    view.ax.apply_aspect()
    box = view.ax.get_legend().get_window_extent(fig.canvas.get_renderer())
    (x0, y0), (x1, y1) = view.ax.transData.inverted().transform(box.get_points())
    per_pixel = (y1 - y0) / box.height
    lap = ww.surrogate_lap()
    paths = [lap["truth"],                                              # clear of the legend
             np.array([[-2.5, -2.2, 0.0], [-0.5, -1.9, 0.0], [0.0, 0.0, 1.0]]),  # under it
             np.array([[1.5, -1.5, 0.0], [-1.2, -1.8, 3.0]])]  # the robot beside it
    # paths 0 to 4 pixels above its top edge: a stroke's edge, blurred, reaches it
    paths += [np.array([[x0 - 0.3, y1 + d * per_pixel, 0.0], [x1 + 0.3, y1 + d * per_pixel, 0.0],
                        [1.5, 1.5, 0.0]]) for d in (0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0)]

    def update(view, k):
        view.show(paths[k], paths[k][::-1], text=f"path {k}")
        return view.blit_artists()

    panel = Panel({"k": ipywidgets.IntSlider(value=0, min=0, max=len(paths) - 1)}, ww._setup,
                  update)
    try:
        legend = panel.state.ax.get_legend()
        seen = set()
        for k in (0, 1, 0, 2, 2, 1, 1, 0, *range(3, len(paths)), 0, *range(3, len(paths))):
            panel.redraw(k=k)
            seen.add(any(a is legend for a in panel._blit))
            np.testing.assert_array_equal(_png_pixels(panel), _full_draw(ww._setup, update, dpi=panel.dpi, k=k),
                                          err_msg=f"path {k}")
        assert seen == {True, False}  # both cases met
    finally:
        panel.close()
