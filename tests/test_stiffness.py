"""Mesh stiffness by the potential energy method: physics, limits, convergence, refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st_

from pairs import STEEL, low_fluctuation_pair1
from gearmesh.body import mesh_body_compliance
from gearmesh import slice_compliance as sc
from gearmesh import stiffness as st
from gearmesh.contact import contact_lines, mesh_cycle_rolls, tooth_pair_indices
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair


def geom_of(**changes):
    return pair_geometry(load_pair(low_fluctuation_pair1(**changes)))


@pytest.fixture(scope="module")
def p1():
    return geom_of()


@pytest.fixture(scope="module")
def p1_tables(p1):
    return {m: (sc.slice_compliance_table(p1, 0, m), sc.slice_compliance_table(p1, 1, m)) for m in sc.PEM_METHODS}


@pytest.fixture(scope="module")
def p1_result(p1, p1_tables):
    return st.mesh_stiffness(p1, 360, method="transition", tables=p1_tables["transition"])


def _pair_total_compliance(geom, s, method):
    """c1(ρ1) + c2(ρ2) + c_h (m²/N) at positions s, straight from Gauss (no tables)."""
    c1 = sc.tooth_slice_compliance(sc.tooth_model(geom, 0, method), geom.rho_sap[0] + s)
    c2 = sc.tooth_slice_compliance(sc.tooth_model(geom, 1, method), geom.rho_eap[1] - s)
    return sum(c1.values()) + sum(c2.values()) + sc.hertz_compliance_transverse(geom)


# ----------------------------------------------------------------------------- closed forms


def test_hertz_per_width_is_pi_e_over_4_one_minus_nu_squared():
    assert sc.hertz_stiffness_per_width(210e9, 0.3) == pytest.approx(math.pi * 210e9 / (4 * 0.91), rel=1e-15)
    assert sc.hertz_stiffness_per_width(200e9, 0.0) == pytest.approx(math.pi * 50e9, rel=1e-15)


def test_hertz_in_the_transverse_convention_is_projected_by_cos_beta_b(p1):
    kh0 = math.pi * 210e9 / (4 * (1 - 0.3**2))
    assert 1 / sc.hertz_compliance_transverse(p1) == pytest.approx(kh0 * math.cos(p1.base_helix_angle), rel=1e-14)


def test_sainsot_coefficients_match_the_table_by_hand():
    hf, th = 1.57, 0.11
    # L* by hand from the docs/modelling.md row
    l_hand = -5.574e-5 / th**2 - 1.9986e-3 * hf**2 - 2.3015e-4 * hf / th + 4.7702e-3 / th + 0.0271 * hf + 6.8045
    m_hand = 60.111e-5 / th**2 + 28.100e-3 * hf**2 - 83.431e-4 * hf / th - 9.9256e-3 / th + 0.1624 * hf + 0.9086
    p_hand = -50.952e-5 / th**2 + 185.50e-3 * hf**2 + 0.0538e-4 * hf / th + 53.300e-3 / th + 0.2895 * hf + 0.9236
    q_hand = -6.2042e-5 / th**2 + 9.0889e-3 * hf**2 - 4.0964e-4 * hf / th + 7.8297e-3 / th - 0.1472 * hf + 0.6904
    coeff = sc.sainsot_coefficients(hf, th)
    np.testing.assert_allclose(coeff, [l_hand, m_hand, p_hand, q_hand], rtol=1e-14)
    alpha, u, sf, e = 0.3, 2.1e-3, 4.0e-3, 210e9
    lm, mm, pm, qm = coeff
    hand = math.cos(alpha) ** 2 / e * (lm * (u / sf) ** 2 + mm * u / sf + pm * (1 + qm * math.tan(alpha) ** 2))
    assert sc.fillet_foundation_compliance(alpha, u, sf, th, hf, e) == pytest.approx(hand, rel=1e-14)


def test_iso6336_by_hand(p1):
    iso = st.iso6336_stiffness(p1)
    beta = math.radians(10)
    alpha_t = math.atan(math.tan(math.radians(25)) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    zn1 = 29 / (math.cos(beta_b) ** 2 * math.cos(beta))
    zn2 = 49 / (math.cos(beta_b) ** 2 * math.cos(beta))
    q = 0.04723 + 0.15551 / zn1 + 0.25791 / zn2  # x1 = x2 = 0
    cb = (1 + 0.5 * (1.2 - 1.25)) * (1 - 0.02 * (20 - 25))
    xi = p1.pair.material.youngs_modulus / 206e9  # ISO 6336-1 9.3.1: q' is steel's (206 GPa)
    c_prime = 1 / q * 0.8 * 1.0 * cb * math.cos(beta) * xi
    c_ga = c_prime * (0.75 * p1.eps_alpha + 0.25)
    assert iso["material_factor"] == pytest.approx(xi, rel=1e-15)
    assert iso["C_B"] == pytest.approx(0.975 * 1.1, rel=1e-14)
    assert iso["c_prime"] == pytest.approx(c_prime, rel=1e-13)
    assert iso["c_gamma_alpha"] == pytest.approx(c_ga, rel=1e-13)
    assert iso["c_gamma_beta"] == pytest.approx(0.85 * c_ga, rel=1e-13)
    assert iso["K_gamma_alpha"] == pytest.approx(c_ga * 20 * 1e6, rel=1e-13)


@pytest.mark.parametrize("modulus_GPa", [206.0, 210.0, 70.0])
def test_iso6336_stiffness_scales_with_the_modulus(modulus_GPa):
    """ISO 6336-1 9.3.1: c' (and with it cγα, cγβ) in proportion to E/E_st, E_st = 206 GPa; the
    fitted q' itself is the steel pair's."""
    steel = st.iso6336_stiffness(geom_of(material={"youngs_modulus_GPa": 206.0}))
    other = st.iso6336_stiffness(geom_of(material={"youngs_modulus_GPa": modulus_GPa}))
    assert other["q_prime"] == steel["q_prime"]
    for key in ("c_prime", "c_gamma_alpha", "c_gamma_beta", "K_gamma_alpha"):
        assert other[key] == pytest.approx(steel[key] * modulus_GPa / 206.0, rel=1e-14)


def test_iso6336_profile_shift_terms_by_hand():
    geom = geom_of(profile_shift=[0.3, -0.1], helix_angle_deg=15)
    iso = st.iso6336_stiffness(geom)
    zn1, zn2, x1, x2 = iso["zn1"], iso["zn2"], 0.3, -0.1
    q = (0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * x1 - 0.11654 * x1 / zn1 - 0.00193 * x2
         - 0.24188 * x2 / zn2 + 0.00529 * x1**2 + 0.00182 * x2**2)
    assert iso["q_prime"] == pytest.approx(q, rel=1e-14)
    assert zn1 == pytest.approx(29 / (math.cos(geom.base_helix_angle) ** 2 * math.cos(math.radians(15))), rel=1e-14)


def test_lste_is_transverse_load_over_k(p1_result, p1):
    e = st.lste(p1_result, 200.0)
    assert np.allclose(e, 200.0 / p1.base_radius[0] / p1_result.K, rtol=1e-15)
    # order of magnitude: a few µm for 200 N m on this small pair
    assert 1e-6 < e.mean() < 1e-4


# ----------------------------------------------------------------------------- one slice


@pytest.mark.parametrize("method", sc.PEM_METHODS)
def test_gauss_equals_adaptive_quadrature_per_component(p1, method):
    for gear in (0, 1):
        model = sc.tooth_model(p1, gear, method)
        moments = sc.fixed_moments_quad(model)
        rho = np.array([p1.rho_sap[gear], 0.5 * (p1.rho_sap[gear] + p1.rho_eap[gear]), p1.rho_eap[gear]])
        fast = sc.tooth_slice_compliance(model, rho)
        for k, r in enumerate(rho):
            ref = sc.tooth_slice_compliance_quad(model, float(r), moments=moments)
            for name in sc.COMPONENTS:
                assert fast[name][k] == pytest.approx(ref[name], rel=1e-9), (gear, name, k)


def test_load_angle_satisfies_tian_relation(p1):
    """α1 + α2 = ρ/r_b with α2 = ψ_b (Tian 2004), and the load line is tangent to the base circle."""
    model = sc.tooth_model(p1, 0, "improved")
    rho = np.linspace(p1.rho_sap[0], p1.rho_eap[0], 7)
    x, y, a1, _ = sc.contact_point(model, rho)
    assert np.allclose(a1 + model.psi_b, rho / model.base_radius, rtol=1e-13)
    # distance from the gear centre to the load line = r_b
    d = np.abs(x * np.sin(a1) - y * np.cos(a1))
    assert np.allclose(d, model.base_radius, rtol=1e-12)


def test_compliance_grows_towards_the_tip(p1_tables):
    for tab in p1_tables["transition"]:
        assert np.all(np.diff(tab.values["bending"]) > 0)
        assert np.all(np.diff(sum(tab.values[k] for k in sc.COMPONENTS)) > 0)


def test_table_interpolation_matches_direct_gauss(p1, p1_tables):
    tab = p1_tables["transition"][1]
    rho = np.linspace(p1.rho_sap[1], p1.rho_eap[1], 1001)[1:-1:7]
    direct = sc.tooth_slice_compliance(tab.model, rho)
    interp = tab(rho)
    for k in sc.COMPONENTS:
        assert np.allclose(interp[k], direct[k], rtol=1e-9)


def test_transition_fillet_is_the_generated_profile(p1):
    """The transition cantilever uses profile.py's fillet, continuous with the involute."""
    from gearmesh import profile as prof

    for gear in (0, 1):
        model = sc.tooth_model(p1, gear, "transition")
        (y_lo, y_hi, xf), = model.fixed
        x_form, y_form = sc._involute_xy(model.base_radius, model.psi_b, model.a_start)
        assert y_hi == pytest.approx(float(y_form), rel=1e-12)
        assert float(xf(np.array([y_hi]))[0]) == pytest.approx(float(x_form), rel=1e-9)
        # the fillet root is on the root circle at θ_f
        assert float(xf(np.array([y_lo]))[0]) == pytest.approx(p1.root_radius[gear] * math.sin(model.theta_f),
                                                                rel=1e-9)
        p = prof.tooth_profile(p1, gear)
        assert model.a_start == pytest.approx(math.atan(p.form_roll / model.base_radius), rel=1e-14)


