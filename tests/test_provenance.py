"""Every result is checked against everything it depends on (issue 29, items 1-4 and 9): its own
data against its digest, the pair data of each file a study table reads, the config sections it
was made from, the input files it was made from, the optimum's pair file against the run that
wrote it; ``gearmesh check`` names every damaged, foreign, edited or stale file of a results
folder, the files nothing downstream reads included; a folder where a file belongs is refused."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import netCDF4
import pytest
import xarray as xr

from gearmesh.cli import main
from gearmesh.errors import GearmeshInputError
from gearmesh.pairfile import pair_from_dict
from gearmesh.pipeline import write_pair
from gearmesh.upstream import Expected, read_input
from pairs import low_fluctuation_pair1
from test_upstream import _write as _write_upstream

STUDY = {"study": "s", "pairs": ["low_fluctuation_pair1"], "tolerances": {"samples": 4},
         "impact": {"torques_Nm": [100], "points": 10}, "variants": {"standard": {}, "relief": {}}}
RELIEF = {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 1}}
BASE = "results/s/low_fluctuation_pair1"


def _write(*args, **kwargs) -> str:
    """A stage's output as a job of this study writes it (tests/test_upstream.py)."""
    return _write_upstream(*args, **{"study": STUDY, **kwargs})


def _pair(modification=None):
    return pair_from_dict(low_fluctuation_pair1(**({"modification": modification} if modification else {})))


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _refused(call, path: str, *words: str) -> str:
    with pytest.raises(GearmeshInputError) as info:
        call()
    line = f"gearmesh: error: {info.value}"
    assert "\n" not in line and line.startswith(f"gearmesh: error: {path}"), line
    assert f"snakemake --forcerun {path}" in line, line
    for word in words:
        assert word in line, line
    return line


def _edit(path: str, name: str, factor: float) -> None:
    """Change a data value in place, attributes untouched (keeps the file's digest claim)."""
    with netCDF4.Dataset(path, "a") as nc:
        nc.variables[name][...] = nc.variables[name][...] * factor


def test_an_edited_value_is_refused(work):
    path = _write(f"{BASE}/standard/ltca.nc", "ltca", "standard", _pair())
    read_input(path, Expected(STUDY, _pair(), "standard"))
    _edit(path, "x", 1.01)
    _refused(lambda: read_input(path, Expected(STUDY, _pair(), "standard")), path, "digest")


def test_a_table_checks_each_file_against_its_own_variant(work):
    """impact_table read relief's impact.nc made with a tip relief of 20 µm when the config said
    21 (the relief row read 8071 N instead of 7599 N), exit 0."""
    path = _write(f"{BASE}/relief/impact.nc", "impact", "relief", _pair(RELIEF))
    relief21 = {"gear": {**RELIEF["gear"], "tip_relief_um": 21}}
    table = Expected(STUDY, None, None, lambda name, variant: _pair(relief21 if variant == "relief" else None))
    _refused(lambda: read_input(path, table), path, "modification.gear.tip_relief_um", "21")
    read_input(path, Expected(STUDY, None, None, lambda name, variant: _pair(RELIEF)))


def test_a_file_made_with_other_tolerances_is_refused(work):
    """The impact stage takes the study's tolerances: other samples are another result."""
    path = _write(f"{BASE}/standard/impact.nc", "impact", "standard", _pair(), sections=["impact", "tolerances"])
    changed = {**STUDY, "tolerances": {"samples": 8}}
    _refused(lambda: read_input(path, Expected(changed, _pair(), "standard")), path, "tolerances.samples")


def test_a_file_made_from_an_older_input_is_stale(work):
    stiffness = _write(f"{BASE}/stiffness.nc", "stiffness", None, _pair())
    dynamics = _write(f"{BASE}/standard/dynamics.nc", "dynamics", "standard", _pair(), inputs=[stiffness])
    read_input(dynamics, Expected(STUDY, _pair(), "standard"))
    _write(stiffness, "stiffness", None, _pair(), data=(0.0, 1.0, 2.5))  # remade, the dynamics not
    _refused(lambda: read_input(dynamics, Expected(STUDY, _pair(), "standard")), dynamics, "stiffness.nc", "stale")


