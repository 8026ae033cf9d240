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
from gearmesh import optimise as op
from gearmesh.datasets.optimise import result_dataset, run_settings
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.io import check_documented
from gearmesh.ltca import MESH_ORDERS, lte_harmonics, ltca, ltca_model
from gearmesh.plots.optimise import plot_pareto
from gearmesh.stress import contact_stress, iso_root_stress_slices

from test_optimise import COARSE, model, pair  # noqa: F401 (the coarse impact model and its pair, as fixtures)

TORQUES = (400.0, 1000.0, 1600.0)
CANDIDATE = [40, 40, 2, 2, 20, 10]  # µm / mm: reliefs, lengths, crowning, unmodified lead


def _problem(model, **settings):
    settings = {"population": 8, "generations": 3, "objective": "robust", "torque": 1000.0, "torques": TORQUES,
                **settings}
    return op.problem(model, op.check_settings(**settings))


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
    full = ltca(mod_geom, list(TORQUES), model=ltca_model(mod_geom, lt.grid.roll.size - 1, COARSE["points"],
                                                           lt.lead_slope, lt.law.name, lt.method,
                                                           lt.grid.extension / geom.transverse_base_pitch,
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
    ev = op._evaluate(_problem(model, pressure_factor=1e6), params, None)  # the criteria, no penalty yet
    std = _problem(model, pressure_factor=1e6).standard
    ratio = float(op._ratios(free.settings, ev.force[:, 0], ev.lte_peak_to_peak, ev.max_line_load,
                             ev.dynamic_factor, ev.criteria, std)[name][0])
    assert math.isfinite(ratio) and ratio > 0
    loose = _problem(model, **{factor: ratio * (1 + 1e-9)})
    tight = _problem(model, **{factor: ratio * (1 - 1e-3)})
    ev_loose, ev_tight = op.evaluate(loose, params), op.evaluate(tight, params)
    assert ev_loose.violation[0] == 0.0
    assert ev_tight.violation[0] == pytest.approx(1 / (1 - 1e-3) - 1, rel=1e-6)
    assert ev_tight.objective[0] > ev_loose.objective[0] == pytest.approx(float(ev_loose.value[0, 0].max()))


@pytest.mark.parametrize("key,which", [("S_Hmin", 0), ("S_Fmin", 1)])
def test_safety_factor_penalty_is_zero_exactly_when_the_minimum_holds(model, key, which):
    """S_H, S_F of ISO 6336-2/-3 method B with the LTCA's load factors: the penalty vanishes at
    S = S_min and grows as S_min/S − 1 beyond; the crowned candidate's K_Hβ lowers its S below the
    unmodified pair's (whose own K_Hα is 1 by definition)."""
    probe = _problem(model, pressure_factor=1e6)
    params = probe.decode([CANDIDATE])
    crit = op._evaluate(probe, params, None).criteria
    s = op.safety_factors(probe, crit, probe.standard.criteria)[which]
    s_std = op.safety_factors(probe, probe.standard.criteria, probe.standard.criteria)[which]
    assert s.shape == (1, 3) and np.all(s < s_std) and np.all(np.diff(s_std[0]) < 0)  # more torque, less safety
    worst = float(s.min())
    assert op.evaluate(_problem(model, **{key: worst * (1 - 1e-9)}), params).violation[0] == 0.0
    assert op.evaluate(_problem(model, **{key: worst * 1.01}), params).violation[0] == pytest.approx(0.01, rel=1e-6)


def test_the_standard_gear_meets_every_relative_criterion_at_factor_one(model):
    prob = _problem(model, pressure_factor=1.0, root_stress_factor=1.0, harmonic_factor=1.0, impact_factor=1.0,
                    worst_impact_factor=1.0)
    ev = op.evaluate(prob, np.zeros((1, 2, 6)))
    assert ev.violation[0] == 0.0


def test_nsga2_front_over_three_objectives_is_non_dominated_and_drawn(model, tmp_path):
    prob = _problem(model, method="nsga2", pareto_objectives=("impact", "te_harmonics", "root_stress"),
                    population=10, generations=3, seed=1, root_stress_factor=1.1)
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
    ds.attrs["pair_name"] = "seed000_case"
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
    ({"pressure_factor": -1.0}, "constraints.pressure_factor"),
    ({"root_stress_factor": 0.0}, "constraints.root_stress_factor"),
    ({"harmonic_factor": float("nan")}, "constraints.harmonic_factor"),
    ({"worst_impact_factor": "half"}, "constraints.worst_impact_factor"),
    ({"harmonic_orders": (4,)}, "constraints.harmonic_orders"),
    ({"harmonic_orders": (1, 1)}, "constraints.harmonic_orders"),
    ({"S_Hmin": 0.0}, "constraints.S_Hmin"),
    ({"S_Fmin": 11.0}, "constraints.S_Fmin"),
    ({"S_Fmin": "1.4"}, "constraints.S_Fmin"),
])
def test_bad_criteria_settings_are_refused_naming_the_field(settings, field):
    settings = {"method": "nsga2", **settings}
    with pytest.raises(GearmeshInputError) as exc:
        op.check_settings(**settings)
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