# ----------------------------------------------------------------------------- the three methods


def _cantilever(geom, gear, method, rho):
    c = sc.tooth_slice_compliance(sc.tooth_model(geom, gear, method), rho)
    return c["bending"] + c["shear"] + c["axial"]


def test_methods_order_when_base_circle_is_below_root_circle(p1, p1_tables):
    """r_b < r_f (both gears of the low-fluctuation paper pair 1, αn = 25°).

    The traditional cantilever adds a fictitious involute segment between base and root
    circles inside the gear body: it is MORE compliant than the improved one at every
    contact point, so K_traditional < K_improved. The transition model (real fillet, root
    thickness S_f from the real fillet) is stiffer still. The transition-curve paper claims the classical
    method is stiffer than the transition one for r_b < r_f: not so for these models.
    """
    assert np.all(p1.base_radius < p1.root_radius)
    for gear in (0, 1):
        rho = np.linspace(p1.rho_sap[gear], p1.rho_eap[gear], 9)
        assert np.all(_cantilever(p1, gear, "traditional", rho) > _cantilever(p1, gear, "improved", rho))
    means = {m: st.mesh_stiffness(p1, 60, method=m, tables=p1_tables[m], components=False).mean for m in sc.PEM_METHODS}
    assert means["traditional"] < means["improved"] < means["transition"]


