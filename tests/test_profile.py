"""Physics of the hob-generated transverse profile (gearmesh.profile)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from gearmesh.errors import GearmeshInputError
from gearmesh.gear import involute, max_tool_tip_radius, pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.profile import (
    generating_rack,
    half_thickness,
    rack_flank_envelope,
    rack_rounding_envelope,
    tooth_profile,
    form_point,
)

from pairs import low_fluctuation_pair1


def pair(**changes):
    """The low-fluctuation paper pair 1 at a 20° pressure angle (the ISO 53 tip radius fits), no bore."""
    return load_pair(low_fluctuation_pair1(**{"normal_pressure_angle_deg": 20, "bore_radius_mm": None, **changes}))


# An undercut pinion that still works: z 12 (z_min ≈ 17 at 20°), gear tip shortened to 0.8 m_n.
UNDERCUT = dict(name="u", teeth=[12, 16], normal_module_mm=2, normal_pressure_angle_deg=20,
                helix_angle_deg=0, face_width_mm=10, profile_shift=[0.0, 0.3],
                addendum_coefficient=[1.0, 0.8])

PAIRS = [
    dict(),
    dict(normal_pressure_angle_deg=25),  # tool tip radius 0.38 clamped to the full radius
    dict(helix_angle_deg=30, profile_shift=[0.3, -0.1]),
    dict(teeth=[17, 60], helix_angle_deg=20, tool_tip_radius_coefficient=0.2),
    dict(teeth=[31, 37], helix_angle_deg=0, tool_tip_radius_coefficient=0.0),  # sharp tool corner
]


def analytic_psi(geom, gear, radius):
    """ψ(R) = s_t/(2r) + inv αt − inv α(R), ISO 21771, from gear.py's thickness."""
    alpha = np.arccos(geom.base_radius[gear] / radius)
    return (geom.transverse_thickness[gear] / (2 * geom.reference_radius[gear])
            + involute(geom.transverse_pressure_angle) - involute(alpha))


@pytest.mark.parametrize("changes", PAIRS)
@pytest.mark.parametrize("gear", [0, 1])
def test_involute_is_the_analytic_involute(changes, gear):
    geom = pair_geometry(pair(**changes))
    prof = tooth_profile(geom, gear)
    inv = prof.segment == 1
    R = prof.radius[inv]
    np.testing.assert_allclose(R, np.hypot(geom.base_radius[gear], prof.roll[inv]), rtol=1e-14)
    np.testing.assert_allclose(np.arctan2(prof.x[inv], prof.y[inv]), analytic_psi(geom, gear, R), atol=1e-14)
    # thickness at the reference circle is gear.py's s_t = m_t(π/2 + 2x tan αn)
    r = geom.reference_radius[gear]
    assert 2 * r * analytic_psi(geom, gear, r) == pytest.approx(geom.transverse_thickness[gear], rel=1e-14)
    assert np.all(np.isnan(prof.roll[~inv]))
    # the involute's tangent is perpendicular to the base-circle string: for a unit tangent
    # t·P = r_b (the tangent line passes r_b from the centre, its normal touches the base circle)
    dot = prof.tangent_x[inv] * prof.x[inv] + prof.tangent_y[inv] * prof.y[inv]
    np.testing.assert_allclose(dot, geom.base_radius[gear], rtol=1e-12)


@pytest.mark.parametrize("changes", PAIRS)
@pytest.mark.parametrize("gear", [0, 1])
def test_fillet_joins_involute_smoothly_at_form_point(changes, gear):
    geom = pair_geometry(pair(**changes))
    prof = tooth_profile(geom, gear)
    assert not prof.undercut
    X, Y, dX, dY = rack_rounding_envelope(prof.rack, np.array([prof.form_rounding_angle]))
    i = np.argmax(prof.segment == 1)
    scale = geom.reference_radius[gear]
    assert X[0] == pytest.approx(prof.x[i], abs=1e-14 * scale)
    assert Y[0] == pytest.approx(prof.y[i], abs=1e-14 * scale)
    tf = -np.array([dX[0], dY[0]]) / math.hypot(dX[0], dY[0])  # t decreases root→tip
    assert tf @ np.array([prof.tangent_x[i], prof.tangent_y[i]]) == pytest.approx(1.0, abs=1e-12)
    # the same form point as ISO 21771 / gear.py unless the tool tip radius had to be clamped
    if not prof.rack.tip_radius_clamped:
        assert prof.form_radius == pytest.approx(geom.form_radius[gear], rel=1e-13)


