"""What a figure's PNG says about its text: size, dpi, and the smallest font it records.

Shared by ``benchmarks/reading.py`` and the browser tests. A figure of the book records its
smallest font size in a ``wheelkin:min_font_pt`` text chunk (``wheelkin.style.setup`` and
``wheelkin.animation`` write it); matplotlib writes the dpi in the ``pHYs`` chunk. The text's
height on screen, in CSS pixels, is then ``font_pt x dpi / 72 x shown_width / png_width``.

>>> round(text_px_from(8, 100, shown_width=670, png_width=670), 1)
11.1
"""

from __future__ import annotations

import base64
import struct
import zlib
from pathlib import Path
from urllib.parse import unquote, urlsplit

#: The smallest font assumed in a figure that does not record its own (matplotlib's default
#: tick label size, rcParams["xtick.labelsize"] = "medium" = font.size = 10 pt).
ASSUMED_MIN_FONT_PT = 10.0
#: The dpi assumed for a PNG without a pHYs chunk (matplotlib's inline default at 72 dpi).
ASSUMED_DPI = 72.0



def text_px_from(font_pt: float, dpi: float, shown_width: float, png_width: float) -> float:
    """Height on screen (CSS px) of ``font_pt`` text drawn at ``dpi``, PNG shown scaled."""
    return font_pt * dpi / 72.0 * shown_width / png_width


def png_info(data: bytes) -> dict:
    """Width, height, dpi (from pHYs) and text chunks of a PNG; {} if it is not one."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return {}
    info: dict = {"text": {}}
    pos = 8
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            info["width"], info["height"] = struct.unpack(">II", body[:8])
        elif kind == b"pHYs" and len(body) == 9:
            x, _y, unit = struct.unpack(">IIB", body)
            if unit == 1:  # pixels per metre
                info["dpi"] = x * 0.0254
        elif kind == b"tEXt":
            key, _, value = body.partition(b"\0")
            info["text"][key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"iTXt":
            key, _, rest = body.partition(b"\0")
            flag, _method = rest[0], rest[1]
            _lang, _, rest = rest[2:].partition(b"\0")
            _tkey, _, value = rest.partition(b"\0")
            if flag:
                value = zlib.decompress(value)
            info["text"][key.decode("latin-1")] = value.decode("utf-8", "replace")
        elif kind == b"IEND":
            break
    return info


def image_bytes(src: str, page_file: Path) -> bytes:
    if src.startswith("data:"):
        head, _, payload = src.partition(",")
        return base64.b64decode(payload) if ";base64" in head else unquote(payload).encode()
    path = urlsplit(src).path
    target = (page_file.parent / unquote(path)).resolve()
    return target.read_bytes() if target.is_file() else b""


def text_px(data: bytes, shown_width: float) -> tuple[float | None, bool]:
    """(smallest text on screen in CSS px, whether the font size was assumed)."""
    info = png_info(data)
    if not info or not info.get("width") or shown_width <= 0:
        return None, False
    dpi = info.get("dpi") or ASSUMED_DPI
    recorded = info["text"].get("wheelkin:min_font_pt")
    font_pt = float(recorded) if recorded else ASSUMED_MIN_FONT_PT
    return text_px_from(font_pt, dpi, shown_width, info["width"]), recorded is None