def test_methods_order_when_base_circle_is_above_root_circle():
    """r_b > r_f (20 teeth at 20°): traditional ignores the root-to-base material, so it is
    STIFFER than improved at every contact point (the improved potential-energy paper's claim holds only here)."""
    geom = pair_geometry(load_pair({
        "name": "z20", "teeth": [20, 40], "normal_module_mm": 2, "normal_pressure_angle_deg": 20,
        "helix_angle_deg": 15, "face_width_mm": 20, "bore_radius_mm": [10, 20], "material": dict(STEEL)}))
    assert geom.base_radius[0] > geom.root_radius[0]
    rho = np.linspace(geom.rho_sap[0], geom.rho_eap[0], 9)
    assert np.all(_cantilever(geom, 0, "traditional", rho) < _cantilever(geom, 0, "improved", rho))
    means = {m: st.mesh_stiffness(geom, 60, method=m, components=False).mean for m in ("traditional", "improved")}
    assert means["traditional"] > means["improved"]


# ----------------------------------------------------------------------------- helical assembly


def test_fast_equals_reference_quadrature_on_a_small_grid():
    """Tables + interpolation + sums against per-slice adaptive quadrature at every point (the
    teeth: rigid webs, as the shipped pair states; the bodies' series term in tests/test_body.py)."""
    geom = geom_of()
    for method in ("improved", "transition"):
        ref = st.mesh_stiffness_reference(geom, 3, 6, method)
        fast = st.mesh_stiffness(geom, 3, 6, method, rule="centre").K
        assert np.max(np.abs(fast / ref - 1)) < 1e-6


