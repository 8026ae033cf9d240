"""The optimiser's dataset (ga.nc), the optimum as a pair, and the CLI summary.

Engineering units at the boundary (N·m, rpm, µm / mm genes), SI inside the Dataset; every
variable carries ``units`` and ``long_name``. The optimisation: :mod:`gearmesh.optimise`; the
manufacturing tolerances: :mod:`gearmesh.tolerance`.

A study names its optimisations (``optimise: {NAME: {...}}``); each runs once per pair into
``results/{study}/{pair}/optimise/NAME/`` and a variant ``{from: optimise.NAME}`` takes its
optimum. The study's ``tolerances:`` section (ISO 1328-1 grade of the lead, modification
tolerances, samples) is the manufactured population every run and the impact stage share.
"""

from __future__ import annotations

import json
import math
import warnings
from typing import Any, Mapping

import numpy as np
import xarray as xr

from ..fe_tables import use_fe_tables
from ..errors import GearmeshInputError
from ..gear import GEARS, GearPair, Modification, pair_geometry
from ..impact.model import SCENARIOS, impact_model
from ..pairfile import MODIFICATION_UNITS
from ..robust import CRITERIA, CRITERION_UNITS
from ..io import name_force_lines, variable
from ..ltca import MESH_ORDERS
from ..optimise.checks import resolve_settings
from ..optimise.constraints import constraint_factors
from ..optimise.evaluation import Problem
from ..optimise.genes import GENE_SYMBOLS, gene_table
from ..optimise.objective import problem, standard_penalised_objective
from ..optimise.search import OptimisationResult, optimise
from ..surface import MODIFICATION_FIELDS
from ..schema import defaults, settings_object
from ..settings import Impact, Optimise
from .ltca import _geometry

__all__ = ["optimise_dataset", "result_dataset", "optimum_pair", "optimise_summary", "run_settings", "run_problem",
           "check_optimise", "OPTIMISE_SOURCE"]

_TO_SI = {"um": 1e-6, "mm": 1e-3}
#: The six modification parameters in words (the mesh-in impact paper's y1 to y6), for descriptions.
MODIFICATION_TEXT = ", ".join(name.replace("_", " ") for name in MODIFICATION_FIELDS)
#: A variant that takes an optimum names its run: ``{from: optimise.NAME}``.
OPTIMISE_SOURCE = "optimise."


def run_settings(pair: GearPair, *, impact: Mapping[str, Any] | None = None,
                 tolerances: Mapping[str, Any] | None = None, **section):
    """One optimisation of ``pair`` as it runs: (geometry, resolved settings, gene keywords,
    impact-model keywords, tolerance model). The one path of every door (the workflow's stage, the
    CLI, the Python API).

    The impact model is the study's, so the optimum is optimal for the model the impact stage
    evaluates it with.

    Parameters
    ----------
    pair : GearPair
        The pair to optimise.
    impact : Mapping, optional
        The study's ``impact:`` section (driver, points, contact law, slice method, corner
        extension, window and face sampling, added inertia, energy velocity); None: the declared
        defaults. ``points``, ``contact_law``, ``corner_extension``, ``window_positions`` and
        ``face_samples`` given in ``section`` override it.
    tolerances : Mapping, optional
        The study's ``tolerances:`` section (:func:`gearmesh.tolerance.study_tolerances`).
    **section
        The study's ``optimise.NAME`` section (:class:`gearmesh.settings.Optimise`: every default
        and bound there), parsed once; :func:`gearmesh.optimise.checks.resolve_settings` turns it
        into the run's settings (pinion torques, SI) and refuses what breaks a rule between fields.

    Returns
    -------
    tuple
        (PairGeometry, the resolved settings, gene keywords ``modify``/``bounds``/``fixed``,
        impact-model keywords of :func:`gearmesh.impact.model.impact_model`, tolerance model).

    Raises
    ------
    GearmeshInputError
        Naming the field of a bad value.
    """
    declared = settings_object(Optimise, section)
    imp = settings_object(Impact, impact, "impact")
    geom = _geometry(pair)
    settings, tol_model = resolve_settings(geom, declared, imp.energy_velocity, tolerances)
    genes = {"modify": declared.modify, "bounds": declared.bounds, "fixed": declared.fixed}
    gene_table(geom, **genes)

    def pick(own, key):
        return getattr(imp, key) if own is None else own

    d = declared
    model = {"contact": d.contact_model(imp), "driver": imp.driver, "added_inertia_kg_m2": imp.added_inertia_kg_m2,
             "window_positions": pick(d.window_positions, "window_positions"),
             "face_samples": pick(d.face_samples, "face_samples"), "cycle_positions": d.cycle_positions}
    return geom, settings, genes, model, tol_model


