"""Speed benchmarks: one JSON line per benchmark row.

Each row: name, median seconds of today's code over ``--repeats`` runs and, where a baseline
computes the same thing in the same process (an independent straightforward implementation, or the
same public function with its optimisation switched off, on the same inputs), its time, the
speed-up ratio and the equality: ``max_rel_diff`` of the results and ``equal``, whether it is
within 1e-6 (or within the bound a row states with the reason for its difference). The last line
sums up; the exit status is 1 when a benchmark crashed or an equality broke, never because of a
time.

``--smoke`` runs every benchmark once (one repeat, the slow baselines on a small part of their work,
the default study once with the job server), as CI does after the tests: a few minutes.
Run by hand: ``python benchmarks/run.py [NAME ...]``; never by pytest.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
import traceback

import numpy as np

from bench_dynamics import bench_damping_search, bench_default_sweep, bench_dynamics
from bench_impact import bench_impact
from bench_ltca import bench_ltca
from bench_optimise import bench_dynamic_objective, bench_optimise, bench_population_criteria
from bench_workflow import bench_imports, bench_study
from common import ROOT, bounded_difference, equality, median_seconds, timed_calls
from gearmesh.contact import contact_lines, mesh_cycle_rolls, tooth_pair_indices
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair

#: Slices of the pointwise contact-line sum (the contact-line paper's algorithm).
POINTWISE_SLICES = 200


def contact_length_pointwise(geom, roll, n_points: int = POINTWISE_SLICES) -> np.ndarray:
    """The contact-line paper's algorithm, written plainly: for every position and tooth pair, march across
    the face in ``n_points`` slices, keep the slices whose contact lies in the active zone and
    sum the distances between consecutive contact points (x, y, z)."""
    tb = math.tan(geom.base_helix_angle)
    h = 1 if geom.pair.helix_hand == "right" else -1
    z = np.linspace(-geom.face_width / 2, geom.face_width / 2, n_points)
    alpha = geom.operating_pressure_angle
    total = np.zeros(len(roll))
    for p, r in enumerate(roll):
        for j in tooth_pair_indices(geom):
            points = []
            for zk in z:
                s = r + j * geom.transverse_base_pitch + h * zk * tb
                if 0 <= s <= geom.path_of_contact:
                    rho = geom.rho_sap[0] + s
                    points.append((geom.base_radius[0] * math.cos(alpha) + rho * math.sin(alpha),
                                   -geom.base_radius[0] * math.sin(alpha) + rho * math.cos(alpha), zk))
            for a, b in zip(points, points[1:]):
                total[p] += math.dist(a, b)
    return total


def bench_contact_lines(repeats: int, smoke: bool = False) -> dict:
    """Contact lines at 360 positions against the contact-line paper's pointwise sum. The sum of chords of a
    straight line between its first and last slice inside the active zone is shorter than the line
    by less than one slice spacing Δz/cos βb at each end (a line shorter than that may hold no two
    slices and count nothing): 0 ≤ exact − pointwise ≤ 2·J·Δz/cos βb at each position, J the tooth
    pairs that can be in contact. That bound is checked (relative to the exact length)."""
    geom = pair_geometry(load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml"))
    roll = mesh_cycle_rolls(geom, 360)
    fast, _, result, _ = timed_calls(lambda: contact_lines(geom, roll).total_length, repeats)
    base, reference = median_seconds(lambda: contact_length_pointwise(geom, roll), 1 if smoke else max(3, repeats // 3))
    slice_line = geom.face_width / (POINTWISE_SLICES - 1) / math.cos(geom.base_helix_angle)
    bound = 2 * tooth_pair_indices(geom).size * slice_line
    short = result - reference
    holds = bool(np.all(short >= -1e-12 * result) and np.all(short <= bound))
    return {"name": "contact_lines_360_positions", "median_s": fast, "baseline": "the contact-line paper pointwise sum, 200 slices",
            "baseline_median_s": base, "ratio": base / fast,
            **bounded_difference(float(np.max(np.abs(short) / result)), float(np.max(bound / result)),
                                 "the pointwise sum misses the part of each line beyond its last slice at either "
                                 "end: 0 <= exact - pointwise <= 2 J dz / cos(beta_b) per position"),
            "equal": holds}


def bench_tvms(repeats: int, smoke: bool = False) -> dict:
    """Helical TVMS, 1000 slices x 360 positions (issue 3 target: under 0.2 s), tables built
    inside the timing, against the straightforward per-slice scipy quad (no tables) at one
    position, scaled to 360 positions; both with whole slices (rule 'centre'), the teeth alone:
    the low-fluctuation paper's pair file holds its gear bodies rigid, as the quadrature does."""
    from gearmesh.body import mesh_body_compliance
    from gearmesh.stiffness import mesh_stiffness, mesh_stiffness_reference

    geom = pair_geometry(load_pair(ROOT / "config/pairs/low_fluctuation_pair1.yaml"))
    if mesh_body_compliance(geom):
        raise RuntimeError("low_fluctuation_pair1 no longer holds its gear bodies rigid: the quadrature baseline has the "
                           "teeth alone; give the benchmark a pair whose bodies are rigid")
    method = "transition"  # the quad baseline is the potential-energy cantilever's
    t_fast, _ = median_seconds(lambda: mesh_stiffness(geom, 360, 1000, method, components=False, rule="centre"),
                               repeats)
    t_one, ref = median_seconds(lambda: mesh_stiffness_reference(geom, 1, 1000, method), 1 if smoke else 3)
    check = mesh_stiffness(geom, 1, 1000, method, components=False, rule="centre").K
    return {"name": "tvms_1000_slices_360_positions", "median_s": t_fast,
            "baseline": "per-slice scipy quad at each position (1 position timed, x360)",
            "baseline_median_s": 360 * t_one, "ratio": 360 * t_one / t_fast, **equality(check, ref)}


