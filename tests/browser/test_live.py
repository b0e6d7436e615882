"""Live pages and precomputed panels, in Debian's headless chromium, with no network but 127.0.0.1.

Static site (``make book``; served as ``make serve`` serves it):
- every page that shows a live panel has its precomputed view, one per panel cell, with real
  labelled controls; moving each control (from the keyboard for a slider) swaps in another
  image, which loads; no request leaves the site;
- no page of the static site has a live control, or refers to the live scripts.

Live pages (``tools/serve_live.py``, what ``make serve-live`` runs, on free ports, stopped at
the end: the test checks that its Jupyter server is gone):
- on every page with a panel, "Make this page live" starts a kernel; every panel appears in
  the page; moving each slider and drop-down of each panel changes its image (a check box is
  toggled, and the panel stays up without an error: it may leave the figure as it was);
- a code cell edited in the page runs and shows its new output;
- no request, WebSocket included, leaves 127.0.0.1; no uncaught error in the page.

Needs ``make book`` first, and for the live part Thebe vendored (``make vendor``) and
``jupyter_server`` (``requirements-lab.txt``, as the browser layer installs it).
"""

from __future__ import annotations

import re

import pytest

from tools.book_site import IN_CI, PAGES, SITE
from tools.live_site import (
    PANEL_CONTROLS,
    PANEL_PAGES,
    live_ready,
    lock_down,
    make_live,
    move_control,
    run_edited_cell,
    serve_live,
    toggle_checkbox,
    wait_port_closed,
)

PANEL_PAGE_NAMES = sorted(PANEL_PAGES)


def test_the_book_has_panel_pages():
    assert len(PANEL_PAGE_NAMES) >= 10, PANEL_PAGE_NAMES


# ------------------------------------------------------------------ the static site

@pytest.mark.parametrize("page", PAGES)
def test_static_site_has_no_live_control(page):
    text = (SITE / f"{page}.html").read_text(encoding="utf-8")
    # Markup, not prose: "How to use" names the button in its text. (sphinx-thebe, which
    # Jupyter Book always loads, leaves an inert configuration and loader in every page; with
    # launch_buttons.thebe false it shows no button.)
    for mark in ('id="wk-live-config"', 'class="wk-live', '"/_live/', "thebe-launch-button"):
        assert mark not in text, f"{page}.html carries {mark!r}: the static site has no live mode"


@pytest.mark.parametrize("page", PANEL_PAGE_NAMES)
def test_precomputed_views_move_without_a_kernel(browser, site_url, page):
    context = browser.new_context(viewport={"width": 1366, "height": 900})
    external: list[str] = []
    failed: list[str] = []
    lock_down(context, external)
    web = context.new_page()
    web.on("response", lambda r: failed.append(f"{r.status} {r.url}") if r.status >= 400 else None)
    try:
        web.goto(f"{site_url}{page}.html", wait_until="load", timeout=60_000)
        views = web.locator(".wk-precomputed.wk-pc-ready")
        assert views.count() == len(PANEL_PAGES[page]), (
            f"{page}: {views.count()} precomputed views for panels {PANEL_PAGES[page]}")
        for v in range(views.count()):
            view = views.nth(v)
            assert view.get_attribute("data-panel") == PANEL_PAGES[page][v]
            assert view.locator(".wk-pc-controls").is_visible()
            assert re.search(r"Precomputed at (?:[\d × ]+= )?\d+ positions", view.inner_text())
            image = view.locator("img.wk-pc-image")
            controls = view.locator("[data-axis]")
            assert 1 <= controls.count() <= 2
            for c in range(controls.count()):
                control = controls.nth(c)
                label = view.locator(f"label[for='{control.get_attribute('id')}']")
                assert label.count() == 1 and label.inner_text().strip(), "a control's label"
                before = image.get_attribute("src")
                control.focus()
                if control.evaluate("e => e.tagName") == "SELECT":
                    count = control.locator("option").count()
                    current = control.evaluate("s => s.selectedIndex")
                    control.select_option(index=(current + 1) % count)
                else:
                    at_max = control.evaluate("e => e.value === e.max")
                    control.press("ArrowLeft" if at_max else "ArrowRight")
                web.wait_for_function(
                    "([img, before]) => img.getAttribute('src') !== before && img.complete "
                    "&& img.naturalWidth > 0", arg=[image.element_handle(), before],
                    timeout=10_000)
                assert image.evaluate("img => img.naturalWidth") == int(
                    image.get_attribute("width")), "the new image is the panel's size"
    finally:
        context.close()
    assert not failed, f"{page}: failed requests: {failed}"
    assert not external, f"{page}: requests outside the site: {sorted(set(external))}"


