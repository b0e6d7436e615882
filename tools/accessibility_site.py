"""What the accessibility tests (tests/browser/test_accessibility.py) run in a page: axe-core,
the walk over every control, motion.

``axe-core`` is pinned in ``package.json`` (a development dependency: the tests load it into
each page; readers never get it) and installed by ``npm ci`` (``make book`` runs it through
``tools/vendor_assets.py``). Every page is audited with the WCAG 2.0 and 2.1 rule sets of
levels A and AA (:data:`AXE_TAGS`), no rule turned off.
"""

from __future__ import annotations

import functools
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

from tools.book_site import ROOT

AXE_DIR = ROOT / "node_modules" / "axe-core"
#: The WCAG rule sets of axe-core run on every page: WCAG 2.0 and 2.1, levels A and AA.
AXE_TAGS = ("wcag2a", "wcag2aa", "wcag21a", "wcag21aa")
#: The window the audit uses: a laptop screen, as the issue's first audit did.
VIEWPORT = {"width": 1366, "height": 768}
#: How long a page is watched for an animation that starts by itself (ms).
STILL_MS = 1200


def axe_version() -> str:
    """The installed axe-core's version ('' when npm has not installed it)."""
    package = AXE_DIR / "package.json"
    return json.loads(package.read_text())["version"] if package.is_file() else ""


def pinned_axe_version() -> str:
    """The version package-lock.json pins (what ``npm ci`` installs)."""
    lock = json.loads((ROOT / "package-lock.json").read_text())
    return lock["packages"]["node_modules/axe-core"]["version"]


@functools.cache
def axe_source() -> str:
    return (AXE_DIR / "axe.min.js").read_text(encoding="utf-8")


def site_pages(site: Path, fallback: list[str]) -> list[str]:
    """Every HTML page of a built site (landing and redirect pages, the index and search
    pages included), by name without ``.html``; ``fallback`` when the site is not built."""
    if not (site / "index.html").is_file():
        return list(fallback)
    skip = ("_static/", "_sources/", "_images/")
    names = (p.relative_to(site).as_posix() for p in site.rglob("*.html"))
    return sorted(n[:-5] for n in names if not n.startswith(skip))


def is_redirect_stub(site: Path, page: str) -> bool:
    """A page that only sends the reader on (tools/redirects.py, the site's index.html)."""
    path = site / f"{page}.html"
    text = path.read_text(encoding="utf-8", errors="replace") if path.is_file() else ""
    sends_on = "window.location.replace(" in text or re.search(
        r"<meta[^>]+http-equiv=[\"']?refresh", text, re.I) is not None
    return sends_on and 'id="main-content"' not in text


def without_redirect(html: str) -> str:
    """A redirect page's HTML without what sends the reader on (scripts, a no-script refresh).

    >>> without_redirect('<head><script>location.replace("a")</script><noscript><meta '
    ...                  'http-equiv="refresh" content="0; url=a"></noscript></head>')
    '<head></head>'
    """
    html = re.sub(r"<script\b.*?</script>\s*", "", html, flags=re.S | re.I)
    html = re.sub(r"<noscript\b.*?</noscript>\s*", "", html, flags=re.S | re.I)
    return re.sub(r"<meta[^>]+http-equiv=[\"']?refresh[^>]*>\s*", "", html, flags=re.I)


@dataclass
class PageAudit:
    """What auditing one page found."""

    page: str
    #: axe's violations: rule id, impact, help text, number of elements, the first targets
    violations: list[dict] = field(default_factory=list)
    #: how many (rule, element) checks passed, and how many rules applied to the page
    passed_checks: int = 0
    rules_applied: int = 0
    #: the same audit with the page switched to the theme's dark colours
    dark_violations: list[dict] = field(default_factory=list)
    #: rules whose result axe leaves to a human (for the record, not a failure)
    incomplete: list[str] = field(default_factory=list)
    #: the controls of the page and what the walk over them found
    controls: int = 0
    unreachable: list[str] = field(default_factory=list)
    no_visible_focus: list[str] = field(default_factory=list)
    #: animations whose frame changed with nobody pressing anything
    moving_by_itself: list[str] = field(default_factory=list)
    #: figures whose alt text says no more than the caption, animations without a
    #: description, tables without a header cell
    undescribed: list[str] = field(default_factory=list)
    figures: int = 0
    animations: int = 0
    tables: int = 0


WAIT_FOR_MATH = """async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    await MathJax.startup.promise;
  }
  // accessibility.js marks wide equations after MathJax, debounced: let it run.
  await new Promise(r => setTimeout(r, 300));
}"""

