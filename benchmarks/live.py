"""Live pages and precomputed views: what a reader waits for and what a page costs.

Live pages (``tools/serve_live.py`` on free ports, Debian's headless chromium, every request
kept on 127.0.0.1), for every page that shows a live panel:

- **kernel ready**: from the click on "Make this page live" to a kernel started and connected
  (``window.wheelkinLive.timings.kernelReadyMs``), and **page ready**: until the set-up cell
  and the panel cells have run and every panel shows its figure; medians per chapter;
- **slider to image**: for every slider and drop-down of every panel, ``--moves`` moves
  (arrow keys on a slider, as a reader's keyboard; the next option of a drop-down), each
  timed in the page from the key or change event to the panel's image element getting its
  new picture (a MutationObserver on its ``src``): the kernel's
  redraw, the widget messages both ways and the browser's update; median and p95 per panel.
  Budget (issue #25): 150 ms median on this machine.

Precomputed views (the built site ``_build/html``), per page with panels:

- **extra bytes**: all the images of its views, the view's HTML and the script and style
  (total), and what a first visit loads of it (the image at the defaults of each view, the
  HTML, the script and the style);
- **build time**: drawing every image of every panel from an empty cache, two panels at a time
  (what ``make book`` adds to a fresh clone; later builds reuse the cache).

Usage: ``python -m benchmarks.live [--moves 6] [--only PAGE ...] [--no-write]`` after
``make book``; writes the "live" section of benchmarks/RESULTS.md.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from tools.book_pages import chapter_of
from tools.book_site import CHROMIUM, CHROMIUM_ARGS, SITE
from tools.live_site import PANEL_CONTROLS, PANEL_PAGES, lock_down, make_live, serve_live
from tools.results import cpu, markers, write_section

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

BUDGET_MS = 150.0
BEGIN, END = markers("live")

#: Arm a timer on panel p's image: from the next key or click event to the image's new src.
_ARM = r"""
([p]) => {
  const cell = document.querySelectorAll('.wk-panel-cell')[p];
  const img = cell.querySelector('.thebe-output img.widget-image');
  const before = img.src;
  let from = null;
  const mark = () => { if (from === null) from = performance.now(); };
  document.addEventListener('keydown', mark, {capture: true, once: true});
  document.addEventListener('pointerdown', mark, {capture: true, once: true});
  document.addEventListener('change', mark, {capture: true, once: true});
  window.__wkChange = new Promise((resolve, reject) => {
    const observer = new MutationObserver(() => {
      if (img.src !== before) { observer.disconnect(); resolve(performance.now() - from); }
    });
    observer.observe(img, {attributes: true, attributeFilter: ['src']});
    setTimeout(() => { observer.disconnect(); reject(new Error('no new image')); }, 30000);
  });
}
"""
_CONTROLS = ".noUi-handle, .widget-dropdown select, .widget-checkbox input"


def _move(page, panel: int, control: dict, forward: bool) -> float:
    out = page.locator(".wk-panel-cell").nth(panel).locator(".thebe-output").first
    target = out.locator(_CONTROLS).nth(control["index"])
    page.evaluate(_ARM, [panel])
    if control["kind"] == "slider":
        target.focus()
        target.press("ArrowRight" if forward else "ArrowLeft")
    elif control["kind"] == "select":
        count = target.locator("option").count()
        current = target.evaluate("s => s.selectedIndex")
        target.select_option(index=(current + 1) % count)
    else:
        target.click()
    return float(page.evaluate("() => window.__wkChange"))


def measure_live(pages: list[str], moves: int) -> tuple[list[dict], list[dict]]:
    """Kernel and page ready per page; slider-to-image times per panel."""
    from playwright.sync_api import sync_playwright

    page_rows, panel_rows = [], []
    with serve_live() as url, sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), headless=True,
                                             args=CHROMIUM_ARGS)
        try:
            for name in pages:
                context = browser.new_context(viewport={"width": 1366, "height": 900})
                external: list[str] = []
                lock_down(context, external)
                page = context.new_page()
                try:
                    page.goto(f"{url}{name}.html", wait_until="load", timeout=60_000)
                    timings = make_live(page)
                    page_rows.append({"page": name, "chapter": chapter_of(Path(name)),
                                      "kernel": timings["kernelReadyMs"],
                                      "ready": timings["pageReadyMs"]})
                    for panel in page.evaluate(PANEL_CONTROLS):
                        times, missed = [], []
                        for control in panel["controls"]:
                            if control["kind"] == "checkbox":
                                continue  # may leave the figure as it is: nothing to time
                            # Away from the end it starts at, then back: every move redraws.
                            forward = not control["atMax"]
                            for k in range(moves):
                                if control["kind"] == "slider" and k == moves // 2:
                                    forward = not forward
                                try:
                                    times.append(_move(page, panel["panel"], control,
                                                       forward))
                                except Exception as exc:
                                    missed.append(f"{control['label']} move {k}: "
                                                  f"{str(exc).splitlines()[0]}")
                        if missed:
                            print(f"{name}: moves without a new image in 30 s: {missed}",
                                  file=sys.stderr)
                        panel_rows.append({"page": name,
                                           "panel": PANEL_PAGES[name][panel["panel"]],
                                           "times": times, "missed": len(missed)})
                finally:
                    context.close()
                if external:
                    raise RuntimeError(f"{name}: requests outside 127.0.0.1: {external}")
        finally:
            browser.close()
    return page_rows, panel_rows


def precomputed_bytes(pages: list[str]) -> list[dict]:
    """Extra bytes per page: all images, and a first visit's share."""
    static = SITE / "_static"
    assets = sum((static / f).stat().st_size for f in ("precomputed.js", "precomputed.css"))
    rows = []
    for name in pages:
        html = (SITE / f"{name}.html").read_text(encoding="utf-8")
        views = re.findall(r'<div class="wk-precomputed".*?<p class="wk-pc-note">.*?</p></div>',
                           html, re.S)
        view_html = sum(len(v.encode()) for v in views)
        total = first = 0
        for panel, src in zip(PANEL_PAGES[name],
                              re.findall(r'<img class="wk-pc-image" src="([^"]+)"', html),
                              strict=True):
            folder = static / "precomputed" / panel
            total += sum(p.stat().st_size for p in folder.glob("*.png"))
            first += (SITE / name).parent.joinpath(src).resolve().stat().st_size
        rows.append({"page": name, "panels": len(PANEL_PAGES[name]),
                     "total": total + view_html + assets, "first": first + view_html + assets})
    return rows


