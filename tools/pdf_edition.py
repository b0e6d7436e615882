#!/usr/bin/env python
"""The printed edition: a PDF of the whole book, built with Jupyter Book's LaTeX builder.

Usage::

    python -m tools.pdf_edition [--out _build/pdf]     # or: make pdf  (make tex installs TeX)

The book is copied into ``_build/pdf_src/`` and its notebooks transformed for paper:

- every animation (matplotlib's ``to_jshtml`` player, frames embedded as base64 PNG) becomes
  three of its frames (first, middle, last), each printed at the animation's own size (the
  same size and legibility as the static figures), followed by its caption;
- live panels (cells whose output is a widget, or a ``remove-output`` cell that makes a panel)
  and their "Live panel" margin notes are left out;
- folded code (``hide-input``) is left out, its output kept;
- solutions are left out (a page cannot fold them, and the printed book is the one a class
  gets; instructors have them in the notebooks), with the sentences that point at them;
  exercise stubs are printed without output.

Then ``jupyter-book build --builder pdflatex`` runs XeLaTeX (Unicode: the book's Greek,
arrows and check marks) with the FreeSerif/FreeSans and DejaVu Sans Mono fonts; the PDF is
copied to ``<out>/wheelkin.pdf``. The TeX packages: ``make tex`` (Debian: texlive-xetex,
texlive-latex-extra, texlive-fonts-recommended, latexmk, xindy, fonts-freefont-otf,
fonts-dejavu-core, poppler-utils).
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

from tools.book_pages import toc_files
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
    note = f"*Animation, frames {shown} of {len(frames)}.* {text}".strip()
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
    changes.update(animations=0, panels=0, folded=0)
    cells = []
    for cell in nb.cells:
        if is_live_panel(cell):
            changes["panels"] += 1
            continue
        tags = _tags(cell)
        if cell.cell_type == "markdown":
            new = _MARGIN_PANEL.sub("", cell.source)
            if new != cell.source:
                cell.source = new
                if not new.strip():
                    continue
            cells.append(cell)
            continue
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


def copy_sources(src: Path) -> list[Path]:
    """The book into ``src``, its notebooks transformed; returns the notebooks written."""
    shutil.rmtree(src, ignore_errors=True)
    src.mkdir(parents=True)
    shutil.copytree(ROOT / "book", src / "book")
    shutil.copy2(ROOT / "_toc.yml", src / "_toc.yml")
    written = []
    for page in toc_files(ROOT / "_toc.yml"):
        for suffix in (".md", ".rst", ".ipynb"):
            path = ROOT / (page + suffix)
            if not path.is_file() or (src / (page + suffix)).exists():
                continue
            (src / page).parent.mkdir(parents=True, exist_ok=True)
            if suffix == ".ipynb":
                nb, _ = print_notebook(nbformat.read(path, as_version=4))
                nbformat.write(nb, src / (page + suffix))
                written.append(src / (page + suffix))
            else:
                text = path.read_text(encoding="utf-8")
                (src / (page + suffix)).write_text(
                    remove_solution_sentences(_MARGIN_PANEL.sub("", text)), encoding="utf-8")
    copy_includes(src)
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    config["exclude_patterns"] = [*config.get("exclude_patterns", []), "_build"]
    sphinx = config.setdefault("sphinx", {})
    sphinx.pop("local_extensions", None)  # the web edition's (offline assets, redirects)
    sphinx_config = sphinx.setdefault("config", {})
    sphinx_config["latex_elements"] = {
        "papersize": "a4paper",
        "pointsize": "11pt",
        # Unicode everywhere (Greek, arrows, the checks' marks): FreeSerif text, DejaVu code.
        "fontpkg": "\\setmainfont{FreeSerif}\n\\setsansfont{FreeSans}\n"
                   "\\setmonofont{DejaVu Sans Mono}[Scale=0.85]\n",
        "figure_align": "H",
        # A citation in a section title (the API pages' docstrings): a robust \\hyperlink
        # survives titlesec's moving arguments.
        "preamble": "\\let\\wheelkinhyperlink\\hyperlink\n"
                    "\\DeclareRobustCommand{\\hyperlink}[2]{\\wheelkinhyperlink{#1}{#2}}\n",
    }
    sphinx_config["latex_show_urls"] = "footnote"
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
