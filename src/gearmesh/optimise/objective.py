"""The objective of candidates: the problem set up with the standard (unmodified) gear evaluated
once (:func:`problem`), every candidate × torque × manufactured gear in one batch of the impact model
(:func:`evaluate`), and the diagnostics of an optimum (:func:`diagnose`: load window, tolerance
spread, scenario per torque).

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import GearmeshInputError
from ..dynamics.population import POPULATION_CONTACT, population_dynamics
from ..impact.energy import load_grid, load_window
from ..impact.model import SCENARIO_NONE, ImpactModel
from ..robust import box_scenarios, design_box_worst
from ..tolerance import ToleranceModel, manufactured_population, sample_statistic, unit_deviations
from .checks import OptimiseSettings
from .constraints import _criteria, _design_lte_line, _over_samples, _score, _with_dynamics, _with_reference, \
    _with_sample_criteria
from .evaluation import OBJECTIVE_VALUES, Evaluation, Problem, impact_values, load_statistic
from .genes import gene_table

def _evaluate(prob: "Problem", params: np.ndarray, standard: Evaluation | None) -> Evaluation:
    """:func:`evaluate`, against the ``standard`` evaluation (None: evaluating the standard itself)."""
    s, model = prob.settings, prob.model
    deviations = prob.population_deviations
    nc = params.shape[0]
    ns = deviations.shape[0] + 1
    rows, lead = _manufactured_rows(model, prob.tolerance, params, deviations)
    iv = impact_values(model, s, rows, lead, s.objective_torques)
    value = OBJECTIVE_VALUES[s.objective](prob, rows, lead, iv)
    shape = (nc, ns, len(s.objective_torques))
    value, force, vel, scen = (a.reshape(shape) for a in (value, iv.force, iv.velocity, iv.scenario))
    per_gear = load_statistic(value, s.statistic, s.weights)  # (C, S): each manufactured gear over the spectrum
    f = per_gear[:, 0] if s.tolerance_statistic is None else sample_statistic(per_gear, s.tolerance_statistic,
                                                                              s.tolerance_level)
    # with the max over the samples, a candidate its nominal gear refuses is refused: its samples' contact is spared
    screened = standard is not None and _over_samples(s) and s.tolerance_statistic == "max"
    crit = _criteria(prob, params, rows, lead, over_samples=not screened) if s.needs_criteria else None
    lte, line = _design_lte_line(s, crit, nc)
    # failed: no impact found, a non-finite value, or a touch without a closing velocity (a
    # crossing the impact model did not resolve: zero force would be an artefact, not an optimum)
    failed = (~np.isfinite(f) | np.any(scen == SCENARIO_NONE, axis=(1, 2)) | ~np.all(np.isfinite(value), axis=(1, 2))
              | np.any(~(vel > 0), axis=(1, 2)))
    kv = np.full((nc, len(s.objective_torques)), np.nan)
    if s.objective == "dynamic":  # the nominal gear is sample 0 of the objective's rows
        kv = value[:, 0]
    raw = Evaluation(f, value, force, vel, scen, failed, lte, line, kv, np.zeros(nc), crit,
                     worst_force=force.max(axis=1))
    if screened and crit is not None:
        raw = _with_sample_criteria(prob, params, rows, lead, raw, standard)
    if s.dynamic_factor is not None and s.objective != "dynamic":
        raw = _with_dynamics(prob, params, raw, standard)
    return raw if standard is None else _score(prob, raw, standard)



def _manufactured_rows(model: ImpactModel, tolerance: ToleranceModel, params: np.ndarray, deviations: np.ndarray):
    """Rows (C·S, 2, 6) and lead slopes (C·S, 2) of the manufactured population of each candidate
    (sample 0 the nominal): :func:`gearmesh.tolerance.manufactured_population` on the model."""
    return manufactured_population(model.geom, tolerance, params, model.lead_slope, deviations)


def problem(model: ImpactModel, settings: OptimiseSettings, modify=("pinion",), bounds=None,
            fixed=None, tolerance: ToleranceModel | None = None) -> Problem:
    """Set up the optimisation of ``model``'s pair.

    Genes, the manufactured population's unit deviations (``settings.tolerance_samples`` of ``tolerance``, seeded by the
    settings' seed), and the standard (unmodified) gear evaluated once, with the same population.

    Parameters
    ----------
    model : ImpactModel
        The prepared impact model (:func:`gearmesh.impact.impact_model`).
    settings : OptimiseSettings
        The run settings (:func:`gearmesh.optimise.checks.resolve_settings`).
    modify, bounds, fixed
        The gears optimised and the gene bounds and fixed values (:func:`gene_table`).
    tolerance : ToleranceModel or None
        The tolerance model of the manufactured population (:mod:`gearmesh.tolerance`).

    Returns
    -------
    Problem
        Genes, base parameters, population and the standard gear's evaluation.
    """
    genes, base = gene_table(model.geom, modify, bounds, fixed)
    tolerance = tolerance or ToleranceModel(np.zeros((2, 6)), np.zeros(2))
    robust = settings.tolerance_statistic is not None and bool(tolerance.dimensions)
    reference = None
    if robust and (settings.criteria_over_samples or settings.sampling == "box"):
        reference = design_box_worst(model, tolerance, np.zeros((2, 6)), settings.objective_torques,
                                     settings.speed_rpm, settings.energy_velocity)[0]
    if settings.sampling == "box" and reference is not None:
        deviations = box_scenarios(tolerance, reference)
    else:
        deviations = unit_deviations(len(tolerance.dimensions), settings.tolerance_samples,
                                     "lhs" if settings.sampling == "box" else settings.sampling,
                                     settings.tolerance_seed)
    if settings.tolerance_statistic is not None and deviations.shape[0] == 0:
        raise GearmeshInputError("tolerances", None, "define no deviation (no lead grade, no modification "
                                                     "tolerance): the tolerance statistic has nothing to sample")
    dynamics = population_dynamics(model.geom, settings.objective_torques, settings.dynamic_speed_grid,
                                   backlash=settings.backlash, tables=model.ltca.tables,
                                   contact=POPULATION_CONTACT.with_(contact_law=model.ltca.law.name,
                                                                    method=model.ltca.method),
                                   misalignment_torque=settings.torque) if settings.uses_dynamics else None
    prob = Problem(model, genes, base, settings, tolerance, deviations, None, dynamics, reference)
    standard = _with_reference(_evaluate(prob, np.zeros((1, 2, 6)), None), reference)
    if not np.all(np.isfinite(standard.objective)) or np.any(standard.scenario == SCENARIO_NONE):
        raise GearmeshInputError("torques_Nm" if len(settings.objective_torques) > 1 else "torque_Nm",
                                 list(settings.objective_torques),
                                 "gives the standard (unmodified) gear no mesh-in impact: nothing to reduce")
    return replace(prob, standard=standard)



def standard_penalised_objective(prob: Problem) -> float:
    """The unmodified pair as a candidate of the run: its J with the constraints' penalties.

    Scored from its evaluation in :func:`problem` (no second impact batch).

    Parameters
    ----------
    prob : Problem
        The problem (:func:`problem`).

    Returns
    -------
    float
        J (N, or m/s for the 'velocity' objective), penalties included.
    """
    return float(_score(prob, prob.standard, prob.standard).objective[0])


def evaluate(prob: Problem, params: np.ndarray) -> Evaluation:
    """The objective of candidates ``params`` (C, 2, 6) m.

    Every candidate × torque × manufactured sample in one batch of the impact model (:mod:`gearmesh.optimise`).

    Parameters
    ----------
    prob : Problem
        The problem (:func:`problem`).
    params : numpy.ndarray
        (C, 2, 6) modification parameters (m).

    Returns
    -------
    Evaluation
        ``objective`` J (C,) (N, or m/s for 'velocity', penalties included) and per (C, S, T) the quantities behind it.
    """
    return _evaluate(prob, params, prob.standard)


# --------------------------------------------------------------------------------------
# Diagnostics of an optimum: load window, tolerance spread, scenario per torque
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Diagnostics:
    """An optimum against the standard gear (SI): ``window_torque`` (W,) the load-window grid
    (pinion, N m), ``window_force`` / ``window_standard`` (W,) their nominal F_s there,
    ``window_scenario`` / ``window_standard_scenario`` (W,), ``load_window`` (low, high) N m;
    ``spread_force`` / ``spread_standard`` (S, T) F_s of every manufactured sample (0 the nominal)
    at the objective torques, ``spread_scenario`` (S, T)."""

    window_torque: np.ndarray
    window_force: np.ndarray
    window_standard: np.ndarray
    window_scenario: np.ndarray
    window_standard_scenario: np.ndarray
    load_window: tuple[float, float]
    spread_force: np.ndarray
    spread_standard: np.ndarray
    spread_scenario: np.ndarray
    spread_standard_scenario: np.ndarray


def diagnose(prob: Problem, params: np.ndarray) -> Diagnostics:
    """Load window, tolerance spread and scenarios of the micro-geometry ``params`` against the standard gear.

    Two batches of the impact model (:mod:`gearmesh.optimise`).

    Parameters
    ----------
    prob : Problem
        The problem (:func:`problem`).
    params : numpy.ndarray
        (2, 6) modification parameters (m).

    Returns
    -------
    Diagnostics
        ``load_window`` (low, high) N m, the window's F_s against the standard's (N), the spread of F_s over the
        manufactured samples (N) and the scenarios.
    """
    s, model = prob.settings, prob.model
    both = np.stack([np.asarray(params, dtype=float), np.zeros((2, 6))])
    grid = load_grid(s.objective_torques, s.load_window_step, s.load_window_top)
    lead = np.broadcast_to(np.asarray(model.lead_slope, dtype=float), (2, 2))
    w = impact_values(model, s, both, lead, grid)
    rows, rows_lead = _manufactured_rows(model, prob.tolerance, both, prob.deviations)
    sp = impact_values(model, s, rows, rows_lead, s.objective_torques)
    shape = (2, prob.deviations.shape[0] + 1, len(s.objective_torques))
    force, scen = sp.force.reshape(shape), sp.scenario.reshape(shape)
    return Diagnostics(window_torque=grid, window_force=w.force[0], window_standard=w.force[1],
                       window_scenario=w.scenario[0], window_standard_scenario=w.scenario[1],
                       load_window=load_window(grid, w.force[0], w.force[1], s.torque),
                       spread_force=force[0], spread_standard=force[1], spread_scenario=scen[0],
                       spread_standard_scenario=scen[1])
