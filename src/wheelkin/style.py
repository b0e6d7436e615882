r"""The book's figure style: every figure drawn at the size the page shows it, text legible.

A figure in the book is drawn at :data:`DPI` dots per inch and at most
:data:`COLUMN_WIDTH_IN` inches wide, so that its PNG is shown at its drawn size in the page's
text column (670 px at a 1280 px window). Text of :data:`MIN_FONT_PT` points is then

.. math:: 8\,\mathrm{pt} \times \frac{100\,\mathrm{px/in}}{72\,\mathrm{pt/in}} = 11.1\,\mathrm{px}

on screen, the smallest the book allows. :func:`setup` sets matplotlib's defaults to this style;
:func:`check_figure` lists what breaks it in a drawn figure: text that is too small, two texts
that overlap, text that leaves the figure.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> setup()
>>> fig, ax = plt.subplots(figsize=(4, 3))
>>> _ = ax.set_xlabel("x (m)")
>>> check_figure(fig)
[]
>>> _ = ax.text(0.5, 0.5, "tiny", fontsize=5)
>>> [problem.split(":")[0] for problem in check_figure(fig)]
['too small']
>>> plt.close(fig)
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

__all__ = ["CHECK_ENV", "COLUMN_WIDTH_IN", "DPI", "MIN_FONT_PT", "MIN_TEXT_PX", "FigureCheckError",
           "assert_readable", "check_figure", "checking", "fixed_layout", "min_font_pt", "setup"]

#: Dots per inch of every figure and animation frame.
DPI: int = 100
#: The widest figure, in inches, that the page shows at its drawn size (670 px).
COLUMN_WIDTH_IN: float = 6.7
#: The smallest font size allowed, in points (11.1 px on screen at :data:`DPI`).
MIN_FONT_PT: float = 8.0
#: The smallest text height on screen, in CSS pixels.
MIN_TEXT_PX: float = 11.0

_RC = {
    "figure.dpi": DPI,
    "savefig.dpi": DPI,
    "figure.figsize": (COLUMN_WIDTH_IN, 4.2),
    "font.size": 10.0,
    "axes.titlesize": 11.0,
    "axes.labelsize": 10.0,
    "xtick.labelsize": 9.0,
    "ytick.labelsize": 9.0,
    "legend.fontsize": 9.0,
    "figure.titlesize": 11.0,
    "legend.framealpha": 0.9,
    "axes.grid": False,
    "savefig.bbox": None,
    "figure.constrained_layout.use": True,
}


def setup() -> None:
    """Set matplotlib's defaults to the book's style (call once, in a notebook's first cell).

    In IPython it also makes the inline backend keep the figure's drawn size (no "tight"
    cropping) and wraps its PNG formatter: every figure a cell shows records its smallest font
    size in the PNG (a ``wheelkin:min_font_pt`` text chunk, read by
    ``benchmarks/reading.py``) and, when the environment variable
    :data:`CHECK_ENV` is ``1`` (``tools/execute_notebooks.py`` sets it), is checked with
    :func:`check_figure`: a problem raises :class:`FigureCheckError` in the cell that shows it.
    Animations shown with :func:`wheelkin.animation.show` are checked the same way.
    """
    import matplotlib as mpl

    global _CHECKING
    mpl.rcParams.update(_RC)
    _CHECKING = os.environ.get(CHECK_ENV, "") == "1"
    try:  # the inline backend would otherwise crop or pad the figure ("tight" bbox)
        from IPython import get_ipython

        shell = get_ipython()
        if shell is not None:
            import matplotlib.pyplot as plt

            # Load the backend now (pyplot loads it lazily, at the first figure), so that the
            # inline backend's PNG formatter exists and can be wrapped before any figure.
            plt.switch_backend(mpl.get_backend())
            shell.run_line_magic("config",
                                 "InlineBackend.print_figure_kwargs = {'bbox_inches': None}")
            _wrap_png_formatter(shell)
    except ImportError:  # pragma: no cover - IPython is there wherever notebooks run
        pass


class FigureCheckError(ValueError):
    """A figure or animation frame that :func:`check_figure` finds hard to read."""


#: The environment variable that turns the automatic figure check on (value ``1``).
CHECK_ENV = "WHEELKIN_CHECK_FIGURES"
_CHECKING = False


def fixed_layout() -> Any:
    """A layout engine for a figure laid out by hand (``subplots_adjust``, gridspec margins).

    Pass it as ``Figure(..., layout=fixed_layout())``. Not ``layout="none"``: a figure without
    an engine gets the book style's constrained layout back from its first ``savefig`` (which
    restores "no engine" as the rc default), so a panel's or an animation's frames after the
    first would move. A placeholder engine keeps the hand-set layout through every save.

    Examples
    --------
    >>> import io, matplotlib
    >>> from matplotlib.figure import Figure
    >>> with matplotlib.rc_context({"figure.constrained_layout.use": True}):  # as setup()
    ...     fig = Figure(figsize=(4, 3), layout=fixed_layout())
    ...     ax = fig.add_subplot(111); fig.subplots_adjust(left=0.3)
    ...     for _ in range(2):
    ...         fig.savefig(io.BytesIO(), format="png")
    >>> print(round(float(ax.get_position().x0), 2))
    0.3
    """
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    return PlaceHolderLayoutEngine(adjust_compatible=True, colorbar_gridspec=True)


def checking() -> bool:
    """Whether shown figures are checked: :func:`setup` ran with :data:`CHECK_ENV` = ``1``."""
    return _CHECKING


def assert_readable(fig: Any, what: str = "figure", **kwargs: Any) -> None:
    """Raise :class:`FigureCheckError` naming ``what`` and every problem of ``fig``."""
    found = check_figure(fig, **kwargs)
    if found:
        raise FigureCheckError(f"{what}: " + "; ".join(found))


def min_font_pt(fig: Any) -> float | None:
    """The smallest font size (pt) of the texts ``fig`` draws, or None if it has none."""
    sizes = [text.get_fontsize() for text in _texts(fig)]
    return min(sizes) if sizes else None


def png_with_text(data: bytes, key: str, value: str) -> bytes:
    r"""``data`` (a PNG) with a ``tEXt`` chunk ``key=value`` inserted after its header.

    >>> import struct, zlib
    >>> ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0)
    >>> def chunk(kind, body):
    ...     crc = zlib.crc32(kind + body)
    ...     return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", crc)
    >>> png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IEND", b"")
    >>> b"tEXtk\x00v" in png_with_text(png, "k", "v")
    True
    """
    import struct
    import zlib

    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("data must be a PNG (it does not start with the PNG signature)")
    length = struct.unpack(">I", data[8:12])[0]
    end_of_header = 8 + 12 + length
    body = key.encode("latin-1") + b"\0" + value.encode("latin-1")
    chunk = (struct.pack(">I", len(body)) + b"tEXt" + body
             + struct.pack(">I", zlib.crc32(b"tEXt" + body) & 0xFFFFFFFF))
    return data[:end_of_header] + chunk + data[end_of_header:]


def _wrap_png_formatter(shell: Any) -> None:
    """Wrap the inline backend's PNG formatter of figures (once): record, then check."""
    import base64

    from matplotlib.figure import Figure

    formatter = shell.display_formatter.formatters.get("image/png")
    if formatter is None:  # pragma: no cover - a shell without the PNG formatter
        return
    try:
        original = formatter.lookup_by_type(Figure)
    except KeyError:  # not the inline backend: nothing to wrap
        return
    if getattr(original, "_wheelkin_wrapped", False):
        return

    def png(fig: Any, *args: Any, **kwargs: Any) -> Any:
        if _CHECKING:
            assert_readable(fig, "figure")
        out = original(fig, *args, **kwargs)
        smallest = min_font_pt(fig)
        if out is None or smallest is None:
            return out
        value = f"{smallest:g}"
        if isinstance(out, bytes):
            return png_with_text(out, "wheelkin:min_font_pt", value)
        if isinstance(out, str):  # base64
            raw = png_with_text(base64.b64decode(out), "wheelkin:min_font_pt", value)
            return base64.b64encode(raw).decode("ascii")
        return out  # pragma: no cover - (data, metadata) tuples of the retina formatter

    png._wheelkin_wrapped = True  # type: ignore[attr-defined]
    formatter.for_type(Figure, png)


