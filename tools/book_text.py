"""The book's text as the prose guards read it: markdown cells, their outputs, and links.

Shared by the prose guards (``tests/book/test_prose_numbers.py``, ``test_notation_data.py``,
``test_claims.py``) and the student-edition guard (``tests/kit/test_student_tasks.py``). The
pages are those of ``_toc.yml`` (``book_pages.toc_files``), so a new chapter is read the moment
it is listed.

- :func:`prose` strips from a markdown text what is not prose: fenced code, inline code,
  directive options, MyST labels, the targets of roles (``{ref}`...```) and addresses;
- :func:`output_text` is the text a code cell printed or displayed (stream, plain, Markdown,
  LaTeX, small HTML; never images or the frames of an animation);
- :func:`page_of_label` finds the page that defines a ``(label)=``, so that a guard can follow
  a ``{ref}`` or ``{doc}`` link to the page it points at.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import nbformat

from tools.book_pages import ROOT, toc_files

#: HTML outputs larger than this are animations or widgets, not text.
MAX_HTML_CHARS = 20_000

_FENCE = re.compile(r"^(?P<f>```+|~~~+)[^\n]*\n.*?^(?P=f)[ \t]*$", re.M | re.S)
_INLINE_CODE = re.compile(r"(`+)(?!\s)(.+?)(?<!\s)\1", re.S)
_ROLE = re.compile(r"\{(?:ref|doc|numref|eq|cite:p|cite:t|cite|download|term)\}`[^`]*`")
_LABEL = re.compile(r"^\([\w:.-]+\)=[ \t]*$", re.M)
_DIRECTIVE_OPTION = re.compile(r"^:[\w-]+:.*$", re.M)
_DIRECTIVE = re.compile(r"^(?::{3,}|`{3,})\{[\w-]+\}.*$", re.M)
_URL = re.compile(r"<?https?://\S+>?")
_MATH_LABEL = re.compile(r"\$\$[ \t]*\([\w:.-]+\)")
_HTML_COMMENT = re.compile(r"<!--.*?-->", re.S)


def prose(text: str) -> str:
    """``text`` without code, labels, directive lines, role targets and addresses."""
    text = _HTML_COMMENT.sub(" ", text)
    text = _FENCE.sub(" ", text)
    text = _ROLE.sub(" ", text)
    text = _INLINE_CODE.sub(" ", text)
    text = _LABEL.sub(" ", text)
    text = _DIRECTIVE.sub(" ", text)
    text = _DIRECTIVE_OPTION.sub(" ", text)
    text = _MATH_LABEL.sub("$$", text)
    return _URL.sub(" ", text)


def tags(cell) -> set[str]:
    """The cell's tags."""
    return set(cell.get("metadata", {}).get("tags", []))


def output_text(cell) -> str:
    """What a code cell printed or displayed, as text (no images, no animation frames)."""
    if cell.get("cell_type") != "code":
        return ""
    parts = []
    for out in cell.get("outputs", []):
        if out.get("output_type") == "stream":
            parts.append(str(out.get("text", "")))
        elif out.get("output_type") == "error":
            parts.append(str(out.get("evalue", "")))
        data = out.get("data", {})
        for kind in ("text/markdown", "text/latex", "text/plain"):
            if kind in data:
                parts.append(str(data[kind]))
        html = data.get("text/html")
        if html and len(str(html)) <= MAX_HTML_CHARS and "image/png" not in data:
            parts.append(re.sub(r"<[^>]+>", " ", str(html)))
    return "\n".join(parts)


@cache
def read_notebook(path: Path):
    """A notebook, read once per process."""
    return nbformat.read(path, as_version=4)


def toc_pages(root: Path = ROOT) -> list[Path]:
    """Every page the table of contents lists, notebooks and Markdown pages, in order."""
    pages = []
    for page in toc_files(root / "_toc.yml"):
        for suffix in (".ipynb", ".md"):
            if (root / (page + suffix)).is_file():
                pages.append(root / (page + suffix))
                break
    return pages


def chapter_pages(root: Path = ROOT) -> list[Path]:
    """The pages of the chapters: every page under ``notebooks/`` that the toc lists."""
    return [p for p in toc_pages(root) if "notebooks" in p.relative_to(root).parts[:1]]


def page_markdown(path: Path) -> list[str]:
    """The markdown of a page: each markdown cell of a notebook, or the whole Markdown file."""
    if path.suffix == ".md":
        return [path.read_text(encoding="utf-8")]
    return [c.source for c in read_notebook(path).cells if c.cell_type == "markdown"]


def page_outputs(path: Path) -> str:
    """Everything a page's code cells printed (empty for a Markdown page)."""
    if path.suffix != ".ipynb":
        return ""
    return "\n".join(output_text(c) for c in read_notebook(path).cells)


@cache
def _labels(root: Path = ROOT) -> dict[str, Path]:
    found: dict[str, Path] = {}
    for page in toc_pages(root):
        texts = page_markdown(page)
        if page.suffix == ".ipynb":  # labels a cell prints (admonitions made by code)
            texts = [*texts, page_outputs(page)]
        for text in texts:
            for label in re.findall(r"^\(([\w:.-]+)\)=[ \t]*$", text, re.M):
                found.setdefault(label, page)
    return found


def page_of_label(label: str, root: Path = ROOT) -> Path | None:
    """The page that defines ``(label)=``, or None."""
    return _labels(root).get(label)


_REF = re.compile(r"\{(?:ref|numref)\}`(?:[^`<]*<)?([\w:.-]+)>?`")
_DOC = re.compile(r"\{doc\}`(?:[^`<]*<)?([^`>]+)>?`")


def linked_pages(text: str, page: Path, root: Path = ROOT) -> list[Path]:
    """The pages a markdown text links to with ``{ref}`` or ``{doc}``."""
    out = []
    for label in _REF.findall(text):
        target = page_of_label(label, root)
        if target is not None:
            out.append(target)
    for doc in _DOC.findall(text):
        doc = doc.strip()
        base = root if doc.startswith("/") else page.parent
        stem = (base / doc.lstrip("/")).resolve()
        for suffix in (".ipynb", ".md"):
            candidate = stem.with_suffix(suffix) if stem.suffix in ("", ".md", ".ipynb") \
                else Path(str(stem) + suffix)
            if candidate.is_file():
                out.append(candidate)
                break
    return out
