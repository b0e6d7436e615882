"""The parts of the printed edition that need no PDF: one numbering for both editions (from
``_toc.yml``), the web's section numbers (``tools/numbering.py``) and the text for paper
(``tools/pdf_text.py``). Expected values are written out by hand from the rules."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

import yaml
from docutils import nodes
from sphinx import addnodes

from tests.pdf.printed_pdf import ROOT
from tools import book_pages, pdf_text
from tools.book_pages import book_structure
from tools.numbering import book_numbers

TOC = """
format: jb-book
root: intro
parts:
  - caption: About
    chapters:
      - file: how
  - caption: First
    numbered: true
    chapters:
      - file: one/index
        sections:
          - file: one/a
          - file: one/b
  - caption: Second
    numbered: true
    chapters:
      - file: two/index
  - caption: Back
    chapters:
      - file: errata
      - file: api/index
        sections:
          - file: api/x
"""


def _toc(tmp_path: Path, text: str = TOC) -> Path:
    path = tmp_path / "_toc.yml"
    path.write_text(text, encoding="utf-8")
    return path


# ----------------------------------------------------------------------------- structure
def test_structure_numbers_chapters_across_parts_and_letters_the_back_matter(tmp_path):
    found = [(d.page, d.matter, d.number, d.part) for d in book_structure(_toc(tmp_path))]
    assert found == [("intro", "front", None, None), ("how", "front", None, "About"),
                     ("one/index", "main", "1", "First"), ("two/index", "main", "2", "Second"),
                     ("errata", "back", "A", "Back"), ("api/index", "back", "B", "Back")]
    one = book_structure(_toc(tmp_path))[2]
    assert one.pages == ("one/index", "one/a", "one/b")
    assert (one.level("one/index"), one.level("one/b"), one.has_pages("one/index"),
            one.has_pages("one/a")) == (1, 2, True, False)


def test_the_books_chapters_are_numbered_as_their_folders():
    """Chapter NN's folder (notebooks/NN_name) is chapter NN of both editions: a chapter put
    into an unnumbered part, or out of order, fails here."""
    chapters = [d for d in book_structure() if d.page.startswith("notebooks/")]
    assert chapters
    for division in chapters:
        folder = re.match(r"notebooks/(\d\d)_", division.page)
        assert division.matter == "main", f"{division.page} is not in a numbered part"
        assert division.number == str(int(folder.group(1))), (
            f"{division.page} is chapter {division.number} of the book")
    assert [d.matter for d in book_structure()][-1] == "back"


# ----------------------------------------------------------------------------- web numbers
class _Env:
    """The part of Sphinx's environment that numbering reads: tocs and titles."""

    def __init__(self):
        self.tocs, self.titles = {}, {}

    def page(self, name: str, headings: list, children: tuple = ()):
        """A page whose toc has its title, ``headings`` (nested lists of names) and, after
        them, a toctree of ``children``."""
        def item(anchor, title, subs=()):
            ref = nodes.reference("", title, anchorname=anchor)
            entry = nodes.list_item("", addnodes.compact_paragraph("", "", ref))
            if subs:
                entry += nodes.bullet_list("", *subs)
            return entry

        def build(spec):
            return [item("#" + (h if isinstance(h, str) else h[0]), "x",
                         build(h[1]) if not isinstance(h, str) else ()) for h in spec]

        subs = build(headings)
        if children:
            subs.append(addnodes.toctree(entries=[(None, c) for c in children]))
        self.tocs[name] = nodes.bullet_list("", item("", name, subs))
        self.titles[name] = nodes.title()


def test_web_numbers_are_the_printed_ones(tmp_path):
    env = _Env()
    env.page("intro", ["what"])
    env.page("how", ["web"])
    env.page("one/index", ["sections", "first"], ("one/a", "one/b"))
    env.page("one/a", [("step", ["detail", ("deeper", ["deepest"])]), "summary"])
    env.page("one/b", ["summary"])
    env.page("two/index", ["x"])
    env.page("errata", ["rover", "mecanum"])
    env.page("api/index", ["modules"], ("api/x",))
    env.page("api/x", [])
    numbers = book_numbers(env, _toc(tmp_path))
    assert "intro" not in numbers and "how" not in numbers  # front matter: no numbers
    assert numbers["one/index"] == {"": (1,), "#sections": (), "#first": ()}
    assert numbers["one/a"] == {"": (1, 1), "#step": (1, 1, 1), "#detail": (),
                                "#deeper": (), "#deepest": (), "#summary": (1, 1, 2)}
    assert numbers["one/b"] == {"": (1, 2), "#summary": (1, 2, 1)}
    assert numbers["two/index"] == {"": (2,), "#x": (2, 1)}
    assert numbers["errata"] == {"": ("A",), "#rover": ("A", 1), "#mecanum": ("A", 2)}
    assert numbers["api/index"] == {"": ("B",), "#modules": ()}
    assert numbers["api/x"] == {"": ("B", 1)}
    # the toc's nodes carry them too (the sidebar and the page titles show these)
    reference = env.tocs["one/a"][0][0][0]
    assert reference["secnumber"] == [1, 1] and env.titles["one/b"]["secnumber"] == [1, 2]


# ----------------------------------------------------------------------------- paper text
QUESTION = """Text before.

::::{admonition} Check your understanding: predict, then see
:class: tip
What happens?

:::{admonition} Answer
:class: dropdown
It turns left.
:::
::::

::::{admonition} Think
:class: tip
Why?

:::{admonition} Answer
:class: dropdown
- because
:::
::::
"""


