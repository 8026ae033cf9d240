"""Validity of loads, speeds and work sizes, checked before any computation (GearmeshInputError).

Geometric ranges (module, face width, teeth, modification depths, names) live beside the pair
data in :mod:`gearmesh.gear`; here are the limits that need a pair's geometry and a load, a
speed or a stage's grid: the nominal contact stress and deflection of a torque, the rim speed
of a rotational speed, and the size of the grids and sweeps a stage would allocate. Each limit
says where it comes from. The functions that compute (``gearmesh.datasets.*``) call these
checks at their entry, so the Python API, the command line and the workflow refuse the same
values with the same one line, in bounded time and memory.
"""

from __future__ import annotations

import math

import numpy as np

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
#: Highest centrifugal hoop stress ρ·v_a² (Pa) at the tip circle accepted: the ultimate tensile
#: strength of maraging steel 18Ni(300), about 2.0 GPa (ASM Handbook vol. 1, 1990), above that
#: of any carburising or through-hardening gear steel (EN 10084 18CrNiMo7-6 core: 1.08–1.32 GPa).
#: ρv² is the hoop stress of a thin ring rotating at rim speed v (Timoshenko & Goodier, Theory
#: of Elasticity, §32); a solid or webbed body of that rim speed carries at most (3 + ν)/4 of it
#: at a small bore, a thin rim loaded by its teeth more. Steel (7850 kg/m³) reaches it at a tip
#: speed of about 505 m/s, well above the pitch-line velocities of high-speed turbo gear units
#: (of the order of 100–200 m/s): beyond, the gear bursts, and no model here has centrifugal
#: loads or rim growth, or teeth that are not quasi-static (the ratio of the mesh frequency to a
#: tooth's first natural frequency grows as the pitch-line velocity over the speed of sound).
MAX_RIM_STRESS = 2.0e9
#: Density (kg/m³) of steel, for a pair without a material (as :data:`ISO6336_STEEL_MODULUS`).
STEEL_DENSITY = 7850.0

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


def check_loads(geom: PairGeometry, pinion_torques, field: str, given) -> None:
    """:func:`check_load` on each of ``pinion_torques`` (N m); ``given`` the values as the user
    gave them (same order), named ``field[k]`` when there are several."""
    values = np.ravel(given).tolist()
    for k, (t1, value) in enumerate(zip(np.ravel(pinion_torques), values)):
        check_load(geom, float(t1), f"{field}[{k}]" if len(values) > 1 else field, value)


def max_speed_rpm(geom: PairGeometry, on: str = "pinion") -> float:
    """Highest speed (rpm) of the ``on`` gear ('pinion' or 'gear') at which the faster tip circle
    stays within :data:`MAX_RIM_STRESS`: ρ (ω_g r_a,g)² ≤ σ_max for both gears, ω2 = ω1 z1/z2."""
    pair = geom.pair
    density = pair.material.density if pair.material else STEEL_DENSITY
    v_max = math.sqrt(MAX_RIM_STRESS / density)
    z1, z2 = pair.teeth
    ratio_to_pinion = 1.0 if on == "pinion" else z2 / z1  # ω1 = ω_on × ratio
    omega1 = min(v_max / float(geom.tip_radius[0]), v_max / float(geom.tip_radius[1]) * z2 / z1)
    return omega1 / ratio_to_pinion * 30.0 / math.pi


def check_speeds(geom: PairGeometry, speeds_rpm, field: str, on: str = "pinion") -> None:
    """Refuse any speed (rpm of the ``on`` gear) above :func:`max_speed_rpm`: the centrifugal
    hoop stress of the faster tip circle would exceed :data:`MAX_RIM_STRESS`. ``speeds_rpm``
    are numbers already checked finite and positive; the advice is to lower the speed."""
    limit = max_speed_rpm(geom, on)
    values = np.ravel(np.asarray(speeds_rpm, dtype=float))
    if values.size and values.max() > limit:
        k = int(np.argmax(values))
        pair = geom.pair
        pitch = float(values[k]) * math.pi / 30 * float(geom.reference_radius[0 if on == "pinion" else 1])
        raise GearmeshInputError(f"{field}[{k}]" if values.size > 1 else field, float(values[k]),
                                 f"rpm of the {on} of {pair.name} is a pitch-line velocity of {pitch:.4g} m/s; at "
                                 f"most {limit:.5g} rpm, where the centrifugal hoop stress rho v^2 of the tip circle "
                                 f"reaches {MAX_RIM_STRESS / 1e9:g} GPa, the strength of the strongest steels "
                                 "(gearmesh.limits.MAX_RIM_STRESS): lower the speed")


def check_grid(field: str, value: object, points: int, limit: int, what: str) -> None:
    """Refuse a stage grid of ``points`` (e.g. slices × positions) above ``limit``."""
    if points > limit:
        raise GearmeshInputError(field, value, f"gives {points:.3g} {what}; at most {limit:.3g} "
                                 "(memory, see gearmesh.limits)")


def _count(field: str, value) -> int:
    """``value`` as an integer >= 1 (a grid size), refused naming ``field`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise GearmeshInputError(field, value, "must be an integer >= 1")
    return int(value)


def check_slice_grid(slices, positions) -> tuple[int, int]:
    """``slices`` and ``positions`` of a slice-model run as integers, refused when their product
    exceeds :data:`MAX_STIFFNESS_POINTS`."""
    slices, positions = _count("slices", slices), _count("positions", positions)
    check_grid("slices", slices, slices * positions, MAX_STIFFNESS_POINTS, "slice-positions")
    return slices, positions


def check_contact_grid(positions, points) -> tuple[int, int]:
    """``positions`` and ``points`` of a TCA/LTCA as integers, refused when the (positions + 1) ×
    points candidates per contact line exceed :data:`MAX_CONTACT_POINTS`."""
    positions, points = _count("positions", positions), _count("points", points)
    check_grid("points", points, (positions + 1) * points, MAX_CONTACT_POINTS, "contact candidates per line")
    return positions, points
