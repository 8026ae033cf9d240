"""Direct time integration of the mesh-in event (:func:`simulate_engagement`): the two-inertia
torsional system driven through the touch, the check of the energy method.

Everything inside is SI (m, N, s, rad, kg); the event and its conventions: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import GearmeshInputError
from ..limits import check_speeds
from ..deflection import mesh_misalignment
from ..deviation import with_misalignment
from ..ltca_solve import _invert, solve_contact
from ..ltca_model import ContactLaw, point_compliance
from ..separation import basis_gap
from ..tca import candidate_grid
from .model import SCENARIO_NONE, ImpactModel
from .static import _approach_at, impact_static


def simulate_engagement(model: ImpactModel, torque: float, speed_rpm: float, params=None, samples: int = 600,
                        cycles_after: float = 2.5) -> dict[str, np.ndarray | float]:
    """Direct time integration of the mesh-in event, to check the energy method.

    The two-inertia torsional system in its relative coordinate x (transverse approach along
    the line of action, gear held): m_eq·ẍ = F_bt − F_mesh(x, τ(t)), τ advancing at r_b1·Ω1,
    F_mesh the LTCA contact force of every point of every pair (the entering one included) at
    approach x (:func:`gearmesh.ltca_solve.solve_contact`'s point laws, inverted directly). No
    damping: the energy method is conservative. It starts in static equilibrium a little before
    the touch (x = δ, ẋ = dδ/dt), integrates (scipy solve_ivp, RK45) through the touch for
    ``cycles_after`` periods of the mesh's natural frequency √(k/m_eq), and reports over the
    impact window — from the touch to one natural period after it (compression and rebound of
    the impact; later the undamped mesh keeps ringing under its own stiffness fluctuation, which
    is not the impact) — the entering pair's largest force (``entering_peak``), its largest
    excess over its quasi-static force at the same mesh position (``entering_excess``: the
    dynamic impact, the quantity the dynamics reports), and the largest mesh force above the
    static force F_bt (``peak_above_static``). (A window that closed at the entering pair's first
    local maximum could close a few µs after a grazing touch, on a wiggle of a few newtons.)
    The energy method's premise — all of ½·m_eq·v² goes into the entering pair — ignores the
    pairs already in mesh, which unload as x rebounds; the ratio measures that.

    Parameters
    ----------
    model : ImpactModel
        The prepared model (:func:`impact_model`).
    torque : float
        Pinion torque (N m); must give a mesh-in contact in the search window.
    speed_rpm : float
        Pinion speed (rpm).
    params : array_like or None
        Modification parameters (2, 6) or (1, 2, 6) (m); only the first set is used; None: the
        pair's own.
    samples : int, default 600
        Time-like rolls at which the mesh points are tabulated and the result sampled.
    cycles_after : float, default 2.5
        Natural periods integrated after the touch.

    Returns
    -------
    dict
        ``time`` (s), ``tau`` (m), ``approach`` x (m), ``mesh_force``, ``entering_force`` and
        ``entering_static`` (N) over the samples; ``static_force`` F_bt, ``peak_above_static``,
        ``entering_peak``, ``entering_excess`` (N); ``peak_time``, ``period``, ``touch_time`` (s).
    """
    g, law = model.geom, model.ltca.law
    params = model.params(params)[:1]
    st = impact_static(model, [torque], params)
    if st.scenario[0, 0] == SCENARIO_NONE:
        raise GearmeshInputError("torque_Nm", torque, "gives no mesh-in contact in the search window")
    speed = float(check_speeds(None, [speed_rpm], "speed_rpm")[0])
    f_bt = float(st.force[0])
    t_star = float(st.tau[0, 0])
    lead = with_misalignment(model.lead_slope, float(mesh_misalignment(g, f_bt)))  # this torque's mesh
    period = _natural_period(model, params, lead, float(st.roll[0, 0]), f_bt)
    rate = float(g.base_radius[0]) * speed * 2 * math.pi / 60.0  # dτ/dt (m/s)
    tau0 = t_star - max(0.02 * g.transverse_base_pitch, 0.5 * period * rate)
    tau1 = t_star + cycles_after * period * rate
    taus = np.linspace(tau0, tau1, int(samples))
    gaps, comps, enter = _mesh_points(model, params, lead, taus)
    loads = _mesh_loads(law, tau0, taus, gaps, comps)
    t, x = _integrate(model, params, lead, st.force, loads, tau0, tau1, rate, period, samples)
    q = np.array([loads(xi, tau0 + rate * ti) for xi, ti in zip(x, t)])
    total = q.sum(axis=1)
    entering = q[:, enter].sum(axis=1)
    t_touch = (t_star - tau0) / rate
    # the entering pair's quasi-static load at every sampled mesh position (the LTCA at F_bt)
    q_static, _, _, _ = solve_contact(gaps, comps, np.full(taus.size, f_bt), law)
    entering_static = np.interp(tau0 + rate * t, taus, q_static[:, enter].sum(axis=1))
    window = (t >= t_touch) & (t <= t_touch + period)
    excess = entering - entering_static
    i_peak = int(np.flatnonzero(window)[np.argmax(excess[window])]) if window.any() else t.size - 1
    return {"time": t, "tau": tau0 + rate * t, "approach": x, "mesh_force": total, "entering_force": entering,
            "entering_static": entering_static, "static_force": f_bt,
            "peak_above_static": float(total[window].max() - f_bt) if window.any() else np.nan,
            "entering_peak": float(entering[window].max()) if window.any() else np.nan,
            "entering_excess": float(excess[i_peak]), "peak_time": float(t[i_peak]), "period": period,
            "touch_time": t_touch}


def _natural_period(model: ImpactModel, params: np.ndarray, lead, roll: float, f_bt: float) -> float:
    """The time scale of the event: the period 2π·√(m_eq/k) (s) of the mesh's natural frequency, k the
    tangent mesh stiffness of all pairs at pinion roll ``roll`` (m, the touch) under the transverse
    force ``f_bt`` (N), for the one parameter set ``params`` (1, 2, 6) with lead slopes ``lead`` (m)."""
    g, law = model.geom, model.ltca.law
    grid0 = candidate_grid(g, np.array([roll]), model.points, lead,
                           model.extension / g.transverse_base_pitch, pairs=model.window_pairs)
    gap0 = basis_gap(g, grid0.basis, np.broadcast_to(grid0.z, grid0.s.shape), lead, params[0])
    comp0 = point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid0.s, grid0.region, grid0.rho_pinion,
                             grid0.rho_gear, with_hertz=law.name == "linear") / grid0.dz
    _, _, k0, _ = solve_contact(gap0.reshape(1, -1), comp0.reshape(1, -1), np.array([f_bt]), law)
    return 2 * math.pi * math.sqrt(model.equivalent_mass / float(k0[0]))


def _mesh_points(model: ImpactModel, params: np.ndarray, lead, taus: np.ndarray):
    """The candidate points of every pair (the entering one included) at the time-like rolls ``taus``
    (R,) m: separations (R, M) m (inf where no point), compliances (R, M) m/N (1 where no point; the
    law's linear part not added) and which of the M points belong to the entering pair (M,)."""
    g, law = model.geom, model.ltca.law
    grid = candidate_grid(g, model.roll(taus), model.points, lead, model.extension / g.transverse_base_pitch,
                          pairs=model.window_pairs)
    gaps = basis_gap(g, grid.basis, np.broadcast_to(grid.z, grid.s.shape), lead, params[0])
    comps = point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid.s, grid.region, grid.rho_pinion,
                             grid.rho_gear, with_hertz=law.name == "linear") / grid.dz
    nr = taus.size
    gaps = np.where(np.isfinite(gaps), gaps, np.inf).reshape(nr, -1)
    comps = np.where(np.isfinite(comps), comps, 1.0).reshape(nr, -1)
    enter = np.zeros(gaps.shape[1], dtype=bool).reshape(grid.s.shape[1:])
    enter[model.window_enter_column] = True
    return gaps, comps, enter.reshape(-1)


def _mesh_loads(law: ContactLaw, tau0: float, taus: np.ndarray, gaps: np.ndarray, comps: np.ndarray):
    """The point loads q(x, τ) (M,) N at approach x (m) and time-like roll τ (m): every point's law
    inverted directly, its separation and compliance interpolated linearly between the sampled rolls
    ``taus`` (R,) (from ``tau0``) of :func:`_mesh_points`."""
    nr = taus.size
    c_eff = comps + law.linear

    def at(tau):
        u = (tau - tau0) / (taus[1] - taus[0])
        i = int(min(max(math.floor(u), 0), nr - 2))
        w = u - i
        with np.errstate(invalid="ignore"):
            gg = gaps[i] + w * (gaps[i + 1] - gaps[i])
        return np.where(np.isfinite(gg), gg, np.inf), c_eff[i] + w * (c_eff[i + 1] - c_eff[i])

    def loads(x, tau):
        gg, cc = at(tau)
        d = x - gg
        q, _ = _invert(np.where(np.isfinite(d), d, -1.0)[None], cc[None], law.coefficient, law.exponent)
        return q[0]

    return loads


def _integrate(model: ImpactModel, params: np.ndarray, lead, force: np.ndarray, loads, tau0: float, tau1: float,
               rate: float, period: float, samples: int) -> tuple[np.ndarray, np.ndarray]:
    """m_eq·ẍ = F_bt − Σq(x, τ(t)) from τ0 to τ1 (m) at dτ/dt = ``rate`` (m/s), started in static
    equilibrium at τ0 (the approach of all pairs there and its rate), by scipy's solve_ivp (RK45,
    steps at most ``period``/40): ``samples`` times (s) from 0 and the approach x (m) at them."""
    from scipy.integrate import solve_ivp

    g, m, f_bt = model.geom, model.equivalent_mass, float(force[0])

    def rhs(t, y):
        return [y[1], (f_bt - loads(y[0], tau0 + rate * t).sum()) / m]

    # static start: approach of all pairs at τ0 and its rate
    h = 1e-7 * g.transverse_base_pitch
    d_lo, d0, d_hi = _approach_at(model, params, lead[None], force, np.array([tau0 - h, tau0, tau0 + h])[:, None, None],
                                  others=False)[:, 0, 0]
    v0 = (d_hi - d_lo) / (2 * h) * rate
    t_end = (tau1 - tau0) / rate
    sol = solve_ivp(rhs, (0.0, t_end), [d0, v0], method="RK45", rtol=1e-7, atol=1e-12, max_step=period / 40,
                    dense_output=True)
    t = np.linspace(0.0, t_end, int(samples))
    return t, sol.sol(t)[0]
