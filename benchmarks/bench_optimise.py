"""Optimiser benchmarks on the default study's two optimisations of the mesh-in impact paper's case pair
(config/config.yaml's ``optimise`` section, each set up as its optimise job sets it up:
:func:`bench_impact.study_problem`), each against a baseline that computes the same thing.

``bench_optimise(repeats)``:

* ``optimise_generation_<N>_candidates``: one generation of the ``design_point`` run (the single-point
  objective) — its population's candidates (seed 0 draws within the gene bounds) evaluated as one
  batch (:func:`gearmesh.optimise.evaluate`, as the GA calls it).
* ``robust_generation_<N>_candidates``: one generation of the ``optimised`` run as the GA evaluates
  it — every candidate × manufactured gear × spectrum torque of impact, the loaded-contact criteria
  over the manufactured gears and the dynamic factor of each candidate at the spectrum torques.
  Baseline of both: the same :func:`gearmesh.optimise.evaluate` one candidate at a time (the
  batching switched off), over the first ``subset`` candidates, its time scaled to all; equality of
  the objective J, F_s, the constraints' violation and the dynamic factor.
* ``default_study_ga_runs``: both GA runs of the default study, set-up included, as the optimise
  jobs run them (without writing the files): the summed time; equality of each run's optimum J as
  the run's batch evaluation found it against the optimum evaluated alone afterwards.

``bench_population_criteria(repeats)``: ``population_criteria_generation_<N>_candidates``, the
loaded-contact criteria of one generation of the ``optimised`` run over its manufactured population
(:func:`gearmesh.impact.ltca_criteria` with its samples started from their nominal, the tabulated
contact law). Baseline: the same function with the tabulated solve replaced by the package's exact
:func:`gearmesh.ltca_solve.solve_contact` (Newton on every point's own inversion) and every gear solved
from scratch (``samples=1``); equality of LTE p-p, flank and edge pressure and root stress.

``bench_dynamic_objective(repeats)``: ``dynamic_objective_generation_<N>_candidates``, the dynamic
factor K_v of the ``optimised`` run's candidates at the spectrum torques (nominal gears; the
contact-driven 8-DOF pair over the run's speed range and each candidate's resonances,
:func:`gearmesh.dynamics.population.dynamic_factors`). Baseline: the same function with every speed's
steady state found by the physical-time transient instead of by shooting (``steady_state:
transient``), over the first ``subset`` candidates, its time scaled to all; equality of K_v.

Every row has median_s / cpu_s (today) and baseline_median_s / baseline_cpu_s, their ratios and
the equality. Run by hand: ``python benchmarks/run.py optimise population_criteria dynamic_objective``.
"""

from __future__ import annotations

import json
import sys
from dataclasses import replace

import numpy as np

from bench_impact import row, study_problem
from common import equality, timed_calls
from straightforward import exact_for_tabulated


def _evaluated(ev) -> list[np.ndarray]:
    """The compared quantities of an :class:`gearmesh.optimise.Evaluation`."""
    return [ev.objective, ev.force, ev.violation, ev.dynamic_factor]


def generation(run: str, repeats: int, subset: int) -> dict:
    """One generation of ``run`` in one batch against one candidate at a time (module docstring)."""
    from gearmesh.optimise import evaluate

    prob, params = study_problem(run)
    part = min(subset, params.shape[0])
    new = timed_calls(lambda: _evaluated(evaluate(prob, params)), repeats)
    old = timed_calls(lambda: [np.concatenate(v) for v in zip(*(_evaluated(evaluate(prob, params[i:i + 1]))
                                                                  for i in range(part)))], 1, warm_up=False)
    name = "optimise_generation" if run == "design_point" else "robust_generation"
    return row(f"{name}_{params.shape[0]}_candidates", new, old, scale=params.shape[0] / part,
               evaluations=params.shape[0], run=run,
               baseline=f"the same evaluate one candidate at a time, the first {part} of {params.shape[0]}, "
                        "time scaled to all",
               **equality([a[:part] for a in new[2]], old[2]))


