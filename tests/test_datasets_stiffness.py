"""The stiffness stage as a user meets it: dataset, tables, variants, CLI."""

from __future__ import annotations

import json

import numpy as np
import pytest
from pairs import low_fluctuation_pair1

from gearmesh.cli import main
from gearmesh.datasets.stiffness import (
    apply_variant,
    slice_convergence_dataset,
    stiffness_dataset,
    stiffness_table_dataset,
)
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.io import add_provenance, read_dataset, write_dataset


@pytest.fixture(scope="module")
def pair1():
    return load_pair(low_fluctuation_pair1())


def test_dataset_is_documented_and_consistent(pair1, tmp_path):
    ds = stiffness_dataset(pair1, positions=90, torque_Nm=200, torque_on="gear")
    back = read_dataset(write_dataset(add_provenance(ds, {}, "", "t"), tmp_path / "k.nc"))
    k = back["mesh_stiffness"].values
    # the Fourier mean is the mean of K; the LSTE is F/K with F = T1/r_b1, T1 = T2 z1/z2
    assert float(back.fourier_mean) == pytest.approx(k.mean(), rel=1e-12)
    geom = pair_geometry(pair1)
    force = 200 * 29 / 49 / geom.base_radius[0]
    np.testing.assert_allclose(back["lste"].values, force / k, rtol=1e-12)
    assert float(back.min_stiffness) <= k.min() and float(back.max_stiffness) >= k.max()
    # components in series give K back
    inv = (1 / back["component_stiffness"].values).sum(axis=0)
    np.testing.assert_allclose(1 / inv, k, rtol=1e-9)


def test_integer_overlap_pairs_have_flat_stiffness(pair1):
    """The low-fluctuation paper Table 1: pairs 2 (beta 15.95) and 3 (b 31.66) have eps_beta = 1 -> eps_k ~ 0."""
    pairs = {"p1": pair1,
             "p2": load_pair(low_fluctuation_pair1(helix_angle_deg=15.9554207)),
             "p3": load_pair(low_fluctuation_pair1(face_width_mm=31.6604943))}
    table = stiffness_table_dataset(pairs, pairs=list(pairs), positions=120, torque_Nm=200, torque_on="gear")
    eps_k = table["fluctuation"].values[:, 0]
    lste_pp = table["lste_peak_to_peak"].values[:, 0]
    assert eps_k[0] > 0.2 and eps_k[1] < 1e-3 and eps_k[2] < 1e-3
    assert lste_pp[1] < 0.01 * lste_pp[0] and lste_pp[2] < 0.01 * lste_pp[0]
    # a wider face is stiffer: lower mean LSTE (the low-fluctuation paper section 5)
    assert table["lste_mean"].values[2, 0] < table["lste_mean"].values[0, 0]


def test_contact_ratio_variants_reach_their_targets(pair1):
    p = apply_variant(pair1, "r", {"eps_alpha": 1.6, "eps_beta": 2.0})
    geom = pair_geometry(p)
    assert geom.eps_alpha == pytest.approx(1.6, abs=1e-9) and geom.eps_beta == pytest.approx(2.0, abs=1e-9)
    assert p.name == f"{pair1.name}-r"
    with pytest.raises(GearmeshInputError) as info:
        apply_variant(pair1, "bad", {"eps_alpha": 0.8})
    assert info.value.field == "eps_alpha"


def test_clipped_slices_converge_at_second_order(pair1):
    ds = slice_convergence_dataset({"p1": pair1}, pairs=["p1"], slices=(20, 40, 80, 640), positions=60)
    err = np.abs(ds["mean_relative_difference"].sel(rule="clip").values[0, :3])
    order = np.log2(err[:-1] / err[1:])
    assert np.all(order > 1.7), order


