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

from tests.own_layer import ignored_unless_asked
from tests.pdf.printed_pdf import Printed, read_pdf
from tools.book_pages import book_structure

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def pytest_ignore_collect(collection_path, config):
    return ignored_unless_asked(HERE, collection_path, config)


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
