"""Three-dimensional tooth flanks: involute helicoids, body frames, contact mapping, modification.

Frames (shared with :mod:`gearmesh.contact`). Fixed frame: pinion axis = z, pinion centre at
the origin, gear centre at (a, 0, 0); the pinion drives counter-clockwise (CCW) about +z; the
transverse line of action runs from T1 = r_b1(cos αwt, −sin αwt) along
d = (sin αwt, cos αwt); the face spans z ∈ [−b/2, b/2] (b = ``geom.face_width``).

Body frames. Each gear's body frame is the frame of :func:`gearmesh.profile.tooth_profile`
(centre at the origin, tooth 0 centreline on +y in the slice z = 0), with z parallel to the
fixed z (the gear's body frame is translated to (a, 0, 0), never flipped). Teeth are numbered
CCW, tooth k turned by 2πk/z. Both contacting flanks — the pinion's driving flank and the
gear's driven flank — are the CCW-side flank of their tooth, i.e. the *x < 0* side in the
body frame (the mirror image of the profile's x > 0 flank). A body point b maps to the fixed
frame by f = R_z(Φ)·b (+ (a, 0, 0) for the gear), with

    Φ1(φ1) = ρ_SAP1/r_b1 − αwt − π/2 − ψ01 + φ1,
    Φ2(φ1) = π/2 − αwt − ψ02 + ρ_EAP2/r_b2 − φ1·r_b1/r_b2,

ψ0 = s_t/(2r) + inv αt, and φ1 = roll/r_b1 the pinion rotation of contact.py (roll = r_b1 φ1).
These put the contact of tooth pair j = 0 in slice z = 0 at s = 0 (pinion ρ1 = ρ_SAP1, gear
ρ2 = ρ_EAP2) when roll = 0, as contact.py assumes; pair j is pinion tooth j and gear tooth −j.

Helix: slice z of a gear is slice 0 turned CCW by z·k/r_b, k the signed tan βb of the flank:
k1 = h tan βb for the pinion (h = +1 right hand: CCW as z grows, contact.py), k2 = −h tan βb
for the gear (opposite hand). This is the contact-line paper's helicoid z = pθ with lead parameter
p = r_b/k (p = r_b/tan βb in magnitude).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .gear import PairGeometry, involute
from .profile import tooth_profile

__all__ = [
    "involute_helicoid",
    "involute_helicoid_z",
    "flank_tan_base_helix",
    "flank_point",
    "body_rotation",
    "plane_of_action_point",
    "plane_of_action_normal",
    "pinion_contact_point",
    "gear_contact_point",
    "MODIFICATION_FIELDS",
    "modification_parameters",
    "relief_depth",
    "modification_depth",
    "ToothSurface",
    "tooth_surface",
]


# --------------------------------------------------------------------------------------
# Involute helicoid (the contact-line paper)
# --------------------------------------------------------------------------------------


def involute_helicoid_z(base_radius: float, tan_beta_b: float, u, z, sigma: float = 0.0, side: int = 1):
    """Involute helicoid point and outward unit normal at roll angle ``u`` and axial ``z``.

    The contact-line paper with the side sign s: A = σ + s·u + θ, θ = z·k/r_b (k = ``tan_beta_b``, signed:
    k > 0 turns slices CCW as z grows, k = 0 a spur flank),

        r = r_b [cos A + s u sin A,  sin A − s u cos A,  z/r_b]        (r_b·(e(A) − s u t(A)))

    s = +1 is the contact-line paper's orientation (string unwound clockwise; a flank on the CW side of its
    tooth), s = −1 the mirror image (CCW side). The unit normal pointing out of the tooth,
    along the unwound string and tilted by the base helix angle (Litvin & Fuentes, Gear
    Geometry and Applied Theory, 2nd ed., §10.4), is

        n = (−s t(A), s k)/√(1 + k²),     t(A) = (−sin A, cos A).

    The point lies at radius r_b√(1 + u²); the roll length is ρ = r_b u.

    Parameters
    ----------
    base_radius : float
        r_b (m).
    tan_beta_b : float
        Signed tan βb k (-).
    u : array_like
        Roll angle (rad, ≥ 0).
    z : array_like
        Axial position (m); broadcast with ``u``.
    sigma : float, default 0.0
        Angle (rad) of the involute's start on the base circle in slice z = 0.
    side : {1, -1}, default 1
        Side sign s.

    Returns
    -------
    points : ndarray
        broadcast(u, z) + (3,) (m).
    normals : ndarray
        Outward unit normals, same shape (-).

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    .. [2] F. L. Litvin, A. Fuentes, Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10.4.
    """
    u, z = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(z, dtype=float))
    k = float(tan_beta_b)
    A = sigma + side * u + z * (k / base_radius)
    cA, sA = np.cos(A), np.sin(A)
    pts = np.stack([base_radius * (cA + side * u * sA), base_radius * (sA - side * u * cA), z], axis=-1)
    c = 1.0 / math.sqrt(1.0 + k * k)
    nrm = np.stack([side * sA * c, -side * cA * c, np.full(u.shape, side * k * c)], axis=-1)
    return pts, nrm


def involute_helicoid(base_radius: float, lead_parameter: float, u, theta, sigma: float = 0.0, side: int = 1):
    """The contact-line paper's involute helicoid r(u, θ): z = pθ with lead parameter p = r_b/tan βb (m/rad).

    x = r_b cos(σ + s u + θ) + s r_b u sin(σ + s u + θ),
    y = r_b sin(σ + s u + θ) − s r_b u cos(σ + s u + θ),  z = p θ   (s = ``side``, the contact-line paper: s = 1).

    The form of :func:`involute_helicoid_z`, which also covers spur flanks (p = ∞).

    Parameters
    ----------
    base_radius : float
        r_b (m).
    lead_parameter : float
        p (m/rad, signed; p < 0 is a left-hand flank, must be finite).
    u : array_like
        Roll angle (rad).
    theta : array_like
        Helical parameter θ (rad); broadcast with ``u``.
    sigma : float, default 0.0
        Start angle on the base circle (rad).
    side : {1, -1}, default 1
        Side sign s.

    Returns
    -------
    points : ndarray
        broadcast(u, theta) + (3,) (m).
    normals : ndarray
        Outward unit normals, same shape (-).

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    """
    p = float(lead_parameter)
    return involute_helicoid_z(base_radius, base_radius / p, u, p * np.asarray(theta, dtype=float), sigma, side)


def flank_tan_base_helix(geom: PairGeometry, gear: int) -> float:
    """Signed tan βb of the contacting flank of ``gear`` (0/1): +h tan βb for the pinion, −h
    for the gear (h = +1 right-hand pinion); slices turn CCW by z·k/r_b.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 for the pinion, 1 for the gear.

    Returns
    -------
    float
        k (-).
    """
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    return (h if gear == 0 else -h) * math.tan(geom.base_helix_angle)


def _psi0(geom: PairGeometry, gear: int) -> float:
    """ψ0 = s_t/(2r) + inv αt (rad), the involute's polar angle from the centreline at r_b."""
    return float(geom.transverse_thickness[gear] / (2 * geom.reference_radius[gear])
                 + involute(geom.transverse_pressure_angle))


