"""What the sign-off's worst-case search costs, and what a cheaper search would lose (issue 36).

The box search (:func:`gearmesh.robust.box_worst`) is most of the default study's impact jobs. For
each variant of the study, on the model, torques, speed and tolerance box its impact job builds
(``impact_dataset`` run until it calls the search, with the study's FE tables from results/ when a
run has made them): the shipped search, the same search stopped at a coarser last step
(``min_step``), and an independent check of it, a structured grid (every corner of the modification
deviations at ``--levels`` lead-mismatch levels, the box's structure: :mod:`gearmesh.robust`).

Per search: the manufactured gears evaluated, the CPU seconds, and against the shipped search's
worst of every criterion and torque: the largest shortfall (``max_lower``: its worst lower by that
fraction; a cheaper search that loses worst-case value would sign off gears the drawing allows
without having seen the worst one) and the largest excess (``max_higher``: where another search
found a worse gear than the shipped one, the shipped search missed it).

Run by hand after ``snakemake --cores 2`` (it reads results/ for the FE tables and the optimised
designs): ``python benchmarks/bench_box_search.py [--levels 33] [--steps 0.0625 0.125 0.25]``.
One JSON line per variant and search.
"""

from __future__ import annotations

import argparse
import functools
import json
import time

import numpy as np
import yaml

from bench_impact_population import _job
from common import ROOT


class _Captured(Exception):
    """Stops an impact job where it calls the box search, carrying what the search is given."""


def search_inputs(variant: str, config: dict) -> dict:
    """The box search's inputs of ``variant``'s impact job: its model, tolerance model, design
    parameters, judged torques, design speed and energy velocity, as the job hands them to
    :func:`gearmesh.robust.design_box_worst` (the job run until that call)."""
    import gearmesh.datasets.impact as stage

    def capture(model, tolerance, params, torques, speed_rpm, energy_velocity):
        raise _Captured(dict(model=model, tolerance=tolerance, params=params, torques=torques, speed_rpm=speed_rpm,
                             energy_velocity=energy_velocity))

    search = stage.design_box_worst
    stage.design_box_worst = capture
    try:
        _job(variant, config)[0]()
    except _Captured as stop:
        return stop.args[0]
    finally:
        stage.design_box_worst = search
    raise RuntimeError(f"the impact job of {variant} searches no tolerance box")


def grid_search(evaluate, k: int, mismatch: bool = True, levels: int = 33, **_):
    """A stand-in for :func:`gearmesh.robust.box_worst` with its arguments: the search's first stage
    (every corner of the modification deviations at each lead-mismatch level, the box's structure) at
    ``levels`` lead-mismatch levels instead of its own, evaluated in blocks of at most 200 gears by
    ``evaluate`` (the search's own: :func:`gearmesh.robust.design_box_worst` hands it over); the
    largest of each column there."""
    import gearmesh.robust as robust

    own = robust.MISMATCH_LEVELS
    robust.MISMATCH_LEVELS = np.linspace(-1.0, 1.0, levels)
    try:
        units = robust._first_stage(k, mismatch)
    finally:
        robust.MISMATCH_LEVELS = own
    values = np.vstack([np.asarray(evaluate(block), dtype=float).reshape(block.shape[0], -1)
                        for block in np.array_split(units, -(-units.shape[0] // 200))])
    worst = np.argmax(np.where(np.isfinite(values), values, -np.inf), axis=0)
    return robust.BoxWorst(values=values[worst, np.arange(values.shape[1])], points=units[worst],
                           evaluated=units.shape[0])


def _compare(name: str, variant: str, values: np.ndarray, evaluated: int, cpu: float, shipped: np.ndarray) -> dict:
    rel = (values - shipped) / np.abs(shipped)
    return {"variant": variant, "search": name, "evaluated": int(evaluated), "cpu_s": round(cpu, 2),
            "max_lower": float(max(0.0, -np.nanmin(rel))), "max_higher": float(max(0.0, np.nanmax(rel))),
            "columns_lower_1e-3": int(np.sum(rel < -1e-3)), "columns": int(rel.size)}


def main() -> int:
    import gearmesh.robust as robust

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=33, help="lead-mismatch levels of the grid (default 33)")
    parser.add_argument("--steps", type=float, nargs="*", default=[1 / 16, 1 / 8, 1 / 4],
                        help="coarser last steps of the search to try (default 1/16 1/8 1/4)")
    args = parser.parse_args()
    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    shipped_search = robust.box_worst
    for variant in config["variants"]:
        inputs = search_inputs(variant, config)

        def search(method=shipped_search, **options):
            robust.box_worst = functools.partial(method, **options)
            try:
                c0 = time.process_time()
                worst = robust.design_box_worst(inputs["model"], inputs["tolerance"], inputs["params"],
                                                inputs["torques"], inputs["speed_rpm"], inputs["energy_velocity"])[0]
                return worst, time.process_time() - c0
            finally:
                robust.box_worst = shipped_search

        shipped, cpu = search()
        print(json.dumps(_compare("shipped", variant, shipped.values, shipped.evaluated, cpu, shipped.values)),
              flush=True)
        for step in args.steps:
            worst, cpu = search(min_step=step)
            print(json.dumps(_compare(f"min_step {step:g}", variant, worst.values, worst.evaluated, cpu,
                                      shipped.values)), flush=True)
        grid, cpu = search(grid_search, levels=args.levels)
        print(json.dumps(_compare(f"grid {args.levels} mismatch levels x corners", variant, grid.values,
                                  grid.evaluated, cpu, shipped.values)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
