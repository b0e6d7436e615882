#!/usr/bin/env python
"""The printed edition: a PDF of the whole book, built with Jupyter Book's LaTeX builder.

Usage::

    python -m tools.pdf_edition [--out _build/pdf]     # or: make pdf  (make tex installs TeX)

The book is copied into ``_build/pdf_src/`` and the copy is made into a printed book
(docs/DESIGN.md, "The printed edition"):

- numbered as the web edition, from ``_toc.yml``'s parts (``book_pages.book_structure``): the
  preface, how to use and notation as front matter (roman pages, no numbers), the chapters in
  their parts, the back matter as appendices A, B, ...; a chapter's landing page prints its own
  headings without numbers, so that its first section is N.1 as on the web;
- every animation (matplotlib's ``to_jshtml`` player, frames embedded as base64 PNG) becomes
  three of its frames (first, middle, last), each printed at the animation's own size, followed
  by its caption;
- live panels and their "Live panel" margin notes are left out; folded code (``hide-input``) is
  left out, its output kept; solutions are left out, as in the student edition; prose about
  folded cells and the live panel is said as paper says it (``pdf_text.paper_wording``);
- each *check your understanding* answer moves to the end of its chapter, numbered, and the
  question points to it by number and page (and back);
- cross-references print the target's number and page (``tools/pdf_latex.py``);
- the index lists the notation page's symbols and the terms of ``book/index_terms.yml``.

Then ``jupyter-book build --builder pdflatex`` runs XeLaTeX (Unicode: the book's Greek,
arrows and check marks) with the FreeSerif/FreeSans and DejaVu Sans Mono fonts, and xindy for
the index; the PDF is copied to ``<out>/wheelkin.pdf``. The TeX packages: ``make tex`` (Debian:
texlive-xetex, texlive-latex-extra, texlive-fonts-recommended, latexmk, xindy,
fonts-freefont-otf, fonts-dejavu-core, poppler-utils).
"""

from __future__ import annotations

import argparse
import base64
import html
import io
import json
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import nbformat
import yaml

from tools import pdf_text
from tools.book_pages import book_structure, toc_files
from tools.student_edition import (
    copy_includes,
    remove_solution_sentences,
    student_notebook,
)

ROOT = Path(__file__).resolve().parents[1]

#: The commands the build needs (``make tex`` installs them).
NEEDED = ("xelatex", "latexmk", "xindy", "pdfinfo", "pdftotext")
FRAMES_SHOWN = 3
_FRAME = re.compile(r'frames\[(\d+)\] = "data:image/png;base64,((?:[A-Za-z0-9+/=]|\\\n)+)"')
_CAPTION = re.compile(r"<figcaption[^>]*>(.*?)</figcaption>", re.S)
_ALT = re.compile(r'<img[^>]*\balt="([^"]*)"', re.S)
_MARGIN_PANEL = re.compile(r"^(:{3,}|`{3,})\{margin\}\s*Live panel.*?^\1[ \t]*\n?", re.S | re.M)
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"


def _tags(cell) -> set[str]:
    return set(cell.get("metadata", {}).get("tags", []))


def _text(value) -> str:
    return "".join(value) if isinstance(value, list) else str(value)


def animation_frames(markup: str) -> list[bytes]:
    """The PNG frames embedded in a ``to_jshtml`` player, in order."""
    frames = sorted((int(i), data) for i, data in _FRAME.findall(markup))
    return [base64.b64decode(data.replace("\\\n", "")) for _, data in frames]


def _plain(fragment: str) -> str:
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", fragment)).split())


def strip_outputs(markup: str, index: int, count: int) -> list[dict]:
    """The outputs that replace one animation: frames and a caption (markdown)."""
    frames = animation_frames(markup)
    caption = _CAPTION.search(markup)
    alt = _ALT.search(markup)
    text = _plain(caption.group(1)) if caption else ""
    picks = sorted({round(k * (len(frames) - 1) / (FRAMES_SHOWN - 1))
                    for k in range(FRAMES_SHOWN)}) if len(frames) > 1 else [0]
    outputs = []
    for pick in picks:
        if pick >= len(frames):
            continue
        png = _with_dpi(frames[pick])
        outputs.append(nbformat.v4.new_output(
            "display_data", data={"image/png": base64.b64encode(png).decode("ascii"),
                                  "text/plain": f"<frame {pick + 1} of {len(frames)}>"},
            metadata={"image/png": {"alt": _plain(alt.group(1)) if alt else text}}))
    shown = ", ".join(str(p + 1) for p in picks)
    note = f"*Animation, frames {shown} of {len(frames)}.* {pdf_text.paper_caption(text)}".strip()
    outputs.append(nbformat.v4.new_output("display_data", data={"text/markdown": note,
                                                                "text/plain": note}))
    return outputs


