#!/usr/bin/env python
"""Re-execute notebooks in place, deterministically: executing twice gives no git diff.

Usage::

    python -m tools.execute_notebooks notebooks/*.ipynb        # execute, write in place
    python -m tools.execute_notebooks --check notebooks/01_conventions.ipynb
                                      # execute, write nothing, fail if the file would change
    python -m tools.execute_notebooks --normalise notebooks/*.ipynb
                                      # no execution: only rewrite in canonical form

Each notebook runs top to bottom in a fresh kernel of *this* Python environment, with its
working directory in the notebook's folder (so relative paths work), under an environment
that removes the usual sources of noise (``PYTHONHASHSEED=0``, the inline matplotlib
backend, ``SOURCE_DATE_EPOCH``, UTC, a C locale). Widget state is not stored: live panels are
tagged ``remove-output`` and the HTML book has no kernel to drive them.

Then :func:`normalise` removes what still differs between runs: timing metadata, execution
counts (renumbered 1, 2, ...), the random model ids of widget outputs and the random element
ids of matplotlib ``to_jshtml`` players (mapped, in order of appearance, to ids derived from
the notebook's name). The notebook is written with nbformat (indent 1, sorted keys, a final
newline).

A notebook fails (exit status 1, nothing written) when a cell raises, times out, or prints a
warning on stderr; the message names the notebook and the cell.

Figures are checked (``wheelkin.style.check_figure``: text too small, overlapping, or leaving
the figure) in every notebook that calls ``wheelkin.style.setup()``: the kernel runs with
``WHEELKIN_CHECK_FIGURES=1``, and ``style.setup()`` then checks every figure a cell shows and
``wheelkin.animation.show`` every frame of every animation; a problem is an
error in that cell (``FigureCheckError: ...`` naming the texts). Notebooks still in
first-edition form do not call ``style.setup()`` and are not checked. ``--no-figure-check``
turns the check off for a run.

Notebooks may sit in chapter folders (``notebooks/03_rover/01_geometry.ipynb``): the ids that
:func:`normalise` derives are seeded with the path below ``notebooks/`` (``03_rover/01_geometry``),
so they stay unique across the book.
"""

from __future__ import annotations

import argparse
import copy
import difflib
import hashlib
import os
import re
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import nbformat

from tools.book_pages import notebook_id

#: Environment of the kernel (and of nbval's kernel: the Makefile exports the same values).
DETERMINISTIC_ENV = {
    "PYTHONHASHSEED": "0",
    "MPLBACKEND": "module://matplotlib_inline.backend_inline",
    "SOURCE_DATE_EPOCH": "1767225600",  # 2026-01-01T00:00:00Z, for any embedded date
    "TZ": "UTC",
    "LC_ALL": "C.UTF-8",
    "PYDEVD_DISABLE_FILE_VALIDATION": "1",  # silences debugpy's "frozen modules" notice
}
#: Set to "1" in the kernel's environment: wheelkin.style.setup() then checks every figure.
FIGURE_CHECK_ENV = "WHEELKIN_CHECK_FIGURES"

KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"
#: Cell metadata that records when or how long a cell ran.
TIMING_KEYS = ("execution", "ExecuteTime", "papermill")
#: A random id from uuid.uuid4().hex (the version nibble is 4, the variant nibble 8-b).
UUID4_HEX = re.compile(r"\b[0-9a-f]{12}4[0-9a-f]{3}[89ab][0-9a-f]{15}\b")
#: The element id of a to_jshtml player (matplotlib's template names its <img> _anim_img<id>).
PLAYER_ID = re.compile(r"_anim_img([0-9a-f]{32})")
WARNING_WORDS = re.compile(r"warning", re.IGNORECASE)


class NotebookFailure(Exception):
    """A notebook that did not run cleanly (the message names the notebook and the cell)."""


def stable_hex(*parts: str) -> str:
    """A 32-hex-digit id derived from ``parts`` (same parts, same id)."""
    return hashlib.md5("/".join(parts).encode()).hexdigest()


def _replace_in(obj, mapping: dict[str, str]):
    """A copy of a JSON-like object with every mapped id replaced inside its strings."""
    if not mapping:
        return obj
    if isinstance(obj, str):
        for old, new in mapping.items():
            if old in obj:
                obj = obj.replace(old, new)
        return obj
    if isinstance(obj, list):
        return [_replace_in(v, mapping) for v in obj]
    if isinstance(obj, dict):
        return type(obj)((_replace_in(k, mapping), _replace_in(v, mapping))
                         for k, v in obj.items())
    return obj


def _join(text) -> str:
    return "".join(text) if isinstance(text, list) else str(text)


