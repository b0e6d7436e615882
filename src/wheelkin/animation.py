"""Animations that play in a static HTML page, with stable element ids.

Matplotlib's :meth:`~matplotlib.animation.Animation.to_jshtml` embeds every frame as a PNG
and adds a small player (play, pause, step, a frame slider) that runs in the browser without a
kernel. It names its HTML elements with a random UUID, so re-executing a notebook would change
the stored output every time, and its ``<img>`` has no ``alt`` text. :func:`to_html` fixes
both: the id is derived from a name you give, and the image carries your alt text.

Use :func:`show` in a notebook cell::

    anim = FuncAnimation(fig, update, frames=40)
    show(anim, name="rover-sweep", alt="The rover's wheels steering from left to right",
         caption="Sweeping the steering command from -100 to 100.")
"""

from __future__ import annotations

import hashlib
import html as _html
import re
from typing import Any

try:
    import matplotlib.pyplot as plt
    from matplotlib.animation import Animation
except ModuleNotFoundError as exc:
    raise ModuleNotFoundError("wheelkin.animation needs matplotlib: install the extra, "
                              "pip install \".[plot]\" from a checkout") from exc

try:  # IPython comes with the notebook extra; only show() needs it
    from IPython.display import HTML
except ImportError:  # pragma: no cover - the plot extra alone
    HTML = Any

__all__ = ["FRAME_SLIDER_LABEL", "MAX_BYTES", "accessible_player", "describe", "palette_png",
           "show", "to_html"]

#: Budget for one animation's HTML (bytes). A page must stay under 3 MB in all.
MAX_BYTES = 2_000_000

_UUID = re.compile(r"_anim_img([0-9a-f]{32})")
_FA_LINK = re.compile(r'<link rel="stylesheet"\s+href="https://[^"]*font-awesome[^"]*">')
_ICONS = {
    "fa-minus": "&minus;", "fa-fast-backward": "|&#9664;&#9664;", "fa-step-backward": "|&#9664;",
    "fa-play fa-flip-horizontal": "&#9664;", "fa-pause": "&#10074;&#10074;", "fa-play": "&#9654;",
    "fa-step-forward": "&#9654;|", "fa-fast-forward": "&#9654;&#9654;|", "fa-plus": "+",
}
#: The accessible name of a player's frame slider (matplotlib writes it without one).
FRAME_SLIDER_LABEL = "Animation frame"
_SLIDER = re.compile(
    r'<input id="_anim_slider[0-9a-f]+" type="range" class="anim-slider"(?! aria-label)')
_FRAME = re.compile(r'(frames\[\d+\] = "data:image/png;base64,)((?:[A-Za-z0-9+/=]|\\\n)+)(")')


def _palette_frame(match: re.Match, colors: int, min_font_pt: float | None = None,
                   dpi: float | None = None) -> str:
    """One embedded PNG frame, re-encoded with an adaptive palette of ``colors`` colours.

    The frame keeps its dpi (the PNG's pHYs chunk; ``dpi``, the figure's, when the frame has
    none) and, when given, records the smallest font size drawn in it (a
    ``wheelkin:min_font_pt`` text chunk), as every figure of the book does.
    """
    import base64

    data = base64.b64decode(match.group(2).replace("\\\n", ""))
    png = palette_png(data, colors, min_font_pt=min_font_pt, dpi=dpi)
    return match.group(1) + base64.b64encode(png).decode("ascii") + match.group(3)


def palette_png(data: bytes, colors: int = 256, *, min_font_pt: float | None = None,
                dpi: float | None = None) -> bytes:
    """A PNG re-encoded with an adaptive palette of ``colors`` colours (2..256, no dithering).

    Line drawings lose nothing visible and shrink about threefold (the median-cut palette keeps
    even a faint grid line; Pillow's faster octree rounds it to white). The PNG keeps its dpi (its
    pHYs chunk; ``dpi`` when it has none) and, when given, records the smallest font size drawn
    in it (a ``wheelkin:min_font_pt`` text chunk), as every figure of the book does. Used for
    animation frames and for the precomputed views of the live panels
    (:mod:`wheelkin.widgets.precomputed`).
    """
    import io

    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    if not 2 <= colors <= 256:
        raise ValueError(f"colors must be in [2, 256], got {colors}")
    image = Image.open(io.BytesIO(data)).convert("RGB")
    found = Image.open(io.BytesIO(data)).info.get("dpi") or ((dpi, dpi) if dpi else None)
    quantised = image.quantize(colors=colors, method=Image.Quantize.MEDIANCUT, dither=0)
    info = PngInfo()
    if min_font_pt is not None:
        info.add_text("wheelkin:min_font_pt", f"{min_font_pt:g}")
    buf = io.BytesIO()
    extra = {"dpi": tuple(round(d) for d in found)} if found else {}
    quantised.save(buf, format="png", optimize=True, pnginfo=info, **extra)
    return buf.getvalue()


