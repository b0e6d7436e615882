"""Sphinx extension: make the built book load nothing from outside itself.

Loaded by ``_config.yml`` (``sphinx.local_extensions``). Two jobs:

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


def setup(app):
    app.connect("config-inited", _use_vendored_or_cdn, priority=100)
    app.connect("doctree-resolved", _strip_player_stylesheet)
    app.connect("html-page-context", _drop_duplicate_scripts, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
