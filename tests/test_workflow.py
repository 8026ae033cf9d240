"""A tiny end-to-end Snakemake run in a scratch copy of the workflow, and its refusal path."""

from __future__ import annotations

import hashlib
import json
import re
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from gearmesh.io import read_dataset

pytestmark = [pytest.mark.workflow,
              pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")]


def _scratch_workflow(root: Path, tmp: Path, config: dict) -> Path:
    for item in ("Snakefile", "workflow", "config"):
        src = root / item
        (shutil.copytree(src, tmp / item) if src.is_dir() else shutil.copy(src, tmp / item))
    (tmp / "test_config.yaml").write_text(yaml.safe_dump(config))
    # the package as it is now, first on the jobs' path: rules carry the digest of the code they
    # run, so a checkout edited while the test runs must not change it between run and dry run
    (tmp / "package").symlink_to(_package_copy(root), target_is_directory=True)
    return tmp


def _package_copy(root: Path) -> Path:
    """A copy of ``src/gearmesh`` as it is now, in a folder named by its content and never written
    after it is made: every workflow test (and every run of the suite) of the same code shares it,
    and with it the loops numba compiles and caches beside the source, which each fresh copy would
    compile again (about 5 s for the dynamics, in every job process that runs it)."""
    partial = Path(tempfile.mkdtemp(prefix="gearmesh-test-package-"))
    shutil.copytree(root / "src" / "gearmesh", partial / "gearmesh", ignore=shutil.ignore_patterns("__pycache__"))
    digest = hashlib.sha256()
    for path in sorted(p for p in (partial / "gearmesh").rglob("*") if p.is_file()):
        digest.update(str(path.relative_to(partial)).encode() + b"\0" + path.read_bytes() + b"\0")
    target = partial.with_name(f"gearmesh-test-package-{digest.hexdigest()[:16]}")
    try:
        partial.rename(target)
    except OSError:  # made by an earlier test or run (or another worker meanwhile): the same content
        shutil.rmtree(partial)
    return target


def _package_env(package: Path) -> dict:
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(package), os.environ.get("PYTHONPATH", "")])}