def run_problem(pair: GearPair, **settings) -> Problem:
    """The optimisation problem of ``pair``, its impact model built once and its standard gear
    evaluated.

    Parameters
    ----------
    pair : GearPair
        The pair to optimise.
    **settings
        ``impact``, ``tolerances`` and the ``optimise.NAME`` section, as :func:`run_settings` takes them.

    Returns
    -------
    Problem
        The problem (:class:`gearmesh.optimise.evaluation.Problem`) :func:`gearmesh.optimise.optimise` solves.
    """
    geom, checked, genes, model, tol = run_settings(pair, **settings)
    return problem(impact_model(geom, **model), checked, tolerance=tol, **genes)


def check_optimise(config: Mapping[str, Any], pairs: Mapping[str, GearPair]) -> None:
    """Before any job runs: every named optimisation of the study's ``optimise:`` section for every
    pair (fields named ``optimise.NAME.…``; the shared ``tolerances.…`` under their own name), and
    every variant taking an optimum (``{from: optimise.NAME}``) names a run and has no
    modification of its own.

    Parameters
    ----------
    config : Mapping[str, Any]
        The loaded study (:func:`gearmesh.config.load_study`).
    pairs : Mapping[str, GearPair]
        The study's pairs by name (every name of ``config["pairs"]``).

    Raises
    ------
    GearmeshInputError
        Naming ``optimise.NAME.FIELD``, ``tolerances.FIELD``, ``variants.V.from``,
        ``variants.V.modification`` or ``variants.optimise`` (a reserved name).
    """
    runs = config.get("optimise") or {}
    for variant, spec in (config.get("variants") or {}).items():
        source = spec.get("from")
        if source is None:
            continue
        name = source[len(OPTIMISE_SOURCE):] if source.startswith(OPTIMISE_SOURCE) else None
        if name not in runs:
            raise GearmeshInputError(f"variants.{variant}.from", source,
                                     f"must be optimise.NAME with NAME one of the study's optimisations {sorted(runs)}")
        if spec.get("modification"):
            raise GearmeshInputError(f"variants.{variant}.modification", spec["modification"],
                                     "cannot be given with 'from': the variant takes the optimiser's modification")
    if "optimise" in (config.get("variants") or {}):
        raise GearmeshInputError("variants.optimise", config["variants"]["optimise"],
                                 "is reserved (results/{study}/{pair}/optimise/ holds the optimiser's files)")
    for run, section in runs.items():
        for name in config["pairs"]:
            try:
                run_settings(pairs[name], **section, impact=config.get("impact"), tolerances=config.get("tolerances"))
            except GearmeshInputError as exc:
                field = exc.field if exc.field.startswith("tolerances") else f"optimise.{run}.{exc.field}"
                raise GearmeshInputError(field, exc.value, exc.rule) from None


def _si(result: OptimisationResult, values: np.ndarray) -> np.ndarray:
    """Gene values (µm / mm) in m."""
    factors = np.array([_TO_SI[g.unit] for g in result.problem.genes])
    return np.asarray(values, dtype=float) * factors


def _objective_units(result: OptimisationResult) -> tuple[str, str]:
    s = result.problem.settings
    what = "impact velocity |v_n|" if s.objective == "velocity" else "mesh-in impact force F_s"
    units = "m s-1" if s.objective == "velocity" else "N"
    if len(s.objective_torques) > 1:
        what = ("largest " if s.statistic == "max" else "duty-cycle mean ") + what + " over the load spectrum"
    else:
        what += " at the design torque"
    if s.tolerance_statistic is not None:
        level = f" {s.tolerance_level:g} %" if s.tolerance_statistic in ("percentile", "cvar") else ""
        what += f", {s.tolerance_statistic}{level} over the nominal and {s.tolerance_samples} tolerance samples"
    return units, what


