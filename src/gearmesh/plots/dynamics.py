"""Dynamics-stage figures: RMS against speed, mesh-force time series and spectra."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .common import UM, plain_axis, plt, save as _save, title as _title


def _resonances(ax, ds: xr.Dataset) -> None:
    """Faint vertical lines where mesh harmonics meet natural frequencies (in the speed range),
    one legend entry per harmonic."""
    if "resonance_speed" not in ds:
        return
    lo, hi = float(ds.speed.min()), float(ds.speed.max())
    styles = {1: ":", 2: "--", 3: "-."}
    for j, row in zip(ds.harmonic.values, ds.resonance_speed.values):
        label = f"{int(j)}× mesh frequency = natural frequency"
        for n in row:
            if lo <= n <= hi:
                ax.axvline(n, color="0.55", lw=0.8, ls=styles.get(int(j), ":"), label=label)
                label = None


def plot_rms_against_speed(ds: xr.Dataset, path: str | Path) -> Path:
    """Dynamic TE and mesh deflection (standard deviation, transverse line of action),
    displacement and velocity RMS against speed for both gears (seed 001 §4 figures).

    Displacements are shown as their standard deviation (the vibration about the static
    bearing deflection); vertical lines: speeds where mesh harmonics 1 (dotted), 2 (dashed),
    3 (dash-dot) meet the natural frequencies of the linearised model.
    """
    speed = ds.speed.values
    fig, axes = plt.subplots(3, 1, figsize=(9, 10.5), sharex=True)
    ax = axes[0]
    ax.plot(speed, ds.dynamic_te_std.values * UM, lw=1.3, label="dynamic TE (bodies' approach δ + e)")
    ax.plot(speed, ds.mesh_deflection_std.values * UM, lw=1.3, ls="--", label="mesh deflection δ_m")
    if "on_grid" in ds:
        added = ds.on_grid.values == 0
        ax.plot(speed[added], ds.dynamic_te_std.values[added] * UM, "k.", ms=2.5,
                label="speeds added around predicted resonances")
    ax.set_ylabel("standard deviation along the\ntransverse line of action (µm)")
    colors = {"x": "tab:blue", "y": "tab:orange", "z": "tab:green"}
    for ax, var, unit, scale, label in ((axes[1], "displacement_std", "µm", UM, "displacement (std)"),
                                        (axes[2], "velocity_rms", "mm/s", 1e3, "velocity RMS")):
        for g, ls in zip(ds.gear.values, ("-", "--")):
            for d in ds.direction.values:
                ax.plot(speed, ds[var].sel(gear=g, direction=d).values * scale, color=colors.get(str(d), None),
                        ls=ls, lw=1.1, label=f"{g} {d}")
        ax.set_ylabel(f"{label} ({unit})")
        ax.set_yscale("log")
        ax.legend(fontsize=7, ncol=2)
    for ax in axes:
        _resonances(ax, ds)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, loc="best", framealpha=0.9)
    axes[-1].set_xlabel("pinion speed (rpm)")
    axes[0].set_title(_title(ds, "steady-state RMS against speed"))
    return _save(fig, path)


def plot_force_spectrum(ds: xr.Dataset, path: str | Path) -> Path:
    """Mesh-force time series (two mesh periods) and amplitude spectrum at the kept speeds."""
    n = ds.sizes.get("sample_speed", 0)
    fig, axes = plt.subplots(max(n, 1), 2, figsize=(11, 1.0 + 2.6 * max(n, 1)), squeeze=False, layout="constrained")
    meshes = list(ds.mesh.values) if "mesh" in ds.dims else [None]
    same = ""
    if len(meshes) > 1:  # identical meshes (symmetric train): one trace, said so, not one hidden under the other
        series = ds.mesh_force_series.values
        scale = float(np.max(np.abs(series))) or 1.0
        if all(np.max(np.abs(series[..., k] - series[..., 0])) <= 1e-9 * scale for k in range(1, len(meshes))):
            same = " = ".join(map(str, meshes)) + " (identical to 1e-9)"
            meshes = meshes[:1]
    for i in range(n):
        sel = ds.isel(sample_speed=i)
        t = sel.time.values
        f_mesh = float(sel.frequency.values[np.flatnonzero(sel.order.values == 1)[0]])
        keep = t <= 2.0 / f_mesh
        for mname in meshes:
            F = sel.mesh_force_series if mname is None else sel.mesh_force_series.sel(mesh=mname)
            S = sel.mesh_force_spectrum if mname is None else sel.mesh_force_spectrum.sel(mesh=mname)
            lab = "" if mname is None else (same or str(mname))
            axes[i, 0].plot(t[keep] * 1e3, F.values[keep], lw=1.2, label=lab or None)
            fr, amp = sel.frequency.values[1:], S.values[1:]
            axes[i, 1].vlines(fr, 0, amp, lw=1.5, label=lab or None)
        axes[i, 0].axhline(float(np.atleast_1d(ds.static_mesh_force.values)[0]), color="k", lw=0.8, ls="--",
                           label="static force")
        axes[i, 0].set_ylabel("normal mesh force (N)")
        plain_axis(axes[i, 0], ds.mesh_force_series.isel(sample_speed=i).values, "N", "force")
        axes[i, 0].set_title(f"{float(sel.sample_speed):g} rpm, mesh frequency {f_mesh:.1f} Hz", fontsize=9)
        axes[i, 1].set_ylabel("amplitude, normal force (N)")
        axes[i, 1].set_yscale("log")
        top = float(np.nanmax(ds.mesh_force_spectrum.isel(sample_speed=i).values[1:]))
        if top > 0:
            axes[i, 1].set_ylim(top * 1e-4, top * 2.0)
        axes[i, 0].legend(fontsize=7)
        for ax in axes[i]:
            ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time (ms)")
    axes[-1, 1].set_xlabel("frequency (Hz)")
    fig.suptitle(_title(ds, "dynamic mesh force normal to the flanks: time series and spectrum (DC removed)"))
    return _save(fig, path)


def dynamics_figures(inputs, outputs) -> None:
    """The ``plot_dynamics`` rule: outputs 'rms' and 'spectrum' from input 'dynamics'."""
    ds = inputs["dynamics"]
    if "rms" in outputs:
        plot_rms_against_speed(ds, outputs["rms"])
    if "spectrum" in outputs:
        plot_force_spectrum(ds, outputs["spectrum"])


def train_figures(inputs, outputs) -> None:
    """The ``plot_train`` rule: output 'spectrum' (both meshes) from input 'train'."""
    plot_force_spectrum(inputs["train"], outputs["spectrum"])


def plot_dynamics_comparison(datasets, path) -> None:
    """Mesh-deflection std and pinion lateral (y) and axial (z) velocity RMS against speed, all pairs."""
    fig, axes = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    for ds in datasets:
        name = ds.attrs.get("pair_name", "")
        speed = ds["speed"].values
        axes[0].plot(speed, ds["mesh_deflection_std"].values * UM, lw=1.2, label=name)
        for ax, direction in zip(axes[1:], ("y", "z")):
            ax.plot(speed, ds["velocity_rms"].sel(gear="pinion", direction=direction).values * 1e3, lw=1.2)
    axes[0].set_ylabel("mesh deflection std (µm),\ntransverse (seed 001's DTE)")
    axes[1].set_ylabel("pinion y velocity RMS (mm/s)")
    axes[2].set_ylabel("pinion z velocity RMS (mm/s)")
    axes[2].set_xlabel("pinion speed (rpm)")
    for ax in axes:
        ax.set_yscale("log")
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    axes[0].set_title("speed sweeps of the study's pairs (standard variant)")
    _save(fig, path)


def dynamics_comparison_figures(inputs, outputs) -> None:
    """The ``plot_dynamics_comparison`` rule."""
    plot_dynamics_comparison(inputs["dynamics"], outputs["dynamics_comparison"])
