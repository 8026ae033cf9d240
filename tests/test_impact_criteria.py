"""What an engineer signs off, in the optimiser (issue 27): the loaded contact's criteria of every
candidate (TE mesh orders, contact pressure flank and edge, root stress) checked against
independent computations, the constraints' penalty zero exactly when a criterion holds, NSGA-II's
front over three objectives non-dominated, and bad settings refused with the field named.

test_optimise's coarse impact model (16 points per line) keeps the runs small."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings as hsettings, strategies as st

from gearmesh import impact as im
from gearmesh.impact.criteria import _tangent_start
from gearmesh import optimise as op
from gearmesh.optimise.constraints import _ratios, _score
from gearmesh.optimise.objective import _evaluate, _manufactured_rows
from gearmesh.optimise.search import _verified
from gearmesh.datasets.optimise import result_dataset, run_settings
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.io import check_documented
from gearmesh.ltca import MESH_ORDERS, lte_harmonics, ltca
from gearmesh.ltca_model import ltca_model
from gearmesh.plots.optimise import plot_pareto
from gearmesh.stress import contact_stress, iso_root_stress_slices

from test_optimise import (COARSE, ROBUST_TOLERANCES, ROOT, model, pair,  # noqa: F401 (the coarse impact model and
                           problem_of, run_settings_of)  # its pair, as fixtures; settings through the declaration)

TORQUES = (400.0, 1000.0, 1600.0)
CANDIDATE = [40, 40, 2, 2, 20, 10]  # µm / mm: reliefs, lengths, crowning, unmodified lead


def _problem(model, **section):
    section = {"population": 8, "generations": 3, "objective": "robust", "torque_Nm": 1000.0,
               "torques_Nm": list(TORQUES), **section}
    return op.problem(model, run_settings_of(model, **section)[0])


def test_lte_harmonics_recover_the_amplitudes_of_a_sampled_cycle():
    p = 32
    x = 2 * np.pi * np.arange(p) / p
    amp = np.array([0.7, 0.05, 0.3])
    lte = 5.0 + sum(a * np.cos(k * x + 0.3 * k) for k, a in zip(MESH_ORDERS, amp)) + 0.1 * np.cos(7 * x)
    np.testing.assert_allclose(lte_harmonics(lte), amp, rtol=1e-12)
    with pytest.raises(ValueError):
        lte_harmonics(lte[:6])


def _least_squares_amplitude(y, order):
    """Amplitude of mesh order ``order`` by a least-squares fit of a mean, cos and sin (no FFT)."""
    x = 2 * np.pi * np.arange(y.size) / y.size
    a = np.column_stack([np.ones_like(x), np.cos(order * x), np.sin(order * x)])
    c = np.linalg.lstsq(a, y, rcond=None)[0]
    return math.hypot(c[1], c[2])


def test_criteria_of_a_candidate_agree_with_the_ltca_and_the_stress_functions(pair, model):
    """The optimiser's re-evaluated gaps against a full LTCA of the modified pair on the same grid,
    and its harmonics against a least-squares fit of the stored LTE."""
    geom = pair_geometry(pair)
    prob = _problem(model)
    params = prob.decode([CANDIDATE])
    crit = im.ltca_criteria(model, TORQUES, params)
    from gearmesh.gear import Modification
    from gearmesh.surface import MODIFICATION_FIELDS

    mods = tuple(Modification(**{f: float(params[0, g, k]) for k, f in enumerate(MODIFICATION_FIELDS)})
                 for g in range(2))
    mod_geom = pair_geometry(pair.with_changes(modification=mods))
    lt = model.ltca
    contact = COARSE["contact"].with_(contact_law=lt.law.name, method=lt.method,
                                      extension=lt.grid.extension / geom.transverse_base_pitch)
    full = ltca(mod_geom, list(TORQUES), model=ltca_model(mod_geom, lt.grid.roll.size - 1, contact, lt.lead_slope,
                                                           tables=lt.tables))
    np.testing.assert_allclose(crit.lte_peak_to_peak[0], np.ptp(full.lte, axis=1), rtol=1e-6)
    for t in range(len(TORQUES)):
        for k, order in enumerate(MESH_ORDERS):
            assert crit.te_harmonics[0, t, k] == pytest.approx(_least_squares_amplitude(full.lte[t], order),
                                                               rel=1e-6, abs=1e-13)
    g = full.grid
    c = contact_stress(mod_geom, full.line_load, g.region, g.rho_pinion, g.rho_gear)
    flank = np.where(c.edge, 0.0, c.pressure).max(axis=(1, 2, 3))
    edge = np.where(c.edge, c.pressure, 0.0).max(axis=(1, 2, 3))
    np.testing.assert_allclose(crit.flank_pressure[0], flank, rtol=1e-6)
    np.testing.assert_allclose(crit.edge_pressure[0], edge, rtol=1e-6, atol=1.0)
    np.testing.assert_allclose(crit.peak_pressure[0], c.peak(), rtol=1e-6)
    root = np.maximum(iso_root_stress_slices(mod_geom, 0, full.line_load, g.rho_pinion).max(axis=(1, 2, 3)),
                      iso_root_stress_slices(mod_geom, 1, full.line_load, g.rho_gear).max(axis=(1, 2, 3)))
    np.testing.assert_allclose(crit.root_stress[0], root, rtol=1e-6)
    # ltca_metrics is the same solve without the stresses
    lte, line = im.ltca_metrics(model, TORQUES, params)
    np.testing.assert_array_equal(lte, crit.lte_peak_to_peak)
    np.testing.assert_array_equal(line, crit.max_line_load)


@hsettings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 10.0), min_size=6, max_size=6), st.lists(st.floats(0.01, 10.0), min_size=3, max_size=3))
def test_worst_ratio_is_at_most_one_exactly_when_no_value_exceeds_its_reference(values, refs):
    v = np.array(values).reshape(2, 3)
    r = np.array(refs)
    ratio = op.worst_ratio(v, r)
    assert np.array_equal(ratio <= 1.0, np.all(v <= r, axis=1))
    np.testing.assert_allclose(ratio, np.max(v / r, axis=1))


@pytest.mark.parametrize("name,factor", [("pressure", "pressure_factor"), ("root_stress", "root_stress_factor"),
                                         ("te_harmonics", "harmonic_factor"), ("force", "impact_factor"),
                                         ("worst_force", "worst_impact_factor")])
def test_penalty_is_zero_exactly_when_the_criterion_holds(model, name, factor):
    free = _problem(model)
    params = free.decode([CANDIDATE])
    ev = _evaluate(_problem(model, constraints={"pressure_factor": 1e6}), params, None)  # the criteria, no penalty yet
    std = _problem(model, constraints={"pressure_factor": 1e6}).standard
    ratio = float(_ratios(free.settings, ev.force[:, 0], ev.lte_peak_to_peak, ev.max_line_load,
                             ev.dynamic_factor, ev.criteria, std)[name][0])
    assert math.isfinite(ratio) and ratio > 0
    loose = _problem(model, constraints={factor: ratio * (1 + 1e-9)})
    tight = _problem(model, constraints={factor: ratio * (1 - 1e-3)})
    ev_loose, ev_tight = op.evaluate(loose, params), op.evaluate(tight, params)
    assert ev_loose.violation[0] == 0.0
    assert ev_tight.violation[0] == pytest.approx(1 / (1 - 1e-3) - 1, rel=1e-6)
    assert ev_tight.objective[0] > ev_loose.objective[0] == pytest.approx(float(ev_loose.value[0, 0].max()))


@pytest.mark.parametrize("key,which", [("S_Hmin", 0), ("S_Fmin", 1)])
def test_safety_factor_penalty_is_zero_exactly_when_the_minimum_holds(model, key, which):
    """S_H, S_F of ISO 6336-2/-3 method B with the LTCA's load factors: the penalty vanishes at
    S = S_min and grows as S_min/S − 1 beyond; the crowned candidate's K_Hβ lowers its S below the
    unmodified pair's (whose own K_Hα is 1 by definition)."""
    probe = _problem(model, constraints={"pressure_factor": 1e6})
    params = probe.decode([CANDIDATE])
    crit = _evaluate(probe, params, None).criteria
    s = op.safety_factors(probe, crit, probe.standard.criteria)[which]
    s_std = op.safety_factors(probe, probe.standard.criteria, probe.standard.criteria)[which]
    assert s.shape == (1, 3) and np.all(s < s_std) and np.all(np.diff(s_std[0]) < 0)  # more torque, less safety
    worst = float(s.min())
    assert op.evaluate(_problem(model, constraints={key: worst * (1 - 1e-9)}), params).violation[0] == 0.0
    assert op.evaluate(_problem(model, constraints={key: worst * 1.01}), params).violation[0] == pytest.approx(0.01, rel=1e-6)