def flank_point(geom: PairGeometry, gear: int, rho, z, tooth: int = 0):
    """Point and outward unit normal of the contacting (CCW-side, x < 0) involute flank of
    tooth ``tooth`` of gear ``gear``, in that gear's body frame (module docstring).

    The helicoid of :func:`involute_helicoid_z` with side s = −1, start angle
    σ = π/2 + ψ0 + 2π·tooth/z and k = :func:`flank_tan_base_helix`; its transverse section
    is the mirror of the involute of :func:`gearmesh.profile.tooth_profile`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 for the pinion, 1 for the gear.
    rho : array_like
        Roll length of this gear (m).
    z : array_like
        Axial position (m); broadcast with ``rho``.
    tooth : int, default 0
        Tooth number (counted CCW).

    Returns
    -------
    points : ndarray
        broadcast(rho, z) + (3,) (m).
    normals : ndarray
        Outward unit normals, same shape (-).
    """
    rb = float(geom.base_radius[gear])
    sigma = math.pi / 2 + _psi0(geom, gear) + 2 * math.pi * tooth / geom.pair.teeth[gear]
    return involute_helicoid_z(rb, flank_tan_base_helix(geom, gear), np.asarray(rho, dtype=float) / rb,
                               z, sigma, side=-1)


# --------------------------------------------------------------------------------------
# Plane of action <-> body frames
# --------------------------------------------------------------------------------------


