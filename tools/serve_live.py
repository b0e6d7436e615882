#!/usr/bin/env python
"""Serve the built book with live pages: its code cells and panels run in a local kernel.

``make serve-live`` runs this after building the book (if it is not built) and installing the
lab stack (``requirements-lab.txt`` brings ``jupyter_server``). It

1. starts a Jupyter server with the book's kernel (the venv's ``python3``) on 127.0.0.1, in
   ``notebooks/`` (a page's kernel runs in its notebook's folder, as when the notebooks were
   executed), with a random token, only the site's origin allowed (CORS and WebSockets), no
   browser opened, idle kernels culled after 30 minutes, its log in ``_build/serve-live.log``;
2. serves the built site (``_build/html``) on 127.0.0.1, adding to every notebook's page a
   small configuration (the server's URL and token, the page's notebook), ``book/_live/live.js``
   and ``live.css`` (the "Make this page live" control), and serving Thebe from
   ``_vendor_live/`` (``tools/vendor_assets.py``) at ``/_live/thebe/``;
3. prints one URL, and on Ctrl-C (or SIGTERM) stops the site and the Jupyter server with its
   kernels.

The plain site (``make book``, ``make serve``) has none of this: the pages carry no live
control, and nothing in them refers to ``/_live/``.

Usage: ``python -m tools.serve_live [--port 8001] [--kernel-port 8889] [--site DIR]``; a port
of 0 takes a free one. Run as root (CI, a container), the Jupyter server needs ``--allow-root``,
which is passed then.
"""

from __future__ import annotations

import argparse
import functools
import http.server
import json
import os
import secrets
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path
from urllib.parse import unquote, urlsplit

from tools.vendor_assets import VENDOR_LIVE, live_complete

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "_build" / "html"
LIVE_ASSETS = ROOT / "book" / "_live"

NOTEBOOKS = ROOT / "notebooks"
LOG = ROOT / "_build" / "serve-live.log"
KERNEL_NAME = "python3"
#: The environment of a live kernel: the notebooks' own (tools/execute_notebooks.py, NB_ENV).
KERNEL_ENV = {"PYTHONHASHSEED": "0", "MPLBACKEND": "module://matplotlib_inline.backend_inline",
              "PYDEVD_DISABLE_FILE_VALIDATION": "1"}
#: Marks a notebook's page: myst-nb's code cell container.
_CODE_CELL = '<div class="cell'


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def notebook_of(page: str) -> str | None:
    """The notebook (relative to notebooks/) of a site page such as ``notebooks/05_x/02_y.html``."""
    parts = Path(page).with_suffix(".ipynb").parts
    if len(parts) < 2 or parts[0] != "notebooks":
        return None
    rel = Path(*parts[1:])
    return rel.as_posix() if (NOTEBOOKS / rel).is_file() else None


def live_head(config: dict) -> str:
    """What a live page gets before ``</head>``: the configuration, the script and the style."""
    data = json.dumps(config).replace("</", "<\\/")
    return (f'<script type="application/json" id="wk-live-config">{data}</script>\n'
            '<link rel="stylesheet" href="/_live/live.css">\n'
            '<script defer src="/_live/live.js"></script>\n')


class JupyterServer:
    """A Jupyter server for the live pages, in its own process group."""

    def __init__(self, port: int, token: str, origin: str, log: Path = LOG) -> None:
        self.port, self.token, self.origin = port, token, origin
        self.url = f"http://127.0.0.1:{port}"
        log.parent.mkdir(parents=True, exist_ok=True)
        self._log = open(log, "w", encoding="utf-8")
        command = [
            sys.executable, "-m", "jupyter_server",
            "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={port}", "--ServerApp.port_retries=0",
            "--ServerApp.open_browser=False", f"--ServerApp.root_dir={NOTEBOOKS}",
            f"--IdentityProvider.token={token}", f"--ServerApp.allow_origin={origin}",
            "--ServerApp.allow_credentials=False",
            f"--MappingKernelManager.default_kernel_name={KERNEL_NAME}",
            "--MappingKernelManager.cull_idle_timeout=1800",
            "--MappingKernelManager.cull_interval=300",
            "--ServerApp.terminals_enabled=False",
        ]
        if os.geteuid() == 0:
            command.append("--allow-root")  # a container or CI runs as root
        env = {**os.environ, **KERNEL_ENV}
        self.process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=self._log,
                                        stderr=subprocess.STDOUT, env=env, cwd=NOTEBOOKS,
                                        start_new_session=True)

    def wait_ready(self, timeout: float = 60.0) -> None:
        deadline = time.monotonic() + timeout
        url = f"{self.url}/api/status"
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"the Jupyter server stopped (exit {self.process.returncode})"
                                   f"; see {LOG}")
            try:
                request = urllib.request.Request(url, headers={"Authorization":
                                                               f"token {self.token}"})
                with urllib.request.urlopen(request, timeout=2) as response:
                    if response.status == 200:
                        return
            except (urllib.error.URLError, OSError):
                pass
            time.sleep(0.2)
        raise RuntimeError(f"the Jupyter server did not answer in {timeout:.0f} s; see {LOG}")

    def stop(self, timeout: float = 15.0) -> None:
        """SIGTERM (the server shuts its kernels down), then SIGKILL if it lingers."""
        if self.process.poll() is None:
            try:
                os.killpg(self.process.pid, signal.SIGTERM)
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                os.killpg(self.process.pid, signal.SIGKILL)
                self.process.wait()
            except ProcessLookupError:
                pass
        self._log.close()


