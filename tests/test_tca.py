"""Unloaded TCA: zero TE of perfect pairs, exact tip-edge separations, reliefs and lead errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from pairs import low_fluctuation_pair1

from gearmesh.datasets.ltca import tca_dataset
from gearmesh.deviation import Deviations, read_deviations
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import Modification, pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict
from gearmesh.io import check_documented
from gearmesh.separation import (REGION_APPROACH_TIP, REGION_FLANK, REGION_RECESS_TIP, approach_tip_separation,
                                 flank_separation, recess_tip_separation)
from gearmesh.tca import candidate_grid, engagement_point, tca



@pytest.fixture(scope="module")
def helical_z29_71_m5():
    return load_pair(Path(__file__).resolve().parents[1] / "config/pairs/helical_z29_71_m5.yaml")


def _geom(pair, **mods):
    return pair_geometry(pair.with_changes(**mods)) if mods else pair_geometry(pair)


@pytest.mark.parametrize("data", [low_fluctuation_pair1(), low_fluctuation_pair1(helix_angle_deg=0),
                                  low_fluctuation_pair1(helix_angle_deg=21.84, helix_hand="left")])
def test_unmodified_aligned_pair_has_zero_te(data):
    geom = pair_geometry(pair_from_dict(data))
    res = tca(geom, positions=32, points=40)
    assert np.all(res.te == 0.0)  # every flank point of the active zone has zero separation
    flank = res.grid.region == REGION_FLANK
    assert np.all(res.grid.gap[flank] == 0.0)
    tips = (res.grid.region == REGION_APPROACH_TIP) | (res.grid.region == REGION_RECESS_TIP)
    assert tips.any() and np.all(res.grid.gap[tips] > 0)  # tip edges outside the zone stand off
    assert res.te_next_pair_at_engagement == 0.0 and res.te_at_engagement == 0.0


def test_seed000_unmodified_zero_te_and_engagement(helical_z29_71_m5):
    geom = pair_geometry(helical_z29_71_m5)
    res = tca(geom)
    assert res.te_peak_to_peak == 0.0
    roll_a, j_a, z_a = engagement_point(geom)
    # the entering corner reaches s = 0 exactly at roll_A
    s = roll_a + j_a * geom.transverse_base_pitch + z_a * math.tan(geom.base_helix_angle)
    assert abs(s) < 1e-15 and 0 <= roll_a < geom.transverse_base_pitch and z_a == 0.5 * geom.face_width


def _pinion_involute_distance(geom, px, py, s):
    """Brute force: the smallest distance from (px, py) to the pinion flank (sampled, then refined)."""
    rb1 = geom.base_radius[0]
    sigma = -geom.operating_pressure_angle + (geom.rho_sap[0] + s) / rb1

    def dist(u):
        tau = sigma - u
        return np.hypot(rb1 * np.cos(tau) - rb1 * u * np.sin(tau) - px, rb1 * np.sin(tau) + rb1 * u * np.cos(tau) - py)

    u = np.linspace(0.05, 1.2, 20001)
    k = int(np.argmin(dist(u)))
    best = minimize_scalar(dist, bounds=(u[max(k - 1, 0)], u[min(k + 1, u.size - 1)]), method="bounded",
                           options={"xatol": 1e-14})
    return float(best.fun)


def test_approach_tip_separation_is_the_true_distance_to_the_pinion_flank(helical_z29_71_m5):
    """The gear tip point, rotated back by −s/r_b2, stands off the pinion involute by the gap
    (brute-force distance to the sampled involute: independent of the σ = θ + inv u formula)."""
    geom = pair_geometry(helical_z29_71_m5)
    a, rb2 = geom.center_distance, geom.base_radius[1]
    awt = geom.operating_pressure_angle
    for s in (-0.2e-3, -1e-3, -3e-3):
        gap, rho = approach_tip_separation(geom, s, 0.0)
        ax = geom.base_radius[0] * math.cos(awt) + geom.rho_sap[0] * math.sin(awt)
        ay = -geom.base_radius[0] * math.sin(awt) + geom.rho_sap[0] * math.cos(awt)
        psi = -s / rb2
        px = a + math.cos(psi) * (ax - a) - math.sin(psi) * ay
        py = math.sin(psi) * (ax - a) + math.cos(psi) * ay
        assert gap == pytest.approx(_pinion_involute_distance(geom, px, py, s), rel=1e-5, abs=1e-10)
        assert math.hypot(px, py) == pytest.approx(math.hypot(geom.base_radius[0], float(rho)), rel=1e-12)


def test_recess_tip_separation_is_the_pinion_turn_that_closes_it(helical_z29_71_m5):
    """Turn the pinion on by gap/r_b1 (gear held): its tip point then lies on the gear flank
    (brute-force distance to the gear involute)."""
    geom = pair_geometry(helical_z29_71_m5)
    a, (rb1, rb2) = geom.center_distance, geom.base_radius
    awt, g = geom.operating_pressure_angle, geom.path_of_contact
    ex = rb1 * math.cos(awt) + geom.rho_eap[0] * math.sin(awt)
    ey = -rb1 * math.sin(awt) + geom.rho_eap[0] * math.cos(awt)
    for e in (0.5e-3, 1e-3, 2e-3):
        s = g + e
        gap = float(recess_tip_separation(geom, s, 0.0)[0])
        sigma2 = math.pi - awt + (geom.rho_eap[1] - s) / rb2

        def dist(u, px, py):
            tau = sigma2 - u
            return math.hypot(a + rb2 * math.cos(tau) - rb2 * u * math.sin(tau) - px,
                              rb2 * math.sin(tau) + rb2 * u * math.cos(tau) - py)

        def off(turn):
            psi = e / rb1 + turn
            px, py = math.cos(psi) * ex - math.sin(psi) * ey, math.sin(psi) * ex + math.cos(psi) * ey
            u = np.linspace(0.3, 1.5, 20001)
            k = int(np.argmin([dist(x, px, py) for x in u[::50]])) * 50
            lo, hi = u[max(k - 60, 0)], u[min(k + 60, u.size - 1)]
            return minimize_scalar(lambda x: dist(x, px, py), bounds=(lo, hi), method="bounded",
                                   options={"xatol": 1e-14}).fun

        assert off(0.0) > 0.9 * gap  # the tip stands off the flank before the turn
        assert off(gap / rb1) < 1e-4 * gap  # and touches it after (to the brute-force floor)
        # the turn is solved exactly: the distance is V-shaped about it, 0.5 % either side alike
        below, above = off(0.995 * gap / rb1), off(1.005 * gap / rb1)
        assert abs(below - above) < 1e-4 * below


def test_tip_separations_are_continuous_and_grow_quadratically(helical_z29_71_m5):
    geom = pair_geometry(helical_z29_71_m5)
    g = geom.path_of_contact
    for fun, base in ((approach_tip_separation, lambda e: -e), (recess_tip_separation, lambda e: g + e)):
        eps = np.array([1e-6, 1e-4, 1e-3, 2e-3])
        gap = fun(geom, base(eps), 0.0 * eps)[0]
        assert np.all(gap > 0) and gap[0] < 1e-10
        # conjugate involutes touching at the zone end part quadratically: gap/eps² ≈ const
        ratio = gap[1:] / eps[1:] ** 2
        assert np.ptp(ratio) / ratio.mean() < 0.1


def test_more_tip_relief_on_the_gear_opens_the_entering_corner(helical_z29_71_m5):
    """The gear tip enters first (pinion drives): its relief y2 opens TE(φ1A) by ≈ y2/cos βb."""
    values = []
    for y2 in (0.0, 5e-6, 10e-6, 20e-6):
        mod = Modification(tip_relief=y2, tip_relief_length=3e-3 if y2 else 0.0)
        geom = pair_geometry(helical_z29_71_m5.with_changes(modification=(Modification(), mod)))
        values.append(tca(geom, positions=8, points=30).te_next_pair_at_engagement)
    values = np.array(values)
    assert np.all(np.diff(values) > 0)
    cb = math.cos(pair_geometry(helical_z29_71_m5).base_helix_angle)
    assert values[-1] == pytest.approx(20e-6 / cb, rel=0.02)


def test_pinion_root_relief_and_crowning_also_open_the_entry(helical_z29_71_m5):
    base = tca(pair_geometry(helical_z29_71_m5), positions=8, points=30).te_next_pair_at_engagement
    root = Modification(root_relief=10e-6, root_relief_length=2e-3)
    crown = Modification(crowning=10e-6)
    for mod in (root, crown):
        geom = pair_geometry(helical_z29_71_m5.with_changes(modification=(mod, Modification())))
        assert tca(geom, positions=8, points=30).te_next_pair_at_engagement > base + 5e-6


def test_flank_separation_converts_normal_depth_to_the_transverse_direction(helical_z29_71_m5):
    mod = Modification(tip_relief=20e-6, tip_relief_length=3e-3)
    geom = pair_geometry(helical_z29_71_m5.with_changes(modification=(mod, Modification())))
    gap = flank_separation(geom, geom.path_of_contact, 0.0)  # pinion tip
    assert gap == pytest.approx(20e-6 / math.cos(geom.base_helix_angle), rel=1e-12)


def test_crowned_pair_te_and_first_contact_at_face_centre_for_spur():
    pair = pair_from_dict(low_fluctuation_pair1(helix_angle_deg=0))
    geom = pair_geometry(pair.with_changes(modification=(Modification(crowning=8e-6), Modification())))
    res = tca(geom, positions=16, points=41)
    active = np.isfinite(res.contact_z)
    assert np.allclose(res.contact_z[active], 0.0, atol=1e-12)  # symmetric crowning: the centre touches
    assert np.all(res.te == 0.0)  # the middle slice (z = 0) is unmodified


def test_lead_slope_errors_of_both_gears_cancel_and_add():
    pair = pair_from_dict(low_fluctuation_pair1(helix_angle_deg=0))
    geom = pair_geometry(pair)
    b = geom.face_width
    opposite = candidate_grid(geom, np.array([0.3e-3]), 20, (10e-6, -10e-6), 0.0)
    flank = opposite.region == REGION_FLANK
    assert np.all(np.abs(opposite.gap[flank]) < 1e-15)  # matching errors cancel: no gap, no TE
    aligned = tca(geom, positions=8, points=21, lead_slope=(10e-6, -10e-6))
    assert np.all(np.abs(aligned.te) < 1e-15)
    # + stands proud at the leading face end (z = +b/2 of a right-hand pinion, −b/2 of a left-hand
    # one): the gap closes towards it whatever the hand (gearmesh.deviation)
    for hand, sign in (("right", -1.0), ("left", 1.0)):
        g = pair_geometry(pair.with_changes(helix_hand=hand))
        one = candidate_grid(g, np.array([0.3e-3]), 20, (10e-6, 0.0), 0.0)
        slope = np.polyfit(one.z, one.gap[0, np.flatnonzero((one.region[0] > 0).any(axis=1))[0]], 1)[0]
        assert slope == pytest.approx(sign * 10e-6 / b, rel=1e-9)


def test_tca_dataset_is_documented_and_refuses_bad_input(helical_z29_71_m5):
    ds = tca_dataset(helical_z29_71_m5.with_changes(deviations=Deviations(lead_slope=(5e-6, 0.0))), positions=8, points=10)
    check_documented(ds)
    assert set(ds["separation"].dims) == {"position", "line", "point"}
    assert float(ds["lead_slope"][0]) == pytest.approx(5e-6)
    with pytest.raises(GearmeshInputError, match=r"lead_slope_deviation_um\[0\]"):
        read_deviations({"lead_slope_deviation_um": [float("nan"), 0.0]})
    with pytest.raises(GearmeshInputError, match="lead_slope_deviation_um"):
        read_deviations({"lead_slope_deviation_um": [1.0, 2.0, 3.0]})
    with pytest.raises(GearmeshInputError, match="positions"):
        tca_dataset(helical_z29_71_m5, positions=0)
    bad = helical_z29_71_m5.with_changes(modification=(Modification(tip_relief=-5e-6, tip_relief_length=1e-3), Modification()))
    with pytest.raises(GearmeshInputError, match="modification.pinion.tip_relief_um"):
        tca_dataset(bad)
    nan = helical_z29_71_m5.with_changes(modification=(Modification(), Modification(crowning=float("nan"))))
    with pytest.raises(GearmeshInputError, match="modification.gear.crowning_um"):
        tca_dataset(nan)
    long = helical_z29_71_m5.with_changes(modification=(Modification(tip_relief=5e-6, tip_relief_length=40e-3), Modification()))
    with pytest.raises(GearmeshInputError, match="relief_length"):
        tca_dataset(long)