@pytest.mark.parametrize("beta, hand", [(10.0, "right"), (10.0, "left"), (0.0, "right"), (33.0, "right")])
def test_centre_rule_samples_are_the_points_of_contact_roll_positions(beta, hand):
    from gearmesh.contact import contact_roll_positions

    geom = geom_of(helix_angle_deg=beta, helix_hand=hand)
    roll = mesh_cycle_rolls(geom, 37)
    z, dz = st.slice_centres(geom, 83)
    s = contact_roll_positions(geom, roll, z)
    smp = st.slice_samples(geom, roll, 83, rule="centre")
    ok = np.isfinite(s)
    assert smp.s.size == ok.sum()
    flat = np.flatnonzero(ok.ravel())
    assert np.array_equal(smp.line * 83 + smp.slice_index, flat)
    assert np.array_equal(smp.s, s.ravel()[flat])  # bit for bit
    assert np.all(smp.width == dz)


def test_beta_zero_is_the_spur_slice_model():
    """β = 0: every slice of a pair sees the same s; K = Σ_pairs b/(c1 + c2 + c_h) exactly,
    whatever the number of slices or the rule."""
    geom = geom_of(helix_angle_deg=0)
    roll = mesh_cycle_rolls(geom, 24)
    ks = [st.mesh_stiffness(geom, 24, n, "transition", rule=r, components=False).K
          for n in (1, 7, 1000) for r in ("centre", "clip")]
    for k in ks[1:]:
        assert np.allclose(k, ks[0], rtol=1e-12)
    s = roll[:, None] + tooth_pair_indices(geom)[None, :] * geom.transverse_base_pitch
    inside = (s >= 0) & (s <= geom.path_of_contact)
    spur = np.zeros_like(s)
    spur[inside] = geom.face_width / _pair_total_compliance(geom, s[inside], "transition")
    assert np.allclose(ks[0], spur.sum(axis=1), rtol=1e-6)
    # one or two pairs: K jumps between the two levels (εα = 1.47)
    assert set(inside.sum(axis=1)) == {1, 2}