def make_handler(site: Path, config: dict):
    """A request handler: the site, with live pages, and /_live/ from the live assets."""

    class Handler(http.server.SimpleHTTPRequestHandler):
        def log_message(self, format, *args):  # quiet: one URL is all the terminal shows
            pass

        def translate_path(self, path: str) -> str:
            clean = unquote(urlsplit(path).path)
            if clean.startswith("/_live/thebe/"):
                return str(VENDOR_LIVE / "thebe" / clean[len("/_live/thebe/"):])
            if clean.startswith("/_live/"):
                return str(LIVE_ASSETS / clean[len("/_live/"):])
            return super().translate_path(path)

        def end_headers(self):
            self.send_header("Cache-Control", "no-store")  # a restarted server: a new token
            super().end_headers()

        def do_GET(self):
            path = Path(self.translate_path(self.path))
            if path.is_dir():
                if not urlsplit(self.path).path.endswith("/"):
                    return super().do_GET()  # the redirect to the folder's URL
                path = path / "index.html"
            if path.suffix != ".html" or not path.is_file() or not path.is_relative_to(site):
                return super().do_GET()
            text = path.read_text(encoding="utf-8")
            page = path.relative_to(site).as_posix()
            notebook = notebook_of(page)
            if notebook and _CODE_CELL in text and "</head>" in text:
                text = text.replace("</head>", live_head({**config, "notebook": notebook})
                                    + "</head>", 1)
            body = text.encode("utf-8")
            self.send_response(200)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

    return functools.partial(Handler, directory=str(site))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, default=8001, help="the site's port (0: a free one)")
    parser.add_argument("--kernel-port", type=int, default=8889,
                        help="the Jupyter server's port (0: a free one)")
    parser.add_argument("--site", type=Path, default=SITE, help="the built book")
    args = parser.parse_args(argv)
    site = args.site.resolve()
    if not (site / "index.html").is_file():
        print(f"serve_live: no built book in {site}: run `make book`", file=sys.stderr)
        return 2
    if not live_complete():
        print("serve_live: Thebe is not vendored (_vendor_live/): run "
              "`python -m tools.vendor_assets` (needs npm)", file=sys.stderr)
        return 2
    port = args.port or free_port()
    kernel_port = args.kernel_port or free_port()
    origin = f"http://127.0.0.1:{port}"
    token = secrets.token_hex(24)
    try:
        httpd = http.server.ThreadingHTTPServer(("127.0.0.1", port), make_handler(site, {}))
    except OSError as exc:
        print(f"serve_live: cannot serve the site on 127.0.0.1:{port} ({exc.strerror}): "
              "choose another port (make serve-live LIVE_PORT=...)", file=sys.stderr)
        return 2
    jupyter = JupyterServer(kernel_port, token, origin)
    config = {"baseUrl": jupyter.url, "wsUrl": f"ws://127.0.0.1:{kernel_port}", "token": token,
              "kernelName": KERNEL_NAME, "thebe": "/_live/thebe/index.js",
              "thebeCss": "/_live/thebe/thebe.css", "requireJs": "/_static/require.js"}
    httpd.RequestHandlerClass = make_handler(site, config)
    stopping = threading.Event()

    def stop(*_args):
        stopping.set()

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    try:
        jupyter.wait_ready()
        thread.start()
        print(f"Live book: {origin}/  (Ctrl-C to stop)", flush=True)
        while not stopping.wait(0.5):
            if jupyter.process.poll() is not None:
                print(f"serve_live: the Jupyter server stopped; see {LOG}", file=sys.stderr)
                return 1
        return 0
    except RuntimeError as exc:
        print(f"serve_live: {exc}", file=sys.stderr)
        return 1
    finally:
        if thread.is_alive():
            httpd.shutdown()
        httpd.server_close()
        jupyter.stop()
        print("serve_live: stopped the site and the Jupyter server", flush=True)


if __name__ == "__main__":
    sys.exit(main())
