"""MyST text for paper: the transformations ``tools/pdf_edition.py`` applies to the book's
markdown (pages and notebook cells) in the printed edition's copy, never to the book itself.

- :func:`headings_to_rubrics`: a page with pages listed under it (a chapter's landing page)
  prints its own headings without numbers, so that its first section is N.1 in both editions.
- :func:`split_answers`: a *check your understanding* question keeps its place; its folded
  answer moves to the chapter's end, and each points to the other by number and page.
- :func:`raw_latex`: a block of LaTeX for the printed edition only.

>>> print(headings_to_rubrics("# Title\\n\\n## Sections\\n\\n```python\\n## not a heading\\n```"))
# Title
<BLANKLINE>
```{rubric} Sections
:heading-level: 2
```
<BLANKLINE>
```python
## not a heading
```
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_FENCE = re.compile(r"^\s*(`{3,}|~{3,}|:{3,})")
_HEADING = re.compile(r"^(#{2,6})[ \t]+(.+?)[ \t]*#*[ \t]*$")
_H1 = re.compile(r"^#[ \t]+(.+?)[ \t]*$", re.M)

#: A question: an admonition whose nested admonition "Answer" is a dropdown.
_QUESTION = re.compile(
    r"^(?P<fence>:{4,}|`{4,})\{admonition\}[ \t]*(?P<title>[^\n]*)\n"
    r"(?P<body>.*?)^(?P=fence)[ \t]*$", re.M | re.S)
_ANSWER = re.compile(
    r"^(?P<fence>:{3,}|`{3,})\{admonition\}[ \t]*Answer\b[^\n]*\n"
    r"(?P<options>(?:[ \t]*:[\w-]+:[^\n]*\n)*)(?P<answer>.*?)^(?P=fence)[ \t]*\n?",
    re.M | re.S)
_CHECK = "Check your understanding"
#: The first line of a block that cannot take a run-in "Answer 6.3" before it.
_BLOCK_START = re.compile(r"^\s*(?:[-*+] |\d+[.)] |\$\$|`{3,}|~{3,}|:{3,}|\||#|>|\()")


def raw_latex(*lines: str) -> str:
    """A MyST block of raw LaTeX (ignored by every other builder)."""
    return "```{raw} latex\n" + "\n".join(lines) + "\n```\n"


def headings_to_rubrics(text: str) -> str:
    """``text`` with every heading below the title turned into an unnumbered rubric of the
    same level (code and directive blocks are left alone)."""
    out, fence = [], None
    for line in text.split("\n"):
        opening = _FENCE.match(line)
        if fence is None and opening:
            fence = opening.group(1)
        elif fence is not None and line.strip().startswith(fence[0] * len(fence)) \
                and not line.strip().lstrip(fence[0]).strip():
            fence = None
        heading = _HEADING.match(line) if fence is None else None
        if heading:
            out += ["```{rubric} " + heading.group(2),
                    f":heading-level: {len(heading.group(1))}", "```"]
        else:
            out.append(line)
    return "\n".join(out)


def retitle(text: str, title: str) -> str:
    """``text`` with its first level-one heading replaced by ``title``."""
    return _H1.sub(lambda m: "# " + title, text, count=1)


@dataclass
class Answer:
    number: str
    text: str


def split_answers(text: str, prefix: str, answers: list[Answer]) -> str:
    """``text`` with each question numbered and its folded answer replaced by a pointer.

    The answers are appended to ``answers`` (numbered ``prefix.k``, or ``k`` without a
    prefix, continuing the list), in the order of the text.
    """

    def question(match: re.Match) -> str:
        body = match.group("body")
        found = _ANSWER.search(body)
        if not found or "dropdown" not in found.group("options"):
            return match.group(0)
        number = f"{prefix}.{len(answers) + 1}" if prefix else str(len(answers) + 1)
        answers.append(Answer(number, found.group("answer").strip("\n")))
        pointer = "{wklatex}`\\wkquestion{" + number + "}`\n"
        body = body[:found.start()] + pointer + body[found.end():]
        # where the question starts: the answer's "question on p. ..." leads here
        start = re.search(r"^(?![ \t]*:[\w-]+:)[ \t]*\S", body, re.M)
        anchor = "{wklatex}`\\wkquestionstart{" + number + "}`"
        if start is None or _BLOCK_START.match(body[start.start():]):
            at = start.start() if start else len(body)
            body = body[:at] + anchor + "\n\n" + body[at:]
        else:
            body = body[:start.start()] + anchor + body[start.start():]
        title = match.group("title").strip()
        if title.startswith(_CHECK):
            title = f"{_CHECK} {number}{title[len(_CHECK):]}"
        else:
            title = f"Question {number}: {title}"
        fence = match.group("fence")
        return f"{fence}{{admonition}} {title}\n{body}{fence}"

    return _QUESTION.sub(question, text)


def answers_section(answers: list[Answer]) -> str:
    """The chapter's answers, for its last page: a heading and each answer, run in."""
    parts = [raw_latex(r"\wkanswers")]
    for answer in answers:
        marker = "{wklatex}`\\wkanswer{" + answer.number + "}`"
        if _BLOCK_START.match(answer.text):
            parts.append(marker + "\n\n" + answer.text + "\n")
        else:
            parts.append(marker + " " + answer.text + "\n")
    return "\n".join(parts)


