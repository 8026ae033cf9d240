"""netCDF output: every variable documented, provenance attached, writes atomic."""

from __future__ import annotations

import errno
import json
import os
import pickle
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import gearmesh
import gearmesh.io
from gearmesh.errors import GearmeshInputError
from gearmesh.io import (STALE_AGE, TEMPORARY_NAME, OutputError, add_provenance, check_output_tree, config_digest,
                         host_name, read_dataset, remove_stale_temporaries, study_folders, temporary_path, variable,
                         write_dataset)


def _dataset():
    return xr.Dataset({"k": variable(("x",), np.arange(3.0), "N m-1", "stiffness")},
                      coords={"x": variable(("x",), np.arange(3.0), "m", "position")})


def test_round_trip_keeps_units_and_provenance(tmp_path):
    config = {"study": "t", "n": 3}
    ds = add_provenance(_dataset(), config, "the mesh-in impact paper", "test")
    path = write_dataset(ds, tmp_path / "a" / "out.nc")
    back = read_dataset(path)
    np.testing.assert_array_equal(back["k"].values, np.arange(3.0))
    assert back["k"].attrs["units"] == "N m-1" and back["x"].attrs["long_name"] == "position"
    assert json.loads(back.attrs["config_json"]) == config
    assert back.attrs["config_sha256"] == config_digest(config)[1]
    assert back.attrs["gearmesh_version"] == gearmesh.__version__ != ""


def test_digest_is_independent_of_key_order():
    assert config_digest({"a": 1, "b": 2})[1] == config_digest({"b": 2, "a": 1})[1]
    assert config_digest({"a": 1})[1] != config_digest({"a": 2})[1]


def test_undocumented_variable_is_refused_and_nothing_written(tmp_path):
    ds = add_provenance(_dataset(), {}, "", "t")
    ds["bare"] = ("x", np.zeros(3))
    with pytest.raises(ValueError, match="bare"):
        write_dataset(ds, tmp_path / "out.nc")
    assert list(tmp_path.iterdir()) == []


def test_missing_provenance_is_refused(tmp_path):
    with pytest.raises(ValueError, match="provenance"):
        write_dataset(_dataset(), tmp_path / "out.nc")


def test_failed_write_leaves_no_file(tmp_path, monkeypatch):
    ds = add_provenance(_dataset(), {}, "", "t")

    def boom(self, path, **kwargs):
        open(path, "w").write("partial")
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", boom)
    with pytest.raises(OSError):
        write_dataset(ds, tmp_path / "out.nc")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------------------
# Temporaries of killed writers, full disks (issue 20)
# --------------------------------------------------------------------------------------


def _dead_pid() -> int:
    """The PID of a process of this host that has exited."""
    proc = subprocess.Popen([sys.executable, "-c", ""])
    proc.wait()
    return proc.pid


def test_a_temporary_name_carries_the_writers_host_and_pid(tmp_path):
    match = TEMPORARY_NAME.fullmatch(temporary_path(tmp_path / "impact_table.csv").name)
    assert match and match["stem"] == "impact_table" and match["host"] == host_name()
    assert int(match["pid"]) == os.getpid() and match["suffix"] == ".csv"
    legacy = TEMPORARY_NAME.fullmatch(".ltca.12345.tmp.nc")  # an earlier gearmesh's, no host
    assert legacy and legacy["stem"] == "ltca" and legacy["host"] is None


def test_only_temporaries_no_live_process_writes_are_removed(tmp_path):
    """A live writer's temporary stays (another run's job in flight); a dead writer's of this host
    goes; another host's goes only when a day old; other files are never touched."""
    host, now = host_name(), time.time()
    names = {
        "live": f".ltca.{host}.{os.getpid()}.tmp.nc",
        "dead": f".ltca.{host}.{_dead_pid()}.tmp.nc",
        "other_host": f".ga.node-17.{os.getpid()}.tmp.nc",
        "other_host_old": f".ga.node-17.{_dead_pid()}.tmp.png",
        "legacy": ".tca.12345.tmp.nc",
        "legacy_old": ".tca.12346.tmp.nc",
        "not_temporary": ".ltca.nc",
        "result": "ltca.nc",
    }
    folder = tmp_path / "results/s/p/standard"
    folder.mkdir(parents=True)
    for key, name in names.items():
        (folder / name).write_bytes(b"x")
        if key.endswith("_old"):
            os.utime(folder / name, (now - 2 * STALE_AGE, now - 2 * STALE_AGE))
    removed = remove_stale_temporaries(tmp_path / "results", now=now)
    assert sorted(p.name for p in removed) == sorted(names[k] for k in ("dead", "other_host_old", "legacy_old"))
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        names[k] for k in ("live", "other_host", "legacy", "not_temporary", "result"))
    assert remove_stale_temporaries(tmp_path / "nothing") == []


def _full_disk(error: BaseException):
    def write(self, path, **kwargs):
        open(path, "wb").write(b"CDF\x01partial")
        raise error

    return write


@pytest.mark.parametrize("error", [OSError(errno.ENOSPC, "No space left on device"),
                                   OSError(errno.EDQUOT, "Disk quota exceeded")])
def test_a_full_disk_names_the_file_and_says_so(tmp_path, monkeypatch, error):
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _full_disk(error))
    path = tmp_path / "results" / "ltca.nc"
    with pytest.raises(OutputError) as info:
        write_dataset(add_provenance(_dataset(), {}, "", "t"), path)
    assert str(info.value).startswith(f"{path} = 'not written': the disk is full ({os.strerror(error.errno)}")
    assert "\n" not in str(info.value)
    assert list(path.parent.iterdir()) == []


