"""Pair data, validation and basic geometry (gearmesh.gear) against hand-derived values.

Every expected number is derived in the comments from ISO 21771:2007 formulas (the
calculator steps are written out), not copied from the code's output.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gearmesh.errors import GearmeshInputError
from gearmesh.gear import GearPair, Modification, involute, pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict, pair_to_dict

from pairs import STEEL, low_fluctuation_pair1


def spur_20_40(**over):
    d = dict(name="spur", teeth=[20, 40], normal_module_mm=4, normal_pressure_angle_deg=20,
             helix_angle_deg=0, face_width_mm=30)
    d.update(over)
    return d


def refusal(data=None, pair=None) -> GearmeshInputError:
    with pytest.raises(GearmeshInputError) as info:
        p = pair if pair is not None else pair_from_dict(data)
        pair_geometry(p)
    return info.value


# --------------------------------------------------------------------------------------
# Contact ratios, masses, inertias
# --------------------------------------------------------------------------------------


def test_seed001_pair1_contact_ratios_mass_inertia():
    g = pair_geometry(pair_from_dict(low_fluctuation_pair1()))
    # Hand derivation (mm):
    #   mt = 1.75/cos10° = 1.75/0.984808 = 1.776997
    #   αt = atan(tan25°/cos10°) = atan(0.466308/0.984808) = atan(0.473501) = 25.3376°
    #   r1 = 29·1.776997/2 = 25.76645, r2 = 49·1.776997/2 = 43.53642, a = 69.30287
    #   rb = r cos αt: 23.28776, 39.34829;  ra = r + 1.75: 27.51645, 45.28642
    #   ρa1 = √(27.51645² − 23.28776²) = √214.8349 = 14.65725
    #   ρa2 = √(45.28642² − 39.34829²) = √502.5712 = 22.41810
    #   a sin αt = 69.30287·0.427952 = 29.65824;  gα = 14.65725 + 22.41810 − 29.65824 = 7.41711
    #   pbt = π·1.776997·cos αt = 5.04556;  εα = 7.41711/5.04556 = 1.47002  (Table 1: 1.470)
    #   εβ = 20 sin10°/(π·1.75) = 3.47296/5.49779 = 0.6317           (Table 1: 0.632)
    assert g.transverse_module == pytest.approx(1.776997e-3, rel=1e-6)
    assert math.degrees(g.transverse_pressure_angle) == pytest.approx(25.3376, abs=1e-4)
    assert g.center_distance == pytest.approx(69.30287e-3, rel=1e-6)
    assert g.path_of_contact == pytest.approx(7.41711e-3, rel=2e-6)
    assert g.transverse_base_pitch == pytest.approx(5.04556e-3, rel=2e-6)
    assert g.eps_alpha == pytest.approx(1.470, abs=5e-4)
    assert g.eps_beta == pytest.approx(0.632, abs=5e-4)
    assert g.eps_gamma == pytest.approx(2.102, abs=1e-3)  # Table 1 εγ = 2.102
    # Mass and inertia of the disc of reference radius minus the bore (the low-fluctuation paper convention):
    #   m1 = 7850·π·(25.76645² − 15²)·20·1e-9 = 7850·π·438.910·20e-9 = 0.21648 kg  (0.2165)
    #   m2 = 7850·π·(43.53642² − 25²)·20e-9 = 7850·π·1270.42·20e-9 = 0.62661 kg     (0.6266)
    #   J1 = m1(r1² + ri²)/2 = 0.21648·(663.910 + 225)e-6/2 = 0.962e-4 kg m²      (0.96e-4)
    #   J2 = 0.62661·(1895.42 + 625)e-6/2 = 7.897e-4 kg m²                         (7.90e-4)
    np.testing.assert_allclose(g.mass, [0.2165, 0.6266], atol=1e-4)
    np.testing.assert_allclose(g.inertia, [0.96e-4, 7.90e-4], rtol=5e-3)
    # A standard pair at its standard distance has zero backlash and αwt = αt.
    assert g.backlash_normal == pytest.approx(0.0, abs=1e-12)
    assert g.operating_pressure_angle == pytest.approx(g.transverse_pressure_angle, abs=1e-12)


def test_spur_textbook_contact_ratio():
    g = pair_geometry(pair_from_dict(spur_20_40()))
    # z 20/40, m 4, α 20°, standard: rb = 37.58770, 75.17541; ra = 44, 84
    #   ρa1 = √(44² − 37.5877²) = 22.87279, ρa2 = √(84² − 75.17541²) = 37.47876
    #   a sin α = 120·0.342020 = 41.04242; gα = 19.30914; pb = π·4·cos20° = 11.80853
    #   εα = 1.63519 (textbook value for 20/40 teeth at 20°: 1.635)
    assert g.eps_alpha == pytest.approx(1.63519, abs=1e-5)
    assert g.eps_beta == 0.0
    assert g.base_helix_angle == 0.0
    np.testing.assert_allclose(g.base_radius, [37.58770e-3, 75.17541e-3], rtol=1e-6)


def test_zero_backlash_centre_distance_with_shifts():
    g = pair_geometry(pair_from_dict(spur_20_40(profile_shift=[0.3, 0.2])))
    # inv αw = inv 20° + 2 tan20°·(0.3 + 0.2)/60 = 0.0149044 + 0.0060662 = 0.0209706
    #   αw = 22.31671°,  a0 = 120 cos20°/cos αw = 121.89302 mm
    assert math.degrees(g.operating_pressure_angle) == pytest.approx(22.31671, abs=1e-5)
    assert g.zero_backlash_center_distance == pytest.approx(121.89302e-3, rel=1e-7)
    assert g.center_distance == g.zero_backlash_center_distance
    assert g.backlash_normal == pytest.approx(0.0, abs=1e-12)
    # Tip radii grow by x·m: 44 + 1.2, 84 + 0.8
    np.testing.assert_allclose(g.tip_radius, [45.2e-3, 84.8e-3], rtol=1e-12)
    assert not g.shift_inferred


def test_backlash_when_centre_distance_is_larger():
    a0 = 121.89302
    g = pair_geometry(pair_from_dict(spur_20_40(profile_shift=[0.3, 0.2], center_distance_mm=a0 + 0.1)))
    # cos αw' = 120 cos20°/122.00... -> αw' = 22.43085°; along the line of action
    #   j_bn = 2(rb1 + rb2)(inv αw' − inv αw0) = 2·112.76311·(0.0213082 − 0.0209706) = 0.07613 mm
    #   (first order: 2 Δa sin αw0 = 0.2·0.37971 = 0.07595 mm)
    assert math.degrees(g.operating_pressure_angle) == pytest.approx(22.43085, abs=1e-4)
    assert g.backlash_normal == pytest.approx(0.07613e-3, rel=2e-4)
    assert g.backlash_normal > 0


def test_shift_inferred_and_split_from_centre_distance():
    g = pair_geometry(pair_from_dict(spur_20_40(center_distance_mm=122.0)))
    # cos αw = 120 cos20°/122 -> αw = 22.43879°, inv αw = 0.0213317
    #   Σx = (0.0213317 − 0.0149044)·60/(2 tan20°) = 0.52977, split 0.26489 each
    assert g.shift_inferred
    np.testing.assert_allclose(g.profile_shift, [0.26489, 0.26489], atol=2e-5)
    assert g.center_distance == pytest.approx(0.122)
    assert g.backlash_normal == pytest.approx(0.0, abs=1e-10)


def test_seed001_pair_file_and_round_trip():
    path = Path(__file__).resolve().parents[1] / "config" / "pairs" / "low_fluctuation_pair1.yaml"
    if path.exists():  # the library file gives the standard distance rounded to 69.30 mm
        assert pair_geometry(load_pair(path)).eps_alpha == pytest.approx(1.470, abs=5e-4)
    q = pair_from_dict(low_fluctuation_pair1(profile_shift=[0.1, -0.1]))
    assert pair_from_dict(pair_to_dict(q)) == q


# --------------------------------------------------------------------------------------
# Refusals of pair_from_dict (form of the data)
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize("data, field", [
    ([1, 2], "pair"),
    (low_fluctuation_pair1(colour="red"), "pair.colour"),
    (low_fluctuation_pair1(name=""), "name"),
    (low_fluctuation_pair1(name=3), "name"),
    (low_fluctuation_pair1(teeth=29), "teeth"),
    (low_fluctuation_pair1(teeth=[29, 49, 3]), "teeth"),
    (low_fluctuation_pair1(teeth=[29.0, 49]), "teeth[0]"),
    (low_fluctuation_pair1(teeth=[29, True]), "teeth[1]"),
    (low_fluctuation_pair1(teeth=[4, 49]), "teeth[0]"),
    (low_fluctuation_pair1(normal_module_mm=0), "normal_module_mm"),
    (low_fluctuation_pair1(normal_module_mm=-1.75), "normal_module_mm"),
    (low_fluctuation_pair1(normal_module_mm="1.75"), "normal_module_mm"),
    (low_fluctuation_pair1(normal_module_mm=float("nan")), "normal_module_mm"),
    (low_fluctuation_pair1(normal_pressure_angle_deg=0), "normal_pressure_angle_deg"),
    (low_fluctuation_pair1(normal_pressure_angle_deg=45), "normal_pressure_angle_deg"),
    (low_fluctuation_pair1(normal_pressure_angle_deg=True), "normal_pressure_angle_deg"),
    (low_fluctuation_pair1(helix_angle_deg=-1), "helix_angle_deg"),
    (low_fluctuation_pair1(helix_angle_deg=60), "helix_angle_deg"),
    (low_fluctuation_pair1(helix_hand="up"), "helix_hand"),
    (low_fluctuation_pair1(face_width_mm=0), "face_width_mm"),
    (low_fluctuation_pair1(face_width_mm=[20, -1]), "face_width_mm[1]"),
    (low_fluctuation_pair1(face_width_mm=[20, 20, 20]), "face_width_mm"),
    (low_fluctuation_pair1(profile_shift=[0.1, 3.0]), "profile_shift[1]"),
    (low_fluctuation_pair1(profile_shift="0.1"), "profile_shift"),
    (low_fluctuation_pair1(center_distance_mm=0), "center_distance_mm"),
    (low_fluctuation_pair1(center_distance_mm=-69.3), "center_distance_mm"),
    (low_fluctuation_pair1(addendum_coefficient=0), "addendum_coefficient"),
    (low_fluctuation_pair1(dedendum_coefficient=[1.25, -1]), "dedendum_coefficient[1]"),
    (low_fluctuation_pair1(tool_tip_radius_coefficient=-0.1), "tool_tip_radius_coefficient"),
    (low_fluctuation_pair1(bore_radius_mm=[-1, 25]), "bore_radius_mm[0]"),
    (low_fluctuation_pair1(material="steel"), "material"),
    (low_fluctuation_pair1(material={**STEEL, "colour": 1}), "material.colour"),
    (low_fluctuation_pair1(material={**STEEL, "poisson_ratio": 0.5}), "material.poisson_ratio"),
    (low_fluctuation_pair1(material={**STEEL, "youngs_modulus_GPa": 0}), "material.youngs_modulus_GPa"),
    (low_fluctuation_pair1(material={**STEEL, "density_kg_m3": -1}), "material.density_kg_m3"),
    (low_fluctuation_pair1(modification=[1]), "modification"),
    (low_fluctuation_pair1(modification={"wheel": {}}), "modification.wheel"),
    (low_fluctuation_pair1(modification={"pinion": 5}), "modification.pinion"),
    (low_fluctuation_pair1(modification={"pinion": {"tip_relief_mm": 1}}), "modification.pinion.tip_relief_mm"),
    (low_fluctuation_pair1(modification={"gear": {"crowning_um": -1}}), "modification.gear.crowning_um"),
])
def test_pair_from_dict_refusals(data, field):
    with pytest.raises(GearmeshInputError) as info:
        pair_from_dict(data)
    assert info.value.field == field
    assert field.split("[")[0].split(".")[0] in str(info.value) or field in str(info.value)


@pytest.mark.parametrize("missing", ["name", "teeth", "normal_module_mm", "normal_pressure_angle_deg",
                                     "helix_angle_deg", "face_width_mm"])
def test_missing_required_key(missing):
    data = low_fluctuation_pair1()
    del data[missing]
    with pytest.raises(GearmeshInputError) as info:
        pair_from_dict(data)
    assert info.value.field == missing


def test_load_pair_refusals(tmp_path):
    with pytest.raises(GearmeshInputError) as info:
        load_pair(tmp_path / "absent.yaml")
    assert info.value.field == "pair file"
    bad = tmp_path / "bad.yaml"
    bad.write_text("teeth: [29, 49\n")
    with pytest.raises(GearmeshInputError) as info:
        load_pair(bad)
    assert info.value.field == "pair file"


# --------------------------------------------------------------------------------------
# Refusals of pair_geometry (physics of the pair)
# --------------------------------------------------------------------------------------


def test_centre_distance_below_zero_backlash():
    # shifts given (0.3/0.2): a0 = 121.89302 mm (above); 121.8 mm would interpenetrate
    err = refusal(spur_20_40(profile_shift=[0.3, 0.2], center_distance_mm=121.8))
    assert err.field == "center_distance_mm"
    # standard pair 29/49 (a0 = 69.30287 mm) with explicit zero shifts at 69.2 mm
    err = refusal(low_fluctuation_pair1(profile_shift=[0, 0], center_distance_mm=69.2))
    assert err.field == "center_distance_mm"


def test_centre_distance_below_base_circles():
    # Σ rb = 112.76311 mm for 20/40, m 4: 112 mm leaves no line of action at all
    err = refusal(spur_20_40(center_distance_mm=112.0))
    assert err.field == "center_distance_mm"


def test_seed000_centre_distance_cannot_exist():
    """The mesh-in impact paper Table 1: 29/71, mn 5, αn 20°, β 27.5°, b 42, a = 261.0 mm.

    αt = atan(tan20°/cos27.5°) = 22.3100°; standard a = 100·5/(2 cos27.5°) = 281.85 mm;
    Σ rb = 281.85·cos αt = 260.748 mm, so 261.0 mm needs αwt = acos(260.748/261) = 2.5° and a
    total shift Σx = (inv 2.5° − inv 22.31°)·100/(2 tan20°) ≈ −2.88: the tips cut past the
    base tangent points. With explicit zero shifts it is simply below zero backlash.
    """
    base = dict(name="s000", teeth=[29, 71], normal_module_mm=5, normal_pressure_angle_deg=20,
                helix_angle_deg=27.5, face_width_mm=42)
    assert pair_geometry(pair_from_dict(base)).center_distance == pytest.approx(281.85e-3, abs=1e-5)
    err = refusal({**base, "profile_shift": [0, 0], "center_distance_mm": 261.0})
    assert err.field == "center_distance_mm"
    # Without shifts the inferred shifts undercut both gears: the form circle needs profile.py.
    pytest.importorskip("gearmesh.profile")
    err = refusal({**base, "center_distance_mm": 261.0})
    assert err.field == "center_distance_mm"


def test_shift_sum_too_negative():
    # inv αwt0 = inv 20° + 2 tan20°·(−5.8)/20 = 0.0149 − 0.2111 < 0: no operating angle
    err = refusal(dict(name="n", teeth=[10, 10], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10, profile_shift=[-2.9, -2.9]))
    assert err.field == "profile_shift"


def test_pointed_teeth():
    # z 10, x = 1.2: s_t = m(π/2 + 2·1.2·tan20°) = 2.444 m, but at r_a = (5 + 2.2) m the
    # thickness 2r_a(s/2r + inv20° − inv αa) with αa = acos(4.6985/7.2) = 49.26° goes negative
    err = refusal(dict(name="p", teeth=[10, 40], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10, profile_shift=[1.2, 0.0]))
    assert err.field == "profile_shift[0]"
    assert "pointed" in err.rule


def test_fillet_interference():
    # 29/49 standard at αn 25° with addendum 1.2 and a 0.38 mn tool tip: the gear tip
    # (ρ_SAP1 = a sin αt − ρa2) reaches below the pinion's form point (h_FfP = 1.25 − 0.38(1 − sin25°) = 1.03 mn)
    err = refusal(low_fluctuation_pair1(addendum_coefficient=[1.0, 1.2]))
    assert err.field == "profile_shift[0]"
    assert "fillet interference" in err.rule


def test_fillet_interference_with_undercut():
    # 13/13 at 20°, standard: z < 2/sin²20° = 17.1 -> the pinion is undercut (the rack's
    # straight flank ends h_FfP/sin α = (1.25 − 0.38·0.658)·2/0.342 = 5.85 mm below the pitch
    # point, past T1 at r sin α = 13·0.342 = 4.45 mm), and the mate's tip reaches into the
    # undercut. The true form point comes from the trochoid (gearmesh.profile).
    pytest.importorskip("gearmesh.profile")
    err = refusal(dict(name="u", teeth=[13, 13], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10))
    assert err.field == "profile_shift[0]"
    assert "undercut" in err.rule


def test_involute_interference_past_base_tangent_point():
    # 14/100, m 2, α 20°: T1 lies r1 sin α = 14·sin20° = 4.788 mm from the pitch point. A short
    # pinion tool (h_f = 0.8, ρ* = 0) leaves no undercut (form point h_FfP/sin α = 1.6/0.342 =
    # 4.678 mm < 4.788 mm), but a gear addendum of 1.5 m reaches
    # ρa2 = √(103² − 93.969²) = 42.176 mm > a sin α = 114·0.34202 = 38.990 mm along the line of
    # action: ρ_SAP1 = 38.990 − 42.176 < 0, the gear tip passes T1.
    err = refusal(dict(name="i", teeth=[14, 100], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10, addendum_coefficient=[1.0, 1.5],
                       dedendum_coefficient=[0.8, 1.25], tool_tip_radius_coefficient=0))
    assert err.field == "addendum_coefficient[1]"
    assert "involute interference" in err.rule


def test_tip_inside_base_circle():
    # z 60, αn 20°: r − rb = 30 m (1 − cos20°) = 1.81 m, but with x1 = −2.9 the pinion tip is
    # only (h_a + x1) m = −1.9 m above the reference circle: r_a = 56.2 mm < r_b = 56.382 mm
    err = refusal(dict(name="t", teeth=[60, 60], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10, profile_shift=[-2.9, 2.9]))
    assert err.field == "addendum_coefficient[0]"


def test_root_at_or_below_axis():
    # z 5, m 2: r = 5 mm; h_f = 3 -> r_f = 5 − 6 < 0
    err = refusal(dict(name="r", teeth=[5, 40], normal_module_mm=2, normal_pressure_angle_deg=20,
                       helix_angle_deg=0, face_width_mm=10, dedendum_coefficient=[3.0, 1.25]))
    assert err.field == "dedendum_coefficient[0]"


def test_eps_alpha_below_one():
    # addendum 0.4 on 29/49, αn 25°: ρa1 = √(26.4664² − 23.2878²) = 12.576, ρa2 = √(44.2364² −
    # 39.3483²) = 20.211, gα = 12.576 + 20.211 − 29.659 = 3.128 mm < pbt = 5.046 mm: εα = 0.62
    err = refusal(low_fluctuation_pair1(addendum_coefficient=0.4))
    assert err.field == "addendum_coefficient"


def test_negative_tip_clearance():
    # A sharp-cornered tool (ρ* = 0) with dedendum 1.0 and addendum 1.05: each tip circle
    # cuts the mate's root circle (c = a − r_a2 − r_f1 = (1.0 − 1.05)·m < 0), while the curved
    # 40-tooth tips stay above the form points on the line of action (a rack tip would not).
    err = refusal(dict(name="c", teeth=[40, 40], normal_module_mm=2, normal_pressure_angle_deg=25,
                       helix_angle_deg=0, face_width_mm=10, addendum_coefficient=1.05,
                       dedendum_coefficient=1.0, tool_tip_radius_coefficient=0.0))
    assert err.field in ("addendum_coefficient[0]", "addendum_coefficient[1]")
    assert "clearance" in err.rule


def test_bore_not_below_root():
    # pinion root r_f1 = 25.76645 − 1.25·1.75 = 23.579 mm: a 23.6 mm bore reaches past it
    err = refusal(low_fluctuation_pair1(bore_radius_mm=[23.6, 25]))
    assert err.field == "bore_radius_mm[0]"
    err = refusal(low_fluctuation_pair1(bore_radius_mm=[15, 41.4]))  # gear root 41.349 mm
    assert err.field == "bore_radius_mm[1]"


# --------------------------------------------------------------------------------------
# validate_modifications
# --------------------------------------------------------------------------------------


def _with_mod(**mod):
    return pair_from_dict(low_fluctuation_pair1(modification={"pinion": mod}))


def test_modification_refusals():
    # active roll length of the pinion flank: ρa1 − ρ_SAP1 = 14.657 − 7.240 = 7.417 mm
    err = refusal(pair=_with_mod(root_relief_um=5, root_relief_length_mm=4, tip_relief_um=5,
                                 tip_relief_length_mm=4))
    assert err.field == "modification.pinion.root_relief_length_mm + tip_relief_length_mm"
    err = refusal(pair=_with_mod(root_relief_um=5))
    assert err.field == "modification.pinion.root_relief_length_mm"
    err = refusal(pair=_with_mod(tip_relief_length_mm=1))
    assert err.field == "modification.pinion.tip_relief_length_mm"
    err = refusal(pair=_with_mod(unmodified_lead_length_mm=25))
    assert err.field == "modification.pinion.unmodified_lead_length_mm"
    err = refusal(pair=_with_mod(crowning_um=5, unmodified_lead_length_mm=20))
    assert err.field == "modification.pinion.unmodified_lead_length_mm"
    # the same lengths within the flank are accepted
    g = pair_geometry(_with_mod(root_relief_um=5, root_relief_length_mm=3, tip_relief_um=5,
                                tip_relief_length_mm=3, crowning_um=5, unmodified_lead_length_mm=10))
    assert g.pair.modification[0].tip_relief == pytest.approx(5e-6)
    assert g.pair.modification[1] == Modification()


def test_involute_function():
    assert float(involute(math.radians(20))) == pytest.approx(0.0149044, abs=1e-7)  # table value
    pair = pair_from_dict(low_fluctuation_pair1())
    assert pair.teeth == (29, 49) and pair.normal_module == pytest.approx(1.75e-3)
    assert pair.face_width == pytest.approx((20e-3, 20e-3)) and pair.material.density == 7850
