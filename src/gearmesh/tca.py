"""Unloaded tooth contact analysis (TCA) of a modified helical pair.

Everything inside is SI (m, rad). Frames and the line of action are those of
:mod:`gearmesh.contact`: the pinion centre at the origin, the gear centre at (a, 0), the
transverse line of action from T1 = r_b1(cos αwt, −sin αwt) along d = (sin αwt, cos αwt);
``s`` is the distance along it from the start of active profile A; tooth pair j in the
transverse slice z touches (if it can) at s = roll + j·p_bt + h·z·tan βb.

The displacement direction (one convention for TCA, LTCA, stiffness and impact)
---------------------------------------------------------------------------------
Every separation ("gap"), every transmission error and every approach is a **transverse
displacement along the line of action, r_b1·Δφ1 with the gear held** — the convention of
:mod:`gearmesh.stiffness` (δ_t = r_b1Δφ1 + r_b2Δφ2, F_bt = T1/r_b1), so an LTE can be set
beside F/K(φ). A depth δ_n removed along a flank normal opens a transverse gap δ_n/cos βb
(:mod:`gearmesh.separation`). A lead slope error (fHβ-type) is taken as ISO 1328-1 measures
helix deviations, in the transverse plane along the base tangent, so it adds to the transverse
gap unchanged.

Positive TE means the gear lags its conjugate position (the pinion has to turn further by
TE/r_b1 before the flanks touch); as a gear angle it is TE/r_b2, and the mesh-in impact paper's
θ_TE = φ2 − (N1/N2)φ1 equals −TE/r_b2 with φ2 counted in the gear's direction of travel.

Candidate points
----------------
The points of a contact line are the centres z_k of N equal transverse slices over the
face (the 'centre' rule of :func:`gearmesh.stiffness.slice_samples`: the same points, bit
for bit, as :func:`gearmesh.contact.contact_roll_positions`). A point is a candidate when
its s lies within the active zone [0, g_α] (flank-to-flank, region 1) or up to
``extension`` beyond it, where load can bring a tip corner into contact before SAP or
after EAP (the mesh-in impact paper, scenario 1):

* region 2, s < 0 (approach): the gear's tip edge, not yet at the start of the path of
  contact A, against the pinion flank;
* region 3, s > g_α (recess): the pinion's tip edge, past the end of the path E, against
  the gear flank.

Their separations, the exact 2-D distances of the tip edges from the mating flanks, are
:mod:`gearmesh.separation`'s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .contact import hand_sign, mesh_cycle_rolls
from .choices import DEFAULT_CORNER_EXTENSION
from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
from .separation import SeparationBasis, basis_gap, flank_separation, separation_basis

__all__ = [
    "CandidateGrid", "TCAResult", "check_modifications", "check_extension", "point_centres", "pair_lead_slope",
    "candidate_grid", "engagement_point", "engagement_separation", "tca",
]

#: Default reach of the candidate points beyond the active zone, as a fraction of p_bt.
DEFAULT_EXTENSION = DEFAULT_CORNER_EXTENSION


# --------------------------------------------------------------------------------------
# Input checks
# --------------------------------------------------------------------------------------


_MOD_FIELDS = (("root_relief", "root_relief_um", 1e6), ("tip_relief", "tip_relief_um", 1e6),
               ("root_relief_length", "root_relief_length_mm", 1e3),
               ("tip_relief_length", "tip_relief_length_mm", 1e3), ("crowning", "crowning_um", 1e6),
               ("unmodified_lead_length", "unmodified_lead_length_mm", 1e3))


def check_modifications(pair_or_geom) -> None:
    """Refuse non-finite or negative modification parameters (also for pairs built in code).

    Lengths against the flank and the face are checked by :func:`gearmesh.gear.validate_modifications`
    (run by ``pair_geometry``); this adds the sign and finiteness, naming the pair-file key
    (GearmeshInputError).

    Parameters
    ----------
    pair_or_geom : GearPair or PairGeometry
        The pair (or its geometry) whose ``modification`` [pinion, gear] is checked.

    Raises
    ------
    GearmeshInputError
        Not one modification per gear, or a parameter not finite or negative.
    """
    pair = getattr(pair_or_geom, "pair", pair_or_geom)
    mods = getattr(pair, "modification", None)
    if not isinstance(mods, (tuple, list)) or len(mods) != 2:
        raise GearmeshInputError("modification", mods, "must hold one modification per gear [pinion, gear]")
    for gear, mod in zip(GEARS, mods):
        for attr, key, scale in _MOD_FIELDS:
            v = getattr(mod, attr)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                    or not math.isfinite(v):
                raise GearmeshInputError(f"modification.{gear}.{key}", v, "must be a finite number")
            if v < 0:
                raise GearmeshInputError(f"modification.{gear}.{key}", v * scale, "must not be negative")


def pair_lead_slope(geom: PairGeometry, lead_slope=None) -> tuple[float, float]:
    """The lead slope deviations (m) a model takes: ``lead_slope`` as given, or None: the pair's own
    (``pair.deviations.lead_slope``, :mod:`gearmesh.deviation`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width.

    Returns
    -------
    tuple of float
        (pinion, gear) lead slope deviations, m.
    """
    if lead_slope is None:
        return tuple(float(v) for v in geom.pair.deviations.lead_slope)
    return tuple(float(v) for v in lead_slope)


def check_count(name: str, value, minimum: int, maximum: int) -> int:
    """An integer count within its bounds, else a GearmeshInputError naming ``name``.

    Parameters
    ----------
    name : str
        Field named in the error.
    value : int
        The count (a bool is refused).
    minimum, maximum : int
        Inclusive bounds.

    Returns
    -------
    int
        ``value`` as an int.

    Raises
    ------
    GearmeshInputError
        ``value`` not an integer in [minimum, maximum].
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not minimum <= value <= maximum:
        raise GearmeshInputError(name, value, f"must be an integer in [{minimum}, {maximum}]")
    return int(value)


def check_extension(extension) -> float:
    """The reach of the tip-edge candidates (fraction of p_bt) as a float in [0, 1].

    Parameters
    ----------
    extension : float
        Reach beyond the active zone, fraction of the transverse base pitch p_bt.

    Returns
    -------
    float
        ``extension``.

    Raises
    ------
    GearmeshInputError
        ``corner_extension`` not a finite number in [0, 1].
    """
    if isinstance(extension, bool) or not isinstance(extension, (int, float, np.floating, np.integer)) \
            or not math.isfinite(extension) or not 0 <= extension <= 1:
        raise GearmeshInputError("corner_extension", extension, "must lie in [0, 1] (fraction of the base pitch)")
    return float(extension)


# --------------------------------------------------------------------------------------
# The candidate grid
# --------------------------------------------------------------------------------------


def point_centres(geom: PairGeometry, n_points: int) -> tuple[np.ndarray, float]:
    """Centres z_k (m) of ``n_points`` equal transverse slices over [−b/2, b/2] and their width (m)
    (as :func:`gearmesh.stiffness.slice_centres`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    n_points : int
        Number of slices across the face width.

    Returns
    -------
    z : numpy.ndarray
        (n_points,) slice centres, m.
    dz : float
        Slice width b/n_points, m.
    """
    dz = geom.face_width / n_points
    return -0.5 * geom.face_width + dz * (np.arange(n_points) + 0.5), dz


@dataclass(frozen=True)
class CandidateGrid:
    """Every candidate contact point at every roll (SI); arrays (P, J, N) unless stated.

    roll (P,) pinion roll distance r_b1·φ1 (m); pairs (J,) tooth-pair indices j; z (N,)
    point (slice centre) positions across the face (m), dz their width (m); s position on
    the line of action from A (m); region 0 none / 1 flank / 2 gear tip on pinion flank
    (approach) / 3 pinion tip on gear flank (recess); rho_pinion, rho_gear the roll
    lengths (m) of the touched points (the tip roll length for the tip edge); gap the
    unloaded transverse separation (m), NaN where not a candidate; basis its
    :class:`~gearmesh.separation.SeparationBasis` (gaps of other modifications without new
    geometry), when known.
    """

    roll: np.ndarray
    pairs: np.ndarray
    z: np.ndarray
    dz: float
    s: np.ndarray
    region: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray
    gap: np.ndarray
    extension: float
    basis: SeparationBasis | None = None

    @property
    def candidate(self) -> np.ndarray:
        return self.region > 0


def _pair_range(geom: PairGeometry, roll: np.ndarray, ext: float) -> np.ndarray:
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    pbt = geom.transverse_base_pitch
    j_min = math.floor((-ext - half_axial - float(roll.max())) / pbt)
    j_max = math.ceil((geom.path_of_contact + ext + half_axial - float(roll.min())) / pbt)
    return np.arange(j_min, j_max + 1)


def candidate_grid(geom: PairGeometry, roll, n_points: int = 50, lead_slope=(0.0, 0.0),
                   extension: float = DEFAULT_EXTENSION, pairs: np.ndarray | None = None,
                   misalignment: float = 0.0) -> CandidateGrid:
    """Candidate points and their unloaded separations at the pinion rolls ``roll`` (m).

    Tooth pair j in the slice z lies at s = roll + j·p_bt + h·z·tan βb (module docstring); tooth pairs
    that never have a candidate are dropped unless ``pairs`` is given. The tip-edge candidates are the
    corner contact before A and after E of [1]_ (scenario 1).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : float or array_like
        (P,) pinion roll distances r_b1·φ1, m.
    n_points : int, default 50
        Slice centres across the face.
    lead_slope : sequence of 2 float, default (0, 0)
        Lead slope deviations [pinion, gear], m over the face width (:mod:`gearmesh.deviation`).
    extension : float, default :data:`DEFAULT_EXTENSION`
        Reach beyond the active zone as a fraction of the transverse base pitch (0: flank contact
        only).
    pairs : numpy.ndarray of int, optional
        (J,) tooth-pair indices to keep; None: those with a candidate.
    misalignment : float, default 0.0
        The mesh's further lead mismatch, m (:mod:`gearmesh.deviation`).

    Returns
    -------
    CandidateGrid
        ``roll`` (P,) m, ``pairs`` (J,), ``z`` (N,) m, ``dz`` m, and (P, J, N) arrays ``s`` (m),
        ``region``, ``rho_pinion``, ``rho_gear`` (m), ``gap`` (m, NaN where no candidate), with the
        ``basis``; ``extension`` in m.

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears, docs/references.md.
    """
    roll = np.atleast_1d(np.asarray(roll, dtype=float))
    ext = float(extension) * geom.transverse_base_pitch
    z, dz = point_centres(geom, n_points)
    trim = pairs is None
    if trim:
        pairs = _pair_range(geom, roll, ext)
    pairs = np.asarray(pairs)
    s = (roll[:, None, None] + pairs[None, :, None] * geom.transverse_base_pitch
         + hand_sign(geom) * z[None, None, :] * math.tan(geom.base_helix_angle))
    zz = np.broadcast_to(z, s.shape)
    basis = separation_basis(geom, s, ext)
    region = basis.region
    gap = basis_gap(geom, basis, zz, lead_slope, misalignment=misalignment)
    rho1, rho2 = basis.rho_pinion, basis.rho_gear
    if trim:
        keep = (region > 0).any(axis=(0, 2))
        if keep.any() and not keep.all():
            idx = np.flatnonzero(keep)
            sl = slice(idx[0], idx[-1] + 1)
            pairs, s, gap = pairs[sl], s[:, sl], gap[:, sl]
            basis = SeparationBasis(*(getattr(basis, f.name)[:, sl] for f in fields(SeparationBasis)))
            region, rho1, rho2 = basis.region, basis.rho_pinion, basis.rho_gear
    return CandidateGrid(roll=roll, pairs=pairs, z=z, dz=dz, s=s, region=region, rho_pinion=rho1,
                         rho_gear=rho2, gap=gap, extension=ext, basis=basis)


# --------------------------------------------------------------------------------------
# The start of engagement
# --------------------------------------------------------------------------------------


def engagement_point(geom: PairGeometry) -> tuple[float, int, float]:
    """The theoretical start of engagement φ1A of the next tooth pair within one mesh cycle.

    The line of pair j first reaches the start of active profile (s = 0) at the face end
    where h·z·tan βb is largest, z_A = h·b/2 (the corner of the entering tooth): at
    roll_A + j·p_bt + (b/2)·tan βb = 0. For β = 0 the whole line enters at once (z_A = 0).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    roll_a : float
        Pinion roll of the start of engagement, in [0, p_bt), m.
    j_a : int
        Index of the entering tooth pair.
    z_a : float
        Axial position of the entering corner, m.
    """
    pbt = geom.transverse_base_pitch
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    roll_a = (-half_axial) % pbt
    if roll_a >= pbt * (1 - 1e-12):
        roll_a = 0.0
    j_a = int(round(-(roll_a + half_axial) / pbt))
    z_a = hand_sign(geom) * 0.5 * geom.face_width if half_axial > 0 else 0.0
    return float(roll_a), j_a, float(z_a)


# --------------------------------------------------------------------------------------
# TCA
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TCAResult:
    """Unloaded TCA over one mesh cycle (SI, transverse displacements along the line of action).

    grid : the :class:`CandidateGrid` (separations of every point).
    te : (P,) unloaded transmission error, the smallest separation over all pairs (m).
    te_pair : (P, J) each tooth pair's own TE curve, its smallest separation (m).
    contact_s, contact_z, contact_rho_pinion, contact_rho_gear : (P, J) where each pair
        touches first (the centre of its points within ``tolerance`` of its smallest
        separation), m; NaN for a pair without candidates.
    roll_engagement, pair_engagement, z_engagement : the start of engagement
        (:func:`engagement_point`).
    te_at_engagement : TE (m) of the whole mesh at φ1A.
    te_next_pair_at_engagement : the entering pair's own separation (m) at φ1A — its TE
        curve there (the mesh-in impact paper's TE(φ1A), compared with LTE(φ1A)).
    lead_slope : (2,) lead slope deviations (m over the face width); misalignment the mesh's
        further lead mismatch (m; :mod:`gearmesh.deviation`).
    """

    grid: CandidateGrid
    te: np.ndarray
    te_pair: np.ndarray
    contact_s: np.ndarray
    contact_z: np.ndarray
    contact_rho_pinion: np.ndarray
    contact_rho_gear: np.ndarray
    roll_engagement: float
    pair_engagement: int
    z_engagement: float
    te_at_engagement: float
    te_next_pair_at_engagement: float
    lead_slope: tuple[float, float]
    misalignment: float = 0.0

    @property
    def te_peak_to_peak(self) -> float:
        return float(np.nanmax(self.te) - np.nanmin(self.te))


def first_contact(grid: CandidateGrid, te_pair: np.ndarray, tolerance: float):
    """Where each tooth pair touches first: the centre of its points within ``tolerance`` of its
    smallest separation.

    Parameters
    ----------
    grid : CandidateGrid
        The candidate points, arrays (P, J, N).
    te_pair : numpy.ndarray
        (P, J) each pair's smallest separation, m.
    tolerance : float
        Separation within which points count as the first contact, m.

    Returns
    -------
    s, z, rho_pinion, rho_gear : numpy.ndarray
        (P, J) line-of-action position, axial position and touched roll lengths, m; NaN for a pair
        without candidates.
    """
    near = np.isfinite(grid.gap) & (grid.gap <= te_pair[..., None] + tolerance)
    cnt = near.sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        def centre(a):
            return np.where(cnt > 0, np.where(near, a, 0.0).sum(axis=-1) / cnt, np.nan)
        zz = np.broadcast_to(grid.z, grid.s.shape)
        return (centre(grid.s), centre(zz), centre(np.nan_to_num(grid.rho_pinion)),
                centre(np.nan_to_num(grid.rho_gear)))


def nanmin(a, axis):
    """Minimum over ``axis`` ignoring NaN and inf; NaN where no value is finite (without numpy's
    all-NaN warning).

    Parameters
    ----------
    a : array_like
        The values.
    axis : int or tuple of int
        Axis or axes to reduce.

    Returns
    -------
    numpy.ndarray
        The minima, NaN where a slice has no finite value.
    """
    with np.errstate(invalid="ignore"):
        fin = np.isfinite(a)
        out = np.min(np.where(fin, a, np.inf), axis=axis)
    return np.where(np.isinf(out), np.nan, out)


def engagement_separation(geom: PairGeometry, n_points: int, lead_slope, extension: float,
                          misalignment: float = 0.0) -> tuple[float, float]:
    """(TE of the mesh, separation of the entering pair) at φ1A (m): the grid points at roll_A and,
    exactly, the entering corner (s = 0, z = z_A).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    n_points : int
        Slice centres across the face.
    lead_slope : sequence of 2 float
        Lead slope deviations [pinion, gear], m over the face width.
    extension : float
        Reach of the tip-edge candidates, fraction of p_bt.
    misalignment : float, default 0.0
        The mesh's further lead mismatch, m.

    Returns
    -------
    te : float
        Unloaded TE of the whole mesh at φ1A, m.
    te_next : float
        The entering pair's own separation at φ1A, m.
    """
    roll_a, j_a, z_a = engagement_point(geom)
    grid = candidate_grid(geom, np.array([roll_a]), n_points, lead_slope, extension, misalignment=misalignment)
    corner = float(flank_separation(geom, 0.0, z_a, lead_slope, misalignment))
    per_pair = nanmin(grid.gap[0], axis=-1)
    k = np.flatnonzero(grid.pairs == j_a)
    nxt = corner if k.size == 0 or not np.isfinite(per_pair[k[0]]) else min(corner, float(per_pair[k[0]]))
    return float(min(np.nanmin(per_pair), nxt)), nxt


def tca(geom: PairGeometry, positions: int = 64, points: int = 50, lead_slope=None,
        extension: float = DEFAULT_EXTENSION, tolerance: float = 1e-9) -> TCAResult:
    """Unloaded tooth contact analysis over one mesh cycle.

    The unloaded TE at each roll is the smallest separation of any candidate point (the
    rotation, ×r_b1, that closes it: module docstring); an unmodified aligned pair has
    zero TE to round-off because every flank point of the active zone has zero gap. Lead slope
    deviations are taken as ISO 1328-1 [1]_ measures helix deviations (module docstring); the
    tip-edge candidates are the corner contact of [2]_.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; its pair carries the modifications of both gears.
    positions : int, default 64
        Pinion roll positions evenly over one transverse base pitch.
    points : int, default 50
        Points (slice centres) per contact line across the face width.
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width
        (:func:`gearmesh.deviation.lead_gap`); None: the pair's own (``pair.deviations``, with its
        stated mesh misalignment).
    extension : float, default :data:`DEFAULT_EXTENSION`
        Reach of the tip-edge candidates beyond the active zone, fraction of p_bt.
    tolerance : float, default 1e-9
        Separation (m) within which points count as the first contact of a pair.

    Returns
    -------
    TCAResult
        ``te`` (P,) m, ``te_pair`` (P, J) m, first-contact positions (P, J) m, the start of
        engagement and the TE there (m), the ``grid``.

    Raises
    ------
    GearmeshInputError
        Modifications, counts or ``extension`` out of range.

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth.
    .. [2] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears, docs/references.md.
    """
    check_modifications(geom)
    positions = check_count("positions", positions, 1, 100000)
    points = check_count("points", points, 1, 100000)
    extension = check_extension(extension)
    lead_slope = pair_lead_slope(geom, lead_slope)
    mis = geom.pair.deviations.misalignment
    roll = mesh_cycle_rolls(geom, positions)
    grid = candidate_grid(geom, roll, points, lead_slope, extension, misalignment=mis)
    te_pair = nanmin(grid.gap, axis=-1)
    te = nanmin(te_pair, axis=-1)
    cs, cz, c1, c2 = first_contact(grid, te_pair, tolerance)
    roll_a, j_a, z_a = engagement_point(geom)
    te_a, next_a = engagement_separation(geom, points, lead_slope, extension, mis)
    return TCAResult(grid=grid, te=te, te_pair=te_pair, contact_s=cs, contact_z=cz, contact_rho_pinion=c1,
                     contact_rho_gear=c2, roll_engagement=roll_a, pair_engagement=j_a, z_engagement=z_a,
                     te_at_engagement=te_a, te_next_pair_at_engagement=next_a, lead_slope=lead_slope,
                     misalignment=mis)
