"""Optimiser benchmarks (seed 000's case pair, the default study), today's code against the code
before issue 17's kernel work (:mod:`bench_baseline`) in the same run.

``bench_optimise(repeats)``:

* ``optimise_generation_40_candidates``: one GA generation of seed 000's single-point objective —
  40 candidates (seed 0 draws within the gene bounds) evaluated as one batch on the prepared
  impact model at 1000 N·m and 5000 rpm (:func:`gearmesh.optimise.evaluate`, as the GA calls it);
  max_rel_diff of F_s.
* ``robust_generation_with_dynamic_constraint``: one generation of the default study's
  ``optimised`` run as the GA evaluates it — 40 candidates × 9 manufactured gears × 3 torques of
  impact, and the dynamic factor of each candidate at the 3 torques; max_rel_diff of the
  objective J.
* ``default_study_ga_runs``: both GA runs of the default study (``optimised``: robust, dynamic
  constraint, 30 × 12; ``design_point``: 40 × 30), set-up included, as the optimise jobs run them
  (without writing the files): the summed time, whether the GA took the same path (every
  generation's genes identical) and the optimum, and max_rel_diff of the optima's objective J.
  Issue 17's target: ≤ 20 s on the issue's machine (≤ 8.5 s on the machine of the work).

``bench_population_criteria(repeats)``: ``population_criteria_generation_30_candidates``, the
loaded-contact criteria of one generation of the default study's ``optimised`` run over its
manufactured population (30 candidates × 9 gears × 3 torques × 32 positions, the study's impact
model: :func:`gearmesh.impact.ltca_criteria` with its samples started from their nominal), against
the straightforward evaluation in the same run (:func:`straightforward_criteria`: one exact
:func:`gearmesh.ltca.solve_contact` over every grid point of every gear, the stresses by
:func:`gearmesh.stress.contact_stress` and :func:`gearmesh.stress.iso_root_stress_slices` of the
loads, as ltca_criteria did before issue 27's population default); max_rel_diff over LTE p-p,
flank, edge and root stress.

``bench_dynamic_objective(repeats)``: ``dynamic_objective_generation_40_candidates``, the dynamic
factor K_v of 40 candidates at the 3 torques of the default study (nominal gears; the
contact-driven 8-DOF pair over 1000–15000 rpm and each candidate's resonances), the default
study's constraint; max_rel_diff of K_v.

Every row has median_s / cpu_s (today) and baseline_median_s / baseline_cpu_s (before), their
ratios, and the differences; every model the slice cantilever tooth (:data:`bench_impact.TOOTH_METHOD`). Run by hand: ``python benchmarks/run.py optimise dynamic_objective``.
"""

from __future__ import annotations

import json
import sys

import numpy as np

from bench_baseline import baseline_call
from bench_impact import TOOTH_METHOD, compare, robust_problem, study_section
from common import ROOT, timed_calls

TORQUE, SPEED = 1000.0, 5000.0


def point_generation(repeats: int):
    """(wall s, CPU s, F_s (40,)) of one generation of the single-point objective."""
    from gearmesh.gear import load_pair, pair_geometry
    from gearmesh.impact import impact_model
    from gearmesh.optimise import check_settings, evaluate, problem

    model = impact_model(pair_geometry(load_pair(ROOT / "config/pairs/seed000_case.yaml")), method=TOOTH_METHOD)
    prob = problem(model, check_settings(population=40, generations=30, seed=0, torque=TORQUE, speed_rpm=SPEED))
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    params = prob.decode(low + (high - low) * np.random.default_rng(0).random((40, low.size)))
    return timed_calls(lambda: np.asarray(evaluate(prob, params).force).reshape(40, -1)[:, 0], repeats)


def robust_generation(repeats: int):
    """(wall s, CPU s, J (40,)) of one generation of the default study's ``optimised`` run."""
    from gearmesh.optimise import evaluate

    prob, params = robust_problem()
    return timed_calls(lambda: evaluate(prob, params).objective, repeats)


def dynamic_generation(repeats: int):
    """(wall s, CPU s, K_v (40, 3)) of the dynamic factors of 40 candidates (module docstring)."""
    from gearmesh.dynamics.population import dynamic_factors

    prob, params = robust_problem()
    lead = np.zeros((params.shape[0], 2))
    return timed_calls(lambda: dynamic_factors(prob.dynamics, params, lead), repeats)


def study_runs(repeats: int):
    """(wall s, CPU s, (genes of every generation, optimum genes, optimum J) per run) of both GA runs
    of the default study, set-up included."""
    from gearmesh.datasets.optimise import run_problem
    from gearmesh.gear import load_pair
    from gearmesh.optimise import optimise

    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")

    def both():
        out = {}
        for name in ("optimised", "design_point"):
            result = optimise(run_problem(pair, **study_section(name)))
            out[name] = (result.history.arrays()["genes"], result.optimum_genes,
                         float(result.optimum_evaluation.objective[0]))
        return out

    return timed_calls(both, repeats, warm_up=False)  # as a job runs them: once, compiled loops from the cache


