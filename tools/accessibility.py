"""Sphinx extension: the book's fixes for WCAG 2.1 AA (checked by axe-core in the browser tests).

Loaded by ``_config.yml`` (``sphinx.local_extensions``). Each fix is made where the markup is
written, so that the built pages pass axe-core's WCAG 2.0/2.1 A and AA rules with no rule
turned off (``tests/browser/test_accessibility.py``, ``book/accessibility.md``):

1. **The sidebar's collapsible chapters** (axe ``summary-name``): the theme writes each
   chapter's expand/collapse ``<summary>`` with an icon only. Each gets a visually hidden
   name, "Sections of <chapter title>" (screen readers add "expanded" or "collapsed").
2. **The code folds** (``label-content-name-mismatch``): myst-nb names every "Show code cell
   source" fold "Toggle hidden content", a name that does not contain what the reader sees
   (speech-input users say what they see). The fold is written without that ``aria-label``,
   so its name is its visible text. The search button's template is overridden for the same
   reason (``book/_templates/search-button-field.html``).
3. **The references page** (``aria-required-children``, ``aria-deprecated-role``): docutils
   writes each citation with the role ``doc-biblioentry`` (deprecated in DPUB-ARIA 1.1)
   inside a ``role="list"``, which then has no list items. Each citation is a ``listitem``.
4. **The animation players** (``label``, ``label-content-name-mismatch``): a player stored in
   a notebook before :func:`wheelkin.animation.accessible_player` existed gets its frame
   slider named and its pause icon drawn as a symbol here, by that same function (a player
   written now already has both, and is left as it is).
5. **The site's index.html**, which sends the reader to the first page, is written as a
   whole document (``html-has-lang``, ``document-title``) instead of a bare ``<meta>``.
6. **The general and module indexes** lay out their entries with tables; those are marked
   ``role="presentation"``, as layout, not data tables without header cells.
7. **Wide displayed equations and motion**: ``book/_static/accessibility.js`` makes a
   displayed equation that scrolls sideways reachable by keyboard (axe
   ``scrollable-region-focusable``, as the theme does for wide code and tables), and under
   ``prefers-reduced-motion`` sets every animation player to play once and stop; it also
   names the answers' folds by their titles and makes the module index's group togglers
   (images only a mouse could click) buttons. ``book/_static/accessibility.css`` draws a
   visible focus ring on every control the theme leaves without one, turns transitions off
   under ``prefers-reduced-motion`` and shows the dark theme's cell outputs on white. This
   extension adds both files to every page.
"""

from __future__ import annotations

import functools
import html
import re
from pathlib import Path

from docutils import nodes

#: What a collapsible chapter's toggle is called, before the chapter's title.
TOGGLE_NAME = "Sections of"
STATIC_FILES = {"js": "accessibility.js", "css": "accessibility.css"}


def name_sidebar_toggles(fragment: str) -> str:
    """Give every icon-only ``<summary>`` of the theme's navigation a visually hidden name.

    >>> name_sidebar_toggles('<li class="toctree-l1 has-children"><a class="reference '
    ...     'internal" href="a.html">Frames, units</a><details><summary><span '
    ...     'class="toctree-toggle" role="presentation"><i class="fa-solid"></i></span>'
    ...     '</summary><ul></ul></details></li>')  # doctest: +NORMALIZE_WHITESPACE
    '<li class="toctree-l1 has-children"><a class="reference internal"
    href="a.html">Frames, units</a><details><summary><span class="toctree-toggle"
    role="presentation"><i class="fa-solid"></i></span><span class="visually-hidden">Sections
    of Frames, units</span></summary><ul></ul></details></li>'
    """
    from bs4 import BeautifulSoup

    if "<summary" not in fragment:
        return fragment
    soup = BeautifulSoup(fragment, "html.parser")
    return str(soup) if _name_toggles_in(soup) else fragment


def _name_toggles_in(soup) -> bool:
    """Name the icon-only toggles of a parsed navigation in place; True if any was named.
    A toggle that has a name (a part's caption, an earlier call) is left as it is."""
    changed = False
    for summary in soup.select("li.has-children > details > summary"):
        if summary.get_text(strip=True) or summary.get("aria-label"):
            continue
        item = summary.find_parent("li")
        link = item.find("a", recursive=False) if item else None
        title = " ".join(link.get_text().split()) if link else ""
        label = soup.new_tag("span", attrs={"class": "visually-hidden"})
        label.string = f"{TOGGLE_NAME} {title}" if title else "Sections"
        summary.append(label)
        changed = True
    return changed


def _wrap_toctree(app, pagename, templatename, context, doctree) -> None:
    """The theme's navigation function, wrapped so that its toggles come out named. It
    returns a parsed tree (which it caches: naming it again changes nothing) or a string."""
    from bs4 import Tag

    generate = context.get("generate_toctree_html")
    if generate is None or getattr(generate, "_wheelkin_named", False):
        return

    @functools.wraps(generate)
    def named(*args, **kwargs):
        out = generate(*args, **kwargs)
        if isinstance(out, str):
            return name_sidebar_toggles(out)
        if isinstance(out, Tag):
            _name_toggles_in(out)
        return out

    named._wheelkin_named = True
    context["generate_toctree_html"] = named


