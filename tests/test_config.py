"""Study configs: schema defaults, refusals naming the field, every shipped config valid."""

from __future__ import annotations

import pytest

from gearmesh.config import check_study, load_study, study_pairs, validate_study
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry


def test_defaults_are_filled():
    config = validate_study({"study": "s", "pairs": ["p"]})
    assert config["contact_lines"]["positions"] == 360
    assert config["geometry"]["face_points"] == 21
    assert config["pairs_dir"] == "config/pairs"


@pytest.mark.parametrize("config, field", [
    ({"pairs": ["p"]}, "study"),
    ({"study": "s", "pairs": []}, "pairs"),
    ({"study": "s", "pairs": ["p"], "contact_lines": {"positions": 2}}, "contact_lines.positions"),
    ({"study": "s", "pairs": ["p"], "geometry": {"face_points": "many"}}, "geometry.face_points"),
    ({"study": "bad name", "pairs": ["p"]}, "study"),
    ({"study": "s", "pairs": ["p"], "helix_sweep": {"pairs": ["p"], "start_deg": 1}}, "helix_sweep.stop_deg"),
])
def test_bad_config_names_the_field(config, field):
    with pytest.raises(GearmeshInputError) as info:
        validate_study(config)
    assert info.value.field == field


def test_unknown_pair_is_refused(root, monkeypatch):
    monkeypatch.chdir(root)
    with pytest.raises(GearmeshInputError) as info:
        study_pairs(validate_study({"study": "s", "pairs": ["no_such_pair"]}))
    assert info.value.field == "pairs"


@pytest.mark.parametrize("name", ["config/config.yaml", "config/studies/contact_lines.yaml",
                                  "config/studies/low_fluctuation.yaml", "config/studies/printing_train.yaml",
                                  "config/studies/transition_curve.yaml", "config/studies/stiffness_methods.yaml"])
def test_shipped_studies_and_their_pairs_are_valid(root, monkeypatch, name):
    monkeypatch.chdir(root)
    config = load_study(root / name)
    pairs = check_study(config)  # every stage setting, variant and load checked up front
    assert set(config["pairs"]) <= set(pairs)
    for name_, pair in pairs.items():
        assert pair.name == name_
        assert pair_geometry(pair).eps_alpha >= 1


def test_every_pair_file_is_a_working_pair(root):
    from gearmesh.pairfile import load_pair

    files = sorted((root / "config/pairs").glob("*.yaml"))
    assert len(files) >= 9  # one per pair of every seed
    for path in files:
        pair = load_pair(path)
        assert pair.name == path.stem
        assert pair_geometry(pair).eps_alpha >= 1
