"""Contact lines of a helical pair in the plane of action, and their total length.

Frame convention (shared by every module): the pinion axis is the z axis, the pinion centre
the origin, the gear centre at (a, 0, 0). The pinion drives counter-clockwise about +z; the
transverse line of action runs from the pinion base tangent point
T1 = r_b1 (cos αwt, −sin αwt) in the direction d = (sin αwt, cos αwt), through the pitch point
(r_w1, 0), to T2. The face runs over z ∈ [−b/2, b/2] with its centre at z = 0.

In the plane of action a contact line is straight and inclined at the base helix angle βb
to the axis (seed 002; Litvin & Fuentes, Gear Geometry and Applied Theory, 2nd ed., §14).
Measure ``s`` from the start of active profile A (pinion roll length ρ1 = ρ_SAP1) along the
line of action; the active zone is 0 ≤ s ≤ g_α. For tooth pair j at pinion roll distance
``roll`` = r_b1·φ1 the contact in the transverse slice at z sits at

    s_j(z) = roll + j·p_bt + h·z·tan βb,     h = +1 (right-hand pinion) or −1 (left-hand),

because a right-hand helicoid turns each slice counter-clockwise by z·tan βb / r_b1 as z
grows, which advances its contact along the line of action like a forward rotation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .gear import PairGeometry


def hand_sign(geom: PairGeometry) -> int:
    """+1 for a right-hand pinion, −1 for a left-hand pinion (the gear has the other hand)."""
    return 1 if geom.pair.helix_hand == "right" else -1


def tooth_pair_indices(geom: PairGeometry) -> np.ndarray:
    """Indices j of every tooth pair that can be in the active zone during one base pitch.

    With roll ∈ [0, p_bt) and h·z·tan βb ∈ [−b tan βb/2, b tan βb/2], s_j ∈ [0, g_α] needs
    j·p_bt ∈ (−p_bt − b tan βb/2, g_α + b tan βb/2].
    """
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    pbt = geom.transverse_base_pitch
    j_min = -math.ceil(half_axial / pbt) - 1
    j_max = math.ceil((geom.path_of_contact + half_axial) / pbt)
    return np.arange(j_min, j_max + 1)


def contact_roll_positions(geom: PairGeometry, roll: np.ndarray, z: np.ndarray,
                           pairs: np.ndarray | None = None) -> np.ndarray:
    """Position s (m) of the contact on the line of action for every roll, tooth pair, slice.

    Parameters
    ----------
    roll : (P,) pinion roll distance r_b1·φ1 (m).
    z : (S,) axial positions of the transverse slices (m), within [−b/2, b/2].
    pairs : tooth-pair indices j (default :func:`tooth_pair_indices`).

    Returns
    -------
    (P, J, S) array of s, NaN where the slice of that pair is outside the active zone
    [0, g_α]. The pinion roll length at the contact is ρ1 = ρ_SAP1 + s and the gear roll
    length ρ2 = ρ_EAP2 − s.
    """
    pairs = tooth_pair_indices(geom) if pairs is None else np.asarray(pairs)
    roll = np.asarray(roll, dtype=float)
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
    length is its axial extent divided by cos βb (seed 002's sum of segment lengths, here in
    closed form per line). For β = 0 a line covers the whole face or none of it.
    """
    pairs = tooth_pair_indices(geom)
    roll = np.asarray(roll, dtype=float)
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
    [max(0, f_α + f_β − 1), min(f_α, f_β)] (derivation in docs of seed 001 §1, written out
    here because the document only names the piecewise phases). The mean is exactly
    l_mean = b ε_α / cos βb (DESIGN.md). For β = 0: L ∈ {⌊ε_α⌋b, ⌈ε_α⌉b}.
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
    """``n_positions`` pinion roll distances (m) evenly over one base pitch, end excluded."""
    if n_positions < 1:
        raise ValueError("n_positions must be at least 1")
    return np.arange(n_positions) * (geom.transverse_base_pitch / n_positions)
