"""wheelkin.style: the legibility check, and the hooks that run it on every figure shown.

The expected values are hand calculations: a font of s pt drawn at d dpi and shown at its
drawn width is s x d / 72 px tall on screen (8 pt at 100 dpi: 11.1 px; 7 pt: 9.7 px).
"""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest
from matplotlib.animation import FuncAnimation

from wheelkin import animation, style


@pytest.fixture
def fig():
    with matplotlib.rc_context():
        style.setup()
        figure, ax = plt.subplots(figsize=(4, 3), dpi=100)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        yield figure
        plt.close(figure)


def kinds(problems: list[str]) -> list[str]:
    return sorted({p.split(":")[0] for p in problems})


def test_a_clean_figure_has_no_problem(fig):
    fig.axes[0].plot([0, 1], [0, 1], label="path")
    fig.axes[0].legend()
    assert style.check_figure(fig) == []


def test_tick_labels_outside_the_limits_are_not_drawn_so_not_checked(fig):
    # The locator of 0..1 (with margins) also makes ticks at -0.2 and 1.2, never drawn.
    ax = fig.axes[0]
    ax.plot([0, 1], [0, 1])
    fig.canvas.draw()
    labels = {t.get_text() for t in ax.xaxis.get_ticklabels()}
    assert "\N{MINUS SIGN}0.2" in labels
    assert style.check_figure(fig) == []


@pytest.fixture
def blank():
    """A figure with no axes: texts placed on it meet no tick label."""
    figure = plt.figure(figsize=(4, 3), dpi=100)
    yield figure
    plt.close(figure)


def test_the_smallest_font_is_8_pt_at_100_dpi(blank):
    # 8 pt x 100/72 = 11.1 px >= 11: allowed; 7 pt = 9.7 px: too small.
    fig = blank
    fig.text(0.1, 0.1, "eight", fontsize=8)
    assert style.check_figure(fig) == []
    fig.text(0.5, 0.1, "seven", fontsize=7)
    problems = style.check_figure(fig)
    assert kinds(problems) == ["too small"]
    assert "'seven' is 9.7 px" in problems[0]


def test_a_figure_shown_at_half_its_width_has_half_the_text(fig):
    # 10 pt at 100 dpi is 13.9 px drawn, 6.9 px when the page shows the figure at 200 px.
    problems = style.check_figure(fig, shown_width_px=200)
    assert "too small" in kinds(problems)
    assert any("'x (m)' is 6.9 px" in p for p in problems)


def test_two_texts_on_top_of_each_other_overlap(blank):
    fig = blank
    fig.text(0.4, 0.5, "body centre", fontsize=10)
    fig.text(0.42, 0.5, "bar value", fontsize=10)
    problems = style.check_figure(fig)
    assert kinds(problems) == ["overlap"]
    assert "'body centre' and 'bar value'" in problems[0]


def test_texts_side_by_side_do_not_overlap(blank):
    fig = blank
    fig.text(0.05, 0.5, "left", fontsize=10)
    fig.text(0.6, 0.5, "right", fontsize=10)
    assert style.check_figure(fig) == []


def test_a_text_that_leaves_the_figure_is_cut_off(blank):
    fig = blank
    fig.text(0.97, 0.5, "the time stamp", fontsize=10)
    assert kinds(style.check_figure(fig)) == ["cut off"]


def test_hidden_text_is_not_checked(fig):
    fig.text(0.97, 0.5, "hidden", fontsize=4).set_visible(False)
    assert style.check_figure(fig) == []


def test_bad_min_px_is_refused(fig):
    with pytest.raises(ValueError, match="min_px"):
        style.check_figure(fig, min_px=0)


def test_png_text_chunk_is_read_back_by_pil(fig):
    from PIL import Image

    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    tagged = style.png_with_text(buf.getvalue(), "wheelkin:min_font_pt", "8")
    assert Image.open(io.BytesIO(tagged)).text["wheelkin:min_font_pt"] == "8"
    with pytest.raises(ValueError, match="PNG"):
        style.png_with_text(b"GIF89a", "k", "v")


def test_min_font_pt(fig):
    fig.text(0.1, 0.1, "small", fontsize=8.5)
    assert style.min_font_pt(fig) == 8.5


def _moving_text_animation(last_x: float):
    figure = plt.figure(figsize=(4, 3), dpi=100)
    text = figure.text(0.1, 0.5, "moving label", fontsize=10)
    xs = [0.1, (0.1 + last_x) / 2, last_x]
    return FuncAnimation(figure, lambda i: [text.set_x(xs[i])], frames=3)


@pytest.mark.parametrize(("last_x", "cut"), [(0.5, False), (0.9, True)])
def test_animation_frames_are_checked_when_checking_is_on(monkeypatch, last_x, cut):
    with matplotlib.rc_context():
        monkeypatch.setenv(style.CHECK_ENV, "1")
        style.setup()
        assert style.checking()
        anim = _moving_text_animation(last_x)
        if cut:
            with pytest.raises(style.FigureCheckError, match="last frame: cut off"):
                animation.to_html(anim, name="moving", alt="a label moving right")
        else:
            assert "_anim_img" in animation.to_html(anim, name="moving", alt="a label")
        monkeypatch.setenv(style.CHECK_ENV, "0")
        style.setup()
    assert not style.checking()


def test_animation_frames_are_not_checked_when_checking_is_off(monkeypatch):
    with matplotlib.rc_context():
        monkeypatch.setenv(style.CHECK_ENV, "0")
        style.setup()
        html = animation.to_html(_moving_text_animation(0.9), name="moving", alt="a label")
    assert "_anim_img" in html


class _OwnWriterAnimation(FuncAnimation):
    """An animation whose HTML writer has its own grab_frame (as the sandbox's does)."""

    def to_jshtml(self, fps=None, embed_frames=True, default_mode=None):
        import tempfile
        from pathlib import Path

        from matplotlib.animation import HTMLWriter

        class OwnWriter(HTMLWriter):
            def grab_frame(self, **savefig_kwargs):
                self.fig.canvas.draw()
                return super().grab_frame(**savefig_kwargs)

        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp, "a.html")
            self.save(str(path), writer=OwnWriter(fps=5, embed_frames=True,
                                                  default_mode=default_mode or "loop"))
            return path.read_text()


def test_animation_with_its_own_writer_is_checked_too(monkeypatch):
    with matplotlib.rc_context():
        monkeypatch.setenv(style.CHECK_ENV, "1")
        style.setup()
        figure = plt.figure(figsize=(4, 3), dpi=100)
        text = figure.text(0.1, 0.5, "moving label", fontsize=10)
        anim = _OwnWriterAnimation(figure, lambda i: [text.set_x([0.1, 0.5, 0.9][i])], frames=3)
        with pytest.raises(style.FigureCheckError, match="last frame: cut off"):
            animation.to_html(anim, name="own", alt="a label moving right")
        monkeypatch.setenv(style.CHECK_ENV, "0")
        style.setup()
