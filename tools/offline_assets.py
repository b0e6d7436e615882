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
4. A light first visit (docs/DESIGN.md, "The site"): the theme loads Font Awesome's
   JavaScript (``scripts/fontawesome.js``, 1.5 MB) on every page, only to replace each
   ``<i class="fa-...">`` icon by an inline SVG. The theme's stylesheet already carries Font
   Awesome's CSS (every ``.fa-*:before`` glyph and the ``@font-face`` of its web fonts), which
   draws the same icons from the web font, so the ``<script>`` is removed from every page after
   the build (only when that stylesheet does carry the icon classes; otherwise the build warns
   and keeps the script). The ipywidgets scripts (``require.js``, ``embed-amd.js``) are added
   by myst-nb only to pages that store widget state, and the book stores none.
5. MathJax in parts: the combined ``tex-chtml.js`` (1.16 MB) bundles MathJax's context menu
   (``ui/menu``, 0.43 MB). Where the pinned MathJax package is installed (``node_modules/``,
   as ``make book`` leaves it) the pages load ``startup.js`` and its loader fetches only
   the TeX input, the CommonHTML output with its font data, and the assistive MathML that
   screen readers read (0.76 MB in all); the component files are copied into the build. The
   formulas look and read the same; the right-click menu (zoom, "show math as") is gone.
"""

from __future__ import annotations

import re
from pathlib import Path

from docutils import nodes

from tools.vendor_assets import vendor_complete

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


#: MathJax 3 components loaded instead of the combined tex-chtml.js (no ui/menu), as
#: (file under node_modules/mathjax/es5, file under _static/mathjax).
MATHJAX_PARTS: tuple[tuple[str, str], ...] = (
    ("startup.js", "startup.js"),
    ("core.js", "core.js"),
    ("input/tex.js", "input/tex.js"),
    ("output/chtml.js", "output/chtml.js"),
    ("output/chtml/fonts/tex.js", "output/chtml/fonts/tex.js"),
    ("a11y/assistive-mml.js", "a11y/assistive-mml.js"),
)
MATHJAX_ES5 = Path(__file__).resolve().parents[1] / "node_modules" / "mathjax" / "es5"
#: What config-inited decided, for build-finished (one build per process).
_STATE: dict[str, bool] = {}


def _mathjax_in_parts(app, config) -> None:
    vendor = Path(app.srcdir) / VENDOR_DIRNAME
    if not vendor_complete(vendor) or not all((MATHJAX_ES5 / src).is_file()
                                              for src, _ in MATHJAX_PARTS):
        return  # the combined file (vendored) or the CDN's
    config.mathjax_path = "mathjax/startup.js"
    settings = dict(config.mathjax3_config or {})
    loader = dict(settings.get("loader", {}))
    loader["load"] = ["input/tex", "output/chtml", "a11y/assistive-mml"]
    settings["loader"] = loader
    config.mathjax3_config = settings
    _STATE["mathjax_parts"] = True


def _copy_mathjax_parts(app, exception) -> None:
    if exception is not None or app.builder.format != "html":
        return
    if not _STATE.get("mathjax_parts"):
        return
    import shutil

    target = Path(app.outdir) / "_static" / "mathjax"
    for src, dest in MATHJAX_PARTS:
        (target / dest).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(MATHJAX_ES5 / src, target / dest)


def setup(app):
    app.connect("build-finished", _light_first_visit)
    app.connect("build-finished", _copy_mathjax_parts)
    app.connect("config-inited", _mathjax_in_parts, priority=101)
    app.connect("config-inited", _use_vendored_or_cdn, priority=100)
    app.connect("doctree-resolved", _strip_player_stylesheet)
    app.connect("html-page-context", _drop_duplicate_scripts, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