def accessible_player(html: str) -> str:
    """``html`` with every player's controls as assistive technology needs them.

    Matplotlib's player names its buttons (``aria-label``) but not its frame slider, which a
    screen reader then announces as an unnamed slider: the slider is named
    :data:`FRAME_SLIDER_LABEL`. The pause button's icon is drawn with a symbol (two heavy bars)
    rather than the letters "II", which speech input would take for the button's name.
    Idempotent: a player that has both is left as it is. The book's build applies it to the
    players stored before it existed (``tools/accessibility.py``).

    >>> accessible_player('<input id="_anim_slider0a" type="range" class="anim-slider">')
    '<input id="_anim_slider0a" type="range" class="anim-slider" aria-label="Animation frame">'
    >>> once = accessible_player('<button aria-label="Pause"><span aria-hidden="true">II</span>')
    >>> once == accessible_player(once), "II" in once
    (True, False)
    """
    if not isinstance(html, str):
        raise ValueError(f"html must be a string, got {type(html).__name__}")
    html = _SLIDER.sub(lambda m: f'{m.group(0)} aria-label="{FRAME_SLIDER_LABEL}"', html)
    return html.replace('<span aria-hidden="true">II</span>',
                        f'<span aria-hidden="true">{_ICONS["fa-pause"]}</span>')


def describe(description: str, player_id: str) -> str:
    """The fold under a player that holds its description, which the frames point to.

    >>> describe("The dot <moves> right.", "0a")  # doctest: +NORMALIZE_WHITESPACE
    '<details class="wheelkin-animation-description"><summary>Describe the
    animation</summary><p id="desc0a">The dot &lt;moves&gt; right.</p></details>'
    """
    return ('<details class="wheelkin-animation-description"><summary>Describe the animation'
            f'</summary><p id="desc{player_id}">{_html.escape(description)}</p></details>')


def stable_id(name: str) -> str:
    """A 32-hex-digit id derived from ``name`` (the same name always gives the same id).

    >>> stable_id("demo")
    'fe01ce2a7fbac8fafaed7c982a04e229'
    """
    if not isinstance(name, str) or not name:
        raise ValueError(f"name must be a non-empty string, got {name!r}")
    return hashlib.md5(name.encode()).hexdigest()


