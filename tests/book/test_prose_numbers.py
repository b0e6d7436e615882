"""Numbers in the prose come from cells (docs/DESIGN.md, "Every number in the prose is produced
by a cell").

Every number with two or more significant digits in a markdown cell of a chapter page must
appear in an output of that page, or of a page the same cell links to (``{ref}``, ``{doc}``).
A number matches an output's number if it is the same number written the same way, or that
number rounded to the prose's decimals (the prose may quote 0.741 as 0.74, never 0.74 as
0.741). The chapters' landing pages (``index.md``) have no outputs: their numbers must come
from the pages they link.

What is not checked, and why (the allowlist; each entry is a reason, not a number):

- code (fenced blocks and inline ``code``): it quotes code, the sources' or the library's;
- a number glued to letters (``int32``, ``Q16``, ``32U4``, ``P12``): a name, not a quantity;
- exponents (``10^{-6}``, ``2^{31}``): the notation of powers;
- years and dates (an 18xx-20xx integer that no unit follows; a day before a month's name);
- numbering: equation, section, chapter, step, exercise, figure, row, motor, wheel and
  waypoint numbers (``eq. 13.10``, ``steps 5 and 7``, ``REP 103``);
- :data:`SOURCE_VALUES`: the numbers the four sources print, quoted as the source's values,
  and :data:`CONSTANTS`, the definitions of the units the sources use and standard gravity;
- the data a question or an exercise poses: the numbers of a "Check your understanding"
  question (before its answer) and of an exercise's statement are the reader's givens, not
  results; an answer may repeat them.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import nbformat
import pytest

from tools.book_text import (
    chapter_pages,
    linked_pages,
    output_text,
    page_markdown,
    page_outputs,
    prose,
)

ROOT = Path(__file__).resolve().parents[2]

#: The sources' printed values, quoted as such in the prose. Each is printed by the source
#: named (the documents in the book's references); the prose says whose value it is.
SOURCE_VALUES: dict[str, tuple[str, ...]] = {
    # The Open Source Rover walkthrough: d1..d4 (eq. 5), the 30 in example and its table,
    # the 45 deg stops, r_min (eq. 15), the 20 in software limit, the 250 in threshold.
    "osr_controls": ("7.254", "10.5", "10.073", "96.59", "62.52", "49.73", "17.754", "45",
                     "250", "-100"),
    # The mecanum simulator: its 15 ft/s top speed, 6 in grid, 3 ft edge margin.
    "florida2014mecanum": ("15",),
    # The Radon Ulzer README and robot constants: 85 mm track, 12 counts, 75.81 gear ratio,
    # 36 mm wheel, its circumference, ENC; the firmware source's 6-step speedometer, 5 ms
    # controller and the ENC/100 = 80 step odometry trigger.
    "radonulzer": ("85", "0.085", "12", "75.81", "36", "113.097", "0.113097", "8043", "80"),
    # The Webots waypoint lab: its wheel rate, waypoints and the tutorial robot's 64 ms step
    # and 10 rad/s motor limit (Webots' defaults, read as the lab's).
    "webots_waypoint_lab": ("7.5", "1.5", "-1.5", "0.5", "-0.5", "1.0", "-1.0", "64"),
}
#: Exact definitions: the inch and the foot in metres, standard gravity in m/s².
CONSTANTS = ("0.0254", "0.3048", "9.81")
ALLOWED = frozenset([*(v.lstrip("+-") for values in SOURCE_VALUES.values() for v in values),
                     *CONSTANTS])
#: A "Check your understanding" question: its body up to the folded answer, then the answer.
_QUESTION = re.compile(r"\{admonition\} Check your understanding[^\n]*\n(?P<body>.*?)"
                       r"(?:\{admonition\} Answer|\*Answer\.\*)(?P<answer>.*?)(?=^:{3,}\s*$|\Z)",
                       re.M | re.S)
#: An exercise's statement: from its heading or bold lead to the end of the cell.
EXERCISE_LEAD = re.compile(r"^(?:#{1,4}[ \t]+Exercise\b|\*\*(?:Exercise\b|\d+[.:)]))", re.M)

_NUMBER = re.compile(r"(?<![\w.^{}\\])(?<!\^\{)(?<!\^)[-+−]?\d+(?:[,\u202f]\d{3})*(?:\.\d+)?(?![\w])")
_NUMBERING = re.compile(
    r"\b(?:eqs?\.|equations?|sections?|chapters?|ch\.|steps?|exercises?|figures?|fig\.|"
    r"rows?|motors?|wheels?|REP|columns?|tables?|commit|version|issue|waypoints?|case|"
    r"cells?|lines?|parts?|#)\s*(?:\{?eq\}?)?[\s(-]*"
    r"(?:[\d.]+\s*(?:,|and|or|to|–|-|↔)\s*)*$", re.I)
_MONTHS = ("January|February|March|April|May|June|July|August|September|October|November|"
           "December")
_DATE = re.compile(rf"^\s*(?:{_MONTHS})\b")
_YEAR_UNIT = re.compile(r"^\s*(?:%|mm|cm|m\b|s\b|ms\b|steps|runs|rad|°|in\b|ft|×|times)")
_EXPONENT = re.compile(r"(?:\^\{?-?|e[-+]?)$")


def significant_digits(token: str) -> int:
    """Significant digits of a decimal number as written (trailing zeros of an integer are not
    significant; those after a decimal point are)."""
    digits = token.lstrip("+-−").replace(",", "").replace("\u202f", "")
    if "." in digits:
        whole, frac = digits.split(".")
        joined = (whole + frac).lstrip("0")
        return len(joined) if joined else 1
    stripped = digits.lstrip("0").rstrip("0")
    return max(len(stripped), 1)


def _normal(token: str) -> str:
    return token.lstrip("+-−").replace(",", "").replace("\u202f", "")


def numbers_in(text: str) -> list[tuple[str, str, str]]:
    """(number, text before, text after) for every number of a prose text."""
    out = []
    for match in _NUMBER.finditer(text):
        before = text[max(0, match.start() - 40):match.start()]
        after = text[match.end():match.end() + 20]
        out.append((match.group(0), before, after))
    return out


def is_exempt(token: str, before: str, after: str) -> bool:
    """Whether the allowlist covers this number in this place (see the module docstring)."""
    value = _normal(token)
    if _EXPONENT.search(before):
        return True
    if re.fullmatch(r"1[89]\d\d|20\d\d", value) and not _YEAR_UNIT.match(after):
        return True
    if _DATE.match(after):
        return True
    if _NUMBERING.search(before):
        return True
    return value in ALLOWED


def output_numbers(text: str) -> set[str]:
    """Every number an output text prints, normalised (no sign, no thousands separator)."""
    return {_normal(m.group(0)) for m in re.finditer(r"\d+(?:[,\u202f]\d{3})*(?:\.\d+)?", text)}


def matches(token: str, printed: set[str]) -> bool:
    """Whether a prose number is printed, as written or rounded to the prose's decimals."""
    value = _normal(token)
    if value in printed:
        return True
    decimals = len(value.split(".")[1]) if "." in value else 0
    target = float(value)
    for other in printed:
        other_decimals = len(other.split(".")[1]) if "." in other else 0
        if other_decimals > decimals and math.isclose(
                round(float(other), decimals), target, abs_tol=0.5 * 10 ** -(decimals + 3)):
            return True
    return False


