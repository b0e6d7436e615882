"""wheelkin.animation's frame check: every frame of a player, when the run checks figures or
when the caller asks (``check=True``, as ``wheelkin.display.play`` does).

The animations move a 10 pt label across a 4 x 3 in figure; at x = 0.9 of the width the label
(about 1 in long) runs off the right edge, which the check reports as "cut off".
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest
from matplotlib.animation import FuncAnimation

from wheelkin import animation, style


@pytest.fixture(autouse=True)
def _style(monkeypatch):
    with matplotlib.rc_context():
        monkeypatch.setenv(style.CHECK_ENV, "0")
        style.setup()
        yield
        monkeypatch.setenv(style.CHECK_ENV, "0")
        style.setup()
    plt.close("all")


def _label_animation(xs):
    figure = plt.figure(figsize=(4, 3), dpi=100)
    text = figure.text(0.1, 0.5, "moving label", fontsize=10)
    return FuncAnimation(figure, lambda i: [text.set_x(xs[i])], frames=len(xs))


def test_check_true_checks_every_frame_with_the_run_check_off():
    assert not style.checking()
    anim = _label_animation([0.1, 0.5, 0.9, 0.5])
    with pytest.raises(style.FigureCheckError, match=r"animation 'mid': frame 2: cut off"):
        animation.to_html(anim, name="mid", alt="a label", check=True)


def test_the_run_check_covers_the_middle_frames_too(monkeypatch):
    monkeypatch.setenv(style.CHECK_ENV, "1")
    style.setup()
    anim = _label_animation([0.1, 0.9, 0.1])
    with pytest.raises(style.FigureCheckError, match=r"frame 1: cut off"):
        animation.to_html(anim, name="mid", alt="a label")


def test_the_animation_check_can_be_turned_off_for_one_animation(monkeypatch):
    monkeypatch.setenv(style.CHECK_ENV, "1")
    style.setup()
    anim = _label_animation([0.1, 0.9])
    assert "_anim_img" in animation.to_html(anim, name="off", alt="a label", check=False)


def test_the_animation_check_flag_must_be_a_bool_or_none():
    anim = _label_animation([0.1, 0.2])
    with pytest.raises(ValueError, match="check must be True, False or None"):
        animation.to_html(anim, name="x", alt="x", check="yes")
    animation.to_html(anim, name="x", alt="x")  # rendered: no warning when it is collected
