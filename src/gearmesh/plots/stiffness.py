"""Stiffness-stage figures: K(φ) with its Fourier fit and the ISO mean, the comparison table,
and the slice-count convergence."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..choices import TOOTH_MODEL_NAMES
from .common import MM, plain_axis, save, subplots, title, UM

N_PER_UM = 1e-6  # N/m -> N/µm


def plot_mesh_stiffness(ds: xr.Dataset, path: str | Path) -> Path:
    """K(φ), its Fourier series, the ISO 6336-1 mean, one tooth pair's k, and the LSTE."""
    n = 3 if "lste" in ds else 2
    fig, axes = subplots(n, 1, figsize=(7.5, 2.8 * n), sharex=False)
    ax = axes[0]
    x = ds["position"].values * MM
    ax.plot(x, ds["mesh_stiffness"].values * N_PER_UM, lw=1.8, label="K(φ), slice model")
    ax.plot(x, ds["mesh_stiffness_fourier"].values * N_PER_UM, "--", lw=1.2,
            label=f"Fourier, order {ds.attrs.get('fourier_order', '')}")
    ax.axhline(float(ds["iso6336_mesh_stiffness"]) * N_PER_UM, color="k", ls=":", lw=1, label="ISO 6336-1 cγα·b")
    ax.set_ylabel("K (N/µm)")
    ax.set_xlabel("pinion roll distance over one base pitch (mm)")
    model = TOOTH_MODEL_NAMES.get(ds.attrs.get("tooth_model", ""), ds.attrs.get("tooth_model", ""))
    ax.set_title(title(ds, f"mesh stiffness, {model}, {ds.attrs.get('slices', '')} slices; "
                           f"εk = {100 * float(ds.fluctuation):.1f} %"))
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    plain_axis(ax, ds["mesh_stiffness"].values * N_PER_UM, "N/µm", "K(φ)")
    ax = axes[1]
    ax.plot(ds["pair_position"].values * MM, ds["pair_stiffness"].values * N_PER_UM, lw=1.5, color="tab:green")
    ax.set_xlabel("one tooth pair: mid-face contact position on the line of action (mm)")
    ax.set_ylabel("k pair (N/µm)")
    ax.grid(alpha=0.3)
    if n == 3:
        ax = axes[2]
        ax.plot(x, ds["lste"].values * UM, lw=1.5, color="tab:red")
        ax.set_xlabel("pinion roll distance over one base pitch (mm)")
        ax.set_ylabel("LSTE F/K (µm)")
        ax.set_title(f"pinion torque {float(ds.pinion_torque):.1f} N m: mean {float(ds.lste_mean) * UM:.2f} µm, "
                     f"peak-to-peak {float(ds.lste_peak_to_peak) * UM:.2f} µm", fontsize=9)
        ax.grid(alpha=0.3)
        plain_axis(ax, ds["lste"].values * UM, "µm", "LSTE")
    fig.tight_layout()
    return save(fig, path)


def plot_stiffness_table(ds: xr.Dataset, path: str | Path) -> Path:
    """Mean K (bars, min–max whiskers) of every case and method, with the ISO value as a line
    across each case's bars; the legend beside the axes, clear of the bars."""
    cases, methods = ds["case"].values, ds["model"].values
    fig, ax = subplots(figsize=(min(16, 4 + 0.9 * len(cases) * max(1, len(methods) // 2)), 4.5), layout="constrained")
    width = 0.8 / len(methods)
    idx = np.arange(len(cases))
    for k, m in enumerate(methods):
        sel = ds.sel(model=m)
        mean = sel["mean_stiffness"].values * N_PER_UM
        err = np.stack([mean - sel["min_stiffness"].values * N_PER_UM, sel["max_stiffness"].values * N_PER_UM - mean])
        ax.bar(idx + (k - (len(methods) - 1) / 2) * width, mean, width, yerr=err, capsize=3, label=str(m))
    ax.hlines(ds["iso6336_mesh_stiffness"].isel(model=0).values * N_PER_UM, idx - 0.45, idx + 0.45, color="k", lw=1.8,
              zorder=5, label="ISO 6336-1 cγα·b")
    ax.set_xticks(idx, [str(c) for c in cases], rotation=20, ha="right", fontsize=8)
    ax.set_ylabel("mesh stiffness (N/µm): mean, whiskers min–max")
    ax.set_title("mesh stiffness by case and cantilever method")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="method", title_fontsize=8)
    ax.grid(alpha=0.3, axis="y")
    return save(fig, path)


#: The slice rules as a reader knows them (:mod:`gearmesh.stiffness`: 'centre' takes a whole slice
#: when its centre is on the active flank, 'clip' clips the end slices to it).
SLICE_RULES = {"centre": "whole slices (by their centre)", "clip": "end slices clipped"}


def plot_slice_convergence(ds: xr.Dataset, path: str | Path) -> Path:
    """|relative difference of the mean K| against the slice count, both slice rules."""
    fig, ax = subplots(figsize=(6.5, 4))
    n = ds["slices"].values
    for pair in ds["pair"].values:
        for rule in ds["rule"].values:
            err = np.abs(ds["mean_relative_difference"].sel(pair=pair, rule=rule).values)
            keep = err > 0
            ax.loglog(n[keep], err[keep], "o-", label=f"{pair}, {SLICE_RULES.get(str(rule), str(rule))}")
    ax.set_xlabel("slices over the face width")
    ax.set_ylabel("|mean K / finest clipped − 1|")
    ax.set_title("slice-count convergence of the mean mesh stiffness")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return save(fig, path)


def stiffness_figures(inputs, outputs) -> None:
    """The figure of the ``stiffness`` rule."""
    plot_mesh_stiffness(inputs["stiffness"], outputs["stiffness"])


def stiffness_table_figures(inputs, outputs) -> None:
    """The figure of the ``stiffness_table`` rule."""
    plot_stiffness_table(inputs["stiffness_table"], outputs["stiffness_table"])


def slice_convergence_figures(inputs, outputs) -> None:
    """The figure of the ``slice_convergence`` rule."""
    plot_slice_convergence(inputs["slice_convergence"], outputs["slice_convergence"])
