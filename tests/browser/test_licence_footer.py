"""Every built page names the licences in its footer and links the reuse page, which exists.

The footer is written per page by tools/licence_footer.py; this reads the built HTML (no
browser needed, but it belongs to the layer that has the built site).
"""

from __future__ import annotations

import re
from urllib.parse import unquote

import pytest

from tools.book_site import PAGES, SITE


@pytest.mark.parametrize("page", PAGES)
def test_footer_names_the_licences_and_links_the_reuse_page(page):
    html = SITE / f"{page}.html"
    assert html.is_file(), f"{page}.html was not built"
    text = html.read_text(encoding="utf-8")
    footer = re.search(r'<p class="wheelkin-licence">(.*?)</p>', text, re.S)
    assert footer, f"{page}: no licence footer"
    assert "CC BY 4.0" in footer.group(1) and "MIT" in footer.group(1)
    href = re.search(r'href="([^"]+)"', footer.group(1)).group(1)
    if href == "#":  # the reuse page itself
        assert page == "book/reuse", f"{page}: the footer links to the page itself"
        return
    assert (html.parent / unquote(href)).resolve().is_file(), f"{page}: {href} does not exist"
