"""Study tables over the dynamics results: the RMS changes between pairs (the low-fluctuation
paper's comparisons) and the energy method beside the contact-driven dynamics (the engagement table).
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import xarray as xr

from ...errors import GearmeshInputError
from .. import one_pair, variant_names
from ...io import name_force_lines, variable
from ...limits import same_point
from ...arguments import check_arguments
from ...schema import section_keys, settings_object
from ...choices import IMPACT_INDEX
from ...settings import DynamicsComparison

def _grid(ds: xr.Dataset) -> xr.Dataset:
    """The speeds of the configured grid (without the added resonance speeds), at the sweep's
    first torque."""
    ds = ds.isel(torque=0) if "torque" in ds.dims else ds
    return ds.isel(speed=ds["on_grid"].values.astype(bool)) if "on_grid" in ds else ds


@check_arguments(DynamicsComparison, exclude=section_keys(DynamicsComparison))
def dynamics_comparison_dataset(dynamics: Sequence[xr.Dataset], **section: Any) -> xr.Dataset:
    """RMS changes between pairs over a common speed sweep (the low-fluctuation paper §4–5, its comparisons).

    Over the configured speeds (``on_grid``; each pair's added resonance speeds differ), at each
    sweep's first torque. For
    each (pair, reference) couple: the mean over speeds of the relative change of the
    mesh-deflection standard deviation (the low-fluctuation paper's "DTE"), and for each gear and direction the mean relative change and the
    change of the highest peak of the displacement standard deviation and velocity RMS
    (the low-fluctuation paper reports "across most speeds" and "at the resonance peaks"). Default couples:
    every pair against the first.

    Parameters
    ----------
    dynamics : sequence of xarray.Dataset
        Each pair's dynamics.nc (its standard variant).
    **section
        A study's ``dynamics_comparison:`` section (:class:`gearmesh.settings.DynamicsComparison`:
        ``couples``, [pair, reference] names), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        dynamics_comparison.nc (dim couple).
    """
    given = settings_object(DynamicsComparison, section).couples
    by_name = {d.attrs.get("pair_name", str(i)): d for i, d in enumerate(dynamics)}
    names = list(by_name)
    couples = given or tuple((n, names[0]) for n in names[1:])
    for pair, ref in couples:
        for n in (pair, ref):
            if n not in by_name:
                raise GearmeshInputError("dynamics_comparison.couples", [pair, ref], f"{n} is not a pair of the study")
        if not np.array_equal(_grid(by_name[pair])["speed"].values, _grid(by_name[ref])["speed"].values):
            raise GearmeshInputError("dynamics.speeds_rpm", None, f"{pair} and {ref} were swept over different speeds")

    def change(new, old):
        return float(np.mean(new / old - 1)), float(new.max() / old.max() - 1)

    rows = {"dte_mean": [], "dte_peak": []}
    grid = {f"{q}_{k}": [] for q in ("displacement", "velocity") for k in ("mean", "peak")}
    for pair, ref in couples:
        new, old = _grid(by_name[pair]), _grid(by_name[ref])
        m, p = change(new["mesh_deflection_std"].values, old["mesh_deflection_std"].values)
        rows["dte_mean"].append(m)
        rows["dte_peak"].append(p)
        for q, var in (("displacement", "displacement_std"), ("velocity", "velocity_rms")):
            a, b = new[var].values, old[var].values  # (speed, gear, direction)
            grid[f"{q}_mean"].append(np.mean(a / b - 1, axis=0))
            grid[f"{q}_peak"].append(a.max(axis=0) / b.max(axis=0) - 1)
    d1, d3 = ("couple",), ("couple", "gear", "direction")
    first = dynamics[0]
    return xr.Dataset({
        "mesh_deflection_std_change_mean": variable(d1, rows["dte_mean"], "1",
                                                    "mean over speeds of the relative change of the mesh-deflection "
                                                    "std (the low-fluctuation paper's DTE)"),
        "mesh_deflection_std_change_peak": variable(d1, rows["dte_peak"], "1",
                                                    "relative change of the highest mesh-deflection std peak"),
        "displacement_change_mean": variable(d3, np.array(grid["displacement_mean"]), "1",
                                             "mean over speeds of the relative change of displacement std"),
        "displacement_change_peak": variable(d3, np.array(grid["displacement_peak"]), "1",
                                             "relative change of the highest displacement std peak"),
        "velocity_change_mean": variable(d3, np.array(grid["velocity_mean"]), "1",
                                         "mean over speeds of the relative change of velocity RMS"),
        "velocity_change_peak": variable(d3, np.array(grid["velocity_peak"]), "1",
                                         "relative change of the highest velocity RMS peak"),
    }, coords={
        "couple": variable(d1, np.array([f"{p} vs {r}" for p, r in couples]), "1", "pair against its reference"),
        "gear": variable(("gear",), first["gear"].values, "1", "gear of the pair"),
        "direction": variable(("direction",), first["direction"].values, "1", "x, y lateral; z axial"),
    })


def engagement_table_dataset(impact: Sequence[xr.Dataset], dynamics: Sequence[xr.Dataset]) -> xr.Dataset:
    """The energy method beside the dynamics driven by the real contact, per variant and torque at
    the impact stage's design speed: does F_s rank the variants as the dynamics does?

    From ``impact.nc``: F_s (closed form and energy balance), the quasi-static mesh-in roll, and
    the undamped engagement simulation's largest excess of the entering pair over its
    quasi-static load where it was run; from ``dynamics.nc`` (``contact`` excitation) at the
    speed of its grid nearest the design speed: the entering pair's dynamic impact, its largest
    force, the dynamic mesh-in roll, the peak mesh force, and the peak mesh force over the whole
    sweep. Every force transverse (the impact stage's direction: normal × cos βb), so F_s and
    the dynamics stand in one unit. Torques are those both stages ran (pinion torques).

    Parameters
    ----------
    impact : sequence of xarray.Dataset
        The ``impact.nc`` of every variant of one pair (its ``design_speed_rpm`` attribute, r/min).
    dynamics : sequence of xarray.Dataset
        The ``dynamics.nc`` of the same variants, each with the ``contact`` excitation.

    Returns
    -------
    xarray.Dataset
        Forces (N, transverse), rolls (m) and force ratios (1) on (variant, torque), torque the pinion
        torque T1 (N m);
        attributes ``design_speed_rpm``, ``dynamics_speed_rpm`` and each stage's tooth model and contact law.

    Raises
    ------
    GearmeshInputError
        ``variants`` when the two cover different variants, ``dynamics.excitation`` when a dynamics
        result was not driven by the contact, ``dynamics.torques_Nm`` when they share no torque.
    """
    names, by_name = _engagement_inputs(impact, dynamics)
    torques = _shared_torques(impact, dynamics)
    design = float(impact[0].attrs["design_speed_rpm"])
    cols, speed_used = _engagement_columns(impact, [by_name[name] for name in names], torques, design)
    ds = xr.Dataset(_engagement_variables(cols),
                    coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
                            "torque": variable(("torque",), torques, "N m", "pinion torque T1")})
    ds.attrs.update({"design_speed_rpm": design, "dynamics_speed_rpm": speed_used,
                     "force_direction": "transverse (F_bt convention of the LTCA and the impact model)",
                     **{f"{key}_{stage}": str(sets[0].attrs.get(key, "")) for stage, sets in
                        (("impact", impact), ("dynamics", dynamics)) for key in ("tooth_model", "contact_law")}})
    return name_force_lines(ds, "transverse")


def _engagement_inputs(impact: Sequence[xr.Dataset], dynamics: Sequence[xr.Dataset]) -> tuple[list[str], dict]:
    """The variants of the impact results, in their order, and the dynamics result of each name;
    refused unless both cover the same variants of one pair and every dynamics was driven by the
    contact."""
    names = variant_names("impact", impact)
    by_name = dict(zip(variant_names("dynamics", dynamics), dynamics))
    one_pair(impact=impact, dynamics=dynamics)
    if set(by_name) != set(names):
        raise GearmeshInputError("variants", sorted(by_name), f"impact and dynamics must cover the same variants "
                                 f"({sorted(names)})")
    for d in dynamics:
        if d.attrs.get("excitation_name") != "contact":
            raise GearmeshInputError("dynamics.excitation", d.attrs.get("excitation_name"),
                                     "must be 'contact' for the engagement table")
    return names, by_name


def _shared_torques(impact: Sequence[xr.Dataset], dynamics: Sequence[xr.Dataset]) -> np.ndarray:
    """The pinion torques (N·m) of the first dynamics result that the impact stage ran too."""
    t_dyn = np.asarray(dynamics[0]["pinion_torque"].values, dtype=float)
    t_imp = np.asarray(impact[0]["torque"].values, dtype=float)
    torques = np.array([t for t in t_dyn if same_point(t_imp, t).any()])
    if not torques.size:
        raise GearmeshInputError("dynamics.torques_Nm", t_dyn.tolist(), f"share no torque with impact.torques_Nm "
                                 f"{t_imp.tolist()} (pinion torques)")
    return torques


def _engagement_columns(impact: Sequence[xr.Dataset], dynamics: Sequence[xr.Dataset], torques: np.ndarray,
                        design: float) -> tuple[dict[str, np.ndarray], float]:
    """Per variant (``impact`` and ``dynamics`` in one order) and torque: the impact stage's values
    at the design speed and the dynamics' at the speed of its grid nearest it (returned too), its
    forces made transverse; NaN where not run."""
    cols = {k: np.full((len(impact), torques.size), np.nan) for k in (
        "fs", "fs_eb", "sim", "static_roll", "impact", "enter", "roll", "peak", "peak_all")}
    speed_used = np.nan
    for v, (imp, dyn) in enumerate(zip(impact, dynamics)):
        # normal -> transverse: cos βb = F_bt / F_normal of the static mesh force (F_bt = T1/r_b1)
        c = float(dyn["pinion_torque"].values[0]) / float(imp["base_radius"].values[0]) \
            / float(dyn["static_mesh_force"].values[0])
        grid = dyn["speed"].values[dyn["on_grid"].values.astype(bool)]
        speed_used = float(grid[np.argmin(np.abs(grid - design))])
        for k, t in enumerate(torques):
            i = int(np.flatnonzero(same_point(imp["torque"].values, t))[0])
            j = int(np.flatnonzero(same_point(dyn["pinion_torque"].values, t))[0])
            at = imp.sel(speed=design)
            cols["fs"][v, k] = float(at["impact_force"].values[i])
            cols["fs_eb"][v, k] = float(at["impact_force_energy_balance"].values[i])
            if "simulated_entering_excess" in imp:
                cols["sim"][v, k] = float(imp["simulated_entering_excess"].values[i])
            cols["static_roll"][v, k] = float(imp["roll_before_engagement"].values[i])
            d = dyn.isel(torque=j).sel(speed=speed_used)
            cols["impact"][v, k] = float(d["dynamic_impact_force"]) * c
            cols["enter"][v, k] = float(d["entering_pair_force_max"]) * c
            cols["roll"][v, k] = float(d["mesh_in_roll_before_A"])
            cols["peak"][v, k] = float(d["mesh_force_max"]) * c
            cols["peak_all"][v, k] = float(dyn.isel(torque=j)["mesh_force_max"].max()) * c
    return cols, speed_used


def _engagement_variables(cols: dict[str, np.ndarray]) -> dict[str, xr.Variable]:
    """The engagement table's variables (variant, torque) from its columns, with the ratios of the
    impact index F_s to the simulated and to the dynamic excess."""
    dims = ("variant", "torque")
    with np.errstate(divide="ignore", invalid="ignore"):
        over = {key: np.where(cols[key] > 0, cols["fs"] / cols[key], np.nan) for key in ("sim", "impact")}
    return {
        "impact_force": variable(dims, cols["fs"], "N", f"{IMPACT_INDEX} at the design speed (closed form of the "
                                                        f"energy method; an index of the impact, not a force the teeth "
                                                        f"carry)"),
        "impact_force_energy_balance": variable(dims, cols["fs_eb"], "N",
                                                f"{IMPACT_INDEX} by the energy balance at the design speed"),
        "simulated_entering_excess": variable(dims, cols["sim"], "N",
                                              "undamped engagement simulation: the entering pair's largest excess "
                                              "over its quasi-static load (NaN: not simulated)"),
        "impact_index_over_simulated_excess": variable(dims, over["sim"], "1", "F_s over the simulated excess of the "
                                                       "entering pair (NaN: not simulated)"),
        "impact_index_over_dynamic_impact": variable(dims, over["impact"], "1", "F_s over the entering pair's excess in "
                                                     "the steady-state dynamics (NaN: no excess)"),
        "dynamic_impact_force": variable(dims, cols["impact"], "N",
                                         "steady-state dynamics (contact excitation) at the speed nearest the design "
                                         "speed: the entering pair's largest excess over its quasi-static force "
                                         "(transverse)"),
        "entering_pair_force_max": variable(dims, cols["enter"], "N",
                                            "steady-state dynamics: the entering pair's largest force in the first "
                                            "part of its engagement (transverse)"),
        "static_mesh_in_roll_before_A": variable(dims, cols["static_roll"], "m",
                                                 "impact model: roll before A at which the entering pair first "
                                                 "touches in the quasi-static mesh"),
        "mesh_in_roll_before_A": variable(dims, cols["roll"], "m",
                                          "steady-state dynamics: roll before A at which the entering pair first "
                                          "carries load"),
        "peak_mesh_force": variable(dims, cols["peak"], "N",
                                    "steady-state dynamics: peak mesh force at the speed nearest the design speed "
                                    "(transverse)"),
        "peak_mesh_force_sweep": variable(dims, cols["peak_all"], "N",
                                          "steady-state dynamics: peak mesh force over the whole speed sweep "
                                          "(transverse)"),
    }
