"""The printed edition reads like the web edition (issue #26), checked on the built PDF.

The expected values come from the book's sources, never from the PDF tool: the chapters, their
numbers and titles from ``_toc.yml`` and the pages' headings; the questions and answers, the
figures and the notation's symbols from the notebooks and pages as they are stored.
"""

from __future__ import annotations

import json
import re

import yaml

from tests.pdf.printed_pdf import ROOT, is_part
from tools import pdf_text
from tools.book_pages import page_title
from tools.book_text import page_markdown

#: A page with fewer words is blank, or a part's title page (running head and page number).
MIN_WORDS_ON_A_PAGE = 40
ROMAN = re.compile(r"^[ivxlcdm]+$")


def _flat(text: str) -> str:
    """Letters and digits only, lower case: what survives hyphenation, ligatures and layout."""
    return re.sub(r"[^0-9a-z]+", "", text.lower())


def _words(text: str) -> int:
    return len(re.findall(r"[A-Za-z]{2,}", text))


def _chapter_titles(structure):
    """[(number or None, title)] of every division, as the web shows them."""
    out = []
    for division in structure:
        title = page_title(division.page)
        if division is structure[0]:
            title = "Preface"  # the web's root page; its title is the book's, on the title page
        out.append((division.number, title))
    return out


def _norm_title(title: str) -> str:
    return " ".join(title.replace("\u2019", "'").replace("`", "").split())


# ----------------------------------------------------------------------------- chapters
def test_outline_lists_the_chapters_with_the_web_numbers_and_titles(printed, structure):
    """The PDF's outline: front matter unnumbered, then "6 Odometry: where am I?" as chapter 6
    of the web's toc, then the appendices "A Errata" ..., in the toc's order."""
    found = [_norm_title(entry.title) for entry, _ in printed.chapters()]
    expected = [_norm_title(f"{number} {title}" if number else title)
                for number, title in _chapter_titles(structure)]
    assert found == expected


def test_parts_follow_the_toc(printed, structure):
    parts = [re.sub(r"^[IVXLC]+ ", "", e.title) for e in printed.outline if is_part(e)]
    expected = list(dict.fromkeys(d.part for d in structure if d.matter == "main"))
    assert parts == expected


def test_front_matter_has_roman_pages_and_chapter_1_page_1(printed, structure):
    chapters = printed.chapters()
    for (entry, _), division in zip(chapters, structure, strict=True):
        label = printed.labels[entry.page]
        if division.matter == "front":
            assert ROMAN.match(label), f"{entry.title} starts on page {label}, not roman"
        else:
            assert label.isdigit(), f"{entry.title} starts on page {label}, not arabic"
    first_main = next(e for e in printed.outline if is_part(e))
    assert printed.labels[first_main.page] == "1"


def test_no_chapter_fits_on_one_page(printed):
    """A chapter has at least two pages of text: none is a page and a blank (the first
    edition printed the preface's six sections as six such chapters)."""
    short = []
    for entry, end in printed.chapters():
        full = [p for p in range(entry.page, end) if _words(printed.pages[p]) >= MIN_WORDS_ON_A_PAGE]
        if len(full) < 2:
            short.append(f"{entry.title} ({len(full)} page of text)")
    assert not short, "chapters shorter than two pages: " + ", ".join(short)


# ----------------------------------------------------------------------------- answers
def _questions(division) -> list[pdf_text.Answer]:
    """The division's questions, numbered as print numbers them, from the stored sources."""
    answers: list[pdf_text.Answer] = []
    for page in division.pages:
        for suffix in (".md", ".ipynb"):
            path = ROOT / f"{page}{suffix}"
            if not path.is_file():
                continue
            for text in page_markdown(path):
                pdf_text.split_answers(text, division.number or "", answers)
    return answers