def _with_dpi(png: bytes, dpi: int = 100) -> bytes:
    """The frame re-saved with its resolution stated (LaTeX sizes an image by it)."""
    from PIL import Image

    image = Image.open(io.BytesIO(png))
    buf = io.BytesIO()
    image.save(buf, format="png", dpi=(dpi, dpi), optimize=True)
    return buf.getvalue()


def is_live_panel(cell) -> bool:
    if cell.cell_type != "code":
        return False
    if any(WIDGET_MIME in out.get("data", {}) for out in cell.get("outputs", [])):
        return True
    return "remove-output" in _tags(cell) and re.search(r"panel", cell.source, re.I) is not None


def print_notebook(nb) -> tuple[nbformat.NotebookNode, dict]:
    """The printed edition of one notebook, and what changed, counted."""
    nb, changes = student_notebook(nb)
    changes.update(animations=0, panels=0, folded=0, wording=0)
    cells = []
    for cell in nb.cells:
        if is_live_panel(cell):
            changes["panels"] += 1
            continue
        tags = _tags(cell)
        if cell.cell_type == "markdown":
            new = pdf_text.paper_wording(_MARGIN_PANEL.sub("", cell.source))
            if new != cell.source:
                changes["wording"] += 1
                cell.source = new
                if not new.strip():
                    continue
            cells.append(cell)
            continue
        figure = cell.metadata.get("mystnb", {}).get("figure", {})
        if figure.get("caption"):
            figure["caption"] = pdf_text.paper_wording(figure["caption"])
        if cell.cell_type != "code":
            cells.append(cell)
            continue
        if "hide-input" in tags or "hide-cell" in tags:
            changes["folded"] += 1
            cell.metadata["tags"] = [t for t in cell.metadata.get("tags", [])
                                     if t not in ("hide-input", "hide-cell")] + ["remove-input"]
        if "exercise" in tags:
            cell.outputs = []
        outputs = []
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            markup = _text(data.get("text/html", ""))
            if "_anim_img" in markup and _FRAME.search(markup):
                changes["animations"] += 1
                outputs += strip_outputs(markup, changes["animations"], len(outputs))
                cell.metadata.get("mystnb", {}).pop("figure", None)
                continue
            if WIDGET_MIME in data:
                continue
            outputs.append(out)
        cell.outputs = outputs
        cells.append(cell)
    nb.cells = cells
    return nb, changes


