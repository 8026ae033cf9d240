"""The static (speed-independent) part of the mesh-in impact: the entering pair's separation
against roll and the force the pairs already in mesh carry when compressed to it, the touch roll
where the two meet (:func:`_crossing`), the mesh-in point M there — on a tip edge outside the active
zone (scenario ``edge``) or on two flanks inside it (``surface``) — with its closing rate, and the
entering pair's force–approach curve from M (:func:`impact_static`).

Everything inside is SI (m, N, s, rad, kg); the event and its conventions: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..deflection import mesh_misalignment
from ..deviation import with_misalignment
from ..ltca import check_torques
from ..ltca_solve import _invert, law_scales, log_universal_inverse, solve_contact
from ..ltca_model import ContactLaw, point_compliance
from ..separation import REGION_APPROACH_TIP, REGION_RECESS_TIP, SeparationBasis, basis_gap, separation_basis
from ..tca import candidate_grid, point_centres
from ..contact import hand_sign
from .model import SCENARIO_EDGE, SCENARIO_NONE, SCENARIO_SURFACE, ImpactModel, _without_column


# --------------------------------------------------------------------------------------
# The entering pair: separation against roll, refined minimum over the face
# --------------------------------------------------------------------------------------


def _parabolic_min(values: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Minimum over the last axis of samples ``values`` at equally spaced ``x``, refined by the
    parabola through the three samples centred on the smallest one (the end triple at either
    end, so the refined minimum does not jump when the smallest sample reaches an end); the
    vertex is used when it lies within that triple, else the smallest sample. Returns
    (minimum, its x); NaN where every sample is NaN."""
    v = np.where(np.isfinite(values), values, np.inf)
    n = v.shape[-1]
    k = np.argmin(v, axis=-1)
    vk = np.take_along_axis(v, k[..., None], -1)[..., 0]
    kc = np.clip(k, 1, n - 2)

    def at(i):
        return np.take_along_axis(v, i[..., None], -1)[..., 0]

    vm, v0, vp = at(kc - 1), at(kc), at(kc + 1)
    h = x[1] - x[0]
    with np.errstate(invalid="ignore", divide="ignore"):
        curv = vm - 2 * v0 + vp
        off = 0.5 * (vm - vp) / np.where(curv > 0, curv, 1.0)
        inside = np.isfinite(vm + v0 + vp) & (curv > 0) & (np.abs(off) <= 1.0)
        vertex = v0 - 0.25 * (vm - vp) * off
    use = inside & (vertex < vk)
    vmin = np.where(use, vertex, vk)
    xmin = np.where(use, x[kc] + off * h, x[k])
    return np.where(np.isinf(vk), np.nan, vmin), xmin


def _rows(a: np.ndarray, ndim: int) -> np.ndarray:
    """Per-row arrays (C, ...) with ``ndim`` unit axes inserted after the row axis (to broadcast
    one parameter set or lead-slope pair per row against points)."""
    return a.reshape(a.shape[:1] + (1,) * ndim + a.shape[1:])


#: Face samples either side of the previous minimum that :func:`_enter_gap` searches when told
#: where the minimum was (a touch iteration moves the roll by micrometres).
_NEAR_SAMPLES = 6


def _enter_gap(model: ImpactModel, params: np.ndarray, tau: np.ndarray, lead: np.ndarray, near=None):
    """Smallest separation of the entering pair over the face (m) and where (z), at time-like
    rolls ``tau`` (N,), one parameter set ``params`` (N, 2, 6) and lead-slope pair ``lead`` (N, 2)
    per roll. With ``near`` (N,) face positions of a minimum found at a neighbouring roll, only the
    :data:`_NEAR_SAMPLES` face samples either side of it are searched; a row whose minimum falls on
    the edge of that block (and not at a face end) is searched over the whole face."""
    g = model.geom
    tau = np.asarray(tau, dtype=float)
    z = model.z_fine
    if near is None:
        s = model.s_enter(tau[:, None], z)
        gap = basis_gap(g, separation_basis(g, s, np.inf), z, _rows(lead, 1), _rows(params, 1))
        return _parabolic_min(gap, z)
    h, n = z[1] - z[0], 2 * _NEAR_SAMPLES + 1
    first = np.clip(np.rint((np.asarray(near) - z[0]) / h).astype(np.intp) - _NEAR_SAMPLES, 0, z.size - n)
    zz = z[first[:, None] + np.arange(n)]
    s = model.s_enter(tau[:, None], zz)
    gap = basis_gap(g, separation_basis(g, s, np.inf), zz, _rows(lead, 1), _rows(params, 1))
    local = np.arange(n) * h
    gmin, x = _parabolic_min(gap, local)
    k = np.argmin(np.where(np.isfinite(gap), gap, np.inf), axis=1)
    inside = ((k > 0) | (first == 0)) & ((k < n - 1) | (first == z.size - n)) & np.isfinite(gmin)
    zmin = zz[:, 0] + x
    if not inside.all():
        gmin[~inside], zmin[~inside] = _enter_gap(model, params[~inside], tau[~inside], lead[~inside])
    return gmin, zmin


