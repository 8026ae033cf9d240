"""Two clean runs give the same bytes, and what a run published is checked (issue 39 items 2, 3, 6;
issue 38 item 2), on a small study run end to end twice: every netCDF file, optimum pair file,
table and figure byte-identical (the GA's wall time and the FE solve times are logged, not
written); ``gearmesh check`` passes on the genuine results from any folder and names a swapped
figure or an edited table; another study's optimum put in place with its ga.nc is refused by the
jobs that read it."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from gearmesh.cli import main
from test_workflow import _scratch_workflow, _snakemake

pytestmark = [pytest.mark.workflow,
              pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")]

OPTIMISE = {"population": 4, "generations": 2, "torque_Nm": 100, "torques_Nm": [50, 100], "objective": "robust",
            "tolerance_statistic": "max", "speed_rpm": 3000, "points": 10, "window_positions": 16,
            "face_samples": 33, "cycle_positions": 8, "load_window_step_Nm": 25}
CONFIG = {"study": "det", "pairs": ["low_fluctuation_pair1"], "contact_lines": {"positions": 24},
          "geometry": {"involute_points": 20, "fillet_points": 10, "face_points": 5},
          "stiffness": {"slices": 40, "positions": 24},
          "variants": {"standard": {}, "optimised": {"from": "optimise.robust"}},
          "tolerances": {"grade": 6, "samples": 2}, "optimise": {"robust": OPTIMISE},
          "tca": {"positions": 8, "points": 6}, "ltca": {"torques_Nm": [100], "positions": 8, "points": 6},
          "rating": {"speed_rpm": 3000}}
BASE = "results/det/low_fluctuation_pair1"


def _files(work: Path) -> dict[str, bytes]:
    return {p.relative_to(work).as_posix(): p.read_bytes() for p in sorted((work / "results").rglob("*"))
            if p.is_file()}


def test_two_clean_runs_give_the_same_bytes_and_check_what_they_publish(root, tmp_path, monkeypatch, capsys):
    runs = []
    for name in ("one", "two"):
        (tmp_path / name).mkdir()
        work = _scratch_workflow(root, tmp_path / name, CONFIG)
        proc = _snakemake(work)
        assert proc.returncode == 0, proc.stderr[-3000:]
        runs.append(work)
    one, two = (_files(w) for w in runs)
    assert sorted(one) == sorted(two)
    kinds = {Path(p).suffix for p in one}
    assert {".nc", ".png", ".csv", ".yaml"} <= kinds, kinds
    differ = [p for p in one if one[p] != two[p]]
    assert not differ, differ
    work = runs[0]
    assert "wall_seconds" in (work / "logs/det/low_fluctuation_pair1/optimise/robust.log").read_text()

    # gearmesh check passes on the genuine results from results/ and with an absolute path
    monkeypatch.chdir(work / "results")
    assert main(["check", "det"]) == 0
    monkeypatch.chdir(tmp_path)
    assert main(["check", str(work / "results/det"), "--configfile", str(work / "test_config.yaml")]) == 0
    # ... and names another variant's figure over this one's and an edited table
    figure = work / BASE / "optimised/plots/te_lte.png"
    shutil.copy2(work / BASE / "standard/plots/te_lte.png", figure)
    table = work / BASE / "load_capacity_table.csv"
    table.write_text(table.read_text().replace(",standard,", ",standard ,", 1) + "\n")
    capsys.readouterr()
    assert main(["check", str(work / "results/det")]) == 2
    err = capsys.readouterr().err
    assert f"gearmesh: error: {BASE}/optimised/plots/te_lte.png = 'the figure drawn as {BASE}/standard" in err, err
    assert f"gearmesh: error: {BASE}/load_capacity_table.csv = 'an edited table'" in err, err
    shutil.copy2(runs[1] / BASE / "optimised/plots/te_lte.png", figure)
    shutil.copy2(runs[1] / BASE / "load_capacity_table.csv", table)
    assert main(["check", str(work / "results/det")]) == 0  # the same bytes: the other run's files are as good

    # another study's optimum with its own ga.nc, put in place together: the jobs that read it refuse it
    (tmp_path / "other").mkdir()
    other = _scratch_workflow(root, tmp_path / "other",
                              {**CONFIG, "optimise": {"robust": {**OPTIMISE, "seed": 7}}})
    proc = _snakemake(other, "--", f"{BASE}/optimise/robust/pair.yaml")  # after --: a target, not a config
    assert proc.returncode == 0, proc.stderr[-3000:]
    for name in ("pair.yaml", "ga.nc"):
        shutil.copy2(other / BASE / "optimise/robust" / name, work / BASE / "optimise/robust" / name)
    proc = _snakemake(work, "--", f"{BASE}/optimised/ltca.nc")
    assert proc.returncode != 0
    line = next(x for x in proc.stderr.splitlines() if x.startswith("gearmesh: error:"))
    assert line.startswith(f"gearmesh: error: {BASE}/optimise/robust/pair.yaml = 'the optimum of "), line
    assert "not this study's optimisation" in line and "optimise.robust.seed" in line, line
    assert f"snakemake --forcerun {BASE}/optimise/robust/pair.yaml" in line, line