def _undrawn_tick_labels(fig: Any) -> set[int]:
    """ids of the axis texts matplotlib keeps but does not draw: ticks outside the view, and
    every text of an axis that is switched off.

    A locator places ticks beyond the axis limits (a plot of 0..1 has a tick at -0.2; a log
    axis from 1e-10 to 0.1 one at 1e-12); their labels are visible Text objects that are never
    drawn, so they are not checked. The limits are compared on the axis's own scale (decades
    on a log axis). An axes with ``axis("off")`` draws none of its axes' texts.
    """
    from matplotlib.text import Text

    skip: set[int] = set()
    for ax in fig.get_axes():
        for axis in (getattr(ax, "xaxis", None), getattr(ax, "yaxis", None)):
            if axis is None:
                continue
            if not getattr(ax, "axison", True):
                skip.update(id(text) for text in axis.findobj(Text))
                continue
            scale = axis.get_transform()
            with np.errstate(all="ignore"):
                lo, hi = sorted(scale.transform(np.asarray(axis.get_view_interval(), float)))
            tol = 1e-9 * max(1.0, abs(lo), abs(hi))
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                loc = tick.get_loc()
                with np.errstate(all="ignore"):
                    where = None if loc is None else float(scale.transform([loc])[0])
                if where is None or not lo - tol <= where <= hi + tol:
                    skip.update({id(tick.label1), id(tick.label2)})
    return skip


