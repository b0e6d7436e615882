"""Which artists a blitting panel must redraw for its picture to equal a full draw.

A blitting :class:`~wheelkin.widgets.Panel` restores a picture of everything but the artists
its ``update`` returns and draws those over it. The picture equals a full draw when the list
holds the artists that move *and* every other artist a full draw paints after the first of
them over pixels they may have touched: the frame (spines) over the paths, a legend over a
path that runs under it. Text is the dearest thing to draw (a legend of three entries costs
more than every path and the robot together), so :class:`BlitList` leaves out a static
artist drawn later when its extent does not meet any moving artist's extent (both padded
by a safe margin): a title above the axes, a legend in a corner the paths do not reach.
"""

from __future__ import annotations

import numpy as np
from matplotlib.collections import Collection
from matplotlib.lines import Line2D
from matplotlib.text import Text
from matplotlib.transforms import Bbox

__all__ = ["BlitList"]

#: Padding (points) of every extent, so that two padded extents apart are at least twice
#: this apart: more than the paint of both artists reaches beyond the extents matplotlib
#: reports (half a stroke, its antialiasing, a projecting cap or a mitred corner (Agg's mitre
#: limit: twice the stroke), a text box's pad: 0.3 of its font size, 2.4 pt at 8 pt). Line
#: extents already include half a marker.
MARGIN_POINTS = 5.0


class BlitList:
    """The list of artists ``update`` returns to its panel, chosen anew for every picture.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes the moving artists are on (the panel's only axes).
    moving : list of Artist
        Every artist ``update`` may change.

    Call the instance after moving the artists: it returns the moving artists and the
    static ones they need redrawn, in a full draw's order (by zorder, then as
    ``Axes.get_children`` lists them, as ``Axes.draw`` sorts them). When the list changes,
    the artists it drops are made ordinary again (not animated), so that the panel's next
    background, drawn because the list changed, includes them.
    """

    def __init__(self, ax, moving) -> None:
        self.ax = ax
        self.moving = list(moving)
        order = sorted((a for a in ax.get_children() if a is not ax.patch),
                       key=lambda artist: artist.get_zorder())
        first = min(i for i, artist in enumerate(order)
                    if any(artist is m for m in self.moving))
        self.order = order[first:]
        self.static = [a for a in self.order if not any(a is m for m in self.moving)]
        self._static_extents: tuple | None = None
        self._last: list | None = None

    def _pad(self) -> float:
        return MARGIN_POINTS * self.ax.get_figure(root=True).dpi / 72.0

    def _extent(self, artist, renderer) -> Bbox | None:
        """Where ``artist`` may paint (pixels), padded; None if it paints nothing. Unsure
        (an extent matplotlib cannot give): its clip box, or the whole figure."""
        if not artist.get_visible():
            return None
        if isinstance(artist, Text) and not artist.get_text():
            return None
        if isinstance(artist, Line2D) and len(artist.get_xdata()) == 0:
            return None
        if isinstance(artist, Collection) and len(artist.get_paths()) == 0:
            return None
        clip = artist.get_clip_box() if artist.get_clip_on() else None
        try:
            box = artist.get_window_extent(renderer)
            finite = bool(np.all(np.isfinite(box.extents)))
        except Exception:  # any failure: be conservative
            finite = False
        if not finite or box.x1 < box.x0 or box.y1 < box.y0:
            whole = clip if clip is not None else self.ax.get_figure(root=True).bbox
            return Bbox(whole.get_points())
        pad = self._pad()
        box = Bbox.from_extents(box.x0 - pad, box.y0 - pad, box.x1 + pad, box.y1 + pad)
        return Bbox.intersection(box, clip) if clip is not None else box

    def __call__(self) -> list:
        renderer = self.ax.get_figure(root=True).canvas.get_renderer()
        self.ax.apply_aspect()  # the axes' place in a full draw (equal aspect shrinks them)
        size = tuple(self.ax.get_figure(root=True).bbox.bounds)
        if self._static_extents is None or self._static_extents[0] != size:
            # static artists: their extents change only with the figure's size
            self._static_extents = (size, [self._extent(a, renderer) for a in self.static])
        moving = [box for box in (self._extent(a, renderer) for a in self.moving)
                  if box is not None]
        needed = {id(a) for a, box in zip(self.static, self._static_extents[1], strict=True)
                  if box is not None and any(box.overlaps(m) for m in moving)}
        out = [a for a in self.order if id(a) in needed or any(a is m for m in self.moving)]
        if self._last is not None and out != self._last:
            for artist in self._last:
                if not any(artist is a for a in out):
                    artist.set_animated(False)
        self._last = out
        return out