#: What the web edition and the notebooks say that paper cannot: the code behind a figure or a
#: check is in the notebook (the printed page leaves it out), a live panel is the notebook's.
#: Applied to every printed paragraph and caption; tests/pdf checks that no word about
#: clicking or folding is left (``UI_WORDS``).
PAPER_WORDING: list[tuple[re.Pattern, str]] = [(re.compile(p), r) for p, r in [
    (r"[ \t]*\(folded[ \t\n]+(?:cells?|code)\)", ""),
    (r"\(folded[ \t\n]+(?:cells?|code)[;,][ \t\n]*", "("),
    (r"[ \t]*\(folded\)", ""),
    (r"(\w),[ \t\n]+folded[ \t\n]+(cells?)\b", r"\1 \2"),
    (r"\b([Tt])he[ \t\n]+folded[ \t\n]+(?:cells?|code)(?:[ \t\n]+below)?\b", r"\1he notebook"),
    (r"\b[Aa][ \t\n]+folded[ \t\n]+cell\b", "the notebook"),
    (r"\b([Tt])he[ \t\n]+live[ \t\n]+panel\b", r"\1he notebook's live panel"),
    (r"\b([Tt])he[ \t\n]+panel[ \t\n]+below\b", r"\1he notebook's live panel"),
    (r"\b([Tt])he[ \t\n]+(?:panel|slider)'s\b", r"\1he live panel's"),
    (r"\b([Tt])he[ \t\n]+panel\b", r"\1he notebook's live panel"),
]]

#: A sentence of an animation's caption about its player: paper shows three frames instead.
_PLAYER_SENTENCE = re.compile(r"\b(?:sliders?|buttons?|step through|click|play|pause)\b", re.I)

#: Words about the web page's or the notebook's controls; none may reach the printed pages.
#: (A steering angle "folded into" its range and "the fold" of that angle are mathematics.)
UI_WORDS = re.compile(
    r"\bclick|\bdropdown|\bshow code|(?<![\w_])buttons?\b|\bunfold"
    r"|\bfold(?:ed|ing)?\b(?!\s+(?:them\s+|it\s+)?into\b)(?<!\bthe fold)", re.I)


def paper_wording(text: str) -> str:
    """``text`` as paper says it (:data:`PAPER_WORDING`)."""
    for pattern, replacement in PAPER_WORDING:
        text = pattern.sub(replacement, text)
    return text


def paper_caption(text: str) -> str:
    """An animation's caption without the sentences about its player."""
    sentences = re.split(r"(?<=[.!?])\s+", text.strip())
    return paper_wording(" ".join(s for s in sentences if not _PLAYER_SENTENCE.search(s)))


# ----------------------------------------------------------------------------- the index
#: Text the index never touches: code, math, roles, labels, links, directive fences and
#: options, headings, HTML.
_PROTECTED = re.compile(
    r"```.*?```|~~~.*?~~~|\$\$.*?\$\$(?:[ \t]*\([\w-]+\))?|\$[^$\n]+\$|\{[\w:-]+\}`[^`]*`|`[^`\n]*`"
    r"|^[ \t]*\([\w-]+\)=[ \t]*$|!?\[[^\]\n]*\]\([^)\n]*\)|<[^>\n]+>|^[ \t]*#[^\n]*$"
    r"|^[ \t]*(?::{3,}|`{3,})[^\n]*$|^[ \t]*:[\w-]+:[^\n]*$", re.S | re.M)
_GREEK = ("alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda "
          "mu nu xi pi rho sigma tau upsilon phi varphi chi psi omega").split()
_LATEX_SPECIAL = {c: "\\" + c for c in "&%#_{}"}


@dataclass
class Term:
    """A term of the index: its entry (``!`` separates a sub-entry) and its forms."""

    entry: str
    forms: list[re.Pattern]