RUN_AXE = """async (tags) => {
  const result = await axe.run(document, {
    runOnly: {type: "tag", values: tags},
    resultTypes: ["violations", "incomplete"],
  });
  return {
    violations: result.violations.map(v => ({
      id: v.id, impact: v.impact, help: v.help, count: v.nodes.length,
      targets: v.nodes.slice(0, 5).map(n => n.target.join(" ") + "  " + n.html.slice(0, 160)),
    })),
    passed_checks: result.passes.reduce((n, p) => n + p.nodes.length, 0),
    rules_applied: result.passes.length + result.violations.length,
    incomplete: result.incomplete.map(v => v.id),
  };
}"""

#: The theme's dark colours, switched on as its colour-mode button does (pydata-sphinx-theme's
#: setTheme: the mode and theme attributes, and the dark variant of its menus).
DARK_THEME = """() => {
  document.documentElement.dataset.mode = "dark";
  document.documentElement.dataset.theme = "dark";
  document.querySelectorAll(".dropdown-menu").forEach(m => m.classList.add("dropdown-menu-dark"));
  // The theme's colour transitions end at once, so that axe measures the dark colours.
  void document.body.getBoundingClientRect();
  for (const a of document.getAnimations()) a.finish();
}"""

RULE_COUNT = """(tags) => axe.getRules(tags).length"""

#: Every control of a page and a short name for it; shared by the walks below.
CONTROLS_JS = r"""
const NATIVE = "a[href], area[href], button, input:not([type=hidden]), select, textarea, " +
  "iframe, details > summary:first-of-type, [contenteditable]:not([contenteditable=false])";
const ROLES = "[role=button], [role=link], [role=checkbox], [role=radio], [role=slider], " +
  "[role=spinbutton], [role=switch], [role=tab], [role=menuitem], [role=option], " +
  "[role=combobox], [role=textbox], [role=searchbox], [role=treeitem]";
function shown(el) {
  if (el.closest("[inert]")) return false;
  if (!el.checkVisibility({visibilityProperty: true, contentVisibilityAuto: true})) return false;
  // Content of a closed <details> (Chromium gives it client rects all the same).
  for (let d = el.parentElement && el.parentElement.closest("details"); d;
       d = d.parentElement && d.parentElement.closest("details")) {
    if (!d.open && !(el.matches("summary") && el.parentElement === d)) return false;
  }
  return el.getClientRects().length > 0;
}
function controls() {
  const found = new Set();
  for (const el of document.querySelectorAll(NATIVE + ", " + ROLES)) {
    if (el.disabled || el.getAttribute("aria-disabled") === "true") continue;
    if (shown(el)) found.add(el);
  }
  // Anything else in the tab order (a scrolling region, a widget of its own).
  for (const el of document.querySelectorAll("[tabindex]")) {
    if (el.tabIndex >= 0 && shown(el)) found.add(el);
  }
  return [...found];
}
function describe(el) {
  const name = (el.getAttribute("aria-label") || el.getAttribute("title") ||
                el.textContent || el.value || "").trim().replace(/\s+/g, " ").slice(0, 50);
  const id = el.id ? "#" + el.id.slice(0, 40) : "";
  const cls = el.classList.length ? "." + [...el.classList].slice(0, 2).join(".") : "";
  return `${el.tagName.toLowerCase()}${id}${cls} "${name}"`;
}
"""

#: Every control is in the tab order and shows where the focus is, once focused from the
#: keyboard. "Shows" means a style of the control, of its pseudo-elements, of its parent or of
#: a child changes on focus (an outline, a shadow, a colour, a border, an underline, its size or
#: place, for a link that is hidden until focused). Transitions are finished first.
FOCUS_CHECK = "(() => {" + CONTROLS_JS + r"""
  // What a style shows: an outline or a border only when it is drawn (a style that is not
  // "none", a width, a colour that is not transparent), and the rest as they are.
  const SHOWN = ["box-shadow", "background-color", "color", "text-decoration-line", "clip",
    "clip-path", "width", "height", "opacity", "transform", "position", "left", "top"];
  function drawn(cs, prefix) {
    const style = cs.getPropertyValue(prefix + "-style");
    const width = parseFloat(cs.getPropertyValue(prefix + "-width")) || 0;
    const color = cs.getPropertyValue(prefix + "-color");
    if (style === "none" || style === "hidden" || width <= 0 ||
        /rgba\([^)]*,\s*0\)$/.test(color) || color === "transparent") return "-";
    return `${style} ${width} ${color}`;
  }
  function style(el, pseudo) {
    const cs = getComputedStyle(el, pseudo);
    const parts = ["outline", "border-top", "border-right", "border-bottom", "border-left"]
      .map(p => drawn(cs, p));
    return parts.concat(SHOWN.map(p => cs.getPropertyValue(p))).join("|");
  }
  function look(el) {
    // The control, its pseudo-elements, its parent and its children (the theme draws the
    // ring of a sidebar toggle on the icon inside it).
    const parts = [style(el, null), style(el, "::before"), style(el, "::after"),
                   el.parentElement ? style(el.parentElement, null) : ""];
    for (const child of [...el.children].slice(0, 6)) parts.push(style(child, null));
    return parts.join("#");
  }
  function settle() { for (const a of document.getAnimations()) a.finish(); }
  const all = controls();
  const unreachable = [], invisible = [];
  const scroll = [window.scrollX, window.scrollY];
  for (const el of all) {
    if (el.tabIndex < 0) { unreachable.push(describe(el)); continue; }
    if (document.activeElement && document.activeElement !== document.body) {
      document.activeElement.blur();
    }
    settle();
    const before = look(el);
    el.focus();
    settle();
    if (document.activeElement !== el) {
      unreachable.push(describe(el) + " (takes no focus)");
      continue;
    }
    const after = look(el);
    if (!el.matches(":focus-visible")) { invisible.push(describe(el) + " (not :focus-visible)"); }
    else if (after === before) { invisible.push(describe(el)); }
    el.blur();
  }
  settle();
  window.scrollTo(scroll[0], scroll[1]);
  return {controls: all.length, unreachable, invisible};
})()"""

