"""Sphinx extension: the web edition numbers chapters, sections and appendices as the printed one.

Both editions take their numbers from ``_toc.yml`` (``book_pages.book_structure``): the chapters
of the parts marked ``numbered: true`` are 1, 2, ... across parts; the unnumbered parts after
them are appendices, lettered A, B, ...; the front matter (the preface, how to use, notation) has
no numbers. Sphinx alone cannot say this: it numbers each part from 1 (sphinx-multitoc-numbering
fixes that, not the rest), it numbers a chapter's landing page's own headings ("Sections", "What
to know first") before the chapter's sections, so that the first section would be 6.4, and it
cannot letter an appendix.

This extension replaces the section numbers Sphinx assigned by the ones LaTeX prints
(``tools/pdf_edition.py``):

- a chapter is N, its sections (the pages listed under it) N.1, N.2, ..., their headings N.1.1;
  deeper headings have no number (LaTeX's ``secnumdepth`` 2);
- a page that has pages listed under it (a chapter's landing page, the library reference's
  index) numbers its children, not its own headings below the title;
- an appendix is A, its headings A.1, ...

Figure, table and equation numbers follow (per chapter: Fig. 6.3, (4.2), Fig. A.1), as LaTeX
numbers them per chapter. The numbers are assigned before Sphinx numbers the figures, by wrapping
the toctree collector's section numbering: after sphinx-multitoc-numbering has patched it (which
jupyter-book does once the application exists, hence the wrap at ``env-before-read-docs``) and
after sphinx-external-toc's numbering styles, which would otherwise number the appendices.
"""

from __future__ import annotations

from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.environment.collectors.toctree import TocTreeCollector

from tools.book_pages import book_structure

#: Levels that carry a number: chapter, section, subsection (LaTeX: secnumdepth 2).
MAX_DEPTH = 3


def _toc_path(app) -> Path:
    path = Path(app.srcdir) / getattr(app.config, "external_toc_path", "_toc.yml")
    return path if path.is_file() else Path(app.srcdir) / "_toc.yml"


def book_numbers(env, toc: Path) -> dict[str, dict[str, tuple]]:
    """{docname: {anchor: number}} for every page of a numbered division, as LaTeX prints it.

    A number is a tuple (``(6, 1, 2)``, ``("A", 1)``); ``()`` marks a heading without one.
    """
    numbers: dict[str, dict[str, tuple]] = {}

    def number_page(docname: str, number: tuple) -> None:
        if docname not in env.tocs or docname in numbers:
            return
        secnums: dict[str, tuple] = {}
        numbers[docname] = secnums
        title = env.titles.get(docname)
        top = [item for item in env.tocs[docname].children if isinstance(item, nodes.list_item)]
        for index, item in enumerate(top):
            walk_item(docname, item, number if index == 0 else (), secnums, title)
            title = None

    def walk_item(docname, item, number, secnums, title) -> None:
        para = item.children[0] if item.children else None
        if isinstance(para, addnodes.compact_paragraph) and para.children:
            reference = para.children[0]
            if "skip_section_number" in para:  # an API object's entry: never numbered
                reference.setdefault("secnumber", None)
                return
            secnums[reference["anchorname"]] = number
            reference["secnumber"] = list(number) or None
            if title is not None:
                title["secnumber"] = list(number) or None
        for child in item.children[1:]:
            if isinstance(child, nodes.bullet_list):
                walk_list(docname, child, number, secnums)

    def walk_list(docname, blist, prefix, secnums) -> None:
        entries = []
        for child in blist.children:  # an ``only`` node's entries count in its place
            entries += child.children if isinstance(child, addnodes.only) else [child]
        has_pages = any(isinstance(e, addnodes.toctree) for e in entries)
        own = children = 0
        for entry in entries:
            if isinstance(entry, nodes.list_item):
                numbered = bool(prefix) and not has_pages and len(prefix) < MAX_DEPTH
                if numbered:
                    own += 1
                walk_item(docname, entry, (*prefix, own) if numbered else (), secnums, None)
            elif isinstance(entry, addnodes.toctree):
                for _title, ref in entry["entries"]:
                    if ref in env.tocs and ref != "self":
                        children += 1
                        number_page(ref, (*prefix, children) if prefix else ())

    for division in book_structure(toc):
        if division.number is None:
            continue
        head = int(division.number) if division.number.isdigit() else division.number
        number_page(division.page, (head,))
    return numbers


def _renumber(env, toc: Path) -> list[str]:
    """Overwrite Sphinx's section numbers with the book's; the pages whose numbers changed."""
    changed = []
    for docname, secnums in book_numbers(env, toc).items():
        if env.toc_secnumbers.get(docname) != secnums:
            changed.append(docname)
        env.toc_secnumbers[docname] = secnums
    return changed


def _collector_classes() -> list[type]:
    """The toctree collector classes in use: the most derived ones (sphinx-external-toc
    subclasses Sphinx's collector and post-processes its numbers; ours must come last)."""
    leaves, todo = [], [TocTreeCollector]
    while todo:
        cls = todo.pop()
        subclasses = cls.__subclasses__()
        todo += subclasses
        if not subclasses:
            leaves.append(cls)
    return leaves


def _wrap_numbering(app, env, docnames) -> None:
    toc = _toc_path(app)
    for cls in _collector_classes():
        current = cls.assign_section_numbers
        if getattr(current, "wheelkin_numbering", False):
            continue

        def assign_section_numbers(self, env, _current=current):
            old = {doc: dict(nums) for doc, nums in env.toc_secnumbers.items()}
            changed = _current(self, env)
            _renumber(env, toc)
            return sorted(set(changed) | {doc for doc, nums in env.toc_secnumbers.items()
                                          if old.get(doc) != nums})

        assign_section_numbers.wheelkin_numbering = True
        cls.assign_section_numbers = assign_section_numbers


def setup(app):
    app.connect("env-before-read-docs", _wrap_numbering)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
