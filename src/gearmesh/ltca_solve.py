"""The exact solve of the LTCA's contact problem of independent points (a diagonal influence matrix).

Everything inside is SI (m, N), in the transverse convention of :mod:`gearmesh.tca`. Points i with
unloaded separations g_i, linear compliances c_i and the local contact law δ_c = coef·q^m
(:class:`gearmesh.ltca_model.ContactLaw`, m < 1) deflect δ − g_i = f_i(q_i) = c_i·q_i + coef·q_i^m;
under the force F the problem is

    q_i ≥ 0,   Σ q_i = F,   δ − g_i = f_i(q_i) where q_i > 0,   q_i = 0 where g_i ≥ δ

(the LTCA's model: :mod:`gearmesh.ltca`).

Independent slices make the compliance matrix diagonal, so the complementarity problem is
solved *exactly* by one monotone scalar equation per position: q_i(δ) = f_i⁻¹((δ − g_i)_+)
is convex and increasing in δ, so Newton's method on S(δ) = Σ q_i(δ) − F from an upper
bound converges monotonically (no active-set cycling, no tolerance on the contact set),
with an inner Newton inversion of each f_i (concave, from an upper bound). This is the
active-set/NNLS problem (docs/modelling.md) for a diagonal influence matrix; the tangent mesh
stiffness dF/dδ = Σ_loaded 1/f_i'(q_i) follows exactly.

The inversion of the contact law q_i = f_i⁻¹(d) is done two ways: exactly, by Newton's method per
point (:func:`solve_contact`), and from one universal table of X + X^m = y read by cubic Hermite
interpolation (:func:`invert_tabulated`, relative error about 1e-13), whose load sums over many
rows run in compiled loops (numba, ``cache=True``: the on-disk cache is keyed by this module's file;
:func:`load_sums`, :func:`solve_contact_tabulated`).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .errors import GearmeshInputError
from .ltca_model import ContactLaw

__all__ = ["solve_contact", "solve_contact_tabulated", "load_sums", "law_point_scales"]


# --------------------------------------------------------------------------------------
# The contact law inverted: q from its approach, exactly (Newton) and from one universal table
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

# --------------------------------------------------------------------------------------
# The compiled load sums (numba kernels, cached on disk by this module's file)
# --------------------------------------------------------------------------------------


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
                    point_q, point_dq, scales, rows, comp_rows):
    """The loop of :func:`load_sums` (compiled by numba on first use): for each row r of ``rows``
    (indices k into ``gap`` and ``mask``, comp_rows[k] into ``comp`` and ``scales``), the sums over its points i of q_i,
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
        kc = comp_rows[k]
        for i in range(npts):
            g = gap[k, i]
            if not approach[r, nu - 1] - g > 0.0:  # not reached by the largest approach (or no point: inf)
                continue
            c = comp[kc, i]
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
                big_q, log_cq, cq = scales[0, kc, i], scales[1, kc, i], scales[2, kc, i]
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
              points: bool = False, scales: np.ndarray | None = None, rows: np.ndarray | None = None,
              compliance_rows: np.ndarray | None = None):
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
    compliance_rows : numpy.ndarray of int, optional
        (R,) the row of ``compliance`` (and ``scales``) of each row of ``gap``, for rows whose points
        are those of fewer distinct rows (e.g. many gears at the same roll positions): ``compliance``
        (R_c, M), the same sums as with the rows repeated; None: row for row.

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
    comp_rows = (np.arange(gap.shape[0]) if compliance_rows is None
                 else np.ascontiguousarray(compliance_rows, dtype=np.int64))
    mask = np.zeros((0, 0), dtype=np.bool_) if mask is None else np.ascontiguousarray(mask, dtype=np.bool_)
    out = [np.zeros(x.shape) for _ in range(3)]
    per_point = [np.zeros((rows.size, gap.shape[1]) if points else (0, 0)) for _ in range(2)]
    outside = np.zeros(rows.size, dtype=np.bool_)
    scales = np.zeros((0, 0, 0)) if scales is None or not law.coefficient else np.ascontiguousarray(scales, dtype=float)
    lo, _, h = _TABLE_LOG_Y
    v_tab, s_tab = _universal_inverse(float(law.exponent))
    _kernel("loop")(gap, comp, x, mask, float(law.coefficient), float(law.exponent), v_tab, s_tab, lo, h, *out,
                    outside, *per_point, scales, rows, comp_rows)
    for r in np.flatnonzero(outside):
        k = rows[r]
        d = x[r, :, None] - gap[k, None, :]
        q, dq = invert_tabulated(np.where(np.isfinite(d), d, -1.0), np.broadcast_to(comp[comp_rows[k]], d.shape),
                                 law.coefficient, law.exponent)
        masked = np.where(mask[k], q, 0.0).sum(axis=1) if mask.size else np.zeros(d.shape[0])
        out[0][r], out[1][r], out[2][r] = q.sum(axis=1), dq.sum(axis=1), masked
        if points:
            per_point[0][r], per_point[1][r] = q[-1], dq[-1]
    return (*out, *per_point) if points else tuple(out)