def test_the_standard_gear_meets_every_relative_criterion_at_factor_one(model):
    prob = _problem(model, constraints={"pressure_factor": 1.0, "root_stress_factor": 1.0, "harmonic_factor": 1.0,
                                        "impact_factor": 1.0, "worst_impact_factor": 1.0})
    ev = op.evaluate(prob, np.zeros((1, 2, 6)))
    assert ev.violation[0] == 0.0


def test_nsga2_front_over_three_objectives_is_non_dominated_and_drawn(model, tmp_path):
    prob = _problem(model, method="nsga2", pareto_objectives=("impact", "te_harmonics", "root_stress"),
                    population=10, generations=3, seed=1, constraints={"root_stress_factor": 1.1})
    res = op.optimise(prob)
    genes, pts = res.pareto
    assert pts.shape[1] == 3 and op.pareto_mask(pts).all()
    # every evaluated candidate is dominated by (or equal to) a front member
    h = res.history.arrays()
    allp = h["pareto"].reshape(-1, 3)
    ok = ~h["failed"].reshape(-1) & np.all(np.isfinite(allp), axis=1)
    for row in allp[ok]:
        assert np.any(np.all(pts <= row, axis=1))
    np.testing.assert_array_equal(res.optimum_genes, genes[0])  # the chosen design: the front's least J
    ds = result_dataset(res)
    ds.attrs["pair_name"] = "helical_z29_71_m5"
    check_documented(ds)
    assert {"pareto_te_harmonics_ratio", "pareto_root_stress_ratio", "optimum_lte_harmonics",
            "standard_root_stress", "violation", "standard_penalised_objective"} <= set(ds.data_vars)
    # a candidate meets the constraint exactly when its root-stress ratio is within the factor
    v, r = ds["violation"].values, ds["root_stress_ratio"].values
    done = np.isfinite(v)
    assert np.array_equal(v[done] == 0, r[done] <= 1.1)
    assert plot_pareto(ds, tmp_path / "pareto.png").stat().st_size > 1000


