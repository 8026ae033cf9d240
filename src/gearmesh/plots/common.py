"""What every figure module shares: the Agg backend, saving, titles, unit scale."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from ..io import atomic_output  # noqa: E402

MM = 1e3  # m -> mm
UM = 1e6  # m -> µm

__all__ = ["MM", "UM", "plain_axis", "plt", "save", "title"]


def save(fig, path: str | Path) -> Path:
    """Write ``fig`` as PNG atomically (parent folders created) and close it."""
    try:
        with atomic_output(path) as tmp:
            fig.savefig(tmp, dpi=130, bbox_inches="tight", format="png")
    finally:
        plt.close(fig)
    return Path(path)


def title(ds: xr.Dataset, what: str) -> str:
    """'PAIR — what' from the dataset's pair_name attribute."""
    return f"{ds.attrs.get('pair_name', '')} — {what}".strip(" —")


#: A curve whose peak-to-peak is below this fraction of its mean is drawn flat, with a note.
FLAT = 1e-4


def plain_axis(ax, values, unit: str, what: str = "") -> None:
    """Plain y tick labels (no offset or scientific notation such as "1e-5 + 6.736"), and a
    curve that is constant to better than :data:`FLAT` of its mean shown as what it is: flat
    (axis at least ±5 % of the mean wide) with a note giving its relative and absolute
    peak-to-peak, instead of noise or slice discretisation blown up into a square wave."""
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
