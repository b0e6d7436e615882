"""Kernel-free views of the live panels: each panel's main controls sampled on a grid.

In the static web page a live panel cannot run (there is no kernel). For every registered
panel, :data:`GRIDS` names its one or two main controls and the values they take there; every
other control keeps its default. :func:`render` draws each combination with the panel's own
code (:meth:`wheelkin.widgets.Panel.redraw`) and encodes it as a palette PNG that records its
smallest font (:func:`wheelkin.animation.palette_png`). The book's Sphinx extension
``tools/live_pages.py`` writes these images into the site, with real form controls that a
small script (``book/_static/precomputed.js``) turns into image swaps.

Each grid contains its controls' defaults, so the page opens on the figure the live panel
opens on, and every value is one the control can take (tests/panels/test_precomputed.py).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import ipywidgets as widgets
import numpy as np

from wheelkin.widgets import Panel, all_panels

__all__ = ["GRIDS", "Grid", "describe", "grid", "render"]


def _span(lo: float, hi: float, step: float) -> tuple[float, ...]:
    """``lo, lo + step, ..., hi`` (inclusive), rounded so that 0.1 steps print as 0.1."""
    count = round((hi - lo) / step) + 1
    return tuple(float(round(v, 6)) for v in np.linspace(lo, hi, count))


def _ints(lo: int, hi: int, step: int) -> tuple[int, ...]:
    return tuple(range(lo, hi + 1, step))


@dataclass(frozen=True)
class Grid:
    """The values a panel is drawn at in the static page.

    Attributes
    ----------
    panel : str
        The registered panel's name.
    axes : tuple of (str, tuple)
        One or two (control name, values) pairs; the images cover every combination.
    """

    panel: str
    axes: tuple[tuple[str, tuple[Any, ...]], ...]

    @property
    def shape(self) -> tuple[int, ...]:
        """The number of values of each axis."""
        return tuple(len(values) for _, values in self.axes)

    @property
    def size(self) -> int:
        """The number of images."""
        return int(np.prod(self.shape))

    def positions(self) -> Iterator[tuple[int, ...]]:
        """Every index tuple, the last axis fastest."""
        return itertools.product(*(range(n) for n in self.shape))

    def values_at(self, index: Sequence[int]) -> dict[str, Any]:
        """The controls' values at an index tuple, by control name."""
        return {name: values[i] for (name, values), i in zip(self.axes, index, strict=True)}

    @staticmethod
    def file_name(index: Sequence[int]) -> str:
        """The image's file name at an index tuple: ``"3-7.png"``."""
        return "-".join(str(i) for i in index) + ".png"


#: The grid of every registered panel (its main controls; the others stay at their defaults).
GRIDS: dict[str, Grid] = {grid.panel: grid for grid in (
    Grid("conventions.twist_icr", (("omega", _span(-2.0, 2.0, 0.25)),
                                   ("vy", _span(-1.0, 1.0, 0.5)))),
    Grid("sandbox.slip", (("omega", _span(0.0, 6.0, 0.5)), ("mu", _span(0.2, 1.0, 0.2)))),
    Grid("rover.steering", (("command", _ints(-100, 100, 10)),)),
    Grid("mecanum.wheel_rates", (("FL", _span(-80.0, 80.0, 10.0)),
                                 ("FR", _span(-80.0, 80.0, 40.0)))),
    Grid("mecanum.waypoint", (("goal_heading_deg", _span(-180.0, 180.0, 30.0)),
                              ("goal_x", _span(-4.0, 4.0, 1.0)))),
    Grid("mecanum.circle", (("radius", _span(-4.0, 4.0, 1.0)),
                            ("lap_time", (1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0)))),
    Grid("diffdrive.wheel_speeds", (("omega_mrad_per_s", _ints(-6000, 6000, 500)),
                                    ("v_steps_per_s", _ints(-2000, 2000, 1000)))),
    Grid("diffdrive.speedometer", (("speed_mm_per_s", (10.0, 20.0, 30.0, 50.0, 75.0, 100.0,
                                                       150.0, 200.0, 300.0, 500.0)),
                                   ("window_ms", (2.0, 4.0, 6.0, 10.0, 20.0, 50.0, 100.0)))),
    Grid("odometry.square", (("step_mm", (1, 2, 5, 10, 20, 50, 100)),
                             ("diameter_error_pct", _span(-2.0, 2.0, 0.5)))),
    Grid("waypoints.lab", (("lookahead", _span(0.05, 0.5, 0.05)),
                           ("speed", _span(0.1, 0.5, 0.1)))),
    Grid("unified.constraints", (("omega", _span(-2.0, 2.0, 0.4)), ("vy", _span(-0.5, 0.5, 0.25)))),
    Grid("carlike.steering", (("delta_deg", _span(-24.0, 24.0, 3.0)),
                              ("geometry", ("ackermann", "linkage", "parallel")))),
    Grid("carlike.rover", (("delta_deg", _span(-45.0, 45.0, 2.5)),)),
    Grid("controllability.manoeuvre", (("epsilon", _span(0.05, 0.5, 0.05)),
                                       ("vehicle", ("car", "differential drive")))),
    Grid("carlike.pure_pursuit", (("bearing_deg", _span(-60.0, 60.0, 10.0)),
                                  ("lookahead", (0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.5)))),
    Grid("control.pose", (("heading_deg", _span(-180.0, 150.0, 30.0)),
                          ("k_beta", (-8.0, -6.0, -4.0, -3.0, -2.0, -1.0, -0.5)))),
)}


