"""Benchmark of the dynamics stage: the 496-speed sweep of seed 001 pair 1 (500:50000:100 rpm,
T_out = 200 N·m, backlash 60 µm) as one RK4 batch, against a per-speed solve_ivp loop.

The baseline integrates the full 8-DOF equations (:func:`gearmesh.dynamics.reference_solution`,
DOP853, rtol 1e-6 — about the accuracy of the batch) at ``subset`` speeds spread over the
sweep, over the same transient and record window, and its time is scaled to 496 speeds.
Run by hand: ``python benchmarks/bench_dynamics.py`` (or from benchmarks/run.py).
"""

from __future__ import annotations

import json

import numpy as np

from gearmesh import dynamics as dy
from gearmesh.gear import load_pair, pair_geometry
from gearmesh.stiffness import mesh_stiffness

from common import ROOT, median_seconds


def bench_dynamics(repeats: int = 3, subset: int = 6, baseline_rtol: float = 1e-6) -> dict:
    """Median time of the whole sweep (stiffness + model + batch RK4) and the scaled baseline."""
    pair = load_pair(ROOT / "config/pairs/seed001_pair1.yaml")
    speeds = np.arange(500.0, 50000.0 + 1.0, 100.0)

    def sweep():
        geom = pair_geometry(pair)
        model = dy.pair_model(geom, 200.0, mesh_stiffness(geom, components=False).K)
        return model, dy.simulate(model, speeds)

    fast, (model, result) = median_seconds(sweep, repeats)
    pick = np.unique(np.linspace(0, speeds.size - 1, subset).round().astype(int))

    def baseline():
        return [dy.reference_solution(model, float(speeds[i]), rtol=baseline_rtol, atol=1e-13) for i in pick]

    base, refs = median_seconds(baseline, 1)
    base_scaled = base * speeds.size / pick.size
    diff = max(abs(float(result.dte_std[0, i]) / float(r["dte_std"][0]) - 1) for i, r in zip(pick, refs))
    return {"name": "dynamics_sweep_496_speeds", "median_s": fast,
            "baseline": f"per-speed solve_ivp (DOP853, rtol {baseline_rtol:g}) on {pick.size} speeds, scaled to "
                        f"{speeds.size}",
            "baseline_median_s": base_scaled, "ratio": base_scaled / fast,
            "max_rel_diff": diff, "rk4_steps": int(result.n_steps)}


if __name__ == "__main__":
    print(json.dumps(bench_dynamics()), flush=True)
