"""The constraints: each candidate's loaded-contact criteria (of its nominal gear, or reduced over
its manufactured gears), their worst ratios to the standard gear's (or its tolerance box's worst),
the safety factors, and the penalised objective J with the NSGA-II objectives (:func:`_score`).

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..dynamics.population import dynamic_factors
from ..impact.criteria import LTCACriteria, ltca_criteria
from ..ltca import MESH_ORDERS
from ..robust import CRITERIA, BoxWorst
from ..stress import edge_pressure_reference
from ..tolerance import sample_statistic
from .checks import OptimiseSettings
from .evaluation import FAILURE_FACTOR, Evaluation, Problem

def _over_samples(s: "OptimiseSettings") -> bool:
    """Whether the loaded-contact criteria are taken over the manufactured samples."""
    return s.criteria_over_samples and s.tolerance_statistic is not None


def _design_lte_line(s: "OptimiseSettings", crit: LTCACriteria | None, nc: int) -> tuple[np.ndarray, np.ndarray]:
    """LTE peak-to-peak and largest line load at the design torque (NaN without criteria)."""
    if crit is None:
        return np.full(nc, np.nan), np.full(nc, np.nan)
    return crit.lte_peak_to_peak[:, s.design_index], crit.max_line_load[:, s.design_index]


def _with_sample_criteria(prob: "Problem", params: np.ndarray, rows: np.ndarray, lead: np.ndarray, raw: Evaluation,
                          standard: Evaluation) -> Evaluation:
    """``raw`` (criteria of the nominal gears) with the criteria over the manufactured samples for
    the candidates whose nominal gear meets every constraint (tolerance statistic max). The max over
    the samples is never below the nominal gear's (sample 0), so a candidate its nominal gear already
    refuses is refused: its violation, J and Pareto objectives stay the nominal gear's, lower bounds
    of its own, and its samples' contact is never solved (most candidates of a run)."""
    nc = params.shape[0]
    kv = np.array(raw.dynamic_factor, dtype=float)
    kv[:] = standard.dynamic_factor[0]  # the dynamic constraint is checked after, on its own
    pre = _score(prob, replace(raw, dynamic_factor=kv), standard)
    need = np.flatnonzero(~pre.failed & (pre.violation == 0))
    if not need.size:
        return raw
    ns = rows.shape[0] // nc
    take = (need[:, None] * ns + np.arange(ns)).reshape(-1)
    over = _criteria(prob, params[need], rows[take], lead[take])
    crit = raw.criteria
    merged = {}
    for name in ("lte_peak_to_peak", "te_harmonics", "max_line_load", "flank_pressure", "edge_pressure",
                 "root_stress"):
        a = np.array(getattr(crit, name), dtype=float, copy=True)
        a[need] = getattr(over, name)
        merged[name] = a
    crit = LTCACriteria(**merged, load=crit.load)
    lte, line = _design_lte_line(prob.settings, crit, nc)
    return replace(raw, criteria=crit, lte_peak_to_peak=lte, max_line_load=line)


def _with_dynamics(prob: "Problem", params: np.ndarray, raw: Evaluation, standard: Evaluation | None) -> Evaluation:
    """``raw`` with the dynamic factor of its nominal gears
    (:func:`gearmesh.dynamics.population.dynamic_factors`), computed for the candidates that meet every
    other constraint: the dynamic constraint cannot make another candidate feasible, so theirs is left
    at the standard's (no excess; their J a lower bound), which spares most candidates' dynamics."""
    nc = params.shape[0]
    need = np.ones(nc, dtype=bool)
    kv = np.array(raw.dynamic_factor, dtype=float)
    if standard is not None:
        kv[:] = standard.dynamic_factor[0]
        pre = _score(prob, replace(raw, dynamic_factor=kv), standard)
        need = ~pre.failed & (pre.violation == 0)
    if need.any():
        lead = np.broadcast_to(np.asarray(prob.model.lead_slope, float), (int(need.sum()), 2))
        kv[need] = dynamic_factors(prob.dynamics, params[need], lead)
    return replace(raw, dynamic_factor=kv)


def _score(prob: "Problem", raw: Evaluation, standard: Evaluation) -> Evaluation:
    """The candidates' measured ``raw`` evaluation (objective f, no penalty) scored against the
    ``standard``'s: the constraints' violation, J = f + penalty·f_std·violation, the NSGA-II
    objectives (:mod:`gearmesh.optimise`)."""
    s, crit, f = prob.settings, raw.criteria, raw.objective
    lte, line, kv, nc = raw.lte_peak_to_peak, raw.max_line_load, raw.dynamic_factor, raw.objective.shape[0]
    ratios = _ratios(s, raw.worst_force, lte, line, kv, crit, standard)
    if s.S_Hmin is not None or s.S_Fmin is not None:
        sh, sf = safety_factors(prob, crit, standard.criteria)
        ratios.update(S_H=worst_ratio(np.divide(s.S_Hmin or 0.0, sh), 1.0),
                      S_F=worst_ratio(np.divide(s.S_Fmin or 0.0, sf), 1.0))
    violation = np.zeros(nc)
    for name, factor in constraint_factors(s).items():
        with np.errstate(invalid="ignore"):
            violation += np.maximum(0.0, ratios[name] / factor - 1.0)
    failed = raw.failed | ~np.isfinite(violation)
    j = f + s.penalty * standard.objective[0] * violation
    j = np.where(failed, FAILURE_FACTOR * standard.objective[0], j)
    pareto = None
    if s.method == "nsga2":
        lte = np.where(failed, FAILURE_FACTOR * standard.lte_peak_to_peak[0], lte)
        pareto = np.column_stack([j if k == "impact" else lte if k == "lte" else
                                  np.where(failed, FAILURE_FACTOR, ratios[k]) for k in s.pareto_objectives])
    return Evaluation(j, raw.value, raw.force, raw.velocity, raw.scenario, failed, lte, line, kv,
                      np.where(failed, np.nan, violation), crit, pareto, raw.worst_force)