# --- the optimum's pair file --------------------------------------------------------------------


def _optimum(run: str, seed: int) -> str:
    ga = _write(f"{BASE}/optimise/{run}/ga.nc", "optimise", None, _pair(), sections=[])
    made = {"ga": ga, "data_sha256": xr.load_dataset(ga).attrs["gearmesh_data_sha256"]}
    path = f"{BASE}/optimise/{run}/pair.yaml"
    write_pair(_pair({"pinion": {"crowning_um": 5 + seed}}), path, made)
    return path


def test_the_optimum_pair_file_carries_its_provenance(work):
    from gearmesh.upstream import check_optimum

    a, b = _optimum("a", 0), _optimum("b", 1)
    check_optimum(a)
    shutil.copy2(b, a)  # the design point's optimum over the recommended one (cp -p)
    _refused(lambda: check_optimum(a), a, "copy of another run's optimum")
    a = _optimum("a", 0)
    Path(a).write_text(Path(a).read_text().replace("crowning_um: 5.0", "crowning_um: 7.0"))
    _refused(lambda: check_optimum(a), a, "edited")
    a = _optimum("a", 0)
    Path(a).write_text(Path(a).read_text().split("\n", 1)[1])  # the provenance line removed
    _refused(lambda: check_optimum(a), a, "without provenance")
    a = _optimum("a", 0)
    _edit(f"{BASE}/optimise/a/ga.nc", "x", 3.0)
    with netCDF4.Dataset(f"{BASE}/optimise/a/ga.nc", "a") as nc:
        nc.setncattr("gearmesh_data_sha256", "0" * 64)  # a rerun of the optimisation
    _refused(lambda: check_optimum(a), a, "older")


# --- gearmesh check over a results folder ------------------------------------------------------


def _tree() -> list[str]:
    files = [_write(f"{BASE}/geometry.nc", "geometry", None, _pair()),
             _write(f"{BASE}/standard/tca.nc", "tca", "standard", _pair()),
             _write(f"{BASE}/relief/tca.nc", "tca", "relief", _pair(RELIEF))]
    files.append(_write(f"{BASE}/impact_table.nc", "impact_table", None, _pair(), inputs=files[1:]))
    return files


