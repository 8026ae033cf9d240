"""ISO 6336 influence factors of a load capacity rating, each a function of its own inputs.

Units: the standard's own (N, mm, µm, N/mm², m/s), as named in each function; :func:`gearmesh.rating.rating`
converts a pair's SI values once and calls these.

* ISO 6336-1 (load factors): the ISO 1328-1 tolerances of an accuracy grade, K_v by method C,
  K_Hβ by method C and K_Fβ from it, K_Hα = K_Fα by method B.
* ISO 6336-2 (pitting): Z_H, Z_E, Z_ε, Z_B/Z_D, the lubrication, velocity and roughness factors
  Z_L, Z_v, Z_R, and the life factor Z_NT.
* ISO 6336-3 (tooth bending): Y_β, Y_B, Y_DT, Y_δrelT, Y_RrelT, Y_X, the life factor Y_NT and the
  mean stress factor Y_M.

Each cites its clause; :mod:`gearmesh.rating` takes them (or the LTCA's load factors, or given ones)
into the rating.
"""

from __future__ import annotations

import math

from .choices import DEFAULT_LIFE_FACTOR_CONDITIONS, LIFE_FACTOR_CONDITIONS
from .errors import GearmeshInputError
from .gear import PairGeometry

__all__ = [
    "METHOD_C_SPEED_LIMIT", "iso1328_tolerances", "dynamic_factor_c", "face_load_factor_c", "face_factor_root",
    "transverse_load_factor_b", "zone_factor", "elasticity_factor", "contact_ratio_factor", "single_pair_factors",
    "life_factor_contact", "life_factor_root", "LONG_LIFE_CYCLES", "IDLER_MEAN_STRESS_FACTOR", "mean_stress_factor",
    "lubrication_velocity_roughness", "helix_factor_root", "rim_factor", "deep_tooth_factor",
    "notch_sensitivity_factor", "root_roughness_factor", "size_factor_root",
]

#: ISO 6336-1:1996 method C, K1 by ISO 1328-1 grade 3..12 (spur, helical); K2 0.0193 spur, 0.0087 helical.
_K1 = {3: (2.1, 1.9), 4: (3.9, 3.5), 5: (7.5, 6.7), 6: (14.9, 13.3), 7: (26.8, 23.9), 8: (39.1, 34.8),
       9: (52.8, 47.0), 10: (76.6, 68.2), 11: (102.6, 91.4), 12: (146.3, 130.3)}
_K2 = (0.0193, 0.0087)
#: Range of method C's K_v: z1·v/100·√(u²/(1 + u²)) below 10 m/s (ISO 6336-1:1996 6.3.4; DIN 3990-1 3.4.3).
METHOD_C_SPEED_LIMIT = 10.0


# --------------------------------------------------------------------------------------
# ISO 6336-1 factors
# --------------------------------------------------------------------------------------


def iso1328_tolerances(grade: int, d_mm: float, b_mm: float, m_n_mm: float) -> dict[str, float]:
    """ISO 1328-1:1995 tolerances (µm) of grade ``grade`` [1]_: single pitch f_pt = 0.3(m_n + 0.4√d) + 4,
    helix slope f_Hβ = 0.07√d + 0.45√b + 3 and total helix F_β = 0.1√d + 0.63√b + 4.2 at grade 5, each
    times 2^((Q − 5)/2) (clause 5.3; the standard's rounding of the tabulated values is not applied).

    Parameters
    ----------
    grade : int
        Accuracy grade Q.
    d_mm : float
        Reference diameter d, mm.
    b_mm : float
        Face width b, mm.
    m_n_mm : float
        Normal module m_n, mm.

    Returns
    -------
    dict of str to float
        ``f_pt``, ``f_Hbeta``, ``F_beta``, µm.

    References
    ----------
    .. [1] ISO 1328-1:1995, Cylindrical gears — ISO system of accuracy — Part 1: Definitions and allowable
       values of deviations relevant to corresponding flanks of gear teeth, clause 5.3.
    """
    step = 2.0 ** (0.5 * (grade - 5))
    return {"f_pt": (0.3 * (m_n_mm + 0.4 * math.sqrt(d_mm)) + 4.0) * step,
            "f_Hbeta": (0.07 * math.sqrt(d_mm) + 0.45 * math.sqrt(b_mm) + 3.0) * step,
            "F_beta": (0.1 * math.sqrt(d_mm) + 0.63 * math.sqrt(b_mm) + 4.2) * step}


