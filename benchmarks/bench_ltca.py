"""LTCA speed benchmark: one torque over a mesh cycle (64 positions, 50 points per line) of the
default study's ``relief`` variant of the case pair.

``bench_ltca(repeats)`` returns one JSON-able dict in the style of ``benchmarks/run.py``:
name, median_s (the whole :func:`gearmesh.ltca.ltca` call, tables and grid included),
solve_median_s (the load solve alone on a prepared model, as the GA and load sweeps use
it), the baseline and its median, the ratio and the equality of the loaded TE, the tangent mesh
stiffness and the point loads.

Baseline: the same :func:`gearmesh.ltca.ltca` call with its contact solve done the straightforward
way (:mod:`straightforward`: a Python loop over positions, each position's approach δ by scipy's
brentq on Σq(δ) = F and every point's load by its own brentq on c·q + A·q^0.9 = δ − g; no
vectorisation, no Newton), so that whatever the LTCA adds around the solve (the gear bodies, the
deflections) is on both sides. Run by hand: ``python benchmarks/bench_ltca.py``.
"""

from __future__ import annotations

import json
import sys

from gearmesh.contact_model import ContactModel
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair, variant_pair
from gearmesh.ltca import ltca, ltca_model

from common import CASE_PAIR, equality, median_seconds, study_config, timed_calls
from straightforward import replace_contact_solvers


def bench_ltca(repeats: int = 7) -> dict:
    geom = pair_geometry(variant_pair(load_pair(CASE_PAIR), "relief", study_config()["variants"]["relief"]))
    torque = 1000.0
    fast, _, result, _ = timed_calls(lambda: ltca(geom, [torque], 64, ContactModel(points=50)), repeats)
    model = ltca_model(geom, 64, ContactModel(points=50))
    solve, _, _, _ = timed_calls(lambda: ltca(geom, [torque], model=model), repeats)
    with replace_contact_solvers():
        base, reference = median_seconds(lambda: ltca(geom, [torque], 64, ContactModel(points=50)), 1)
    return {"name": "ltca_1_torque_64_positions_50_points", "median_s": fast, "solve_median_s": solve,
            "baseline": "the same ltca call, its contact solve by per-position brentq on the approach and "
                        "per-point brentq on each load (Python loops)",
            "baseline_median_s": base, "ratio": base / fast,
            **equality([result.lte, result.stiffness, result.load],
                       [reference.lte, reference.stiffness, reference.load])}


if __name__ == "__main__":
    print(json.dumps(bench_ltca(int(sys.argv[1]) if len(sys.argv) > 1 else 7)), flush=True)
