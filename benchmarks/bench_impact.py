"""Impact benchmarks on the default study's robust optimisation problem (the mesh-in impact paper's case pair,
config/config.yaml's ``optimise.optimised`` with the study's impact model and tolerances, built as
the optimise job builds it), each against a baseline that computes the same thing on the same model.

* ``impact_one_evaluation``: one mesh-in impact evaluation alone, :func:`gearmesh.impact.impact_static`
  + :func:`gearmesh.impact.impact_response` at 1000 N·m and 5000 rpm on the prepared model (what a
  load/speed map repeats). Baseline: the same calls with every contact solve and every inversion
  of the contact law done the straightforward way (:mod:`straightforward`).
* ``impact_robust_generation``: the impact part of one generation of the robust optimisation — its
  population's candidates (seed 0 draws within the gene bounds) × their manufactured gears (the nominal and the
  tolerance samples) × the objective torques in one batch (:func:`gearmesh.optimise.impact_values`,
  as the GA calls it). Baseline: the same function one manufactured gear at a time (the batching
  switched off), over the first ``subset`` candidates' gears, its time scaled to all.

Each row: median_s (today), baseline_median_s, ratio, the equality of F_s (and of the other
quantities compared), and the process CPU time (cpu_s, cpu_min_s: on a machine shared with other
work the least CPU time is the steadiest figure). Run by hand: ``python benchmarks/run.py impact``.
"""

from __future__ import annotations

import functools
import json

import numpy as np

from common import CASE_PAIR, equality, stage_settings, timed_calls
from straightforward import replace_contact_solvers

TORQUE, SPEED = 1000.0, 5000.0


@functools.lru_cache(maxsize=2)
def study_problem(run: str = "optimised"):
    """The default study's optimisation ``run`` of the case pair, set up as its optimise job does
    (:func:`gearmesh.datasets.optimise.run_problem` with the stage's settings), and one
    generation's candidates' parameters (the run's population, seed 0 draws within the gene bounds)."""
    from gearmesh.datasets.optimise import run_problem
    from gearmesh.pairfile import load_pair

    prob = run_problem(load_pair(CASE_PAIR), **stage_settings("optimise", run))
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    params = prob.decode(low + (high - low) * np.random.default_rng(0).random((prob.settings.population, low.size)))
    return prob, params


def row(name: str, new, old, scale: float = 1.0, evaluations: int = 1, **extra) -> dict:
    """A benchmark row: today's (wall, CPU, _, least CPU) against the baseline's, the baseline's
    times multiplied by ``scale`` (a baseline timed on a part of the work)."""
    wall, cpu, _, cpu_min = new
    b_wall, b_cpu, _, b_cpu_min = (v * scale if i != 2 else v for i, v in enumerate(old))
    out = {"name": name, "median_s": wall, "cpu_s": cpu, "cpu_min_s": cpu_min, **extra,
           "baseline_median_s": b_wall, "baseline_cpu_s": b_cpu, "ratio": b_wall / wall, "cpu_ratio": b_cpu / cpu,
           "cpu_min_ratio": b_cpu_min / cpu_min}
    if evaluations > 1:
        out.update({"evaluations": evaluations, "per_evaluation_s": wall / evaluations,
                    "per_evaluation_cpu_min_s": cpu_min / evaluations})
    return out


def bench_impact(repeats: int, subset: int = 4) -> list[dict]:
    from gearmesh.impact import impact_response, impact_static
    from gearmesh.optimise.evaluation import impact_values
    from gearmesh.optimise.objective import _manufactured_rows

    prob, params = study_problem()
    model = prob.model

    def one():
        static, resp = impact_response(model, impact_static(model, [TORQUE]), [SPEED])
        return np.concatenate([resp.force.ravel(), resp.force_energy_balance.ravel(), static.approach.ravel(),
                               static.tau.ravel(), static.lte_engagement.ravel()])

    new = timed_calls(one, repeats)
    with replace_contact_solvers() as replaced:
        old = timed_calls(one, 1, warm_up=False)
    alone = row("impact_one_evaluation", new, old, **equality(new[2], old[2]),
                baseline="the same impact_static + impact_response, every contact solve and inversion of the "
                         "contact law by brentq per row and per point (Python loops)", baseline_replaced=replaced,
                compared="F_s, its energy balance, the approach and roll of the touch, the LTE at the engagement")

    rows, lead = _manufactured_rows(model, prob.tolerance, params, prob.population_deviations)
    torques = prob.settings.objective_torques
    gears = rows.shape[0] // params.shape[0]
    part = min(subset, params.shape[0]) * gears

    def batch():
        return impact_values(model, prob.settings, rows, lead, torques).force

    def one_at_a_time():
        return np.concatenate([impact_values(model, prob.settings, rows[i:i + 1], lead[i:i + 1], torques).force
                               for i in range(part)])

    n = max(3, repeats // 2)
    new = timed_calls(batch, n)
    old = timed_calls(one_at_a_time, 1, warm_up=False)
    batch_row = row(f"impact_robust_generation_{params.shape[0]}x{gears}x{len(torques)}", new, old,
                    scale=rows.shape[0] / part, evaluations=rows.shape[0] * len(torques),
                    baseline=f"the same impact_values one manufactured gear at a time, the first {part} of "
                             f"{rows.shape[0]} gears, time scaled to all",
                    **equality(new[2][:part], old[2]))
    return [alone, batch_row]


if __name__ == "__main__":
    for r in bench_impact(5):
        print(json.dumps(r), flush=True)