def dynamic_factor_c(grade: int, eps_beta: float, v: float, z1: int, u: float, load_per_width: float,
                     k1: tuple[float, float] | None = None) -> float:
    """K_v by ISO 6336-1:1996 method C (6.3.4 [1]_; DIN 3990-1 eq. 3.05 [2]_):
    K_v = 1 + (K1/(K_A F_t/b) + K2)·(z1 v/100)·√(u²/(1 + u²)), K_A F_t/b ≥ 100 N/mm; K1 (spur,
    helical) of the grade. ε_β ≥ 1 takes the helical column, ε_β < 1 interpolates
    K_vα − ε_β(K_vα − K_vβ). Grades finer than 3 take grade 3's K1 (conservative).

    Parameters
    ----------
    grade : int
        ISO 1328-1 accuracy grade.
    eps_beta : float
        Overlap ratio ε_β.
    v : float
        Pitch-line speed, m/s.
    z1 : int
        Pinion teeth.
    u : float
        Gear ratio z2/z1.
    load_per_width : float
        K_A F_t/b, N/mm.
    k1 : tuple of 2 float, optional
        (spur, helical) K1 overriding the grade's.

    Returns
    -------
    float
        Dynamic factor K_v.

    References
    ----------
    .. [1] ISO 6336-1:1996, Calculation of load capacity of spur and helical gears — Part 1: Basic
       principles, introduction and general influence factors, clause 6.3.4 (method C).
    .. [2] DIN 3990-1:1987, Tragfähigkeitsberechnung von Stirnrädern — Einführung und allgemeine Einflussfaktoren, eq. 3.05.
    """
    if grade < 3:
        grade = 3  # the table starts at grade 3; finer grades take its value (conservative)
    k1 = _K1[grade] if k1 is None else k1
    w = max(load_per_width, 100.0)
    speed = z1 * v / 100.0 * math.sqrt(u**2 / (1 + u**2))
    kv = [1 + (k1[i] / w + _K2[i]) * speed for i in (0, 1)]
    return kv[1] if eps_beta >= 1 else kv[0] - eps_beta * (kv[0] - kv[1])


def face_load_factor_c(fm_per_width: float, c_gamma_beta: float, f_ma: float, b_over_d1: float,
                       crowned: bool = False, running_in: bool = True) -> tuple[float, dict[str, float]]:
    """K_Hβ by ISO 6336-1 method C (7.6 [1]_): f_sh = (F_m/b)·A·(b/d1)² (pinion bending and torsion, the
    pinion between bearings, no stiffening factor; A = 0.023 µm·mm/N, 0.012 with crowning),
    F_βx = 1.33 f_sh + f_ma, y_β = 0.15 F_βx ≤ 6 µm (case-hardened; 0 with ``running_in`` False),
    F_βy = F_βx − y_β, K_Hβ = 1 + c_γβ F_βy/(2 F_m/b) ≤ 2, else √(2 c_γβ F_βy/(F_m/b)).

    Parameters
    ----------
    fm_per_width : float
        F_m/b, N/mm.
    c_gamma_beta : float
        Mesh stiffness c_γβ, N/(mm·µm).
    f_ma : float
        Mesh misalignment f_ma, µm.
    b_over_d1 : float
        Face width over pinion reference diameter.
    crowned : bool, default False
        Crowned flanks (A = 0.012).
    running_in : bool, default True
        Take the running-in allowance y_β.

    Returns
    -------
    k_hbeta : float
        Face load factor K_Hβ.
    terms : dict of str to float
        ``f_sh_um``, ``F_betax_um``, ``y_beta_um``, ``F_betay_um``, µm.

    References
    ----------
    .. [1] ISO 6336-1, Calculation of load capacity of spur and helical gears — Part 1: Basic principles,
       introduction and general influence factors, clause 7.6 (method C).
    """
    a = 0.012 if crowned else 0.023
    f_sh = fm_per_width * a * b_over_d1**2
    f_bx = 1.33 * f_sh + f_ma
    y_b = min(0.15 * f_bx, 6.0) if running_in else 0.0
    f_by = f_bx - y_b
    k = 1 + c_gamma_beta * f_by / (2 * fm_per_width)
    if k > 2:
        k = math.sqrt(2 * c_gamma_beta * f_by / fm_per_width)
    return k, {"f_sh_um": f_sh, "F_betax_um": f_bx, "y_beta_um": y_b, "F_betay_um": f_by}


