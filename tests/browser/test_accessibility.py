"""Accessibility of the web editions, in Debian's chromium (book/accessibility.md says what).

1. **axe-core** (pinned in package.json, run in each page) finds no violation of its WCAG
   2.0/2.1 level A and AA rules on any HTML page of the built book (_build/html: every page of
   _toc.yml, the landing and redirect pages, the index and the search page) or of the student
   edition (_build/student/html, ``make student``; ``WHEELKIN_STUDENT_SITE`` names another),
   at a 1366x768 window. No rule is turned off.
2. **Every control** of every page (links, buttons, folds, the sidebar's toggles, inputs,
   sliders, anything in the tab order) is in the tab order and shows where the focus is when
   focused from the keyboard; no animation changes its frame before the reader asks.
3. **Reduced motion**: with ``prefers-reduced-motion: reduce`` the players play once and stop,
   and the theme's transitions and smooth scrolling are off.
4. **A keyboard-only walk through one chapter** (:data:`WALK_CHAPTER`, every page of it): the
   skip link, Tab through every control (each reached, its focus seen on screen), each kind of
   control used with the keys a reader would press, and on to the next page by its link.
5. The accessibility page states what this module measured (the numbers of the last run are
   written to _build/accessibility/audit.json; ``python -m tools.accessibility_report``
   copies them into the page).
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import time
from pathlib import Path

import pytest

from tools import accessibility_site as a11y
from tools.book_site import CHROMIUM, IN_CI, PAGES, ROOT, SITE, serve
from tools.student_edition import INSTRUCTOR_PAGES

STUDENT_SITE = Path(os.environ.get("WHEELKIN_STUDENT_SITE")
                    or ROOT / "_build" / "student" / "html")
BOOK_PAGES = a11y.site_pages(SITE, PAGES)
STUDENT_PAGES = a11y.site_pages(STUDENT_SITE, [p for p in PAGES if p not in INSTRUCTOR_PAGES])
#: The chapter walked by keyboard only: it has folds, a table, an animation player and an
#: answer to show; every page of it is walked, from its landing page on by "next" links.
WALK_CHAPTER = "notebooks/03_rover"
RESULTS = ROOT / "_build" / "accessibility" / "audit.json"
PAGE = ROOT / "book" / "accessibility.md"
#: What the walk measured, and what the audits found, for the accessibility page.
MEASURED: dict = {"book": {}, "student": {}, "walk": {}}


# --------------------------------------------------------------------------- fixtures


@pytest.fixture(scope="session")
def axe_ready():
    """axe-core as package-lock.json pins it (``make book`` installs it with ``npm ci``)."""
    if not a11y.axe_version():
        message = ("axe-core is not installed in node_modules/: run `make book` (npm ci "
                   "installs it from package-lock.json)")
        if IN_CI:
            pytest.fail(message)
        pytest.skip(message)
    assert a11y.axe_version() == a11y.pinned_axe_version(), (
        f"node_modules has axe-core {a11y.axe_version()}, package-lock.json pins "
        f"{a11y.pinned_axe_version()}: run `npm ci`")
    return a11y.axe_version()


@pytest.fixture(scope="session")
def student_site_url():
    if not (STUDENT_SITE / "index.html").is_file():
        pytest.fail(f"no student web edition in {STUDENT_SITE}: run `make student` first "
                    "(`make browser` does)")
    with serve(STUDENT_SITE) as url:
        yield url


@pytest.fixture(scope="session")
def audit(browser, axe_ready):
    """audit(edition, base URL, page) -> PageAudit, once per page (cached)."""
    cache: dict[tuple[str, str], a11y.PageAudit] = {}
    contexts = {}
    roots = {"book": SITE, "student": STUDENT_SITE}

    def context(edition):
        if edition not in contexts:
            contexts[edition] = browser.new_context(viewport=a11y.VIEWPORT)
        return contexts[edition]

    def run(edition: str, base: str, page_name: str) -> a11y.PageAudit:
        key = (edition, page_name)
        if key in cache:
            return cache[key]
        url = f"{base}{page_name}.html"
        page = context(edition).new_page()
        stub = a11y.is_redirect_stub(roots[edition], page_name)
        if stub:
            # A redirect page is audited as it is written, less the redirect itself (its
            # script and its no-script refresh), which would leave it before axe could look.
            def without_redirect(route):
                response = route.fetch()
                route.fulfill(response=response, body=a11y.without_redirect(response.text()))
            page.route(url, without_redirect)
        try:
            page.goto(url, wait_until="load", timeout=60_000)
            page.evaluate(a11y.WAIT_FOR_MATH)
            started = time.monotonic()
            frames = page.evaluate(a11y.PLAYER_FRAMES)
            page.add_script_tag(content=a11y.axe_source())
            found = page.evaluate(a11y.RUN_AXE, list(a11y.AXE_TAGS))
            report = a11y.PageAudit(page_name, found["violations"], found["passed_checks"],
                                    found["rules_applied"], found["incomplete"])
            described = page.evaluate(a11y.DESCRIPTIONS, [a11y.MIN_WORDS, a11y.NEW_WORDS])
            report.undescribed = described["problems"]
            report.figures, report.animations, report.tables = (
                described["figures"], described["animations"], described["tables"])
            page.keyboard.press("Tab")  # from here on, focus comes from the keyboard
            focus = page.evaluate(a11y.FOCUS_CHECK)
            report.controls = focus["controls"]
            report.unreachable = focus["unreachable"]
            report.no_visible_focus = focus["invisible"]
            page.evaluate(a11y.DARK_THEME)
            report.dark_violations = page.evaluate(a11y.RUN_AXE,
                                                   list(a11y.AXE_TAGS))["violations"]
            if frames:
                rest = a11y.STILL_MS / 1000 - (time.monotonic() - started)
                page.wait_for_timeout(max(0, rest) * 1000)
                now = page.evaluate(a11y.PLAYER_FRAMES)
                report.moving_by_itself = sorted(k for k, v in frames.items()
                                                 if now.get(k) != v)
        finally:
            page.close()
        cache[key] = report
        MEASURED[edition][page_name] = {
            "violations": sum(v["count"] for v in report.violations),
            "dark_violations": sum(v["count"] for v in report.dark_violations),
            "rules": sorted({v["id"] for v in report.violations + report.dark_violations}),
            "passed_checks": report.passed_checks, "controls": report.controls,
            "keyboard_problems": len(report.unreachable) + len(report.no_visible_focus),
            "moving": len(report.moving_by_itself),
            "figures": report.figures, "animations": report.animations,
            "tables": report.tables, "undescribed": len(report.undescribed)}
        return report

    yield run
    for ctx in contexts.values():
        ctx.close()


def _violations_message(report: a11y.PageAudit) -> str:
    lines = []
    for theme, found in (("", report.violations), (" (dark theme)", report.dark_violations)):
        for v in found:
            lines.append(f"{v['id']}{theme} ({v['impact']}, {v['count']} elements): {v['help']}")
            lines.extend(f"    {t}" for t in v["targets"])
    return "\n".join(lines)


def _keyboard_message(report: a11y.PageAudit) -> list[str]:
    problems = [f"not in the tab order: {c}" for c in report.unreachable]
    problems += [f"no visible focus: {c}" for c in report.no_visible_focus]
    problems += [f"animation moving by itself: {c}" for c in report.moving_by_itself]
    return problems


# --------------------------------------------------------------------------- axe-core


def test_axe_core_is_pinned_for_the_tests_only():
    """package.json pins one exact axe-core as a development dependency (the tests load it;
    tools/vendor_assets.py copies nothing of it into the site)."""
    package = json.loads((ROOT / "package.json").read_text())
    assert package.get("devDependencies", {}).get("axe-core") == a11y.pinned_axe_version()
    assert "axe-core" not in package.get("dependencies", {})
    from tools.vendor_assets import COPIES
    assert not [src for src, _ in COPIES if "axe" in src], "axe-core is not for readers"
    if (SITE / "_static").is_dir():
        shipped = [p.name for p in (SITE / "_static").rglob("axe*.js")]
        assert not shipped, f"axe-core was copied into the site: {shipped}"


#: Every page of both editions, as (edition, page); the ids read ``book-<page>`` and
#: ``student-<page>``.
EDITION_PAGES = [pytest.param(edition, page, id=f"{edition}-{page}")
                 for edition, pages in (("book", BOOK_PAGES), ("student", STUDENT_PAGES))
                 for page in pages]
#: The fixture that serves each edition.
EDITION_URL = {"book": "site_url", "student": "student_site_url"}


@pytest.fixture
def audited(request, audit):
    """audited(edition, page) -> (PageAudit, the page's name in a failure message); the
    student site is served (and required) only when a student page is audited."""
    def run(edition: str, page: str) -> tuple[a11y.PageAudit, str]:
        url = request.getfixturevalue(EDITION_URL[edition])
        where = page if edition == "book" else f"student edition, {page}"
        return audit(edition, url, page), where

    return run


@pytest.mark.parametrize(("edition", "page"), EDITION_PAGES)
def test_page_passes_axe(audited, edition, page):
    report, where = audited(edition, page)
    assert report.rules_applied > 0, f"{page}: axe ran no rule (was the page empty?)"
    assert not report.violations and not report.dark_violations, (
        f"{where}: axe-core {a11y.axe_version()} finds WCAG 2.1 A/AA violations:\n"
        f"{_violations_message(report)}")


@pytest.mark.parametrize(("edition", "page"), EDITION_PAGES)
def test_page_controls_by_keyboard(audited, edition, page):
    report, where = audited(edition, page)
    problems = _keyboard_message(report)
    assert not problems, f"{where}:\n" + "\n".join(problems)


@pytest.mark.parametrize(("edition", "page"), EDITION_PAGES)
def test_page_describes_figures_and_tables(audited, edition, page):
    """Every figure's alt text says more than its caption (what it shows and what to notice),
    every animation has a description tied to its frames, every table has header cells."""
    report, where = audited(edition, page)
    problems = report.undescribed
    assert not problems, f"{where}:\n" + "\n".join(problems)


def test_axe_catches_a_known_violation(browser, axe_ready):
    """The audit can fail: a page with an unnamed slider and an unnamed fold is caught."""
    context = browser.new_context(viewport=a11y.VIEWPORT)
    try:
        page = context.new_page()
        page.set_content('<!DOCTYPE html><html lang="en"><head><title>t</title></head><body>'
                         '<main><input type="range"><details><summary></summary>x</details>'
                         "</main></body></html>")
        page.add_script_tag(content=a11y.axe_source())
        found = page.evaluate(a11y.RUN_AXE, list(a11y.AXE_TAGS))
    finally:
        context.close()
    assert {v["id"] for v in found["violations"]} >= {"label", "summary-name"}


def test_keyboard_checks_catch_a_hidden_focus(browser):
    """The checks can fail: a button whose focus ring is removed, a link taken out of the tab
    order and an animation that starts by itself are each caught."""
    context = browser.new_context(viewport=a11y.VIEWPORT)
    try:
        page = context.new_page()
        page.set_content(
            '<!DOCTYPE html><html lang="en"><head><title>t</title><style>'
            "#bare:focus { outline: none; } </style></head><body><main>"
            '<button id="ringed">ringed</button> <button id="bare">bare</button> '
            '<a href="#x" tabindex="-1">away</a>'
            '<div class="animation"><img id="_anim_img1" src="data:,a"></div>'
            # A new frame every 200 ms while the page is open: on a loaded machine, one
            # timed change could come before the first look at the frames.
            "<script>let n = 0; setInterval(() => { "
            "document.getElementById('_anim_img1').src = 'data:,' + (++n); "
            "}, 200);</script></main></body></html>")
        frames = page.evaluate(a11y.PLAYER_FRAMES)
        page.keyboard.press("Tab")
        found = page.evaluate(a11y.FOCUS_CHECK)
        walker = Walker(page)
        seen = {}
        for name in ("ringed", "bare"):
            page.focus(f"#{name}")
            seen[name] = walker.focus_seen()
        page.wait_for_timeout(600)
        moved = page.evaluate(a11y.PLAYER_FRAMES)
    finally:
        context.close()
    assert found["invisible"] == ['button#bare "bare"'], found
    assert found["unreachable"] == ['a "away"'], found
    assert seen == {"ringed": True, "bare": False}
    assert frames != moved


# --------------------------------------------------------------------------- motion


def _pages_with_players() -> list[str]:
    return [p for p in PAGES if (SITE / f"{p}.html").is_file()
            and 'class="anim-slider"' in (SITE / f"{p}.html").read_text(encoding="utf-8")]


def test_reduced_motion_plays_once_and_stops(browser, site_url):
    """Under prefers-reduced-motion: every player is set to play once, the theme's
    transitions and smooth scrolling are off; Play (from the keyboard) runs to the last frame
    and stops there. Without the preference the players keep the mode they were made with."""
    pages = _pages_with_players()
    if not pages:
        pytest.skip("no page has an animation player")
    page_name = pages[0]
    modes = {}
    for motion in ("no-preference", "reduce"):
        context = browser.new_context(viewport=a11y.VIEWPORT, reduced_motion=motion)
        try:
            page = context.new_page()
            page.goto(f"{site_url}{page_name}.html", wait_until="load")
            page.evaluate(a11y.WAIT_FOR_MATH)
            modes[motion] = page.evaluate("""() => [...document.querySelectorAll(
                'form.anim-state')].map(f => f.querySelector('input:checked').value)""")
            if motion == "no-preference":
                continue
            still = page.evaluate("""() => {
              const out = [getComputedStyle(document.documentElement).scrollBehavior];
              for (const el of document.querySelectorAll('.btn, .bd-sidebar-primary, a')) {
                const cs = getComputedStyle(el);
                out.push(...cs.transitionDuration.split(',').map(s => s.trim()),
                         ...cs.animationDuration.split(',').map(s => s.trim()));
              }
              return out; }""")
            # Play from the keyboard, the fastest speed, and watch it end and stay.
            player = page.locator("div.animation").first
            player.locator("button[title='Increase speed']").focus()
            for _ in range(8):
                page.keyboard.press("Enter")
            player.locator("button[title='Play']").focus()
            page.keyboard.press("Enter")
            slider = player.locator("input.anim-slider")
            page.wait_for_function("s => s.value === s.max", arg=slider.element_handle(),
                                   timeout=30_000)
            last = slider.input_value()
            page.wait_for_timeout(600)
            assert slider.input_value() == last, "the animation went on after its last frame"
        finally:
            context.close()
    assert modes["reduce"] and set(modes["reduce"]) == {"once"}, modes
    assert modes["no-preference"] != modes["reduce"] or set(modes["no-preference"]) == {
        "once"}, "the players' mode did not depend on the preference"
    assert still[0] == "auto", f"smooth scrolling under reduced motion: {still[0]}"
    moving = sorted({d for d in still[1:] if d not in ("0s", "")})
    assert not moving, f"transitions or CSS animations under reduced motion: {moving}"


# --------------------------------------------------------------------------- the walk


def _walk_pages() -> list[str]:
    return [p for p in PAGES if p == WALK_CHAPTER or p.startswith(WALK_CHAPTER + "/")]


class Walker:
    """One page walked with the keyboard only (the page's own scripts answer the keys)."""

    def __init__(self, page):
        self.page = page
        self.used: dict[str, int] = {}
        self.problems: list[str] = []

    def active(self):
        return self.page.evaluate(a11y.ACTIVE)

    def settle(self, ms: int = 60):
        self.page.wait_for_timeout(ms)
        self.page.evaluate("() => { for (const a of document.getAnimations()) a.finish(); }")

    def focus_seen(self) -> bool:
        """The focused control looks different on screen from the same control unfocused
        (two screenshots of it and 8 px around it). Scrolling moves the theme's header and
        sidebars a moment later, so a control seen the same twice is looked at once more."""
        return self._focus_seen(0) or self._focus_seen(300)

    def _focus_seen(self, wait_ms: int) -> bool:
        # The control's box and those of what it holds (the theme draws a sidebar toggle's
        # ring on its icon, placed outside the toggle's own box), and 8 px around, once a
        # transition (the skip link slides in) has ended.
        self.settle(0)
        self.page.evaluate("() => document.activeElement.scrollIntoView("
                           "{block: 'center', inline: 'nearest'})")
        self.settle(wait_ms)
        box = self.page.evaluate("""() => { const el = document.activeElement;
            let [l, t, r, b] = [Infinity, Infinity, -Infinity, -Infinity];
            for (const e of [el, ...[...el.querySelectorAll('*')].slice(0, 30)]) {
              const q = e.getBoundingClientRect();
              if (q.width === 0 && q.height === 0) continue;
              l = Math.min(l, q.left); t = Math.min(t, q.top);
              r = Math.max(r, q.right); b = Math.max(b, q.bottom);
            }
            if (l === Infinity) return {x: 0, y: 0, width: 0, height: 0};
            const x = Math.max(0, l - 8), y = Math.max(0, t - 8);
            return {x, y, width: Math.min(innerWidth, r + 8) - x,
                    height: Math.min(innerHeight, b + 8) - y}; }""")
        if box["width"] < 1 or box["height"] < 1:
            return False
        focused = self.page.screenshot(clip=box)
        self.page.evaluate("() => { window.__a11yFocus = document.activeElement; "
                           "document.activeElement.blur(); }")
        self.settle(0)
        plain = self.page.screenshot(clip=box)
        self.page.evaluate("() => window.__a11yFocus.focus()")
        self.settle(0)
        return focused != plain

    def mutations(self, action) -> int:
        """How many changes of the page (DOM or attribute) ``action`` caused."""
        self.page.evaluate("""() => { window.__a11yChanges = 0;
            window.__a11yObserver = new MutationObserver(m => { window.__a11yChanges += m.length; });
            window.__a11yObserver.observe(document.documentElement,
              {subtree: true, childList: true, attributes: true, characterData: true}); }""")
        action()
        self.settle(150)
        return self.page.evaluate("() => { window.__a11yObserver.disconnect(); "
                                  "return window.__a11yChanges; }")

    def use(self, stop: dict) -> None:
        """Use the focused control with the keys a reader would press; check that it works."""
        page, kind = self.page, self.kind(stop)
        if kind is None:
            return
        self.used[kind] = self.used.get(kind, 0) + 1
        state = page.evaluate("() => document.activeElement.closest('details')?.open ?? null")
        if kind in ("sidebar toggle", "code fold"):
            for key in ("Enter", "Space"):
                page.keyboard.press(key)
                self.settle()
                now = page.evaluate("() => document.activeElement.closest('details').open")
                if now == state:
                    self.problems.append(f"{stop['name']}: {key} did not open/close it")
                state = now
        elif kind == "answer fold":
            before = page.evaluate("() => document.activeElement.getAttribute('aria-expanded')")
            page.keyboard.press("Enter")
            self.settle(200)
            after = page.evaluate("() => document.activeElement.getAttribute('aria-expanded')")
            if after == before:
                self.problems.append(f"{stop['name']}: Enter did not show the answer")
            page.keyboard.press("Enter")
            self.settle(200)
        elif kind == "dropdown":
            page.keyboard.press("Enter")
            self.settle(200)
            opened = page.evaluate("() => document.activeElement.getAttribute('aria-expanded')")
            page.keyboard.press("ArrowDown")
            self.settle()
            inside = page.evaluate("() => !!document.activeElement.closest('.dropdown-menu')")
            page.keyboard.press("Escape")
            self.settle(200)
            back = page.evaluate("() => document.activeElement.getAttribute('aria-expanded')")
            if opened != "true" or not inside or back != "false":
                self.problems.append(f"{stop['name']}: dropdown by keyboard: opened={opened}, "
                                     f"arrow into menu={inside}, Escape closed={back}")
        elif kind == "search":
            page.keyboard.press("Enter")
            self.settle(200)
            field = page.evaluate("() => document.activeElement.type")
            page.keyboard.type("rover")
            page.keyboard.press("Escape")
            self.settle(200)
            back = self.active()
            if field != "search" or not back or back["index"] != stop["index"]:
                self.problems.append(f"search by keyboard: field focused={field}, focus "
                                     f"back on the button={back}")
        elif kind == "colour mode":
            mode = page.evaluate("() => document.documentElement.dataset.mode")
            page.keyboard.press("Enter")
            self.settle()
            if page.evaluate("() => document.documentElement.dataset.mode") == mode:
                self.problems.append("the colour mode button did nothing on Enter")
            for _ in range(3):  # back to the mode the page started in
                if page.evaluate("() => document.documentElement.dataset.mode") == mode:
                    break
                page.keyboard.press("Enter")
                self.settle()
        elif kind == "play":
            frame = page.evaluate("() => document.activeElement.closest('.animation')"
                                  ".querySelector('img').src")
            page.keyboard.press("Enter")
            try:
                page.wait_for_function(
                    "f => document.activeElement.closest('.animation')"
                    ".querySelector('img').src !== f", arg=frame, timeout=5_000)
            except Exception:
                self.problems.append(f"{stop['name']}: Enter on Play did not play")
            page.keyboard.press("Shift+Tab")  # Pause is just before Play
            if (self.active() or {}).get("name", "").find("Pause") < 0:
                self.problems.append("Shift+Tab from Play did not reach Pause")
            page.keyboard.press("Enter")
            self.settle(100)
            src = "() => document.activeElement.closest('.animation').querySelector('img').src"
            frame = page.evaluate(src)
            self.settle(700)
            if page.evaluate(src) != frame:
                self.problems.append("Enter on Pause did not stop the animation")
            page.keyboard.press("Tab")  # back on Play
        elif kind in ("frame slider", "slider"):
            read = ("() => { const el = document.activeElement; return el.value ?? "
                    "el.getAttribute('aria-valuenow'); }")
            value = page.evaluate(read)
            at_end = page.evaluate("() => { const el = document.activeElement; "
                                   "const max = el.max ?? el.getAttribute('aria-valuemax'); "
                                   "return max !== undefined && String(el.value ?? "
                                   "el.getAttribute('aria-valuenow')) === String(max); }")
            key = "ArrowLeft" if at_end else "ArrowRight"
            changes = self.mutations(lambda: page.keyboard.press(key))
            if page.evaluate(read) == value:
                self.problems.append(f"{stop['name']}: {key} did not move the slider")
            elif changes == 0:
                self.problems.append(f"{stop['name']}: {key} moved the slider, the page did "
                                     "not change")
        elif kind == "radio":
            group = page.evaluate("() => document.activeElement.name")
            before = page.evaluate("g => [...document.activeElement.form.elements]"
                                   ".filter(e => e.name === g && e.checked).map(e => e.value)",
                                   group)
            page.keyboard.press("ArrowRight")
            self.settle()
            after = page.evaluate("g => [...document.activeElement.form.elements]"
                                  ".filter(e => e.name === g && e.checked).map(e => e.value)",
                                  group)
            if after == before:
                self.problems.append(f"{stop['name']}: the arrow key did not change the choice")
            page.keyboard.press("ArrowLeft")
            self.settle()
        elif kind == "scrolling region":
            left = page.evaluate("() => document.activeElement.scrollLeft")
            page.keyboard.press("ArrowRight")
            self.settle(200)
            if page.evaluate("() => document.activeElement.scrollLeft") <= left:
                self.problems.append(f"{stop['name']}: the arrow key did not scroll it")
        elif kind == "player step":
            read = "() => document.activeElement.closest('.animation').querySelector('input').value"
            value = int(page.evaluate(read))
            top = int(page.evaluate("() => document.activeElement.closest('.animation')"
                                    ".querySelector('input').max"))
            expected = top if "Last" in stop["name"] else min(value + 1, top)
            page.keyboard.press("Enter")
            self.settle()
            if int(page.evaluate(read)) != expected:
                self.problems.append(f"{stop['name']}: Enter showed frame "
                                     f"{page.evaluate(read)}, not {expected}")
        elif kind == "button":
            changes = self.mutations(lambda: page.keyboard.press("Enter"))
            if changes == 0:
                self.problems.append(f"{stop['name']}: Enter changed nothing on the page")

    def kind(self, stop: dict) -> str | None:
        """What the focused control is, for :meth:`use` (None: nothing to use on it here; a
        link is followed only to the next page)."""
        return self.page.evaluate("""() => {
          const el = document.activeElement;
          if (el.matches('.bd-sidebar-primary summary')) return 'sidebar toggle';
          if (el.matches('summary')) return 'code fold';
          if (el.matches('button.toggle-button')) return 'answer fold';
          if (el.matches('.dropdown-toggle')) return 'dropdown';
          if (el.matches('.search-button-field')) return 'search';
          if (el.matches('.theme-switch-button')) return 'colour mode';
          if (el.matches('.animation button[title="Play"]')) return 'play';
          if (el.matches('.animation button[title="Next frame"], ' +
                         '.animation button[title="Last frame"]')) return 'player step';
          // The player's other buttons (speed, first, previous, backwards, Pause): Pause is
          // used with Play; the rest change what the others do.
          if (el.matches('.animation button')) return null;
          if (el.matches('.animation input[type=range]')) return 'frame slider';
          if (el.matches('input[type=range], [role=slider]')) return 'slider';
          if (el.matches('input[type=radio], [role=radio]')) return 'radio';
          if (el.matches('mjx-container[tabindex], .pst-scrollable-table-container, pre, ' +
                         '.cell_output > .output') && el.scrollWidth > el.clientWidth)
            return 'scrolling region';
          // Buttons of the page's content (a live panel's, say); the theme's own buttons
          // (fullscreen, the sidebar toggles, copy) are not pressed here.
          if (el.matches('.bd-article button:not(.copybtn), .bd-article [role=button], ' +
                         '.bd-article input[type=checkbox], .bd-article select'))
            return 'button';
          return null; }""")

    def walk(self, page_name: str) -> dict:
        page = self.page
        # The skip link comes first, shows itself, and leads into the page's content.
        page.keyboard.press("Tab")
        first = self.active()
        if not first or "Skip to main content" not in first["name"]:
            self.problems.append(f"{page_name}: the first Tab stop is {first}, not the skip link")
        elif not self.focus_seen():
            self.problems.append(f"{page_name}: the skip link does not show when focused")
        page.keyboard.press("Enter")
        self.settle()
        if page.evaluate("() => location.hash") != "#main-content":
            self.problems.append(f"{page_name}: Enter on the skip link did not lead to the content")
        page.keyboard.press("Tab")
        if not page.evaluate("() => !!document.activeElement.closest('.bd-main')"):
            self.problems.append(f"{page_name}: after the skip link, Tab left the content")
        # From the top again: Tab through every stop until the focus leaves the page.
        page.goto(page.url.split("#")[0], wait_until="load")
        page.evaluate(a11y.WAIT_FOR_MATH)
        names = page.evaluate(a11y.LIST_CONTROLS)
        seen, unseen_focus, stops = set(), [], 0
        for _ in range(4 * len(names) + 20):
            page.keyboard.press("Tab")
            self.settle(20)
            stop = self.active()
            if stop is None:
                break  # past the last control
            if stop["index"] is not None and stop["index"] in seen:
                break
            stops += 1
            if stop["index"] is not None:
                seen.add(stop["index"])
            if not self.focus_seen():
                unseen_focus.append(stop["name"])
            self.use(stop)
        # A radio group is one stop (the arrow keys choose inside it): one radio reached
        # counts for its group.
        radios = page.evaluate("""(seen) => {
            const key = el => (el.form ? el.form.name : '') + '/' + el.name;
            const groups = new Set([...document.querySelectorAll('input[type=radio]')]
              .filter(el => seen.includes(el.dataset.a11yIndex)).map(key));
            return [...document.querySelectorAll('input[type=radio][data-a11y-index]')]
              .filter(el => groups.has(key(el))).map(el => el.dataset.a11yIndex); }""",
            sorted(seen))
        missing = [n for i, n in enumerate(names) if str(i) not in seen and str(i) not in radios]
        self.problems += [f"{page_name}: Tab never reached {n}" for n in missing]
        self.problems += [f"{page_name}: focus not seen on screen: {n}" for n in unseen_focus]
        return {"controls": len(names), "stops": stops, "reached": len(names) - len(missing)}


def test_keyboard_walk_through_a_chapter(browser, site_url):
    pages = _walk_pages()
    if not pages:
        pytest.skip(f"{WALK_CHAPTER} is not in _toc.yml")
    context = browser.new_context(viewport=a11y.VIEWPORT)
    problems, walked, used = [], [], {}
    try:
        page = context.new_page()
        page.goto(f"{site_url}{pages[0]}.html", wait_until="load")
        for index, name in enumerate(pages):
            here = page.url.split("?")[0].split("#")[0]
            assert here.endswith(f"{name}.html"), f"the walk is on {here}, expected {name}"
            page.evaluate(a11y.WAIT_FOR_MATH)
            walker = Walker(page)
            figures = walker.walk(name)
            problems += walker.problems
            for kind, n in walker.used.items():
                used[kind] = used.get(kind, 0) + n
            walked.append({"page": name, **figures})
            if index + 1 == len(pages):
                break
            # On to the next page by keyboard: Tab to the "next" link, Enter.
            page.evaluate("() => { document.activeElement.blur(); window.scrollTo(0, 0); }")
            for _ in range(4 * figures["controls"] + 20):
                page.keyboard.press("Tab")
                if page.evaluate("() => document.activeElement.matches('a.right-next')"):
                    break
            else:
                problems.append(f"{name}: Tab never reached the next-page link")
                break
            with page.expect_navigation():
                page.keyboard.press("Enter")
            page.wait_for_load_state("load")
    finally:
        context.close()
    MEASURED["walk"] = {"chapter": WALK_CHAPTER, "pages": walked, "used": used}
    kinds = {"sidebar toggle", "code fold", "answer fold", "dropdown", "search", "colour mode",
             "play", "player step", "frame slider", "radio"}
    assert kinds <= set(used), f"the walk never used: {sorted(kinds - set(used))}"
    assert not problems, "keyboard walk:\n" + "\n".join(problems)


# --------------------------------------------------------------------------- the page


def test_page_says_truly_whether_the_pdf_is_tagged():
    """The accessibility page's word on the printed edition matches the built PDF (read with
    poppler's pdfinfo), when this machine has built one (`make pdf`)."""
    import shutil

    pdf = ROOT / "_build" / "pdf" / "wheelkin.pdf"
    if not pdf.is_file() or shutil.which("pdfinfo") is None:
        pytest.skip("no printed edition built here (make pdf), or no pdfinfo")
    out = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True, timeout=60,
                         check=True).stdout
    tagged = any(line.split(":", 1)[1].strip() == "yes" for line in out.splitlines()
                 if line.startswith("Tagged:"))
    says_untagged = "is not tagged" in " ".join(PAGE.read_text(encoding="utf-8").split())
    assert says_untagged != tagged, (f"the PDF is {'' if tagged else 'not '}tagged; "
                                     "book/accessibility.md says otherwise")


def _chromium_version() -> str:
    try:
        out = subprocess.run([str(CHROMIUM), "--version"], capture_output=True, text=True,
                             timeout=30, check=False).stdout
    except OSError:
        return ""
    versions = [w for w in out.split() if w.count(".") >= 2 and w.replace(".", "").isdigit()]
    return versions[0] if versions else ""


def _totals(pages: dict) -> dict:
    """An edition's audit over all its pages: pages, violations (light and dark theme),
    passed checks, controls, keyboard problems, and its figures, animations and data tables
    with how many of them are not described (test_page_describes_figures_and_tables)."""
    return {"pages": len(pages),
            **{k: sum(p[k] for p in pages.values())
               for k in ("violations", "dark_violations", "passed_checks", "controls",
                         "keyboard_problems", "figures", "animations", "tables",
                         "undescribed")}}


def test_accessibility_page_states_the_measured_result(browser, axe_ready):
    """Runs last: what this session measured (every page of both editions audited) is
    written to _build/accessibility/audit.json, and the page's figures must equal it."""
    book, student = MEASURED["book"], MEASURED["student"]
    if set(book) != set(BOOK_PAGES) or set(student) != set(STUDENT_PAGES) \
            or not MEASURED["walk"]:
        pytest.skip("only the whole module measures every page (and walks the chapter)")
    context = browser.new_context()
    try:
        page = context.new_page()
        page.set_content("<!DOCTYPE html><title>x</title>")
        page.add_script_tag(content=a11y.axe_source())
        rules = page.evaluate(a11y.RULE_COUNT, list(a11y.AXE_TAGS))
    finally:
        context.close()
    walk = MEASURED["walk"]
    results = {
        "axe_core": axe_ready, "tags": list(a11y.AXE_TAGS), "rules": rules,
        "chromium": _chromium_version(), "viewport": a11y.VIEWPORT,
        "python": platform.python_version(),
        "book": _totals(book), "student": _totals(student),
        "walk": {"chapter": walk["chapter"], "pages": len(walk["pages"]),
                 "stops": sum(p["stops"] for p in walk["pages"]),
                 "controls": sum(p["controls"] for p in walk["pages"]),
                 "reached": sum(p["reached"] for p in walk["pages"]),
                 "used": walk["used"]},
        "per_page": {"book": book, "student": student},
    }
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    from tools.accessibility_report import stated, summary

    claimed, measured = stated(PAGE.read_text(encoding="utf-8")), summary(results)
    assert claimed == measured, (
        "book/accessibility.md does not state what the tests measured: run "
        "`.venv/bin/python -m tools.accessibility_report` (it copies "
        f"{RESULTS.relative_to(ROOT)} into the page).\nthe page: {claimed}\nmeasured: {measured}")
