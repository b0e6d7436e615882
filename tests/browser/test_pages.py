"""Every page of the built book, in Debian's headless chromium, with no network but 127.0.0.1.

For each page listed in _toc.yml (nested sections included): it loads with no console error
and without one request leaving the site; MathJax typeset every formula; every image has alt
text; every internal link resolves (anchors included); every animation plays. And the reader's
rules (docs/DESIGN.md, "Budgets"): no visible code line scrolls sideways at 1366 px; no page is
taller than 20,000 px at 1280 px; every figure's text is at least 11 px on screen; a first
visit (the page and every asset it loads) costs at most 3 MB. Needs ``make book`` first
(``make test`` builds it); the screenshots land in _build/screenshots/.
"""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import unquote, urldefrag

import pytest

from tools.book_pages import chapter_of
from tools.book_site import NON_CHAPTER_NOTEBOOKS, PAGES, ROOT, SITE
from tools.png_text import image_bytes, text_px

MAX_PAGE_BYTES = 3_000_000
#: A reader's first visit of a page: the page and every script, style, font and image it loads.
MAX_FIRST_VISIT_BYTES = 3_000_000
MAX_HEIGHT_PX = 20_000
MIN_TEXT_PX = 11.0


def test_toc_lists_pages():
    assert PAGES, "_toc.yml lists no pages"
    assert len(PAGES) == len(set(PAGES)), f"_toc.yml lists a page twice: {PAGES}"


@pytest.mark.parametrize("page", PAGES)
def test_page_weight(page):
    """A page, with the images it shows, stays within the 3 MB budget."""
    html = SITE / f"{page}.html"
    assert html.is_file(), f"{page}.html was not built"
    text = html.read_text(encoding="utf-8")
    total = len(text.encode())
    for src in set(re.findall(r'<img[^>]+src="([^"]+)"', text)):
        if not src.startswith(("data:", "http:", "https:")):
            image = (html.parent / unquote(src.split("#")[0].split("?")[0])).resolve()
            total += image.stat().st_size if image.is_file() else 0
    assert total <= MAX_PAGE_BYTES, f"{page} weighs {total / 1e6:.2f} MB (budget 3 MB)"


@pytest.mark.parametrize("page", PAGES)
def test_loads_without_console_errors(visit, page):
    report = visit(page)
    errors, failed = report.console_errors, report.failed_requests
    assert not errors, f"{page}: console errors:\n" + "\n".join(errors)
    assert not failed, f"{page}: failed requests:\n" + "\n".join(failed)


@pytest.mark.parametrize("page", PAGES)
def test_makes_no_request_outside_the_site(visit, page):
    external = visit(page).external_requests
    assert not external, (
        f"{page} asked for {len(external)} resources outside the site "
        "(vendor them: package.json, tools/vendor_assets.py):\n"
        + "\n".join(sorted(set(external))))


@pytest.mark.parametrize("page", PAGES)
def test_math_is_typeset(visit, page):
    math = visit(page).math
    assert not math["untypeset"], f"{page}: formulas MathJax did not typeset: {math['untypeset']}"
    assert not math["errors"], f"{page}: MathJax errors: {math['errors']}"
    assert not math["raw"], f"{page}: raw TeX left in the text: {math['raw']}"


@pytest.mark.parametrize("page", PAGES)
def test_images_have_alt_text(visit, page):
    missing = visit(page).images_without_alt
    assert not missing, f"{page}: images without a real alt text: {missing}"


@pytest.mark.parametrize("page", PAGES)
def test_internal_links_resolve(visit, fetch, site_url, page):
    broken = []
    for href in sorted(set(visit(page).links)):
        if not href.startswith(site_url):
            continue  # another site: not followed (the book must not need it)
        target, fragment = urldefrag(href)
        status, ids = fetch(target)
        if status != 200:
            broken.append(f"{href}: HTTP {status}")
        elif fragment and target.endswith((".html", "/")) and unquote(fragment) not in ids:
            broken.append(f"{href}: no element with id {unquote(fragment)!r}")
    assert not broken, f"{page}: broken internal links:\n" + "\n".join(broken)


