"""Fixtures for the browser tests: the built book served on 127.0.0.1, and Debian's chromium.

Each page of ``_toc.yml`` is loaded once (:func:`visit`), with every request that leaves
127.0.0.1 aborted and recorded; the tests then check what was recorded. Screenshots of every
page go to ``_build/screenshots/`` for a human to look at.
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from tools.book_site import (
    ALLOWED_CONSOLE_ERRORS,
    CHROMIUM,
    CHROMIUM_ARGS,
    IN_CI,
    SCREENSHOTS,
    SITE,
    serve,
)


@dataclass
class PageReport:
    """What loading one page showed."""

    page: str
    url: str
    console_errors: list[str] = field(default_factory=list)
    external_requests: list[str] = field(default_factory=list)
    failed_requests: list[str] = field(default_factory=list)
    math: dict = field(default_factory=dict)
    images_without_alt: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    animations: list[dict] = field(default_factory=list)
    screenshot: Path | None = None
    #: bytes of every response of the first (empty-cache) visit, by URL
    first_visit: dict[str, int] = field(default_factory=dict)
    #: the page's height in CSS px at a 1280x900 window
    height: int = 0
    #: figure and animation images: src, natural (PNG) width and shown width, in CSS px
    images: list[dict] = field(default_factory=list)
    #: visible code lines wider than their code box at a 1366x768 window
    overflowing_code: list[str] = field(default_factory=list)


@pytest.fixture(scope="session")
def site_url():
    """The built book, served from _build/html on a free port of 127.0.0.1."""
    if not (SITE / "index.html").is_file():
        pytest.fail("no built book in _build/html: run `make book` first")
    with serve(SITE) as url:
        yield url


@pytest.fixture(scope="session")
def browser():
    """Debian's headless chromium, driven by playwright (never a downloaded browser)."""
    if not CHROMIUM.exists():
        message = (f"{CHROMIUM} not found: install Debian's chromium "
                   "(`sudo apt-get install chromium`) to run the browser tests")
        if IN_CI:
            pytest.fail(message)
        pytest.skip(message)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        instance = playwright.chromium.launch(executable_path=str(CHROMIUM), headless=True,
                                              args=CHROMIUM_ARGS)
        try:
            yield instance
        finally:
            instance.close()


@pytest.fixture(scope="session")
def screenshots_dir():
    shutil.rmtree(SCREENSHOTS, ignore_errors=True)
    SCREENSHOTS.mkdir(parents=True)
    return SCREENSHOTS


def page_url(site_url: str, page: str) -> str:
    return f"{site_url}{page}.html"


# JavaScript run in the page once MathJax has finished.
_MATH_STATE = r"""
() => {
  const main = document.querySelector("#main-content") || document.querySelector("main")
               || document.body;
  const untypeset = [];
  for (const el of main.querySelectorAll(".math")) {
    if (!el.querySelector("mjx-container")) untypeset.push(el.textContent.trim().slice(0, 80));
  }
  const errors = [...main.querySelectorAll("mjx-merror")].map(
      e => (e.getAttribute("data-mjx-error") || e.textContent).slice(0, 120));
  const skip = "pre, code, script, style, textarea, mjx-container, .highlight";
  const walker = document.createTreeWalker(main, NodeFilter.SHOW_TEXT, {
    acceptNode(node) {
      return node.parentElement && node.parentElement.closest(skip)
          ? NodeFilter.FILTER_REJECT : NodeFilter.FILTER_ACCEPT;
    }});
  const rawTex = /\$\$|\\\[|\\\]|\\\(|\\begin\{|\$[^$\n]*\\[A-Za-z]+/;
  const raw = [];
  while (walker.nextNode()) {
    const text = walker.currentNode.nodeValue;
    if (rawTex.test(text)) raw.push(text.trim().slice(0, 120));
  }
  // A display formula written inside a paragraph ($$ not on lines of its own) comes out as
  // inline math between stray dollar signs: "$<formula>$".
  for (const box of main.querySelectorAll("mjx-container")) {
    const before = box.parentElement.closest(".math") || box;
    const prev = before.previousSibling, next = before.nextSibling;
    if ((prev && prev.nodeType === 3 && prev.nodeValue.endsWith("$")) ||
        (next && next.nodeType === 3 && next.nodeValue.startsWith("$"))) {
      raw.push("stray $ around: " + (box.getAttribute("aria-label") ||
               before.textContent).slice(0, 80));
    }
  }
  return {count: main.querySelectorAll("mjx-container").length,
          untypeset, errors, raw};
}
"""