def _enter_gap_window(model: ImpactModel, params: np.ndarray, lead: np.ndarray):
    """The same on the window grid (C, R), reusing the window's entering-line basis."""
    gap = basis_gap(model.geom, model.enter_fine_basis, model.z_fine, _rows(lead, 2), _rows(params, 2))
    return _parabolic_min(gap, model.z_fine)


def _solve_rows(gap: np.ndarray, compliance: np.ndarray, force: np.ndarray, law: ContactLaw,
                rtol: float = 1e-12, delta_start=None) -> np.ndarray:
    """Approach δ (m) of each row (NaN for a row without any candidate point); ``rtol`` of the
    load sum (and 100× finer for each point's inversion)."""
    ok = np.isfinite(gap).any(axis=1)
    delta = np.full(gap.shape[0], np.nan)
    if ok.any():
        start = None if delta_start is None else np.asarray(delta_start, dtype=float).reshape(-1)[ok]
        _, d, _, _ = solve_contact(gap[ok], compliance[ok], force[ok], law, rtol=rtol, inner_tol=min(1e-14, rtol / 100),
                                   delta_start=start)
        delta[ok] = d
    return delta


def _point_loads(model: ImpactModel, approach: np.ndarray, gap: np.ndarray, compliance: np.ndarray):
    """Loads q (N) and tangent stiffnesses dq/dδ (N/m) of points of separation ``gap`` at the
    approach ``approach`` (broadcast): each point's law inverted directly (NaN gap: no point)."""
    law = model.ltca.law
    d = approach - gap
    return _invert(np.where(np.isfinite(d), d, -1.0), compliance, law.coefficient, law.exponent)


def _others_at(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray):
    """Separations (N, M) and compliances (N, M) (m/N, law's linear part added) of the pairs
    already in mesh at time-like rolls ``tau`` (N,), one parameter set and lead pair per roll:
    the exact candidate points of the window's tooth pairs at those rolls (no interpolation)."""
    g = model.geom
    z, dz = point_centres(g, model.points)
    s = (model.roll(tau)[:, None, None] + model.window_pairs[None, :, None] * g.transverse_base_pitch
         + hand_sign(g) * z[None, None, :] * math.tan(g.base_helix_angle))
    basis = _without_column(separation_basis(g, s, model.extension), model.window_enter_column)
    gap = basis_gap(g, basis, z, _rows(lead, 2), _rows(params, 2))
    comp = point_compliance(g, model.ltca.pair_table, model.ltca.tables, s, basis.region, basis.rho_pinion,
                            basis.rho_gear, with_hertz=model.ltca.law.name == "linear") / dz + model.ltca.law.linear
    n = gap.shape[0]
    return gap.reshape(n, -1), comp.reshape(n, -1)


def _touch_force(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray, near=None):
    """The force F*(τ) at which the entering pair touches at time-like roll τ, exactly, for rows
    (N,): the force the pairs already in mesh carry when they are compressed to the entering
    pair's smallest separation g(τ), F* = Σ_i q_i(g(τ) − g_i(τ)). Returns F* (N), the tangent
    stiffness ΣdF/dδ there (N/m), g (m) and its face position z (m); ``near`` as :func:`_enter_gap`;
    and the other pairs' points there (:class:`_Others`)."""
    gap_e, z_e = _enter_gap(model, params, tau, lead, near)
    gap_o, comp = _others_at(model, params, lead, tau)
    q, dq = _point_loads(model, gap_e[:, None], gap_o, comp)
    return q.sum(axis=1), dq.sum(axis=1), gap_e, z_e, _Others(gap_o, comp, q, dq)


@dataclass
class _Others:
    """The points of the pairs already in mesh at a touch roll, rows (N, M): separations (m),
    compliances (m/N), loads q (N) and dq/dδ (N/m) at the entering pair's separation."""

    gap: np.ndarray
    comp: np.ndarray
    q: np.ndarray
    dq: np.ndarray

    def put(self, rows: np.ndarray, other: "_Others") -> "_Others":
        """``other`` written into ``rows`` (allocated at the first write, NaN elsewhere)."""
        for name in ("gap", "comp", "q", "dq"):
            here, there = getattr(self, name), getattr(other, name)
            if here is None:
                here = np.full((self.gap_rows, there.shape[1]), np.nan)
                setattr(self, name, here)
            here[rows] = there
        return self

    gap_rows: int = 0


