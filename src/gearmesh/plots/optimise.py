"""Optimiser figures: convergence (GA and random search on one axis), the optimum's
modification map δ(profile, face) on each flank it modifies, and NSGA-II's Pareto front.

The figure jobs (``optimise_figures``, ``pareto_figures``, each ``(inputs, outputs)`` as every ``*_figures``
of :mod:`gearmesh.plots`) take ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by
name), and ``outputs``, a mapping of str to the path of each PNG by name; they write them and return None.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.ticker import MaxNLocator

from ..surface import relief_depth
from .common import figure, MM, number, plain_log_axis, save as _save, subplots, title as _title, UM

__all__ = ["plot_convergence", "plot_modification", "plot_pareto", "optimise_figures", "pareto_figures"]


def _scale(ds: xr.Dataset) -> tuple[float, str]:
    """Factor and label of the objective axis."""
    units = ds["objective"].attrs.get("units", "")
    return (1.0, "N") if units == "N" else (1.0, units.replace(" s-1", "/s"))


def _change(optimum: float, standard: float) -> str:
    """'x % below the standard gear' (or above), never a signed percentage."""
    change = 100.0 * (1.0 - optimum / standard)
    return f"{abs(change):.1f} % {'below' if change >= 0 else 'above'} the standard gear"


def plot_convergence(ds: xr.Dataset, path: str | Path) -> Path:
    """Best objective so far and the population median against generation, for the run and (when
    it ran) the random search of the same budget, with the standard gear's objective.

    Parameters
    ----------
    ds : xarray.Dataset
        ga.nc: over ``generation`` ``best_objective``, ``median_objective`` (and ``random_*``), in the
        ``objective`` variable's units (N for F_s, m s-1 for the velocity), ``evaluations``,
        ``standard_objective``, ``optimum_objective``, ``objective_torque`` (N m); attributes
        ``method``, ``objective``, ``seed``, ``constraints`` and the tolerance statistic.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, ax = subplots(figsize=(7.5, 4.5))
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
    torques = ds["objective_torque"].values
    where = f"{number(torques[0])} N m" if torques.size == 1 else \
        f"{ds.attrs.get('objective_statistic', 'max')} over {', '.join(number(t) for t in torques)} N m"
    tol = ds.attrs.get("tolerance_statistic", "none (nominal)")
    if not tol.startswith("none"):
        where += f", {tol} over nominal + {ds.attrs.get('tolerance_samples', 0)} tolerance samples"
    quantity = "|v_n|" if ds.attrs.get("objective") == "velocity" else "F_s"
    penalised = ds.attrs.get("constraints", "{}") not in ("", "{}")  # J = objective + the constraints' penalty
    ax.set_ylabel(f"objective J = {quantity} + penalty of violated\nconstraints ({unit})" if penalised
                  else f"objective: {quantity} ({unit})")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    opt, std = float(ds["optimum_objective"]) * k, float(ds["standard_objective"]) * k

    def value(v: float) -> str:
        return f"{v:.0f}" if abs(v) >= 100 else f"{v:.3g}"

    plain_log_axis(ax)
    name = "J" if penalised else quantity
    ax.set_title(_title(ds, f"{ds.attrs.get('objective', '')} objective {name} ({quantity}, {where}), random seed "
                            f"{ds.attrs.get('seed', '')}\noptimum {name} {value(opt)} {unit}, {_change(opt, std)} "
                            f"({value(std)} {unit})"), fontsize=9)
    return _save(fig, path)


def _depth_map(ds: xr.Dataset, gear: int, n_profile: int = 161, n_face: int = 121):
    """Roll lengths (m), face positions (m) and the removed depth δ (m) on gear ``gear``'s flank."""
    rho = np.linspace(float(ds["rho_sap"][gear]), float(ds["rho_eap"][gear]), n_profile)
    half = 0.5 * float(ds["face_width"])
    z = np.linspace(-half, half, n_face)
    depth = relief_depth(ds["optimum_modification"].values[gear], float(ds["rho_sap"][gear]),
                         float(ds["rho_eap"][gear]), float(ds["face_width"]), rho[:, None], z[None, :])
    return rho, z, depth


def _words(p_gear) -> str:
    """The mesh-in impact paper's six parameters of one gear (y1..y6, m) in words."""
    y1, y2, y3, y4, y5, y6 = p_gear
    parts = [f"tip relief {number(y2 * UM)} µm over {number(y4 * MM)} mm" if y2 > 0 and y4 > 0 else "no tip relief",
             f"root relief {number(y1 * UM)} µm over {number(y3 * MM)} mm" if y1 > 0 and y3 > 0 else "no root relief",
             f"lead crowning {number(y5 * UM)} µm outside the middle {number(y6 * MM)} mm" if y5 > 0 else "no crowning"]
    return ", ".join(parts)