#: The printed edition's LaTeX: front matter (roman pages, no numbers), main matter (arabic,
#: numbered chapters in parts), appendices (lettered), the answers at a chapter's end, and the
#: cross-references' number and page (tools/pdf_latex.py writes them).
PREAMBLE = r"""
\let\wheelkinhyperlink\hyperlink
\DeclareRobustCommand{\hyperlink}[2]{\wheelkinhyperlink{#1}{#2}}
\addto\captionsenglish{\renewcommand{\contentsname}{Contents}}
\usepackage{etoolbox}
\makeatletter
\newcommand\wkdepth{-1}
\pretocmd{\chapter}{\setcounter{secnumdepth}{\wkdepth}}{}{}
\AtBeginDocument{\pagenumbering{roman}}% the title page is i, the contents follow
\renewcommand{\sphinxtableofcontents}{%
  \begingroup\parskip\z@skip\sphinxtableofcontentshook\tableofcontents\endgroup
  \if@openright\cleardoublepage\else\clearpage\fi}
\newcommand\wkfrontmatter{\renewcommand\wkdepth{-1}}
\newcommand\wkmainmatter{\cleardoublepage\pagenumbering{arabic}\renewcommand\wkdepth{2}%
  \setcounter{secnumdepth}{2}}
\newcommand\wkpart[1]{\part{#1}}
\newcommand\wkappendices{\cleardoublepage\appendix\renewcommand\wkdepth{2}%
  \setcounter{secnumdepth}{2}\part*{Appendices}\addcontentsline{toc}{part}{Appendices}}
% The bibliography in the References appendix (tools/pdf_latex.py): a list, no chapter.
\patchcmd{\thebibliography}{\chapter*{\bibname}\@mkboth{\MakeUppercase\bibname}%
  {\MakeUppercase\bibname}}{}{}{}
\renewenvironment{sphinxthebibliography}[1]{\begin{thebibliography}{#1}}{\end{thebibliography}}
\makeatother
\newcommand\wkxref[2]{#1~\ref{#2}, p.~\pageref{#2}}
\newcommand\wknumref[2]{\hyperref[#2]{#1~\ref*{#2}} (p.~\pageref*{#2})}
\newcommand\wknumrefcomma[2]{\hyperref[#2]{#1~\ref*{#2}}, p.~\pageref*{#2}}
\newcommand\wkpageref[1]{p.~\pageref{#1}}
\newcommand\wkquestionstart[1]{\phantomsection\label{wkq:#1}}
\newcommand\wkquestion[1]{\textit{Answer~\hyperref[wka:#1]{#1} on p.~\pageref{wka:#1}.}}
\newcommand\wkanswers{\section*{Answers to the questions}%
  \addcontentsline{toc}{section}{Answers to the questions}\markright{Answers to the questions}}
\newcommand\wkanswer[1]{\phantomsection\label{wka:#1}%
  \textbf{Answer~#1} (question on p.~\pageref{wkq:#1}).\enspace}
"""

#: The printed edition's root page: the title only (the preface becomes a chapter of the front
#: matter, "Preface", so that every page of the book is a chapter under it).
PRINT_ROOT = "print_root"
PREFACE_TITLE = "Preface"


class Page:
    """One page of the printed copy: a notebook or a markdown file, transformed in memory."""

    def __init__(self, page: str, path: Path):
        self.page, self.path = page, path
        self.nb = nbformat.read(path, as_version=4) if path.suffix == ".ipynb" else None
        self.text = None if self.nb is not None else path.read_text(encoding="utf-8")

    def markdown(self) -> list:
        """The markdown cells (a notebook) or the page itself, as objects with ``source``."""
        if self.nb is not None:
            return [cell for cell in self.nb.cells if cell.cell_type == "markdown"]
        return [self]

    @property
    def source(self) -> str:
        return self.text

    @source.setter
    def source(self, value: str) -> None:
        self.text = value

    def prepend(self, markdown: str) -> None:
        if self.nb is not None:
            self.nb.cells.insert(0, nbformat.v4.new_markdown_cell(markdown))
        else:
            self.text = markdown + "\n" + self.text

    def append(self, markdown: str) -> None:
        if self.nb is not None:
            self.nb.cells.append(nbformat.v4.new_markdown_cell(markdown))
        else:
            self.text = self.text.rstrip("\n") + "\n\n" + markdown

    def write(self, dest: Path) -> None:
        dest.parent.mkdir(parents=True, exist_ok=True)
        if self.nb is not None:
            nbformat.write(self.nb, dest)
        else:
            dest.write_text(self.text, encoding="utf-8")


def _load_pages(src: Path) -> dict[str, Page]:
    """Every page of the toc, transformed for paper (notebooks: :func:`print_notebook`)."""
    pages: dict[str, Page] = {}
    for page in toc_files(ROOT / "_toc.yml"):
        for suffix in (".md", ".rst", ".ipynb"):
            path = ROOT / (page + suffix)
            if path.is_file():
                loaded = Page(page, path)
                if loaded.nb is not None:
                    loaded.nb, _ = print_notebook(loaded.nb)
                else:
                    loaded.text = pdf_text.paper_wording(
                        remove_solution_sentences(_MARGIN_PANEL.sub("", loaded.text)))
                pages[page] = loaded
                break
    return pages


