"""The book says how it may be reused: licences, citation, and editions an instructor can pin.

Code under MIT (LICENSE), text and figures under CC BY 4.0 (LICENSE-CONTENT), both named in the
README and on the reuse page; CITATION.cff is valid CFF 1.2 with the code's licence; every
edition that CHANGELOG.md gives a commit for names a commit of this repository (a course can
check it out). The footer of every built page is checked in tests/browser/test_licence_footer.py.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]


def test_code_is_mit_and_content_is_cc_by():
    code = (ROOT / "LICENSE").read_text(encoding="utf-8")
    content = (ROOT / "LICENSE-CONTENT").read_text(encoding="utf-8")
    assert code.startswith("MIT License")
    assert "Permission is hereby granted, free of charge" in code
    assert "Creative Commons Attribution 4.0 International Public License" in content
    # The full legal code, not a pointer to it: its last section and its closing notice.
    assert "Section 8 -- Interpretation." in content
    assert "Creative Commons may be contacted at creativecommons.org." in content


def test_readme_and_reuse_page_name_both_licences():
    for page in ("README.md", "book/reuse.md"):
        text = (ROOT / page).read_text(encoding="utf-8")
        for needle in ("CC BY 4.0", "MIT", "LICENSE-CONTENT", "LICENSE", "CITATION.cff"):
            assert needle in text, f"{page} does not mention {needle}"
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    assert "file: book/reuse" in toc, "the reuse page is not in the book"


def test_citation_file_is_cff_1_2_with_the_code_licence():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0"
    for key in ("message", "title", "authors", "version", "license"):
        assert cff.get(key), f"CITATION.cff lacks {key}"
    assert cff["license"] == "MIT"
    assert all("name" in a or "family-names" in a for a in cff["authors"])


def test_every_pinned_edition_is_a_commit_of_this_repository():
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    editions = re.findall(r"^## Edition (\d+) \([^)]*commit ([0-9a-f]{7,40})", changelog, re.M)
    assert len(editions) >= 2, "CHANGELOG.md pins fewer than two editions to a commit"
    for number, sha in editions:
        result = subprocess.run(["git", "-C", str(ROOT), "cat-file", "-t", sha],
                                capture_output=True, text=True, check=False)
        if result.returncode != 0 and "not a git repository" in result.stderr:
            return  # an unpacked archive without history: nothing to check against
        assert result.stdout.strip() == "commit", f"edition {number}: {sha} is not a commit"