def face_factor_root(k_hbeta: float, b_over_h: float) -> float:
    """K_Fβ = K_Hβ^N_F, N_F = (b/h)²/(1 + b/h + (b/h)²), b/h not below 3 (ISO 6336-1, 8.3 [1]_).

    Parameters
    ----------
    k_hbeta : float
        Face load factor for contact stress K_Hβ.
    b_over_h : float
        Face width over tooth depth b/h.

    Returns
    -------
    float
        Face load factor for root stress K_Fβ.

    References
    ----------
    .. [1] ISO 6336-1, Calculation of load capacity of spur and helical gears — Part 1: Basic principles,
       introduction and general influence factors.
    """
    r = max(b_over_h, 3.0)
    return k_hbeta ** (r**2 / (1 + r + r**2))


def transverse_load_factor_b(eps_alpha: float, eps_gamma: float, z_eps: float, c_gamma_alpha: float,
                             f_pb: float, fth_per_width: float) -> tuple[float, float, float]:
    """K_Hα, K_Fα by ISO 6336-1 method B (8.3.2 [1]_): y_α = 0.075 f_pb ≤ 3 µm (case-hardened),
    ε_γ ≤ 2: K = ε_γ/2·(0.9 + 0.4 c_γα (f_pb − y_α)/(F_tH/b)); ε_γ > 2: K = 0.9 + 0.4 √(2(ε_γ − 1)/ε_γ)·
    c_γα (f_pb − y_α)/(F_tH/b); bounds 1 ≤ K_Hα ≤ ε_γ/(ε_α Z_ε²), 1 ≤ K_Fα ≤ ε_γ/(0.25 ε_α + 0.75).

    Parameters
    ----------
    eps_alpha, eps_gamma : float
        Transverse and total contact ratios ε_α, ε_γ.
    z_eps : float
        Contact ratio factor Z_ε (:func:`contact_ratio_factor`).
    c_gamma_alpha : float
        Mesh stiffness c_γα, N/(mm·µm).
    f_pb : float
        Base pitch deviation f_pb, µm.
    fth_per_width : float
        F_tH/b = F_t K_A K_v K_Hβ/b, N/mm.

    Returns
    -------
    k_halpha, k_falpha : float
        Transverse load factors K_Hα, K_Fα.
    y_alpha : float
        Running-in allowance y_α, µm.

    References
    ----------
    .. [1] ISO 6336-1, Calculation of load capacity of spur and helical gears — Part 1: Basic principles,
       introduction and general influence factors, clause 8.3.2 (method B).
    """
    y_a = min(0.075 * f_pb, 3.0)
    term = c_gamma_alpha * (f_pb - y_a) / max(fth_per_width, 1e-9)
    k = eps_gamma / 2 * (0.9 + 0.4 * term) if eps_gamma <= 2 else 0.9 + 0.4 * math.sqrt(2 * (eps_gamma - 1) / eps_gamma) * term
    k_h = min(max(k, 1.0), eps_gamma / (eps_alpha * z_eps**2))
    k_f = min(max(k, 1.0), eps_gamma / (0.25 * eps_alpha + 0.75))
    return k_h, k_f, y_a