# --------------------------------------------------------------------------------------
# The contact problem solved
# --------------------------------------------------------------------------------------


def _contact_rows(gap: np.ndarray, compliance: np.ndarray, force, law: ContactLaw, compliance_rows=None):
    """The contact problem of :func:`solve_contact` made ready to solve: separations (B, M) with
    inf where no point can touch, compliances (B, M) with the law's linear part, forces (B,) and
    the upper bound of the approach δ (B,) with all of F on the point closest to contact. With
    ``compliance_rows`` (B,) the compliances are (B_c, M), row compliance_rows[b] that of row b
    (:func:`solve_contact_tabulated`), and 1 where a compliance is not finite instead of where a
    separation is not (a point that cannot touch is never loaded: its compliance is not used)."""
    g = np.where(np.isfinite(gap), gap, np.inf)
    shared = compliance_rows is not None
    c_eff = np.where(np.isfinite(compliance if shared else gap), compliance, 1.0) + law.linear
    force = np.asarray(force, dtype=float)
    rows = np.arange(g.shape[0])
    i_min = np.argmin(g, axis=1)
    g_min = g[rows, i_min]
    if not np.all(np.isfinite(g_min)):
        raise GearmeshInputError("positions", int(np.sum(~np.isfinite(g_min))),
                                 "roll positions without any candidate contact point")
    coef, m = law.coefficient, law.exponent
    c_min = c_eff[np.asarray(compliance_rows) if shared else rows, i_min]
    return g, c_eff, force, g_min + c_min * force + (coef * force**m if coef else 0.0)


def solve_contact_tabulated(gap: np.ndarray, compliance: np.ndarray, force: np.ndarray, law: ContactLaw,
                            delta_start=None, rtol: float = 1e-12, max_iter: int = 100, compliance_rows=None):
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
    compliance_rows : array_like of int, optional
        (B,) with ``compliance`` (B_c, M): the row of ``compliance`` of each problem, for problems at
        the same points (many gears at the same roll positions: the law's point scales computed once
        a point, :func:`law_point_scales`); the same loads as with the rows repeated. None: row for row.

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
    g, c_eff, force, bound = _contact_rows(gap, compliance, force, law, compliance_rows)
    delta = bound.copy() if delta_start is None else np.where(np.asarray(delta_start) < bound, delta_start, bound)
    q, dq = np.zeros(g.shape), np.zeros(g.shape)
    rows = np.arange(delta.size)
    scales = law_point_scales(c_eff, law)  # once: the points are the same in every pass
    for _ in range(max_iter):
        s, k, _, q_rows, dq_rows = load_sums(g, c_eff, delta[rows, None], law, points=True,
                                             scales=scales if scales.size else None, rows=rows,
                                             compliance_rows=compliance_rows)
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
