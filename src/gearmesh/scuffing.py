"""Scuffing load capacity: Blok's flash temperature along the path of contact from the LTCA's own
load, and the rated values of ISO/TS 6336-20:2017 (flash temperature method) and ISO/TS 6336-21:2017
(integral temperature method).

Units: SI inside the physics (N/m, m/s, m, K), the standards' engineering units inside the
empirical formulas (N/mm, mm, µm, mPa·s, °C), converted where each is called.

Flash temperature (Blok 1937; Jaeger 1942). Frictional heat q(x) = μ p(x) |v1 − v2| is released in
the Hertzian band (half-width b_H, semi-elliptic pressure p(x) = p_0 √(1 − x²/b_H²),
p_0 = 2w/(π b_H)). At the Péclet numbers of gear teeth (v b_H/(2κ) ≫ 1) each surface point is
heated as a half-space by a flux that lasts (b_H − x)/v_i, so its surface temperature rise is
θ_i(x) = (1/(B_i √(π v_i))) ∫_{−b_H}^{x} q_i(ξ)/√(x − ξ) dξ, with B_i = √(λ_i ρ_i c_i) the thermal
contact coefficient. Blok's postulate (equal maximum temperatures of both surfaces) splits the
heat as q_i ∝ B_i √v_i, and the maximum of the integral over the band gives

    θ_fl = C_B μ w |v1 − v2| / ((B_1 √v1 + B_2 √v2) √b_H),   C_B = 2 J_max/π^(3/2) = 0.78598,

J_max = max_x ∫_{−1}^{x} √(1 − s²)/√(x − s) ds = 2.18831 (at x = 0.652 b_H). Here b_H is the
**half**-width; Blok's often quoted 1.11 is the same constant with the full width 2 b_H
(0.78598·√2 = 1.1115). ``tests/test_scuffing.py`` computes C_B afresh and checks it against the full
2-D moving-source solution of Jaeger (the K_0 kernel) at large Péclet number. For involute
helicoids the rolling speeds v_i = ω_i ρ_i are normal to the contact line, the load w per unit
contact-line length is the LTCA's line load, and the relative radius normal to the line is
ρ1ρ2/((ρ1 + ρ2) cos β_b), as in :mod:`gearmesh.stress`. Written with ISO's symbols this is
θ_fl = μ X_M X_G X_αβ (X_Γ w_Bt)^(3/4) v^(1/2)/a^(1/4): C_B (π/8)^(1/4) = 0.62220 is the product of
the constants 0.51 (X_G) and 1.22 (X_αβ) of ISO/TR 13989-1, and X_M = E_r^(1/4)/B_M is 50.0
K·N^(−3/4)·s^(1/2)·m^(−1/2)·mm for steel (both as recalled from the standard, whose text could not
be consulted here; the Blok/Jaeger derivation above is independent of it).

Rated values (ISO/TR 13989-1/-2:2000, whose method ISO/TS 6336-20/-21:2017 took over; the empirical
constants below are as recalled from those texts and DIN 3990-4, not checked against them here):

* mean coefficient of friction μ_mC = 0.045 (w_Bt K_Bγ/(v_ΣC ρ_redC))^0.2 η_oil^(−0.05) X_R X_L,
  X_R = 2.2 (R_a/ρ_redC)^0.25 (w_Bt N/mm, v_ΣC m/s, ρ_redC mm, η_oil mPa·s at the oil temperature,
  R_a = the flank Ra of both gears, µm); one μ for both methods;
* flash temperature method: θ_M = θ_oil + 0.47 X_S X_mp θ_flm (θ_flm the mean flash temperature
  over the path), θ_B = θ_M + θ_fl, θ_S = 80 + (0.85 + 1.4 X_W) X_L S_FZG² °C (FZG A/8.3/90),
  S_B = (θ_S − θ_oil)/(θ_B,max − θ_oil);
* integral temperature method: θ_flaint the mean flash temperature over the path of contact (here
  the LTCA's own, where the standard approximates it by θ_flaE X_ε), θ_M = θ_oil + 0.7 X_S X_mp
  θ_flaint, θ_int = θ_M + C_2 θ_flaint (C_2 = 1.5), θ_intS = θ_MT + X_WrelT C_2 θ_flaintT with the
  FZG test gears' θ_MT = 80 + 0.23 T_1T X_L and θ_flaintT = 0.2 T_1T X_L (T_1T the pinion torque of
  the load stage, ISO 14635-1, N·m), S_intS = θ_intS/θ_int.

Factors taken and named in every result (:data:`SCUFFING_ASSUMPTIONS`): steel on steel
(B_M = 13 795 N/(m·s^½·K), ISO/TR 13989-1), mineral oil X_L = 1, dip lubrication X_S = 1, one mesh
per gear X_mp = 1, case-hardened steel of average retained austenite X_W = 1 (X_WT = 1 of the test
gears), oil density 895 kg/m³ at 15 °C (a mineral gear oil), η = ν ρ. Kinematic viscosity at the
oil temperature by the Ubbelohde–Walther relation of ASTM D341 through ν40 and ν100.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry

__all__ = ["BLOK_COEFFICIENT", "STEEL_THERMAL_CONTACT_COEFFICIENT", "FZG_PINION_TORQUE_NM", "SCUFFING_ASSUMPTIONS",
           "walther_viscosity", "oil_dynamic_viscosity", "helical_load_factor", "friction_coefficient",
           "flash_temperature", "flash_scuffing_temperature", "integral_scuffing_temperature", "PathKinematics",
           "path_kinematics", "ScuffingRating", "scuffing_rating"]

#: C_B of θ_fl = C_B μ w |v1 − v2|/((B_1√v1 + B_2√v2)√b_H), b_H the Hertzian half-width: 2 J_max/π^(3/2)
#: with J_max = 2.188307 the largest surface-temperature integral of a semi-elliptic band source
#: (module docstring; recomputed in tests/test_scuffing.py).
BLOK_COEFFICIENT = 0.785983
#: B_M = √(λ ρ c) of steel, N/(m·s^½·K) (ISO/TR 13989-1: λ 50 N/(s·K), ρ c of steel).
STEEL_THERMAL_CONTACT_COEFFICIENT = 13795.0
#: Pinion torque T_1T (N·m) of each load stage of the FZG test A/8.3/90 (ISO 14635-1:2000, Table 2).
FZG_PINION_TORQUE_NM = {1: 3.3, 2: 13.7, 3: 35.3, 4: 60.8, 5: 94.1, 6: 135.3, 7: 183.4, 8: 239.3, 9: 302.0,
                        10: 372.6, 11: 450.1, 12: 534.5}
#: Factors the rating takes without a pair-file key for them (module docstring), named in its notes.
SCUFFING_ASSUMPTIONS = {"X_L": 1.0, "X_S": 1.0, "X_mp": 1.0, "X_W": 1.0, "X_WT": 1.0, "C_2": 1.5,
                        "B_M": STEEL_THERMAL_CONTACT_COEFFICIENT, "oil_density_15C_kg_m3": 895.0}
#: Relative thermal expansion of a mineral oil's density per kelvin (ρ_θ = ρ_15 (1 − 7·10⁻⁴ (θ − 15))).
_OIL_EXPANSION = 7e-4
#: Bulk-temperature weights of the flash (0.47) and integral (0.7) temperature methods.
_BULK_FLASH, _BULK_INTEGRAL = 0.47, 0.7


def walther_viscosity(nu40: float, nu100: float, temperature_C):
    """Kinematic viscosity (mm²/s) at ``temperature_C`` through ν40 and ν100 (mm²/s) by the
    Ubbelohde–Walther relation of ASTM D341 [1]_: log₁₀ log₁₀(ν + 0.7) = A − B log₁₀ T, T in K (valid for
    ν ≥ 2 mm²/s).

    Parameters
    ----------
    nu40 : float
        Kinematic viscosity at 40 °C, mm²/s.
    nu100 : float
        Kinematic viscosity at 100 °C, mm²/s; positive and below ``nu40``.
    temperature_C : float or array_like
        Oil temperature, °C.

    Returns
    -------
    float or numpy.ndarray
        Kinematic viscosity ν, mm²/s, shaped like ``temperature_C``.

    Raises
    ------
    GearmeshInputError
        ``viscosity_100C_mm2_s`` not positive or not below ``nu40``.

    References
    ----------
    .. [1] ASTM D341, Standard practice for viscosity–temperature equations and charts for liquid
       petroleum or hydrocarbon products.
    """
    if not 0 < nu100 < nu40:
        raise GearmeshInputError("viscosity_100C_mm2_s", nu100, f"must be positive and below viscosity_40C_mm2_s "
                                                                f"({nu40:g})")
    w = [math.log10(math.log10(nu + 0.7)) for nu in (nu40, nu100)]
    t = [math.log10(273.15 + c) for c in (40.0, 100.0)]
    b = (w[0] - w[1]) / (t[1] - t[0])
    a = w[0] + b * t[0]
    return 10.0 ** (10.0 ** (a - b * np.log10(273.15 + np.asarray(temperature_C, dtype=float)))) - 0.7


def oil_dynamic_viscosity(nu40: float, nu100: float, temperature_C: float) -> float:
    """Dynamic viscosity η (mPa·s) = ν (mm²/s) × ρ (g/cm³) at ``temperature_C``, ρ of a mineral oil
    (:data:`SCUFFING_ASSUMPTIONS`, 7·10⁻⁴/K expansion).

    Parameters
    ----------
    nu40 : float
        Kinematic viscosity at 40 °C, mm²/s.
    nu100 : float
        Kinematic viscosity at 100 °C, mm²/s.
    temperature_C : float
        Oil temperature, °C.

    Returns
    -------
    float
        Dynamic viscosity η, mPa·s.
    """
    rho = SCUFFING_ASSUMPTIONS["oil_density_15C_kg_m3"] * 1e-3 * (1 - _OIL_EXPANSION * (temperature_C - 15.0))
    return float(walther_viscosity(nu40, nu100, temperature_C)) * rho


def helical_load_factor(eps_gamma: float) -> float:
    """K_Bγ of ISO/TR 13989 [1]_: 1 for ε_γ ≤ 2, 1 + 0.2 √((ε_γ − 2)(5 − ε_γ)) up to 3.5, 1.3 above.

    Parameters
    ----------
    eps_gamma : float
        Total contact ratio ε_γ = ε_α + ε_β (dimensionless).

    Returns
    -------
    float
        Helical load factor K_Bγ (dimensionless).

    References
    ----------
    .. [1] ISO/TR 13989-1:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 1: Flash temperature method.
    """
    if eps_gamma <= 2:
        return 1.0
    return 1 + 0.2 * math.sqrt((eps_gamma - 2) * (5 - eps_gamma)) if eps_gamma < 3.5 else 1.3


def friction_coefficient(w_bt_N_mm: float, v_sum_m_s: float, rho_red_mm: float, eta_mPas: float, ra_um: float,
                         x_l: float = 1.0) -> float:
    """μ_mC = 0.045 (w_Bt K_Bγ/(v_ΣC ρ_redC))^0.2 η^(−0.05) X_R X_L, X_R = 2.2 (R_a/ρ_redC)^0.25
    (ISO/TR 13989-2 [1]_; ``w_bt_N_mm`` already times K_Bγ).

    The standard's engineering units are kept: the constants are empirical and belong to them.

    Parameters
    ----------
    w_bt_N_mm : float
        Transverse unit load times K_Bγ, w_Bt K_Bγ, N/mm.
    v_sum_m_s : float
        Sum of the tangential speeds at the pitch point v_ΣC, m/s.
    rho_red_mm : float
        Relative (reduced) radius of curvature at the pitch point ρ_redC, mm.
    eta_mPas : float
        Dynamic viscosity of the oil at the oil temperature, mPa·s.
    ra_um : float
        Flank arithmetic mean roughness R_a, µm.
    x_l : float, default 1.0
        Lubricant factor X_L (1 for mineral oil).

    Returns
    -------
    float
        Mean coefficient of friction μ_mC (dimensionless).

    References
    ----------
    .. [1] ISO/TR 13989-2:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 2: Integral temperature method.
    """
    x_r = 2.2 * (ra_um / rho_red_mm) ** 0.25
    return 0.045 * (w_bt_N_mm / (v_sum_m_s * rho_red_mm)) ** 0.2 * eta_mPas ** -0.05 * x_r * x_l


def flash_temperature(w, rho1, rho2, v1, v2, mu, reduced_modulus: float, cos_beta_b: float = 1.0,
                      b1: float = STEEL_THERMAL_CONTACT_COEFFICIENT, b2: float = STEEL_THERMAL_CONTACT_COEFFICIENT):
    """Blok's flash temperature (K) of a Hertzian line contact [1]_, [2]_ (module docstring for the
    derivation and the constant :data:`BLOK_COEFFICIENT`); arrays broadcast.

    Parameters
    ----------
    w : array_like
        Normal load per unit contact-line length, N/m; zero or negative gives 0.
    rho1, rho2 : array_like
        Transverse radii of curvature of pinion and gear at the point, m.
    v1, v2 : array_like
        The surfaces' rolling speeds normal to the contact line, m/s.
    mu : array_like
        Coefficient of friction (dimensionless).
    reduced_modulus : float
        E_r = 2/((1 − ν1²)/E1 + (1 − ν2²)/E2), Pa.
    cos_beta_b : float, default 1.0
        cos β_b, for the normal relative radius ρ_red/cos β_b.
    b1, b2 : float, default :data:`STEEL_THERMAL_CONTACT_COEFFICIENT`
        Thermal contact coefficients B_i = √(λ_i ρ_i c_i), N/(m·s^½·K).

    Returns
    -------
    numpy.ndarray
        Flash temperature θ_fl, K, of the broadcast shape; 0 where ``w`` ≤ 0.

    References
    ----------
    .. [1] Blok H., "Theoretical study of temperature rise at surfaces of actual contact under
       oiliness lubricating conditions", Proc. General Discussion on Lubrication and Lubricants,
       Institution of Mechanical Engineers, London, vol. 2 (1937) 222–235.
    .. [2] Jaeger J.C., "Moving sources of heat and the temperature at sliding contacts",
       J. Proc. Roy. Soc. New South Wales 76 (1942) 203–224.
    """
    w, rho1, rho2, v1, v2 = (np.asarray(a, dtype=float) for a in (w, rho1, rho2, v1, v2))
    with np.errstate(invalid="ignore", divide="ignore"):
        radius = rho1 * rho2 / ((rho1 + rho2) * cos_beta_b)
        half_width = np.sqrt(8 * np.maximum(w, 0.0) * radius / (math.pi * reduced_modulus))
        out = BLOK_COEFFICIENT * mu * w * np.abs(v1 - v2) / ((b1 * np.sqrt(v1) + b2 * np.sqrt(v2)) * np.sqrt(half_width))
    return np.where(w > 0, out, 0.0)


def flash_scuffing_temperature(fzg_load_stage: int, x_w: float = 1.0, x_l: float = 1.0) -> float:
    """θ_S (°C) = 80 + (0.85 + 1.4 X_W) X_L S_FZG² of the flash temperature method (FZG A/8.3/90) [1]_, [2]_.

    Parameters
    ----------
    fzg_load_stage : int
        Failure load stage S_FZG of the oil in the FZG test A/8.3/90.
    x_w : float, default 1.0
        Welding factor X_W.
    x_l : float, default 1.0
        Lubricant factor X_L.

    Returns
    -------
    float
        Scuffing temperature θ_S, °C.

    References
    ----------
    .. [1] ISO/TR 13989-1:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 1: Flash temperature method.
    .. [2] ISO/TS 6336-20:2017, Calculation of load capacity of spur and helical gears — Part 20:
       Calculation of scuffing load capacity — Flash temperature method.
    """
    return 80.0 + (0.85 + 1.4 * x_w) * x_l * fzg_load_stage**2


def integral_scuffing_temperature(fzg_load_stage: int, x_w: float = 1.0, x_l: float = 1.0) -> float:
    """θ_intS (°C) = θ_MT + X_WrelT C_2 θ_flaintT with θ_MT = 80 + 0.23 T_1T X_L, θ_flaintT = 0.2 T_1T X_L,
    T_1T the stage's pinion torque (:data:`FZG_PINION_TORQUE_NM`), X_WrelT = X_W/X_WT [1]_, [2]_, [3]_.

    Parameters
    ----------
    fzg_load_stage : int
        Failure load stage of the oil in the FZG test A/8.3/90 (1–12).
    x_w : float, default 1.0
        Welding factor X_W.
    x_l : float, default 1.0
        Lubricant factor X_L.

    Returns
    -------
    float
        Integral scuffing temperature θ_intS, °C.

    References
    ----------
    .. [1] ISO/TR 13989-2:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 2: Integral temperature method.
    .. [2] ISO/TS 6336-21:2017, Calculation of load capacity of spur and helical gears — Part 21:
       Calculation of scuffing load capacity — Integral temperature method.
    .. [3] ISO 14635-1:2000, Gears — FZG test procedures — Part 1: FZG test method A/8,3/90 for
       relative scuffing load-carrying capacity of oils, Table 2 (pinion torque per load stage).
    """
    t1 = FZG_PINION_TORQUE_NM[int(fzg_load_stage)]
    c2, x_wt = SCUFFING_ASSUMPTIONS["C_2"], SCUFFING_ASSUMPTIONS["X_WT"]
    return 80.0 + 0.23 * t1 * x_l + x_w / x_wt * c2 * 0.2 * t1 * x_l


@dataclass(frozen=True)
class PathKinematics:
    """Every LTCA point's place on the path of contact (arrays (P, J, N)): ``on_path`` flank points
    between A and E (the LTCA's region 1), ``s`` the distance from A (m), ``rho1``, ``rho2`` the
    radii of curvature (m), ``v1``, ``v2`` the rolling speeds normal to the contact line (m/s) at the
    pinion speed the kinematics were made for."""

    on_path: np.ndarray
    s: np.ndarray
    rho1: np.ndarray
    rho2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray


def path_kinematics(geom: PairGeometry, grid, speed_rpm: float) -> PathKinematics:
    """:class:`PathKinematics` of an LTCA's candidate grid (:class:`gearmesh.tca.CandidateGrid`) at
    pinion speed ``speed_rpm``: v_i = ω_i ρ_i, ω2 = ω1 z1/z2.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    grid : CandidateGrid
        The LTCA's candidate points, arrays (P, J, N) (:func:`gearmesh.tca.candidate_grid`).
    speed_rpm : float
        Pinion speed, rpm.

    Returns
    -------
    PathKinematics
        ``on_path`` (P, J, N) bool, ``s`` (m), ``rho1``, ``rho2`` (m), ``v1``, ``v2`` (m/s); NaN off
        the path.
    """
    omega1 = 2 * math.pi * speed_rpm / 60.0
    omega2 = omega1 * geom.pair.teeth[0] / geom.pair.teeth[1]
    on = grid.region == 1
    rho1 = np.where(on, grid.rho_pinion, np.nan)
    rho2 = np.where(on, grid.rho_gear, np.nan)
    return PathKinematics(on_path=on, s=np.where(on, grid.s, np.nan), rho1=rho1, rho2=rho2,
                          v1=omega1 * rho1, v2=omega2 * rho2)


@dataclass(frozen=True)
class ScuffingRating:
    """The scuffing rating at each torque (arrays (T,) unless stated; °C for temperatures, their
    differences in K): ``flash`` the flash temperature of every LTCA point (T, P, J, N), NaN off the
    path; ``mu`` μ_mC; ``flash_max`` θ_fl,max; ``flash_mean`` the mean over the path (θ_flm =
    θ_flaint); ``bulk_flash``, ``contact_max``, ``scuffing_temperature``, ``safety_flash`` θ_M, θ_B,max,
    θ_S (scalar), S_B of the flash temperature method; ``bulk_integral``, ``integral``,
    ``integral_scuffing_temperature`` (scalar), ``safety_integral`` θ_M, θ_int, θ_intS, S_intS of the
    integral method; ``viscosity_oil`` ν at the oil temperature (mm²/s); ``path`` the kinematics."""

    flash: np.ndarray
    mu: np.ndarray
    flash_max: np.ndarray
    flash_mean: np.ndarray
    bulk_flash: np.ndarray
    contact_max: np.ndarray
    scuffing_temperature: float
    safety_flash: np.ndarray
    bulk_integral: np.ndarray
    integral: np.ndarray
    integral_scuffing_temperature: float
    safety_integral: np.ndarray
    viscosity_oil: float
    path: PathKinematics

    def notes(self) -> list[str]:
        a = SCUFFING_ASSUMPTIONS
        return [f"scuffing (ISO/TS 6336-20/-21): flash temperature by Blok from the LTCA's line load along the path "
                f"of contact times K_A K_v, steel B_M {a['B_M']:g} N/(m s^0.5 K), mineral oil X_L {a['X_L']:g}, dip "
                f"lubrication X_S {a['X_S']:g}, X_mp {a['X_mp']:g}, welding factor X_W {a['X_W']:g} (case-hardened, "
                f"average retained austenite), oil density {a['oil_density_15C_kg_m3']:g} kg/m3 at 15 C; tip-edge "
                f"contacts off the path not rated"]


def scuffing_rating(geom: PairGeometry, line_load: np.ndarray, grid, speed_rpm: float, inputs: Mapping[str, Any],
                    load_factor, w_bt_N_mm) -> ScuffingRating:
    """The scuffing rating of an LTCA's line load by the flash and the integral temperature methods.

    Blok's flash temperature [1]_ of every LTCA point on the path of contact from the LTCA's own line load,
    then the flash [2]_, [4]_ and integral temperature methods [3]_, [5]_ (factors: :data:`SCUFFING_ASSUMPTIONS`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    line_load : numpy.ndarray
        The LTCA's line load, (T, P, J, N) N/m.
    grid : CandidateGrid
        The LTCA's candidate grid (:class:`gearmesh.tca.CandidateGrid`).
    speed_rpm : float
        Pinion speed, rpm.
    inputs : Mapping
        Rating inputs: ``flank_Ra_um``, ``viscosity_40C_mm2_s``, ``viscosity_100C_mm2_s``,
        ``oil_temperature_C``, ``fzg_load_stage`` (:func:`gearmesh.rating.rating_inputs`).
    load_factor : array_like
        (T,) K_A K_v applied to the line load.
    w_bt_N_mm : array_like
        (T,) the rating's K_A K_v K_Hβ K_Hα F_t/b, N/mm, for μ_mC (times K_Bγ here).

    Returns
    -------
    ScuffingRating
        ``flash`` (T, P, J, N) K; (T,): ``mu``, ``flash_max``, ``flash_mean`` (K), ``contact_max`` θ_B,max (°C),
        ``safety_flash`` S_B, ``integral`` θ_int (°C), ``safety_integral`` S_intS; θ_S, θ_intS (°C, scalars).

    References
    ----------
    .. [1] Blok H., "Theoretical study of temperature rise at surfaces of actual contact under
       oiliness lubricating conditions", Proc. General Discussion on Lubrication and Lubricants,
       Institution of Mechanical Engineers, London, vol. 2 (1937) 222–235.
    .. [2] ISO/TR 13989-1:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 1: Flash temperature method.
    .. [3] ISO/TR 13989-2:2000, Calculation of scuffing load capacity of cylindrical, bevel and hypoid
       gears — Part 2: Integral temperature method.
    .. [4] ISO/TS 6336-20:2017, Calculation of load capacity of spur and helical gears — Part 20:
       Calculation of scuffing load capacity — Flash temperature method.
    .. [5] ISO/TS 6336-21:2017, Calculation of load capacity of spur and helical gears — Part 21:
       Calculation of scuffing load capacity — Integral temperature method.
    """
    mat = geom.pair.material
    e_r = mat.youngs_modulus / (1 - mat.poisson_ratio**2)
    cos_bb = math.cos(geom.base_helix_angle)
    path = path_kinematics(geom, grid, speed_rpm)
    theta_oil = float(inputs["oil_temperature_C"])
    nu40, nu100 = float(inputs["viscosity_40C_mm2_s"]), float(inputs["viscosity_100C_mm2_s"])
    eta = oil_dynamic_viscosity(nu40, nu100, theta_oil)
    rho_c = [float(geom.base_radius[i]) * math.tan(geom.operating_pressure_angle) for i in (0, 1)]
    rho_red_mm = 1e3 * rho_c[0] * rho_c[1] / ((rho_c[0] + rho_c[1]) * cos_bb)
    v_sum = 2 * (2 * math.pi * speed_rpm / 60.0) * rho_c[0]  # v_ΣC = 2 ω1 ρ_C1
    k_bg = helical_load_factor(geom.eps_gamma)
    load_factor = np.atleast_1d(np.asarray(load_factor, dtype=float))
    w_bt = np.atleast_1d(np.asarray(w_bt_N_mm, dtype=float))
    mu = np.array([friction_coefficient(w * k_bg, v_sum, rho_red_mm, eta, float(inputs["flank_Ra_um"]))
                   for w in w_bt])
    w = np.asarray(line_load, dtype=float) * load_factor[:, None, None, None]
    flash = flash_temperature(w, path.rho1, path.rho2, path.v1, path.v2, mu[:, None, None, None], e_r, cos_bb)
    flash = np.where(path.on_path, flash, np.nan)
    flash_max = np.nanmax(flash, axis=(1, 2, 3))
    flash_mean = np.nanmean(flash, axis=(1, 2, 3))
    a = SCUFFING_ASSUMPTIONS
    stage = int(inputs["fzg_load_stage"])
    bulk_flash = theta_oil + _BULK_FLASH * a["X_S"] * a["X_mp"] * flash_mean
    contact_max = bulk_flash + flash_max
    theta_s = flash_scuffing_temperature(stage, a["X_W"], a["X_L"])
    bulk_int = theta_oil + _BULK_INTEGRAL * a["X_S"] * a["X_mp"] * flash_mean
    integral = bulk_int + a["C_2"] * flash_mean
    theta_int_s = integral_scuffing_temperature(stage, a["X_W"], a["X_L"])
    return ScuffingRating(flash=flash, mu=mu, flash_max=flash_max, flash_mean=flash_mean, bulk_flash=bulk_flash,
                          contact_max=contact_max, scuffing_temperature=theta_s,
                          safety_flash=(theta_s - theta_oil) / (contact_max - theta_oil), bulk_integral=bulk_int,
                          integral=integral, integral_scuffing_temperature=theta_int_s,
                          safety_integral=theta_int_s / integral,
                          viscosity_oil=float(walther_viscosity(nu40, nu100, theta_oil)), path=path)
