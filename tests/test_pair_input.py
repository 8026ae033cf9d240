"""Reading pair data as engineers give it (issue 18): names, datasheet quantities, material
defaults and centre distances printed to a few decimals."""

from __future__ import annotations

import json

import pytest
import yaml

from gearmesh.cli import main
from gearmesh.gear import load_pair

from pairs import seed001_pair1


def _write(path, data) -> str:
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return str(path)


# --------------------------------------------------------------------------------------
# Names: optional in the command line (the file stem), kept as given; the library's rule
# --------------------------------------------------------------------------------------


def test_a_renamed_pair_file_keeps_its_name(tmp_path, capsys):
    path = _write(tmp_path / "copy_of_the_pair.yaml", seed001_pair1())
    assert main(["geometry", path, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "seed001_pair1"


def test_a_pair_file_without_name_is_named_after_its_file(tmp_path, capsys):
    data = seed001_pair1()
    del data["name"]
    path = _write(tmp_path / "my_pair.yaml", data)
    assert load_pair(path).name == "my_pair"
    assert main(["validate", path, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "my_pair"


def test_a_file_name_that_is_no_pair_name_needs_a_name(tmp_path, capsys):
    data = seed001_pair1()
    del data["name"]
    path = _write(tmp_path / "my pair.yaml", data)
    assert main(["geometry", path]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearmesh: error: name = None: is required") and "'my pair'" in err
    data["name"] = "mine"
    assert main(["geometry", _write(tmp_path / "my pair.yaml", data), "--json"]) == 0


def test_the_study_library_keeps_name_equal_to_file(tmp_path, capsys):
    (tmp_path / "pairs").mkdir()
    _write(tmp_path / "pairs" / "p.yaml", seed001_pair1(name="other"))
    study = tmp_path / "study.yaml"
    study.write_text(f"study: s\npairs: [p]\npairs_dir: {tmp_path / 'pairs'}\n")
    assert main(["validate", str(study)]) == 2
    assert capsys.readouterr().err.startswith("gearmesh: error: name = 'other': must equal the file name 'p'")
