"""Every stage checks what it reads (issue 20): a file copied from another variant or another
stage, a truncated file, a file made for other pair data or other settings, or one without
provenance is refused with one line naming the file and how to regenerate it."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from gearmesh.errors import GearmeshInputError
from gearmesh.pairfile import pair_from_dict
from gearmesh.io import variable, write_dataset
from gearmesh.pipeline import finish
from gearmesh.upstream import Expected, first_difference, identify, read_input, record_sources
from pairs import low_fluctuation_pair1

STUDY = {"study": "s", "pairs": ["low_fluctuation_pair1"], "ltca": {"torques_Nm": [100, 200], "positions": 8},
         "tca": {"positions": 8}}
RELIEF = {"gear": {"tip_relief_um": 10, "tip_relief_length_mm": 1}}


def _pair(modification=None):
    return pair_from_dict(low_fluctuation_pair1(**({"modification": modification} if modification else {})))


def _write(path: str, rule: str, variant: str | None, pair, study=STUDY, inputs=(), sections=None,
           data=(0.0, 1.0, 2.0)) -> str:
    """A stage's output as a workflow job writes it (pipeline._write_outputs): what it is, the
    ``inputs`` it was made from and the config ``sections`` it depends on (its rule's by
    default), then provenance; its data ``data``."""
    ds = xr.Dataset({"x": variable(("i",), np.asarray(data), "m", "a number")})
    wildcards = {"study": "s", "pair": pair.name, **({"variant": variant} if variant else {})}
    identify(ds, path, rule, wildcards)
    record_sources(ds, list(inputs), [rule] if sections is None else sections)
    finish(ds, path, study, pair, f"gearmesh {rule}")
    return path


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _copy(src: str, dst: str) -> None:
    Path(dst).parent.mkdir(parents=True, exist_ok=True)
    shutil.copy(src, dst)


def _refused(path: str, expected: Expected, *words: str) -> str:
    with pytest.raises(GearmeshInputError) as info:
        read_input(path, expected)
    line = f"gearmesh: error: {info.value}"
    assert "\n" not in line
    assert line.startswith(f"gearmesh: error: {path} = ")
    assert f"snakemake --forcerun {path}" in line
    for word in words:
        assert word in line, line
    return line


def test_the_file_made_for_this_job_is_read(work):
    path = _write("results/s/low_fluctuation_pair1/relief/ltca.nc", "ltca", "relief", _pair(RELIEF))
    ds = read_input(path, Expected(STUDY, _pair(RELIEF), "relief"))
    assert ds["x"].values.tolist() == [0.0, 1.0, 2.0]


def test_another_variants_file_copied_over_is_refused(work):
    """cp relief/ltca.nc standard/ltca.nc used to pass: the standard dynamics ran on relief's LTCA."""
    relief = _write("results/s/low_fluctuation_pair1/relief/ltca.nc", "ltca", "relief", _pair(RELIEF))
    standard = "results/s/low_fluctuation_pair1/standard/ltca.nc"
    _copy(relief, standard)
    _refused(standard, Expected(STUDY, _pair(), "standard"), "written as results/s/low_fluctuation_pair1/relief/ltca.nc",
             "copy")


def test_another_stages_file_copied_over_is_refused(work):
    """tca.nc over ltca.nc failed with "No variable named 'torque'"."""
    tca = _write("results/s/low_fluctuation_pair1/standard/tca.nc", "tca", "standard", _pair())
    ltca = "results/s/low_fluctuation_pair1/standard/ltca.nc"
    _copy(tca, ltca)
    _refused(ltca, Expected(STUDY, _pair(), "standard"), "the tca result written as")


@pytest.mark.parametrize("keep", [0.5, 0.05])
def test_a_truncated_file_is_called_damaged(work, keep):
    path = _write("results/s/low_fluctuation_pair1/standard/ltca.nc", "ltca", "standard", _pair())
    data = open(path, "rb").read()
    open(path, "wb").write(data[:int(len(data) * keep)])
    line = _refused(path, Expected(STUDY, _pair(), "standard"), "damaged", "truncated or corrupt")
    assert line.count(path) == 2  # named as the field and in the recovery, not repeated by the library


def test_a_file_made_for_other_pair_data_is_refused(work):
    """Same path, but the variant's modification changed and the file was not remade."""
    path = _write("results/s/low_fluctuation_pair1/relief/ltca.nc", "ltca", "relief", _pair(RELIEF))
    other = {"gear": {"tip_relief_um": 12, "tip_relief_length_mm": 1}}
    _refused(path, Expected(STUDY, _pair(other), "relief"), "modification.gear.tip_relief_um = 10",
             "has modification.gear.tip_relief_um = 12")


def test_a_pair_stage_file_is_compared_without_the_modification(work):
    """stiffness.nc is made once per pair (no variant) and read by every variant's dynamics."""
    path = _write("results/s/low_fluctuation_pair1/stiffness.nc", "stiffness", None, _pair())
    read_input(path, Expected(STUDY, _pair(RELIEF), "relief"))
    wider = pair_from_dict(low_fluctuation_pair1(face_width_mm=21, modification=RELIEF))
    _refused(path, Expected(STUDY, wider, "relief"), "face_width_mm[0] = 20")


def test_a_file_made_with_other_settings_of_its_stage_is_refused(work):
    path = _write("results/s/low_fluctuation_pair1/standard/ltca.nc", "ltca", "standard", _pair())
    now = {**STUDY, "ltca": {"torques_Nm": [100, 200, 300], "positions": 8}}
    _refused(path, Expected(now, _pair(), "standard"), "ltca.torques_Nm = [100, 200]",
             "this run has ltca.torques_Nm = [100, 200, 300]")
    other_stage = {**STUDY, "tca": {"positions": 16}}  # another stage's settings do not matter
    read_input(path, Expected(other_stage, _pair(), "standard"))


def test_a_file_of_another_study_is_refused(work):
    path = _write("results/s/low_fluctuation_pair1/standard/ltca.nc", "ltca", "standard", _pair())
    _refused(path, Expected({**STUDY, "study": "t"}, _pair(), "standard"), "made for study 's'")


def test_a_file_without_provenance_is_refused(work):
    path = "results/s/low_fluctuation_pair1/standard/ltca.nc"
    ds = xr.Dataset({"x": variable(("i",), np.arange(3.0), "m", "a number")},
                    attrs={"gearmesh_version": "0", "config_sha256": "0"})
    write_dataset(ds, path)
    _refused(path, Expected(STUDY), "no gearmesh provenance")


def test_a_missing_file_is_named(work):
    _refused("results/s/x.nc", Expected(STUDY), "does not exist")


def test_first_difference_names_the_first_differing_key():
    assert first_difference({"a": [1, 2.0], "b": 1}, {"a": [1, 2.0 * (1 + 1e-12)], "b": 1}) is None
    assert first_difference({"a": [1, 2]}, {"a": [1, 3]}) == "a[1]"
    assert first_difference({"a": {"b": 1}}, {"a": {}}) == "a.b"
    assert first_difference({"a": [1]}, {"a": [1, 2]}) == "a"
    assert first_difference(True, 1) == ""
