"""Reference solutions of the dynamic models, kept to check the compiled step loop of
:mod:`gearmesh.dynamics.integrate` (tests, ``benchmarks/bench_dynamics.py``):

* :func:`simulate_numpy` — the batch RK4 in numpy over all speeds at once that the compiled loop
  replaced (same step rules, same phases: the two agree to round-off) for every excitation (the
  ``contact`` table read with numpy's own indexing, a check of the compiled loop's);
* :func:`reference_solution` — one speed by scipy's solve_ivp (DOP853, tight tolerances) on the
  *full* equations (absolute rotations, rigid-body mode not removed), every excitation
  including ``contact``: an independent integrator on an independent formulation.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import GearmeshInputError
from .integrate import SolverSettings, SweepResult, _stage_tables, step_plan
from .model import GearModel

def _phase_tables(model: GearModel, m: np.ndarray):
    """k, e, de/dt tables at the 2m half-step phases of each speed, padded: (mesh, S, 2·max m)."""
    S, L = m.size, int(2 * m.max())
    k = np.zeros((model.m, S, L))
    e = np.zeros((model.m, S, L))
    ed = np.zeros((model.m, S, L))  # de/dphase (per cycle)
    for s in range(S):
        ph = np.arange(2 * m[s]) / (2.0 * m[s])
        for i, ml in enumerate(model.meshes):
            k[i, s, :ph.size] = ml.stiffness(ph)
            ee, ss = ml.error(ph)
            e[i, s, :ph.size] = ee
            ed[i, s, :ph.size] = ss
    return k, e, ed


def _contact_phase_tables(model: GearModel, m: np.ndarray, f_mesh: np.ndarray, contact: list[int], length: int):
    """Row, row weight, g_min (m) and dg_min/dt (m/s) of the contact meshes at the 2m half-step phases
    of each speed (:func:`gearmesh.dynamics.integrate._stage_tables`), padded: (4, meshes, S·length)."""
    out = np.zeros((4, model.m, m.size, length))
    for s in range(m.size):
        tab = _stage_tables(model, int(m[s]), float(f_mesh[s]))
        for i in contact:
            out[:, i, s, :tab.shape[2]] = tab[:, i]
    return out.reshape(4, model.m, -1)


def _contact_force(table, delta, ddot, tab, cb: float, c_m: float, bl: float):
    """Normal force, deflection statistic, contact loss and back contact (0/1) of a contact mesh at
    normal approach ``delta`` and its rate ``ddot`` (arrays over speeds), ``tab`` (4, S) its stage
    values (:func:`_contact_phase_tables`): the table bilinear in (row, approach beyond the first
    touch), the back flanks across the backlash, the damper on the first touching point's rate."""
    r, a, g0, g_rate = tab[0].astype(np.intp), tab[1], tab[2], tab[3]
    x = delta / cb
    u_front = x - g0
    u_back = -x - bl / cb - g0
    front, back = u_front > 0.0, (u_front <= 0.0) & (u_back > 0.0)
    u = np.where(front, u_front, np.where(back, u_back, 0.0))
    du = table.approach[1] - table.approach[0]
    col = np.minimum((u / du).astype(np.intp), table.approach.size - 2)
    b = u / du - col
    f_r = table.force[r, col] + b * (table.force[r, col + 1] - table.force[r, col])
    f_r1 = table.force[r + 1, col] + b * (table.force[r + 1, col + 1] - table.force[r + 1, col])
    f = np.maximum(f_r + a * (f_r1 - f_r), 0.0)
    side = np.where(back, -1.0, 1.0)
    force = np.where(front | back, side * f / cb + c_m * (ddot - side * g_rate * cb), 0.0)
    return force, u_front * cb, (~front & ~back).astype(float), back.astype(float)


