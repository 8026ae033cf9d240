"""Validity of loads and work sizes, checked before any computation (GearmeshInputError).

Geometric ranges (module, face width, modification depths, names) live beside the pair
data in :mod:`gearmesh.gear`; here are the limits that need a pair's geometry and a load,
or a stage's grid: the nominal contact stress and deflection of a torque, and the size of
the grids and sweeps a stage would allocate. Each limit says where it comes from.
"""

from __future__ import annotations

import math

from .errors import GearmeshInputError
from .gear import PairGeometry

#: Highest nominal contact stress σ_H0 (Pa) accepted: ISO 6336-5's highest allowable contact
#: stress number (case-hardened steel, quality ME: σ_Hlim = 1650 MPa) times ISO 6336-2's static
#: life factor Z_NT = 1.6. Above it every steel flank yields or pits at the first cycles, so a
#: linear-elastic result has no meaning.
MAX_CONTACT_STRESS = 1650e6 * 1.6
#: Largest nominal mesh deflection F_bt/(c_γα b), as a fraction of the normal module: the slice
#: and contact models are linear, for deflections small against the tooth (2.25 m_n high).
#: Steel pairs at :data:`MAX_CONTACT_STRESS` deflect about 0.02–0.06 m_n; 0.1 m_n also bounds
#: soft materials, whose contact stress stays low while the teeth bend away.
MAX_DEFLECTION_TO_MODULE = 0.1
#: Young's modulus (Pa) of the steel that ISO 6336-1's c' refers to; c' scales with E/E_st.
ISO6336_STEEL_MODULUS = 206e9

#: Most slice × position points of one slice-model stiffness run: measured about 400 bytes per
#: point (seed 001 pair, 1000 slices × 2000 positions: 0.9 GB, 2.5 s), so 4e6 points stay under
#: about 1.6 GB.
MAX_STIFFNESS_POINTS = 4_000_000
#: Most position × point candidates of one TCA/LTCA torque: measured about 1 kB per candidate
#: (2000 positions × 50 points: 0.2 GB), so 1e6 stay under about 1 GB.
MAX_CONTACT_POINTS = 1_000_000
#: Most helix angles of a sweep: each is a full pair geometry and contact-line run (about
#: 10 ms); the seeds use fewer than 100.
MAX_SWEEP_ANGLES = 2000


def nominal_load(geom: PairGeometry, pinion_torque: float) -> dict[str, float]:
    """Nominal contact stress σ_H0 (Pa, ISO 6336-2 method B) and mesh deflection (m) of a
    pinion torque (N m).

    σ_H0 = Z_H Z_E Z_ε √(F_t (u + 1)/(d1 b u)), with F_t = 2 T1/d1, Z_H = √(2 cos βb cos αwt /
    (cos² αt sin αwt)), Z_E = √(E/(2π(1 − ν²))) for two gears of one material (steel when the
    pair has none) and Z_ε of ISO 6336-2 eq. (8)–(10); Z_β ≈ 1 is left out (it lies within
    ±7 % for β < 30°; the limit is coarse). Deflection δ = F_bt/(c_γα b) with c_γα b from
    ISO 6336-1 (:func:`gearmesh.stiffness.iso6336_stiffness`) scaled by E/206 GPa.
    """
    from .stiffness import iso6336_stiffness

    pair = geom.pair
    material = pair.material
    e_mod = material.youngs_modulus if material else ISO6336_STEEL_MODULUS
    nu = material.poisson_ratio if material else 0.3
    d1 = 2 * float(geom.reference_radius[0])
    b = geom.face_width
    u = pair.teeth[1] / pair.teeth[0]
    f_t = 2 * pinion_torque / d1
    z_h = math.sqrt(2 * math.cos(geom.base_helix_angle) * math.cos(geom.operating_pressure_angle)
                    / (math.cos(geom.transverse_pressure_angle) ** 2 * math.sin(geom.operating_pressure_angle)))
    z_e = math.sqrt(e_mod / (2 * math.pi * (1 - nu**2)))
    ea, eb = geom.eps_alpha, geom.eps_beta
    z_eps = math.sqrt(1 / ea) if eb >= 1 else math.sqrt((4 - ea) / 3 * (1 - eb) + eb / ea)
    sigma = z_h * z_e * z_eps * math.sqrt(f_t * (u + 1) / (d1 * b * u))
    stiffness = iso6336_stiffness(geom)["K_gamma_alpha"] * e_mod / ISO6336_STEEL_MODULUS
    deflection = pinion_torque / float(geom.base_radius[0]) / stiffness
    return {"contact_stress": sigma, "deflection": deflection}


def check_load(geom: PairGeometry, pinion_torque: float, field: str, value: object) -> None:
    """Refuse a pinion torque (N m) whose nominal contact stress exceeds
    :data:`MAX_CONTACT_STRESS` or whose deflection exceeds :data:`MAX_DEFLECTION_TO_MODULE`
    normal modules (:func:`nominal_load`); ``field`` and ``value`` are what the user gave."""
    load = nominal_load(geom, pinion_torque)
    if load["contact_stress"] > MAX_CONTACT_STRESS:
        raise GearmeshInputError(field, value, f"gives a nominal contact stress of {load['contact_stress'] / 1e6:.4g} "
                                 f"MPa on {geom.pair.name}, above the static strength of any steel "
                                 f"({MAX_CONTACT_STRESS / 1e6:g} MPa, ISO 6336-2/-5)")
    limit = MAX_DEFLECTION_TO_MODULE * geom.pair.normal_module
    if load["deflection"] > limit:
        raise GearmeshInputError(field, value, f"deflects the mesh of {geom.pair.name} by "
                                 f"{load['deflection'] * 1e6:.4g} µm, more than {MAX_DEFLECTION_TO_MODULE:g} normal "
                                 f"module ({limit * 1e6:.4g} µm): outside the linear models")


def check_grid(field: str, value: object, points: int, limit: int, what: str) -> None:
    """Refuse a stage grid of ``points`` (e.g. slices × positions) above ``limit``."""
    if points > limit:
        raise GearmeshInputError(field, value, f"gives {points:.3g} {what}; at most {limit:.3g} "
                                 "(memory, see gearmesh.limits)")