def body_rotation(geom: PairGeometry, gear: int, phi1) -> np.ndarray:
    """Angle Φ (rad, CCW about +z) of gear ``gear``'s body frame in the fixed frame at pinion
    rotation φ1 = roll/r_b1 (rad): Φ1 and Φ2 of the module docstring.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 for the pinion, 1 for the gear.
    phi1 : array_like
        Pinion rotation φ1 (rad).

    Returns
    -------
    ndarray
        Φ (rad), the shape of ``phi1``.
    """
    phi1 = np.asarray(phi1, dtype=float)
    awt = geom.operating_pressure_angle
    rb = geom.base_radius
    if gear == 0:
        return geom.rho_sap[0] / rb[0] - awt - math.pi / 2 - _psi0(geom, 0) + phi1
    return math.pi / 2 - awt - _psi0(geom, 1) + geom.rho_eap[1] / rb[1] - phi1 * (rb[0] / rb[1])


def plane_of_action_point(geom: PairGeometry, rho1, z) -> np.ndarray:
    """Fixed-frame point (m) of the plane of action at pinion roll length ρ1 (m) and z (m):
    T1 + ρ1·d (contact.py), shape broadcast(rho1, z) + (3,).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    rho1 : array_like
        Pinion roll length ρ1 (m).
    z : array_like
        Axial position (m); broadcast with ``rho1``.
    """
    rho1, z = np.broadcast_arrays(np.asarray(rho1, dtype=float), np.asarray(z, dtype=float))
    awt, rb1 = geom.operating_pressure_angle, float(geom.base_radius[0])
    return np.stack([rb1 * math.cos(awt) + rho1 * math.sin(awt),
                     -rb1 * math.sin(awt) + rho1 * math.cos(awt), z], axis=-1)


def plane_of_action_normal(geom: PairGeometry) -> np.ndarray:
    """Unit normal (fixed frame) of the plane of action, out of the pinion's driving flank:
    (d cos βb, −h sin βb). It is the common normal of both flanks at every contact point.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    ndarray
        (3,) unit vector (-).
    """
    bb = geom.base_helix_angle
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    awt = geom.operating_pressure_angle
    return np.array([math.sin(awt) * math.cos(bb), math.cos(awt) * math.cos(bb), -h * math.sin(bb)])


def _rotate_z(pts: np.ndarray, angle) -> np.ndarray:
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    x, y = pts[..., 0], pts[..., 1]
    return np.stack([c * x - s * y, s * x + c * y, pts[..., 2]], axis=-1)


def pinion_contact_point(geom: PairGeometry, rho1, z, phi1) -> np.ndarray:
    """The plane-of-action point (ρ1, z) at pinion rotation φ1 in the pinion body frame (m).

    b = R_z(−Φ1(φ1))·(T1 + ρ1 d, z). When (ρ1, z, φ1) is a contact of pair j
    (ρ1 = ρ_SAP1 + r_b1 φ1 + j p_bt + h z tan βb) the point lies on the driving flank of
    pinion tooth j (:func:`flank_point`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    rho1 : array_like
        Pinion roll length ρ1 (m).
    z : array_like
        Axial position (m).
    phi1 : array_like
        Pinion rotation φ1 (rad); the three broadcast together.

    Returns
    -------
    ndarray
        Points broadcast(rho1, z, phi1) + (3,) (m).
    """
    f = plane_of_action_point(geom, rho1, z)
    return _rotate_z(f, -body_rotation(geom, 0, phi1))