def arrange(pages: dict[str, Page], structure: list, preface: str) -> dict[str, int]:
    """Front matter, parts, appendices, landing pages and answers, in the pages; returns the
    number of questions of each division. ``preface`` is the book's root page."""
    questions: dict[str, int] = {}
    structure = [d for d in structure if d.page in pages]
    main = [d for d in structure if d.matter == "main"]
    back = [d for d in structure if d.matter == "back"]
    previous_part = None
    for division in structure:
        first = pages.get(division.page)
        if first is None:
            continue
        markers = []
        if division is structure[0]:
            markers.append(r"\wkfrontmatter")
        if main and division is main[0]:
            markers.append(r"\wkmainmatter")
        if division.matter == "main" and division.part and division.part != previous_part:
            markers.append(r"\wkpart{" + division.part + "}")
            previous_part = division.part
        if back and division is back[0]:
            markers.append(r"\wkappendices")
        if division.page == preface:
            for cell in first.markdown()[:1]:
                cell.source = pdf_text.retitle(cell.source, PREFACE_TITLE)
        if markers:
            first.prepend(pdf_text.raw_latex(*markers))
        answers: list[pdf_text.Answer] = []
        for name in division.pages:
            page = pages.get(name)
            if page is None:
                continue
            for cell in page.markdown():
                if division.has_pages(name):
                    cell.source = pdf_text.headings_to_rubrics(cell.source)
                cell.source = pdf_text.split_answers(cell.source, division.number or "",
                                                     answers)
        questions[division.page] = len(answers)
        if answers:
            pages[division.pages[-1]].append(pdf_text.answers_section(answers))
    return questions


#: The label of the notation page, whose tables' symbols the index lists.
NOTATION_LABEL = "notation"
#: The terms of the index (``book/index_terms.yml``).
INDEX_TERMS = Path("book") / "index_terms.yml"


def index_entries(pages: dict[str, Page], terms: list[pdf_text.Term]) -> dict[str, int]:
    """The index: the notation page's symbols (in their rows, and where each is introduced)
    and the terms, on the pages that discuss them. Returns the entries placed, by kind."""
    counts = {"symbols": 0, "introduced": 0, "terms": 0}
    label_line = re.compile(rf"^\({NOTATION_LABEL}\)=[ \t]*$", re.M)
    notation = next((p for p in pages.values()
                     if any(label_line.search(c.source) for c in p.markdown())), None)
    if notation is not None:
        for cell in notation.markdown():
            cell.source, at_labels = pdf_text.index_symbols(cell.source)
            counts["symbols"] += sum(len(v) for v in at_labels.values())
            for label, entries in at_labels.items():
                for page in pages.values():
                    for target in page.markdown():
                        placed = pdf_text.after_label(target.source, label, "".join(entries))
                        if placed is not None:
                            target.source = placed
                            counts["introduced"] += len(entries)
    placed: set[str] = set()
    for page in pages.values():
        counts["terms"] += pdf_text.index_terms(page.markdown(), terms, placed)
    counts["terms"] += pdf_text.index_rare_terms([p.markdown() for p in pages.values()], terms,
                                                 placed)
    return counts


def print_toc(toc: dict) -> dict:
    """The printed edition's toc: its root is the title page, the book's root the first page
    of the front matter, in a part of its own (so that its chapter is never numbered)."""
    toc = json.loads(json.dumps(toc))
    root = toc.pop("root")
    parts = toc.get("parts")
    if parts is None:
        parts = [{"numbered": True, "chapters": toc.pop("chapters", [])}]
    toc["parts"] = [{"caption": PREFACE_TITLE, "chapters": [{"file": root}]}, *parts]
    return {"format": toc.pop("format", "jb-book"), "root": PRINT_ROOT, **toc}


def pdf_text_root(toc: dict) -> str:
    """The book's root page (``book/intro``), without its suffix."""
    return str(toc["root"]).rsplit(".", 1)[0] if str(toc["root"]).endswith(
        (".md", ".ipynb")) else str(toc["root"])


