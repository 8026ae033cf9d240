"""Mesh-in impact figures: the mesh-in impact index F_s (the energy method of the mesh-in impact
paper, :data:`gearmesh.choices.IMPACT_INDEX`) against speed and torque, the trajectory of the
mesh-in point M on the pinion flank as the load rises (the paper's Table 3), and the direct
simulation of the engagement beside F_s.

The figure jobs (``impact_figures``, ``impact_study_figures``, each ``(inputs, outputs)`` as every
``*_figures`` of :mod:`gearmesh.plots`) take ``inputs``, a mapping of str to xarray.Dataset (or to a list of
them, one per variant), the rule's netCDF inputs by name, and ``outputs``, a mapping of str to the path of
each PNG by name; they write them and return None.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.patches import Rectangle

from ..choices import IMPACT_INDEX
from ..impact.model import SCENARIOS
from .common import (MM, apart, coinciding, legend_below, number, palette, plain_log_axis, save as _save, subplots,
                     text_line, title as _title)

__all__ = ["impact_figures", "impact_study_figures", "plot_robustness"]

_COLORS = {"none": "0.6", "surface": "tab:green", "edge": "tab:red"}


def plot_force_against_speed(ds: xr.Dataset, path: str | Path) -> Path:
    """F_s (closed form, solid; energy balance, dashed) against pinion speed, one line per torque
    (torques whose curves coincide share one line and one legend entry).

    Parameters
    ----------
    ds : xarray.Dataset
        impact.nc: ``impact_force`` and ``impact_force_energy_balance`` (N, transverse) over
        (torque, speed) (N m, rpm), ``scenario`` over torque; attribute ``variant``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, ax = subplots(figsize=(7, 4.4))
    closed = ds["impact_force"].transpose("torque", "speed").values * 1e-3
    balance = ds["impact_force_energy_balance"].transpose("torque", "speed").values * 1e-3
    torques, scenarios = ds["torque"].values, ds["scenario"].values
    groups = coinciding(closed)
    for color, group in zip(palette(len(groups)), groups):
        k = group[0]
        label = ", ".join(f"{number(torques[j])} N m ({SCENARIOS[int(scenarios[j])]})" for j in group)
        ax.plot(ds["speed"], closed[k], "o-", color=color, ms=3, label=f"T1 = {label}")
        ax.plot(ds["speed"], balance[k], "--", color=color, lw=0.9)
    ax.set_xlabel("pinion speed (rpm)")
    ax.set_ylabel(f"{IMPACT_INDEX}, transverse (kN)")
    ax.set_title(_title(ds, f"impact index against speed — {ds.attrs.get('variant', '')} "
                            "(solid: closed form, dashed: energy balance)"), fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    return _save(fig, path)


def plot_mesh_in_trajectory(ds: xr.Dataset, path: str | Path) -> Path:
    """Where M lies on the pinion flank (face position against roll length) for every torque,
    coloured by scenario, with SAP, tip and face ends (the mesh-in impact paper Table 3): the whole flank on
    the left, a close-up around the points (labelled with their torque) on the right.

    Parameters
    ----------
    ds : xarray.Dataset
        impact.nc: over torque (N m) ``mesh_in_face_position``, ``mesh_in_rho_pinion`` (m) and
        ``scenario``; ``face_width``, ``rho_sap``, ``rho_eap`` (m); attribute ``variant``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] *Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears*, Table 3.
    """
    fig, axes = subplots(1, 2, figsize=(11, 4.6), gridspec_kw={"width_ratios": [1, 1.3]})
    b = float(ds["face_width"]) * MM
    sap, eap = float(ds["rho_sap"][0]) * MM, float(ds["rho_eap"][0]) * MM
    z = ds["mesh_in_face_position"].values * MM
    rho = ds["mesh_in_rho_pinion"].values * MM
    found = np.isfinite(z) & np.isfinite(rho)
    for ax in axes:
        ax.add_patch(Rectangle((-b / 2, sap), b, eap - sap, fc="0.94", ec="0.5", lw=0.8, zorder=0))
        ax.axhline(sap, color="tab:cyan", ls="--", lw=0.8)
        ax.axhline(eap, color="tab:cyan", lw=0.8)
        ax.plot(z, rho, "-", color="0.5", lw=0.8)
        named = set()
        for k in np.flatnonzero(found):
            scen = SCENARIOS[int(ds["scenario"][k])]
            # the scenarios named in the close-up, where points a hair apart are told apart
            ax.plot(z[k], rho[k], "o", color=_COLORS[scen], ms=7,
                    label=f"{scen} contact" if scen not in named and ax is axes[1] else None)
            named.add(scen)
        ax.set_xlabel("face position z (mm)")
        ax.grid(alpha=0.3)
    pad = 0.08 * b
    axes[0].set_xlim(-b / 2 - pad, b / 2 + pad)
    lo = min(sap, np.nanmin(rho)) if found.any() else sap
    axes[0].set_ylim(lo - 0.05 * (eap - sap), eap + 0.05 * (eap - sap))
    axes[0].set_ylabel("pinion roll length ρ1 (mm)")
    axes[0].set_title("whole flank", fontsize=9)
    for ax in axes:  # the lines named once, in the legend under the whole flank
        ax.lines[0].set_label("start of active profile (SAP)" if ax is axes[0] else None)
        ax.lines[1].set_label("tip" if ax is axes[0] else None)
    legend_below(axes[0], ncol=2)
    if found.any():
        legend_below(axes[1], ncol=2)
        # close-up: at least 5 % of the face and of the active flank around the points
        zc, rc = 0.5 * (np.max(z[found]) + np.min(z[found])), 0.5 * (np.max(rho[found]) + np.min(rho[found]))
        hz = max(0.6 * np.ptp(z[found]), 0.05 * b)
        hr = max(0.6 * np.ptp(rho[found]), 0.05 * (eap - sap))
        axes[1].set_xlim(zc - hz, zc + hz)
        axes[1].set_ylim(rc - hr, rc + hr)
        _torque_labels(axes[1], z, rho, found, ds.torque.values, zc, hz, hr)
    axes[1].set_title("close-up around the mesh-in points", fontsize=9)
    fig.suptitle(_title(ds, f"mesh-in point M on the pinion flank — {ds.attrs.get('variant', '')}"), fontsize=10)
    return _save(fig, path)


def _torque_labels(ax, z, rho, found, torques, zc: float, hz: float, hr: float, fontsize: float = 7) -> None:
    """One label per mesh-in point of the close-up, its torque, on the side towards the middle;
    points that coincide on the page share one label, and labels on one side are moved apart
    vertically (a thin line to their point) so that none covers another."""
    groups, done = [], np.zeros(z.size, dtype=bool)
    for k in np.flatnonzero(found):
        if not done[k]:
            same = found & (np.abs(z - z[k]) <= 0.02 * hz) & (np.abs(rho - rho[k]) <= 0.02 * hr)
            done |= same
            groups.append((k, ", ".join(number(float(t)) for t in torques[same]) + " N m"))
    lo, hi = ax.get_ylim()
    for left in (False, True):
        side = [(k, text) for k, text in groups if (z[k] > zc + 0.2 * hz) == left]
        if not side:
            continue
        own = np.array([(rho[k] - lo) / (hi - lo) for k, _ in side])
        shift = (apart(own, text_line(ax, fontsize)) - own) * ax.get_position().height * \
            ax.get_figure().get_figheight() * 72.0  # axes fractions -> points
        for (k, text), dy in zip(side, shift):
            line = {"arrowprops": {"arrowstyle": "-", "color": "0.5", "lw": 0.5, "shrinkA": 0, "shrinkB": 3}} \
                if abs(dy) > 0.5 else {}
            ax.annotate(text, (z[k], rho[k]), xytext=(-10 if left else 10, dy), textcoords="offset points",
                        ha="right" if left else "left", va="center", fontsize=fontsize, **line)


def plot_simulation(ds: xr.Dataset, path: str | Path) -> Path:
    """The direct time integration at the design speed: total mesh force and the entering pair's
    force against time, with the static force and the energy-method F_s (and F_s above static);
    the legend under the axes, clear of the curves.

    Parameters
    ----------
    ds : xarray.Dataset
        impact.nc: over ``sim_time`` (s) ``sim_mesh_force``, ``sim_entering_force`` and
        ``sim_entering_static`` (N, transverse), ``sim_static_force`` (N), ``sim_torque`` (N m),
        ``sim_touch_time``, ``sim_period``, ``sim_peak_time`` (s), ``impact_force`` (N) and
        ``simulated_entering_excess`` (N); attribute ``design_speed_rpm``. Without ``sim_time`` the
        figure says no simulation ran.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, ax = subplots(figsize=(7, 4.4))
    if "sim_time" not in ds.coords:
        ax.text(0.5, 0.5, "no simulation in this study (impact.simulate_torques_Nm empty)", ha="center",
                transform=ax.transAxes)
        ax.set_axis_off()
        return _save(fig, path)
    t = ds["sim_time"].values * 1e3
    f0 = float(ds["sim_static_force"])
    k = int(np.flatnonzero(np.isclose(ds["torque"].values, float(ds["sim_torque"])))[0])
    fs = float(ds["impact_force"].sel(speed=float(ds.attrs["design_speed_rpm"]))[k])
    ax.plot(t, ds["sim_mesh_force"] * 1e-3, color="k", lw=1.3, label="mesh force, all pairs (simulated)")
    ax.plot(t, ds["sim_entering_force"] * 1e-3, color="tab:red", lw=1.2, label="entering pair (simulated)")
    if "sim_entering_static" in ds:
        ax.plot(t, ds["sim_entering_static"] * 1e-3, color="tab:red", lw=0.9, ls=":",
                label="entering pair, quasi-static")
    ax.axhline(f0 * 1e-3, color="0.4", ls=":", lw=1, label=f"static force F_bt = {number(f0 * 1e-3)} kN")
    excess = float(ds["simulated_entering_excess"].values[k]) if "simulated_entering_excess" in ds else np.nan
    ratio = f" = {number(fs / excess, 2)} × the simulated excess" if np.isfinite(excess) and excess > 0 else ""
    ax.axhline(fs * 1e-3, color="tab:blue", ls="--", lw=1,
               label=f"{IMPACT_INDEX} (energy method) = {number(fs * 1e-3)} kN{ratio}")
    ax.axhline((f0 + fs) * 1e-3, color="tab:blue", ls=":", lw=1, label="F_bt + F_s")
    t0, period = float(ds["sim_touch_time"]) * 1e3, float(ds["sim_period"]) * 1e3
    ax.axvline(t0, color="0.6", lw=0.8, label="quasi-static touch")
    if period > 0:  # a window of no width is not drawn, nor listed
        ax.axvspan(t0, t0 + period, color="0.9", zorder=0, label="impact window: one natural period from the touch")
    ax.axvline(float(ds["sim_peak_time"]) * 1e3, color="tab:red", lw=0.8, ls="--",
               label="largest excess of the entering pair over quasi-static")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("transverse force (kN)")
    ax.set_title(_title(ds, f"engagement at {number(float(ds['sim_torque']))} N m, "
                            f"{number(float(ds.attrs['design_speed_rpm']))} rpm — {ds.attrs.get('variant', '')}"),
                 fontsize=9)
    ax.grid(alpha=0.3)
    legend_below(ax)
    return _save(fig, path)


def impact_figures(inputs: Mapping[str, xr.Dataset], outputs: Mapping[str, str]) -> None:
    """Per-variant figures of ``impact.nc``.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["impact"]``, writes
        ``outputs["force_speed"]``, ``outputs["trajectory"]`` and ``outputs["simulation"]``.
    """
    ds = inputs["impact"]
    plot_force_against_speed(ds, outputs["force_speed"])
    plot_mesh_in_trajectory(ds, outputs["trajectory"])
    plot_simulation(ds, outputs["simulation"])


def _design_torque(ds: xr.Dataset) -> float:
    """The torque the variants are compared at against speed: the impact stage's design torque
    when it is one of the map's torques, else the middle one."""
    torques = ds["torque"].values
    if "design_torque" in ds and np.isclose(torques, float(ds["design_torque"])).any():
        return float(ds["design_torque"])
    return float(torques[len(torques) // 2])


def impact_study_figures(inputs: Mapping[str, Sequence[xr.Dataset]], outputs: Mapping[str, str]) -> None:
    """The variants side by side, one line each (colour = variant): the mesh-in impact index F_s
    against torque at the design speed and against speed at the design torque (each variant's whole
    torque × speed map is its own impact_speed figure); where the engagement was simulated, the
    entering pair's simulated excess over its quasi-static force (crosses), and F_s over it in the
    legend: the index is many times the force the simulation finds.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["impact"]``, every
        variant's impact.nc (``impact_force`` (N) over (torque, speed), ``simulated_entering_excess``
        (N)), writes ``outputs["impact_force"]`` and, when asked, ``outputs["robustness"]``
        (:func:`plot_robustness`).
    """
    sets = inputs["impact"]
    sets = sets if isinstance(sets, (list, tuple)) else [sets]
    ref = sets[0]
    design = float(ref.attrs.get("design_speed_rpm", ref["speed"].values[0]))
    torque = _design_torque(ref)
    fig, axes = subplots(1, 2, figsize=(12, 5.0), layout="constrained")
    simulated = False
    span = float(np.ptp(ref["torque"].values)) or 1.0
    for k, (color, ds) in enumerate(zip(colormaps["tab10"](np.arange(len(sets))), sets)):
        force = ds["impact_force"].transpose("torque", "speed")
        label = ds.attrs.get("variant", "")
        excess = ds["simulated_entering_excess"].values if "simulated_entering_excess" in ds else np.array([])
        at_speed = force.sel(speed=design).values
        if np.isfinite(excess).any():
            t_sim = ds["torque"].values[np.isfinite(excess)]
            e_sim = excess[np.isfinite(excess)]
            dodge = (k - (len(sets) - 1) / 2) * 0.012 * span  # the variants' crosses side by side, not on one another
            axes[0].plot(t_sim + dodge, e_sim * 1e-3, "x", color=color, ms=8, mew=1.8, label=None if simulated else
                         "simulated excess of the entering pair over its quasi-static force (crosses)")
            simulated = True
            ratios = ", ".join(f"{number(f / e, 2)}× at {number(t)} N m" for t, f, e in
                               zip(t_sim, at_speed[np.isfinite(excess)], e_sim) if e > 0)
            label += f" (F_s / simulated excess: {ratios})" if ratios else ""
        axes[0].plot(ds["torque"].values, at_speed * 1e-3, "-o", color=color, lw=1.8, ms=4, label=label)
        axes[1].plot(ds["speed"].values, force.sel(torque=torque).values * 1e-3, "-o", color=color, lw=1.8, ms=4)
    axes[0].set_xlabel("pinion torque T1 (N m)")
    axes[1].set_xlabel("pinion speed (rpm)")
    axes[0].set_title(f"against torque at {number(design)} rpm", fontsize=9)
    axes[1].set_title(f"against speed at {number(torque)} N m", fontsize=9)
    for ax in axes:
        ax.set_ylabel(f"{IMPACT_INDEX}, transverse (kN)")
        ax.grid(alpha=0.3)
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=8,
               title="variant (colour)", title_fontsize=8)
    fig.suptitle(_title(ref, f"{IMPACT_INDEX} (the energy method of the mesh-in impact paper), all variants"),
                 fontsize=10)
    _save(fig, outputs["impact_force"])
    if "robustness" in outputs:
        plot_robustness(sets, outputs["robustness"])


def _load_windows(ax, sets, colors) -> None:
    """F_s (closed form) against torque on the load-window grid at the design speed, one line per
    variant, the design torque marked; under it, on an axis of its own sharing the torque axis,
    each variant's load window against ``standard`` as a bar (its ends in the legend)."""
    from mpl_toolkits.axes_grid1 import make_axes_locatable

    from ..impact.energy import load_window

    names = [ds.attrs.get("variant", "") for ds in sets]
    std = sets[names.index("standard")] if "standard" in names else None
    design = float(sets[0]["design_torque"]) if "design_torque" in sets[0] else None
    bars = make_axes_locatable(ax).append_axes("bottom", size="28%", pad=0.3, sharex=ax) if std is not None else None
    rows = []
    for color, ds in zip(colors, sets):
        t, f = ds["window_torque"].values, ds["window_impact_force"].values
        label = ds.attrs.get("variant", "")
        if bars is not None and ds is not std:
            low, high = load_window(t, f, std["window_impact_force"].values, design)
            label += f": below standard {number(low)}–{number(high)} N m" if np.isfinite(low) else \
                ": not below standard at the design torque"
            if np.isfinite(low):
                bars.plot([low, high], [len(rows)] * 2, color=color, lw=6, solid_capstyle="butt")
            rows.append(ds.attrs.get("variant", ""))
        ax.plot(t, f * 1e-3, "-", color=color, lw=1.6, label=label)
        ax.plot(ds["torque"].values, ds["impact_force"].sel(speed=float(ds.attrs["design_speed_rpm"])).values * 1e-3,
                "o", color=color, ms=4)
    for a in (ax, bars) if bars is not None else (ax,):
        if design is not None:
            a.axvline(design, color="0.4", lw=0.8, ls=":")
        a.grid(alpha=0.3, which="both")
    ax.set_yscale("log")
    plain_log_axis(ax)
    ax.set_ylabel("F_s, closed form, transverse (kN)")
    ax.set_title(f"{IMPACT_INDEX} against torque at {number(float(sets[0].attrs['design_speed_rpm']))} rpm\n"
                 "(dots: the study torques; dotted: the design torque)", fontsize=8)
    low_axis = ax
    if bars is not None:
        ax.tick_params(labelbottom=False)
        bars.set_yticks(range(len(rows)), rows, fontsize=7)
        bars.set_ylim(-0.7, len(rows) - 0.3)
        bars.invert_yaxis()
        bars.set_title("load window: torques where the variant's F_s is below the standard's", fontsize=7)
        low_axis = bars
    low_axis.set_xlabel("pinion torque T1 (N m)")
    # under the torque axis, below its label (an axes fraction of the short bar axis is a few points)
    low_axis.legend(handles=ax.get_legend_handles_labels()[0], loc="upper center", fontsize=7, ncol=1,
                    bbox_to_anchor=(0.5, -0.16 if low_axis is ax else -0.75))


def _tolerance_spread(ax, sets, colors) -> None:
    """At each study torque, per variant: the range of F_s over the manufactured population (bar),
    the worst over the tolerance box (bar), and the nominal (dot)."""
    torques = sets[0]["judged_torque"].values
    width = 0.8 / len(sets)
    x = np.arange(torques.size)
    for k, (color, ds) in enumerate(zip(colors, sets)):
        f = ds["population_impact_force"].values * 1e-3
        top = np.maximum(f.max(axis=0), ds["box_worst_impact_force"].values * 1e-3)
        pos = x - 0.4 + width * (k + 0.5)
        ax.vlines(pos, f.min(axis=0), top, color=color, lw=5, alpha=0.55,
                  label=f"{ds.attrs.get('variant', '')}: {f.shape[0] - 1} gears and the box worst (bar)")
        ax.plot(pos, top, "_", color="k", ms=8, mew=1.2)
        ax.plot(pos, f[0], "o", color=color, ms=3, mec="k", mew=0.4)
    ax.set_xticks(x, [number(t) for t in torques])
    ax.set_yscale("log")
    plain_log_axis(ax)
    ax.set_xlabel("pinion torque T1 (N m)")
    ax.set_ylabel(f"{IMPACT_INDEX}, closed form, transverse (kN)")
    grade = sets[0].attrs.get("lead_grade_iso1328", -1)
    what = f"lead ISO 1328-1 class {grade}" if grade and grade > 0 else "no lead tolerance"
    toleranced = sorted({name.split(".")[-1].replace("_um", "").replace("_", " ") for name in
                         str(sets[0].attrs.get("toleranced", "")).replace(",", " ").split()})
    ax.set_title(f"tolerance spread: {what};\nwithin their tolerances: {', '.join(toleranced) or 'nothing'}", fontsize=8)
    ax.grid(alpha=0.3, which="both", axis="y")
    legend_below(ax, ncol=1)


#: The panels of the robustness page, each drawn when every variant's impact.nc has its data:
#: (variable needed, panel). A panel of the peak dynamic mesh force joins here when the
#: dynamics provide it.
ROBUSTNESS_PANELS = (("window_impact_force", _load_windows), ("population_impact_force", _tolerance_spread))


def plot_robustness(sets: Sequence[xr.Dataset], path) -> Path:
    """The variants side by side off the design point: F_s against torque on a fine grid with each
    variant's load window, and the spread of F_s under the manufacturing tolerance samples at each
    study torque (the panels of :data:`ROBUSTNESS_PANELS` whose data the variants have).

    Parameters
    ----------
    sets : sequence of xarray.Dataset
        Every variant's impact.nc: ``window_impact_force`` (N) over ``window_torque`` (N m) and
        ``design_torque``; the tolerance samples' ``population_impact_force`` (N); attribute ``variant``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        The PNG written.
    """
    panels = [draw for need, draw in ROBUSTNESS_PANELS if all(need in ds for ds in sets)]
    fig, axes = subplots(1, max(len(panels), 1), figsize=(6.4 * max(len(panels), 1), 5.0), squeeze=False)
    colors = colormaps["tab10"](np.arange(len(sets)))
    for ax, draw in zip(axes[0], panels):
        draw(ax, sets, colors)
    if not panels:
        axes[0, 0].text(0.5, 0.5, "no load-window grid and no tolerance samples in this study", ha="center",
                        va="center", transform=axes[0, 0].transAxes)
        axes[0, 0].set_axis_off()
    fig.suptitle(_title(sets[0], "off the design point: load windows and manufacturing tolerances"), fontsize=10)
    return _save(fig, path)
