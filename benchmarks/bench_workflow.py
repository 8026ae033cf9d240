"""Workflow benchmarks: what starting a job costs, and where a whole study's time goes.

``bench_imports(repeats)``: median CPU and wall seconds of ``python -c "import X"`` for the
modules a job starts with, and which heavy libraries ``import gearmesh`` loads (none should).

``bench_study(repeats)``: the default study from an empty ``results/`` in a scratch copy of the
workflow, run with the job server (the default) and without it (``GEARMESH_JOBSERVER=off``: every
job a Python process of its own, as before the server and as on a cluster), alternately in the
same session. For each: wall time, the run's total CPU (every process it started, waited for),
and from the jobs' logs (``done in W s (figures F s) after S s of start-up, CPU C1 s + C2 s``)
the job overhead — the sum over jobs of the wall time before the work starts, the issue's
"job wall time − time inside the package function" — and its share of the total CPU. Run by
hand: ``python benchmarks/run.py imports study`` (a few minutes).
"""

from __future__ import annotations

import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from common import ROOT

IMPORTS = ("gearmesh", "gearmesh.jobserver", "gearmesh.pipeline", "gearmesh.datasets.ltca",
           "gearmesh.datasets.dynamics", "gearmesh.plots.impact")
HEAVY = ("numpy", "yaml", "scipy", "scipy.optimize", "matplotlib", "xarray", "pandas", "numba", "netCDF4")
LOG_LINE = re.compile(r"done in ([\d.]+) s \(figures ([\d.]+) s\) after ([\d.]+) s of start-up, "
                      r"CPU ([\d.]+) s \+ ([\d.]+) s")


def _timed(cmd: list[str], env: dict | None = None, cwd: Path | None = None) -> tuple[float, float]:
    """(wall s, CPU s of the command and everything it waited for) of one run of ``cmd``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{proc.stderr[-3000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def bench_imports(repeats: int) -> list[dict]:
    rows = []
    for module in IMPORTS:
        runs = [_timed([sys.executable, "-c", f"import {module}"]) for _ in range(repeats)]
        rows.append({"name": f"import {module}", "median_s": statistics.median(w for w, _ in runs),
                     "median_cpu_s": statistics.median(c for _, c in runs)})
    probe = f"import sys, gearmesh; print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    loaded = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True).stdout.strip()
    rows.append({"name": "heavy modules loaded by import gearmesh", "modules": loaded.split(",") if loaded else []})
    return rows


def _scratch(tmp: Path) -> Path:
    for item in ("Snakefile", "workflow", "config"):
        src = ROOT / item
        shutil.copytree(src, tmp / item) if src.is_dir() else shutil.copy(src, tmp / item)
    return tmp


def job_times(logs: Path) -> dict:
    """Totals over the job logs under ``logs``: jobs, start-up and work (wall and CPU), figures."""
    rows = [tuple(map(float, m.groups())) for log in logs.rglob("*.log")
            if (m := LOG_LINE.search(log.read_text()))]
    if not rows:
        raise RuntimeError(f"no job log under {logs} has the line 'done in ... CPU ...' (gearmesh.pipeline): "
                           "update LOG_LINE")
    work, figures, startup, cpu_startup, cpu_work = (sum(col) for col in zip(*rows))
    return {"jobs": len(rows), "startup_wall_s": startup, "work_wall_s": work, "figures_wall_s": figures,
            "startup_cpu_s": cpu_startup, "work_cpu_s": cpu_work}


def _study_run(server: bool) -> dict:
    exe = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or "snakemake"
    env = {k: v for k, v in os.environ.items() if k != "GEARMESH_JOBSERVER"}
    if not server:
        env["GEARMESH_JOBSERVER"] = "off"
    with tempfile.TemporaryDirectory() as tmp:
        work = _scratch(Path(tmp))
        wall, cpu = _timed([exe, "--cores", "2", "--quiet"], env=env, cwd=work)
        jobs = job_times(work / "logs")
    return {"wall_s": wall, "cpu_s": cpu, **jobs, "overhead_share_of_cpu": jobs["startup_wall_s"] / cpu}


def bench_study(repeats: int, servers=(True, False)) -> list[dict]:
    """The default study with and without the job server (``servers``), alternately, ``repeats``
    times each."""
    runs = {server: [] for server in servers}
    for _ in range(repeats):
        for server in servers:
            runs[server].append(_study_run(server))
    out = []
    for server, results in runs.items():
        row = {"name": "default study, job server" if server else "default study, a process per job"}
        for key in results[0]:
            row[key] = statistics.median(r[key] for r in results)
        out.append(row)
    if len(runs) == 2:
        walls = [a["wall_s"] / b["wall_s"] for a, b in zip(runs[False], runs[True])]
        out.append({"name": "default study wall, a process per job / job server", "ratio": statistics.median(walls)})
    return out
