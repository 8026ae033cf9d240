"""Low-fluctuation design of a helical pair: integer overlap or transverse contact ratio.

The low-fluctuation paper §1 and §5 (and the contact-line paper): the total contact-line length L(φ) of a helical pair,
and with it the mesh stiffness, is constant over the mesh cycle when ε_α or ε_β is a
positive integer, ε_α = N⁺ or ε_β = N⁺. Since ε_β = b sin β / (π m_n) (ISO 21771:2007
eq. 91), an integer overlap ratio N is reached by the helix angle

    β = arcsin(π m_n N / b)                    (the contact-line paper; the low-fluctuation paper §1)

("forward": the next integer above the current ε_β, i.e. a larger β; "backward": the
integer below, a smaller β) or by the face width

    b = π m_n N / sin β                        (the low-fluctuation paper §1, their eq. for b).

Changing β changes the transverse pressure angle α_t, the base helix angle β_b and the
radii, hence ε_α: every candidate pair is re-derived with :func:`gearmesh.gear.pair_geometry`
(and refused by it if it cannot work). The contact-line fluctuation coefficient
ε_l = (L_max − L_min)/b (the low-fluctuation paper §5) against β is the V-curve of the low-fluctuation paper §5, whose
minimum (zero) is at integer ε_β.

All inputs and outputs are SI (m, rad); errors are :class:`GearmeshInputError` naming the
field in pair-file terms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Sequence

import numpy as np

from .contact import contact_length_closed_form, contact_length_summary
from .errors import GearmeshInputError
from .gear import GearPair, PairGeometry, involute, pair_geometry
from .limits import MAX_HELIX_ANGLE

_INTEGER_TOL = 1e-9


class DesignResult(NamedTuple):
    """A designed pair: the new :class:`GearPair`, its ε_β and ε_α (-), and its geometry."""

    pair: GearPair
    eps_beta: float
    eps_alpha: float
    geometry: PairGeometry


def _target_integer(eps: float, direction: str, n: int | None, field: str, value: object, what: str) -> int:
    """The integer N to reach: given ``n``, or the next one above (forward) / below (backward).

    ``field`` is the pair-file key the design changes and ``value`` its value now, for the error.

    An ε already integral (within 1e−9) is its own target in both directions.
    """
    if n is not None:
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise GearmeshInputError(f"{what} target", n, "must be a positive integer")
        return int(n)
    if direction not in ("forward", "backward"):
        raise GearmeshInputError("direction", direction, "must be 'forward' or 'backward'")
    nearest = round(eps)
    if nearest >= 1 and abs(eps - nearest) <= _INTEGER_TOL:
        return int(nearest)
    if direction == "forward":
        return int(math.floor(eps)) + 1
    target = int(math.floor(eps))
    if target < 1:
        raise GearmeshInputError(field, value, f"{what} = {eps:.4f} < 1: there is no positive integer below it "
                                 "(backward design impossible; design forward)")
    return target


def _face_width_change(pair: GearPair, new_b: float) -> tuple[float, float]:
    """Both face widths moved by the same amount, so the meshing (smaller) width becomes ``new_b``
    and a deliberately wider pinion or gear stays wider by the same margin."""
    delta = new_b - min(pair.face_width)
    return (pair.face_width[0] + delta, pair.face_width[1] + delta)


def pair_with_helix_angle(pair: GearPair, helix_angle: float, center_distance: str = "zero_backlash") -> GearPair:
    """``pair`` with the helix angle ``helix_angle`` (rad), the rest of its design kept.

    The centre distance depends on β (a = (z1 + z2) m_n / (2 cos β) for zero shift), so a
    given one cannot simply be carried over:

    - ``"zero_backlash"`` (default): keep the profile shifts (as given or as inferred by
      :func:`pair_geometry` from the old centre distance) and take the new zero-backlash
      centre distance (ISO 21771:2007 eqs. 57–59).
    - ``"keep"``: keep the operating centre distance a and re-choose the total shift for
      zero backlash at a (inv α_wt = inv α_t + 2 tan α_n Σx/Σz with cos α_wt = (r1 + r2) cos α_t / a),
      keeping the shift difference x1 − x2.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    helix_angle : float
        β (rad), in [0, 60°).
    center_distance : {'zero_backlash', 'keep'}, default 'zero_backlash'
        What becomes of a given centre distance (above).

    Returns
    -------
    GearPair
        The new pair (not yet through :func:`pair_geometry`).

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry, eqs. 57–59.
    """
    if not 0 <= helix_angle < MAX_HELIX_ANGLE:
        raise GearmeshInputError("helix_angle_deg", math.degrees(helix_angle), "must lie in [0, 60) degrees")
    if pair.center_distance is None:
        return pair.with_changes(helix_angle=helix_angle)
    geom = pair_geometry(pair)
    x = np.asarray(geom.profile_shift, dtype=float)
    if center_distance == "zero_backlash":
        return pair.with_changes(helix_angle=helix_angle, profile_shift=(float(x[0]), float(x[1])),
                                 center_distance=None)
    if center_distance != "keep":
        raise GearmeshInputError("center_distance", center_distance, "must be 'zero_backlash' or 'keep'")
    a = geom.center_distance
    an = pair.normal_pressure_angle
    alpha_t = math.atan(math.tan(an) / math.cos(helix_angle))
    r_sum = sum(pair.teeth) * pair.normal_module / math.cos(helix_angle) / 2
    cos_awt = r_sum * math.cos(alpha_t) / a
    if not 0 < cos_awt < 1:
        raise GearmeshInputError("center_distance_mm", a * 1e3,
                                 f"cannot be kept at helix angle {math.degrees(helix_angle):.4f} deg: the base "
                                 f"circles need more than {r_sum * math.cos(alpha_t) * 1e3:.3f} mm")
    x_sum = (involute(math.acos(cos_awt)) - involute(alpha_t)) * sum(pair.teeth) / (2 * math.tan(an))
    dx = x[0] - x[1]
    return pair.with_changes(helix_angle=helix_angle, profile_shift=((x_sum + dx) / 2, (x_sum - dx) / 2),
                             center_distance=a)


def integer_overlap_helix_angle(pair: GearPair, direction: str = "forward", n: int | None = None,
                                center_distance: str = "zero_backlash") -> DesignResult:
    """Helix angle giving an integer overlap ratio ε_β = N (the low-fluctuation paper §1, §5; the contact-line paper).

    β = arcsin(π m_n N / b) with b the meshing face width (m) and m_n the normal module (m).
    ``direction`` "forward" takes N = the next integer above the current ε_β (β grows),
    "backward" the integer below (β shrinks, N ≥ 1); ``n`` sets N directly. The low-fluctuation paper
    Table 1: pair 1 (β 10°, b 20 mm, ε_β 0.632) forward → 15.95°; pair 4 (21.84°, ε_β 1.353)
    backward → 15.95°. ``center_distance`` as in :func:`pair_with_helix_angle`.

    Refuses (field ``helix_angle_deg``) when π m_n N > b (no angle exists) or β ≥ 60°;
    the new pair must pass :func:`pair_geometry` (its refusals propagate).

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    direction : {'forward', 'backward'}, default 'forward'
        The next integer above the current ratio, or the one below (≥ 1).
    n : int, optional
        The integer N itself (≥ 1); overrides ``direction``.
    center_distance : {'zero_backlash', 'keep'}, default 'zero_backlash'
        As in :func:`pair_with_helix_angle`.

    Returns
    -------
    DesignResult
        The new pair, its ``eps_beta`` and ``eps_alpha`` (-) and its geometry.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §1, §5, Table 1.
    .. [2] *Numerical Simulation of Meshing Line Position and Length for Helical Gears*.
    .. [3] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry, eq. 91.
    """
    geom0 = pair_geometry(pair)
    target = _target_integer(geom0.eps_beta, direction, n, "helix_angle_deg",
                             round(math.degrees(pair.helix_angle), 9), "eps_beta")
    b = geom0.face_width
    arg = math.pi * pair.normal_module * target / b
    if arg > 1:
        raise GearmeshInputError("helix_angle_deg", math.degrees(pair.helix_angle),
                                 f"no helix angle gives eps_beta = {target}: it needs a face width of at least "
                                 f"pi*mn*N = {math.pi * pair.normal_module * target * 1e3:.3f} mm "
                                 f"(have {b * 1e3:.3f} mm)")
    beta = math.asin(arg)
    if beta >= MAX_HELIX_ANGLE:
        raise GearmeshInputError("helix_angle_deg", math.degrees(beta),
                                 f"eps_beta = {target} needs a helix angle of {math.degrees(beta):.3f} deg, "
                                 "at or above the 60 deg limit")
    new = pair_with_helix_angle(pair, beta, center_distance)
    geom = pair_geometry(new)
    return DesignResult(new, geom.eps_beta, geom.eps_alpha, geom)


def integer_overlap_face_width(pair: GearPair, direction: str = "forward", n: int | None = None) -> DesignResult:
    """Face width giving an integer overlap ratio ε_β = N (the low-fluctuation paper §1: b = π m_n N / sin β).

    b in m, m_n in m, β in rad. ``direction`` "forward" widens the face to the next
    integer above the current ε_β, "backward" narrows it to the integer below (N ≥ 1).
    Both face widths move by the same amount (a wider pinion stays wider). The low-fluctuation paper
    Table 1: pair 1 (β 10°, b 20 mm) → b = 31.66 mm. Refuses a spur pair (field
    ``helix_angle_deg``: ε_β = 0 for any face width).

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    direction : {'forward', 'backward'}, default 'forward'
        The next integer above the current ratio, or the one below (≥ 1).
    n : int, optional
        The integer N itself (≥ 1); overrides ``direction``.

    Returns
    -------
    DesignResult
        The new pair, its ``eps_beta`` and ``eps_alpha`` (-) and its geometry.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §1, Table 1.
    """
    if pair.helix_angle == 0:
        raise GearmeshInputError("helix_angle_deg", 0.0,
                                 "a spur pair has eps_beta = 0 for any face width; no face width makes it integer")
    geom0 = pair_geometry(pair)
    target = _target_integer(geom0.eps_beta, direction, n, "face_width_mm",
                             [round(b * 1e3, 9) for b in pair.face_width], "eps_beta")
    new_b = math.pi * pair.normal_module * target / math.sin(pair.helix_angle)
    widths = _face_width_change(pair, new_b)
    new = pair.with_changes(face_width=widths)
    geom = pair_geometry(new)
    return DesignResult(new, geom.eps_beta, geom.eps_alpha, geom)


def _eps_alpha_of_addendum(geom: PairGeometry, ha: float) -> float:
    """ε_α (-) when both addendum coefficients are ``ha`` (shifts, centre distance kept).

    ε_α = (Σ √(r_a,i² − r_b,i²) − a sin α_wt) / p_bt with r_a,i = r_i + (h_a + x_i) m_n
    (ISO 21771:2007 eqs. 45, 87).
    """
    mn = geom.pair.normal_module
    ra = geom.reference_radius + (ha + geom.profile_shift) * mn
    rho_a = np.sqrt(np.maximum(ra**2 - geom.base_radius**2, 0.0))
    return float((rho_a.sum() - geom.center_distance * math.sin(geom.operating_pressure_angle))
                 / geom.transverse_base_pitch)


def transverse_ratio_addendum(pair: GearPair, eps_alpha: float, keep_clearance: bool = True) -> DesignResult:
    """Addendum coefficient h_a* (-, both gears) giving the transverse contact ratio ``eps_alpha``.

    ε_α grows monotonically with the addendum: solved by Brent's method on the closed form
    of :func:`_eps_alpha_of_addendum` (profile shifts and centre distance kept, the shifts
    as given or inferred). ``keep_clearance`` raises the dedendum coefficient by the same
    amount as the addendum so the tip clearance is unchanged (a "high contact ratio"
    design; the deeper tool may undercut). The result is checked by :func:`pair_geometry`:
    long addenda soon give pointed teeth or interference and are refused there. Refuses
    (field ``addendum_coefficient``) when no h_a* in (0, 3] reaches ``eps_alpha``.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    eps_alpha : float
        Target transverse contact ratio ε_α (-).
    keep_clearance : bool, default True
        Raise the dedendum coefficient with the addendum (tip clearance kept).

    Returns
    -------
    DesignResult
        The new pair, its ``eps_beta`` and ``eps_alpha`` (-) and its geometry.

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry, eqs. 45, 87.
    """
    geom0 = pair_geometry(pair)
    fixed_pair = pair.with_changes(profile_shift=tuple(float(v) for v in geom0.profile_shift),
                                   center_distance=geom0.center_distance)
    lo, hi = 1e-3, 3.0
    f = lambda h: _eps_alpha_of_addendum(geom0, h) - eps_alpha  # noqa: E731
    if f(lo) > 0 or f(hi) < 0:
        raise GearmeshInputError("addendum_coefficient", list(pair.addendum_coefficient),
                                 f"no addendum coefficient in (0, 3] gives eps_alpha = {eps_alpha}")
    from scipy.optimize import brentq  # imported here: scipy.optimize costs ~0.7 s of start-up
    ha = brentq(f, lo, hi, xtol=1e-14, rtol=1e-14)
    changes = {"addendum_coefficient": (ha, ha)}
    if keep_clearance:
        changes["dedendum_coefficient"] = tuple(hf + ha - ha0 for hf, ha0 in
                                                zip(pair.dedendum_coefficient, pair.addendum_coefficient[::-1]))
    new = (fixed_pair if pair.center_distance is not None else pair.with_changes(
        profile_shift=fixed_pair.profile_shift)).with_changes(**changes)
    geom = pair_geometry(new)
    return DesignResult(new, geom.eps_beta, geom.eps_alpha, geom)


def integer_transverse_addendum(pair: GearPair, direction: str = "forward", n: int | None = None,
                                keep_clearance: bool = True) -> DesignResult:
    """Addendum coefficient giving an integer ε_α = N (the low-fluctuation paper §1): N is the next integer
    above (forward) or below (backward) the current ε_α; see :func:`transverse_ratio_addendum`.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    direction : {'forward', 'backward'}, default 'forward'
        The next integer above the current ratio, or the one below (≥ 1).
    n : int, optional
        The integer N itself (≥ 1); overrides ``direction``.
    keep_clearance : bool, default True
        As in :func:`transverse_ratio_addendum`.

    Returns
    -------
    DesignResult
        The new pair, its ``eps_beta`` and ``eps_alpha`` (-) and its geometry.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §1.
    """
    target = _target_integer(pair_geometry(pair).eps_alpha, direction, n, "addendum_coefficient",
                             list(pair.addendum_coefficient), "eps_alpha")
    return transverse_ratio_addendum(pair, target, keep_clearance)


def pair_with_contact_ratios(pair: GearPair, eps_alpha: float | None = None,
                             eps_beta: float | None = None) -> GearPair:
    """``pair`` redesigned to the given contact ratios: ε_β by the face width
    (b = π m_n ε_β / sin β, the low-fluctuation paper §1), ε_α by the addendum at constant tip clearance
    (:func:`transverse_ratio_addendum`); the transition-curve paper's contact-ratio study.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    eps_alpha : float, optional
        Target transverse contact ratio (≥ 1); None keeps the addenda.
    eps_beta : float, optional
        Target overlap ratio (> 0, helical pairs only); None keeps the face widths.

    Returns
    -------
    GearPair
        The redesigned pair.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §1.
    .. [2] [untitled] *Mesh stiffness of helical gears with the hob-generated root transition curve*.
    """
    if eps_beta is not None:
        if pair.helix_angle == 0 or eps_beta <= 0:
            raise GearmeshInputError("eps_beta", eps_beta, "needs a helical pair and a positive target")
        pair = pair.with_changes(face_width=_face_width_change(
            pair, math.pi * pair.normal_module * eps_beta / math.sin(pair.helix_angle)))
    if eps_alpha is not None:
        if eps_alpha < 1:
            raise GearmeshInputError("eps_alpha", eps_alpha, "must be at least 1 for a continuous mesh")
        pair = transverse_ratio_addendum(pair, eps_alpha).pair
    return pair


@dataclass(frozen=True)
class FluctuationCurve:
    """ε_l against helix angle (the low-fluctuation paper §5, the V-curve); arrays of the sweep length.

    ``helix_angle`` (rad); ``eps_alpha``, ``eps_beta`` (-) of each β's own geometry;
    ``l_mean``, ``l_min``, ``l_max`` (m) in closed form; ``eps_l`` = (l_max − l_min)/b (-)
    closed form, ``eps_l_numeric`` from the exactly clipped contact lines at every slope
    change of L (independent of the closed form), ``eps_l_sampled`` on an even grid of
    ``n_positions`` rolls (NaN if not asked). ``valid`` is False (values NaN) where
    :func:`pair_geometry` refuses the pair; ``reasons`` gives its message there.
    """

    helix_angle: np.ndarray
    eps_alpha: np.ndarray
    eps_beta: np.ndarray
    l_mean: np.ndarray
    l_min: np.ndarray
    l_max: np.ndarray
    eps_l: np.ndarray
    eps_l_numeric: np.ndarray
    eps_l_sampled: np.ndarray
    valid: np.ndarray
    reasons: tuple[str, ...]


def overlap_fluctuation_curve(pair: GearPair, helix_angles: Sequence[float] | np.ndarray,
                              n_positions: int | None = None,
                              center_distance: str = "zero_backlash") -> FluctuationCurve:
    """The contact-line fluctuation coefficient ε_l(β) over a sweep of helix angles (rad).

    Each β gets its own pair geometry (α_t, β_b, radii, ε_α all change with β;
    ``center_distance`` as in :func:`pair_with_helix_angle`), then L_min, L_max from
    :func:`gearmesh.contact.contact_length_closed_form` and, independently, from the
    clipped contact lines (:func:`gearmesh.contact.contact_length_summary`). The low-fluctuation paper §5:
    a V-shaped curve with its minimum ε_l = 0 at integer ε_β.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI).
    helix_angles : array_like
        (B,) helix angles β (rad).
    n_positions : int, optional
        Even roll grid for ``eps_l_sampled`` (default None: NaN).
    center_distance : {'zero_backlash', 'keep'}, default 'zero_backlash'
        As in :func:`pair_with_helix_angle`.

    Returns
    -------
    FluctuationCurve
        Per β (B,): ``eps_alpha``, ``eps_beta``, ``eps_l`` (-), ``l_mean``, ``l_min``, ``l_max`` (m),
        ``eps_l_numeric``, ``eps_l_sampled`` (-), ``valid`` and ``reasons``.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, §5.
    """
    betas = np.asarray(helix_angles, dtype=float)
    n = betas.size
    out = {k: np.full(n, np.nan) for k in ("eps_alpha", "eps_beta", "l_mean", "l_min", "l_max", "eps_l",
                                           "eps_l_numeric", "eps_l_sampled")}
    valid = np.zeros(n, dtype=bool)
    reasons: list[str] = []
    for k, beta in enumerate(betas.ravel()):
        try:
            geom = pair_geometry(pair_with_helix_angle(pair, float(beta), center_distance))
        except GearmeshInputError as exc:
            reasons.append(str(exc))
            continue
        reasons.append("")
        valid[k] = True
        mean, lo, hi = contact_length_closed_form(geom)
        summ = contact_length_summary(geom, n_positions)
        out["eps_alpha"][k], out["eps_beta"][k] = geom.eps_alpha, geom.eps_beta
        out["l_mean"][k], out["l_min"][k], out["l_max"][k] = mean, lo, hi
        out["eps_l"][k] = (hi - lo) / geom.face_width
        out["eps_l_numeric"][k] = summ.numeric_eps_l
        out["eps_l_sampled"][k] = summ.sampled_eps_l
    return FluctuationCurve(helix_angle=betas, valid=valid, reasons=tuple(reasons), **out)