def test_constant_per_width_stiffness_sums_to_contact_length(p1):
    """Σ_slices k0·width = k0·L(φ)·cos βb (L from contact.contact_lines): exact with the clip
    rule, within one slice per line end with the centre rule."""
    roll = mesh_cycle_rolls(p1, 97)
    cl = contact_lines(p1, roll)
    k0 = 3.0e10
    target = k0 * cl.length * math.cos(p1.base_helix_angle)  # (P, J)
    clip = st.line_slice_sum(p1, roll, 50, lambda s: np.full_like(s, k0), rule="clip")
    assert np.allclose(clip, target, rtol=1e-12, atol=1e-9 * k0 * p1.face_width)
    dz = p1.face_width / 200
    centre = st.line_slice_sum(p1, roll, 200, lambda s: np.full_like(s, k0), rule="centre")
    assert np.all(np.abs(centre - target) <= k0 * dz * (1 + 1e-9))


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(beta=st_.floats(0.0, 35.0), b=st_.floats(5.0, 60.0), z1=st_.integers(18, 60),
       hand=st_.sampled_from(["right", "left"]), n=st_.integers(3, 120))
def test_clip_rule_sums_contact_length_exactly_for_random_pairs(beta, b, z1, hand, n):
    try:
        geom = geom_of(helix_angle_deg=beta, face_width_mm=b, teeth=[z1, 49], helix_hand=hand)
    except GearmeshInputError:
        assume(False)
    roll = mesh_cycle_rolls(geom, 31)
    target = contact_lines(geom, roll).total_length * math.cos(geom.base_helix_angle)
    got = st.line_slice_sum(geom, roll, n, np.ones_like, rule="clip").sum(axis=1)
    assert np.allclose(got, target, rtol=1e-11, atol=1e-14)
    # the mean total length is b·εα/cos βb (docs/modelling.md), in the transverse width b·εα
    fine = mesh_cycle_rolls(geom, 4096)
    mean = st.line_slice_sum(geom, fine, n, np.ones_like, rule="clip").sum(axis=1).mean()
    assert mean == pytest.approx(geom.face_width * geom.eps_alpha, rel=2e-3 if beta < 1 else 1e-6)


def test_components_add_up_in_series(p1_result):
    inv = sum(1.0 / v for v in p1_result.components.values())
    assert np.allclose(inv, 1.0 / p1_result.K, rtol=1e-10)
    assert set(p1_result.components) == {f"{c}_{g}" for c in sc.COMPONENTS for g in ("pinion", "gear")} | {"hertz"}
    # the bodies' foundation and the contact are the soft parts; axial compression is tiny
    comp = {k: v.mean() for k, v in p1_result.components.items()}
    assert comp["axial_pinion"] > 10 * comp["fillet_pinion"]


def test_single_pair_curve_rebuilds_the_total(p1, p1_result):
    r = p1_result
    pbt = p1.transverse_base_pitch
    # support of one pair: (εα + εβ)·p_bt, to one roll step
    support = np.ptp(r.pair_roll[r.k_pair > 0])
    step = pbt / r.roll.size
    assert abs(support - (p1.eps_alpha + p1.eps_beta) * pbt) <= 2 * step
    total = np.zeros_like(r.K)
    for u, k in zip(r.pair_roll, r.k_pair):
        p = int(round((u % pbt) / step)) % r.roll.size
        total[p] += k
    assert np.allclose(total, r.K, rtol=1e-12)


def test_single_pair_curves_in_parallel_and_the_bodies_in_series():
    """With solid-disc bodies held at the bore (stated as a hub; the shipped pair states rigid webs,
    its source's model) the mesh stiffness is the pairs' curves in parallel, the bodies in series."""
    geom = geom_of(web_thickness_mm=None, hub_diameter_mm=[30.0, 50.0])
    c_body = mesh_body_compliance(geom)
    assert c_body > 0
    r = st.mesh_stiffness(geom, 60, 64, "transition", components=True)
    pbt, step = geom.transverse_base_pitch, geom.transverse_base_pitch / r.roll.size
    total = np.zeros_like(r.K)
    for u, k in zip(r.pair_roll, r.k_pair):
        total[int(round((u % pbt) / step)) % r.roll.size] += k
    assert np.allclose(1.0 / (1.0 / total + c_body), r.K, rtol=1e-12)
    assert r.components["body"][0] == pytest.approx(1 / c_body)


