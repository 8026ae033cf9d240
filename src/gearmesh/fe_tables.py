"""The finite-element tooth's slice compliance tables (:mod:`gearmesh.fe`) as the stiffness
stage, the LTCA, the impact and the dynamics use them (``method='fe'``): an in-process cache
of each gear's FE tooth compliance keyed by its section data and settings, seeded from the
pair's ``fe_compliance.nc`` in the workflow, and the :class:`gearmesh.tooth.SliceComplianceTable`
built from it. SI: roll lengths in m, compliances per unit width in m²/N.
"""

from __future__ import annotations

import json

import numpy as np

from .errors import GearmeshInputError
from .fe import DEFAULT_NEIGHBOURS, DEFAULT_ROLL_NODES, DEFAULT_SIZE, ToothCompliance, tooth_compliance
from .fe_elastic import DEFAULT_PLANE
from .gear import GEARS, PairGeometry
from .pairfile import pair_to_dict
from .tooth import SliceComplianceTable, tooth_model

__all__ = ["fe_tooth_compliance_cached", "seed_cache", "use_fe_tables", "fe_slice_compliance_table", "compliance_table"]


#: pair-file keys the transverse section does not depend on (a renamed variant, another face
#: width or hand shares the mesh); modifications are not in pair_to_dict (they are gaps, not shape)
_NOT_IN_SECTION = ("name", "face_width_mm", "helix_hand")


def _cache_key(geom: PairGeometry, gear: int, settings: tuple) -> str:
    """Everything the FE table depends on: the pair's section data (profile, shifts, bore,
    material) and the settings."""
    data = {k: v for k, v in pair_to_dict(geom.pair).items() if k not in _NOT_IN_SECTION}
    data["profile_shift"] = [float(x) for x in geom.profile_shift]  # as resolved (centre distance)
    return json.dumps([data, gear, settings], sort_keys=True, default=str)


_CACHE: dict[str, ToothCompliance] = {}
_CACHE_SIZE = 32


def fe_tooth_compliance_cached(geom: PairGeometry, gear: int, n_roll: int = DEFAULT_ROLL_NODES,
                               plane: str = DEFAULT_PLANE, size: float = DEFAULT_SIZE,
                               neighbours: int | None = DEFAULT_NEIGHBOURS) -> ToothCompliance:
    """:func:`gearmesh.fe.tooth_compliance` at ``n_roll`` equally spaced roll lengths over [ρ_SAP, ρ_EAP],
    kept in an in-process LRU cache keyed by the pair data and the settings, so that the
    stages of one process (stiffness, LTCA, impact, the GA's candidates of one pair) mesh
    and solve each gear once.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    n_roll : int
        Roll-length nodes (≥ 4; default :data:`gearmesh.fe.DEFAULT_ROLL_NODES`, 17).
    plane : {'strain', 'stress'}
        Plane state (default 'strain').
    size : float
        Element edge on the loaded tooth in normal modules (default 0.05).
    neighbours : int or None
        Teeth modelled each side of the loaded one (default None: the whole gear).

    Returns
    -------
    ToothCompliance
        ``rho`` (m) and the compliances ``total``, ``tooth``, ``body`` (m²/N) at it.
    """
    if int(n_roll) != n_roll or n_roll < 4:
        raise GearmeshInputError("n_roll", n_roll, "must be a whole number >= 4 (cubic spline)")
    settings = (int(n_roll), plane, float(size), neighbours)
    key = _cache_key(geom, gear, settings)
    rho = np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], int(n_roll))
    hit = _CACHE.get(key)
    if hit is None:
        hit = tooth_compliance(geom, gear, rho, plane, size, neighbours)
        if len(_CACHE) >= _CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))  # oldest first
        _CACHE[key] = hit
    return hit


