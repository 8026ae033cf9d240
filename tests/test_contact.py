"""Contact lines in the plane of action (gearmesh.contact): physics invariants.

The numeric total length (exactly clipped lines summed) is checked against independent
closed forms (l_mean = b εα / cos βb, docs/modelling.md; min/max of the low-fluctuation paper §1) over random valid
pairs; the 3-D end points are checked against the involute-helicoid equations (the contact-line paper).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from gearmesh.contact import (
    contact_length_closed_form,
    contact_length_fluctuation,
    contact_length_summary,
    contact_line_end_points,
    contact_lines,
    contact_lines_benchmark,
    contact_roll_positions,
    flank_reference_angles,
    mesh_cycle_rolls,
    plane_of_action_points,
    tooth_pair_indices,
)
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import GearPair, involute, pair_geometry

SETTINGS = settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])


def make_pair(z1, z2, mn_mm, an_deg, beta_deg, b_mm, x1=0.0, x2=0.0, hand="right"):
    return GearPair(name="h", teeth=(z1, z2), normal_module=mn_mm * 1e-3,
                    normal_pressure_angle=math.radians(an_deg), helix_angle=math.radians(beta_deg),
                    face_width=(b_mm * 1e-3, b_mm * 1e-3), profile_shift=(x1, x2), helix_hand=hand)


def geometry_or_skip(pair):
    """pair_geometry, or hypothesis.assume(False) for pairs it refuses."""
    try:
        return pair_geometry(pair)
    except GearmeshInputError:
        assume(False)


@st.composite
def valid_pairs(draw, beta=None, hand=None):
    z1 = draw(st.integers(14, 45))
    z2 = draw(st.integers(z1, 110))
    mn = draw(st.sampled_from([1.0, 1.5, 1.75, 2.0, 2.25, 3.0, 5.0]))
    an = draw(st.floats(17.0, 25.0))
    if beta is None:
        beta = draw(st.one_of(st.just(0.0), st.floats(0.5, 40.0)))
    b = draw(st.floats(4.0, 80.0))
    x1 = draw(st.floats(-0.2, 0.5))
    x2 = draw(st.floats(-0.2, 0.5))
    h = hand if hand is not None else draw(st.sampled_from(["right", "left"]))
    return make_pair(z1, z2, mn, an, beta, b, x1, x2, h)


SEED001_P1 = make_pair(29, 49, 1.75, 25, 10, 20)


# --------------------------------------------------------------------------------------
# Total length: numeric against closed form
# --------------------------------------------------------------------------------------


@SETTINGS
@given(valid_pairs())
def test_total_length_mean_min_max_match_closed_form(pair):
    geom = geometry_or_skip(pair)
    mean, lo, hi = contact_length_closed_form(geom)
    b = geom.face_width
    # l_mean = b εα / cos βb (docs/modelling.md), independent of εβ
    assert mean == pytest.approx(b * geom.eps_alpha / math.cos(geom.base_helix_angle), rel=1e-12)
    # Exact numeric extremes: L is piecewise linear, evaluated at every slope change.
    s = contact_length_summary(geom, n_positions=2000)
    assert s.numeric_mean == pytest.approx(mean, rel=1e-9)
    assert s.numeric_min == pytest.approx(lo, rel=1e-9, abs=1e-12)
    assert s.numeric_max == pytest.approx(hi, rel=1e-9, abs=1e-12)
    # A fine even grid (the contact-line paper's L_ave = ΣL_k/N_k) converges to the same mean and stays
    # within the closed-form bounds.
    L = contact_lines(geom, mesh_cycle_rolls(geom, 2000)).total_length
    tol = 2 * (hi - lo) / 2000 + 1e-12
    assert L.mean() == pytest.approx(mean, abs=tol + 1e-9 * mean)
    assert L.min() >= lo - 1e-12 and L.max() <= hi + 1e-12
    frac = geom.eps_alpha % 1.0
    if geom.base_helix_angle > 0 or min(frac, 1.0 - frac) > 2 / 2000:
        # a spur pair's L is piecewise constant: an even grid reaches a plateau only if it is
        # wider than the grid spacing (εα = 1.9998 leaves a single-pair window of 2e-4 p_bt)
        assert L.min() <= lo + tol + (hi - lo) * 2e-3 and L.max() >= hi - tol - (hi - lo) * 2e-3
    assert contact_length_fluctuation(geom) == pytest.approx((hi - lo) / b)


@SETTINGS
@given(valid_pairs())
def test_lines_lie_in_active_zone_and_are_inclined_at_base_helix_angle(pair):
    geom = geometry_or_skip(pair)
    lines = contact_lines(geom, mesh_cycle_rolls(geom, 97))
    on = lines.length > 0
    g, half = geom.path_of_contact, geom.face_width / 2
    eps = 1e-12
    for arr in (lines.s_start, lines.s_end):
        assert np.all((arr[on] >= -eps) & (arr[on] <= g + eps))
    for arr in (lines.z_start, lines.z_end):
        assert np.all((arr[on] >= -half - eps) & (arr[on] <= half + eps))
    assert np.all(np.isnan(lines.s_start[~on]))
    ds, dz = lines.s_end[on] - lines.s_start[on], lines.z_end[on] - lines.z_start[on]
    # In the plane of action (orthonormal coordinates s, z) the segment length is √(Δs² + Δz²)
    np.testing.assert_allclose(lines.length[on], np.hypot(ds, dz), rtol=1e-12, atol=1e-15)
    # ... and its angle to the axis is βb, with the sign of the hand
    if geom.base_helix_angle > 0:
        h = 1 if pair.helix_hand == "right" else -1
        np.testing.assert_allclose(ds, h * math.tan(geom.base_helix_angle) * dz, rtol=1e-9, atol=1e-15)
    else:
        assert np.all(ds == 0) and np.allclose(dz, geom.face_width)
    # The 3-D fixed-frame end points are the same distance apart
    ends = contact_line_end_points(geom, lines).points.fixed
    d3 = np.linalg.norm(ends[:, :, 1] - ends[:, :, 0], axis=-1)
    np.testing.assert_allclose(d3[on], lines.length[on], rtol=1e-9)
    # The pointwise view agrees: slices with a finite s are exactly those inside a line.
    zs = np.linspace(-half, half, 11)
    s = contact_roll_positions(geom, lines.roll, zs, lines.pairs)
    inside = (zs[None, None, :] >= np.nan_to_num(lines.z_start, nan=np.inf)[..., None] - 1e-15) & \
             (zs[None, None, :] <= np.nan_to_num(lines.z_end, nan=-np.inf)[..., None] + 1e-15)
    interior = np.isfinite(s) & ~inside
    assert not interior.any()


@SETTINGS
@given(valid_pairs(hand="right"))
def test_both_hands_give_the_same_total_length(pair):
    geom_r = geometry_or_skip(pair)
    geom_l = pair_geometry(pair.with_changes(helix_hand="left"))
    roll = mesh_cycle_rolls(geom_r, 400)
    Lr = contact_lines(geom_r, roll).total_length
    Ll = contact_lines(geom_l, roll).total_length
    # The face is centred at z = 0, so mirroring z maps each right-hand line onto the
    # left-hand one of the same s-range: L is equal with zero shift; find the best shift anyway.
    errs = [np.abs(Lr - np.roll(Ll, k)).max() for k in range(len(roll))]
    assert int(np.argmin(errs)) == 0
    assert errs[0] <= 1e-12


@SETTINGS
@given(valid_pairs(), st.integers(-3, 4))
def test_total_length_period_is_one_base_pitch(pair, k):
    geom = geometry_or_skip(pair)
    roll = mesh_cycle_rolls(geom, 61)
    L0 = contact_lines(geom, roll).total_length
    Lk = contact_lines(geom, roll + k * geom.transverse_base_pitch).total_length
    np.testing.assert_allclose(Lk, L0, rtol=1e-9, atol=1e-14)
    # pointwise: the number of slices in contact is periodic too (no tooth pair is lost
    # for rolls outside the first base pitch)
    zs = np.linspace(-geom.face_width / 2, geom.face_width / 2, 9)
    n0 = np.isfinite(contact_roll_positions(geom, roll, zs)).sum(axis=(1, 2))
    nk = np.isfinite(contact_roll_positions(geom, roll + k * geom.transverse_base_pitch, zs)).sum(axis=(1, 2))
    assert np.array_equal(n0, nk) or np.abs(n0 - nk).max() <= 1  # a slice exactly on s = 0 or g_α may flip


@SETTINGS
@given(st.integers(17, 40), st.integers(40, 90), st.sampled_from([1.5, 2.0, 3.0]),
       st.integers(1, 3), st.floats(8.0, 35.0), st.sampled_from(["right", "left"]))
def test_integer_overlap_ratio_gives_constant_length(z1, z2, mn, n, beta_deg, hand):
    b_mm = math.pi * mn * n / math.sin(math.radians(beta_deg))  # εβ = N exactly (the low-fluctuation paper §1)
    assume(b_mm <= 200)
    geom = geometry_or_skip(make_pair(z1, z2, mn, 20.0, beta_deg, b_mm, hand=hand))
    assert geom.eps_beta == pytest.approx(n, rel=1e-12)
    L = contact_lines(geom, mesh_cycle_rolls(geom, 300)).total_length
    l_mean = geom.face_width * geom.eps_alpha / math.cos(geom.base_helix_angle)
    np.testing.assert_allclose(L, l_mean, rtol=1e-9)
    assert contact_length_fluctuation(geom) == pytest.approx(0.0, abs=1e-9)


def test_integer_transverse_ratio_gives_constant_length():
    # εα = 2 by the addendum (design.integer_transverse_addendum) -> constant L for any εβ
    from gearmesh.design import integer_transverse_addendum

    res = integer_transverse_addendum(SEED001_P1, "forward")
    L = contact_lines(res.geometry, mesh_cycle_rolls(res.geometry, 300)).total_length
    assert res.eps_alpha == pytest.approx(2.0, abs=1e-9)
    assert np.ptp(L) <= 1e-9 * L.mean()


@SETTINGS
@given(valid_pairs(beta=0.0))
def test_small_helix_angle_tends_to_spur_step_function(spur):
    geom0 = geometry_or_skip(spur)
    roll = mesh_cycle_rolls(geom0, 500)
    L0 = contact_lines(geom0, roll).total_length
    b = geom0.face_width
    # spur: L is ⌊εα⌋b or ⌈εα⌉b, the larger for a fraction frac(εα) of the cycle
    n = math.floor(geom0.eps_alpha)
    assert set(np.round(L0 / b, 9)) <= {float(n), float(n + 1)}
    assert np.mean(L0 > (n + 0.5) * b) == pytest.approx(geom0.eps_alpha - n, abs=2 / 500 + 1e-9)
    for beta in (1e-3, 1e-5):
        geom = pair_geometry(spur.with_changes(helix_angle=beta))
        L = contact_lines(geom, roll).total_length
        # differs from the step only within b tan βb of each step (two steps per cycle);
        # elsewhere only by O(β²) (1/cos βb, and αt, εα change with cos β)
        width = b * math.tan(geom.base_helix_angle)
        differ = np.abs(L - L0) > (1e-9 + 10 * beta**2) * b
        assert differ.mean() <= 2 * width / geom.transverse_base_pitch + 2 / 500 + 1e-12
        assert np.abs(L - L0).max() <= b * (1 + 1e-6)
        mean, lo, hi = contact_length_closed_form(geom)
        fa, fb = geom.eps_alpha % 1, geom.eps_beta % 1
        if fb <= fa <= 1 - fb:  # the step is resolved: both plateaus exist
            assert lo == pytest.approx(n * b, rel=1e-3) and hi == pytest.approx((n + 1) * b, rel=1e-3)
        else:  # frac(εα) within εβ of an integer: the ramps overlap and cut a plateau short
            assert n * b * (1 - 1e-3) <= lo <= hi <= (n + 1) * b * (1 + 1e-3)


def test_seed001_pair1_numbers():
    geom = pair_geometry(SEED001_P1)
    # εα = 1.47003, εβ = 0.63170, βb = 9.05478° (test_gear.py); in base pitches per sin βb:
    #   L sin βb / pbt ∈ [⌊εβ⌋εα + ⌊εα⌋fβ + max(0, fα + fβ − 1), … + min(fα, fβ)]
    #   = [0 + 0.63170 + 0.10173, 0.63170 + 0.47003] = [0.73343, 1.10173]
    #   pbt / sin βb = 5.04556 / 0.157378 = 32.0600 mm -> L ∈ [23.5138, 35.3214] mm
    #   l_mean = 20·1.47003/cos 9.05478° = 29.4005/0.987537 = 29.7715 mm
    #   εl = (35.3214 − 23.5138)/20 = 0.5904
    mean, lo, hi = contact_length_closed_form(geom)
    assert mean == pytest.approx(29.7715e-3, rel=2e-5)
    assert lo == pytest.approx(23.5138e-3, rel=2e-5)
    assert hi == pytest.approx(35.3214e-3, rel=2e-5)
    assert contact_length_fluctuation(geom) == pytest.approx(0.5904, abs=1e-3)


# --------------------------------------------------------------------------------------
# 3-D end points: fixed, pinion and gear frames, involute parameters
# --------------------------------------------------------------------------------------


def _polar_angle(xyz):
    return np.arctan2(xyz[..., 1], xyz[..., 0])


def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


@SETTINGS
@given(valid_pairs())
def test_end_points_lie_on_the_involute_helicoids(pair):
    geom = geometry_or_skip(pair)
    ends = contact_line_end_points(geom, mesh_cycle_rolls(geom, 37))
    pts = ends.points
    on = np.isfinite(pts.u_pinion)
    assume(on.any())
    rb1, rb2 = geom.base_radius
    z1, z2 = pair.teeth
    h = 1 if pair.helix_hand == "right" else -1
    tb = math.tan(geom.base_helix_angle)
    sigma1, sigma2 = flank_reference_angles(geom)
    j = np.broadcast_to(ends.pairs[None, :, None], on.shape)
    z = pts.fixed[..., 2]
    # radii: r = r_b √(1 + u²) in both body frames
    np.testing.assert_allclose(np.hypot(pts.pinion[..., 0], pts.pinion[..., 1])[on],
                               rb1 * np.sqrt(1 + pts.u_pinion[on] ** 2), rtol=1e-12)
    np.testing.assert_allclose(np.hypot(pts.gear[..., 0], pts.gear[..., 1])[on],
                               rb2 * np.sqrt(1 + pts.u_gear[on] ** 2), rtol=1e-12)
    # ρ1 + ρ2 = T1T2 = a sin αwt
    np.testing.assert_allclose((pts.u_pinion * rb1 + pts.u_gear * rb2)[on],
                               geom.center_distance * math.sin(geom.operating_pressure_angle), rtol=1e-12)
    # polar angle: θ = σ − inv(u) ± 2πj/z ± h z tan βb / r_b, for every roll (a fixed surface)
    th1 = _polar_angle(pts.pinion) + involute(np.arctan(pts.u_pinion)) - 2 * np.pi * j / z1 - h * z * tb / rb1
    th2 = _polar_angle(pts.gear) + involute(np.arctan(pts.u_gear)) + 2 * np.pi * j / z2 + h * z * tb / rb2
    assert np.abs(_wrap(th1[on] - sigma1)).max() < 1e-9
    assert np.abs(_wrap(th2[on] - sigma2)).max() < 1e-9
    # tooth-0 frames: the same surface without the tooth offset
    th1t = _polar_angle(pts.pinion_tooth) + involute(np.arctan(pts.u_pinion)) - h * z * tb / rb1
    assert np.abs(_wrap(th1t[on] - sigma1)).max() < 1e-9
    th2t = _polar_angle(pts.gear_tooth) + involute(np.arctan(pts.u_gear)) + h * z * tb / rb2
    assert np.abs(_wrap(th2t[on] - sigma2)).max() < 1e-9
    # u lies within the active profile of each gear
    assert np.all(pts.u_pinion[on] * rb1 >= geom.rho_sap[0] - 1e-12)
    assert np.all(pts.u_pinion[on] * rb1 <= geom.rho_eap[0] + 1e-12)
    assert np.all(pts.u_gear[on] * rb2 >= geom.rho_sap[1] - 1e-12)
    assert np.all(pts.u_gear[on] * rb2 <= geom.rho_eap[1] + 1e-12)
    # all three frames describe one point in space
    c1, s1 = np.cos(ends.phi_pinion)[:, None, None], np.sin(ends.phi_pinion)[:, None, None]
    back1 = np.stack([c1 * pts.pinion[..., 0] - s1 * pts.pinion[..., 1],
                      s1 * pts.pinion[..., 0] + c1 * pts.pinion[..., 1]], -1)
    c2, s2 = np.cos(ends.phi_gear)[:, None, None], np.sin(ends.phi_gear)[:, None, None]
    back2 = np.stack([c2 * pts.gear[..., 0] + s2 * pts.gear[..., 1] + geom.center_distance,
                      -s2 * pts.gear[..., 0] + c2 * pts.gear[..., 1]], -1)
    np.testing.assert_allclose(back1[on], pts.fixed[..., :2][on], atol=1e-12)
    np.testing.assert_allclose(back2[on], pts.fixed[..., :2][on], atol=1e-12)


def test_reference_tooth0_at_sap_at_roll_zero():
    geom = pair_geometry(SEED001_P1)
    p = plane_of_action_points(geom, 0.0, 0.0, 0.0)
    # at roll 0 the body frames coincide with the fixed frame; the point is A at ρ_SAP1
    np.testing.assert_allclose(p.pinion, p.fixed, atol=1e-15)
    assert np.hypot(*p.fixed[:2]) == pytest.approx(geom.sap_radius[0], rel=1e-12)
    assert float(p.rho_pinion) == pytest.approx(geom.rho_sap[0])
    assert float(p.rho_gear) == pytest.approx(geom.rho_eap[1])  # the gear tip
    # the pitch point (r_w1, 0) is at s = ρ_w1 − ρ_SAP1 = r_b1 tan αwt − ρ_SAP1
    s_c = geom.base_radius[0] * math.tan(geom.operating_pressure_angle) - geom.rho_sap[0]
    pc = plane_of_action_points(geom, 0.0, s_c, 0.0)
    np.testing.assert_allclose(pc.fixed, [geom.operating_pitch_radius[0], 0.0, 0.0], atol=1e-15)
    # the gear frame at roll 0 is the fixed frame shifted to the gear centre
    np.testing.assert_allclose(pc.gear, [-geom.operating_pitch_radius[1], 0.0, 0.0], atol=1e-15)


def test_benchmark_kernel_is_vectorised_and_consistent():
    geom = pair_geometry(make_pair(29, 71, 5, 20, 27.5, 42))
    lines = contact_lines_benchmark(geom, 360)
    assert lines.length.shape == (360, len(tooth_pair_indices(geom)))
    np.testing.assert_allclose(lines.total_length.mean(),
                               geom.face_width * geom.eps_alpha / math.cos(geom.base_helix_angle), rtol=1e-3)


def test_end_points_agree_with_surface_module_flanks():
    """Cross-module agreement: the tooth-0-frame end points, turned into gearmesh.surface's
    body frames (tooth 0 centreline on +y; ours are theirs turned by Φ(φ1 = 0)), lie on its
    flank of tooth 0 at the same roll length and z."""
    surface = pytest.importorskip("gearmesh.surface")
    for hand, beta in (("right", 15.0), ("left", 27.5), ("right", 0.0)):
        geom = pair_geometry(make_pair(29, 49, 1.75, 25, beta, 20, 0.1, -0.05, hand))
        pts = contact_line_end_points(geom, mesh_cycle_rolls(geom, 23)).points
        on = np.isfinite(pts.u_pinion)
        for gear, mine, rho in ((0, pts.pinion_tooth, pts.rho_pinion), (1, pts.gear_tooth, pts.rho_gear)):
            phi0 = float(surface.body_rotation(geom, gear, 0.0))
            c, s = math.cos(-phi0), math.sin(-phi0)
            theirs_frame = np.stack([c * mine[..., 0] - s * mine[..., 1], s * mine[..., 0] + c * mine[..., 1],
                                     mine[..., 2]], -1)
            flank, _ = surface.flank_point(geom, gear, rho[on], mine[..., 2][on])
            np.testing.assert_allclose(theirs_frame[on], flank, atol=1e-12)
