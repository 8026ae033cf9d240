"""Plausibility for every input (issue 39, items 4 and 6): right sign, wrong unit or absurd size is
refused in one line with the range in the key's unit and the likely slip, before the first
expensive step; Supports and Body check themselves; the tables refuse another pair's datasets;
no raw exception, no message that blames the wrong thing."""

from __future__ import annotations

import dataclasses
import errno
import os

import pytest
import xarray as xr
import yaml

from gearmesh.body import Body
from gearmesh.cli import main
from gearmesh.config import check_study, validate_study
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pair, load_pair, pair_from_dict
from gearmesh.supports import Supports
from pairs import low_fluctuation_pair1


def _case(**changes) -> dict:
    """The default study's pair (supports, bore, 42 mm face) with ``changes``."""
    data = yaml.safe_load(example_pair("helical_z29_71_m5").read_text())
    return {**data, **changes}


def _one_line(argv: list[str], capsys) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and err.startswith("gearmesh: error: "), err
    return err.strip()


@pytest.mark.parametrize("changes, words", [
    # fatigue limits within what materials have (ISO 6336-5), the slip named
    ({"material": {"contact_fatigue_limit_MPa": 1e9}}, ("material.contact_fatigue_limit_MPa", "MPa", "did you give Pa?")),
    ({"material": {"contact_fatigue_limit_MPa": 1.5}}, ("did you give GPa? (1.5 GPa = 1500 MPa)",)),
    ({"material": {"bending_fatigue_limit_MPa": 5e8}}, ("material.bending_fatigue_limit_MPa", "did you give Pa?")),
    ({"material": {"youngs_modulus_GPa": 210000, "poisson_ratio": 0.3, "density_kg_m3": 7850}},
     ("material.youngs_modulus_GPa", "did you give MPa?")),
    ({"material": {"youngs_modulus_GPa": 210, "poisson_ratio": 0.3, "density_kg_m3": 7.85}},
     ("material.density_kg_m3", "did you give g/cm3?")),
    # bearings within what bearings have: N/m given as N/um
    ({"bearing_radial_stiffness_N_per_um": [1.59e9, 3.166e9]},
     ("bearing_radial_stiffness_N_per_um[0]", "N/um", "did you give N/m?")),
    ({"bearing_axial_stiffness_N_per_um": 0.001}, ("bearing_axial_stiffness_N_per_um[0]", "[1, 100000] N/um")),
    # geometry that fits: web from a stated minimum, shaft within the bore, span over the face
    ({"web_thickness_mm": 1e-6}, ("web_thickness_mm[0]", "MIN_WEB_TO_FACE")),
    ({"web_thickness_mm": 0.02}, ("web_thickness_mm[0]", "did you give m? (0.02 m = 20 mm)")),
    ({"shaft_diameter_mm": [600, 1400]}, ("shaft_diameter_mm[0] = 600.0", "bore diameter 60 mm")),
    ({"bearing_span_mm": [20, 180]}, ("bearing_span_mm[0] = 20.0", "face width 42 mm")),
    # oil and surfaces
    ({"lubricant": {"viscosity_40C_mm2_s": 2.2e-4}}, ("lubricant.viscosity_40C_mm2_s", "did you give m2/s?")),
    ({"roughness_um": {"flank_Rz": 0.0025}}, ("roughness_um.flank_Rz", "did you give mm?")),
    # validate refuses what rating refuses
    ({"tip_edge_radius_mm": 1000}, ("tip_edge_radius_mm = 1000.0", "half the normal tip thickness")),
])
def test_an_implausible_pair_file_is_refused_in_one_line(tmp_path, capsys, changes, words):
    path = tmp_path / "p.yaml"
    path.write_text(yaml.safe_dump(_case(**changes)))
    line = _one_line(["validate", str(path)], capsys)
    for word in words:
        assert word in line, line


def test_the_shipped_pairs_are_plausible():
    from gearmesh.pairfile import example_pairs

    for name, path in example_pairs().items():
        pair_geometry(load_pair(path))