# --------------------------------------------------------------------------------------
# ISO 6336-2 factors
# --------------------------------------------------------------------------------------


def zone_factor(geom: PairGeometry) -> float:
    """Z_H = √(2 cos βb cos α_wt/(cos² α_t sin α_wt)) (ISO 6336-2, 6.1 [1]_).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    float
        Zone factor Z_H.

    References
    ----------
    .. [1] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting).
    """
    bb, awt, at = geom.base_helix_angle, geom.operating_pressure_angle, geom.transverse_pressure_angle
    return math.sqrt(2 * math.cos(bb) * math.cos(awt) / (math.cos(at) ** 2 * math.sin(awt)))


def elasticity_factor(youngs_modulus: float, poisson_ratio: float) -> float:
    """Z_E (√(N/mm²)) of two gears of one material: √(E/(2π(1 − ν²))) (ISO 6336-2, 7 [1]_), E in Pa.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E, Pa.
    poisson_ratio : float
        Poisson's ratio ν.

    Returns
    -------
    float
        Elasticity factor Z_E, √(N/mm²).

    References
    ----------
    .. [1] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting).
    """
    return math.sqrt(youngs_modulus * 1e-6 / (2 * math.pi * (1 - poisson_ratio**2)))


def contact_ratio_factor(eps_alpha: float, eps_beta: float) -> float:
    """Z_ε (ISO 6336-2, 8 [1]_): ε_β < 1: √((4 − ε_α)/3·(1 − ε_β) + ε_β/ε_α); ε_β ≥ 1: √(1/ε_α).

    Parameters
    ----------
    eps_alpha : float
        Transverse contact ratio ε_α.
    eps_beta : float
        Overlap ratio ε_β.

    Returns
    -------
    float
        Contact ratio factor Z_ε.

    References
    ----------
    .. [1] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting).
    """
    if eps_beta < 1:
        return math.sqrt((4 - eps_alpha) / 3 * (1 - eps_beta) + eps_beta / eps_alpha)
    return math.sqrt(1 / eps_alpha)


def single_pair_factors(geom: PairGeometry) -> tuple[float, float, float, float]:
    """(Z_B, Z_D, M1, M2), ISO 6336-2 clause 6.2 [1]_: M1 = tan α_wt/√((√(d_a1²/d_b1² − 1) − 2π/z1)·
    (√(d_a2²/d_b2² − 1) − (ε_α − 1)2π/z2)), M2 with the gears exchanged; spur: Z_B = max(1, M1),
    Z_D = max(1, M2); ε_β ≥ 1: 1; ε_β < 1: Z = M − ε_β(M − 1), not below 1.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    tuple of float
        Single pair tooth contact factors Z_B, Z_D and the ratios M1, M2.

    References
    ----------
    .. [1] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting), clause 6.2.
    """
    z1, z2 = geom.pair.teeth
    awt, ea, eb = geom.operating_pressure_angle, geom.eps_alpha, geom.eps_beta
    t1, t2 = (math.sqrt((float(geom.tip_radius[i]) / float(geom.base_radius[i])) ** 2 - 1) for i in (0, 1))
    m1 = math.tan(awt) / math.sqrt((t1 - 2 * math.pi / z1) * (t2 - (ea - 1) * 2 * math.pi / z2))
    m2 = math.tan(awt) / math.sqrt((t2 - 2 * math.pi / z2) * (t1 - (ea - 1) * 2 * math.pi / z1))
    if eb >= 1:
        return 1.0, 1.0, m1, m2
    return max(1.0, m1 - eb * (m1 - 1)), max(1.0, m2 - eb * (m2 - 1)), m1, m2


