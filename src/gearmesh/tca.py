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
beside F/K(φ). A depth δ_n removed along the flank normal of a helicoid opens a transverse
gap δ_n / cos βb (the unit normal of the plane of action has the transverse component
cos βb along d; :func:`gearmesh.surface.plane_of_action_normal`). A lead slope error
(fHβ-type) is taken as ISO 1328-1 measures helix deviations, in the transverse plane along
the base tangent, so it adds to the transverse gap unchanged.

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

The tip edge moves on its tip circle, off the line of action, and touches the mating flank
at a roll length slightly *above* that flank's SAP (the tip circle leaves A away from the
mating centre): the extended path of contact of corner contact.

Their separation is the exact 2-D distance, per transverse slice, between the tip point
of one gear (rotated to where it is at that roll) and the involute of the other:
with inv(u) = u − arctan u, the involutes of a base circle r_b are parallel curves
σ = θ + inv(u) = const (θ the polar angle of a point, u = √(r²/r_b² − 1)), a distance
r_b·Δσ apart along their common normal, which is tangent to the base circle (Litvin &
Fuentes, Gear Geometry and Applied Theory, 2nd ed. 2004, §10.3). So

* approach: gap = r_b1·(σ1(P) − σ1,flank), exactly the pinion rotation (×r_b1) that brings
  the pinion flank to the gear tip P with the gear held;
* recess: the pinion rotation ψ (× r_b1) that carries the pinion tip point P onto the gear
  involute, σ2(R(ψ)P) = σ2,flank, solved by Newton's method from the first-order estimate
  r_b2·(σ2(P) − σ2,flank)/|n2·(e_z × P)| (the gear-normal distance over the moment arm of
  the gear-flank normal n2 about the pinion axis, which equals r_b1 on the line of action).

Both reduce continuously to the flank formula at s = 0 and s = g_α. The flank
modifications add at the touched point (pinion at the roll length ρ_P = √(|P|² − r_b1²)
of the involute through P, gear tip relief at the tip; the depth of the tip edge projected
on the mating normal). Tip edges are sharp (no chamfer, no tip rounding); a point whose
touched roll length falls below the form circle (the fillet) is not a candidate; the helix
makes the real edge contact 3-D, which is approximated here slice by slice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .contact import hand_sign, mesh_cycle_rolls
from .choices import DEFAULT_CORNER_EXTENSION
from .deviation import lead_gap, profile_gap
from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
from .surface import modification_parameters, relief_depth

__all__ = [
    "REGION_NONE", "REGION_FLANK", "REGION_APPROACH_TIP", "REGION_RECESS_TIP",
    "CandidateGrid", "TCAResult", "check_modifications", "check_extension", "point_centres", "pair_lead_slope",
    "SeparationBasis", "separation_basis", "basis_gap", "approach_tip_point", "recess_tip_point",
    "flank_separation", "approach_tip_separation", "recess_tip_separation",
    "candidate_grid", "engagement_point", "engagement_separation", "tca",
]

REGION_NONE, REGION_FLANK, REGION_APPROACH_TIP, REGION_RECESS_TIP = 0, 1, 2, 3

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
# Separations
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
class SeparationBasis:
    """Unloaded separations of candidate points, split into what the micro-geometry cannot
    change and the weights of both flanks' modification depths (arrays of one shape, SI):

        gap = base + w_pinion·δ1(ρ_pinion, z) + w_gear·δ2(ρ_gear, z) + lead(z)

    ``region`` 0 none / 1 flank / 2 approach tip edge / 3 recess tip edge; ``base`` the
    separation of the unmodified flanks (0 on the flank, the exact tip-edge distance
    outside the active zone; NaN for no candidate); ``w_pinion``, ``w_gear`` the transverse
    gap one metre of normal depth of each flank opens at the touched point; ``rho_pinion``,
    ``rho_gear`` the touched roll lengths (m). A GA re-evaluates ``gap`` for every candidate
    modification without recomputing the geometry (:func:`basis_gap`).
    """

    region: np.ndarray
    base: np.ndarray
    w_pinion: np.ndarray
    w_gear: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray


def _wrap(angle):
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def _inv(u):
    """inv as a function of u = tan α: u − arctan u (= tan α − α)."""
    return u - np.arctan(u)


def _frame(geom: PairGeometry):
    awt = geom.operating_pressure_angle
    rb1 = float(geom.base_radius[0])
    t1 = np.array([rb1 * math.cos(awt), -rb1 * math.sin(awt)])
    d = np.array([math.sin(awt), math.cos(awt)])
    return awt, t1, d


