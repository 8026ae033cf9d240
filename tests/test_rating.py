"""ISO 6336-2/-3 rating (gearmesh.rating): factors against a worked example, K_Hβ from the LTCA
against method C, bad inputs refused in one line, the CLI's JSON."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gearmesh.contact_model import ContactModel
from gearmesh.cli import main
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import pair_from_dict
from gearmesh.ltca import ltca
from gearmesh.rating import check_factors, ltca_load_factors, rating, rating_inputs
from gearmesh.rating_factors import (contact_ratio_factor, dynamic_factor_c, face_factor_root, face_load_factor_c,
                                     single_pair_factors, zone_factor)
from test_stress import SPUR

#: Worked example: hanslhansl/din3990 tests/test_1.py (DIN 3990-11, the method B of ISO 6336:1996 for
#: these factors): 55 kW at 980 rpm, K_A 1.75, DIN grades 6/7 (K1 = 9.6 spur), c_γ = 20 N/(mm µm).
P_KW, N1, K_A = 55.0, 980.0, 1.75


@pytest.fixture(scope="module")
def spur():
    return pair_geometry(pair_from_dict({**SPUR, "material": {"youngs_modulus_GPa": 206}}))


def test_contact_factors_agree_with_the_worked_example(spur):
    assert zone_factor(spur) == pytest.approx(2.3959406670899934, rel=1e-9)
    assert contact_ratio_factor(spur.eps_alpha, spur.eps_beta) == pytest.approx(0.906214912960638, rel=1e-9)
    z_b, z_d, m1, m2 = single_pair_factors(spur)
    assert (z_b, z_d) == pytest.approx((1.00554704549864, 1.0), rel=1e-9)
    assert m2 == pytest.approx(0.8835590102280203, rel=1e-9)
    t1 = P_KW * 1e3 / (N1 * 2 * math.pi / 60)
    r = rating(spur, t1, N1, application_factor=K_A, factors={"K_v": 1.0278576187783273, "K_Hbeta": 1.1064272863295082})
    assert r.values["Z_E"] == pytest.approx(189.8, abs=0.02)
    assert r.values["sigma_H0_MPa"] == pytest.approx(875.3827378988153, rel=2e-4)  # Z_E 189.81 against 189.8
    assert r.values["K_Halpha"] == 1.0  # the example's K_Hα = 1 (grade 6, this load)
    assert r.values["sigma_H_MPa"][0] == pytest.approx(1241.7875902772687, rel=2e-4)
    assert r.values["force_tangential_N"] == pytest.approx(14103.41869503906, rel=1e-9)
    assert r.given == ["K_A", "K_Hbeta", "K_v"] and r.sources["K_v"] == "given" and r.sources["K_Halpha"] == "iso"


def test_dynamic_and_face_factors_agree_with_the_worked_example():
    kv = dynamic_factor_c(6, 0.0, 3.89976368065613, 19, 104 / 19, 507.4215196611504, k1=(9.6, 8.5))
    assert kv == pytest.approx(1.0278576187783273, rel=1e-9)
    k_hb, parts = face_load_factor_c(25368.536123904036 / 48.64, 20.0, 0.0, 0.64)
    assert parts["f_sh_um"] == pytest.approx(4.913484891366676, rel=1e-9)
    assert parts["F_betax_um"] == pytest.approx(6.534934905517679, rel=1e-9)
    assert k_hb == pytest.approx(1.1064272863295082, rel=1e-4)  # the example's y_β is 0.4 % larger
    assert face_factor_root(1.1064272863295082, 48.64 / 9.0) == pytest.approx(1.0864854433487987, rel=1e-6)


def test_ltca_face_load_factor_is_one_aligned_and_follows_method_c_with_a_lead_slope(spur):
    """Linear contact law (the ISO model's springs), no running-in: K_Hβ = 1 + c̄ F_β/(2 F/b) with c̄
    the LTCA's mean mesh stiffness per unit width, at the centre of the end slice (1 − 1/N of F_β)."""
    n = 20
    for f in (0.0, 5e-6, 10e-6):
        res = ltca(spur, [500.0], 32, ContactModel(points=n, contact_law="linear"), lead_slope=(f, 0.0))
        k = ltca_load_factors(res.load)["K_Hbeta"][0]
        c = res.stiffness.mean() / spur.face_width
        expected = 1 + c * f * (1 - 1 / n) / (2 * res.force[0] / spur.face_width)
        assert k == pytest.approx(expected, rel=2e-3)
        # ISO method C's formula with the same stiffness and misalignment, no bending, no running-in
        iso, _ = face_load_factor_c(res.force[0] / spur.face_width * 1e-3, c * 1e-9, f * 1e6 * (1 - 1 / n), 0.0,
                                    running_in=False)
        assert k == pytest.approx(iso, rel=2e-3)


def test_rating_safety_factors_are_limits_over_stresses(spur):
    r = rating(spur, 500.0, 1500.0, life_hours=20000.0).values
    for i in (0, 1):
        assert r["S_H"][i] == pytest.approx(r["sigma_HG_MPa"][i] / r["sigma_H_MPa"][i])
        assert r["S_F"][i] == pytest.approx(r["sigma_FG_MPa"][i] / r["sigma_F_MPa"][i])
    # doubling the torque: σ_H by √2, σ_F by 2 when the factors are held
    fixed = {"K_v": 1.1, "K_Hbeta": 1.2, "K_Fbeta": 1.15, "K_Halpha": 1.0, "K_Falpha": 1.0}
    a, b = (rating(spur, t, 1500.0, factors=fixed).values for t in (500.0, 1000.0))
    assert b["sigma_H_MPa"][0] / a["sigma_H_MPa"][0] == pytest.approx(math.sqrt(2))
    assert b["sigma_F_MPa"][1] / a["sigma_F_MPa"][1] == pytest.approx(2.0)


@pytest.mark.parametrize("given, field", [
    ({"contact_fatigue_limit_MPa": -1500}, "contact_fatigue_limit_MPa"),
    ({"bending_fatigue_limit_MPa": 0}, "bending_fatigue_limit_MPa"),
    ({"accuracy_grade": 13}, "accuracy_grade"),
    ({"accuracy_grade": 0}, "accuracy_grade"),
    ({"accuracy_grade": 5.5}, "accuracy_grade"),
    ({"viscosity_40C_mm2_s": 100, "viscosity_100C_mm2_s": 150}, "viscosity_100C_mm2_s"),
])
def test_bad_rating_inputs_are_refused(given, field):
    with pytest.raises(GearmeshInputError, match=field):
        rating_inputs(given)


@pytest.mark.parametrize("spec, field", [
    ({"material": {"contact_fatigue_limit_MPa": -1}}, "material.contact_fatigue_limit_MPa"),
    ({"accuracy_grade": 13}, "accuracy_grade"),
    ({"roughness_um": {"flank_Rz": -2}}, "roughness_um.flank_Rz"),
    ({"roughness_um": {"flank_Rq": 2}}, "flank_Rq"),
    ({"lubricant": {"oil_temperature_C": 400}}, "lubricant.oil_temperature_C"),
    ({"tip_edge_radius_mm": 0}, "tip_edge_radius_mm"),
])
def test_bad_pair_file_rating_inputs_are_refused(spec, field):
    with pytest.raises(GearmeshInputError, match=field.replace(".", r"\.")):
        pair_from_dict({**SPUR, **spec})


@pytest.mark.parametrize("factors, name", [({"K_v": 0.9}, "K_v"), ({"K_Hbeta": 0.5}, "K_Hbeta"),
                                           ({"K_Q": 1.2}, "K_Q"), ({"Z_L": -1.0}, "Z_L")])
def test_bad_factors_are_refused(factors, name):
    with pytest.raises(GearmeshInputError, match=name):
        check_factors(factors)


CLI_KEYS = {"Z_H", "Z_E", "Z_epsilon", "Z_beta", "sigma_H0_MPa", "sigma_H_MPa", "sigma_HP_MPa", "S_H", "Y_F", "Y_S",
            "Y_beta", "sigma_F0_MPa", "sigma_F_MPa", "sigma_FP_MPa", "S_F", "K_v", "K_Hbeta", "K_Fbeta", "K_Halpha",
            "K_Falpha"}


def test_cli_rating_json(root, capsys):
    pair = str(root / "config/pairs/helical_z29_71_m5.yaml")
    assert main(["rating", pair, "--torque-Nm", "1000", "--speed-rpm", "5000", "--factor", "K_v=1.2",
                 "--application-factor", "1.25", "--points", "20", "--positions", "16", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert CLI_KEYS <= set(out)
    for key in ("sigma_H_MPa", "S_H", "Y_F", "S_F", "sigma_FP_MPa"):
        assert len(out[key]) == 2
    assert out["K_v"] == 1.2 and out["K_A"] == 1.25 and out["factors_given"] == ["K_A", "K_v"]
    assert out["ltca"]["peak_contact_pressure_at"]["on"] in ("edge", "flank")
    assert len(out["ltca"]["peak_root_stress_MPa"]) == 2
    for fe, iso, ratio in zip(out["ltca"]["peak_root_stress_fe_MPa"], out["ltca"]["peak_root_stress_MPa"],
                              out["ltca"]["root_stress_fe_over_iso"]):
        assert fe == pytest.approx(iso * ratio) and 0.5 < ratio < 1.5
    assert any("contact_fatigue_limit_MPa" in n for n in out["notes"])


@pytest.mark.parametrize("args, message", [
    (["--factor", "K_v=0.9"], "factor K_v = 0.9: must lie in [1, 10]"),
    (["--factor", "K_v"], "--factor"),
    (["--application-factor", "0.5"], "--application-factor = 0.5: must be at least 1"),  # the option, as typed
    (["--speed-rpm", "-5"], "speed_rpm"),
])
def test_cli_rating_refuses_bad_input_in_one_line(root, capsys, args, message):
    base = ["rating", str(root / "config/pairs/helical_z29_71_m5.yaml"), "--torque-Nm", "1000", "--speed-rpm", "5000"]
    try:
        code = main(base + args)
    except SystemExit as exc:  # argparse's own refusals (the one line of gearmesh.cli._Parser)
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0]


def test_ltca_dataset_carries_the_load_capacity_variables():
    from gearmesh.datasets.ltca import ltca_dataset
    from gearmesh.datasets.rating import reference_ltca
    from gearmesh.pairfile import example_pair, load_pair, variant_pair

    base = load_pair(example_pair("helical_z29_71_m5"))
    relief = variant_pair(base, "relief", {"modification": {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 3}}})
    kw = dict(torques_Nm=[400.0, 1600.0], positions=16, points=20, method="transition")
    std, mod = ltca_dataset(base, **kw), ltca_dataset(relief, **kw)
    for name in ("contact_pressure", "peak_contact_pressure", "root_stress", "peak_root_stress", "K_Hbeta_ltca",
                 "K_Fbeta_ltca", "K_Halpha_ltca", "K_Falpha_ltca", "lte_harmonics", "peak_contact_pressure_on_edge"):
        assert {"units", "long_name"} <= set(mod[name].attrs), name
    assert list(mod.mesh_order.values) == [1, 2, 3]
    assert np.all(std.K_Halpha_ltca.values == 1.0)  # the unmodified pair is its own reference
    # the relief variant's K_Hα: its largest tooth-pair load over the unmodified pair's
    assert np.allclose(mod.K_Halpha_ltca.values,
                       np.maximum(mod.pair_load.max(("position", "line")).values
                                  / std.pair_load.max(("position", "line")).values, 1.0), rtol=1e-9)
    # harmonics: the amplitude of order k of a mesh cycle's LTE by direct projection
    lte = mod.lte.values[1]
    n = lte.size
    k = 2
    amp = 2 * abs(np.sum(lte * np.exp(-2j * np.pi * k * np.arange(n) / n))) / n
    assert mod.lte_harmonics.values[1, k - 1] == pytest.approx(amp, rel=1e-12)
    assert np.all(mod.peak_root_stress.values[1] > mod.peak_root_stress.values[0])


def test_load_capacity_table_names_the_variants_from_the_jobs_wildcards():
    from gearmesh.datasets.rating import load_capacity_table_dataset

    def ds(variant, s_h):
        import xarray as xr
        out = xr.Dataset({"S_H": (("torque", "gear"), [[s_h, s_h + 1]]), "S_F": (("torque", "gear"), [[3.0, 2.0]]),
                          "peak_contact_pressure": (("torque",), [1e9]),
                          "peak_contact_pressure_on_edge": (("torque",), [1]),
                          "peak_root_stress": (("torque", "gear"), [[1e8, 2e8]]), "K_Hbeta": (("torque",), [1.2]),
                          "shaft_misalignment": (("torque",), [-1e-6])}, coords={"torque": [1000.0]})
        out.attrs["gearmesh_wildcards_json"] = json.dumps({"variant": variant})
        return out

    table = load_capacity_table_dataset([ds("standard", 2.0), ds("relief", 1.5)])
    assert list(table.variant.values) == ["standard", "relief"]
    assert table.S_H.values.tolist() == [[2.0], [1.5]] and table.S_F.values.tolist() == [[2.0], [2.0]]
    assert table.peak_root_stress.values.tolist() == [[2e8], [2e8]]


# --------------------------------------------------------------------------------------
# Life factors (ISO 6336-2/-3:2019) and the mean stress factor Y_M
# --------------------------------------------------------------------------------------


def test_life_factors_follow_the_standards_lines():
    """ISO 6336-2:2019 Table 2 line 2 and ISO 6336-3:2019 Table 3 (case-hardened): the tabulated points,
    and between the knee and 10¹⁰ the closed forms of the standards' figures, (5e7/N)^0.0307 and
    (3e6/N)^0.02 (written here independently of the code's log-log table)."""
    from gearmesh.rating_factors import life_factor_contact, life_factor_root

    for n, z in ((1e4, 1.6), (1e5, 1.6), (5e7, 1.0), (1e10, 0.85), (1e12, 0.85)):
        assert life_factor_contact(n) == pytest.approx(z, rel=1e-12)
    for n, y in ((1e2, 2.5), (1e3, 2.5), (3e6, 1.0), (1e10, 0.85)):
        assert life_factor_root(n) == pytest.approx(y, rel=1e-12)
    for n in (1e8, 1e9, 3e9):
        assert life_factor_contact(n) == pytest.approx((5e7 / n) ** 0.0307, rel=2e-3)
        assert life_factor_root(n) == pytest.approx((3e6 / n) ** 0.02, rel=2e-3)
    # optimum conditions: 1.0 beyond the knee, the same curve before it
    assert life_factor_contact(1e9, "optimum") == life_factor_root(1e9, "optimum") == 1.0
    assert life_factor_contact(1e6, "optimum") == life_factor_contact(1e6)
    with pytest.raises(GearmeshInputError, match="life_factor_conditions"):
        life_factor_root(1e9, "ideal")


def test_endurance_takes_the_long_life_end_and_optimum_conditions_hold_one(spur):
    """Without life_hours: N_L = 1e10, so under 'normal' conditions S_H and S_F are 0.85 of the
    'optimum' ones exactly (the issue's +17.6 % against a commercial report is 1/0.85 = 1.176)."""
    normal = rating(spur, 500.0, 1500.0, rating_inputs())
    optimum = rating(spur, 500.0, 1500.0, rating_inputs({"life_factor_conditions": "optimum"}))
    for key in ("S_H", "S_F"):
        assert np.array(normal.values[key]) / np.array(optimum.values[key]) == pytest.approx([0.85, 0.85], rel=1e-12)
    assert normal.values["Z_NT"] == [0.85, 0.85] and optimum.values["Y_NT"] == [1.0, 1.0]
    assert any("1e+10" in n and "normal conditions" in n for n in normal.notes)
    assert any("life_factor_conditions = normal not given" in n for n in normal.notes)
    # a finite life on the sloping branch: the pinion sees u times the gear's cycles
    r = rating(spur, 500.0, 1500.0, life_hours=20000.0).values
    n1 = 20000.0 * 60 * 1500.0
    assert r["load_cycles"][0] == pytest.approx(n1) and r["Z_NT"][0] == pytest.approx((5e7 / n1) ** 0.0307, rel=2e-3)


def test_an_idlers_bending_safety_is_its_one_way_safety_times_y_m(spur):
    """Y_M (ISO 6336-3:2019) in σ_FG: the idler's S_F is the same gear's one-way S_F times 0.7, the
    other gear and pitting untouched."""
    from gearmesh.rating_factors import IDLER_MEAN_STRESS_FACTOR

    one_way = rating(spur, 500.0, 1500.0, rating_inputs()).values
    idler = rating(spur, 500.0, 1500.0, rating_inputs({"idler_gear": "gear"})).values
    assert idler["Y_M"] == [1.0, IDLER_MEAN_STRESS_FACTOR] and one_way["Y_M"] == [1.0, 1.0]
    assert idler["S_F"][1] == pytest.approx(one_way["S_F"][1] * 0.7, rel=1e-12)
    assert idler["S_F"][0] == one_way["S_F"][0] and idler["S_H"] == one_way["S_H"]
    given = rating(spur, 500.0, 1500.0, factors={"Y_M": 0.8})
    assert given.values["Y_M"] == [0.8, 0.8] and given.sources["Y_M"] == "given"


def test_pair_file_life_idler_and_fzg_keys_are_read_and_refused_in_one_line():
    pair = pair_from_dict({**SPUR, "life_factor_conditions": "optimum", "idler_gear": "pinion",
                           "lubricant": {"fzg_load_stage": 9}})
    given = dict(pair.rating_inputs)
    assert given["life_factor_conditions"] == "optimum" and given["idler_gear"] == "pinion"
    assert given["fzg_load_stage"] == 9 and isinstance(given["fzg_load_stage"], int)
    for spec, field in (({"life_factor_conditions": "best"}, "life_factor_conditions"),
                        ({"idler_gear": "both"}, "idler_gear"), ({"idler_gear": True}, "idler_gear"),
                        ({"lubricant": {"fzg_load_stage": 13}}, "lubricant.fzg_load_stage"),
                        ({"lubricant": {"fzg_load_stage": 0}}, "lubricant.fzg_load_stage"),
                        ({"lubricant": {"fzg_load_stage": 8.5}}, "lubricant.fzg_load_stage")):
        with pytest.raises(GearmeshInputError) as info:
            pair_from_dict({**SPUR, **spec})
        assert info.value.field == field


#: The KISSsoft report's stage of tests/test_pairfile.py (issue 18): only its geometry is in the
#: repository; the report's life factors and safety factors are not.
KISSSOFT_STAGE = {"teeth": [24, 95], "normal_module_mm": 14, "normal_pressure_angle_deg": 20, "helix_angle_deg": 10,
                  "face_width_mm": 360, "profile_shift": [0.48, 0.6691], "center_distance_mm": 861.000,
                  "tip_diameter_mm": [380.747, 1395.376], "basic_rack_profile": "ISO 53 A",
                  "bore_diameter_mm": [179.10, 1193.32]}


def test_the_commercial_stage_at_endurance_moves_by_the_long_life_factor_alone():
    """The report's stage rated at endurance: 'normal' against 'optimum' conditions changes S_H and
    S_F by 0.85 and nothing else (the size of the discrepancy issue 34 measured, +17.6 % / +17.7 %)."""
    geom = pair_geometry(pair_from_dict({**KISSSOFT_STAGE, "name": "kisssoft_stage"}))
    a = rating(geom, 80e3, 300.0, rating_inputs()).values
    b = rating(geom, 80e3, 300.0, rating_inputs({"life_factor_conditions": "optimum"})).values
    assert [x / y for x, y in zip(b["S_H"], a["S_H"])] == pytest.approx([1 / 0.85] * 2, rel=1e-12)
    assert [x / y for x, y in zip(b["S_F"], a["S_F"])] == pytest.approx([1 / 0.85] * 2, rel=1e-12)
    assert a["sigma_H_MPa"] == b["sigma_H_MPa"] and a["sigma_F_MPa"] == b["sigma_F_MPa"]


def test_the_rating_command_differs_from_a_study_only_by_its_listed_overrides():
    """``gearmesh rating`` runs a study's ``rating:`` and ``ltca:`` sections (commands._rating_sections):
    given only its operating point, every key it sets is the declared default but the speed, and
    what it leaves out of the LTCA's is the map its one torque replaces and the LTCA's model (the
    declared defaults). rating_summary refuses the LTCA's torque map rather than parse and ignore it."""
    from pathlib import Path

    from gearmesh.cli import build_parser
    from gearmesh.commands import _rating_sections
    from gearmesh.datasets.rating import rating_summary
    from gearmesh.schema import defaults, jsonable
    from gearmesh.pairfile import load_pair
    from gearmesh.settings import Ltca, Rating

    path = str(Path(__file__).resolve().parents[1] / "config/pairs/helical_z29_71_m5.yaml")
    pair = load_pair(path)
    args = build_parser().parse_args(["rating", path, "--torque-Nm", "1000", "--speed-rpm", "5000"])
    rating, contact = _rating_sections(args)
    assert rating == {**defaults(Rating), "speed_rpm": 5000.0}
    declared = defaults(Ltca)
    assert set(contact) == set(declared) - {"torques_Nm", "contact_law", "method", "corner_extension"}
    assert {k: jsonable(v) for k, v in contact.items()} == {k: declared[k] for k in contact}
    with pytest.raises(GearmeshInputError, match="torques_Nm"):
        rating_summary(pair, 1000.0, speed_rpm=5000.0, ltca_section={"torques_Nm": [1000.0]})
    with pytest.raises(GearmeshInputError, match="speed_rpm"):
        rating_summary(pair, 1000.0, speed_rpm=-1.0)