# --------------------------------------------------------------------------------------
# The static (speed-independent) part: mesh-in point, slope, F–δ curve
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ImpactStatic:
    """Speed-independent impact quantities for C modifications × T torques (SI).

    ``torque`` (T,) pinion torque, ``force`` (T,) F_bt; per (C, T): ``scenario`` 0 none /
    1 surface / 2 edge; ``tau`` time-like roll of the touch (m, negative = before the
    theoretical engagement), ``roll`` the pinion roll there; ``approach`` δ_others at the
    touch (m); ``gap_rate`` −dg/dτ and ``approach_rate`` dδ/dτ there (-): the closing rate of
    g − δ per unit roll is their sum (:attr:`slope`);
    ``s``, ``z``, ``rho_pinion``, ``rho_gear`` where M lies (m); ``region`` its candidate
    region; ``te_engagement`` the entering pair's separation at the theoretical engagement
    (m; the mesh-in impact paper's TE(φ1A)), ``lte_engagement`` the approach of all pairs there (LTE(φ1A);
    NaN unless asked for); ``curve_force`` / ``curve_approach`` (C, T, K) the F–δ curve of the
    entering pair alone from M (N, m; F = 0 at δ = 0 implied), from the separations and
    compliances of its slices ``curve_separation`` / ``curve_compliance`` (C, T, L);
    ``params`` (C, 2, 6) and ``lead_slope`` (C, 2) the micro-geometry of each row (m).
    """

    torque: np.ndarray
    force: np.ndarray
    scenario: np.ndarray
    tau: np.ndarray
    roll: np.ndarray
    approach: np.ndarray
    gap_rate: np.ndarray
    approach_rate: np.ndarray
    s: np.ndarray
    z: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray
    region: np.ndarray
    te_engagement: np.ndarray
    lte_engagement: np.ndarray
    curve_force: np.ndarray
    curve_approach: np.ndarray
    params: np.ndarray
    curve_separation: np.ndarray
    curve_compliance: np.ndarray
    lead_slope: np.ndarray

    @property
    def slope(self) -> np.ndarray:
        """−d(g − δ)/dτ at the touch (-): the closing rate of the entering pair per unit roll."""
        return self.gap_rate + self.approach_rate


#: Illinois iterations of the touch roll within its window cell (each an exact evaluation).
_MAX_TOUCH_ITERATIONS = 60
#: The touch is pinned down when the entering pair's separation and the loaded approach differ
#: by at most this (m) — the criterion of an "impact found".
_TOUCH_TOLERANCE = 1e-12


def _crossing(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force: np.ndarray):
    """Touch roll τ*, the entering pair's smallest separation there and its face position for
    every (C, T) of transverse forces ``force`` (C, T) N (:mod:`gearmesh.impact`; NaN where the touch fell
    on a window roll), whether found and whether at the window start, and the entering pair's
    separation at the theoretical engagement (C,).

    The touch condition g(τ) = δ_others(τ) is solved as F*(τ) = F_bt (:func:`_touch_force`):
    since the other pairs' force grows with their approach, g > δ_others exactly where
    F*(τ) > F_bt. F* needs one inversion per point and no load iteration, and does not depend
    on the torque: one pass over the window grid brackets every torque's touch (the first
    roll with F* ≤ F_bt; :func:`_window_touch_force`), then a secant iteration with exact
    evaluations of F* pins it down inside its cell."""
    nc, nt = force.shape
    k0 = int(np.flatnonzero(model.tau == 0.0)[0])
    f_win, g_win = _window_touch_force(model, params, lead, force.min(axis=1), k0)
    below = f_win[:, None, :] <= force[:, :, None]  # NaN: not below
    found = below.any(axis=-1)
    k = np.argmax(below, axis=-1)  # first roll at or past the touch
    at_start = found & (k == 0)
    t_star, g_star, z_star = (np.full((nc, nt), np.nan) for _ in range(3))
    cc, tt = np.nonzero(found & ~at_start)
    if cc.size:
        kk = k[cc, tt]
        a, b = model.tau[kk - 1], model.tau[kk]
        target = force[cc, tt]
        fa, fb = f_win[cc, kk - 1] - target, f_win[cc, kk] - target  # fa > 0 ≥ fb: the bracket
        # secant iteration from the cubic estimate (its slope for the first step), kept inside the
        # bracket (bisection when a step would leave it); every evaluation exact
        x_last, slope = _inverse_cubic(model.tau, f_win[cc], kk, target, a, b, fa, fb)
        f_last, g_last, z_last = (np.full(cc.size, np.nan) for _ in range(3))
        last_others = _Others(None, None, None, None, cc.size)
        active = np.flatnonzero(fb != 0.0)
        x_next = x_last.copy()
        for _ in range(_MAX_TOUCH_ITERATIONS):
            if not active.size:
                break
            c = x_next[active]
            f_c, k_c, g_c, z_c, o_c = _touch_force(model, params[cc[active]], lead[cc[active]], c)
            g_last[active], z_last[active] = g_c, z_c
            last_others.put(active, o_c)
            fc = f_c - target[active]
            up = fc > 0
            a[active] = np.where(up, c, a[active])
            fa[active] = np.where(up, fc, fa[active])
            b[active] = np.where(up, b[active], c)
            fb[active] = np.where(up, fb[active], fc)
            with np.errstate(invalid="ignore", divide="ignore"):
                prev_x, prev_f = x_last[active], f_last[active]
                step = np.where(np.isfinite(prev_f), fc * (c - prev_x) / (fc - prev_f), fc / slope[active])
                nxt = c - step
            ai, bi = a[active], b[active]
            nxt = np.where(np.isfinite(nxt) & (nxt > ai) & (nxt < bi), nxt, 0.5 * (ai + bi))
            x_last[active], f_last[active] = c, fc
            x_next[active] = nxt
            # pinned down: |g − δ| ≈ |F* − F_bt|/K below the touch tolerance, or the cell collapsed
            stop = (np.abs(fc) <= 0.5 * _TOUCH_TOLERANCE * k_c) | (bi - ai <= 1e-15)
            active = active[~stop]
        t_star[cc, tt] = np.where(np.isfinite(f_last), x_last, b)
        g_star[cc, tt], z_star[cc, tt] = g_last, z_last
        if last_others.gap is not None:  # the other pairs at each touch roll, as last evaluated
            evaluated = np.isfinite(f_last)
            at_touch = _Others(None, None, None, None, nc * nt).put(cc[evaluated] * nt + tt[evaluated],
                                                                    _Others(*(getattr(last_others, f)[evaluated] for f in
                                                                              ("gap", "comp", "q", "dq"))))
            return t_star, g_star, z_star, found & ~at_start, at_start, g_win[:, k0], at_touch
    return t_star, g_star, z_star, found & ~at_start, at_start, g_win[:, k0], None


