"""Load capacity rating of a helical pair by ISO 6336-2 (pitting) and ISO 6336-3 (tooth bending), method B.

Units: the standard's own inside the formulas (N, mm, µm, N/mm², m/s), converted once at the
entry of :func:`rating` (SI in, engineering units out with the unit in the key name).

Factors (ISO 6336-1; the functions of :mod:`gearmesh.rating_factors`) are computed two ways, and any
may be given instead (``factors``):

* ``iso``: the standard's methods — K_v by the simplified method C of ISO 6336-1:1996 (6.3.4,
  also DIN 3990-1 eq. 3.05) from the ISO 1328-1 accuracy grade; K_Hβ by method C (F_βx from
  the pinion's bending f_sh and the mesh misalignment f_ma = f_Hβ of the grade, running-in
  y_β, c_γβ of ISO 6336-1 method B); K_Fβ = K_Hβ^N_F; K_Hα = K_Fα by method B from the base
  pitch deviation f_pb of the grade and the running-in y_α, with the standard's bounds.
* ``ltca``: from the LTCA's own load distribution (ISO 6336-1 method A definitions):
  K_Hβ = the peak over the face of the line load per unit face width summed over the mesh
  cycle, over its mean; K_Fβ = K_Hβ^N_F; K_Hα = K_Fα = the largest load a tooth pair carries
  over the cycle over the same of the unmodified, error-free pair's LTCA (1 for that pair).
  K_v is the standard's (the dynamics stage's K_v is not used here).

Pitting (ISO 6336-2:2006, method B): Z_H, Z_E, Z_ε, Z_β = 1/√cos β, Z_B/Z_D (single pair
contact), σ_H0 = Z_H Z_E Z_ε Z_β √(F_t/(d1 b)·(u+1)/u), σ_H = Z_B,D σ_H0 √(K_A K_v K_Hβ K_Hα),
σ_HG = σ_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X, σ_HP = σ_HG/S_Hmin, S_H = σ_HG/σ_H.
Bending (ISO 6336-3:2006, method B): Y_F, Y_S at the outer point of single pair tooth contact
(:func:`gearmesh.stress.gear_root_form`), Y_β, Y_B, Y_DT, σ_F0 = F_t/(b m_n) Y_F Y_S Y_β Y_B Y_DT,
σ_F = σ_F0 K_A K_v K_Fβ K_Fα, σ_FG = σ_Flim Y_ST Y_NT Y_δrelT Y_RrelT Y_X Y_M, σ_FP = σ_FG/S_Fmin,
S_F = σ_FG/σ_F. Life factors Z_NT, Y_NT by ISO 6336-2/-3:2019 (the 'normal' long-life line to 0.85
at 10¹⁰ cycles unless the inputs say 'optimum'); Y_M = 0.7 for an idler gear.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from .choices import DEFAULT_LIFE_FACTOR_CONDITIONS
from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
from .pairfile import check_rating_input
from .limits import FACTOR_RANGES
from .rating_factors import (LONG_LIFE_CYCLES, METHOD_C_SPEED_LIMIT, contact_ratio_factor, deep_tooth_factor,
                             dynamic_factor_c, elasticity_factor, face_factor_root, face_load_factor_c,
                             helix_factor_root, iso1328_tolerances, life_factor_contact, life_factor_root,
                             lubrication_velocity_roughness, mean_stress_factor, notch_sensitivity_factor,
                             rim_factor, root_roughness_factor, single_pair_factors, size_factor_root,
                             transverse_load_factor_b, zone_factor)
from .stress import gear_root_form

__all__ = [
    "DEFAULT_INPUTS", "FACTOR_NAMES", "FACTOR_SOURCES", "RatingInputs", "rating_inputs", "check_factors",
    "Rating", "rated_transverse_factor", "ltca_load_factors", "rating",
]

#: Inputs when the pair file gives none, each named in the result's notes.
#: Case-hardened wrought steel, quality MQ, ISO 6336-5:2016 (σ_Hlim 1500 N/mm², σ_Flim 500 N/mm²);
#: ISO 1328-1 grade 6 (ground gears); ground flanks Ra 0.4 / Rz 2.5 µm and a hobbed, unground
#: root Rz 10 µm (assumed, typical of ground case-hardened gears); ISO VG 220 oil (ν40 220,
#: ν100 19 mm²/s, ISO 3448 mid-points) at 70 °C (assumed), FZG load stage 12 (ISO 14635-1; the
#: least a CLP gear oil must reach by DIN 51517-3); life factors for 'normal' long-life conditions
#: (ISO 6336-2/-3:2019: 0.85 at 10¹⁰ cycles); neither gear an idler (one-way bending, Y_M = 1).
DEFAULT_INPUTS = {
    "contact_fatigue_limit_MPa": 1500.0, "bending_fatigue_limit_MPa": 500.0, "accuracy_grade": 6,
    "flank_Ra_um": 0.4, "flank_Rz_um": 2.5, "root_Rz_um": 10.0,
    "viscosity_40C_mm2_s": 220.0, "viscosity_100C_mm2_s": 19.0, "oil_temperature_C": 70.0,
    "fzg_load_stage": 12, "life_factor_conditions": DEFAULT_LIFE_FACTOR_CONDITIONS, "idler_gear": "none",
}
_SOURCES = {
    "contact_fatigue_limit_MPa": "ISO 6336-5:2016 case-hardened wrought steel MQ",
    "bending_fatigue_limit_MPa": "ISO 6336-5:2016 case-hardened wrought steel MQ",
    "accuracy_grade": "ISO 1328-1 grade 6 assumed",
    "flank_Ra_um": "ground flank assumed", "flank_Rz_um": "ground flank assumed", "root_Rz_um": "hobbed root assumed",
    "viscosity_40C_mm2_s": "ISO VG 220 assumed", "viscosity_100C_mm2_s": "ISO VG 220 assumed",
    "oil_temperature_C": "assumed",
    "fzg_load_stage": "the least of a CLP gear oil, DIN 51517-3 (scuffing)",
    "life_factor_conditions": "ISO 6336-2/-3 long-life line, Z_NT = Y_NT = 0.85 at 1e10 cycles; 'optimum' "
                              "holds 1.0 where optimum lubrication, material, manufacturing and experience apply",
    "idler_gear": "one-way bending of both gears, Y_M = 1",
}
#: Factors that may be given instead of computed (``--factor NAME=VALUE``), with their lower bound
#: (their ranges in the standard: :data:`gearmesh.limits.FACTOR_RANGES`).
FACTOR_NAMES = {name: low for name, (low, _) in FACTOR_RANGES.items()}
FACTOR_SOURCES = ("iso", "ltca")


@dataclass(frozen=True)
class RatingInputs:
    """Material, accuracy, roughness and lubricant of a rating (engineering units), and which
    were taken from :data:`DEFAULT_INPUTS` (``defaulted``)."""

    values: Mapping[str, Any]
    defaulted: tuple[str, ...] = ()

    def __getitem__(self, key: str) -> Any:
        return self.values[key]

    def notes(self) -> list[str]:
        return [f"{k} = {_text(self.values[k])} not given: {_SOURCES[k]}" for k in self.defaulted]


def _text(value: Any) -> str:
    return f"{value:g}" if isinstance(value, (int, float)) else str(value)


def rating_inputs(given: Mapping[str, Any] | None = None) -> RatingInputs:
    """The given inputs checked by the pair reader's rules, the others filled from :data:`DEFAULT_INPUTS`.

    Names of :data:`DEFAULT_INPUTS` (e.g. a pair's ``rating_inputs``; others such as
    ``tip_edge_radius_mm`` are not the rating's and are skipped) are checked by
    :func:`gearmesh.pairfile.check_rating_input` (grade an integer 1..12, limits, roughness and
    viscosities positive, ν100 < ν40).

    Parameters
    ----------
    given : Mapping, optional
        Rating inputs in engineering units, keys with their unit (e.g. ``flank_Ra_um``,
        ``viscosity_40C_mm2_s``, ``contact_fatigue_limit_MPa``); None: all defaults.

    Returns
    -------
    RatingInputs
        ``values`` (all of :data:`DEFAULT_INPUTS`' keys) and the names ``defaulted``.

    Raises
    ------
    GearmeshInputError
        An input outside its rule, or ``viscosity_100C_mm2_s`` not below ``viscosity_40C_mm2_s``.
    """
    given = {k: v for k, v in dict(given or {}).items() if k in DEFAULT_INPUTS}
    out = {k: check_rating_input(k, given[k]) if k in given else default for k, default in DEFAULT_INPUTS.items()}
    if out["viscosity_100C_mm2_s"] >= out["viscosity_40C_mm2_s"]:
        raise GearmeshInputError("viscosity_100C_mm2_s", out["viscosity_100C_mm2_s"],
                                 f"must be below viscosity_40C_mm2_s ({out['viscosity_40C_mm2_s']:g})")
    return RatingInputs(values=out, defaulted=tuple(k for k in DEFAULT_INPUTS if k not in given))


def check_factors(factors: Mapping[str, Any] | None) -> dict[str, float]:
    """Given factors {name: value} (a mapping): names of :data:`FACTOR_NAMES`, each a finite number
    within its range in the standard (:data:`gearmesh.limits.FACTOR_RANGES`: the load factors K_*
    at least 1, the life factors within ISO 6336-2/-3's tables, ...).

    Parameters
    ----------
    factors : Mapping of str to float, optional
        Factors given instead of computed, e.g. ``{'K_v': 1.2}`` (dimensionless).

    Returns
    -------
    dict of str to float
        The checked factors.

    Raises
    ------
    GearmeshInputError
        Not a mapping, an unknown name, or a value not finite or out of its range.
    """
    if factors is not None and not isinstance(factors, Mapping):
        raise GearmeshInputError("factors", factors, "must be a mapping {name: value}, e.g. {'K_v': 1.2}")
    out = {}
    for name, value in dict(factors or {}).items():
        if name not in FACTOR_RANGES:
            raise GearmeshInputError(f"factor {name}", value, f"must be one of {sorted(FACTOR_RANGES)}")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise GearmeshInputError(f"factor {name}", value, "must be a finite number")
        low, high = FACTOR_RANGES[name]
        if not low <= value <= high:
            raise GearmeshInputError(f"factor {name}", value, f"must lie in [{low:g}, {high:g}], its range in ISO 6336 "
                                     "(gearmesh.limits.FACTOR_RANGES)")
        out[name] = float(value)
    return out


# --------------------------------------------------------------------------------------
# Load factors from the LTCA (method A definitions)
# --------------------------------------------------------------------------------------


def ltca_load_factors(load: np.ndarray, reference_load: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """K_Hβ and K_Hα per torque from LTCA point loads ``load`` (T, P, J, N) N.

    K_Hβ: the load of every slice summed over tooth pairs and mesh positions (the face load
    distribution over a cycle), its maximum over its mean (ISO 6336-1 method A [1]_: the peak load per
    unit face width over the mean). K_Hα: the largest load a tooth pair carries over the cycle,
    over the same of ``reference_load`` (the LTCA of the same pair unmodified and error-free, same
    torques and grid): how far the load sharing between pairs departs from the ideal one that
    Z_ε and Z_B already assume; 1 without a reference (the unmodified pair is its own). The LTCA
    has no pitch errors, so this K_Hα carries the modifications' effect, not ISO's f_pb.

    Parameters
    ----------
    load : numpy.ndarray
        (T, P, J, N) LTCA point loads, N.
    reference_load : numpy.ndarray, optional
        (T, P, J', N) point loads of the unmodified, error-free pair, N.

    Returns
    -------
    dict of str to numpy.ndarray
        ``K_Hbeta`` and ``K_Halpha``, each (T,).

    References
    ----------
    .. [1] ISO 6336-1, Calculation of load capacity of spur and helical gears — Part 1: Basic principles,
       introduction and general influence factors, method A.
    """
    q = np.asarray(load, dtype=float)
    face = q.sum(axis=(1, 2))  # (T, N)
    k_hb = face.max(axis=1) / face.mean(axis=1)
    if reference_load is None:
        k_ha = np.ones(q.shape[0])
    else:
        k_ha = q.sum(axis=3).max(axis=(1, 2)) / np.asarray(reference_load, dtype=float).sum(axis=3).max(axis=(1, 2))
    return {"K_Hbeta": k_hb, "K_Halpha": k_ha}


# --------------------------------------------------------------------------------------
# The rating
# --------------------------------------------------------------------------------------


@dataclass
class Rating:
    """Values of a rating in engineering units: ``values`` (name → float or [pinion, gear]),
    ``given`` factor names, ``sources`` factor name → 'iso' | 'ltca' | 'given', ``notes``."""

    values: dict[str, Any]
    given: list[str]
    sources: dict[str, str]
    notes: list[str] = field(default_factory=list)


def rated_transverse_factor(k_halpha):
    """The LTCA's K_Hα (scalar or array) as the rating takes it: at least 1, since ISO 6336-1
    defines no load factor below 1 (:func:`check_factors`); better load sharing than the
    unmodified pair's earns no credit below the standard's own assumption.

    Parameters
    ----------
    k_halpha : float or array_like
        The LTCA's transverse load factor K_Hα.

    Returns
    -------
    float or numpy.ndarray
        max(K_Hα, 1).
    """
    return np.maximum(k_halpha, 1.0)


def rating(geom: PairGeometry, pinion_torque: float, speed_rpm: float, inputs: RatingInputs | None = None,
           application_factor: float = 1.0, life_hours: float | None = None, factors: Mapping[str, float] | None = None,
           method: str = "iso", ltca_factors: Mapping[str, float] | None = None, running_in: bool = True) -> Rating:
    """ISO 6336-2/-3 method B rating of ``geom`` at a pinion torque and speed (module docstring).

    Load factors by ISO 6336-1 [1]_, pitting by ISO 6336-2 [2]_, bending by ISO 6336-3 [3]_.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with material and modifications (:func:`gearmesh.gear.pair_geometry`).
    pinion_torque : float
        Pinion torque T1, N·m.
    speed_rpm : float
        Pinion speed, rpm.
    inputs : RatingInputs, optional
        Material, accuracy, roughness and lubricant (:func:`rating_inputs`); None: the defaults.
    application_factor : float, default 1.0
        Application factor K_A.
    life_hours : float, optional
        Required life, h; None: the long-life end of the life factors (N_L = 10¹⁰: 0.85 under the
        inputs' 'normal' ``life_factor_conditions``, 1 under 'optimum').
    factors : Mapping of str to float, optional
        Factors given instead of computed (:func:`check_factors`).
    method : {'iso', 'ltca'}, default 'iso'
        Where K_Hβ, K_Fβ, K_Hα, K_Fα come from.
    ltca_factors : Mapping of str to float, optional
        The LTCA's ``K_Hbeta`` and ``K_Halpha`` (:func:`ltca_load_factors`), needed for 'ltca'.
    running_in : bool, default True
        Take the running-in allowances y_β of K_Hβ (method C).

    Returns
    -------
    Rating
        ``values`` in engineering units (σ_H, σ_F, σ_HG, σ_FG in MPa, safety factors S_H, S_F
        [pinion, gear], every factor), ``given`` names, ``sources`` of each factor and ``notes``.

    Raises
    ------
    GearmeshInputError
        An unknown ``method``, a factor out of range, or 'ltca' without the LTCA's factors.

    References
    ----------
    .. [1] ISO 6336-1, Calculation of load capacity of spur and helical gears — Part 1: Basic principles,
       introduction and general influence factors.
    .. [2] ISO 6336-2, Calculation of load capacity of spur and helical gears — Part 2: Calculation of
       surface durability (pitting), method B.
    .. [3] ISO 6336-3, Calculation of load capacity of spur and helical gears — Part 3: Calculation of
       tooth bending strength, method B.
    """
    if method not in FACTOR_SOURCES:
        raise GearmeshInputError("method", method, f"must be one of {list(FACTOR_SOURCES)}")
    given = check_factors({**({"K_A": application_factor} if application_factor != 1.0 else {}), **(factors or {})})
    check_factors({"K_A": application_factor})
    inputs = inputs or rating_inputs()
    op = _operating_point(geom, pinion_torque, speed_rpm, inputs)
    pick = _FactorChoice(given, method, {"K_A": "given"})
    load, z_eps, iso_factors = _load_factors(geom, op, given.get("K_A", application_factor), pick,
                                             dict(ltca_factors or {}), running_in)
    cycles = [LONG_LIFE_CYCLES if life_hours is None else life_hours * 60.0 * n for n in (speed_rpm, speed_rpm / op.u)]
    conditions = inputs["life_factor_conditions"]
    pitting = _pitting(geom, op, load, z_eps, inputs, pick, cycles)
    bending = _bending(geom, op, load, inputs, pick, cycles)
    values = {
        "pinion_torque_Nm": float(pinion_torque), "speed_rpm": float(speed_rpm), "pitch_line_speed_m_s": op.v,
        "force_tangential_N": op.ft, "accuracy_grade": op.grade, **load, **pitting, **bending,
        "load_cycles": _per_gear(cycles), "life_factor_conditions": conditions, "iso_factors": iso_factors,
    }
    notes = inputs.notes()
    speed_term = op.z1 * op.v / 100.0 * math.sqrt(op.u**2 / (1 + op.u**2))
    if pick.sources["K_v"] == "iso" and speed_term > METHOD_C_SPEED_LIMIT:
        notes.append(f"K_v by method C outside its range: z1 v/100 sqrt(u^2/(1+u^2)) = {speed_term:.3g} m/s > "
                     f"{METHOD_C_SPEED_LIMIT:g} m/s; give K_v (--factor K_v=...) from a dynamic analysis")
    if life_hours is None:
        notes.append(f"life_hours not given: the long-life end of the life factors, N_L = {LONG_LIFE_CYCLES:g} "
                     f"({conditions} conditions: Z_NT = {pitting['Z_NT'][0]:g}, Y_NT = {bending['Y_NT'][0]:g}; "
                     f"ISO 6336-2/-3:2019)")
    notes.append("Z_W = 1 (both gears case-hardened), Z_X = 1 (ISO 6336-2), S_Hmin = S_Fmin = 1 unless given")
    return Rating(values=values, given=sorted(given), sources=pick.sources, notes=notes)


def _per_gear(a) -> list[float]:
    """[pinion, gear] as floats."""
    return [float(a[0]), float(a[1])]


@dataclass(frozen=True)
class _OperatingPoint:
    """What every part of a rating takes of the pair and its load (ISO 6336 units: mm, N, m/s):
    teeth z1, ratio u, normal module mn, face width b, reference diameter d1, tangential force ft
    at the reference circle, pitch-line speed v, accuracy grade and its ISO 1328-1 tolerances (µm)."""

    z1: int
    u: float
    mn: float
    b: float
    d1: float
    ft: float
    v: float
    grade: int
    tol: dict[str, float]


def _operating_point(geom: PairGeometry, pinion_torque: float, speed_rpm: float,
                     inputs: RatingInputs) -> _OperatingPoint:
    """The pair's rating dimensions and load at pinion torque ``pinion_torque`` (N·m) and speed ``speed_rpm``."""
    p = geom.pair
    z1, z2 = p.teeth
    mn = p.normal_module * 1e3
    b = geom.face_width * 1e3
    d1 = 2 * float(geom.reference_radius[0]) * 1e3
    v = math.pi * d1 * 1e-3 * speed_rpm / 60.0
    grade = inputs["accuracy_grade"]
    return _OperatingPoint(z1=z1, u=z2 / z1, mn=mn, b=b, d1=d1, ft=2 * pinion_torque / (d1 * 1e-3), v=v, grade=grade,
                           tol=iso1328_tolerances(grade, d1, b, mn))


@dataclass(frozen=True)
class _FactorChoice:
    """Where each factor of a rating comes from, recorded in ``sources``: given (``given``), the
    LTCA's (``method`` 'ltca', where it has one) or ISO 6336's."""

    given: Mapping[str, float]
    method: str
    sources: dict[str, str]

    def __call__(self, name: str, iso_value, ltca_value=None):
        if name in self.given:
            self.sources[name] = "given"
            return self.given[name]
        if self.method == "ltca" and ltca_value is not None:
            self.sources[name] = "ltca"
            return ltca_value
        self.sources[name] = "iso"
        return iso_value


def _load_factors(geom: PairGeometry, op: _OperatingPoint, k_a: float, pick: _FactorChoice,
                  ltca_factors: dict[str, float], running_in: bool) -> tuple[dict[str, float], float, dict[str, Any]]:
    """The load factors K_A, K_v, K_Hβ, K_Fβ, K_Hα, K_Fα (ISO 6336-1: K_v method C, K_Hβ method C,
    K_Hα method B, or the LTCA's/given), the contact ratio factor Z_ε they use, and the ISO
    values with their inputs (``iso_factors`` of the result)."""
    p = geom.pair
    ft, b, d1 = op.ft, op.b, op.d1
    stiff = _iso_stiffness(geom)
    c_ga, c_gb = stiff["c_gamma_alpha"], stiff["c_gamma_beta"]
    k_v = pick("K_v", dynamic_factor_c(op.grade, geom.eps_beta, op.v, op.z1, op.u, k_a * ft / b))
    fm = ft * k_a * k_v / b
    crowned = any(m.crowning > 0 for m in p.modification)
    k_hb_iso, fb = face_load_factor_c(fm, c_gb, op.tol["f_Hbeta"], b / d1, crowned, running_in)
    if pick.method == "ltca" and not {"K_Hbeta", "K_Halpha"} <= set(ltca_factors):
        raise GearmeshInputError("method", pick.method, "needs the LTCA's K_Hbeta and K_Halpha")
    k_hb = pick("K_Hbeta", k_hb_iso, ltca_factors.get("K_Hbeta"))
    b_over_h = b / (1e3 * max(float(geom.tip_radius[i] - geom.root_radius[i]) for i in (0, 1)))
    k_fb_iso = face_factor_root(k_hb_iso, b_over_h)
    k_fb = pick("K_Fbeta", k_fb_iso, face_factor_root(ltca_factors["K_Hbeta"], b_over_h) if "K_Hbeta" in ltca_factors
                else None)
    z_eps = contact_ratio_factor(geom.eps_alpha, geom.eps_beta)
    f_pb = op.tol["f_pt"] * math.cos(geom.transverse_pressure_angle)
    k_ha_iso, k_fa_iso, y_a = transverse_load_factor_b(geom.eps_alpha, geom.eps_gamma, z_eps, c_ga, f_pb,
                                                       ft * k_a * k_v * k_hb / b)
    k_ha = pick("K_Halpha", k_ha_iso, ltca_factors.get("K_Halpha"))
    k_fa = pick("K_Falpha", k_fa_iso, ltca_factors.get("K_Halpha"))
    factors = {"K_A": k_a, "K_v": k_v, "K_Hbeta": k_hb, "K_Fbeta": k_fb, "K_Halpha": k_ha, "K_Falpha": k_fa}
    iso = {"K_v": dynamic_factor_c(op.grade, geom.eps_beta, op.v, op.z1, op.u, k_a * ft / b),
           "K_Hbeta": k_hb_iso, "K_Fbeta": k_fb_iso, "K_Halpha": k_ha_iso, "K_Falpha": k_fa_iso,
           **fb, "f_pb_um": f_pb, "f_Hbeta_um": op.tol["f_Hbeta"], "y_alpha_um": y_a,
           "c_gamma_alpha_N_mm_um": c_ga, "c_gamma_beta_N_mm_um": c_gb}
    return factors, z_eps, iso


def _pitting(geom: PairGeometry, op: _OperatingPoint, load: Mapping[str, float], z_eps: float,
             inputs: RatingInputs, pick: _FactorChoice, cycles: list[float]) -> dict[str, Any]:
    """Contact stress σ_H, permissible σ_HG, σ_HP and safety S_H of each gear (ISO 6336-2 method B)
    with their factors, at ``cycles`` load cycles of each gear."""
    p, given = geom.pair, pick.given
    mat = p.material
    ft, b, d1, u = op.ft, op.b, op.d1, op.u
    z_h = zone_factor(geom)
    z_e = elasticity_factor(mat.youngs_modulus, mat.poisson_ratio)
    z_b_, z_d_, m1, m2 = single_pair_factors(geom)
    z_beta = 1 / math.sqrt(math.cos(p.helix_angle))
    s_h0 = z_h * z_e * z_eps * z_beta * math.sqrt(ft / (d1 * b) * (u + 1) / u)
    k_h = load["K_A"] * load["K_v"] * load["K_Hbeta"] * load["K_Halpha"]
    s_h = [z_b_ * s_h0 * math.sqrt(k_h), z_d_ * s_h0 * math.sqrt(k_h)]
    conditions = inputs["life_factor_conditions"]
    s_hlim = inputs["contact_fatigue_limit_MPa"]
    rho_c = [1e3 * float(geom.base_radius[i]) * math.tan(geom.operating_pressure_angle) for i in (0, 1)]
    rho_red = rho_c[0] * rho_c[1] / (rho_c[0] + rho_c[1])  # mm, at the pitch point
    lvr = lubrication_velocity_roughness(s_hlim, inputs["viscosity_40C_mm2_s"], op.v, inputs["flank_Rz_um"], rho_red)
    z_l, z_v, z_r = pick("Z_L", lvr["Z_L"]), pick("Z_v", lvr["Z_v"]), pick("Z_R", lvr["Z_R"])
    z_w, z_x = pick("Z_W", 1.0), pick("Z_X", 1.0)
    z_nt = [given.get("Z_NT", life_factor_contact(n, conditions)) for n in cycles]
    pick.sources["Z_NT"] = "given" if "Z_NT" in given else "iso"
    s_hmin = given.get("S_Hmin", 1.0)
    s_hg = [s_hlim * zn * z_l * z_v * z_r * z_w * z_x for zn in z_nt]
    return {
        "Z_H": z_h, "Z_E": z_e, "Z_epsilon": z_eps, "Z_beta": z_beta, "Z_B": z_b_, "Z_D": z_d_, "M_1": m1, "M_2": m2,
        "sigma_H0_MPa": s_h0, "sigma_H_MPa": _per_gear(s_h), "Z_NT": _per_gear(z_nt), "Z_L": z_l, "Z_v": z_v,
        "Z_R": z_r, "Z_W": z_w, "Z_X": z_x, "sigma_HG_MPa": _per_gear(s_hg),
        "sigma_HP_MPa": _per_gear([s / s_hmin for s in s_hg]), "S_H": _per_gear([g / s for g, s in zip(s_hg, s_h)]),
        "S_Hmin": s_hmin,
    }


def _bending(geom: PairGeometry, op: _OperatingPoint, load: Mapping[str, float], inputs: RatingInputs,
             pick: _FactorChoice, cycles: list[float]) -> dict[str, Any]:
    """Tooth-root stress σ_F, permissible σ_FG, σ_FP and safety S_F of each gear (ISO 6336-3
    method B) with their factors, at ``cycles`` load cycles of each gear."""
    p, given = geom.pair, pick.given
    forms = [gear_root_form(geom, i) for i in (0, 1)]
    y_beta = helix_factor_root(geom.eps_beta, p.helix_angle)
    h_t = [float(geom.tip_radius[i] - geom.root_radius[i]) for i in (0, 1)]
    bore = p.bore_radius or (0.0, 0.0)
    y_b = [rim_factor(float(geom.root_radius[i]) - bore[i], h_t[i]) for i in (0, 1)]
    eps_an = geom.eps_alpha / math.cos(geom.base_helix_angle) ** 2
    y_dt = deep_tooth_factor(eps_an, op.grade)
    s_f0 = [op.ft / (op.b * op.mn) * f.Y_F * f.Y_S * y_beta * yb * y_dt for f, yb in zip(forms, y_b)]
    k_f = load["K_A"] * load["K_v"] * load["K_Fbeta"] * load["K_Falpha"]
    s_f = [s * k_f for s in s_f0]
    s_flim = inputs["bending_fatigue_limit_MPa"]
    conditions = inputs["life_factor_conditions"]
    y_nt = [given.get("Y_NT", life_factor_root(n, conditions)) for n in cycles]
    pick.sources["Y_NT"] = "given" if "Y_NT" in given else "iso"
    y_d = [pick("Y_deltarelT", notch_sensitivity_factor(f.q_s)) for f in forms]
    y_r = pick("Y_RrelT", root_roughness_factor(inputs["root_Rz_um"]))
    y_x = pick("Y_X", size_factor_root(op.mn))
    s_fmin = given.get("S_Fmin", 1.0)
    y_m = [given.get("Y_M", mean_stress_factor(inputs["idler_gear"] == name)) for name in GEARS]
    pick.sources["Y_M"] = "given" if "Y_M" in given else "iso"
    s_fg = [s_flim * 2.0 * yn * yd * y_r * y_x * ym for yn, yd, ym in zip(y_nt, y_d, y_m)]
    return {
        "Y_F": _per_gear([f.Y_F for f in forms]), "Y_S": _per_gear([f.Y_S for f in forms]), "Y_beta": y_beta,
        "Y_B": _per_gear(y_b), "Y_DT": y_dt, "sigma_F0_MPa": _per_gear(s_f0), "sigma_F_MPa": _per_gear(s_f),
        "Y_ST": 2.0, "Y_NT": _per_gear(y_nt), "Y_deltarelT": _per_gear(y_d), "Y_RrelT": y_r, "Y_X": y_x,
        "Y_M": _per_gear(y_m), "sigma_FG_MPa": _per_gear(s_fg), "sigma_FP_MPa": _per_gear([s / s_fmin for s in s_fg]),
        "S_F": _per_gear([g / s for g, s in zip(s_fg, s_f)]), "S_Fmin": s_fmin,
    }


def _iso_stiffness(geom: PairGeometry) -> dict[str, float]:
    """c_γα, c_γβ (N/(mm µm)) of ISO 6336-1 method B (:func:`gearmesh.stiffness.iso6336_stiffness`)."""
    from .stiffness import iso6336_stiffness

    return iso6336_stiffness(geom)
