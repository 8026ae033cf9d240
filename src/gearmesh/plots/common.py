"""What every figure module shares: the Agg backend, saving, titles, unit scale."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

from ..io import atomic_output  # noqa: E402

MM = 1e3  # m -> mm
UM = 1e6  # m -> µm

__all__ = ["MM", "UM", "plt", "save", "title"]


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
