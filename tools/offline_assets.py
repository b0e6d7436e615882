"""Sphinx extension: make the built book load nothing from outside itself.

Loaded by ``_config.yml`` (``sphinx.local_extensions``). Four jobs:

1. ``_config.yml`` points MathJax and the widget scripts at copies in ``_vendor/`` (see
   ``tools/vendor_assets.py``). When ``_vendor/`` is absent (no npm on this machine) this
   extension switches those settings back to the CDN defaults of Sphinx and myst-nb and drops
   ``_vendor`` from ``html_static_path``, so the build still passes ``-W``.
   ``tools/vendor_assets.py`` has already said so, once.
2. sphinx-thebe (always loaded by Jupyter Book) registers its inline configuration script
   twice, which throws "Identifier 'THEBE_JS_URL' has already been declared" in every page:
   duplicate scripts are dropped from each page.
3. Matplotlib's ``to_jshtml`` player (the book's animations) links a Font Awesome 4 stylesheet
   from a CDN for its button icons. The theme already ships Font Awesome 6, whose ``fa fa-*``
   classes draw the same icons, so that ``<link>`` is removed from every HTML output.
4. A light first visit (docs/DESIGN.md, "A light first visit"): the theme loads Font Awesome's
   JavaScript (``scripts/fontawesome.js``, 1.5 MB) on every page, only to replace each
   ``<i class="fa-...">`` icon by an inline SVG. The theme's stylesheet already carries Font
   Awesome's CSS (every ``.fa-*:before`` glyph and the ``@font-face`` of its web fonts), which
   draws the same icons from the web font, so the ``<script>`` is removed from every page after
   the build (only when that stylesheet does carry the icon classes; otherwise the build warns
   and keeps the script). The ipywidgets scripts (``require.js``, ``embed-amd.js``) are added
   by myst-nb only to pages that store widget state, and the book stores none.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from docutils import nodes

sys.path.insert(0, str(Path(__file__).resolve().parent))
from vendor_assets import vendor_complete

VENDOR_DIRNAME = "_vendor"

#: The ``<link>`` to Font Awesome 4 that matplotlib's animation player carries.
_PLAYER_STYLESHEET = re.compile(
    r"<link\s+rel=\"stylesheet\"\s+href=\"https?://[^\"]*/font-awesome/[^\"]*\"\s*/?>\s*"
)


def _use_vendored_or_cdn(app, config) -> None:
    vendor = Path(app.srcdir) / VENDOR_DIRNAME
    if vendor_complete(vendor):
        return
    from myst_nb.core.config import ipywidgets_js_factory
    from sphinx.ext.mathjax import MATHJAX_URL

    config.mathjax_path = MATHJAX_URL
    config.nb_ipywidgets_js = ipywidgets_js_factory()
    config.html_static_path = [p for p in config.html_static_path if p != VENDOR_DIRNAME]


def _strip_player_stylesheet(app, doctree, docname) -> None:
    for node in doctree.findall(nodes.raw):
        if "html" not in node.get("format", "").split():
            continue
        text = node.astext()
        if _PLAYER_STYLESHEET.search(text):
            new = _PLAYER_STYLESHEET.sub("", text)
            node.children = [nodes.Text(new)]
            node.rawsource = new


def _drop_duplicate_scripts(app, pagename, templatename, context, doctree) -> None:
    scripts = context.get("script_files")
    if not scripts:
        return
    seen, unique = set(), []
    for script in scripts:
        attributes = getattr(script, "attributes", {}) or {}
        # The same inline script is registered once with filename None and once with "".
        key = (str(getattr(script, "filename", script) or ""),
               tuple(sorted((k, str(v)) for k, v in attributes.items())))
        if key not in seen:
            seen.add(key)
            unique.append(script)
    context["script_files"] = unique


#: The theme's Font Awesome script tag (pydata-sphinx-theme's layout writes it on every page).
_FONTAWESOME_SCRIPT = re.compile(
    r'[ \t]*<script\b[^>]*\bsrc="[^"]*_static/scripts/fontawesome\.js[^"]*"[^>]*>\s*</script>\n?')
#: Proof that a stylesheet draws the icons by itself: Font Awesome's CSS for its menu icon.
_ICON_CSS = re.compile(r"\.fa-bars:before[^{]*\{content:")


def _theme_css_draws_icons(outdir: Path) -> bool:
    css = outdir / "_static" / "styles" / "pydata-sphinx-theme.css"
    return css.is_file() and bool(_ICON_CSS.search(css.read_text(encoding="utf-8")))


def drop_fontawesome_script(outdir: Path) -> int:
    """Remove the theme's fontawesome.js tag from every HTML page; return how many changed."""
    changed = 0
    for page in outdir.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        new = _FONTAWESOME_SCRIPT.sub("", text)
        if new != text:
            page.write_text(new, encoding="utf-8")
            changed += 1
    return changed


def _light_first_visit(app, exception) -> None:
    if exception is not None or app.builder.format != "html":
        return
    outdir = Path(app.outdir)
    if not _theme_css_draws_icons(outdir):
        from sphinx.util import logging

        logging.getLogger(__name__).warning(
            "offline_assets: the theme's stylesheet has no Font Awesome icon classes; "
            "fontawesome.js is kept (the first visit stays heavier)")
        return
    drop_fontawesome_script(outdir)


def setup(app):
    app.connect("build-finished", _light_first_visit)
    app.connect("config-inited", _use_vendored_or_cdn, priority=100)
    app.connect("doctree-resolved", _strip_player_stylesheet)
    app.connect("html-page-context", _drop_duplicate_scripts, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
