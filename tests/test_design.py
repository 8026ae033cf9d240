"""Low-fluctuation design (gearmesh.design): integer overlap / transverse contact ratio.

Reference numbers are the low-fluctuation paper Table 1 and §5, derived by hand in the comments.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearmesh.contact import contact_length_fluctuation, contact_lines, mesh_cycle_rolls
from gearmesh.design import (
    integer_overlap_face_width,
    integer_overlap_helix_angle,
    integer_transverse_addendum,
    overlap_fluctuation_curve,
    pair_with_helix_angle,
)
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import GearPair, pair_geometry
from gearmesh.pairfile import pair_from_dict

from pairs import STEEL


def seed001(beta_deg=10.0, b_mm=20.0, **over):
    d = dict(name="s001", teeth=[29, 49], normal_module_mm=1.75, normal_pressure_angle_deg=25,
             helix_angle_deg=beta_deg, face_width_mm=b_mm, bore_radius_mm=[15, 25], material=STEEL)
    d.update(over)
    return pair_from_dict(d)


def test_seed001_pair1_forward_helix_angle():
    # β = arcsin(π·1.75·1/20) = arcsin(0.274889) = 15.9554°  (Table 1, pair 2: 15.95°)
    res = integer_overlap_helix_angle(seed001(), "forward")
    assert math.degrees(res.pair.helix_angle) == pytest.approx(15.9554, abs=1e-4)
    assert res.eps_beta == pytest.approx(1.0, abs=1e-12)
    assert res.geometry.eps_beta == res.eps_beta
    # the rest of the design is kept; εα follows the new αt (it drops, 1.470 -> 1.422)
    assert res.pair.teeth == (29, 49) and res.pair.face_width == pytest.approx((0.02, 0.02))
    assert res.eps_alpha < 1.470
    L = contact_lines(res.geometry, mesh_cycle_rolls(res.geometry, 200)).total_length
    assert np.ptp(L) <= 1e-9 * L.mean()


def test_seed001_pair1_face_width():
    # b = π·1.75·1/sin10° = 5.497787/0.173648 = 31.6604 mm  (Table 1, pair 3: 31.66 mm)
    res = integer_overlap_face_width(seed001(), "forward")
    assert res.pair.face_width[0] * 1e3 == pytest.approx(31.6604, abs=1e-4)
    assert res.eps_beta == pytest.approx(1.0, abs=1e-12)
    assert res.pair.helix_angle == pytest.approx(math.radians(10))
    # the face width does not touch the transverse geometry: εα unchanged
    assert res.eps_alpha == pytest.approx(pair_geometry(seed001()).eps_alpha, rel=1e-14)


def test_seed001_pair4_backward_helix_angle():
    # pair 4: εβ = 20 sin21.84°/(π·1.75) = 7.44068/5.49779 = 1.3534 (Table 1: 1.353);
    # backward to N = 1 -> 15.9554° (the same minimum as forward from pair 1, the low-fluctuation paper §5)
    p4 = seed001(21.84)
    assert pair_geometry(p4).eps_beta == pytest.approx(1.353, abs=5e-4)
    res = integer_overlap_helix_angle(p4, "backward")
    assert math.degrees(res.pair.helix_angle) == pytest.approx(15.9554, abs=1e-4)
    fwd = integer_overlap_helix_angle(seed001(), "forward")
    assert res.pair.helix_angle == pytest.approx(fwd.pair.helix_angle, rel=1e-14)
    # forward from pair 4 goes to εβ = 2: β = arcsin(2·0.274889) = arcsin(0.549779) = 33.3518°
    res2 = integer_overlap_helix_angle(p4, "forward")
    assert math.degrees(res2.pair.helix_angle) == pytest.approx(33.3518, abs=1e-4)
    assert res2.eps_beta == pytest.approx(2.0, abs=1e-12)


def test_backward_face_width_and_explicit_target():
    res = integer_overlap_face_width(seed001(21.84), "backward")
    # b = 5.497787/sin21.84° = 5.497787/0.372016 = 14.7784 mm
    assert res.pair.face_width[0] * 1e3 == pytest.approx(14.7784, abs=1e-4)
    res = integer_overlap_helix_angle(seed001(), n=2)
    assert res.eps_beta == pytest.approx(2.0)


def test_unequal_face_widths_keep_their_margin():
    p = seed001(face_width_mm=[24, 20])
    res = integer_overlap_face_width(p, "forward")
    assert res.pair.face_width[0] - res.pair.face_width[1] == pytest.approx(0.004)
    assert res.eps_beta == pytest.approx(1.0)


def test_already_integer_is_kept():
    res = integer_overlap_helix_angle(seed001(), "forward")
    again = integer_overlap_helix_angle(res.pair, "forward")
    assert again.pair.helix_angle == pytest.approx(res.pair.helix_angle, rel=1e-12)


@pytest.mark.parametrize("call, field", [
    # π mn N = 5.4978 mm > b = 5 mm: no helix angle reaches εβ = 1
    (lambda: integer_overlap_helix_angle(seed001(5.0, 5.0), "forward"), "helix_angle_deg"),
    # εβ = 2 on b = 12 mm needs arcsin(10.9956/12) = 66.4° >= 60°
    (lambda: integer_overlap_helix_angle(seed001(10.0, 12.0), n=2), "helix_angle_deg"),
    # εβ = 0.632: no positive integer below it
    (lambda: integer_overlap_helix_angle(seed001(), "backward"), "helix_angle_deg"),
    (lambda: integer_overlap_face_width(seed001(), "backward"), "face_width_mm"),
    (lambda: integer_overlap_face_width(seed001(0.0), "forward"), "helix_angle_deg"),
    (lambda: integer_overlap_helix_angle(seed001(), "sideways"), "direction"),
    (lambda: integer_overlap_helix_angle(seed001(), n=0), "eps_beta target"),
    (lambda: integer_transverse_addendum(seed001(), n=7), "addendum_coefficient"),
    (lambda: pair_with_helix_angle(seed001(), math.radians(61)), "helix_angle_deg"),
])
def test_design_refusals(call, field):
    with pytest.raises(GearmeshInputError) as info:
        call()
    assert info.value.field == field


def test_keep_centre_distance_refused_when_it_needs_interfering_shifts():
    # 29/49 at a = 69.30 mm with β 15.95°: zero backlash needs Σx ≈ −0.91 -> fillet interference
    p = seed001(center_distance_mm=69.30)
    with pytest.raises(GearmeshInputError):
        integer_overlap_helix_angle(p, "forward", center_distance="keep")
    res = integer_overlap_helix_angle(p, "forward")  # default: shifts kept, new zero-backlash a
    assert res.geometry.backlash_normal == pytest.approx(0.0, abs=1e-12)
    assert res.pair.center_distance is None


def test_keep_centre_distance_keeps_it_and_the_shift_difference():
    p = seed001(10.0, 40.0, profile_shift=[0.3, 0.1], center_distance_mm=70.0)
    g0 = pair_geometry(p)
    res = integer_overlap_helix_angle(p, "backward", center_distance="keep")
    assert res.geometry.center_distance == pytest.approx(0.0700)
    x = res.geometry.profile_shift
    assert x[0] - x[1] == pytest.approx(0.2)
    assert res.geometry.backlash_normal == pytest.approx(0.0, abs=1e-12)
    assert res.eps_beta == pytest.approx(1.0) and g0.eps_beta > 1


def test_integer_transverse_contact_ratio_by_addendum():
    p = seed001()
    fwd = integer_transverse_addendum(p, "forward")
    assert fwd.eps_alpha == pytest.approx(2.0, abs=1e-9)
    # keep_clearance: tip clearance unchanged (0.25 mn = 0.4375 mm)
    np.testing.assert_allclose(fwd.geometry.tip_clearance, pair_geometry(p).tip_clearance, atol=1e-12)
    bwd = integer_transverse_addendum(p, "backward")
    assert bwd.eps_alpha == pytest.approx(1.0, abs=1e-9)
    assert bwd.pair.addendum_coefficient[0] < 1 < fwd.pair.addendum_coefficient[0]
    assert contact_length_fluctuation(fwd.geometry) == pytest.approx(0.0, abs=1e-9)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(st.integers(15, 40), st.integers(40, 100), st.sampled_from([1.0, 2.0, 3.0]), st.floats(5.0, 35.0),
       st.floats(10.0, 80.0), st.sampled_from(["forward", "backward"]))
def test_designed_pair_really_has_integer_overlap(z1, z2, mn, beta, b, direction):
    pair = GearPair(name="r", teeth=(z1, z2), normal_module=mn * 1e-3, normal_pressure_angle=math.radians(20),
                    helix_angle=math.radians(beta), face_width=(b * 1e-3, b * 1e-3))
    for design in (integer_overlap_helix_angle, integer_overlap_face_width):
        try:
            res = design(pair, direction)
        except GearmeshInputError:
            continue
        n = round(res.eps_beta)
        assert n >= 1 and res.eps_beta == pytest.approx(n, abs=1e-9)
        # recomputed from scratch: εβ = b sin β/(π mn)
        g = pair_geometry(res.pair)
        assert g.face_width * math.sin(res.pair.helix_angle) / (math.pi * res.pair.normal_module) == \
            pytest.approx(n, abs=1e-9)
        eb0 = pair_geometry(pair).eps_beta
        if direction == "forward":
            assert n >= eb0 - 1e-9 and n < eb0 + 1
        else:
            assert n <= eb0 + 1e-9 and n > eb0 - 1
        assert contact_length_fluctuation(g) == pytest.approx(0.0, abs=1e-9)


def test_v_curve_minimum_at_integer_overlap():
    betas = np.radians(np.linspace(6.0, 26.0, 81))  # 0.25° steps
    curve = overlap_fluctuation_curve(seed001(), betas, n_positions=200)
    assert curve.valid.all()
    # closed form and clipped lines agree everywhere
    np.testing.assert_allclose(curve.eps_l_numeric, curve.eps_l, rtol=1e-9, atol=1e-12)
    assert np.all(curve.eps_l_sampled <= curve.eps_l + 1e-12)
    # each β has its own εα: it falls as β grows (αt grows with β)
    assert np.all(np.diff(curve.eps_alpha) < 0)
    k = int(np.argmin(curve.eps_l))
    # minimum at the grid point nearest 15.9554° (εβ = 1), where εl ~ 0
    assert math.degrees(curve.helix_angle[k]) == pytest.approx(16.0, abs=0.13)
    assert curve.eps_beta[k] == pytest.approx(1.0, abs=0.01)
    assert curve.eps_l[k] < 0.01
    # V shape: decreasing to the minimum over the sweep from pair 1 (10°), increasing after it
    # up to pair 4 (21.84°)
    i10, i22 = int(np.argmin(np.abs(np.degrees(betas) - 10))), int(np.argmin(np.abs(np.degrees(betas) - 21.75)))
    assert np.all(np.diff(curve.eps_l[i10:k + 1]) < 0)
    assert np.all(np.diff(curve.eps_l[k:i22 + 1]) > 0)
    # at exactly εβ = 1, εl = 0
    exact = overlap_fluctuation_curve(seed001(), [math.asin(math.pi * 1.75 / 20)])
    assert exact.eps_l[0] == pytest.approx(0.0, abs=1e-12)
    assert exact.eps_l_numeric[0] == pytest.approx(0.0, abs=1e-12)


def test_v_curve_marks_refused_angles():
    # 29/49 at αn 25° with a 0.4 addendum: εα ≈ 0.6 < 1 for every β -> all invalid, with the reason
    curve = overlap_fluctuation_curve(seed001().with_changes(addendum_coefficient=(0.4, 0.4)),
                                      np.radians([5.0, 15.0]))
    assert not curve.valid.any()
    assert np.all(np.isnan(curve.eps_l))
    assert all("eps_alpha" in r for r in curve.reasons)