#: name: function(repeats, smoke) -> row or rows. The smoke run gives the slow baselines a small part
#: of their work (a few candidates, a few speeds), which is enough to check the equality.
BENCHMARKS = {
    "contact_lines": bench_contact_lines,
    "tvms": bench_tvms,
    "ltca": lambda repeats, smoke: bench_ltca(repeats),
    "dynamics": lambda repeats, smoke: bench_dynamics(repeats, baseline_speeds=8 if smoke else None),
    "dynamics_default": lambda repeats, smoke: bench_default_sweep(min(repeats, 3), subset=1 if smoke else 2,
                                                                   baseline_speeds=1 if smoke else None),
    "damping_search": lambda repeats, smoke: bench_damping_search(repeats),
    "impact": lambda repeats, smoke: bench_impact(repeats, subset=1 if smoke else 4),
    "optimise": lambda repeats, smoke: bench_optimise(min(repeats, 5), subset=1 if smoke else 4),
    "dynamic_objective": lambda repeats, smoke: bench_dynamic_objective(min(repeats, 3), subset=1 if smoke else 4),
    "population_criteria": lambda repeats, smoke: bench_population_criteria(min(repeats, 5)),
    "imports": lambda repeats, smoke: bench_imports(repeats),
    # a default-study run takes about a minute: repeats // 5 runs of each (one by default); the smoke
    # run only with the job server
    "study": lambda repeats, smoke: bench_study(1 if smoke else max(1, repeats // 5), servers=(True,) if smoke
                                                else (True, False)),
}


def broken(row: dict) -> list[str]:
    """What is wrong with a row's equality: a false ``equal`` (here or in a nested check), or a
    ``max_rel_diff`` without its verdict."""
    out = []
    for key, value in row.items():
        if isinstance(value, dict):
            out += [f"{key}.{b}" for b in broken(value)]
    if "max_rel_diff" in row and "equal" not in row:
        out.append("max_rel_diff without a verdict")
    if row.get("equal") is False:
        out.append(f"max_rel_diff {row.get('max_rel_diff')} beyond {row.get('bound', row.get('tolerance'))}")
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help=f"benchmarks to run (default all: {', '.join(BENCHMARKS)})")
    parser.add_argument("--repeats", type=int, default=7, help="timed runs of today's code (at least 3; 1 with --smoke)")
    parser.add_argument("--smoke", action="store_true",
                        help="every benchmark once, the slow baselines on a part of their work: fails on a crash or "
                             "a broken equality, never on a time (CI)")
    args = parser.parse_args()
    unknown = [n for n in args.names if n not in BENCHMARKS]
    if unknown:
        parser.error(f"unknown benchmark {unknown[0]!r}; use {', '.join(BENCHMARKS)}")
    repeats = 1 if args.smoke else max(3, args.repeats)
    failures, t0 = [], time.perf_counter()
    for name in args.names or BENCHMARKS:
        try:
            result = BENCHMARKS[name](repeats, args.smoke)
        except Exception:  # noqa: BLE001 (report every benchmark, then fail)
            traceback.print_exc()
            failures.append(f"{name}: crashed")
            continue
        for row in result if isinstance(result, list) else [result]:
            print(json.dumps(row), flush=True)
            failures += [f"{row['name']}: {b}" for b in broken(row)]
    print(json.dumps({"summary": "failed" if failures else "ok", "failures": failures,
                      "wall_s": time.perf_counter() - t0}), flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
