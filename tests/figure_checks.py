"""Layout faults a test can find in a drawn matplotlib figure (no image snapshots):

* a legend entry whose artist is not drawn: no point inside the axes, zero width or height
  (a zero-width band), invisible;
* a curve listed in a legend that another curve hides (the same points to within a pixel);
* texts that overlap (titles, labels, tick labels, annotations, legend entries);
* a text that straddles the frame of its axes (a label cut by the axes);
* a legend inside an axes that covers a curve of that axes;
* a text or legend off the canvas (cut by the file's edge), for a figure written as laid out
  (not cropped to its tight bounding box).

``layout_faults(fig, cropped)`` draws the figure once on an Agg canvas and returns the faults as sentences.
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import Collection, PathCollection, PolyCollection
from matplotlib.container import Container
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text
from matplotlib.transforms import Bbox

PIXEL = 1.0


@contextmanager
def _recording_texts(found: list):
    """Record every Text that is drawn, with its window extent at the time it is drawn."""
    draw = Text.draw

    def recorded(self, renderer):
        draw(self, renderer)
        if self.get_visible() and self.get_text().strip():
            found.append((self, self.get_window_extent(renderer)))

    Text.draw = recorded
    try:
        yield found
    finally:
        Text.draw = draw


def _display_points(line: Line2D) -> np.ndarray:
    xy = np.asarray(line.get_xydata(), dtype=float)
    xy = xy[np.isfinite(xy).all(axis=1)] if xy.size else xy.reshape(0, 2)
    return line.get_transform().transform(xy) if len(xy) else xy


def _inside(points: np.ndarray, box: Bbox, pad: float = PIXEL) -> np.ndarray:
    return ((points[:, 0] >= box.x0 - pad) & (points[:, 0] <= box.x1 + pad)
            & (points[:, 1] >= box.y0 - pad) & (points[:, 1] <= box.y1 + pad))


def _line_drawn(line: Line2D, frame: Bbox) -> bool:
    if not line.get_visible() or line.get_alpha() == 0:
        return False
    if line.get_linestyle() in ("None", "", " ") and line.get_marker() in ("None", "", " ", None):
        return False
    pts = _display_points(line)
    return bool(len(pts)) and bool(_inside(pts, frame).any())


def _extent_drawn(box: Bbox, frame: Bbox, both: bool) -> bool:
    if not np.all(np.isfinite(box.get_points())):
        return False
    sizes = (box.width > 0.5, box.height > 0.5)
    big = all(sizes) if both else any(sizes)
    return big and box.overlaps(frame)


def _drawn(artist, ax, renderer) -> bool:
    """Whether ``artist`` (a legend handle of ``ax``) shows anything inside ``ax``."""
    frame = ax.get_window_extent(renderer)
    if isinstance(artist, Container):
        return any(_drawn(a, ax, renderer) for a in artist.get_children() if a is not None)
    if isinstance(artist, Line2D):
        return _line_drawn(artist, frame)
    if not artist.get_visible() or artist.get_alpha() == 0:
        return False
    if isinstance(artist, Patch):
        return _extent_drawn(artist.get_window_extent(renderer), frame, both=True)
    if isinstance(artist, Collection):
        offsets = artist.get_offsets()
        if isinstance(artist, PathCollection) and len(artist.get_paths()) and len(offsets):  # scatter
            pts = artist.get_offset_transform().transform(np.asarray(offsets, dtype=float))
            pts = pts[np.isfinite(pts).all(axis=1)]
            return bool(len(pts)) and bool(_inside(pts, frame).any())
        box = artist.get_datalim(ax.transData).transformed(ax.transData)
        return _extent_drawn(box, frame, both=isinstance(artist, PolyCollection))
    return True


def _hidden_by(line: Line2D, other: Line2D, order: dict) -> bool:
    """``line`` lies under ``other``: ``other`` drawn above it (higher zorder, or the same and
    later), through the same points to within a pixel, and at least as wide."""
    if other is line or not other.get_visible():
        return False
    above = (other.get_zorder(), order[id(other)]) > (line.get_zorder(), order[id(line)])
    if not above or other.get_linewidth() < line.get_linewidth() - 0.05:
        return False
    a, b = _display_points(line), _display_points(other)
    return len(a) > 0 and len(a) == len(b) and bool(np.all(np.abs(a - b) <= PIXEL))


def _legend_faults(ax, renderer) -> list[str]:
    faults = []
    handles, labels = ax.get_legend_handles_labels()
    lines = list(ax.get_lines())
    order = {id(line): k for k, line in enumerate(lines)}
    for handle, label in zip(handles, labels):
        if not _drawn(handle, ax, renderer):
            faults.append(f"legend entry {label!r}: nothing drawn in the axes")
        elif isinstance(handle, Line2D) and any(_hidden_by(handle, other, order) for other in lines):
            faults.append(f"legend entry {label!r}: the curve is hidden under another")
    return faults


def _covered_curves(legend: Legend, axes, renderer) -> list[str]:
    """Curves (3 or more points) of ``axes`` that pass under the legend box."""
    box = legend.get_window_extent(renderer)
    faults = []
    for ax in axes:
        if not box.overlaps(ax.get_window_extent(renderer)):
            continue
        for line in ax.get_lines():
            pts = _display_points(line)
            if len(pts) < 3 or not _line_drawn(line, ax.get_window_extent(renderer)):
                continue
            # every segment sampled every 2 px, kept where it is inside the axes
            dense = [pts[:1]]
            for p, q in zip(pts[:-1], pts[1:]):
                n = int(min(max(np.hypot(*(q - p)) / 2.0, 1), 2000))
                dense.append(p + (q - p) * np.linspace(0, 1, n + 1)[1:, None])
            dense = np.concatenate(dense)
            dense = dense[_inside(dense, ax.get_window_extent(renderer), pad=0)]
            inner = Bbox.from_extents(box.x0 + 2, box.y0 + 2, box.x1 - 2, box.y1 - 2)
            if len(dense) and _inside(dense, inner, pad=0).any():
                faults.append(f"legend covers the curve {line.get_label()!r}")
        for patch in ax.patches:  # bars and other filled data areas (background areas have zorder < 1)
            if patch.get_visible() and patch.get_fill() and patch.get_zorder() >= 1:
                inter = Bbox.intersection(box, patch.get_window_extent(renderer))
                if inter is not None and inter.width > 2 and inter.height > 2:
                    faults.append(f"legend covers the patch {patch.get_label()!r}")
    return faults


def _text_faults(texts, fig) -> list[str]:
    faults = []
    upright = [(t, b) for t, b in texts if round(t.get_rotation()) % 90 == 0]
    for i, (t, b) in enumerate(upright):
        for u, c in upright[i + 1:]:
            if u is t:
                continue
            inter = Bbox.intersection(b, c)
            if inter is not None and inter.width > PIXEL and inter.height > PIXEL:
                faults.append(f"texts overlap: {t.get_text()!r} and {u.get_text()!r}")
    for ax in fig.axes:
        frame = ax.get_window_extent()
        for t in ax.texts:
            box = next((b for u, b in texts if u is t), None)
            if box is None:
                continue
            inter = Bbox.intersection(box, frame)
            if inter is not None and 0.05 * box.width * box.height < inter.width * inter.height < \
                    0.95 * box.width * box.height:
                faults.append(f"text {t.get_text()!r} is cut by the frame of its axes")
    return faults


def _off_canvas(texts, fig, renderer) -> list[str]:
    canvas = fig.bbox
    boxes = [(repr(t.get_text()), b) for t, b in texts] + [("a legend", g.get_window_extent(renderer)) for g in
                                                           [*fig.legends, *(ax.get_legend() for ax in fig.axes)] if g]
    return [f"{name} is off the canvas" for name, b in boxes
            if b.x0 < canvas.x0 - PIXEL or b.y0 < canvas.y0 - PIXEL or b.x1 > canvas.x1 + PIXEL or b.y1 > canvas.y1 + PIXEL]


def layout_faults(fig, cropped: bool = True) -> list[str]:
    """Every fault of the kinds listed in the module docstring, as sentences; texts and legends off
    the canvas unless the figure is written ``cropped`` to its tight bounding box."""
    FigureCanvasAgg(fig)
    texts: list = []
    with _recording_texts(texts):
        fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    faults = []
    for ax in fig.axes:
        faults += _legend_faults(ax, renderer)
        if ax.get_legend() is not None:
            faults += _covered_curves(ax.get_legend(), [ax], renderer)
    for legend in fig.legends:
        faults += _covered_curves(legend, fig.axes, renderer)
    faults += _text_faults(texts, fig)
    if not cropped:
        faults += _off_canvas(texts, fig, renderer)
    return faults