def test_questions_are_numbered_and_their_answers_move():
    answers: list[pdf_text.Answer] = []
    text = pdf_text.split_answers(QUESTION, "6", answers)
    assert [(a.number, a.text) for a in answers] == [("6.1", "It turns left."),
                                                     ("6.2", "- because")]
    assert "It turns left" not in text and "because" not in text
    assert "{admonition} Check your understanding 6.1: predict, then see" in text
    assert "{admonition} Question 6.2: Think" in text
    assert text.count("\\wkquestion{6.1}") == 1 and text.count("\\wkquestion{6.2}") == 1
    assert ":class: tip\n{wklatex}`\\wkquestionstart{6.1}`What happens?" in text
    assert ":class: tip\n{wklatex}`\\wkquestionstart{6.2}`Why?" in text
    section = pdf_text.answers_section(answers)
    assert "{wklatex}`\\wkanswer{6.1}` It turns left." in section
    assert "{wklatex}`\\wkanswer{6.2}`\n\n- because" in section  # a list is not run in


def test_a_landing_pages_headings_become_unnumbered_rubrics():
    text = "(x)=\n# Title\n\n## Sections\n\n:::{note}\n## inside\n:::\n\n### What next #\n"
    out = pdf_text.headings_to_rubrics(text)
    assert "# Title" in out and "## inside" in out
    assert "```{rubric} Sections\n:heading-level: 2\n```" in out
    assert "```{rubric} What next\n:heading-level: 3\n```" in out


def test_paper_wording():
    cases = {
        "The folded cell asserts that": "The notebook asserts that",
        "The figure (folded code) draws": "The figure draws",
        "by $0.1/36$ (folded cell):": "by $0.1/36$:",
        "(folded cell; every frame passes)": "(every frame passes)",
        "The live panel sets": "The notebook's live panel sets",
        "In the panel, set": "In the notebook's live panel, set",
        "the left panel of the figure": "the left panel of the figure",
        "imports in its first, folded cell to show": "imports in its first cell to show",
        "in its first (folded) cell instead": "in its first cell instead",
    }
    assert {k: pdf_text.paper_wording(k) for k in cases} == cases
    assert pdf_text.paper_caption("A sweep. Use the slider or the step buttons to stop. "
                                  "Watch the ICR.") == "A sweep. Watch the ICR."


def test_ui_words_are_found_and_mathematics_is_not():
    for said in ("click the bar", "a dropdown", "folded away", "open the folded cells",
                 "a rocket button", "Show code cell"):
        assert pdf_text.UI_WORDS.search(said), said
    for said in ("an angle folded into (-pi/2, pi/2]", "when the fold reverses it", "tenfold",
                 "UMBmark will fold them into E_b", "launch_buttons.colab_url"):
        assert not pdf_text.UI_WORDS.search(said), said


def test_notation_symbols_become_index_entries():
    text = ("| symbol | meaning | unit | introduced |\n| --- | --- | --- | --- |\n"
            "| $\\omega$ | the body's yaw rate, $\\dot\\theta$ | rad/s | {ref}`chapter-x` |\n"
            "| $E_d$, $E_b$ | UMBmark's two errors: wheels, track | 1 | the lab |\n"
            "| $\\delta_m$, $\\delta_s$ | degrees of mobility, steerability | 1 | |\n"
            "| ICR | instantaneous centre of rotation: a point | m | |\n")
    out, at_labels = pdf_text.index_symbols(text)
    assert "| $\\omega$ {wklatex}`\\index{omega@$\\omega$ (the body's yaw rate)}` |" in out
    assert "\\index{E d@$E_d$ (UMBmark's two errors)}" in out
    assert "\\index{E b@$E_b$ (UMBmark's two errors)}" in out
    # a list of meanings names all the cell's symbols: it is not cut at its comma
    assert "\\index{delta s@$\\delta_s$ (degrees of mobility, steerability)}" in out
    assert "\\index{ICR@ICR (instantaneous centre of rotation)}" in out
    assert at_labels == {"chapter-x": ["\\index{omega@$\\omega$ (the body's yaw rate)}"]}


def test_terms_are_indexed_where_they_are_discussed():
    class Cell:
        def __init__(self, source):
            self.source = source

    terms = pdf_text.load_terms([{"term": "odometry"}, {"term": "twist", "match": ["twists?"]},
                                 {"term": "pose"}])
    cells = [Cell("# Odometry\n\nThis is *odometry*; `odometry` in code."),
             Cell("A twist, and $twist$ in math, and twists again."),
             Cell("A pose, then a pose again.")]
    assert pdf_text.index_terms(cells, terms) == 2
    assert cells[0].source.endswith(
        "This is *odometry{wklatex}`\\index{odometry|spxpagem}`*; `odometry` in code.")
    assert cells[1].source == ("A twist{wklatex}`\\index{twist}`, and $twist$ in math, and "
                               "twists again.")
    assert cells[2].source == "A pose, then a pose again."  # twice: not discussed here
    placed = {"odometry", "twist"}
    assert pdf_text.index_rare_terms([cells], terms, placed) == 1  # named, so still indexed
    assert cells[2].source == "A pose{wklatex}`\\index{pose}`, then a pose again."
    assert "pose" in placed


def test_every_index_term_matches_the_book():
    """Each term's forms are valid and occur in the book's pages (a stale term fails here
    before the PDF is built)."""
    terms = yaml.safe_load((ROOT / "book" / "index_terms.yml").read_text(encoding="utf-8"))
    assert terms and all("term" in t for t in terms)
    text = "\n".join(p.read_text(encoding="utf-8", errors="replace")
                     for p in [*ROOT.glob("notebooks/*/*.ipynb"), *ROOT.glob("book/*.md")])
    for term in pdf_text.load_terms(terms):
        assert any(form.search(text) for form in term.forms), term.entry


def test_the_examples_in_the_tools_docstrings_hold():
    for module in (pdf_text, book_pages):
        assert doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE).failed == 0
