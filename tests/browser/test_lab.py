"""`make lab` starts JupyterLab on 127.0.0.1 in notebooks/, with jupyterlab-myst enabled.

Runs the Makefile's own target (so the command the README gives is the one tested) on a free
port with a token of its own, waits for the server, and asks it: the lab page's configuration
lists jupyterlab-myst among the extensions it loads and disables none of them, and the
server's root is notebooks/ (its contents API lists the chapters). Skipped, with the reason,
where requirements-lab.txt is not installed (the browser layer of `make test` installs it, so
CI runs this once).
"""

from __future__ import annotations

import json
import os
import re
import secrets
import signal
import socket
import subprocess
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
LAB_STAMP = ROOT / ".venv" / ".installed-lab"
STARTUP_S = 45


def _lab_ready() -> str | None:
    """Why the lab cannot be tested here, or None."""
    try:
        import jupyterlab  # noqa: F401
        import jupyterlab_myst  # noqa: F401
    except ImportError as exc:
        return f"requirements-lab.txt is not installed ({exc.name} missing): run `make lab` once"
    if not LAB_STAMP.exists():
        return "`make lab` has not set itself up here (no .venv/.installed-lab): run it once"
    # `make lab` would first reinstall (minutes): the test starts the server only when the
    # set-up is current (the browser layer of `make test` makes it so).
    current = subprocess.run(["make", "-q", str(LAB_STAMP.relative_to(ROOT))], cwd=ROOT,
                             capture_output=True)
    if current.returncode != 0:
        return ("the requirements changed since `make lab` last set itself up: run "
                "`make lab` (or `make browser`) once")
    return None


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def _get(url: str) -> tuple[int, bytes]:
    try:
        with urllib.request.urlopen(url, timeout=10) as response:
            return response.status, response.read()
    except urllib.error.HTTPError as exc:
        return exc.code, b""


@pytest.fixture(scope="module")
def lab():
    reason = _lab_ready()
    if reason:
        pytest.skip(reason)
    port, token = _free_port(), secrets.token_hex(16)
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(ROOT / "_build" / "lab-test-config"))
    process = subprocess.Popen(
        ["make", "--no-print-directory", "lab", f"LAB_PORT={port}",
         f"LAB_ARGS=--IdentityProvider.token={token} --LabApp.news_url=None "
         "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate "
         "--LabApp.extension_manager=readonly"],
        cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        start_new_session=True)
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + STARTUP_S
        while True:
            if process.poll() is not None:
                output = process.stdout.read().decode(errors="replace")[-3000:]
                pytest.fail(f"`make lab` exited with {process.returncode}:\n{output}")
            try:
                status, _ = _get(f"{base}/api/status?token={token}")
                if status == 200:
                    break
            except OSError:
                pass
            if time.monotonic() > deadline:
                pytest.fail(f"JupyterLab did not answer on {base} within {STARTUP_S} s")
            time.sleep(0.5)
        yield base, token
    finally:
        _stop(process)


def _stop(process: subprocess.Popen) -> None:
    """End the process group this test started (make and the server it runs), by its id."""
    for sig, wait in ((signal.SIGTERM, 15), (signal.SIGKILL, 5)):
        try:
            os.killpg(process.pid, sig)
        except ProcessLookupError:
            break
        try:
            process.wait(timeout=wait)
            break
        except subprocess.TimeoutExpired:
            continue
    process.stdout.close()


def _page_config(html: str) -> dict:
    match = re.search(r'<script id="jupyter-config-data" type="application/json">(.*?)</script>',
                      html, re.S)
    assert match, "the lab page carries no jupyter-config-data"
    return json.loads(match.group(1))


def test_lab_loads_jupyterlab_myst(lab):
    base, token = lab
    status, body = _get(f"{base}/lab?token={token}")
    assert status == 200, f"/lab answered {status}"
    config = _page_config(body.decode())
    names = {ext.get("name") for ext in config.get("federated_extensions", [])}
    assert "jupyterlab-myst" in names, f"jupyterlab-myst is not loaded; extensions: {names}"
    disabled = config.get("disabledExtensions", [])
    assert not any("myst" in str(d) for d in disabled), f"myst is disabled: {disabled}"


def test_lab_serves_the_notebooks_folder(lab):
    base, token = lab
    status, body = _get(f"{base}/api/contents?token={token}")
    assert status == 200, f"/api/contents answered {status}"
    names = {item["name"] for item in json.loads(body)["content"]}
    chapters = {p.name for p in (ROOT / "notebooks").glob("[0-9][0-9]_*")}
    assert chapters and chapters <= names, (
        f"the lab's root is not notebooks/: it lists {sorted(names)[:10]}")


def test_lab_listens_on_localhost_only(lab):
    base, _token = lab
    assert base.startswith("http://127.0.0.1:")
    port = int(base.rsplit(":", 1)[1])
    others = [a[4][0] for a in socket.getaddrinfo(socket.gethostname(), None, socket.AF_INET)
              if not a[4][0].startswith("127.")]
    for address in others:
        with socket.socket() as sock:
            sock.settimeout(1)
            assert sock.connect_ex((address, port)) != 0, f"the lab answers on {address}"