def test_cli_stiffness_json(root, capsys):
    assert main(["stiffness", str(root / "config/pairs/low_fluctuation_pair1.yaml"), "--torque-Nm", "200", "--on", "gear",
                 "--positions", "90", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("mean_mesh_stiffness_transverse_N_per_um", "min_mesh_stiffness_transverse_N_per_um", "max_mesh_stiffness_transverse_N_per_um",
                "fluctuation_percent", "iso6336_c_single_N_per_mm_um", "iso6336_c_gamma_alpha_N_per_mm_um",
                "lste_mean_um", "lste_peak_to_peak_um"):
        assert key in out
    assert out["min_mesh_stiffness_transverse_N_per_um"] < out["mean_mesh_stiffness_transverse_N_per_um"] < out["max_mesh_stiffness_transverse_N_per_um"]


@pytest.mark.parametrize("args, field", [
    (["--torque-Nm", "-5"], "torque_Nm"),
    (["--slices", "0"], "--slices"),
])
def test_cli_stiffness_refuses_bad_options(root, capsys, args, field):
    assert main(["stiffness", str(root / "config/pairs/low_fluctuation_pair1.yaml"), *args]) == 2
    assert capsys.readouterr().err.startswith(f"gearmesh: error: {field}")


def test_cli_stiffness_without_material_is_steel_and_says_so(tmp_path, capsys):
    path = tmp_path / "p.yaml"
    text = ("name: p\nteeth: [29, 49]\nnormal_module_mm: 2\nnormal_pressure_angle_deg: 20\n"
            "helix_angle_deg: 10\nface_width_mm: 20\nbore_radius_mm: [10, 20]\n")
    path.write_text(text)
    assert main(["stiffness", str(path), "--slices", "40", "--positions", "40", "--json"]) == 0
    default = json.loads(capsys.readouterr().out)
    assert "material not given" in default["notes"][0]
    path.write_text(text + "material: {youngs_modulus_GPa: 206, poisson_ratio: 0.3, density_kg_m3: 7850}\n")
    assert main(["stiffness", str(path), "--slices", "40", "--positions", "40", "--json"]) == 0
    given = json.loads(capsys.readouterr().out)
    assert given["notes"] == []
    assert given["mean_mesh_stiffness_transverse_N_per_um"] == default["mean_mesh_stiffness_transverse_N_per_um"]


def test_the_stiffness_command_is_a_study_section():
    """``gearmesh stiffness`` runs a study's ``stiffness:`` section (commands._stiffness_section):
    given only the pair, every key it sets is the declared default, and it leaves out only the
    Fourier order (declared default) and the torque (none: no LSTE, as a study leaving it out)."""
    from pathlib import Path

    from gearmesh.cli import build_parser
    from gearmesh.commands import _stiffness_section
    from gearmesh.schema import defaults, jsonable
    from gearmesh.settings import Stiffness

    path = str(Path(__file__).resolve().parents[1] / "config/pairs/helical_z29_71_m5.yaml")
    section = _stiffness_section(build_parser().parse_args(["stiffness", path]))
    declared = defaults(Stiffness)
    assert set(declared) - set(section) == {"fourier_order"} | ({"torque_Nm"} & set(declared))
    assert {k: jsonable(v) for k, v in section.items()} == {k: declared[k] for k in section}
    given = _stiffness_section(build_parser().parse_args(["stiffness", path, "--torque-Nm", "500"]))
    assert given["torque_Nm"] == 500.0


@pytest.mark.parametrize("function, section, field", [
    (stiffness_table_dataset, {"positions": 4}, "positions"),
    (stiffness_table_dataset, {"methods": ["cubic"]}, "methods[0]"),
    (stiffness_table_dataset, {"torque_on": "rack"}, "torque_on"),
    (stiffness_table_dataset, {"variants": {"a b": {}}}, "variants"),
    (stiffness_table_dataset, {"slice": 40}, "slice"),  # an unknown key
    (stiffness_table_dataset, {"pairs": ["p2"]}, "pairs"),  # a pair not given
    (slice_convergence_dataset, {"slices": [40]}, "slices"),
    (slice_convergence_dataset, {"method": "cubic"}, "method"),
    (slice_convergence_dataset, {"rule": "clip"}, "rule"),  # an unknown key
    (slice_convergence_dataset, {"pairs": []}, "pairs"),
])
def test_the_study_tables_refuse_a_bad_setting_by_its_key(pair1, function, section, field):
    """The stiffness table and the slice convergence parse their section once
    (gearmesh.schema.settings_object): a value outside its declaration, an unknown key and a pair
    the caller did not give are refused by their key."""
    with pytest.raises(GearmeshInputError) as info:
        function({"p1": pair1}, **({"pairs": ["p1"]} | section))
    assert info.value.field == field


def test_a_study_table_takes_the_pairs_its_section_names_in_its_order(pair1):
    """``pairs`` names the table's pairs (in its order) among the loaded ``gear_pairs``; a pair left
    unnamed is not computed, and a pair's row does not depend on the others."""
    p2 = load_pair(low_fluctuation_pair1(helix_angle_deg=15.9554207))
    both = slice_convergence_dataset({"p1": pair1, "p2": p2, "unnamed": pair1}, pairs=["p2", "p1"],
                                     slices=(20, 40), positions=16)
    alone = slice_convergence_dataset({"p2": p2}, pairs=["p2"], slices=(20, 40), positions=16)
    assert both["pair"].values.tolist() == ["p2", "p1"]
    np.testing.assert_array_equal(both["mean_stiffness"].sel(pair="p2").values,
                                  alone["mean_stiffness"].sel(pair="p2").values)
    assert not np.array_equal(both["mean_stiffness"].sel(pair="p1").values,
                              both["mean_stiffness"].sel(pair="p2").values)