@pytest.mark.parametrize("settings,field", [
    ({"pareto_objectives": ("impact", "noise")}, "pareto_objectives[1]"),
    ({"pareto_objectives": ("lte", "impact")}, "pareto_objectives"),
    ({"pareto_objectives": ("impact",)}, "pareto_objectives"),
    ({"method": "ga", "pareto_objectives": ("impact", "pressure")}, "pareto_objectives"),
    ({"constraints": {"pressure_factor": -1.0}}, "constraints.pressure_factor"),
    ({"constraints": {"root_stress_factor": 0.0}}, "constraints.root_stress_factor"),
    ({"constraints": {"harmonic_factor": float("nan")}}, "constraints.harmonic_factor"),
    ({"constraints": {"worst_impact_factor": "half"}}, "constraints.worst_impact_factor"),
    ({"constraints": {"harmonic_orders": (4,)}}, "constraints.harmonic_orders[0]"),
    ({"constraints": {"harmonic_orders": (1, 1)}}, "constraints.harmonic_orders"),
    ({"constraints": {"S_Hmin": 0.0}}, "constraints.S_Hmin"),
    ({"constraints": {"S_Fmin": 11.0}}, "constraints.S_Fmin"),
    ({"constraints": {"S_Fmin": "1.4"}}, "constraints.S_Fmin"),
])
def test_bad_criteria_settings_are_refused_naming_the_field(model, settings, field):
    with pytest.raises(GearmeshInputError) as exc:
        run_settings_of(model, **{"method": "nsga2", **settings})
    assert exc.value.field == field


@pytest.mark.parametrize("section,field", [
    ({"constraints": {"noise_factor": 1.0}}, "constraints.noise_factor"),
    ({"constraints": {"pressure_factor": -0.5}}, "pressure_factor"),
    ({"constraints": {"S_Hmin": 50}}, "S_Hmin"),
    ({"method": "nsga2", "pareto_objectives": ["impact", "flash_temperature"]}, "pareto_objectives"),
])
def test_bad_criteria_in_a_study_section_are_refused(pair, section, field):
    with pytest.raises(GearmeshInputError) as exc:
        run_settings(pair, torque_Nm=1000, **section)
    assert field in exc.value.field