def _merge_streams(outputs: list) -> list:
    """Join consecutive stdout (or stderr) outputs into one.

    The kernel flushes its streams on a timer, so one ``print`` can arrive as two messages
    ("rank =" and " 2\\n") on one run and as one on the next. Merged, the stored text is the
    same either way (nbval compares merged streams too).
    """
    merged: list = []
    for output in outputs:
        previous = merged[-1] if merged else None
        if (output.get("output_type") == "stream" and previous is not None
                and previous.get("output_type") == "stream"
                and previous.get("name") == output.get("name")):
            previous["text"] = _join(previous.get("text", "")) + _join(output.get("text", ""))
        else:
            merged.append(output)
    return merged


def normalise(nb: nbformat.NotebookNode, name: str) -> nbformat.NotebookNode:
    """Return ``nb`` in canonical form: the same however often and wherever it was executed.

    ``name`` (the notebook's path below ``notebooks/`` without suffix, ``notebook_id``) seeds
    the replacement ids, so that ids stay unique across the pages of the book.
    """
    nb = copy.deepcopy(nb)
    nb.metadata.pop("widgets", None)
    nb.metadata.pop("papermill", None)
    nb.metadata["kernelspec"] = dict(KERNELSPEC)
    nb.nbformat, nb.nbformat_minor = 4, max(5, nb.get("nbformat_minor", 5))  # 4.5: cell ids

    mapping: dict[str, str] = {}
    widgets = players = 0
    count = 0
    for index, cell in enumerate(nb.cells):
        for key in TIMING_KEYS:
            cell.metadata.pop(key, None)
        if "id" not in cell or not cell.id:
            cell.id = stable_hex(name, "cell", str(index))[:8]
        if cell.cell_type != "code":
            continue
        if cell.get("execution_count") is not None:
            count += 1
            cell.execution_count = count
        cell.outputs = _merge_streams(cell.get("outputs", []))
        for output in cell.get("outputs", []):
            if output.get("output_type") == "execute_result":
                output.execution_count = cell.execution_count
            data = output.get("data", {})
            view = data.get(WIDGET_VIEW)
            if isinstance(view, dict) and isinstance(view.get("model_id"), str):
                old = view["model_id"]
                if old not in mapping:
                    mapping[old] = stable_hex(name, "widget", str(widgets))
                    widgets += 1
            for player in PLAYER_ID.findall(_join(data.get("text/html", ""))):
                if player not in mapping:
                    new = stable_hex(name, "animation", str(players))
                    players += 1
                    if UUID4_HEX.fullmatch(player):  # random: matplotlib's own uuid4 id
                        mapping[player] = new
    nb.cells = nbformat.from_dict(_replace_in(nb.cells, mapping))
    return nb


def dumps(nb: nbformat.NotebookNode) -> str:
    """The notebook as text: nbformat's JSON (indent 1, sorted keys) and a final newline."""
    text = nbformat.writes(nb, version=4)
    return text if text.endswith("\n") else text + "\n"


def problems(nb: nbformat.NotebookNode) -> list[str]:
    """Error outputs and warnings printed on stderr, as 'cell N: ...' lines."""
    found = []
    for index, cell in enumerate(nb.cells):
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                found.append(f"cell {index}: {output.get('ename')}: {output.get('evalue')}")
            elif output.get("output_type") == "stream" and output.get("name") == "stderr":
                text = _join(output.get("text", ""))
                if WARNING_WORDS.search(text):
                    first = next(line for line in text.splitlines() if WARNING_WORDS.search(line))
                    found.append(f"cell {index} printed a warning on stderr: {first.strip()}")
    return found


def _kernel_manager_class(socket_dir: str):
    """A kernel manager starting ipykernel with *this* interpreter, over IPC sockets.

    The sockets live in ``socket_dir`` (an absolute path: the kernel runs in the notebook's
    folder, this process in the repository's).
    """
    from ipykernel.kernelspec import RESOURCES, get_kernel_dict
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    class CurrentEnvironment(KernelSpecManager):
        def get_kernel_spec(self, kernel_name):
            return self.kernel_spec_class(resource_dir=RESOURCES, **get_kernel_dict())

    class Manager(KernelManager):
        def __init__(self, **kwargs):
            kwargs.setdefault("kernel_spec_manager", CurrentEnvironment())
            kwargs.setdefault("transport", "ipc")  # local sockets: nothing listens on TCP
            kwargs.setdefault("ip", os.path.join(socket_dir, "kernel"))
            super().__init__(**kwargs)

    return Manager