def test_every_door_defaults_to_the_robust_objective_over_the_tolerance_samples():
    """Issue 27 item 4: the study schema, the Python API and ``gearmesh optimise`` give one default:
    the robust objective, the worst case over the nominal and the tolerance samples."""
    import argparse
    import inspect

    from gearmesh.cli import CLI_LEAD_GRADE, build_parser
    from gearmesh.schema import defaults
    from gearmesh.settings import Optimise, Tolerances

    declared = defaults(Optimise)
    assert declared["objective"] == "robust" and declared["tolerance_statistic"] == "max"
    api = inspect.signature(run_settings).parameters
    assert api["objective"].default == declared["objective"]
    assert api["tolerance_statistic"].default == declared["tolerance_statistic"]
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)).choices["optimise"]
    cli = {a.dest: a.default for a in sub._actions}
    assert cli["objective"] == declared["objective"]
    assert cli["tolerance_statistic"] == declared["tolerance_statistic"]
    assert cli["samples"] == defaults(Tolerances)["samples"] > 0
    assert cli["grade"] == CLI_LEAD_GRADE  # a population to be robust over without a tolerances section
    assert "OUT.yaml" in sub.format_usage()  # --write-pair OUT.yaml, the name its help gives


def test_criteria_over_samples_are_the_tolerance_statistic_of_each_manufactured_gears_own(model):
    """criteria_over_samples: each criterion is the statistic over the nominal and the tolerance
    samples of that gear's own LTCA (computed here one manufactured gear at a time), for the
    candidate and for the unmodified pair it is held against; without it, the nominal gear's."""
    from gearmesh.tolerance import tolerance_model

    tol = tolerance_model(model.geom, grade=6, modification={"tip_relief_um": 2, "crowning_um": 2})
    common = {"population": 4, "generations": 1, "objective": "robust", "torque": 1000.0, "torques": TORQUES,
              "tolerance_samples": 2, "tolerance_statistic": "max", "root_stress_factor": 1.1}
    over = op.problem(model, op.check_settings(**common, criteria_over_samples=True), tolerance=tol)
    nominal = op.problem(model, op.check_settings(**common), tolerance=tol)
    params = over.decode([CANDIDATE])
    rows, lead = op._manufactured_rows(model, over.tolerance, params, over.population_deviations)
    assert rows.shape[0] == 3  # the nominal and two samples
    each = [im.ltca_criteria(model, TORQUES, rows[k:k + 1], lead_slope=lead[k:k + 1]) for k in range(3)]
    ev = op.evaluate(over, params)
    for name in ("root_stress", "flank_pressure", "edge_pressure", "lte_peak_to_peak", "te_harmonics"):
        worst = np.max([getattr(c, name)[0] for c in each], axis=0)
        np.testing.assert_allclose(getattr(ev.criteria, name)[0], worst, rtol=1e-12)
        np.testing.assert_allclose(getattr(op.evaluate(nominal, params).criteria, name)[0], getattr(each[0], name)[0],
                                   rtol=1e-12)
    std_rows, std_lead = op._manufactured_rows(model, over.tolerance, np.zeros((1, 2, 6)), over.population_deviations)
    std_root = np.max([im.ltca_criteria(model, TORQUES, std_rows[k:k + 1], lead_slope=std_lead[k:k + 1]).root_stress[0]
                       for k in range(3)], axis=0)
    np.testing.assert_allclose(over.standard.criteria.root_stress[0], std_root, rtol=1e-12)
    ratios = op._ratios(over.settings, ev.force[:, 0], ev.lte_peak_to_peak, ev.max_line_load, ev.dynamic_factor,
                        ev.criteria, over.standard)
    assert ratios["root_stress"][0] == pytest.approx(np.max(ev.criteria.root_stress[0] / std_root), rel=1e-12)