def gear_contact_point(geom: PairGeometry, rho1, z, phi1) -> np.ndarray:
    """The plane-of-action point (pinion roll ρ1, z) at pinion rotation φ1 in the gear body
    frame (m): b = R_z(−Φ2(φ1))·(f − (a, 0, 0)). A contact of pair j lies on gear tooth −j
    at gear roll length ρ2 = ρ_EAP2 − (ρ1 − ρ_SAP1).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    rho1 : array_like
        Pinion roll length ρ1 (m).
    z : array_like
        Axial position (m).
    phi1 : array_like
        Pinion rotation φ1 (rad); the three broadcast together.

    Returns
    -------
    ndarray
        Points broadcast(rho1, z, phi1) + (3,) (m).
    """
    f = plane_of_action_point(geom, rho1, z)
    f = f - np.array([geom.center_distance, 0.0, 0.0])
    return _rotate_z(f, -body_rotation(geom, 1, phi1))


# --------------------------------------------------------------------------------------
# Micro-geometry modification (the mesh-in impact paper, six parameters)
# --------------------------------------------------------------------------------------


MODIFICATION_FIELDS = ("root_relief", "tip_relief", "root_relief_length", "tip_relief_length", "crowning",
                       "unmodified_lead_length")


def modification_parameters(geom: PairGeometry) -> np.ndarray:
    """The mesh-in impact paper's six parameters y1..y6 of both gears as a (2, 6) array (m), in the order of
    :data:`MODIFICATION_FIELDS` (pinion row 0, gear row 1).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    References
    ----------
    .. [1] *Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears*.
    """
    return np.array([[float(getattr(mod, f)) for f in MODIFICATION_FIELDS] for mod in geom.pair.modification])


def relief_depth(params, rho_sap: float, rho_eap: float, face_width: float, rho, z) -> np.ndarray:
    """Material removed (m) by the mesh-in impact paper's six parameters ``params`` (last axis y1..y6, m, in the
    order of :data:`MODIFICATION_FIELDS`) at roll length ρ and axial position z (m).

    The formulas of :func:`modification_depth`, vectorised over modifications: the leading
    axes of ``params`` broadcast against ``rho`` and ``z`` (a batch of candidate
    modifications, e.g. a GA population of shape (C, 1, 6) against points (1, M)). A zero
    amount or zero length is no relief; ρ = NaN gives 0.

    Parameters
    ----------
    params : array_like
        (..., 6) y1..y6 (m).
    rho_sap, rho_eap : float
        Roll lengths of the start and end of active profile (m).
    face_width : float
        b (m).
    rho : array_like
        Roll lengths (m), NaN on the fillet.
    z : array_like
        Axial positions (m).

    Returns
    -------
    ndarray or float
        Depth δ ≥ 0 (m), broadcast(params[..., 0], rho, z); a scalar for scalar arguments.

    References
    ----------
    .. [1] *Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears* (its printed profile and lead forms replaced, see :func:`modification_depth`).
    """
    y1, y2, y3, y4, y5, y6 = np.moveaxis(np.asarray(params, dtype=float), -1, 0)
    rho = np.asarray(rho, dtype=float)
    z = np.asarray(z, dtype=float)
    shape = np.broadcast_shapes(y1.shape, rho.shape, z.shape)
    depth = np.zeros(shape)
    # each relief as amount·(max(0, distance into its zone)/length)², amount and reciprocal length
    # taken zero where either is zero — on the small parameter arrays, not on the points; the
    # point arrays (C × points for a population) worked on in place, one temporary per relief
    with np.errstate(invalid="ignore"):  # ρ = NaN propagates, set to 0 below
        for amount, length, into in ((y2, y4, lambda: rho - (rho_eap - y4)), (y1, y3, lambda: (rho_sap + y3) - rho)):
            on = (amount > 0) & (length > 0)
            if np.any(on):  # skipped where no set has this relief (the common case)
                r = np.asarray(np.multiply(np.maximum(into(), 0.0), np.where(on, 1.0 / np.where(on, length, 1.0), 0.0)))
                np.multiply(r, r, out=r)
                np.multiply(r, np.where(on, amount, 0.0), out=r)
                depth += r
    if np.any(y5 > 0):  # crowning
        r = np.maximum(np.abs(z) - 0.5 * y6, 0.0) / np.where(face_width > y6, 0.5 * (face_width - y6), 1.0)
        depth += np.where(y5 > 0, y5, 0.0) * (r * r)
    nan = np.isnan(rho)
    if nan.any():
        depth[np.broadcast_to(nan, shape)] = 0.0
        return depth
    return depth if depth.ndim else depth[()]  # scalar arguments: a scalar, as numpy's arithmetic gives


