"""LTCA speed benchmark: one torque over a mesh cycle (64 positions, 50 points per line).

``bench_ltca(repeats)`` returns one JSON-able dict in the style of ``benchmarks/run.py``:
name, median_s (the whole :func:`gearmesh.ltca.ltca` call, tables and grid included),
solve_median_s (the load solve alone on a prepared model, as the GA and load sweeps use
it), the baseline and its median, the ratio and the largest relative LTE difference.

Baseline: the straightforward solve — a Python loop over positions, each position's
approach δ by scipy's brentq on Σq(δ) = F and every point's load by its own brentq on
c·q + A·q^0.9 = δ − g (no vectorisation, no Newton), on the same prepared model.
Run by hand: ``python benchmarks/bench_ltca.py``.
"""

from __future__ import annotations

import json
import sys

import numpy as np
from scipy.optimize import brentq

from gearmesh.gear import Modification, load_pair, pair_geometry
from gearmesh.ltca import ltca, ltca_model

from common import ROOT, median_seconds


def _baseline_lte(model, force: float) -> np.ndarray:
    law = model.law
    p = model.grid.roll.size - 1
    out = np.empty(p)
    for i in range(p):
        gap = model.grid.gap[i].ravel()
        comp = model.compliance[i].ravel()
        ok = np.isfinite(gap)
        gap, comp = gap[ok], comp[ok]

        def total(delta):
            s = 0.0
            for g, c in zip(gap, comp):
                d = delta - g
                if d > 0:
                    s += brentq(lambda q: c * q + law.coefficient * q**law.exponent - d, 0.0, d / c, xtol=1e-12)
            return s - force

        lo = gap.min()
        out[i] = brentq(total, lo, lo + comp[np.argmin(gap)] * force + law.coefficient * force**law.exponent,
                        xtol=1e-15, rtol=1e-13)
    return out


def bench_ltca(repeats: int = 7) -> dict:
    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    mod = (Modification(tip_relief=20e-6, tip_relief_length=3e-3, crowning=10e-6), Modification())
    geom = pair_geometry(pair.with_changes(modification=mod))
    torque = 1000.0
    fast, result = median_seconds(lambda: ltca(geom, [torque], positions=64, points=50), repeats)
    model = ltca_model(geom, positions=64, points=50)
    solve, _ = median_seconds(lambda: ltca(geom, [torque], model=model), repeats)
    force = torque / geom.base_radius[0]
    base, reference = median_seconds(lambda: _baseline_lte(model, force), 1)
    return {"name": "ltca_1_torque_64_positions_50_points", "median_s": fast, "solve_median_s": solve,
            "baseline": "per-position brentq on the approach, per-point brentq on each load (Python loops)",
            "baseline_median_s": base, "ratio": base / fast,
            "max_rel_diff": float(np.max(np.abs(result.lte[0] - reference) / reference))}


if __name__ == "__main__":
    print(json.dumps(bench_ltca(int(sys.argv[1]) if len(sys.argv) > 1 else 7)), flush=True)