def _visit_fold(self, node) -> None:
    """myst-nb's fold of a hidden cell, named by its visible text ("Show code cell source")."""
    classes = " ".join(node["classes"])
    self.body.append(f'<details class="admonition hide {classes}">\n')
    self.body.append("<summary>\n")
    self.body.append(
        f'<p class="collapsed admonition-title">{html.escape(node["prompt_show"])}</p>\n')
    self.body.append(
        f'<p class="expanded admonition-title">{html.escape(node["prompt_hide"])}</p>\n')
    self.body.append("</summary>\n")


def _visit_citation(self, node) -> None:
    """A citation as a ``listitem`` of the ``list`` that docutils opens around citations."""
    if not isinstance(node.previous_sibling(), type(node)):
        self.body.append('<div role="list" class="citation-list">\n')
    self.body.append(self.starttag(node, "div", classes=[node.tagname], role="listitem"))


def _depart_citation(self, node) -> None:
    self.body.append("</div>\n")
    if not isinstance(node.next_node(descend=False, siblings=True), type(node)):
        self.body.append("</div>\n")


def _override_writers(app) -> None:
    """Registered once every extension has registered its own (myst-nb's fold node)."""
    from myst_nb.sphinx_ import HideCodeCellNode, depart_HideCellInput

    app.add_node(HideCodeCellNode, override=True, html=(_visit_fold, depart_HideCellInput))
    app.add_node(nodes.citation, override=True, html=(_visit_citation, _depart_citation))


def _label_players(app, doctree, docname) -> None:
    """Every animation player stored before the library named its controls, named now."""
    from wheelkin.animation import accessible_player

    for node in doctree.findall(nodes.raw):
        if "html" not in node.get("format", "").split():
            continue
        text = node.astext()
        if 'class="anim-slider"' not in text:
            continue
        new = accessible_player(text)
        if new != text:
            node.children = [nodes.Text(new)]
            node.rawsource = new


def _write_root_page(app, exception) -> None:
    """The site's ``index.html``, which only sends the reader to the first page, as a whole
    document (a language, a title, a link), before sphinx-external-toc writes its bare
    one-line ``<meta>`` refresh (it writes one only where there is none)."""
    if exception is not None or app.builder.format != "html":
        return
    index = Path(app.outdir) / "index.html"
    if app.config.root_doc == "index" or index.exists():
        return
    target = html.escape(app.builder.get_target_uri(app.config.root_doc), quote=True)
    title = html.escape(app.config.html_title or app.config.project)
    language = html.escape(app.config.language or "en", quote=True)
    index.write_text(
        f'<!DOCTYPE html>\n<html lang="{language}">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{title}</title>\n"
        f'<meta http-equiv="refresh" content="0; url={target}">\n'
        f'<link rel="canonical" href="{target}">\n</head>\n<body>\n'
        f'<main><p>The book starts at <a href="{target}">{title}</a>.</p></main>\n'
        "</body>\n</html>\n", encoding="utf-8")


#: Sphinx lays out its general and module indexes with tables: they hold no data to read
#: by row and column, so they are marked as layout (their lists and links read as they are).
_INDEX_TABLE = re.compile(r'<table(?![^>]*\brole=)(?=[^>]*class="indextable)')


def mark_layout_tables(html_text: str) -> str:
    """The index pages' layout tables marked ``role="presentation"`` (idempotent).

    >>> mark_layout_tables('<table class="indextable genindextable"><tr><td>a</td></tr>')
    '<table role="presentation" class="indextable genindextable"><tr><td>a</td></tr>'
    >>> mark_layout_tables(mark_layout_tables('<table class="indextable">')).count("role")
    1
    """
    return _INDEX_TABLE.sub('<table role="presentation"', html_text)


def _mark_index_tables(app, exception) -> None:
    if exception is not None or app.builder.format != "html":
        return
    for page in Path(app.outdir).glob("*index*.html"):
        text = page.read_text(encoding="utf-8")
        new = mark_layout_tables(text)
        if new != text:
            page.write_text(new, encoding="utf-8")


def setup(app):
    static = Path(__file__).resolve().parents[1] / "book" / "_static"
    for name in STATIC_FILES.values():
        if not (static / name).is_file():  # pragma: no cover - a broken checkout
            raise FileNotFoundError(f"tools/accessibility.py needs book/_static/{name}")
    app.add_js_file(STATIC_FILES["js"], defer="defer")
    app.add_css_file(STATIC_FILES["css"])
    app.connect("builder-inited", _override_writers)
    app.connect("html-page-context", _wrap_toctree, priority=900)
    app.connect("doctree-resolved", _label_players)
    app.connect("build-finished", _write_root_page, priority=400)
    app.connect("build-finished", _mark_index_tables)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
