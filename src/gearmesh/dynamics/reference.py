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
    """Steady-state response of ``model`` at every speed (rpm), one RK4 batch in numpy (the kernel the compiled loop replaced).

    Always with the physical-time transient. ``contact`` meshes read their table as the compiled loop does (bilinear, the
    same stage phases), written independently with numpy; the entering-pair statistics are not computed (None).

    Parameters
    ----------
    model : GearModel
        The model.
    speed_rpm : array_like
        (S,) driver speeds (rpm).
    settings : SolverSettings
        Solver settings (transient, record cycles, step).
    series : bool, default False
        Also return, per speed, the record window sampled at every step: time (s), δ (m, meshes), F (N), y (n) and
        ẏ (n). Keep it for a few speeds only.
    y0 : numpy.ndarray or None
        Start state (reduced coordinates, at rest); None: the static state.
    progress : callable or None
        Called with the fraction of steps done, about every 5 %.

    Returns
    -------
    SweepResult
        Statistics per speed (SI): ``dte_*``, ``approach_*`` (m), ``force_*`` (N), ``y_std`` (m), ...
    """
    speed_rpm = np.atleast_1d(np.asarray(speed_rpm, dtype=float))
    if speed_rpm.size == 0 or not np.all(np.isfinite(speed_rpm)) or np.any(speed_rpm <= 0):
        raise GearmeshInputError("speed_rpm", speed_rpm.tolist(), "must be positive finite speeds")
    if settings.record_cycles < 2 or settings.record_cycles % 2:
        raise GearmeshInputError("record_cycles", settings.record_cycles, "must be an even number >= 2")
    f_mesh, m, n_tr, dt = step_plan(model, speed_rpm, settings)
    n_rec = settings.record_cycles
    total = (n_tr + n_rec) * m
    n_steps = int(total.max())
    start = n_steps - total  # idle (Δt = 0) before
    system = _BatchSystem(model, m, f_mesh)
    ys = model.static_state() if y0 is None else np.asarray(y0, dtype=float)
    Y = np.zeros((2 * model.n, speed_rpm.size))
    Y[:model.n] = ys[:, None]
    stats = _WindowStats(system, ys, n_steps - n_rec * m, n_steps - (n_rec // 2) * m, dt, series)
    report_every = max(1, n_steps // 20)
    for b0 in range(0, n_steps, settings.block):
        if progress is not None and b0 // report_every != (b0 + settings.block) // report_every:
            progress(b0 / n_steps)
        nb = min(settings.block, n_steps - b0)
        idx, k, e, hdt_b, dt_b = system.block_phases(b0, nb, start, m, dt)
        for j in range(nb):
            step = b0 + j
            ej = [(e[0][q][:, j], e[1][q][:, j]) if system.has_e else (None, None) for q in range(3)]
            delta, F, apart, back = system.force(Y, k[0][:, j], *ej[0], idx[0][j])
            if step >= stats.rec_first:
                stats.add(step, Y, delta, F, apart, back, ej[0][0])
            Y = system.rk4_step(Y, F, hdt_b[j], dt_b[j], k[1][:, j], k[2][:, j], ej[1], ej[2], idx[1][j], idx[2][j])
    if progress is not None:
        progress(1.0)
    return stats.result(speed_rpm, f_mesh, m, n_tr, dt, n_rec, n_steps)


class _BatchSystem:
    """The equations of ``model`` over a batch of S speeds at once, state Y (2n, S): the mesh
    forces (linear, with backlash, or from the contact table) and the RK4 step, with the
    stiffness, error and contact tables at the 2m half-step phases of each speed."""

    def __init__(self, model: GearModel, m: np.ndarray, f_mesh: np.ndarray):
        S, n, nm = m.size, model.n, model.m
        self.model, self.n, self.nm, self.S = model, n, nm, S
        ktab, etab, edtab = _phase_tables(model, m)
        L = ktab.shape[2]
        self.has_e = any(ml.e is not None for ml in model.meshes)
        edtab = edtab * f_mesh[None, :, None]  # de/dt (m/s)
        self.kflat, self.eflat, self.edflat = (t.reshape(nm, S * L) for t in (ktab, etab, edtab))
        self.row = np.arange(S) * L
        self.c_m = model.damping[:, None]
        self.bl = model.backlash
        self.linear = not math.isfinite(self.bl)
        # A_lin (n, 2n) = [−Kr, −Cr]
        self.A_lin = np.hstack([-model.Kr, -model.Cr])
        self.G2 = np.zeros((2 * nm, 2 * n))
        self.G2[:nm, :n] = model.G
        self.G2[nm:, n:] = model.G
        self.Bneg = -model.B
        self.f0 = model.f0[:, None]
        self.contact = [i for i, ml in enumerate(model.meshes) if ml.contact is not None]
        # (4, meshes, S·L): row, weight, g_min, ġ_min
        self.ctab = _contact_phase_tables(model, m, f_mesh, self.contact, L)
        self.cb = model.cos_beta_b

    def block_phases(self, b0: int, nb: int, start: np.ndarray, m: np.ndarray, dt: np.ndarray):
        """For steps b0 … b0+nb−1 of each speed (idle before its ``start``): the half-step phase
        indices 2·loc, 2·loc+1, 2·loc+2 (mod 2m), the stiffness and (error, de/dt) at them, and the
        half and whole time steps (0 while idle)."""
        steps = np.arange(b0, b0 + nb)
        local = steps[:, None] - start[None, :]  # (nb, S) step index within each speed's run
        active = local >= 0
        loc = np.maximum(local, 0)
        idx = tuple((2 * loc + q) % (2 * m)[None, :] for q in range(3))
        k = tuple(np.take(self.kflat, i + self.row[None, :], axis=1) for i in idx)  # (nm, nb, S)
        if self.has_e:
            e = (tuple(np.take(self.eflat, i + self.row[None, :], axis=1) for i in idx),
                 tuple(np.take(self.edflat, i + self.row[None, :], axis=1) for i in idx))
        else:
            e = ((None,) * 3, (None,) * 3)
        dt_s = dt[None, :]
        return idx, k, e, np.where(active, 0.5 * dt_s, 0.0), np.where(active, dt_s, 0.0)

    def force(self, Y, k, e, ed, idx):
        """Deflection statistic δ, mesh force F (N), contact loss and back contact of each mesh."""
        nm = self.nm
        d = self.G2 @ Y
        delta, ddot = d[:nm], d[nm:]
        if self.has_e:
            delta = delta - e
            ddot = ddot - ed
        if self.linear:
            F = k * delta + self.c_m * ddot
        else:
            f = delta - np.clip(delta, -self.bl, 0.0)
            F = k * f + self.c_m * ddot
            F *= (f != 0.0)
        apart = back = None
        if self.contact:
            S = self.S
            delta, F, apart, back = delta.copy(), F.copy(), np.zeros((nm, S)), np.zeros((nm, S))
            for i in self.contact:
                F[i], delta[i], apart[i], back[i] = _contact_force(self.model.meshes[i].contact, d[i], d[nm + i],
                                                                   np.take(self.ctab[:, i], idx + self.row, axis=1),
                                                                   self.cb, float(self.c_m[i, 0]), self.bl)
        return delta, F, apart, back

    def deriv(self, Y, F):
        """dY/dt of the state Y under the mesh forces F."""
        n = self.n
        dY = np.empty_like(Y)
        dY[:n] = Y[n:]
        acc = self.A_lin @ Y
        acc += self.Bneg @ F
        acc += self.f0
        dY[n:] = acc
        return dY

    def rk4_step(self, Y, F, h2, h, k1, k2, ej1, ej2, i1, i2):
        """One classical RK4 step of length ``h`` (``h2`` = h/2) from Y, whose mesh forces are F:
        the stiffness (and error) ``k1`` at the half step, ``k2`` at the end."""
        K1 = self.deriv(Y, F)
        K2 = self.deriv(Y + h2 * K1, self.force(Y + h2 * K1, k1, *ej1, i1)[1])
        Yt = Y + h2 * K2
        K3 = self.deriv(Yt, self.force(Yt, k1, *ej1, i1)[1])
        Yt = Y + h * K3
        K4 = self.deriv(Yt, self.force(Yt, k2, *ej2, i2)[1])
        return Y + (h / 6.0) * (K1 + 2.0 * K2 + 2.0 * K3 + K4)


class _WindowStats:
    """The sums over the record window of each speed (from ``rec_start``; its second half from
    ``half_start``) that the statistics of :class:`SweepResult` come from, shifted by the static
    state so that no variance cancels; with ``series`` every recorded step kept."""

    def __init__(self, system: _BatchSystem, ys: np.ndarray, rec_start: np.ndarray, half_start: np.ndarray,
                 dt: np.ndarray, series: bool):
        n, nm, S = system.n, system.nm, system.S
        self.system, self.rec_start, self.half_start, self.dt = system, rec_start, half_start, dt
        self.ys_col = ys[:, None]
        self.d_ref = (system.model.G @ ys)[:, None]
        z = lambda *shape: np.zeros(shape)  # noqa: E731
        self.sy, self.syy, self.svv = z(n, S), z(n, S), z(n, S)
        self.sd, self.sdd, self.sf, self.sff = z(nm, S), z(nm, S), z(nm, S), z(nm, S)
        self.sd_h, self.sdd_h = z(nm, S), z(nm, S)  # second half of the window
        self.sa, self.saa = z(nm, S), z(nm, S)  # approach δ + e of the bodies
        self.fmin, self.fmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
        self.dmin, self.dmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
        self.ngap, self.nback = z(nm, S), z(nm, S)
        self.rec_first = int(rec_start.min())
        self.store = [dict(t=[], delta=[], F=[], y=[], v=[]) for _ in range(S)] if series else None

    def add(self, step: int, Y, delta, F, apart, back, e) -> None:
        """Step ``step`` of the state Y, its δ, F, contact loss and back contact, and error ``e``
        (None without one), into the sums of the speeds whose window it lies in."""
        system, n = self.system, self.system.n
        w = (step >= self.rec_start)
        wf = w.astype(float)
        wh = (step >= self.half_start).astype(float)
        yc = Y[:n] - self.ys_col  # shifted by the static state: no cancellation in the variance
        yw = yc * wf
        self.sy += yw
        self.syy += yw * yc
        self.svv += Y[n:] * Y[n:] * wf
        dc = delta - self.d_ref
        dw = dc * wf
        self.sd += dw
        self.sdd += dw * dc
        self.sd_h += dc * wh
        self.sdd_h += dc * dc * wh
        ac = dc + e if system.has_e else dc
        for i in system.contact:  # the bodies' approach G·y (δ is the deflection beyond the first touch)
            ac[i] = (system.G2[i] @ Y) - self.d_ref[i]
        self.sa += ac * wf
        self.saa += ac * ac * wf
        self.sf += F * wf
        self.sff += F * F * wf
        self.fmin = np.minimum(self.fmin, np.where(w, F, np.inf))
        self.fmax = np.maximum(self.fmax, np.where(w, F, -np.inf))
        self.dmin = np.minimum(self.dmin, np.where(w, delta, np.inf))
        self.dmax = np.maximum(self.dmax, np.where(w, delta, -np.inf))
        if not system.linear or system.contact:
            gap_f, back_f = (delta < 0) & (delta > -system.bl), delta <= -system.bl
            for i in system.contact:
                gap_f[i], back_f[i] = apart[i], back[i]
            self.ngap += gap_f * wf
            self.nback += back_f * wf
        if self.store is not None:
            for s in np.flatnonzero(w):
                st = self.store[s]
                st["t"].append((step - self.rec_start[s]) * self.dt[s])
                st["delta"].append(delta[:, s].copy())
                st["F"].append(F[:, s].copy())
                st["y"].append(Y[:n, s].copy())
                st["v"].append(Y[n:, s].copy())

    def result(self, speed_rpm, f_mesh, m, n_tr, dt, n_rec: int, n_steps: int) -> SweepResult:
        """The statistics of the record window (means, standard deviations, RMS, extremes, the
        fractions apart and on the back flanks, the steady-state check between its halves)."""
        N = (n_rec * m).astype(float)[None, :]
        Nh = N / 2
        yc_mean = self.sy / N
        y_mean = yc_mean + self.ys_col
        dc_mean = self.sd / N
        dte_mean = dc_mean + self.d_ref
        dte_var = np.maximum(self.sdd / N - dc_mean**2, 0.0)
        m1 = (self.sd - self.sd_h) / Nh
        v1 = np.maximum((self.sdd - self.sdd_h) / Nh - m1**2, 0.0)
        m2 = self.sd_h / Nh
        v2 = np.maximum(self.sdd_h / Nh - m2**2, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            change = np.abs(np.sqrt(v2) - np.sqrt(v1)) / np.maximum(np.sqrt(dte_var), 1e-300)
        ac_mean = self.sa / N
        f_mean = self.sf / N
        out_series = None
        if self.store is not None:
            out_series = [{k: np.asarray(v) for k, v in st.items()} for st in self.store]
        return SweepResult(
            speed_rpm=speed_rpm, mesh_frequency=f_mesh, steps_per_cycle=m, transient_cycles=n_tr, dt=dt,
            y_mean=y_mean, y_std=np.sqrt(np.maximum(self.syy / N - yc_mean**2, 0.0)), v_rms=np.sqrt(self.svv / N),
            dte_mean=dte_mean, dte_std=np.sqrt(dte_var), dte_rms=np.sqrt(dte_var + dte_mean**2),
            dte_min=self.dmin, dte_max=self.dmax, approach_mean=ac_mean + self.d_ref,
            approach_std=np.sqrt(np.maximum(self.saa / N - ac_mean**2, 0.0)),
            force_mean=f_mean, force_min=self.fmin, force_max=self.fmax,
            force_std=np.sqrt(np.maximum(self.sff / N - f_mean**2, 0.0)),
            gap_fraction=self.ngap / N, back_fraction=self.nback / N, steady_change=change, n_steps=n_steps,
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
    """The same steady state at one speed by :func:`scipy.integrate.solve_ivp` on the *full* equations.

    Absolute rotations included, rigid-body mode not removed, from the same static state, over the same physical-time
    transient and record window (dense output sampled at ``samples_per_cycle`` points per mesh period). Slow; for
    tests and the benchmark baseline.

    Parameters
    ----------
    model, speed_rpm, settings : GearModel, float, SolverSettings
        The model, the driver speed (rpm) and the solver settings (record cycles, transient).
    rtol, atol, method : float, float, str
        Tolerances and method of :func:`scipy.integrate.solve_ivp` (default 1e-10, 1e-14, 'DOP853').
    samples_per_cycle : int, default 256
        Dense-output samples per mesh period.
    start, transient_cycles : numpy.ndarray or None, int or None
        (2n,) a reduced state (positions, velocities) at mesh phase 0 to start from instead (e.g. the shooting's
        periodic state); mesh periods before recording instead of the physical-time transient.

    Returns
    -------
    dict
        dte_mean, dte_std, dte_rms (m, of the deflection statistic), approach_mean, approach_std (m, G·q),
        force_mean/min/max (N, per mesh), y_std (reduced translations and q, for comparison), v_rms, and 'nfev'.
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
