"""TCA/LTCA figures: TE and LTE against rotation for every torque, the loaded contact pattern
on the pinion flank, and the unloaded separations of the TCA."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .common import MM, UM, plt, save as _save, title as _title

__all__ = ["plot_te_lte", "plot_contact_pattern", "plot_tca", "tca_figures", "ltca_figures"]


def _angle_mrad(ds: xr.Dataset) -> np.ndarray:
    return ds["pinion_angle"].values * 1e3


def plot_te_lte(ds: xr.Dataset, path: str | Path) -> Path:
    """Unloaded TE and the LTE of every torque over one mesh cycle (µm along the transverse
    line of action, + gear lags), with the start of engagement φ1A, LTE(φ1A) and the
    entering pair's separation TE(φ1A) (seed 000's comparison)."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    x = _angle_mrad(ds)
    xa = float(ds["pinion_angle_engagement"]) * 1e3
    ax.plot(x, ds["te"].values * UM, color="k", lw=1.6, label="TE (unloaded)")
    colors = plt.cm.viridis(np.linspace(0.1, 0.85, ds.sizes["torque"]))
    for color, k in zip(colors, range(ds.sizes["torque"])):
        sel = ds.isel(torque=k)
        ax.plot(x, sel["lte"].values * UM, color=color, lw=1.6,
                label=f"LTE, T1 = {float(sel.torque):g} N m (p-p {float(sel.lte_peak_to_peak) * UM:.2f} µm)")
        ax.plot([xa], [float(sel["lte_at_engagement"]) * UM], "o", color=color, ms=5)
    ax.axvline(xa, color="0.4", ls=":", lw=1.0, label="start of engagement φ1A")
    ax.plot([xa], [float(ds["te_next_pair_at_engagement"]) * UM], "s", color="k", ms=5,
            label="entering pair's separation TE(φ1A)")
    ax.set_xlabel("pinion rotation φ1 over one mesh cycle (mrad)")
    ax.set_ylabel("transmission error along the line of action (µm)")
    ax.set_title(_title(ds, f"TE and LTE ({ds.attrs.get('contact_law', '')} contact law)"))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    return _save(fig, path)


def _pattern(ds: xr.Dataset, k: int, bins: int = 80):
    """The largest line load over the mesh cycle at each (pinion roll length, z) cell (N/mm)."""
    sel = ds.isel(torque=k)
    rho = ds["rho_pinion"].values
    # tip-edge points of the recess touch the pinion at its tip: plot them there
    load = sel["line_load"].values * 1e-3
    rho_sap, rho_eap = (float(v) for v in (ds["rho_sap"][0], ds["rho_eap"][0]))
    lo = min(rho_sap, np.nanmin(rho)) if np.isfinite(rho).any() else rho_sap
    edges = np.linspace(lo, rho_eap, bins + 1)
    ok = np.isfinite(rho) & (load > 0)
    cell = np.clip(np.searchsorted(edges, rho[ok], side="right") - 1, 0, bins - 1)
    col = np.broadcast_to(np.arange(ds.sizes["point"]), load.shape)[ok]
    grid = np.full((bins, ds.sizes["point"]), np.nan)
    np.fmax.at(grid, (cell, col), load[ok])
    return edges, grid


def plot_contact_pattern(ds: xr.Dataset, path: str | Path) -> Path:
    """The loaded contact pattern on the pinion flank for every torque: the largest line load
    (N/mm) over the mesh cycle against axial position z and pinion roll length ρ1, with the
    SAP and tip (EAP) marked."""
    n = ds.sizes["torque"]
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 4.6), squeeze=False, sharey=True)
    z = ds["point"].values * MM
    dz = float(ds["point_width"]) * MM
    z_edges = np.append(z - 0.5 * dz, z[-1] + 0.5 * dz)
    patterns = [_pattern(ds, k) for k in range(n)]
    vmax = max(float(np.nanmax(p[1])) if np.isfinite(p[1]).any() else 1.0 for p in patterns)
    mesh = None
    for k, ax in enumerate(axes[0]):
        edges, grid = patterns[k]
        mesh = ax.pcolormesh(z_edges, edges * MM, grid, cmap="inferno", vmin=0, vmax=vmax, shading="flat")
        for name, ls in (("rho_sap", "--"), ("rho_eap", "-")):
            ax.axhline(float(ds[name][0]) * MM, color="tab:cyan", ls=ls, lw=0.9)
        sel = ds.isel(torque=k)
        ax.set_title(f"T1 = {float(sel.torque):g} N m\nmax {float(sel.max_line_load_cycle) * 1e-3:.0f} N/mm", fontsize=9)
        ax.set_xlabel("z across the face (mm)")
    axes[0][0].set_ylabel("pinion roll length ρ1 (mm); dashed SAP, solid tip")
    fig.colorbar(mesh, ax=axes[0].tolist(), label="largest line load over the mesh cycle (N/mm)")
    fig.suptitle(_title(ds, "loaded contact pattern on the pinion flank"), y=1.04)
    return _save(fig, path)


