"""Optimiser figures: convergence (GA and random search on one axis), the optimum's
modification map δ(profile, face) on each flank it modifies, and NSGA-II's Pareto front."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..surface import relief_depth
from .common import MM, UM, plt, save as _save, title as _title

__all__ = ["plot_convergence", "plot_modification", "plot_pareto", "optimise_figures", "pareto_figures"]


def _scale(ds: xr.Dataset) -> tuple[float, str]:
    """Factor and label of the objective axis."""
    units = ds["objective"].attrs.get("units", "")
    return (1.0, "N") if units == "N" else (1.0, units.replace(" s-1", "/s"))


def plot_convergence(ds: xr.Dataset, path: str | Path) -> Path:
    """Best objective so far and the population median against generation, for the run and for
    the random search of the same budget, with the standard gear's objective for reference."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    k, unit = _scale(ds)
    gen = ds["generation"].values
    runs = [("", ds.attrs.get("method", "GA").upper(), "tab:blue")]
    if "random_objective" in ds:
        runs.append(("random_", "random search (same budget)", "tab:orange"))
    for prefix, label, color in runs:
        n = int(ds[f"{prefix}evaluations"])
        ax.plot(gen, ds[f"{prefix}best_objective"].values * k, color=color, lw=2.0, marker="o", ms=3,
                label=f"{label}: best so far ({n} evaluations)")
        ax.plot(gen, ds[f"{prefix}median_objective"].values * k, color=color, lw=1.0, ls="--",
                label=f"{label}: population median")
    ax.axhline(float(ds["standard_objective"]) * k, color="k", lw=1.0, ls=":", label="standard (unmodified) gear")
    ax.set_yscale("log")
    ax.set_xlabel("generation (0: initial population)")
    what = {"force": "F_s at the design point", "velocity": "|v_n| at the design point",
            "robust": f"F_s over the torques ({ds.attrs.get('objective_statistic', '')})"}
    ax.set_ylabel(f"objective: {what.get(ds.attrs.get('objective'), '')} ({unit})")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    red = float(ds["reduction"])
    ax.set_title(_title(ds, f"{ds.attrs.get('objective', '')} objective, seed {ds.attrs.get('seed', '')}: "
                            f"optimum {float(ds['optimum_objective']) * k:.4g} {unit} ({red:+.1f} % vs standard)"),
                 fontsize=9)
    return _save(fig, path)


def _depth_map(ds: xr.Dataset, gear: int, n_profile: int = 121, n_face: int = 81):
    """Roll lengths (m), face positions (m) and the removed depth δ (m) on gear ``gear``'s flank."""
    rho = np.linspace(float(ds["rho_sap"][gear]), float(ds["rho_eap"][gear]), n_profile)
    half = 0.5 * float(ds["face_width"])
    z = np.linspace(-half, half, n_face)
    depth = relief_depth(ds["optimum_modification"].values[gear], float(ds["rho_sap"][gear]),
                         float(ds["rho_eap"][gear]), float(ds["face_width"]), rho[:, None], z[None, :])
    return rho, z, depth


def plot_modification(ds: xr.Dataset, path: str | Path) -> Path:
    """The optimum's material removal δ (µm) against axial position z and roll length ρ on the
    active flank of the pinion and of the gear where it is modified (seed 000's parabolic tip
    and root reliefs and lead crowning, :func:`gearmesh.surface.modification_depth`)."""
    p = ds["optimum_modification"].values
    gears = [g for g in range(2) if g == 0 or np.any(p[g] > 0)]
    fig, axes = plt.subplots(1, len(gears), figsize=(5.2 * len(gears), 4.6), squeeze=False)
    symbols = ds["parameter_symbol"].values
    for ax, g in zip(axes[0], gears):
        rho, z, depth = _depth_map(ds, g)
        mesh = ax.pcolormesh(z * MM, rho * MM, depth * UM, cmap="viridis", shading="auto")
        levels = np.linspace(0, max(float(depth.max()), 1e-9), 8)[1:] * UM
        if depth.max() > 0:
            cs = ax.contour(z * MM, rho * MM, depth * UM, levels=levels, colors="w", linewidths=0.6)
            ax.clabel(cs, fmt="%.0f", fontsize=6)
        fig.colorbar(mesh, ax=ax, label="material removed δ (µm)")
        name = str(ds["gear"].values[g])
        text = ", ".join(f"{s} {v * (UM if k in (0, 1, 4) else MM):.3g}{' µm' if k in (0, 1, 4) else ' mm'}"
                         for k, (s, v) in enumerate(zip(symbols, p[g])))
        ax.set_title(f"{name} flank\n{text}", fontsize=7)
        ax.set_xlabel("z across the face (mm)")
        ax.set_ylabel(f"{name} roll length ρ (mm), SAP to tip")
    fig.suptitle(_title(ds, "optimum micro-geometry δ(profile, face)"), y=1.02)
    return _save(fig, path)


def plot_pareto(ds: xr.Dataset, path: str | Path) -> Path:
    """NSGA-II: F_s against peak-to-peak LTE at the design torque for every evaluated candidate
    (failed ones left out), the Pareto front and the standard gear."""
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ok = ds["failed"].values == 0
    f = ds["objective"].values[ok]
    lte = ds["lte_peak_to_peak"].values[ok] * UM
    ax.scatter(lte, f, s=6, color="0.7", label="evaluated candidates")
    ax.plot(ds["pareto_lte_peak_to_peak"].values * UM, ds["pareto_objective"].values, "o-", color="tab:red",
            ms=4, lw=1.2, label=f"Pareto front ({ds.sizes['front']} points)")
    ax.plot([float(ds["standard_lte_peak_to_peak"]) * UM], [float(ds["standard_objective"])], "ks", ms=6,
            label="standard (unmodified) gear")
    ax.set_yscale("log")
    ax.set_xlabel(f"peak-to-peak LTE at {float(ds['design_torque']):g} N m (µm)")
    ax.set_ylabel(f"mesh-in impact force F_s at {float(ds['speed']):g} rpm (N)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    ax.set_title(_title(ds, "NSGA-II: impact force against LTE"), fontsize=9)
    return _save(fig, path)


def optimise_figures(inputs, outputs) -> None:
    """The figures of the ``plot_optimise`` rule from its ``ga`` dataset."""
    plot_convergence(inputs["ga"], outputs["convergence"])
    plot_modification(inputs["ga"], outputs["modification"])


def pareto_figures(inputs, outputs) -> None:
    """The figure of the ``plot_pareto`` rule (NSGA-II runs)."""
    plot_pareto(inputs["ga"], outputs["pareto"])