def test_every_door_defaults_to_the_robust_objective_over_the_tolerance_samples(pair):
    """Issue 27 item 4: the study schema, the Python API and ``gearmesh optimise`` give one default:
    the robust objective, the worst case over the nominal and the tolerance samples."""
    import argparse

    from gearmesh.cli import CLI_LEAD_GRADE, build_parser
    from gearmesh.schema import defaults
    from gearmesh.settings import Optimise, Tolerances

    declared = defaults(Optimise)
    assert declared["objective"] == "robust" and declared["tolerance_statistic"] == "max"
    api = run_settings(pair, tolerances={"grade": 6})[1]  # the Python API's run, its section left to the defaults
    assert api.objective == declared["objective"]
    assert api.tolerance_statistic == declared["tolerance_statistic"]
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)).choices["optimise"]
    cli = {a.dest: a.default for a in sub._actions}
    assert cli["objective"] == declared["objective"]
    assert cli["tolerance_statistic"] == declared["tolerance_statistic"]
    assert cli["samples"] == defaults(Tolerances)["samples"] > 0
    assert cli["grade"] == CLI_LEAD_GRADE  # a population to be robust over without a tolerances section
    assert "OUT.yaml" in sub.format_usage()  # --write-pair OUT.yaml, the name its help gives


def _straightforward_criteria(model, torques, params, lead) -> dict[str, np.ndarray]:
    """One manufactured gear's criteria (T, ...) the straightforward way, as main's ltca_criteria
    computed them: gaps from the separation basis, the exact solve (ltca_solve.solve_contact, cold) on
    every grid point, the stresses by contact_stress and iso_root_stress_slices of the loads."""
    from gearmesh.deflection import mesh_misalignment
    from gearmesh.ltca_solve import solve_contact
    from gearmesh.stress import pair_edge_radius
    from gearmesh.separation import SeparationBasis, basis_gap

    g, lt = model.geom, model.ltca
    grid = lt.grid
    p = grid.gap.shape[0] - 1
    basis = SeparationBasis(*(getattr(grid.basis, f)[:p] for f in SeparationBasis.__dataclass_fields__))
    out = {k: [] for k in ("lte_peak_to_peak", "te_harmonics", "flank_pressure", "edge_pressure", "root_stress",
                           "max_line_load")}
    for t in torques:
        force = t / g.base_radius[0]  # each torque at its mesh misalignment (the shafts' f_sh at its force)
        gap = basis_gap(g, basis, np.broadcast_to(grid.z, basis.base.shape), lead, params,
                        misalignment=mesh_misalignment(g, force)).reshape(p, -1)
        q, delta, _, _ = solve_contact(gap, lt.compliance[:p].reshape(p, -1), np.full(p, force), lt.law)
        w = q.reshape(basis.base.shape) / grid.dz
        c = contact_stress(g, w, grid.region[:p], grid.rho_pinion[:p], grid.rho_gear[:p], pair_edge_radius(g))
        out["lte_peak_to_peak"].append(np.ptp(delta))
        out["te_harmonics"].append(lte_harmonics(delta))
        out["flank_pressure"].append(np.where(c.edge, 0.0, c.pressure).max())
        out["edge_pressure"].append(np.where(c.edge, c.pressure, 0.0).max())
        out["root_stress"].append(max(iso_root_stress_slices(g, 0, w, grid.rho_pinion[:p]).max(),
                                      iso_root_stress_slices(g, 1, w, grid.rho_gear[:p]).max()))
        out["max_line_load"].append(w.max())
    return {k: np.array(v) for k, v in out.items()}


def _assert_criterion(name, fast, straight):
    """Equal within the contact solve's tolerance (rtol 1e-12 on the load sum): 1e-9 of the value,
    the small TE harmonics within 1e-9 of the largest."""
    atol = 1e-9 * np.max(np.abs(straight)) if name == "te_harmonics" else 0.0
    np.testing.assert_allclose(fast, straight, rtol=1e-9, atol=atol, err_msg=name)


