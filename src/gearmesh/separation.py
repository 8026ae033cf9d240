"""Unloaded separations (gaps) of candidate contact points of a modified helical pair: flank to
flank, and tip edge to flank beyond the active zone.

Everything inside is SI (m, rad), in the frames of :mod:`gearmesh.contact` and the displacement
convention of :mod:`gearmesh.tca`: a gap is a transverse displacement along the line of action,
r_b1·Δφ1 with the gear held; ``s`` is the distance along the transverse line of action from the
start of active profile A. A point lies in region 1 on the flanks (s ∈ [0, g_α]), region 2 at the
gear's tip edge before A (approach), region 3 at the pinion's tip edge past the end of the path E
(recess), region 0 nowhere (no candidate).

A depth δ_n removed along the flank normal of a helicoid opens a transverse
gap δ_n / cos βb (the unit normal of the plane of action has the transverse component
cos βb along d; :func:`gearmesh.surface.plane_of_action_normal`).

Tip edges
---------
The tip edge moves on its tip circle, off the line of action, and touches the mating flank
at a roll length slightly *above* that flank's SAP (the tip circle leaves A away from the
mating centre): the extended path of contact of corner contact.

A tip edge's separation is the exact 2-D distance, per transverse slice, between the tip point
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
from dataclasses import dataclass

import numpy as np

from .deviation import lead_gap, profile_gap
from .gear import PairGeometry
from .surface import modification_parameters, relief_depth

__all__ = [
    "REGION_NONE", "REGION_FLANK", "REGION_APPROACH_TIP", "REGION_RECESS_TIP",
    "SeparationBasis", "separation_basis", "basis_gap", "approach_tip_point", "recess_tip_point",
    "flank_separation", "approach_tip_separation", "recess_tip_separation",
]

REGION_NONE, REGION_FLANK, REGION_APPROACH_TIP, REGION_RECESS_TIP = 0, 1, 2, 3


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