def bench_optimise(repeats: int = 3) -> list[dict]:
    n = max(3, repeats)
    rows = [compare("optimise_generation_40_candidates", point_generation(n),
                    baseline_call("bench_optimise", "point_generation", n), evaluations=40),
            compare("robust_generation_with_dynamic_constraint", robust_generation(1),
                    baseline_call("bench_optimise", "robust_generation", 1), evaluations=40)]
    new, old = study_runs(1), baseline_call("bench_optimise", "study_runs", 1)
    summary = lambda runs: np.array([runs[k][2] for k in ("optimised", "design_point")])  # noqa: E731
    row = compare("default_study_ga_runs", (new[0], new[1], summary(new[2]), new[3]),
                  None if old is None else (old[0], old[1], summary(old[2]), old[3]),
                  runs="optimised (robust, dynamic constraint, 30 x 12) + design_point (40 x 30)")
    if old is not None:
        row["same_path"] = all(np.array_equal(new[2][k][0], old[2][k][0], equal_nan=True) for k in new[2])
        row["same_optimum"] = all(np.array_equal(new[2][k][1], old[2][k][1]) for k in new[2])
    rows.append(row)
    return rows


def straightforward_criteria(model, torques, params, lead) -> np.ndarray:
    """(C, 4, T) LTE p-p, flank and edge pressure, root stress of gears ``params`` (C, 2, 6) with
    lead slopes ``lead`` (C, 2): every grid point of every gear in one exact solve, stresses of the
    loads (the baseline of :func:`population_criteria`)."""
    from gearmesh.ltca import solve_contact
    from gearmesh.stress import contact_stress, iso_root_stress_slices, pair_edge_radius
    from gearmesh.tca import SeparationBasis, basis_gap

    g, lt = model.geom, model.ltca
    grid, nc, nt = lt.grid, params.shape[0], len(torques)
    p = grid.gap.shape[0] - 1
    basis = SeparationBasis(*(getattr(grid.basis, f)[:p] for f in SeparationBasis.__dataclass_fields__))
    gap = basis_gap(g, basis, np.broadcast_to(grid.z, basis.base.shape), lead[:, None, None, None, :],
                    params[:, None, None, None, :, :]).reshape(nc, 1, p, -1)
    m = gap.shape[-1]
    force = np.asarray(torques) / g.base_radius[0]
    q, delta, _, _ = solve_contact(np.broadcast_to(gap, (nc, nt, p, m)).reshape(-1, m),
                                   np.broadcast_to(lt.compliance[:p].reshape(p, m), (nc, nt, p, m)).reshape(-1, m),
                                   np.broadcast_to(force[:, None], (nc, nt, p)).reshape(-1), lt.law)
    w = q.reshape(nc, nt, *basis.base.shape) / grid.dz
    r1, r2 = grid.rho_pinion[:p], grid.rho_gear[:p]
    c = contact_stress(g, w, grid.region[:p], r1, r2, pair_edge_radius(g))
    root = np.maximum(iso_root_stress_slices(g, 0, w, r1), iso_root_stress_slices(g, 1, w, r2))
    return np.stack([np.ptp(delta.reshape(nc, nt, p), axis=-1), np.where(c.edge, 0.0, c.pressure).max(axis=(2, 3, 4)),
                     np.where(c.edge, c.pressure, 0.0).max(axis=(2, 3, 4)), root.max(axis=(2, 3, 4))], axis=1)


def population_criteria(repeats: int) -> tuple:
    """Today's and the straightforward (wall s, CPU s, criteria (30, 4, 3), least CPU s) of one
    generation's criteria over the manufactured population (module docstring)."""
    from gearmesh.impact import ltca_criteria
    from gearmesh.optimise import _manufactured_rows

    prob, params = robust_problem()
    params = params[:30]
    rows, lead = _manufactured_rows(prob.model, prob.tolerance, params, prob.population_deviations)
    torques, samples = prob.settings.objective_torques, rows.shape[0] // params.shape[0]

    def today():
        c = ltca_criteria(prob.model, torques, rows, lead_slope=lead, samples=samples)
        return np.stack([c.lte_peak_to_peak, c.flank_pressure, c.edge_pressure, c.root_stress], axis=1)

    return (timed_calls(today, repeats),
            timed_calls(lambda: straightforward_criteria(prob.model, torques, rows, lead), repeats))


def bench_population_criteria(repeats: int = 3) -> dict:
    new, old = population_criteria(repeats)
    row = compare("population_criteria_generation_30_candidates", new, old, evaluations=30 * 9)
    return {**row, "baseline": "straightforward: one exact solve_contact over every grid point, stresses of the loads"}


def bench_dynamic_objective(repeats: int = 3) -> dict:
    return compare("dynamic_objective_generation_40_candidates", dynamic_generation(repeats),
                   baseline_call("bench_optimise", "dynamic_generation", repeats), evaluations=40)


if __name__ == "__main__":
    for row in bench_optimise(int(sys.argv[1]) if len(sys.argv) > 1 else 3) + [bench_population_criteria(),
                                                                               bench_dynamic_objective()]:
        print(json.dumps(row), flush=True)
