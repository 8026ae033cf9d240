"""The contact problem of the LTCA solved the straightforward way, independently of the package's
solvers, as the baseline of the benchmarks whose code solves it.

The problem (:func:`gearmesh.ltca_solve.solve_contact`): points i of one row with unloaded separations
g_i (m; NaN or inf where no point can touch) and linear compliances c_i (m/N, plus the contact
law's linear part) under the transverse force F (N); find the approach δ with Σ q_i(δ) = F, where a
point with g_i < δ carries q_i > 0 solving c_i·q + a·q^m = δ − g_i (the local contact law
δ_c = a·q^m) and the others carry nothing. Here each row's δ by scipy's brentq on Σ q_i(δ) − F
(increasing in δ) between the smallest separation (nothing carried) and that separation plus the
approach of its point carrying all of F, and every loaded point's q_i by its own brentq on
[0, (δ − g_i)/c_i]: Python loops, no vectorisation, no Newton, no tables.

:func:`replace_contact_solvers` puts it in place of the package's solvers (exact and tabulated)
and of its inversions of the contact law (Newton per point, the tabulated universal inverse)
wherever a gearmesh module calls them, so that the same public function (``ltca``,
``impact_static``, ``ltca_criteria``) runs with the straightforward solve: everything the function
adds around the solve (gear bodies, deflections, stresses) is then the same on both sides.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from common import Swap, swapped

#: brentq's tolerances: relative 1e-15 (4 eps is its floor), absolute far below any load or approach.
RTOL, XTOL = 1e-15, 1e-300


def _point_load(d: float, c: float, coef: float, m: float) -> float:
    """q ≥ 0 with c·q + coef·q^m = d (N) for d > 0."""
    if coef == 0.0:
        return d / c
    return brentq(lambda q: c * q + coef * q**m - d, 0.0, d / c, xtol=XTOL, rtol=RTOL)


def solve_rows(gap, compliance, force, law):
    """Loads (B, M) N, approach δ (B,) m and each point's dq/dδ (B, M) N/m (0 where unloaded) of the
    rows (module docstring); ``law`` a :class:`gearmesh.ltca_model.ContactLaw`."""
    gap = np.asarray(gap, dtype=float)
    comp = np.asarray(compliance, dtype=float) + law.linear
    force = np.broadcast_to(np.asarray(force, dtype=float), gap.shape[:1])
    coef, m = law.coefficient, law.exponent
    q, delta, dq = np.zeros(gap.shape), np.empty(gap.shape[0]), np.zeros(gap.shape)
    for r in range(gap.shape[0]):
        points = [(g, c) for g, c in zip(gap[r], comp[r]) if np.isfinite(g)]
        if not points:
            raise ValueError(f"row {r}: no candidate point")
        g0, c0 = min(points)

        def excess(x):
            return sum(_point_load(x - g, c, coef, m) for g, c in points if x > g) - force[r]

        high = g0 + c0 * force[r] + (coef * force[r] ** m if coef else 0.0)
        delta[r] = brentq(excess, g0, high, xtol=XTOL, rtol=RTOL)
        for i, (g, c) in enumerate(zip(gap[r], comp[r])):
            if np.isfinite(g) and delta[r] > g:
                q[r, i] = _point_load(delta[r] - g, c, coef, m)
                dq[r, i] = 1.0 / (c + (coef * m * q[r, i] ** (m - 1.0) if coef else 0.0))
    return q, delta, dq


def invert_law(d, c, coef: float, m: float, *args, **kwargs):
    """q ≥ 0 with c·q + coef·q^m = d and dq/dd, elementwise (0 where d ≤ 0), each by brentq: the
    straightforward form of :func:`gearmesh.ltca_solve._invert` and :func:`gearmesh.ltca_solve.invert_tabulated`."""
    d = np.asarray(d, dtype=float)
    c = np.broadcast_to(np.asarray(c, dtype=float), d.shape)
    q, dq = np.zeros(d.shape), np.zeros(d.shape)
    for i in zip(*np.nonzero(d > 0)):
        q[i] = _point_load(float(d[i]), float(c[i]), coef, m)
        dq[i] = 1.0 / (c[i] + (coef * m * q[i] ** (m - 1.0) if coef else 0.0))
    return q, dq


def log_universal_root(u, m: float):
    """ln X of the root X of X + X^m = e^u, elementwise, each by brentq in ln X between the bounds
    the larger term gives (it is between y/2 and y): the straightforward form of
    :func:`gearmesh.ltca_solve.log_universal_inverse`."""
    u = np.asarray(u, dtype=float)
    out = np.empty(u.shape)
    for i, ui in np.ndenumerate(u):
        lo, hi = min(ui - np.log(2.0), (ui - np.log(2.0)) / m), min(ui, ui / m)
        out[i] = brentq(lambda v: np.logaddexp(v, m * v) - ui, lo, hi, xtol=1e-15, rtol=RTOL)
    return out


def _exact_form(original):
    """:func:`solve_rows` with :func:`gearmesh.ltca_solve.solve_contact`'s signature and returns."""
    def solve(gap, compliance, force, law, *args, **kwargs):
        q, delta, dq = solve_rows(gap, compliance, force, law)
        return q, delta, dq.sum(axis=1), 1
    return solve


