"""Sphinx extension of the printed edition's LaTeX build (``tools/pdf_edition.py`` loads it).

- A cross-reference prints where it leads on paper: a reference with its own text keeps the
  text and adds the number and page, "the errata page (Appendix A, p. 401)"; one that would print
  the target's title prints its number instead, "Section 6.1 (p. 201)", "Chapter 1 (p. 1)"
  (a ``{doc}`` reference keeps the page's title: it names a page, as in a chapter's map of its
  sections). A target without a number (front matter, a landing page's own headings, a box, a
  figure named by ``{ref}``) gets its page: "How to use this book (p. xi)". The number is
  LaTeX's (``\\ref``), so it is the one printed at the target; which targets carry one follows
  ``book_pages.book_structure`` of the printed toc, as ``tools/numbering.py`` does for the web.
- The bibliography stays in the References appendix (Sphinx would gather it into a chapter of
  its own at the end of the book).
- The index is the book's terms and symbols (``tools/pdf_edition.py`` places them); the
  library's objects are left out of it (the library reference lists them by module).
- Paper's wording (``pdf_text.paper_wording``) applies to the library's docstrings too.
- ``{wklatex}`` is an inline role that passes LaTeX through (the questions' pointers to their
  answers, index entries).
"""

from __future__ import annotations

from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.util import docname_join
from sphinx.writers.latex import LaTeXTranslator

from tools.book_pages import book_structure

#: Levels that carry a number: chapter, section, subsection (secnumdepth 2).
MAX_DEPTH = 3


def latex_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    return [nodes.raw(rawtext, text, format="latex")], []


class Numbering:
    """Which targets of the printed book carry a number, and what the text calls them."""

    def __init__(self, env, toc: Path):
        self.env = env
        self.pages: dict[str, tuple[str, int, bool]] = {}  # page -> (matter, level, has pages)
        for division in book_structure(toc):
            for page in division.pages:
                self.pages[page] = (division.matter, division.level(page),
                                    division.has_pages(page))
        self._ids: dict[str, dict[str, int]] = {}

    def section_depths(self, docname: str) -> dict[str, int]:
        """{id: depth} of the page's sections (1: its title) and 0 for any other target."""
        if docname not in self._ids:
            found: dict[str, int] = {}
            try:
                tree = self.env.get_doctree(docname)
            except Exception:  # a page that was not read: its targets have no number
                tree = None
            for node in tree.findall(nodes.Element) if tree is not None else []:
                for node_id in node.get("ids", []):
                    if isinstance(node, nodes.section):
                        depth, parent = 1, node.parent
                        while parent is not None:
                            depth += isinstance(parent, nodes.section)
                            parent = parent.parent
                        found.setdefault(node_id, depth)
                    else:
                        found.setdefault(node_id, 0)
            self._ids[docname] = found
        return self._ids[docname]

    def word(self, docname: str, anchor: str | None) -> str | None:
        """"Chapter", "Appendix" or "Section" for a numbered target, None for any other."""
        if docname not in self.pages:
            return None
        matter, level, has_pages = self.pages[docname]
        if matter == "front":
            return None
        depth = 1 if anchor is None else self.section_depths(docname).get(anchor, 0)
        if depth == 0 or (depth > 1 and has_pages):
            return None
        level += depth - 1
        if level == 1:
            return "Chapter" if matter == "main" else "Appendix"
        return "Section" if level <= MAX_DEPTH else None


