"""Live panels: sliders that redraw a matplotlib figure in place (needs a running kernel).

A :class:`Panel` owns one figure, built once by ``setup``; every slider change calls
``update(state, **values)``, which moves the existing artists (no new figure, no re-layout),
and the figure is re-rendered to PNG into an :class:`ipywidgets.Image`. That keeps a redraw
well under the book's 50 ms budget and the output stable.

In the static HTML book a panel cannot work (there is no kernel), so chapters tag the cell
that displays a panel ``remove-output`` and show a precomputed animation instead: no control
in the HTML looks live and does nothing.

Each chapter defines its panels in a module of this package (``wheelkin.widgets.rover`` ...)
and registers a factory with :func:`register`, so that the tests can sweep every slider of
every panel (:func:`all_panels`) and the benchmarks can time every redraw.
"""

from __future__ import annotations

import io
import time
from collections.abc import Callable, Mapping
from typing import Any

try:
    import ipywidgets as widgets
    import matplotlib.pyplot as plt
except ModuleNotFoundError as exc:
    raise ModuleNotFoundError("wheelkin.widgets needs ipywidgets and matplotlib: install the "
                              "extra, pip install \".[notebook]\" from a checkout") from exc
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from wheelkin._registry import load_chapter_modules

__all__ = ["Panel", "all_panels", "register", "slider_values"]

_FACTORIES: dict[str, Callable[[], Panel]] = {}
CHAPTER_MODULES = ("conventions", "sandbox", "rover", "mecanum", "diffdrive", "odometry",
                   "waypoints", "unified", "carlike", "controllability", "control")


