"""ISO 6336-1 method B's dynamic factor K_v and resonance speed n_E1: the standard's own
equations, beside which the 8-DOF model is compared (docs/validation.md, "Dynamics against
ISO 6336-1"). Nothing here feeds the model.

ISO 6336-1:2006 (the same equations in the 2019 edition), clause 6.5 "Dynamic factor, method B":

* Resonance speed of the pinion n_E1 = 30 000/(π z1)·√(c_γα/m_red) (r/min; c_γα in N/(mm·µm),
  m_red in kg/mm), the reduced mass per unit face width of the pair as two rigid discs on rigid
  supports m_red = J1* J2*/(J1* r_b2² + J2* r_b1²) (J* the polar moment of inertia per unit face
  width): the torsional natural frequency √(c_γα b/m_red b) of the mesh spring between the two
  inertias. Here J* is the pair's own (the gear bodies as :func:`gearmesh.gear.gear_body_mass_inertia`
  makes them), not the standard's solid-disc estimate from d_m.
* Resonance ratio N = n1/n_E1; lower limit of the main resonance range N_S = 0.85 for
  F_t K_A/b ≥ 100 N/mm, else 0.5 + 0.35√(F_t K_A/(100 b)).
* K_v = N K + 1 with K = C_v1 B_p + C_v2 B_f + C_v3 B_k (subcritical, N ≤ N_S);
  C_v1 B_p + C_v2 B_f + C_v4 B_k + 1 (main resonance, N_S < N ≤ 1.15);
  C_v5 B_p + C_v6 B_f + C_v7 (supercritical, N ≥ 1.5); linear in N between 1.15 and 1.5.
* B_p = c' f_pb,eff/(F_t K_A/b), B_f = c' f_f,eff/(F_t K_A/b) (pitch and profile deviations
  after running-in), B_k = |1 − c' C_a/(F_t K_A/b)| (C_a the tip relief, µm).
* C_v1…C_v7 of the total contact ratio ε_γ (ISO 6336-1:2006 Table 8): for 1 < ε_γ ≤ 2:
  0.32, 0.34, 0.23, 0.90, 0.47, 0.47; for ε_γ > 2: 0.32, 0.57/(ε_γ − 0.3), 0.096/(ε_γ − 1.56),
  (0.57 − 0.05ε_γ)/(ε_γ − 1.44), 0.47, 0.12/(ε_γ − 1.74); C_v7 = 0.75 (ε_γ ≤ 1.5),
  0.125 sin(π(ε_γ − 2)) + 0.875 (1.5 < ε_γ ≤ 2.5), 1 (ε_γ > 2.5).
"""

from __future__ import annotations

import math

import numpy as np

from ..gear import PairGeometry
from ..stiffness import iso6336_stiffness


def reduced_mass_per_width(geom: PairGeometry) -> float:
    """Reduced mass per unit face width m_red (kg/mm) of the pair's own bodies.

    m_red = J1* J2*/(J1* r_b2² + J2* r_b1²), J* = J/b (kg·mm²/mm), r_b in mm — the two gears as rigid discs on rigid
    supports (module docstring).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry: ``inertia`` (2,) kg m² of the gear bodies, ``base_radius`` (2,) m, ``face_width`` m.

    Returns
    -------
    float
        m_red (kg/mm), in the standard's units.

    References
    ----------
    .. [1] ISO 6336-1:2006, clause 6.5 (dynamic factor, method B); the same equations in ISO 6336-1:2019.
    """
    b_mm = geom.face_width * 1e3
    j1, j2 = (float(j) * 1e6 / b_mm for j in geom.inertia)
    r1, r2 = (float(r) * 1e3 for r in geom.base_radius)
    return j1 * j2 / (j1 * r2**2 + j2 * r1**2)


def reduced_mass_solid_discs(geom: PairGeometry) -> float:
    """ISO 6336-1's own estimate of m_red (kg/mm) for solid gears of mean diameter d_m = (d_a + d_f)/2.

    m_red = (π/8)(d_m1/d_b1)² d_m1²/(1/ρ1 + 1/(ρ2 u²)) (ρ in kg/mm³, u = z2/z1) — bores and webs left out.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (tip, root and base radii in m; the material's density in kg/m³, both gears alike).

    Returns
    -------
    float
        m_red (kg/mm).

    References
    ----------
    .. [1] ISO 6336-1:2006, clause 6.5 (dynamic factor, method B); the same equations in ISO 6336-1:2019.
    """
    rho = geom.pair.material.density * 1e-9
    dm1 = float(geom.tip_radius[0] + geom.root_radius[0]) * 1e3
    db1 = 2 * float(geom.base_radius[0]) * 1e3
    u = geom.pair.teeth[1] / geom.pair.teeth[0]
    return math.pi / 8 * (dm1 / db1) ** 2 * dm1**2 / (1 / rho + 1 / (rho * u**2))