def study_runs():
    """(wall s, CPU s, {run: (optimum J of the run, optimum J evaluated alone)}, CPU s) of both GA
    runs of the default study, set-up included (module docstring)."""
    from gearmesh.datasets.optimise import run_problem
    from gearmesh.pairfile import load_pair
    from gearmesh.optimise import evaluate, optimise

    from common import CASE_PAIR, stage_settings, study_config

    pair = load_pair(CASE_PAIR)
    results = {}

    def both():
        for name in study_config()["optimise"]:
            results[name] = optimise(run_problem(pair, **stage_settings("optimise", name)))

    wall, cpu, _, cpu_min = timed_calls(both, 1, warm_up=False)  # as a job runs them: once
    found = {}
    for name, result in results.items():
        h = result.history.arrays()
        genes, objective = h["genes"].reshape(-1, h["genes"].shape[-1]), h["objective"].reshape(-1)
        at = int(np.flatnonzero(np.all(genes == result.optimum_genes, axis=1))[0])
        found[name] = (objective[at], float(evaluate(result.problem, result.optimum[None]).objective[0]))
    return wall, cpu, found, cpu_min


def bench_optimise(repeats: int = 3, subset: int = 4) -> list[dict]:
    n = max(1, repeats)
    rows = [generation("design_point", n, subset), generation("optimised", 1, subset)]
    wall, cpu, found, cpu_min = study_runs()
    runs = sorted(found)
    rows.append({"name": "default_study_ga_runs", "median_s": wall, "cpu_s": cpu, "cpu_min_s": cpu_min,
                 "runs": runs, "compared": "each run's optimum J as its batch evaluation found it against the "
                                           "optimum evaluated alone afterwards",
                 **equality([found[k][0] for k in runs], [found[k][1] for k in runs])})
    return rows


def bench_population_criteria(repeats: int = 3, subset: int = 4) -> dict:
    from gearmesh.impact import ltca_criteria
    from gearmesh.optimise.objective import _manufactured_rows

    prob, params = study_problem()
    rows, lead = _manufactured_rows(prob.model, prob.tolerance, params, prob.population_deviations)
    torques, samples = prob.settings.objective_torques, rows.shape[0] // params.shape[0]

    def criteria(n: int, samples: int):
        c = ltca_criteria(prob.model, torques, rows[:n], lead_slope=lead[:n], samples=samples)
        return [c.lte_peak_to_peak, c.flank_pressure, c.edge_pressure, c.root_stress]

    new = timed_calls(lambda: criteria(rows.shape[0], samples), repeats)
    with exact_for_tabulated() as replaced:
        old = timed_calls(lambda: criteria(rows.shape[0], 1), 1, warm_up=False)
    return row(f"population_criteria_generation_{params.shape[0]}_candidates", new, old,
               evaluations=rows.shape[0], baseline="the same ltca_criteria, every gear solved from scratch by the "
                                                   "exact solve_contact (no tabulated law, no start from the nominal)",
               baseline_replaced=replaced, **equality(new[2], old[2]))


def bench_dynamic_objective(repeats: int = 3, subset: int = 4) -> dict:
    from gearmesh.dynamics.population import dynamic_factors

    prob, params = study_problem()
    pd = prob.dynamics
    lead = np.broadcast_to(np.asarray(prob.model.lead_slope, dtype=float), (params.shape[0], 2))
    part = min(subset, params.shape[0])
    transient = replace(pd, settings=replace(pd.settings, steady_state="transient"))
    new = timed_calls(lambda: dynamic_factors(pd, params, lead), repeats)
    old = timed_calls(lambda: dynamic_factors(transient, params[:part], lead[:part]), 1, warm_up=False)
    return row(f"dynamic_objective_generation_{params.shape[0]}_candidates", new, old, scale=params.shape[0] / part,
               evaluations=params.shape[0],
               baseline=f"the same dynamic_factors, every steady state by the physical-time transient instead of "
                        f"shooting, the first {part} of {params.shape[0]} candidates, time scaled to all",
               **equality(new[2][:part], old[2]))


if __name__ == "__main__":
    for r in bench_optimise(int(sys.argv[1]) if len(sys.argv) > 1 else 3) + [bench_population_criteria(),
                                                                             bench_dynamic_objective()]:
        print(json.dumps(r), flush=True)
