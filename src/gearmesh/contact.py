"""Contact lines of a helical pair in the plane of action, and their total length.

Frame convention (shared by every module): the pinion axis is the z axis, the pinion centre
the origin, the gear centre at (a, 0, 0). The pinion drives counter-clockwise about +z; the
transverse line of action runs from the pinion base tangent point
T1 = r_b1 (cos αwt, −sin αwt) in the direction d = (sin αwt, cos αwt), through the pitch point
(r_w1, 0), to T2. The face runs over z ∈ [−b/2, b/2] with its centre at z = 0.

In the plane of action a contact line is straight and inclined at the base helix angle βb
to the axis (the contact-line paper; Litvin & Fuentes, Gear Geometry and Applied Theory, 2nd ed., §14).
Measure ``s`` from the start of active profile A (pinion roll length ρ1 = ρ_SAP1) along the
line of action; the active zone is 0 ≤ s ≤ g_α. For tooth pair j at pinion roll distance
``roll`` = r_b1·φ1 the contact in the transverse slice at z sits at

    s_j(z) = roll + j·p_bt + h·z·tan βb,     h = +1 (right-hand pinion) or −1 (left-hand),

because a right-hand helicoid turns each slice counter-clockwise by z·tan βb / r_b1 as z
grows, which advances its contact along the line of action like a forward rotation.

Body frames (:func:`plane_of_action_points`, :func:`contact_line_end_points`): the pinion
body frame turns with the pinion by φ1 = roll / r_b1 (counter-clockwise), the gear body
frame sits at the gear centre (a, 0, 0) and turns clockwise by φ2 = φ1 z1/z2 = roll / r_b2;
both coincide with the (translated) fixed frame at roll = 0, when tooth pair 0 touches at
the start of active profile in the slice z = 0. Pinion tooth j is tooth 0 turned by
+2πj/z1, gear tooth j is gear tooth 0 turned by −2πj/z2; the flank equations in these
frames are in :func:`flank_reference_angles`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .gear import PairGeometry


def hand_sign(geom: PairGeometry) -> int:
    """+1 for a right-hand pinion, −1 for a left-hand pinion (the gear has the other hand).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    """
    return 1 if geom.pair.helix_hand == "right" else -1


def tooth_pair_indices(geom: PairGeometry) -> np.ndarray:
    """Indices j of every tooth pair that can be in the active zone during one base pitch.

    With roll ∈ [0, p_bt) and h·z·tan βb ∈ [−b tan βb/2, b tan βb/2], s_j ∈ [0, g_α] needs
    j·p_bt ∈ (−p_bt − b tan βb/2, g_α + b tan βb/2].

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    ndarray of int
        (J,) consecutive tooth-pair indices j.
    """
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    pbt = geom.transverse_base_pitch
    j_min = -math.ceil(half_axial / pbt) - 1
    j_max = math.ceil((geom.path_of_contact + half_axial) / pbt)
    return np.arange(j_min, j_max + 1)


def _pair_indices_for_rolls(geom: PairGeometry, roll: np.ndarray) -> np.ndarray:
    """:func:`tooth_pair_indices`, widened so that rolls outside [0, p_bt) lose no pair.

    For rolls within one base pitch the result is exactly :func:`tooth_pair_indices`;
    for others (a mesh-in position before the cycle, several cycles) the range grows to
    j·p_bt ∈ [−roll_max − b tan βb/2, g_α + b tan βb/2 − roll_min].
    """
    base = tooth_pair_indices(geom)
    roll = np.asarray(roll, dtype=float)
    if roll.size == 0 or not np.all(np.isfinite(roll)):
        return base
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    pbt = geom.transverse_base_pitch
    j_min = min(int(base[0]), math.floor((-half_axial - float(roll.max())) / pbt))
    j_max = max(int(base[-1]), math.ceil((geom.path_of_contact + half_axial - float(roll.min())) / pbt))
    return np.arange(j_min, j_max + 1)


def contact_roll_positions(geom: PairGeometry, roll: np.ndarray, z: np.ndarray,
                           pairs: np.ndarray | None = None) -> np.ndarray:
    """Position s (m) of the contact on the line of action for every roll, tooth pair, slice.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : ndarray
        (P,) pinion roll distance r_b1·φ1 (m).
    z : ndarray
        (S,) axial positions of the transverse slices (m), within [−b/2, b/2].
    pairs : ndarray of int, optional
        (J,) tooth-pair indices j (default :func:`tooth_pair_indices`, widened to cover
        rolls outside one base pitch).

    Returns
    -------
    ndarray
        (P, J, S) s (m), NaN where the slice of that pair is outside the active zone
        [0, g_α]. The pinion roll length at the contact is ρ1 = ρ_SAP1 + s and the gear roll
        length ρ2 = ρ_EAP2 − s.
    """
    roll = np.asarray(roll, dtype=float)
    pairs = _pair_indices_for_rolls(geom, roll) if pairs is None else np.asarray(pairs)
    z = np.asarray(z, dtype=float)
    s = (roll[:, None, None] + pairs[None, :, None] * geom.transverse_base_pitch
         + hand_sign(geom) * z[None, None, :] * math.tan(geom.base_helix_angle))
    return np.where((s >= 0) & (s <= geom.path_of_contact), s, np.nan)


@dataclass(frozen=True)
class ContactLines:
    """Contact lines over rotation positions (all SI).

    ``s_start``/``s_end`` and ``z_start``/``z_end`` are the clipped end points of each line
    in the plane of action, shape (P, J), NaN for a pair not in contact; ``length`` is the
    length of each line and ``total_length`` their sum L(φ) (P,).
    """

    roll: np.ndarray
    pairs: np.ndarray
    s_start: np.ndarray
    s_end: np.ndarray
    z_start: np.ndarray
    z_end: np.ndarray
    length: np.ndarray
    total_length: np.ndarray


def contact_lines(geom: PairGeometry, roll: np.ndarray) -> ContactLines:
    """Every contact line clipped to the active zone, exactly, at each pinion roll distance.

    Each line is the segment {s = roll + j p_bt + h z tan βb, 0 ≤ s ≤ g_α, |z| ≤ b/2}; its
    length is its axial extent divided by cos βb (the contact-line paper's sum of segment lengths, here in
    closed form per line). For β = 0 a line covers the whole face or none of it.
    ``roll`` may lie outside [0, p_bt): the tooth-pair set is widened to cover it (for
    rolls within one base pitch it is :func:`tooth_pair_indices`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : ndarray
        (P,) pinion roll distances r_b1·φ1 (m).

    Returns
    -------
    ContactLines
        End points ``s_start``, ``s_end``, ``z_start``, ``z_end`` (P, J) (m, NaN out of contact),
        ``length`` (P, J) (m) and ``total_length`` L (P,) (m).

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    """
    roll = np.asarray(roll, dtype=float)
    pairs = _pair_indices_for_rolls(geom, roll)
    half_b = 0.5 * geom.face_width
    g = geom.path_of_contact
    s_mid = roll[:, None] + pairs[None, :] * geom.transverse_base_pitch  # s at z = 0
    tb = math.tan(geom.base_helix_angle)
    h = hand_sign(geom)
    if tb > 0:
        # z where the line meets s = 0 and s = g_α, ordered along +z
        z_a = (0.0 - s_mid) / (h * tb)
        z_e = (g - s_mid) / (h * tb)
        lo = np.clip(np.minimum(z_a, z_e), -half_b, half_b)
        hi = np.clip(np.maximum(z_a, z_e), -half_b, half_b)
    else:
        inside = (s_mid >= 0) & (s_mid <= g)
        lo = np.where(inside, -half_b, 0.0)
        hi = np.where(inside, half_b, 0.0)
    axial = hi - lo
    active = axial > 0
    length = np.where(active, axial / math.cos(geom.base_helix_angle), 0.0)
    nan = np.nan
    z_start = np.where(active, lo, nan)
    z_end = np.where(active, hi, nan)
    s_start = np.where(active, s_mid + h * tb * lo, nan)
    s_end = np.where(active, s_mid + h * tb * hi, nan)
    return ContactLines(roll=roll, pairs=pairs, s_start=s_start, s_end=s_end, z_start=z_start,
                        z_end=z_end, length=length, total_length=length.sum(axis=1))


def contact_length_closed_form(geom: PairGeometry) -> tuple[float, float, float]:
    """Mean, minimum and maximum total contact-line length (m), in closed form.

    In base-pitch units each line covers ε_β of the line of action clipped to [0, ε_α], so
    L·sin βb/p_bt = ⌊ε_β⌋ε_α + ⌊ε_α⌋f_β + μ, where f = frac(ε) and μ, the overlap of a
    window of length f_α with a periodic set of duty f_β, ranges over
    [max(0, f_α + f_β − 1), min(f_α, f_β)] (derivation in docs of the low-fluctuation paper §1, written out
    here because the document only names the piecewise phases). The mean is exactly
    l_mean = b ε_α / cos βb (docs/modelling.md). For β = 0: L ∈ {⌊ε_α⌋b, ⌈ε_α⌉b}.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    mean, min, max : float
        L_mean, L_min, L_max (m).

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §1.
    """
    ea, eb = geom.eps_alpha, geom.eps_beta
    b = geom.face_width
    mean = b * ea / math.cos(geom.base_helix_angle)
    if geom.base_helix_angle == 0:
        lo = math.floor(ea) * b
        hi = math.ceil(ea) * b if ea % 1 else lo
        return mean, lo, hi
    fa, fb = ea % 1.0, eb % 1.0
    base = math.floor(eb) * ea + math.floor(ea) * fb
    scale = geom.transverse_base_pitch / math.sin(geom.base_helix_angle)
    return mean, (base + max(0.0, fa + fb - 1.0)) * scale, (base + min(fa, fb)) * scale


def mesh_cycle_rolls(geom: PairGeometry, n_positions: int) -> np.ndarray:
    """``n_positions`` pinion roll distances (m) evenly over one base pitch, end excluded.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    n_positions : int
        Number of positions (≥ 1).

    Returns
    -------
    ndarray
        (n_positions,) roll distances in [0, p_bt) (m).
    """
    if n_positions < 1:
        raise ValueError("n_positions must be at least 1")
    return np.arange(n_positions) * (geom.transverse_base_pitch / n_positions)


# --------------------------------------------------------------------------------------
# Contact lines in 3-D: fixed frame, pinion body frame, gear body frame
# --------------------------------------------------------------------------------------


def pinion_rotation(geom: PairGeometry, roll: np.ndarray | float) -> np.ndarray:
    """Pinion rotation angle φ1 = roll / r_b1 (rad, counter-clockwise about +z) at a roll distance (m).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : float or ndarray
        Pinion roll distance (m), any shape.
    """
    return np.asarray(roll, dtype=float) / geom.base_radius[0]


def gear_rotation(geom: PairGeometry, roll: np.ndarray | float) -> np.ndarray:
    """Gear rotation angle φ2 = φ1·z1/z2 = roll / r_b2 (rad, clockwise about its axis) at a roll distance (m).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : float or ndarray
        Pinion roll distance (m), any shape.
    """
    return np.asarray(roll, dtype=float) / geom.base_radius[1]


def flank_reference_angles(geom: PairGeometry) -> tuple[float, float]:
    """Body-frame base-circle start angles σ1, σ2 (rad) of the contacting flank of tooth 0.

    The body frames coincide with the fixed frame at roll = 0 (the gear's translated to
    its centre (a, 0, 0)); at roll = 0 the contact of tooth pair 0 in the slice z = 0 is at
    the start of active profile A (s = 0, pinion roll length ρ_SAP1, gear tip). With
    inv(u) = u − arctan u and involute parameter u = ρ/r_b, the contacting flank of tooth
    j in the slice z is, in polar coordinates (r = r_b√(1+u²), θ) of each body frame,

        pinion: θ1 = σ1 − inv(u1) + 2πj/z1 + h·z·tan βb / r_b1,   σ1 = ρ_SAP1/r_b1 − αwt
        gear:   θ2 = σ2 − inv(u2) − 2πj/z2 − h·z·tan βb / r_b2,   σ2 = π − αwt + ρ_EAP2/r_b2

    (the pinion drives counter-clockwise with its leading flank; the gear turns clockwise
    and is pushed on its trailing flank, so on both the tooth body lies at smaller θ and
    the tooth centre line in the slice z = 0 is at σ − inv(αt) − s_t/(2r)). Derived from the
    involute-helicoid equations of the contact-line paper (x = r_b cos(σ+u) + r_b u sin(σ+u), …) with
    the unwinding sense of these flanks; Litvin & Fuentes (2004) §10, §14.

    The body frames of :mod:`gearmesh.surface` (tooth 0 centre line on +y) are these frames
    turned by −Φ(0) = −(σ − π/2 − ψ0), ψ0 = s_t/(2r) + inv αt (``surface.body_rotation`` at
    φ1 = 0); tests/test_contact.py checks the two agree.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    sigma1, sigma2 : float
        σ1, σ2 (rad).

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    .. [2] F. L. Litvin, A. Fuentes, Gear Geometry and Applied Theory, 2nd ed., Cambridge University
       Press, 2004, §10, §14.
    """
    awt = geom.operating_pressure_angle
    sigma1 = geom.rho_sap[0] / geom.base_radius[0] - awt
    sigma2 = math.pi - awt + geom.rho_eap[1] / geom.base_radius[1]
    return float(sigma1), float(sigma2)


def _rotate_z(xyz: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotate points (..., 3) counter-clockwise by ``angle`` (broadcast over ...) about +z."""
    c, s = np.cos(angle), np.sin(angle)
    x, y = xyz[..., 0], xyz[..., 1]
    return np.stack([c * x - s * y, s * x + c * y, np.broadcast_to(xyz[..., 2], x.shape)], axis=-1)


@dataclass(frozen=True)
class FramePoints:
    """Points of the plane of action in the three frames (all SI, m and rad).

    ``fixed``, ``pinion``, ``gear`` have shape (..., 3): the point in the fixed frame, in
    the pinion body frame (pinion centre at the origin) and in the gear body frame (gear
    centre at the origin, same axis directions at roll = 0). ``pinion_tooth`` and
    ``gear_tooth`` rotate the body-frame points of tooth j onto tooth 0 (by −2πj/z1 and
    +2πj/z2), so that every contact maps onto the one flank surface of tooth 0.
    ``u_pinion``/``u_gear`` are the involute parameters u = ρ/r_b (rad) and
    ``rho_pinion``/``rho_gear`` the roll lengths ρ (m) of each gear at the point.
    """

    fixed: np.ndarray
    pinion: np.ndarray
    gear: np.ndarray
    pinion_tooth: np.ndarray
    gear_tooth: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray
    u_pinion: np.ndarray
    u_gear: np.ndarray


def plane_of_action_points(geom: PairGeometry, roll: np.ndarray | float, s: np.ndarray | float,
                           z: np.ndarray | float, pair: np.ndarray | int = 0) -> FramePoints:
    """Map plane-of-action coordinates (s, z) at pinion roll ``roll`` to the three frames.

    The fixed-frame point is T1 + ρ1·d + z·e_z with T1 = r_b1(cos αwt, −sin αwt) and
    d = (sin αwt, cos αwt) (module docstring). The pinion body frame is the fixed frame
    rotated with the pinion, φ1 = roll/r_b1 counter-clockwise: p_body = R(−φ1) p. The gear
    body frame has its origin at the gear centre (a, 0, 0) and turns clockwise by
    φ2 = φ1 z1/z2: g_body = R(+φ2)(p − (a, 0, 0)). The reference (roll = 0 ↔ tooth 0 at
    the start of active profile in the slice z = 0) is :func:`flank_reference_angles`.
    ``roll``, ``s``, ``z`` and ``pair`` are broadcast together (all SI).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : float or ndarray
        Pinion roll distance r_b1·φ1 (m).
    s : float or ndarray
        Position along the transverse line of action from the start of active profile A (m);
        pinion roll length ρ1 = ρ_SAP1 + s, gear roll length ρ2 = ρ_EAP2 − s.
    z : float or ndarray
        Axial position (m), face centre at 0.
    pair : int or ndarray, default 0
        Tooth-pair index j (only used for the tooth-0 frames).

    Returns
    -------
    FramePoints
        The points (..., 3) (m) in the fixed, pinion and gear frames and on tooth 0 of each
        gear, with the roll lengths ρ (m) and involute parameters u (rad) of each gear.
    """
    roll, s, z, pair = np.broadcast_arrays(np.asarray(roll, float), np.asarray(s, float),
                                           np.asarray(z, float), np.asarray(pair, float))
    awt = geom.operating_pressure_angle
    rb1, rb2 = geom.base_radius
    z1, z2 = geom.pair.teeth
    rho1 = geom.rho_sap[0] + s
    rho2 = geom.rho_eap[1] - s
    x = rb1 * math.cos(awt) + rho1 * math.sin(awt)
    y = -rb1 * math.sin(awt) + rho1 * math.cos(awt)
    fixed = np.stack([x, y, z], axis=-1)
    phi1 = roll / rb1
    phi2 = roll / rb2
    pinion = _rotate_z(fixed, -phi1)
    gear = _rotate_z(fixed - np.array([geom.center_distance, 0.0, 0.0]), phi2)
    return FramePoints(
        fixed=fixed, pinion=pinion, gear=gear,
        pinion_tooth=_rotate_z(pinion, -2 * math.pi * pair / z1),
        gear_tooth=_rotate_z(gear, 2 * math.pi * pair / z2),
        rho_pinion=rho1, rho_gear=rho2, u_pinion=rho1 / rb1, u_gear=rho2 / rb2,
    )


@dataclass(frozen=True)
class ContactLineEnds:
    """End points of every contact line at every roll position (SI).

    ``points`` holds the end points in all frames (:class:`FramePoints`, arrays of shape
    (P, J, 2, 3) for coordinates and (P, J, 2) for ρ and u; index 2 of the third axis is
    (start, end) = (smaller z, larger z)), NaN where tooth pair j is not in contact.
    ``phi_pinion``/``phi_gear`` (P,) are the rotation angles φ1, φ2 (rad).
    """

    roll: np.ndarray
    pairs: np.ndarray
    phi_pinion: np.ndarray
    phi_gear: np.ndarray
    points: FramePoints


def contact_line_end_points(geom: PairGeometry, roll: np.ndarray | ContactLines) -> ContactLineEnds:
    """3-D end points of every contact line, in the fixed, pinion and gear frames.

    Vectorised over positions and lines; the mapping is
    :func:`plane_of_action_points` applied to the exactly clipped ends (s, z) of
    :func:`contact_lines` (the contact-line paper: contact points on the involute helicoids; the
    involute parameter at the ends is u = ρ/r_b for each gear).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    roll : ndarray or ContactLines
        (P,) pinion roll distances (m), or a :class:`ContactLines` already computed by
        :func:`contact_lines`.

    Returns
    -------
    ContactLineEnds
        ``points`` (P, J, 2, 3) (m; (start, end) = (smaller z, larger z), NaN out of contact)
        and the rotation angles ``phi_pinion``, ``phi_gear`` (P,) (rad).

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    """
    lines = roll if isinstance(roll, ContactLines) else contact_lines(geom, roll)
    s = np.stack([lines.s_start, lines.s_end], axis=-1)  # (P, J, 2)
    z = np.stack([lines.z_start, lines.z_end], axis=-1)
    r = lines.roll[:, None, None]
    j = lines.pairs[None, :, None]
    pts = plane_of_action_points(geom, r, s, z, j)
    return ContactLineEnds(roll=lines.roll, pairs=lines.pairs, phi_pinion=pinion_rotation(geom, lines.roll),
                           phi_gear=gear_rotation(geom, lines.roll), points=pts)


# --------------------------------------------------------------------------------------
# Mesh-cycle summary of L(φ)
# --------------------------------------------------------------------------------------


def contact_length_breakpoints(geom: PairGeometry) -> np.ndarray:
    """Roll distances (m) in [0, p_bt) where L(roll) changes slope (or jumps, for β = 0).

    L is piecewise linear in the roll: a line's clipped length changes slope only when one
    of its ends crosses a corner of the active zone, i.e. when roll + j p_bt ± h(b/2)tan βb
    equals 0 or g_α. Returned sorted and unique, together with the midpoints between
    consecutive ones (so that the exact extremes of a step function are also sampled).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    ndarray
        Sorted roll distances (m), breakpoints and midpoints alternating.
    """
    pbt = geom.transverse_base_pitch
    half = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    g = geom.path_of_contact
    corners = np.array([0.0 - half, 0.0 + half, g - half, g + half])
    bp = np.unique(np.mod(corners, pbt))
    bp = np.unique(np.concatenate([bp, [0.0]]))
    ext = np.concatenate([bp, [bp[0] + pbt]])
    mids = 0.5 * (ext[:-1] + ext[1:])
    return np.sort(np.concatenate([bp, mids]))


@dataclass(frozen=True)
class ContactLengthSummary:
    """Mean, minimum and maximum of the total contact length L(φ) over a mesh cycle (m),
    and the contact-line fluctuation coefficient ε_l = (L_max − L_min)/b (-) of the low-fluctuation paper §5.

    ``closed_form`` values come from :func:`contact_length_closed_form`; ``numeric`` values
    from :func:`contact_lines` evaluated at every slope change of L (exact, since L is
    piecewise linear) and, if ``n_positions`` was given, ``sampled`` values from an even grid.
    """

    mean: float
    min: float
    max: float
    eps_l: float
    numeric_mean: float
    numeric_min: float
    numeric_max: float
    numeric_eps_l: float
    sampled_mean: float = math.nan
    sampled_min: float = math.nan
    sampled_max: float = math.nan
    sampled_eps_l: float = math.nan


def contact_length_fluctuation(geom: PairGeometry) -> float:
    """ε_l = (L_max − L_min)/b (-), closed form (the low-fluctuation paper §5; zero for integer ε_α or ε_β).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §5.
    """
    _, lo, hi = contact_length_closed_form(geom)
    return (hi - lo) / geom.face_width


def contact_length_summary(geom: PairGeometry, n_positions: int | None = None) -> ContactLengthSummary:
    """Mesh-cycle summary of L(φ): closed form, exact numeric, and optionally sampled.

    The numeric mean integrates the piecewise-linear L exactly (trapezoids between
    breakpoints; for β = 0 the midpoint value of each step). ``n_positions`` adds the
    statistics of L on :func:`mesh_cycle_rolls` (the plain mean of the contact-line paper, L_ave = ΣL_k/N_k).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    n_positions : int, optional
        Even grid over one base pitch for the ``sampled_*`` values (default None: none, NaN).

    Returns
    -------
    ContactLengthSummary
        ``mean``, ``min``, ``max`` (m) and ``eps_l`` (-) in closed form, their ``numeric_*`` and
        ``sampled_*`` counterparts.

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    .. [2] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §5.
    """
    mean, lo, hi = contact_length_closed_form(geom)
    b = geom.face_width
    pbt = geom.transverse_base_pitch
    bp = contact_length_breakpoints(geom)
    L = contact_lines(geom, bp).total_length
    if geom.base_helix_angle > 0:
        x = np.concatenate([bp, [bp[0] + pbt]])
        y = np.concatenate([L, [L[0]]])
        num_mean = float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) / pbt)
    else:
        # bp alternates breakpoint, midpoint: each midpoint value holds over its interval
        ext = np.concatenate([bp, [bp[0] + pbt]])
        widths = np.diff(ext[::2]) if len(ext[::2]) > 1 else np.array([pbt])
        num_mean = float(np.sum(L[1::2] * widths) / pbt)
    out = dict(mean=float(mean), min=float(lo), max=float(hi), eps_l=float((hi - lo) / b), numeric_mean=num_mean,
               numeric_min=float(L.min()), numeric_max=float(L.max()),
               numeric_eps_l=float((L.max() - L.min()) / b))
    if n_positions:
        Ls = contact_lines(geom, mesh_cycle_rolls(geom, n_positions)).total_length
        out.update(sampled_mean=float(Ls.mean()), sampled_min=float(Ls.min()), sampled_max=float(Ls.max()),
                   sampled_eps_l=float((Ls.max() - Ls.min()) / b))
    return ContactLengthSummary(**out)


def contact_lines_benchmark(geom: PairGeometry, n_positions: int = 360) -> ContactLines:
    """Contact lines at ``n_positions`` rolls over one base pitch (the benchmark kernel).

    One vectorised call of :func:`contact_lines` on a (P, J) grid; no Python loop over
    positions or teeth.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    n_positions : int, default 360
        Number of roll positions P.

    Returns
    -------
    ContactLines
        As :func:`contact_lines`.
    """
    return contact_lines(geom, mesh_cycle_rolls(geom, n_positions))