def posed_data(text: str) -> set[str]:
    """The numbers a question or an exercise statement of ``text`` poses (its givens)."""
    data = set()
    for question in _QUESTION.finditer(text):
        data |= {_normal(t) for t, _, _ in numbers_in(prose(question.group("body")))}
    lead = EXERCISE_LEAD.search(text)
    if lead:
        data |= {_normal(t) for t, _, _ in numbers_in(prose(text[lead.start():]))}
    return data


def unprinted_numbers(markdown: str, printed: set[str]) -> list[str]:
    """The numbers of two or more significant digits in ``markdown`` that no output prints
    and the allowlist does not cover, each with a little of its context."""
    found = []
    text = prose(markdown)
    given = posed_data(markdown)
    for token, before, after in numbers_in(text):
        if significant_digits(token) < 2 or is_exempt(token, before, after):
            continue
        if _normal(token) in given:
            continue
        if not matches(token, printed):
            context = " ".join((before[-25:] + token + after).split())
            found.append(f"{token} («{context}»)")
    return found


def page_problems(page: Path) -> list[str]:
    """Every number of a page's markdown cells that no cell printed."""
    own = page_outputs(page)
    problems = []
    cells = ([c for c in nbformat.read(page, as_version=4).cells if c.cell_type == "markdown"]
             if page.suffix == ".ipynb" else None)
    texts = [c.source for c in cells] if cells is not None else page_markdown(page)
    for index, text in enumerate(texts):
        linked = "\n".join(page_outputs(p) for p in linked_pages(text, page))
        printed = output_numbers(own + "\n" + linked)
        for item in unprinted_numbers(text, printed):
            where = f"markdown cell {index}" if cells is not None else "page"
            problems.append(f"{where}: {item}")
    return problems