def _log_interp(n: float, points: tuple[tuple[float, float], ...]) -> float:
    """Log-log interpolation in a table of (N_L, factor), constant outside."""
    if n <= points[0][0]:
        return points[0][1]
    for (n0, f0), (n1, f1) in zip(points, points[1:]):
        if n <= n1:
            return f0 * (f1 / f0) ** (math.log(n / n0) / math.log(n1 / n0))
    return points[-1][1]


#: N_L the rating takes without ``life_hours``: the long-life end of the standard's curves (10¹⁰).
LONG_LIFE_CYCLES = 1e10


def life_factor_contact(cycles: float, conditions: str = DEFAULT_LIFE_FACTOR_CONDITIONS) -> float:
    """Z_NT of case-hardened steel (Eh, IF), no pitting permitted: ISO 6336-2:2019 Table 2, line 2
    (method B [1]_): 1.6 up to N_L = 10⁵, 1.0 at 5·10⁷, then ``conditions`` 'normal' 0.85 at 10¹⁰
    (Z_NT = (5·10⁷/N_L)^0.0307 between, the standard's Figure 6), 'optimum' 1.0; log-log between
    the points and constant beyond 10¹⁰, where the standard's table ends.

    Parameters
    ----------
    cycles : float
        Number of load cycles N_L.
    conditions : {'normal', 'optimum'}, default 'normal'
        Long-life conditions (:data:`gearmesh.choices.LIFE_FACTOR_CONDITIONS`).

    Returns
    -------
    float
        Life factor Z_NT.

    Raises
    ------
    GearmeshInputError
        Unknown ``life_factor_conditions``.

    References
    ----------
    .. [1] ISO 6336-2:2019, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting), Table 2.
    """
    return _log_interp(cycles, ((1e5, 1.6), (5e7, 1.0), (1e10, _long_life_value(conditions))))


def life_factor_root(cycles: float, conditions: str = DEFAULT_LIFE_FACTOR_CONDITIONS) -> float:
    """Y_NT of case-hardened steel (Eh, IF root): ISO 6336-3:2019 Table 3 (method B [1]_): 2.5 up to
    N_L = 10³, 1.0 at 3·10⁶, then ``conditions`` 'normal' 0.85 at 10¹⁰ (Y_NT = (3·10⁶/N_L)^0.02
    between, the standard's Figure 5), 'optimum' 1.0; log-log between the points, constant beyond 10¹⁰.

    Parameters
    ----------
    cycles : float
        Number of load cycles N_L.
    conditions : {'normal', 'optimum'}, default 'normal'
        Long-life conditions (:data:`gearmesh.choices.LIFE_FACTOR_CONDITIONS`).

    Returns
    -------
    float
        Life factor Y_NT.

    Raises
    ------
    GearmeshInputError
        Unknown ``life_factor_conditions``.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength, Table 3.
    """
    return _log_interp(cycles, ((1e3, 2.5), (3e6, 1.0), (1e10, _long_life_value(conditions))))


def _long_life_value(conditions: str) -> float:
    """The life factors' value at 10¹⁰ cycles for the long-life ``conditions`` (:data:`gearmesh.choices.LIFE_FACTOR_CONDITIONS`)."""
    if conditions not in LIFE_FACTOR_CONDITIONS:
        raise GearmeshInputError("life_factor_conditions", conditions, f"must be one of {list(LIFE_FACTOR_CONDITIONS)}")
    return 0.85 if conditions == "normal" else 1.0


#: Y_M of an idler gear (reversed bending: one flank's mesh loads a fillet in tension, the other's
#: in compression): ISO 6336-3:2006 clause 5 (σ_FE × 0.7 for idler gears) and ISO 6336-3:2019's
#: method C value for idler gears of case-hardened steel; 1 for one-way bending.
IDLER_MEAN_STRESS_FACTOR = 0.7


