"""Sphinx extension: every live panel of the book also works in the static page, precomputed.

Loaded by ``_config.yml`` (``sphinx.local_extensions``). A notebook cell that shows a live
panel is tagged ``remove-output`` (a panel needs a kernel) and names its panel in its metadata,
``{"wheelkin": {"panel": "diffdrive.wheel_speeds"}}``. For each such cell this extension:

1. puts, in the cell, the panel's precomputed view: real form controls (a range slider per
   numeric control, a ``<select>`` for a choice), labelled with the panel's own control names,
   over the figure at the controls' defaults, and a note that says how many positions were
   drawn and where to run the panel for any value. The controls are ``hidden`` until
   ``book/_static/precomputed.js`` runs: without JavaScript the reader sees the figure and the
   note, and no control that does nothing;
2. adds ``precomputed.js`` and ``precomputed.css`` to the pages that have such a view, and to
   no other page;
3. after the build, writes the images into ``_static/precomputed/<panel>/`` (one PNG per grid
   position, ``wheelkin.widgets.precomputed``: drawn by the panel's own code). They are
   rendered once into ``_build/.precomputed/`` and reused while the library, the grids and the
   plotting stack are unchanged (a fingerprint decides), two panels at a time.

The page loads only the image at the defaults; the others are fetched when a control moves
(the first-visit budget of docs/DESIGN.md holds). A cell that names a panel without a grid, or
no registered panel, is a build warning (an error under ``-W``).
"""

from __future__ import annotations

import hashlib
import html
import json
import shutil
import sys
from pathlib import Path

from docutils import nodes

import wheelkin

#: The library whose code draws the images (the venv's wheelkin, editable from the checkout).
LIBRARY = Path(wheelkin.__file__).resolve().parent
#: The checkout's build folder holds the cache, also for a build of a copy of the book (the
#: student edition builds one, with these tools copied beside it).
_CHECKOUT = LIBRARY.parents[1]
ROOT = _CHECKOUT if (_CHECKOUT / "_config.yml").is_file() else Path(__file__).resolve().parents[1]
CACHE = ROOT / "_build" / ".precomputed"
STATIC_DIR = "precomputed"
JS_FILE, CSS_FILE = "precomputed.js", "precomputed.css"
#: The section of "How to use" that tells the three ways to meet a panel.
HOW_TO_USE = "book/how_to_use.html#how-to-use-live"
STAMP = ".fingerprint"

_DESCRIPTIONS: dict[str, dict] = {}


def _warn(message: str, location=None) -> None:
    from sphinx.util import logging

    logging.getLogger(__name__).warning(message, location=location)


def panel_of(node: nodes.Element) -> str | None:
    """The panel a notebook code cell shows (its ``wheelkin.panel`` metadata), or None."""
    if node.get("nb_element") != "cell_code":
        return None
    meta = node.get("cell_metadata") or {}
    name = (meta.get("wheelkin") or {}).get("panel")
    return name if isinstance(name, str) and name else None


def _panel_cells(doctree: nodes.document) -> list[nodes.container]:
    return [n for n in doctree.findall(nodes.container) if panel_of(n)]


def _record(app, doctree) -> None:
    env = app.env
    if not hasattr(env, "wheelkin_panels"):
        env.wheelkin_panels = {}
    names = [panel_of(cell) for cell in _panel_cells(doctree)]
    if names:
        env.wheelkin_panels[env.docname] = names
    else:
        env.wheelkin_panels.pop(env.docname, None)


def _purge(app, env, docname) -> None:
    getattr(env, "wheelkin_panels", {}).pop(docname, None)


def _merge(app, env, docnames, other) -> None:
    if not hasattr(env, "wheelkin_panels"):
        env.wheelkin_panels = {}
    for docname in docnames:
        if docname in getattr(other, "wheelkin_panels", {}):
            env.wheelkin_panels[docname] = other.wheelkin_panels[docname]


def _describe(name: str) -> dict | None:
    if name not in _DESCRIPTIONS:
        from wheelkin.widgets import all_panels
        from wheelkin.widgets.precomputed import GRIDS, describe

        if name not in all_panels() or name not in GRIDS:
            return None
        _DESCRIPTIONS[name] = describe(name)
    return _DESCRIPTIONS[name]


def _slug(name: str) -> str:
    return "pc-" + name.replace(".", "-").replace("_", "-")


