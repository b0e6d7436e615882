r"""The book's display helpers: equations, tables, prose with numbers, figures, animations.

Every notebook of the book imports these in its first (folded) cell instead of defining its
own, as gtbook keeps ``gtbook.display`` in its package::

    from wheelkin.display import md_table, play, say, show_eq, show_figure

- :func:`show_eq` displays an equation ``lhs = rhs`` (a sympy expression or LaTeX text);
- :func:`md_table` builds a Markdown table (display it, or end a cell with it);
- :func:`say` displays a sentence of prose that carries computed numbers;
- :func:`show_figure` checks a figure with ``wheelkin.style.check_figure`` (text large
  enough, inside the figure, not overlapping) and shows it;
- :func:`play` shows an animation as a player that works without a kernel
  (``wheelkin.animation.to_html``), every frame checked the same way.

They need IPython (and sympy for :func:`show_eq` of an expression), which the book's
environment has.

>>> print(md_table(["wheel", "rate (rad/s)"], [["left", 7.5], ["right", 12.5]]).data)
| wheel | rate (rad/s) |
| --- | --- |
| left | 7.5 |
| right | 12.5 |
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

try:
    from IPython.display import HTML, Markdown, Math, display
except ModuleNotFoundError as exc:  # pragma: no cover - IPython comes with the notebook extra
    raise ModuleNotFoundError("wheelkin.display needs IPython: install the notebook extra, "
                              "pip install \".[notebook]\" from a checkout") from exc

__all__ = ["equation_latex", "md_table", "play", "say", "show_eq", "show_figure"]


def show_eq(lhs: str, rhs: Any) -> None:
    r"""Display the equation ``lhs = rhs``.

    Parameters
    ----------
    lhs : str
        The left-hand side, LaTeX (e.g. ``r"\omega_L"``).
    rhs : sympy expression or str
        The right-hand side: a sympy object (typeset with ``sympy.latex``) or LaTeX text,
        used as it is.

    Examples
    --------
    >>> import sympy as sp
    >>> show_eq("v", sp.Rational(1, 2) * sp.Symbol("omega"))
    <IPython.core.display.Math object>
    >>> show_eq(r"\theta", r"\frac{\pi}{2}")
    <IPython.core.display.Math object>
    """
    display(Math(equation_latex(lhs, rhs)))


def equation_latex(lhs: str, rhs: Any) -> str:
    r"""The LaTeX of ``lhs = rhs`` that :func:`show_eq` displays.

    >>> import sympy as sp
    >>> equation_latex(r"\omega", sp.Symbol("v") / sp.Symbol("R"))
    '\\omega = \\frac{v}{R}'
    >>> equation_latex("x", "1")
    'x = 1'
    """
    if not isinstance(lhs, str) or not lhs.strip():
        raise ValueError(f"lhs must be a non-empty LaTeX string, got {lhs!r}")
    if isinstance(rhs, str):
        body = rhs
    else:
        import sympy as sp  # type: ignore[import-untyped]

        body = sp.latex(rhs)
    return f"{lhs} = {body}"


def md_table(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> Markdown:
    r"""A Markdown table: display it, or end a cell with it.

    Parameters
    ----------
    header : sequence of str
        The column titles (at least one).
    rows : iterable of sequences
        One sequence of cells per row, as many as the header has; each cell is written with
        ``str`` (format numbers before, e.g. ``f"{x:.3f}"``). A ``|`` in a cell is escaped.

    Returns
    -------
    IPython.display.Markdown
        The table; its text is ``.data``. A ``ValueError`` names the row and the cell when
        the header is empty, a row has another number of cells than the header, or a cell
        holds a line break (a Markdown table row is one line).

    Examples
    --------
    >>> print(md_table(["a", "|v|"], [[1, "2"]]).data)
    | a | \|v\| |
    | --- | --- |
    | 1 | 2 |
    >>> md_table(["a", "b"], [[1]])
    Traceback (most recent call last):
    ...
    ValueError: rows[0] has 1 cell, the header has 2
    """
    if isinstance(header, str) or not isinstance(header, Sequence) or len(header) == 0:
        raise ValueError(f"header must be a non-empty sequence of column titles, got {header!r}")
    if isinstance(rows, str) or not isinstance(rows, Iterable):
        raise ValueError(f"rows must be an iterable of rows (sequences of cells), got {rows!r}")
    lines = [_row(header, "header"), "|" + " --- |" * len(header)]
    for i, row in enumerate(rows):
        if isinstance(row, str) or not isinstance(row, Sequence):
            raise ValueError(f"rows[{i}] must be a sequence of cells, got {row!r}")
        if len(row) != len(header):
            raise ValueError(f"rows[{i}] has {len(row)} cell{'s' if len(row) != 1 else ''}, "
                             f"the header has {len(header)}")
        lines.append(_row(row, f"rows[{i}]"))
    return Markdown("\n".join(lines))


def _row(cells: Sequence[Any], where: str) -> str:
    texts = []
    for j, cell in enumerate(cells):
        text = str(cell)
        if "\n" in text or "\r" in text:
            raise ValueError(f"{where}[{j}] holds a line break; a table cell is one line: "
                             f"{text!r}")
        texts.append(text.replace("|", r"\|"))
    return "| " + " | ".join(texts) + " |"


def say(text: str) -> None:
    """Display ``text`` as Markdown: a sentence of prose that carries computed numbers.

    >>> say(f"The wheel turns at {7.5:.1f} rad/s.")
    <IPython.core.display.Markdown object>
    """
    if not isinstance(text, str):
        raise ValueError(f"text must be a string of Markdown, got {type(text).__name__}")
    display(Markdown(text))


def show_figure(fig: Any) -> None:
    """Check ``fig`` with ``wheelkin.style.check_figure``, then show it (and close it).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A finished figure. It is shown once, where this is called, and closed so that the
        notebook does not show it a second time at the end of the cell. A problem raises
        ``wheelkin.style.FigureCheckError`` naming every text at fault: too small on the
        page, overlapping another, or cut off at the figure's edge.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from wheelkin import style
    >>> style.setup()
    >>> fig, ax = plt.subplots(figsize=(4, 3))
    >>> _ = ax.set_xlabel("x (m)", fontsize=5)
    >>> show_figure(fig)
    Traceback (most recent call last):
    ...
    wheelkin.style.FigureCheckError: figure: too small: 'x (m)' is 6.9 px on screen (at least 11)
    >>> plt.close(fig)
    """
    from matplotlib.figure import Figure

    from wheelkin import style

    if not isinstance(fig, Figure):
        raise ValueError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
    style.assert_readable(fig, "figure")
    display(fig)
    import matplotlib.pyplot as plt

    plt.close(fig)


def play(anim: Any, *, name: str, alt: str, caption: str | None = None,
         description: str | None = None, **kwargs: Any) -> HTML:
    """An animation as a player that runs in the static page, every frame checked.

    ``wheelkin.animation.to_html`` with ``check=True``: each frame is checked with
    ``wheelkin.style.check_figure`` as it is written, whether or not the figure check of
    the run is on.

    Parameters
    ----------
    anim : matplotlib.animation.Animation
        The animation (its figure is closed afterwards).
    name : str
        Unique on the page; the player's element ids are derived from it.
    alt : str
        What a reader who cannot see the frames should know.
    caption : str, optional
        Shown under the player.
    description : str, optional
        What happens, in words, and what to notice: in a collapsible note under the player,
        announced with the frames by screen readers. Every animation of the book has one.
    **kwargs
        ``fps``, ``default_mode``, ``max_bytes``, ``colors`` of
        ``wheelkin.animation.to_html``.

    Returns
    -------
    IPython.display.HTML
        The player: end a cell with it, or ``display`` it. A frame that is hard to read raises
        ``wheelkin.style.FigureCheckError`` naming the animation, the frame and the text.
    """
    from wheelkin import animation

    if "check" in kwargs:
        raise ValueError("play always checks the frames; use wheelkin.animation.show "
                         "to choose")
    return animation.show(anim, name=name, alt=alt, caption=caption, check=True,
                          description=description, **kwargs)