def _criteria(prob: "Problem", params: np.ndarray, rows: np.ndarray, lead: np.ndarray,
              over_samples: bool = True) -> LTCACriteria:
    """The candidates' loaded-contact criteria (C, T, ...): of the nominal gears, or with
    ``criteria_over_samples`` (and a tolerance statistic, and ``over_samples``) of every manufactured
    gear ``rows``, ``lead`` ((C·S, ...), sample 0 the nominal, as :func:`_manufactured_rows`), each
    quantity reduced over the S gears by the tolerance statistic; the point loads stay the nominal
    gear's (S_Hmin, S_Fmin are nominal)."""
    s, model = prob.settings, prob.model
    if not (over_samples and _over_samples(s)):
        return ltca_criteria(model, s.objective_torques, params, stresses=s.needs_stresses)
    nc = params.shape[0]
    ns = rows.shape[0] // nc
    c = ltca_criteria(model, s.objective_torques, rows, lead_slope=lead, stresses=s.needs_stresses, samples=ns)

    def over_samples(a: np.ndarray) -> np.ndarray:
        a = np.asarray(a).reshape(nc, ns, *a.shape[1:])
        return sample_statistic(np.moveaxis(a, 1, -1), s.tolerance_statistic, s.tolerance_level)

    return LTCACriteria(lte_peak_to_peak=over_samples(c.lte_peak_to_peak), te_harmonics=over_samples(c.te_harmonics),
                        max_line_load=over_samples(c.max_line_load), flank_pressure=over_samples(c.flank_pressure),
                        edge_pressure=over_samples(c.edge_pressure), root_stress=over_samples(c.root_stress),
                        load=c.load.reshape(nc, ns, *c.load.shape[1:])[:, 0])


