"""Loaded tooth contact analysis (LTCA) of a modified helical pair.

Everything inside is SI (m, N, rad). Displacements, separations and loads follow the
transverse line-of-action convention of :mod:`gearmesh.tca` and :mod:`gearmesh.stiffness`:
a point's load q is the transverse force it carries (its moment about the pinion axis over
r_b1), the applied force is F_bt = T1/r_b1, and the approach δ is the transverse rigid
displacement r_b1·Δφ1 (gear held). The normal load per unit length of contact line of a
point of width Δz is q/Δz (a slice carries a line Δz/cos βb long under the normal load
q/cos βb), which is also its transverse load per unit face width.

Model
-----
At every roll position the candidate points of :func:`gearmesh.tca.candidate_grid` (the
slice centres of every tooth pair in or near the active zone, with their unloaded
separations g_i) are loaded through independent transverse slices (Smith's slice theory,
as :mod:`gearmesh.stiffness`): point i of width Δz deflects

    δ − g_i = f_i(q_i) = c_i·q_i + δ_c(q_i),   c_i = (c_1(ρ1) + c_2(ρ2))/Δz,

with c_1, c_2 the per-unit-width bending + shear + axial + fillet-foundation compliances of
both teeth from :func:`gearmesh.slice_compliance.slice_compliance_table` resampled by
:func:`gearmesh.slice_compliance.pair_slice_table` (Yang & Lin 1987, Tian 2004, Sainsot et al.
2004; the tip-edge points of regions 2/3 take each tooth's compliance at its own touched
roll length — the tip of one, ρ_P of the other — for a load along the line of action: the
small inclination of an edge load off the line of action is neglected) and δ_c the local
contact approach. The contact problem is

    q_i ≥ 0,   Σ q_i = F,   δ − g_i = f_i(q_i) where q_i > 0,   q_i = 0 where g_i ≥ δ.

Independent slices make the compliance matrix diagonal, so the complementarity problem is
solved *exactly* by one monotone scalar equation per position: q_i(δ) = f_i⁻¹((δ − g_i)_+)
is convex and increasing in δ, so Newton's method on S(δ) = Σ q_i(δ) − F from an upper
bound converges monotonically (no active-set cycling, no tolerance on the contact set),
with an inner Newton inversion of each f_i (concave, from an upper bound). This is the
active-set/NNLS problem (docs/modelling.md) for a diagonal influence matrix; the tangent mesh
stiffness dF/dδ = Σ_loaded 1/f_i'(q_i) follows exactly.

Why independent slices: it is the model whose unloaded, linearised limit *is* the
stiffness stage (K = Σ slices in parallel), so LTE = F/K(φ) holds to round-off and the
two stages cannot drift apart; neighbouring-slice coupling (the tooth as a plate, e.g.
Schmidt's/Seager's influence coefficients) spreads load across the face and softens
edge peaks — left out, see the report.

The local contact law and the load-independent model (points, separations, compliances) are
:mod:`gearmesh.ltca_model`'s; this module solves the contact at each load.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np

from .choices import DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD
from .errors import GearmeshInputError
from .gear import PairGeometry, pinion_torque
from .limits import positive_values
from .loads import check_loads
from .body import mesh_body_compliance
from .deflection import mesh_deflection, mesh_misalignment
from .deviation import lead_gap
from .ltca_model import ContactLaw, LTCAModel, contact_law, ltca_model
from .tooth import require_stiffness_data
from .separation import REGION_APPROACH_TIP, REGION_RECESS_TIP
from .tca import (DEFAULT_EXTENSION, CandidateGrid, TCAResult, first_contact, nanmin, engagement_point,
                  engagement_separation, pair_lead_slope)

__all__ = [
    "check_torques", "pinion_torques", "solve_contact", "solve_contact_tabulated", "load_sums", "law_point_scales",
    "LTCAResult", "ltca", "contact_tangent_compliance",
    "edge_tangent_stiffness", "with_loaded_extension", "MESH_ORDERS", "lte_harmonics", "torque_gaps",
]

#: Mesh orders of the loaded-TE harmonics (ltca.nc, the optimiser's TE criteria).
MESH_ORDERS = (1, 2, 3)


def contact_tangent_compliance(geom: PairGeometry, pinion_torque: float) -> float:
    """The linear mesh stiffness's contact compliance (m²/N per unit transverse width).

    The role of :func:`gearmesh.slice_compliance.hertz_compliance_transverse`: the tangent of the LTCA's
    Palmgren law [1]_, [2]_ (:func:`~gearmesh.ltca_model.contact_law`) at the mean line load of
    ``pinion_torque``, c = 0.9 δ_t(f)/f with f = F_bt/(b εα) the transverse force per unit of contact
    width (the contact lines' transverse widths sum to b εα on average, l_mean = b εα/cos βb). So the
    stiffness stage's TVMS, the LTCA's loaded stiffness and the contact table's tangent are one
    stiffness at one load (issue 28; Palmgren's law is of the size of Weber's contact part,
    docs/validation.md). The tangent falls as f^-0.1: ±10 % of the contact compliance for a load 2.5× off.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its material (:func:`gearmesh.gear.pair_geometry`).
    pinion_torque : float
        Pinion torque T1, N·m (positive, finite).

    Returns
    -------
    float
        Tangent contact compliance per unit transverse width, m²/N.

    Raises
    ------
    GearmeshInputError
        ``torque_Nm`` not positive and finite, or the pair lacks the stiffness data.

    References
    ----------
    .. [1] Palmgren A., Ball and Roller Bearing Engineering, 3rd ed., SKF Industries, Philadelphia,
       1959.
    .. [2] Harris T.A., Kotzalas M.N., Rolling Bearing Analysis, 5th ed., CRC Press, Boca Raton, 2007,
       eq. 6.41.
    """
    require_stiffness_data(geom, need_bore=False)
    if not (math.isfinite(pinion_torque) and pinion_torque > 0):
        raise GearmeshInputError("torque_Nm", pinion_torque, "must be a positive finite number")
    f = pinion_torque / float(geom.base_radius[0]) / (geom.face_width * geom.eps_alpha)
    law = contact_law(geom, 1.0)  # width 1 m: δ_t = coefficient · f^0.9
    return law.exponent * law.coefficient * f ** law.exponent / f


def edge_tangent_stiffness(result: "LTCAResult") -> np.ndarray:
    """Tangent stiffness (T, P) in N/m of the loaded tip-edge points beyond the active zone.

    The loaded extension of contact (the unrelieved tips that touch under load before the start and
    after the end of the active profile; Munro 1990, Velex & Maatar 1996 [1]_). Each loaded point i of
    :func:`solve_contact` has δ − g_i = c_i q_i + coef·q_i^m, so its tangent is
    1/(c_i + coef·m·q_i^(m−1)); the LTCA's tangent ``stiffness`` is the sum over all loaded points,
    this the sum over the tip-edge ones alone (teeth only: the bodies' series compliance,
    :mod:`gearmesh.body`, is not in it).

    Parameters
    ----------
    result : LTCAResult
        An LTCA (:func:`ltca`) with its ``model`` and ``load`` (T, P, J, N) N.

    Returns
    -------
    numpy.ndarray
        (T, P) tangent stiffness of the tip-edge points (regions 2 and 3), N/m.

    References
    ----------
    .. [1] Velex P., Maatar M., "A mathematical model for analyzing the influence of shape
       deviations and mounting errors on gear dynamic behaviour", J. Sound Vib. 191 (1996) 629–660.
    """
    model = result.model
    law, g = model.law, model.grid
    corner = (g.region == REGION_APPROACH_TIP) | (g.region == REGION_RECESS_TIP)
    p = result.load.shape[1]
    q = result.load
    c = model.compliance[None, :p] + law.linear
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = c + (law.coefficient * law.exponent * q ** (law.exponent - 1.0) if law.coefficient else 0.0)
        k = np.where(corner[None, :p] & (q > 0), 1.0 / slope, 0.0)
    return k.sum(axis=(2, 3))


def with_loaded_extension(geom: PairGeometry, K: np.ndarray, pinion_torque: float, method: str = DEFAULT_TOOTH_METHOD,
                          points: int = 50) -> np.ndarray:
    """The linear TVMS ``K`` with the loaded extension of contact added in parallel with the teeth.

    Added inside the bodies' series compliance: the tip-edge tangent stiffness
    (:func:`edge_tangent_stiffness`) of the LTCA at ``pinion_torque`` on the same rolls. The linear
    TVMS counts the active zone only; under load the unrelieved tips also touch beyond it, and that
    contact is what the LTCA's tangent has and the TVMS lacks (issue 28: for the default pair at
    1000 N·m 77 of its 767 N/µm). So ``tvms``, ``ltca`` and ``contact`` are one mesh stiffness at
    one load.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    K : array_like
        (P,) linear mesh stiffness, N/m, evenly over one mesh cycle from roll 0, as
        :func:`gearmesh.stiffness.mesh_stiffness`.
    pinion_torque : float
        Pinion torque T1 of the LTCA, N·m.
    method : str, default 'fe'
        Tooth model of the LTCA (:data:`gearmesh.choices.TOOTH_METHODS`).
    points : int, default 50
        Candidate points per contact line of the LTCA.

    Returns
    -------
    numpy.ndarray
        (P,) mesh stiffness with the loaded tip-edge contact, N/m (``K`` itself when no tip edge
        carries load).

    References
    ----------
    .. [1] Velex P., Maatar M., "A mathematical model for analyzing the influence of shape
       deviations and mounting errors on gear dynamic behaviour", J. Sound Vib. 191 (1996) 629–660.
    """
    K = np.asarray(K, dtype=float)
    res = ltca(geom, [pinion_torque], positions=K.size, points=points, method=method)
    k_edge = edge_tangent_stiffness(res)[0]
    if not np.any(k_edge):
        return K
    c = mesh_body_compliance(geom)
    if c:
        return 1.0 / (1.0 / (1.0 / (1.0 / K - c) + k_edge) + c)
    return K + k_edge


# --------------------------------------------------------------------------------------
# The exact solve of the diagonal contact problem
# --------------------------------------------------------------------------------------


def _invert(d, c, coef: float, m: float, q_start=None, tol: float = 1e-14, max_iter: int = 60):
    """q ≥ 0 with c·q + coef·q^m = d for d ≥ 0 (elementwise), and dq/dd = 1/f'(q).

    f is concave (m < 1), so Newton from an upper bound (q0 = min(d/c, (d/coef)^(1/m)), both
    bounds) steps once below the root and then rises monotonically to it. Only the points
    with d > 0 are iterated (most candidate points of a contact problem carry nothing).
    """
    d = np.asarray(d, dtype=float)
    c = np.broadcast_to(c, d.shape)
    pos = d > 0
    q_out = np.zeros(d.shape)
    dq_out = np.zeros(d.shape)
    if not pos.any():
        return q_out, dq_out
    dd, cc = d[pos], c[pos]
    if coef == 0.0:
        q_out[pos], dq_out[pos] = dd / cc, 1.0 / cc
        return q_out, dq_out
    q = np.minimum(dd / cc, (dd / coef) ** (1.0 / m))
    if q_start is not None:
        qs = np.broadcast_to(q_start, d.shape)[pos]
        q = np.minimum(q, np.where(qs > 0, qs, q))
    for _ in range(max_iter):
        qm1 = q ** (m - 1.0)
        fp = cc + coef * m * qm1
        step = (cc * q + coef * q * qm1 - dd) / fp
        q = q - step
        if np.all(np.abs(step) <= tol * q):
            break
    q_out[pos] = q
    dq_out[pos] = 1.0 / (cc + coef * m * q ** (m - 1.0))
    return q_out, dq_out


#: Range and step of ln y of the tabulated universal inverse (:func:`invert_tabulated`).
_TABLE_LOG_Y = (-80.0, 80.0, 1.0 / 32.0)


@functools.lru_cache(maxsize=4)
def _universal_inverse(m: float) -> tuple[np.ndarray, np.ndarray]:
    """ln X and d ln X/d ln y on the grid of ln y (:data:`_TABLE_LOG_Y`), X(y) the root of
    X + X^m = y, solved by Newton in ln X to round-off (each node independently)."""
    lo, hi, h = _TABLE_LOG_Y
    u = np.arange(lo, hi + 0.5 * h, h)
    v = np.minimum(u, u / m)  # the larger-term asymptote, an upper bound of ln X
    for _ in range(200):
        x, xm = np.exp(v), np.exp(m * v)
        step = (np.log(x + xm) - u) * (x + xm) / (x + m * xm)  # Newton on ln(X + X^m) = u in ln X
        v = v - step
        if np.all(np.abs(step) <= 1e-15 * np.maximum(1.0, np.abs(v))):
            break
    x, xm = np.exp(v), np.exp(m * v)
    return v, (x + xm) / (x + m * xm)


def law_scales(c, coef: float, m: float) -> tuple[np.ndarray, np.ndarray]:
    """ln Q and ln(c·Q) of points of compliance ``c`` (m/N) under the law c·q + coef·q^m: Q =
    (coef/c)^(1/(1−m)) is the load at which both terms are equal (:func:`invert_tabulated`).

    Parameters
    ----------
    c : array_like
        Linear compliances of the points, m/N.
    coef : float
        Coefficient of the power-law term, m/N^m.
    m : float
        Exponent of the power-law term (< 1).

    Returns
    -------
    log_q : numpy.ndarray
        ln Q, Q in N, shaped like ``c``.
    log_cq : numpy.ndarray
        ln(c·Q), c·Q in m, shaped like ``c``.
    """
    log_c = np.log(c)
    log_q = (math.log(coef) - log_c) / (1.0 - m)
    return log_q, log_c + log_q


def log_universal_inverse(u: np.ndarray, m: float) -> np.ndarray:
    """ln X of the root X of X + X^m = y for ln y = ``u`` (array), from the table of
    :func:`_universal_inverse` by cubic Hermite interpolation; NaN outside the table.

    Parameters
    ----------
    u : numpy.ndarray
        ln y (dimensionless).
    m : float
        Exponent of the power-law term (< 1).

    Returns
    -------
    numpy.ndarray
        ln X, shaped like ``u``; NaN where |ln y| lies beyond the table.
    """
    lo, hi, h = _TABLE_LOG_Y
    v_tab, s_tab = _universal_inverse(float(m))
    t = (u - lo) * (1.0 / h)
    inside = (t >= 0.0) & (t < v_tab.size - 1)
    i = np.where(inside, t, 0.0).astype(np.intp)
    t = t - i
    t2 = t * t
    h00, h01 = (2 * t - 3) * t2 + 1, (3 - 2 * t) * t2
    h10, h11 = ((t - 2) * t + 1) * t * h, (t - 1) * t2 * h
    v = h00 * v_tab[i] + h10 * s_tab[i] + h01 * v_tab[i + 1] + h11 * s_tab[i + 1]
    return np.where(inside, v, np.nan) if not inside.all() else v


def invert_tabulated(d, c, coef: float, m: float):
    """q ≥ 0 with c·q + coef·q^m = d (elementwise; 0 where d ≤ 0) and dq/dd, from one universal table.

    Instead of a Newton iteration per point: with Q = (coef/c)^(1/(1−m)) (the load at which both terms
    are equal) q = Q·X(d/(c·Q)), X the root of X + X^m = y, tabulated once in ln X against ln y and read
    by cubic Hermite interpolation (values and slopes at the nodes; relative error of q about 1e-13
    over the table, checked by test). dq/dd = X/(c·(X + m·(y − X))) needs no power (X^m = y − X).
    Outside the table (|ln y| > 80) the exact :func:`_invert`. For ``coef`` = 0 (linear law) q = d/c
    exactly.

    Parameters
    ----------
    d : array_like
        Approach beyond each point's separation, δ − g, m.
    c : array_like
        Linear compliance of each point, m/N, broadcast to ``d``.
    coef : float
        Coefficient of the power-law term, m/N^m (0: linear law).
    m : float
        Exponent of the power-law term (< 1).

    Returns
    -------
    q : numpy.ndarray
        Load of each point, N, shaped like ``d``.
    dq : numpy.ndarray
        Tangent dq/dd, N/m (0 where unloaded).
    """
    d = np.asarray(d, dtype=float)
    c = np.broadcast_to(np.asarray(c, dtype=float), d.shape)
    pos = d > 0
    q_out, dq_out = np.zeros(d.shape), np.zeros(d.shape)
    if not pos.any():
        return q_out, dq_out
    dd, cc = d[pos], c[pos]
    if coef == 0.0:
        q_out[pos], dq_out[pos] = dd / cc, 1.0 / cc
        return q_out, dq_out
    log_q, log_cq = law_scales(cc, coef, m)
    u = np.log(dd) - log_cq
    v = log_universal_inverse(u, m)
    x, y = np.exp(v), np.exp(u)
    q = np.exp(log_q + v)
    dq = x / (cc * (x + m * (y - x)))
    outside = np.isnan(v)
    if outside.any():
        q[outside], dq[outside] = _invert(dd[outside], cc[outside], coef, m)
    q_out[pos], dq_out[pos] = q, dq
    return q_out, dq_out



def _law_scales_loop(comp, coef, m, big_q, log_cq, cq):
    """Each point's scales of the universal inverse (:func:`law_scales`) for the loop of
    :func:`load_sums`: Q, ln(c·Q) and c·Q into ``big_q``, ``log_cq``, ``cq`` (the rows' shape), with
    the loop's own expressions (compiled alike: the same values it would compute itself)."""
    rows, npts = comp.shape
    for k in range(rows):
        for i in range(npts):
            c = comp[k, i]
            log_c = np.log(c)
            log_q = (np.log(coef) - log_c) / (1.0 - m)
            big_q[k, i] = np.exp(log_q)
            log_cq[k, i] = log_c + log_q
            cq[k, i] = c * big_q[k, i]


def _load_sums_loop(gap, comp, approach, mask, coef, m, v_tab, s_tab, lo, h, force, stiff, masked, outside,
                    point_q, point_dq, scales, rows):
    """The loop of :func:`load_sums` (compiled by numba on first use): for each row r of ``rows``
    (indices k into ``gap``, ``comp``, ``mask``, ``scales``), the sums over its points i of q_i,
    dq_i/dd and (``mask``; (0, 0): none) q_i at every approach x_rj, d = x_rj − g_ki, into row r of
    the outputs; with ``point_q``, ``point_dq`` (len(rows), points) (else (0, 0)) each point's q_i
    and dq_i/dd at the last approach; ``scales`` (3, R, points) the points' Q, ln(c·Q), c·Q from
    :func:`_law_scales_loop` (else (0, 0, 0): computed here)."""
    npts = gap.shape[1]
    nu = approach.shape[1]
    last = v_tab.size - 1
    inv_h = 1.0 / h
    points = point_q.shape[0] > 0
    scaled = scales.shape[0] > 0
    masking = mask.shape[0] > 0
    for r in range(rows.size):
        k = rows[r]
        for i in range(npts):
            g = gap[k, i]
            if not approach[r, nu - 1] - g > 0.0:  # not reached by the largest approach (or no point: inf)
                continue
            c = comp[k, i]
            counted = masking and mask[k, i]
            if coef == 0.0:
                for j in range(nu):
                    d = approach[r, j] - g
                    if d > 0.0:
                        force[r, j] += d / c
                        stiff[r, j] += 1.0 / c
                        if counted:
                            masked[r, j] += d / c
                if points:
                    point_q[r, i] = (approach[r, nu - 1] - g) / c
                    point_dq[r, i] = 1.0 / c
                continue
            if scaled:
                big_q, log_cq, cq = scales[0, k, i], scales[1, k, i], scales[2, k, i]
            else:
                log_c = np.log(c)
                log_q = (np.log(coef) - log_c) / (1.0 - m)
                big_q = np.exp(log_q)
                log_cq = log_c + log_q
                cq = c * big_q
            for j in range(nu):
                d = approach[r, j] - g
                if d <= 0.0:
                    continue
                t = (np.log(d) - log_cq - lo) * inv_h
                if not (t >= 0.0 and t < last):
                    outside[r] = True
                    continue
                ti = int(t)
                t -= ti
                t2 = t * t
                v = (((2 * t - 3) * t2 + 1) * v_tab[ti] + ((t - 2) * t + 1) * t * h * s_tab[ti]
                     + (3 - 2 * t) * t2 * v_tab[ti + 1] + (t - 1) * t2 * h * s_tab[ti + 1])
                x = np.exp(v)
                q = big_q * x
                dq = x / (c * (x + m * (d / cq - x)))
                force[r, j] += q
                stiff[r, j] += dq
                if counted:
                    masked[r, j] += q
                if points and j == nu - 1:
                    point_q[r, i] = q
                    point_dq[r, i] = dq


_COMPILED: dict = {}


def _kernel(name: str):
    """The compiled loop ``name`` ('loop': :func:`_load_sums_loop`, 'scales': :func:`_law_scales_loop`),
    compiled (or loaded from numba's on-disk cache) on first use."""
    if name not in _COMPILED:
        from numba import njit

        _COMPILED[name] = njit(cache=True)({"loop": _load_sums_loop, "scales": _law_scales_loop}[name])
    return _COMPILED[name]


def law_point_scales(compliance: np.ndarray, law: ContactLaw) -> np.ndarray:
    """Q, ln(c·Q) and c·Q (3, R, M) of points of compliance ``compliance`` (R, M) m/N under ``law``.

    As :func:`load_sums` computes them (its ``scales``: a Newton iteration over the approach passes
    the same points many times); (0, 0, 0) for a linear law, which needs none.

    Parameters
    ----------
    compliance : numpy.ndarray
        (R, M) linear compliance of each point, m/N, the law's linear part included.
    law : ContactLaw
        The local contact law (:func:`gearmesh.ltca_model.contact_law`).

    Returns
    -------
    numpy.ndarray
        (3, R, M): Q (N), ln(c·Q) (c·Q in m), c·Q (m); shape (0, 0, 0) for a linear law.
    """
    comp = np.ascontiguousarray(compliance, dtype=float)
    if not law.coefficient:
        return np.zeros((0, 0, 0))
    out = np.empty((3,) + comp.shape)
    _kernel("scales")(comp, float(law.coefficient), float(law.exponent), out[0], out[1], out[2])
    return out


def load_sums(gap: np.ndarray, compliance: np.ndarray, approach: np.ndarray, law: ContactLaw, mask=None,
              points: bool = False, scales: np.ndarray | None = None, rows: np.ndarray | None = None):
    """Per row, the total load, its tangent and the masked points' load at several approaches.

    Σ q_i (N), Σ dq_i/dδ (N/m) and the load of the points in ``mask``: q_i the root of
    c_i·q + coef·q^m = δ − g_i (0 where δ ≤ g_i). With ``rows`` only those rows of ``gap``,
    ``compliance``, ``mask`` and ``scales`` are taken, ``approach`` one row for each, and the results
    have len(rows) rows: what the same call on the rows taken out gives, without copying them.

    Each root by :func:`invert_tabulated`'s method — q = Q·X(y), Q = (coef/c)^(1/(1−m)) the load
    at which both terms are equal, y = d/(c·Q), X the root of X + X^m = y from its universal table
    by cubic Hermite interpolation, dq/dd = X/(c·(X + m·(y − X))) — in one compiled pass (numba):
    Q and c·Q once per point (or taken from ``scales``, :func:`law_point_scales` of the same
    points), only the points the largest approach reaches. A row with a point beyond the universal
    table is summed again by :func:`invert_tabulated` (Newton there).

    Parameters
    ----------
    gap : numpy.ndarray
        (R, M) unloaded separations of the points, m; inf where no point.
    compliance : numpy.ndarray
        (R, M) linear compliances, m/N, the law's linear part included.
    approach : numpy.ndarray
        (R, U) approaches δ, m, increasing along each row ((len(rows), U) with ``rows``).
    law : ContactLaw
        The local contact law (:func:`gearmesh.ltca_model.contact_law`).
    mask : numpy.ndarray of bool, optional
        (R, M) points whose load is summed apart (e.g. the entering pair); None: none.
    points : bool, default False
        Also return each point's q_i and dq_i/dδ at the last approach.
    scales : numpy.ndarray, optional
        (3, R, M) the points' scales from :func:`law_point_scales`; None: computed here.
    rows : numpy.ndarray of int, optional
        Indices of the rows to sum; None: all.

    Returns
    -------
    force, stiffness, masked : numpy.ndarray
        (R, U) Σ q_i (N), Σ dq_i/dδ (N/m), Σ of the masked q_i (N).
    point_load, point_tangent : numpy.ndarray
        Only with ``points``: (R, M) q_i (N) and dq_i/dδ (N/m) at the last approach.
    """
    gap, comp = np.ascontiguousarray(gap, dtype=float), np.ascontiguousarray(compliance, dtype=float)
    x = np.ascontiguousarray(approach, dtype=float)
    rows = np.arange(gap.shape[0]) if rows is None else np.ascontiguousarray(rows, dtype=np.int64)
    mask = np.zeros((0, 0), dtype=np.bool_) if mask is None else np.ascontiguousarray(mask, dtype=np.bool_)
    out = [np.zeros(x.shape) for _ in range(3)]
    per_point = [np.zeros((rows.size, gap.shape[1]) if points else (0, 0)) for _ in range(2)]
    outside = np.zeros(rows.size, dtype=np.bool_)
    scales = np.zeros((0, 0, 0)) if scales is None or not law.coefficient else np.ascontiguousarray(scales, dtype=float)
    lo, _, h = _TABLE_LOG_Y
    v_tab, s_tab = _universal_inverse(float(law.exponent))
    _kernel("loop")(gap, comp, x, mask, float(law.coefficient), float(law.exponent), v_tab, s_tab, lo, h, *out,
                    outside, *per_point, scales, rows)
    for r in np.flatnonzero(outside):
        k = rows[r]
        d = x[r, :, None] - gap[k, None, :]
        q, dq = invert_tabulated(np.where(np.isfinite(d), d, -1.0), np.broadcast_to(comp[k], d.shape),
                                 law.coefficient, law.exponent)
        masked = np.where(mask[k], q, 0.0).sum(axis=1) if mask.size else np.zeros(d.shape[0])
        out[0][r], out[1][r], out[2][r] = q.sum(axis=1), dq.sum(axis=1), masked
        if points:
            per_point[0][r], per_point[1][r] = q[-1], dq[-1]
    return (*out, *per_point) if points else tuple(out)


def _contact_rows(gap: np.ndarray, compliance: np.ndarray, force, law: ContactLaw):
    """The contact problem of :func:`solve_contact` made ready to solve: separations (B, M) with
    inf where no point can touch, compliances (B, M) with the law's linear part, forces (B,) and
    the upper bound of the approach δ (B,) with all of F on the point closest to contact."""
    g = np.where(np.isfinite(gap), gap, np.inf)
    c_eff = np.where(np.isfinite(gap), compliance, 1.0) + law.linear
    force = np.asarray(force, dtype=float)
    rows = np.arange(g.shape[0])
    i_min = np.argmin(g, axis=1)
    g_min = g[rows, i_min]
    if not np.all(np.isfinite(g_min)):
        raise GearmeshInputError("positions", int(np.sum(~np.isfinite(g_min))),
                                 "roll positions without any candidate contact point")
    coef, m = law.coefficient, law.exponent
    return g, c_eff, force, g_min + c_eff[rows, i_min] * force + (coef * force**m if coef else 0.0)


def solve_contact_tabulated(gap: np.ndarray, compliance: np.ndarray, force: np.ndarray, law: ContactLaw,
                            delta_start=None, rtol: float = 1e-12, max_iter: int = 100):
    """:func:`solve_contact`'s problem with the tabulated inversion of the contact law
    (:func:`invert_tabulated`, relative error of a load about 1e-13, below ``rtol``), for many rows.

    The approach of each row by Newton on S(δ) = Σ q_i(δ) − F with the compiled load sums of
    :func:`load_sums`, each row until its own |S| ≤ rtol·F/10 (the rows still iterating copied out
    for each pass, their loads kept from the pass that meets it), from ``delta_start`` where it is
    below the default upper bound (all of F on the point closest to contact). S is convex and
    increasing: Newton from an upper bound descends monotonically to the root, and from a point left
    of it steps once to its right.

    Parameters
    ----------
    gap : numpy.ndarray
        (B, M) unloaded separations, m; NaN or inf for points that cannot touch.
    compliance : numpy.ndarray
        (B, M) linear compliance of each point, m/N: teeth (+ linear contact).
    force : numpy.ndarray
        (B,) total transverse force, N, > 0.
    law : ContactLaw
        The local contact law (:func:`~gearmesh.ltca_model.contact_law`).
    delta_start : array_like, optional
        (B,) guesses of the approach, m (a warm start).
    rtol : float, default 1e-12
        Relative tolerance of the load sum.
    max_iter : int, default 100
        Newton passes before a RuntimeError.

    Returns
    -------
    q : numpy.ndarray
        (B, M) loads, N.
    delta : numpy.ndarray
        (B,) approach δ, m.
    dq : numpy.ndarray
        (B, M) each point's tangent dq_i/dδ, N/m (0 where unloaded).

    Raises
    ------
    GearmeshInputError
        A row without any candidate contact point.
    RuntimeError
        The load sum does not converge.
    """
    g, c_eff, force, bound = _contact_rows(gap, compliance, force, law)
    delta = bound.copy() if delta_start is None else np.where(np.asarray(delta_start) < bound, delta_start, bound)
    q, dq = np.zeros(g.shape), np.zeros(g.shape)
    rows = np.arange(delta.size)
    scales = law_point_scales(c_eff, law)  # once: the points are the same in every pass
    for _ in range(max_iter):
        s, k, _, q_rows, dq_rows = load_sums(g, c_eff, delta[rows, None], law, points=True,
                                             scales=scales if scales.size else None, rows=rows)
        resid = s[:, 0] - force[rows]
        done = np.abs(resid) <= 0.1 * rtol * force[rows]
        q[rows[done]], dq[rows[done]] = q_rows[done], dq_rows[done]
        rows, resid, k = rows[~done], resid[~done], k[~done, 0]
        if not rows.size:
            return q, delta, dq
        with np.errstate(divide="ignore", invalid="ignore"):  # k = 0: left of every point, back to the bound
            delta[rows] = np.where(k > 0, delta[rows] - resid / k, bound[rows])
    raise RuntimeError("tabulated LTCA load solve did not converge (load sum differs from the applied force)")


def solve_contact(gap: np.ndarray, compliance: np.ndarray, force: np.ndarray, law: ContactLaw,
                  rtol: float = 1e-12, max_iter: int = 200, inner_tol: float = 1e-14, delta_start=None):
    """Loads, approach and tangent stiffness of independent contact points (exact LCP solve).

    Complementarity holds exactly: q_i > 0 only where g_i < δ, and there
    δ − g_i = c_i q_i + δ_c(q_i) to the inner tolerance; Σ q = F to ``rtol`` (module docstring:
    Newton on the convex increasing load sum from an upper bound).

    Parameters
    ----------
    gap : numpy.ndarray
        (B, M) unloaded separations, m; NaN or inf for points that cannot touch.
    compliance : numpy.ndarray
        (B, M) linear compliance of each point, m/N: teeth (+ linear contact).
    force : numpy.ndarray
        (B,) total transverse force, N, > 0.
    law : ContactLaw
        The local contact law (:func:`~gearmesh.ltca_model.contact_law`).
    rtol : float, default 1e-12
        Relative tolerance of the load sum.
    max_iter : int, default 200
        Newton steps on the approach.
    inner_tol : float, default 1e-14
        Relative tolerance of each point's inversion.
    delta_start : array_like, optional
        (B,) guesses of the approach, m, used where they are an upper bound closer than the default
        one (a warm start: fewer Newton steps, same root).

    Returns
    -------
    q : numpy.ndarray
        (B, M) loads, N.
    delta : numpy.ndarray
        (B,) approach δ, m.
    stiffness : numpy.ndarray
        (B,) tangent stiffness dF/dδ, N/m.
    iterations : int
        Newton steps used.

    Raises
    ------
    GearmeshInputError
        A row without any candidate contact point.
    RuntimeError
        The load sum does not converge.
    """
    g, c_eff, force, delta = _contact_rows(gap, compliance, force, law)
    coef, m = law.coefficient, law.exponent
    q = None
    if delta_start is not None:
        ds = np.asarray(delta_start, dtype=float)
        ok = np.isfinite(ds) & (ds < delta)
        if ok.any():
            d = np.where(ok, ds, delta)[:, None] - g
            q_s, _ = _invert(np.where(np.isfinite(d), d, -1.0), c_eff, coef, m, tol=inner_tol)
            delta = np.where(ok & (q_s.sum(axis=1) >= force), ds, delta)  # still an upper bound: Newton from it
    it = 0
    converged = False
    for it in range(1, max_iter + 1):
        d = delta[:, None] - g
        q, dq = _invert(np.where(np.isfinite(d), d, -1.0), c_eff, coef, m, q, tol=inner_tol)
        resid = q.sum(axis=1) - force
        if np.all(np.abs(resid) <= rtol * force):
            converged = True
            break
        # convex increasing S(δ): Newton from the right decreases monotonically to the root
        delta = delta - resid / dq.sum(axis=1)
    if not converged:
        d = delta[:, None] - g
        q, dq = _invert(np.where(np.isfinite(d), d, -1.0), c_eff, coef, m, q, tol=inner_tol)
    if not np.all(np.abs(q.sum(axis=1) - force) <= max(1e-9, 10 * rtol) * force):
        raise RuntimeError("LTCA load solve did not converge (load sum differs from the applied force)")
    return q, delta, dq.sum(axis=1), it


# --------------------------------------------------------------------------------------
# Torques
# --------------------------------------------------------------------------------------


def check_torques(torques, field: str = "torques_Nm") -> np.ndarray:
    """Torques (N·m) as a 1-d float array; refuses empty, non-numeric, non-finite, non-positive.

    Parameters
    ----------
    torques : float or array_like
        Torque(s), N·m.
    field : str, default 'torques_Nm'
        Field named in the error.

    Returns
    -------
    numpy.ndarray
        (T,) torques, N·m.

    Raises
    ------
    GearmeshInputError
        Empty, non-numeric, non-finite or non-positive torques.
    """
    return positive_values(torques, field, "N m", note="; the pinion drives")


def pinion_torques(geom: PairGeometry, torques, on: str = "pinion", field: str = "torques_Nm") -> np.ndarray:
    """Pinion torques T1 (N·m): as given, or from gear torques T2 by T1 = T2·z1/z2.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    torques : float or array_like
        Torque(s), N·m.
    on : {'pinion', 'gear'}, default 'pinion'
        The member the torques act on.
    field : str, default 'torques_Nm'
        Field named in an error.

    Returns
    -------
    numpy.ndarray
        (T,) pinion torques T1, N·m.
    """
    return pinion_torque(geom.pair, check_torques(torques, field), on)


def loaded_pinion_torques(geom: PairGeometry, torques, on: str = "pinion",
                          field: str = "torques_Nm") -> tuple[np.ndarray, np.ndarray]:
    """The torques as given and as pinion torques T1 (N·m), each refused (GearmeshInputError
    naming ``field``) above the contact-stress and deflection limits of
    :func:`gearmesh.loads.check_load`: the entry check of every stage that loads the mesh.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    torques : float or array_like
        Torque(s), N·m.
    on : {'pinion', 'gear'}, default 'pinion'
        The member the torques act on.
    field : str, default 'torques_Nm'
        Field named in an error.

    Returns
    -------
    given : numpy.ndarray
        (T,) the torques as given, N·m.
    pinion : numpy.ndarray
        (T,) pinion torques T1, N·m.

    Raises
    ------
    GearmeshInputError
        Torques not positive and finite, or beyond the load limits.
    """
    given = check_torques(torques, field)
    t1 = pinion_torque(geom.pair, given, on)
    check_loads(geom, t1, field, given)
    return given, t1


# --------------------------------------------------------------------------------------
# LTCA
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LTCAResult:
    """LTCA over one mesh cycle at several torques (SI; transverse convention).

    torque (T,) pinion torque T1 (N·m); force (T,) F_bt = T1/r_b1 (N);
    load (T, P, J, N) transverse load of every point (N) — line load q/Δz (N/m);
    lte (T, P) loaded transmission error = approach δ (m); stiffness (T, P) tangent mesh
    stiffness dF/dδ (N/m); pairs_in_contact (T, P); corner_load (T, P) load on tip edges
    (regions 2, 3) (N); lte_at_engagement, stiffness_at_engagement,
    corner_load_at_engagement (T,) at φ1A; tca the unloaded :class:`~gearmesh.tca.TCAResult`
    on the same grid; model the :class:`~gearmesh.ltca_model.LTCAModel`; iterations the Newton steps used;
    misalignment (T,) the mesh's lead mismatch beyond the gears' lead slopes (m: the stated f_ma
    and the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`);
    system_approach (T,) the supports' translation of the gear centres along the transverse line
    of action (m, not in ``lte``: :mod:`gearmesh.deflection`).
    """

    torque: np.ndarray
    force: np.ndarray
    load: np.ndarray
    lte: np.ndarray
    stiffness: np.ndarray
    pairs_in_contact: np.ndarray
    corner_load: np.ndarray
    lte_at_engagement: np.ndarray
    stiffness_at_engagement: np.ndarray
    corner_load_at_engagement: np.ndarray
    tca: TCAResult
    model: LTCAModel
    iterations: int
    misalignment: np.ndarray | None = None
    system_approach: np.ndarray | None = None

    @property
    def grid(self) -> CandidateGrid:
        return self.tca.grid

    @property
    def line_load(self) -> np.ndarray:
        """Normal load per unit contact-line length (N/m) = transverse load per unit width."""
        return self.load / self.model.grid.dz

    @property
    def max_line_load(self) -> np.ndarray:
        """(T, P) largest line load (N/m) at each position."""
        return self.line_load.max(axis=(2, 3))


def _tca_from_grid(model: LTCAModel, te_pair_full: np.ndarray, tol: float = 1e-9) -> TCAResult:
    geom, g = model.geom, model.grid
    p = g.roll.size - 1
    grid = CandidateGrid(roll=g.roll[:p], pairs=g.pairs, z=g.z, dz=g.dz, s=g.s[:p], region=g.region[:p],
                         rho_pinion=g.rho_pinion[:p], rho_gear=g.rho_gear[:p], gap=g.gap[:p], extension=g.extension)
    te_pair = te_pair_full[:p]
    cs, cz, c1, c2 = first_contact(grid, te_pair, tol)
    roll_a, j_a, z_a = engagement_point(geom)
    te_a, next_a = engagement_separation(geom, g.z.size, model.lead_slope, g.extension / geom.transverse_base_pitch,
                                         model.misalignment)
    return TCAResult(grid=grid, te=nanmin(te_pair, axis=-1), te_pair=te_pair, contact_s=cs, contact_z=cz,
                     contact_rho_pinion=c1, contact_rho_gear=c2, roll_engagement=roll_a, pair_engagement=j_a,
                     z_engagement=z_a, te_at_engagement=te_a, te_next_pair_at_engagement=next_a,
                     lead_slope=model.lead_slope, misalignment=model.misalignment)


def torque_gaps(model: LTCAModel, misalignment: np.ndarray) -> np.ndarray:
    """The grid's separations (T, P+1, J, N) (m) at each torque's mesh misalignment ``misalignment``
    (T,) m (the stated f_ma and the load's f_sh; the grid carries the stated one alone).

    Parameters
    ----------
    model : LTCAModel
        The load-independent LTCA model (:func:`gearmesh.ltca_model.ltca_model`).
    misalignment : numpy.ndarray
        (T,) mesh misalignment of each torque, m.

    Returns
    -------
    numpy.ndarray
        (T, P+1, J, N) unloaded separations, m.
    """
    g, geom = model.grid, model.geom
    mis = np.asarray(misalignment, dtype=float)
    if np.all(mis == model.misalignment):
        return np.broadcast_to(g.gap[None], (mis.size,) + g.gap.shape)
    z = np.broadcast_to(g.z, g.gap.shape)
    lead = np.asarray(model.lead_slope)
    return (g.gap[None] - lead_gap(geom, lead, z, model.misalignment)[None]
            + lead_gap(geom, lead, z[None], mis[:, None, None, None]))


def _solve(model: LTCAModel, force: np.ndarray, misalignment: np.ndarray | None = None):
    """All torques and positions of ``model`` in one vectorised solve: loads (T, P+1, J, N),
    approach (T, P+1), tangent stiffness (T, P+1), Newton iterations; ``misalignment`` (T,) m the
    mesh misalignment per torque (None: the grid's)."""
    g = model.grid
    pp, jj, nn = g.gap.shape
    nt = force.size
    if misalignment is None:
        misalignment = np.full(nt, model.misalignment)
    gap = torque_gaps(model, misalignment).reshape(nt * pp, jj * nn)
    comp = np.broadcast_to(model.compliance.reshape(1, pp, jj * nn), (nt, pp, jj * nn)).reshape(nt * pp, jj * nn)
    q, delta, k, it = solve_contact(gap, comp, np.repeat(force, pp), model.law)
    return q.reshape(nt, pp, jj, nn), delta.reshape(nt, pp), k.reshape(nt, pp), it


def _reach_exceeded(model: LTCAModel, q: np.ndarray) -> bool:
    """True when a loaded tip-edge point lies in the outer fifth of the candidate zone."""
    g = model.grid
    if g.extension <= 0:
        return False
    far = (((g.region == REGION_APPROACH_TIP) & (g.s < -0.8 * g.extension))
           | ((g.region == REGION_RECESS_TIP) & (g.s > model.geom.path_of_contact + 0.8 * g.extension)))
    return bool(np.any((q > 0) & far[None]))


def ltca(geom: PairGeometry, torques, positions: int = 64, points: int = 50, lead_slope=None,
         on: str = "pinion", contact_law_name: str = DEFAULT_CONTACT_LAW, method: str = DEFAULT_TOOTH_METHOD,
         extension: float = DEFAULT_EXTENSION, model: LTCAModel | None = None, misalignment=None) -> LTCAResult:
    """Loaded TCA at each torque over one mesh cycle (and at the start of engagement φ1A).

    When loaded tip edges reach the outer fifth of the candidate zone beyond the active profile, the
    zone is doubled (up to one base pitch) and the LTCA repeated; with a given ``model`` a RuntimeWarning
    is issued instead. Each torque's mesh misalignment — the stated f_ma and the system deflection's f_sh
    under its force (:func:`gearmesh.deflection.mesh_misalignment`) — adds to the separations as a lead
    mismatch (:func:`torque_gaps`); the supports' translation along the line of action is reported
    beside the LTE (``system_approach``), not in it.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius; carries the modifications).
    torques : float or array_like
        Torque(s), N·m, on the pinion or, with ``on='gear'``, on the gear.
    positions, points : int
        Roll positions per mesh cycle (default 64) and candidate points per contact line (50).
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width; None: the pair's own (:mod:`gearmesh.deviation`).
    on : {'pinion', 'gear'}, default 'pinion'
        The member ``torques`` act on.
    contact_law_name : {'palmgren', 'linear'}, default 'palmgren'
        Local contact law (:func:`gearmesh.ltca_model.contact_law`).
    method : str, default 'fe'
        Cantilever (tooth) model of the slice compliance (:data:`gearmesh.choices.TOOTH_METHODS`).
    extension : float, default :data:`gearmesh.tca.DEFAULT_EXTENSION`
        Reach of the tip-edge candidates beyond the active zone, fraction of p_bt.
    model : LTCAModel, optional
        A prepared :class:`~gearmesh.ltca_model.LTCAModel` to reuse (the grid arguments then ignored).
    misalignment : float or array_like, optional
        The mesh misalignment of each torque, m, instead of the pair's own (e.g. the rating's with ISO's f_ma).

    Returns
    -------
    LTCAResult
        ``torque`` (T,) N·m, ``force`` F_bt (T,) N, ``load`` (T, P, J, N) N, ``lte`` (T, P) m, ``stiffness``
        (T, P) N/m, ``corner_load`` (T, P) N, the values at φ1A, the unloaded ``tca`` and the ``model``.

    Raises
    ------
    GearmeshInputError
        Torques, counts, method or modifications out of range.
    """
    t1 = pinion_torques(geom, torques, on)
    lead_slope = pair_lead_slope(geom, lead_slope)
    force = t1 / geom.base_radius[0]
    misalignment = (mesh_misalignment(geom, force) if misalignment is None
                    else np.broadcast_to(np.asarray(misalignment, dtype=float), force.shape).copy())
    own = model is None
    while True:
        if own:
            model = ltca_model(geom, positions, points, lead_slope, contact_law_name, method, extension)
        q, delta, k, it = _solve(model, force, misalignment)
        if not _reach_exceeded(model, q):
            break
        if not own or extension >= 1.0:
            warnings.warn("LTCA: tip-edge contact reaches the end of the candidate zone beyond the active "
                          "profile; raise corner_extension", RuntimeWarning, stacklevel=2)
            break
        extension = min(1.0, 2.0 * extension)  # the load reaches further than the candidates: widen
    c_body = mesh_body_compliance(geom)
    if c_body:  # the bodies bend under the total force, in series (gearmesh.body)
        delta, k = delta + c_body * force[:, None], 1.0 / (1.0 / k + c_body)
    g = model.grid
    pp = g.gap.shape[0]
    pair_load = q.sum(axis=3)
    in_contact = (pair_load > 1e-9 * force[:, None, None]).sum(axis=2)
    corner = ((g.region == REGION_APPROACH_TIP) | (g.region == REGION_RECESS_TIP))
    corner_load = np.where(corner[None], q, 0.0).sum(axis=(2, 3))
    te_pair = nanmin(g.gap, axis=-1)
    tca_res = _tca_from_grid(model, te_pair)
    p = pp - 1
    return LTCAResult(torque=t1, force=force, load=q[:, :p], lte=delta[:, :p], stiffness=k[:, :p],
                      pairs_in_contact=in_contact[:, :p], corner_load=corner_load[:, :p],
                      lte_at_engagement=delta[:, p], stiffness_at_engagement=k[:, p],
                      corner_load_at_engagement=corner_load[:, p], tca=tca_res, model=model, iterations=it,
                      misalignment=misalignment, system_approach=mesh_deflection(geom).approach_per_force * force)


def lte_harmonics(lte, orders=MESH_ORDERS) -> np.ndarray:
    """Amplitudes (m) of mesh orders ``orders`` of a loaded TE sampled at P evenly spaced rolls over
    one mesh cycle, end excluded (last axis; :func:`gearmesh.contact.mesh_cycle_rolls`): the
    one-sided discrete Fourier amplitude 2·|X_k|/P of order k (exact for a band-limited signal of
    orders below P/2).

    Parameters
    ----------
    lte : array_like
        (..., P) loaded transmission error, m.
    orders : sequence of int, default :data:`MESH_ORDERS`
        Mesh orders, each below P/2.

    Returns
    -------
    numpy.ndarray
        (..., len(orders)) amplitudes, m.

    Raises
    ------
    ValueError
        An order at or above P/2.
    """
    lte = np.asarray(lte, dtype=float)
    n = lte.shape[-1]
    if max(orders) >= n / 2:
        raise ValueError(f"mesh order {max(orders)} needs more than {2 * max(orders)} positions per cycle")
    return 2.0 * np.abs(np.fft.rfft(lte, axis=-1)[..., list(orders)]) / n
