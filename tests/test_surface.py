"""Physics of the 3-D flanks, the plane-of-action mapping and the modification (gearmesh.surface)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearmesh.contact import contact_roll_positions, tooth_pair_indices
from gearmesh.gear import involute, pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.surface import (
    body_rotation,
    flank_point,
    gear_contact_point,
    involute_helicoid,
    involute_helicoid_z,
    modification_depth,
    pinion_contact_point,
    plane_of_action_normal,
    tooth_surface,
)

from pairs import low_fluctuation_pair1


def pair_dict(**changes):
    return low_fluctuation_pair1(**{"name": "t", **changes})


def geometry(**changes):
    return pair_geometry(load_pair(pair_dict(**changes)))


# --------------------------------------------------------------------------------------
# The helicoid itself
# --------------------------------------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(rb=st.floats(5e-3, 0.2), beta_b=st.floats(-45, 45), u=st.floats(0.0, 1.5),
       theta=st.floats(-1.0, 1.0), sigma=st.floats(-math.pi, math.pi), side=st.sampled_from([1, -1]))
def test_helicoid_normal_is_unit_and_normal(rb, beta_b, u, theta, sigma, side):
    if abs(beta_b) < 1e-3:
        beta_b = 1e-3
    p = rb / math.tan(math.radians(beta_b))
    pt, n = involute_helicoid(rb, p, u, theta, sigma, side)
    assert np.linalg.norm(n) == pytest.approx(1.0, abs=1e-14)
    # partial derivatives by central differences
    h = 1e-6
    du = (involute_helicoid(rb, p, u + h, theta, sigma, side)[0]
          - involute_helicoid(rb, p, u - h, theta, sigma, side)[0]) / (2 * h)
    dth = (involute_helicoid(rb, p, u, theta + h, sigma, side)[0]
           - involute_helicoid(rb, p, u, theta - h, sigma, side)[0]) / (2 * h)
    noise = 1e-9 * rb  # round-off of the differences, r_b·ε/h
    assert abs(n @ du) <= 1e-8 * np.linalg.norm(du) + noise
    assert abs(n @ dth) <= 1e-8 * np.linalg.norm(dth) + noise
    # radius r_b √(1 + u²), z = p θ
    assert math.hypot(pt[0], pt[1]) == pytest.approx(rb * math.sqrt(1 + u * u), rel=1e-13)
    assert pt[2] == pytest.approx(p * theta, rel=1e-14, abs=1e-18)
    # outward: along the unwound string, i.e. away from the base tangent point
    A = sigma + side * u + theta
    tangent_point = rb * np.array([math.cos(A), math.sin(A)])
    expected = rb * u * math.cos(math.radians(beta_b))
    assert (pt[:2] - tangent_point) @ n[:2] == pytest.approx(expected, rel=1e-9, abs=1e-15)


def test_helicoid_matches_seed002_equations_and_spur_limit():
    rb, p, sigma = 0.03, 0.08, 0.3
    u, th = np.linspace(0, 1, 5), np.linspace(-0.2, 0.2, 5)
    pt, _ = involute_helicoid(rb, p, u, th, sigma, side=1)
    A = sigma + u + th  # the contact-line paper: x' = r_b u sin(σ+u+θ) + r_b cos(σ+u+θ), y' = r_b sin(…) − r_b u cos(…)
    np.testing.assert_allclose(pt[:, 0], rb * u * np.sin(A) + rb * np.cos(A), rtol=1e-15, atol=1e-18)
    np.testing.assert_allclose(pt[:, 1], rb * np.sin(A) - rb * u * np.cos(A), rtol=1e-15, atol=1e-18)
    np.testing.assert_allclose(pt[:, 2], p * th, rtol=1e-15)
    spur, n = involute_helicoid_z(rb, 0.0, u, np.array([0.01] * 5), sigma, side=1)
    np.testing.assert_array_equal(n[:, 2], 0.0)
    np.testing.assert_allclose(spur[:, :2], involute_helicoid_z(rb, 0.0, u, 0.0, sigma, 1)[0][:, :2])


# --------------------------------------------------------------------------------------
# Plane of action -> body frames
# --------------------------------------------------------------------------------------

MAPPING_CASES = [
    dict(),
    dict(helix_angle_deg=0),
    dict(helix_angle_deg=30, helix_hand="left"),
    dict(teeth=[17, 71], normal_pressure_angle_deg=20, helix_angle_deg=22, profile_shift=[0.3, -0.1],
         face_width_mm=40, bore_radius_mm=None),
    dict(teeth=[23, 31], normal_pressure_angle_deg=18, helix_angle_deg=35, helix_hand="left",
         center_distance_mm=58.5, bore_radius_mm=None),
]


def contacts(geom, n_roll=5, n_z=7):
    """Every (ρ1, z, φ1, pair j) contact of one mesh cycle, from contact.py."""
    roll = np.linspace(0, geom.transverse_base_pitch, n_roll, endpoint=False)
    z = np.linspace(-0.5, 0.5, n_z) * geom.face_width
    s = contact_roll_positions(geom, roll, z)
    pairs = tooth_pair_indices(geom)
    ip, jj, iz = np.nonzero(np.isfinite(s))
    return (geom.rho_sap[0] + s[ip, jj, iz], z[iz], roll[ip] / geom.base_radius[0], pairs[jj], s[ip, jj, iz])


def on_flank_residual(geom, gear, pts, tooth):
    """Independent implicit test of the involute helicoid: untwist the slice, turn back by
    the tooth, then the polar angle from the centreline (x < 0 side) must be ψ(R)."""
    rb = geom.base_radius[gear]
    h = 1 if geom.pair.helix_hand == "right" else -1
    k = (h if gear == 0 else -h) * math.tan(geom.base_helix_angle)
    ang = -(pts[..., 2] * k / rb + 2 * math.pi * tooth / geom.pair.teeth[gear])
    x = np.cos(ang) * pts[..., 0] - np.sin(ang) * pts[..., 1]
    y = np.sin(ang) * pts[..., 0] + np.cos(ang) * pts[..., 1]
    R = np.hypot(x, y)
    psi = (geom.transverse_thickness[gear] / (2 * geom.reference_radius[gear])
           + involute(geom.transverse_pressure_angle) - involute(np.arccos(rb / R)))
    return (np.arctan2(-x, y) - psi) * R, R


@pytest.mark.parametrize("changes", MAPPING_CASES)
def test_plane_of_action_points_lie_on_both_flanks(changes):
    geom = geometry(**changes)
    rho1, z, phi1, j, s = contacts(geom)
    assert rho1.size > 10
    scale = geom.reference_radius.max()
    # pinion: on tooth j's driving flank at radius √(r_b1² + ρ1²)
    b1 = pinion_contact_point(geom, rho1, z, phi1)
    for jv in np.unique(j):
        m = j == jv
        res, R = on_flank_residual(geom, 0, b1[m], jv)
        assert np.max(np.abs(res)) < 1e-15 * scale * 50
        np.testing.assert_allclose(R, np.hypot(geom.base_radius[0], rho1[m]), rtol=1e-13)
        np.testing.assert_allclose(b1[m], flank_point(geom, 0, rho1[m], z[m], tooth=jv)[0], atol=1e-15 * scale * 10)
    # gear: on tooth −j's driven flank at roll ρ2 = ρ_EAP2 − s
    b2 = gear_contact_point(geom, rho1, z, phi1)
    rho2 = geom.rho_eap[1] - s
    for jv in np.unique(j):
        m = j == jv
        res, R = on_flank_residual(geom, 1, b2[m], -jv)
        assert np.max(np.abs(res)) < 1e-15 * scale * 50
        np.testing.assert_allclose(R, np.hypot(geom.base_radius[1], rho2[m]), rtol=1e-13)
    # the flanks' outward normals are ± the plane-of-action normal (common normal, no penetration)
    N = plane_of_action_normal(geom)
    for jv in np.unique(j):
        m = j == jv
        _, n1 = flank_point(geom, 0, rho1[m], z[m], tooth=jv)
        _, n2 = flank_point(geom, 1, rho2[m], z[m], tooth=-jv)
        rot = lambda v, a: np.stack([np.cos(a) * v[:, 0] - np.sin(a) * v[:, 1],  # noqa: E731
                                     np.sin(a) * v[:, 0] + np.cos(a) * v[:, 1], v[:, 2]], -1)
        np.testing.assert_allclose(rot(n1, body_rotation(geom, 0, phi1[m])), np.broadcast_to(N, n1.shape), atol=1e-14)
        np.testing.assert_allclose(rot(n2, body_rotation(geom, 1, phi1[m])), -np.broadcast_to(N, n2.shape), atol=1e-14)


def test_contact_line_inclination_and_plane_normal():
    # the plane-of-action normal is (d cos βb, −h sin βb): perpendicular to every contact line
    geom = geometry(helix_angle_deg=25)
    N = plane_of_action_normal(geom)
    awt, bb = geom.operating_pressure_angle, geom.base_helix_angle
    line = np.array([math.sin(awt) * math.tan(bb), math.cos(awt) * math.tan(bb), 1.0])  # ds/dz = tan βb
    assert N @ line == pytest.approx(0.0, abs=1e-15)
    assert np.linalg.norm(N) == pytest.approx(1.0, abs=1e-15)


# --------------------------------------------------------------------------------------
# The full flank and its modification
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize("changes", [dict(), dict(helix_angle_deg=30, helix_hand="left"), dict(helix_angle_deg=0)])
@pytest.mark.parametrize("gear", [0, 1])
def test_unmodified_surface_is_the_exact_helicoid(changes, gear):
    geom = geometry(**changes)
    a = tooth_surface(geom, gear, 45, 9, modified=True)  # zero modification
    b = tooth_surface(geom, gear, 45, 9, modified=False)
    for name in ("x", "y", "z", "nx", "ny", "nz"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.x.shape == (45, 9)
    inv = a.segment == 1
    pts, nrm = flank_point(geom, gear, a.rho[inv], a.z[inv])
    np.testing.assert_allclose(np.stack([a.x[inv], a.y[inv], a.z[inv]], -1), pts, rtol=0, atol=1e-15)
    np.testing.assert_allclose(np.stack([a.nx[inv], a.ny[inv], a.nz[inv]], -1), nrm, atol=1e-14)
    np.testing.assert_allclose(np.sqrt(a.nx**2 + a.ny**2 + a.nz**2), 1.0, atol=1e-14)
    r = np.hypot(a.x, a.y)
    np.testing.assert_allclose(r, a.radius, rtol=1e-14)
    assert r.min() == pytest.approx(geom.root_radius[gear], rel=1e-13)
    # fillet included: the normal is orthogonal to the helix through each point,
    # ∂P/∂z = (−w y, w x, 1) with w = ±tan βb / r_b (hand of this gear)
    h = 1 if geom.pair.helix_hand == "right" else -1
    w = (h if gear == 0 else -h) * math.tan(geom.base_helix_angle) / geom.base_radius[gear]
    assert np.max(np.abs(-w * a.y * a.nx + w * a.x * a.ny + a.nz)) < 1e-14
    # ... and to the profile direction (finite differences along the profile, fillet and involute)
    dp = np.stack([np.diff(a.x, axis=0), np.diff(a.y, axis=0), np.diff(a.z, axis=0)], -1)
    nmid = np.stack([a.nx[:-1] + a.nx[1:], a.ny[:-1] + a.ny[1:], a.nz[:-1] + a.nz[1:]], -1)
    cosang = np.sum(dp * nmid, -1) / (np.linalg.norm(dp, axis=-1) * np.linalg.norm(nmid, axis=-1))
    jump = np.argmax(a.segment[:, 0] == 1) - 1  # fillet→involute step: tangent-continuous too
    assert np.max(np.abs(cosang)) < 5e-3 and abs(cosang[jump]).max() < 5e-3


MODS = {
    "tip": ({"tip_relief_um": 12, "tip_relief_length_mm": 1.2}, "tip"),
    "root": ({"root_relief_um": 8, "root_relief_length_mm": 0.9}, "root"),
    "crown": ({"crowning_um": 6, "unmodified_lead_length_mm": 8}, "crown"),
}


def modified_geometry(gear_name, spec, **changes):
    return geometry(modification={gear_name: spec}, **changes)


@pytest.mark.parametrize("gear", [0, 1])
@pytest.mark.parametrize("kind", sorted(MODS))
def test_each_parameter_gives_its_amount_at_its_edge(kind, gear):
    spec, _ = MODS[kind]
    geom = modified_geometry(("pinion", "gear")[gear], spec)
    mod = geom.pair.modification[gear]
    other = modification_depth(geom, 1 - gear, np.linspace(geom.rho_sap[1 - gear], geom.rho_eap[1 - gear], 5), 0.0)
    np.testing.assert_array_equal(other, 0.0)  # only this gear is modified
    b = geom.face_width
    if kind == "tip":
        tip, L = geom.rho_eap[gear], mod.tip_relief_length
        assert modification_depth(geom, gear, tip, 0.3 * b) == pytest.approx(mod.tip_relief, rel=1e-12)
        assert modification_depth(geom, gear, tip - L, 0.0) == 0.0
        assert modification_depth(geom, gear, tip - 1.5 * L, 0.0) == 0.0
        mid = modification_depth(geom, gear, tip - L / 2, 0.0)
        assert mid == pytest.approx(mod.tip_relief / 4, rel=1e-9)  # parabolic
    elif kind == "root":
        sap, L = geom.rho_sap[gear], mod.root_relief_length
        assert modification_depth(geom, gear, sap, -0.2 * b) == pytest.approx(mod.root_relief, rel=1e-12)
        assert modification_depth(geom, gear, sap + L, 0.0) == 0.0
        assert modification_depth(geom, gear, geom.rho_eap[gear], 0.0) == 0.0
        assert modification_depth(geom, gear, sap + L / 2, 0.0) == pytest.approx(mod.root_relief / 4, rel=1e-9)
    else:
        rho = 0.5 * (geom.rho_sap[gear] + geom.rho_eap[gear])
        half = mod.unmodified_lead_length / 2
        for sign in (1, -1):
            assert modification_depth(geom, gear, rho, sign * b / 2) == pytest.approx(mod.crowning, rel=1e-12)
            assert modification_depth(geom, gear, rho, sign * half) == 0.0
        assert modification_depth(geom, gear, rho, 0.0) == 0.0
        z = np.linspace(0, b / 2, 21)
        np.testing.assert_array_equal(modification_depth(geom, gear, rho, z),
                                      modification_depth(geom, gear, rho, -z))  # symmetric in z
        assert np.all(np.diff(modification_depth(geom, gear, rho, z)) >= 0)  # grows towards the ends
    # on the fillet (ρ = NaN) nothing is removed
    assert modification_depth(geom, gear, np.nan, b / 2) == 0.0


@pytest.mark.parametrize("gear", [0, 1])
def test_modified_surface_moves_inward_by_the_depth(gear):
    spec = {"tip_relief_um": 10, "tip_relief_length_mm": 1.0, "root_relief_um": 5, "root_relief_length_mm": 0.8,
            "crowning_um": 4, "unmodified_lead_length_mm": 6}
    geom = modified_geometry(("pinion", "gear")[gear], spec)
    m = tooth_surface(geom, gear, 60, 11)
    u = tooth_surface(geom, gear, 60, 11, modified=False)
    disp = np.stack([m.x - u.x, m.y - u.y, m.z - u.z], -1)
    np.testing.assert_allclose(np.linalg.norm(disp, axis=-1), m.depth, rtol=1e-9, atol=1e-17)
    n = np.stack([u.nx, u.ny, u.nz], -1)
    np.testing.assert_allclose(np.sum(disp * n, -1), -m.depth, rtol=1e-9, atol=1e-17)  # along −n: removed
    np.testing.assert_allclose(m.depth, modification_depth(geom, gear, u.rho, u.z), rtol=0, atol=0)
    assert np.all(m.depth[m.segment == 0] == 0)
    assert m.depth[-1, 0] == pytest.approx(10e-6 + 4e-6, rel=1e-9)  # tip corner at the face end
    # the tip relief thins the tooth: the modified tip is inside the involute
    assert np.hypot(m.x[-1, 5], m.y[-1, 5]) < np.hypot(u.x[-1, 5], u.y[-1, 5])


AMOUNT = st.one_of(st.just(0.0), st.floats(0.1, 30))  # µm


@settings(max_examples=40, deadline=None)
@given(y1=AMOUNT, y2=AMOUNT, f3=st.floats(0.05, 0.45), f4=st.floats(0.05, 0.45),
       y5=AMOUNT, f6=st.floats(0, 0.95), rho=st.floats(-0.2, 1.2), zf=st.floats(-0.5, 0.5))
def test_depth_is_never_negative(y1, y2, f3, f4, y5, f6, rho, zf):
    geom0 = geometry()
    active = (geom0.rho_eap[0] - geom0.rho_sap[0]) * 1e3
    spec = {"root_relief_um": y1, "root_relief_length_mm": f3 * active if y1 > 0 else 0.0,
            "tip_relief_um": y2, "tip_relief_length_mm": f4 * active if y2 > 0 else 0.0,
            "crowning_um": y5, "unmodified_lead_length_mm": f6 * 20}
    geom = modified_geometry("pinion", spec)
    r = geom.rho_sap[0] + rho * (geom.rho_eap[0] - geom.rho_sap[0])
    d = modification_depth(geom, 0, r, zf * geom.face_width)
    assert np.all(d >= 0)
    assert modification_depth(geom, 0, r, -zf * geom.face_width) == d  # symmetric crowning
