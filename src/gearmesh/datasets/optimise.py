"""The optimiser's dataset (ga.nc), the optimum as a pair, and the CLI summary.

Engineering units at the boundary (N·m, rpm, µm / mm genes), SI inside the Dataset; every
variable carries ``units`` and ``long_name``. The optimisation: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

import json
import warnings
from typing import Any, Mapping

import numpy as np
import xarray as xr

from ..fe import use_fe_tables
from ..errors import GearmeshInputError
from ..gear import GEARS, GearPair, Modification, pair_geometry
from ..impact import SCENARIOS, impact_model
from ..io import variable
from ..ltca import pinion_torques
from ..optimise import (GENE_SYMBOLS, OptimisationResult, Problem, check_positive, check_settings, gene_table, optimise,
                        problem)
from ..surface import MODIFICATION_FIELDS
from .ltca import _geometry

__all__ = ["optimise_dataset", "result_dataset", "optimum_pair", "optimise_summary", "run_settings", "run_problem",
           "check_optimise"]

_TO_SI = {"um": 1e-6, "mm": 1e-3}


def run_settings(pair: GearPair, method: str = "ga", objective: str = "force", population: int = 40,
                 generations: int = 30, seed: int = 0, torque_Nm: float = 1000.0, on: str = "pinion",
                 speed_rpm: float = 5000.0, torques_Nm=(400.0, 1000.0, 1600.0), statistic: str = "max",
                 weights=None, modify=("pinion",), bounds: Mapping[str, Any] | None = None,
                 fixed: Mapping[str, Any] | None = None, constraints: Mapping[str, Any] | None = None,
                 random_baseline: bool = True, mutation_probability: float = 0.3, mutation_scale: float = 0.1,
                 keep_elitism: int = 2, points: int | None = None, window_positions: int = 64, face_samples: int = 257,
                 cycle_positions: int = 32, contact_law: str | None = None, corner_extension: float | None = None,
                 impact: Mapping[str, Any] | None = None):
    """Check the config's ``optimise:`` section (as keywords) for ``pair``: (geometry, settings,
    gene keywords, impact-model keywords). Torques are given on ``on`` (converted to the
    pinion). Refuses a bad value with GearmeshInputError naming the field.

    The impact model is the study's: ``impact`` is its ``impact:`` section (driver, points, lead
    slopes, contact law, slice method, corner extension, added inertia, energy velocity), so
    the optimum is optimal for the model the impact stage evaluates it with; ``points``,
    ``contact_law`` and ``corner_extension`` given here override it (None: the section's, or
    the package defaults without one)."""
    from ..tca import check_lead_slope

    geom = _geometry(pair)
    imp = dict(impact or {})
    constraints = dict(constraints or {})
    unknown = set(constraints) - {"lte_factor", "line_load_factor", "penalty"}
    if unknown:
        key = sorted(unknown)[0]
        raise GearmeshInputError(f"constraints.{key}", constraints[key],
                                 "is not a constraint; use lte_factor, line_load_factor, penalty")
    design = float(pinion_torques(geom, [check_positive("torque_Nm", torque_Nm)], on, field="torque_Nm")[0])
    robust = tuple(float(t) for t in pinion_torques(geom, torques_Nm, on, field="torques_Nm"))
    settings = check_settings(method=method, objective=objective, population=population, generations=generations,
                              seed=seed, torque=design, torques=robust, weights=weights, statistic=statistic,
                              speed_rpm=speed_rpm, lte_factor=constraints.get("lte_factor"),
                              line_load_factor=constraints.get("line_load_factor"),
                              penalty=constraints.get("penalty", 10.0), mutation_probability=mutation_probability,
                              mutation_scale=mutation_scale, keep_elitism=keep_elitism,
                              random_baseline=random_baseline,
                              energy_velocity=imp.get("energy_velocity", "transverse"))
    genes = {"modify": modify, "bounds": bounds, "fixed": fixed}
    gene_table(geom, **genes)
    lead = tuple(v * 1e-6 for v in check_lead_slope(imp.get("lead_slope_um", (0.0, 0.0))))
    model = {"points": imp.get("points", 50) if points is None else points,
             "contact_law_name": imp.get("contact_law", "palmgren") if contact_law is None else contact_law,
             "extension": imp.get("corner_extension", 0.25) if corner_extension is None else corner_extension,
             "method": imp.get("method", "transition"), "driver": imp.get("driver", "pinion"), "lead_slope": lead,
             "added_inertia_kg_m2": imp.get("added_inertia_kg_m2", (0.0, 0.0)),
             "window_positions": window_positions, "face_samples": face_samples, "cycle_positions": cycle_positions}
    return geom, settings, genes, model


def run_problem(pair: GearPair, **settings) -> Problem:
    """The optimisation problem of ``pair`` (settings: :func:`run_settings`), its impact model
    built once and its standard gear evaluated."""
    geom, checked, genes, model = run_settings(pair, **settings)
    return problem(impact_model(geom, **model), checked, **genes)


def check_optimise(config: Mapping[str, Any], pairs: Mapping[str, GearPair]) -> None:
    """Before any job runs: the study's ``optimise:`` section for every pair (fields named
    ``optimise.…``), and every variant taking the optimiser's pair (``{from: optimise}``)
    has the section and no modification of its own."""
    for variant, spec in (config.get("variants") or {}).items():
        if spec.get("from") is None:
            continue
        if "optimise" not in config:
            raise GearmeshInputError(f"variants.{variant}.from", spec["from"], "needs an 'optimise:' section in the study")
        if spec.get("modification"):
            raise GearmeshInputError(f"variants.{variant}.modification", spec["modification"],
                                     "cannot be given with 'from': the variant takes the optimiser's modification")
    if "optimise" in (config.get("variants") or {}):
        raise GearmeshInputError("variants.optimise", config["variants"]["optimise"],
                                 "is reserved (results/{study}/{pair}/optimise/ holds the optimiser's files)")
    if "optimise" not in config:
        return
    for name in config["pairs"]:
        try:
            run_settings(pairs[name], **config["optimise"], impact=config.get("impact"))
        except GearmeshInputError as exc:
            raise GearmeshInputError(f"optimise.{exc.field}", exc.value, exc.rule) from None


def _si(result: OptimisationResult, values: np.ndarray) -> np.ndarray:
    """Gene values (µm / mm) in m."""
    factors = np.array([_TO_SI[g.unit] for g in result.problem.genes])
    return np.asarray(values, dtype=float) * factors


def _objective_units(result: OptimisationResult) -> tuple[str, str]:
    s = result.problem.settings
    if s.objective == "velocity":
        return "m s-1", "impact velocity |v_n| at the design torque and speed"
    if s.objective == "robust":
        what = "largest" if s.statistic == "max" else "weighted mean"
        return "N", f"{what} mesh-in impact force F_s over the objective torques"
    return "N", "mesh-in impact force F_s at the design torque and speed"


def _nanmedian(values: np.ndarray) -> np.ndarray:
    """Median of each generation over the evaluated candidates (NaN: padding of a short batch)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an all-padding generation gives NaN
        return np.nanmedian(values, axis=1)