def test_criteria_over_samples_are_the_tolerance_statistic_of_each_manufactured_gears_own(model):
    """criteria_over_samples: each criterion is the statistic over the nominal and the tolerance
    samples of that gear's own LTCA — here the straightforward exact LTCA of one manufactured gear
    at a time (:func:`_straightforward_criteria`), against the optimiser's tabulated batch with its
    samples started from their nominal — for the candidate and for the unmodified pair it is held
    against; without it, the nominal gear's."""
    common = {"population": 4, "generations": 1, "objective": "robust", "torque_Nm": 1000.0,
              "torques_Nm": list(TORQUES), "tolerance_statistic": "max"}
    tolerances = {**ROBUST_TOLERANCES, "samples": 2}
    over = problem_of(model, tolerances, **common, constraints={
        "root_stress_factor": 1.1, "criteria_over_samples": True})
    nominal = problem_of(model, tolerances, **common, constraints={
        "root_stress_factor": 1.1, "criteria_over_samples": False})
    params = over.decode([CANDIDATE])
    rows, lead = _manufactured_rows(model, over.tolerance, params, over.population_deviations)
    assert rows.shape[0] == 3  # the nominal and two samples
    each = [_straightforward_criteria(model, TORQUES, rows[k], lead[k]) for k in range(3)]
    ev = op.evaluate(over, params)
    for name in ("root_stress", "flank_pressure", "edge_pressure", "lte_peak_to_peak", "te_harmonics"):
        worst = np.max([c[name] for c in each], axis=0)
        _assert_criterion(name, getattr(ev.criteria, name)[0], worst)
        _assert_criterion(name, getattr(op.evaluate(nominal, params).criteria, name)[0], each[0][name])
    std_rows, std_lead = _manufactured_rows(model, over.tolerance, np.zeros((1, 2, 6)), over.population_deviations)
    std_root = np.max([_straightforward_criteria(model, TORQUES, std_rows[k], std_lead[k])["root_stress"]
                       for k in range(3)], axis=0)
    # the reference is the unmodified pair's worst gear of its tolerance box, never below its samples'
    from gearmesh.robust import CRITERIA
    box_root = over.reference.values[:, CRITERIA.index("peak_root_stress")]
    assert np.all(box_root >= std_root * (1 - 1e-9))
    std_ref = np.maximum(std_root, box_root)
    _assert_criterion("root_stress", over.standard.criteria.root_stress[0], std_ref)
    ratios = _ratios(over.settings, ev.force[:, 0], ev.lte_peak_to_peak, ev.max_line_load, ev.dynamic_factor,
                        ev.criteria, over.standard)
    assert ratios["root_stress"][0] == pytest.approx(np.max(ev.criteria.root_stress[0] / std_ref), rel=1e-9)


def test_population_batch_equals_each_gear_solved_on_its_own(model):
    """ltca_criteria over runs of manufactured gears (``samples``: each sample started from its
    nominal's tangent) gives every gear's criteria and loads as the same gears solved cold, one
    problem each, and as the straightforward exact LTCA."""
    from gearmesh.tolerance import apply_deviations, tolerance_model, unit_deviations

    tol = tolerance_model(model.geom, grade=5, modification={"tip_relief_um": 3, "crowning_um": 3})
    dev = unit_deviations(len(tol.dimensions), 4, "corners", 0)[:4]
    prob = _problem(model)
    params = prob.decode([CANDIDATE, [10, 30, 1, 3, 5, 20]])
    p, lead = apply_deviations(tol, params, model.lead_slope, dev)
    rows, lead = p.reshape(-1, 2, 6), lead.reshape(-1, 2)
    batch = im.ltca_criteria(model, TORQUES, rows, lead_slope=lead, samples=5)
    cold = im.ltca_criteria(model, TORQUES, rows, lead_slope=lead)
    for name in ("lte_peak_to_peak", "te_harmonics", "max_line_load", "flank_pressure", "edge_pressure",
                 "root_stress", "load"):
        _assert_criterion(name, getattr(batch, name), getattr(cold, name)) if name != "load" else \
            np.testing.assert_allclose(batch.load, cold.load, rtol=0, atol=1e-10 * cold.load.max())
    for k in (0, 3, 7):
        straight = _straightforward_criteria(model, TORQUES, rows[k], lead[k])
        for name, value in straight.items():
            _assert_criterion(name, getattr(batch, name)[k], value)
    with pytest.raises(GearmeshInputError) as exc:
        im.ltca_criteria(model, TORQUES, rows, lead_slope=lead, samples=3)  # 10 gears are no runs of 3
    assert exc.value.field == "samples"