@pytest.mark.parametrize("gear", [0, 1])
def test_envelope_derivatives_match_finite_differences(gear):
    geom = pair_geometry(pair(helix_angle_deg=25))
    rack = generating_rack(geom.pair, gear, float(geom.profile_shift[gear]))
    t = np.linspace(rack.normal_pressure_angle + 0.01, math.pi / 2 - 0.01, 7)
    h = 1e-6
    X, Y, dX, dY = rack_rounding_envelope(rack, t)
    Xp, Yp, _, _ = rack_rounding_envelope(rack, t + h)
    Xm, Ym, _, _ = rack_rounding_envelope(rack, t - h)
    np.testing.assert_allclose(dX, (Xp - Xm) / (2 * h), rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(dY, (Yp - Ym) / (2 * h), rtol=1e-6, atol=1e-12)
    rho = np.linspace(1e-3, 5e-3, 5)
    _, _, dX, dY = rack_flank_envelope(rack, rho)
    Xp, Yp, _, _ = rack_flank_envelope(rack, rho + 1e-9)
    Xm, Ym, _, _ = rack_flank_envelope(rack, rho - 1e-9)
    np.testing.assert_allclose(dX, (Xp - Xm) / 2e-9, rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose(dY, (Yp - Ym) / 2e-9, rtol=1e-5, atol=1e-9)


@pytest.mark.parametrize("changes", PAIRS)
@pytest.mark.parametrize("gear", [0, 1])
def test_profile_spans_root_to_tip(changes, gear):
    geom = pair_geometry(pair(**changes))
    prof = tooth_profile(geom, gear, n_fillet=40, n_involute=50)
    assert prof.x.size == 90 and np.sum(prof.segment == 0) == 40
    rf, ra = geom.root_radius[gear], geom.tip_radius[gear]
    assert prof.radius[0] == pytest.approx(rf, rel=1e-14)  # middle of the root space
    assert prof.radius.min() == pytest.approx(rf, rel=1e-14)
    assert prof.radius.max() == pytest.approx(ra, rel=1e-14) and prof.radius[-1] == pytest.approx(ra, rel=1e-14)
    assert np.all(prof.radius >= rf * (1 - 1e-14)) and np.all(prof.radius <= ra * (1 + 1e-14))
    z = geom.pair.teeth[gear]
    assert math.atan2(prof.x[0], prof.y[0]) == pytest.approx(math.pi / z, abs=1e-13)
    assert np.all(np.diff(prof.segment) >= 0)  # fillet, then involute
    assert np.all(np.diff(prof.y) > 0)  # root to tip


def test_tip_rounding_clamped_to_full_radius():
    # ISO 53: ρ_fP,max = 0.472 m for αP 20°, h_fP 1.25 m
    assert max_tool_tip_radius(1.0, 1.25, math.radians(20)) == pytest.approx(0.472, abs=5e-4)
    geom = pair_geometry(pair(normal_pressure_angle_deg=25))  # 0.38 m does not fit at 25°
    prof = tooth_profile(geom, 0)
    assert prof.rack.tip_radius_clamped
    assert prof.rack.tip_radius == pytest.approx(max_tool_tip_radius(1.75e-3, 1.25 * 1.75e-3, math.radians(25)))
    # full-radius tip: no root land, the trochoid starts at the middle of the space along the root circle
    t_root = np.array([-math.cos(math.pi / 29), math.sin(math.pi / 29)])  # along the root circle
    assert t_root @ np.array([prof.tangent_x[0], prof.tangent_y[0]]) == pytest.approx(1.0, abs=1e-12)


def test_pointed_rack_is_refused():
    with pytest.raises(GearmeshInputError) as err:
        tooth_profile(pair_geometry(pair(dedendum_coefficient=[2.2, 1.25], profile_shift=[0.6, 0.0])), 0)
    assert err.value.field == "dedendum_coefficient[0]"


def test_undercut_form_point_is_where_trochoid_cuts_involute():
    geom = pair_geometry(load_pair(UNDERCUT))
    assert geom.undercut[0] and not geom.undercut[1]
    prof = tooth_profile(geom, 0, n_fillet=80)
    assert prof.undercut
    assert prof.form_radius == pytest.approx(geom.form_radius[0], rel=1e-14)
    rb = geom.base_radius[0]
    assert prof.form_radius > rb
    # independent of the root finder: dense trochoid, sign of (polar angle − ψ) against R
    t = np.linspace(prof.rack.normal_pressure_angle, math.pi / 2, 200001)
    X, Y, _, _ = rack_rounding_envelope(prof.rack, t)
    R = np.hypot(X, Y)
    ok = R > rb
    g = np.arctan2(X[ok], Y[ok]) - analytic_psi(geom, 0, R[ok])
    k = np.nonzero(np.diff(np.sign(g)))[0]
    Rs = R[ok]
    Rk = Rs[k] - g[k] * (Rs[k + 1] - Rs[k]) / (g[k + 1] - g[k])  # linear interpolation of the zero
    assert Rk.max() == pytest.approx(prof.form_radius, abs=1e-9)
    # below the form point the fillet lies inside the involute (the tooth is thinned)
    tf = np.linspace(prof.form_rounding_angle, math.pi / 2, 2001)[1:]
    Xf, Yf, _, _ = rack_rounding_envelope(prof.rack, tf)
    Rf = np.hypot(Xf, Yf)
    above = Rf > rb
    assert above.any()
    assert np.all(np.arctan2(Xf[above], Yf[above]) < analytic_psi(geom, 0, Rf[above]))
    # the form point sits on both curves, with a corner between them
    i = np.argmax(prof.segment == 1)
    Xf, Yf, dX, dY = rack_rounding_envelope(prof.rack, np.array([prof.form_rounding_angle]))
    assert Xf[0] == pytest.approx(prof.x[i], abs=1e-12) and Yf[0] == pytest.approx(prof.y[i], abs=1e-12)
    tf = -np.array([dX[0], dY[0]]) / math.hypot(dX[0], dY[0])
    assert tf @ np.array([prof.tangent_x[i], prof.tangent_y[i]]) < math.cos(math.radians(1))
    assert np.all(np.diff(prof.y) > 0)


def test_undercut_with_inferred_shift_and_whole_involute_cut():
    p = load_pair(UNDERCUT)
    explicit, undercut = form_point(p, 0, p.profile_shift[0])
    assert undercut
    geom = pair_geometry(p)
    # without shifts, the centre distance's total shift 0.3 is split equally (gear.py), and
    # the form point follows the resolved shift
    inferred = load_pair({k: v for k, v in UNDERCUT.items() if k != "profile_shift"}
                         | {"center_distance_mm": geom.center_distance * 1e3})
    split = load_pair(UNDERCUT | {"profile_shift": [0.15, 0.15]})
    assert pair_geometry(inferred).rho_form[0] == pytest.approx(pair_geometry(split).rho_form[0], rel=1e-9)
    assert form_point(split, 0, 0.15)[0] < explicit  # more shift, less undercut
    # z 5, x −1: the trochoid cuts past the tip; the value reported is ≥ the tip roll length
    tiny = load_pair(dict(name="c", teeth=[5, 40], normal_module_mm=2, normal_pressure_angle_deg=20,
                          helix_angle_deg=0, face_width_mm=10, profile_shift=[-1.0, 0.0]))
    at = math.radians(20)
    r = 5.0e-3
    rb, ra = r * math.cos(at), r + 0.0
    assert form_point(tiny, 0, -1.0)[0] >= math.sqrt(ra**2 - rb**2)
@pytest.mark.parametrize("changes", PAIRS[:3])
def test_half_thickness_is_exact_and_continuous(changes):
    geom = pair_geometry(pair(**changes))
    prof = tooth_profile(geom, 0)
    y0, y1 = prof.y_range
    np.testing.assert_allclose(half_thickness(prof, prof.y), prof.x, rtol=1e-12, atol=1e-15)
    assert np.isnan(half_thickness(prof, np.array([y0 - 1e-6, y1 + 1e-6]))).all()
    # on the involute: x = R sin ψ(R) at the R with R cos ψ(R) = y
    R = np.linspace(prof.form_radius, geom.tip_radius[0], 9)
    psi = analytic_psi(geom, 0, R)
    np.testing.assert_allclose(half_thickness(prof, R * np.cos(psi)), R * np.sin(psi), rtol=1e-12)
    # no jump anywhere: a fine grid changes by no more than its slope allows
    y = np.linspace(y0, y1, 20001)
    x = half_thickness(prof, y)
    assert np.all(np.isfinite(x))
    assert np.max(np.abs(np.diff(x))) < 50 * (y[1] - y[0])


def test_half_thickness_of_undercut_tooth_dips_below_involute():
    geom = pair_geometry(load_pair(UNDERCUT))
    prof = tooth_profile(geom, 0)
    R = np.linspace(geom.base_radius[0] * 1.0001, prof.form_radius * 0.9999, 5)
    psi = analytic_psi(geom, 0, R)
    # at the involute's height the real tooth is thinner than the (cut-away) involute
    assert np.all(half_thickness(prof, R * np.cos(psi)) < R * np.sin(psi))


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(z1=st.integers(12, 40), z2=st.integers(20, 90), an=st.floats(16, 25), beta=st.floats(0, 35),
       x1=st.floats(-0.3, 0.6), rho=st.floats(0.0, 0.45), hf=st.floats(1.1, 1.4))
def test_random_gears_give_consistent_profiles(z1, z2, an, beta, x1, rho, hf):
    try:
        geom = pair_geometry(pair(teeth=[z1, z2], normal_pressure_angle_deg=an, helix_angle_deg=beta,
                                  profile_shift=[x1, 0.0], tool_tip_radius_coefficient=rho,
                                  dedendum_coefficient=hf))
    except GearmeshInputError:
        assume(False)
    for gear in (0, 1):
        prof = tooth_profile(geom, gear, n_fillet=30, n_involute=30)
        assert np.all(np.diff(prof.y) > 0)
        assert np.all(prof.x > 0)
        assert prof.radius.min() == pytest.approx(geom.root_radius[gear], rel=1e-12)
        assert prof.radius.max() == pytest.approx(geom.tip_radius[gear], rel=1e-12)
        assert prof.form_radius >= geom.base_radius[gear]
        inv = prof.segment == 1
        np.testing.assert_allclose(np.arctan2(prof.x[inv], prof.y[inv]),
                                   analytic_psi(geom, gear, prof.radius[inv]), atol=1e-13)
        if not prof.undercut:
            i = np.argmax(inv)
            _, _, dX, dY = rack_rounding_envelope(prof.rack, np.array([prof.form_rounding_angle]))
            tf = -np.array([dX[0], dY[0]]) / math.hypot(dX[0], dY[0])
            assert tf @ np.array([prof.tangent_x[i], prof.tangent_y[i]]) == pytest.approx(1.0, abs=1e-10)


def test_marginal_undercut_starts_the_involute_near_the_base_circle():
    # sharp tool corner reaching 0.54 mm past the interference point: the corner's trochoid
    # passes within microns of the involute's cusp; the crossing is found there, no loop left
    geom = pair_geometry(pair(teeth=[24, 31], normal_pressure_angle_deg=19.000746443171526,
                              helix_angle_deg=2.25, profile_shift=[-0.25, 0.0],
                              tool_tip_radius_coefficient=0.0, dedendum_coefficient=1.125))
    prof = tooth_profile(geom, 0)
    assert prof.undercut and 0.0 <= prof.form_roll < 0.5e-3
    assert prof.form_radius - geom.base_radius[0] < 5e-6
    assert np.all(np.isfinite(prof.tangent_x)) and np.all(np.diff(prof.y) > 0)
    y = np.linspace(*prof.y_range, 5001)
    assert np.all(np.isfinite(half_thickness(prof, y)))