def build_time() -> tuple[float, int, int]:
    """Seconds to draw every panel's images from an empty cache (two at a time); count, bytes."""
    from live_pages import ensure_rendered

    from wheelkin.widgets.precomputed import GRIDS

    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        ensure_rendered(sorted(GRIDS), cache=Path(cache))
        seconds = time.perf_counter() - start
        files = list(Path(cache).rglob("*.png"))
        return seconds, len(files), sum(f.stat().st_size for f in files)


def _ms(values) -> str:
    return f"{statistics.median(values):.0f}"


def section(page_rows, panel_rows, byte_rows, build, moves) -> str:
    load = os.getloadavg()
    lines = [BEGIN, "## Live pages and precomputed panels", "",
             f"Machine: {cpu()}; Debian's chromium, headless. Date: {_dt.date.today()}. Load "
             f"average (1, 5, 15 min) at the end: {load[0]:.1f}, {load[1]:.1f}, {load[2]:.1f}. "
             "Produced by `python -m benchmarks.live` (method in its docstring).", "",
             "### Kernel ready after *Make this page live* (per chapter)", "",
             "| chapter | pages | kernel ready, median (s) | page ready, median (s) |",
             "| --- | --- | --- | --- |"]
    chapters: dict[str, list[dict]] = {}
    for row in page_rows:
        chapters.setdefault(row["chapter"], []).append(row)
    for chapter, rows in chapters.items():
        lines.append(f"| {chapter} | {len(rows)} | "
                     f"{statistics.median(r['kernel'] for r in rows) / 1000:.1f} | "
                     f"{statistics.median(r['ready'] for r in rows) / 1000:.1f} |")
    lines += ["", "*Kernel ready*: a kernel started and connected; *page ready*: the page's "
              "set-up cell and its panel cells have run and every panel shows its figure.", "",
              f"### Slider to image ({moves} moves of every control; budget {BUDGET_MS:.0f} ms "
              "median)", "",
              "| page | panel | moves timed | median (ms) | p95 (ms) | verdict |",
              "| --- | --- | --- | --- | --- | --- |"]
    worst = 0.0
    for row in panel_rows:
        median = statistics.median(row["times"])
        worst = max(worst, median)
        timed = f"{len(row['times'])}" + (f" ({row['missed']} without a new image in 30 s)"
                                           if row["missed"] else "")
        lines.append(f"| {row['page']} | {row['panel']} | {timed} | {median:.0f} "
                     f"| {np.percentile(row['times'], 95):.0f} | "
                     f"{'ok' if median <= BUDGET_MS else 'over'} |")
    if any(row["missed"] for row in panel_rows):
        lines += ["", "A move counted *without a new image* is not timed: the panel drew the "
                  "same figure again (a value past a limit the model holds), so the widget "
                  "had no new image to send."]
    lines += ["", f"Slowest median: {worst:.0f} ms "
              f"({'within' if worst <= BUDGET_MS else 'over'} the {BUDGET_MS:.0f} ms budget).",
              "", "### Precomputed views: bytes per page", "",
              "| page | panels | extra bytes, total (kB) | extra bytes, first visit (kB) |",
              "| --- | --- | --- | --- |"]
    for row in byte_rows:
        lines.append(f"| {row['page']} | {row['panels']} | {row['total'] / 1000:.0f} | "
                     f"{row['first'] / 1000:.0f} |")
    seconds, count, size = build
    lines += ["", "Total: the page's views' HTML, every image of its panels, "
              "`precomputed.js` and `precomputed.css`; first visit: the same less the images "
              "not at the defaults (loaded only when a control moves).", "",
              f"Build time: {count} images ({size / 1e6:.1f} MB) drawn from an empty cache in "
              f"{seconds:.0f} s, two panels at a time; a build with the cache up to date "
              "copies them (the cache is redrawn when the library, the grids or the plotting "
              "stack change).", END]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--moves", type=int, default=6)
    parser.add_argument("--only", nargs="*", default=None)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    pages = sorted(PANEL_PAGES) if not args.only else args.only
    page_rows, panel_rows = measure_live(pages, args.moves)
    byte_rows = precomputed_bytes(pages)
    build = build_time()
    text = section(page_rows, panel_rows, byte_rows, build, args.moves)
    print(text)
    if not args.no_write:
        write_section("live", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