def grid(name: str) -> Grid:
    """The grid of panel ``name``; ``ValueError`` for a panel without one."""
    if name not in GRIDS:
        raise ValueError(f"no precomputed grid for panel {name!r}; panels with one: "
                         f"{', '.join(sorted(GRIDS))}")
    return GRIDS[name]


def _label(control: Any, value: Any) -> str:
    """``value`` as the control's readout shows it (an option's label for a choice)."""
    options = getattr(control, "options", None)
    if options:
        for option in options:
            if isinstance(option, tuple) and option[1] == value:
                return str(option[0])
        return str(value)
    fmt = getattr(control, "readout_format", None)
    if isinstance(value, bool):
        return "on" if value else "off"
    if fmt:
        try:
            return format(value, fmt)
        except (TypeError, ValueError):
            pass
    return str(value)


def describe(name: str, panel: Panel | None = None) -> dict[str, Any]:
    """What the static page shows of panel ``name``: title, image size, axes and fixed controls.

    ``axes`` lists, per grid axis, the control's name and label (its description), its kind
    (``"slider"``, or ``"choice"`` for a drop-down), the values as the control's readout
    prints them, and the index of the control's default. ``fixed``
    lists the other controls with their default values as printed.
    """
    spec = grid(name)
    own = panel is None
    if panel is None:
        panel = all_panels()[name]()
    try:
        axes = []
        for control_name, values in spec.axes:
            control = panel.controls[control_name]
            choice = isinstance(control, widgets.Dropdown | widgets.RadioButtons
                                | widgets.ToggleButtons)
            axes.append({"name": control_name, "label": control.description,
                         "kind": "choice" if choice else "slider",
                         "values": [_label(control, v) for v in values],
                         "start": values.index(control.value)})
        fixed = [{"name": n, "label": c.description, "value": _label(c, c.value)}
                 for n, c in panel.controls.items() if n not in dict(spec.axes)]
        width, height = panel.size_px
        return {"panel": name, "title": panel.title or name, "width": width,
                "height": height, "axes": axes, "fixed": fixed, "count": spec.size}
    finally:
        if own:
            panel.close()


def render(name: str, positions: Sequence[Sequence[int]] | None = None,
           ) -> Iterator[tuple[tuple[int, ...], bytes]]:
    """Draw panel ``name`` at every grid position (or at ``positions``) with its own code.

    Yields ``(index, png)``: the index tuple and the figure as a palette PNG (256 colours,
    the figure's dpi, its smallest font recorded). One panel is built and redrawn in place.
    """
    from wheelkin import style
    from wheelkin.animation import palette_png

    spec = grid(name)
    panel = all_panels()[name]()
    try:
        smallest = style.min_font_pt(panel.figure)
        for index in (spec.positions() if positions is None else positions):
            index = tuple(int(i) for i in index)
            panel.redraw(**spec.values_at(index))
            yield index, palette_png(panel.image.value, 256,
                                     min_font_pt=style.min_font_pt(panel.figure) or smallest,
                                     dpi=panel.dpi)
    finally:
        panel.close()