def test_tangent_start_of_a_sample_is_an_upper_bound_of_its_approach(model):
    """The nominal gear's tangent estimate δ_n + Σ k_i Δg_i / Σ k_i is an upper bound of each
    sample's exact approach (each q_i convex in δ), close to it (the deviations are small)."""
    from gearmesh.ltca_solve import solve_contact, solve_contact_tabulated
    from gearmesh.separation import SeparationBasis, basis_gap
    from gearmesh.tolerance import apply_deviations, tolerance_model, unit_deviations

    g, lt = model.geom, model.ltca
    grid = lt.grid
    p = grid.gap.shape[0] - 1
    basis = SeparationBasis(*(getattr(grid.basis, f)[:p] for f in SeparationBasis.__dataclass_fields__))
    tol = tolerance_model(g, grade=6, modification={"tip_relief_um": 2, "crowning_um": 2})
    params = _problem(model).decode([CANDIDATE])
    rows, lead = apply_deviations(tol, params, model.lead_slope, unit_deviations(len(tol.dimensions), 6, "lhs", 2))
    rows, lead = rows.reshape(-1, 2, 6), lead.reshape(-1, 2)
    gap = basis_gap(g, basis, np.broadcast_to(grid.z, basis.base.shape), lead[:, None, None, None, :],
                    rows[:, None, None, None, :, :]).reshape(7, p, -1)
    comp, force = lt.compliance[:p].reshape(p, -1), 1600.0 / g.base_radius[0]
    _, dn, kn = solve_contact_tabulated(gap[0], comp, np.full(p, force), lt.law)
    start = _tangent_start((gap[1:] - gap[:1])[None], dn[None, None], kn[None, None])[0, :, 0]  # (6, P)
    for s in range(6):
        _, exact, _, _ = solve_contact(gap[s + 1], comp, np.full(p, force), lt.law)
        assert np.all(start[s] >= exact * (1 - 1e-12))
        assert np.all(start[s] - exact <= 0.05 * exact)


@pytest.mark.parametrize("law_name", ["palmgren", "linear"])
def test_tabulated_solve_equals_the_exact_solve_from_any_start(pair, law_name):
    """solve_contact_tabulated: the loads and approach of solve_contact to its tolerance, the load
    sum equal to F, from the default bound, from a start right of the root and from one left of
    every point (no load there: back to the bound)."""
    from gearmesh.ltca_solve import solve_contact, solve_contact_tabulated
    from gearmesh.ltca_model import contact_law

    geom = pair_geometry(pair)
    law = contact_law(geom, geom.face_width / 40, law_name)
    rng = np.random.default_rng(4)
    gap = rng.uniform(0.0, 20e-6, (50, 40))
    gap[:, ::7] = np.inf  # points that are no candidates
    gap[:, 1] = rng.uniform(0.0, 1e-9, 50)  # one point close to contact in every row
    comp = rng.uniform(2e-11, 8e-11, (50, 40))
    force = rng.uniform(1e3, 4e5, 50)
    q, delta, _, _ = solve_contact(gap, comp, force, law)
    for start in (None, delta * 1.3, np.full(50, -1.0)):
        qt, dt, dq = solve_contact_tabulated(gap, comp, force, law, start)
        np.testing.assert_allclose(dt, delta, rtol=1e-11)
        assert np.all(np.abs(qt - q) <= 1e-11 * force[:, None])
        np.testing.assert_allclose(qt.sum(axis=1), force, rtol=1e-12)
        assert np.all((qt > 0) == (dq > 0)) and np.all(qt[~np.isfinite(gap)] == 0)
    # problems at the same points share their compliance row: the same solution bit for bit
    which = rng.integers(0, 5, 50)
    comp5 = comp[:5]
    for start in (None, delta * 1.3):
        alone = solve_contact_tabulated(gap, comp5[which], force, law, start)
        shared = solve_contact_tabulated(gap, comp5, force, law, start, compliance_rows=which)
        for a, b in zip(alone, shared):
            np.testing.assert_array_equal(a, b)