def fit_modifications(geom: PairGeometry, params) -> np.ndarray:
    """Parameter sets (C, 2, 6) (m) made valid modifications of ``geom``'s flanks (a copy): relief
    lengths whose sum exceeds the active roll length scaled down to fit it, an amount without a
    length (or the reverse) no relief, the unmodified lead length inside the face — so
    :func:`gearmesh.gear.validate_modifications` accepts every set (GA candidates, tolerance samples).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    params : array_like
        (C, 2, 6) or (2, 6) y1..y6 of pinion and gear (m).

    Returns
    -------
    ndarray
        (C, 2, 6) fitted parameter sets (m).
    """
    p = np.array(params, dtype=float, ndmin=3)
    for gear in range(2):
        active = float(geom.rho_eap[gear] - geom.rho_sap[gear]) * (1 - 1e-9)
        total = p[:, gear, 2] + p[:, gear, 3]
        scale = np.where(total > active, active / np.where(total > 0, total, 1.0), 1.0)
        p[:, gear, 2:4] *= scale[:, None]
        for amount, length in ((0, 2), (1, 3)):
            none = (p[:, gear, amount] <= 0) | (p[:, gear, length] <= 0)
            p[none, gear, amount] = 0.0
            p[none, gear, length] = 0.0
        p[:, gear, 5] = np.minimum(p[:, gear, 5], geom.face_width * (1 - 1e-6))
    return p


def modification_depth(geom: PairGeometry, gear: int, rho, z) -> np.ndarray:
    """Material removed (m, ≥ 0, along the surface normal) at roll length ρ (m) and z (m).

    The sum of three parabolic reliefs with the mesh-in impact paper's six parameters
    (:class:`gearmesh.gear.Modification`, y1..y6):

    * tip relief  δ = y2·((ρ − (ρ_tip − y4))/y4)²  for ρ > ρ_tip − y4, ρ_tip = ρ_EAP;
    * root relief δ = y1·(((ρ_SAP + y3) − ρ)/y3)²  for ρ < ρ_SAP + y3;
    * crowning    δ = y5·((|z| − y6/2)/((b − y6)/2))²  for |z| > y6/2, b = geom.face_width;

    so each relief is 0 where it starts and reaches its amount at the tip, at the start of
    active profile and at the face ends (ISO 21771:2007 §7 profile and helix modifications;
    the usual parabolic forms, e.g. Litvin & Fuentes §9.6). The mesh-in impact paper prints
    δ_p = Δ(1 − (1 − 2h/L)²), a bump that vanishes at both ends of the relief zone (zero at
    the tip), and δ_l = y5(1 − (2|w|/(B − L_w))²), which falls towards the face ends; both
    contradict "tip relief", "root relief" and "crowning" and are replaced here. Below the
    SAP the root parabola continues (non-active flank). ρ = NaN (the fillet, not ground)
    gives 0. ``rho`` and ``z`` broadcast. (:func:`relief_depth` is the same for a batch of
    parameter sets.)

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 for the pinion, 1 for the gear.
    rho : array_like
        Roll length of this gear (m), NaN on the fillet.
    z : array_like
        Axial position (m).

    Returns
    -------
    ndarray
        δ (m), broadcast(rho, z).

    References
    ----------
    .. [1] *Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears*.
    .. [2] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry, §7.
    .. [3] F. L. Litvin, A. Fuentes, Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §9.6.
    """
    rho, z = np.broadcast_arrays(np.asarray(rho, dtype=float), np.asarray(z, dtype=float))
    return relief_depth(modification_parameters(geom)[gear], float(geom.rho_sap[gear]), float(geom.rho_eap[gear]),
                        geom.face_width, rho, z)


# --------------------------------------------------------------------------------------
# The whole flank
# --------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ToothSurface:
    """A flank on a (profile, face) grid in the gear body frame; every array (n_profile, n_face).

    ``x, y, z`` points (m) after modification; ``nx, ny, nz`` outward unit normals of the
    unmodified flank; ``rho`` roll length (m, NaN on the fillet); ``radius`` of the
    unmodified point (m); ``segment`` 0 fillet / 1 involute; ``depth`` material removed (m).
    """

    gear: int
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    nx: np.ndarray
    ny: np.ndarray
    nz: np.ndarray
    rho: np.ndarray
    radius: np.ndarray
    segment: np.ndarray
    depth: np.ndarray


