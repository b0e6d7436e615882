#!/usr/bin/env python
"""Vendor the book's JavaScript into ``_vendor/`` so that the built HTML works offline.

``package.json`` pins MathJax 3, require.js and the ipywidgets html-manager; ``npm ci``
installs exactly what ``package-lock.json`` records into ``node_modules/``, and this script
copies the few files the pages load into ``_vendor/`` (git-ignored). ``_config.yml`` lists
``_vendor`` in ``html_static_path``, so Sphinx copies it into ``_build/html/_static/``, and
points ``mathjax_path`` and ``nb_ipywidgets_js`` at those copies.

Without npm (or when ``npm ci`` fails) the script says so in one line and leaves no
``_vendor/``; the Sphinx extension ``tools/offline_assets.py`` then switches the book back to
the CDN defaults of Sphinx and myst-nb, so the build still passes ``-W``. Under CI
(``CI=true``) a missing npm is an error: CI proves that the site works offline.

Thebe (pinned too) is for the live pages of ``make serve-live`` only: its webpack bundle goes
into ``_vendor_live/thebe/`` (git-ignored), which ``tools/serve_live.py`` serves beside the site,
so that the static site does not carry 3 MB of scripts that no page of it loads.

Run by ``make book``; it does nothing when ``_vendor/`` is already up to date.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VENDOR = ROOT / "_vendor"
VENDOR_LIVE = ROOT / "_vendor_live"
NODE_MODULES = ROOT / "node_modules"
STAMP_NAME = ".stamp"

#: (source under node_modules/, destination under _vendor/). Directories are copied whole.
COPIES: tuple[tuple[str, str], ...] = (
    # MathJax 3: the TeX input + CommonHTML output component, its web fonts, and the TeX
    # extensions that its autoload loads on first use (\boldsymbol, \cancel, ...). Its
    # loader finds the fonts and extensions relative to the script ([mathjax]/...).
    ("mathjax/es5/tex-chtml.js", "mathjax/tex-chtml.js"),
    ("mathjax/es5/output/chtml/fonts/woff-v2", "mathjax/output/chtml/fonts/woff-v2"),
    ("mathjax/es5/input/tex/extensions", "mathjax/input/tex/extensions"),
    ("mathjax/LICENSE", "mathjax/LICENSE"),
    # require.js, which the widget manager needs (the package ships only the unminified file).
    ("requirejs/require.js", "require.js"),
    # The ipywidgets 8 html-manager (1.x): renders stored widget state without a kernel. The
    # book stores none (live panels are tagged remove-output), so pages load it only if a
    # notebook ever stores widget state; it is vendored so that such a page stays offline.
    ("@jupyter-widgets/html-manager/dist/embed-amd.js", "embed-amd.js"),
)

#: Thebe's bundle for the live pages, (source under node_modules/, destination under
#: _vendor_live/): index.js, the chunks it loads by name and its stylesheet, without source maps
#: and type declarations. The bundle carries CodeMirror and the ipywidgets 8 manager; its
#: require.js (fetched from a CDN by name) is served from the site's own copy (book/_live/live.js).
LIVE_COPIES: tuple[tuple[str, str], ...] = (("thebe/lib", "thebe"),)
_LIVE_SKIP = ("*.map", "types")
#: Files whose presence means "_vendor_live/ is usable" (read by tools/serve_live.py).
LIVE_REQUIRED: tuple[str, ...] = ("thebe/index.js", "thebe/thebe.css")

#: Files whose presence means "_vendor/ is usable" (read by tools/offline_assets.py).
REQUIRED: tuple[str, ...] = ("mathjax/tex-chtml.js", "require.js", "embed-amd.js")

FALLBACK_MESSAGE = "npm not found: the book will load MathJax/require.js/widgets from CDNs"


def vendor_complete(vendor: Path = VENDOR) -> bool:
    """True when every required file is in ``vendor`` (a complete earlier run)."""
    return (vendor / STAMP_NAME).is_file() and all((vendor / f).is_file() for f in REQUIRED)


def live_complete(vendor: Path = VENDOR_LIVE) -> bool:
    """True when Thebe's bundle is in ``vendor`` (a complete earlier run)."""
    return (vendor / STAMP_NAME).is_file() and all((vendor / f).is_file() for f in LIVE_REQUIRED)


