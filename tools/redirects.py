"""Sphinx extension: the first edition's chapter URLs lead to the chapters' new pages.

A chapter that moved from one notebook (``notebooks/03_rover.ipynb``, page
``notebooks/03_rover.html``) into a folder (``notebooks/03_rover/index.md`` with section
notebooks) would leave every old link and bookmark broken. For each such chapter this writes a
small stub at the old address that sends the reader on:

- to the section page that now holds the anchor the old link named, when the anchor is a
  label or section id of the chapter's new pages (``03_rover.html#erratum-rover-...`` goes to
  the section with that erratum);
- otherwise to the chapter's landing page (``03_rover/index.html``).

The stub works without JavaScript too (``<meta http-equiv="refresh">`` to the landing page, and
a link). Which chapters moved is derived from the build: an old page ``notebooks/NN_name`` is
redirected when ``notebooks/NN_name/index`` is a built page and ``notebooks/NN_name`` is not.
More redirects can be listed in ``_config.yml`` (``sphinx.config.wheelkin_redirects``:
``{old docname: new docname}``).

>>> moved_chapters({"notebooks/03_rover/index", "notebooks/03_rover/01_x", "notebooks/01_a"})
{'notebooks/03_rover': 'notebooks/03_rover/index'}
"""

from __future__ import annotations

import html
import json
import posixpath
import re
from pathlib import Path

_CHAPTER_INDEX = re.compile(r"^(notebooks/\d\d_[\w-]+)/index$")


def moved_chapters(docnames: set[str]) -> dict[str, str]:
    """{old chapter page: new landing page} for every chapter folder whose old page is gone."""
    out = {}
    for doc in sorted(docnames):
        match = _CHAPTER_INDEX.match(doc)
        if match and match.group(1) not in docnames:
            out[match.group(1)] = doc
    return out


def _anchors(env, prefix: str) -> dict[str, str]:
    """{anchor id: docname} for the labels and section ids of the pages under ``prefix``."""
    found: dict[str, str] = {}
    for _label, (doc, anchor, *_rest) in env.domaindata["std"]["labels"].items():
        if doc.startswith(prefix) and anchor:
            found.setdefault(anchor, doc)
    for doc in sorted(env.found_docs):
        if not doc.startswith(prefix):
            continue
        try:
            tree = env.get_doctree(doc)
        except Exception:  # a page that was not read (excluded): nothing to map
            continue
        for node in tree.findall(lambda n: bool(getattr(n, "get", None) and n.get("ids"))):
            for anchor in node["ids"]:
                found.setdefault(anchor, doc)
    return found


_STUB = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>Moved: {title}</title>
<meta name="robots" content="noindex">
<link rel="canonical" href="{target}">
<script>
(function () {{
  var anchors = {anchors};
  var id = decodeURIComponent(window.location.hash.slice(1));
  var page = Object.prototype.hasOwnProperty.call(anchors, id) ? anchors[id] : null;
  window.location.replace(page ? page + "#" + encodeURIComponent(id) : "{target}");
}})();
</script>
<noscript><meta http-equiv="refresh" content="0; url={target}"></noscript>
</head>
<body>
<p>This chapter has moved to <a href="{target}">{title}</a>.</p>
</body>
</html>
"""


def _relative(from_doc: str, to_doc: str, suffix: str) -> str:
    return posixpath.relpath(to_doc + suffix, posixpath.dirname(from_doc) or ".")


def write_redirects(app, exception) -> None:
    if exception is not None or app.builder.format != "html":
        return
    env = app.builder.env
    docnames = set(env.found_docs)
    mapping = moved_chapters(docnames)
    mapping.update(app.config.wheelkin_redirects or {})
    suffix = app.builder.out_suffix
    outdir = Path(app.outdir)
    for old, new in sorted(mapping.items()):
        if old in docnames:
            continue  # the old page is still built: never overwrite it
        prefix = posixpath.dirname(new) + "/" if new.endswith("/index") else new
        anchors = {anchor: _relative(old, doc, suffix)
                   for anchor, doc in _anchors(env, prefix).items()}
        title = env.titles[new].astext() if new in env.titles else new
        target = _relative(old, new, suffix)
        page = outdir / (old + suffix)
        page.parent.mkdir(parents=True, exist_ok=True)
        page.write_text(_STUB.format(title=html.escape(title), target=html.escape(target),
                                     anchors=json.dumps(anchors, sort_keys=True)),
                        encoding="utf-8")


def setup(app):
    app.add_config_value("wheelkin_redirects", {}, "html", types=[dict])
    app.connect("build-finished", write_redirects)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