def load_terms(data: list[dict]) -> list[Term]:
    """Terms from ``book/index_terms.yml``'s list (``term``, optional ``match``)."""
    terms = []
    for item in data or []:
        forms = item.get("match") or [re.escape(item["term"].split("!")[-1])]
        terms.append(Term(item["term"], [re.compile(rf"\b(?:{form})\b", re.I)
                                         for form in forms]))
    return terms


def latex_text(text: str) -> str:
    """Markdown text (with ``$math$``) as LaTeX: math kept, bold/italic marks dropped, the
    special characters escaped."""
    out = []
    for index, chunk in enumerate(re.split(r"(\$[^$]+\$)", text)):
        if index % 2:
            out.append(chunk)
        else:
            chunk = re.sub(r"\*+|`", "", chunk)
            out.append("".join(_LATEX_SPECIAL.get(c, c) for c in chunk))
    return "".join(out).strip()


def sort_key(latex: str) -> str:
    r"""An index sort key for a symbol: Greek letters by name, accents after the letter, a
    bold or calligraphic symbol after its plain namesake (the index would merge two entries
    of one key).

    >>> sort_key(r"\dot\varphi_i"), sort_key(r"\mathbf c"), sort_key(r"\Delta s")
    ('varphi i dot', 'c bold', 'Delta s')
    >>> sort_key(r"\mathbf u_i"), sort_key("u_i"), sort_key(r"\mathcal V")
    ('u i bold', 'u i', 'V script')
    """
    bold = re.search(r"\\(?:mathbf|boldsymbol)\b", latex) is not None
    script = re.search(r"\\mathcal\b", latex) is not None
    key = re.sub(r"\\dot(?![A-Za-z])\s*\\?(\w+)|\\dot\{\\?(\w+)\}",
                 lambda m: (m.group(1) or m.group(2)) + " dot", latex)
    key = re.sub(r"\\(?:mathbf|mathrm|mathcal|boldsymbol|operatorname|text)\b", "", key)
    key = re.sub(r"\\([A-Za-z]+)", lambda m: m.group(1) + " "
                 if m.group(1).lower() in _GREEK else " ", key)
    key = re.sub(r"[^A-Za-z0-9]+", " ", key)
    return " ".join(key.split() + (["bold"] if bold else []) + (["script"] if script else []))


@dataclass
class Symbol:
    """One row of the notation page: the symbol, what it is, where it is introduced."""

    latex: str
    meaning: str
    introduced: str | None

    def index_entry(self) -> str:
        """``\\index{sort key@display (meaning)}``, e.g. ``\\index{omega@$\\omega$ (yaw rate)}``."""
        display = f"${self.latex}$"
        if re.fullmatch(r"[A-Za-z]{2,}", self.latex):
            display = latex_text(self.latex)  # a name, e.g. ICR
        meaning = re.sub(r'["!@|]', "", self.meaning)
        return (r"\index{" + sort_key(self.latex).replace("@", "") + "@" + display
                + (f" ({meaning})" if meaning else "") + "}")


def _short_meaning(cell: str, stops: str = ":;,(") -> str:
    """The meaning's head, up to the first colon, semicolon, comma or parenthesis outside
    math: "heading: angle from ..." gives "heading"."""
    depth, out = 0, []
    for char in cell:
        depth ^= char == "$"
        if not depth and char in stops:
            break
        out.append(char)
    return latex_text("".join(out))


def notation_symbols(text: str) -> list[tuple[int, Symbol]]:
    """(line number, symbol) for each row of the page's tables with a ``symbol`` column; a
    cell of several symbols (``$E_d$, $E_b$``) gives one symbol each."""
    found, header = [], None
    for number, line in enumerate(text.split("\n")):
        if not line.lstrip().startswith("|"):
            header = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            header = [c.lower() for c in cells]
            continue
        if set(cells) <= {"---", ":---", "---:", ":---:", ""} or "symbol" not in header:
            continue
        row = dict(zip(header, cells, strict=False))
        introduced = re.search(r"\{ref\}`(?:[^`<]*<)?([\w-]+)>?`", row.get("introduced", ""))
        parts = re.findall(r"\$([^$]+)\$", row["symbol"]) or [row["symbol"]]
        # "degrees of mobility, steerability and ...": a list names several symbols
        meaning = _short_meaning(row.get("meaning", ""), ":;(" if len(parts) > 1 else ":;,(")
        for part in parts:
            latex = part.split("=")[0].strip()
            if latex:
                found.append((number, Symbol(latex, meaning,
                                             introduced.group(1) if introduced else None)))
    return found