def approach_tip_point(geom: PairGeometry, s) -> tuple[np.ndarray, np.ndarray]:
    """Fixed-frame transverse position (x, y) (m) of the gear tip point that reaches the start of
    the path of contact A after the gear turns on by −s/r_b2 (s < 0): P = O2 + R(−s/r_b2)(A − O2).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the line of action before A (s < 0), m.

    Returns
    -------
    x, y : numpy.ndarray
        Coordinates of the tip point in the pinion-centred fixed frame, m, shaped like ``s``.
    """
    s = np.asarray(s, float)
    _, t1, d = _frame(geom)
    a = geom.center_distance
    ax, ay = t1 + geom.rho_sap[0] * d
    psi = -s / float(geom.base_radius[1])
    c, sn = np.cos(psi), np.sin(psi)
    return a + c * (ax - a) - sn * ay, sn * (ax - a) + c * ay


def recess_tip_point(geom: PairGeometry, s) -> tuple[np.ndarray, np.ndarray]:
    """Fixed-frame transverse position (x, y) (m) of the pinion tip point that left the end of the
    path of contact E a pinion turn (s − g_α)/r_b1 ago (s > g_α): P = R((s − g_α)/r_b1)·E.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the line of action beyond E (s > g_α), m.

    Returns
    -------
    x, y : numpy.ndarray
        Coordinates of the tip point in the pinion-centred fixed frame, m, shaped like ``s``.
    """
    s = np.asarray(s, float)
    _, t1, d = _frame(geom)
    ex, ey = t1 + geom.rho_eap[0] * d
    psi = (s - geom.path_of_contact) / float(geom.base_radius[0])
    c, sn = np.cos(psi), np.sin(psi)
    return c * ex - sn * ey, sn * ex + c * ey


def _approach_basis(geom: PairGeometry, s):
    """(base distance, ρ_P, weight of the gear tip relief) of approach tip-edge points (module docstring)."""
    awt = geom.operating_pressure_angle
    rb1, rb2 = (float(r) for r in geom.base_radius)
    px, py = approach_tip_point(geom, s)
    with np.errstate(invalid="ignore"):
        u = np.sqrt((px * px + py * py) / rb1**2 - 1.0)
    theta = np.arctan2(py, px)
    dist = rb1 * (_wrap(theta + awt) + _inv(u) - (geom.rho_sap[0] + s) / rb1)
    # normals (transverse): pinion involute through P, gear involute at its tip
    tau1 = theta - np.arctan(u)
    tau2 = np.arctan2(py, px - geom.center_distance) - math.atan(geom.rho_eap[1] / rb2)
    return dist, rb1 * u, np.abs(np.cos(tau1 - tau2))


def _recess_basis(geom: PairGeometry, s):
    """(unmodified gap, ρ_gear, weight of the pinion tip relief, factor r_b1/arm) of recess
    tip-edge points (module docstring).

    The gap of the unmodified flanks is exact: the pinion rotation ψ (gear held) that carries
    the pinion tip point P onto the gear involute, σ2(R(ψ)P) = σ2,flank, by Newton's method
    from the first-order estimate (normal distance)/arm, times r_b1. The modifications add to
    first order through r_b1/arm (the moment arm of the gear-flank normal about the pinion axis).
    """
    awt = geom.operating_pressure_angle
    rb1, rb2 = (float(r) for r in geom.base_radius)
    a = geom.center_distance
    px, py = recess_tip_point(geom, s)
    flank = (geom.rho_eap[1] - s) / rb2

    def sigma_gap(x, y):
        """σ2 of the gear involute through (x, y) less the flank's (rad); rb2× it is the normal distance."""
        with np.errstate(invalid="ignore"):
            u2 = np.sqrt(((x - a) ** 2 + y * y) / rb2**2 - 1.0)
        return _wrap(np.arctan2(y, x - a) - (math.pi - awt)) + _inv(u2) - flank, u2

    f0, u2 = sigma_gap(px, py)
    dist = rb2 * f0
    tau2 = np.arctan2(py, px - a) - np.arctan(u2)
    n2x, n2y = -np.sin(tau2), np.cos(tau2)
    arm = np.abs(-n2x * py + n2y * px)
    psi = dist / arm  # first order
    h = 1e-7
    for _ in range(4):  # Newton on the pinion rotation; converged to round-off in 2–3 steps
        c, sn = np.cos(psi), np.sin(psi)
        f, _ = sigma_gap(c * px - sn * py, sn * px + c * py)
        cp, sp = np.cos(psi + h), np.sin(psi + h)
        cm, sm = np.cos(psi - h), np.sin(psi - h)
        fp, _ = sigma_gap(cp * px - sp * py, sp * px + cp * py)
        fm, _ = sigma_gap(cm * px - sm * py, sm * px + cm * py)
        with np.errstate(invalid="ignore", divide="ignore"):
            psi = psi - f / ((fp - fm) / (2 * h))
    c, sn = np.cos(psi), np.sin(psi)
    f, _ = sigma_gap(c * px - sn * py, sn * px + c * py)
    # far from the flank (no nearby involute point to rotate onto) there is no candidate
    psi = np.where(np.abs(f) <= 1e-12, psi, np.nan)
    tau1 = np.arctan2(py, px) - math.atan(geom.rho_eap[0] / rb1)
    return rb1 * psi, rb2 * u2, np.abs(np.cos(tau1 - tau2)), rb1 / arm


