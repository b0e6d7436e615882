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

from typing import Any

__all__ = ["COLUMN_WIDTH_IN", "DPI", "MIN_FONT_PT", "MIN_TEXT_PX", "check_figure", "setup"]

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
    """Set matplotlib's defaults to the book's style (call once, in a notebook's first cell)."""
    import matplotlib as mpl

    mpl.rcParams.update(_RC)
    try:  # the inline backend would otherwise crop or pad the figure ("tight" bbox)
        from IPython import get_ipython

        shell = get_ipython()
        if shell is not None:
            shell.run_line_magic("config", "InlineBackend.print_figure_kwargs = {'bbox_inches': None}")
    except ImportError:  # pragma: no cover - IPython is there wherever notebooks run
        pass


def _texts(fig: Any) -> list[Any]:
    from matplotlib.text import Text

    out = []
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip():
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