def _snakemake(cwd: Path, *args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    bin_dir = Path(sys.executable).parent
    exe = shutil.which("snakemake", path=str(bin_dir)) or "snakemake"
    return subprocess.run([exe, "--cores", "2", "--configfile", "test_config.yaml", *args],
                          cwd=cwd, capture_output=True, text=True, timeout=600,
                          env=env or _package_env(cwd / "package"))


def _planned_jobs(proc: subprocess.CompletedProcess) -> dict[str, int]:
    """{rule: count} from the "Job stats" table of a dry run."""
    jobs, table = {}, False
    for line in (proc.stdout + proc.stderr).splitlines():
        parts = line.split()
        if parts[:2] == ["job", "count"]:
            table = True
        elif table and len(parts) == 2 and parts[1].isdigit():
            if parts[0] == "total":
                break
            jobs[parts[0]] = int(parts[1])
    return jobs


def _check_report(work: Path) -> None:
    """`snakemake --report` holds every figure and table of the run, with their captions."""
    proc = _snakemake(work, "--report", "report.html")
    assert proc.returncode == 0, proc.stderr[-3000:]
    html = (work / "report.html").read_text()
    wanted = sorted(str(p.relative_to(work)) for p in (work / "results").rglob("*")
                    if p.suffix in (".png", ".csv"))
    assert len(wanted) >= 12
    missing = [p for p in wanted if p not in html]
    assert not missing, f"not in the report: {missing}"
    assert "Where our results differ from the source document" in html  # the workflow page
    assert "<strong>relief</strong>" in html  # captions rendered with the job's wildcards
    assert '"low_fluctuation_pair1 / relief"' in html  # subcategory per pair and variant
    # the job panel names each job's function, without the digest that reruns it when its code changes
    assert "gearmesh.datasets.ltca:ltca_dataset" in html
    assert not re.search(r"gearmesh\.[\w.]+:\w+@[0-9a-f]{16}", html)


def _check_code_change_reruns(root: Path, work: Path, tmp: Path) -> None:
    """Results follow the code: with a changed copy of one package module first on the path,
    a dry run plans exactly the jobs whose functions can run that module."""
    package = tmp / "changed"
    shutil.copytree(work / "package", package)
    module = package / "gearmesh" / "plots" / "ltca.py"
    module.write_text(module.read_text() + "\n# a change\n")
    proc = _snakemake(work, "--dry-run", env=_package_env(package))
    assert proc.returncode == 0, proc.stderr[-3000:]
    # the figures are drawn by the jobs that write their data: those rerun, and what reads their files
    # (the LTCA-excited dynamics, its variants figure, the LTE table and the LSTE table)
    assert _planned_jobs(proc) == {"tca": 3, "ltca": 3, "dynamics": 3, "plot_dynamics_variants": 1,
                                   "lte_table": 1, "lste_comparison": 1, "all": 1}, proc.stdout[-3000:]


def _check_slurm_profile_dry_run(work: Path) -> None:
    """The SLURM profile plans the study (needs snakemake-executor-plugin-slurm: the 'slurm' extra)."""
    if importlib.util.find_spec("snakemake_executor_plugin_slurm") is None:
        return
    proc = _snakemake(work, "--profile", "workflow/profiles/slurm", "--dry-run", "--forceall")
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert _planned_jobs(proc).get("dynamics", 0) >= 2


def test_workflow_runs_end_to_end_and_reruns_nothing(root, tmp_path):
    config = {"study": "e2e", "pairs": ["low_fluctuation_pair1"], "contact_lines": {"positions": 24},
              "geometry": {"involute_points": 20, "fillet_points": 10, "face_points": 5},
              "stiffness": {"slices": 40, "positions": 24, "torque_Nm": 100, "torque_on": "pinion"},
              "variants": {"standard": {}, "relief": {"modification": {
                  "gear": {"tip_relief_um": 10, "tip_relief_length_mm": 1}}}, "optimised": {"from": "optimise.robust"}},
              "tolerances": {"grade": 6, "modification": {"tip_relief_um": 2}, "samples": 2},
              "optimise": {"robust": {"population": 4, "generations": 2, "torque_Nm": 100, "torques_Nm": [50, 100],
                                      "objective": "robust", "tolerance_statistic": "max", "speed_rpm": 3000,
                                      "points": 10, "window_positions": 16, "face_samples": 33, "cycle_positions": 8,
                                      "load_window_step_Nm": 25}},
              "tca": {"positions": 8, "points": 6},
              "ltca": {"torques_Nm": [100], "positions": 8, "points": 6},
              "dynamics": {"torques_Nm": 100, "on": "pinion", "speeds_rpm": {"start": 2000, "stop": 4000, "step": 1000},
                           "sample_speeds_rpm": [3000], "record_cycles": 4},
              "helix_sweep": {"pairs": ["low_fluctuation_pair1"], "start_deg": 8, "stop_deg": 16, "step_deg": 4,
                              "positions": 16}}
    work = _scratch_workflow(root, tmp_path, config)
    proc = _snakemake(work)
    assert proc.returncode == 0, proc.stderr[-3000:]
    base = work / "results/e2e/low_fluctuation_pair1"
    lines = read_dataset(base / "contact_lines.nc")
    assert lines.sizes["position"] == 24
    assert lines.attrs["config_sha256"] == hashlib.sha256(lines.attrs["config_json"].encode()).hexdigest()
    assert "low_fluctuation_pair1" in lines.attrs["config_json"]
    geometry = read_dataset(base / "geometry.nc")
    assert abs(float(geometry["eps_alpha"]) - 1.4702) < 1e-3  # the low-fluctuation paper Table 1: 1.470
    stiffness = read_dataset(base / "stiffness.nc")
    assert stiffness.attrs["tooth_model"] == "fe" and float(stiffness.mean_stiffness) > 0  # the default (issue 19)
    for png in ("tooth_profile", "contact_length", "contact_lines", "stiffness"):
        assert (base / "plots" / f"{png}.png").stat().st_size > 1000
    assert (work / "results/e2e/plots/helix_sweep.png").exists()
    # the GA's optimum runs through the same rules as any variant
    ga = read_dataset(base / "optimise/robust/ga.nc")
    assert ga.sizes["generation"] == 3 and ga.sizes["tolerance_sample"] == 3 and ga.sizes["objective_torque"] == 2
    optimum = yaml.safe_load((base / "optimise/robust/pair.yaml").read_text())
    for png in ("convergence", "modification"):
        assert (base / "optimise/robust/plots" / f"{png}.png").stat().st_size > 1000
    for variant in ("standard", "relief", "optimised"):
        ltca = read_dataset(base / variant / "ltca.nc")
        assert ltca.sizes["position"] == 8
        # each stage applies its variant's micro-geometry; the optimised one is the GA's optimum
        modification = json.loads(ltca.attrs["config_json"])["pair"].get("modification")
        if variant == "relief":
            assert modification["gear"]["tip_relief_um"] == pytest.approx(10)
        else:
            assert modification == {"standard": None, "optimised": optimum["modification"]}[variant]
        for png in ("tca", "te_lte", "contact_pattern", "dynamics_rms", "dynamics_spectrum"):
            assert (base / variant / "plots" / f"{png}.png").stat().st_size > 1000
        # the loads carry the applied force at every position
        total = ltca["load"].sum(dim=[d for d in ltca["load"].dims if d not in ("torque", "position")])
        np.testing.assert_allclose(total.values, np.broadcast_to(ltca["force"].values[:, None], total.shape), rtol=1e-9)
        dyn = read_dataset(base / variant / "dynamics.nc")
        mean, static = xr.broadcast(dyn["mesh_force_mean"], dyn["static_mesh_force"])
        np.testing.assert_allclose(mean.values, static.values, rtol=1e-4)
    lte = read_dataset(base / "lte_table.nc")  # what the landing page shows, as the variants' LTCA says
    assert sorted(lte["variant"].values) == ["optimised", "relief", "standard"]
    np.testing.assert_array_equal(lte["lte_mean"].sel(variant="relief").values,
                                  read_dataset(base / "relief/ltca.nc")["lte_mean"].values)
    _check_descriptions_in_the_readers_language(work / "results")
    comparison = read_dataset(work / "results/e2e/lste_comparison.nc")
    assert comparison.sizes["pair"] == 1
    again = _snakemake(work, "--dry-run")
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr
    _check_report(work)
    _check_code_change_reruns(root, work, tmp_path)
    _check_slurm_profile_dry_run(work)
    _check_swapped_input_is_refused(work)  # last: it leaves a failed job behind


def _check_descriptions_in_the_readers_language(results: Path) -> None:
    """Every variable's long_name in every result file says what it means (issue 25): the source
    documents by subject, not "the mesh-in impact paper"; contact scenarios and modification parameters
    physically, not "scenario 2" or "y1..y6"."""
    jargon = re.compile(r"\b[Ss]eed \d{3}|\bscenario \d|y1\.\.y6|withheld")
    found = {f"{path.name}:{name}": var.attrs.get("long_name", "")
             for path in sorted(results.rglob("*.nc")) for name, var in read_dataset(path).variables.items()
             if jargon.search(str(var.attrs.get("long_name", "")))}
    assert not found, found


def _check_swapped_input_is_refused(work: Path) -> None:
    """Another variant's LTCA copied over standard's (issue 20): the jobs that read it refuse it
    with one line naming the file and how to regenerate it, and write nothing from it."""
    base = work / "results/e2e/low_fluctuation_pair1"
    before = shutil.copy(base / "standard/dynamics.nc", work / "dynamics_before.nc")
    shutil.copy(base / "relief/ltca.nc", base / "standard/ltca.nc")
    proc = _snakemake(work)
    assert proc.returncode != 0
    wanted = ("gearmesh: error: results/e2e/low_fluctuation_pair1/standard/ltca.nc = 'the ltca result written as "
              "results/e2e/low_fluctuation_pair1/relief/ltca.nc'")
    assert wanted in proc.stderr, proc.stderr[-3000:]
    assert "snakemake --forcerun results/e2e/low_fluctuation_pair1/standard/ltca.nc" in proc.stderr
    # nothing made from it: the dynamics either refused it (Snakemake removed its output first) or never ran
    assert not (base / "standard/dynamics.nc").exists() or \
        (base / "standard/dynamics.nc").read_bytes() == before.read_bytes()
    # the advice works: the file is remade and what reads it with it, bit-identical to the first run
    proc = _snakemake(work, "--forcerun", "results/e2e/low_fluctuation_pair1/standard/ltca.nc")
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert read_dataset(base / "standard/dynamics.nc").identical(read_dataset(before))


def test_workflow_refuses_a_bad_pair_before_writing_anything(root, tmp_path):
    work = _scratch_workflow(root, tmp_path, {"study": "bad", "pairs": ["broken"]})
    (work / "config/pairs/broken.yaml").write_text(
        "name: broken\nteeth: [29, 71]\nnormal_module_mm: 5\nnormal_pressure_angle_deg: 20\n"
        "helix_angle_deg: 27.5\nface_width_mm: 42\ncenter_distance_mm: 261.0\n")
    proc = _snakemake(work)
    assert proc.returncode != 0
    assert "gearmesh: error: center_distance_mm" in proc.stderr
    assert not (work / "results").exists()