PAGES = chapter_pages()


def _id(page: Path) -> str:
    return page.relative_to(ROOT / "notebooks").with_suffix("").as_posix()


@pytest.mark.parametrize("page", PAGES, ids=_id)
def test_numbers_in_the_prose_are_printed_by_a_cell(page):
    problems = page_problems(page)
    assert not problems, (
        f"{_id(page)}: numbers in the prose that no cell of the page (or of a page it links) "
        "prints; let a cell print the sentence (a Markdown output), or cite the table that "
        "holds the number:\n" + "\n".join(problems))


# --- the guard itself, on planted examples -----------------------------------------------------

def _cell_output(text: str):
    cell = nbformat.v4.new_code_cell("")
    cell.outputs = [nbformat.v4.new_output("display_data", data={"text/markdown": text})]
    return cell


def test_the_guard_flags_a_number_no_cell_prints():
    printed = output_numbers(output_text(_cell_output("The robot ends 0.741 m away.")))
    assert unprinted_numbers("It ends 0.74 m away.", printed) == []  # rounded from 0.741
    assert unprinted_numbers("It ends 0.741 m away.", printed) == []
    flagged = unprinted_numbers("It ends 0.75 m away, after 12.5 s.", printed)
    assert [f.split()[0] for f in flagged] == ["0.75", "12.5"]


def test_the_guard_does_not_invent_precision():
    printed = output_numbers("0.74")
    assert unprinted_numbers("It ends 0.741 m away.", printed) != []


def test_the_allowlist():
    printed: set[str] = set()
    quiet = [
        "Ackermann's 1818 patent; the version of 21 August 2024.",  # a year, a date
        "Modern Robotics eq. 13.10, section 13.2, chapters 3 and 13, steps 5 and 7.",
        "The `int32` product `2 * 1000 * 1000`, an ATmega32U4 and Q16; P12.",  # names, code
        "$2^{31} - 1$ and $10^{-6}$.",  # exponents
        "The document's $d_1 = 7.254$ in and its 17.754 in.",  # the source's own values
        "One significant digit: 0.3 m, 100 steps, 2000 runs, 0.05 s.",
    ]
    for text in quiet:
        assert unprinted_numbers(text, printed) == [], text
    assert unprinted_numbers("A 2025 mm track.", printed) != []  # a unit: not a year
    assert unprinted_numbers("The robot turned 52°.", printed) != []


def test_a_question_may_pose_its_data_but_not_its_results():
    question = ("::::{admonition} Check your understanding: predict\n:class: tip\n"
                "A robot at 170° turns left by 20°.\n\n:::{admonition} Answer\n"
                ":class: dropdown\nFrom 170° to 190°, so the log reads RESULT.\n:::\n::::")
    flagged = unprinted_numbers(question.replace("RESULT", "-340°"), set())
    assert [f.split()[0] for f in flagged] == ["190", "-340"]  # results, not givens
    assert unprinted_numbers(question.replace("RESULT", "the angle less a turn").replace(
        " to 190°", ""), set()) == []


def test_significant_digits():
    assert [significant_digits(t) for t in
            ("0.01", "10", "250", "2000", "0.10", "1.0", "17.754", "-3141", "2,000")] == \
        [1, 1, 2, 1, 2, 2, 5, 4, 1]
