"""GA optimisation of the micro-geometry: determinism, bounds and validity, better than the
standard gear and than random search, the dataset and figures, NSGA-II, refusals.

A coarse impact model (16 points per line, 24 window rolls, 65 face samples) keeps the
runs small: it exercises the optimiser, not the converged physics."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from gearmesh.contact_model import ContactModel
from gearmesh import impact as im
from gearmesh import optimise as op
from gearmesh.impact import load_grid, load_window
from gearmesh.cli import main as cli_main
from gearmesh.config import check_study, validate_study
from gearmesh.datasets.optimise import optimum_pair, result_dataset, run_settings
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import Modification, pair_geometry, validate_modifications
from gearmesh.pairfile import MODIFICATION_UNITS, load_pair
from gearmesh.io import check_documented
from gearmesh.plots.optimise import plot_convergence, plot_modification, plot_pareto
from gearmesh.surface import MODIFICATION_FIELDS

ROOT = Path(__file__).resolve().parents[1]
COARSE = {"contact": ContactModel(points=16), "window_positions": 24, "face_samples": 65}


@pytest.fixture(scope="module")
def pair():
    return load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")


@pytest.fixture(scope="module")
def model(pair):
    return im.impact_model(pair_geometry(pair), **COARSE)


#: The manufactured population of the robust runs: ISO 1328-1 class 6 lead, ± 2 µm tip relief and crowning.
ROBUST_TOLERANCES = {"grade": 6, "modification": {"tip_relief_um": 2, "crowning_um": 2}}


def run_settings_of(model, tolerances=None, **section):
    """The run settings and tolerance model of a study's optimisation ``section`` (its config keys)
    for ``model``'s pair, through the declaration as every door builds them
    (:func:`run_settings`); unless given, the nominal single-point form (objective force, no
    tolerance statistic)."""
    section = {"objective": "force", "tolerance_statistic": None, **section}
    _, settings, _, _, tol = run_settings(model.geom.pair, tolerances=tolerances, **section)
    return settings, tol


def problem_of(model, tolerances=None, **section):
    """The optimisation problem of ``model`` with the run settings of ``section`` (:func:`run_settings_of`)."""
    settings, tol = run_settings_of(model, tolerances, **section)
    return op.problem(model, settings, tolerance=tol)


def _run(model, tolerances=None, **section):
    return op.optimise(problem_of(model, tolerances, **{"population": 10, "generations": 6, **section}))


@pytest.fixture(scope="module")
def ga(model):
    return _run(model, seed=3, random_baseline=True)


def _with_modification(pair, params):
    mods = tuple(Modification(**{f: float(params[g, k]) for k, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
    return pair.with_changes(modification=mods)


def test_same_seed_gives_a_bit_identical_history_and_optimum(model, ga):
    again = _run(model, seed=3)
    for name, value in ga.history.arrays().items():
        assert np.array_equal(value, again.history.arrays()[name], equal_nan=True), name
    assert np.array_equal(ga.optimum_genes, again.optimum_genes)
    assert np.array_equal(ga.optimum, again.optimum)
    assert ga.evaluations == again.evaluations
    other = _run(model, seed=4)
    assert not np.array_equal(other.history.arrays()["genes"], ga.history.arrays()["genes"])


def test_genes_stay_in_bounds_and_every_candidate_is_a_valid_modification(pair, model, ga):
    genes = ga.history.arrays()["genes"].reshape(-1, len(ga.problem.genes))
    low = np.array([g.low for g in ga.problem.genes])
    high = np.array([g.high for g in ga.problem.genes])
    assert np.all(genes >= low) and np.all(genes <= high)
    # the mesh-in impact paper's bounds in mn = 5 mm and B = 42 mm
    np.testing.assert_allclose(low, [5, 5, 0.5, 0.5, 5, 0])
    np.testing.assert_allclose(high, [75, 75, 4, 4, 75, 21])
    for params in ga.problem.decode(genes[::7]):
        validate_modifications(pair_geometry(_with_modification(pair, params)))
    # relief lengths that cannot fit the active flank together are scaled to fit it
    geom = model.geom
    active_mm = float(geom.rho_eap[0] - geom.rho_sap[0]) * 1e3
    genes_, base = op.gene_table(geom, bounds={"root_relief_length_mm": [0.9 * active_mm, active_mm],
                                                 "tip_relief_length_mm": [0.9 * active_mm, active_mm]})
    p = op.decode(geom, genes_, base, [[50, 50, active_mm, active_mm, 20, 10]])[0]
    assert p[0, 2] + p[0, 3] <= active_mm * 1e-3 and p[0, 2] == pytest.approx(p[0, 3])
    validate_modifications(pair_geometry(_with_modification(pair, p)))


def test_optimum_beats_the_standard_gear_at_the_design_point(ga):
    opt, std = ga.optimum_evaluation, ga.problem.standard
    assert not opt.failed[0]
    assert opt.force[0, 0, 0] < 0.5 * std.force[0, 0, 0]
    assert opt.objective[0] == pytest.approx(np.min(ga.history.arrays()["objective"]))
    assert ga.history.best[-1] <= ga.history.best[0]
    assert np.all(np.diff(ga.history.best) <= 0)


@pytest.mark.slow
def test_ga_beats_random_search_with_the_same_budget_over_seeds(model, pair):
    """The robust objective (worst F_s over 400 and 1600 N m and over the nominal and two tolerance
    samples): over five seeds the GA's median best beats the median of a random search with the
    same number of distinct evaluations. 16 x 12: with 10 x 6 (about 55 evaluations) the GA has
    hardly begun to select and a random search's lucky draws decide; the GA's lead grows with the
    budget (40 x 30: README)."""
    ga_best, random_best = [], []
    for seed in range(5):
        res = _run(model, {**ROBUST_TOLERANCES, "samples": 2, "seed": seed}, seed=seed, population=16, generations=12,
                   objective="robust", torque_Nm=400.0, torques_Nm=[400.0, 1600.0], tolerance_statistic="max",
                   random_baseline=True)
        assert res.baseline.evaluations == res.evaluations
        ga_best.append(res.history.best[-1])
        random_best.append(res.baseline.history.best[-1])
    assert np.median(ga_best) < np.median(random_best)


def test_fixed_genes_robust_objective_and_constraints(model):
    res = _run(model, objective="robust", torque_Nm=400.0, torques_Nm=[400.0, 1600.0], generations=2,
               constraints={"lte_factor": 1.2}, seed=1)
    prob = res.problem
    assert len(prob.genes) == 6
    ev = op.evaluate(prob, res.optimum[None])
    expected = ev.force[:, 0].max(axis=1) + prob.settings.penalty * prob.standard.objective * ev.violation
    np.testing.assert_allclose(ev.objective, expected, rtol=1e-12)
    assert ev.force.shape == (1, 1, 2)
    fixed = op.problem(model, run_settings_of(model, population=4, generations=1)[0],
                       fixed={"crowning_um": 0, "unmodified_lead_length_mm": 0})
    assert [g.name for g in fixed.genes] == [f"pinion.{k}" for k in op.GENE_KEYS[:4]]
    both = op.problem(model, run_settings_of(model, population=4, generations=1)[0], modify=["pinion", "gear"])
    assert len(both.genes) == 12 and {g.gear for g in both.genes} == {0, 1}
    # the mesh-in impact paper's alternative objective, |v_n| at the design point
    slow = op.problem(model, run_settings_of(model, population=4, generations=1, objective="velocity")[0])
    ev = op.evaluate(slow, slow.decode([[40, 40, 2, 2, 20, 10]]))
    assert ev.objective[0] == ev.velocity[0, 0, 0] > 0
    # a tight LTE factor penalises a candidate in proportion to its excess
    strict = op.problem(model, run_settings_of(model, population=4, generations=1,
                                                      constraints={"lte_factor": 1e-3})[0])
    ev = op.evaluate(strict, strict.decode([[40, 40, 2, 2, 20, 10]]))
    assert ev.violation[0] > 1 and ev.objective[0] > ev.force[0, 0, 0]


def test_nsga2_front_is_non_dominated_and_the_dataset_documents_it(model, tmp_path):
    res = _run(model, method="nsga2", seed=2)
    genes, pts = res.pareto
    f = pts[:, 0]
    assert len(f) >= 1 and np.all(np.diff(f) >= 0)
    assert op.pareto_mask(pts).all()
    ds = result_dataset(res)
    ds.attrs["pair_name"] = "helical_z29_71_m5"
    check_documented(ds)
    assert plot_pareto(ds, tmp_path / "pareto.png").stat().st_size > 1000


def test_dataset_figures_and_the_optimum_as_a_pair(pair, ga, tmp_path):
    ds = result_dataset(ga, {"population": 10})
    check_documented(ds)
    assert ds.sizes["generation"] == 7 and ds.sizes["candidate"] == 10 and ds.sizes["gene"] == 6
    assert ds.attrs["method"] == "ga" and ds.attrs["seed"] == 3
    assert int(ds["evaluations"]) == ga.evaluations and int(ds["random_evaluations"]) == ga.evaluations
    assert ds["optimum_genes"].attrs["units"] == "m"
    assert float(ds["reduction"]) > 50
    best = pair_geometry(optimum_pair(pair, ds))
    # the optimum to the drawing's resolution (0.01 µm depths, 0.001 mm lengths): within half a step
    steps = [1e-6 * 0.01 if MODIFICATION_UNITS[f] == "um" else 1e-3 * 0.001 for f in MODIFICATION_FIELDS]
    np.testing.assert_allclose([getattr(best.pair.modification[0], f) for f in MODIFICATION_FIELDS], ga.optimum[0],
                               rtol=0, atol=max(steps))
    assert np.all(np.abs([getattr(best.pair.modification[0], f) for f in MODIFICATION_FIELDS] - ga.optimum[0])
                  <= np.array(steps) * (1 + 1e-9))
    ds.attrs["pair_name"] = "helical_z29_71_m5"
    for plot, name in ((plot_convergence, "convergence"), (plot_modification, "modification")):
        assert plot(ds, tmp_path / f"{name}.png").stat().st_size > 1000


@pytest.mark.parametrize("settings, field", [
    ({"population": 1}, "population"),
    ({"generations": 0}, "generations"),
    ({"method": "pso"}, "method"),
    ({"objective": "noise"}, "objective"),
    ({"seed": -1}, "seed"),
    ({"speed_rpm": 0}, "speed_rpm"),
    ({"torque_Nm": -5}, "torque_Nm"),
    ({"torques_Nm": []}, "torques_Nm"),
    ({"torques_Nm": [400, 1600]}, "torque_Nm"),
    ({"torques_Nm": [1000, 1000]}, "torques_Nm"),
    ({"weights": [1, 2]}, "weights"),
    ({"torques_Nm": [400, 1000], "weights": [1, 2]}, "weights"),
    ({"objective": "dynamic", "dynamic_speeds_rpm": [5000]}, "dynamic_speeds_rpm"),
    ({"objective": "robust"}, "objective"),
    ({"tolerance_statistic": "max"}, "tolerance_statistic"),
    ({"tolerance_statistic": "max", "torque_Nm": 1000}, "tolerance_statistic"),
    ({"tolerance_statistic": "max", "tolerances": {"grade": 6, "samples": 0}}, "tolerance_statistic"),
    ({"tolerance_statistic": "cvar", "tolerance_level_percent": 100, "tolerances": {"grade": 6}},
     "tolerance_level_percent"),
    ({"torques_Nm": [400, 1000], "load_window_step_Nm": 600}, "load_window_step_Nm"),
    ({"tolerances": {"grade": 0}}, "tolerances.grade"),
    ({"tolerances": {"modification": {"tip_relief_um": float("nan")}}}, "tolerances.modification.tip_relief_um"),
    ({"method": "nsga2", "objective": "velocity"}, "objective"),
    ({"constraints": {"lte": 2}}, "constraints.lte"),
    ({"constraints": {"lte_factor": 0}}, "constraints.lte_factor"),
    ({"bounds": {"root_relief_um": [50, 10]}}, "bounds.root_relief_um"),
    ({"bounds": {"crowning_um": [0, 900]}}, "bounds.crowning_um"),
    ({"bounds": {"tooth_count": [0, 1]}}, "bounds.tooth_count"),
    ({"fixed": {"crowning_um": -1}}, "fixed.crowning_um"),
    ({"modify": ["wheel"]}, "modify[0]"),
    ({"keep_elitism": 40}, "keep_elitism"),
])
def test_bad_settings_are_refused_with_the_field_named(pair, settings, field):
    # the nominal, single-point form: the default (robust, max over the samples) needs tolerances (tested)
    settings = {"objective": "force", "tolerance_statistic": None, **settings}
    with pytest.raises(GearmeshInputError) as err:
        run_settings(pair, **settings)
    assert err.value.field == field


def test_bad_study_settings_and_variants_are_refused_before_any_job(capsys):
    base = {"study": "s", "pairs": ["helical_z29_71_m5"], "variants": {"standard": {},
                                                                 "optimised": {"from": "optimise.best"}}}
    with pytest.raises(GearmeshInputError, match="must be optimise.NAME"):
        check_study(validate_study(base), ROOT)
    bad = {**base, "optimise": {"best": {"bounds": {"root_relief_um": [10, 5]}, "objective": "force",
                                         "tolerance_statistic": None}}}
    with pytest.raises(GearmeshInputError) as err:
        check_study(validate_study(bad), ROOT)
    assert err.value.field == "optimise.best.bounds.root_relief_um"
    with pytest.raises(GearmeshInputError) as err:
        validate_study({**base, "optimise": {"best": {"population": 2}}})
    assert err.value.field.startswith("optimise.best.population")
    assert cli_main(["optimise", str(ROOT / "config/pairs/helical_z29_71_m5.yaml"), "--torque-Nm", "1000",
                     "--speed-rpm", "5000", "--population", "2"]) == 2
    assert capsys.readouterr().err.strip() == "gearmesh: error: --population = 2: must be at least 4"


def test_the_impact_model_is_the_studys_impact_section(pair):
    impact = {"points": 20, "energy_velocity": "normal", "driver": "gear", "window_positions": 24}
    _, settings, _, model, _ = run_settings(pair, impact=impact, objective="force", tolerance_statistic=None)
    assert model["contact"].points == 20 and model["driver"] == "gear"
    assert model["window_positions"] == 24 and settings.energy_velocity == "normal"
    _, _, _, model, _ = run_settings(pair, points=16, impact=impact, objective="force", tolerance_statistic=None)
    assert model["contact"].points == 16
    _, settings, _, model, tol = run_settings(pair, objective="force", tolerance_statistic=None)
    assert model["contact"].points == 50 and model["window_positions"] == 32 and settings.energy_velocity == "transverse"
    assert tol.dimensions == []


def test_load_window_is_the_run_around_the_design_torque():
    grid = np.array([100.0, 200, 300, 400, 500, 600])
    standard = np.array([5.0, 5, 5, 5, 5, 5])
    force = np.array([6.0, 4, 4, 4, 7, 4])  # beats from 200 to 400, not at 500, again at 600
    assert load_window(grid, force, standard, 300.0) == (200.0, 400.0)
    assert load_window(grid, force, standard, 600.0) == (600.0, 600.0)
    assert all(math.isnan(v) for v in load_window(grid, force, standard, 500.0))
    np.testing.assert_allclose(load_grid([400, 1000, 1600], 50), np.arange(50, 2001, 50))
    np.testing.assert_allclose(load_grid([130], 50), [50, 100, 130, 150])


#: A robust run: the CVaR 50 % over the nominal and three samples of the worst case over three torques.
ROBUST = {"tolerances": {**ROBUST_TOLERANCES, "samples": 3, "seed": 5}, "seed": 5, "objective": "robust",
          "torque_Nm": 1000.0, "torques_Nm": [400.0, 1000.0, 1600.0], "tolerance_statistic": "cvar",
          "tolerance_level_percent": 50.0, "load_window_step_Nm": 100.0}


@pytest.fixture(scope="module")
def robust(model):
    return _run(model, **ROBUST)


def test_robust_run_is_bit_identical_and_its_objective_is_the_two_step_statistic(model, robust):
    again = _run(model, **ROBUST)
    assert np.array_equal(robust.optimum, again.optimum)
    for name, value in robust.history.arrays().items():
        assert np.array_equal(value, again.history.arrays()[name], equal_nan=True), name
    ev = robust.optimum_evaluation
    assert ev.force.shape == (1, 4, 3)  # nominal + 3 samples, 3 torques
    worst = ev.force[0].max(axis=1)  # each manufactured gear over the spectrum
    tail = np.sort(worst)[2:].mean()  # CVaR 50 % of four equal atoms: the mean of the worst two
    assert ev.objective[0] == pytest.approx(tail, rel=1e-12)
    # the standard gear is scored with the same population and statistic
    std = robust.problem.standard
    assert std.objective[0] == pytest.approx(np.sort(std.force[0].max(axis=1))[2:].mean(), rel=1e-12)


def test_diagnostics_window_spread_and_scenarios(robust):
    d = robust.diagnostics
    assert d.window_torque[0] == 100 and d.window_torque[-1] == pytest.approx(2000)
    assert set([400.0, 1000.0, 1600.0]) <= set(d.window_torque)
    low, high = d.load_window
    beats = d.window_force < d.window_standard
    inside = (d.window_torque >= low) & (d.window_torque <= high)
    assert np.all(beats[inside]) and low <= 1000 <= high
    # the spread's nominal row is the optimum's own nominal evaluation, in another batch: equal to the
    # round-off of the point inversions (whose Newton steps stop when the whole batch has converged),
    # far below the touch tolerance's own spread of F_s (~1e-7)
    np.testing.assert_allclose(d.spread_force[0], robust.optimum_evaluation.force[0, 0], rtol=1e-10)
    assert d.spread_force.shape == (4, 3) and np.all(d.spread_scenario > 0)
    k = int(np.flatnonzero(d.window_torque == 1000.0)[0])
    assert d.window_force[k] == pytest.approx(d.spread_force[0, 1], rel=1e-10)  # same model, same point


def test_cli_json_by_torque_load_window_and_write_pair_round_trip(tmp_path, capsys):
    """--write-pair writes the optimum as a pair named after its file; every subcommand reads it."""
    out = tmp_path / "best_gear.yaml"
    case = str(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    assert cli_main(["optimise", case, "--objective", "robust", "--torques-Nm", "400,1000,1600", "--tolerance-samples",
                     "2", "--grade", "6", "--population", "4", "--generations", "1", "--write-pair", str(out),
                     "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert [r["torque_Nm"] for r in summary["by_torque"]] == [400.0, 1000.0, 1600.0]
    for row in summary["by_torque"]:
        assert {"torque_Nm", "impact_force_transverse_N", "standard_impact_force_transverse_N", "scenario"} <= set(row)
        assert row["scenario"] in ("surface", "edge")
    assert len(summary["load_window_Nm"]) == 2 and summary["torque_Nm"] == 1000.0
    # a window that runs to the end of its grid says so; the robust run is no single-point optimum
    at_end = summary["load_window_Nm"][1] == summary["load_window_grid_Nm"][1]
    assert at_end == any("end of the window's torque grid" in n for n in summary["notes"])
    assert not any(n.startswith("single-point") for n in summary["notes"])
    written = load_pair(out)
    assert written.name == "best_gear"
    genes = summary["genes"]
    # the file states the optimum to the drawing's resolution: 0.01 µm depths, 0.001 mm lengths
    for key, value in genes.items():
        gear, name = key.split(".")
        unit = name.rsplit("_", 1)[1]
        step = {"um": 0.01, "mm": 0.001}[unit]
        stated = getattr(written.modification[0 if gear == "pinion" else 1], name.rsplit("_", 1)[0]) * \
            {"um": 1e6, "mm": 1e3}[unit]
        assert abs(stated - value) <= step * (1 + 1e-9) and abs(stated / step - round(stated / step)) < 1e-6, key
    assert "9.89540935122" not in out.read_text() and len(max(re.findall(r"\d+\.\d+", out.read_text()), key=len)) < 12
    for argv in (["validate", str(out)], ["geometry", str(out)], ["stiffness", str(out), "--slices", "20",
                                                                  "--positions", "16"],
                 ["ltca", str(out), "--torque-Nm", "1000", "--positions", "8", "--points", "10"],
                 ["impact", str(out), "--torque-Nm", "1000", "--speed-rpm", "5000", "--points", "16"],
                 ["dynamics", str(out), "--torque-Nm", "1000", "--on", "pinion", "--speeds", "5000"]):
        assert cli_main([*argv, "--json"]) == 0, argv
        capsys.readouterr()
    # the impact the CLI evaluates on the written pair is the one the optimiser reported, to what
    # the drawing's rounding of the modification moves it
    assert cli_main(["impact", str(out), "--torque-Nm", "1000", "--speed-rpm", "5000", "--json"]) == 0
    impact = json.loads(capsys.readouterr().out)
    assert impact["impact_force_transverse_N"] == pytest.approx(summary["by_torque"][1]["impact_force_transverse_N"], rel=1e-2)


def test_optimum_notes_name_a_single_point_optimum_and_an_open_load_window():
    """The notes an optimum carries: the single-point objective's risk, and a load window whose
    ends are its grid's ends (1250 N m was reported as the window's top where the grid stopped)."""
    from types import SimpleNamespace

    from gearmesh.datasets.optimise import optimum_notes

    grid = np.arange(50.0, 1251.0, 50.0)

    def notes(objective, torques, samples, window, **criteria):
        settings = {"needs_criteria": False, "criteria_over_samples": True, "tolerance_statistic": "max", **criteria}
        prob = SimpleNamespace(settings=SimpleNamespace(objective=objective, objective_torques=torques, **settings),
                               deviations=np.zeros((samples, 3)))
        return optimum_notes(prob, SimpleNamespace(load_window=window, window_torque=grid))

    single = notes("force", (1000.0,), 0, (700.0, 1100.0))
    assert len(single) == 1 and single[0].startswith("single-point optimum")
    assert notes("robust", (400.0, 1000.0), 8, (700.0, 1100.0)) == []
    assert notes("robust", (1000.0,), 0, (700.0, 1100.0))[0].startswith("single-point")  # nothing to be robust over
    top = notes("robust", (400.0, 1000.0), 8, (350.0, 1250.0))
    assert len(top) == 1 and "1250 N m" in top[0] and "end of the window's torque grid" in top[0]
    assert "start of the window's torque grid" in notes("robust", (400.0, 1000.0), 8, (50.0, 900.0))[0]
    assert notes("robust", (400.0, 1000.0), 8, (math.nan, math.nan)) == []  # no window: nothing to qualify
    # constraints on the loaded contact: judged on every manufactured gear (the default) or said to be nominal
    assert notes("robust", (400.0, 1000.0), 8, (700.0, 1100.0), needs_criteria=True) == []
    for nominal in ({"criteria_over_samples": False}, {"tolerance_statistic": None}):
        said = notes("robust", (400.0, 1000.0), 8, (700.0, 1100.0), needs_criteria=True, **nominal)
        assert len(said) == 1 and said[0].startswith("nominal criteria")


def _cli_text(value) -> str:
    """A setting's value as the command line writes it (comma lists, true/false, none)."""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, (list, tuple)):
        return ",".join(map(str, value))
    return "none" if value is None else str(value)