def plot_tca(ds: xr.Dataset, path: str | Path) -> Path:
    """Unloaded TCA: the TE of the mesh and of each tooth pair over one mesh cycle, and the
    path of each pair's first-contact point on the pinion flank (z, ρ1)."""
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    x = _angle_mrad(ds)
    ax1.plot(x, ds["te"].values * UM, color="0.75", lw=4.0, label="TE of the mesh", zorder=1)
    # a tooth pair whose whole contact line touches at once (perfect flanks) has no single
    # first-contact point: those positions are left out of the path instead of an arbitrary point
    sep = ds["separation"].values
    finite = np.isfinite(sep)
    spread = np.where(finite, sep, -np.inf).max(axis=2) - np.where(finite, sep, np.inf).min(axis=2)
    whole_line = (finite.sum(axis=2) >= 2) & (spread < 1e-9)  # (position, line)
    styles = ("--", "-.", ":", (0, (5, 1, 1, 1)))
    for j in range(ds.sizes["line"]):
        te_j = ds["te_pair"].isel(line=j).values * UM
        note = " (0 over the cycle)" if np.nanmax(np.abs(te_j)) == 0 else ""
        ax1.plot(x, te_j, lw=1.3, ls=styles[j % len(styles)], label=f"pair j = {int(ds.line[j])}{note}", zorder=2)
        z = np.where(whole_line[:, j], np.nan, ds["contact_z"].isel(line=j).values) * MM
        ax2.plot(z, ds["contact_rho_pinion"].isel(line=j).values * MM, ".-", ms=3, lw=0.8,
                 label=f"pair j = {int(ds.line[j])}")
    ax1.axvline(float(ds["pinion_angle_engagement"]) * 1e3, color="0.4", ls=":", lw=1.0, label="φ1A")
    ax1.set_yscale("symlog", linthresh=1.0)  # the µm TE and the 100 µm separations of the other pairs
    ax1.set_ylim(bottom=-0.05)
    ax1.set_xlabel("pinion rotation φ1 over one mesh cycle (mrad)")
    ax1.set_ylabel("unloaded separation / TE (µm),\nlinear to 1 µm, logarithmic above")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    if whole_line.any():
        ax2.text(0.02, 0.02, "whole line touching at once (perfect flanks): no single point, not drawn",
                 transform=ax2.transAxes, fontsize=7, color="0.3")
    half = 0.5 * float(ds["face_width"]) * MM
    ax2.add_patch(plt.Rectangle((-half, float(ds.rho_sap[0]) * MM), 2 * half,
                                float(ds.rho_eap[0] - ds.rho_sap[0]) * MM, fill=False, ec="0.4"))
    ax2.set_xlabel("z across the face (mm)")
    ax2.set_ylabel("pinion roll length ρ1 (mm)")
    ax2.set_title("first-contact points of each pair", fontsize=9)
    fig.suptitle(_title(ds, f"unloaded TCA, TE p-p {float(ds.te_peak_to_peak) * UM:.2f} µm"))
    return _save(fig, path)


def tca_figures(inputs, outputs) -> None:
    """The figure of the ``tca`` rule from its ``tca`` dataset."""
    plot_tca(inputs["tca"], outputs["tca"])


def ltca_figures(inputs, outputs) -> None:
    """The figures of the ``ltca`` rule from its ``ltca`` dataset."""
    plot_te_lte(inputs["ltca"], outputs["te_lte"])
    plot_contact_pattern(inputs["ltca"], outputs["contact_pattern"])
