"""Page and notebook sizes: every page of the built book and every notebook file.

Budget (DESIGN.md): each HTML page and each notebook file <= 3 MB (MB = 10^6 bytes here).

Run it after ``make book``: it reads the built site in ``_build/html`` (if that is missing it
says so, with the hint, and exits with status 1). For every page in ``_toc.yml`` (in reading
order, from ``tools/book_pages.py``):

* *HTML*: the page's file, which holds everything embedded in it (the animations' frames and
  any other ``data:`` URI, counted separately for information);
* *images and media*: the local files the page itself shows (``img``, ``picture``/``source``,
  ``video``, ``audio``, ``track``, ``iframe``, ``embed``, ``object``), each counted once;
* the page's weight, HTML + images and media, is what the budget is checked against;
* *shared*: the site's scripts and stylesheets the page loads (``script src``, ``link`` with
  rel stylesheet, preload, modulepreload or icon, and what those stylesheets import or
  ``url()``, of a ``@font-face`` only its first source), the same for every page and cached
  by the browser after the first one. They are reported beside the page weight (and as a
  first-visit total), not checked against the page budget. Files that MathJax loads on
  demand (fonts, TeX extensions) are not visible in the HTML and are not counted.

A page of ``_toc.yml`` missing from the build, or a local file that a page references but
that is not in the build, makes the measurement void: it is listed, and the exit status is 1.
Every notebook's (``notebooks/**/*.ipynb``) size is checked against the same budget. A budget
not met is a verdict in the table (the exit status stays 0, as for the other benchmarks).

Usage: ``python -m benchmarks.sizes [--root DIR] [--no-write]``; ``--root`` measures another
checkout's build (its ``_toc.yml``, ``_build/html`` and ``notebooks/``), e.g. a scratch copy.
Writes the "Page and notebook sizes" section of benchmarks/RESULTS.md (between its markers,
other sections kept).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import os
import platform
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

from tools.results import RESULTS, markers, write_section

ROOT = Path(__file__).resolve().parents[1]

BEGIN, END = markers("sizes")

BUDGET = 3_000_000  # bytes
MB = 1e6

#: Tags and attributes whose local files are the page's own content (images and media).
CONTENT = {"img": ("src", "srcset"), "source": ("src", "srcset"), "video": ("src", "poster"),
           "audio": ("src",), "track": ("src",), "iframe": ("src",), "embed": ("src",),
           "object": ("data",), "input": ("src",)}
#: ``link`` relations that make the browser fetch the file.
FETCHED_LINKS = {"stylesheet", "preload", "modulepreload", "icon", "shortcut"}
DATA_URI = re.compile(rb"data:[\w.+/-]+(?:;[\w.+=-]+)*;base64,[A-Za-z0-9+/=]+")
CSS_URL = re.compile(r"url\(\s*['\"]?([^'\")]+)['\"]?\s*\)")
CSS_IMPORT = re.compile(r"@import\s+(?:url\(\s*)?['\"]?([^'\")\s;]+)")
CSS_FONT_FACE = re.compile(r"@font-face\s*\{([^}]*)\}")
CSS_SRC = re.compile(r"(?:^|;)\s*src\s*:([^;]*)")


class _References(HTMLParser):
    """Collects (kind, url) for every file a page makes the browser fetch."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.found: list[tuple[str, str]] = []

    def handle_starttag(self, tag, attrs):
        values = {name: value for name, value in attrs if value is not None}
        if tag == "script" and values.get("src"):
            self.found.append(("shared", values["src"]))
        elif tag == "link" and values.get("href"):
            rels = set(values.get("rel", "").lower().split())
            if rels & FETCHED_LINKS:
                self.found.append(("shared", values["href"]))
        for attr in CONTENT.get(tag, ()):
            value = values.get(attr)
            if not value:
                continue
            if attr == "srcset":  # "a.png 1x, b.png 2x": count every candidate
                for candidate in value.split(","):
                    if candidate.strip():
                        self.found.append(("content", candidate.split()[0]))
            else:
                self.found.append(("content", value))

    handle_startendtag = handle_starttag


def local_file(url: str, base: Path, site: Path) -> Path | None:
    """The file a local URL points to (relative to ``base``, or to ``site`` if it starts with
    "/"); None for remote, data and fragment-only URLs."""
    parts = urlsplit(url.strip())
    if parts.scheme or parts.netloc or not parts.path:
        return None
    path = unquote(parts.path)
    return (site / path.lstrip("/")) if path.startswith("/") else (base / path)


def _resolve(path: Path) -> Path:
    return Path(os.path.normpath(path))


