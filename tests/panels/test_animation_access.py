"""wheelkin.animation's player for assistive technology: a named frame slider, a pause icon
that is a symbol, and a description of what happens tied to the frames.

The HTML is parsed (html.parser), not searched as text: the test reads the attributes a
screen reader would, and follows ``aria-describedby`` to the element it names.
"""

from __future__ import annotations

from html.parser import HTMLParser

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest
from matplotlib.animation import FuncAnimation

from wheelkin import animation

#: An animation refused before it is drawn warns when it is collected; that is expected here.
pytestmark = pytest.mark.filterwarnings(
    "ignore:Animation was deleted without rendering:UserWarning",
    "ignore::pytest.PytestUnraisableExceptionWarning")


class _Elements(HTMLParser):
    """Every start tag with its attributes, and the text inside each element with an id."""

    def __init__(self):
        super().__init__()
        self.tags: list[tuple[str, dict]] = []
        self.text: dict[str, str] = {}
        self._open: list[str | None] = []

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        self.tags.append((tag, attributes))
        if tag not in ("input", "img", "br", "meta", "link"):
            self._open.append(attributes.get("id"))
            if attributes.get("id"):
                self.text.setdefault(attributes["id"], "")

    def handle_endtag(self, tag):
        if self._open and tag not in ("input", "img", "br", "meta", "link"):
            self._open.pop()

    def handle_data(self, data):
        for element in self._open:
            if element:
                self.text[element] += data


def _parse(html: str) -> _Elements:
    parser = _Elements()
    parser.feed(html)
    return parser


def _dot_animation():
    figure = plt.figure(figsize=(3, 2), dpi=50)
    axes = figure.add_axes((0, 0, 1, 1))
    axes.set_xlim(0, 4)
    (dot,) = axes.plot([0], [0.5], "o")
    return FuncAnimation(figure, lambda i: [dot.set_xdata([i])], frames=4)


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def test_frame_slider_is_named_and_pause_is_a_symbol():
    page = _parse(animation.to_html(_dot_animation(), name="dot", alt="A dot", colors=None))
    sliders = [a for t, a in page.tags if t == "input" and a.get("type") == "range"]
    assert [s.get("aria-label") for s in sliders] == [animation.FRAME_SLIDER_LABEL]
    pause = [a for t, a in page.tags if t == "button" and a.get("aria-label") == "Pause"]
    assert len(pause) == 1
    html = animation.to_html(_dot_animation(), name="dot", alt="A dot", colors=None)
    pause_html = html[html.index('aria-label="Pause"'):]
    pause_html = pause_html[:pause_html.index("</button>")]
    assert ">II<" not in pause_html and "&#10074;&#10074;" in pause_html


def test_description_is_shown_in_a_fold_and_tied_to_the_frames():
    text = "The dot moves from the left edge to the right in four steps; notice it never stops."
    page = _parse(animation.to_html(_dot_animation(), name="dot", alt="A dot on a line",
                                    caption="A moving dot.", colors=None, description=text))
    images = [a for t, a in page.tags if t == "img"]
    assert len(images) == 1 and images[0]["alt"] == "A dot on a line"
    target = images[0].get("aria-describedby")
    assert target and page.text[target] == text
    assert any(t == "details" and "wheelkin-animation-description" in a.get("class", "")
               for t, a in page.tags)


def test_without_description_nothing_points_nowhere():
    page = _parse(animation.to_html(_dot_animation(), name="dot", alt="A dot", colors=None))
    assert not [a for t, a in page.tags if "aria-describedby" in a]


@pytest.mark.parametrize("bad", ["", "   ", 3])
def test_bad_description_is_refused(bad):
    with pytest.raises(ValueError, match="description must be a non-empty text"):
        animation.to_html(_dot_animation(), name="dot", alt="A dot", description=bad)


def test_accessible_player_mends_a_stored_player_once():
    """A player written before the library named its slider, as a notebook may store it."""
    html = animation.to_html(_dot_animation(), name="old", alt="A dot", colors=None)
    old = html.replace(f' aria-label="{animation.FRAME_SLIDER_LABEL}"', "").replace(
        "&#10074;&#10074;", "II")
    mended = animation.accessible_player(old)
    assert mended == html
    assert animation.accessible_player(mended) == mended
