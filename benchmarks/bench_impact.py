"""Impact benchmark: one mesh-in impact evaluation (one torque, one speed) of seed 000's pair.

``bench_impact(repeats)`` returns one JSON-able dict in the style of ``benchmarks/run.py``:
median_s of :func:`gearmesh.impact.impact_static` + :func:`gearmesh.impact.impact_response`
on a prepared model (what a load/speed map and the GA repeat), batch_median_s for 40
modifications in one call (one GA generation) and its per-candidate cost, against the
straightforward baseline: the same evaluation building everything from scratch (slice tables,
LTCA grid, window) each time, as a script calling the stage per load would. Results must be
identical (max_rel_diff of F_s). Run by hand: ``python benchmarks/bench_impact.py``.
"""

from __future__ import annotations

import json

import numpy as np

from gearmesh.gear import load_pair, pair_geometry
from gearmesh.impact import impact_model, impact_response, impact_static

from common import ROOT, median_seconds


def _evaluate(model, params=None):
    st = impact_static(model, [1000.0], params)
    return impact_response(model, st, [5000.0])[1].force[:, 0, 0]


def bench_impact(repeats: int) -> dict:
    geom = pair_geometry(load_pair(ROOT / "config/pairs/seed000_case.yaml"))
    model = impact_model(geom)
    fast, result = median_seconds(lambda: _evaluate(model), repeats)
    base, reference = median_seconds(lambda: _evaluate(impact_model(geom)), max(3, repeats // 2))
    rng = np.random.default_rng(0)
    mn, b = geom.pair.normal_module, geom.face_width
    params = np.zeros((40, 2, 6))
    params[:, 0] = np.column_stack([rng.uniform(0.001, 0.015, 40) * mn, rng.uniform(0.001, 0.015, 40) * mn,
                                    rng.uniform(0.1, 0.8, 40) * mn, rng.uniform(0.1, 0.8, 40) * mn,
                                    rng.uniform(0.001, 0.015, 40) * mn, rng.uniform(0.01, 0.5, 40) * b])
    batch, _ = median_seconds(lambda: _evaluate(model, params), max(3, repeats // 2))
    return {"name": "impact_one_torque_one_speed", "median_s": fast, "batch_40_median_s": batch,
            "batch_per_candidate_s": batch / 40, "baseline": "model rebuilt for every evaluation",
            "baseline_median_s": base, "ratio": base / fast,
            "max_rel_diff": float(np.max(np.abs(result - reference) / np.abs(reference)))}


if __name__ == "__main__":
    print(json.dumps(bench_impact(5)))