_IMAGES_WITHOUT_ALT = r"""
() => [...document.images].filter(img => {
  const alt = (img.getAttribute("alt") || "").trim();
  const src = img.getAttribute("src") || "";
  const file = src.split("/").pop();
  // Sphinx writes the file name as alt when none was given: that is no description either.
  return !alt || alt === src || alt === file || /\.(png|jpe?g|gif|svg|webp)$/i.test(alt);
}).map(img => (img.id ? "#" + img.id + " " : "") + (img.getAttribute("src") || "").slice(0, 80))
"""


# Figure images of the page (cell outputs, animation players), at their shown size.
_IMAGES = r"""
() => [...document.querySelectorAll(".cell_output img, div.animation img")]
  .filter(img => img.getClientRects().length > 0 && !img.closest("details:not([open])"))
  .map(img => ({src: img.currentSrc || img.src, natural: img.naturalWidth,
                shown: img.getBoundingClientRect().width,
                animation: !!img.closest("div.animation"),
                id: img.id || (img.getAttribute("alt") || "").slice(0, 60)}))
"""

# Visible code lines (inputs not folded) wider than their box: measured with the box's font.
_OVERFLOWING_CODE = r"""
() => {
  const canvas = document.createElement("canvas").getContext("2d");
  const found = [];
  for (const pre of document.querySelectorAll(".cell_input pre, div.highlight pre")) {
    // Folded away: a closed <details> (Chromium still gives its content client rects).
    if (pre.getClientRects().length === 0 || pre.closest("details:not([open])")) continue;
    if (pre.closest(".cell_output")) continue;  // an output, not code
    const style = getComputedStyle(pre);
    // A block that wraps its lines (the library reference's examples) cannot scroll
    // sideways as long as nothing in it is wider than its box.
    if (style.whiteSpace === "pre-wrap" || style.whiteSpace === "break-spaces") {
      if (pre.scrollWidth > pre.clientWidth + 1) {
        found.push(`${pre.scrollWidth} px > ${pre.clientWidth} px: a wrapped block overflows`);
      }
      continue;
    }
    canvas.font = `${style.fontWeight} ${style.fontSize} ${style.fontFamily}`;
    const inner = pre.clientWidth - parseFloat(style.paddingLeft) -
                  parseFloat(style.paddingRight);
    for (const line of pre.textContent.replace(/\n$/, "").split("\n")) {
      const width = canvas.measureText(line.replace(/\t/g, "        ")).width;
      if (width > inner + 0.5) {
        found.push(`${Math.round(width)} px > ${Math.round(inner)} px: ${line.slice(0, 90)}`);
      }
    }
  }
  return found;
}
"""


def _play_animations(page) -> list[dict]:
    """Press Play on every to_jshtml player; report whether its frame changed."""
    results = []
    players = page.locator("div.animation")
    for index in range(players.count()):
        player = players.nth(index)
        image = player.locator("img").first
        name = image.get_attribute("id") or f"animation {index}"
        handle = image.element_handle()
        page.evaluate("img => { img.dataset.before = img.src; }", handle)
        try:
            player.locator("button[title='Play']").click(timeout=5_000)
            page.wait_for_function("img => img.src !== img.dataset.before", arg=handle,
                                   timeout=5_000)
            changed, error = True, ""
        except Exception as exc:
            changed, error = False, f"{type(exc).__name__}: {str(exc).splitlines()[0]}"
        finally:
            pause = player.locator("button[title='Pause']")
            if pause.count():
                pause.click(timeout=5_000)
        results.append({"name": name, "changed": changed, "error": error})
    return results


