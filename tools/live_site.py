"""The live pages' side of the browser tests and of benchmarks/live.py.

- :data:`PANEL_PAGES`: the book's pages that show a live panel, with the panels' names (from
  the notebooks' ``wheelkin.panel`` cell metadata);
- :func:`serve_live`: ``tools/serve_live.py`` on free ports, stopped afterwards;
- :func:`lock_down`: a browser page whose requests leave 127.0.0.1 only to be aborted and
  recorded;
- :func:`make_live` and the panel drivers: click "Make this page live", then move each
  control of each panel and wait for its image to change.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import signal
import subprocess
import threading
import time
from collections.abc import Iterator
from urllib.parse import urlsplit

from tools.book_site import ROOT, SITE, toc_files

PYTHON = ROOT / ".venv" / "bin" / "python"


def _panel_pages() -> dict[str, list[str]]:
    pages: dict[str, list[str]] = {}
    for page in toc_files():
        path = ROOT / f"{page}.ipynb"
        if not path.is_file():
            continue
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        names = [c["metadata"]["wheelkin"]["panel"] for c in cells
                 if c["cell_type"] == "code" and "panel" in c["metadata"].get("wheelkin", {})]
        if names:
            pages[page] = names
    return pages


#: page -> the panels it shows, in page order.
PANEL_PAGES: dict[str, list[str]] = _panel_pages()


def live_ready() -> str | None:
    """Why live pages cannot be served here, or None when they can."""
    from tools.vendor_assets import live_complete

    if not (SITE / "index.html").is_file():
        return "no built book: run `make book`"
    if not live_complete():
        return "Thebe is not vendored (_vendor_live/): run `make vendor` (needs npm)"
    try:
        subprocess.run([str(PYTHON), "-c", "import jupyter_server"], check=True,
                       capture_output=True)
    except (subprocess.CalledProcessError, OSError):
        return "jupyter_server is not installed: install requirements-lab.txt (make lab)"
    return None


@contextlib.contextmanager
def serve_live(timeout: float = 120.0) -> Iterator[str]:
    """Run ``tools/serve_live.py`` on free ports; yield the URL it prints; stop it after.

    Stopping sends SIGTERM (what Ctrl-C does to it) and waits for its clean exit: the site and
    the Jupyter server with its kernels are stopped, or the process group is killed.
    """
    command = [str(PYTHON), "-m", "tools.serve_live", "--port", "0", "--kernel-port", "0",
               "--site", str(SITE)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True, start_new_session=True, cwd=ROOT)
    lines: list[str] = []
    found = threading.Event()
    url: list[str] = []

    def read():
        for line in process.stdout:
            lines.append(line)
            match = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
            if match and not url:
                url.append(match.group(1))
                found.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        if not found.wait(timeout):
            raise RuntimeError("serve_live printed no URL in time:\n" + "".join(lines))
        yield url[0]
    finally:
        if process.poll() is None:
            process.send_signal(signal.SIGTERM)
            try:
                process.wait(30)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
        reader.join(5)
        if process.stdout is not None:
            process.stdout.close()
        serve_live.output = "".join(lines)  # type: ignore[attr-defined]
        serve_live.returncode = process.returncode  # type: ignore[attr-defined]


def lock_down(context, external: list[str]) -> None:
    """Abort and record every request of ``context`` that leaves 127.0.0.1."""

    def route(route_request):
        parts = urlsplit(route_request.request.url)
        if parts.scheme in ("data", "blob", "about") or parts.hostname == "127.0.0.1":
            route_request.continue_()
        else:
            external.append(route_request.request.url)
            route_request.abort()

    context.route("**/*", route)
    # WebSockets (the kernel's channels) go around page.route: check their address instead.
    context.on("page", lambda page: page.on(
        "websocket", lambda ws: None if urlsplit(ws.url).hostname == "127.0.0.1"
        else external.append(ws.url)))


def make_live(page, timeout_ms: int = 240_000) -> dict:
    """Click "Make this page live" and wait until the page is set up; return its timings."""
    page.get_by_role("button", name="Make this page live").click()
    page.wait_for_function(
        "() => document.body.getAttribute('data-wk-live') === 'ready' || "
        "(window.wheelkinLive && window.wheelkinLive.status === 'error')", timeout=timeout_ms)
    status = page.evaluate("() => window.wheelkinLive.status")
    if status != "live":
        message = page.locator(".wk-live-status").inner_text()
        raise AssertionError(f"the page did not become live: {message}")
    return page.evaluate("() => window.wheelkinLive.timings")


#: The live panels of the page, each with its controls: (panel index, control index, kind).
PANEL_CONTROLS = r"""
() => [...document.querySelectorAll('.wk-panel-cell')].map((cell, p) => {
  const out = cell.querySelector('.thebe-output');
  const controls = out ? [...out.querySelectorAll(
      '.noUi-handle, .widget-dropdown select, .widget-checkbox input')] : [];
  return {panel: p, hasImage: !!(out && out.querySelector('img.widget-image')),
          controls: controls.map((c, k) => ({
            index: k, kind: c.matches('select') ? 'select'
                           : c.matches('input') ? 'checkbox' : 'slider',
            label: (c.closest('.widget-inline-hbox, .widget-hslider, .widget-dropdown,'
                              + ' .widget-checkbox') || c).innerText.replace(/\u200b/g, '')
                   .trim().split('\n')[0],
            atMax: c.matches('.noUi-handle')
                   && c.getAttribute('aria-valuenow') === c.getAttribute('aria-valuemax')}))};
})
"""

#: Arm a watcher on panel p's image: resolves with the ms from arming to its next change.
_ARM = r"""
([p]) => {
  const cell = document.querySelectorAll('.wk-panel-cell')[p];
  const img = cell.querySelector('.thebe-output img.widget-image');
  const before = img.src;
  window.__wkChange = new Promise(resolve => {
    const start = performance.now();
    const observer = new MutationObserver(() => {
      if (img.src !== before) { observer.disconnect(); resolve(performance.now() - start); }
    });
    observer.observe(img, {attributes: true, attributeFilter: ['src']});
  });
}
"""


def move_control(page, panel: int, control: dict, timeout_ms: int = 30_000) -> float:
    """Move one control of a live panel (keyboard for a slider); return ms to the new image."""
    cell = page.locator(".wk-panel-cell").nth(panel)
    out = cell.locator(".thebe-output")
    page.evaluate(_ARM, [panel])
    if control["kind"] == "slider":
        handle = out.locator(".noUi-handle, .widget-dropdown select, .widget-checkbox input"
                             ).nth(control["index"])
        handle.focus()
        handle.press("ArrowLeft" if control["atMax"] else "ArrowRight")
    elif control["kind"] == "select":
        select = out.locator(".noUi-handle, .widget-dropdown select, .widget-checkbox input"
                             ).nth(control["index"])
        options = select.locator("option")
        current = select.evaluate("s => s.selectedIndex")
        select.select_option(index=(current + 1) % options.count())
    else:
        out.locator(".noUi-handle, .widget-dropdown select, .widget-checkbox input"
                    ).nth(control["index"]).click()
    return page.evaluate(f"""() => Promise.race([window.__wkChange,
        new Promise((_, reject) => setTimeout(() => reject(new Error('no new image')),
                                               {timeout_ms}))])""")


def toggle_checkbox(page, panel: int, control: dict, settle_ms: int = 2_000) -> None:
    """Click a live panel's check box; the panel must stay up, with no error output.

    A check box may leave the figure as it was (the circle panel's "refuse instead of
    scaling" changes nothing while the speed is within the vehicle's limit), so no new image is
    required; the click must reach the kernel without an error.
    """
    out = page.locator(".wk-panel-cell").nth(panel).locator(".thebe-output").first
    box = out.locator(".noUi-handle, .widget-dropdown select, .widget-checkbox input"
                      ).nth(control["index"])
    before = box.is_checked()
    box.click()
    page.wait_for_timeout(settle_ms)
    assert box.is_checked() != before
    errors = out.locator(".jp-RenderedText[data-mime-type='application/vnd.jupyter.stderr']")
    assert errors.count() == 0, errors.all_inner_texts()
    assert out.locator("img.widget-image").count() == 1


def run_edited_cell(page, code: str, expect: str, timeout_ms: int = 60_000) -> str:
    """Type ``code`` into the page's last code cell, run it with Shift-Enter; return its output."""
    box = page.locator(".thebe-cell").last
    folded = box.locator("xpath=ancestor::details[1]")
    if folded.count() and not folded.evaluate("d => d.open"):
        folded.locator("summary").first.click()  # a folded cell: unfold it, as a reader would
    editor = box.locator(".CodeMirror")
    editor.scroll_into_view_if_needed()
    editor.click()
    page.keyboard.press("Control+A")
    page.keyboard.type(code)
    page.keyboard.press("Shift+Enter")
    cell = page.locator("div.cell").filter(has=page.locator(".thebe-cell")).last
    output = cell.locator(".thebe-output").filter(has_text=expect).first
    output.wait_for(timeout=timeout_ms)
    return output.inner_text()


def wait_port_closed(url: str, timeout: float = 10.0) -> bool:
    """True once nothing listens at ``url``'s port any more."""
    import socket

    port = urlsplit(url).port
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as sock:
            if sock.connect_ex(("127.0.0.1", port)) != 0:
                return True
        time.sleep(0.2)
    return False
