"""ISO 6336-1 method B's dynamic factor as gearmesh.dynamics.iso6336 computes it: the ranges of N,
the C_v table at the ε_γ = 2 switch, B_k, and n_E1 as the torsional frequency of the two bodies."""

import math

import numpy as np
import pytest

from gearmesh.dynamics import iso6336
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pair, load_pair
from gearmesh.stiffness import iso6336_stiffness


@pytest.fixture(scope="module")
def geom():
    return pair_geometry(load_pair(example_pair("helical_z29_71_m5")))


def test_resonance_speed_is_the_torsional_frequency(geom):
    """n_E1 = 60/(2π z1)·√(c_γα b (J1 r_b2² + J2 r_b1²)/(J1 J2)) in SI."""
    c = iso6336_stiffness(geom)["c_gamma_alpha"] * 1e9 * geom.face_width  # N/m
    J1, J2 = (float(j) for j in geom.inertia)
    r1, r2 = (float(r) for r in geom.base_radius)
    omega = math.sqrt(c * (J1 * r2**2 + J2 * r1**2) / (J1 * J2))
    assert iso6336.resonance_speed(geom) == pytest.approx(60 * omega / (2 * math.pi * geom.pair.teeth[0]), rel=1e-12)
    assert iso6336.resonance_speed(geom, solid_discs=True) > 0


def test_velocity_factors_rows_of_the_table():
    """Both rows of ISO 6336-1:2006 Table 8 (they do not meet at ε_γ = 2: C_v4 0.90 against
    0.84, the standard's own step) and C_v7's three pieces, which do meet."""
    assert iso6336.velocity_factors(1.8)[:6] == (0.32, 0.34, 0.23, 0.90, 0.47, 0.47)
    assert iso6336.velocity_factors(3.0)[:6] == pytest.approx((0.32, 0.57 / 2.7, 0.096 / 1.44, 0.42 / 1.56, 0.47,
                                                               0.12 / 1.26))
    for e in (1.5, 2.5):
        assert iso6336.velocity_factors(e)[6] == pytest.approx(iso6336.velocity_factors(e + 1e-9)[6], abs=1e-6)


def test_dynamic_factor_ranges(geom):
    n_e1 = iso6336.resonance_speed(geom)
    cv = iso6336.velocity_factors(geom.eps_gamma)
    kv = iso6336.dynamic_factor(geom, n_e1 * np.array([0.5, 1.0, 1.15, 1.325, 1.5, 2.0]), 1000.0)
    assert kv[0] == pytest.approx(1 + 0.5 * cv[2])  # subcritical, perfect gears: B_k = 1
    assert kv[1] == pytest.approx(1 + cv[3]) and kv[2] == pytest.approx(1 + cv[3])  # main resonance
    assert kv[4] == pytest.approx(cv[6]) and kv[5] == pytest.approx(cv[6])  # supercritical
    assert kv[3] == pytest.approx(0.5 * (kv[2] + kv[4]))  # linear in between
    # a tip relief equal to the deflection c'C_a = F_t/b makes B_k = 0: no excitation left
    iso = iso6336_stiffness(geom)
    ft_b = 1000.0 / (geom.pair.normal_module * geom.pair.teeth[0] / (2 * math.cos(geom.pair.helix_angle))) \
        / (geom.face_width * 1e3)
    assert iso6336.dynamic_factor(geom, n_e1, 1000.0, tip_relief_um=ft_b / iso["c_prime"]) == pytest.approx(1.0)
