"""The nominal load of a torque on a pair and its limits (ISO 6336-2 contact stress, mesh
deflection): the entry check of every stage that loads the mesh (GearmeshInputError).

The limits themselves (:data:`gearmesh.limits.MAX_CONTACT_STRESS`,
:data:`gearmesh.limits.MAX_DEFLECTION_TO_MODULE`) live with every other limit in
:mod:`gearmesh.limits`; this module needs the ISO 6336-1 stiffness of
:mod:`gearmesh.stiffness`, which :mod:`gearmesh.limits` must not import (the pair data take
their limits from it).
"""

from __future__ import annotations

import math

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry
from .limits import ISO6336_STEEL_MODULUS, MAX_CONTACT_STRESS, MAX_DEFLECTION_TO_MODULE
from .stiffness import iso6336_stiffness


def nominal_load(geom: PairGeometry, pinion_torque: float) -> dict[str, float]:
    """Nominal contact stress σ_H0 (Pa, ISO 6336-2 method B) and mesh deflection (m) of a
    pinion torque (N m).

    σ_H0 = Z_H Z_E Z_ε √(F_t (u + 1)/(d1 b u)), with F_t = 2 T1/d1, Z_H = √(2 cos βb cos αwt /
    (cos² αt sin αwt)), Z_E = √(E/(2π(1 − ν²))) for two gears of one material (steel when the
    pair has none) and Z_ε of ISO 6336-2 eq. (8)–(10); Z_β ≈ 1 is left out (it lies within
    ±7 % for β < 30°; the limit is coarse). Deflection δ = F_bt/(c_γα b) with c_γα b from
    ISO 6336-1 (:func:`gearmesh.stiffness.iso6336_stiffness`, which scales it by E/206 GPa).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    pinion_torque : float
        Pinion torque T1 (N m).

    Returns
    -------
    dict of str to float
        ``contact_stress``: nominal contact stress σ_H0 (Pa); ``deflection``: mesh deflection δ (m).

    References
    ----------
    .. [1] ISO 6336-2:2019, Calculation of load capacity of spur and helical gears — Part 2:
       Calculation of surface durability (pitting), method B, eqs. (8)–(10) (Z_ε).
    .. [2] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1: Basic
       principles, introduction and general influence factors, clause 9 (mesh stiffness c_γα).
    """
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
    stiffness = iso6336_stiffness(geom)["K_gamma_alpha"]  # already scaled by E/E_st (ISO 6336-1 9.3.1)
    deflection = pinion_torque / float(geom.base_radius[0]) / stiffness
    return {"contact_stress": sigma, "deflection": deflection}


def check_load(geom: PairGeometry, pinion_torque: float, field: str, value: object) -> None:
    """Refuse a pinion torque (N m) whose nominal contact stress exceeds
    :data:`MAX_CONTACT_STRESS` or whose deflection exceeds :data:`MAX_DEFLECTION_TO_MODULE`
    normal modules (:func:`nominal_load`); ``field`` and ``value`` are what the user gave.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    pinion_torque : float
        Pinion torque T1 (N m).
    field : str
        The field the torque came from, as the error names it.
    value : object
        The value as the user gave it.

    Raises
    ------
    GearmeshInputError
        Naming ``field`` and ``value``, when the nominal contact stress exceeds
        :data:`MAX_CONTACT_STRESS` or the mesh deflection exceeds :data:`MAX_DEFLECTION_TO_MODULE` m_n.
    """
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
    gave them (same order), named ``field[k]`` when there are several.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    pinion_torques : array_like
        Pinion torques T1 (N m), any shape.
    field : str
        The field the torques came from.
    given : array_like
        The values as the user gave them, in the order of ``pinion_torques``.

    Raises
    ------
    GearmeshInputError
        Naming ``field[k]`` (or ``field`` for a single torque) for the first torque
        :func:`check_load` refuses.
    """
    values = np.ravel(given).tolist()
    for k, (t1, value) in enumerate(zip(np.ravel(pinion_torques), values)):
        check_load(geom, float(t1), f"{field}[{k}]" if len(values) > 1 else field, value)