def test_the_cli_reproduces_the_studys_optimum_from_its_section(capsys):
    """The default study's recommended optimisation, every key of its section that is not its
    declared default given on the command line by the option the declaration made for it (its
    constraints, the sign-off criteria, included), finds the optimum the workflow's function finds
    from the section itself (tiny budget, same seed: the same genes)."""
    import argparse

    from gearmesh.cli import build_parser
    from gearmesh.config import load_study
    from gearmesh.datasets.optimise import optimise_dataset
    from gearmesh.schema import defaults
    from gearmesh.settings import Constraints, Optimise

    study = load_study(ROOT / "config/config.yaml")
    section = {**study["optimise"]["optimised"], "population": 4, "generations": 1}
    tolerances = study["tolerances"]
    action = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    parser = action.choices["optimise"]
    flags = {a.dest: a.option_strings[0] for a in parser._actions if a.option_strings}
    flags |= {key: flag for _, (_, key, flag) in parser.get_default("setting_options").items()}
    declared = {**defaults(Optimise), **defaults(Constraints)}
    given = [(k, v) for key, value in section.items()
             for k, v in (value.items() if key == "constraints" else [(key, value)]) if declared.get(k) != v]
    assert {"pressure_factor", "root_stress_factor", "harmonic_factor", "impact_factor", "worst_impact_factor",
            "dynamic_factor", "pareto_objectives"} <= {k for k, _ in given}
    argv = ["optimise", str(ROOT / "config/pairs/helical_z29_71_m5.yaml"), "--json"]
    for key, value in given:
        argv += [flags[key], _cli_text(value)]  # KeyError: a key of the section without an option
    # the study's tolerances section: lead class, samples, sampling, ±2 µm on every amount, ±0.2 mm
    # on every relief length
    mod = tolerances["modification"]
    assert {v for k, v in mod.items() if k.endswith("_um")} == {2} and tolerances["seed"] == 0
    assert {v for k, v in mod.items() if k.endswith("_mm")} == {0.2}
    assert set(mod) == {"root_relief_um", "tip_relief_um", "crowning_um", "root_relief_length_mm",
                        "tip_relief_length_mm"}
    argv += ["--grade", str(tolerances["grade"]), "--tolerance-samples", str(tolerances["samples"]),
             "--sampling", tolerances["sampling"], "--amount-tolerance-um", "2", "--length-tolerance-mm", "0.2"]
    assert cli_main(argv) == 0
    cli = json.loads(capsys.readouterr().out)
    workflow = optimise_dataset(load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml"), **section,
                                impact=study["impact"], tolerances=tolerances)
    units = {"um": 1e-6, "mm": 1e-3}
    genes = [v * units[k.rsplit("_", 1)[1]] for k, v in cli["genes"].items()]
    np.testing.assert_allclose(genes, workflow["optimum_genes"].values, rtol=1e-12)
    assert cli["objective_value"] == pytest.approx(float(workflow["optimum_objective"]), rel=1e-12)