def copy_sources(src: Path) -> list[Path]:
    """The book into ``src``, transformed for paper; returns the notebooks written."""
    shutil.rmtree(src, ignore_errors=True)
    src.mkdir(parents=True)
    shutil.copytree(ROOT / "book", src / "book")
    book_toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    toc = print_toc(book_toc)
    (src / "_toc.yml").write_text(yaml.safe_dump(toc, sort_keys=False), encoding="utf-8")
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    (src / f"{PRINT_ROOT}.md").write_text(f"# {config['title']}\n", encoding="utf-8")
    pages = _load_pages(src)
    arrange(pages, book_structure(src / "_toc.yml"), pdf_text_root(book_toc))
    terms_file = ROOT / INDEX_TERMS
    terms = pdf_text.load_terms(yaml.safe_load(terms_file.read_text(encoding="utf-8"))
                                if terms_file.is_file() else [])
    index_entries(pages, terms)
    written = []
    for name, page in pages.items():
        dest = src / (name + page.path.suffix)
        page.write(dest)
        if page.nb is not None:
            written.append(dest)
    copy_includes(src)
    config["exclude_patterns"] = [*config.get("exclude_patterns", []), "_build"]
    sphinx = config.setdefault("sphinx", {})
    # The web edition's extensions (offline assets, redirects, numbering) are not needed:
    # LaTeX numbers the printed book itself; tools/pdf_latex.py prints the references.
    sphinx["local_extensions"] = {"tools.pdf_latex": str(ROOT)}
    sphinx_config = sphinx.setdefault("config", {})
    sphinx_config["latex_elements"] = {
        "papersize": "a4paper",
        "pointsize": "11pt",
        # Unicode everywhere (Greek, arrows, the checks' marks): FreeSerif text, DejaVu code.
        "fontpkg": "\\setmainfont{FreeSerif}\n\\setsansfont{FreeSans}\n"
                   "\\setmonofont{DejaVu Sans Mono}[Scale=0.85]\n",
        "figure_align": "H",
        # The PDF's outline numbers its chapters as the book does ("6 Odometry: ...").
        "passoptionstopackages": "\\PassOptionsToPackage{bookmarksnumbered}{hyperref}\n",
        # A citation in a section title (the API pages' docstrings): a robust \\hyperlink
        # survives titlesec's moving arguments.
        "preamble": PREAMBLE,
    }
    sphinx_config["latex_show_urls"] = "footnote"
    sphinx_config["latex_domain_indices"] = False  # the library is appendix F, not an index
    config["latex"] = {"latex_engine": "xelatex", "use_jupyterbook_latex": False,
                       "latex_documents": {"targetname": "wheelkin.tex"}}
    (src / "_config.yml").write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")
    return written


def missing_tools() -> list[str]:
    return [tool for tool in NEEDED if shutil.which(tool) is None]


def pages(pdf: Path) -> int:
    info = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True, check=True)
    match = re.search(r"^Pages:\s+(\d+)", info.stdout, re.M)
    return int(match.group(1)) if match else 0


def build(out: Path, src: Path) -> dict:
    """Build the PDF into ``out``; return its path, page count and build seconds."""
    missing = missing_tools()
    if missing:
        raise SystemExit(f"pdf_edition: missing {', '.join(missing)}: run `make tex` "
                         "(Debian's TeX packages, as root)")
    start = time.perf_counter()
    notebooks = copy_sources(src)
    jb = Path(sys.executable).with_name("jupyter-book")
    log = src / "build.log"
    with log.open("w", encoding="utf-8") as f:
        done = subprocess.run([str(jb), "build", str(src), "--builder", "pdflatex"],
                              stdout=f, stderr=subprocess.STDOUT, check=False)
    built = src / "_build" / "latex" / "wheelkin.pdf"
    if done.returncode != 0 or not built.is_file():
        tail = log.read_text(encoding="utf-8", errors="replace").splitlines()[-30:]
        raise SystemExit("pdf_edition: the LaTeX build failed (" + str(log) + "):\n"
                         + "\n".join(tail))
    out.mkdir(parents=True, exist_ok=True)
    target = out / "wheelkin.pdf"
    shutil.copy2(built, target)
    seconds = time.perf_counter() - start
    summary = {"pdf": str(target), "pages": pages(target), "seconds": round(seconds, 1),
               "notebooks": len(notebooks), "bytes": target.stat().st_size}
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    return summary


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "_build" / "pdf")
    parser.add_argument("--src", type=Path, default=ROOT / "_build" / "pdf_src")
    parser.add_argument("--sources-only", action="store_true",
                        help="write the transformed sources, do not run LaTeX")
    args = parser.parse_args(argv)
    if args.sources_only:
        written = copy_sources(args.src.resolve())
        print(f"pdf_edition: {len(written)} notebooks in {args.src}")
        return 0
    summary = build(args.out.resolve(), args.src.resolve())
    print(f"pdf_edition: {summary['pdf']}: {summary['pages']} pages, "
          f"{summary['bytes'] / 1e6:.1f} MB, built in {summary['seconds']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
