"""The live-panel core: one redraw per change, blitting, and the return-None fallback."""

import io
from pathlib import Path

import ipywidgets as W
import numpy as np
import pytest
from matplotlib.figure import Figure
from PIL import Image

import wheelkin
from wheelkin.widgets import Panel, slider_values


def _panel(calls, blit=True, switch_at=None):
    def setup():
        fig = Figure(figsize=(3, 2))
        ax = fig.add_subplot()
        ax.set_xlim(-1, 1)
        ax.set_ylim(-1, 1)
        (line,) = ax.plot([], [], color=(0, 0, 1), lw=4)
        return fig, {"ax": ax, "line": line}

    def update(state, a, b):
        calls.append((a, b))
        state["line"].set_data([-1, 1], [a, a])
        if switch_at is not None and a > switch_at:
            state["ax"].set_ylim(-2, 2)
            return None
        state["ax"].set_ylim(-1, 1)
        return [state["line"]] if blit else None

    controls = {"a": W.FloatSlider(min=0.0, max=0.9, value=0.1),
                "b": W.IntSlider(min=0, max=4, value=0)}
    return Panel(controls, setup, update)


def _blue_rows(panel):
    """Rows of the rendered image that contain the blue line (its height on the canvas)."""
    im = np.asarray(Image.open(io.BytesIO(panel.image.value)).convert("RGB")).astype(int)
    mask = (im[..., 2] > 200) & (im[..., 0] < 60) & (im[..., 1] < 60)
    return np.flatnonzero(mask.any(axis=1))


@pytest.mark.parametrize("blit", [True, False])
def test_one_update_per_change_and_per_redraw(blit):
    calls = []
    panel = _panel(calls, blit=blit)
    assert calls == [(0.1, 0)]                      # the initial draw
    panel.controls["a"].value = 0.5                 # a slider move: exactly one redraw
    assert calls[-1] == (0.5, 0) and len(calls) == 2
    panel.redraw(a=0.2, b=3)                        # several overrides: still one redraw
    assert calls[-1] == (0.2, 3) and len(calls) == 3


def test_blitted_frames_match_full_redraws():
    fast, slow = _panel([], blit=True), _panel([], blit=False)
    for a in (0.0, 0.3, 0.6, 0.9):
        fast.redraw(a=a)
        slow.redraw(a=a)
        np.testing.assert_array_equal(_blue_rows(fast), _blue_rows(slow))
        assert _blue_rows(fast).size > 0


def test_returning_none_after_blitting_redraws_everything_and_keeps_the_artists():
    panel = _panel([], blit=True, switch_at=0.5)
    low = _blue_rows(panel)
    panel.redraw(a=0.8)           # limits change: full redraw, the line must still be drawn
    assert _blue_rows(panel).size > 0
    panel.redraw(a=0.1)           # back to blitting: the same picture as at the start
    np.testing.assert_array_equal(_blue_rows(panel), low)


def test_unknown_control_is_named():
    panel = _panel([])
    with pytest.raises(ValueError, match="unknown control 'c'"):
        panel.redraw(c=1)


def test_slider_values_cover_the_whole_range():
    assert slider_values(W.FloatSlider(min=-2.0, max=2.0), n=5) == [-2.0, -1.0, 0.0, 1.0, 2.0]
    assert slider_values(W.IntSlider(min=0, max=3), n=9) == [0, 1, 2, 3]
    assert slider_values(W.Checkbox()) == [False, True]
    assert slider_values(W.Dropdown(options=[("x", 1), ("y", 2)])) == [1, 2]