class PrintedReferences(SphinxPostTransform):
    """Each internal reference, before Sphinx resolves it, gets its number and page."""

    default_priority = 5  # before the ReferencesResolver (10)
    builders = ("latex",)

    def run(self, **kwargs) -> None:
        env = self.env
        numbering = getattr(env, "wheelkin_print_numbering", None)
        if numbering is None:
            numbering = Numbering(env, Path(env.srcdir) / "_toc.yml")
            env.wheelkin_print_numbering = numbering
        std = env.domaindata["std"]
        for node in list(self.document.findall(addnodes.pending_xref)):
            if node.get("refdomain") != "std" or node.get("reftype") not in ("ref", "doc"):
                continue
            if self._in_title(node):  # a moving argument: no reference number in a title
                continue
            target = node["reftarget"]
            if node["reftype"] == "doc":
                docname = docname_join(node.get("refdoc", ""), target)
                if docname not in env.all_docs:
                    continue
                anchor, latex_id = None, docname + "::doc"
            else:
                found = std["labels"].get(target.lower()) or std["anonlabels"].get(target.lower())
                if not found or not found[0]:
                    continue
                docname, anchor = found[0], found[1]
                latex_id = f"{docname}:{anchor}" if anchor else docname + "::doc"
            label = LaTeXTranslator.idescape(None, latex_id)
            word = numbering.word(docname, anchor)
            inside = self._inside_parentheses(node)  # "(Section 6.2, p. 129)", not nested
            if node["reftype"] == "ref" and not node.get("refexplicit") and word:
                macro = "wknumrefcomma" if inside else "wknumref"
                node.replace_self(nodes.raw("", rf"\{macro}{{{word}}}{{{label}}}",
                                            format="latex"))
                continue
            where = (rf"\wkxref{{{word}}}{{{label}}}" if word else rf"\wkpageref{{{label}}}")
            tail = f", {where}" if inside else f" ({where})"
            node.parent.insert(node.parent.index(node) + 1, nodes.raw("", tail, format="latex"))

    @staticmethod
    def _inside_parentheses(node) -> bool:
        """Whether the text of the paragraph before ``node`` leaves a parenthesis open."""
        block = node.parent
        while block is not None and not isinstance(
                block, (nodes.paragraph, nodes.term, nodes.entry, nodes.list_item)):
            block = block.parent
        if block is None:
            return False
        before = []
        for child in block.findall():
            if child is node:
                break
            if isinstance(child, nodes.Text):
                before.append(str(child))
        text = "".join(before)
        return text.count("(") > text.count(")")

    @staticmethod
    def _in_title(node) -> bool:
        parent = node.parent
        while parent is not None:
            if isinstance(parent, (nodes.title, nodes.caption, nodes.rubric)):
                return True
            parent = parent.parent
        return False


class _BibliographyMark(SphinxPostTransform):
    """Marks where the book's bibliography is (the references page), before Sphinx gathers
    the citations at the end of the document."""

    default_priority = 745  # Sphinx's BibliographyTransform: 750
    builders = ("latex",)

    def run(self, **kwargs) -> None:
        first = next(iter(self.document.findall(nodes.citation)), None)
        if first is not None:
            first.parent.insert(first.parent.index(first), nodes.comment("", _BIBLIOGRAPHY))


class _BibliographyInPlace(SphinxPostTransform):
    """Puts the gathered bibliography back where the references page shows it: the printed
    References appendix holds the list, not an extra chapter at the end."""

    default_priority = 760
    builders = ("latex",)

    def run(self, **kwargs) -> None:
        from sphinx.builders.latex.nodes import thebibliography

        mark = next((n for n in self.document.findall(nodes.comment)
                     if n.astext() == _BIBLIOGRAPHY), None)
        found = next(iter(self.document.findall(thebibliography)), None)
        if mark is None:
            return
        if found is not None:
            found.parent.remove(found)
            mark.replace_self(found)
        else:
            mark.parent.remove(mark)


_BIBLIOGRAPHY = "wheelkin: the bibliography goes here"


class _PaperWording(SphinxPostTransform):
    """The wording for paper (``pdf_text.paper_wording``) in text the PDF tool does not
    rewrite itself: the library's docstrings ("its first, folded cell")."""

    default_priority = 6
    builders = ("latex",)

    def run(self, **kwargs) -> None:
        from tools import pdf_text

        skip = (nodes.literal, nodes.literal_block, nodes.math, nodes.math_block, nodes.raw,
                nodes.comment)
        for text in list(self.document.findall(nodes.Text)):
            if any(isinstance(a, skip) for a in _ancestors(text)):
                continue
            new = pdf_text.paper_wording(str(text))
            if new != str(text):
                text.parent.replace(text, nodes.Text(new))


def _ancestors(node):
    parent = node.parent
    while parent is not None:
        yield parent
        parent = parent.parent


class _LibraryOutOfIndex(SphinxPostTransform):
    """The library's objects and modules stay out of the index of terms and symbols: they are
    listed, module by module, in the library reference appendix."""

    default_priority = 5
    builders = ("latex",)

    def run(self, **kwargs) -> None:
        for node in list(self.document.findall(addnodes.index)):
            following = node.next_node(descend=False, siblings=True)
            module = any(kind == "pair" and "module" in text.split(";")[0]
                         for kind, text, *_ in node.get("entries", []))
            if isinstance(following, addnodes.desc) or module:
                node.parent.remove(node)


def setup(app):
    app.add_role("wklatex", latex_role)
    app.add_post_transform(PrintedReferences)
    app.add_post_transform(_BibliographyMark)
    app.add_post_transform(_BibliographyInPlace)
    app.add_post_transform(_LibraryOutOfIndex)
    app.add_post_transform(_PaperWording)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