def test_supports_and_body_check_themselves():
    """Code-built supports with negative bearings gave a dynamic factor of 2.6e17; a code-built body
    with a negative web a raw ValueError deep in the plate solution."""
    pair = load_pair(example_pair("helical_z29_71_m5"))
    with pytest.raises(GearmeshInputError, match=r"bearing_radial_stiffness_N_per_um\[0\] = -1"):
        dataclasses.replace(pair.supports, bearing_radial=(-1e6, 1e9))
    with pytest.raises(GearmeshInputError, match="did you give N/m"):
        Supports(bearing_radial=(1.5e14, 1.5e14), bearing_axial=(1e7, 1e7))
    with pytest.raises(GearmeshInputError, match="bearing_span_mm"):
        Supports(bearing_radial=(1e9, 1e9), bearing_axial=(1e8, 1e8), shaft_diameter=(0.06, 0.14))
    with pytest.raises(GearmeshInputError, match=r"shaft_diameter_mm\[1\] = -1"):
        Supports(bearing_radial=(1e9, 1e9), bearing_axial=(1e8, 1e8), shaft_diameter=(0.06, -0.001),
                 bearing_span=(0.15, 0.18))
    with pytest.raises(GearmeshInputError, match=r"web_thickness_mm\[0\] = -1"):
        Body(web_thickness=(-0.001, 0.01))
    with pytest.raises(GearmeshInputError, match=r"hub_diameter_mm\[1\]"):
        Body(hub_diameter=(0.1, float("nan")))
    with pytest.raises(GearmeshInputError, match="web_thickness_mm"):
        Body(web_thickness=0.01)
    thin = pair.with_changes(body=Body(web_thickness=(1e-9, 1e-9)))  # a web 1 nm thick
    with pytest.raises(GearmeshInputError, match=r"web_thickness_mm\[0\]"):
        pair_geometry(thin)
    Body(web_thickness=(float("inf"), 0.01))  # rigid and a web


@pytest.fixture
def no_ltca(monkeypatch):
    """The LTCA of the rating command fails the test if it runs: a refusal must come before it."""
    import gearmesh.datasets.rating as rating

    monkeypatch.setattr(rating, "ltca", lambda *a, **k: pytest.fail("the LTCA ran before the refusal"))


@pytest.mark.parametrize("args, words", [
    (["--speed-rpm", "1e9"], ("speed_rpm = 1000000000.0", "pitch-line velocity", "lower the speed")),
    (["--factor", "Z_NT=1e9"], ("factor Z_NT = 1000000000.0", "[0.85, 1.6]")),
    (["--factor", "K_v=1e300"], ("factor K_v = 1e+300", "[1, 10]")),
    (["--factor", "S_Hmin=0.5"], ("factor S_Hmin",)),
    (["--application-factor", "20"], ("--application-factor = 20",)),
])
def test_the_rating_door_refuses_before_the_ltca(capsys, no_ltca, args, words):
    """A rating at 1e9 rpm gave S_H 0.008 (the README says speeds above the burst speed are refused);
    --factor refusals came 20-35 s after the LTCA."""
    pair = str(example_pair("helical_z29_71_m5"))
    line = _one_line(["rating", pair, "--torque-Nm", "1000", "--speed-rpm", "5000", *args], capsys)
    for word in words:
        assert word in line, line


def test_the_rating_api_refuses_factors_given_as_a_list(no_ltca):
    from gearmesh.datasets.rating import rating_summary

    pair = load_pair(example_pair("helical_z29_71_m5"))
    with pytest.raises(GearmeshInputError, match="factors = "):
        rating_summary(pair, 1000, speed_rpm=5000, factors=[("K_v", 1.2)])


def _study(**sections) -> dict:
    return validate_study({"study": "s", "pairs": ["helical_z29_71_m5"], **sections})


def test_a_study_is_refused_before_any_job():
    with pytest.raises(GearmeshInputError, match=r"rating.speed_rpm = 1000000000.0.*lower the speed"):
        check_study(_study(ltca={"torques_Nm": [1000]}, rating={"speed_rpm": 1e9}))
    with pytest.raises(GearmeshInputError, match=r"dynamics.bearing_k_radial_N_per_m = 150.*did you give N/um"):
        check_study(_study(dynamics={"torques_Nm": 1000, "speeds_rpm": [1000], "bearing_k_radial_N_per_m": 150,
                                     "bearing_k_axial_N_per_m": 1e7}))


# --- tables of a pair's variants ---------------------------------------------------------------------