def _row_compliance(compliance, compliance_rows=None):
    """Each problem's own compliance row: ``compliance`` taken row for row by ``compliance_rows``
    (:func:`gearmesh.ltca_solve.solve_contact_tabulated`'s problems at shared points), else as given."""
    return compliance if compliance_rows is None else np.asarray(compliance)[np.asarray(compliance_rows)]


def _tabulated_form(original):
    """:func:`solve_rows` with :func:`gearmesh.ltca_solve.solve_contact_tabulated`'s signature and returns."""
    def solve(gap, compliance, force, law, *args, compliance_rows=None, **kwargs):
        return solve_rows(gap, _row_compliance(compliance, compliance_rows), force, law)
    return solve


def replace_contact_solvers():
    """A context in which every gearmesh call of ``solve_contact`` or ``solve_contact_tabulated``
    runs :func:`solve_rows`, and every inversion of the contact law :func:`invert_law` or
    :func:`log_universal_root` (raises on leaving if none was called: :func:`common.swapped`; yields
    the list of those called)."""
    return swapped(Swap("gearmesh.ltca_solve.solve_contact", _exact_form),
                   Swap("gearmesh.ltca_solve.solve_contact_tabulated", _tabulated_form),
                   Swap("gearmesh.ltca_solve._invert", lambda original: invert_law),
                   Swap("gearmesh.ltca_solve.invert_tabulated", lambda original: invert_law),
                   Swap("gearmesh.ltca_solve.log_universal_inverse", lambda original: log_universal_root))


def exact_for_tabulated():
    """A context in which every gearmesh call of ``solve_contact_tabulated`` runs the package's exact
    :func:`gearmesh.ltca_solve.solve_contact` instead (its Newton on every point's own inversion, no table):
    the tabulated inversion switched off."""
    from gearmesh.ltca_solve import solve_contact

    def make(original):
        def solve(gap, compliance, force, law, *args, compliance_rows=None, **kwargs):
            compliance = _row_compliance(compliance, compliance_rows)
            q, delta, _, _ = solve_contact(gap, compliance, force, law)
            c = np.asarray(compliance, dtype=float) + law.linear
            with np.errstate(divide="ignore", invalid="ignore"):
                dq = np.where(q > 0, 1.0 / (c + law.coefficient * law.exponent * q ** (law.exponent - 1.0)), 0.0)
            return q, delta, dq
        return solve

    return swapped(Swap("gearmesh.ltca_solve.solve_contact_tabulated", make))
