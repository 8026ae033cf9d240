"""Dynamics-stage figures: RMS against speed, mesh-force time series and spectra, the entering
pair's engagement (contact excitation) and the variants' peak mesh force against speed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .common import MM, UM, plain_axis, plt, save as _save, title as _title


def _at_torque(ds: xr.Dataset, k: int | None = None) -> xr.Dataset:
    """The sweep at one torque (the middle one by default) of a dataset with a torque dimension."""
    if "torque" not in ds.dims:
        return ds
    return ds.isel(torque=ds.sizes["torque"] // 2 if k is None else k)


def _torque_label(ds: xr.Dataset) -> str:
    if "torque" not in ds.coords or ds["torque"].ndim:
        return ""
    return f"{float(ds['torque']):g} N m on the {ds.attrs.get('torque_on', 'pinion')}"


#: A dynamic TE fluctuation below this (µm) is below what the model means: the slice and position
#: discretisation of an ideally constant-stiffness (integer-overlap) pair leave a few nanometres,
#: while the flank form and pitch deviations of real gears are micrometres (ISO 1328-1: a few µm
#: even at accuracy grade 4 for these sizes), so the figure says so instead of plotting noise as a result.
MEANINGFUL_TE_UM = 0.01

#: Harmonics 2 and 3 are drawn only for modes with at least this fraction of their strain energy in
#: the mesh (the higher mesh harmonics are weak; a bearing mode they would meet barely responds),
#: harmonic 1 for every mode — so a sweep over a wide speed range is not crowded with lines.
MESH_ENERGY_MIN = 0.05


def _resonances(ax, ds: xr.Dataset) -> None:
    """Faint vertical lines where mesh harmonics meet natural frequencies (in the speed range):
    harmonic 1 for every mode, harmonics 2 and 3 for modes with at least :data:`MESH_ENERGY_MIN`
    of their strain energy in the mesh; one legend entry per harmonic."""
    if "resonance_speed" not in ds:
        return
    lo, hi = float(ds.speed.min()), float(ds.speed.max())
    styles = {1: ":", 2: "--", 3: "-."}
    mesh_modes = ds["mesh_energy_fraction"].values >= MESH_ENERGY_MIN if "mesh_energy_fraction" in ds \
        else np.ones(ds.sizes["mode"], dtype=bool)
    for j, row in zip(ds.harmonic.values, ds.resonance_speed.values):
        keep = np.ones(row.size, dtype=bool) if int(j) == 1 else mesh_modes
        label = f"{int(j)}× mesh frequency = natural frequency" + \
            ("" if int(j) == 1 else f" (modes ≥ {MESH_ENERGY_MIN:.0%} mesh energy)")
        for n in row[keep]:
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
    torques = range(ds.sizes["torque"]) if "torque" in ds.dims else [None]
    colors = plt.cm.viridis(np.linspace(0.1, 0.85, len(torques)))
    for k, color in zip(torques, colors):
        d = _at_torque(ds, k)
        tl = f", {_torque_label(d)}" if k is not None else ""
        ax.plot(speed, d.dynamic_te_std.values * UM, lw=1.3, color=color,
                label=f"dynamic TE (bodies' approach δ + e){tl}")
        ax.plot(speed, d.mesh_deflection_std.values * UM, lw=1.0, ls="--", color=color,
                label=f"mesh deflection δ_m{tl}")
    mid = _at_torque(ds)
    if "on_grid" in ds:
        added = ds.on_grid.values == 0
        ax.plot(speed[added], mid.dynamic_te_std.values[added] * UM, "k.", ms=2.5,
                label="speeds added around predicted resonances")
    top = float(np.nanmax(ds.dynamic_te_std.values)) * UM
    subtitle = ""
    if top < MEANINGFUL_TE_UM:
        subtitle = (f"\nlargest TE fluctuation {top * 1e3:.2g} nm: below what the model means (its discretisation "
                    "leaves nanometres,\nreal flanks deviate by micrometres) — read it as no excitation")
    ax.set_ylabel("standard deviation along the\ntransverse line of action (µm)")
    dir_colors = {"x": "tab:blue", "y": "tab:orange", "z": "tab:green"}
    at = f" at {_torque_label(mid)}" if _torque_label(mid) else ""
    for ax, var, unit, scale, label in ((axes[1], "displacement_std", "µm", UM, "displacement (std)"),
                                        (axes[2], "velocity_rms", "mm/s", 1e3, "velocity RMS")):
        for g, ls in zip(ds.gear.values, ("-", "--")):
            for d in ds.direction.values:
                ax.plot(speed, mid[var].sel(gear=g, direction=d).values * scale, color=dir_colors.get(str(d), None),
                        ls=ls, lw=1.1, label=f"{g} {d}")
        ax.set_ylabel(f"{label}{at} ({unit})" if not at else f"{label} ({unit})\n{at.strip()}")
        ax.set_yscale("log")
        ax.legend(fontsize=7, ncol=2)
    for ax in axes:
        _resonances(ax, mid)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, loc="best", framealpha=0.9)
    axes[-1].set_xlabel("pinion speed (rpm)")
    axes[0].set_title(_title(ds, "steady-state RMS against speed") + subtitle, fontsize=11 if not subtitle else 9)
    return _save(fig, path)


def plot_force_spectrum(ds: xr.Dataset, path: str | Path) -> Path:
    """Mesh-force time series (two mesh periods) and amplitude spectrum at the kept speeds (at
    the middle torque of a sweep over several)."""
    ds = _at_torque(ds)
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
    at = f", {_torque_label(ds)}" if _torque_label(ds) else ""
    fig.suptitle(_title(ds, f"dynamic mesh force normal to the flanks{at}: time series and spectrum (DC removed)"))
    return _save(fig, path)


def plot_engagement(ds: xr.Dataset, path: str | Path) -> Path:
    """The engagement in the steady state (``contact`` excitation): per kept speed (rows) and
    torque (columns), the mesh force and the force of the tooth pair entering in each cycle over
    the first two recorded mesh cycles (normal, kN), with A (the theoretical start of
    engagement, solid), the quasi-static mesh-in point (dotted) and the dynamic one (dashed)."""
    n_s = ds.sizes.get("sample_speed", 0)
    torques = list(range(ds.sizes["torque"])) if "torque" in ds.dims else [None]
    fig, axes = plt.subplots(max(n_s, 1), len(torques), figsize=(4.2 * len(torques), 1.2 + 2.6 * max(n_s, 1)),
                             squeeze=False, sharex=True, layout="constrained")
    pitch, roll_a = float(ds.transverse_base_pitch), float(ds.roll_engagement)
    for c, k in enumerate(torques):
        d = _at_torque(ds, k)
        for r in range(n_s):
            ax = axes[r, c]
            sel = d.isel(sample_speed=r)
            f_mesh = float(sel.frequency.values[np.flatnonzero(sel.order.values == 1)[0]])
            cyc = sel.time.values * f_mesh  # mesh cycles from the start of the record (phase 0 = roll 0)
            keep = cyc <= 2.0
            ax.plot(cyc[keep], sel.mesh_force_series.values[keep] * 1e-3, lw=1.2, color="tab:blue",
                    label="mesh force (all pairs)")
            # the entering pair is followed from p_bt/2 before A to p_bt/2 after it; break the line
            # where the next pair takes its place instead of drawing a drop
            fe = sel.entering_pair_force_series.values[keep] * 1e-3
            window = np.mod(cyc[keep] * pitch - roll_a + 0.5 * pitch, pitch)
            wrap = np.concatenate([[False], np.diff(window) < 0])
            fe = np.where(wrap | np.roll(wrap, -1), np.nan, fe)  # the samples on both sides of the switch
            ax.plot(cyc[keep], fe, lw=1.2, color="tab:red", label="entering pair (±½ base pitch about A)")
            i_s = int(np.argmin(np.abs(d.speed.values - float(sel.sample_speed))))
            marks = ((0.0, "k", "-", "A (theoretical start of engagement)"),
                     (float(d.static_mesh_in_roll_before_A), "0.3", ":", "quasi-static mesh-in point"),
                     (float(d.mesh_in_roll_before_A.values[i_s]), "tab:red", "--", "dynamic mesh-in point"))
            for before, color, ls, label in marks:
                for cycle in (0, 1, 2):
                    x = (roll_a - before) / pitch + cycle
                    if 0 <= x <= 2:
                        ax.axvline(x, color=color, ls=ls, lw=0.9, label=label)
                        label = None
            ax.set_title(f"{float(sel.sample_speed):g} rpm, {_torque_label(d)}: mesh-in "
                         f"{float(d.mesh_in_roll_before_A.values[i_s]) * MM:.2f} mm before A "
                         f"(quasi-static {float(d.static_mesh_in_roll_before_A) * MM:.2f})", fontsize=7)
            ax.grid(alpha=0.3)
            if c == 0:
                ax.set_ylabel("normal force (kN)")
    axes[0, 0].legend(fontsize=6, loc="upper left", framealpha=0.9)
    for ax in axes[-1]:
        ax.set_xlabel("mesh cycles (pinion roll / transverse base pitch)")
    fig.suptitle(_title(ds, "engagement in the steady state, driven by the real tooth contact"), fontsize=10)
    return _save(fig, path)


def dynamics_figures(inputs, outputs) -> None:
    """The figures of the ``dynamics`` rule: outputs 'rms', 'spectrum' and (contact) 'engagement' from input 'dynamics'."""
    ds = inputs["dynamics"]
    if "rms" in outputs:
        plot_rms_against_speed(ds, outputs["rms"])
    if "spectrum" in outputs:
        plot_force_spectrum(ds, outputs["spectrum"])
    if "engagement" in outputs:
        plot_engagement(ds, outputs["engagement"])


def plot_variants_peak_force(datasets, path: str | Path) -> Path:
    """Peak dynamic mesh force (normal) against speed, every variant on one axis (colour), one
    panel per torque; the static force as a dashed line; with the contact excitation a second
    row: the entering pair's dynamic impact (its force above its quasi-static force)."""
    ref = datasets[0]
    torques = list(range(ref.sizes["torque"])) if "torque" in ref.dims else [None]
    contact = all("dynamic_impact_force" in d for d in datasets)
    rows = 2 if contact else 1
    fig, axes = plt.subplots(rows, len(torques), figsize=(4.3 * len(torques), 3.6 * rows), squeeze=False,
                             layout="constrained")
    colors = plt.cm.tab10(np.arange(len(datasets)))
    for c, k in enumerate(torques):
        for color, ds in zip(colors, datasets):
            d = _at_torque(ds, k)
            name = ds.attrs.get("variant", "")
            axes[0, c].plot(d.speed.values, d.mesh_force_max.values * 1e-3, lw=1.3, color=color, label=name)
            if contact:
                axes[1, c].plot(d.speed.values, d.dynamic_impact_force.values * 1e-3, lw=1.3, color=color, label=name)
        d0 = _at_torque(ref, k)
        axes[0, c].axhline(float(d0.static_mesh_force) * 1e-3, color="k", ls="--", lw=0.8, label="static force")
        axes[0, c].set_title(_torque_label(d0), fontsize=9)
        axes[0, c].set_ylabel("peak dynamic mesh force, normal (kN)")
        if contact:
            axes[1, c].set_ylabel("entering pair: dynamic impact,\nforce above quasi-static (kN)")
        for ax in axes[:, c]:
            ax.grid(alpha=0.3)
            ax.set_xlabel("pinion speed (rpm)")
    axes[0, 0].legend(fontsize=7, title="variant", title_fontsize=7)
    fig.suptitle(_title(ref, "peak dynamic mesh force against speed, all variants"), fontsize=10)
    return _save(fig, path)


def dynamics_variants_figures(inputs, outputs) -> None:
    """The figure of the ``engagement_table`` rule (or ``plot_dynamics_variants`` without one)."""
    sets = inputs["dynamics"]
    plot_variants_peak_force(sets if isinstance(sets, (list, tuple)) else [sets], outputs["dynamics_variants"])


def train_figures(inputs, outputs) -> None:
    """The figure of the ``train_dynamics`` rule: output 'spectrum' (both meshes) from input 'train'."""
    plot_force_spectrum(inputs["train"], outputs["spectrum"])


def plot_dynamics_comparison(datasets, path) -> None:
    """Mesh-deflection std and pinion lateral (y) and axial (z) velocity RMS against speed, all pairs."""
    fig, axes = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    for ds in datasets:
        name = ds.attrs.get("pair_name", "")
        ds = _at_torque(ds, 0)  # the comparison is at each sweep's first torque
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
    """The figure of the ``dynamics_comparison`` rule."""
    plot_dynamics_comparison(inputs["dynamics"], outputs["dynamics_comparison"])
