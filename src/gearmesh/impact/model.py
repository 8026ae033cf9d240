"""The impact model of a pair: everything the mesh-in impact reuses between torques, speeds and
modifications (:class:`ImpactModel`, :func:`impact_model`: the LTCA model, the engagement point of
the driver, the search window of the pairs already in mesh, the entering pair's line over the face),
with the gears' inertias and the equivalent mass of the mesh-in impact paper.

Everything inside is SI (m, N, s, rad, kg); the event and its conventions: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..choices import DEFAULT_CYCLE_POSITIONS
from ..contact_model import LTCA_CONTACT, ContactModel
from ..errors import GearmeshInputError
from ..gear import PairGeometry
from ..ltca_model import LTCAModel, ContactLaw, contact_law, ltca_model, point_compliance
from ..body import mesh_body_compliance
from ..surface import modification_parameters
from ..separation import SeparationBasis, separation_basis
from ..tca import candidate_grid, engagement_point, pair_lead_slope
from ..contact import hand_sign

SCENARIOS = ("none", "surface", "edge")
SCENARIO_NONE, SCENARIO_SURFACE, SCENARIO_EDGE = 0, 1, 2
DRIVERS = ("pinion", "gear")


# --------------------------------------------------------------------------------------
# Inertia and equivalent mass (the mesh-in impact paper)
# --------------------------------------------------------------------------------------


def impact_paper_inertia(geom: PairGeometry) -> np.ndarray:
    """Polar moments (kg m²) of both gears by the mesh-in impact paper.

    J_i = πρB_i(r_bi⁴ − r_hi⁴)/2 — a solid disc of the base radius r_b over the face width B,
    less the hub bore r_h.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`); its pair must carry a
        ``material`` (density ρ, kg/m³) and a ``bore_radius`` (m), else
        :class:`~gearmesh.errors.GearmeshInputError`.

    Returns
    -------
    numpy.ndarray
        (2,) polar moments [pinion, gear] (kg m²).

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md).
    """
    pair = geom.pair
    if pair.material is None or pair.bore_radius is None:
        raise GearmeshInputError("material" if pair.material is None else "bore_radius_mm", None,
                                 "is required for the gear inertias of the impact model (the mesh-in impact paper's discs)")
    rb, rh, b = geom.base_radius, np.asarray(pair.bore_radius), np.asarray(pair.face_width)
    return math.pi * pair.material.density * b * (rb**4 - rh**4) / 2.0


def equivalent_mass(geom: PairGeometry, inertia) -> float:
    """Equivalent mass m_eq = J1·J2/(J1·r_b2² + J2·r_b1²) (kg) of the mesh-in impact.

    The mass of the relative coordinate r_b1·θ1 + r_b2·θ2 along the transverse line of action
    (the mesh-in impact paper).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (base radii r_b1, r_b2 in m).
    inertia : array_like
        (2,) polar moments [J1, J2] (kg m²), e.g. :func:`impact_paper_inertia`.

    Returns
    -------
    float
        m_eq (kg).

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md).
    """
    j1, j2 = (float(v) for v in inertia)
    rb1, rb2 = (float(v) for v in geom.base_radius)
    return j1 * j2 / (j1 * rb2**2 + j2 * rb1**2)


# --------------------------------------------------------------------------------------
# The load-, speed- and modification-independent model
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ImpactModel:
    """Everything the impact objective reuses between torques, speeds and modifications (SI).

    ``ltca`` the LTCA model (slice tables, pair table, contact law); ``driver`` 'pinion' or
    'gear' and ``sigma`` ±1 (:mod:`gearmesh.impact`); ``roll_engagement`` the roll at which the
    entering corner reaches the end of the active zone it enters by, ``pair_enter`` its
    tooth-pair index, ``z_corner`` that corner. The search window: ``tau`` (R,) time-like
    rolls, ``window`` the other pairs' candidate points at those rolls, flattened
    (:class:`WindowPoints`; the entering pair is column ``window_enter_column`` of the tooth
    pairs ``window_pairs``), ``enter_fine_basis`` (R, Nz) the entering pair on
    ``z_fine`` (Nz,) points over the face. ``points`` the LTCA points per line (the other
    pairs), ``local_points`` / ``local_keep`` / ``local_law`` the entering line's own slicing
    for its local stiffness; ``inertia`` (2,) kg m², ``equivalent_mass`` kg; ``lead_slope`` the
    gears' lead slope deviations (m); ``body_compliance`` the described gear bodies' compliance in
    series with the mesh (m/N, :func:`gearmesh.body.mesh_body_compliance`), in the entering pair's
    force–approach curve as in the LTCA. The mesh misalignment of each torque (the stated f_ma and
    the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`) is added where a
    torque is known (:func:`impact_static`, :func:`ltca_criteria`).
    """

    geom: PairGeometry
    ltca: LTCAModel
    driver: str
    sigma: int
    roll_engagement: float
    pair_enter: int
    z_corner: float
    extension: float
    tau: np.ndarray
    window: "WindowPoints"
    window_enter_column: int
    window_pairs: np.ndarray
    z_fine: np.ndarray
    enter_fine_basis: SeparationBasis
    points: int
    local_points: int
    local_keep: int
    local_law: ContactLaw
    inertia: np.ndarray
    equivalent_mass: float
    lead_slope: tuple[float, float]
    body_compliance: float = 0.0

    def roll(self, tau):
        """Pinion roll (m) of time-like roll ``tau`` (m)."""
        return self.roll_engagement + self.sigma * np.asarray(tau, dtype=float)

    def s_enter(self, tau, z):
        """Line-of-action position (m) of the entering pair's point at axial ``z`` (m)."""
        g = self.geom
        return (self.roll(tau) + self.pair_enter * g.transverse_base_pitch
                + hand_sign(g) * np.asarray(z, dtype=float) * math.tan(g.base_helix_angle))

    def params(self, params=None) -> np.ndarray:
        """Modification parameters as (C, 2, 6) (m); default the pair's own (C = 1)."""
        if params is None:
            return modification_parameters(self.geom)[None]
        p = np.asarray(params, dtype=float)
        if p.ndim == 2:
            p = p[None]
        if p.ndim != 3 or p.shape[1:] != (2, 6) or not np.all(np.isfinite(p)) or np.any(p < 0):
            raise GearmeshInputError("modification", p.shape, "must be finite, non-negative (C, 2, 6) parameters (m)")
        return p

    def lead_slopes(self, lead_slope, rows: int) -> np.ndarray:
        """Lead slope errors as (C, 2) (m over the face width): one [pinion, gear] pair per
        parameter set, default the model's own for every set."""
        if lead_slope is None:
            return np.broadcast_to(np.asarray(self.lead_slope, dtype=float), (rows, 2))
        f = np.asarray(lead_slope, dtype=float)
        if f.ndim == 1:
            f = f[None]
        if f.shape != (rows, 2) or not np.all(np.isfinite(f)):
            raise GearmeshInputError("lead_slope", f.shape, f"must be finite [pinion, gear] pairs, one per parameter "
                                                            f"set ({rows}, 2) (m)")
        return f