def test_the_commands_differences_from_a_study_are_its_listed_overrides_alone(pair):
    """``gearmesh optimise`` runs a study's section (commands._optimise_section): given only its
    design torque, every key is the declared default and the run resolves to a study's with an
    empty section (and the command's lead class); the differences are the listed ones — the
    design torque the spectrum's middle, weights the duty-cycle mean, no samples the nominal."""
    from gearmesh.cli import CLI_LEAD_GRADE, build_parser
    from gearmesh.commands import _optimise_section
    from gearmesh.schema import defaults, jsonable
    from gearmesh.settings import Constraints, Optimise, Tolerances

    path = str(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    args = build_parser().parse_args(["optimise", path, "--torque-Nm", "1000"])
    section, tolerances = _optimise_section(args, None, None)
    declared = defaults(Optimise)
    assert set(section) <= set(declared) and "constraints" in section
    assert {k: jsonable(v) for k, v in section.items()} == {k: declared[k] for k in section}
    assert section["constraints"] == defaults(Constraints)
    assert tolerances == {"grade": CLI_LEAD_GRADE, "samples": defaults(Tolerances)["samples"],
                          "sampling": defaults(Tolerances)["sampling"]}
    study = run_settings(pair, tolerances={"grade": CLI_LEAD_GRADE})[1]
    assert run_settings(pair, **section, tolerances=tolerances)[1] == study
    args = build_parser().parse_args(["optimise", path, "--torques-Nm", "400,1000,1600", "--weights", "1,2,1",
                                      "--tolerance-samples", "0"])
    section, tolerances = _optimise_section(args, [400.0, 1000.0, 1600.0], [1.0, 2.0, 1.0])
    assert (section["torque_Nm"], section["statistic"], section["tolerance_statistic"]) == (1000.0, "mean", None)
    assert tolerances["samples"] == 0


def test_every_door_judges_the_criteria_over_the_manufactured_population(pair, monkeypatch):
    """Issue 27: the loaded-contact criteria over the manufactured gears is the one declared
    default (settings.Constraints), and the schema, the checked settings, the study's optimise
    sections, the Python API (optimise_dataset) and ``gearmesh optimise`` all take it from there."""
    import yaml

    from gearmesh import cli
    from gearmesh.datasets import optimise as dop
    from gearmesh.schema import defaults
    from gearmesh.settings import Constraints

    assert defaults(Constraints)["criteria_over_samples"] is True
    schema = yaml.safe_load((ROOT / "src/gearmesh/schemas/config.schema.yaml").read_text())
    run = schema["properties"]["optimise"]["additionalProperties"]
    assert run["properties"]["constraints"]["properties"]["criteria_over_samples"]["default"] is True
    nominal = {"objective": "force", "tolerance_statistic": None}
    assert run_settings(pair, **nominal)[1].criteria_over_samples is True
    assert run_settings(pair, **nominal, constraints={"criteria_over_samples": False})[1].criteria_over_samples is False
    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    for name, section in config["optimise"].items():
        checked = run_settings(pair, **section, impact=config.get("impact"), tolerances=config.get("tolerances"))[1]
        assert checked.criteria_over_samples is True, name

    seen = []

    class Seen(Exception):
        pass

    def capture(model, settings, **kwargs):
        seen.append(settings)
        raise Seen

    monkeypatch.setattr(dop, "impact_model", lambda geom, **kwargs: None)
    monkeypatch.setattr(dop, "problem", capture)
    with pytest.raises(Seen):
        dop.optimise_dataset(pair, torque_Nm=1000, torques_Nm=[400, 1000], tolerances={"grade": 6, "samples": 2})
    with pytest.raises(Seen):
        cli.main(["optimise", str(ROOT / "config/pairs/helical_z29_71_m5.yaml"), "--torques-Nm", "400,1000",
                  "--method", "nsga2"])
    assert [s.criteria_over_samples for s in seen] == [True, True]
    assert all(s.tolerance_statistic == "max" for s in seen)


def _rows_of_candidates(model):
    """Three parameter sets (a candidate, the unmodified pair, a tip relief) with lead slopes of
    their own (m), as a manufactured population gives them."""
    genes, base = op.gene_table(model.geom, ("pinion",))
    params = op.decode(model.geom, genes, base, [CANDIDATE, [0, 0, 0, 0, 0, 0], [0, 30, 0, 3, 0, 0]])
    lead = np.array([[4e-6, -2e-6], [0.0, 0.0], [-7e-6, 3e-6]])
    return params, lead


def test_torques_of_their_own_misalignment_solve_as_each_torque_alone(model):
    """impact_static at torques whose mesh misalignments differ (the system deflection grows with
    the load) solves every (set, torque) row in one batch: each field equals that torque solved
    alone, to round-off (1e-12 relative; the approach rate, a one-sided difference over 1e-6 p_bt,
    to 1e-11 absolute: the point loads' round-off divided by that step)."""
    from gearmesh.deflection import mesh_misalignment

    assert np.unique(mesh_misalignment(model.geom, np.array(TORQUES) / model.geom.base_radius[0])).size == 3
    params, lead = _rows_of_candidates(model)
    both = im.impact_static(model, TORQUES, params, lead_slope=lead)
    alone = [im.impact_static(model, [t], params, lead_slope=lead) for t in TORQUES]
    assert {im.SCENARIO_SURFACE, im.SCENARIO_EDGE} <= set(both.scenario.ravel())  # both kinds of touch covered
    for name in im.ImpactStatic.__dataclass_fields__:
        got = getattr(both, name)
        if name in ("params", "lead_slope"):
            np.testing.assert_array_equal(got, params if name == "params" else lead)
            continue
        want = np.concatenate([getattr(a, name) for a in alone], axis=0 if name in ("torque", "force") else 1)
        if got.dtype.kind != "f":
            np.testing.assert_array_equal(got, want, err_msg=name)
        else:
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-11 if name == "approach_rate" else 0.0,
                                       err_msg=name)