def separation_basis(geom: PairGeometry, s, extension: float = np.inf) -> SeparationBasis:
    """The :class:`SeparationBasis` of points at line-of-action positions ``s`` (m, any shape).

    Flank points for s ∈ [0, g_α], tip-edge points up to ``extension`` beyond it (region 2 before A,
    region 3 after E; module docstring: the tip-edge distances by the parallel involutes of [1]_), no
    candidate elsewhere or where the touched roll length falls below the mating form circle.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the transverse line of action from A, m.
    extension : float, default inf
        Reach of the tip-edge candidates beyond the active zone, m.

    Returns
    -------
    SeparationBasis
        ``region``, ``base`` (m), ``w_pinion``, ``w_gear`` (transverse gap per metre of normal depth),
        ``rho_pinion``, ``rho_gear`` (m), each shaped like ``s``; NaN where no candidate.

    References
    ----------
    .. [1] Litvin F.L., Fuentes A., Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10.3.
    """
    s = np.asarray(s, dtype=float)
    g = geom.path_of_contact
    cb = math.cos(geom.base_helix_angle)
    region = np.zeros(s.shape, dtype=np.int8)
    nan = np.full(s.shape, np.nan)
    base, w1, w2, rho1, rho2 = nan.copy(), nan.copy(), nan.copy(), nan.copy(), nan.copy()
    flank = (s >= 0) & (s <= g)
    appr = (s < 0) & (s >= -extension)
    rec = (s > g) & (s <= g + extension)
    if flank.any():
        base[flank], w1[flank], w2[flank] = 0.0, 1.0 / cb, 1.0 / cb
        rho1[flank] = geom.rho_sap[0] + s[flank]
        rho2[flank] = geom.rho_eap[1] - s[flank]
        region[flank] = REGION_FLANK
    if appr.any():
        dist, rho_p, cosang = _approach_basis(geom, s[appr])
        ok = np.isfinite(rho_p) & (rho_p >= geom.rho_form[0] - 1e-12)
        base[appr] = np.where(ok, dist, np.nan)
        w1[appr], w2[appr] = 1.0 / cb, cosang / cb
        rho1[appr], rho2[appr] = rho_p, geom.rho_eap[1]
        region[appr] = np.where(ok, REGION_APPROACH_TIP, REGION_NONE)
    if rec.any():
        gap0, rho_g, cosang, factor = _recess_basis(geom, s[rec])
        ok = np.isfinite(rho_g) & np.isfinite(gap0) & (rho_g >= geom.rho_form[1] - 1e-12)
        base[rec] = np.where(ok, gap0, np.nan)
        w1[rec], w2[rec] = cosang * factor / cb, factor / cb
        rho1[rec], rho2[rec] = geom.rho_eap[0], rho_g
        region[rec] = np.where(ok, REGION_RECESS_TIP, REGION_NONE)
    none = region == REGION_NONE
    for arr in (base, w1, w2, rho1, rho2):
        arr[none] = np.nan
    return SeparationBasis(region=region, base=base, w_pinion=w1, w_gear=w2, rho_pinion=rho1, rho_gear=rho2)


