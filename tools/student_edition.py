#!/usr/bin/env python
"""The student edition: every notebook of the book without its solutions, executed, and a web
edition built from them.

Usage::

    python -m tools.student_edition [--out _build/student] [--no-html] [-j 2]
    make student

For every notebook that ``_toc.yml`` lists (chapters and their sections, at any depth):

- cells tagged ``solution`` are removed, with their outputs;
- cells tagged ``solution-note`` are removed: a sentence pointing at a folded solution, or a
  cell that gives an exercise's answer or judgement (the numbers of a design question's
  verdict, our choices for a design); in other markdown cells, a sentence such as "the
  solution is folded below" is removed (the fallback for cells not yet tagged);
- an exercise's statement is never removed: a ``solution-note`` or ``solution`` cell that holds
  an exercise's heading (``## Exercise 2``, ``**Exercise 2.**``, ``**2. ...**``) is an error,
  since the student would get a stub without its task (``tests/kit/test_student_tasks.py``
  checks every exercise's statement, and that nothing after a stub gives its answer away);
- the notebook is executed top to bottom in a fresh kernel (as ``tools/execute_notebooks.py``
  does: deterministic, failing on an error or a warning), so every cell has its output, and an
  unfinished exercise does not stop it (its ``check`` reports "not written yet");
- the exercise stubs (``exercise``) are kept, their outputs cleared, ready to be written.

While executing, the tool looks at the notebook's global names before each exercise stub and
records the short or generic ones (``a``, ``ax``, ``fig`` ...) with the cell that made them
(``stray_globals.json``): a student's undefined name must raise a plain ``NameError``.

The pages (``book/``, landing pages) are copied as they are, except this book's instructors'
page, and ``jupyter-book`` builds the student web edition into ``<out>/html``.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import nbformat
import yaml

from tools.book_pages import toc_files

ROOT = Path(__file__).resolve().parents[1]

#: Pages of the teacher's book that the student edition leaves out.
INSTRUCTOR_PAGES = ("book/instructors",)
#: A sentence that points at a folded solution (the fallback when a cell is not tagged
#: ``solution-note``): it mentions a solution and folding, hiding or "below".
SOLUTION_SENTENCE = re.compile(
    r"(?:(?<=[.!?])\s+|(?<=[.!?][)\]])\s+|^)"             # where a sentence starts
    r"[^.!?]*?\bsolutions?\b[^.!?]*?\b(?:folded|fold|hidden|collapsed|below)\b[^.!?]*[.!?]",
    re.IGNORECASE)
#: The same in parentheses: "(the solution is folded below)".
SOLUTION_ASIDE = re.compile(
    r"[ \t]*\([^()]*\bsolutions?\b[^()]*\b(?:folded|fold|hidden|collapsed|below)\b[^()]*\)",
    re.IGNORECASE)
#: An exercise's heading or bold lead: the start of a statement, which is never removed.
EXERCISE_LEAD = re.compile(
    r"^(?:#{1,4}[ \t]+Exercise\b|\*\*(?:Exercise\b|\d+(?:[.:)]| \()))", re.M)
#: Global names a hidden cell must not leave behind (besides every single letter).
GENERIC_NAMES = frozenset({
    "fig", "ax", "axs", "axes", "ani", "anim", "line", "lines", "t", "ts", "xs", "ys", "zs",
    "im", "img", "sc", "cb", "cbar", "data", "df", "res", "result", "tmp", "val", "idx",
    "frame", "frames", "artist", "artists", "handles", "label", "labels", "text", "patch",
    "row", "col", "out", "arr", "grid", "dt", "dx", "dy", "pts", "xy", "xx", "yy",
})
#: Tags of cells whose code the reader does not see.
HIDDEN_TAGS = {"hide-input", "remove-input", "remove-cell", "hide-cell"}


def _tags(cell) -> set[str]:
    return set(cell.get("metadata", {}).get("tags", []))


def is_stray(name: str) -> bool:
    """Whether ``name`` is a short or generic global that could shadow a student's typo."""
    return (len(name) == 1 and name.isalpha()) or name in GENERIC_NAMES


def toc_notebooks(root: Path = ROOT) -> list[Path]:
    """Every notebook the table of contents lists, in reading order (paths from ``root``)."""
    return [Path(page + ".ipynb") for page in toc_files(root / "_toc.yml")
            if (root / (page + ".ipynb")).is_file()]


