"""The printed edition (tools/pdf_edition.py): ``make pdf`` builds _build/pdf/wheelkin.pdf,
then runs these checks (its own layer of ``make test``)."""

from __future__ import annotations

import base64
import io
import json
import re
import shutil
import subprocess
from pathlib import Path

import nbformat
import pytest

from tools import pdf_edition
from tools.student_edition import toc_notebooks

ROOT = Path(__file__).resolve().parents[2]

PDF = ROOT / "_build" / "pdf" / "wheelkin.pdf"
#: The book has about 40 section pages; far fewer pages means chapters went missing.
MIN_PAGES = 150


@pytest.fixture(scope="module")
def text():
    if not PDF.is_file():
        pytest.fail(f"{PDF.relative_to(ROOT)} is missing: run `make pdf`")
    if shutil.which("pdftotext") is None:
        pytest.fail("pdftotext is missing: run `make tex` (poppler-utils)")
    done = subprocess.run(["pdftotext", "-layout", str(PDF), "-"], capture_output=True,
                          text=True, check=True)
    return done.stdout.replace("\u2019", "'").replace("\u2018", "'")


def _first_animation():
    """(notebook, caption) of the first animation with a caption in the book."""
    for rel in toc_notebooks():
        nb = nbformat.read(ROOT / rel, as_version=4)
        for cell in nb.cells:
            for out in cell.get("outputs", []):
                markup = pdf_edition._text(out.get("data", {}).get("text/html", ""))
                caption = pdf_edition._CAPTION.search(markup)
                if "_anim_img" in markup and caption:
                    return rel, pdf_edition._plain(caption.group(1))
    return None, None


def test_the_pdf_has_the_whole_book(text):
    assert pdf_edition.pages(PDF) > MIN_PAGES
    summary = json.loads((PDF.parent / "summary.json").read_text(encoding="utf-8"))
    assert summary["pages"] == pdf_edition.pages(PDF)
    for rel in toc_notebooks()[:: max(1, len(toc_notebooks()) // 8)]:
        title = next((line.lstrip("# ").strip() for c in nbformat.read(
            ROOT / rel, as_version=4).cells if c.cell_type == "markdown"
            for line in c.source.splitlines() if line.startswith("# ")), None)
        if title and "{" not in title and "$" not in title:
            assert " ".join(title.split()[:3]) in " ".join(text.split()), f"{rel}: {title}"


def test_no_animation_player_or_live_panel_leaked(text):
    flat = " ".join(text.split())
    for leaked in ("frames[", "_anim_img", "data:image/png;base64", "anim_step_forward",
                   "Needs a running kernel"):  # the live panel's margin note
        assert leaked not in flat


def test_an_animation_becomes_frames_and_its_caption(text):
    rel, caption = _first_animation()
    if rel is None:
        pytest.skip("no animation with a caption in the book")
    flat = " ".join(text.split())
    words = " ".join(caption.split()[:6])
    assert words in flat, f"the caption of {rel}'s first animation is not in the PDF: {words}"
    assert "Animation, frames 1," in flat


def test_strip_outputs_of_a_player():
    """A to_jshtml-like player with 10 frames becomes frames 1, 5, 10 and the caption."""
    from PIL import Image

    pngs = []
    for shade in range(10):
        buf = io.BytesIO()
        Image.new("RGB", (40, 30), (shade * 20, 0, 0)).save(buf, format="png")
        pngs.append(base64.b64encode(buf.getvalue()).decode())
    markup = ('<img id="_anim_imgabc" alt="A red square darkening">'
              + "".join(f'frames[{i}] = "data:image/png;base64,{p}";\n'
                        for i, p in enumerate(pngs))
              + "<figcaption>The square &amp; its shade.</figcaption>")
    outputs = pdf_edition.strip_outputs(markup, 1, 0)
    assert [o.data["text/plain"] for o in outputs[:-1]] == [
        "<frame 1 of 10>", "<frame 5 of 10>", "<frame 10 of 10>"]
    assert outputs[-1].data["text/markdown"] == (
        "*Animation, frames 1, 5, 10 of 10.* The square & its shade.")
    frame = Image.open(io.BytesIO(base64.b64decode(outputs[1].data["image/png"])))
    assert frame.getpixel((5, 5))[0] == 4 * 20 and round(frame.info["dpi"][0]) == 100


def test_print_notebook_leaves_out_folded_code_panels_and_solutions():
    hidden = nbformat.v4.new_code_cell("fig = draw()")
    hidden.metadata["tags"] = ["hide-input"]
    panel = nbformat.v4.new_code_cell("rover_panel()")
    panel.metadata["tags"] = ["remove-output"]
    solution = nbformat.v4.new_code_cell("def f(x):\n    return x")
    solution.metadata["tags"] = ["solution", "hide-input"]
    margin = nbformat.v4.new_markdown_cell(
        "Text.\n\n:::{margin} Live panel\nNeeds a running kernel.\n:::\n")
    nb = nbformat.v4.new_notebook(cells=[hidden, panel, solution, margin])
    printed, changes = pdf_edition.print_notebook(nb)
    assert [c.source for c in printed.cells] == ["fig = draw()", "Text.\n\n"]
    assert "remove-input" in printed.cells[0].metadata["tags"]
    assert (changes["panels"], changes["solutions"], changes["folded"]) == (1, 1, 1)


def test_pdf_sources_have_no_player(tmp_path):
    """The transformed sources (_build/pdf_src) hold no player and no widget output."""
    src = ROOT / "_build" / "pdf_src"
    if not src.is_dir():
        pytest.fail("run `make pdf` first")
    for path in src.rglob("*.ipynb"):
        raw = path.read_text(encoding="utf-8")
        assert "_anim_img" not in raw and "widget-view+json" not in raw, path
        assert not re.search(r'"solution"', raw), path