@pytest.mark.parametrize("page", PAGES)
def test_animations_play(visit, page):
    """Press Play on every animation of the page: its frame must change."""
    stuck = [f"{a['name']}: {a['error'] or 'frame did not change'}"
             for a in visit(page).animations if not a["changed"]]
    assert not stuck, f"{page}: animations that do not play:\n" + "\n".join(stuck)


@pytest.mark.parametrize("page", PAGES)
def test_screenshot_taken(visit, page):
    shot = visit(page).screenshot
    assert shot is not None and shot.stat().st_size > 0, f"{page}: no screenshot"
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{page}: screenshot is not a PNG"


def test_the_book_has_animations_once_chapters_exist(visit):
    """Every chapter shows a precomputed animation, so a book with chapters has some."""
    chapters = [p for p in PAGES if p.startswith("notebooks/")
                and chapter_of(Path(p)) not in NON_CHAPTER_NOTEBOOKS
                and (ROOT / f"{p}.ipynb").is_file()]
    if not chapters:
        pytest.skip("no chapter notebook is in _toc.yml yet")
    total = sum(len(visit(p).animations) for p in chapters)
    assert total > 0, f"no animation (div.animation) on any chapter page: {chapters}"


@pytest.mark.parametrize("page", PAGES)
def test_no_visible_code_line_scrolls_sideways(visit, page):
    """At a 1366x768 laptop window every visible (unfolded) code line fits its box."""
    lines = visit(page).overflowing_code
    assert not lines, (f"{page}: {len(lines)} visible code lines need horizontal scrolling at "
                       "1366 px (at most 79 characters, or fold the cell with hide-input):\n"
                       + "\n".join(lines[:15]))


@pytest.mark.parametrize("page", PAGES)
def test_page_is_not_too_tall(visit, page):
    height = visit(page).height
    assert 0 < height <= MAX_HEIGHT_PX, (
        f"{page} is {height:,} px tall at 1280 px (at most {MAX_HEIGHT_PX:,}): split it into "
        "section pages")


@pytest.mark.parametrize("page", PAGES)
def test_figure_text_is_legible(visit, page):
    """Every figure is shown at its natural width or more, or its text stays >= 11 px.

    The text's size on screen comes from the PNG: the smallest font the figure records
    (wheelkin.style writes it), its dpi and the scale the page shows it at. A figure that does
    not record its font is held to the first rule (shown at least at its natural width) or,
    scaled down, to matplotlib's default 10 pt tick labels.
    """
    html = SITE / f"{page}.html"
    problems, seen = [], set()
    for image in visit(page).images:
        key = (image["src"][:200], round(image["shown"]))
        if key in seen or not image["natural"]:
            continue
        seen.add(key)
        px, assumed = text_px(image_bytes(image["src"], html), image["shown"])
        name = image["id"] or image["src"][-60:]
        scaled_down = image["shown"] < image["natural"] - 1
        if px is None:
            if scaled_down:
                problems.append(f"{name}: shown at {image['shown']:.0f} px of its "
                                f"{image['natural']} px (not a PNG: text size unknown)")
        elif px < MIN_TEXT_PX and (scaled_down or not assumed):
            problems.append(f"{name}: text {px:.1f} px on screen (shown at {image['shown']:.0f}"
                            f" px of {image['natural']} px{', font assumed 10 pt' if assumed else ''})")
    assert not problems, f"{page}: figures whose text is under {MIN_TEXT_PX:g} px:\n" + "\n".join(
        problems)


@pytest.mark.parametrize("page", PAGES)
def test_first_visit_weight(visit, page):
    """A reader's first visit (empty cache): the page and every asset it loads, <= 3 MB."""
    loaded = visit(page).first_visit
    total = sum(loaded.values())
    biggest = sorted(loaded.items(), key=lambda item: -item[1])[:5]
    assert total <= MAX_FIRST_VISIT_BYTES, (
        f"{page}: the first visit loads {total / 1e6:.2f} MB in {len(loaded)} requests (budget "
        f"3 MB); the largest:\n" + "\n".join(f"{size / 1e6:.2f} MB {url}"
                                              for url, size in biggest))
