"""The CPU of the default study's figures (issue 36): every figure of a finished study redrawn
from its netCDF files with the plot functions its jobs use, timed job by job.

The jobs are the study's plan (``tests/workflow_plan.py``: Snakemake's DAG of the default study).
Each job that draws is redrawn as :func:`gearmesh.pipeline._draw` does it: a stage or table job's
``params.figures`` gets its named netCDF inputs and its own netCDF outputs read back, under their
file stems; a figure job's ``params.function`` (``run_plot``) gets its named inputs. Reading the
files is not timed; drawing and saving is (``time.process_time`` of this process: matplotlib
draws in one thread).

``python benchmarks/bench_figures.py --study DIR``: DIR holds a finished default study
(``DIR/results/...``); one JSON line per plot module (CPU seconds, figures, PNG bytes) and a total.
``--vs SRC``: also draw with the package at ``SRC`` (e.g. another worktree's ``src``), each side in
a fresh process, alternately ``--repeats`` times; the medians of each side and their ratio.
``--keep DIR``: keep the PNGs drawn (``DIR/a``, ``DIR/b`` with ``--vs``) to look at them.
Run by hand; never by pytest.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

from common import ROOT

sys.path.insert(0, str(ROOT / "tests"))


def drawing_jobs() -> list[dict]:
    """The default study's jobs that draw figures: rule, wildcards, the drawing function, whether it
    reads the job's own netCDF outputs (a stage or table) or only its inputs (a figure job), its
    named netCDF inputs and its outputs (paths relative to the study's root)."""
    from workflow_plan import plan

    jobs = []
    for job in plan([])["jobs"]:
        outputs = {o["name"]: o["path"] for o in job["output"] if o["name"]}
        if not any(p.endswith(".png") for p in outputs.values()):
            continue
        params = job["params"]
        own = "figures" in params
        inputs = {k: v for k, v in job["input"].items() if k not in ("pair", "")}
        jobs.append({"rule": job["rule"], "wildcards": job["wildcards"], "draws": params["figures" if own else "function"],
                     "own": own, "inputs": inputs, "outputs": outputs})
    return jobs


def draw_all(study: Path, out: Path) -> list[dict]:
    """Every drawing job of the study under ``study`` redrawn into ``out`` (the study's relative
    paths kept): one row per job with its module, CPU and wall seconds, figures and PNG bytes."""
    from gearmesh.io import DATA_ATTR, figure_sources, read_dataset
    from gearmesh.stages import resolve
    from gearmesh.upstream import file_digest

    jobs = drawing_jobs()
    for job in jobs:  # imports before any timing
        resolve(job["draws"])
    rows = []
    for job in jobs:
        def read(path):
            return read_dataset(study / path)

        data = {k: [read(p) for p in v] if isinstance(v, list) else read(v) for k, v in job["inputs"].items()}
        pngs = {k: str(out / p) for k, p in job["outputs"].items() if p.endswith(".png")}
        if job["own"]:
            written = {p: read(p) for p in job["outputs"].values() if p.endswith(".nc")}
            data.update({Path(p).stem: ds for p, ds in written.items()})
            sources = {str(study / p): ds.attrs[DATA_ATTR] for p, ds in written.items()}
        else:
            sources = {str(study / p): file_digest(study / p) for v in job["inputs"].values()
                       for p in (v if isinstance(v, list) else [v])}
        function = resolve(job["draws"])
        c0, w0 = time.process_time(), time.perf_counter()
        with figure_sources(sources):
            function(data, pngs)
        cpu, wall = time.process_time() - c0, time.perf_counter() - w0
        rows.append({"job": " ".join([job["rule"], *sorted(job["wildcards"].get(k, "") for k in ("variant", "run"))]).strip(),
                     "module": job["draws"].partition(":")[0].rpartition(".")[2], "cpu_s": cpu, "wall_s": wall,
                     "figures": len(pngs), "png_bytes": sum(Path(p).stat().st_size for p in pngs.values())})
    return rows


def by_module(rows: list[dict]) -> dict[str, dict]:
    """The rows summed per plot module, and ``total``."""
    out: dict[str, dict] = defaultdict(lambda: {"cpu_s": 0.0, "wall_s": 0.0, "figures": 0, "png_bytes": 0})
    for row in rows:
        for key in (row["module"], "total"):
            for field in ("cpu_s", "wall_s", "figures", "png_bytes"):
                out[key][field] += row[field]
    return dict(sorted(out.items(), key=lambda kv: (kv[0] == "total", kv[0])))


def _child(src: str, study: Path, out: Path) -> dict[str, dict]:
    """:func:`by_module` of a fresh process that draws with the package at ``src``."""
    env = {**os.environ, "PYTHONPATH": src}
    run = subprocess.run([sys.executable, __file__, "--study", str(study), "--keep", str(out), "--rows"], env=env,
                         check=True, capture_output=True, text=True, cwd=Path(__file__).parent)
    return by_module([json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")])


def compare(base_src: str, study: Path, repeats: int, keep: Path) -> None:
    """A (the package at ``base_src``) against B (the package this process imports), alternately
    in fresh processes: per module the median CPU of each and the ratio A/B; PNG bytes of each."""
    import gearmesh

    ours = str(Path(gearmesh.__file__).resolve().parents[1])
    runs: dict[str, list[dict]] = {"a": [], "b": []}
    for _ in range(repeats):
        for side, src in (("a", base_src), ("b", ours)):
            runs[side].append(_child(src, study, keep / side))
    for module in runs["a"][0]:
        a = statistics.median(r[module]["cpu_s"] for r in runs["a"])
        b = statistics.median(r[module]["cpu_s"] for r in runs["b"])
        print(json.dumps({"module": module, "figures": runs["b"][0][module]["figures"], "a_cpu_s": round(a, 3),
                          "b_cpu_s": round(b, 3), "ratio": round(a / b, 2),
                          "a_png_bytes": runs["a"][0][module]["png_bytes"],
                          "b_png_bytes": runs["b"][0][module]["png_bytes"]}), flush=True)
    print(json.dumps({"a": base_src, "b": ours, "repeats": repeats}))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--study", type=Path, required=True, help="root of a finished default study (holds results/)")
    parser.add_argument("--vs", metavar="SRC", help="the package source to compare with (A); this process's is B")
    parser.add_argument("--repeats", type=int, default=3, help="alternate runs of each side with --vs")
    parser.add_argument("--keep", type=Path, help="write the PNGs under this folder (default a temporary one)")
    parser.add_argument("--rows", action="store_true", help="one JSON line per job instead of per module")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        keep = args.keep or Path(tmp)
        if args.vs:
            compare(args.vs, args.study.resolve(), max(1, args.repeats), keep.resolve())
            return 0
        rows = draw_all(args.study.resolve(), keep.resolve())
        for row in rows if args.rows else [{"module": k, **v} for k, v in by_module(rows).items()]:
            print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