def to_html(
    anim: Animation,
    *,
    name: str,
    alt: str,
    caption: str | None = None,
    fps: float | None = None,
    default_mode: str = "loop",
    max_bytes: int = MAX_BYTES,
    colors: int | None = 256,
    check: bool | None = None,
    description: str | None = None,
) -> str:
    """Render ``anim`` to self-contained HTML with a stable id and alt text.

    Parameters
    ----------
    anim : matplotlib.animation.Animation
        The animation. Its figure is closed afterwards, so it is not shown a second time.
    name : str
        Unique on the page; the element ids are derived from it.
    alt : str
        Alternative text for the frames (what a reader who cannot see them should know).
    caption : str, optional
        Shown under the player, in a ``<figcaption>``.
    fps : float, optional
        Frames per second of playback (default: from the animation's interval).
    default_mode : {"loop", "once", "reflect"}
        What the player does at the last frame.
    max_bytes : int
        Raise ``ValueError`` if the HTML is larger (keeps pages within their size budget).
    colors : int or None
        Re-encode every frame as a palette PNG with this many colours (2..256): line drawings
        lose nothing visible and the frames shrink about threefold. ``None`` keeps matplotlib's
        full-colour frames.
    check : bool or None
        Check every frame with :func:`wheelkin.style.check_figure` as it is written, and raise
        :class:`wheelkin.style.FigureCheckError` naming the animation, the frame and the
        problem. ``None`` (default): only when the figure check is on
        (:func:`wheelkin.style.checking`); ``True``: always; ``False``: never.
    description : str, optional
        What happens in the animation, in words, for a reader who cannot see it move: the
        motion, and what to notice (``alt`` says what a frame shows). It is shown under the
        player in a fold, "Describe the animation", and screen readers announce it with the
        frames (``aria-describedby``).
    """
    if not isinstance(anim, Animation):
        raise ValueError(f"anim must be a matplotlib Animation, got {type(anim).__name__}")
    if not isinstance(alt, str) or not alt.strip():
        raise ValueError("alt must be a non-empty description of the animation")
    if default_mode not in ("loop", "once", "reflect"):
        raise ValueError(f"default_mode must be 'loop', 'once' or 'reflect', got {default_mode!r}")
    if check is not None and not isinstance(check, bool):
        raise ValueError(f"check must be True, False or None, got {check!r}")
    if description is not None and (not isinstance(description, str)
                                    or not description.strip()):
        raise ValueError("description must be a non-empty text (what happens in the "
                         f"animation) or None, got {description!r}")
    new_id = stable_id(name)
    from wheelkin import style

    try:
        raw = _jshtml_checked(anim, name, style.checking() if check is None else check,
                              fps=fps, default_mode=default_mode)
        smallest = style.min_font_pt(anim._fig)
        fig_dpi = anim._fig.dpi
    finally:
        plt.close(anim._fig)
    match = _UUID.search(raw)
    if match is None:  # pragma: no cover - matplotlib changed its template
        raise RuntimeError("could not find the player's element id in matplotlib's HTML")
    out = raw.replace(match.group(1), new_id)
    # matplotlib's player links Font Awesome 4 from a CDN for its button icons: drop the link
    # (the book must work offline) and draw the icons with characters every font has.
    out = _FA_LINK.sub("", out)
    for icon, text in _ICONS.items():
        out = out.replace(f'<i class="fa {icon}"></i>', f'<span aria-hidden="true">{text}</span>')
    out = accessible_player(out)
    if colors is not None:
        out = _FRAME.sub(lambda m: _palette_frame(m, int(colors), smallest, fig_dpi), out)
    described = f' aria-describedby="desc{new_id}"' if description else ""
    out = out.replace(
        f'<img id="_anim_img{new_id}">',
        f'<img id="_anim_img{new_id}" alt="{_html.escape(alt, quote=True)}"{described}>',
    )
    if description:
        out += describe(description, new_id)
    if caption:
        out = (
            f'<figure class="wheelkin-animation" id="fig-{_html.escape(name)}">{out}'
            f"<figcaption>{_html.escape(caption)}</figcaption></figure>"
        )
    size = len(out.encode())
    if size > max_bytes:
        raise ValueError(
            f"animation {name!r} is {size / 1e6:.2f} MB, over max_bytes={max_bytes / 1e6:.2f} MB: "
            "use fewer frames, a smaller figure or a lower dpi"
        )
    return out


def _jshtml_checked(anim: Animation, name: str, check: bool, **kwargs) -> str:
    """``anim.to_jshtml(**kwargs)``; with ``check``, every frame is checked as it is written,
    and a problem raises :class:`wheelkin.style.FigureCheckError` naming the animation and the
    frame ("first frame", "frame 7", "last frame").

    The check wraps the ``grab_frame`` of whichever writer ``anim.save`` is given (matplotlib's
    ``HTMLWriter`` or a subclass with its own ``grab_frame``, like the sandbox's), for this
    animation only.
    """
    from wheelkin import style

    if not check:
        return anim.to_jshtml(embed_frames=True, **kwargs)
    found: list[list[str]] = []
    save = anim.save

    def checked_save(*args, writer=None, **save_kwargs):
        if writer is not None and not isinstance(writer, str):
            grab = writer.grab_frame

            def grab_frame(**savefig_kwargs):
                out = grab(**savefig_kwargs)
                # The frame was just drawn: measure its texts without drawing it again.
                found.append(style.check_figure(writer.fig, draw=False))
                return out

            writer.grab_frame = grab_frame
        return save(*args, writer=writer, **save_kwargs)

    anim.save = checked_save  # this animation only
    try:
        raw = anim.to_jshtml(embed_frames=True, **kwargs)
    finally:
        del anim.save
    last = len(found) - 1
    problems = [f"{'first frame' if k == 0 else 'last frame' if k == last else f'frame {k}'}: {p}"
                for k, frame in enumerate(found) for p in frame]
    if problems:
        raise style.FigureCheckError(f"animation {name!r}: " + "; ".join(problems))
    return raw


def show(anim: Animation, **kwargs: Any) -> HTML:
    """Display ``anim`` in a notebook as a kernel-free player (see :func:`to_html`; the book's
    notebooks use :func:`wheelkin.display.play`, which always checks the frames)."""
    from IPython.display import HTML

    return HTML(to_html(anim, **kwargs))