def _history_variables(result: OptimisationResult, prefix: str, label: str) -> dict[str, xr.Variable]:
    h = result.history.arrays()
    units, what = _objective_units(result)
    gc, g = ("generation", "candidate"), ("generation",)
    obj = h["objective"]
    out = {
        f"{prefix}objective": variable(gc, obj, units, f"{label}: objective J of each candidate ({what}; "
                                                       "penalties included, failed candidates at the failure value)"),
        f"{prefix}best_objective": variable(g, result.history.best, units, f"{label}: best objective so far"),
        f"{prefix}median_objective": variable(g, _nanmedian(obj), units,
                                              f"{label}: median objective of the generation's candidates"),
        f"{prefix}impact_force": variable(gc, h["force"], "N", f"{label}: F_s of each candidate at the design torque "
                                                               "(the first objective torque)"),
        f"{prefix}scenario": variable(gc, h["scenario"].astype(np.int8), "1",
                                      f"{label}: mesh-in scenario at the design torque: "
                                      + ", ".join(f"{k} {n}" for k, n in enumerate(SCENARIOS)) + ", -1 not evaluated"),
        f"{prefix}failed": variable(gc, h["failed"].astype(np.int8), "1",
                                    f"{label}: 1 for a failed candidate (no impact found, a non-finite force or no closing velocity)"),
        f"{prefix}cumulative_evaluations": variable(g, h["evaluations"], "1",
                                                    f"{label}: distinct candidates evaluated so far"),
        f"{prefix}population": variable(("generation", "candidate", "gene"), _si(result, h["genes"]), "m",
                                        f"{label}: gene values of each candidate (before the validity repair)"),
        f"{prefix}evaluations": variable((), np.int64(result.evaluations), "1", f"{label}: distinct candidates evaluated"),
        f"{prefix}wall_time": variable((), result.wall_s, "s", f"{label}: wall time of the run"),
    }
    if np.isfinite(h["lte"]).any():
        out[f"{prefix}lte_peak_to_peak"] = variable(gc, h["lte"], "m", f"{label}: peak-to-peak LTE at the design "
                                                                       "torque of each candidate")
    return out