class Panel:
    """Sliders driving a figure that is redrawn in place.

    Parameters
    ----------
    controls : mapping of str to ipywidgets.ValueWidget
        The controls, by the keyword name that ``update`` receives.
    setup : callable () -> (Figure, state)
        Builds the figure and its artists once; ``state`` is anything ``update`` needs
        (typically a dict of artists).
    update : callable (state, **values) -> None or list of artists
        Moves the artists to show ``values``. It must not raise for any value a control can
        take; a value the model rejects is shown as a message in the figure instead.
        If it returns the list of artists it changes (the same list every call), the panel
        *blits*: the rest of the figure (axes, ticks, labels: most of the drawing cost) is
        rendered once and only those artists are redrawn over it. When an update changes
        anything outside that list (axis limits, a title), it returns None for that call: the
        panel then redraws everything, and blits again from the next list it gets.
    title : str, optional
        Shown above the controls.
    dpi : int
        Resolution of the rendered PNG (default: the book's, :data:`wheelkin.style.DPI`).

    The figure is built under the book's figure style (:func:`wheelkin.style.setup`'s
    matplotlib defaults) and shown at its natural size: the image widget is exactly as many
    CSS pixels as the PNG, never stretched by the output area, so its text is as large as
    drawn (at least 11 px for 8 pt at 100 dpi). More than :data:`ONE_COLUMN_CONTROLS`
    controls are laid out in two columns, so that a panel with its sliders fits a
    1366x768 laptop screen (:data:`MAX_HEIGHT_PX`).
    """

    #: Up to this many controls are stacked in one column; more go into two columns.
    ONE_COLUMN_CONTROLS = 3
    #: The height of one row of controls in JupyterLab (a 28 px slider and its margins).
    ROW_PX = 32
    #: The height of the title line.
    TITLE_PX = 24
    #: The tallest a panel may be, title, controls and figure together: what a 1366x768
    #: laptop shows of a notebook (768 px less the browser's and JupyterLab's bars).
    MAX_HEIGHT_PX = 600

    def __init__(
        self,
        controls: Mapping[str, widgets.ValueWidget],
        setup: Callable[[], tuple[Figure, Any]],
        update: Callable[..., None],
        *,
        title: str | None = None,
        dpi: int | None = None,
    ) -> None:
        from wheelkin import style

        if dpi is None:
            dpi = style.DPI
        if not (isinstance(dpi, int | float) and 50 <= dpi <= 300):
            raise ValueError(f"dpi must be in [50, 300], got {dpi!r}")
        self.controls = dict(controls)
        self._update = update
        self.dpi = dpi
        with plt.ioff(), plt.rc_context(style._RC):
            self.figure, self.state = setup()
        # The panel shows its figure through the Image widget only: keep pyplot from showing
        # it again under a later cell.
        plt.close(self.figure)
        FigureCanvasAgg(self.figure)  # render off-screen, whatever the notebook's backend
        self.figure.set_dpi(dpi)
        self._blit: list | None = None
        self._background = None
        width, height = self.size_px
        # The natural size, in CSS pixels: the output area must not stretch the image.
        self.image = widgets.Image(format="png", layout=widgets.Layout(
            width=f"{width}px", height=f"{height}px", max_width="none", flex="0 0 auto"))
        self.title = title
        self._muted = False
        for control in self.controls.values():
            control.observe(self._on_change, names="value")
            # A control's description names it in words ("yaw rate ω (rad/s)"), which screen
            # readers announce: it is shown whole, not cut to the default label width.
            look = getattr(control, "style", None)
            if look is not None and getattr(look, "description_width", None) == "":
                look.description_width = "initial"
        self.redraw()

    @property
    def size_px(self) -> tuple[int, int]:
        """The rendered image's size in pixels: (width, height) = figure size x dpi."""
        return (round(self.figure.get_figwidth() * self.dpi),
                round(self.figure.get_figheight() * self.dpi))

    @property
    def height_px(self) -> int:
        """The panel's height on screen: title, rows of controls and figure."""
        n = len(self.controls)
        rows = n if n <= self.ONE_COLUMN_CONTROLS else -(-n // 2)
        return (self.TITLE_PX if self.title else 0) + rows * self.ROW_PX + self.size_px[1]

    def values(self) -> dict[str, Any]:
        """The controls' current values, by name."""
        return {name: c.value for name, c in self.controls.items()}

    def redraw(self, **overrides: Any) -> float:
        """Apply ``overrides`` to the controls (without triggering redraws), redraw once.

        Returns the wall time of the redraw in seconds (used by the benchmarks).
        """
        unknown = [name for name in overrides if name not in self.controls]
        if unknown:
            raise ValueError(f"unknown control {unknown[0]!r}; known: {', '.join(self.controls)}")
        self._muted = True  # setting several controls must not redraw once per control
        try:
            for name, value in overrides.items():
                self.controls[name].value = value
        finally:
            self._muted = False
        start = time.perf_counter()
        changed = self._update(self.state, **self.values())
        canvas = self.figure.canvas
        if changed:
            artists = list(changed)
            if self._blit != artists:  # a new list: render everything else once
                for artist in self._blit or ():  # artists dropped from the list are static
                    artist.set_animated(False)
                for artist in artists:
                    artist.set_animated(True)
                canvas.draw()
                self._background = canvas.copy_from_bbox(self.figure.bbox)
                self._blit = artists
            canvas.restore_region(self._background)
            for artist in artists:
                self.figure.draw_artist(artist)
        else:
            if self._blit:  # back to full redraws: the blitted artists must be drawn again
                for artist in self._blit:
                    artist.set_animated(False)
                self._blit = self._background = None
            canvas.draw()
        self.image.value = _png(canvas)
        return time.perf_counter() - start

    def _on_change(self, _change) -> None:
        if not self._muted:
            self.redraw()

    @property
    def widget(self) -> widgets.Widget:
        """The whole panel: title, controls and figure."""
        children = []
        if self.title:
            children.append(widgets.HTML(f"<b>{self.title}</b>"))
        controls = list(self.controls.values())
        if len(controls) <= self.ONE_COLUMN_CONTROLS:
            children.append(widgets.VBox(controls))
        else:
            half = -(-len(controls) // 2)
            children.append(widgets.HBox([widgets.VBox(controls[:half]),
                                          widgets.VBox(controls[half:])]))
        children.append(self.image)
        return widgets.VBox(children)

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)

    def close(self) -> None:
        """Release the figure and the widgets."""
        plt.close(self.figure)
        for control in self.controls.values():
            control.close()
        self.image.close()


def _png(canvas) -> bytes:
    """The canvas's current pixels as PNG (light compression: fast, a few kB larger)."""
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.asarray(canvas.buffer_rgba())).save(buf, format="png", compress_level=1)
    return buf.getvalue()


def slider_values(control: widgets.ValueWidget, n: int = 5) -> list[Any]:
    """``n`` values spread over a control's whole range (for sweeps in tests and benchmarks)."""
    if hasattr(control, "options") and control.options:
        opts = list(control.options)
        values = [o[1] if isinstance(o, tuple) else o for o in opts]
        return values
    if isinstance(control, widgets.Checkbox | widgets.ToggleButton):
        return [False, True]
    lo, hi = getattr(control, "min", None), getattr(control, "max", None)
    if lo is None or hi is None:
        return [control.value]
    if isinstance(control.value, int) and not isinstance(control.value, bool):
        span = sorted({round(lo + (hi - lo) * k / (n - 1)) for k in range(n)})
        return span
    return [lo + (hi - lo) * k / (n - 1) for k in range(n)]


def register(name: str) -> Callable[[Callable[[], Panel]], Callable[[], Panel]]:
    """Decorator: register a zero-argument panel factory under ``name``."""

    def deco(factory: Callable[[], Panel]) -> Callable[[], Panel]:
        if name in _FACTORIES:
            raise ValueError(f"a panel named {name!r} is already registered")
        _FACTORIES[name] = factory
        return factory

    return deco


def all_panels() -> dict[str, Callable[[], Panel]]:
    """Every registered panel factory, by name (imports every chapter's module)."""
    load_chapter_modules(__name__, CHAPTER_MODULES)
    return dict(_FACTORIES)