def simulate_numpy(model: GearModel, speed_rpm, settings: SolverSettings = SolverSettings(),
             series: bool = False, y0: np.ndarray | None = None, progress=None) -> SweepResult:
    """Steady-state response of ``model`` at every speed (rpm), one RK4 batch in numpy (the
    kernel the compiled loop replaced), always with the physical-time transient. ``contact``
    meshes read their table as the compiled loop does (bilinear, the same stage phases), written
    independently with numpy; the entering-pair statistics are not computed (None).

    ``series=True`` also returns, per speed, the record window sampled at every step:
    time (s), δ (m, meshes), F (N), y (n) and ẏ (n). Keep it for a few speeds only.
    ``progress`` (optional) is called with the fraction of steps done, about every 5 %.
    """
    speed_rpm = np.atleast_1d(np.asarray(speed_rpm, dtype=float))
    if speed_rpm.size == 0 or not np.all(np.isfinite(speed_rpm)) or np.any(speed_rpm <= 0):
        raise GearmeshInputError("speed_rpm", speed_rpm.tolist(), "must be positive finite speeds")
    if settings.record_cycles < 2 or settings.record_cycles % 2:
        raise GearmeshInputError("record_cycles", settings.record_cycles, "must be an even number >= 2")
    f_mesh, m, n_tr, dt = step_plan(model, speed_rpm, settings)
    S, n, nm = speed_rpm.size, model.n, model.m
    n_rec = settings.record_cycles
    total = (n_tr + n_rec) * m
    n_steps = int(total.max())
    start = n_steps - total  # idle (Δt = 0) before
    rec_start = n_steps - n_rec * m
    half_start = n_steps - (n_rec // 2) * m
    ktab, etab, edtab = _phase_tables(model, m)
    L = ktab.shape[2]
    has_e = any(ml.e is not None for ml in model.meshes)
    edtab = edtab * f_mesh[None, :, None]  # de/dt (m/s)
    kflat, eflat, edflat = (t.reshape(nm, S * L) for t in (ktab, etab, edtab))
    row = np.arange(S) * L
    c_m = model.damping[:, None]
    bl = model.backlash
    linear = not math.isfinite(bl)
    # state Y (2n, S); A_lin (n, 2n) = [−Kr, −Cr]
    A_lin = np.hstack([-model.Kr, -model.Cr])
    G2 = np.zeros((2 * nm, 2 * n))
    G2[:nm, :n] = model.G
    G2[nm:, n:] = model.G
    Bneg = -model.B
    f0 = model.f0[:, None]
    ys = model.static_state() if y0 is None else np.asarray(y0, dtype=float)
    Y = np.zeros((2 * n, S))
    Y[:n] = ys[:, None]
    ys_col = ys[:, None]
    d_ref = (model.G @ ys)[:, None]
    contact = [i for i, ml in enumerate(model.meshes) if ml.contact is not None]
    ctab = _contact_phase_tables(model, m, f_mesh, contact, L)  # (4, meshes, S·L): row, weight, g_min, ġ_min
    cb = model.cos_beta_b

    def force(Y, k, e, ed, idx):
        d = G2 @ Y
        delta, ddot = d[:nm], d[nm:]
        if has_e:
            delta = delta - e
            ddot = ddot - ed
        if linear:
            F = k * delta + c_m * ddot
        else:
            f = delta - np.clip(delta, -bl, 0.0)
            F = k * f + c_m * ddot
            F *= (f != 0.0)
        apart = back = None
        if contact:
            delta, F, apart, back = delta.copy(), F.copy(), np.zeros((nm, S)), np.zeros((nm, S))
            for i in contact:
                F[i], delta[i], apart[i], back[i] = _contact_force(model.meshes[i].contact, d[i], d[nm + i],
                                                                   np.take(ctab[:, i], idx + row, axis=1), cb,
                                                                   float(c_m[i, 0]), bl)
        return delta, F, apart, back

    def deriv(Y, F):
        dY = np.empty_like(Y)
        dY[:n] = Y[n:]
        acc = A_lin @ Y
        acc += Bneg @ F
        acc += f0
        dY[n:] = acc
        return dY

    # accumulators
    z = lambda *shape: np.zeros(shape)  # noqa: E731
    sy, syy, svv = z(n, S), z(n, S), z(n, S)
    sd, sdd, sf, sff = z(nm, S), z(nm, S), z(nm, S), z(nm, S)
    sd_h, sdd_h = z(nm, S), z(nm, S)  # second half of the window
    sa, saa = z(nm, S), z(nm, S)  # approach δ + e of the bodies
    fmin, fmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
    dmin, dmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
    ngap, nback = z(nm, S), z(nm, S)
    rec_first = int(rec_start.min())
    store = [dict(t=[], delta=[], F=[], y=[], v=[]) for _ in range(S)] if series else None
    dt_s = dt[None, :]
    report_every = max(1, n_steps // 20)
    for b0 in range(0, n_steps, settings.block):
        if progress is not None and b0 // report_every != (b0 + settings.block) // report_every:
            progress(b0 / n_steps)
        nb = min(settings.block, n_steps - b0)
        steps = np.arange(b0, b0 + nb)
        local = steps[:, None] - start[None, :]  # (nb, S) step index within each speed's run
        active = local >= 0
        loc = np.maximum(local, 0)
        # half-step phase indices 2·loc and 2·loc+1, 2·loc+2 (mod 2m)
        i0 = (2 * loc) % (2 * m)[None, :]
        i1 = (2 * loc + 1) % (2 * m)[None, :]
        i2 = (2 * loc + 2) % (2 * m)[None, :]
        k0, k1, k2 = (np.take(kflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))  # (nm, nb, S)
        if has_e:
            e0, e1, e2 = (np.take(eflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))
            d0, d1, d2 = (np.take(edflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))
        else:
            e0 = e1 = e2 = d0 = d1 = d2 = None
        hdt_b = np.where(active, 0.5 * dt_s, 0.0)
        dt_b = np.where(active, dt_s, 0.0)
        for j in range(nb):
            step = b0 + j
            ej = (e0[:, j], d0[:, j]) if has_e else (None, None)
            delta, F, apart, back = force(Y, k0[:, j], *ej, i0[j])
            if step >= rec_first:
                w = (step >= rec_start)
                wf = w.astype(float)
                wh = (step >= half_start).astype(float)
                yc = Y[:n] - ys_col  # shifted by the static state: no cancellation in the variance
                yw = yc * wf
                sy += yw
                syy += yw * yc
                svv += Y[n:] * Y[n:] * wf
                dc = delta - d_ref
                dw = dc * wf
                sd += dw
                sdd += dw * dc
                sd_h += dc * wh
                sdd_h += dc * dc * wh
                ac = dc + e0[:, j] if has_e else dc
                for i in contact:  # the bodies' approach G·y (δ is the deflection beyond the first touch)
                    ac[i] = (G2[i] @ Y) - d_ref[i]
                sa += ac * wf
                saa += ac * ac * wf
                sf += F * wf
                sff += F * F * wf
                fmin = np.minimum(fmin, np.where(w, F, np.inf))
                fmax = np.maximum(fmax, np.where(w, F, -np.inf))
                dmin = np.minimum(dmin, np.where(w, delta, np.inf))
                dmax = np.maximum(dmax, np.where(w, delta, -np.inf))
                if not linear or contact:
                    gap_f, back_f = (delta < 0) & (delta > -bl), delta <= -bl
                    for i in contact:
                        gap_f[i], back_f[i] = apart[i], back[i]
                    ngap += gap_f * wf
                    nback += back_f * wf
                if series:
                    for s in np.flatnonzero(w):
                        st = store[s]
                        st["t"].append((step - rec_start[s]) * dt[s])
                        st["delta"].append(delta[:, s].copy())
                        st["F"].append(F[:, s].copy())
                        st["y"].append(Y[:n, s].copy())
                        st["v"].append(Y[n:, s].copy())
            h2, h = hdt_b[j], dt_b[j]
            K1 = deriv(Y, F)
            ej = (e1[:, j], d1[:, j]) if has_e else (None, None)
            K2 = deriv(Y + h2 * K1, force(Y + h2 * K1, k1[:, j], *ej, i1[j])[1])
            Yt = Y + h2 * K2
            K3 = deriv(Yt, force(Yt, k1[:, j], *ej, i1[j])[1])
            Yt = Y + h * K3
            ej = (e2[:, j], d2[:, j]) if has_e else (None, None)
            K4 = deriv(Yt, force(Yt, k2[:, j], *ej, i2[j])[1])
            Y = Y + (h / 6.0) * (K1 + 2.0 * K2 + 2.0 * K3 + K4)
    if progress is not None:
        progress(1.0)
    N = (n_rec * m).astype(float)[None, :]
    Nh = N / 2
    yc_mean = sy / N
    y_mean = yc_mean + ys_col
    dc_mean = sd / N
    dte_mean = dc_mean + d_ref
    dte_var = np.maximum(sdd / N - dc_mean**2, 0.0)
    m1 = (sd - sd_h) / Nh
    v1 = np.maximum((sdd - sdd_h) / Nh - m1**2, 0.0)
    m2 = sd_h / Nh
    v2 = np.maximum(sdd_h / Nh - m2**2, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        change = np.abs(np.sqrt(v2) - np.sqrt(v1)) / np.maximum(np.sqrt(dte_var), 1e-300)
    ac_mean = sa / N
    f_mean = sf / N
    out_series = None
    if series:
        out_series = [{k: np.asarray(v) for k, v in st.items()} for st in store]
    return SweepResult(
        speed_rpm=speed_rpm, mesh_frequency=f_mesh, steps_per_cycle=m, transient_cycles=n_tr, dt=dt,
        y_mean=y_mean, y_std=np.sqrt(np.maximum(syy / N - yc_mean**2, 0.0)), v_rms=np.sqrt(svv / N),
        dte_mean=dte_mean, dte_std=np.sqrt(dte_var), dte_rms=np.sqrt(dte_var + dte_mean**2),
        dte_min=dmin, dte_max=dmax, approach_mean=ac_mean + d_ref,
        approach_std=np.sqrt(np.maximum(saa / N - ac_mean**2, 0.0)),
        force_mean=f_mean, force_min=fmin, force_max=fmax, force_std=np.sqrt(np.maximum(sff / N - f_mean**2, 0.0)),
        gap_fraction=ngap / N, back_fraction=nback / N, steady_change=change, n_steps=n_steps,
        series=out_series)


# --------------------------------------------------------------------------------------
# Reference: one speed with scipy.integrate.solve_ivp on the full (unreduced) equations
# --------------------------------------------------------------------------------------


def _reference_force(ml, delta: float, ddot: float, t: float, f_mesh: float, c_m: float, bl: float, cb: float):
    """Normal force (N) and deflection statistic (m) of one mesh at time ``t`` (s), written from
    the mesh law's own methods (independently of the compiled loop)."""
    ph = f_mesh * t
    if ml.contact is None:
        k = float(ml.stiffness(np.array(ph)))
        e, es = (float(v) for v in ml.error(np.array(ph)))
        d, dd = delta - e, ddot - es * f_mesh
        if not math.isfinite(bl) or d > 0:
            return k * d + c_m * dd, d
        if d < -bl:
            return k * (d + bl) + c_m * dd, d
        return 0.0, d
    tab = ml.contact
    w = float(tab.window_position((ph + ml.phase_offset) % 1.0 * tab.pitch))
    g0 = float(tab.gap(w))
    k = min(int(w / (tab.pitch / tab.positions)), tab.positions - 1)
    g_rate = (tab.gap_min[k + 1] - tab.gap_min[k]) / (tab.pitch / tab.positions) * tab.pitch * f_mesh
    x = delta / cb
    if x > g0:
        f, _ = tab.evaluate(x, w)
        return float(f) / cb + c_m * (ddot - g_rate * cb), (x - g0) * cb
    if math.isfinite(bl):
        u = -x - bl / cb - g0
        if u > 0:
            f, _ = tab.evaluate(g0 + u, w)
            return -float(f) / cb + c_m * (ddot + g_rate * cb), (x - g0) * cb
    return 0.0, (x - g0) * cb


def reference_solution(model: GearModel, speed_rpm: float, settings: SolverSettings = SolverSettings(),
                       rtol: float = 1e-10, atol: float = 1e-14, method: str = "DOP853",
                       samples_per_cycle: int = 256, start: np.ndarray | None = None,
                       transient_cycles: int | None = None) -> dict[str, np.ndarray]:
    """The same steady state at one speed by :func:`scipy.integrate.solve_ivp` on the *full*
    equations (absolute rotations included, rigid-body mode not removed), from the same
    static state, over the same physical-time transient and record window (dense output sampled
    at ``samples_per_cycle`` points per mesh period). Slow; for tests and the benchmark baseline.
    ``start`` (2n,) a reduced state (positions, velocities) at mesh phase 0 to start from instead
    (e.g. the shooting's periodic state), ``transient_cycles`` mesh periods before recording
    instead of the physical-time transient.

    Returns dte_mean, dte_std, dte_rms (of the deflection statistic), approach_mean,
    approach_std (G·q), force_mean/min/max (per mesh), y_std (reduced translations and q, for
    comparison), v_rms, and 'nfev'.
    """
    from scipy.integrate import solve_ivp

    f_mesh, m, n_tr, _ = step_plan(model, np.array([speed_rpm]), settings)
    f_mesh, n_tr = float(f_mesh[0]), int(n_tr[0]) if transient_cycles is None else int(transient_cycles)
    full = model.full
    M, Kb, Cb, Gf, tau = full["M"], full["K_bearing"], full["C_bearing"], full["G"], full["forces"]
    rot, R = list(full["rotations"]), full["R"]
    nf = M.shape[0]
    Minv = np.diag(1.0 / np.diag(M))
    bl, cb = float(model.backlash), model.cos_beta_b
    c_m = model.damping
    # full static state from the reduced one: translations as is, rotations θ = R⁺ q
    ys = np.concatenate([model.static_state(), np.zeros(model.n)]) if start is None else np.asarray(start, float)
    n = model.n
    x0 = np.zeros(2 * nf)
    trans = [i for i in range(nf) if i not in rot]
    x0[trans] = ys[:model.n_trans]
    x0[rot] = np.linalg.pinv(R) @ ys[model.n_trans:n]
    x0[nf:][trans] = ys[n:n + model.n_trans]
    x0[nf:][rot] = np.linalg.pinv(R) @ ys[n + model.n_trans:]

    def forces(t, q, v):
        delta, ddot = Gf @ q, Gf @ v
        out = [_reference_force(ml, float(delta[i]), float(ddot[i]), t, f_mesh, float(c_m[i]), bl, cb)
               for i, ml in enumerate(model.meshes)]
        return np.array([f for f, _ in out]), np.array([d for _, d in out]), delta

    def rhs(t, x):
        q, v = x[:nf], x[nf:]
        F, _, _ = forces(t, q, v)
        acc = Minv @ (tau - Kb @ q - Cb @ v - Gf.T @ F)
        return np.concatenate([v, acc])

    t_mesh = 1.0 / f_mesh
    t_rec0 = n_tr * t_mesh
    t_end = (n_tr + settings.record_cycles) * t_mesh
    n_s = settings.record_cycles * samples_per_cycle
    t_eval = t_rec0 + np.arange(n_s) * (t_mesh / samples_per_cycle)
    sol = solve_ivp(rhs, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    X = sol.y
    per = [forces(t, X[:nf, k], X[nf:, k]) for k, t in enumerate(t_eval)]
    F = np.array([p[0] for p in per]).T
    delta = np.array([p[1] for p in per]).T
    app = np.array([p[2] for p in per]).T
    red = np.vstack([X[trans], R @ X[rot]])
    red_v = np.vstack([X[nf:][trans], R @ X[nf:][rot]])
    return {"dte_mean": delta.mean(axis=1), "dte_std": delta.std(axis=1), "dte_rms": np.sqrt((delta**2).mean(axis=1)),
            "approach_mean": app.mean(axis=1), "approach_std": app.std(axis=1),
            "force_mean": F.mean(axis=1), "force_min": F.min(axis=1), "force_max": F.max(axis=1),
            "y_std": red.std(axis=1), "v_rms": np.sqrt((red_v**2).mean(axis=1)), "nfev": sol.nfev,
            "t": t_eval, "delta": delta, "F": F}
