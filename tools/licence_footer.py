"""Sphinx extension: every page's footer names the book's licences and links the reuse page.

The theme's ``extra_footer`` option is static HTML, the same string on every page, so it
cannot hold a relative link that works from pages at different depths (and offline, from
``file://``). This extension fills it per page, with Sphinx's own ``pathto``.
"""

from __future__ import annotations

from typing import Any

#: The page that explains the licences, citation and editions (a document name of the book).
REUSE_PAGE = "book/reuse"


def _footer(app: Any, pagename: str, templatename: str, context: dict, doctree: Any) -> None:
    if REUSE_PAGE not in app.env.all_docs:
        return
    href = context["pathto"](REUSE_PAGE)
    context["theme_extra_footer"] = (
        '<p class="wheelkin-licence">Text and figures: CC BY 4.0; code: MIT. '
        f'The wheelkin authors, 2026. <a href="{href}">Reusing and citing this book</a>.</p>'
    )


def setup(app: Any) -> dict[str, Any]:
    app.connect("html-page-context", _footer)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