def _fingerprint() -> str:
    """Changes whenever the pinned packages or the list of copied files change."""
    digest = hashlib.sha256()
    for name in ("package.json", "package-lock.json"):
        path = ROOT / name
        digest.update(path.read_bytes() if path.exists() else b"-")
    digest.update(json.dumps([COPIES, LIVE_COPIES, _LIVE_SKIP]).encode())
    return digest.hexdigest()


def _in_ci() -> bool:
    return os.environ.get("CI", "").lower() in ("1", "true", "yes")


def _fallback(reason: str) -> int:
    """No usable npm: remove any partial _vendor/, say so once, and carry on (not in CI)."""
    shutil.rmtree(VENDOR, ignore_errors=True)
    shutil.rmtree(VENDOR_LIVE, ignore_errors=True)
    if _in_ci():
        print(f"vendor_assets: {reason}; CI must build an offline site: install npm "
              "(apt-get install npm) and try again", file=sys.stderr)
        return 1
    print(reason if reason == FALLBACK_MESSAGE else f"{reason}: the book will load "
          "MathJax/require.js/widgets from CDNs")
    return 0


def _copy(src: Path, dest: Path) -> None:
    dest.parent.mkdir(parents=True, exist_ok=True)
    if src.is_dir():
        shutil.copytree(src, dest)
    else:
        shutil.copy2(src, dest)


def main() -> int:
    fingerprint = _fingerprint()
    stamp = VENDOR / STAMP_NAME
    if (vendor_complete() and stamp.read_text().strip() == fingerprint and live_complete()
            and (VENDOR_LIVE / STAMP_NAME).read_text().strip() == fingerprint):
        return 0  # up to date
    npm = shutil.which("npm")
    if npm is None:
        return _fallback(FALLBACK_MESSAGE)
    command = [npm, "ci" if (ROOT / "package-lock.json").exists() else "install",
               "--ignore-scripts", "--no-audit", "--no-fund", "--loglevel=error"]
    print(f"vendor_assets: {' '.join(command[1:])} (pinned in package-lock.json)")
    done = subprocess.run(command, cwd=ROOT, check=False)
    if done.returncode != 0:
        return _fallback(f"npm {command[1]} failed (exit {done.returncode})")
    missing = [src for src, _ in COPIES + LIVE_COPIES if not (NODE_MODULES / src).exists()]
    if missing:
        print(f"vendor_assets: npm installed no {', '.join(missing)}: check package.json",
              file=sys.stderr)
        return 1
    staging = NODE_MODULES / ".wheelkin-vendor-staging"  # git-ignored, like node_modules
    shutil.rmtree(staging, ignore_errors=True)
    for src, dest in COPIES:
        _copy(NODE_MODULES / src, staging / dest)
    (staging / STAMP_NAME).write_text(fingerprint + "\n")
    shutil.rmtree(VENDOR, ignore_errors=True)
    staging.rename(VENDOR)
    size = sum(p.stat().st_size for p in VENDOR.rglob("*") if p.is_file())
    print(f"vendor_assets: {len(COPIES)} assets, {size / 1e6:.1f} MB in _vendor/")
    staging = NODE_MODULES / ".wheelkin-vendor-live-staging"
    shutil.rmtree(staging, ignore_errors=True)
    for src, dest in LIVE_COPIES:
        shutil.copytree(NODE_MODULES / src, staging / dest,
                        ignore=shutil.ignore_patterns(*_LIVE_SKIP))
    (staging / STAMP_NAME).write_text(fingerprint + "\n")
    shutil.rmtree(VENDOR_LIVE, ignore_errors=True)
    staging.rename(VENDOR_LIVE)
    size = sum(p.stat().st_size for p in VENDOR_LIVE.rglob("*") if p.is_file())
    print(f"vendor_assets: Thebe for the live pages, {size / 1e6:.1f} MB in _vendor_live/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
