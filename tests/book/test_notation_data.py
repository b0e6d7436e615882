"""One meaning per symbol (guard 4 of issue 21): the notation as data, and the chapters held to it.

``book/notation.yml`` holds the notation page's rows (symbol, meaning, unit, sign, the chapter
that introduces it); ``book/notation.md``'s tables are made from it
(``tools/notation_table.py``). For every row with a ``check`` (see the file's header), the
chapters listed in ``_toc.yml`` are read, in order:

- **first use**: the first chapter whose prose (or printed Markdown) writes one of the row's
  tokens in math, outside a sentence that cites a source, must be the row's ``introduced``
  chapter;
- **one meaning**: where a chapter *names* the symbol (a noun phrase right before it, "the half
  track $b$"; after it, "$b$ is the ...", "$b$, the ..."; or a table row that holds it), the
  name must use one of the row's words; a name that belongs to a row's ``phrases`` ("half
  track") must carry that row's symbol; and a row's ``aliases`` (another spelling of the same
  quantity, ``r_w`` for ``r``) are not used at all.

A sentence that quotes a source (it cites one, or speaks of the document's, README's, lab's,
paper's symbol) is the source's notation, converted where the chapter reads it, and is not
held to the book's. Simple text rules, not understanding; the guard is shown to catch the
conflicts issue 21 found on planted text at the end of this file.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from tools.book_text import chapter_pages, page_markdown, prose, read_notebook
from tools.notation_table import DATA, PAGE, load, page_with_tables

ROOT = Path(__file__).resolve().parents[2]

MATH = re.compile(r"\$\$(.+?)\$\$|\$(.+?)\$", re.S)
#: A sentence in a source's voice: its notation is the source's, quoted.
SOURCE_VOICE = re.compile(
    r"\{cite|README|firmware|document's|documents|the document|report's|the report|lab's|"
    r"paper's|the paper|simulator's|the simulator|\btheir\b|\bwrites\b|\bcalls\b",
    re.IGNORECASE)
#: Words that do not name anything: a noun phrase stops at them.
STOP = frozenset("""a an the of by to with and or for at in on is are was be its their this that
these those then as so from per over into than each every both when while where which who it we
you one two three four half-way not no nor if else all any some same other another only just
about between through after before under above up down out off than divided multiplied times
minus plus gives give given giving set sets makes make takes take keep keeps hold holds reach
reaches say says said turns write writes written use uses used call calls called becomes become
equals equal let has have had do does did get gets see shows show find finds means mean
number how what why wheel's sign could would should can may might must will larger smaller
longer shorter wider narrower positive negative signed small large tiny new true wrong example
measures needs asks brings push pushes helps changes costs moves double halve doubles halves
drives steers turned doubling halving chapter's along across symbol symbols letter letters
notation""".split())
#: What may stand right before a noun phrase that names a symbol ("the half track $b$").
DETERMINERS = frozenset("a an the its our each half".split())
WORD = re.compile(r"[A-Za-z][A-Za-z'-]*")


def rows(data: dict | None = None) -> list[dict]:
    data = data or load()
    return [row for section in data["sections"] for row in section["rows"]]


def checked_rows(data: dict | None = None) -> list[dict]:
    return [row for row in rows(data) if row.get("check", {}).get("tokens")]


def token_pattern(token: str) -> re.Pattern:
    """A token as a whole symbol inside math: not a part of a command or a longer name, not a
    subscript or an exponent, not followed by a subscript (``T_w`` is another symbol), and a
    plain letter not in bold (``\\mathbf u_i``, a roller's axis, is not ``u_i``, an input) nor
    upright (``\\mathrm{m/s}`` is a unit, not a mass) nor calligraphic (``\\mathcal V``, a
    Lyapunov function, is not ``V``, a rim speed)."""
    body = re.escape(token)
    bold = "" if token.startswith("\\") else (r"(?<!\\mathbf )(?<!\\mathbf\{)(?<!\\boldsymbol\{)"
                                              r"(?<!\\mathrm\{)(?<!\\text\{)"  # a unit: m/s
                                              r"(?<!\\mathcal )(?<!\\mathcal\{)")  # another letter
    return re.compile(rf"(?<![\\A-Za-z_^]){bold}{body}(?![A-Za-z_])")


def _math(text: str):
    for match in MATH.finditer(text):
        yield match, (match.group(1) or match.group(2))


def uses(text: str, row: dict) -> bool:
    """Whether a prose text writes one of the row's tokens in its math."""
    patterns = [token_pattern(t) for t in row["check"]["tokens"]]
    return any(p.search(body) for _, body in _math(text) for p in patterns)


def sentences(text: str) -> list[str]:
    """Table rows and the sentences of each paragraph."""
    out = []
    for paragraph in re.split(r"\n\s*\n", text):
        lines = paragraph.splitlines()
        out += [ln for ln in lines if ln.lstrip().startswith("|")]
        flat = " ".join(" ".join(ln for ln in lines if not ln.lstrip().startswith("|")).split())
        out += [s for s in re.split(r"(?<=[.!?])\s+(?=[A-Z$({*])", flat) if s.strip()]
    return out


def _name_before(sentence: str, start: int) -> list[str]:
    """The noun phrase right before a math, if a determiner opens it: "the lap time", "a
    steering arm of length" (a phrase ends at a word of :data:`STOP`, a participle or a
    punctuation mark)."""
    before = re.sub(r"\$[^$]*\$", " , ", sentence[:start])
    if re.search(r"[,;:(\[]\s*$", before):
        return []
    tokens = re.findall(r"[A-Za-z][A-Za-z'-]*|[^\sA-Za-z]", before)[-6:]
    name: list[str] = []
    opener = None
    for token in reversed(tokens):
        word = token.lower()
        participle = not name and word.endswith(("ed", "ing"))  # "doubling $W$"
        if not WORD.fullmatch(token) or word in STOP or participle:
            opener = word
            break
        name.insert(0, token)
    if not name or opener not in DETERMINERS | {"of"}:
        return []
    return name


def _name_after(sentence: str, end: int) -> list[str]:
    after = sentence[end:]
    match = re.match(r"\s*(?:,\s*the|\(the|is the|is a|is its|for the|denotes the)\s+"
                     r"([^.,;:()]{1,60})", after)
    return WORD.findall(match.group(1))[:5] if match else []


def namings(sentence: str):
    """(the math's body, the words that name it, from a table?) for each math in the sentence
    that a noun phrase or a table row names."""
    if sentence.lstrip().startswith("|"):
        cells = [c.strip() for c in sentence.strip().strip("|").split("|")]
        if cells and set(cells[0]) <= set("- "):
            return
        text_words = [w for c in cells for w in WORD.findall(re.sub(r"\$[^$]*\$", " ", c))]
        for cell in cells[:2]:
            for _, body in _math(cell):
                if cell.startswith("$") and len(cell) <= len(body) + 40:
                    yield body, text_words, True
        return
    for match, body in _math(sentence):
        name = _name_before(sentence, match.start()) or _name_after(sentence, match.end())
        if name:
            yield body, name, False


def _words_after(sentence: str, body: str) -> list[str]:
    """The few words after a math, up to a punctuation mark ("the angle $\\gamma$ with the
    axle"): they may name the symbol too."""
    at = sentence.find(body)
    if at < 0:
        return []
    match = re.match(r"\$*\s*([^.,;:()$]{0,40})", sentence[at + len(body):])
    return WORD.findall(match.group(1))[:4] if match else []


def _has_word(name: list[str], words: list[str]) -> bool:
    lowered = [w.lower() for w in name]
    return any(n.startswith(w.lower()[:max(4, len(w) - 2)]) or n == w.lower()
               for n in lowered for w in words)


def meaning_problems(text: str, data: dict | None = None) -> list[str]:
    """Names of a checked symbol without one of its words, a row's phrase on another symbol,
    and aliases, in one chapter's prose."""
    problems = []
    table_rows = checked_rows(data)
    for sentence in sentences(_without_source_tables(prose(text))):
        quoted = bool(SOURCE_VOICE.search(sentence))
        for row in table_rows:
            for alias in row["check"].get("aliases", []):
                if any(token_pattern(alias).search(b) for _, b in _math(sentence)):
                    problems.append(f"{alias} for {row['symbol']}: {sentence.strip()[:100]!r}")
        if quoted:
            continue
        for body, name, from_table in namings(sentence):
            bare = body.strip()
            for row in table_rows:
                patterns = [token_pattern(t) for t in row["check"]["tokens"]]
                lead = re.match(r"([^=<>]+?)\s*(?:=|<|>|\\le|\\ge|$)", bare)
                own = lead and any(p.fullmatch(lead.group(1).strip()) for p in patterns)
                if own and not _has_word(name + _words_after(sentence, body),
                                         row["check"].get("words", [])):
                    problems.append(f"{row['symbol']} named {' '.join(name)!r}: "
                                    f"{sentence.strip()[:100]!r}")
                phrase = " ".join(name).lower()
                if not own and not from_table \
                        and any(p in phrase for p in row["check"].get("phrases", [])) \
                        and lead and re.fullmatch(r"[\\\w{}]+", lead.group(1).strip()) \
                        and not any(token_pattern(t).search(bare)
                                    for r in table_rows for t in r["check"]["tokens"]
                                    if r is not row):
                    problems.append(f"{' '.join(name)!r} is {row['symbol']}, written "
                                    f"${bare}$: {sentence.strip()[:100]!r}")
    return problems


#: The first cell of a table that translates a source's symbols ("| document | meaning |").
SOURCE_TABLE = re.compile(r"^\|\s*(?:document|README|source|the lab's|report|paper)\b", re.I)


def _without_source_tables(text: str) -> str:
    """``text`` without the tables that quote a source's symbols (by their header)."""
    out, skipping = [], False
    for line in text.splitlines():
        if line.lstrip().startswith("|"):
            if not skipping and SOURCE_TABLE.match(line.strip()) and not out[-1:] == ["|"]:
                skipping = True
            if skipping:
                continue
        else:
            skipping = False
        out.append(line)
    return "\n".join(out)


def _chapter_label(page: Path) -> str | None:
    index = page.parent / "index.md"
    if not index.is_file():
        return None
    match = re.search(r"^\((chapter-[\w-]+)\)=", index.read_text(encoding="utf-8"), re.M)
    return match.group(1) if match else None


def _printed_markdown(page: Path) -> list[str]:
    """The Markdown a page's cells print: a reader meets a symbol there too."""
    if page.suffix != ".ipynb":
        return []
    return [str(out["data"]["text/markdown"]) for cell in read_notebook(page).cells
            if cell.cell_type == "code" for out in cell.get("outputs", [])
            if "text/markdown" in out.get("data", {})]


def first_uses(data: dict | None = None) -> dict[str, str | None]:
    """For each checked row, the label of the first chapter (in the toc's order) that uses it."""
    found: dict[str, str | None] = {}
    pages = chapter_pages()
    for row in checked_rows(data):
        found[row["symbol"]] = None
        for page in pages:
            texts = [*page_markdown(page), *_printed_markdown(page)]
            if any(uses(prose(sentence), row) for text in texts for sentence in sentences(text)
                   if "{cite" not in sentence):
                found[row["symbol"]] = _chapter_label(page)
                break
    return found


# --- the checks -----------------------------------------------------------------------------

def test_the_notation_page_is_made_from_the_data():
    page = PAGE.read_text(encoding="utf-8")
    assert page_with_tables(page, load()) == page, (
        "book/notation.md's tables differ from book/notation.yml: run "
        "`.venv/bin/python -m tools.notation_table --write`")


def test_every_introduced_chapter_exists():
    labels = {_chapter_label(p) for p in chapter_pages()}
    wrong = [f"{r['symbol']}: {r['introduced']}" for r in rows() if r["introduced"] not in labels]
    assert not wrong, "rows introduced in no chapter of the toc: " + ", ".join(wrong)


def test_first_use_is_where_the_notation_page_says():
    first = first_uses()
    wrong = [f"{row['symbol']}: the page says {row['introduced']}, first used in "
             f"{first[row['symbol']]}"
             for row in checked_rows() if first[row["symbol"]] != row["introduced"]]
    assert not wrong, "wrong 'introduced' entries in book/notation.yml:\n" + "\n".join(wrong)


@pytest.mark.parametrize("page", chapter_pages(),
                         ids=lambda p: p.relative_to(ROOT / "notebooks").as_posix())
def test_a_symbol_keeps_its_meaning(page):
    problems = [p for text in page_markdown(page) for p in meaning_problems(text)]
    assert not problems, (f"{page.relative_to(ROOT)} names a symbol of book/notation.yml with "
                          "another meaning (rename it, or give the row a word it lacks):\n"
                          + "\n".join(problems))


# --- the guard itself, on planted text --------------------------------------------------------

DATA_TEXT = DATA.read_text(encoding="utf-8")


def test_the_guard_catches_the_conflicts_issue_21_found():
    data = yaml.safe_load(DATA_TEXT)
    planted = {
        "computation of the turn term $T = \\omega W\\,\\mathrm{ENC}/(2\\cdot10^6)$ steps/s.": "$T$",
        "The steering arm of length $a$ is fixed to the kingpin.": "$a = L/2$",
        "The steering arms sit at the arm angle $\\gamma$ from the car's axis.": "$\\gamma$",
        "Every side bends by the angle $\\beta$ (positive: to the left).": "$\\beta$",
        "The wheels are $W$ apart, on lines $d$ to either side of the centre; the half "
        "track $d$ is 0.06 m.": "half track",
        "The wheel radius $r_w$ is 0.04 m.": "r_w",
        "A controller sends the steering command $c$ to the rover.": "$\\mathbf c",
        "Its wheels turn at the lap time $R$ of the circuit.": "$R$",  # "its" is not a source
        # since chapter 10: q is the configuration, eta the integrating factor
        "The rover turns by the steering command $q$ from -100 to 100.": "$q$",
        "The grip share $\\eta$ stays below one on a dry floor.": "$\\eta(q)$",
        # issue 21's k, V, tau and m: one meaning each
        "The Euler step $k$ has length $h$.": "$k = b",
        "The centre of mass moves at the rate $V$ along the path.": "$V$",
        "The update's duration $\\tau$ does not matter.": "$\\tau$",
        "A vehicle has the number of fields $m$ of its constraints.": "$m$",
    }
    for text, expected in planted.items():
        found = meaning_problems(text, data)
        assert any(expected in p for p in found), (text, found)
    quiet = ["The lap time $T$ and the radius $R_c$ of the circle.",
             "The half track $b$ and the half wheelbase $a$ of the vehicle.",
             "The document's angle $\\theta$ is the heading change.",  # a source's voice
             "| $\\gamma$ | angle between a floor roller's axis and the wheel's axle |",
             "Each input $u_i$ is a speed or a rate.",  # plain u: not the roller's bold axis
             "The symbols $W$, $L$ and $r$ of the vehicle.",
             "The floor roller's axis $\\mathbf u_i$ and the input $u_i$ of the field.",
             "The share of the grip $U$ and the configuration $q$ of the car.",
             "The lever arm $k$, the wheel noise $k_w$ and the rim speed $V$.",
             "The motor lag $\\tau$ and the mass $m$ at $0.5~\\mathrm{m/s}$."]
    for text in quiet:
        assert meaning_problems(text, data) == [], (text, meaning_problems(text, data))


def test_the_guard_catches_a_wrong_first_use(monkeypatch):
    data = yaml.safe_load(DATA_TEXT)
    for row in checked_rows(data):
        if row["symbol"] == "$\\chi$":
            row["introduced"] = "chapter-waypoints"  # the page's entry before issue 21
    found = {row["symbol"]: row["introduced"] for row in checked_rows(data)}
    assert found["$\\chi$"] != first_uses(data)["$\\chi$"] == "chapter-sandbox"