_LABEL_LINE = re.compile(r"^[ \t]*\([\w-]+\)=[ \t]*$")


def remove_solution_sentences(text: str) -> str:
    """``text`` without sentences that point at a folded solution."""
    text = SOLUTION_ASIDE.sub("", text)
    out, para = [], []

    def flush() -> None:
        if para:
            joined = "\n".join(para)
            new = SOLUTION_SENTENCE.sub("", joined).lstrip(" ")
            if new.strip() or not joined.strip():
                out.append(new)
            para.clear()

    for line in text.split("\n"):  # paragraphs: runs of lines, headings on their own
        if not line.strip() or line.lstrip().startswith(("#", ":::", "```")) \
                or _LABEL_LINE.match(line):
            flush()
            out.append(line)
        else:
            para.append(line)
    flush()
    return "\n".join(out)


def student_notebook(nb: nbformat.NotebookNode) -> tuple[nbformat.NotebookNode, dict]:
    """The student's copy of ``nb`` (not executed) and what was changed, counted."""
    nb = nbformat.from_dict(json.loads(json.dumps(nb)))
    changes = {"solutions": 0, "notes": 0, "sentences": 0, "exercises": 0}
    cells = []
    for index, cell in enumerate(nb.cells):
        tags = _tags(cell)
        if tags & {"solution", "solution-note"} and cell.cell_type == "markdown" \
                and EXERCISE_LEAD.search(cell.source):
            raise ValueError(
                f"cell {index} is tagged {sorted(tags & {'solution', 'solution-note'})} but holds "
                f"an exercise's statement ({EXERCISE_LEAD.search(cell.source).group(0)!r}): the "
                "student edition would delete the task; split the cell or untag it")
        if "solution" in tags:
            changes["solutions"] += 1
            continue
        if "solution-note" in tags:
            # Whole: a pointer, an answer or a verdict. A task tagged so was refused above.
            changes["notes"] += 1
            continue
        if cell.cell_type == "markdown":
            new = remove_solution_sentences(cell.source)
            if new != cell.source:
                changes["sentences"] += 1
                cell.source = new
        if "exercise" in tags:
            changes["exercises"] += 1
        cells.append(cell)
    nb.cells = cells
    return nb, changes


# ----------------------------------------------------------------------------- execution

PROBE = (
    "import json as _j, types as _t\n"
    "print('WHEELKIN-PROBE' + _j.dumps({k: id(v) for k, v in list(globals().items())"
    " if not k.startswith('_') and not isinstance(v, _t.ModuleType)"
    " and k not in ('In', 'Out', 'exit', 'quit', 'get_ipython')}))\n"
    "del _j, _t"
)


