"""The printed edition (``make pdf``: tools/pdf_edition.py builds _build/pdf/wheelkin.pdf, then
runs these tests, the ``pdf`` layer of ``make test``).

Collected only when pytest is pointed at ``tests/pdf`` (or a file in it), never by the library
layer's ``pytest tests``: most tests read the built PDF. ``WHEELKIN_PDF`` names another PDF to
check (the tests' own defects are planted in copies).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.pdf.printed_pdf import Printed, read_pdf
from tools.book_pages import book_structure

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def pytest_ignore_collect(collection_path, config):
    asked = [Path(str(a).split("::")[0]).resolve() for a in config.args]
    if any(a == HERE or HERE in a.parents for a in asked):
        return None
    path = collection_path.resolve()
    if path == HERE or HERE in path.parents:
        return True
    return None


@pytest.fixture(scope="session")
def pdf_path() -> Path:
    path = Path(os.environ.get("WHEELKIN_PDF") or ROOT / "_build" / "pdf" / "wheelkin.pdf")
    if not path.is_file():
        pytest.fail(f"{path} is missing: run `make pdf`")
    return path


@pytest.fixture(scope="session")
def printed(pdf_path) -> Printed:
    return read_pdf(pdf_path)


@pytest.fixture(scope="session")
def structure():
    return book_structure(ROOT / "_toc.yml")
