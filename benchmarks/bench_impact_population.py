"""What the manufactured gears' loaded contact (issue 27, the sign-off table's population basis)
adds to the default study's impact jobs: each variant's impact.nc built as the workflow builds it
(config/config.yaml's impact and tolerances sections, the finite-element tooth with the study's
FE tables from results/ when a run has made them, else the slice cantilever) with the population's
criteria (A) and with :func:`gearmesh.datasets.impact._add_population_contact` skipped (B), in one
run, alternating; the median of ``repeats`` calls each, wall and process CPU. On a machine shared
with other work the A/B difference of whole jobs is noisy; the last line times the addition alone
(the manufactured gears' :func:`gearmesh.impact.ltca_criteria` on a prepared model of the
``standard`` job, five torques × nine gears), median of 5 calls after a warm-up.

Run by hand after ``snakemake --cores 2``: ``python benchmarks/bench_impact_population.py [repeats]``.
One JSON line per variant and one for the study's four jobs together.
"""

from __future__ import annotations

import json
import statistics
import sys
import time

import xarray as xr
import yaml

from common import ROOT

RESULTS = ROOT / "results/impact_case/helical_z29_71_m5"


def _job(variant: str, config: dict):
    """The impact job of ``variant``: a no-argument call of impact_dataset as the workflow makes it."""
    from gearmesh.datasets.impact import impact_dataset
    from gearmesh.pairfile import load_pair, variant_pair

    spec = config["variants"][variant]
    if "from" in spec:
        pair = load_pair(RESULTS / "optimise" / spec["from"].split(".", 1)[1] / "pair.yaml")
    else:
        pair = variant_pair(load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml"), variant, spec)
    section = {k: v for k, v in config["impact"].items()}
    fe = RESULTS / "fe_compliance.nc"
    if fe.exists():
        tables = xr.load_dataset(fe)
        section.update(method="fe")
    else:
        tables = None
        section.update(method="transition")
    return lambda: impact_dataset(pair, **section, variant=variant, fe_compliance=tables,
                                  tolerances=config["tolerances"]), section["method"]


def _timed(func) -> tuple[float, float]:
    c0, w0 = time.process_time(), time.perf_counter()
    func()
    return time.perf_counter() - w0, time.process_time() - c0


def _addition_alone(config: dict) -> dict:
    """The population contact alone on the ``standard`` job's model (module docstring)."""
    import numpy as np

    from common import timed_calls
    from gearmesh.datasets.impact import _model
    from gearmesh.fe_tables import use_fe_tables
    from gearmesh.gear import pair_geometry
    from gearmesh.pairfile import load_pair
    from gearmesh.impact import ltca_criteria
    from gearmesh.schema import defaults
    from gearmesh.settings import Impact
    from gearmesh.tolerance import manufactured_population, study_tolerances, unit_deviations

    pair = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    d = defaults(Impact)
    fe = RESULTS / "fe_compliance.nc"
    method = "fe" if fe.exists() else "transition"
    if fe.exists():
        use_fe_tables(xr.load_dataset(fe), pair_geometry(pair))
    model = _model(pair, d["points"], d["lead_slope_um"], d["contact_law"], method, d["corner_extension"], "pinion",
                   d["added_inertia_kg_m2"], d["window_positions"], d["face_samples"])
    tol, samples, sampling, seed = study_tolerances(model.geom, config["tolerances"])
    rows, lead = manufactured_population(model.geom, tol, model.params(), model.lead_slope,
                                         unit_deviations(len(tol.dimensions), samples, sampling, seed))
    torques = np.array(config["impact"]["torques_Nm"], dtype=float)
    wall, cpu, _, cpu_min = timed_calls(lambda: ltca_criteria(model, torques, rows, lead_slope=lead), 5)
    return {"name": "population_contact_alone", "tooth_model": method, "gears": int(rows.shape[0]),
            "torques": int(torques.size), "median_s": wall, "cpu_s": cpu, "cpu_min_s": cpu_min}


def main(repeats: int = 3) -> None:
    import gearmesh.datasets.impact as stage

    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    with_population = stage._add_population_contact
    totals = {"A": [0.0, 0.0], "B": [0.0, 0.0]}
    for variant in config["variants"]:
        job, method = _job(variant, config)
        runs = {"A": [], "B": []}
        for _ in range(repeats):
            for key, add in (("A", with_population), ("B", lambda *args: None)):
                stage._add_population_contact = add
                try:
                    runs[key].append(_timed(job))
                finally:
                    stage._add_population_contact = with_population
        row = {"name": f"impact_job_{variant}", "tooth_model": method, "repeats": repeats}
        for key in runs:
            wall = statistics.median(r[0] for r in runs[key])
            cpu = statistics.median(r[1] for r in runs[key])
            totals[key][0] += wall
            totals[key][1] += cpu
            row |= {f"{key}_median_s": wall, f"{key}_cpu_s": cpu}
        row["added_s"] = row["A_median_s"] - row["B_median_s"]
        row["ratio"] = row["A_median_s"] / row["B_median_s"]
        print(json.dumps(row))
    print(json.dumps(_addition_alone(config)))
    print(json.dumps({"name": "impact_jobs_all_variants", "A_median_s": totals["A"][0], "B_median_s": totals["B"][0],
                      "A_cpu_s": totals["A"][1], "B_cpu_s": totals["B"][1],
                      "ratio": totals["A"][0] / totals["B"][0]}))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
