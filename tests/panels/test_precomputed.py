"""The precomputed views of the live panels (wheelkin.widgets.precomputed, tools/live_pages.py).

Every registered panel has a grid; each grid holds values its controls can take and their
defaults (the page opens on what the live panel opens on); the images are the panel's own
drawing at those values; every panel cell of the book names a panel that has a grid, and every
panel is shown by some page.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import ipywidgets as W
import numpy as np
import pytest
from PIL import Image

from tools.book_pages import toc_files
from tools.png_text import png_info
from wheelkin.widgets import all_panels
from wheelkin.widgets.precomputed import GRIDS, Grid, describe, grid, render

ROOT = Path(__file__).resolve().parents[2]

PANELS = sorted(all_panels())


def _allowed(control, value) -> bool:
    options = getattr(control, "options", None)
    if options:
        return value in [o[1] if isinstance(o, tuple) else o for o in options]
    if isinstance(control, W.Checkbox | W.ToggleButton):
        return isinstance(value, bool)
    if not control.min <= value <= control.max:
        return False
    steps = (value - control.min) / control.step
    return abs(steps - round(steps)) < 1e-9


def test_every_panel_has_a_grid_and_no_grid_lacks_a_panel():
    assert sorted(GRIDS) == PANELS


@pytest.mark.parametrize("name", PANELS)
def test_grid_values_are_the_controls_own(name):
    spec = grid(name)
    panel = all_panels()[name]()
    try:
        assert 1 <= len(spec.axes) <= 2, f"{name}: one or two main controls"
        for control_name, values in spec.axes:
            control = panel.controls[control_name]
            bad = [v for v in values if not _allowed(control, v)]
            assert not bad, f"{name}.{control_name}: values the control cannot take: {bad}"
            assert len(set(values)) == len(values) >= 2
            assert control.value in values, (
                f"{name}.{control_name}: the default {control.value!r} is not on the grid")
    finally:
        panel.close()


def test_describe_names_labels_values_and_defaults():
    info = describe("diffdrive.wheel_speeds")
    omega, v = info["axes"]
    assert (omega["label"], v["label"]) == ("yaw rate ω (mrad/s)", "speed v (steps/s)")
    assert omega["values"][0] == "-6000" and omega["values"][-1] == "6000"
    assert omega["values"][omega["start"]] == "1000" and v["values"][v["start"]] == "1000"
    assert info["count"] == 25 * 5 and (info["width"], info["height"]) == (670, 360)
    steering = describe("carlike.steering")
    assert steering["axes"][1]["kind"] == "choice"
    assert steering["axes"][1]["values"] == ["ideal Ackermann", "trapezoidal linkage",
                                             "parallel steer"]
    assert {f["name"] for f in describe("odometry.square")["fixed"]} == {"base_error_pct",
                                                                         "direction"}


def test_an_image_is_the_panels_own_drawing_at_those_values():
    """The image at a grid position is the live panel's figure after the same slider moves."""
    spec = grid("rover.steering")
    (index, png), = render("rover.steering", [(3,)])
    panel = all_panels()["rover.steering"]()
    try:
        panel.redraw(**spec.values_at(index))
        live = np.asarray(Image.open(io.BytesIO(panel.image.value)).convert("RGB"), float)
    finally:
        panel.close()
    shown = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), float)
    assert shown.shape == live.shape
    # A 256-colour palette of a line drawing: the pixels agree within a level or two.
    error = np.abs(shown - live).max(axis=2)
    assert np.percentile(error, 99) <= 2 and error.mean() < 0.5, (
        f"mean {error.mean():.2f}, 99th percentile {np.percentile(error, 99):.0f} levels")
    info = png_info(png)
    assert round(info["dpi"]) == 100 and float(info["text"]["wheelkin:min_font_pt"]) >= 8


def test_images_differ_along_each_axis():
    spec = grid("diffdrive.wheel_speeds")
    start = tuple(a for a in (14, 3))
    moved = [(0, 3), (14, 0)]
    images = dict(render("diffdrive.wheel_speeds", [start, *moved]))
    for index in moved:
        assert images[index] != images[start], f"{spec.values_at(index)} drew the same image"


def test_file_names_and_positions():
    spec = Grid("x", (("a", (1, 2, 3)), ("b", (0.0, 1.0))))
    assert spec.shape == (3, 2) and spec.size == 6
    assert list(spec.positions())[:3] == [(0, 0), (0, 1), (1, 0)]
    assert Grid.file_name((2, 1)) == "2-1.png"
    assert spec.values_at((2, 1)) == {"a": 3, "b": 1.0}
    with pytest.raises(ValueError, match="no precomputed grid for panel 'nope'"):
        grid("nope")


def _panel_cells():
    for page in toc_files():
        path = ROOT / f"{page}.ipynb"
        if not path.is_file():
            continue
        for index, cell in enumerate(json.loads(path.read_text(encoding="utf-8"))["cells"]):
            if cell["cell_type"] == "code":
                yield page, index, cell


def test_every_panel_cell_names_its_panel_and_every_panel_is_shown():
    shown, unnamed = set(), []
    for page, index, cell in _panel_cells():
        name = cell["metadata"].get("wheelkin", {}).get("panel")
        source = "".join(cell["source"])
        if name is None:
            if "remove-output" in cell["metadata"].get("tags", []) and "panel" in source:
                unnamed.append(f"{page} cell {index}")
            continue
        assert name in GRIDS, f"{page} cell {index}: panel {name!r} has no grid"
        assert "remove-output" in cell["metadata"].get("tags", []), (
            f"{page} cell {index}: a panel cell is tagged remove-output")
        shown.add(name)
    assert not unnamed, f"panel cells without wheelkin.panel metadata: {unnamed}"
    assert shown == set(GRIDS), f"panels no page shows: {sorted(set(GRIDS) - shown)}"


def test_the_note_counts_positions_without_a_one_axis_product():
    """One slider: "21 positions"; two: "21 × 5 = 105 positions" (never "21 = 21")."""
    from tools.live_pages import view_html

    def axis(name, n):
        return {"name": name, "label": name, "kind": "slider", "start": 0,
                "values": [str(v) for v in range(n)]}

    def note(axes, count):
        info = {"axes": axes, "fixed": [], "count": count, "panel": "p.q", "title": "T",
                "width": 10, "height": 10}
        return view_html(info, "b/", "../", "u")

    one = note([axis("command", 21)], 21)
    assert "Precomputed at 21 positions of command." in one and "21 = 21" not in one
    two = note([axis("command", 21), axis("speed", 5)], 105)
    assert "Precomputed at 21 × 5 = 105 positions of command and speed." in two