def execute_student(path: Path, name: str, cell_timeout: int = 300) -> dict:
    """Execute the student notebook at ``path`` in place; return the stray globals found
    before each exercise stub: ``{"cell N": {name: {"cell": M, "hidden": bool}}}``.

    Raises ``execute_notebooks.NotebookFailure`` when a cell raises or prints a warning.
    """
    import os

    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError, CellTimeoutError

    from tools.execute_notebooks import (
        DETERMINISTIC_ENV,
        NotebookFailure,
        _kernel_manager_class,
        dumps,
        normalise,
        problems,
    )

    os.environ.update(DETERMINISTIC_ENV)
    nb = nbformat.read(path, as_version=4)
    stray: dict[str, dict] = {}
    bound: dict[str, tuple[int, int]] = {}  # name -> (cell that bound it, id of the value)
    with tempfile.TemporaryDirectory(prefix="wheelkin-student-") as sockets:
        client = NotebookClient(
            nb, kernel_manager_class=_kernel_manager_class(sockets), kernel_name="python3",
            timeout=cell_timeout, startup_timeout=60, allow_errors=False, record_timing=False,
            store_widget_state=False, resources={"metadata": {"path": str(path.parent)}})
        probe_cell = nbformat.v4.new_code_cell(PROBE)

        def probe() -> dict[str, int]:
            probe_cell.outputs = []
            nb.cells.append(probe_cell)
            try:
                client.execute_cell(probe_cell, len(nb.cells) - 1)
            finally:
                nb.cells.pop()
            text = "".join(o.get("text", "") for o in probe_cell.outputs
                           if o.get("output_type") == "stream")
            line = next(x for x in text.splitlines() if x.startswith("WHEELKIN-PROBE"))
            return json.loads(line[len("WHEELKIN-PROBE"):])

        with client.setup_kernel():
            for index, cell in enumerate(list(nb.cells)):
                if cell.cell_type != "code":
                    continue
                if "exercise" in _tags(cell):
                    found = {k: {"cell": bound[k][0], "hidden": bool(
                        _tags(nb.cells[bound[k][0]]) & HIDDEN_TAGS)}
                        for k in sorted(bound) if is_stray(k)}
                    if found:
                        stray[f"cell {index}"] = found
                try:
                    client.execute_cell(cell, index)
                except CellTimeoutError:
                    raise NotebookFailure(f"{path}: cell {index} ran longer than "
                                          f"{cell_timeout} s") from None
                except CellExecutionError as exc:
                    raise NotebookFailure(f"{path}: cell {index} raised {exc.ename}: "
                                          f"{exc.evalue}") from None
                now = probe()
                for key, ident in now.items():
                    if key not in bound or bound[key][1] != ident:
                        bound[key] = (index, ident)
                for key in [k for k in bound if k not in now]:  # deleted by the cell
                    del bound[key]
    found = problems(nb)
    if found:
        raise NotebookFailure(f"{path}: " + "; ".join(found))
    nb = normalise(nb, name)
    for cell in nb.cells:
        if cell.cell_type == "code" and "exercise" in _tags(cell):
            cell.outputs, cell.execution_count = [], None
    path.write_text(dumps(nb), encoding="utf-8")
    return stray


def _execute_one(args: tuple[str, str]) -> tuple[str, dict | str, float]:
    path, name = args
    start = time.perf_counter()
    try:
        stray = execute_student(Path(path), name)
    except Exception as exc:
        return path, f"FAIL {exc}", time.perf_counter() - start
    return path, stray, time.perf_counter() - start


# ----------------------------------------------------------------------------- the edition

def student_toc(toc: dict) -> dict:
    """The table of contents without the instructors' pages."""
    def keep(node):
        if isinstance(node, list):
            return [keep(n) for n in node if not (isinstance(n, dict) and str(
                n.get("file", "")).removesuffix(".md") in INSTRUCTOR_PAGES)]
        if isinstance(node, dict):
            return {k: keep(v) for k, v in node.items()}
        return node
    return keep(toc)


def copy_sources(out: Path, notebooks: list[Path]) -> None:
    """The book's pages and configuration into ``out`` (notebooks are written separately)."""
    out.mkdir(parents=True, exist_ok=True)
    for page in toc_files(ROOT / "_toc.yml"):
        if page in INSTRUCTOR_PAGES:
            continue
        for suffix in (".md", ".rst"):
            src = ROOT / (page + suffix)
            if src.is_file():
                (out / page).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, out / (page + suffix))
    shutil.copytree(ROOT / "book", out / "book", dirs_exist_ok=True,
                    ignore=shutil.ignore_patterns("instructors.md"))
    (out / "tools").mkdir(exist_ok=True)
    for helper in (ROOT / "tools").glob("*.py"):  # the Sphinx extensions and their helpers
        shutil.copy2(helper, out / "tools" / helper.name)
    if (ROOT / "_vendor").is_dir():
        shutil.copytree(ROOT / "_vendor", out / "_vendor", dirs_exist_ok=True)
    copy_includes(out)
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    (out / "_toc.yml").write_text(yaml.safe_dump(student_toc(toc), sort_keys=False),
                                  encoding="utf-8")
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    config["title"] = f"{config.get('title', 'wheelkin')} (student edition)"
    config["exclude_patterns"] = [*config.get("exclude_patterns", []), "html",
                                  "stray_globals.json", "html-warnings.txt"]
    (out / "_config.yml").write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")


_INCLUDE = re.compile(r"^(?:```|:::)\{(?:include|literalinclude)\}\s+(\S+)", re.M)


