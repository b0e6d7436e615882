"""The chapters follow the notation page (book/notation.md, docs/DESIGN.md "One notation").

Two decisions are checked in the text of every chapter (markdown cells of the notebooks and the
chapters' landing pages), sentence by sentence (a table row counts as a sentence):

- "wheel base" / "wheelbase" means the front-to-back length L only: a sentence that calls the
  track (the side-to-side W) a wheel base fails, unless it quotes or translates a source (the
  word in quotes or code, or the sentence names the source: README, firmware, UMBmark, ...);
- the steering angle δ is positive to the left: a sentence that defines δ as positive to the
  right (or clockwise) fails, unless the δ carries a source's subscript (δ_OSR) or is named
  as the source's ("the document's δ", "its angle δ").

Simple text rules, not understanding: they catch the two errors the review found and their
close variants; the detector itself is tested on sentences written for the purpose.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

from tools.book_pages import NOTEBOOKS, notebook_id, notebooks

ROOT = Path(__file__).resolve().parents[2]

#: Words that put a sentence in a source's context (quoting or translating its convention).
SOURCE_CONTEXT = re.compile(
    r"README|firmware|UMBmark|Borenstein|\bOSR\b|Open Source Rover|the document|the source|"
    r"the lab's|simulator|\bits\b|\bcalls?\b|\bwrites?\b|\bsays?\b|\bquot|\btranslat|"
    r"\\mathrm\{(?:OSR|src)\}|_\{?\\?(?:mathrm\{)?(?:OSR|src|doc)", re.IGNORECASE)
#: "wheel base", "wheelbase" (not a source's identifier such as the firmware's `wheelBase`).
WHEEL_BASE = re.compile(r"[Ww]heel[ -]?base")
QUOTED_WHEEL_BASE = re.compile(r"[\"“'`‘*][^\"”'`’*]{0,20}[Ww]heel[ -]?base[^\"”'`’*]{0,20}[\"”'`’*]")
#: Marks of the side-to-side length next to the word.
TRACK = re.compile(r"\btrack\b|\$W\b|\bW\b|side[- ]to[- ]side|wheel to wheel", re.IGNORECASE)
#: Where one phrase ends and the next begins: "half the wheelbase plus half the track".
SEPARATOR = re.compile(r"[,;|]|\b(?:and|plus|against|versus|or|than|while|but|relative to|"
                       r"compared (?:with|to)|divided by|over)\b")
WINDOW = 30
DELTA = re.compile(r"\\delta(?!_[{]?\\?(?:mathrm\{)?(?:OSR|src|m|s|M)\b)|δ(?!_?(?:OSR|src))")
RIGHT_POSITIVE = re.compile(
    r"(?:positive|>\s*0|\+)[^.|]{0,60}\b(?:right|clockwise)\b|"
    r"\b(?:right|clockwise)\b[^.|]{0,30}(?:positive|\+)", re.IGNORECASE)
#: δ named as a source's ("the document's δ", "its angle δ"): the source's convention, quoted.
SOURCE_DELTA = re.compile(r"(?:document's|source's|OSR's|\bits|\btheir)\s+(?:\w+\s+){0,2}"
                          r"(?:\$|\\\(|)\s*(?:\\delta|δ)")
#: A sentence that writes the source's δ with its subscript is a translation (δ = -δ_OSR).
TRANSLATED_DELTA = re.compile(r"\\delta_\{?\\?(?:mathrm\{)?(?:OSR|src)|δ_?(?:OSR|src)")
COUNTER = re.compile(r"counter-?clockwise|anti-?clockwise|to the left|turns? left", re.IGNORECASE)


def sentences(text: str) -> list[str]:
    """Table rows, and the sentences of each paragraph (wrapped lines joined)."""
    out = []
    for paragraph in re.split(r"\n\s*\n", text):
        rows = [line for line in paragraph.splitlines() if line.lstrip().startswith("|")]
        out.extend(rows)
        prose = " ".join(line for line in paragraph.splitlines()
                         if not line.lstrip().startswith("|"))
        flat = " ".join(prose.split())
        out.extend(s for s in re.split(r"(?<=[.!?])\s+(?=[A-Z$({*])", flat) if s.strip())
    return out


def _near(sentence: str, start: int, end: int) -> str:
    """The text around [start, end) up to the nearest phrase separator, WINDOW chars at most."""
    before = sentence[max(0, start - WINDOW):start]
    after = sentence[end:end + WINDOW]
    cut = list(SEPARATOR.finditer(before))
    before = before[cut[-1].end():] if cut else before
    cut_after = SEPARATOR.search(after)
    after = after[:cut_after.start()] if cut_after else after
    return before + " " + after


def wheel_base_for_track(sentence: str) -> bool:
    """Does the sentence call the track (side-to-side, W) a wheel base, outside a source?"""
    if QUOTED_WHEEL_BASE.search(sentence) or SOURCE_CONTEXT.search(sentence):
        return False
    return any(TRACK.search(_near(sentence, m.start(), m.end()))
               for m in WHEEL_BASE.finditer(sentence))


def delta_right_positive(sentence: str) -> bool:
    """Does the sentence define the steering angle δ as positive to the right?"""
    if not DELTA.search(sentence) or not RIGHT_POSITIVE.search(sentence):
        return False
    if SOURCE_DELTA.search(sentence) or TRANSLATED_DELTA.search(sentence):
        return False  # the source's own δ, named as the source's or converted to ours
    if COUNTER.search(sentence) and not re.search(r"(?<!counter-)(?<!anti-)\bclockwise\b|"
                                                  r"\bright\b", sentence):
        return False
    return True


def _texts(path: Path) -> str:
    if path.suffix == ".md":
        return path.read_text(encoding="utf-8")
    nb = nbformat.read(path, as_version=4)
    return "\n\n".join(c.source for c in nb.cells if c.cell_type == "markdown")


def _chapter_files() -> list[Path]:
    pages = sorted(p for p in NOTEBOOKS.rglob("*.md") if ".ipynb_checkpoints" not in p.parts)
    return notebooks() + pages


FILES = _chapter_files()


@pytest.mark.parametrize("path", FILES, ids=lambda p: notebook_id(p))
def test_wheel_base_means_the_wheelbase(path):
    found = sorted({s.strip()[:160] for s in sentences(_texts(path)) if wheel_base_for_track(s)})
    assert not found, (f"{notebook_id(path)} calls the track width W a wheel base (the notation "
                       "page: 'wheel base' means L only; quote a source's word in quotes):\n"
                       + "\n".join(found))


@pytest.mark.parametrize("path", FILES, ids=lambda p: notebook_id(p))
def test_steering_angle_is_positive_to_the_left(path):
    found = sorted({s.strip()[:160] for s in sentences(_texts(path)) if delta_right_positive(s)})
    assert not found, (f"{notebook_id(path)} defines δ as positive to the right (the notation "
                       "page: δ > 0 turns left; a source's δ is written δ_OSR):\n"
                       + "\n".join(found))


# --- the detector, on sentences written for the purpose ----------------------------------------

@pytest.mark.parametrize(("sentence", "flagged"), [
    ("The Zumo has two driven wheels, 85 mm apart (the wheel base $W$).", True),
    ("The wheel base W is the distance between the left and right wheels.", True),
    ('The firmware calls the track width $W$ its "wheel base".', False),
    ("| track width (\"wheel base\" in the README) | $W$ | 85 | mm |", False),
    ("The wheelbase $L$ is the front-to-back distance between the axles.", False),
    ("Borenstein's UMBmark calls the track the wheelbase b.", False),
    ("The track W is 0.12 m.", False),
    ("$k$ is the sum of half the wheelbase and half the track width.", False),
    ("| wheelBase | $W$ | track width: wheel to wheel, mm |", False),
    ("A shorter wheelbase relative to the track width slides less.", False),
])
def test_wheel_base_detector(sentence, flagged):
    assert wheel_base_for_track(sentence) is flagged


@pytest.mark.parametrize(("sentence", "flagged"), [
    ("A corner angle $\\delta_i>0$ means the wheel's front edge is turned toward the right.",
     True),
    ("The steering angle δ is positive clockwise.", True),
    ("The steering angle $\\delta$ is positive to the left (counter-clockwise).", False),
    ("The document's angle $\\delta_\\mathrm{OSR} > 0$ turns the rover right.", False),
    ("| $\\delta_i$ | steering angle, counter-clockwise + (rad) |", False),
    ("The rover document measures its angle positive to the right; we write it δ_OSR.", False),
    ("The document's angle $\\delta$ is positive to the right.", False),
    ("| its steering angle, **positive right** | $\\delta_\\mathrm{OSR} = -\\delta$ |", False),
])
def test_delta_detector(sentence, flagged):
    assert delta_right_positive(sentence) is flagged


def test_the_first_edition_errors_are_caught():
    """The two sentences of the first edition that the review found, as they were written."""
    odometry = ("The Zumo has two driven wheels, 85 mm apart (the wheel base $W$, measured "
                "from wheel to wheel as in the rest of the book), and a skid at the back.")
    rover = ("A corner angle $\\delta_i>0$ means the wheel's front edge is turned toward the "
             "rover's right, as in the document's figure.")
    assert wheel_base_for_track(odometry)
    assert any(delta_right_positive(s) for s in sentences(rover)) or delta_right_positive(rover)