def seed_cache(ds, geom: PairGeometry) -> None:
    """Put the FE tooth compliances of a ``fe_compliance.nc`` (rule ``fe_compliance``,
    :func:`gearmesh.datasets.fe.fe_compliance_dataset` of the same pair) into the in-process
    cache under the settings they were computed with, so a stage of the same pair with the
    same settings reads them instead of meshing again: the table is computed once per gear
    geometry in the workflow, and every stage using ``method: fe`` takes it from the file.

    Parameters
    ----------
    ds : xarray.Dataset
        The pair's ``fe_compliance.nc`` (roll in m, compliances in m²/N, per gear).
    geom : PairGeometry
        The pair's geometry; its roll nodes must be those of ``ds`` (else
        :class:`gearmesh.errors.GearmeshInputError`).

    Returns
    -------
    None
    """
    settings = (int(ds.attrs["roll_nodes"]), str(ds.attrs["plane"]), float(ds.attrs["size_normal_modules"]),
                DEFAULT_NEIGHBOURS)
    for gear, name in enumerate(GEARS):
        def var(key):
            return np.asarray(ds[key].values[gear], dtype=float)

        rho = var("roll")
        if not np.allclose(rho, np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], settings[0]), rtol=0, atol=1e-12):
            raise GearmeshInputError("fe_compliance", ds.attrs.get("pair_name", ""),
                                     f"was computed for another {name} geometry than this pair's")
        total = var("fe_compliance")
        _CACHE[_cache_key(geom, gear, settings)] = ToothCompliance(
            rho=rho, total=total, body=var("fe_body"), tooth=var("fe_tooth"), total_left=total,
            wind_up=var("fe_wind_up"), ring_shift=var("fe_ring_shift"), local=var("fe_local"),
            wind_up_radius=float("nan"), load_angle=var("load_angle"), plane=settings[1], size=settings[2],
            neighbours=DEFAULT_NEIGHBOURS, n_elements=int(ds.attrs.get(f"{name}_elements", 0)),
            n_dofs=int(ds.attrs.get(f"{name}_dofs", 0)))


def use_fe_tables(ds, geom: PairGeometry) -> None:
    """:func:`seed_cache` when a stage was handed its pair's ``fe_compliance.nc`` (else nothing).

    Parameters
    ----------
    ds : xarray.Dataset or None
        The pair's ``fe_compliance.nc``, or None.
    geom : PairGeometry
        The pair's geometry.

    Returns
    -------
    None
    """
    if ds is not None:
        seed_cache(ds, geom)


def fe_slice_compliance_table(geom: PairGeometry, gear: int, n_roll: int = DEFAULT_ROLL_NODES,
                              plane: str = DEFAULT_PLANE, size: float = DEFAULT_SIZE,
                              neighbours: int | None = DEFAULT_NEIGHBOURS, profile=None):
    """The :class:`gearmesh.tooth.SliceComplianceTable` of ``method='fe'`` (the same
    object the potential-energy methods build, so the stiffness stage, the LTCA, the impact
    and the dynamics use it unchanged).

    Components: 'bending' the tooth's own deflection (bending + shear + axial of the 2-D
    continuum), 'fillet' the body part (root-section rigid motion), 'shear' and 'axial'
    zero (:mod:`gearmesh.fe`, "Split of c_FE"); cubic splines over ``n_roll`` FE roll positions.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    n_roll : int
        Roll-length nodes of the FE solution (≥ 4; default 17).
    plane : {'strain', 'stress'}
        Plane state (default 'strain').
    size : float
        Element edge on the loaded tooth in normal modules (default 0.05).
    neighbours : int or None
        Teeth modelled each side of the loaded one (default None: the whole gear).
    profile : optional
        The gear's tooth profile (:func:`gearmesh.profile.tooth_profile`) for the table's
        tooth model (default: generated).

    Returns
    -------
    SliceComplianceTable
        Method 'fe': ``rho`` (m), components (m²/N) at the FE roll nodes.
    """
    res = fe_tooth_compliance_cached(geom, gear, n_roll, plane, size, neighbours)
    return compliance_table(geom, gear, res.rho, res.tooth, res.body, res.load_angle, profile)


def compliance_table(geom: PairGeometry, gear: int, rho: np.ndarray, tooth: np.ndarray, body: np.ndarray,
                     load_angle: np.ndarray, profile=None):
    """A :class:`gearmesh.tooth.SliceComplianceTable` (method 'fe') of a tooth compliance
    per unit width (m²/N) given at roll lengths ``rho`` (m): ``tooth`` as 'bending', ``body``
    as 'fillet', 'shear' and 'axial' zero; cubic splines.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    rho : ndarray
        (n,) roll lengths (m), increasing.
    tooth, body : ndarray
        (n,) tooth and body (fillet-foundation) compliance per unit width (m²/N).
    load_angle : ndarray
        (n,) load angle α1 (rad).
    profile : optional
        The gear's tooth profile for the table's tooth model (default: generated).

    Returns
    -------
    SliceComplianceTable
        Method 'fe', callable at roll lengths (m) giving m²/N.
    """
    from scipy.interpolate import CubicSpline

    zero = np.zeros_like(rho)
    values = {"bending": np.asarray(tooth, float), "shear": zero, "axial": zero.copy(), "fillet": np.asarray(body, float)}
    splines = {k: CubicSpline(rho, v) for k, v in values.items()}
    return SliceComplianceTable(gear=gear, method="fe", model=tooth_model(geom, gear, "transition", profile),
                                rho=rho, values=values, load_angle=load_angle, _splines=splines)