def basis_gap(geom: PairGeometry, basis: SeparationBasis, z, lead_slope=(0.0, 0.0), params=None,
              misalignment=0.0) -> np.ndarray:
    """Transverse gaps (m) of the points of ``basis`` at axial positions ``z`` (m, broadcast).

    The pair's own profile slope deviations (:func:`gearmesh.deviation.profile_gap`) are always
    added. NaN where the basis has no candidate.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    basis : SeparationBasis
        The points' separation basis (:func:`separation_basis`).
    z : array_like
        Axial positions of the points, m, broadcast against the basis.
    lead_slope : array_like, default (0, 0)
        (..., 2) the gears' lead slope deviations, m over the face width
        (:func:`gearmesh.deviation.lead_gap`).
    params : array_like, optional
        (..., 2, 6) modification parameters of both gears, m, in the order of
        :data:`gearmesh.surface.MODIFICATION_FIELDS` (leading axes broadcast against the points,
        e.g. (C, 1, 1, 2, 6) for C candidates); None: the pair's own.
    misalignment : float or array_like, default 0.0
        The mesh's further lead mismatch, m, broadcast like ``lead_slope[..., 0]``.

    Returns
    -------
    numpy.ndarray
        Transverse gaps, m, of the broadcast shape of basis, ``params``, ``z``, ``lead_slope`` and
        ``misalignment``.
    """
    if params is None:
        params = modification_parameters(geom)
    params = np.asarray(params, dtype=float)
    lead = np.asarray(lead_slope, dtype=float)
    mis = np.asarray(misalignment, dtype=float)
    shape = np.broadcast_shapes(basis.base.shape, params.shape[:-2], np.shape(z), lead.shape[:-1], mis.shape)
    gap, own = basis.base, False  # own: gap is a fresh array of this call, added to in place

    def add(term):
        nonlocal gap, own
        if own and np.shape(term) == () or own and np.broadcast_shapes(gap.shape, np.shape(term)) == gap.shape:
            gap += term
        else:
            gap, own = gap + term, True

    for gear, (w, rho) in enumerate(((basis.w_pinion, basis.rho_pinion), (basis.w_gear, basis.rho_gear))):
        p = params[..., gear, :]
        if np.any(p):  # an unmodified flank adds nothing (the common case for one of the gears)
            depth = relief_depth(p, float(geom.rho_sap[gear]), float(geom.rho_eap[gear]), geom.face_width,
                                 np.nan_to_num(rho), z)
            if np.broadcast_shapes(depth.shape, w.shape) == depth.shape:
                depth *= w  # the fresh depth array, scaled in place (w·depth, the same product)
            else:
                depth = w * depth
            add(depth)
    if np.any(lead) or np.any(mis):
        add(lead_gap(geom, lead, z, mis))
    profile = geom.pair.deviations.profile_slope
    if any(profile):
        add(profile_gap(geom, profile, basis.rho_pinion, basis.rho_gear))
    return gap if gap.shape == shape else np.array(np.broadcast_to(gap, shape))


def flank_separation(geom: PairGeometry, s, z, lead_slope=(0.0, 0.0), misalignment=0.0) -> np.ndarray:
    """Flank-to-flank transverse gap (m) at s ∈ [0, g_α] (m) and z (m), region 1.

    gap = (δ1(ρ1, z) + δ2(ρ2, z))/cos βb + lead deviation, ρ1 = ρ_SAP1 + s,
    ρ2 = ρ_EAP2 − s, δ the normal depths of :func:`gearmesh.surface.modification_depth`
    (module docstring for the /cos βb). Zero for an unmodified, aligned pair.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the line of action from A, m (clipped to [0, g_α]).
    z : array_like
        Axial positions, m, broadcast against ``s``.
    lead_slope : sequence of 2 float, default (0, 0)
        Lead slope deviations [pinion, gear], m over the face width.
    misalignment : float, default 0.0
        The mesh's further lead mismatch, m.

    Returns
    -------
    numpy.ndarray
        Transverse gaps, m, of the broadcast shape of ``s`` and ``z``.
    """
    s, z = np.broadcast_arrays(np.asarray(s, float), np.asarray(z, float))
    s = np.clip(s, 0.0, geom.path_of_contact)
    return basis_gap(geom, separation_basis(geom, s, 0.0), z, lead_slope, misalignment=misalignment)