def execute(path: Path, cell_timeout: int, check_figures: bool = True) -> nbformat.NotebookNode:
    """Run the notebook at ``path`` in a fresh kernel; return it normalised (not written)."""
    os.environ.update(DETERMINISTIC_ENV)
    os.environ[FIGURE_CHECK_ENV] = "1" if check_figures else "0"
    nb = nbformat.read(path, as_version=4)
    current = {"index": None}
    with tempfile.TemporaryDirectory(prefix="wheelkin-kernel-") as socket_dir:
        _execute(nb, path, cell_timeout, socket_dir, current)
    found = problems(nb)
    if found:
        raise NotebookFailure(f"{path}: " + "; ".join(found))
    return normalise(nb, notebook_id(path))


def _execute(nb, path: Path, cell_timeout: int, socket_dir: str, current: dict) -> None:
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

    client = NotebookClient(
        nb,
        kernel_manager_class=_kernel_manager_class(socket_dir),
        kernel_name="python3",
        timeout=cell_timeout,
        startup_timeout=60,
        allow_errors=False,
        record_timing=False,
        store_widget_state=False,
        resources={"metadata": {"path": str(path.parent.resolve())}},
        on_cell_start=lambda cell, cell_index: current.update(index=cell_index),
    )
    try:
        client.execute()
    except CellTimeoutError:
        raise NotebookFailure(f"{path}: cell {current['index']} ran longer than "
                              f"{cell_timeout} s") from None
    except CellExecutionError as exc:
        summary = f"{exc.ename}: {exc.evalue}" if getattr(exc, "ename", None) else str(exc)
        raise NotebookFailure(f"{path}: cell {current['index']} raised {summary}\n{exc}") from None
    except DeadKernelError as exc:
        raise NotebookFailure(f"{path}: the kernel died in cell {current['index']}: "
                              f"{exc}") from None


def _run_one(path_text: str, cell_timeout: int, check: bool,
             check_figures: bool = True) -> tuple[str, str, float]:
    """Worker: execute one notebook; return (path, status, seconds). Status 'FAIL ...' on error."""
    path = Path(path_text)
    start = time.perf_counter()
    try:
        text = dumps(execute(path, cell_timeout, check_figures))
    except NotebookFailure as exc:
        return path_text, f"FAIL {exc}", time.perf_counter() - start
    except Exception as exc:
        return path_text, f"FAIL {path}: {type(exc).__name__}: {exc}", time.perf_counter() - start
    old = path.read_text(encoding="utf-8")
    seconds = time.perf_counter() - start
    if text == old:
        return path_text, "unchanged", seconds
    if check:
        diff = difflib.unified_diff(old.splitlines(), text.splitlines(), "stored", "re-executed",
                                    n=1, lineterm="")
        lines = list(diff)
        shown = "\n".join(lines[:40]) + ("\n..." if len(lines) > 40 else "")
        return path_text, f"FAIL {path}: re-execution changes the stored file:\n{shown}", seconds
    path.write_text(text, encoding="utf-8")
    return path_text, "updated", seconds


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("notebooks", nargs="+", type=Path)
    parser.add_argument("--timeout", type=int, default=300, help="seconds per cell (300)")
    parser.add_argument("-j", "--jobs", type=int, default=2, help="notebooks at once (2)")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; fail if re-execution would change a file")
    parser.add_argument("--normalise", action="store_true",
                        help="do not execute; only rewrite each file in canonical form")
    parser.add_argument("--no-figure-check", action="store_true",
                        help="do not check the figures of notebooks that call style.setup()")
    args = parser.parse_args(argv)
    paths = [p for p in args.notebooks if p.suffix == ".ipynb"]
    missing = [str(p) for p in paths if not p.is_file()]
    if missing or not paths:
        print(f"execute_notebooks: no such notebook: {', '.join(missing) or args.notebooks}",
              file=sys.stderr)
        return 1
    if args.normalise:
        for path in paths:
            text = dumps(normalise(nbformat.read(path, as_version=4), notebook_id(path)))
            if text != path.read_text(encoding="utf-8"):
                path.write_text(text, encoding="utf-8")
                print(f"normalised {path}")
        return 0

    start = time.perf_counter()
    failures = 0
    jobs = max(1, min(args.jobs, len(paths)))
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(_run_one, str(p), args.timeout, args.check,
                               not args.no_figure_check) for p in paths]
        for future in futures:
            path, status, seconds = future.result()
            if status.startswith("FAIL"):
                failures += 1
                print(f"FAILED  {path} ({seconds:.1f} s)\n        {status[5:]}", file=sys.stderr,
                      flush=True)
            else:
                print(f"{status:9s} {path} ({seconds:.1f} s)", flush=True)
    total = time.perf_counter() - start
    print(f"execute_notebooks: {len(paths) - failures} ok, {failures} failed, {total:.1f} s "
          f"with {jobs} at once")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