def stylesheet_files(sheet: Path, site: Path, found: dict[Path, int], missing: set[str]) -> None:
    """Add to ``found`` the local files a stylesheet makes the browser fetch: its ``@import`` s
    (followed), the first source of each ``@font-face`` ``src`` (the format a current browser
    takes; fonts in the other listed formats are not fetched), and every other ``url()``."""
    text = sheet.read_text(encoding="utf-8", errors="replace")
    urls = [("css", u) for u in CSS_IMPORT.findall(text)]
    for block in CSS_FONT_FACE.findall(text):
        for declaration in CSS_SRC.findall(block):
            first = CSS_URL.search(declaration)
            if first:
                urls.append(("file", first.group(1)))
    rest = CSS_IMPORT.sub("", CSS_FONT_FACE.sub("", text))
    urls += [("file", u) for u in CSS_URL.findall(rest)]
    for kind, url in urls:
        path = local_file(url, sheet.parent, site)
        if path is None:
            continue
        path = _resolve(path)
        if path in found:
            continue
        if not path.is_file():
            missing.add(os.path.relpath(path, site))
            continue
        found[path] = path.stat().st_size
        if kind == "css" or path.suffix == ".css":
            stylesheet_files(path, site, found, missing)


def page_sizes(html: Path, site: Path) -> dict:
    """Sizes of one built page (see the module docstring), and the files it lacks."""
    raw = html.read_bytes()
    parser = _References()
    parser.feed(raw.decode("utf-8", errors="replace"))
    content: dict[Path, int] = {}
    shared: dict[Path, int] = {}
    missing: set[str] = set()
    for kind, url in parser.found:
        path = local_file(url, html.parent, site)
        if path is None:
            continue
        path = _resolve(path)
        if not path.is_file():
            missing.add(os.path.relpath(path, site))
            continue
        (content if kind == "content" else shared)[path] = path.stat().st_size
    for sheet in [p for p in shared if p.suffix == ".css"]:
        stylesheet_files(sheet, site, shared, missing)
    embedded = [m.end() - m.start() for m in DATA_URI.finditer(raw)]
    return {
        "html": len(raw),
        "embedded": sum(embedded),
        "embedded_count": len(embedded),
        "content": sum(content.values()),
        "content_count": len(content),
        "shared": sum(shared.values()),
        "shared_files": shared,
        "missing": sorted(missing),
    }


