"""Impact benchmarks (seed 000's case pair, the default study's impact model), today's code against
the code before issue 17's kernel work (:mod:`bench_baseline`) in the same run.

Every model uses the slice cantilever tooth (:data:`TOOTH_METHOD`), so that both versions compute
the same numbers.

* ``impact_one_evaluation``: one mesh-in impact evaluation alone, :func:`gearmesh.impact.impact_static`
  + :func:`gearmesh.impact.impact_response` at 1000 N·m and 5000 rpm on a prepared model (what a
  load/speed map repeats).
* ``impact_robust_generation``: the impact part of one generation of the default study's robust
  optimisation — 40 candidates (seed 0 draws within seed 000's bounds) × 9 manufactured gears
  (nominal and the 8 tolerance samples) × 3 torques (400, 1000, 1600 N·m) in one batch
  (:func:`gearmesh.optimise.impact_values`, as the GA calls it); per evaluation = the batch over
  its 1080 (candidate, sample, torque) evaluations. Issue 17's targets: ≤ 1 ms per evaluation
  and ≤ 1 s per generation on the issue's machine (about 0.4 ms and 0.4 s on the machine of the
  work, 2.3× faster).

Each row: median_s (today), baseline_median_s (before), ratio, max_rel_diff of F_s, and the
process CPU time of both, median and least (cpu_s, cpu_min_s, baseline_…, cpu_min_ratio: on a
machine shared with other work the wall time includes waiting for a core, and the least CPU time
is the steadiest comparison). Run by hand: ``python benchmarks/run.py impact``.
"""

from __future__ import annotations

import json

import numpy as np

from bench_baseline import BASELINE_NAME, baseline_call
from common import ROOT, timed_calls

TORQUE, SPEED = 1000.0, 5000.0


def evaluation_alone(repeats: int):
    """(wall s, CPU s, F_s) of one evaluation alone (module docstring)."""
    from gearmesh.gear import load_pair, pair_geometry
    from gearmesh.impact import impact_model, impact_response, impact_static

    model = impact_model(pair_geometry(load_pair(ROOT / "config/pairs/seed000_case.yaml")), method=TOOTH_METHOD)

    def one():
        return impact_response(model, impact_static(model, [TORQUE]), [SPEED])[1].force[:, 0, 0]

    return timed_calls(one, repeats)


#: The tooth model of every benchmarked impact and dynamics model: the slice cantilever along the
#: hob fillet, which the code before issue 17's kernel work computes as today's does (the default
#: study has since moved to the finite-element tooth, whose tables the old code builds otherwise),
#: so that old and new differ by the kernels alone.
TOOTH_METHOD = "transition"


def study_section(name: str) -> dict:
    """The default study's ``optimise.NAME`` section with its impact model and tolerances, the
    tooth model :data:`TOOTH_METHOD`."""
    import yaml

    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    return {**config["optimise"][name], "impact": {**config["impact"], "method": TOOTH_METHOD},
            "tolerances": config["tolerances"]}


def robust_problem(constraints=None):
    """The default study's robust optimisation problem of the case pair (config/config.yaml's
    ``optimise.optimised``; ``constraints`` replaces its constraints) and 40 candidates' parameters."""
    from gearmesh.datasets.optimise import run_problem
    from gearmesh.gear import load_pair

    section = study_section("optimised")
    if constraints is not None:
        section["constraints"] = constraints
    prob = run_problem(load_pair(ROOT / "config/pairs/seed000_case.yaml"), **section)
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    params = prob.decode(low + (high - low) * np.random.default_rng(0).random((40, low.size)))
    return prob, params


def robust_generation(repeats: int):
    """(wall s, CPU s, F_s (1080,)) of the impact part of one robust generation (module docstring)."""
    from gearmesh.optimise import _manufactured_rows, impact_values

    prob, params = robust_problem(constraints={})
    rows, lead = _manufactured_rows(prob.model, prob.tolerance, params, prob.population_deviations)
    torques = prob.settings.objective_torques
    return timed_calls(lambda: impact_values(prob.model, prob.settings, rows, lead, torques).force.ravel(), repeats)


def compare(name: str, new, old, evaluations: int = 1, **extra) -> dict:
    """A benchmark row: today's (wall, CPU, result) against the baseline's (or None)."""
    wall, cpu, result, cpu_min = new
    row = {"name": name, "median_s": wall, "cpu_s": cpu, "cpu_min_s": cpu_min, **extra}
    if evaluations > 1:
        row.update({"evaluations": evaluations, "per_evaluation_s": wall / evaluations,
                    "per_evaluation_cpu_min_s": cpu_min / evaluations})
    if old is None:
        return {**row, "baseline": "none (no git history for the old code)"}
    b_wall, b_cpu, reference, b_cpu_min = old
    a, b = np.asarray(result, dtype=float), np.asarray(reference, dtype=float)
    ok = np.isfinite(a) & np.isfinite(b) & (b != 0)
    return {**row, "baseline": BASELINE_NAME, "baseline_median_s": b_wall, "baseline_cpu_s": b_cpu,
            "baseline_cpu_min_s": b_cpu_min, "ratio": b_wall / wall, "cpu_ratio": b_cpu / cpu,
            "cpu_min_ratio": b_cpu_min / cpu_min,
            "max_rel_diff": float(np.max(np.abs(a[ok] - b[ok]) / np.abs(b[ok]))) if ok.any() else float("nan"),
            "same_finite": bool(np.array_equal(np.isfinite(a), np.isfinite(b)))}


def bench_impact(repeats: int) -> list[dict]:
    alone = compare("impact_one_evaluation", evaluation_alone(repeats),
                    baseline_call("bench_impact", "evaluation_alone", repeats))
    n = max(3, repeats // 2)
    batch = compare("impact_robust_generation_40x9x3", robust_generation(n),
                    baseline_call("bench_impact", "robust_generation", n), evaluations=40 * 9 * 3)
    return [alone, batch]


if __name__ == "__main__":
    for row in bench_impact(5):
        print(json.dumps(row), flush=True)
