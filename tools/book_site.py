"""Where the built book is, which pages it has, how it is served and how chromium is
started."""

from __future__ import annotations

import functools
import http.server
import os
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from tools.book_pages import NON_CHAPTER_NOTEBOOKS, toc_files  # noqa: F401

ROOT = Path(__file__).resolve().parents[1]

#: The built book: _build/html, or the folder named by WHEELKIN_SITE (a build of one's own,
#: e.g. `jupyter-book build . --path-output /tmp/x` then WHEELKIN_SITE=/tmp/x/_build/html).
SITE = Path(os.environ.get("WHEELKIN_SITE") or ROOT / "_build" / "html")
SCREENSHOTS = ROOT / "_build" / "screenshots"
CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--no-sandbox",  # CI runs as root
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-quic",
]
PAGES = toc_files()
IN_CI = os.environ.get("CI", "").lower() in ("1", "true", "yes")

#: Console errors that are known upstream noise, as (substring, why it is harmless). Keep this
#: list short and explain every entry; an error that is ours must be fixed, not listed here.
ALLOWED_CONSOLE_ERRORS: list[tuple[str, str]] = []


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):
        pass


class _QuietServer(http.server.ThreadingHTTPServer):
    def handle_error(self, request, client_address):
        pass  # the browser closed a connection it no longer needed (a page was closed)


@contextmanager
def serve(folder: Path) -> Iterator[str]:
    """``folder`` (a built site) served on a free port of 127.0.0.1, in a thread of this
    process, until the block ends; yields its URL (ends with /)."""
    handler = functools.partial(_QuietHandler, directory=str(folder))
    server = _QuietServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()