def approach_tip_separation(geom: PairGeometry, s, z, lead_slope=(0.0, 0.0)):
    """Gap (m) between the gear's tip edge and the pinion flank before the gear tip reaches A (s < 0), region 2.

    In the transverse slice the gear tip point reaches A = T1 + ρ_SAP1·d after the gear
    turns on (clockwise) by −s/r_b2, so now it sits at P = O2 + R(−s/r_b2)(A − O2). The
    pinion rotation that brings the pinion involute to P (gear held) is
    σ1(P) − σ1,flank with σ1(P) = θ1(P) + inv(u_P), σ1,flank = −αwt + (ρ_SAP1 + s)/r_b1
    (module docstring; the parallel involutes of [1]_). Adds the pinion modification at
    ρ_P = r_b1·u_P and the gear tip modification projected on the pinion normal (both /cos βb) and
    the lead deviation.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the line of action before A, m (s > 0 is taken as 0).
    z : array_like
        Axial positions, m, broadcast against ``s``.
    lead_slope : sequence of 2 float, default (0, 0)
        Lead slope deviations [pinion, gear], m over the face width.

    Returns
    -------
    gap : numpy.ndarray
        Transverse gaps, m; NaN where ρ_P falls below the pinion form circle.
    rho_pinion : numpy.ndarray
        Touched pinion roll lengths ρ_P, m.

    References
    ----------
    .. [1] Litvin F.L., Fuentes A., Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10.3.
    """
    s, z = np.broadcast_arrays(np.asarray(s, float), np.asarray(z, float))
    basis = separation_basis(geom, np.minimum(s, -0.0), np.inf)
    basis = _only(basis, REGION_APPROACH_TIP)
    return basis_gap(geom, basis, z, lead_slope), basis.rho_pinion


def recess_tip_separation(geom: PairGeometry, s, z, lead_slope=(0.0, 0.0)):
    """Gap (m) between the pinion's tip edge and the gear flank after the pinion tip left E (s > g_α), region 3.

    The pinion tip left E = T1 + ρ_EAP1·d a pinion turn (s − g_α)/r_b1 ago: P = R((s − g_α)/r_b1)·E.
    With σ2 = θ2 + inv(u2) in the gear-centred polar angle and σ2,flank = π − αwt +
    (ρ_EAP2 − s)/r_b2, the gap is the pinion rotation ψ that brings P onto the flank,
    σ2(R(ψ)P) = σ2,flank, times r_b1 (:func:`_recess_basis`; the parallel involutes of [1]_); the
    modifications enter through r_b1/|n2·(e_z × P)| (the moment arm of the flank normal n2 about the
    pinion axis), as in :func:`approach_tip_separation`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    s : array_like
        Positions on the line of action beyond E, m.
    z : array_like
        Axial positions, m, broadcast against ``s``.
    lead_slope : sequence of 2 float, default (0, 0)
        Lead slope deviations [pinion, gear], m over the face width.

    Returns
    -------
    gap : numpy.ndarray
        Transverse gaps, m; NaN where the touched gear roll length falls below its form circle.
    rho_gear : numpy.ndarray
        Touched gear roll lengths, m.

    References
    ----------
    .. [1] Litvin F.L., Fuentes A., Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10.3.
    """
    s, z = np.broadcast_arrays(np.asarray(s, float), np.asarray(z, float))
    basis = _only(separation_basis(geom, s, np.inf), REGION_RECESS_TIP)
    return basis_gap(geom, basis, z, lead_slope), basis.rho_gear


def _only(basis: SeparationBasis, region: int) -> SeparationBasis:
    """``basis`` with every point outside ``region`` made a non-candidate (NaN)."""
    keep = basis.region == region

    def mask(a):
        return np.where(keep, a, np.nan)

    return SeparationBasis(region=np.where(keep, basis.region, REGION_NONE).astype(np.int8), base=mask(basis.base),
                           w_pinion=mask(basis.w_pinion), w_gear=mask(basis.w_gear),
                           rho_pinion=mask(basis.rho_pinion), rho_gear=mask(basis.rho_gear))


# --------------------------------------------------------------------------------------
# The candidate grid
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class CandidateGrid:
    """Every candidate contact point at every roll (SI); arrays (P, J, N) unless stated.

    roll (P,) pinion roll distance r_b1·φ1 (m); pairs (J,) tooth-pair indices j; z (N,)
    point (slice centre) positions across the face (m), dz their width (m); s position on
    the line of action from A (m); region 0 none / 1 flank / 2 gear tip on pinion flank
    (approach) / 3 pinion tip on gear flank (recess); rho_pinion, rho_gear the roll
    lengths (m) of the touched points (the tip roll length for the tip edge); gap the
    unloaded transverse separation (m), NaN where not a candidate; basis its
    :class:`SeparationBasis` (gaps of other modifications without new geometry), when known.
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