def _book_pages(root: Path):
    """``tools/book_pages.py`` of this repository (the list of pages, from a ``_toc.yml``)."""
    spec = importlib.util.spec_from_file_location("book_pages", ROOT / "tools" / "book_pages.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _git(root: Path, *args: str) -> str | None:
    try:
        done = subprocess.run(["git", *args], cwd=root, capture_output=True, text=True,
                              check=False)
    except OSError:
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def measure(root: Path) -> dict:
    site = root / "_build" / "html"
    pages = []
    for page in _book_pages(root).toc_files(root / "_toc.yml"):
        html = site / f"{page}.html"
        if not html.is_file():
            pages.append({"page": page, "absent": True})
            continue
        sizes = page_sizes(html, site)
        sources = [root / f"{page}{suffix}" for suffix in (".ipynb", ".md")]
        newer = [s for s in sources if s.is_file() and s.stat().st_mtime > html.stat().st_mtime]
        pages.append({"page": page, "absent": False, "stale": bool(newer), **sizes})
    notebooks = [{"name": p.relative_to(root / "notebooks").as_posix(), "size": p.stat().st_size}
                 for p in sorted((root / "notebooks").glob("**/*.ipynb"))
                 if ".ipynb_checkpoints" not in p.parts]
    commit = _git(root, "rev-parse", "--short", "HEAD")
    dirty = _git(root, "status", "--porcelain", "--", "notebooks", "book", "_toc.yml")
    return {"root": root, "site": site, "pages": pages, "notebooks": notebooks,
            "commit": commit, "dirty": bool(dirty)}


def _mb(size: float) -> str:
    return f"{size / MB:.2f}"


def _verdict(size: int) -> str:
    return "met" if size <= BUDGET else "NOT met"


def report(result: dict) -> str:
    if result["commit"]:
        where = f"commit {result['commit']}"
        if result["dirty"]:
            where += " with uncommitted changes to the book's sources"
    else:
        where = "a working tree outside git"
    try:
        import jupyter_book
        builder = f", jupyter-book {jupyter_book.__version__}"
    except ImportError:  # pragma: no cover
        builder = ""
    lines = [
        BEGIN,
        "## Page and notebook sizes",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} logical CPUs; Python "
        f"{platform.python_version()}{builder}. Date: {_dt.date.today().isoformat()}. "
        f"Measured: `_build/html` as `make book` built it from {where}, and the notebook "
        "files. "
        "Produced by `python -m benchmarks.sizes`. MB = 10^6 bytes.",
        "",
        "A page's weight is its HTML file (which embeds the animations' frames and every other "
        "`data:` URI) plus the images and media files it shows; the budget is checked against "
        "it. The site's shared scripts and stylesheets (the same for every page, cached after "
        "the first) are given beside it, with the first-visit total.",
        "",
        "| page | HTML (MB) | of which embedded data (MB, URIs) | images and media (MB, "
        "files) | page weight (MB) | verdict (≤ 3 MB) | shared scripts and styles (MB) | "
        "first visit (MB) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    ok, broken = True, False
    shared_files: dict[Path, int] = {}
    missing: list[str] = []
    stale: list[str] = []
    for row in result["pages"]:
        if row["absent"]:
            ok, broken = False, True
            lines.append(f"| `{row['page']}` | not built | | | | NOT built | | |")
            continue
        weight = row["html"] + row["content"]
        ok = ok and weight <= BUDGET
        shared_files.update(row["shared_files"])
        missing += [f"`{row['page']}`: `{m}`" for m in row["missing"]]
        if row["stale"]:
            stale.append(f"`{row['page']}`")
        lines.append(
            f"| `{row['page']}` | {_mb(row['html'])} | {_mb(row['embedded'])}, "
            f"{row['embedded_count']} | {_mb(row['content'])}, {row['content_count']} | "
            f"{_mb(weight)} | {_verdict(weight)} | {_mb(row['shared'])} | "
            f"{_mb(weight + row['shared'])} |"
        )
    built = [r for r in result["pages"] if not r["absent"]]
    heaviest = max(built, key=lambda r: r["html"] + r["content"], default=None)
    if heaviest is not None:
        lines += ["", f"Heaviest page: `{heaviest['page']}`, "
                  f"{_mb(heaviest['html'] + heaviest['content'])} MB "
                  f"({'every page meets the budget' if ok else 'NOT every page meets the budget'}"
                  ")."]
    if shared_files:
        site = result["site"]
        top = sorted(shared_files.items(), key=lambda kv: -kv[1])[:4]
        lines += ["", f"Shared scripts and styles, all pages together: {len(shared_files)} files, "
                  f"{_mb(sum(shared_files.values()))} MB; the largest: "
                  + ", ".join(f"`{os.path.relpath(p, site)}` {_mb(s)}" for p, s in top) + "."]
    if missing:
        ok, broken = False, True
        lines += ["", "Referenced but not in the build (broken): " + "; ".join(missing) + "."]
    if stale:
        lines += ["", "Built before the latest change to the source of: " + ", ".join(stale)
                  + " (run `make book` again)."]
    lines += [
        "",
        "| notebook | file size (MB) | verdict (≤ 3 MB) |",
        "| --- | --- | --- |",
    ]
    for nb in result["notebooks"]:
        ok = ok and nb["size"] <= BUDGET
        lines.append(f"| `notebooks/{nb['name']}` | {_mb(nb['size'])} | {_verdict(nb['size'])} |")
    if result["notebooks"]:
        big = max(result["notebooks"], key=lambda nb: nb["size"])
        every = all(nb["size"] <= BUDGET for nb in result["notebooks"])
        verdict = "every notebook meets the budget" if every else \
            "NOT every notebook meets the budget"
        lines += ["", f"Largest notebook: `notebooks/{big['name']}`, {_mb(big['size'])} MB "
                  f"({verdict})."]
    lines += ["", "Budget (DESIGN.md): each HTML page and each notebook file ≤ 3 MB.", END]
    result["ok"], result["broken"] = ok, broken
    return "\n".join(lines) + "\n"


def write(section: str) -> None:
    write_section("sizes", section, RESULTS)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", type=Path, default=ROOT,
                        help="the checkout whose build and notebooks to measure (default: this)")
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    site = root / "_build" / "html"
    if not site.is_dir():
        print(f"sizes: no built book in {site}: run `make book` first (in {root}), "
              "then run this again", file=sys.stderr)
        return 1
    result = measure(root)
    section = report(result)
    print(section)
    if not args.no_write:
        write(section)
    if result["broken"]:
        print("sizes: a page of _toc.yml is not built, or references a file not in the build: "
              "run `make book` again", file=sys.stderr)
        return 1
    if not result["ok"]:
        print("sizes: a page or a notebook is over the 3 MB budget (see the table)",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