def view_html(info: dict, base: str, root: str, uid: str) -> str:
    """The precomputed view of one panel, as HTML (``base``: its images' folder URL)."""
    e = html.escape
    start = [axis["start"] for axis in info["axes"]]
    controls = []
    for k, axis in enumerate(info["axes"]):
        cid = f"{uid}-{axis['name'].replace('_', '-')}"
        values = axis["values"]
        current = values[axis["start"]]
        if axis["kind"] == "slider":
            field = (f'<input type="range" id="{cid}" data-axis="{k}" min="0" '
                     f'max="{len(values) - 1}" step="1" value="{axis["start"]}" '
                     f'aria-valuetext="{e(current)}" '
                     f"data-values='{e(json.dumps(values), quote=True)}'>"
                     f'<output for="{cid}" id="{cid}-value">{e(current)}</output>')
        else:  # a choice: its options' labels
            options = "".join(f'<option value="{i}"{" selected" if i == axis["start"] else ""}>'
                              f"{e(v)}</option>" for i, v in enumerate(values))
            field = f'<select id="{cid}" data-axis="{k}">{options}</select>'
        controls.append(f'<div class="wk-pc-control"><label for="{cid}">{e(axis["label"])}'
                        f"</label>{field}</div>")
    fixed = ", ".join(f"{f['label']} {f['value']}" for f in info["fixed"])
    shape = " × ".join(str(len(a["values"])) for a in info["axes"])
    names = " and ".join(a["label"] for a in info["axes"])
    # one axis: "21 positions"; several: "21 × 5 = 105 positions"
    count = f"{shape} = {info['count']}" if len(info["axes"]) > 1 else str(info["count"])
    note = (f"Precomputed at {count} positions of {names}"
            + (f" (the other controls at their defaults: {fixed})" if fixed else "")
            + f'. For any value, <a href="{root}{HOW_TO_USE}">run the panel live</a>.')
    first = "-".join(str(i) for i in start) + ".png"
    at = "; ".join(f"{a['label']} {a['values'][a['start']]}" for a in info["axes"])
    alt = f"{info['title']}: the panel's figure at {at}" + (f"; {fixed}" if fixed else "")
    return (f'<div class="wk-precomputed" id="{uid}" data-panel="{e(info["panel"])}" '
            f'data-base="{e(base)}" role="group" aria-labelledby="{uid}-title" '
            f'data-title="{e(info["title"])}" data-fixed="{e(fixed)}">'
            f'<p class="wk-pc-title" id="{uid}-title">{e(info["title"])}</p>'
            f'<div class="wk-pc-controls" hidden>{"".join(controls)}</div>'
            f'<img class="wk-pc-image" src="{e(base + first)}" width="{info["width"]}" '
            f'height="{info["height"]}" alt="{e(alt)}" decoding="async">'
            f'<p class="wk-pc-note">{note}</p></div>')


def _insert_views(app, doctree, docname) -> None:
    if app.builder.format != "html":
        return
    root = "../" * docname.count("/")
    seen: dict[str, int] = {}
    for cell in _panel_cells(doctree):
        name = panel_of(cell)
        info = _describe(name)
        if info is None:
            _warn(f"live_pages: the cell names panel {name!r}, which is not registered or "
                  "has no grid in wheelkin.widgets.precomputed.GRIDS", location=cell)
            continue
        seen[name] = seen.get(name, 0) + 1
        uid = _slug(name) + (f"-{seen[name]}" if seen[name] > 1 else "")
        base = f"{root}_static/{STATIC_DIR}/{name}/"
        cell["classes"].append("wk-panel-cell")
        cell += nodes.raw("", view_html(info, base, root, uid), format="html")


def _add_assets(app, pagename, templatename, context, doctree) -> None:
    if doctree is None or not getattr(app.env, "wheelkin_panels", {}).get(pagename):
        return
    app.add_css_file(CSS_FILE)
    app.add_js_file(JS_FILE, loading_method="defer")


def fingerprint() -> str:
    """Changes whenever the images could: the library's code, the grids, the plotting stack."""
    import matplotlib
    import PIL

    digest = hashlib.sha256()
    for path in sorted(LIBRARY.rglob("*.py")):
        digest.update(str(path.relative_to(LIBRARY)).encode())
        digest.update(path.read_bytes())
    digest.update(f"{matplotlib.__version__} {PIL.__version__} {sys.version_info[:2]}".encode())
    return digest.hexdigest()


def _render_panel(name: str, folder: str) -> tuple[str, int, int]:
    """Render every image of panel ``name`` into ``folder`` (run in a worker process)."""
    from wheelkin.widgets.precomputed import render

    out = Path(folder)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    count = size = 0
    for index, png in render(name):
        from wheelkin.widgets.precomputed import Grid

        (out / Grid.file_name(index)).write_bytes(png)
        count += 1
        size += len(png)
    return name, count, size


def ensure_rendered(names: list[str], cache: Path = CACHE, workers: int = 2) -> list[str]:
    """Render the panels in ``names`` whose cached images are missing or stale; return them."""
    import concurrent.futures
    import multiprocessing

    stamp = fingerprint()
    stale = [n for n in names if not (cache / n / STAMP).is_file()
             or (cache / n / STAMP).read_text().strip() != stamp]
    if not stale:
        return []
    context = multiprocessing.get_context("spawn")  # a fresh interpreter, not Sphinx's state
    with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
        for name, _count, _size in pool.map(_render_panel, stale,
                                             [str(cache / n) for n in stale]):
            (cache / name / STAMP).write_text(stamp + "\n")
    return stale


def _write_images(app, exception) -> None:
    if exception is not None or app.builder.format != "html":
        return
    names = sorted({n for ns in getattr(app.env, "wheelkin_panels", {}).values() for n in ns
                    if _describe(n) is not None})
    if not names:
        return
    from sphinx.util import logging

    rendered = ensure_rendered(names)
    if rendered:
        logging.getLogger(__name__).info(
            f"live_pages: drew the precomputed views of {len(rendered)} panels")
    target = Path(app.outdir) / "_static" / STATIC_DIR
    for name in names:
        dest = target / name
        shutil.rmtree(dest, ignore_errors=True)
        shutil.copytree(CACHE / name, dest, ignore=shutil.ignore_patterns(STAMP))


def setup(app):
    app.connect("doctree-read", _record)
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.connect("doctree-resolved", _insert_views)
    app.connect("html-page-context", _add_assets)
    app.connect("build-finished", _write_images)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