def test_min_max_include_the_kinks(p1_result):
    assert p1_result.max >= p1_result.K.max()
    assert p1_result.min <= p1_result.K.min()
    assert p1_result.fluctuation == pytest.approx((p1_result.max - p1_result.min) / p1_result.min)


def _observed_order(ns, errors):
    return -np.polyfit(np.log(ns), np.log(errors), 1)[0]


def test_convergence_in_slices(p1, p1_tables):
    """Pointwise error against a 16000-slice solution: O(N⁻²) with the clip rule, O(N⁻¹) with
    the centre rule (contact_roll_positions' points)."""
    pt = sc.pair_slice_table(p1, p1_tables["transition"])
    ref = st.mesh_stiffness(p1, 90, 16000, pair_table=pt, components=False).K
    ns = np.array([25, 50, 100, 200, 400])
    err = {rule: [np.max(np.abs(st.mesh_stiffness(p1, 90, n, pair_table=pt, rule=rule,
                                                   components=False).K / ref - 1)) for n in ns]
           for rule in ("clip", "centre")}
    assert np.all(np.diff(err["clip"]) < 0)
    assert 1.8 < _observed_order(ns, err["clip"]) < 2.2
    assert 0.8 < _observed_order(ns, err["centre"]) < 1.5
    assert err["clip"][ns.tolist().index(st.DEFAULT_SLICES)] < 1e-6


def test_convergence_in_positions(p1, p1_tables):
    """The mean over the cycle and the smooth minimum converge as positions are refined."""
    pt = sc.pair_slice_table(p1, p1_tables["transition"])
    ref = st.mesh_stiffness(p1, 11520, 100, pair_table=pt, components=False)
    ps = np.array([90, 180, 360, 720, 1440])
    res = [st.mesh_stiffness(p1, p, 100, pair_table=pt, components=False) for p in ps]
    err_mean = [abs(r.mean / ref.mean - 1) for r in res]
    err_min = [abs(r.min / ref.min - 1) for r in res]
    assert err_mean[-1] < err_mean[0] / 20 and err_min[-1] < err_min[0] / 20
    assert _observed_order(ps, err_mean) > 1.5
    # the maximum sits on a kink, which is evaluated exactly
    assert all(r.max == pytest.approx(ref.max, rel=1e-12) for r in res)


def test_integer_overlap_ratio_lowers_the_fluctuation(p1, p1_tables):
    """The low-fluctuation paper: pair 1 (εβ = 0.632) against pair 2 (β = 15.95°, εβ = 0.9997) and pair 3
    (b = 31.66 mm, εβ = 1.0000): the fluctuation ε_k falls from 36 % to almost nothing.

    With εβ = 1 the contact lines of all pairs together cover every position s of the path
    exactly once across the face, so in slice theory K = ∫k0(s)ds/tan βb is constant: the
    variation of the slice stiffness along the flank averages out, not only the length.
    """
    base = st.mesh_stiffness(p1, 360, method="transition", tables=p1_tables["transition"], components=False)
    assert base.fluctuation > 0.2
    p2 = geom_of(helix_angle_deg=15.95)
    p3 = geom_of(face_width_mm=31.66)
    assert p2.eps_beta == pytest.approx(1.0, abs=1e-3) and p3.eps_beta == pytest.approx(1.0, abs=1e-4)
    for g in (p2, p3):
        assert st.mesh_stiffness(g, 360, method="transition", components=False).fluctuation < 1e-3
    # and the fluctuation grows again away from the integer (the low-fluctuation paper pair 4, εβ = 1.353)
    assert st.mesh_stiffness(geom_of(helix_angle_deg=21.84), 360, method="transition",
                             components=False).fluctuation > 0.1