@pytest.mark.parametrize("samples", [1, 3])
def test_ltca_criteria_at_torques_of_their_own_misalignment_are_each_torque_alone(model, samples):
    """ltca_criteria solves every torque at its own mesh misalignment in one batch: bit for bit what
    each torque alone gives (every row is its own contact problem, solved to its own tolerance)."""
    params, lead = _rows_of_candidates(model)
    both = im.ltca_criteria(model, TORQUES, params, lead_slope=lead, samples=samples)
    alone = [im.ltca_criteria(model, [t], params, lead_slope=lead, samples=samples) for t in TORQUES]
    for name in im.LTCACriteria.__dataclass_fields__:
        np.testing.assert_array_equal(getattr(both, name), np.concatenate([getattr(a, name) for a in alone], axis=1),
                                      err_msg=name)


def test_a_candidate_its_nominal_gear_refuses_is_refused_without_its_samples_contact(model):
    """Screening by the nominal gear (tolerance statistic max): a candidate whose nominal gear meets
    every constraint is scored on its samples exactly as without screening; one its nominal gear
    already refuses stays refused, its violation a lower bound of the full one (never above it)."""
    prob = problem_of(
        model, {**ROBUST_TOLERANCES, "samples": 2}, population=8, generations=1, objective="robust", torque_Nm=1000.0,
        torques_Nm=list(TORQUES), tolerance_statistic="max", constraints={
            "criteria_over_samples": True, "harmonic_factor": 1.0, "pressure_factor": 1.1, "root_stress_factor": 1.1})
    rng = np.random.default_rng(3)
    genes = np.array([[g.low + (g.high - g.low) * u for g, u in zip(prob.genes, row)]
                      for row in rng.uniform(0.0, 1.0, (12, len(prob.genes)))])
    params = np.vstack([prob.decode(genes), prob.decode([CANDIDATE]), np.zeros((1, 2, 6))])
    screened = op.evaluate(prob, params)
    full = _score(prob, _evaluate(prob, params, None), prob.standard)  # every candidate's samples solved
    ok = ~full.failed & (full.violation == 0)
    assert ok.any() and (~ok & ~full.failed).any()  # both kinds among the candidates
    np.testing.assert_array_equal(screened.failed, full.failed)
    np.testing.assert_allclose(screened.objective[ok], full.objective[ok], rtol=1e-12)
    np.testing.assert_allclose(screened.criteria.te_harmonics[ok], full.criteria.te_harmonics[ok], rtol=1e-12)
    bad = ~ok & ~full.failed
    assert np.all(screened.violation[bad] > 0) and np.all(screened.violation[bad] <= full.violation[bad] * (1 + 1e-12))


def test_the_optimum_is_checked_on_its_own_box_and_a_refused_one_is_not_searched_further(model):
    """_verified: a candidate whose first-stage gears already violate a constraint is refused on
    them (searched no further); the next, the unmodified pair itself, meets every constraint on its
    own box, and its box searched in full is the run's reference, bit for bit (the same search of
    the same gears)."""
    prob = problem_of(
        model, {**ROBUST_TOLERANCES, "samples": 2}, population=8, generations=1, objective="robust", torque_Nm=1000.0,
        torques_Nm=list(TORQUES), tolerance_statistic="max", constraints={
            "criteria_over_samples": True, "harmonic_factor": 1.0, "pressure_factor": 1.0, "root_stress_factor": 1.0})
    crowned = [0, 0, 0, 0, 25, 0]  # 25 µm of crowning: the flank pressure rises well above the reference's
    genes = np.array([crowned, [0] * 6], dtype=float)
    assert np.all(prob.decode(genes[1:]) == 0.0)
    k, v = _verified(prob, genes, np.array([0, 1]))
    assert (k, v.rank, v.tried, v.searched, v.violation) == (1, 1, 2, True, 0.0)
    np.testing.assert_array_equal(v.worst.values, prob.reference.values)
    k, v = _verified(prob, genes[:1], np.array([0]))
    assert (k, v.rank, v.tried, v.searched) == (0, 0, 1, False) and v.violation > 0.0