def worst_ratio(values: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """The largest ratio of ``values`` to the unmodified pair's ``reference`` over every axis but the first.

    1 or less exactly when no entry exceeds the reference. A zero reference counts a zero value as ratio 0 and a positive
    one as infinite.

    Parameters
    ----------
    values : numpy.ndarray
        (C, ...) candidates' values (any unit), the further axes torques, orders, ...
    reference : numpy.ndarray
        (...) the unmodified pair's values (the same unit).

    Returns
    -------
    numpy.ndarray
        (C,) worst ratios (-).
    """
    v = np.asarray(values, dtype=float)
    ref = np.broadcast_to(np.asarray(reference, dtype=float), v.shape[1:])
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(ref > 0, v / np.where(ref > 0, ref, 1.0), np.where(v > 0, np.inf, 0.0))
    return r.reshape(v.shape[0], -1).max(axis=1)


def _ratios(s: OptimiseSettings, force: np.ndarray, lte, line, kv, crit: LTCACriteria | None,
            standard: Evaluation) -> dict[str, np.ndarray]:
    """Each criterion's worst ratio (C,) to the standard gear's (:func:`worst_ratio`), per torque
    of the spectrum unless said: F_s of the worst manufactured gear per torque ('force'; the nominal
    without a tolerance statistic) and its worst case over the torques ('worst_force'), LTE p-p and the largest line load at the design torque, the dynamic
    factor, and from the loaded contact the TE harmonics of ``harmonic_orders`` ('te_harmonics'), the
    flank pressure against the standard's flank pressure and the tip-edge pressure against its
    tip-edge pressure (its flank pressure where it has no edge contact) ('pressure'), and the
    root stress of either gear ('root_stress')."""
    nc = force.shape[0]
    nan = np.full(nc, np.nan)
    ref = standard.criteria
    out = {"force": worst_ratio(force, standard.worst_force[0]),
           "worst_force": worst_ratio(force.max(axis=1), standard.worst_force[0].max()),
           "lte": worst_ratio(lte[:, None], standard.lte_peak_to_peak[0]),
           "line_load": worst_ratio(line[:, None], standard.max_line_load[0]),
           "dynamic": worst_ratio(kv, standard.dynamic_factor[0])}
    if crit is None or ref is None:
        return {**out, "te_harmonics": nan, "pressure": nan, "root_stress": nan}
    k = [MESH_ORDERS.index(o) for o in s.harmonic_orders]
    out["te_harmonics"] = worst_ratio(crit.te_harmonics[..., k], ref.te_harmonics[0][..., k])
    edge_ref = edge_pressure_reference(ref.flank_pressure[0], ref.edge_pressure[0])
    out["pressure"] = np.maximum(worst_ratio(crit.flank_pressure, ref.flank_pressure[0]),
                                 worst_ratio(crit.edge_pressure, edge_ref))
    out["root_stress"] = worst_ratio(crit.root_stress, ref.root_stress[0])
    return out


def safety_factors(prob: "Problem", crit: LTCACriteria, reference: LTCACriteria) -> tuple[np.ndarray, np.ndarray]:
    """S_H and S_F (C, T) of the weaker gear of each candidate at the spectrum torques.

    ISO 6336-2/-3 method B (:func:`gearmesh.rating.rating`, the pair's rating inputs, application factor 1) at the
    objective speed, with K_Hβ and K_Hα from the candidate's LTCA loads and the unmodified pair's
    (:func:`gearmesh.rating.ltca_load_factors`, K_Hα at least 1, as the rating stage).

    Parameters
    ----------
    prob : Problem
        The optimisation problem (:func:`problem`): pair, settings and spectrum torques.
    crit : LTCACriteria
        The candidates' loaded contact (:func:`gearmesh.impact.ltca_criteria`), (C, T) rows.
    reference : LTCACriteria
        The unmodified pair's.

    Returns
    -------
    S_H, S_F : numpy.ndarray
        (C, T) contact and bending safety factors (-).

    References
    ----------
    .. [1] ISO 6336-2:2019, Calculation of load capacity of spur and helical gears — Part 2: Calculation of surface
       durability (pitting), method B.
    .. [2] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation of tooth bending
       strength, method B.
    """
    from ..rating import ltca_load_factors, rated_transverse_factor, rating, rating_inputs

    s, geom = prob.settings, prob.geom
    inputs = rating_inputs(dict(geom.pair.rating_inputs))
    nc, nt = crit.load.shape[:2]
    ref = np.broadcast_to(reference.load[0][None], crit.load.shape).reshape(nc * nt, *crit.load.shape[2:])
    lf = ltca_load_factors(crit.load.reshape(nc * nt, *crit.load.shape[2:]), ref)
    sh, sf = np.empty(nc * nt), np.empty(nc * nt)
    for k in range(nc * nt):
        r = rating(geom, s.objective_torques[k % nt], s.speed_rpm, inputs, method="ltca",
                   ltca_factors={"K_Hbeta": float(lf["K_Hbeta"][k]), "K_Halpha": float(rated_transverse_factor(lf["K_Halpha"][k]))})
        sh[k], sf[k] = min(r.values["S_H"]), min(r.values["S_F"])
    return sh.reshape(nc, nt), sf.reshape(nc, nt)


def constraint_factors(s: OptimiseSettings) -> dict[str, float]:
    """The constraints set, {criterion of :func:`_ratios` (S_H, S_F: S_min/S): factor (1 for S_min)}.

    Parameters
    ----------
    s : OptimiseSettings
        The run settings (:func:`gearmesh.optimise.checks.resolve_settings`).

    Returns
    -------
    dict of str to float
        Factor (-) of every constraint that is set.
    """
    given = {"lte": s.lte_factor, "line_load": s.line_load_factor, "dynamic": s.dynamic_factor,
             "te_harmonics": s.harmonic_factor, "pressure": s.pressure_factor,
             "root_stress": s.root_stress_factor, "force": s.impact_factor, "worst_force": s.worst_impact_factor,
             "S_H": None if s.S_Hmin is None else 1.0, "S_F": None if s.S_Fmin is None else 1.0}
    return {k: v for k, v in given.items() if v is not None}



def _with_reference(standard: Evaluation, reference: BoxWorst | None) -> Evaluation:
    """The standard gear's evaluation with its criteria and F_s those of its worst manufactured gear
    over the tolerance box (``reference``, :func:`gearmesh.robust.design_box_worst`, columns
    :data:`gearmesh.robust.CRITERIA` per objective torque; never below its evaluated samples'): the
    reference every candidate's ratios are taken to, as the sign-off table's."""
    if reference is None or standard.criteria is None:
        return standard if reference is None else replace(standard, worst_force=np.maximum(
            standard.worst_force, reference.values[None, :, CRITERIA.index("impact_force")]))
    w = reference.values  # (T, K)
    c = standard.criteria
    orders = [CRITERIA.index(f"lte_order_{k}") for k in MESH_ORDERS]
    crit = replace(c, te_harmonics=np.maximum(c.te_harmonics, w[None][..., orders]),
                   flank_pressure=np.maximum(c.flank_pressure, w[None, :, CRITERIA.index("peak_flank_pressure")]),
                   edge_pressure=np.maximum(c.edge_pressure, w[None, :, CRITERIA.index("peak_edge_pressure")]),
                   root_stress=np.maximum(c.root_stress, w[None, :, CRITERIA.index("peak_root_stress")]))
    return replace(standard, criteria=crit, worst_force=np.maximum(
        standard.worst_force, w[None, :, CRITERIA.index("impact_force")]))