def _nanmedian(values: np.ndarray) -> np.ndarray:
    """Median of each generation over the evaluated candidates (NaN: padding of a short batch)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an all-padding generation gives NaN
        return np.nanmedian(values, axis=1)


def _scenario_variable(dims, values, what: str) -> xr.Variable:
    return variable(dims, np.asarray(values).astype(np.int8), "1", f"{what}: "
                    + ", ".join(f"{k} {n}" for k, n in enumerate(SCENARIOS)) + ", -1 not evaluated")


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
        f"{prefix}impact_force": variable(gc, h["force"], "N", f"{label}: nominal F_s of each candidate at the design "
                                                               "torque"),
        f"{prefix}scenario": _scenario_variable(gc, h["scenario"], f"{label}: nominal mesh-in scenario at the design "
                                                                   "torque"),
        f"{prefix}failed": variable(gc, h["failed"].astype(np.int8), "1",
                                    f"{label}: 1 for a failed candidate (no impact found, a non-finite value or no "
                                    "closing velocity, at any torque or sample)"),
        f"{prefix}cumulative_evaluations": variable(g, h["evaluations"], "1",
                                                    f"{label}: distinct candidates evaluated so far"),
        f"{prefix}population": variable(("generation", "candidate", "gene"), _si(result, h["genes"]), "m",
                                        f"{label}: gene values of each candidate (before the validity repair)"),
        f"{prefix}evaluations": variable((), np.int64(result.evaluations), "1", f"{label}: distinct candidates evaluated"),
    }
    if np.isfinite(h["lte"]).any():
        out[f"{prefix}lte_peak_to_peak"] = variable(gc, h["lte"], "m", f"{label}: peak-to-peak LTE at the design "
                                                                       "torque of each candidate")
    if constraint_factors(result.problem.settings):
        out[f"{prefix}violation"] = variable(gc, h["violation"], "1", f"{label}: summed relative excess of the "
                                             "constraints of each candidate (0: meets every one; NaN: failed)")
    names = result.problem.settings.pareto_objectives if h["pareto"].shape[-1] else ()
    for k, name in enumerate(names):
        if name in PARETO_RATIOS:
            out[f"{prefix}{name}_ratio"] = variable(gc, h["pareto"][..., k], "1",
                                                    f"{label}: {PARETO_RATIOS[name]} of each candidate")
    return out


#: The ratio objectives of NSGA-II in words (ga.nc long names).
PARETO_RATIOS = {
    "te_harmonics": "worst ratio of the loaded-TE mesh-order amplitudes (harmonic_orders) to the unmodified pair's over the "
                    "load spectrum",
    "pressure": "worst ratio of the peak contact pressure to the unmodified pair's over the load spectrum (flank to "
                "flank, tip edge to tip edge)",
    "root_stress": "worst ratio of the peak root stress to the unmodified pair's over the load spectrum",
}


def _pareto_variable(name: str, units: str, what: str) -> tuple[str, str, str]:
    """(ga.nc name, units, long name) of NSGA-II objective ``name`` on the front."""
    if name == "impact":
        return "pareto_objective", units, f"objective J ({what}; penalties included)"
    if name == "lte":
        return "pareto_lte_peak_to_peak", "m", "peak-to-peak LTE at the design torque"
    return f"pareto_{name}_ratio", "1", PARETO_RATIOS[name]


def _criteria_variables(result: OptimisationResult) -> dict[str, xr.Variable]:
    """The optimum's and the standard gear's loaded contact at the spectrum torques (nominal gear,
    or each quantity's tolerance statistic over the manufactured gears with criteria_over_samples)."""
    opt, std = result.optimum_evaluation.criteria, result.problem.standard.criteria
    if opt is None or std is None:
        return {}
    s = result.problem.settings
    gears = f"{s.tolerance_statistic} over the manufactured gears" if s.criteria_over_samples and \
        s.tolerance_statistic is not None else "nominal gear"
    t, tk = ("objective_torque",), ("objective_torque", "mesh_order")
    out = {}
    for who, c in (("optimum", opt), ("standard", std)):
        label = "optimum" if who == "optimum" else "standard gear"
        out[f"{who}_lte_harmonics"] = variable(tk, c.te_harmonics[0], "m", f"{label}: amplitude of the loaded TE at "
                                                                           f"mesh orders 1-3 ({gears})")
        if np.all(np.isfinite(c.root_stress)):
            out[f"{who}_flank_pressure"] = variable(t, c.flank_pressure[0], "Pa", f"{label}: largest Hertzian contact "
                                                    f"pressure on the flanks over the mesh cycle ({gears})")
            out[f"{who}_edge_pressure"] = variable(t, c.edge_pressure[0], "Pa", f"{label}: largest Hertzian contact "
                                                   f"pressure on the tip edges over the mesh cycle ({gears})")
            out[f"{who}_root_stress"] = variable(t, c.root_stress[0], "Pa", f"{label}: largest tooth-root stress of "
                                                 f"either gear (ISO 6336-3 local form, {gears})")
    return out


def optimise_dataset(pair: GearPair, fe_compliance: xr.Dataset | None = None, **settings) -> xr.Dataset:
    """Run the optimiser on ``pair`` (settings: :func:`run_settings`) and return ga.nc: every
    generation's population, objective, F_s, scenario and best; the random-search baseline
    (when asked for); the optimum genes and parameters; the standard gear and the optimum at the
    spectrum torques under every tolerance sample; the load window; NSGA-II's Pareto front;
    method, seed, evaluations, wall time.

    Parameters
    ----------
    pair : GearPair
        The pair to optimise.
    fe_compliance : xarray.Dataset, optional
        fe_compliance.nc (:func:`gearmesh.datasets.fe.fe_compliance_dataset`): the FE tables an
        impact model of ``method: fe`` needs.
    **settings
        ``impact``, ``tolerances`` and the ``optimise.NAME`` section, as :func:`run_settings` takes them.

    Returns
    -------
    xarray.Dataset
        ga.nc (:func:`result_dataset`).

    Raises
    ------
    GearmeshInputError
        Naming the field of a bad setting.
    """
    if fe_compliance is not None:  # the FE tables of the workflow, before any model is built
        use_fe_tables(fe_compliance, pair_geometry(pair))
    return result_dataset(optimise(run_problem(pair, **settings)), settings)


def _verification_variables(result: OptimisationResult) -> dict[str, xr.Variable]:
    """The optimum checked on its own tolerance box (:class:`gearmesh.optimise.Verification`)."""
    v = result.verification
    if v is None:
        return {}
    t = ("objective_torque",)
    how = ("searched" if v.searched else "the search's first stage, the corners at five lead mismatches: a lower "
           "bound")
    out = {f"verified_worst_{name}": variable(t, v.worst.values[:, k], CRITERION_UNITS[name],
                                              f"optimum: {name.replace('_', ' ')} of its worst manufactured gear over "
                                              f"the tolerance box ({how})")
           for k, name in enumerate(CRITERIA)}
    reference = result.problem.reference
    out |= {f"reference_worst_{name}": variable(t, reference.values[:, k], CRITERION_UNITS[name],
                                                f"standard gear: {name.replace('_', ' ')} of its worst manufactured "
                                                "gear over the tolerance box")
            for k, name in enumerate(CRITERIA)}
    out |= {
        "verified_violation": variable((), v.violation, "1", "optimum: the constraints' summed relative excess on "
                                       "its worst manufactured gears (0: every constraint met on the tolerance box)"),
        "verified_rank": variable((), np.int64(v.rank), "1", "optimum's place among the run's candidates, best "
                                  "first (0: the run's best met the constraints on its tolerance box)"),
        "verified_tried": variable((), np.int64(v.tried), "1", "candidates checked on their tolerance box"),
        "verified_searched": variable((), np.int8(v.searched), "1", "optimum's tolerance box searched in full (1), or "
                                      "its first stage alone (0: refused on it, its worst and violation lower bounds; "
                                      "the sign-off's impact stage searches it in full)"),
    }
    return out


def _diagnostic_variables(result: OptimisationResult) -> dict[str, xr.Variable]:
    d, prob = result.diagnostics, result.problem
    t, w, st = ("objective_torque",), ("window_torque",), ("tolerance_sample", "objective_torque")
    low, high = d.load_window
    data = {
        "window_impact_force": variable(w, d.window_force, "N", "optimum: nominal F_s on the load-window grid"),
        "window_standard_impact_force": variable(w, d.window_standard, "N",
                                                 "standard gear: nominal F_s on the load-window grid"),
        "window_scenario": _scenario_variable(w, d.window_scenario, "optimum: scenario on the load-window grid"),
        "window_standard_scenario": _scenario_variable(w, d.window_standard_scenario,
                                                       "standard gear: scenario on the load-window grid"),
        "load_window": variable(("bound",), np.array([low, high]), "N m",
                                "load window: the contiguous pinion-torque range around the design torque where the "
                                "optimum's F_s is below the standard gear's (grid ends; NaN: not at the design torque)"),
        "tolerance_impact_force": variable(st, d.spread_force, "N",
                                           "optimum: F_s of the nominal (sample 0) and each tolerance sample"),
        "tolerance_standard_impact_force": variable(st, d.spread_standard, "N",
                                                    "standard gear: F_s of the nominal (sample 0) and each tolerance "
                                                    "sample"),
        "tolerance_scenario": _scenario_variable(st, d.spread_scenario, "optimum: scenario of each tolerance sample"),
        "tolerance_deviation": variable(("tolerance_sample", "toleranced"), np.vstack(
            [np.zeros((1, prob.deviations.shape[1])), prob.deviations * _half_widths(prob)]), "m",
            "deviation of each toleranced quantity in each sample (sample 0 the nominal); lead slopes over the "
            "meshing face width"),
        "tolerance_half_width": variable(("toleranced",), _half_widths(prob), "m",
                                         "half-width of each toleranced quantity (ISO 1328-1 f_Hbeta for lead slopes)"),
    }
    opt, std = result.optimum_evaluation, prob.standard
    if np.all(np.isfinite(opt.dynamic_factor)):
        data["dynamic_factor"] = variable(t, opt.dynamic_factor[0], "1", "optimum: dynamic factor (peak over static "
                                          "mesh force of the contact-driven 8-DOF pair over the speed range)")
        data["standard_dynamic_factor"] = variable(t, std.dynamic_factor[0], "1", "standard gear: dynamic factor "
                                                   "(peak over static mesh force over the speed range)")
    return data


def _half_widths(prob: Problem) -> np.ndarray:
    tol = prob.tolerance
    return np.array([tol.lead[g] if kind == "lead" else tol.modification[g, k] for kind, g, k in tol.dimensions])


def result_dataset(result: OptimisationResult, settings: Mapping[str, Any] | None = None) -> xr.Dataset:
    """ga.nc of a finished run (:func:`optimise_dataset`).

    Parameters
    ----------
    result : OptimisationResult
        The finished run (:func:`gearmesh.optimise.optimise`).
    settings : Mapping, optional
        The settings the run was given, recorded in the attributes.

    Returns
    -------
    xarray.Dataset
        ga.nc: per generation the population, objective, F_s (N), scenario and best; the random
        baseline (prefix ``random_``) when run; the optimum's genes and modification (m) against the
        standard gear; its criteria, verification on its tolerance box and Pareto front (NSGA-II);
        method, seed, evaluations in the attributes.
    """
    prob, s = result.problem, result.problem.settings
    units, what = _objective_units(result)
    data = _history_variables(result, "", s.method)
    if result.baseline is not None:
        data.update(_history_variables(result.baseline, "random_", "random search of the same budget"))
    data.update(_optimum_variables(result, units, what))
    if result.diagnostics is not None:
        data.update(_diagnostic_variables(result))
    data.update(_design_torque_variables(result))
    data.update(_criteria_variables(result))
    data.update(_verification_variables(result))
    if constraint_factors(s):  # the unmodified pair as a candidate of this run: its J with the penalties
        data["standard_penalised_objective"] = variable((), standard_penalised_objective(prob), units,
                                                        f"standard gear as a candidate: {what} with the "
                                                        "constraints' penalties")
    data.update(_pareto_variables(result, units, what))
    ds = xr.Dataset(data_vars=data, coords=_result_coordinates(result))
    ds.attrs.update(_result_attributes(result, settings))
    return name_force_lines(ds, "transverse")


def _optimum_variables(result: OptimisationResult, units: str, what: str) -> dict[str, xr.Variable]:
    """The genes' bounds and the optimum against the standard gear: objective, nominal F_s, |v_n| and
    scenario at each spectrum torque; the pair's dimensions and the run's operating point."""
    prob, s = result.problem, result.problem.settings
    geom, genes = prob.geom, prob.genes
    opt, std = result.optimum_evaluation, prob.standard
    t = ("objective_torque",)
    return {
        "gene_low": variable(("gene",), _si(result, [g.low for g in genes]), "m", "lower bound of each gene"),
        "gene_high": variable(("gene",), _si(result, [g.high for g in genes]), "m", "upper bound of each gene"),
        "optimum_genes": variable(("gene",), _si(result, result.optimum_genes), "m", "gene values of the optimum"),
        "optimum_modification": variable(("gear", "parameter"), result.optimum, "m",
                                         f"modification of both gears at the optimum, as applied "
                                         f"({MODIFICATION_TEXT})"),
        "optimum_objective": variable((), float(opt.objective[0]), units, f"optimum: {what}"),
        "standard_objective": variable((), float(std.objective[0]), units, f"standard (unmodified) gear: {what}"),
        "reduction": variable((), 100.0 * (1.0 - float(opt.objective[0]) / float(std.objective[0])), "percent",
                              "reduction of the objective against the standard gear (positive: lower)"),
        "optimum_impact_force": variable(t, opt.force[0, 0], "N", "optimum: nominal mesh-in impact force F_s"),
        "standard_impact_force": variable(t, std.force[0, 0], "N", "standard gear: nominal mesh-in impact force F_s"),
        "optimum_impact_velocity": variable(t, opt.velocity[0, 0], "m s-1", "optimum: nominal impact velocity |v_n|"),
        "standard_impact_velocity": variable(t, std.velocity[0, 0], "m s-1",
                                             "standard gear: nominal impact velocity |v_n|"),
        "optimum_scenario": _scenario_variable(t, opt.scenario[0, 0], "optimum: nominal mesh-in scenario"),
        "standard_scenario": _scenario_variable(t, std.scenario[0, 0], "standard gear: nominal mesh-in scenario"),
        "rho_sap": variable(("gear",), geom.rho_sap, "m", "roll length of the start of active profile"),
        "rho_eap": variable(("gear",), geom.rho_eap, "m", "roll length of the end of active profile"),
        "face_width": variable((), geom.face_width, "m", "meshing face width"),
        "normal_module": variable((), geom.pair.normal_module, "m", "normal module"),
        "speed": variable((), s.speed_rpm, "rpm", "pinion speed of the objective"),
        "design_torque": variable((), s.torque, "N m", "design pinion torque (LTE and line-load constraints, NSGA-II, "
                                                       "the load window's anchor)"),
        "torque_weight": variable(t, np.asarray(s.weights if s.weights else [np.nan] * len(s.torques)), "1",
                                  "time share of each spectrum torque (statistic mean; NaN: equal shares or max)"),
    }


def _design_torque_variables(result: OptimisationResult) -> dict[str, xr.Variable]:
    """Peak-to-peak LTE and largest line load of the optimum and the standard gear at the design
    torque (none when the run did not evaluate them)."""
    opt, std = result.optimum_evaluation, result.problem.standard
    if not np.isfinite(std.lte_peak_to_peak).all():
        return {}
    return {
        "optimum_lte_peak_to_peak": variable((), float(opt.lte_peak_to_peak[0]), "m",
                                             "optimum: peak-to-peak LTE at the design torque"),
        "standard_lte_peak_to_peak": variable((), float(std.lte_peak_to_peak[0]), "m",
                                              "standard gear: peak-to-peak LTE at the design torque"),
        "optimum_max_line_load": variable((), float(opt.max_line_load[0]), "N m-1",
                                          "optimum: largest line load over the mesh cycle at the design torque"),
        "standard_max_line_load": variable((), float(std.max_line_load[0]), "N m-1",
                                           "standard gear: largest line load at the design torque"),
    }


def _pareto_variables(result: OptimisationResult, units: str, what: str) -> dict[str, xr.Variable]:
    """NSGA-II's Pareto front: its genes and each objective (none for another method)."""
    s = result.problem.settings
    data: dict[str, xr.Variable] = {}
    if result.pareto is not None:
        pg, po = result.pareto
        data["pareto_genes"] = variable(("front", "gene"), _si(result, pg), "m", "Pareto front: gene values "
                                        "(ordered by the objective J; the first is the optimum)")
        for k, name in enumerate(s.pareto_objectives):
            key, unit, long_name = _pareto_variable(name, units, what)
            data[key] = variable(("front",), po[:, k], unit, f"Pareto front: {long_name}")
    return data


def _result_coordinates(result: OptimisationResult) -> dict[str, xr.Variable]:
    """The coordinates of ga.nc: generations, candidates, genes, gears, parameters, spectrum torques,
    mesh orders and, where the run has them, the diagnostics' and the verification's."""
    prob, s = result.problem, result.problem.settings
    genes = prob.genes
    t = ("objective_torque",)
    coords = {
        "generation": variable(("generation",), np.arange(s.generations + 1), "1", "generation (0: initial population)"),
        "candidate": variable(("candidate",), np.arange(s.population), "1", "candidate in the generation"),
        "gene": variable(("gene",), np.array([g.name for g in genes]), "1", "gene: gear.pair-file key"),
        "gene_symbol": variable(("gene",), np.array([g.symbol for g in genes]), "1",
                                "symbol of the gene in the mesh-in impact paper (y1 to y6)"),
        "gear": variable(("gear",), np.array(GEARS), "1", "gear"),
        "parameter": variable(("parameter",), np.array(MODIFICATION_FIELDS), "1",
                              f"modification parameter: {MODIFICATION_TEXT}"),
        "parameter_symbol": variable(("parameter",), np.array(GENE_SYMBOLS), "1",
                                     "symbol of the parameter in the mesh-in impact paper (y1 to y6)"),
        "objective_torque": variable(t, np.array(s.objective_torques), "N m", "pinion torques of the load spectrum"),
        "mesh_order": variable(("mesh_order",), np.array(MESH_ORDERS), "1", "harmonic of the mesh frequency"),
    }
    if result.diagnostics is not None:
        coords.update({
            "window_torque": variable(("window_torque",), result.diagnostics.window_torque, "N m",
                                      "pinion torques of the load-window grid"),
            "tolerance_sample": variable(("tolerance_sample",), np.arange(prob.deviations.shape[0] + 1), "1",
                                         "manufactured sample (0: the nominal)"),
            "toleranced": variable(("toleranced",), np.array(prob.tolerance.labels(), dtype=str), "1",
                                   "toleranced quantity: gear.pair-file key, or gear.lead_slope_deviation_um (ISO 1328-1 f_Hbeta)"),
            "bound": variable(("bound",), np.array(["low", "high"]), "1", "ends of the load window"),
        })
    if result.verification is not None:
        coords["criterion"] = variable(("criterion",), np.array(CRITERIA), "1", "sign-off criterion of one gear")
    return coords


def _result_attributes(result: OptimisationResult, settings: Mapping[str, Any] | None) -> dict[str, Any]:
    """ga.nc's attributes: the run's method, objective, tolerances, budget, constraints and settings,
    its measured times."""
    prob, s = result.problem, result.problem.settings
    return {
        "method": s.method, "seed": s.seed, "objective": s.objective, "objective_statistic": s.statistic,
        "tooth_model": prob.model.ltca.method, "contact_law": prob.model.ltca.law.name,
        "notes": "; ".join(optimum_notes(prob, result.diagnostics)),
        "tolerance_statistic": s.tolerance_statistic or "none (nominal)", "tolerance_level_percent": s.tolerance_level,
        "tolerance_samples": int(prob.deviations.shape[0]), "tolerance_sampling": s.sampling,
        "lead_grade_iso1328": -1 if prob.tolerance.grade is None else prob.tolerance.grade,
        "population_size": s.population, "generations": s.generations,
        "failure_factor": "a failed candidate's objective is FAILURE_FACTOR x the standard gear's",
        "pareto_objectives": ",".join(s.pareto_objectives) if s.method == "nsga2" else "",
        "constraints": json.dumps(constraint_factors(s), sort_keys=True),
        "settings_json": json.dumps(dict(settings or {}), sort_keys=True, default=str),
        # measured times: attributes, not data (gearmesh.io.TIMING_SUFFIX: the job's log, not the file)
        "wall_seconds": result.wall_s,
        **({"random_wall_seconds": result.baseline.wall_s} if result.baseline is not None else {}),
    }


#: The resolution an optimum's pair file states its modification to, per gene unit (µm: depths,
#: mm: lengths): 0.01 µm and 0.001 mm, a tenth of what a gear measuring machine resolves (0.1 µm)
#: and far below a drawing's tolerance on a relief (±2 µm in the default study), so the file says
#: what can be made and measured and no digits beyond (ga.nc keeps the optimiser's full values).
MANUFACTURING_RESOLUTION = {"um": 0.01, "mm": 0.001}


def _drawing_value(value: float, unit: str, down: bool = False) -> float:
    """A modification parameter (m) to :data:`MANUFACTURING_RESOLUTION`: to the nearest step, or
    the step below (a length that rounded up would leave the active flank)."""
    step = MANUFACTURING_RESOLUTION[unit] * _TO_SI[unit]
    n = math.floor(value / step) if down else round(value / step)
    return float(np.round(n * MANUFACTURING_RESOLUTION[unit], 6)) * _TO_SI[unit]


def optimum_pair(pair: GearPair, ds: xr.Dataset, name: str | None = None) -> GearPair:
    """``pair`` carrying the optimum modification of ga.nc (both gears, as applied) to the drawing's
    resolution (:data:`MANUFACTURING_RESOLUTION`), rounded to the nearest step, or down where the
    nearest breaks the pair's validity.

    Parameters
    ----------
    pair : GearPair
        The optimised pair.
    ds : xarray.Dataset
        Its ga.nc (:func:`result_dataset`): ``optimum_modification`` (gear, parameter), m.
    name : str, optional
        A new pair name (a pair file's name is its file name); None keeps the pair's.

    Returns
    -------
    GearPair
        ``pair`` with the optimum modification of both gears.

    Raises
    ------
    GearmeshInputError
        When even the rounded-down modification makes no valid pair.
    """
    p = ds["optimum_modification"].values
    units = [MODIFICATION_UNITS[f] for f in MODIFICATION_FIELDS]
    for down in (False, True):
        mods = tuple(Modification(**{f: _drawing_value(float(p[g, k]), units[k], down)
                                     for k, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
        out = pair.with_changes(modification=mods, **({"name": name} if name else {}))
        try:
            pair_geometry(out)  # validity (lengths, depths) by construction; checked here once more
            return out
        except GearmeshInputError:
            if down:
                raise
    return out


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def optimise_summary(pair: GearPair, **settings) -> tuple[dict[str, Any], xr.Dataset]:
    """Headline numbers of one optimisation (the CLI's ``optimise --json``) and its ga.nc Dataset.

    Parameters
    ----------
    pair : GearPair
        The pair to optimise.
    **settings
        ``impact``, ``tolerances`` and the ``optimise.NAME`` section, as :func:`run_settings` takes them.

    Returns
    -------
    summary : dict
        The optimum ``genes`` (by name, the genes' units µm / mm), ``objective_value`` and the
        standard's, ``impact_force_transverse_N`` of the optimum and the standard at the design
        torque, ``reduction_percent``, scenarios, ``by_torque`` (F_s in N, the standard's, the
        scenario and the spread under the tolerance samples at each spectrum torque),
        ``load_window_Nm``, ``evaluations``, ``wall_s`` (s) and ``notes``. Torques (N·m) on the
        gear ``on``, as given.
    ds : xarray.Dataset
        ga.nc (:func:`result_dataset`).
    """
    on = settings.get("on", defaults(Optimise)["on"])
    prob = run_problem(pair, **settings)
    res = optimise(prob)
    s, d = prob.settings, res.diagnostics
    opt, std = res.optimum_evaluation, prob.standard
    to_given = 1.0 if on == "pinion" else pair.teeth[1] / pair.teeth[0]
    k = s.design_index
    by_torque = []
    for i, t in enumerate(s.objective_torques):
        row = {"torque_Nm": t * to_given, "impact_force_transverse_N": float(opt.force[0, 0, i]),
               "standard_impact_force_transverse_N": float(std.force[0, 0, i]), "scenario": SCENARIOS[int(opt.scenario[0, 0, i])]}
        if prob.deviations.shape[0]:
            row.update({"impact_force_tolerance_min_transverse_N": float(d.spread_force[:, i].min()),
                        "impact_force_tolerance_max_transverse_N": float(d.spread_force[:, i].max()),
                        "standard_impact_force_tolerance_min_transverse_N": float(d.spread_standard[:, i].min())})
        if np.isfinite(opt.dynamic_factor[0, i]):
            row.update({"dynamic_factor": float(opt.dynamic_factor[0, i]),
                        "standard_dynamic_factor": float(std.dynamic_factor[0, i])})
        by_torque.append(row)
    low, high = d.load_window
    summary = {
        "name": pair.name,
        "method": s.method,
        "tooth_model": prob.model.ltca.method,
        "contact_law": prob.model.ltca.law.name,
        "objective": s.objective,
        "statistic": s.statistic,
        "tolerance_statistic": s.tolerance_statistic,
        "tolerance_samples": int(prob.deviations.shape[0]),
        "lead_grade": prob.tolerance.grade,
        "seed": s.seed,
        "torque_Nm": s.torque * to_given,
        "torques_Nm": [t * to_given for t in s.objective_torques],
        "torque_on": on,
        "speed_rpm": s.speed_rpm,
        "genes": {g.name: float(v) for g, v in zip(prob.genes, res.optimum_genes)},
        "objective_value": float(opt.objective[0]),
        "standard_objective_value": float(std.objective[0]),
        "impact_force_transverse_N": float(opt.force[0, 0, k]),
        "standard_impact_force_transverse_N": float(std.force[0, 0, k]),
        "reduction_percent": 100.0 * (1.0 - float(opt.force[0, 0, k]) / float(std.force[0, 0, k])),
        "scenario": SCENARIOS[int(opt.scenario[0, 0, k])],
        "standard_scenario": SCENARIOS[int(std.scenario[0, 0, k])],
        "by_torque": by_torque,
        "load_window_Nm": [_finite(low * to_given), _finite(high * to_given)],
        "load_window_grid_Nm": [float(d.window_torque[0] * to_given), float(d.window_torque[-1] * to_given)],
        "evaluations": res.evaluations,
        "wall_s": res.wall_s,
        "notes": optimum_notes(prob, d),
    }
    return summary, result_dataset(res, settings)


def optimum_notes(prob, diagnostics) -> list[str]:
    """What an optimum's numbers do not say by themselves: a single-point objective's risk,
    loaded-contact criteria judged on the nominal gear alone, and a load window that ends where
    its torque grid ends (its true bound lies beyond).

    Parameters
    ----------
    prob : Problem
        The run's problem (:func:`run_problem`).
    diagnostics : Diagnostics
        The finished run's diagnostics (its load window and window torque grid, pinion N·m).

    Returns
    -------
    list[str]
        One sentence per caveat that applies.
    """
    s, notes = prob.settings, []
    single_torque = len(s.objective_torques) == 1
    if s.objective in ("force", "velocity") or (single_torque and not prob.deviations.shape[0]):
        notes.append("single-point optimum: the objective saw one torque and the nominal geometry only; it can be a "
                     "grazing touch that is worse at other loads or under manufacturing deviations (check "
                     "load_window_Nm; the robust objective over --torques-Nm with --tolerance-samples guards "
                     "against it)")
    if s.needs_criteria and not (s.criteria_over_samples and s.tolerance_statistic is not None):
        notes.append("nominal criteria: the loaded-contact constraints and objectives (TE orders, pressure, root "
                     "stress, LTE, line load) were judged on the nominal gear only; a manufactured gear's lead and "
                     "modification deviations can break them (constraints.criteria_over_samples with a "
                     "tolerance_statistic judges every manufactured gear)")
    low, high = diagnostics.load_window
    grid = diagnostics.window_torque
    if math.isfinite(high) and high >= grid[-1]:
        notes.append(f"load window: its upper end {high:g} N m (pinion) is the end of the window's torque grid, not "
                     "where the optimum stops beating the standard gear; that lies beyond (the grid ends at 1.25 "
                     "times the largest spectrum torque, or below where the load limits stop it)")
    if math.isfinite(low) and low <= grid[0]:
        notes.append(f"load window: its lower end {low:g} N m (pinion) is the start of the window's torque grid")
    return notes