def copy_includes(out: Path) -> None:
    """Files that the copied pages include (``{include}``), e.g. benchmarks/RESULTS.md."""
    for page in list(out.rglob("*.md")):
        for target in _INCLUDE.findall(page.read_text(encoding="utf-8")):
            rel = (page.parent.relative_to(out) / target)
            src = (ROOT / rel).resolve()
            if src.is_file() and ROOT in src.parents:
                dest = out / src.relative_to(ROOT)
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, dest)


def build_html(out: Path) -> Path:
    """Build the student web edition of ``out`` into ``out/html``.

    Not with ``-W``: the book's own warnings fail ``make book``, not the student edition.
    Sphinx's warnings are kept in ``out/html-warnings.txt`` and counted.
    """
    jb = Path(sys.executable).with_name("jupyter-book")
    with tempfile.TemporaryDirectory(prefix="wheelkin-student-html-") as tmp:
        done = subprocess.run([str(jb), "build", str(out), "--path-output", tmp, "-n",
                               "--keep-going", "--quiet"], capture_output=True, text=True,
                              check=False)
        warnings = [line for line in (done.stdout + done.stderr).splitlines()
                    if "WARNING" in line or "ERROR" in line or "CRITICAL" in line]
        (out / "html-warnings.txt").write_text("\n".join(warnings) + "\n", encoding="utf-8")
        built = Path(tmp) / "_build" / "html"
        if done.returncode != 0 or not (built / "index.html").is_file():
            raise RuntimeError("the student web edition did not build:\n"
                               + (done.stdout + done.stderr)[-3000:])
        target = out / "html"
        shutil.rmtree(target, ignore_errors=True)
        shutil.copytree(built, target)
    if warnings:
        print(f"student_edition: {len(warnings)} Sphinx warnings (html-warnings.txt)")
    return target


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "_build" / "student")
    parser.add_argument("--no-html", action="store_true", help="notebooks only")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    parser.add_argument("--only", nargs="*", type=Path,
                        help="only these notebooks (paths from the repository)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    out = args.out.resolve()
    notebooks = toc_notebooks()
    if args.only:
        wanted = {p.as_posix() for p in args.only}
        notebooks = [p for p in notebooks if p.as_posix() in wanted]
    shutil.rmtree(out, ignore_errors=True)
    copy_sources(out, notebooks)
    summary = {}
    for rel in notebooks:
        nb, changes = student_notebook(nbformat.read(ROOT / rel, as_version=4))
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(nb, out / rel)
        summary[rel.as_posix()] = changes
        print(f"student {rel}: {changes['solutions']} solutions removed, "
              f"{changes['notes'] + changes['sentences']} notes adjusted, "
              f"{changes['exercises']} exercises", flush=True)
    failures, stray = 0, {}
    # A notebook without exercises or solutions is the book's own, whose stored outputs strict
    # nbval re-checks; only the notebooks that changed are executed again.
    changed = [rel for rel in notebooks if any(summary[rel.as_posix()].values())]
    for rel in notebooks:
        if rel not in changed:
            print(f"kept    {rel} (no exercise: the book's executed outputs)", flush=True)
    jobs = [(str(out / rel), rel.with_suffix("").as_posix().replace("/", "-"))
            for rel in changed]
    with ProcessPoolExecutor(max_workers=max(1, min(args.jobs, len(jobs) or 1))) as pool:
        for path, found, seconds in pool.map(_execute_one, jobs):
            rel = Path(path).relative_to(out).as_posix()
            if isinstance(found, str):
                failures += 1
                print(f"FAILED  {rel} ({seconds:.1f} s)\n        {found[5:]}", file=sys.stderr,
                      flush=True)
                continue
            stray[rel] = found
            names = sorted({n for at in found.values() for n in at})
            print(f"executed {rel} ({seconds:.1f} s)"
                  + (f"; stray globals before an exercise: {', '.join(names)}" if names else ""),
                  flush=True)
    (out / "stray_globals.json").write_text(json.dumps(stray, indent=1, sort_keys=True) + "\n",
                                            encoding="utf-8")
    if failures:
        print(f"student_edition: {failures} notebooks failed", file=sys.stderr)
        return 1
    if not args.no_html:
        html = build_html(out)
        print(f"student_edition: web edition in {html}")
    print(f"student_edition: {len(notebooks)} notebooks in {out} "
          f"({time.perf_counter() - start:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
