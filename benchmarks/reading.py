"""How the built book reads: one row per page of ``_toc.yml``, measured in Chromium.

For every page (``tools/book_pages.py``, nested ``sections:`` included), over a built site
(default ``_build/html``) served on 127.0.0.1:

- **height**: the page's height in CSS px at a 1280x900 window;
- **code**: visible code lines (lines of code cells whose input is not folded);
- **overflow**: visible code lines wider than their code box at a 1366x768 window (each line's
  width measured with the box's own font, against the box's inner width);
- **min fig px**: the smallest figure text on screen, in CSS px, estimated per image as
  ``font_pt x dpi / 72 x shown_width / natural_width``. The dpi is read from the PNG's
  ``pHYs`` chunk (matplotlib writes it); the smallest font size from the PNG's
  ``wheelkin:min_font_pt`` text chunk when the figure carries one (``wheelkin.style`` adds
  it). Without that chunk the smallest font is *assumed* to be matplotlib's default tick label
  size, 10 pt (an upper bound: a figure with a smaller explicit font is worse), and the value is
  marked ``~``. Animation frames are measured the same way (their first frame);
- **words**: words of prose in the page's main column (code, math and figures excluded);
- **figs / anims**: figure images in cell outputs and ``to_jshtml`` animations;
- **first visit**: bytes of every response of a first visit with an empty cache (the page and
  every asset it loads), from the browser's network events.

Run: ``.venv/bin/python -m benchmarks.reading [--site DIR] [--section reading]`` writes the
table as section ``reading`` of RESULTS.md (``--section reading-before`` for the first
edition's site). ``--no-write`` only prints it.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

from tools.book_pages import toc_files
from tools.book_site import CHROMIUM, CHROMIUM_ARGS, serve
from tools.png_text import image_bytes, text_px
from tools.results import cpu, markers, write_section

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


@dataclass
class Row:
    page: str
    height: int = 0
    code_lines: int = 0
    overflow_lines: int = 0
    min_text_px: float | None = None
    min_text_assumed: bool = False
    words: int = 0
    figures: int = 0
    animations: int = 0
    first_visit: int = 0
    requests: int = 0
    notes: list[str] = field(default_factory=list)


# --- the page ---------------------------------------------------------------------------------

_MEASURE = r"""
() => {
  const main = document.querySelector("#main-content article") ||
               document.querySelector("#main-content") || document.querySelector("main") ||
               document.body;
  // Folded content (a closed <details>: hide-input cells, dropdowns) is not on screen, though
  // Chromium still gives it client rects.
  const shown = el => el.getClientRects().length > 0 && !el.closest("details:not([open])") &&
                      getComputedStyle(el).visibility !== "hidden";
  const canvas = document.createElement("canvas").getContext("2d");
  let code = 0, overflow = 0;
  const overflowing = [];
  for (const pre of main.querySelectorAll(".cell_input pre, div.highlight-ipython3 pre")) {
    if (!shown(pre) || pre.closest(".cell_output")) continue;
    const lines = pre.textContent.replace(/\n$/, "").split("\n");
    const style = getComputedStyle(pre);
    canvas.font = `${style.fontWeight} ${style.fontSize} ${style.fontFamily}`;
    const inner = pre.clientWidth - parseFloat(style.paddingLeft) -
                  parseFloat(style.paddingRight);
    code += lines.length;
    for (const line of lines) {
      if (canvas.measureText(line.replace(/\t/g, "        ")).width > inner + 0.5) {
        overflow += 1;
        if (overflowing.length < 3) overflowing.push(line.slice(0, 60));
      }
    }
  }
  const images = [];
  for (const img of main.querySelectorAll(".cell_output img, div.animation img")) {
    if (!shown(img)) continue;
    images.push({src: img.currentSrc || img.src, natural: img.naturalWidth,
                 shown: img.getBoundingClientRect().width,
                 animation: !!img.closest("div.animation")});
  }
  const clone = main.cloneNode(true);
  for (const el of clone.querySelectorAll(
      "pre, script, style, .cell_input, mjx-container, .math, img, .animation, " +
      "nav, .headerlink, .toggle-details__summary")) el.remove();
  const words = (clone.textContent.match(/[A-Za-z0-9\u00C0-\u024F][\w'\u2019.-]*/g) || []).length;
  return {height: Math.max(document.documentElement.scrollHeight, document.body.scrollHeight),
          code, overflow, overflowing, images, words,
          figures: [...main.querySelectorAll(".cell_output img")].filter(
              img => !img.closest("div.animation")).length,
          animations: main.querySelectorAll("div.animation").length};
}
"""


def _settle(page) -> None:
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    try:  # a busy machine can keep a page's network from idling: then measure what loaded
        page.wait_for_load_state("networkidle", timeout=60_000)
    except PlaywrightTimeout:
        pass
    page.evaluate("""async () => {
        if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
          await MathJax.startup.promise; }
        if (document.fonts) await document.fonts.ready; }""")


def measure_page(browser, base: str, site: Path, name: str) -> Row:
    row = Row(name)
    url = f"{base}{name}.html"
    origin = urlsplit(base).netloc
    page_file = site / f"{name}.html"
    if not page_file.is_file():
        row.notes.append("not built")
        return row

    # First visit at 1280x900 with an empty cache: weight, height, words, figures.
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    page = context.new_page()
    sizes: dict[str, int] = {}

    def route(request_route):
        parts = urlsplit(request_route.request.url)
        if parts.scheme in ("data", "blob", "about") or parts.netloc == origin:
            request_route.continue_()
        else:
            row.notes.append(f"external request aborted: {request_route.request.url[:60]}")
            request_route.abort()

    def on_finished(request):
        if urlsplit(request.url).scheme in ("data", "blob", "about"):
            return
        try:
            response = request.response()
            body = response.body() if response is not None else b""
        except Exception:  # a response whose body is gone (redirect, aborted)
            body = b""
        sizes[request.url] = len(body)

    page.route("**/*", route)
    page.on("requestfinished", on_finished)
    page.goto(url, wait_until="load", timeout=60_000)
    _settle(page)
    at_1280 = page.evaluate(_MEASURE)
    context.close()
    row.first_visit = sum(sizes.values())
    row.requests = len(sizes)
    row.height = int(at_1280["height"])
    row.words = int(at_1280["words"])
    row.figures = int(at_1280["figures"])
    row.animations = int(at_1280["animations"])
    seen: set[tuple[str, int]] = set()
    for image in at_1280["images"]:
        key = (image["src"][:200], round(image["shown"]))
        if key in seen:
            continue
        seen.add(key)
        px, assumed = text_px(image_bytes(image["src"], page_file), image["shown"])
        if px is not None and (row.min_text_px is None or px < row.min_text_px):
            row.min_text_px, row.min_text_assumed = px, assumed
        elif px is not None and assumed and abs(px - row.min_text_px) < 1e-9:
            row.min_text_assumed = True

    # Code at a 1366x768 laptop window: visible lines and lines that need scrolling.
    context = browser.new_context(viewport={"width": 1366, "height": 768})
    page = context.new_page()
    page.route("**/*", lambda r: r.continue_() if urlsplit(r.request.url).netloc in
               (origin, "") else r.abort())
    page.goto(url, wait_until="load", timeout=60_000)
    _settle(page)
    at_1366 = page.evaluate(_MEASURE)
    context.close()
    row.code_lines = int(at_1366["code"])
    row.overflow_lines = int(at_1366["overflow"])
    return row


def measure(site: Path, pages: list[str] | None = None) -> list[Row]:
    from playwright.sync_api import sync_playwright

    pages = pages if pages is not None else toc_files()
    with serve(site) as base, sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True,
                                             args=CHROMIUM_ARGS)
        try:
            return [measure_page(browser, base, site, name) for name in pages]
        finally:
            browser.close()


def table(rows: list[Row]) -> str:
    head = ("| page | height (px) | visible code lines | overflowing at 1366 | "
            "min figure text (px) | words | figures | animations | first visit (MB) |\n"
            "|---|--:|--:|--:|--:|--:|--:|--:|--:|")
    lines = [head]
    for r in rows:
        if r.min_text_px is None:
            text = "–"
        else:
            text = ("~" if r.min_text_assumed else "") + f"{r.min_text_px:.1f}"
        note = f" ({'; '.join(sorted(set(r.notes)))[:80]})" if r.notes else ""
        lines.append(f"| {r.page}{note} | {r.height:,} | {r.code_lines:,} | "
                     f"{r.overflow_lines:,} | {text} | {r.words:,} | {r.figures} | "
                     f"{r.animations} | {r.first_visit / 1e6:.2f} |")
    total_code = sum(r.code_lines for r in rows)
    total_over = sum(r.overflow_lines for r in rows)
    lines.append(f"| **all {len(rows)} pages** | max {max(r.height for r in rows):,} | "
                 f"{total_code:,} | {total_over:,} | min "
                 f"{min((r.min_text_px for r in rows if r.min_text_px), default=0):.1f} | "
                 f"{sum(r.words for r in rows):,} | {sum(r.figures for r in rows)} | "
                 f"{sum(r.animations for r in rows)} | max "
                 f"{max(r.first_visit for r in rows) / 1e6:.2f} |")
    return "\n".join(lines)


def section(name: str, site: Path, rows: list[Row], title: str) -> str:
    begin, end = markers(name)
    try:
        shown_site = site.resolve().relative_to(ROOT)
    except ValueError:
        shown_site = site
    return f"""{begin}
## {title}

`benchmarks/reading.py` over `{shown_site}`, headless Chromium ({CHROMIUM}); machine: {cpu()}.
Height, words, figures and first-visit weight at a 1280x900 window (first visit: every
response of an empty-cache load, page and assets); code lines at a 1366x768 window (visible:
not hidden; overflowing: wider than their code box). Figure text on screen =
font pt x dpi / 72 x shown width / PNG width, dpi from the PNG's pHYs chunk; `~` marks
pages whose smallest figure font is not recorded in the PNG and is assumed to be matplotlib's
default tick label size, 10 pt (an upper bound: explicit smaller fonts are not seen).

{table(rows)}
{end}"""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--site", type=Path, default=ROOT / "_build" / "html")
    parser.add_argument("--section", default="reading")
    parser.add_argument("--title", default=None)
    parser.add_argument("--toc", type=Path, default=None,
                        help="the _toc.yml whose pages are measured (default: the tree's)")
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    if not (args.site / "index.html").is_file():
        parser.error(f"no built site in {args.site} (run `make book`)")
    pages = toc_files(args.toc) if args.toc else toc_files()
    rows = measure(args.site, pages)
    title = args.title or ("Reading, first edition (before)" if args.section == "reading-before"
                           else "Reading the built book")
    text = section(args.section, args.site, rows, title)
    print(text)
    if not args.no_write:
        write_section(args.section, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