def test_the_netcdf_librarys_hdf_error_on_a_full_disk_is_called_a_full_disk(tmp_path, monkeypatch):
    """The netCDF library says only "NetCDF: HDF error" (no errno) when the disk fills: the free
    space of the file system decides; with space left the library's error stands."""
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _full_disk(RuntimeError("NetCDF: HDF error")))
    path = tmp_path / "ltca.nc"
    ds = add_provenance(_dataset(), {}, "", "t")
    monkeypatch.setattr(gearmesh.io, "_free_bytes", lambda folder: 4096.0)
    with pytest.raises(OutputError, match="the disk is full"):
        write_dataset(ds, path)
    monkeypatch.setattr(gearmesh.io, "_free_bytes", lambda folder: 1e12)
    with pytest.raises(RuntimeError, match="HDF error") as info:
        write_dataset(ds, path)
    assert not isinstance(info.value, OutputError)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.workflow
def test_a_workflow_job_on_a_full_disk_prints_one_line_naming_the_file(root, tmp_path):
    """The job's stderr is the one line (the log cannot be written either: no logging traceback)."""
    pytest.importorskip("snakemake")
    from snakemake.iocontainers import InputFiles, Log, OutputFiles, Params, Snakemake, Wildcards

    from gearmesh.codeversion import versioned

    nc = tmp_path / "results/s/low_fluctuation_pair1/contact_lines.nc"
    job = Snakemake(InputFiles(fromdict={"pair": str(root / "config/pairs/low_fluctuation_pair1.yaml")}),
                    OutputFiles(fromdict={"nc": str(nc)}),
                    Params(fromdict={"function": versioned("gearmesh.datasets.geometry:contact_lines_dataset"),
                                     "settings": {"positions": 12}}),
                    Wildcards(fromdict={"study": "s", "pair": "low_fluctuation_pair1"}), 1, None,
                    Log([str(tmp_path / "job.log")]), {"study": "s"}, "contact_lines", None)
    blob = tmp_path / "job.pickle"
    blob.write_bytes(pickle.dumps(job))
    code = ("import errno, io, logging, pickle, xarray as xr\n"
            "def full(*args, **kw):\n"
            "    raise OSError(errno.ENOSPC, 'No space left on device')\n"
            "class FullFile(io.StringIO):\n"
            "    write = full\n"
            "xr.Dataset.to_netcdf = full\n"
            "logging.FileHandler._open = lambda self: FullFile()  # the log's disk is full too\n"
            "from gearmesh.pipeline import run_pair_stage\n"
            f"run_pair_stage(pickle.loads(open({str(blob)!r}, 'rb').read()))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "GEARMESH_JOBSERVER": "off"})
    assert proc.returncode == 1
    assert proc.stderr.splitlines() == [f"gearmesh: error: {nc} = 'not written': the disk is full (No space left on "
                                        f"device; {proc.stderr.split('device; ')[1].split(' MB free')[0]} MB free "
                                        "there); free space and rerun"]
    assert not nc.exists() and list(nc.parent.iterdir()) == []


# --------------------------------------------------------------------------------------
# The output tree (issue 20)
# --------------------------------------------------------------------------------------

STUDY = {"study": "s", "pairs": ["p"], "variants": {"standard": {}, "relief": {}}, "optimise": {"ga": {}}}


@pytest.mark.parametrize("blocker", ["results", "results/s", "results/s/p/standard", "results/s/p/optimise/ga/plots",
                                     "logs/s/p"])
def test_a_file_where_the_study_writes_a_folder_is_refused(tmp_path, blocker):
    (tmp_path / blocker).parent.mkdir(parents=True, exist_ok=True)
    (tmp_path / blocker).write_text("not a folder")
    with pytest.raises(GearmeshInputError) as info:
        check_output_tree(study_folders(STUDY), tmp_path)
    assert info.value.field == blocker and "must be a folder" in str(info.value)


def test_a_dangling_link_where_the_study_writes_is_refused(tmp_path):
    (tmp_path / "results").symlink_to(tmp_path / "gone")
    with pytest.raises(GearmeshInputError, match="a link to nothing"):
        check_output_tree(study_folders(STUDY), tmp_path)


def test_an_empty_or_complete_tree_is_accepted(tmp_path):
    check_output_tree(study_folders(STUDY), tmp_path)
    for folder in study_folders(STUDY):
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
    (tmp_path / "elsewhere").symlink_to(tmp_path / "results")
    check_output_tree(study_folders(STUDY), tmp_path)
    assert Path("results/s/p/relief/plots") in study_folders(STUDY)


@pytest.mark.workflow
def test_snakemake_and_validate_refuse_a_results_path_that_is_a_file_up_front(root, tmp_path):
    """results/STUDY/PAIR/standard a file crashed Snakemake mid-run with a traceback."""
    pytest.importorskip("snakemake")
    from test_workflow import _package_env, _scratch_workflow, _snakemake

    config = {"study": "f", "pairs": ["low_fluctuation_pair1"], "stiffness": {"slices": 20, "positions": 24}}
    work = _scratch_workflow(root, tmp_path, config)
    blocker = work / "results/f/low_fluctuation_pair1/standard"
    blocker.parent.mkdir(parents=True)
    blocker.write_text("")
    line = "gearmesh: error: results/f/low_fluctuation_pair1/standard = 'a file': must be a folder"
    proc = _snakemake(work)
    assert proc.returncode == 2 and line in proc.stderr, proc.stderr[-2000:]
    assert sorted(p.name for p in blocker.parent.iterdir()) == ["standard"]  # nothing written
    cli = subprocess.run([sys.executable, "-m", "gearmesh.cli", "validate", "test_config.yaml"], cwd=work,
                         capture_output=True, text=True, timeout=120, env=_package_env(work / "package"))
    assert cli.returncode == 2 and cli.stderr.startswith(line) and len(cli.stderr.splitlines()) == 1