#: Window rolls evaluated per pass of :func:`_window_touch_force`.
_WINDOW_CHUNK = 8


def _window_touch_force(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force_min: np.ndarray, k0: int):
    """F*(c, τ_k) and the entering pair's smallest separation g(c, τ_k) on the window rolls (C, R).

    The rolls are taken in passes of :data:`_WINDOW_CHUNK` from the window's start: a row is done
    once its F* has fallen to its smallest force ``force_min`` (C,) and the roll after that
    crossing is known (the first crossing of every larger force comes no later, since
    F* ≤ F_bt,min implies F* ≤ F_bt), so the rolls after it are left NaN. Roll ``k0`` (the
    theoretical engagement) is always evaluated."""
    w, g = model.window, model.geom
    nc, r = params.shape[0], model.tau.size
    f_win, g_win = np.full((nc, r), np.nan), np.full((nc, r), np.nan)
    ends = np.append(w.starts, w.roll_index.size)
    ends[:-1][w.counts == 0] = w.starts[w.counts == 0]
    active, lo = np.arange(nc), 0
    while active.size and lo < r:
        hi = min(r, lo + _WINDOW_CHUNK)
        pr, lr = params[active], lead[active]
        basis = SeparationBasis(*(getattr(model.enter_fine_basis, f)[lo:hi] for f in SeparationBasis.__dataclass_fields__))
        gap_e, _ = _parabolic_min(basis_gap(g, basis, model.z_fine, _rows(lr, 2), _rows(pr, 2)), model.z_fine)
        pts = slice(int(w.starts[lo]), int(ends[hi]) if hi < r else w.roll_index.size)
        sub = SeparationBasis(*(getattr(w.basis, f)[pts] for f in SeparationBasis.__dataclass_fields__))
        gap_o = basis_gap(g, sub, w.z[pts], _rows(lr, 1), _rows(pr, 1))
        q, _ = _point_loads(model, gap_e[:, w.roll_index[pts] - lo], gap_o, w.compliance[pts])
        f = np.zeros((active.size, hi - lo))
        some = w.counts[lo:hi] > 0
        if some.any():
            f[:, some] = np.add.reduceat(q, w.starts[lo:hi][some] - w.starts[lo], axis=-1)
        f_win[active, lo:hi] = np.where(np.isfinite(gap_e), f, np.nan)
        g_win[active, lo:hi] = gap_e
        below = f_win[active, :hi] <= force_min[active, None]
        k = np.argmax(below, axis=1)
        done = (below.any(axis=1) & (k + 1 < hi)) | (hi == r)
        active, lo = active[~done], hi
    missing = np.isnan(g_win[:, k0])
    if missing.any():  # rows done before the engagement roll: its separation still
        basis = SeparationBasis(*(getattr(model.enter_fine_basis, f)[k0:k0 + 1]
                                  for f in SeparationBasis.__dataclass_fields__))
        g_win[missing, k0] = _parabolic_min(basis_gap(g, basis, model.z_fine, _rows(lead[missing], 2),
                                                      _rows(params[missing], 2)), model.z_fine)[0][:, 0]
    return f_win, g_win


