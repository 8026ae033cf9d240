"""System deflection (gearmesh.deflection) and manufacturing deviations (gearmesh.deviation):
the beam against beam theory written here independently, the supports' translation against
Supports.radial, the mismatch's signs and cancellations, every model seeing the same per-torque
misalignment, and K_Hβ of the misaligned mesh against ISO 6336-1's closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid

from gearmesh.contact_model import ContactModel
from gearmesh.deflection import mesh_deflection, mesh_misalignment, shaft_deflection
from gearmesh.deviation import Deviations, lead_gap, profile_gap, read_deviations
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pair, load_pair, pair_from_dict, pair_to_dict
from gearmesh.impact import impact_model, impact_static
from gearmesh.ltca import ltca
from gearmesh.rating import ltca_load_factors
from gearmesh.supports import read_supports

E, NU = 210e9, 0.3
G = E / (2 * (1 + NU))


def _beam_by_integration(span: float, a: float, ei: float, force: float, couple: float, n: int = 200001):
    """Deflection w along the force and its slope w' (m, rad) at x = a of a simply supported beam
    (rigid supports at 0 and L) under a point force ``force`` and a point couple ``couple`` (N m,
    turning the slope up) at a, by integrating EI w'' = m(x) twice (trapezoids) with w(0) = w(L) = 0:
    m = −R_A x + F (x − a)₊ for the force (R_A = F (L − a)/L), + C (x/L − H(x − a)) for the couple
    (reactions ±C/L). Independent of the frame elements."""
    x = np.linspace(0.0, span, n)
    r_a = force * (span - a) / span
    m = -(r_a * x - force * np.clip(x - a, 0, None)) + couple * (x / span - (x >= a))
    slope = cumulative_trapezoid(m / ei, x, initial=0.0)
    w = cumulative_trapezoid(slope, x, initial=0.0)
    c = -w[-1] / span  # w(L) = 0 with w(0) = 0: add c·x
    w, slope = w + c * x, slope + c
    k = int(np.argmin(np.abs(x - a)))
    return w[k], slope[k]


@pytest.mark.parametrize("offset", [0.0, 0.02, -0.035])
def test_shaft_against_beam_theory_under_a_force_and_a_moment(offset):
    """A uniform shaft (the body as thick as the shaft) on rigid bearings, the load over a face of
    10 µm (a point load to 10⁻⁴: spread over w the couple's slope falls by about 1.5 w/L): its
    deflection and slope against EI w'' = m integrated here, for a transverse force and for the axial
    force's moment F_a·r about the face."""
    d, span, face = 0.06, 0.15, 2e-5
    ei = E * math.pi * d**4 / 64
    a = 0.5 * span + offset
    r = 0.08
    for load, point, force, moment in (((1000.0, 0.0, 0.0), (r, 0.0, 0.0), 1000.0, 0.0),
                                       ((0.0, 0.0, 1000.0), (r, 0.0, 0.0), 0.0, -r * 1000.0)):  # couple about +y: p × F
        sd = shaft_deflection(E, NU, d, span, offset, d, face, face, math.inf, math.inf, np.array(load),
                              np.array(point), 1.0, face_elements=2)
        y, slope = _beam_by_integration(span, a, ei, force, moment)
        mid = sd.z.size // 2
        assert sd.u[mid, 0] == pytest.approx(y, rel=4e-3, abs=1e-8)
        assert sd.theta[mid, 1] == pytest.approx(slope, rel=4e-3, abs=1e-8)  # du_x/dz = θ_y


def test_bearing_springs_move_a_rigid_shaft_as_a_lever():
    """A shaft far stiffer than its bearings: the gear moves as the lever of the two bearing
    deflections, R_A = F c/L and R_B = F a/L each over half the stated stiffness."""
    k, span, s = 800e6, 0.2, 0.03
    sd = shaft_deflection(E, NU, 2.0, span, s, 2.0, 0.01, 0.01, k, math.inf, np.array([1000.0, 0.0, 0.0]),
                          np.array([0.05, 0.0, 0.0]), 1.0, face_elements=2)
    a, c = 0.5 * span + s, 0.5 * span - s
    d_a, d_b = 1000.0 * c / span / (k / 2), 1000.0 * a / span / (k / 2)
    mid = sd.z.size // 2
    assert sd.u[mid, 0] == pytest.approx(d_a + (d_b - d_a) * a / span, rel=1e-4)
    assert sd.theta[mid, 1] == pytest.approx((d_b - d_a) / span, rel=1e-4)


def test_twist_across_the_face_is_the_distributed_torque_integrated():
    """A torque spread evenly over the face and taken out at one shaft end: the twist grows across
    the face as ∫ T(z)/(GJ) dz, T falling linearly to zero at the far face end."""
    d, face, span = 0.16, 0.05, 0.3
    gj = G * math.pi * d**4 / 32
    r, f = 0.08, 1000.0  # a tangential force at r: torque r·f
    sd = shaft_deflection(E, NU, d, span, 0.0, d, face, face, math.inf, math.inf, np.array([0.0, f, 0.0]),
                          np.array([r, 0.0, 0.0]), -1.0)
    z = sd.z
    torque = r * f * (0.5 * face - z) / face  # carried through z towards the −z end, which holds it
    expect = np.concatenate([[0.0], cumulative_trapezoid(torque, z)]) / gj  # relative to the −z face end
    twist = sd.theta[:, 2] - sd.theta[0, 2]
    np.testing.assert_allclose(twist, expect, rtol=1e-3, atol=1e-3 * abs(expect).max())


def test_translation_agrees_with_the_supports_radial_stiffness():
    """The beam's translation of a gear centre under a radial load equals 1/Supports.radial (the
    closed form of bearings as a lever in series with the shaft's a²c²/(3EIL)), the face thin."""
    sup = read_supports({"bearing_radial_stiffness_N_per_um": 900, "bearing_axial_stiffness_N_per_um": 200,
                         "shaft_diameter_mm": 50, "bearing_span_mm": 160, "gear_offset_mm": 25})
    k = sup.radial(E)[0]
    sd = shaft_deflection(E, NU, 0.05, 0.16, 0.025, 0.05, 1e-4, 1e-4, sup.bearing_radial[0], sup.bearing_axial[0],
                          np.array([1.0, 0.0, 0.0]), np.array([0.05, 0.0, 0.0]), 1.0, face_elements=2)
    assert sd.u[1, 0] == pytest.approx(1.0 / k, rel=1e-3)


def _case(**changes):
    data = pair_to_dict(load_pair(example_pair("helical_z29_71_m5")))
    data.update(changes)
    return load_pair(data)


def test_mismatch_grows_with_the_load_and_vanishes_without_shafts():
    """f_sh is linear in F_bt; a pair without shafts has none (the teeth alone, said so); rigid
    bearings on the same shafts leave the shafts' bending alone: a smaller mismatch."""
    geom = pair_geometry(_case())
    d = mesh_deflection(geom)
    assert d.active and d.misalignment_per_force != 0.0
    np.testing.assert_allclose(mesh_misalignment(geom, [1e3, 2e3]), [1e3 * d.misalignment_per_force,
                                                                     2e3 * d.misalignment_per_force])
    bare = pair_geometry(_case().with_changes(supports=read_supports({})))
    assert not mesh_deflection(bare).active and "teeth alone" in mesh_deflection(bare).included
    rigid = pair_geometry(_case(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid"))
    assert 0 < abs(mesh_deflection(rigid).misalignment_per_force) < abs(d.misalignment_per_force)
    # the unfavourable torque side when not stated: no stated side gives a larger mismatch
    for side in (["leading", "leading"], ["leading", "trailing"], ["trailing", "leading"], ["trailing", "trailing"]):
        stated = mesh_deflection(pair_geometry(_case(torque_side=side)))
        assert abs(stated.misalignment_per_force) <= abs(d.misalignment_per_force) * (1 + 1e-12)


def test_spur_pinion_body_twist_is_isos_torsion_term():
    """A spur pair at mid-span on rigid bearings, shafts as thick as the bores: no axial force, no
    tilt (the shafts bend symmetrically under the gear); the mismatch is the bodies' twist across
    the face, r_b·T·b/(2GJ) of each (the torsion part of ISO
    6336-1's f_sh, a solid cylinder of the reference diameter). Each body lags most at the face end
    away from its torque side: with both torques on one side the two twists add, on opposite sides
    they cancel in part."""
    base = pair_to_dict(load_pair(example_pair("helical_z29_71_m5")))
    base.update(helix_angle_deg=0.0, bearing_radial_stiffness_N_per_um="rigid",
                bearing_axial_stiffness_N_per_um="rigid", bearing_span_mm=[150, 180],
                shaft_diameter_mm=[2 * r for r in base["bore_radius_mm"]])
    out = {}
    for side in (["leading", "leading"], ["trailing", "leading"]):
        geom = pair_geometry(load_pair({**base, "torque_side": side}))
        out[tuple(side)] = mesh_deflection(geom).misalignment_per_force
    b = geom.face_width
    rb = geom.base_radius
    twist = [float(rb[i]) * float(rb[i]) * b / (2 * G * math.pi * (2 * float(geom.reference_radius[i])) ** 4 / 32)
             for i in (0, 1)]  # per unit F_bt: torque F_bt·r_b
    assert abs(out[("leading", "leading")]) == pytest.approx(twist[0] + twist[1], rel=0.03)
    assert abs(out[("trailing", "leading")]) == pytest.approx(abs(twist[0] - twist[1]), rel=0.03)


def test_lead_deviations_that_cancel_give_the_aligned_contact():
    """f2 = −f1 is the aligned mesh, in every model: the LTCA's loads and TE, the impact's touch."""
    aligned = pair_geometry(_case(bearing_radial_stiffness_N_per_um=None, bearing_axial_stiffness_N_per_um=None,
                                  shaft_diameter_mm=None, bearing_span_mm=None))
    both = pair_geometry(aligned.pair.with_changes(deviations=Deviations(lead_slope=(12e-6, -12e-6))))
    one = pair_geometry(aligned.pair.with_changes(deviations=Deviations(lead_slope=(12e-6, 0.0))))
    r0, r1, r2 = (ltca(g, [1000.0], 16, ContactModel(points=20, method="transition")) for g in (aligned, both, one))
    np.testing.assert_allclose(r1.load, r0.load, rtol=0, atol=1e-9 * r0.force[0])
    np.testing.assert_allclose(r1.lte, r0.lte, rtol=1e-12)
    assert np.max(np.abs(r2.load - r0.load)) > 0.01 * r0.force[0]
    contact = ContactModel(points=20, method="transition")
    s0, s1 = (impact_static(impact_model(g, contact), [1000.0]) for g in (aligned, both))
    assert s1.tau[0, 0] == pytest.approx(s0.tau[0, 0], abs=1e-12)
    # and f_ma stated is the same mismatch as a lead slope of the pinion
    ma = pair_geometry(aligned.pair.with_changes(deviations=Deviations(mesh_misalignment=12e-6)))
    np.testing.assert_allclose(ltca(ma, [1000.0], 16, contact).load, r2.load, rtol=0,
                               atol=1e-9 * r0.force[0])


def test_profile_slope_gap_is_zero_where_the_flank_stands_proud():
    """f_Hα > 0 stands proud at the tip: no gap at the tip (EAP), f at the start of active profile;
    linear between; f < 0 the other way round."""
    geom = pair_geometry(_case())
    sap, eap = float(geom.rho_sap[0]), float(geom.rho_eap[0])
    rho = np.linspace(sap, eap, 5)
    g = profile_gap(geom, (8e-6, 0.0), rho, np.full(5, float(geom.rho_sap[1])))
    np.testing.assert_allclose(g, np.linspace(8e-6, 0.0, 5), atol=1e-18)
    g = profile_gap(geom, (-8e-6, 0.0), rho, np.full(5, float(geom.rho_sap[1])))
    np.testing.assert_allclose(g, np.linspace(0.0, 8e-6, 5), atol=1e-18)


def test_lead_gap_convention_is_hand_independent():
    """+f stands proud at the leading face end for either hand: zero gap there, f at the trailing end."""
    for hand, lead_z in (("right", 1.0), ("left", -1.0)):
        geom = pair_geometry(_case(helix_hand=hand))
        b = geom.face_width
        z = np.array([lead_z * b / 2, -lead_z * b / 2])
        np.testing.assert_allclose(lead_gap(geom, (5e-6, 0.0), z), [0.0, 5e-6], atol=1e-18)


@pytest.mark.parametrize("spec, field", [
    ({"lead_slope_deviation_um": [1.0]}, "lead_slope_deviation_um"),
    ({"lead_slope_deviation_um": [1.0, "x"]}, "lead_slope_deviation_um[1]"),
    ({"profile_slope_deviation_um": 3.0}, "profile_slope_deviation_um"),
    ({"mesh_misalignment_um": float("inf")}, "mesh_misalignment_um"),
    ({"lead_slope_deviation_um": [5000.0, 0.0]}, "lead_slope_deviation_um[0]"),
])
def test_bad_deviations_are_refused_naming_the_key(spec, field):
    with pytest.raises(GearmeshInputError) as err:
        read_deviations(spec)
    assert err.value.field == field


def test_deviations_round_trip_through_the_pair_file():
    pair = _case(lead_slope_deviation_um=[3.5, -1.25], profile_slope_deviation_um=[0.0, 2.0], mesh_misalignment_um=-4.0,
                 gear_offset_mm=[10.0, -5.0], torque_side=["leading", "trailing"])
    again = load_pair(pair_to_dict(pair))
    assert again.deviations == pair.deviations and again.supports == pair.supports


@pytest.mark.parametrize("spec, field", [
    ({"gear_offset_mm": [80.0, 0.0]}, "gear_offset_mm[0]"),  # half the span is 75 mm
    ({"torque_side": ["left", "leading"]}, "torque_side"),
    ({"web_thickness_mm": 20.0, "bearing_radial_stiffness_N_per_um": None, "bearing_axial_stiffness_N_per_um": None,
      "shaft_diameter_mm": None, "bearing_span_mm": None}, "web_thickness_mm"),  # a body never alone
])
def test_bad_supports_and_bodies_are_refused_naming_the_key(spec, field):
    with pytest.raises(GearmeshInputError) as err:
        pair_geometry(_case(**spec))
    assert err.value.field == field


def test_every_model_takes_each_torques_misalignment():
    """The impact model solved at two torques at once equals each solved alone (each at its own
    mismatch); the LTCA's misalignment is mesh_misalignment's."""
    geom = pair_geometry(_case())
    model = impact_model(geom, ContactModel(points=20, method="transition"))
    both = impact_static(model, [400.0, 1600.0])
    for k, t in enumerate((400.0, 1600.0)):
        alone = impact_static(model, [t])
        assert both.tau[0, k] == pytest.approx(alone.tau[0, 0], abs=1e-12)
    res = ltca(geom, [400.0, 1600.0], 16, ContactModel(points=20, method="transition"))
    np.testing.assert_allclose(res.misalignment, mesh_misalignment(geom, res.force), rtol=1e-15)


#: The NREL 5 MW reference gearbox's third (parallel helical) stage (Nejad, Guo, Gao & Moan 2016,
#: Wind Energy 19:1089), as its KISSsoft report gives it (tests/test_pairfile.py): an uncrowned
#: 360 mm face.
NREL_STAGE_3 = {"name": "nrel_5mw_stage_3", "teeth": [24, 95], "normal_module_mm": 14, "normal_pressure_angle_deg": 20,
                "helix_angle_deg": 10, "face_width_mm": 360, "profile_shift": [0.48, 0.6691],
                "center_distance_mm": 861.000, "tip_diameter_mm": [380.747, 1395.376],
                "basic_rack_profile": "ISO 53 A", "bore_diameter_mm": [179.10, 1193.32]}


@pytest.mark.parametrize("lead_um", [0.0, 10.0, 30.0, 60.0])
def test_face_load_factor_of_a_misaligned_mesh_follows_isos_closed_form(lead_um):
    """An uncrowned pair with a lead mismatch F_βy: ISO 6336-1 (7.6) K_Hβ = 1 + F_βy c_γβ/(2 F_m/b),
    or √(2 F_βy c_γβ/(F_m/b)) once part of the face unloads, with c_γβ the LTCA's own mean mesh
    stiffness per face width: the LTCA's K_Hβ within 10 % of K_Hβ − 1; the aligned pair within 2 %
    of 1 (the LTE's own ripple, phase-shifted along the helix, loads the face slightly unevenly)."""
    geom = pair_geometry(pair_from_dict({**NREL_STAGE_3, "lead_slope_deviation_um": [lead_um, 0.0]}))
    res = ltca(geom, [40e3], 32, ContactModel(points=50))
    k_hb = float(ltca_load_factors(res.load)["K_Hbeta"][0])
    fm = float(res.force[0]) / geom.face_width
    c = float(np.mean(res.stiffness[0])) / geom.face_width
    f = lead_um * 1e-6
    iso = 1 + f * c / (2 * fm)
    if iso > 2:
        iso = math.sqrt(2 * f * c / fm)
    if lead_um == 0:
        assert k_hb == pytest.approx(1.0, abs=0.02)
    else:
        assert k_hb - 1 == pytest.approx(iso - 1, rel=0.10)


def test_beam_f_sh_against_isos_formula_for_the_case_pair():
    """docs/load_capacity.md: ISO 6336-1 method C's f_sh at mid-span, F_m/b·0.023·(b/d1)², is 0.44 µm
    for the case pair at 1000 N·m; the beam gives 0.01–0.55 µm on rigid bearings and 0.03–0.69 µm on
    the pair's own, by the torque sides: ISO's figure inside the beam's range."""
    base = pair_to_dict(load_pair(example_pair("helical_z29_71_m5")))
    sides = (["leading", "leading"], ["trailing", "leading"], ["leading", "trailing"], ["trailing", "trailing"])
    out = {}
    for label, ch in (("rigid", dict(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid")),
                      ("own", {})):
        values = []
        for side in sides:
            geom = pair_geometry(load_pair({**base, **ch, "torque_side": side}))
            values.append(abs(mesh_deflection(geom).misalignment_per_force) * 1000.0 / float(geom.base_radius[0]) * 1e6)
        out[label] = (round(min(values), 2), round(max(values), 2))
    geom = pair_geometry(load_pair(base))
    d1, b = 2e3 * float(geom.reference_radius[0]), geom.face_width * 1e3
    iso = 2 * 1000.0 / (d1 * 1e-3) / b * 0.023 * (b / d1) ** 2
    assert round(iso, 2) == 0.44
    assert out == {"rigid": (0.01, 0.55), "own": (0.03, 0.69)}
    assert out["rigid"][0] < iso < out["rigid"][1]