def index_symbols(text: str) -> tuple[str, dict[str, list[str]]]:
    """The notation page with each symbol's index entry in its row, and the entries to place
    where each symbol is introduced, by label."""
    lines = text.split("\n")
    at_labels: dict[str, list[str]] = {}
    for number, symbol in notation_symbols(text):
        entry = symbol.index_entry()
        cell_end = lines[number].index("|", lines[number].index("|") + 1)
        if entry not in lines[number]:
            lines[number] = (lines[number][:cell_end].rstrip() + " {wklatex}`" + entry + "` "
                             + lines[number][cell_end:])
        if symbol.introduced:
            at_labels.setdefault(symbol.introduced, []).append(entry)
    return "\n".join(lines), at_labels


def after_label(text: str, label: str, latex: str) -> str | None:
    """``text`` with ``latex`` placed after the heading that ``(label)=`` names (or the line
    after the label), None if the label is not in ``text``."""
    match = re.search(rf"^[ \t]*\({re.escape(label)}\)=[ \t]*\n(?:[ \t]*\n)*(#+ .*\n)?",
                      text, re.M)
    if not match:
        return None
    return text[:match.end()] + "\n" + raw_latex(latex) + "\n" + text[match.end():]


def prose_spans(text: str) -> list[tuple[int, int]]:
    """The stretches of ``text`` that are prose (outside :data:`_PROTECTED`)."""
    spans, start = [], 0
    for match in _PROTECTED.finditer(text):
        if match.start() > start:
            spans.append((start, match.start()))
        start = match.end()
    if start < len(text):
        spans.append((start, len(text)))
    return spans


#: A page discusses a term it names this often (a heading counts twice), or emphasises.
MENTIONS = 3


def term_mentions(cells: list, term: Term) -> tuple[int, tuple | None, tuple | None]:
    """How often the page names ``term`` (a heading counts twice), and where it first does in
    its prose, and where it emphasises it: ``(mentions, (cell, offset) | None, ... | None)``."""
    mentions, first, emphasised = 0, None, None
    for index, cell in enumerate(cells):
        text = cell.source
        spans = prose_spans(text)
        for form in term.forms:
            for match in form.finditer(text):
                mentions += 1
                if re.match(r"[ \t]*#", text[text.rfind("\n", 0, match.start()) + 1:]):
                    mentions += 1  # a heading names it
                if not any(a <= match.start() and match.end() <= b for a, b in spans):
                    continue
                here = (index, match.end())
                if first is None or here < first:
                    first = here
                if (emphasised is None and text[match.start() - 1:match.start()] == "*"
                        and text[match.end():match.end() + 1] == "*"):
                    emphasised = here
    return mentions, first, emphasised


def place_entry(cells: list, term: Term, where: tuple, main: bool) -> None:
    """The term's ``\\index`` entry after the occurrence at ``where`` (bold page if ``main``)."""
    entry = latex_text(term.entry.replace("@", "").replace("|", ""))
    key = (sort_key(entry) if "$" in entry else entry).lower()
    mark = ("{wklatex}`\\index{" + key + ("@" + entry if key != entry else "")
            + ("|spxpagem" if main else "") + "}`")
    cell = cells[where[0]]
    cell.source = cell.source[:where[1]] + mark + cell.source[where[1]:]


def index_terms(cells: list, terms: list[Term], placed: set[str] | None = None) -> int:
    """Index each term on this page if the page discusses it: the term is emphasised there,
    or a heading names it, or it occurs :data:`MENTIONS` times. The entry goes after its first
    occurrence in the prose (bold page where it is emphasised). ``cells`` are objects with
    ``source``; the number of entries placed is returned, and their terms added to
    ``placed``."""
    count = 0
    for term in terms:
        mentions, first, emphasised = term_mentions(cells, term)
        if first is None or (mentions < MENTIONS and emphasised is None):
            continue
        place_entry(cells, term, emphasised or first, emphasised is not None)
        count += 1
        if placed is not None:
            placed.add(term.entry)
    return count


def index_rare_terms(pages: list[list], terms: list[Term], placed: set[str]) -> int:
    """A term that no page discusses is indexed where it is named most (once)."""
    count = 0
    for term in terms:
        if term.entry in placed:
            continue
        best = None
        for cells in pages:
            mentions, first, _ = term_mentions(cells, term)
            if first is not None and (best is None or mentions > best[0]):
                best = (mentions, cells, first)
        if best is not None:
            place_entry(best[1], term, best[2], False)
            placed.add(term.entry)
            count += 1
    return count