def _lagrange_cubic(x: np.ndarray, y: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Value and derivative at ``t`` (R,) of the cubic through the four points (``x``, ``y``) (R, 4)
    of each row (Lagrange basis and its derivative)."""
    val, der = np.zeros_like(t), np.zeros_like(t)
    for i in range(4):
        li, dli = np.ones_like(t), np.zeros_like(t)
        for j in range(4):
            if j != i:
                w = 1.0 / (x[:, i] - x[:, j])
                dli = dli * (t - x[:, j]) * w + li * w
                li = li * (t - x[:, j]) * w
        val += y[:, i] * li
        der += y[:, i] * dli
    return val, der


def _inverse_cubic(tau: np.ndarray, f: np.ndarray, k: np.ndarray, target: np.ndarray, a, b, fa, fb) -> np.ndarray:
    """A first estimate of the roll where F* = ``target`` inside window cell [τ_(k−1), τ_k] and the
    slope dF*/dτ there: the cubic through F* at the four nodes k−2 … k+1 as a function of τ, solved
    by two Newton steps from the linear estimate; the linear estimate and the chord's slope where
    the cubic leaves the cell or does not fall (rows (N,), ``f`` (N, R) F* on the window)."""
    r = tau.size
    lin = b - fb * (b - a) / (fb - fa)
    kk = np.clip(k, 2, r - 2)
    nodes = kk[:, None] + np.arange(-2, 2)[None, :]
    x = tau[nodes]
    y = np.take_along_axis(f, nodes, 1) - target[:, None]
    t = lin.copy()
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(2):
            val, der = _lagrange_cubic(x, y, t)
            t = t - val / der
        _, der = _lagrange_cubic(x, y, t)  # the cubic's slope at the estimate (for the first secant step)
    ok = np.isfinite(t) & (t > a) & (t < b) & (der < 0)
    return np.where(ok, t, lin), np.where(ok, der, (fb - fa) / (b - a))


def _enter_points(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray):
    """The entering pair's line at the touch ``tau`` (C, T), discretised for its local stiffness:
    ``local_points`` equal slices over the face, of which the ``local_keep`` with the smallest
    separation from the first to touch are kept (the others cannot load within the curve,
    checked by :func:`impact_response`). Returns separations relative to the first point to touch
    (C, T, K) and compliances (m/N) of those slices."""
    g = model.geom
    z, dz = point_centres(g, model.local_points)
    s = model.s_enter(tau[..., None], z)
    basis = separation_basis(g, s, np.inf)
    gap = basis_gap(g, basis, z, _rows(lead, 2), _rows(params, 2))
    comp = point_compliance(g, model.ltca.pair_table, model.ltca.tables, s, basis.region, basis.rho_pinion,
                            basis.rho_gear, with_hertz=model.ltca.law.name == "linear") / dz
    gap = np.where(np.isfinite(gap), gap, np.inf)
    keep = min(model.local_keep, gap.shape[-1])
    if keep < gap.shape[-1]:
        idx = np.argpartition(gap, keep - 1, axis=-1)[..., :keep]
        gap = np.take_along_axis(gap, idx, -1)
        comp = np.take_along_axis(comp, idx, -1)
    with np.errstate(invalid="ignore"):
        rel = gap - gap.min(axis=-1, keepdims=True)
    return rel, comp


def impact_static(model: ImpactModel, torques, params=None, curve_levels: int = 48,
                  curve_force_min=None, lead_slope=None, engagement: bool = True) -> ImpactStatic:
    """The speed-independent part of the impact: the mesh-in point, closing rates and the entering pair's F–δ curve.

    For pinion torques ``torques`` and modification parameter sets ``params``: the first roll
    where the entering pair's separation, minimised over the face, equals the approach of the
    pairs already in mesh (:mod:`gearmesh.impact`). The lead slopes are additive to the
    separations (:func:`gearmesh.deviation.lead_gap`), so a tolerance sample costs no new
    geometry; each torque adds its mesh misalignment
    (:func:`gearmesh.deflection.mesh_misalignment`: torques of different misalignment are
    solved as one batch of a row per set and torque, each row with its own lead slopes and
    force — what each torque alone gives, to round-off).

    Parameters
    ----------
    model : ImpactModel
        The prepared model (:func:`impact_model`).
    torques : array_like
        (T,) pinion torques (N m).
    params : array_like or None
        (C, 2, 6) modification parameter sets (m); None: the pair's own.
    curve_levels : int, default 48
        Approaches of the entering pair's F–δ curve, geometric up to one at which it carries at
        least ``curve_force_min``; :func:`impact_response` extends it where an impact needs more.
    curve_force_min : float or array_like or None
        (C, T) or scalar force the curve must reach (N); default 4·F_bt.
    lead_slope : array_like or None
        (C, 2) lead slope deviations [pinion, gear] of each set (m over the face width);
        None: the model's for all.
    engagement : bool, default True
        Also the loaded TE of all pairs at the theoretical engagement (``lte_engagement``, one
        more load solve per row; NaN without).

    Returns
    -------
    ImpactStatic
        ``torque`` and ``force`` F_bt (T,) (N m, N); per (C, T) ``scenario`` (0 none, 1 surface,
        2 edge), ``tau`` and ``roll`` of the touch (m), ``approach`` (m), ``gap_rate`` and
        ``approach_rate`` (-), where M lies (``s``, ``z``, roll lengths, m), and the F–δ curve
        ``curve_force``/``curve_approach`` (C, T, K) (N, m).

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md): the TE(φ)/LTE(φ) intersection and the
       quasi-static loading of the entering pair.
    """

    g = model.geom
    params = model.params(params)
    lead = model.lead_slopes(lead_slope, params.shape[0])
    t1 = check_torques(torques)
    force = t1 / float(g.base_radius[0])
    mis = mesh_misalignment(g, force)
    if np.all(mis == mis[0]):
        return _static(model, t1, params, with_misalignment(lead, mis[0]), lead, curve_levels, curve_force_min,
                       engagement)
    # each torque at its own misalignment: one row per (set, torque), each with its own lead rows and
    # force (the rows of a batch are solved independently, so this is each torque solved alone)
    nc, nt = params.shape[0], t1.size
    c, t = np.repeat(np.arange(nc), nt), np.tile(np.arange(nt), nc)
    cfm = None if curve_force_min is None else \
        np.broadcast_to(np.asarray(curve_force_min, dtype=float), (nc, nt)).reshape(-1, 1)
    rows = _static(model, t1[:1], params[c], with_misalignment(lead[c], mis[t]), lead[c], curve_levels, cfm,
                   engagement, force=force[t][:, None])
    return _unstack_rows(rows, t1, force, params, lead)


def _unstack_rows(rows: "ImpactStatic", t1: np.ndarray, force: np.ndarray, params: np.ndarray,
                  lead: np.ndarray) -> "ImpactStatic":
    """The :class:`ImpactStatic` of C sets at T torques from one solved with a row per (set, torque)
    (rows (C·T, 1, ...), set-major): pinion torques ``t1`` (T,) N m, forces ``force`` (T,) N, the
    sets' ``params`` (C, 2, 6) and own lead slopes ``lead`` (C, 2) m."""
    nc, nt = params.shape[0], t1.size
    out = {"torque": t1, "force": force, "params": params, "lead_slope": np.array(lead)}
    for name in ImpactStatic.__dataclass_fields__:
        if name not in out:
            a = getattr(rows, name)
            out[name] = a.reshape((nc, nt) + a.shape[2:])
    return ImpactStatic(**out)


