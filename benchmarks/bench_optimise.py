"""Optimiser speed benchmark (seed 000 case pair, 1000 N·m, 5000 rpm, full impact model).

``bench_optimise(repeats)`` returns one JSON-able dict in the style of ``benchmarks/run.py``:
median_s — one GA generation, 40 candidates evaluated as one batch on the prepared impact
model (:func:`gearmesh.optimise.evaluate`, as the GA calls it); the baseline — the same 40
candidates one by one without reuse (a pair and an impact model built per candidate, then
its impact at the design point), its time, the ratio and the largest relative difference
of F_s; full_run_s — the whole 40 × 30 GA (median of ``full_repeats`` runs, no random
baseline) with its evaluations and optimum. Run by hand: ``python benchmarks/bench_optimise.py``.
"""

from __future__ import annotations

import json
import sys

import numpy as np

from gearmesh.dynamics.population import dynamic_factors, population_dynamics
from gearmesh.gear import Modification, load_pair, pair_geometry
from gearmesh.impact import impact_model, impact_response, impact_static
from gearmesh.optimise import check_settings, evaluate, optimise, problem
from gearmesh.surface import MODIFICATION_FIELDS, modification_parameters

from common import ROOT, median_seconds

TORQUE, SPEED = 1000.0, 5000.0


def _one_by_one(pair, params: np.ndarray) -> np.ndarray:
    """F_s of each candidate with nothing reused: its pair, geometry and impact model built anew."""
    out = np.empty(len(params))
    for k, p in enumerate(params):
        mods = tuple(Modification(**{f: float(p[g, i]) for i, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
        model = impact_model(pair_geometry(pair.with_changes(modification=mods)))
        _, resp = impact_response(model, impact_static(model, [TORQUE]), [SPEED])
        out[k] = resp.force[0, 0, 0]
    return out


def bench_optimise(repeats: int = 5, full_repeats: int = 1) -> dict:
    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    model = impact_model(pair_geometry(pair))
    prob = problem(model, check_settings(population=40, generations=30, seed=0, torque=TORQUE, speed_rpm=SPEED,
                                         random_baseline=False))
    rng = np.random.default_rng(0)
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    params = prob.decode(low + (high - low) * rng.random((40, low.size)))
    batch, ev = median_seconds(lambda: evaluate(prob, params), repeats)
    base, reference = median_seconds(lambda: _one_by_one(pair, params), 1)
    full, res = median_seconds(lambda: optimise(prob), full_repeats)
    ok = np.isfinite(reference) & np.isfinite(ev.force[:, 0]) & (reference > 0)
    return {"name": "optimise_generation_40_candidates", "median_s": batch,
            "baseline": "the same 40 candidates one by one, pair and impact model built per candidate",
            "baseline_median_s": base, "ratio": base / batch,
            "max_rel_diff": float(np.max(np.abs(ev.force[ok, 0] - reference[ok]) / reference[ok])),
            "full_run_40x30_s": full, "full_run_evaluations": res.evaluations,
            "full_run_optimum_force_N": float(res.optimum_evaluation.force[0, 0]),
            "standard_force_N": float(prob.standard.force[0, 0])}


DYNAMIC_TORQUES, DYNAMIC_SPEEDS = (400.0, 1000.0, 1600.0), (1000.0, 5000.0, 15000.0)


def _dynamic_one_by_one(pair, params: np.ndarray, setup) -> np.ndarray:
    """K_v of each candidate with nothing shared: its pair, geometry, table and models built anew."""
    geoms = []
    for p in params:
        mods = tuple(Modification(**{f: float(p[g, i]) for i, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
        geoms.append(pair_geometry(pair.with_changes(modification=mods)))
    return np.vstack([dynamic_factors(population_dynamics(g, DYNAMIC_TORQUES, DYNAMIC_SPEEDS, backlash=setup.backlash),
                                      np.asarray(modification_parameters(g))[None], np.zeros((1, 2)))
                      for g in geoms])


def bench_dynamic_objective(repeats: int = 3) -> dict:
    """One generation of 40 candidates of the dynamic factor (3 torques, nominal gears; the default
    study's constraint) from one shared table layout, against the same candidates one by one."""
    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    geom = pair_geometry(pair)
    model = impact_model(geom)
    prob = problem(model, check_settings(population=40, generations=30, seed=0, torque=TORQUE, speed_rpm=SPEED))
    rng = np.random.default_rng(0)
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    params = prob.decode(low + (high - low) * rng.random((40, low.size)))
    setup = population_dynamics(geom, DYNAMIC_TORQUES, DYNAMIC_SPEEDS, backlash=60e-6)
    batch, kv = median_seconds(lambda: dynamic_factors(setup, params, np.zeros((40, 2))), repeats)
    base, reference = median_seconds(lambda: _dynamic_one_by_one(pair, params, setup), 1)
    return {"name": "dynamic_objective_generation_40_candidates", "median_s": batch,
            "baseline": "the same 40 candidates one by one, pair, table layout and models built per candidate",
            "baseline_median_s": base, "ratio": base / batch,
            "max_rel_diff": float(np.max(np.abs(kv - reference) / reference))}


if __name__ == "__main__":
    print(json.dumps(bench_optimise(int(sys.argv[1]) if len(sys.argv) > 1 else 5)), flush=True)
    print(json.dumps(bench_dynamic_objective()), flush=True)
