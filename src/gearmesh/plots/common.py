"""What every figure module shares: figures without pyplot's global state, saving, titles,
numbers in labels, legends placed clear of the data."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any, Callable

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.text import Text
from matplotlib.ticker import FuncFormatter

from ..pairfile import example_pairs
from ..io import atomic_output, stamp_figure

MM = 1e3  # m -> mm
UM = 1e6  # m -> µm

__all__ = ["DPI", "MM", "UM", "Figure", "apart", "coinciding", "end_labels", "figure", "figure_legend", "lay_out", "legend_below", "number", "on_canvas", "pair_label", "palette", "plain_axis", "plain_log_axis", "save",
           "subplots", "text_line", "title", "wrap_to_width"]


def figure(figsize: tuple[float, float], layout: str | None = None) -> Figure:
    """A new figure of its own (``matplotlib.figure.Figure``, no pyplot registry), so figures can
    be drawn in threads and nothing has to be closed.

    Parameters
    ----------
    figsize : tuple of float
        Width and height (inches).
    layout : str, optional
        Matplotlib layout engine ('constrained', 'tight'); default none.

    Returns
    -------
    matplotlib.figure.Figure
    """
    return Figure(figsize=figsize, layout=layout)


def subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float], layout: str | None = None,
             **kwargs: Any) -> tuple[Figure, Any]:
    """``figure`` and its grid of axes (``Figure.subplots`` keywords: sharex, squeeze, ...).

    Parameters
    ----------
    nrows, ncols : int
        Rows and columns of axes (default 1 each).
    figsize : tuple of float
        Width and height (inches), keyword only.
    layout : str, optional
        Matplotlib layout engine; default none.
    **kwargs
        Passed to ``Figure.subplots``.

    Returns
    -------
    (Figure, Axes or array of Axes)
    """
    fig = figure(figsize, layout)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def palette(n: int, name: str = "viridis", low: float = 0.1, high: float = 0.85) -> np.ndarray:
    """``n`` colours spread over ``name`` from ``low`` to ``high`` (RGBA rows).

    Parameters
    ----------
    n : int
        Number of colours.
    name : str
        Matplotlib colormap (default 'viridis').
    low, high : float
        Span of the colormap used, fractions in [0, 1] (default 0.1 to 0.85).

    Returns
    -------
    numpy.ndarray
        ``(n, 4)`` RGBA rows.
    """
    return colormaps[name](np.linspace(low, high, n))


#: zlib level of the PNG files: 3 instead of Pillow's 6 encodes the study's figures in about 0.7 of
#: the CPU (the same pixels) for about 5 % more bytes (issue 36; ``benchmarks/bench_figures.py``).
PNG_COMPRESS_LEVEL = 3
#: Resolution of the PNG files (dots per inch).
DPI = 130


def save(fig: Figure, path: str | Path) -> Path:
    """Write ``fig`` as PNG atomically (parent folders created), inside a workflow job with the
    provenance of the figure (:func:`gearmesh.io.stamp_figure`).

    A figure with constrained layout is laid out once, at the file's resolution, and written as
    laid out (:func:`lay_out`); any other figure is cropped to its tight bounding box.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (:data:`DPI` dpi, zlib level :data:`PNG_COMPRESS_LEVEL`).
    path : str or Path
        The PNG file to write.

    Returns
    -------
    Path
        ``path``.
    """
    tight = None if lay_out(fig) else "tight"
    with atomic_output(path) as tmp:
        fig.savefig(tmp, dpi=DPI, bbox_inches=tight, format="png", pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
        png = tmp.read_bytes()
        stamped = stamp_figure(png, path)
        if stamped is not png:
            tmp.write_bytes(stamped)
    return Path(path)


def lay_out(fig: Figure) -> bool:
    """Lay out a figure with constrained layout once, at the file's resolution (:data:`DPI`), its
    titles broken into lines that fit on its canvas (:func:`wrap_to_width`), and
    fix it as laid out; True when everything then lies on the canvas, so that the figure is written
    as it is, with constrained layout's margins.

    Constrained layout keeps the axes, their tick labels, titles, labels and legends and the
    figure's outside legends on the canvas, but not the width of an axes title or x label, the
    height of a y label, or a figure-level text: :func:`on_canvas` checks those. Cropping to the
    tight bounding box instead lays the figure out again and measures every artist once more:
    about 15 % of the default study's figure CPU (issue 36; ``benchmarks/bench_figures.py``), and a
    title wider than the figure made the file wider than its panels.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    bool
        False for a figure without constrained layout (left as it is) or with something still off
        the canvas (laid out all the same): to be cropped to its tight bounding box.
    """
    engine = fig.get_layout_engine()
    if not isinstance(engine, ConstrainedLayoutEngine):
        return False
    fig.set_dpi(DPI)
    renderer = FigureCanvasAgg(fig).get_renderer()  # the renderer the PNG is drawn with (cached per size)
    engine.execute(fig)
    if wrap_to_width(fig, renderer):  # a title's height changes the layout, its width does not
        engine.execute(fig)
    fig.set_layout_engine(None)  # laid out: not laid out again when written (no layout engine, no draw to lay it out)
    if fig.get_layout_engine() is not None:  # a matplotlibrc that asks every figure for a layout engine
        fig.set_layout_engine("none")  # kept as laid out all the same
    return on_canvas(fig, renderer)


#: Where a line of a title may be broken, the first kind that gives a fitting line first.
BREAKS = (" — ", "; ", ": ", ", ", " ")


def wrap_to_width(fig: Figure, renderer) -> bool:
    """Break every line of the titles of ``fig`` (its figure-level texts and its axes' titles) that
    would pass the canvas's edge into lines that do not: at the last break of the first kind of
    :data:`BREAKS` that gives a fitting line (the separator kept at the end of the line), else at
    the first break of any kind. A title centred on x fits within twice its distance from the
    nearer edge; one aligned left (right) within its distance from the right (left) edge.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A laid-out figure.
    renderer
        The renderer the figure is drawn with.

    Returns
    -------
    bool
        Whether any title changed.
    """
    box = fig.bbox
    changed = False
    for text in [*fig.texts, *(ax.title for ax in fig.axes)]:
        if not text.get_visible() or not text.get_text() or text.get_rotation() % 180:
            continue
        extent = text.get_window_extent(renderer)
        align = text.get_horizontalalignment()
        if align == "left":
            room = box.x1 - extent.x0
        elif align == "right":
            room = extent.x1 - box.x0
        else:
            room = 2.0 * min(0.5 * (extent.x0 + extent.x1) - box.x0, box.x1 - 0.5 * (extent.x0 + extent.x1))
        if extent.width <= room:
            continue

        def fits(line: str, text: Text = text, room: float = room) -> bool:
            return renderer.get_text_width_height_descent(line, text.get_fontproperties(), ismath=False)[0] <= room

        lines = [piece for line in text.get_text().split("\n") for piece in _broken(line, fits)]
        if "\n".join(lines) != text.get_text():
            text.set_text("\n".join(lines))
            changed = True
    return changed


def _broken(line: str, fits: Callable[[str], bool]) -> list[str]:
    """``line`` as lines that ``fits`` accepts, broken as :func:`wrap_to_width` says (a piece
    without any break stays as it is)."""
    out = []
    while not fits(line):
        cuts = {sep: [m.end() for m in re.finditer(re.escape(sep), line)] for sep in BREAKS}
        every = sorted(c for found in cuts.values() for c in found if c < len(line))
        if not every:
            break
        good = [max(fitting) for sep in BREAKS if (fitting := [c for c in cuts[sep] if fits(line[:c].rstrip())])]
        cut = good[0] if good else every[0]
        out.append(line[:cut].rstrip())
        line = line[cut:]
    return out + [line]


def on_canvas(fig: Figure, renderer, pad: float = 0.5) -> bool:
    """Whether what constrained layout does not keep on the canvas lies on it: the figure-level
    texts and legends, the x extent of each axes' title and x label and the y extent of its y
    label — what matplotlib's layout bounding box leaves out (``Axes.get_tightbbox``,
    ``for_layout_only``), and the only extents of those labels that do not wait for the next draw
    to follow the axes to where the layout put them.

    Parameters
    ----------
    fig, renderer
        As :func:`wrap_to_width`.
    pad : float
        Pixels an extent may pass the canvas's edge (rounding).

    Returns
    -------
    bool
    """
    box = fig.bbox

    def inside(artist, across: bool = True, along: bool = True) -> bool:
        if not artist.get_visible() or (isinstance(artist, Text) and not artist.get_text()):
            return True
        e = artist.get_window_extent(renderer)
        return ((not across or (e.x0 >= box.x0 - pad and e.x1 <= box.x1 + pad))
                and (not along or (e.y0 >= box.y0 - pad and e.y1 <= box.y1 + pad)))

    return (all(inside(a) for a in (*fig.texts, *fig.legends))
            and all(inside(t, along=False) for ax in fig.axes for t in (ax.title, ax.xaxis.label))
            and all(inside(ax.yaxis.label, across=False) for ax in fig.axes))


def pair_label(ds: xr.Dataset) -> str:
    """The dataset's gear pair as a reader knows it: its data ("29/71 teeth, module 5 mm, helix
    27.5°, face 42 mm", from the pair data the result was computed with), after its name for a
    pair of the user's own; the shipped example pairs' names (helical_z29_71_m5, ...) only restate
    their data, so they are left out. Empty for a result of no single pair.

    Parameters
    ----------
    ds : xarray.Dataset
        A stage's dataset; reads its attributes ``pair_name`` and ``config_json`` (the pair's
        ``teeth``, ``normal_module_mm``, ``helix_angle_deg``, ``face_width_mm``).

    Returns
    -------
    str
    """
    name = ds.attrs.get("pair_name", "")
    try:
        pair = json.loads(ds.attrs.get("config_json", "{}")).get("pair") or {}
    except ValueError:
        pair = {}
    if not {"teeth", "normal_module_mm", "helix_angle_deg", "face_width_mm"} <= set(pair):
        return name
    widths = sorted({number(b) for b in pair["face_width_mm"]}) if isinstance(pair["face_width_mm"], list) \
        else [number(pair["face_width_mm"])]
    data = (f"{'/'.join(str(z) for z in pair['teeth'])} teeth, module {number(pair['normal_module_mm'])} mm, "
            f"helix {number(pair['helix_angle_deg'])}°, face {'/'.join(widths)} mm")
    return data if not name or name in example_pairs() else f"{name}: {data}"


def title(ds: xr.Dataset, what: str, own_line: bool = False) -> str:
    """'PAIR — what', the pair as :func:`pair_label` names it.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset the figure is drawn from (its pair attributes).
    what : str
        What the figure shows.
    own_line : bool, default False
        ``what`` on a line of its own (a title too long for one line of its figure).

    Returns
    -------
    str
    """
    pair = pair_label(ds)
    if not pair or not what:
        return pair or what
    return f"{pair} —" + ("\n" if own_line else " ") + what


def number(value: float, digits: int = 3) -> str:
    """A value for a label: whole numbers from 100 up (118.367 → "118", 12500 → "12500"), below
    that ``digits`` significant digits (13.224 → "13.2", 0.01234 → "0.0123"), below 0.001 with an
    exponent (1.22e-15); no trailing zeros. The netCDF file keeps the full value; a label only has
    to tell values apart.

    Parameters
    ----------
    value : float
        The value, in the unit the label states.
    digits : int
        Significant digits below 100 (default 3).

    Returns
    -------
    str
    """
    v = float(value)
    if not np.isfinite(v):
        return str(v)
    if v != 0 and abs(v) < 1e-3:
        return f"{v:.{digits}g}"
    if abs(v) >= 10 ** (digits - 1) or v == round(v):
        return f"{round(v):d}"
    return np.format_float_positional(v, precision=digits, unique=True, fractional=False, trim="-")


def plain_log_axis(ax, axis: str = "y") -> None:
    """Tick labels of a logarithmic axis as plain numbers (5000, 20000; not 5×10³, 2×10⁴); the
    minor ticks at 2, 3 and 5 labelled too on an axis spanning about a decade, at 2 and 5 on one
    spanning up to about two and a half.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes with a logarithmic axis.
    axis : {'y', 'x'}
        Which axis (default 'y').
    """
    target = ax.yaxis if axis == "y" else ax.xaxis
    limits = ax.get_ylim if axis == "y" else ax.get_xlim

    def minor(v: float, _) -> str:
        lo, hi = sorted(abs(x) for x in limits())
        if v <= 0 or lo <= 0 or hi / lo > 300:
            return ""
        digits = (2, 3, 5) if hi / lo <= 12 else (2, 5)
        return number(v) if round(v / 10 ** np.floor(np.log10(v))) in digits else ""

    target.set_major_formatter(FuncFormatter(lambda v, _: number(v) if v > 0 else ""))
    target.set_minor_formatter(FuncFormatter(minor))


def figure_legend(fig, ncol: int = 3, fontsize: float = 8):
    """One legend under all panels of ``fig`` (constrained layout), each label once, in the order
    the panels first use it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure with constrained layout.
    ncol : int
        Legend columns (default 3).
    fontsize : float
        Points (default 8).

    Returns
    -------
    matplotlib.legend.Legend
    """
    seen: dict[str, Any] = {}
    for ax in fig.axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(label, handle)
    return fig.legend(list(seen.values()), list(seen), loc="outside lower center", ncol=ncol, fontsize=fontsize)


def legend_below(ax, ncol: int = 2, **kwargs: Any):
    """The legend of ``ax`` under its x label, so it covers no curve (for axes whose curves fill
    every corner).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    ncol : int
        Legend columns (default 2).
    **kwargs
        Passed to ``Axes.legend``.

    Returns
    -------
    matplotlib.legend.Legend
    """
    return ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=ncol, fontsize=7, **kwargs)


#: Curves closer than this fraction of the axis range everywhere are one curve on the page (a pixel
#: of a 250-pixel axis; lines are 1–2 pixels wide).
SAME_CURVE = 4e-3


def coinciding(curves, span: float | None = None) -> list[list[int]]:
    """Groups of row indices of ``curves`` (rows of y values on one x grid) that coincide to
    :data:`SAME_CURVE` of ``span`` (the axis range; default their own range), in first-appearance
    order: draw one line per group and name every member in its label, instead of a legend entry
    for a curve hidden under another.

    Parameters
    ----------
    curves : array_like
        ``(n, x)`` y values in the unit drawn; NaN where a curve has no value (must match to coincide).
    span : float, optional
        The axis range in the same unit; default the finite values' peak-to-peak.

    Returns
    -------
    list of list of int
    """
    y = np.asarray(curves, dtype=float)
    finite = y[np.isfinite(y)]
    if span is None:
        span = float(np.ptp(finite)) if finite.size else 0.0
    tol = SAME_CURVE * (span or 1.0)
    groups: list[list[int]] = []
    for k, row in enumerate(y):
        for group in groups:
            ref = y[group[0]]
            both = np.isfinite(ref) & np.isfinite(row)
            if np.array_equal(np.isfinite(ref), np.isfinite(row)) and np.all(np.abs(ref[both] - row[both]) <= tol):
                group.append(k)
                break
        else:
            groups.append([k])
    return groups


def text_line(ax, fontsize: float) -> float:
    """The height of one line of text of ``fontsize`` points (with its spacing) as a fraction of
    the height of ``ax``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    fontsize : float
        Points.

    Returns
    -------
    float
    """
    height_pt = ax.get_position().height * ax.get_figure().get_figheight() * 72.0
    return 1.25 * fontsize / max(height_pt, 1.0)


def apart(positions, gap: float, top: float = 1.0) -> np.ndarray:
    """Label positions (axes fractions) moved up as little as needed to be ``gap`` apart, in the
    order of ``positions``; a stack pushed above ``top`` shifted down as a whole.

    Parameters
    ----------
    positions : array_like
        ``(n,)`` wanted positions (axes fractions).
    gap : float
        Least distance between two labels (axes fraction, e.g. :func:`text_line`).
    top : float
        Highest position allowed (default 1.0).

    Returns
    -------
    numpy.ndarray
        ``(n,)`` positions (axes fractions).
    """
    pos = np.asarray(positions, dtype=float)
    placed = np.empty_like(pos)
    last = -np.inf
    for k in np.argsort(pos, kind="stable"):
        placed[k] = max(pos[k], last + gap)
        last = placed[k]
    if pos.size and last > top:
        placed -= last - top
    return placed


def end_labels(ax, ends, texts, fontsize: float = 6.5, color: str = "0.3") -> None:
    """Label lines at their right ends, outside the axes (where no data or frame cuts them),
    moved apart vertically where they would overlap; call after the y limits are final.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes with a linear y axis.
    ends : array_like
        ``(n,)`` the lines' last y values (data units).
    texts : sequence of str
        ``(n,)`` labels.
    fontsize : float
        Points (default 6.5).
    color : str
        Matplotlib colour (default '0.3').
    """
    lo, hi = ax.get_ylim()
    placed = apart((np.asarray(ends, dtype=float) - lo) / (hi - lo), text_line(ax, fontsize))
    for y, text in zip(placed, texts):
        ax.annotate(text, (1.0, y), xycoords="axes fraction", xytext=(3, 0), textcoords="offset points",
                    fontsize=fontsize, color=color, va="center", annotation_clip=False)


#: A curve whose peak-to-peak is below this fraction of its mean is drawn flat, with a note.
FLAT = 1e-4


def plain_axis(ax, values, unit: str, what: str = "") -> None:
    """Plain y tick labels (no offset or scientific notation such as "1e-5 + 6.736"), and a
    curve that is constant to better than :data:`FLAT` of its mean shown as what it is: flat
    (axis at least ±5 % of the mean wide) with a note giving its relative and absolute
    peak-to-peak, instead of noise or slice discretisation blown up into a square wave.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes the curve is drawn on.
    values : array_like
        The curve's y values as drawn (NaN ignored).
    unit : str
        Their unit, for the note.
    what : str
        The curve's name, for the note (default none).
    """
    ax.ticklabel_format(axis="y", style="plain", useOffset=False)
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return
    centre, pp = float(np.mean(v)), float(np.ptp(v))
    if centre == 0 or pp > FLAT * abs(centre):
        return
    lo, hi = ax.get_ylim()
    if hi - lo < 0.1 * abs(centre):
        ax.set_ylim(centre - 0.05 * abs(centre), centre + 0.05 * abs(centre))
    ax.text(0.01, 0.62, f"{what + ' ' if what else ''}constant to {max(pp / abs(centre), 1e-16):.0e} of its mean "
            f"(peak-to-peak {pp:.2g} {unit})", transform=ax.transAxes, fontsize=8, color="0.25",
            bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.85})
