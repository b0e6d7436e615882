"""Claims about the book have evidence (guard 5 of issue 21).

The preface (``book/intro.md``) and "How to use" (``book/how_to_use.md``) say what the book is:
derived, checked, offline, failing when wrong. Each sentence that makes such a claim must name
the test that proves it, in a footnote (``[^nbval]`` in the sentence, ``[^nbval]: ...`` below),
and every test the footnote names must exist:

- a pytest node id, ``tests/<path>.py::test_name``: the file exists and defines the function
  (a file moved to another layer folder of ``tests/`` is found by its name, once);
- a make target, ``make nbval``: the Makefile defines the target.

A claim is a sentence with one of :data:`CLAIM` 's words about the book (derived, checked,
tested, asserts, fails, re-run, offline, network, without Python, exactly what, every
function / figure / ..., at least three, one thing, never raises ...). The footnotes' tests
make the claims true: three of them are here (the chapters derive in sympy and check the
library, the formula modules' functions carry worked examples, the notebooks read no files
and open no connection). The guard is shown to fail on planted pages at the end.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
from pathlib import Path

import nbformat
import pytest

from tools.book_pages import NON_CHAPTER_NOTEBOOKS, chapter_of
from tools.book_text import chapter_pages

ROOT = Path(__file__).resolve().parents[2]

PAGES = [ROOT / "book" / "intro.md", ROOT / "book" / "how_to_use.md"]

#: Words that make a sentence a claim about the book.
CLAIM = re.compile(
    r"\b(?:derived|derives|checked|tested|asserts?|fails?|re-?run|re-?executes?|offline|"
    r"internet|network|without Python|exactly what|deterministic|never (?:raises|shows)|"
    r"at least three|one thing|runs? as a test|nothing leaves|any value|every (?:figure|"
    r"animation|function|symbol|notebook|page|exercise|result|chapter|number|equation|panel|"
    r"control|code cell))\b", re.IGNORECASE)
FOOTNOTE_REF = re.compile(r"\[\^([\w-]+)\](?!:)")
FOOTNOTE_DEF = re.compile(r"^\[\^([\w-]+)\]:\s*(.+?)(?=^\[\^|^\S|\Z)", re.M | re.S)
NODE_ID = re.compile(r"(tests/[\w/]+\.py)(?:::(\w+))?")
MAKE_TARGET = re.compile(r"`make (\w[\w-]*)`")


def sentences(text: str) -> list[str]:
    """The sentences of a page's prose (code blocks, tables and footnote definitions left
    out), each with its footnote references."""
    text = re.sub(r"^```.*?^```", " ", text, flags=re.M | re.S)
    text = FOOTNOTE_DEF.sub(" ", text)
    out = []
    for paragraph in re.split(r"\n\s*\n", text):
        lines = [ln for ln in paragraph.splitlines()
                 if not ln.lstrip().startswith(("|", "#", "(", ":", "```"))]
        flat = " ".join(" ".join(lines).split())
        out.extend(s for s in re.split(r"(?<=[.!?:])\s+(?=[A-Z*`$({])", flat) if s.strip())
    return out


def footnotes(text: str) -> dict[str, str]:
    return {label: " ".join(body.split()) for label, body in FOOTNOTE_DEF.findall(text)}


def _test_file(rel: str, root: Path) -> Path | None:
    path = root / rel
    if path.is_file():
        return path
    moved = [p for p in (root / "tests").rglob(Path(rel).name)]
    return moved[0] if len(moved) == 1 else None


def _defines(path: Path, name: str) -> bool:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return any(isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) and node.name == name
               for node in ast.walk(tree))


def evidence_problems(note: str, root: Path = ROOT) -> list[str]:
    """What is wrong with one footnote: no test named, or a named test that does not exist."""
    problems = []
    ids = NODE_ID.findall(note)
    targets = MAKE_TARGET.findall(note)
    if not ids and not targets:
        return ["it names no test (a `tests/...py::test_name` or a `make <target>`)"]
    makefile = (root / "Makefile").read_text(encoding="utf-8")
    for target in targets:
        if not re.search(rf"^{re.escape(target)}:", makefile, re.M):
            problems.append(f"`make {target}`: no such target in the Makefile")
    for rel, name in ids:
        path = _test_file(rel, root)
        if path is None:
            problems.append(f"{rel}: no such test file")
        elif name and not _defines(path, name):
            problems.append(f"{rel}::{name}: no such test in {path.relative_to(root)}")
    return problems


def claim_problems(text: str, root: Path = ROOT) -> list[str]:
    """Claims without a footnote, footnotes without evidence, references without a note."""
    notes = footnotes(text)
    problems = []
    for sentence in sentences(text):
        if not CLAIM.search(sentence):
            continue
        refs = FOOTNOTE_REF.findall(sentence)
        if not refs:
            problems.append(f"a claim names no test: {sentence[:110]!r}")
        for ref in refs:
            if ref not in notes:
                problems.append(f"[^{ref}] has no footnote: {sentence[:80]!r}")
    for label, note in notes.items():
        problems += [f"[^{label}]: {p}" for p in evidence_problems(note, root)]
    return problems


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_claim_names_the_test_that_proves_it(page):
    problems = claim_problems(page.read_text(encoding="utf-8"))
    assert not problems, f"{page.relative_to(ROOT)}:\n" + "\n".join(problems)


# --- the evidence the pages name that no other test gives ------------------------------------

def _chapters() -> dict[str, list[Path]]:
    found: dict[str, list[Path]] = {}
    for page in chapter_pages():
        if page.suffix == ".ipynb" and chapter_of(page) not in NON_CHAPTER_NOTEBOOKS:
            found.setdefault(chapter_of(page), []).append(page)
    return found


CHAPTERS = _chapters()
SYMPY = re.compile(r"\bsp\.\w+|\bsympy\b")
LIBRARY_CHECK = re.compile(r"\b(?:assert|np\.testing\.assert_\w+)\b")


@pytest.mark.parametrize("chapter", sorted(CHAPTERS))
def test_every_chapter_derives_in_sympy_and_checks_the_library(chapter):
    """A chapter derives in sympy (a code cell that uses it and shows the result) and turns
    the derivation into numbers (``lambdify``) that an ``assert`` compares with the library."""
    code = [c for page in CHAPTERS[chapter] for c in nbformat.read(page, as_version=4).cells
            if c.cell_type == "code"]
    derives = [c for c in code if SYMPY.search(c.source) and c.get("outputs")]
    checks = [c for c in code if "lambdify" in c.source and LIBRARY_CHECK.search(c.source)]
    assert derives, f"{chapter}: no code cell derives anything in sympy and shows it"
    assert checks, (f"{chapter}: no cell turns a sympy result into numbers (lambdify) and "
                    "asserts that the library agrees")


#: The book layer's modules: they draw and print, they hold no formula.
BOOK_LAYER = ("animation", "display", "exercises", "style", "widgets")


def formula_modules(root: Path = ROOT) -> list[str]:
    """The formula modules a robot builder reads: ``wheelkin._registry.FORMULA_MODULES`` where
    the library keeps that list, else the modules the API reference documents
    (``book/api/*.md``) less the sandbox's, the book layer's and the private ones."""
    try:
        from wheelkin._registry import FORMULA_MODULES
    except ImportError:
        names = set()
        for page in (root / "book" / "api").glob("*.md"):
            names |= set(re.findall(r"automodule::\s*(wheelkin[\w.]*)", page.read_text("utf-8")))
        return sorted(n for n in names if not any(p.startswith("_") for p in n.split("."))
                      and not n.startswith("wheelkin.sandbox")
                      and n.split(".")[1] not in BOOK_LAYER)
    return [f"wheelkin.{name}" for name in FORMULA_MODULES]


def test_every_formula_function_has_a_worked_example():
    missing = []
    modules = formula_modules()
    assert len(modules) >= 8, modules
    for name in modules:
        module = importlib.import_module(name)
        for attr in getattr(module, "__all__", ()):
            obj = getattr(module, attr)
            if inspect.isfunction(obj) and obj.__module__ == name \
                    and ">>>" not in (inspect.getdoc(obj) or ""):
                missing.append(f"{name}.{attr}")
    assert not missing, "public functions without a worked example (>>>): " + ", ".join(missing)


FILES_OR_NETWORK = re.compile(
    r"\bopen\(|\burlopen\b|\burllib\b|\brequests\.|\bsocket\b|\bread_csv\b|\bnp\.load\(|"
    r"\bloadtxt\b|\.read_text\(|\.read_bytes\(|\bhttp[s]?://")


def test_notebooks_read_no_files_and_need_no_network():
    found = []
    for page in chapter_pages():
        if page.suffix != ".ipynb":
            continue
        for index, cell in enumerate(nbformat.read(page, as_version=4).cells):
            if cell.cell_type == "code" and FILES_OR_NETWORK.search(cell.source):
                found.append(f"{page.relative_to(ROOT)} cell {index}: "
                             f"{FILES_OR_NETWORK.search(cell.source).group(0)}")
    assert not found, "notebooks that read a file or open a connection:\n" + "\n".join(found)


# --- the guard itself, on planted pages -------------------------------------------------------

def _tree(tmp_path: Path) -> Path:
    (tmp_path / "tests" / "book").mkdir(parents=True)
    (tmp_path / "tests" / "book" / "test_real.py").write_text("def test_it():\n    pass\n")
    (tmp_path / "Makefile").write_text("nbval:\n\ttrue\n")
    return tmp_path


def test_a_claim_with_its_test_passes(tmp_path):
    root = _tree(tmp_path)
    page = ("Every notebook is re-run by the tests.[^a]\n\n"
            "[^a]: `make nbval`, and `tests/book/test_real.py::test_it`.\n")
    assert claim_problems(page, root) == []


def test_the_guard_flags_a_claim_that_names_no_test(tmp_path):
    root = _tree(tmp_path)
    found = claim_problems("A wrong sign fails the build.\n", root)
    assert found and "names no test" in found[0]


def test_the_guard_flags_a_test_that_does_not_exist(tmp_path):
    root = _tree(tmp_path)
    page = ("Every figure is checked offline.[^b]\n\n"
            "[^b]: `tests/book/test_real.py::test_gone` and `make offline`.\n")
    found = claim_problems(page, root)
    assert any("test_gone: no such test" in p for p in found)
    assert any("`make offline`: no such target" in p for p in found)


def test_the_guard_flags_a_live_page_claim_without_a_test(tmp_path):
    root = _tree(tmp_path)
    page = ("Every panel takes any value of every control.\n\n"
            "Nothing leaves your computer.\n")
    assert len([p for p in claim_problems(page, root) if "names no test" in p]) == 2


def test_the_guard_flags_a_footnote_without_a_test(tmp_path):
    root = _tree(tmp_path)
    page = "The book is derived in code.[^c]\n\n[^c]: trust us.\n"
    assert any("names no test" in p for p in claim_problems(page, root))