def _stage(pair, variant: str) -> xr.Dataset:
    """An empty stage dataset of ``pair``'s ``variant``, stamped as the stage functions stamp theirs."""
    from gearmesh.upstream import stamp_pair

    ds = xr.Dataset(attrs={"variant": variant, "pair_name": pair.name})
    return stamp_pair(ds, pair, True)


@pytest.fixture
def pairs():
    one = pair_from_dict(low_fluctuation_pair1())
    relief = pair_from_dict(low_fluctuation_pair1(modification={"gear": {"tip_relief_um": 10, "tip_relief_length_mm": 1}}))
    other = pair_from_dict(low_fluctuation_pair1(name="other", face_width_mm=21))
    return one, relief, other


def test_the_tables_refuse_another_pairs_datasets_or_one_twice(pairs):
    from gearmesh.datasets.rating import load_capacity_table_dataset
    from gearmesh.datasets.signoff import signoff_table_dataset

    one, relief, other = pairs
    with pytest.raises(GearmeshInputError, match=r"rating\[1\] = \"a dataset of pair 'other'\": is not of the pair of rating\[0\]"):
        load_capacity_table_dataset([_stage(one, "standard"), _stage(other, "relief")])
    with pytest.raises(GearmeshInputError, match="has variant 'standard' twice"):
        load_capacity_table_dataset([_stage(one, "standard"), _stage(one, "standard")])
    with pytest.raises(GearmeshInputError, match="rating = \\[\\]: must hold"):
        load_capacity_table_dataset([])
    with pytest.raises(GearmeshInputError, match="rating = 'Dataset': must be a list"):
        load_capacity_table_dataset(_stage(one, "standard"))
    own = [_stage(one, "standard"), _stage(relief, "relief")]
    with pytest.raises(GearmeshInputError, match=r"rating\[1\] = \"a dataset of pair 'other'\": is not of the pair of ltca\[0\]"):
        signoff_table_dataset(own, own, [_stage(one, "standard"), _stage(other, "relief")], reference="standard")
    with pytest.raises(GearmeshInputError, match="impact = .*twice"):
        signoff_table_dataset([own[0], own[0]], own, own, reference="standard")


def test_another_pairs_fe_table_is_named_as_such(pairs):
    """It was blamed on a bearing key (the first key in sorted order that differed)."""
    from gearmesh.datasets.stiffness import stiffness_dataset
    from gearmesh.upstream import stamp_pair

    one, _, other = pairs
    fe = stamp_pair(xr.Dataset(), other, False)
    with pytest.raises(GearmeshInputError) as info:
        stiffness_dataset(one, method="fe", fe_compliance=fe)
    assert str(info.value) == ("fe_compliance = \"a dataset of 'other'\": was computed for pair 'other' (face_width_mm "
                               "= [21.0, 21.0], this pair's [20.0, 20.0]), not for this pair 'low_fluctuation_pair1': pass this pair's own "
                               "fe_compliance dataset (or none)")


# --- messages -----------------------------------------------------------------------------------------


def test_a_full_numba_cache_is_named_by_its_path(tmp_path, monkeypatch):
    """numba's cache write on a full disk said '[Errno 28] No space left on device' and no path."""
    import numba.core.caching as caching

    from gearmesh.pipeline import error_line

    class FullDisk:  # a file on a full disk: every write fails
        def __init__(self, name, mode):
            self.name, self.mode = name, mode

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def write(self, data):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(caching, "open", FullDisk, raising=False)
    cache = caching.IndexDataCacheFile(str(tmp_path / "__pycache__"), "integrate.step-1.py311", ("stamp", 1))
    index = tmp_path / "__pycache__" / "integrate.step-1.py311.nbi"
    with pytest.raises(OSError) as info:
        cache.flush()  # numba's own index write
    line = error_line(info.value)
    assert line.startswith(f"{index} = 'not written': the disk is full (No space left on device)"), line
    assert "NUMBA_CACHE_DIR" in line


def test_validate_says_what_a_file_is_meant_to_be(tmp_path, capsys):
    """An empty study, or one without its study key, was judged as a pair file."""
    path = tmp_path / "s.yaml"
    path.write_text("variants: {standard: {}}\n")
    assert _one_line(["validate", str(path)], capsys) == "gearmesh: error: study = None: is required"
    path.write_text("")
    line = _one_line(["validate", str(path)], capsys)
    assert "neither a gear pair file" in line and "pair file =" not in line