@dataclass(frozen=True)
class WindowPoints:
    """The candidate points of the pairs already in mesh at the rolls of the search window,
    flattened to K points in roll order (only real candidates kept): ``roll_index`` (K,) the
    window roll of each point, ``starts`` (R,) the first point of each roll (a roll without
    any point has none: ``counts`` 0), ``basis`` their separation basis, ``z`` (K,) their face
    positions, ``compliance`` (K,) their linear compliance (m/N, the law's linear part added).
    Everything here is independent of the modification, the lead slope and the load."""

    roll_index: np.ndarray
    starts: np.ndarray
    counts: np.ndarray
    basis: SeparationBasis
    z: np.ndarray
    compliance: np.ndarray

    def per_roll_sum(self, values: np.ndarray) -> np.ndarray:
        """Sum of ``values`` (..., K) over the points of each roll: (..., R)."""
        out = np.zeros(values.shape[:-1] + self.counts.shape)
        some = self.counts > 0
        if some.any():
            out[..., some] = np.add.reduceat(values, self.starts[some], axis=-1)
        return out


def _window_points(basis: SeparationBasis, z: np.ndarray, compliance: np.ndarray) -> WindowPoints:
    """:class:`WindowPoints` of the (R, J, N) window arrays (non-candidates dropped)."""
    keep = np.isfinite(basis.base)
    r = basis.base.shape[0]
    roll_index = np.nonzero(keep)[0]
    counts = keep.reshape(r, -1).sum(axis=1)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.intp)
    flat = SeparationBasis(*(getattr(basis, f)[keep] for f in SeparationBasis.__dataclass_fields__))
    return WindowPoints(roll_index=roll_index, starts=starts, counts=counts, basis=flat, z=np.asarray(z)[keep],
                        compliance=compliance[keep])


