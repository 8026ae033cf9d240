"""netCDF output: every variable documented, provenance attached, writes atomic."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

import gearmesh
from gearmesh.io import add_provenance, config_digest, read_dataset, variable, write_dataset


def _dataset():
    return xr.Dataset({"k": variable(("x",), np.arange(3.0), "N m-1", "stiffness")},
                      coords={"x": variable(("x",), np.arange(3.0), "m", "position")})


def test_round_trip_keeps_units_and_provenance(tmp_path):
    config = {"study": "t", "n": 3}
    ds = add_provenance(_dataset(), config, "seed 000", "test")
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