#: A figure's alt text must say more than its caption: at least this many words, of which
#: at least :data:`NEW_WORDS` are not in the caption. An animation's description the same.
MIN_WORDS = 10
NEW_WORDS = 6

#: Figures (images of the page's content), animations and tables, and how each is described:
#: a figure by its alt text, beyond its caption; an animation by the text its frames point to
#: (aria-describedby), beyond its caption; a table by header cells. A live panel's precomputed
#: view (tools/live_pages.py) is left out: its image is the panel's figure at the values its
#: labelled sliders show, and its alt text says that.
DESCRIPTIONS = """([minWords, newWords]) => {
  const words = t => (t || "").toLowerCase().match(/[a-z0-9]+/g) || [];
  const short = t => (t || "").replace(/\\s+/g, " ").trim().slice(0, 70);
  const main = document.querySelector("#main-content, .bd-article, main") || document.body;
  const problems = [];
  function beyond(text, caption, what) {
    const mine = words(text), theirs = new Set(words(caption));
    const added = new Set(mine.filter(w => !theirs.has(w)));
    if (mine.length < minWords) return `${what} has ${mine.length} words (at least ${minWords})`;
    if (added.size < newWords) {
      return `${what} adds ${added.size} words to its caption (at least ${newWords})`;
    }
    return null;
  }
  const caption = el => {
    const figure = el.closest("figure");
    const cap = figure && figure.querySelector(":scope > figcaption");
    return cap ? cap.textContent : "";
  };
  const figures = [...main.querySelectorAll("img")].filter(img =>
    !img.closest("div.animation") && !img.closest(".wk-precomputed") &&
    !["presentation", "none", "button"].includes(img.getAttribute("role")) &&
    img.getAttribute("alt") !== "");
  for (const img of figures) {
    const found = beyond(img.getAttribute("alt"), caption(img), "its alt text");
    if (found) problems.push(`figure ${short(img.getAttribute("alt"))}: ${found}`);
  }
  const players = [...main.querySelectorAll("div.animation img")];
  for (const img of players) {
    const ids = (img.getAttribute("aria-describedby") || "").split(/\\s+/).filter(Boolean);
    const text = ids.map(id => (document.getElementById(id) || {}).textContent || "").join(" ");
    if (!text.trim()) {
      problems.push(`animation ${img.id}: no description (aria-describedby)`);
      continue;
    }
    const found = beyond(text, caption(img), "its description");
    if (found) problems.push(`animation ${img.id}: ${found}`);
  }
  const tables = [...main.querySelectorAll("table")].filter(
    t => !["presentation", "none"].includes(t.getAttribute("role")));
  for (const table of tables) {
    if (!table.querySelector("th")) {
      problems.push(`table ${short(table.textContent)}: no header cell (th)`);
    }
  }
  return {problems, figures: figures.length, animations: players.length, tables: tables.length};
}"""

#: The frames the animation players show now, by player id.
PLAYER_FRAMES = """() => Object.fromEntries([...document.querySelectorAll("div.animation img")]
  .map((img, i) => [img.id || "animation " + i, img.getAttribute("src") || ""]))"""

#: The controls the Tab key reaches, in order, as ``describe`` names them; ``index`` marks
#: each visited one so that the walk can compare it with ``controls()``.
LIST_CONTROLS = "(() => {" + CONTROLS_JS + """
  return controls().map((el, i) => { el.dataset.a11yIndex = String(i); return describe(el); });
})()"""

ACTIVE = "(() => {" + CONTROLS_JS + """
  const el = document.activeElement;
  if (!el || el === document.body) return null;
  return {index: el.dataset.a11yIndex ?? null, name: describe(el),
          tag: el.tagName.toLowerCase(), type: el.type || "", role: el.getAttribute("role")};
})()"""
