"""Dynamics-stage figures: RMS against speed, mesh-force time series and spectra, the entering
pair's engagement (contact excitation) and the variants' peak mesh force against speed.

The figure jobs (``dynamics_figures``, ``dynamics_variants_figures``, ``train_figures``,
``dynamics_comparison_figures``, each ``(inputs, outputs)`` as every ``*_figures`` of :mod:`gearmesh.plots`)
take ``inputs``, a mapping of str to xarray.Dataset (or a list of them, one per variant or pair), the rule's
netCDF inputs by name, and ``outputs``, a mapping of str to the path of each PNG by name; they write them
and return None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib import colormaps

from .common import (coinciding, figure_legend, MM, number, pair_label, palette, plain_axis, plain_log_axis, save as _save,
                     subplots, title as _title, UM)


def _at_torque(ds: xr.Dataset, k: int | None = None) -> xr.Dataset:
    """The sweep at one torque (the middle one by default) of a dataset with a torque dimension."""
    if "torque" not in ds.dims:
        return ds
    return ds.isel(torque=ds.sizes["torque"] // 2 if k is None else k)


def _torque_label(ds: xr.Dataset) -> str:
    if "torque" not in ds.coords or ds["torque"].ndim:
        return ""
    return f"{number(float(ds['torque']))} N m on the {ds.attrs.get('torque_on', 'pinion')}"


#: A dynamic TE fluctuation below this (µm) is below what the model means: the slice and position
#: discretisation of an ideally constant-stiffness (integer-overlap) pair leave a few nanometres,
#: while the flank form and pitch deviations of real gears are micrometres (ISO 1328-1: a few µm
#: even at accuracy grade 4 for these sizes), so the figure says so instead of plotting noise as a result.
MEANINGFUL_TE_UM = 0.01


def _below_meaning(datasets) -> str:
    """A title line saying the sweeps' dynamic TE is below what the model means, when it is in
    every dataset (empty otherwise)."""
    top = max(float(np.nanmax(ds.dynamic_te_std.values)) * UM for ds in datasets)
    if top >= MEANINGFUL_TE_UM:
        return ""
    return (f"\nlargest TE fluctuation {number(top * 1e3)} nm: below what the model means (its discretisation "
            "leaves nanometres,\nreal flanks deviate by micrometres) — read it as no excitation")

#: Resonance lines are drawn only for modes with at least this fraction of their strain energy in
#: the mesh: the mesh does work on a mode in proportion to that share, so a mode below it (a bearing
#: mode, a free axial mode with 1e-31) is not excited by the mesh and its lines would only crowd the
#: figure (they did on the wide sweeps of the integer-overlap pairs), while the peaks of the
#: displacement curves sit on the lines of the modes above it, for every harmonic.
MESH_ENERGY_MIN = 0.01


def _resonances(ax, ds: xr.Dataset, labelled: bool = True) -> None:
    """Faint vertical lines where mesh harmonics 1–3 meet the natural frequencies (in the speed
    range) of the mesh modes, those with at least :data:`MESH_ENERGY_MIN` of their strain energy in the mesh;
    one legend entry per harmonic (``labelled``)."""
    if "resonance_speed" not in ds:
        return
    lo, hi = float(ds.speed.min()), float(ds.speed.max())
    styles = {1: ":", 2: "--", 3: "-."}
    mesh_modes = ds["mesh_energy_fraction"].values >= MESH_ENERGY_MIN if "mesh_energy_fraction" in ds \
        else np.ones(ds.sizes["mode"], dtype=bool)
    for j, row in zip(ds.harmonic.values, ds.resonance_speed.values):
        label = f"{int(j)}× mesh frequency = natural frequency of a mesh mode" if labelled else None
        for n in row[mesh_modes]:
            if lo <= n <= hi:
                ax.axvline(n, color="0.55", lw=0.8, ls=styles.get(int(j), ":"), label=label)
                label = None


#: The translations of the 8-degree-of-freedom pair, as the dynamics dataset's ``direction`` says.
DIRECTIONS = "x: along the line of centres\ny: across it (the common tangent)\nz: axial"


def plot_rms_against_speed(ds: xr.Dataset, path: str | Path) -> Path:
    """Dynamic TE and mesh deflection (standard deviation, transverse line of action),
    displacement standard deviation and velocity RMS (the same: a periodic motion has no mean
    velocity) against speed for both gears (the low-fluctuation paper's section 4 figures), the
    directions named in the legends (x along the line of centres, y across it, z axial).

    Displacements are shown as their standard deviation (the vibration about the static
    bearing deflection); vertical lines: speeds where mesh harmonics 1 (dotted), 2 (dashed),
    3 (dash-dot) meet the natural frequencies of the linearised model's mesh modes. A TE
    fluctuation below :data:`MEANINGFUL_TE_UM` is drawn in nm and the title says it is below the
    model's meaning.

    Parameters
    ----------
    ds : xarray.Dataset
        dynamics.nc: over (torque, speed) (speed in rpm, torque N m) ``dynamic_te_std``,
        ``mesh_deflection_std`` (m), ``displacement_std`` (m) and ``velocity_rms`` (m/s) also over
        (gear, direction); ``resonance_speed`` (rpm) over (harmonic, mode), ``mesh_energy_fraction``
        (1) over mode, ``on_grid`` over speed where present.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, section 4 (speed sweeps).
    """
    speed = ds.speed.values
    fig, axes = subplots(3, 1, figsize=(11, 10.5), sharex=True, layout="constrained")
    ax = axes[0]
    top = float(np.nanmax(ds.dynamic_te_std.values)) * UM
    tiny = top < MEANINGFUL_TE_UM  # nanometres: drawn in nm and said to be below the model's meaning
    scale, unit = (UM * 1e3, "nm") if tiny else (UM, "µm")
    torques = range(ds.sizes["torque"]) if "torque" in ds.dims else [None]
    colors = palette(len(torques))
    for k, color in zip(torques, colors):
        d = _at_torque(ds, k)
        tl = f", {_torque_label(d)}" if k is not None else ""
        te, deflection = d.dynamic_te_std.values * scale, d.mesh_deflection_std.values * scale
        if len(coinciding([te, deflection])) == 1:  # no separate error e (contact excitation): one curve
            ax.plot(speed, te, lw=1.3, color=color, label=f"dynamic TE = mesh deflection δ_m{tl}")
            continue
        ax.plot(speed, te, lw=1.3, color=color, label=f"dynamic TE (bodies' approach δ + e){tl}")
        ax.plot(speed, deflection, lw=1.0, ls="--", color=color, label=f"mesh deflection δ_m{tl}")
    mid = _at_torque(ds)
    if "on_grid" in ds and np.any(ds.on_grid.values == 0):
        added = ds.on_grid.values == 0
        ax.plot(speed[added], mid.dynamic_te_std.values[added] * scale, "k.", ms=2.5,
                label="speeds added around predicted resonances")
    subtitle = _below_meaning([ds])
    ax.set_ylabel(f"standard deviation along the\ntransverse line of action ({unit})")
    dir_colors = {"x": "tab:blue", "y": "tab:orange", "z": "tab:green"}
    at = f" at {_torque_label(mid)}" if _torque_label(mid) else ""
    for ax, var, unit, scale, label in ((axes[1], "displacement_std", "µm", UM, "displacement, standard deviation"),
                                        (axes[2], "velocity_rms", "mm/s", 1e3, "velocity, standard deviation")):
        for g, ls in zip(ds.gear.values, ("-", "--")):
            for d in ds.direction.values:
                ax.plot(speed, mid[var].sel(gear=g, direction=d).values * scale, color=dir_colors.get(str(d), None),
                        ls=ls, lw=1.1, label=f"{g} {d}")
        ax.set_ylabel(f"{label}{at} ({unit})" if not at else f"{label} ({unit})\n{at.strip()}")
        ax.set_yscale("log")
    for ax in axes:
        _resonances(ax, mid, labelled=ax is axes[0])
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), ncol=1 if ax is axes[0] else 2,
                  title=None if ax is axes[0] else DIRECTIONS, title_fontsize=7)
    axes[-1].set_xlabel("pinion speed (rpm)")
    axes[0].set_title(_title(ds, "steady-state vibration against speed (standard deviations over the period)",
                             own_line=True)
                      + subtitle, fontsize=11 if not subtitle else 9)
    return _save(fig, path)


def plot_force_spectrum(ds: xr.Dataset, path: str | Path) -> Path:
    """Mesh-force time series (two mesh periods) and amplitude spectrum at the kept speeds (at
    the middle torque of a sweep over several).

    Parameters
    ----------
    ds : xarray.Dataset
        dynamics.nc (or train.nc, with a ``mesh`` dimension): over (sample_speed, time)
        ``mesh_force_series`` (N, normal; time in s), over (sample_speed, frequency)
        ``mesh_force_spectrum`` (N; frequency in Hz, ``order`` the mesh order),
        ``static_mesh_force`` (N).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    ds = _at_torque(ds)
    n = ds.sizes.get("sample_speed", 0)
    fig, axes = subplots(max(n, 1), 2, figsize=(11, 1.0 + 2.6 * max(n, 1)), squeeze=False, layout="constrained")
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
        axes[i, 0].set_title(f"{number(float(sel.sample_speed))} rpm, mesh frequency {number(f_mesh)} Hz", fontsize=9)
        axes[i, 1].set_ylabel("amplitude, normal force (N)")
        axes[i, 1].set_yscale("log")
        plain_log_axis(axes[i, 1])
        top = float(np.nanmax(ds.mesh_force_spectrum.isel(sample_speed=i).values[1:]))
        if top > 0:
            axes[i, 1].set_ylim(top * 1e-4, top * 2.0)
        for ax in axes[i]:
            ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time (ms)")
    axes[-1, 1].set_xlabel("frequency (Hz)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    if labels:
        fig.legend(handles, labels, loc="outside lower center", ncol=len(labels), fontsize=8)
    else:  # dynamics.sample_speeds_rpm: [] keeps no series
        for ax in axes[0]:
            ax.text(0.5, 0.5, "no time series kept (dynamics.sample_speeds_rpm is empty)", ha="center",
                    va="center", transform=ax.transAxes, fontsize=9)
    at = f", {_torque_label(ds)}" if _torque_label(ds) else ""
    fig.suptitle(_title(ds, f"dynamic mesh force normal to the flanks{at}: time series and spectrum (mean removed)",
                        own_line=True))
    return _save(fig, path)


def plot_engagement(ds: xr.Dataset, path: str | Path) -> Path:
    """The engagement in the steady state (``contact`` excitation): per kept speed (rows) and
    torque (columns), the mesh force and the force of the tooth pair entering in each cycle over
    the first two recorded mesh cycles (normal, kN), with A (the theoretical start of
    engagement, solid), the quasi-static mesh-in point (dotted) and the dynamic one (dashed).

    Parameters
    ----------
    ds : xarray.Dataset
        dynamics.nc of the contact excitation: over (torque, sample_speed, time) ``mesh_force_series``
        and ``entering_pair_force_series`` (N, normal; time in s), ``frequency`` (Hz) and ``order``,
        ``mesh_in_roll_before_A`` (m) over speed, ``static_mesh_in_roll_before_A``,
        ``transverse_base_pitch``, ``roll_engagement`` (m).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    n_s = ds.sizes.get("sample_speed", 0)
    torques = list(range(ds.sizes["torque"])) if "torque" in ds.dims else [None]
    fig, axes = subplots(max(n_s, 1), len(torques), figsize=(4.4 * len(torques), 1.8 + 2.8 * max(n_s, 1)),
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
            # A wide and pale, the quasi-static point narrower, the dynamic one thin on top: where
            # two coincide both stay visible; a mesh-in at or after A (stored as 0) is not marked
            dynamic, static = float(d.mesh_in_roll_before_A.values[i_s]), float(d.static_mesh_in_roll_before_A)
            marks = ((0.0, "0.55", "-", 2.4, "A (theoretical start of engagement)"),
                     (static, "k", ":", 1.6, "quasi-static mesh-in point"),
                     (dynamic, "tab:red", "--", 0.9, "dynamic mesh-in point"))
            for before, color, ls, lw, label in marks:
                if before <= 0 and label != marks[0][-1]:
                    continue
                for cycle in (0, 1, 2):
                    x = (roll_a - before) / pitch + cycle
                    if 0 <= x <= 2:
                        ax.axvline(x, color=color, ls=ls, lw=lw, label=label)
                        label = None

            def where(before: float) -> str:
                return f"{number(before * MM)} mm before A" if before > 0 else "at or after A"

            head = f"{_torque_label(d)}\n" if r == 0 else ""
            ax.set_title(f"{head}mesh-in {where(dynamic)} (quasi-static {where(static)})", fontsize=8)
            ax.grid(alpha=0.3)
            if c == 0:
                ax.set_ylabel(f"{number(float(sel.sample_speed))} rpm\nnormal force (kN)")
    figure_legend(fig)
    for ax in axes[-1]:
        ax.set_xlabel("mesh cycles (pinion roll / transverse base pitch)")
    fig.suptitle(_title(ds, "engagement in the steady state, driven by the real tooth contact"), fontsize=10)
    return _save(fig, path)


def dynamics_figures(inputs, outputs) -> None:
    """The figures of the ``dynamics`` rule: outputs 'rms', 'spectrum' and (contact) 'engagement' from input
    'dynamics'.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["dynamics"]``, writes those of
        ``outputs["rms"]``, ``outputs["spectrum"]`` and ``outputs["engagement"]`` it holds.
    """
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
    row: the entering pair's dynamic impact (its force above its quasi-static force).

    Parameters
    ----------
    datasets : sequence of xarray.Dataset
        Each variant's dynamics.nc (the first is the reference for the static force and the torques):
        ``mesh_force_max`` (N) over (torque, speed) (rpm), ``static_mesh_force`` (N), with the
        contact excitation ``dynamic_impact_force`` (N); attribute ``variant``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    ref = datasets[0]
    torques = list(range(ref.sizes["torque"])) if "torque" in ref.dims else [None]
    contact = all("dynamic_impact_force" in d for d in datasets)
    rows = 2 if contact else 1
    fig, axes = subplots(rows, len(torques), figsize=(max(6.5, 4.3 * len(torques)), 3.6 * rows), squeeze=False,
                             layout="constrained")
    colors = colormaps["tab10"](np.arange(len(datasets)))
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
    fig.suptitle(_title(ref, "peak dynamic mesh force against speed, all variants") + _below_meaning(datasets),
                 fontsize=10)
    return _save(fig, path)


def dynamics_variants_figures(inputs, outputs) -> None:
    """The figure of the ``engagement_table`` rule (or ``plot_dynamics_variants`` without one).

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["dynamics"]`` (one
        dataset or a list, one per variant), writes ``outputs["dynamics_variants"]``.
    """
    sets = inputs["dynamics"]
    plot_variants_peak_force(sets if isinstance(sets, (list, tuple)) else [sets], outputs["dynamics_variants"])


def train_figures(inputs, outputs) -> None:
    """The figure of the ``train_dynamics`` rule: output 'spectrum' (both meshes) from input 'train'.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["train"]``, writes
        ``outputs["spectrum"]``.
    """
    plot_force_spectrum(inputs["train"], outputs["spectrum"])


def plot_dynamics_comparison(datasets, path) -> Path:
    """Mesh-deflection std and pinion lateral (y) and axial (z) velocity RMS against speed, all pairs.

    Parameters
    ----------
    datasets : sequence of xarray.Dataset
        Each pair's dynamics.nc (standard variant, its first torque): ``mesh_deflection_std`` (m)
        and ``velocity_rms`` (m/s) over (gear, direction) against ``speed`` (rpm).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        The PNG written.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, section 4 (speed sweeps; the dynamic TE, DTE).
    """
    fig, axes = subplots(3, 1, figsize=(8, 8.5), sharex=True)
    for ds in datasets:
        name = pair_label(ds)
        ds = _at_torque(ds, 0)  # the comparison is at each sweep's first torque
        speed = ds["speed"].values
        axes[0].plot(speed, ds["mesh_deflection_std"].values * UM, lw=1.2, label=name)
        for ax, direction in zip(axes[1:], ("y", "z")):
            ax.plot(speed, ds["velocity_rms"].sel(gear="pinion", direction=direction).values * 1e3, lw=1.2)
    axes[0].set_ylabel("mesh deflection std (µm), transverse\n(the low-fluctuation paper's DTE)")
    axes[1].set_ylabel("pinion y velocity RMS (mm/s)")
    axes[2].set_ylabel("pinion z velocity RMS (mm/s)")
    axes[2].set_xlabel("pinion speed (rpm)")
    for ax in axes:
        ax.set_yscale("log")
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    axes[0].set_title("speed sweeps of the study's pairs (standard variant)")
    return _save(fig, path)


def dynamics_comparison_figures(inputs, outputs) -> None:
    """The figure of the ``dynamics_comparison`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["dynamics"]`` (a list,
        one per pair), writes ``outputs["dynamics_comparison"]``.
    """
    plot_dynamics_comparison(inputs["dynamics"], outputs["dynamics_comparison"])