def _engagement(geom: PairGeometry, driver: str) -> tuple[float, int, float]:
    """(roll, pair index, corner z) at which the entering pair's leading corner reaches the end
    of the active zone it enters by: A (s = 0) with the pinion driving, E (s = g_α) with the
    gear driving (roll in [0, p_bt))."""
    if driver == "pinion":
        return engagement_point(geom)
    pbt = geom.transverse_base_pitch
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    # the corner with the smallest s, z = −h·b/2, reaches s = g_α
    roll_e = (geom.path_of_contact + half_axial) % pbt
    if roll_e >= pbt * (1 - 1e-12):
        roll_e = 0.0
    j_e = int(round((geom.path_of_contact + half_axial - roll_e) / pbt))
    z_e = -hand_sign(geom) * 0.5 * geom.face_width if half_axial > 0 else 0.0
    return float(roll_e), j_e, float(z_e)


def impact_model(geom: PairGeometry, contact: ContactModel = LTCA_CONTACT, lead_slope=None, driver: str = "pinion",
                 added_inertia_kg_m2=(0.0, 0.0), window_positions: int = 32, face_samples: int = 257,
                 cycle_positions: int = DEFAULT_CYCLE_POSITIONS, local_points: int = 400, local_keep: int = 400,
                 ltca: LTCAModel | None = None) -> ImpactModel:
    """Prepare the impact objective of ``geom`` (its modification is only the default).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`); SI throughout.
    contact : ContactModel, default :data:`gearmesh.contact_model.LTCA_CONTACT`
        The LTCA's contact model (:class:`gearmesh.contact_model.ContactModel`): points per contact line (the
        other pairs, the local stiffness), local contact law, tooth model, and the reach of the tip-edge candidates
        beyond the active zone (fraction of p_bt, -) that also opens the search window.
    lead_slope : array_like or None
        Lead slope deviations [pinion, gear] (m over the face width); None: the pair's own.
    cycle_positions : int
        Rolls per mesh cycle of the LTCA grid.
    driver : {'pinion', 'gear'}
        The driving gear (:mod:`gearmesh.impact`).
    added_inertia_kg_m2 : (2,) array_like
        Inertia (kg m²) of what hangs on each shaft [pinion, gear], added to the mesh-in impact paper's discs.
    window_positions, face_samples : int
        Grid rolls over the search window (−extension … +1 p_bt); samples of the entering line over the face (min_z).
    local_points, local_keep : int
        Slices of the entering line for its local stiffness, and how many (closest to contact) are loaded: an edge
        contact's F–δ curve spreads along the line and converges only with hundreds (test_convergence_in_local_slices).
    ltca : LTCAModel or None
        A prepared LTCA model (its grid is the one :func:`ltca_criteria` uses); None: built here.

    Returns
    -------
    ImpactModel
        ``tau`` (R,) window rolls (m), ``inertia`` (2,) kg m², ``equivalent_mass`` (kg), ``body_compliance`` (m/N), ...
    """
    if driver not in DRIVERS:
        raise GearmeshInputError("driver", driver, f"must be one of {list(DRIVERS)}")
    added = np.asarray(added_inertia_kg_m2, dtype=float)
    if added.shape != (2,) or not np.all(np.isfinite(added)) or np.any(added < 0):
        raise GearmeshInputError("added_inertia_kg_m2", list(np.atleast_1d(added)),
                                 "must be two finite, non-negative inertias [pinion, gear] (kg m²)")
    for name, value, low, high in (("window_positions", window_positions, 8, 10000),
                                   ("face_samples", face_samples, 9, 100000), ("local_points", local_points, 2, 100000),
                                   ("local_keep", local_keep, 2, 100000)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
            raise GearmeshInputError(name, value, f"must be an integer in [{low}, {high}]")
    lead_slope = pair_lead_slope(geom, lead_slope)
    if ltca is None:
        ltca = ltca_model(geom, positions=cycle_positions, contact=contact, lead_slope=lead_slope)
    inertia = impact_paper_inertia(geom) + added
    pbt = geom.transverse_base_pitch
    points, extension = contact.points, contact.extension
    ext = extension * pbt
    sigma = 1 if driver == "pinion" else -1
    roll_e, j_e, z_c = _engagement(geom, driver)
    # window: from the outer end of the entering corner's tip-edge candidates to one base pitch in
    tau = np.linspace(-ext, pbt, int(window_positions))
    tau = np.unique(np.append(tau, 0.0))
    roll = roll_e + sigma * tau
    grid = candidate_grid(geom, roll, points, tuple(lead_slope), extension)
    col = np.flatnonzero(grid.pairs == j_e)
    if col.size == 0:
        raise RuntimeError("the entering tooth pair is not among the candidate pairs of the window")
    col = int(col[0])
    compliance = point_compliance(geom, ltca.pair_table, ltca.tables, grid.s, grid.region, grid.rho_pinion,
                                  grid.rho_gear, with_hertz=ltca.law.name == "linear") / grid.dz + ltca.law.linear
    # the pairs already in mesh, flattened to their candidate points
    window = _window_points(_without_column(grid.basis, col), np.broadcast_to(grid.z, grid.s.shape), compliance)
    z_fine = np.linspace(-0.5 * geom.face_width, 0.5 * geom.face_width, int(face_samples))
    s_fine = (roll[:, None] + j_e * pbt + hand_sign(geom) * z_fine[None, :] * math.tan(geom.base_helix_angle))
    fine = separation_basis(geom, s_fine, np.inf)
    return ImpactModel(geom=geom, ltca=ltca, driver=driver, sigma=sigma, roll_engagement=roll_e, pair_enter=j_e,
                       z_corner=z_c, extension=ext, tau=tau, window=window, window_enter_column=col, window_pairs=np.asarray(grid.pairs),
                       z_fine=z_fine, enter_fine_basis=fine, points=int(points), local_points=int(local_points),
                       local_keep=int(local_keep),
                       local_law=contact_law(geom, geom.face_width / local_points, ltca.law.name) if ltca.law.name != "linear"
                       else ContactLaw("linear", 0.0, 1.0, 0.0, geom.face_width / local_points), inertia=inertia,
                       equivalent_mass=equivalent_mass(geom, inertia), lead_slope=lead_slope,
                       body_compliance=mesh_body_compliance(geom))


def _without_column(basis: SeparationBasis, column: int) -> SeparationBasis:
    """``basis`` (..., J, N) with tooth pair ``column`` made a non-candidate (the entering pair)."""
    base = np.array(basis.base)
    base[..., column, :] = np.nan
    return replace(basis, base=base)