def tooth_surface(geom: PairGeometry, gear: int, n_profile: int = 90, n_face: int = 21,
                  modified: bool = True, tooth: int = 0, n_fillet: int | None = None) -> ToothSurface:
    """The contacting flank (fillet + involute) of tooth ``tooth`` of gear ``gear`` (0/1).

    The transverse profile of :func:`gearmesh.profile.tooth_profile` (``n_profile`` points,
    ``n_fillet`` of them on the fillet, default a third), mirrored to the x < 0 side, is swept helically over
    z ∈ [−b/2, b/2] (``n_face`` slices): slice z turned CCW by z·k/r_b (module docstring).
    For a profile M(τ) and twist w = k/r_b the outward normal is ∝ (−M_y', M_x', −w M·M'),
    rotated with the slice (normal of a screw surface, Litvin & Fuentes §10.4); on the
    involute it equals the helicoid normal. With ``modified`` the depth of
    :func:`modification_depth` is removed along the normal, P − δ n; zero modification (or
    ``modified=False``) returns the exact generated flank.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 for the pinion, 1 for the gear.
    n_profile : int, default 90
        Points along the profile (≥ 6).
    n_face : int, default 21
        Transverse slices over the face (≥ 1).
    modified : bool, default True
        Remove the pair's modification depth.
    tooth : int, default 0
        Tooth number (counted CCW).
    n_fillet : int, optional
        Profile points on the fillet (default ``n_profile // 3``, at least 2 on each part).

    Returns
    -------
    ToothSurface
        Points ``x``, ``y``, ``z`` (m), unit normals, ``rho`` (m), ``radius`` (m), ``segment``
        and ``depth`` (m), each (n_profile, n_face).

    References
    ----------
    .. [1] F. L. Litvin, A. Fuentes, Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10.4.
    """
    if n_profile < 6 or n_face < 1:
        raise ValueError("n_profile must be at least 6 and n_face at least 1")
    n_fil = max(2, n_profile // 3) if n_fillet is None else n_fillet
    if not 2 <= n_fil <= n_profile - 2:
        raise ValueError("n_fillet must leave at least 2 points on each of fillet and involute")
    prof = tooth_profile(geom, gear, n_fillet=n_fil, n_involute=n_profile - n_fil)
    mx, my = -prof.x, prof.y  # mirrored: the CCW-side flank
    tx, ty = -prof.tangent_x, prof.tangent_y
    rb = float(geom.base_radius[gear])
    w = flank_tan_base_helix(geom, gear) / rb
    zs = np.linspace(-0.5, 0.5, n_face) * geom.face_width if n_face > 1 else np.zeros(1)
    n0 = np.stack([-ty, tx, -w * (mx * tx + my * ty)], axis=-1)
    n0 /= np.linalg.norm(n0, axis=-1, keepdims=True)
    angle = zs[None, :] * w + 2 * math.pi * tooth / geom.pair.teeth[gear]
    pts0 = np.stack([mx, my, np.zeros_like(mx)], axis=-1)[:, None, :]
    pts = _rotate_z(np.broadcast_to(pts0, (mx.size, zs.size, 3)), angle)
    pts[..., 2] = zs[None, :]
    nrm = _rotate_z(np.broadcast_to(n0[:, None, :], (mx.size, zs.size, 3)), angle)
    rho = np.broadcast_to(prof.roll[:, None], (mx.size, zs.size))
    depth = modification_depth(geom, gear, rho, zs[None, :]) if modified else np.zeros(rho.shape)
    if np.any(depth):
        pts = pts - depth[..., None] * nrm
    return ToothSurface(
        gear=gear, x=pts[..., 0], y=pts[..., 1], z=pts[..., 2], nx=nrm[..., 0], ny=nrm[..., 1],
        nz=nrm[..., 2], rho=np.array(rho), radius=np.broadcast_to(prof.radius[:, None], rho.shape).copy(),
        segment=np.broadcast_to(prof.segment[:, None], rho.shape).copy(), depth=depth)
