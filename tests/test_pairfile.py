"""Reading pair data as engineers give it (issue 18): names, datasheet quantities, material
defaults and centre distances printed to a few decimals."""

from __future__ import annotations

import json
import math

import pytest
import yaml

from gearmesh.cli import main
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import Material, pair_geometry, shift_rounding_center_distance
from gearmesh.pairfile import load_pair, pair_from_dict, pair_notes, pair_to_dict

from pairs import low_fluctuation_pair1


def _write(path, data) -> str:
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return str(path)


# --------------------------------------------------------------------------------------
# Names: optional in the command line (the file stem), kept as given; the library's rule
# --------------------------------------------------------------------------------------


def test_a_renamed_pair_file_keeps_its_name(tmp_path, capsys):
    path = _write(tmp_path / "copy_of_the_pair.yaml", low_fluctuation_pair1())
    assert main(["geometry", path, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "low_fluctuation_pair1"


def test_a_pair_file_without_name_is_named_after_its_file(tmp_path, capsys):
    data = low_fluctuation_pair1()
    del data["name"]
    path = _write(tmp_path / "my_pair.yaml", data)
    assert load_pair(path).name == "my_pair"
    assert main(["validate", path, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "my_pair"


def test_a_file_name_that_is_no_pair_name_needs_a_name(tmp_path, capsys):
    data = low_fluctuation_pair1()
    del data["name"]
    path = _write(tmp_path / "my pair.yaml", data)
    assert main(["geometry", path]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearmesh: error: name = None: is required") and "'my pair'" in err
    data["name"] = "mine"
    assert main(["geometry", _write(tmp_path / "my pair.yaml", data), "--json"]) == 0


def test_the_study_library_keeps_name_equal_to_file(tmp_path, capsys):
    (tmp_path / "pairs").mkdir()
    _write(tmp_path / "pairs" / "p.yaml", low_fluctuation_pair1(name="other"))
    study = tmp_path / "study.yaml"
    study.write_text(f"study: s\npairs: [p]\npairs_dir: {tmp_path / 'pairs'}\n")
    assert main(["validate", str(study)]) == 2
    assert capsys.readouterr().err.startswith("gearmesh: error: name = 'other': must equal the file name 'p'")


# --------------------------------------------------------------------------------------
# Material: steel when not given (stated), explicit values override key by key
# --------------------------------------------------------------------------------------


def test_missing_material_is_steel_and_stated(tmp_path, capsys):
    data = low_fluctuation_pair1()
    del data["material"]
    pair = pair_from_dict(data)
    assert (pair.material.youngs_modulus, pair.material.poisson_ratio, pair.material.density) == (206e9, 0.3, 7850)
    assert len(pair_notes(pair)) == 1 and "material not given" in pair_notes(pair)[0]
    assert main(["geometry", _write(tmp_path / "p.yaml", data), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["material"] == {"youngs_modulus_GPa": 206.0, "poisson_ratio": 0.3, "density_kg_m3": 7850.0}
    assert "youngs_modulus_GPa = 206" in out["notes"][0]
    # the mass follows the default density: ρπ(r² − r_i²)b of the pinion, r = 25.7665 mm, r_i = 15 mm
    assert out["mass_kg"][0] == pytest.approx(7850 * math.pi * (25.76651e-3**2 - 15e-3**2) * 20e-3, rel=1e-5)


def test_explicit_material_values_override_key_by_key():
    pair = pair_from_dict(low_fluctuation_pair1(material={"density_kg_m3": 7800}))
    assert (pair.material.youngs_modulus, pair.material.density) == (206e9, 7800)
    note = pair_notes(pair)[0]
    assert "youngs_modulus_GPa" in note and "poisson_ratio" in note and "density" not in note.split("(")[0]
    assert pair_notes(pair_from_dict(low_fluctuation_pair1())) == []
    # written back: only what was given, so reading it fills (and states) the same defaults
    assert pair_to_dict(pair)["material"] == {"density_kg_m3": 7800}
    assert pair_from_dict(pair_to_dict(pair)) == pair
    # a material set in code replaces the defaults: nothing is left out or claimed
    steel = pair.with_changes(material=Material(210e9, 0.29, 7850.0))
    assert pair_notes(steel) == [] and len(pair_to_dict(steel)["material"]) == 3


def test_dataset_attrs_state_the_material_defaults(tmp_path):
    from gearmesh.datasets.geometry import geometry_dataset
    from gearmesh.io import read_dataset
    from gearmesh.pipeline import finish

    data = low_fluctuation_pair1()
    del data["material"]
    pair = pair_from_dict(data)
    path = finish(geometry_dataset(pair), tmp_path / "geometry.nc", {"study": "s"}, pair, "geometry")
    assert "material not given" in read_dataset(path).attrs["pair_notes"]


# --------------------------------------------------------------------------------------
# Centre distance a hair below zero backlash: the shifts' rounding, not interpenetration
# --------------------------------------------------------------------------------------

#: The parallel helical stage of a KISSsoft report (issue 18): shifts printed to four decimals
#: put its zero-backlash distance 0.15 µm above the printed 861.000 mm.
KISSSOFT = {"teeth": [24, 95], "normal_module_mm": 14, "normal_pressure_angle_deg": 20, "helix_angle_deg": 10,
            "face_width_mm": 360, "profile_shift": [0.48, 0.6691], "center_distance_mm": 861.000,
            "tip_diameter_mm": [380.747, 1395.376], "basic_rack_profile": "ISO 53 A",
            "bore_diameter_mm": [179.10, 1193.32]}


def _zero_backlash_distance(data) -> float:
    return pair_geometry(pair_from_dict({"name": "p", **data, "center_distance_mm": None})).center_distance


def test_rounding_tolerance_is_the_printed_shifts_effect_on_a0():
    """Independent check of the closed-form ∂a0/∂Σx: a0 of the shifts each raised by 0.5e-4."""
    data = low_fluctuation_pair1(profile_shift=[0.3, 0.2])
    geom = pair_geometry(pair_from_dict(data))
    raised = _zero_backlash_distance(low_fluctuation_pair1(profile_shift=[0.30005, 0.20005]))
    allowed = shift_rounding_center_distance(geom.pair, geom.transverse_pressure_angle, geom.operating_pressure_angle)
    assert allowed == pytest.approx(raised - geom.center_distance, rel=1e-4)
    assert 0.5e-4 < allowed / geom.pair.normal_module < 2e-4  # about 1e-4 m_n


def test_centre_distance_below_zero_backlash_within_rounding_is_zero_backlash():
    data = {k: v for k, v in KISSSOFT.items() if k in ("teeth", "normal_module_mm", "normal_pressure_angle_deg",
                                                        "helix_angle_deg", "face_width_mm", "profile_shift",
                                                        "center_distance_mm")}
    pair = pair_from_dict({**data, "name": "stage"})
    a0 = _zero_backlash_distance(data)
    assert 0.1e-6 < a0 - 0.861 < 0.3e-6
    geom = pair_geometry(pair)
    assert geom.center_distance == a0 and geom.backlash_normal == pytest.approx(0, abs=1e-15)
    assert any("zero backlash" in note for note in pair_notes(pair))
    # beyond the rounding (1.25 µm here): refused, naming the distance and the limit
    with pytest.raises(GearmeshInputError) as info:
        pair_geometry(pair_from_dict({**data, "name": "stage", "center_distance_mm": 860.9985}))
    assert info.value.field == "center_distance_mm" and "rounding" in str(info.value)
    # above a0 nothing is said
    assert pair_notes(pair_from_dict({**data, "name": "stage", "center_distance_mm": 861.1})) == [
        note for note in pair_notes(pair) if "material" in note]


# --------------------------------------------------------------------------------------
# Datasheet quantities instead of coefficients: tip, root and bore diameters, ISO 53 profile
# --------------------------------------------------------------------------------------


def test_kisssoft_stage_is_accepted_and_its_tip_diameters_give_its_contact_ratio(tmp_path, capsys):
    """The datasheet gives εα = 1.463; its tip diameters (tip shortening included) must give it,
    where the default addendum 1.0 gave 1.557 (issue 18)."""
    assert main(["geometry", _write(tmp_path / "kisssoft_stage.yaml", KISSSOFT), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["eps_alpha"] == pytest.approx(1.463, rel=3e-3)
    assert [2 * r for r in out["tip_radius_mm"]] == pytest.approx([380.747, 1395.376], abs=1e-9)
    assert out["backlash_mm"] == pytest.approx(0, abs=1e-12)
    assert any("zero backlash" in note for note in out["notes"])
    standard = {k: v for k, v in KISSSOFT.items() if k != "tip_diameter_mm"}
    assert pair_geometry(pair_from_dict({**standard, "name": "s"})).eps_alpha == pytest.approx(1.557, abs=1e-3)
    # ISO 53 profile A: hob addendum 1.25 m_n, tip radius 0.38 m_n; inner diameters: bore radii
    pair = load_pair(tmp_path / "kisssoft_stage.yaml")
    assert pair.dedendum_coefficient == (1.25, 1.25) and pair.tool_tip_radius_coefficient == (0.38, 0.38)
    assert pair.bore_radius == pytest.approx((0.08955, 0.59666))


def test_root_diameter_is_the_hob_dedendum_iso21771():
    # spur 20/40, m 4, x 0.3/-0.1: d_f = d - 2 h_fP + 2 x m (ISO 21771 eq. 47)
    # pinion 80 - 10 + 2.4 = 72.4 mm (h_fP = 1.25 m); gear 160 - 11.2 - 0.8 = 148.0 mm (h_fP = 1.4 m)
    data = {"name": "spur", "teeth": [20, 40], "normal_module_mm": 4, "normal_pressure_angle_deg": 20,
            "helix_angle_deg": 0, "face_width_mm": 30, "profile_shift": [0.3, -0.1]}
    pair = pair_from_dict({**data, "root_diameter_mm": [72.4, 148.0]})
    assert pair.dedendum_coefficient == pytest.approx((1.25, 1.4), abs=1e-12)
    geom = pair_geometry(pair)
    assert [2e3 * r for r in geom.root_radius] == pytest.approx([72.4, 148.0], abs=1e-9)


def test_tip_diameter_with_shifts_inferred_from_the_centre_distance():
    # no shifts, a = 122 mm: the zero-backlash total shift is split equally (pair_geometry);
    # the tip diameters are absolute and must come out as given
    data = {"name": "spur", "teeth": [20, 40], "normal_module_mm": 4, "normal_pressure_angle_deg": 20,
            "helix_angle_deg": 0, "face_width_mm": 30, "center_distance_mm": 122.0,
            "tip_diameter_mm": [89.5, 169.5]}
    geom = pair_geometry(pair_from_dict(data))
    assert geom.shift_inferred
    assert [2e3 * r for r in geom.tip_radius] == pytest.approx([89.5, 169.5], abs=1e-9)


@pytest.mark.parametrize("extra, field, other", [
    ({"addendum_coefficient": 1.0, "tip_diameter_mm": [380.747, 1395.376]}, "tip_diameter_mm", "addendum_coefficient"),
    ({"dedendum_coefficient": 1.25}, "basic_rack_profile", "dedendum_coefficient"),
    ({"root_diameter_mm": 300}, "basic_rack_profile", "root_diameter_mm"),
    ({"tool_tip_radius_coefficient": 0.3}, "basic_rack_profile", "tool_tip_radius_coefficient"),
    ({"bore_radius_mm": 80}, "bore_diameter_mm", "bore_radius_mm"),
])
def test_two_keys_for_one_dimension_are_one_error(tmp_path, capsys, extra, field, other):
    data = {**KISSSOFT, **extra}
    assert main(["validate", _write(tmp_path / "p.yaml", data)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"gearmesh: error: {field} = ") and f"conflicts with {other}" in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("change, field", [
    ({"basic_rack_profile": "DIN 867"}, "basic_rack_profile"),
    ({"normal_pressure_angle_deg": 25}, "basic_rack_profile"),
    ({"tip_diameter_mm": [340.0, 1395.376]}, "tip_diameter_mm[0]"),  # below d + 2 x m_n = 354.6 mm
    ({"tip_diameter_mm": [380.747, -1]}, "tip_diameter_mm[1]"),
    ({"bore_diameter_mm": "wide"}, "bore_diameter_mm"),
])
def test_bad_datasheet_values_are_refused(change, field):
    with pytest.raises(GearmeshInputError) as info:
        pair_geometry(pair_from_dict({**KISSSOFT, "name": "k", **change}))
    assert info.value.field == field