def resonance_speed(geom: PairGeometry, c_gamma_alpha: float | None = None, solid_discs: bool = False) -> float:
    """Resonance speed n_E1 (r/min) of the pinion, n_E1 = 30 000/(π z1)·√(c_γα/m_red).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    c_gamma_alpha : float or None
        Mesh stiffness c_γα in N/(mm·µm); None: ISO's own (:func:`gearmesh.stiffness.iso6336_stiffness`).
    solid_discs : bool, default False
        m_red of the standard's solid-disc estimate (:func:`reduced_mass_solid_discs`) instead of the pair's own bodies
        (:func:`reduced_mass_per_width`).

    Returns
    -------
    float
        n_E1 (r/min).

    References
    ----------
    .. [1] ISO 6336-1:2006, clause 6.5 (dynamic factor, method B); the same equations in ISO 6336-1:2019.
    """
    c = iso6336_stiffness(geom)["c_gamma_alpha"] if c_gamma_alpha is None else c_gamma_alpha
    m_red = reduced_mass_solid_discs(geom) if solid_discs else reduced_mass_per_width(geom)
    return 30000.0 / (math.pi * geom.pair.teeth[0]) * math.sqrt(c / m_red)


def velocity_factors(eps_gamma: float) -> tuple[float, ...]:
    """The factors C_v1 … C_v7 of method B for a total contact ratio ε_γ > 1.

    Parameters
    ----------
    eps_gamma : float
        Total contact ratio ε_γ (-), > 1.

    Returns
    -------
    tuple of float
        (C_v1, …, C_v7) (-).

    References
    ----------
    .. [1] ISO 6336-1:2006, clause 6.5, Table 8; the same values in ISO 6336-1:2019.
    """
    e = eps_gamma
    if e <= 2:
        cv = [0.32, 0.34, 0.23, 0.90, 0.47, 0.47]
    else:
        cv = [0.32, 0.57 / (e - 0.3), 0.096 / (e - 1.56), (0.57 - 0.05 * e) / (e - 1.44), 0.47, 0.12 / (e - 1.74)]
    cv7 = 0.75 if e <= 1.5 else (0.125 * math.sin(math.pi * (e - 2)) + 0.875 if e <= 2.5 else 1.0)
    return (*cv, cv7)


def dynamic_factor(geom: PairGeometry, speed_rpm, pinion_torque: float, tip_relief_um: float = 0.0,
                   f_pb_eff_um: float = 0.0, f_f_eff_um: float = 0.0, application_factor: float = 1.0,
                   c_gamma_alpha: float | None = None) -> np.ndarray:
    """K_v of method B at pinion speeds ``speed_rpm``: perfect gears by default (B_p = B_f = 0, no relief: B_k = 1).

    Subcritical, main resonance and supercritical ranges as the module docstring states, linear in N between 1.15 and 1.5.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    speed_rpm : array_like
        Pinion speeds (r/min).
    pinion_torque : float
        Pinion torque (N·m).
    tip_relief_um : float, default 0
        Tip relief C_a (µm).
    f_pb_eff_um, f_f_eff_um : float, default 0
        Effective pitch and profile deviations after running-in, f_pb,eff and f_f,eff (µm).
    application_factor : float, default 1
        K_A (-).
    c_gamma_alpha : float or None
        c_γα (N/(mm·µm)) replacing ISO's in n_E1 only (c' of the B factors stays ISO's); None: ISO's.

    Returns
    -------
    numpy.ndarray
        K_v (-), the shape of ``speed_rpm``.

    References
    ----------
    .. [1] ISO 6336-1:2006, clause 6.5 (dynamic factor, method B) and Table 8; the same equations in ISO 6336-1:2019.
    """
    iso = iso6336_stiffness(geom)
    c1 = iso["c_prime"]
    ft = pinion_torque / (float(geom.pair.normal_module) * geom.pair.teeth[0] / (2 * math.cos(geom.pair.helix_angle)))
    w = ft * application_factor / (geom.face_width * 1e3)  # N/mm
    bp, bf, bk = c1 * f_pb_eff_um / w, c1 * f_f_eff_um / w, abs(1 - c1 * tip_relief_um / w)
    cv = velocity_factors(geom.eps_gamma)
    n_s = 0.85 if w >= 100 else 0.5 + 0.35 * math.sqrt(w / 100)
    N = np.asarray(speed_rpm, dtype=float) / resonance_speed(geom, c_gamma_alpha)
    sub = N * (cv[0] * bp + cv[1] * bf + cv[2] * bk) + 1
    main = cv[0] * bp + cv[1] * bf + cv[3] * bk + 1
    sup = cv[4] * bp + cv[5] * bf + cv[6]
    mid = main + (sup - main) * (N - 1.15) / (1.5 - 1.15)
    return np.where(N <= n_s, sub, np.where(N <= 1.15, main, np.where(N >= 1.5, sup, mid)))