def _zones(ax, side, below, ds: xr.Dataset, gear: int, p_gear) -> None:
    """Where each relief begins (dashed, across the map and the profile, the zone named beside
    the profile) and the unmodified middle of the lead (dashed, across the map and the lead)."""
    y1, y2, y3, y4, y5, y6 = p_gear
    sap, eap = float(ds["rho_sap"][gear]) * MM, float(ds["rho_eap"][gear]) * MM
    for amount, length, start, end, name in ((y2, y4, eap - y4 * MM, eap, "tip relief"),
                                             (y1, y3, sap, sap + y3 * MM, "root relief")):
        if amount > 0 and length > 0:
            edge = start if name == "tip relief" else end
            for a in (ax, side):
                a.axhline(edge, color="w" if a is ax else "0.4", ls="--", lw=0.9)
            side.annotate(f"{name}\n{number(amount * UM)} µm over {number(length * MM)} mm", (1.0, 0.5 * (start + end)),
                          xycoords=("axes fraction", "data"), xytext=(4, 0), textcoords="offset points", va="center",
                          fontsize=7, annotation_clip=False)
    half = 0.5 * float(ds["face_width"]) * MM
    if y5 > 0 and 0 < y6 * MM < 2 * half:
        for x in (-0.5 * y6 * MM, 0.5 * y6 * MM):
            for a in (ax, below):
                a.axvline(x, color="w" if a is ax else "0.4", ls="--", lw=0.9)