def test_iso_and_pem_means_agree_within_a_factor_1_3(p1, p1_tables):
    """The low-fluctuation paper pair 1: ISO 6336-1 cγα·b against the PEM mean of every method."""
    iso = st.iso6336_stiffness(p1)["K_gamma_alpha"]
    for m in sc.PEM_METHODS:
        mean = st.mesh_stiffness(p1, 90, method=m, tables=p1_tables[m], components=False).mean
        assert 1 / 1.3 < mean / iso < 1.3, m


def test_stiffness_scales_with_youngs_modulus(p1_result):
    geom = geom_of(material=dict(STEEL, youngs_modulus_GPa=105))
    half = st.mesh_stiffness(geom, 360, method="transition", components=False)
    assert np.allclose(half.K, 0.5 * p1_result.K, rtol=1e-9)


def test_left_hand_gives_the_same_stiffness(p1_result):
    left = st.mesh_stiffness(geom_of(helix_hand="left"), 360, method="transition", components=False)
    assert np.allclose(left.K, p1_result.K, rtol=1e-9)


# ----------------------------------------------------------------------------- Fourier


def test_fourier_fit_recovers_a_trig_polynomial():
    p = 64
    th = 2 * np.pi * np.arange(p) / p
    v = 5.0 + 1.5 * np.cos(th) - 0.25 * np.sin(2 * th) + 0.1 * np.cos(3 * th) + 0.02 * np.sin(5 * th)
    fit = st.fourier_fit(v, 3)
    assert fit.mean == pytest.approx(5.0)
    assert np.allclose(fit.a, [1.5, 0.0, 0.1], atol=1e-14)
    assert np.allclose(fit.b, [0.0, -0.25, 0.0], atol=1e-14)
    assert fit.rms_error == pytest.approx(0.02 / math.sqrt(2), rel=1e-12)
    assert st.fourier_fit(v, 5).rms_error < 1e-14


def test_fourier_fit_of_the_tvms(p1_result):
    fits = [st.fourier_fit(p1_result.K, n) for n in range(0, 8)]
    assert fits[0].mean == pytest.approx(p1_result.mean, rel=1e-14)
    errs = [f.rms_error for f in fits]
    assert all(b <= a + 1e-9 for a, b in zip(errs, errs[1:]))
    assert fits[3].relative_rms_error < 0.05
    with pytest.raises(GearmeshInputError):
        st.fourier_fit(p1_result.K[:6], 3)


# ----------------------------------------------------------------------------- refusals


def test_missing_bore_radius_is_refused():
    data = low_fluctuation_pair1()
    del data["bore_radius_mm"]
    geom = pair_geometry(load_pair(data))
    with pytest.raises(GearmeshInputError) as info:
        st.mesh_stiffness(geom)
    assert info.value.field == "bore_radius_mm"


def test_missing_material_is_refused():
    geom = pair_geometry(load_pair(low_fluctuation_pair1()).with_changes(material=None))  # a pair built in code
    for call in (lambda: st.mesh_stiffness(geom), lambda: sc.slice_compliance_table(geom, 0, "improved"),
                 lambda: sc.hertz_compliance_transverse(geom)):
        with pytest.raises(GearmeshInputError) as info:
            call()
        assert info.value.field == "material"


def test_unknown_method_and_rule_are_refused(p1):
    with pytest.raises(GearmeshInputError) as info:
        st.mesh_stiffness(p1, method="fem")
    assert info.value.field == "method"
    with pytest.raises(GearmeshInputError) as info:
        st.mesh_stiffness(p1, rule="left")
    assert info.value.field == "rule"
    with pytest.raises(GearmeshInputError) as info:
        st.mesh_stiffness(p1, n_slices=0)
    assert info.value.field == "n_slices"
