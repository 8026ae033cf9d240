"""Speed benchmarks: one JSON line per benchmark.

Each line: name, median seconds of >= 3 runs, and where a straightforward baseline is run
in the same process, its median, the speed-up ratio and the largest relative difference of
the results. Run by hand (``python benchmarks/run.py``), never by pytest.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np

from bench_dynamics import bench_damping_search, bench_default_sweep, bench_dynamics
from bench_impact import bench_impact
from bench_ltca import bench_ltca
from bench_optimise import bench_dynamic_objective, bench_optimise, bench_population_criteria
from bench_workflow import bench_imports, bench_study
from common import ROOT, median_seconds
from gearmesh.contact import contact_lines, mesh_cycle_rolls, tooth_pair_indices
from gearmesh.gear import load_pair, pair_geometry


def contact_length_pointwise(geom, roll, n_points: int = 200) -> np.ndarray:
    """Seed 002's algorithm, written plainly: for every position and tooth pair, march across
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


def bench_contact_lines(repeats: int) -> dict:
    geom = pair_geometry(load_pair(ROOT / "config/pairs/seed000_case.yaml"))
    roll = mesh_cycle_rolls(geom, 360)
    fast, result = median_seconds(lambda: contact_lines(geom, roll).total_length, repeats)
    base, reference = median_seconds(lambda: contact_length_pointwise(geom, roll), max(3, repeats // 3))
    # The pointwise sum misses the part of each line between the last slice and the zone edge,
    # so the two agree to within about one slice length, not to round-off.
    return {"name": "contact_lines_360_positions", "median_s": fast, "baseline": "seed 002 pointwise sum, 200 slices",
            "baseline_median_s": base, "ratio": base / fast,
            "max_rel_diff": float(np.max(np.abs(result - reference) / result))}


def bench_tvms(repeats: int) -> dict:
    """Helical TVMS, 1000 slices x 360 positions (issue 3 target: under 0.2 s), tables built
    inside the timing, against the straightforward per-slice scipy quad (no tables) at one
    position, scaled to 360 positions; both with whole slices (rule 'centre')."""
    from gearmesh.stiffness import mesh_stiffness, mesh_stiffness_reference

    geom = pair_geometry(load_pair(ROOT / "config/pairs/seed001_pair1.yaml"))
    method = "transition"  # the quad baseline is the potential-energy cantilever's
    t_fast, _ = median_seconds(lambda: mesh_stiffness(geom, 360, 1000, method, components=False, rule="centre"),
                               repeats)
    t_one, ref = median_seconds(lambda: mesh_stiffness_reference(geom, 1, 1000, method), 3)
    check = mesh_stiffness(geom, 1, 1000, method, components=False, rule="centre").K
    return {"name": "tvms_1000_slices_360_positions", "median_s": t_fast,
            "baseline": "per-slice scipy quad at each position (1 position timed, x360)",
            "baseline_median_s": 360 * t_one, "ratio": 360 * t_one / t_fast,
            "max_rel_diff": float(np.max(np.abs(check - ref) / ref))}


BENCHMARKS = {"contact_lines": bench_contact_lines, "tvms": bench_tvms, "ltca": bench_ltca,
              "dynamics": bench_dynamics, "dynamics_default": lambda repeats: bench_default_sweep(min(repeats, 3)),
              "damping_search": bench_damping_search,
              "impact": bench_impact,
              "optimise": lambda repeats: bench_optimise(min(repeats, 5)),
              "dynamic_objective": lambda repeats: bench_dynamic_objective(min(repeats, 3)),
              "population_criteria": lambda repeats: bench_population_criteria(min(repeats, 5)),
              "imports": bench_imports,
              # a default-study run takes about a minute: repeats // 5 runs of each (one by default)
              "study": lambda repeats: bench_study(max(1, repeats // 5))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help=f"benchmarks to run (default all: {', '.join(BENCHMARKS)})")
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    for name in args.names or BENCHMARKS:
        result = BENCHMARKS[name](max(3, args.repeats))
        for row in result if isinstance(result, list) else [result]:
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