def _static(model: ImpactModel, t1: np.ndarray, params: np.ndarray, lead: np.ndarray, lead_rows: np.ndarray,
            curve_levels: int, curve_force_min, engagement: bool, force: np.ndarray | None = None) -> "ImpactStatic":
    """:func:`impact_static` at pinion torques ``t1`` (N m) whose separations share the lead rows
    ``lead`` (C, 2) (m, the mesh misalignment of these torques included); ``lead_rows`` the rows'
    own slopes, stored in the result. ``force`` (C, T) N: each row's own transverse forces instead
    of those of ``t1`` (a row per set and torque, :func:`impact_static`; ``torque``, ``force`` of the
    result are then those of ``t1``)."""
    g = model.geom
    nc = params.shape[0]
    f_t = t1 / float(g.base_radius[0])
    force = np.broadcast_to(f_t if force is None else np.asarray(force, dtype=float), (nc, f_t.size))
    nt = force.shape[1]
    t_star, g_star, z_star, found, at_start, te0, at_touch = _crossing(model, params, lead, force)
    if np.any(at_start):
        warnings.warn("impact: the entering pair touches at the outer end of the tip-edge candidates; "
                      "raise corner_extension", RuntimeWarning, stacklevel=2)
    tt = np.where(found, t_star, 0.0)
    delta, gap_rate, approach_rate, z_min, resid = _touch_rates(model, params, lead, force, tt, found, g_star, z_star,
                                                                at_touch)
    found = found & (np.abs(resid).reshape(nc, nt) <= _TOUCH_TOLERANCE)  # a crossing not pinned down is no impact
    delta, gap_rate, approach_rate, z_m = (v.reshape(nc, nt) for v in (delta, gap_rate, approach_rate, z_min))
    s_m = model.s_enter(tt, z_m)
    bm = separation_basis(g, s_m, np.inf)
    region = np.where(found, bm.region, 0).astype(np.int8)
    scenario = _scenario(region, found)
    # TE and LTE at the theoretical engagement (τ = 0, a window roll): all pairs at φ1A
    lte0 = (_approach_at(model, params, lead, force[None], np.zeros((1, nc, nt)), others=False)[0]
            if engagement else np.full((nc, nt), np.nan))
    # F–δ curve of the entering pair alone from M
    # separations from the first slice to touch (→ M as local_points → ∞)
    rel, comp = _enter_points(model, params, lead, tt)
    fmin = 4.0 * force * np.ones((nc, 1)) if curve_force_min is None else \
        np.broadcast_to(np.asarray(curve_force_min, dtype=float), (nc, nt))
    cf, ca = _force_curve(model, rel, comp, _curve_reach(model, rel, comp, fmin), curve_levels)
    nan = ~found
    for arr in (delta, gap_rate, approach_rate, s_m, z_m):
        arr[nan] = np.nan
    cf[nan], ca[nan] = np.nan, np.nan
    return ImpactStatic(torque=t1, force=f_t, scenario=scenario, tau=np.where(found, tt, np.nan),
                        roll=np.where(found, model.roll(tt), np.nan), approach=delta, gap_rate=gap_rate,
                        approach_rate=approach_rate, s=s_m, z=z_m,
                        rho_pinion=np.where(found, bm.rho_pinion, np.nan), rho_gear=np.where(found, bm.rho_gear, np.nan),
                        region=region, te_engagement=np.broadcast_to(te0[:, None], (nc, nt)).copy(),
                        lte_engagement=lte0, curve_force=cf, curve_approach=ca, params=params,
                        curve_separation=rel, curve_compliance=comp, lead_slope=np.array(lead_rows))