def _texts(fig: Any) -> list[Any]:
    from matplotlib.text import Text

    out = []
    undrawn = _undrawn_tick_labels(fig)
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip() or id(text) in undrawn:
            continue
        # A tick label of a hidden axis, or of an axis without ticks, is never drawn.
        axes = text.axes
        if axes is not None and not axes.get_visible():
            continue
        out.append(text)
    return out


def check_figure(
    fig: Any,
    *,
    min_px: float = MIN_TEXT_PX,
    shown_width_px: float | None = None,
    overlap_px: float = 1.0,
    draw: bool = True,
) -> list[str]:
    """What makes ``fig`` hard to read on the page: a list of problems, empty when none.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure, drawn or not (it is drawn here with the Agg renderer).
    min_px : float
        The smallest text height on screen, in CSS pixels (default :data:`MIN_TEXT_PX`).
    shown_width_px : float, optional
        The width at which the page shows the figure; default: its drawn width, or the column
        (:data:`COLUMN_WIDTH_IN` x :data:`DPI` px) if it is wider, since the page scales it down.
    overlap_px : float
        Two texts whose boxes overlap by more than this many pixels in both directions overlap.
    draw : bool
        Draw the figure first (default). ``False`` measures it as it was last drawn (for a
        frame that was just saved: an animation's frame, a panel's redraw).

    Returns
    -------
    list of str
        One line per problem: ``"too small: ..."``, ``"overlap: ..."`` or ``"cut off: ..."``.
    """
    if not (isinstance(min_px, (int, float)) and 0 < min_px < 100):
        raise ValueError(f"min_px must be in (0, 100) px, got {min_px!r}")
    canvas = fig.canvas
    if not hasattr(canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        canvas = FigureCanvasAgg(fig)
        draw = True
    if draw:
        canvas.draw()
    renderer = canvas.get_renderer()
    width_px = fig.get_figwidth() * fig.dpi
    column_px = COLUMN_WIDTH_IN * DPI
    shown = shown_width_px if shown_width_px is not None else min(width_px, column_px)
    scale = shown / width_px
    problems: list[str] = []
    boxes = []
    fig_box = fig.bbox
    for text in _texts(fig):
        label = text.get_text().strip().replace("\n", " ")[:40]
        px = text.get_fontsize() * fig.dpi / 72.0 * scale
        if px < min_px - 1e-9:
            problems.append(f"too small: {label!r} is {px:.1f} px on screen (at least {min_px:g})")
        box = text.get_window_extent(renderer)
        if (box.x0 < fig_box.x0 - 0.5 or box.y0 < fig_box.y0 - 0.5
                or box.x1 > fig_box.x1 + 0.5 or box.y1 > fig_box.y1 + 0.5):
            problems.append(f"cut off: {label!r} leaves the figure")
        boxes.append((label, box))
    for i, (label_a, a) in enumerate(boxes):
        for label_b, b in boxes[i + 1:]:
            dx = min(a.x1, b.x1) - max(a.x0, b.x0)
            dy = min(a.y1, b.y1) - max(a.y0, b.y0)
            if dx > overlap_px and dy > overlap_px:
                problems.append(f"overlap: {label_a!r} and {label_b!r}")
    return problems
