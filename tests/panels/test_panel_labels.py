"""Every control of every live panel is named in words that a screen reader can announce.

ipywidgets shows a control's ``description`` as its label, and it is what a screen reader
reads for it (and what the precomputed view of the panel labels its slider with). A symbol
alone ("μ", "δ (deg)") is read as a Greek letter's name, or as nothing useful: each
description holds at least one word of three letters or more outside its unit's
parentheses, and is shown whole (not cut to ipywidgets' default label width).
"""

from __future__ import annotations

import re

import pytest

from wheelkin.widgets import all_panels

PANELS = sorted(all_panels())
#: A word a listener understands: three letters or more (a symbol such as "vx" is not one).
WORD = re.compile(r"[A-Za-z]{3,}")


def _named_in_words(description: str) -> bool:
    outside_units = re.sub(r"\([^)]*\)", " ", description)
    return WORD.search(outside_units) is not None


@pytest.mark.parametrize("description, ok", [
    ("μ", False), ("δ (deg)", False), ("vx (m/s)", False), ("L_d (m)", False),
    ("friction μ", True), ("yaw rate ω (rad/s)", True), ("command", True),
    ("speed (%)", True), ("(deg) only", True),
])
def test_the_rule(description, ok):
    assert _named_in_words(description) is ok


@pytest.mark.parametrize("name", PANELS)
def test_every_control_is_named_in_words(name):
    panel = all_panels()[name]()
    try:
        for key, control in panel.controls.items():
            description = getattr(control, "description", "") or ""
            assert description.strip(), f"{name}: control {key!r} has no description"
            assert _named_in_words(description), (
                f"{name}: control {key!r} is described {description!r}: add a word that "
                "says what it sets (e.g. 'yaw rate ω (rad/s)')")
            width = getattr(getattr(control, "style", None), "description_width", None)
            assert width != "", f"{name}: control {key!r}'s label is cut to the default width"
    finally:
        import matplotlib.pyplot as plt

        plt.close(panel.figure)