def _touch_rates(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force: np.ndarray, tt: np.ndarray,
                 found: np.ndarray, g_star: np.ndarray, z_star: np.ndarray, at_touch: "_Others | None"):
    """The loaded approach δ_others and the closing rates at the touch rolls ``tt`` (C, T) found by
    :func:`_crossing` (its separations ``g_star``, face positions ``z_star`` and other pairs
    ``at_touch``), for the sets ``params`` with lead rows ``lead`` under transverse forces ``force``
    (C, T) N. Returns, flattened to (C·T,): δ (m), −dg/dτ and dδ/dτ (-), the face position of the
    entering pair's smallest separation (m) and the residual g − δ_others of one Newton step (m)."""
    g = model.geom
    nc, nt = tt.shape
    # at the touch, the rates from one stacked exact evaluation at τ − 2ε, τ − ε, τ: the one-sided
    # (second-order) difference from the approach side is the closing rate just before the touch,
    # positive at any crossing from above even where min_z g or a point's separation has a kink
    # (a point of the pairs in mesh unloading, the minimum jumping along the face or following a kink)
    eps = 1e-6 * g.transverse_base_pitch
    offsets = np.array([-2 * eps, -eps, 0.0])
    rows_c = np.broadcast_to(np.arange(nc)[:, None], (nc, nt)).reshape(-1)
    stack = (tt.reshape(-1)[None, :] + offsets[:, None]).reshape(-1)
    p3, l3 = np.tile(params[rows_c], (3, 1, 1)), np.tile(lead[rows_c], (3, 1))
    # the smallest separation at τ* from the touch iteration (the whole face; searched anew where the
    # touch fell on a window roll), the two earlier rolls near its face position
    gap_min, z_min = g_star.reshape(-1).copy(), z_star.reshape(-1).copy()
    redo = ~np.isfinite(gap_min)
    if redo.any():
        gap_min[redo], z_min[redo] = _enter_gap(model, params[rows_c[redo]], tt.reshape(-1)[redo], lead[rows_c[redo]])
    n2 = 2 * nc * nt
    gap2, _ = (v.reshape(2, nc * nt) for v in _enter_gap(model, p3[:n2], stack[:n2], l3[:n2], np.tile(z_min, 2)))
    gap3 = np.concatenate([gap2, gap_min[None]])
    # the other pairs at τ − 2ε, τ − ε, and at τ itself where the touch iteration left them
    kept = np.zeros(nc * nt, dtype=bool) if at_touch is None else np.isfinite(at_touch.gap).any(axis=1) & found.reshape(-1)
    anew = np.concatenate([np.ones(n2, dtype=bool), ~kept])
    gap_n, comp_n = _others_at(model, p3[anew], l3[anew], stack[anew])
    m = gap_n.shape[-1]
    gap_o, comp = np.empty((3 * nc * nt, m)), np.empty((3 * nc * nt, m))
    gap_o[anew], comp[anew] = gap_n, comp_n
    gap_o, comp = gap_o.reshape(3, nc * nt, m), comp.reshape(3, nc * nt, m)
    q, dq = np.empty((nc * nt, m)), np.empty((nc * nt, m))
    if kept.any():
        gap_o[2, kept], comp[2, kept], q[kept], dq[kept] = (at_touch.gap[kept], at_touch.comp[kept], at_touch.q[kept],
                                                            at_touch.dq[kept])
    q[~kept], dq[~kept] = _point_loads(model, gap_min[~kept, None], gap_o[2, ~kept], comp[2, ~kept])
    stiff = dq.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        resid = (q.sum(axis=1) - force.reshape(-1)) / stiff  # g − δ_others at τ* (one Newton step)
        # δ − g_i = c_i(τ)·q_i + δ_c(q_i) at fixed Σq_i = F_bt: dδ/dτ = Σk_i·(g_i' + c_i'·q_i)/Σk_i
        # (k_i = dq_i/dδ; the compliance changes as the points move along the profile)
        rate_o = (3 * (gap_o[2] + comp[2] * q) - 4 * (gap_o[1] + comp[1] * q) + gap_o[0] + comp[0] * q) / (2 * eps)
        approach_rate = np.sum(np.where(dq > 0, dq * rate_o, 0.0), axis=1) / stiff
    gap_rate = -(3 * gap3[2] - 4 * gap3[1] + gap3[0]) / (2 * eps)
    delta = gap_min - resid
    return delta, gap_rate, approach_rate, z_min, resid


def _scenario(region: np.ndarray, found: np.ndarray) -> np.ndarray:
    """The scenario of each touch (int8): none where no touch was found, edge where the mesh-in point
    lies in a tip-edge region (the mesh-in impact paper's scenario 1), surface on the flanks (scenario 2)."""
    return np.where(~found, SCENARIO_NONE,
                    np.where((region == REGION_APPROACH_TIP) | (region == REGION_RECESS_TIP), SCENARIO_EDGE,
                             SCENARIO_SURFACE)).astype(np.int8)


def _approach_at(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force: np.ndarray, tau: np.ndarray,
                 others: bool, delta_start=None) -> np.ndarray:
    """Approach δ of the other pairs (``others``) or of all pairs at time-like rolls ``tau``
    (..., C, T) — leading axes stack several rolls per (C, T) — by one exact solve on a
    candidate grid at those rolls; ``lead`` (C, 2) the lead slopes of each parameter set."""
    g, law = model.geom, model.ltca.law
    shape = tau.shape
    roll = model.roll(tau).reshape(-1)
    grid = candidate_grid(g, roll, model.points, (0.0, 0.0), model.extension / g.transverse_base_pitch,
                          pairs=model.window_pairs)
    b = _without_column(grid.basis, model.window_enter_column) if others else grid.basis
    p = np.broadcast_to(params[:, None], shape + (2, 6)).reshape(-1, 1, 1, 2, 6)
    f = np.broadcast_to(lead[:, None], shape + (2,)).reshape(-1, 1, 1, 2)
    gap = basis_gap(g, b, np.broadcast_to(grid.z, grid.s.shape), f, p).reshape(roll.size, -1)
    comp = (point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid.s, grid.region, grid.rho_pinion,
                             grid.rho_gear, with_hertz=law.name == "linear") / grid.dz).reshape(roll.size, -1)
    f = np.broadcast_to(force, shape).reshape(-1)
    start = None if delta_start is None else np.broadcast_to(delta_start, shape)
    return _solve_rows(gap, comp, f, law, delta_start=start).reshape(shape)