# ------------------------------------------------------------------ live pages

@pytest.fixture(scope="module")
def kernel_servers():
    """The Jupyter servers' URLs seen by the tests: closed once serve_live has stopped."""
    seen: list[str] = []
    yield seen
    for url in set(seen):
        assert wait_port_closed(url), f"the Jupyter server at {url} outlived serve_live"


@pytest.fixture(scope="module")
def live_url(kernel_servers):
    why = live_ready()
    if why:
        if IN_CI:
            pytest.fail(f"live pages cannot be served: {why}")
        pytest.skip(why)
    with serve_live() as url:
        yield url
    assert serve_live.returncode == 0, f"serve_live did not stop cleanly:\n{serve_live.output}"
    assert "stopped the site and the Jupyter server" in serve_live.output


@pytest.mark.parametrize("page", PANEL_PAGE_NAMES)
def test_live_page_panels_and_cells_run(browser, live_url, kernel_servers, page):
    context = browser.new_context(viewport={"width": 1366, "height": 900})
    external: list[str] = []
    errors: list[str] = []
    lock_down(context, external)
    web = context.new_page()
    web.on("pageerror", lambda exc: errors.append(str(exc)))
    try:
        web.goto(f"{live_url}{page}.html", wait_until="load", timeout=60_000)
        kernel_servers.append(web.evaluate(
            "() => JSON.parse(document.getElementById('wk-live-config').textContent).baseUrl"))
        make_live(web)
        panels = web.evaluate(PANEL_CONTROLS)
        assert len(panels) == len(PANEL_PAGES[page]), f"{page}: panels {panels}"
        stuck = []
        for panel in panels:
            assert panel["hasImage"], f"{page}: panel {panel['panel']} shows no live figure"
            assert web.locator(".wk-panel-cell").nth(panel["panel"]).locator(
                ".wk-precomputed").is_hidden(), "the live panel replaces the precomputed view"
            assert panel["controls"], f"{page}: panel {panel['panel']} has no controls"
            for control in panel["controls"]:
                try:
                    if control["kind"] == "checkbox":
                        toggle_checkbox(web, panel["panel"], control)
                    else:
                        move_control(web, panel["panel"], control)
                except Exception as exc:
                    stuck.append(f"panel {panel['panel']} {control['label'] or control}: {exc}")
        assert not stuck, f"{page}: controls that did not change the image:\n" + "\n".join(stuck)
        output = run_edited_cell(web, "print(sum(range(7)) * 2)", "42")
        assert "42" in output
    finally:
        context.close()
    assert not external, f"{page}: requests outside 127.0.0.1: {sorted(set(external))}"
    assert not errors, f"{page}: uncaught errors in the live page: {errors}"


def test_live_control_only_on_notebook_pages(browser, live_url):
    context = browser.new_context()
    try:
        web = context.new_page()
        web.goto(f"{live_url}book/how_to_use.html", wait_until="load")
        assert web.get_by_role("button", name="Make this page live").count() == 0
        web.goto(f"{live_url}{PANEL_PAGE_NAMES[0]}.html", wait_until="load")
        button = web.get_by_role("button", name="Make this page live")
        assert button.count() == 1 and button.is_visible()
    finally:
        context.close()