def mean_stress_factor(idler: bool) -> float:
    """Y_M, the mean stress influence factor of ISO 6336-3:2019 [1]_ (σ_FG = σ_Flim Y_ST Y_NT Y_δrelT
    Y_RrelT Y_X Y_M): :data:`IDLER_MEAN_STRESS_FACTOR` for an idler (alternating bending), 1 for a
    gear loaded on one flank (the pulsating load, R = 0, of the σ_Flim tests).

    Parameters
    ----------
    idler : bool
        True for an idler gear.

    Returns
    -------
    float
        Mean stress factor Y_M.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    return IDLER_MEAN_STRESS_FACTOR if idler else 1.0


def lubrication_velocity_roughness(sigma_hlim: float, nu40: float, v: float, rz_mean: float,
                                   rho_red_mm: float) -> dict[str, float]:
    """Z_L, Z_v, Z_R of ISO 6336-2 method B (clause 11 [1]_): C_ZL = 0.83 + 0.08(σ_Hlim − 850)/350 on
    850–1200 N/mm² (0.83 below, 0.91 above), Z_L = C_ZL + 4(1 − C_ZL)/(1.2 + 134/ν40)²;
    C_Zv = C_ZL + 0.02, Z_v = C_Zv + 2(1 − C_Zv)/√(0.8 + 32/v); R_z10 = R_z (10/ρ_red)^(1/3),
    C_ZR = 0.32 − 0.0002 σ_Hlim on 850–1200 (0.15 below, 0.08 above), Z_R = (3/R_z10)^C_ZR.

    Parameters
    ----------
    sigma_hlim : float
        Contact fatigue limit σ_Hlim, N/mm².
    nu40 : float
        Kinematic viscosity at 40 °C, mm²/s.
    v : float
        Pitch-line speed, m/s.
    rz_mean : float
        Mean flank roughness (R_z1 + R_z2)/2, µm.
    rho_red_mm : float
        Relative radius of curvature at the pitch point, mm.

    Returns
    -------
    dict of str to float
        ``Z_L``, ``Z_v``, ``Z_R`` and ``R_z10_um`` (µm).

    References
    ----------
    .. [1] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting), clause 11.
    """
    s = min(max(sigma_hlim, 850.0), 1200.0)
    c_zl = 0.83 + 0.08 * (s - 850.0) / 350.0
    z_l = c_zl + 4 * (1 - c_zl) / (1.2 + 134.0 / nu40) ** 2
    c_zv = c_zl + 0.02
    z_v = c_zv + 2 * (1 - c_zv) / math.sqrt(0.8 + 32.0 / v)
    rz10 = rz_mean * (10.0 / rho_red_mm) ** (1 / 3)
    c_zr = 0.15 if sigma_hlim < 850 else 0.08 if sigma_hlim > 1200 else 0.32 - 0.0002 * sigma_hlim
    return {"Z_L": z_l, "Z_v": z_v, "Z_R": (3.0 / rz10) ** c_zr, "R_z10_um": rz10}


# --------------------------------------------------------------------------------------
# ISO 6336-3 factors
# --------------------------------------------------------------------------------------


def helix_factor_root(eps_beta: float, helix_angle: float) -> float:
    """Y_β = 1 − ε_β β/120° with ε_β ≤ 1 and β ≤ 30° taken (ISO 6336-3:2006, 9.3 [1]_).

    Parameters
    ----------
    eps_beta : float
        Overlap ratio ε_β.
    helix_angle : float
        Reference helix angle β, rad.

    Returns
    -------
    float
        Helix factor Y_β.

    References
    ----------
    .. [1] ISO 6336-3:2006, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength, clause 9.3.
    """
    return 1 - min(eps_beta, 1.0) * min(math.degrees(helix_angle), 30.0) / 120.0


def rim_factor(rim_thickness: float, tooth_depth: float) -> float:
    """Y_B (ISO 6336-3, 9.4 [1]_, external gears): s_R/h_t ≥ 1.2: 1; 0.5 < s_R/h_t < 1.2:
    1.6 ln(2.242 h_t/s_R). Below 0.5 the standard does not apply (refused).

    Parameters
    ----------
    rim_thickness : float
        Rim thickness s_R below the root, m (any unit, as ``tooth_depth``).
    tooth_depth : float
        Tooth depth h_t, same unit.

    Returns
    -------
    float
        Rim thickness factor Y_B.

    Raises
    ------
    GearmeshInputError
        s_R/h_t ≤ 0.5 (``bore_radius_mm``).

    References
    ----------
    .. [1] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    r = rim_thickness / tooth_depth
    if r >= 1.2:
        return 1.0
    if r <= 0.5:
        raise GearmeshInputError("bore_radius_mm", None, f"leaves a rim s_R/h_t = {r:.2f} ≤ 0.5, outside ISO 6336-3")
    return 1.6 * math.log(2.242 / r)