def _plain_run(markdown: str, words: int = 7) -> str | None:
    """The first run of ``words`` plain words of ``markdown`` (no math, role, code or markup
    between them): text that prints as it is written."""
    run: list[str] = []
    for token in re.split(r"(\$[^$]*\$|\{[\w:-]+\}`[^`]*`|`[^`]*`|\*+|\n\s*\n)", markdown):
        if re.match(r"\$|\{|`|\*|\n", token or "\n"):
            run = []
            continue
        for word in token.split():
            if re.fullmatch(r"[A-Za-z][A-Za-z,;.'()-]*", word):
                run.append(word)
                if len(run) == words:
                    return " ".join(run)
            else:
                run = []
    return None


def test_every_question_points_to_its_answer_at_its_chapters_end(printed, structure):
    """Each question of the sources is printed as "Check your understanding N.k", says
    "Answer N.k on p. P"; page P holds "Answer N.k (question on p. Q)" in its chapter's
    "Answers to the questions", with the answer's text, and page Q holds the question."""
    chapters = dict(zip([d.page for d in structure], printed.chapters(), strict=True))
    checked = 0
    for division in structure:
        questions = _questions(division)
        if not questions:
            continue
        (entry, end) = chapters[division.page]
        text = "\n".join(printed.body(p) for p in range(entry.page, end))
        assert "Answers to the questions" in text, f"{entry.title}: no answers section"
        answers_start = entry.page + next(
            i for i, page in enumerate(printed.pages[entry.page:end])
            if "Answers to the questions" in page and "Answer " in page)
        for question in questions:
            number = re.escape(question.number)
            pointer = re.search(rf"Answer {number} on p\. (\w+)\.", text)
            assert pointer, f"question {question.number}: no pointer to its answer"
            page = printed.page_of_label(pointer.group(1))
            assert answers_start <= page < end, (
                f"answer {question.number} is on p. {pointer.group(1)}, outside the answers of "
                f"{entry.title}")
            back = re.search(rf"Answer {number}[^\w(]{{0,3}}\(question on p\. (\w+)\)",
                             " ".join(printed.pages[page].split()))
            assert back, f"p. {pointer.group(1)} does not hold answer {question.number}"
            asked = printed.page_of_label(back.group(1))  # the box may open a page earlier
            box = " ".join(" ".join(printed.pages[asked - 1:asked + 1]).split())
            assert re.search(rf"(?:Check your understanding|Question) {number}\b", box), (
                f"p. {back.group(1)} does not hold question {question.number}")
            run = _plain_run(question.text, 10) or _plain_run(question.text, 6)
            if run:
                following = _flat(" ".join(printed.body(p) for p in (page, page + 1)
                                           if p < len(printed.pages)))
                at = following.find(_flat(f"Answer {question.number} (question on p. "))
                assert _flat(run) in following[at:], (
                    f"answer {question.number}'s text ({run!r}) is not after its number")
                chapter = _flat(text)
                assert chapter.count(_flat(run)) == 1, (
                    f"answer {question.number} is printed beside its question too")
            checked += 1
    assert checked >= 3 * len([d for d in structure if d.matter == "main"]) - 3


# ----------------------------------------------------------------------------- wording
def test_no_text_about_clicking_or_folding(printed):
    """Paper cannot be clicked or unfolded: no page speaks of clicking, buttons, dropdowns,
    folded cells or code."""
    found = []
    for index, page in enumerate(printed.pages):
        flat = " ".join(page.split())
        for match in pdf_text.UI_WORDS.finditer(flat):
            found.append(f"p. {printed.labels[index]}: ...{flat[max(0, match.start() - 60):match.end() + 40]}...")
    assert not found, "\n".join(found)


# ----------------------------------------------------------------------------- references
_XREF = re.compile(r"\b(Chapter|Section|Appendix) ([0-9A-Z]+(?:\.\d+)*)(?: \(p\.|, p\.) (\w+)\)?")