def optimise_dataset(pair: GearPair, fe_compliance: xr.Dataset | None = None, **settings) -> xr.Dataset:
    """Run the optimiser on ``pair`` (settings: :func:`run_settings`) and return ga.nc: every
    generation's population, objective, F_s, scenario and best; the random-search baseline
    of the same budget; the optimum genes and parameters; the standard gear and the optimum
    at the objective torques; NSGA-II's Pareto front; method, seed, evaluations, wall time.
    With an impact model of ``method: fe``, ``fe_compliance`` supplies the FE tables."""
    from ..gear import pair_geometry

    if fe_compliance is not None:  # the FE tables of the workflow, before any model is built
        use_fe_tables(fe_compliance, pair_geometry(pair))
    return result_dataset(optimise(run_problem(pair, **settings)), settings)


def result_dataset(result: OptimisationResult, settings: Mapping[str, Any] | None = None) -> xr.Dataset:
    """ga.nc of a finished run (:func:`optimise_dataset`)."""
    prob, s = result.problem, result.problem.settings
    geom = prob.geom
    genes = prob.genes
    units, what = _objective_units(result)
    opt, std = result.optimum_evaluation, prob.standard
    data = _history_variables(result, "", s.method)
    if result.baseline is not None:
        data.update(_history_variables(result.baseline, "random_", "random search of the same budget"))
    t = ("objective_torque",)
    data.update({
        "gene_low": variable(("gene",), _si(result, [g.low for g in genes]), "m", "lower bound of each gene"),
        "gene_high": variable(("gene",), _si(result, [g.high for g in genes]), "m", "upper bound of each gene"),
        "optimum_genes": variable(("gene",), _si(result, result.optimum_genes), "m", "gene values of the optimum"),
        "optimum_modification": variable(("gear", "parameter"), result.optimum, "m",
                                         "seed 000's parameters y1..y6 of both gears at the optimum (as applied)"),
        "optimum_objective": variable((), float(opt.objective[0]), units, f"optimum: {what}"),
        "standard_objective": variable((), float(std.objective[0]), units, f"standard (unmodified) gear: {what}"),
        "reduction": variable((), 100.0 * (1.0 - float(opt.objective[0]) / float(std.objective[0])), "percent",
                              "reduction of the objective against the standard gear"),
        "optimum_impact_force": variable(t, opt.force[0], "N", "optimum: mesh-in impact force F_s"),
        "standard_impact_force": variable(t, std.force[0], "N", "standard gear: mesh-in impact force F_s"),
        "optimum_impact_velocity": variable(t, opt.velocity[0], "m s-1", "optimum: impact velocity |v_n|"),
        "standard_impact_velocity": variable(t, std.velocity[0], "m s-1", "standard gear: impact velocity |v_n|"),
        "optimum_scenario": variable(t, opt.scenario[0].astype(np.int8), "1", "optimum: mesh-in scenario "
                                     + ", ".join(f"{k} {n}" for k, n in enumerate(SCENARIOS))),
        "standard_scenario": variable(t, std.scenario[0].astype(np.int8), "1", "standard gear: mesh-in scenario"),
        "rho_sap": variable(("gear",), geom.rho_sap, "m", "roll length of the start of active profile"),
        "rho_eap": variable(("gear",), geom.rho_eap, "m", "roll length of the end of active profile"),
        "face_width": variable((), geom.face_width, "m", "meshing face width"),
        "normal_module": variable((), geom.pair.normal_module, "m", "normal module"),
        "speed": variable((), s.speed_rpm, "rpm", "pinion speed of the objective"),
        "design_torque": variable((), s.torque, "N m", "design pinion torque (LTE and line-load constraints, NSGA-II)"),
    })
    if np.isfinite(std.lte_peak_to_peak).all():
        data.update({
            "optimum_lte_peak_to_peak": variable((), float(opt.lte_peak_to_peak[0]), "m",
                                                 "optimum: peak-to-peak LTE at the design torque"),
            "standard_lte_peak_to_peak": variable((), float(std.lte_peak_to_peak[0]), "m",
                                                  "standard gear: peak-to-peak LTE at the design torque"),
            "optimum_max_line_load": variable((), float(opt.max_line_load[0]), "N m-1",
                                              "optimum: largest line load over the mesh cycle at the design torque"),
            "standard_max_line_load": variable((), float(std.max_line_load[0]), "N m-1",
                                               "standard gear: largest line load at the design torque"),
        })
    if result.pareto is not None:
        pg, pf, pl = result.pareto
        data.update({
            "pareto_objective": variable(("front",), pf, "N", "Pareto front: F_s at the design torque and speed"),
            "pareto_lte_peak_to_peak": variable(("front",), pl, "m", "Pareto front: peak-to-peak LTE at the design torque"),
            "pareto_genes": variable(("front", "gene"), _si(result, pg), "m", "Pareto front: gene values"),
        })
    coords = {
        "generation": variable(("generation",), np.arange(s.generations + 1), "1", "generation (0: initial population)"),
        "candidate": variable(("candidate",), np.arange(s.population), "1", "candidate in the generation"),
        "gene": variable(("gene",), np.array([g.name for g in genes]), "1", "gene: gear.pair-file key"),
        "gene_symbol": variable(("gene",), np.array([g.symbol for g in genes]), "1", "seed 000's symbol of the gene"),
        "gear": variable(("gear",), np.array(GEARS), "1", "gear"),
        "parameter": variable(("parameter",), np.array(MODIFICATION_FIELDS), "1", "seed 000's parameters y1..y6"),
        "parameter_symbol": variable(("parameter",), np.array(GENE_SYMBOLS), "1", "seed 000's symbols"),
        "objective_torque": variable(t, np.array(s.objective_torques), "N m", "pinion torques of the objective"),
    }
    ds = xr.Dataset(data_vars=data, coords=coords)
    ds.attrs.update({
        "method": s.method, "seed": s.seed, "objective": s.objective, "objective_statistic": s.statistic,
        "population_size": s.population, "generations": s.generations,
        "failure_factor": "a failed candidate's objective is FAILURE_FACTOR x the standard gear's",
        "settings_json": json.dumps(dict(settings or {}), sort_keys=True, default=str),
    })
    return ds