def plot_modification(ds: xr.Dataset, path: str | Path) -> Path:
    """The optimum's material removal δ (µm) on the active flank of the pinion and of the gear
    where it is modified: the map against axial position z and roll length ρ (filled levels, the
    colour bar above it), the profile δ(ρ) at the face centre and at a face end beside it with
    each relief zone named, the lead δ(z) at the tip and at mid-profile below it, dashed lines
    where the reliefs and the crowning begin, and the six parameters in words in the title
    (the mesh-in impact paper's parabolic tip and root reliefs and lead crowning,
    :func:`gearmesh.surface.modification_depth`).

    Parameters
    ----------
    ds : xarray.Dataset
        ga.nc: ``optimum_modification`` (m) over (gear, parameter: y1..y6), ``rho_sap``, ``rho_eap``
        (m) over gear, ``face_width`` (m).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    p = ds["optimum_modification"].values
    gears = [g for g in range(2) if g == 0 or np.any(p[g] > 0)]
    fig = figure(figsize=(8.2 * len(gears), 8.4), layout="constrained")
    grid = fig.add_gridspec(2, 2 * len(gears), width_ratios=[4, 1.7] * len(gears), height_ratios=[4, 1.5])
    notes = []
    for n, g in enumerate(gears):
        rho, z, depth = _depth_map(ds, g)
        ax = fig.add_subplot(grid[0, 2 * n])
        side = fig.add_subplot(grid[0, 2 * n + 1], sharey=ax)
        below = fig.add_subplot(grid[1, 2 * n], sharex=ax)
        top = max(float(depth.max()) * UM, 1e-3)
        levels = MaxNLocator(nbins=10).tick_values(0.0, top)
        filled = ax.contourf(z * MM, rho * MM, depth * UM, levels=levels[levels >= 0], cmap="viridis")
        fig.colorbar(filled, ax=ax, location="top", aspect=30, label="material removed δ (µm)")
        name = str(ds["gear"].values[g])
        ax.set_ylabel(f"{name} roll length ρ (mm), SAP (bottom) to tip")
        ax.tick_params(labelbottom=False)
        mid = z.size // 2
        side.plot(depth[:, mid] * UM, rho * MM, color="tab:blue", label="at the face centre")
        side.plot(depth[:, -1] * UM, rho * MM, color="tab:red", ls="--", label="at a face end")
        side.set_xlabel("δ (µm)")
        side.tick_params(labelleft=False)
        side.grid(alpha=0.3)
        side.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=1)
        side.set_title("profile", fontsize=8)
        below.plot(z * MM, depth[-1] * UM, color="tab:purple", label="at the tip")
        below.plot(z * MM, depth[rho.size // 2] * UM, color="tab:green", ls="--", label="at mid-profile")
        below.set_xlabel("z across the face (mm)")
        below.set_ylabel("δ (µm)")
        below.set_title("lead", fontsize=8)
        below.grid(alpha=0.3)
        below.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2)
        _zones(ax, side, below, ds, g, p[g])
        notes.append(f"{name}: {_words(p[g])}")
    fig.suptitle(_title(ds, "optimum micro-geometry δ(profile, face)") + "\n" + "\n".join(notes), fontsize=9)
    return _save(fig, path)


#: NSGA-II's ratio objectives in words (their constraint limits are ga.nc's ``constraints`` under
#: the same names).
_PARETO_RATIOS = {"te_harmonics": "loaded-TE harmonics", "pressure": "peak contact pressure",
                  "root_stress": "peak root stress"}


def _pareto_axis(ds: xr.Dataset, name: str) -> tuple[str, str, float, float, str, float | None]:
    """(front variable, history variable, scale, the standard gear's value, axis label, the
    constraint's limit or None) of NSGA-II objective ``name``."""
    if name == "lte":
        limit = json.loads(ds.attrs.get("constraints", "{}")).get("lte")
        std = float(ds["standard_lte_peak_to_peak"]) * UM
        return ("pareto_lte_peak_to_peak", "lte_peak_to_peak", UM, std,
                f"peak-to-peak LTE at {number(float(ds['design_torque']))} N m (µm)",
                None if limit is None else limit * std)
    label = _PARETO_RATIOS[name]
    limit = json.loads(ds.attrs.get("constraints", "{}")).get(name)
    return f"pareto_{name}_ratio", f"{name}_ratio", 1.0, 1.0, f"{label}: worst ratio to the standard gear's", limit


def plot_pareto(ds: xr.Dataset, path: str | Path) -> Path:
    """NSGA-II: the objective J (F_s with the constraints' penalties) against each other traded
    objective (ga.nc attribute ``pareto_objectives``) for every evaluated candidate (failed ones
    left out; those meeting every constraint in green), the Pareto front, the chosen design (the
    front's least J), the standard gear (its J as a candidate of the run, penalties included,
    when the run has constraints) and each constraint's limit.

    Parameters
    ----------
    ds : xarray.Dataset
        ga.nc of an NSGA-II run: per candidate ``objective`` (its units), ``failed``, ``violation``,
        ``lte_peak_to_peak`` (m) and the ``*_ratio`` objectives (1); per front point
        ``pareto_objective`` and ``pareto_*``; ``standard_lte_peak_to_peak`` (m),
        ``standard_penalised_objective``, ``design_torque`` (N m), ``speed`` (rpm); attributes
        ``pareto_objectives``, ``constraints``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    names = [n for n in ds.attrs.get("pareto_objectives", "impact,lte").split(",") if n != "impact"]
    fig, axes = subplots(1, len(names), figsize=(4.6 * len(names) + 0.6, 4.8), squeeze=False)
    ok = ds["failed"].values == 0
    feasible = ok & (ds["violation"].values == 0) if "violation" in ds else np.zeros_like(ok)
    f = ds["objective"].values
    front_f = ds["pareto_objective"].values
    std_j = float(ds["standard_penalised_objective"] if "standard_penalised_objective" in ds
                  else ds["standard_objective"])
    for ax, name in zip(axes[0], names):
        front_var, hist_var, scale, standard, label, limit = _pareto_axis(ds, name)
        x_all = ds[hist_var].values * scale
        ax.scatter(x_all[ok & ~feasible], f[ok & ~feasible], s=6, color="0.7", label="evaluated candidates")
        if feasible.any():
            ax.scatter(x_all[feasible], f[feasible], s=10, color="tab:green", label="meets every constraint")
        x = ds[front_var].values * scale
        ax.plot(x, front_f, "o", color="tab:red", ms=4, label=f"Pareto front ({ds.sizes['front']} points)")
        ax.plot([x[0]], [front_f[0]], "*", color="tab:blue", ms=13, mec="k", label="chosen design (least J)")
        ax.plot([standard], [std_j], "ks", ms=6, label="standard (unmodified) gear")
        ax.axvline(standard, color="k", lw=0.6, ls="--")
        if limit is not None:
            ax.axvline(limit, color="tab:red", lw=0.8, ls=":", label="constraint limit")
        ax.set_yscale("log")
        plain_log_axis(ax)
        ax.set_xlabel(label, fontsize=8)
        ax.set_ylabel(f"objective J at {number(float(ds['speed']))} rpm ({ds['objective'].attrs.get('units', '')})")
        ax.grid(alpha=0.3, which="both")
    axes[0][0].legend(fontsize=7)
    n_ok = int(feasible.sum())
    verdict = (f"{n_ok} candidate{'' if n_ok == 1 else 's'} meet{'s' if n_ok == 1 else ''} every constraint" if feasible.any()
               else "no evaluated candidate meets every constraint") if "violation" in ds else ""
    fig.suptitle(_title(ds, "NSGA-II: the objective J against " + ", ".join(names)) + "\n"
                 + "the front is non-dominated in all objectives together" + (f"; {verdict}" if verdict else ""),
                 fontsize=9)
    return _save(fig, path)


def optimise_figures(inputs, outputs) -> None:
    """The figures of the ``optimise`` rule from its ``ga`` dataset.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["ga"]``, writes
        ``outputs["convergence"]`` and ``outputs["modification"]``.
    """
    plot_convergence(inputs["ga"], outputs["convergence"])
    plot_modification(inputs["ga"], outputs["modification"])


def pareto_figures(inputs, outputs) -> None:
    """The figure of the ``plot_pareto`` rule (NSGA-II runs).

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["ga"]``, writes
        ``outputs["pareto"]``.
    """
    plot_pareto(inputs["ga"], outputs["pareto"])