def test_an_artist_dropped_from_the_blit_list_stays_visible():
    def setup():
        fig = Figure(figsize=(3, 2))
        ax = fig.add_subplot()
        ax.set_xlim(-1, 1)
        ax.set_ylim(-1, 1)
        (moving,) = ax.plot([-1, 1], [0, 0], color=(1, 0, 0), lw=4)
        (fixed,) = ax.plot([-1, 1], [0.5, 0.5], color=(0, 0, 1), lw=4)
        return fig, {"moving": moving, "fixed": fixed}

    def update(state, a):
        state["moving"].set_ydata([-a, -a])
        return [state["moving"], state["fixed"]] if a < 0.5 else [state["moving"]]

    panel = Panel({"a": W.FloatSlider(min=0.0, max=0.9, value=0.1)}, setup, update)
    assert _blue_rows(panel).size > 0
    panel.redraw(a=0.7)  # "fixed" leaves the list: it must now be part of the background
    assert _blue_rows(panel).size > 0
    panel.redraw(a=0.8)
    assert _blue_rows(panel).size > 0


# --- every registered panel: its size on a laptop screen, and text you can read ---------------

from wheelkin import style  # noqa: E402
from wheelkin.widgets import all_panels  # noqa: E402

PANELS = sorted(all_panels())
#: A 1366x768 laptop shows about 600 px of a notebook's output (the browser's tab and address
#: bars and JupyterLab's menu, tab and toolbar take the rest).
LAPTOP_HEIGHT_PX = 600
#: One row of ipywidgets controls in JupyterLab: a 28 px slider plus its 2 px margins, rounded.
ROW_PX = 32


def test_panel_image_is_shown_at_its_natural_size():
    panel = _panel([])
    png = Image.open(io.BytesIO(panel.image.value))
    assert panel.image.layout.width == f"{png.width}px"
    assert panel.image.layout.height == f"{png.height}px"
    assert png.width == round(3 * style.DPI)  # figsize (3, 2) at the book's dpi
    panel.close()


@pytest.mark.parametrize("name", PANELS)
def test_panel_fits_a_laptop_screen(name):
    panel = all_panels()[name]()
    try:
        width_px = panel.figure.get_figwidth() * panel.dpi
        figure_px = panel.figure.get_figheight() * panel.dpi
        n = len(panel.controls)
        rows = n if n <= 3 else (n + 1) // 2  # more than three controls: two columns
        total = figure_px + rows * ROW_PX + (24 if panel.title else 0)
        assert width_px <= style.COLUMN_WIDTH_IN * style.DPI + 0.5, (
            f"panel {name} is {width_px:.0f} px wide (at most 670)")
        assert total <= LAPTOP_HEIGHT_PX, (
            f"panel {name} is {total:.0f} px tall with its {n} controls "
            f"(figure {figure_px:.0f} px), over {LAPTOP_HEIGHT_PX} px: a smaller figure")
        assert panel.dpi >= style.DPI, f"panel {name} renders at {panel.dpi} dpi (< {style.DPI})"
    finally:
        panel.close()


@pytest.mark.parametrize("name", PANELS)
def test_panel_text_is_legible_at_every_extreme(name):
    """check_figure on the panel's figure at its start and with every control at min and max."""
    panel = all_panels()[name]()
    # A panel's image is shown at its natural size (not scaled to the book's column).
    shown = {"draw": False, "shown_width_px": panel.size_px[0]}
    try:
        found = [f"start: {p}" for p in style.check_figure(panel.figure, **shown)]
        for end in (0, -1):
            values = {k: slider_values(c)[end] for k, c in panel.controls.items()}
            panel.redraw(**values)
            panel.figure.canvas.draw()
            where = "all controls at " + ("min" if end == 0 else "max")
            found += [f"{where}: {p}" for p in style.check_figure(panel.figure, **shown)]
        assert not found, f"panel {name}:\n" + "\n".join(dict.fromkeys(found))
    finally:
        panel.close()


def test_no_figure_of_the_library_is_made_without_a_layout_engine():
    """A figure with layout="none" gets the book style's constrained layout back from its
    first save, so a panel's or an animation's frames after the first would move."""
    src = Path(wheelkin.__file__).parent
    found = [f"{p.relative_to(src)}:{i}" for p in sorted(src.rglob("*.py"))
             for i, line in enumerate(p.read_text().splitlines(), 1)
             if 'layout="none"' in line and "Not ``layout" not in line]
    assert not found, ("use layout=wheelkin.style.fixed_layout() (a hand-set layout that "
                       f"survives saving), not layout=\"none\": {found}")