def optimum_pair(pair: GearPair, ds: xr.Dataset) -> GearPair:
    """``pair`` carrying the optimum modification of ga.nc (both gears, as applied)."""
    p = ds["optimum_modification"].values
    mods = tuple(Modification(**{f: float(p[g, k]) for k, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
    out = pair.with_changes(modification=mods)
    pair_geometry(out)  # validity (lengths, depths) by construction; checked here once more
    return out


def optimise_summary(pair: GearPair, torque_Nm: float, speed_rpm: float, on: str = "pinion",
                     modify=("pinion",), method: str = "ga", seed: int = 0, population: int = 40,
                     generations: int = 30) -> dict[str, Any]:
    """Headline numbers of one optimisation (the CLI's ``optimise --json``): the optimum genes
    named with units, F_s of the optimum and of the standard gear, the reduction, the
    optimum's scenario at the design point, evaluations and wall time."""
    prob = run_problem(pair, method=method, seed=seed, population=population, generations=generations,
                       torque_Nm=torque_Nm, on=on, speed_rpm=speed_rpm, modify=modify, random_baseline=False)
    res = optimise(prob)
    opt, std = res.optimum_evaluation, prob.standard
    return {
        "name": pair.name,
        "method": method,
        "seed": seed,
        "torque_Nm": float(torque_Nm),
        "torque_on": on,
        "speed_rpm": float(speed_rpm),
        "genes": {g.name: float(v) for g, v in zip(prob.genes, res.optimum_genes)},
        "impact_force_N": float(opt.force[0, 0]),
        "standard_impact_force_N": float(std.force[0, 0]),
        "reduction_percent": 100.0 * (1.0 - float(opt.force[0, 0]) / float(std.force[0, 0])),
        "scenario": SCENARIOS[int(opt.scenario[0, 0])],
        "standard_scenario": SCENARIOS[int(std.scenario[0, 0])],
        "evaluations": res.evaluations,
        "wall_s": res.wall_s,
    }