def test_cross_references_give_the_number_and_the_page_of_their_target(printed):
    """Every "Section 6.1 (p. 126)" of the text leads to a page that shows section 6.1, every
    "Chapter 6 (p. 129)" to the page where chapter 6 opens."""
    opens = {}
    for entry, _ in printed.chapters():
        head = entry.title.split(" ", 1)[0]
        opens[head] = entry.page
    seen = 0
    for page in printed.pages:
        for kind, number, label in _XREF.findall(" ".join(page.split())):
            seen += 1
            assert label in printed.labels, f"{kind} {number}: no page {label}"
            target = printed.page_of_label(label)
            if kind in ("Chapter", "Appendix"):
                assert opens.get(number) == target, f"{kind} {number} does not open on p. {label}"
            else:
                shown = " ".join(printed.pages[target].split())
                assert re.search(rf"(?:^|\s){re.escape(number)}\.? \S", shown), (
                    f"Section {number}: p. {label} does not show it")
    assert seen >= 100, f"only {seen} numbered cross-references in the text"


# ----------------------------------------------------------------------------- figures
def test_figures_carry_the_web_numbers(printed, structure):
    """Chapter N's k-th captioned figure (in the toc's order, as the web numbers it) is printed
    as "Fig. N.k" with its caption."""
    text = " ".join("\n".join(printed.pages).split())
    checked = 0
    for division in structure:
        if division.matter != "main":
            continue
        count = 0
        for page in division.pages:
            path = ROOT / f"{page}.ipynb"
            if not path.is_file():
                continue
            for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
                figure = cell.get("metadata", {}).get("mystnb", {}).get("figure", {})
                if not figure.get("caption") or "remove-output" in cell["metadata"].get("tags", []):
                    continue
                count += 1
                number = f"{division.number}.{count}"
                at = text.find(f"Fig. {number}: ")
                assert at >= 0, f"{page}: no caption of Fig. {number} in the PDF"
                run = _plain_run(pdf_text.paper_wording(figure["caption"]), 5)
                if run:
                    caption = _flat(text[at:at + 80 + len(figure["caption"])])
                    assert _flat(run) in caption, (
                        f"{page}: Fig. {number} is not {figure['caption'][:60]!r}...")
                checked += 1
    assert checked >= 20


# ----------------------------------------------------------------------------- the index
def _index_pages(printed) -> str:
    start = next(e.page for e in printed.outline if e.title == "Index")
    return " ".join(printed.text_in_reading_order(start, len(printed.pages) - 1).split())


def test_the_index_lists_the_notation_symbols(printed):
    """Every symbol of the notation page's tables is in the index, with its meaning."""
    index = _flat(_index_pages(printed))
    notation = (ROOT / "book" / "notation.md").read_text(encoding="utf-8")
    symbols = pdf_text.notation_symbols(notation)
    assert len(symbols) >= 30
    missing = []
    for _, symbol in symbols:
        # the meaning's first words: the text of a two-column index is read in pieces
        # (a one-letter formula stays as its letter: "wheel $i$'s distance" prints "wheel i's")
        meaning = re.sub(r"\$([A-Za-z0-9])\$", r"\1", symbol.meaning)
        meaning = re.sub(r"\$[^$]*\$|\\[a-z]+\{|[{}]", " ", meaning).split()[:3]
        if _flat("(" + " ".join(meaning)) not in index:
            missing.append(f"{symbol.latex} ({symbol.meaning})")
    assert not missing, "symbols missing from the index: " + "; ".join(missing)


def test_the_index_lists_the_terms(printed):
    """Every term of book/index_terms.yml reaches the index (a term that no page discusses
    any more is stale)."""
    index = _flat(_index_pages(printed))
    terms = yaml.safe_load((ROOT / "book" / "index_terms.yml").read_text(encoding="utf-8"))
    missing = [t["term"] for t in terms if _flat(t["term"].split("!")[-1]) not in index]
    assert not missing, f"terms not in the index: {missing}"


def test_the_index_is_of_terms_not_of_library_objects(printed):
    index = _index_pages(printed)
    assert "(in module" not in index and "module wheelkin" not in index