def _sorted_slices(model: ImpactModel, rel: np.ndarray, comp: np.ndarray):
    """The entering line's slices of every row (R, L), in order of separation from the first to
    touch: separations (non-candidates at 1 m, out of reach) and compliances (m/N, the local
    law's linear part added)."""
    law = model.local_law
    length = rel.shape[-1]
    e = np.where(np.isfinite(rel), rel, 1.0).reshape(-1, length)
    c = (np.where(np.isfinite(comp), comp, 1.0) + law.linear).reshape(-1, length)
    order = np.argsort(e, axis=1, kind="stable")
    return np.take_along_axis(e, order, 1), np.take_along_axis(c, order, 1)


def _force_curve(model: ImpactModel, rel: np.ndarray, comp: np.ndarray, dmax: np.ndarray, levels: int):
    """F–δ of the entering pair alone: approaches (C, T, K) geometric from 1e-5·dmax to dmax and
    the force each causes, F(δ) = Σ q_i(δ − e_i) with every slice's own law inverted directly
    (separations ``rel`` e_i from the first slice to touch; no load solve needed this way round).

    Only the loaded (slice, level) pairs are formed: with the slices in order of separation, the
    slices loaded at level k are the first n_k of them (e_i < δ_k)."""
    law = model.local_law
    e, c = _sorted_slices(model, rel, comp)
    rows, length = e.shape
    frac = np.geomspace(1e-5, 1.0, int(levels))
    dm = np.broadcast_to(np.asarray(dmax, dtype=float), rel.shape[:-1]).reshape(-1)
    d = dm[:, None] * frac  # (R, K)
    with np.errstate(invalid="ignore", divide="ignore"):
        first = np.searchsorted(frac, e / dm[:, None], side="right")  # first level with δ_k > e_i
    # the ratio test can differ from δ_k > e_i by one ulp: settle it on δ_k itself
    lower = np.maximum(first - 1, 0)
    first = np.where((first > 0) & (np.take_along_axis(d, np.minimum(lower, levels - 1), 1) > e), lower, first)
    hist = np.zeros((rows, levels + 1), dtype=np.intp)
    np.add.at(hist, (np.arange(rows)[:, None], first), 1)
    n = np.cumsum(hist[:, :levels], axis=1).reshape(-1)  # slices loaded at each (row, level)
    rk = np.repeat(np.arange(rows * levels), n)
    j = np.arange(rk.size) - np.repeat(np.cumsum(n) - n, n)
    flat = (rk // levels) * length + j
    x = d.reshape(-1)[rk] - e.reshape(-1)[flat]  # > 0 by construction
    if law.coefficient:
        # the universal inverse of :func:`gearmesh.ltca_solve.invert_tabulated`, with each slice's
        # scales taken once per slice rather than once per (slice, level)
        log_q, log_cq = law_scales(c, law.coefficient, law.exponent)
        v = log_universal_inverse(np.log(x) - log_cq.reshape(-1)[flat], law.exponent)
        q = np.exp(log_q.reshape(-1)[flat] + v)
        outside = np.isnan(v)
        if outside.any():
            q[outside] = _invert(x[outside], c.reshape(-1)[flat[outside]], law.coefficient, law.exponent)[0]
    else:
        q = x / c.reshape(-1)[flat]
    force = np.bincount(rk, weights=q, minlength=rows * levels).reshape(rel.shape[:-1] + (levels,))
    # the described bodies in series: they bend under the entering pair's force too (gearmesh.body)
    return force, d.reshape(rel.shape[:-1] + (levels,)) + model.body_compliance * force


def _curve_reach(model: ImpactModel, rel: np.ndarray, comp: np.ndarray, force: np.ndarray) -> np.ndarray:
    """An approach (m) at which the entering pair carries at least ``force`` (N), close to the
    least one: δ_lin + coef·q_max^m, δ_lin the approach of the slices with their linear
    compliances alone (exact, from prefix sums over the slices in order of separation) and q_max
    the largest slice load there. An upper bound: at it every loaded slice's law gives at least
    its linear load, since q_i ≤ q_max adds at most coef·q_max^m to its approach."""
    law = model.local_law
    e, c = _sorted_slices(model, rel, comp)
    f = np.broadcast_to(np.asarray(force, dtype=float), rel.shape[:-1]).reshape(-1, 1)
    k = 1.0 / c
    s, t = np.cumsum(k, axis=1), np.cumsum(e * k, axis=1)
    carried = e[:, 1:] * s[:, :-1] - t[:, :-1]  # force when the approach reaches the next slice
    j = np.sum(carried < f, axis=1, keepdims=True)
    delta = (f + np.take_along_axis(t, j, 1)) / np.take_along_axis(s, j, 1)
    q_max = np.max(np.where(np.arange(e.shape[1]) <= j, (delta - e) * k, 0.0), axis=1, keepdims=True)
    reach = delta + (law.coefficient * q_max**law.exponent if law.coefficient else 0.0)
    return reach.reshape(rel.shape[:-1])
