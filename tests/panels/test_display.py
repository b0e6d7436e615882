"""wheelkin.display: the book's display helpers, against values written out by hand.

A table's Markdown is compared with the text a reader would type; an equation's LaTeX with
the LaTeX of the expression written by hand; the figure check with a font size that is too
small by hand calculation (5 pt at 100 dpi is 6.9 px on screen, the book asks for 11 px); the
animation check with a label that leaves the figure in one middle frame only.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest
import sympy as sp
from IPython.display import HTML, Markdown
from matplotlib.animation import FuncAnimation

from wheelkin import display, style


@pytest.fixture(autouse=True)
def _style():
    with matplotlib.rc_context():
        style.setup()
        yield
    plt.close("all")


def _figure(fontsize: float = 10.0):
    fig, ax = plt.subplots(figsize=(4, 3), dpi=100)
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("x (m)", fontsize=fontsize)
    ax.set_ylabel("y (m)")
    return fig


# --------------------------------------------------------------------------- tables


def test_md_table_text():
    table = display.md_table(["vehicle", "δm", "slip (mm)"],
                             [["mecanum", 3, "0.000"], ["skid steer", 1, f"{12.345:.1f}"]])
    assert isinstance(table, Markdown)
    assert table.data == ("| vehicle | δm | slip (mm) |\n"
                          "| --- | --- | --- |\n"
                          "| mecanum | 3 | 0.000 |\n"
                          "| skid steer | 1 | 12.3 |")


def test_md_table_accepts_any_iterable_of_rows_and_no_rows():
    rows = ((f"P{k}", k * k) for k in range(3))
    assert display.md_table(("point", "k²"), rows).data.splitlines()[2:] == [
        "| P0 | 0 |", "| P1 | 1 |", "| P2 | 4 |"]
    assert display.md_table(["only"], []).data == "| only |\n| --- |"


def test_md_table_escapes_a_pipe_in_a_cell():
    assert display.md_table(["$|v|$"], [["a|b"]]).data == "| $\\|v\\|$ |\n| --- |\n| a\\|b |"


@pytest.mark.parametrize(("header", "rows", "message"), [
    ([], [], "header must be a non-empty sequence"),
    ("ab", [], "header must be a non-empty sequence"),
    (["a", "b"], [["1", "2"], ["3"]], r"rows\[1\] has 1 cell, the header has 2"),
    (["a"], [["1", "2"]], r"rows\[0\] has 2 cells, the header has 1"),
    (["a"], ["x"], r"rows\[0\] must be a sequence of cells"),
    (["a"], "x", "rows must be an iterable of rows"),
    (["a"], [["two\nlines"]], r"rows\[0\]\[0\] holds a line break"),
    (["a\nb"], [], r"header\[0\] holds a line break"),
])
def test_md_table_bad_input_names_the_parameter(header, rows, message):
    with pytest.raises(ValueError, match=message):
        display.md_table(header, rows)


# --------------------------------------------------------------------------- equations


def test_equation_latex_of_a_sympy_expression_and_of_text():
    v, w, W = sp.symbols("v omega W")
    assert display.equation_latex(r"v_L", v - w * W / 2) == r"v_L = - \frac{W \omega}{2} + v"
    assert display.equation_latex(r"\theta", r"\frac{\pi}{2}") == r"\theta = \frac{\pi}{2}"


def test_show_eq_displays_the_equation(capsys):
    display.show_eq("x", sp.Integer(2))
    assert capsys.readouterr().out.strip() == "<IPython.core.display.Math object>"


@pytest.mark.parametrize("lhs", ["", "  ", None, 3])
def test_show_eq_needs_a_left_hand_side(lhs):
    with pytest.raises(ValueError, match="lhs must be a non-empty LaTeX string"):
        display.show_eq(lhs, "1")


def test_say_displays_markdown_and_refuses_a_number(capsys):
    display.say("It turns at **7.5** rad/s.")
    assert "Markdown" in capsys.readouterr().out
    with pytest.raises(ValueError, match="text must be a string"):
        display.say(7.5)


# --------------------------------------------------------------------------- figures


def test_show_figure_fails_on_tiny_text():
    fig = _figure(fontsize=5.0)  # 5 pt x 100 dpi / 72 = 6.9 px < 11 px
    with pytest.raises(style.FigureCheckError, match=r"too small: 'x \(m\)' is 6\.9 px"):
        display.show_figure(fig)


def test_show_figure_fails_on_text_cut_off():
    fig = _figure()
    fig.text(0.95, 0.5, "a label running off the edge")
    with pytest.raises(style.FigureCheckError, match="cut off: 'a label running off"):
        display.show_figure(fig)


def test_show_figure_shows_a_legible_figure_once_and_closes_it(capsys):
    fig = _figure()
    display.show_figure(fig)
    assert capsys.readouterr().out.strip() == "Figure(400x300)"
    assert not plt.fignum_exists(fig.number)


def test_show_figure_refuses_what_is_not_a_figure():
    with pytest.raises(ValueError, match="fig must be a matplotlib Figure"):
        display.show_figure(plt.subplots()[1])


# --------------------------------------------------------------------------- animations


def _label_animation(xs):
    figure = plt.figure(figsize=(4, 3), dpi=100)
    text = figure.text(0.1, 0.5, "moving label", fontsize=10)
    return FuncAnimation(figure, lambda i: [text.set_x(xs[i])], frames=len(xs))


def test_play_checks_every_frame_even_with_the_figure_check_off(monkeypatch):
    monkeypatch.setenv(style.CHECK_ENV, "0")
    style.setup()
    assert not style.checking()
    anim = _label_animation([0.1, 0.3, 0.9, 0.3, 0.1])  # only frame 2 runs off the edge
    with pytest.raises(style.FigureCheckError,
                       match=r"animation 'moving': frame 2: cut off: 'moving label'"):
        display.play(anim, name="moving", alt="a label moving right and back")


def test_play_names_the_first_and_the_last_frame():
    with pytest.raises(style.FigureCheckError, match=r"first frame: cut off.*last frame: cut"):
        display.play(_label_animation([0.9, 0.1, 0.9]), name="edges", alt="a label")


def test_play_gives_the_player_with_its_alt_text_and_caption():
    anim = _label_animation([0.1, 0.3, 0.5])
    player = display.play(anim, name="fine", alt="a label moving right", caption="Moving.")
    assert isinstance(player, HTML)
    assert 'alt="a label moving right"' in player.data
    assert "<figcaption>Moving.</figcaption>" in player.data


def test_play_refuses_to_turn_the_check_off():
    with pytest.raises(ValueError, match="play always checks the frames"):
        display.play(object(), name="x", alt="x", check=False)


def test_public_functions_are_typed_and_documented():
    import inspect

    for name in display.__all__:
        fn = getattr(display, name)
        signature = inspect.signature(fn)
        assert signature.return_annotation is not inspect.Signature.empty, name
        assert all(p.annotation is not inspect.Parameter.empty
                   for p in signature.parameters.values()), name
        assert fn.__doc__ and fn.__doc__.strip(), name



# ------------------------------------------------- the check show_figure relies on (style)


def test_tick_labels_beyond_a_log_axis_are_not_checked():
    # 1e-10 .. 0.1 on a log axis: the locator also places 1e-12 below the axis, never drawn;
    # an absolute tolerance of 1e-9 would have counted it as inside (and cut off).
    fig, ax = plt.subplots(figsize=(4, 3), dpi=100)
    ax.semilogy([0, 1], [1e-9, 1e-2])
    ax.set_ylim(1e-10, 1e-1)
    drawn = {t.get_text() for t in ax.get_yticklabels() if t.get_visible()}
    assert any("-12" in t for t in drawn)  # the tick exists ...
    display.show_figure(fig)  # ... and is not reported


def test_an_axis_that_is_off_is_not_checked():
    fig, ax = plt.subplots(figsize=(3, 3), dpi=100)
    ax.plot([0, 1], [0, 1])
    ax.set_position([0.0, 0.0, 1.0, 1.0])  # tick labels would lie outside the figure ...
    assert any(p.startswith("cut off") for p in style.check_figure(fig))
    ax.axis("off")  # ... but are not drawn
    display.show_figure(fig)