def deep_tooth_factor(eps_alpha_n: float, grade: int) -> float:
    """Y_DT (ISO 6336-3, 9.5 [1]_): 1 for ε_αn ≤ 2.05 or grade > 4; −0.666 ε_αn + 2.366 on (2.05, 2.5];
    0.7 above.

    Parameters
    ----------
    eps_alpha_n : float
        Virtual contact ratio ε_αn.
    grade : int
        ISO 1328-1 accuracy grade.

    Returns
    -------
    float
        Deep tooth factor Y_DT.

    References
    ----------
    .. [1] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    if eps_alpha_n <= 2.05 or grade > 4:
        return 1.0
    return -0.666 * eps_alpha_n + 2.366 if eps_alpha_n <= 2.5 else 0.7


def notch_sensitivity_factor(q_s: float) -> float:
    """Y_δrelT of case-hardened steel (ISO 6336-3, 12.3, method B [1]_): (1 + √(ρ'χ*))/(1 + √(ρ'χ*_T)),
    slip-layer thickness ρ' = 0.0030 mm, relative stress gradient χ* = (1 + 2q_s)/5 mm⁻¹,
    χ*_T = 1.2 mm⁻¹ of the standard test gear (q_sT = 2.5).

    Parameters
    ----------
    q_s : float
        Notch parameter q_s = s_Fn/(2ρ_F).

    Returns
    -------
    float
        Relative notch sensitivity factor Y_δrelT.

    References
    ----------
    .. [1] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    rho_p = 0.0030
    return (1 + math.sqrt(rho_p * (1 + 2 * q_s) / 5)) / (1 + math.sqrt(rho_p * 1.2))


def root_roughness_factor(rz: float) -> float:
    """Y_RrelT of case-hardened steel (ISO 6336-3, 13.3, method B [1]_): 1.674 − 0.529 (R_z + 1)^0.1
    for 1 ≤ R_z ≤ 40 µm; 1.120 below 1 µm.

    Parameters
    ----------
    rz : float
        Root roughness R_z, µm.

    Returns
    -------
    float
        Relative surface factor Y_RrelT.

    References
    ----------
    .. [1] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    return 1.120 if rz < 1 else 1.674 - 0.529 * (rz + 1) ** 0.1


def size_factor_root(m_n_mm: float) -> float:
    """Y_X of case-hardened steel (ISO 6336-3, 14 [1]_): 1 for m_n ≤ 5 mm, 1.05 − 0.01 m_n up to 25,
    0.8 above.

    Parameters
    ----------
    m_n_mm : float
        Normal module m_n, mm.

    Returns
    -------
    float
        Size factor Y_X.

    References
    ----------
    .. [1] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength.
    """
    return 1.0 if m_n_mm <= 5 else 1.05 - 0.01 * m_n_mm if m_n_mm < 25 else 0.8
