"""Mesh-in impact figures: impact force against speed and torque (all variants on one axis),
the trajectory of the mesh-in point M on the pinion flank as the load rises (seed 000 Table
3), and the direct simulation of the engagement beside the energy-method force."""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.patches import Rectangle

from ..impact import SCENARIOS
from .common import MM, palette, save as _save, subplots, title as _title

__all__ = ["impact_figures", "impact_study_figures", "plot_robustness"]

_COLORS = {"none": "0.6", "surface": "tab:green", "edge": "tab:red"}


def plot_force_against_speed(ds: xr.Dataset, path: str | Path) -> Path:
    """F_s (closed form, solid; energy balance, dashed) against pinion speed, one line per torque."""
    fig, ax = subplots(figsize=(7, 4.4))
    colors = palette(ds.sizes["torque"])
    for color, k in zip(colors, range(ds.sizes["torque"])):
        sel = ds.isel(torque=k)
        scen = SCENARIOS[int(sel["scenario"])]
        ax.plot(ds["speed"], sel["impact_force"] * 1e-3, "o-", color=color, ms=3,
                label=f"T1 = {float(sel.torque):g} N m ({scen})")
        ax.plot(ds["speed"], sel["impact_force_energy_balance"] * 1e-3, "--", color=color, lw=0.9)
    ax.set_xlabel("pinion speed (rpm)")
    ax.set_ylabel("mesh-in impact force F_s, transverse (kN)")
    ax.set_title(_title(ds, f"impact force against speed — {ds.attrs.get('variant', '')} "
                            "(solid: closed form, dashed: energy balance)"), fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def plot_mesh_in_trajectory(ds: xr.Dataset, path: str | Path) -> Path:
    """Where M lies on the pinion flank (face position against roll length) for every torque,
    coloured by scenario, with SAP, tip and face ends (seed 000 Table 3): the whole flank on
    the left, a close-up around the points (labelled with their torque) on the right."""
    fig, axes = subplots(1, 2, figsize=(11, 4.6), gridspec_kw={"width_ratios": [1, 1.3]})
    b = float(ds["face_width"]) * MM
    sap, eap = float(ds["rho_sap"][0]) * MM, float(ds["rho_eap"][0]) * MM
    z = ds["mesh_in_face_position"].values * MM
    rho = ds["mesh_in_rho_pinion"].values * MM
    found = np.isfinite(z) & np.isfinite(rho)
    for ax in axes:
        ax.add_patch(Rectangle((-b / 2, sap), b, eap - sap, fc="0.94", ec="0.5", lw=0.8))
        ax.axhline(sap, color="tab:cyan", ls="--", lw=0.8)
        ax.axhline(eap, color="tab:cyan", lw=0.8)
        ax.plot(z, rho, "-", color="0.5", lw=0.8)
        for k in np.flatnonzero(found):
            ax.plot(z[k], rho[k], "o", color=_COLORS[SCENARIOS[int(ds["scenario"][k])]], ms=7)
        ax.set_xlabel("face position z (mm)")
        ax.grid(alpha=0.3)
    for scen, color in _COLORS.items():
        if scen != "none":
            axes[0].plot([], [], "o", color=color, label=f"{scen} contact")
    pad = 0.08 * b
    axes[0].set_xlim(-b / 2 - pad, b / 2 + pad)
    lo = min(sap, np.nanmin(rho)) if found.any() else sap
    axes[0].set_ylim(lo - 0.05 * (eap - sap), eap + 0.05 * (eap - sap))
    axes[0].set_ylabel("pinion roll length ρ1 (mm); SAP dashed, tip solid")
    axes[0].set_title("whole flank", fontsize=9)
    axes[0].legend(fontsize=7, loc="upper left")
    if found.any():  # close-up: at least 5 % of the face and of the active flank around the points
        zc, rc = 0.5 * (np.max(z[found]) + np.min(z[found])), 0.5 * (np.max(rho[found]) + np.min(rho[found]))
        hz = max(0.6 * np.ptp(z[found]), 0.05 * b)
        hr = max(0.6 * np.ptp(rho[found]), 0.05 * (eap - sap))
        axes[1].set_xlim(zc - hz, zc + hz)
        axes[1].set_ylim(rc - hr, rc + hr)
        for i, k in enumerate(np.flatnonzero(found)):
            axes[1].annotate(f"{float(ds.torque[k]):g} N m", (z[k], rho[k]), textcoords="offset points",
                             xytext=(8, 10 - 9 * (i % 3)), fontsize=7)
    axes[1].set_title("close-up around the mesh-in points", fontsize=9)
    fig.suptitle(_title(ds, f"mesh-in point M on the pinion flank — {ds.attrs.get('variant', '')}"), fontsize=10)
    return _save(fig, path)


def plot_simulation(ds: xr.Dataset, path: str | Path) -> Path:
    """The direct time integration at the design speed: total mesh force and the entering pair's
    force against time, with the static force and the energy-method F_s (and F_s above static)."""
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
    ax.axhline(f0 * 1e-3, color="0.4", ls=":", lw=1, label=f"static force F_bt = {f0 * 1e-3:.2f} kN")
    ax.axhline(fs * 1e-3, color="tab:blue", ls="--", lw=1, label=f"energy method F_s = {fs * 1e-3:.2f} kN")
    ax.axhline((f0 + fs) * 1e-3, color="tab:blue", ls=":", lw=1, label="F_bt + F_s")
    t0 = float(ds["sim_touch_time"]) * 1e3
    ax.axvline(t0, color="0.6", lw=0.8, label="quasi-static touch")
    ax.axvspan(t0, t0 + float(ds["sim_period"]) * 1e3, color="0.9", zorder=0,
               label="impact window: one natural period from the touch")
    ax.axvline(float(ds["sim_peak_time"]) * 1e3, color="tab:red", lw=0.8, ls="--",
               label="largest excess of the entering pair over quasi-static")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("transverse force (kN)")
    ax.set_title(_title(ds, f"engagement at {float(ds['sim_torque']):g} N m, "
                            f"{float(ds.attrs['design_speed_rpm']):g} rpm — {ds.attrs.get('variant', '')}"), fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def impact_figures(inputs: Mapping[str, xr.Dataset], outputs: Mapping[str, str]) -> None:
    """Per-variant figures of ``impact.nc``."""
    ds = inputs["impact"]
    plot_force_against_speed(ds, outputs["force_speed"])
    plot_mesh_in_trajectory(ds, outputs["trajectory"])
    plot_simulation(ds, outputs["simulation"])


def _family(ax, x, lines, values, bold_value, color, name: str, unit: str, label_ends: bool) -> None:
    """One line per value (rows of ``lines``, N → kN) in ``color``; the ``bold_value`` line bold
    and in the legend, the others thin and (``label_ends``) labelled at their right end."""
    for y, v in zip(lines * 1e-3, values):
        bold = bool(np.isclose(v, bold_value))
        ax.plot(x, y, "-o", color=color, lw=2.2 if bold else 0.8, ms=4 if bold else 2, alpha=1.0 if bold else 0.55,
                label=f"{name} ({v:g} {unit})" if bold else None)
        if label_ends:
            ax.annotate(f"{v:g} {unit}", (x[-1], y[-1]), xytext=(3, 0), textcoords="offset points", fontsize=6,
                        color="0.3", va="center")


def impact_study_figures(inputs: Mapping[str, Sequence[xr.Dataset]], outputs: Mapping[str, str]) -> None:
    """All variants on one axis (colour = variant): F_s against torque, one line per speed, and
    against speed, one line per torque; the design speed / the middle torque bold, the others thin
    and labelled at their ends."""
    sets = inputs["impact"]
    sets = sets if isinstance(sets, (list, tuple)) else [sets]
    ref = sets[0]
    speeds, torques = ref["speed"].values, ref["torque"].values
    design = float(ref.attrs.get("design_speed_rpm", speeds[0]))
    t_bold = torques[len(torques) // 2]
    fig, axes = subplots(1, 2, figsize=(12, 4.8))
    colors = colormaps["tab10"](np.arange(len(sets)))
    for color, ds in zip(colors, sets):
        name = ds.attrs.get("variant", "")
        _family(axes[0], torques, ds["impact_force"].values.T, speeds, design, color, name, "rpm", ds is ref)
        _family(axes[1], speeds, ds["impact_force"].values, torques, t_bold, color, name, "N m", ds is ref)
    axes[0].set_xlabel("pinion torque T1 (N m)")
    axes[1].set_xlabel("pinion speed (rpm)")
    axes[0].set_title(f"against torque: one line per speed (bold: {design:g} rpm; labels: {ref.attrs.get('variant', '')})",
                      fontsize=8)
    axes[1].set_title(f"against speed: one line per torque (bold: {t_bold:g} N m)", fontsize=8)
    for ax in axes:
        ax.set_ylabel("mesh-in impact force F_s, transverse (kN)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, title="variant (colour)", title_fontsize=7)
        ax.margins(x=0.12)
    fig.suptitle(_title(ref, "mesh-in impact force, all variants"), fontsize=10)
    _save(fig, outputs["impact_force"])
    if "robustness" in outputs:
        plot_robustness(sets, outputs["robustness"])


def _load_windows(ax, sets, colors) -> None:
    """F_s (closed form) against torque on the load-window grid at the design speed, one line per
    variant, the design torque marked; each variant's load window against ``standard`` as a bar
    under the curves, its ends in the legend."""
    from ..impact import load_window

    names = [ds.attrs.get("variant", "") for ds in sets]
    std = sets[names.index("standard")] if "standard" in names else None
    design = float(sets[0]["design_torque"]) if "design_torque" in sets[0] else None
    for k, (color, ds) in enumerate(zip(colors, sets)):
        t, f = ds["window_torque"].values, ds["window_impact_force"].values
        label = ds.attrs.get("variant", "")
        if std is not None and ds is not std:
            low, high = load_window(t, f, std["window_impact_force"].values, design)
            label += f": beats standard {low:g}–{high:g} N m" if np.isfinite(low) else ": not at the design torque"
            if np.isfinite(low):
                ax.plot([low, high], [0.06 + 0.035 * k] * 2, transform=ax.get_xaxis_transform(), color=color, lw=4,
                        solid_capstyle="butt")
        ax.plot(t, f * 1e-3, "-", color=color, lw=1.6, label=label)
        ax.plot(ds["torque"].values, ds["impact_force"].sel(speed=float(ds.attrs["design_speed_rpm"])).values * 1e-3,
                "o", color=color, ms=4)
    if design is not None:
        ax.axvline(design, color="0.4", lw=0.8, ls=":")
    ax.set_yscale("log")
    ax.set_xlabel("pinion torque T1 (N m)")
    ax.set_ylabel("F_s, closed form, transverse (kN)")
    ax.set_title(f"F_s against torque at {float(sets[0].attrs['design_speed_rpm']):g} rpm\n(dots: the study torques; "
                 "bars: load windows)", fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left")


def _tolerance_spread(ax, sets, colors) -> None:
    """At each study torque, per variant: the range of F_s over the nominal and the tolerance
    samples (bar) and the nominal (dot)."""
    torques = sets[0]["torque"].values
    width = 0.8 / len(sets)
    x = np.arange(torques.size)
    for k, (color, ds) in enumerate(zip(colors, sets)):
        f = ds["tolerance_impact_force"].values * 1e-3
        pos = x - 0.4 + width * (k + 0.5)
        ax.vlines(pos, f.min(axis=0), f.max(axis=0), color=color, lw=5, alpha=0.55,
                  label=f"{ds.attrs.get('variant', '')}: nominal and {f.shape[0] - 1} samples")
        ax.plot(pos, f[0], "o", color=color, ms=3, mec="k", mew=0.4)
    ax.set_xticks(x, [f"{t:g}" for t in torques])
    ax.set_yscale("log")
    ax.set_xlabel("pinion torque T1 (N m)")
    ax.set_ylabel("F_s, closed form, transverse (kN)")
    grade = sets[0].attrs.get("lead_grade_iso1328", -1)
    what = f"lead ISO 1328-1 class {grade}" if grade and grade > 0 else "no lead tolerance"
    toleranced = sorted({name.split(".")[-1].replace("_um", "") for name in
                         str(sets[0].attrs.get("toleranced", "")).replace(",", " ").split()})
    ax.set_title(f"tolerance spread: {what};\nwithin their tolerances: {', '.join(toleranced) or 'nothing'}", fontsize=8)
    ax.grid(alpha=0.3, which="both", axis="y")
    ax.legend(fontsize=7, loc="upper left")


#: The panels of the robustness page, each drawn when every variant's impact.nc has its data:
#: (variable needed, panel). A panel of the peak dynamic mesh force joins here when the
#: dynamics provide it.
ROBUSTNESS_PANELS = (("window_impact_force", _load_windows), ("tolerance_impact_force", _tolerance_spread))


def plot_robustness(sets: Sequence[xr.Dataset], path) -> None:
    """The variants side by side off the design point: F_s against torque on a fine grid with each
    variant's load window, and the spread of F_s under the manufacturing tolerance samples at each
    study torque (the panels of :data:`ROBUSTNESS_PANELS` whose data the variants have)."""
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
    _save(fig, path)
