"""The reader's edition, page by page: every section teaches, then tests understanding.

Reads the committed notebooks and chapter index pages (nothing is executed). The rules are
docs/DESIGN.md's "Chapter anatomy" and "Teach, then test understanding":

- a section opens with an "In this section" admonition and ends with a Summary of 3-5 bullets;
- a chapter index says what the reader will be able to do;
- a chapter has at least three "Check your understanding" questions, each shown in the page,
  with its answer folded in a dropdown of its own (so that a reader can predict before
  looking), and at least one coded exercise;
- a live panel's margin note that points to an animation below has one below.

A failure names the page and what is missing.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = sorted(p for p in (ROOT / "notebooks").iterdir()
                  if p.is_dir() and re.match(r"\d\d_", p.name))
SECTIONS = sorted(p for chapter in CHAPTERS for p in chapter.glob("[0-9][0-9]_*.ipynb"))

#: A question: an open admonition whose body holds the question, then a folded "Answer".
QUESTION = re.compile(
    r"^(?P<fence>:{4,})\{admonition\} Check your understanding: (?P<kind>[^\n]+)\n"
    r"(?P<body>.*?)^(?P=fence)\s*$", re.M | re.S)
ANSWER = re.compile(r"^(?P<fence>:{3})\{admonition\} Answer\n:class: dropdown\n"
                    r"(?P<answer>.*?)^(?P=fence)\s*$", re.M | re.S)
ANIMATION = 'class="wheelkin-animation"'


def _rel(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


def _markdown(nb) -> list[str]:
    return [c.source for c in nb.cells if c.cell_type == "markdown"]


def _chapter_text(chapter: Path) -> str:
    return "\n".join(text for nb_path in sorted(chapter.glob("[0-9][0-9]_*.ipynb"))
                     for text in _markdown(nbformat.read(nb_path, as_version=4)))


def test_there_are_chapters_and_sections():
    assert len(CHAPTERS) >= 9 and len(SECTIONS) >= 50


@pytest.mark.parametrize("path", SECTIONS, ids=[_rel(p) for p in SECTIONS])
def test_section_opens_with_what_the_reader_will_be_able_to_do(path):
    first = _markdown(nbformat.read(path, as_version=4))[:2]
    assert any(":class: tip" in t and "In this section" in t for t in first), (
        f"{_rel(path)}: its first markdown cells need an 'In this section' admonition "
        "(class tip) saying what the reader will be able to do")


@pytest.mark.parametrize("path", SECTIONS, ids=[_rel(p) for p in SECTIONS])
def test_section_ends_with_a_summary_of_three_to_five_points(path):
    text = "\n".join(_markdown(nbformat.read(path, as_version=4)))
    found = re.search(r"^## Summary[^\n]*\n(?P<body>.*?)(?=^#{1,2} |\Z)", text, re.M | re.S)
    assert found, f"{_rel(path)}: no '## Summary' heading"
    bullets = re.findall(r"^- ", found["body"], re.M)
    assert 3 <= len(bullets) <= 5, (
        f"{_rel(path)}: its Summary has {len(bullets)} bullets; it needs 3 to 5")


@pytest.mark.parametrize("chapter", CHAPTERS, ids=[c.name for c in CHAPTERS])
def test_chapter_index_says_what_the_reader_will_be_able_to_do(chapter):
    index = chapter / "index.md"
    assert index.is_file(), f"{_rel(chapter)}: no index.md"
    text = index.read_text()
    assert re.search(r"you will be able to", text, re.I), (
        f"{_rel(index)}: the chapter must open with what the reader will be able to do")
    assert re.search(r"^\(chapter-[\w-]+\)=", text, re.M), f"{_rel(index)}: no chapter label"


@pytest.mark.parametrize("chapter", CHAPTERS, ids=[c.name for c in CHAPTERS])
def test_chapter_has_three_questions_shown_with_folded_answers(chapter):
    text = _chapter_text(chapter)
    old_style = len(re.findall(r"\{admonition\} Check your understanding", text))
    questions = list(QUESTION.finditer(text))
    assert len(questions) == old_style, (
        f"{chapter.name}: {old_style - len(questions)} 'Check your understanding' "
        "admonitions are not in the form 'question shown, answer folded' "
        "(::::{admonition} ... with a nested :::{admonition} Answer / :class: dropdown)")
    assert len(questions) >= 3, f"{chapter.name}: {len(questions)} questions; it needs 3"
    for q in questions:
        answer = ANSWER.search(q["body"])
        assert answer and answer["answer"].strip(), (
            f"{chapter.name}: question '{q['kind']}' has no folded Answer")
        shown = q["body"][:answer.start()].replace(":class: tip", "").strip()
        assert len(shown) > 20, f"{chapter.name}: question '{q['kind']}' shows no question"
        assert ":class: dropdown" not in q["body"][:answer.start()], (
            f"{chapter.name}: question '{q['kind']}' is itself folded: show it, fold only "
            "the answer")


@pytest.mark.parametrize("chapter", CHAPTERS, ids=[c.name for c in CHAPTERS])
def test_chapter_has_a_coded_exercise(chapter):
    tagged = [c for nb_path in chapter.glob("[0-9][0-9]_*.ipynb")
              for c in nbformat.read(nb_path, as_version=4).cells
              if "exercise" in c.metadata.get("tags", [])]
    assert tagged, f"{chapter.name}: no code cell tagged 'exercise'"


@pytest.mark.parametrize("path", SECTIONS, ids=[_rel(p) for p in SECTIONS])
def test_a_margin_note_that_promises_an_animation_below_has_one(path):
    cells = nbformat.read(path, as_version=4).cells
    for i, cell in enumerate(cells):
        if cell.cell_type != "markdown" or "animation below shows the same" not in cell.source:
            continue
        shown = False
        for later in cells[i + 1:]:
            if later.cell_type == "markdown" and re.match(r"#{1,3} ", later.source.strip()):
                break
            shown = shown or any(ANIMATION in "".join(o.get("data", {}).get("text/html", ""))
                                 for o in later.get("outputs", []))
        assert shown, (f"{_rel(path)}, cell {i}: the live panel's note promises an animation "
                       "below, and there is none before the next heading")