@pytest.mark.parametrize("fault, words", [
    ("copy", "copy of that file"),
    ("empty", "damaged"),
    ("truncated", "damaged"),
    ("folder", "a folder"),
    ("foreign", "no gearmesh provenance"),
    ("edited", "digest"),
    ("stale", "stale"),
    ("missing", "missing"),
])
def test_gearmesh_check_names_every_bad_file(work, capsys, fault, words):
    """Relief's tca.nc over standard's (cp -p), a zero-byte tca.nc, a truncated geometry.nc: files
    nothing downstream reads gave "Nothing to be done", exit 0."""
    geometry, standard, relief, table = _tree()
    assert main(["check", "results/s"]) == 0
    target = {"copy": standard, "empty": standard, "truncated": geometry, "folder": standard,
              "foreign": standard, "edited": geometry, "stale": relief, "missing": relief}[fault]
    if fault == "copy":
        shutil.copy2(relief, standard)
    elif fault == "empty":
        Path(standard).write_bytes(b"")
    elif fault == "truncated":
        Path(geometry).write_bytes(Path(geometry).read_bytes()[:3000])
    elif fault == "folder":
        Path(standard).unlink()
        Path(standard).mkdir()
    elif fault == "foreign":
        xr.Dataset({"x": ("i", [1.0])}).to_netcdf(standard)
    elif fault == "edited":
        _edit(geometry, "x", 1.5)
    elif fault == "stale":  # relief's TCA remade after the table was made from it
        _write(relief, "tca", "relief", _pair(RELIEF), data=(5.0, 6.0, 7.0))
        target = table
    elif fault == "missing":
        Path(relief).unlink()
        target = table
    capsys.readouterr()
    assert main(["check", "results/s"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    bad = [line for line in lines if line.startswith(f"gearmesh: error: {target}")]
    assert bad and all(words in line for line in bad), lines


def test_gearmesh_check_with_the_config_names_a_changed_setting(work, capsys, tmp_path):
    import gearmesh
    import yaml
    from gearmesh.config import validate_study

    study = {**STUDY, "variants": {"standard": {}}, "pairs_dir": str(Path(gearmesh.__file__).parent / "pairs")}
    _write(f"{BASE}/standard/impact.nc", "impact", "standard", _pair(), study=validate_study(study),
           sections=["impact", "tolerances"])
    config = tmp_path / "c.yaml"
    config.write_text(yaml.safe_dump(study))
    assert main(["check", "results/s", "--configfile", str(config)]) == 0
    config.write_text(yaml.safe_dump({**study, "impact": {**STUDY["impact"], "points": 12}}))
    assert main(["check", "results/s", "--configfile", str(config)]) == 2
    assert "impact.points" in capsys.readouterr().err


# --- item 4: a folder where a file belongs --------------------------------------------------------


def test_a_folder_where_an_output_belongs_is_refused(work):
    from gearmesh.io import check_output_files

    patterns = ["results/{study}/{pair}/{variant}/tca.nc", "results/{study}/{pair}/{variant}/plots/tca.png"]
    Path(f"{BASE}/standard/plots").mkdir(parents=True)
    check_output_files(patterns, ["results/s"])
    Path(f"{BASE}/standard/tca.nc").mkdir()
    with pytest.raises(GearmeshInputError, match="must be a file"):
        check_output_files(patterns, ["results/s"])


needs_snakemake = pytest.mark.skipif(shutil.which("snakemake", path=str(Path(sys.executable).parent)) is None,
                                     reason="snakemake not installed")


@pytest.mark.workflow
@needs_snakemake
def test_snakemake_refuses_a_folder_where_a_result_belongs(root, tmp_path):
    """mkdir results/.../tca.nc: the job was skipped, exit 0, the result and its figure missing."""
    for item in ("Snakefile", "workflow", "config"):
        src = root / item
        (shutil.copytree(src, tmp_path / item, symlinks=False) if src.is_dir() else shutil.copy(src, tmp_path / item))
    (tmp_path / "k.yaml").write_text(json.dumps({"study": "k", "pairs": ["low_fluctuation_pair1"]}))
    (tmp_path / "results/k/low_fluctuation_pair1/stiffness.nc").mkdir(parents=True)
    exe = shutil.which("snakemake", path=str(Path(sys.executable).parent))
    proc = subprocess.run([exe, "-n", "--cores", "1", "--configfile", "k.yaml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 2, proc.stderr[-2000:]
    assert proc.stderr.strip() == ("gearmesh: error: results/k/low_fluctuation_pair1/stiffness.nc = 'a folder': must be a "
                                   "file: the study writes one of its results there; move or delete the folder, "
                                   "then rerun")


def test_a_file_made_by_older_code_of_its_function_is_named(work, capsys):
    """The code digest a file claims is compared with its function's code now (item 9)."""
    from gearmesh.codeversion import versioned
    from gearmesh.upstream import FUNCTION_ATTR

    path = _write(f"{BASE}/geometry.nc", "geometry", None, _pair())
    spec = versioned("gearmesh.datasets.geometry:geometry_dataset")
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr(FUNCTION_ATTR, str.__str__(spec))
    assert main(["check", "results/s"]) == 0
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr(FUNCTION_ATTR, "gearmesh.datasets.geometry:geometry_dataset@0123456789abcdef")
    assert main(["check", "results/s"]) == 2
    assert "older code" in capsys.readouterr().err


# --- issue 39 item 3: the optimum belongs to this study ---------------------------------------------


def test_an_optimum_of_other_optimise_settings_is_refused(work):
    """Another run's pair.yaml with its own ga.nc put in place together passed every job (the
    optimised row flipped, exit 0): the optimum is checked against this study's optimisation."""
    from gearmesh.upstream import check_optimum

    ours = {**STUDY, "optimise": {"a": {"generations": 4}}}
    theirs = {**STUDY, "optimise": {"a": {"generations": 9}}}
    ga = _write(f"{BASE}/optimise/a/ga.nc", "optimise", None, _pair(), study=theirs, sections=["optimise"])
    made = {"ga": ga, "data_sha256": xr.load_dataset(ga).attrs["gearmesh_data_sha256"]}
    path = f"{BASE}/optimise/a/pair.yaml"
    write_pair(_pair({"pinion": {"crowning_um": 5}}), path, made)
    check_optimum(path)  # the file itself is the run's unedited optimum
    check_optimum(path, Expected(theirs, _pair()))
    _refused(lambda: check_optimum(path, Expected(ours, _pair())), path, "not this study's optimisation",
             "optimise.a.generations = 9", "this run has optimise.a.generations = 4")
    other = _pair().with_changes(face_width=(0.021, 0.021))  # made for another pair's data
    _refused(lambda: check_optimum(path, Expected(theirs, other)), path, "face_width_mm")


# --- issue 39 item 2: every published file checked ----------------------------------------------------


def _figure(path: str, sources: dict[str, str]) -> str:
    """A figure as a job draws it: saved inside the job's figure_sources."""
    from gearmesh.io import figure_sources
    from gearmesh.plots.common import save, subplots

    fig, ax = subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, len(path) % 7])
    with figure_sources(sources):
        save(fig, path)
    return path


def _with_table(path: str, rule: str, variant, pair) -> tuple[str, str]:
    """A stage's output with its CSV copy, as pipeline._write_outputs writes them."""
    from gearmesh.io import atomic_output
    from gearmesh.tables import write_csv
    from gearmesh.upstream import file_digest, identify, record_sources, record_tables
    from gearmesh.pipeline import finish
    from gearmesh.io import variable
    import numpy as np

    ds = xr.Dataset({"x": variable(("i",), np.arange(3.0), "m", "a number")})
    csv = path.replace(".nc", ".csv")
    with atomic_output(csv) as tmp:
        write_csv(ds, tmp)
        digest = file_digest(tmp)
    identify(ds, path, rule, {"study": "s", "pair": pair.name, **({"variant": variant} if variant else {})})
    record_sources(ds, [], [rule])
    record_tables(ds, {csv: digest})
    finish(ds, path, STUDY, pair, f"gearmesh {rule}")
    return path, csv


@pytest.mark.parametrize("fault, words", [
    ("swapped", "copy of that figure"),
    ("moved", "copy of that figure"),
    ("edited", "edited figure"),
    ("stale", "stale"),
    ("foreign", "without provenance"),
])
def test_gearmesh_check_names_a_bad_figure(work, capsys, fault, words):
    """Another variant's te_lte.png over this one's (cp -p, mv), an edited one, one drawn from a file
    remade since, one not drawn by a job: each was published as it was."""
    geometry, standard, relief, table = _tree()
    ours = _figure(f"{BASE}/standard/plots/te_lte.png", {standard: xr.load_dataset(standard).attrs[
        "gearmesh_data_sha256"]})
    other = _figure(f"{BASE}/relief/plots/te_lte.png", {relief: xr.load_dataset(relief).attrs["gearmesh_data_sha256"]})
    assert main(["check", "results/s"]) == 0
    if fault == "swapped":
        shutil.copy2(other, ours)
    elif fault == "moved":
        shutil.move(other, ours)
    elif fault == "edited":
        data = bytearray(Path(ours).read_bytes())
        data[-20] ^= 0xFF  # a byte of the image data
        Path(ours).write_bytes(bytes(data))
    elif fault == "stale":  # standard's TCA remade after its figure was drawn from it
        _write(standard, "tca", "standard", _pair(), data=(5.0, 6.0, 7.0))
    elif fault == "foreign":
        Path(ours).write_bytes(Path(ours).read_bytes().replace(b"gearmesh\0", b"gearmeshX"))
    capsys.readouterr()
    assert main(["check", "results/s"]) == 2
    lines = [line for line in capsys.readouterr().err.strip().splitlines() if line.startswith(f"gearmesh: error: {ours}")]
    assert len(lines) == 1 and words in lines[0] and f"snakemake --forcerun {ours}" in lines[0], lines


@pytest.mark.parametrize("fault, words", [
    ("edited", "edited table"),
    ("foreign", "no result lists"),
    ("missing", "missing"),
])
def test_gearmesh_check_names_a_bad_table(work, capsys, fault, words):
    """signoff_table.csv with a True turned False (or S_H 2.76 -> 9.76) was published as it was."""
    nc, csv = _with_table(f"{BASE}/signoff_table.nc", "signoff_table", None, _pair())
    assert main(["check", "results/s"]) == 0
    target = csv
    if fault == "edited":
        Path(csv).write_text(Path(csv).read_text().replace("1000", "9000"))
    elif fault == "foreign":
        target = f"{BASE}/standard/extra.csv"
        Path(target).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(csv, target)
    elif fault == "missing":
        Path(csv).unlink()
    capsys.readouterr()
    assert main(["check", "results/s"]) == 2
    lines = [line for line in capsys.readouterr().err.strip().splitlines() if line.startswith(f"gearmesh: error: {target}")]
    assert len(lines) == 1 and words in lines[0], lines


def test_a_figure_drawn_outside_a_job_carries_nothing(tmp_path):
    """The CLI and the API draw figures as they are: the provenance belongs to a job's drawing."""
    from gearmesh.io import figure_provenance
    from gearmesh.plots.common import save, subplots

    fig, _ = subplots(figsize=(2, 2))
    path = save(fig, tmp_path / "a.png")
    assert figure_provenance(path.read_bytes())[0] is None


# --- issue 38 item 2: gearmesh check from any folder, and --json --------------------------------------


def test_gearmesh_check_works_from_any_folder_and_with_an_absolute_path(work, capsys, monkeypatch):
    """From results/ or with an absolute path every file was called a copy ("regenerate it")."""
    _tree()
    _figure(f"{BASE}/plots/x.png", {f"{BASE}/geometry.nc": xr.load_dataset(f"{BASE}/geometry.nc").attrs[
        "gearmesh_data_sha256"]})
    absolute = str(work / "results" / "s")
    monkeypatch.chdir(work / "results")
    assert main(["check", "s"]) == 0
    monkeypatch.chdir(work / "results" / "s" / "low_fluctuation_pair1")
    assert main(["check", absolute]) == 0
    assert main(["check", ".."]) == 0
    capsys.readouterr()
    assert main(["check", "..", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out == {"results": "results/s", "run_folder": str(work), "ok": True, "problems": []}
    shutil.copy2(work / BASE / "relief/tca.nc", work / BASE / "standard/tca.nc")
    assert main(["check", absolute, "--json"]) == 2
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert not out["ok"] and [p.split(" = ")[0] for p in out["problems"]] == [f"{BASE}/standard/tca.nc"]
    assert captured.err.strip() == f"gearmesh: error: {out['problems'][0]}"
    assert main(["check", str(work / "results")]) == 2  # not a study's folder
    assert "results/STUDY" in capsys.readouterr().err