@pytest.fixture(scope="session")
def visit(browser, site_url, screenshots_dir):
    """visit(page) -> PageReport: load a page once (cached), with the network locked down."""
    cache: dict[str, PageReport] = {}
    origin = urlsplit(site_url).netloc

    def load(page_name: str) -> PageReport:
        if page_name in cache:
            return cache[page_name]
        report = PageReport(page_name, page_url(site_url, page_name))
        context = browser.new_context(viewport={"width": 1280, "height": 900})
        page = context.new_page()

        def route(route_request):
            url = route_request.request.url
            parts = urlsplit(url)
            if parts.scheme in ("data", "blob", "about") or parts.netloc == origin:
                route_request.continue_()
            else:
                report.external_requests.append(url)
                route_request.abort()

        def on_console(message):
            if message.type != "error":
                return
            text = message.text
            if any(known in text for known, _why in ALLOWED_CONSOLE_ERRORS):
                return
            where = message.location.get("url", "") if message.location else ""
            report.console_errors.append(f"{text} ({where})" if where else text)

        def on_response(response):
            if response.status >= 400 and urlsplit(response.url).netloc == origin:
                report.failed_requests.append(f"{response.status} {response.url}")

        def on_request_failed(request):
            if urlsplit(request.url).netloc == origin:
                report.failed_requests.append(f"{request.failure} {request.url}")

        def on_finished(request):
            if urlsplit(request.url).scheme in ("data", "blob", "about"):
                return
            try:
                response = request.response()
                size = len(response.body()) if response is not None else 0
            except Exception:  # a body the browser no longer holds (redirects)
                size = 0
            report.first_visit[request.url] = size

        page.route("**/*", route)
        page.on("console", on_console)
        page.on("pageerror", lambda exc: report.console_errors.append(f"page error: {exc}"))
        page.on("response", on_response)
        page.on("requestfailed", on_request_failed)
        page.on("requestfinished", on_finished)
        try:
            page.goto(report.url, wait_until="load", timeout=60_000)
            page.wait_for_load_state("networkidle", timeout=30_000)
            page.evaluate("""async () => {
                if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
                  await MathJax.startup.promise;
                }}""")
            report.math = page.evaluate(_MATH_STATE)
            report.images_without_alt = page.evaluate(_IMAGES_WITHOUT_ALT)
            report.links = page.evaluate(
                "() => [...document.querySelectorAll('a[href]')].map(a => a.href)")
            report.height = page.evaluate(
                "() => Math.max(document.documentElement.scrollHeight, "
                "document.body.scrollHeight)")
            report.images = page.evaluate(_IMAGES)
            shot = screenshots_dir / (page_name.replace("/", "__") + ".png")
            page.screenshot(path=str(shot), full_page=True)
            report.screenshot = shot
            report.animations = _play_animations(page)
            page.set_viewport_size({"width": 1366, "height": 768})  # a laptop screen
            page.wait_for_timeout(200)
            report.overflowing_code = page.evaluate(_OVERFLOWING_CODE)
        finally:
            context.close()
        cache[page_name] = report
        return report

    return load


@pytest.fixture(scope="session")
def fetch(site_url):
    """fetch(url) -> (status, ids in the page): same-site GET, cached."""
    import urllib.error
    import urllib.request
    from html.parser import HTMLParser

    class Ids(HTMLParser):
        def __init__(self):
            super().__init__()
            self.ids: set[str] = set()

        def handle_starttag(self, tag, attrs):
            for key, value in attrs:
                if key == "id" or (key == "name" and tag == "a"):
                    self.ids.add(value or "")

    cache: dict[str, tuple[int, set[str]]] = {}

    def get(url: str) -> tuple[int, set[str]]:
        if url not in cache:
            try:
                with urllib.request.urlopen(url, timeout=30) as response:
                    status, body = response.status, response.read()
            except urllib.error.HTTPError as exc:
                status, body = exc.code, b""
            ids: set[str] = set()
            if url.endswith(".html") or url.endswith("/"):
                parser = Ids()
                parser.feed(body.decode("utf-8", errors="replace"))
                ids = parser.ids
            cache[url] = (status, ids)
        return cache[url]

    return get

