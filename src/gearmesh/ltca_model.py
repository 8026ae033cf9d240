"""The load-independent model of the LTCA (:mod:`gearmesh.ltca`): the local contact law of a
point, and the candidate points of a pair with their unloaded separations and linear
compliances (the slice compliance of both teeth, :mod:`gearmesh.slice_compliance`). The
LTCA solves it at each load; the mesh-in impact and the mesh force take the same model.

Everything inside is SI (m, N, rad), in the transverse line-of-action convention of
:mod:`gearmesh.ltca` (its module docstring: the model of independent slices).

Local contact laws (``contact_law``)
-----------------------------------
* ``'palmgren'`` (default): Palmgren's line-contact approach of two steel bodies,
  δ_n = 3.84·10⁻⁵ Q^0.9 / l^0.8 (mm, N, mm; Palmgren, Ball and Roller Bearing
  Engineering, 1959; Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., 2007, eq.
  6.41). With Q = w·l it is δ_n = 3.84·10⁻⁵ w^0.9 l^0.1 (w in N/mm); the weak length
  factor is taken at the full contact-line length l_ref = b/cos βb so that the law is
  local (independent of how finely the line is sliced). For another material the load is
  scaled by E'_steel/E' (E' = E/(1 − ν²), steel 207 GPa, 0.3). It gives F ∝ δ^(1/0.9),
  n ≈ 1.11 — the exponent the mesh-in impact paper reports for the fitted local stiffness (n ≈ 1.1).
* ``'linear'``: the linear Hertz line-contact stiffness per unit length πE/(4(1−ν²)) of
  the stiffness stage (:func:`gearmesh.slice_compliance.hertz_compliance_transverse`),
  for the comparison LTE = F/K(φ).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .contact import mesh_cycle_rolls
from .choices import CONTACT_LAWS, DEFAULT_CONTACT_LAW
from .contact_model import LTCA_CONTACT, ContactModel
from .errors import GearmeshInputError
from .supports import PALMGREN_LINE, PALMGREN_LINE_EXPONENT
from .gear import PairGeometry
from .slice_compliance import (PairSliceTable, hertz_compliance_transverse, pair_slice_table,
                               slice_compliance_table)
from .tooth import SliceComplianceTable, require_stiffness_data
from .separation import REGION_APPROACH_TIP, REGION_RECESS_TIP
from .tca import (CandidateGrid, check_count, candidate_grid, check_modifications, engagement_point, pair_lead_slope)

__all__ = ["CONTACT_LAWS", "PALMGREN_COEFFICIENT", "PALMGREN_EXPONENT", "ContactLaw", "contact_law",
           "point_compliance", "LTCAModel", "ltca_model"]

# Palmgren's line-contact law (Palmgren 1959; Harris & Kotzalas 2007), mm·N^-0.9·mm^0.8: declared
# once, with the rolling bearings that use it too (gearmesh.supports, the lowest module).
PALMGREN_COEFFICIENT = PALMGREN_LINE
PALMGREN_EXPONENT = PALMGREN_LINE_EXPONENT
_STEEL_E_PRIME = 207e9 / (1.0 - 0.3**2)


@dataclass(frozen=True)
class ContactLaw:
    """Local contact approach of one point of width ``dz`` (m): δ_c(q) = coefficient·q^exponent
    (m, q in N, transverse), plus a linear compliance ``linear`` (m/N) added to the teeth."""

    name: str
    coefficient: float
    exponent: float
    linear: float
    dz: float

    @property
    def force_exponent(self) -> float:
        """n of F ∝ δ^n for the contact alone (1/exponent; 1 for the linear law)."""
        return 1.0 / self.exponent if self.coefficient > 0 else 1.0


def contact_law(geom: PairGeometry, dz: float, name: str = DEFAULT_CONTACT_LAW) -> ContactLaw:
    """The local contact law of a point of width ``dz`` (m) in transverse units (module docstring).

    Palmgren [1]_, [2]_: δ_n [mm] = 3.84e-5·(w·E'_steel/E')^0.9·l_ref^0.1 with w = q/Δz the normal load
    per unit length (N/mm) and l_ref = b/cos βb (mm); transverse δ_t = δ_n/cos βb.
    Linear: δ_t = c_h·q/Δz, c_h of :func:`gearmesh.slice_compliance.hertz_compliance_transverse`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`), with its material.
    dz : float
        Width of the point (slice) along the face, m.
    name : {'palmgren', 'linear'}, default 'palmgren'
        The law (:data:`gearmesh.choices.CONTACT_LAWS`).

    Returns
    -------
    ContactLaw
        δ_c(q) = ``coefficient``·q^``exponent`` (m, q in N, transverse) and the linear compliance
        ``linear`` (m/N) added to the teeth; ``dz`` (m).

    Raises
    ------
    GearmeshInputError
        ``contact_law`` not one of the laws, or the pair lacks the stiffness data.

    References
    ----------
    .. [1] Palmgren A., Ball and Roller Bearing Engineering, 3rd ed., SKF Industries, Philadelphia,
       1959.
    .. [2] Harris T.A., Kotzalas M.N., Rolling Bearing Analysis, 5th ed., CRC Press, Boca Raton, 2007,
       eq. 6.41.
    """
    if name not in CONTACT_LAWS:
        raise GearmeshInputError("contact_law", name, f"must be one of {list(CONTACT_LAWS)}")
    require_stiffness_data(geom, need_bore=False)
    if name == "linear":
        return ContactLaw(name, 0.0, 1.0, hertz_compliance_transverse(geom) / dz, dz)
    mat = geom.pair.material
    cb = math.cos(geom.base_helix_angle)
    scale = _STEEL_E_PRIME / (mat.youngs_modulus / (1.0 - mat.poisson_ratio**2))
    l_ref_mm = geom.face_width / cb * 1e3
    # δ_t [m] = 1e-3/cb · C · (q·scale/(Δz·1e3))^0.9 · l_ref_mm^0.1
    coef = 1e-3 / cb * PALMGREN_COEFFICIENT * (scale / (dz * 1e3)) ** PALMGREN_EXPONENT * l_ref_mm**0.1
    return ContactLaw(name, coef, PALMGREN_EXPONENT, 0.0, dz)


# --------------------------------------------------------------------------------------
# Model set-up (everything that does not depend on the load)
# --------------------------------------------------------------------------------------


def point_compliance(geom: PairGeometry, pair_table: PairSliceTable,
                     tables: tuple[SliceComplianceTable, SliceComplianceTable], s, region, rho_pinion, rho_gear,
                     with_hertz: bool = False) -> np.ndarray:
    """Per-unit-width compliance (m²/N: m of transverse deflection per N/m of load) of candidate
    points at line-of-action positions ``s`` (m) of ``region`` (arrays of one shape).

    Flank points take the pair table at s by linear interpolation, exactly as the stiffness
    stage (:func:`gearmesh.stiffness.mesh_stiffness`); tip-edge points take each tooth's
    table at its own touched roll length (the tip of one, ρ_P of the other). Bending,
    shear, axial compression and fillet foundation of both teeth; with ``with_hertz`` the
    linear Hertz line-contact compliance as well (the stiffness stage's slice sum).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    pair_table : PairSliceTable
        Both teeth's compliances along the path of contact
        (:func:`gearmesh.slice_compliance.pair_slice_table`).
    tables : tuple of SliceComplianceTable
        (pinion, gear) per-tooth compliance tables against roll length, for tip-edge points.
    s : array_like
        Positions along the transverse line of action from A, m.
    region : array_like of int
        Region of each point (:data:`gearmesh.separation.REGION_FLANK`, tip edges
        :data:`gearmesh.separation.REGION_APPROACH_TIP`, :data:`gearmesh.separation.REGION_RECESS_TIP`),
        shaped like ``s``.
    rho_pinion, rho_gear : array_like
        Touched roll lengths (radii of curvature) on pinion and gear, m, shaped like ``s``.
    with_hertz : bool, default False
        Add the linear Hertz line-contact compliance.

    Returns
    -------
    numpy.ndarray
        Compliance per unit face width, m²/N, shaped like ``s``.
    """
    s = np.clip(np.nan_to_num(np.asarray(s, dtype=float)), 0.0, geom.path_of_contact)
    n_int = pair_table.total.size - 1
    t = s * (1.0 / pair_table.ds)
    i = np.minimum(t.astype(np.intp), n_int - 1)
    w = t - i
    if with_hertz:
        per_width = np.take(pair_table.total, i) + w * np.take(pair_table.total_slope, i)
    else:
        tooth_rows = [k for k, name in enumerate(pair_table.columns) if name != "hertz"]
        vals = pair_table.values[tooth_rows].sum(axis=0)
        per_width = np.take(vals, i) + w * np.take(np.diff(vals), i)
    edge = (region == REGION_APPROACH_TIP) | (region == REGION_RECESS_TIP)
    if np.any(edge):
        rho1 = np.clip(rho_pinion[edge], tables[0].rho[0], tables[0].rho[-1])
        rho2 = np.clip(rho_gear[edge], tables[1].rho[0], tables[1].rho[-1])
        c_edge = tables[0].total(rho1) + tables[1].total(rho2)
        if with_hertz:
            c_edge = c_edge + hertz_compliance_transverse(geom)
        per_width = np.array(per_width)
        per_width[edge] = c_edge
    return per_width


@dataclass(frozen=True)
class LTCAModel:
    """The load-independent part of an LTCA: per-gear slice tables and their pair table, grid of
    points (incl. the start of engagement as the last position), compliances and the contact law."""

    geom: PairGeometry
    grid: CandidateGrid  # positions = mesh cycle + [roll_A]
    compliance: np.ndarray  # (P+1, J, N) linear compliance of each point (m/N)
    law: ContactLaw
    method: str
    pair_table: PairSliceTable
    lead_slope: tuple[float, float]
    tables: tuple[SliceComplianceTable, SliceComplianceTable]
    misalignment: float = 0.0  # the stated mesh misalignment f_ma in the grid's separations (m)


def ltca_model(geom: PairGeometry, positions: int = 64, contact: ContactModel = LTCA_CONTACT, lead_slope=None,
               tables: tuple[SliceComplianceTable, SliceComplianceTable] | None = None,
               n_nodes: int = 257) -> LTCAModel:
    """Grid, separations and point compliances (the model of :mod:`gearmesh.ltca`) for :func:`gearmesh.ltca.ltca`.

    Flank points (region 1) take the stiffness stage's pair table at their s, exactly as
    :func:`gearmesh.stiffness.mesh_stiffness` interpolates it; tip-edge points take each
    tooth's table at its own touched roll length (the tip of the one, ρ_P of the other,
    both within the active flank). The grid's separations carry the pair's stated mesh
    misalignment too (the load-dependent f_sh is added per torque by :func:`gearmesh.ltca.ltca`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its modifications (:func:`gearmesh.gear.pair_geometry`).
    positions : int, default 64
        Mesh positions over one mesh cycle (the start of engagement is appended as a last one).
    contact : ContactModel, default :data:`gearmesh.contact_model.LTCA_CONTACT`
        Candidate points per contact line, local contact law (:func:`contact_law`), tooth model of
        the slice compliance and reach of the tip-edge candidates beyond the active zone
        (:class:`gearmesh.contact_model.ContactModel`).
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width; None: the pair's own
        deviations (:func:`gearmesh.tca.pair_lead_slope`).
    tables : tuple of SliceComplianceTable, optional
        Per-gear :class:`~gearmesh.tooth.SliceComplianceTable` to reuse (same tooth model).
    n_nodes : int, default 257
        Nodes of each slice compliance table when ``tables`` is None.

    Returns
    -------
    LTCAModel
        ``grid`` (:class:`gearmesh.tca.CandidateGrid`, positions + 1), ``compliance`` (P+1, J, N) m/N,
        ``law``, ``method``, ``pair_table``, ``lead_slope`` (m), ``tables``, ``misalignment`` f_ma (m).

    Raises
    ------
    GearmeshInputError
        Modifications or ``positions`` out of range, or no stiffness data.
    """
    check_modifications(geom)
    require_stiffness_data(geom)
    positions = check_count("positions", positions, 1, 100000)
    points, method, law_name = contact.points, contact.method, contact.contact_law
    if tables is None:
        tables = (slice_compliance_table(geom, 0, method, n_nodes), slice_compliance_table(geom, 1, method, n_nodes))
    pair_table = pair_slice_table(geom, tables)
    roll_a = engagement_point(geom)[0]
    roll = np.append(mesh_cycle_rolls(geom, positions), roll_a)
    lead_slope = pair_lead_slope(geom, lead_slope)
    mis = geom.pair.deviations.misalignment
    grid = candidate_grid(geom, roll, points, lead_slope, contact.extension, misalignment=mis)
    law = contact_law(geom, grid.dz, law_name)
    if law_name == "linear":  # the Hertz part sits in the tooth compliance, as the stiffness stage
        law = ContactLaw("linear", 0.0, 1.0, 0.0, grid.dz)
    per_width = point_compliance(geom, pair_table, tables, grid.s, grid.region, grid.rho_pinion, grid.rho_gear,
                                 with_hertz=law_name == "linear")
    compliance = per_width / grid.dz
    return LTCAModel(geom=geom, grid=grid, compliance=compliance, law=law, method=method, pair_table=pair_table,
                     lead_slope=lead_slope, tables=tables, misalignment=mis)
