"""Steady-state speed sweeps: classical RK4 in a compiled step loop (numba), one speed after
another, with the step rules of the package docstring (:mod:`gearmesh.dynamics`, "Solver").

The step loop evaluates the mesh laws exactly as :class:`~gearmesh.dynamics.excitation.MeshLaw`
does (Fourier series or periodic linear tables at the exact mesh phase of every RK4 stage), and
for the ``contact`` excitation the mesh force table of :mod:`gearmesh.meshforce` (bilinear in
window position and approach). :func:`gearmesh.dynamics.reference.simulate_numpy` — the batch
numpy RK4 over all speeds this replaced — and
:func:`gearmesh.dynamics.reference.reference_solution` (scipy's solve_ivp on the unreduced
equations) are kept as references; the tests and ``benchmarks/bench_dynamics.py`` compare them.

Why compiled: a sweep of ~10² speeds takes ~10⁴–10⁵ steps per speed on a model of 7–9 reduced
coordinates; numpy spends its time in per-call overhead on such small arrays (the batch over
speeds amortised it only for hundreds of speeds), a compiled loop does the arithmetic alone.
The kernel is cached on disk (numba ``cache=True``) so a job pays the compilation once per
installation, not once per process.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import GearmeshInputError
from .model import GearModel

#: Cap on RK4 steps at one speed (a very low speed would otherwise run for hours: the
#: transient lasts a fixed physical time while the step is bounded by the highest mode).
MAX_STEPS_PER_SPEED = 2_000_000

#: Window of the entering pair's "first part of the engagement" after A (fraction of p_bt): its
#: largest force and its dynamic impact are taken from the window start (p_bt/2 before A) to here.
FIRST_PART_AFTER_A = 0.25


@dataclass(frozen=True)
class SolverSettings:
    """Step and window rules of :func:`simulate` (package docstring).

    courant : ω_max·Δt bound (-); steps_per_cycle_min : m_min; transient_tau : n_τ (-);
    record_cycles : n_rec mesh periods (even); min_transient_cycles : at least this many
    mesh periods before recording; block : steps per block of the numpy reference.
    steady_state : 'shooting' (the periodic steady state by Newton's method on the one-period
    map, :func:`periodic_state`, then ``settle_cycles`` periods before recording; the
    physical-time transient where it does not converge to a stable orbit) or 'transient'
    (always the physical-time transient); shooting_tolerance : the fixed point's residual
    relative to the state's scale; shooting_iterations : at most this many Newton steps.
    """

    courant: float = 0.25
    steps_per_cycle_min: int = 32
    transient_tau: float = 10.0
    record_cycles: int = 8
    min_transient_cycles: int = 2
    block: int = 256
    steady_state: str = "shooting"
    settle_cycles: int = 2
    shooting_tolerance: float = 1e-9
    shooting_iterations: int = 12


@dataclass
class SweepResult:
    """Steady-state statistics per speed (arrays (S,) or (n, S) / (m, S)), SI units.

    ``y_mean``, ``y_std`` (n, S) mean and standard deviation of each reduced coordinate
    (m), ``v_rms`` (n, S) RMS of its velocity (m/s); ``dte_*`` (m, S) of the mesh deflection
    δ (m, along the normal, eq. 1: the elastic approach, statically F/k; with ``contact`` the
    approach beyond the first touch, x − g_min); ``approach_mean``, ``approach_std`` (m, S) of
    the gear bodies' approach along the normal, G·y (statically the loaded TE × cos βb: the
    dynamic transmission error); ``force_*`` (m, S) of F (N; min and max at the steps, as
    ``dte_min``, ``dte_max``); ``gap_fraction``, ``back_fraction`` (m, S) fractions of the
    record window in contact loss and back-side contact; ``steady_change`` (m, S) relative
    change of the deflection standard deviation between the two halves of the window;
    ``series`` optional per-speed time series.

    ``contact`` meshes only (NaN otherwise), normal forces: ``enter_force_max`` (m, S) the
    entering pair's largest force over the first part of its engagement (from p_bt/2 before A to
    :data:`FIRST_PART_AFTER_A`·p_bt after it); ``impact_force`` (m, S) the largest excess there of
    its force over its quasi-static force at the same mesh position (the dynamic impact);
    ``touch_roll_before_A`` (m, S) the roll (m, transverse line of action) before A at which it
    first carried load, the earliest over the recorded cycles (0 at or after A);
    ``table_overrun`` (m, S) fraction of steps above the table's approach range (extrapolated).
    ``shooting_iterations`` (S,) Newton steps of the periodic steady state (−1: it did not
    converge to a stable orbit and the physical-time transient was run instead);
    ``periodic_state`` (S, 2n) that state (positions, velocities at mesh phase 0; NaN where none).
    """

    speed_rpm: np.ndarray
    mesh_frequency: np.ndarray
    steps_per_cycle: np.ndarray
    transient_cycles: np.ndarray
    dt: np.ndarray
    y_mean: np.ndarray
    y_std: np.ndarray
    v_rms: np.ndarray
    dte_mean: np.ndarray
    dte_std: np.ndarray
    dte_rms: np.ndarray
    dte_min: np.ndarray
    dte_max: np.ndarray
    approach_mean: np.ndarray
    approach_std: np.ndarray
    force_mean: np.ndarray
    force_min: np.ndarray
    force_max: np.ndarray
    force_std: np.ndarray
    gap_fraction: np.ndarray
    back_fraction: np.ndarray
    steady_change: np.ndarray
    n_steps: int
    series: list | None = None
    enter_force_max: np.ndarray | None = None
    impact_force: np.ndarray | None = None
    touch_roll_before_A: np.ndarray | None = None
    table_overrun: np.ndarray | None = None
    shooting_iterations: np.ndarray | None = None
    periodic_state: np.ndarray | None = None


def step_plan(model: GearModel, speed_rpm: np.ndarray, settings: SolverSettings = SolverSettings()):
    """Per speed: mesh frequency (Hz), steps per mesh period m_i, transient periods, Δt (s).

    Δt_max = courant/ω_max with ω_max = max |λ| of the model at the maximum stiffness;
    transient time n_τ/σ_min with σ_min = min(−Re λ) at the mean stiffness.
    """
    speed_rpm = np.asarray(speed_rpm, dtype=float)
    kmax = np.array([ml.k_max for ml in model.meshes])
    w_max = float(np.max(np.abs(model.modes(kmax)["eigenvalue"])))
    sigma = float(np.min(model.modes()["decay_rate"]))
    f_mesh = speed_rpm * model.mesh_frequency_per_rpm
    t_mesh = 1.0 / f_mesh
    dt_max = settings.courant / w_max
    if not (math.isfinite(settings.transient_tau) and settings.transient_tau > 0):
        raise GearmeshInputError("transient_tau", settings.transient_tau, "must be a positive finite number")
    steps_per_cycle = np.maximum(settings.steps_per_cycle_min, np.ceil(t_mesh / dt_max))
    cycles = np.maximum(settings.min_transient_cycles, np.ceil(settings.transient_tau / sigma / t_mesh))
    total = steps_per_cycle * (cycles + settings.record_cycles)
    if np.max(total) > MAX_STEPS_PER_SPEED:
        worst = int(np.argmax(total))
        # above the speed where steps_per_cycle_min sets the step, the work grows with the speed
        advice = "lower the speed" if steps_per_cycle[worst] <= settings.steps_per_cycle_min else "raise the speed"
        raise GearmeshInputError(
            "speeds_rpm", float(speed_rpm[worst]),
            f"needs {total[worst]:.3g} time steps at this speed (limit {MAX_STEPS_PER_SPEED:.0e}): the transient "
            f"lasts {settings.transient_tau / sigma:.3g} s and a step is at most {dt_max:.3g} s; {advice}")
    m = steps_per_cycle.astype(np.int64)
    m += m % 2  # even, so that half steps fall on the tabulated grid of 2m points
    return f_mesh, m, cycles.astype(np.int64), t_mesh / m


# --------------------------------------------------------------------------------------
# The mesh laws at the stage phases of one speed, for the compiled loop
# --------------------------------------------------------------------------------------

#: Mesh kinds of the compiled loop.
_LINEAR, _CONTACT = 0, 1


@dataclass(frozen=True)
class _Contact:
    """The contact tables of a model's meshes, stacked (one shape for all; zeros for linear meshes)."""

    force: np.ndarray  # (m, P+1, U) transverse N
    enter: np.ndarray  # (m, P+1, U) the entering pair's load (N)
    enter_gap: np.ndarray  # (m, P+1) its smallest separation (m), inf where none
    enter_static: np.ndarray  # (m, P+1) its quasi-static load at the model's torque (N)
    geom: np.ndarray  # (m, 4) pitch, roll_A, dw, du (m)


def _kinds(model: GearModel) -> np.ndarray:
    return np.array([_CONTACT if ml.contact is not None else _LINEAR for ml in model.meshes], dtype=np.int64)


def _contact_tables(model: GearModel) -> _Contact:
    tabs = [ml.contact for ml in model.meshes if ml.contact is not None]
    P1, U = tabs[0].force.shape if tabs else (2, 2)
    nm = model.m
    out = _Contact(np.zeros((nm, P1, U)), np.zeros((nm, P1, U)), np.full((nm, P1), np.inf), np.zeros((nm, P1)),
                   np.ones((nm, 4)))
    for i, ml in enumerate(model.meshes):
        t = ml.contact
        if t is None:
            continue
        if t.force.shape != (P1, U):
            raise ValueError("the meshes' force tables must have one shape")
        out.force[i], out.enter[i], out.enter_gap[i] = t.force, t.enter_force, t.enter_gap
        x_s, _ = t.static_approach(float(model.static_force[i]) * model.cos_beta_b)  # transverse F_bt
        out.enter_static[i] = t.entering(x_s, t.window)
        out.geom[i] = (t.pitch, t.roll_engagement, t.pitch / t.positions, t.approach[1] - t.approach[0])
    return out


def _stage_tables(model: GearModel, m: int, f_mesh: float) -> np.ndarray:
    """(4, meshes, 2m) values at the half-step phases j/(2m) of one speed: for a linear mesh
    k (N/m), e (m), ė (m/s) from its :class:`~gearmesh.dynamics.excitation.MeshLaw`; for a
    contact mesh the table row (as a float), the row weight, g_min (m) and dg_min/dt (m/s,
    transverse) at the window position of that phase."""
    ph = np.arange(2 * m) / (2.0 * m)
    out = np.zeros((4, model.m, 2 * m))
    for i, ml in enumerate(model.meshes):
        if ml.contact is None:
            out[0, i] = ml.stiffness(ph)
            e, es = ml.error(ph)
            out[1, i], out[2, i] = e, es * f_mesh
            continue
        t = ml.contact
        w = t.window_position(np.mod(ph + ml.phase_offset, 1.0) * t.pitch)
        dw = t.pitch / t.positions
        row = np.minimum((w / dw).astype(np.int64), t.positions - 1)
        out[0, i] = row
        out[1, i] = w / dw - row
        out[2, i] = t.gap_min[row] + out[1, i] * (t.gap_min[row + 1] - t.gap_min[row])
        out[3, i] = (t.gap_min[row + 1] - t.gap_min[row]) / dw * t.pitch * f_mesh
    return out


# --------------------------------------------------------------------------------------
# The compiled loop
# --------------------------------------------------------------------------------------

# statistics per mesh: indices into the accumulator
_D_SUM, _D_SQ, _DH_SUM, _DH_SQ, _A_SUM, _A_SQ, _F_SUM, _F_SQ, _F_MIN, _F_MAX, _D_MIN, _D_MAX, _N_GAP, _N_BACK, \
    _E_MAX, _IMPACT, _TOUCH, _OVERRUN = range(18)
_NQ = 18
# per-mesh state of a stage: force, deflection statistic, contact loss, back contact, transverse
# approach x, column, column weight, above the table
_S_F, _S_D, _S_GAP, _S_BACK, _S_X, _S_COL, _S_B, _S_OVER = range(8)


@njit(cache=True)
def _mesh_forces(Y, j, G, kind, tab, c_force, du, cb, c_m, bl, st):
    """Normal mesh forces at state Y and stage phase index j (the stage tables ``tab``), into
    st[i, :] (the _S_* quantities of mesh i)."""
    n = G.shape[1]
    for i in range(G.shape[0]):
        delta = 0.0
        ddot = 0.0
        for q in range(n):
            delta += G[i, q] * Y[q]
            ddot += G[i, q] * Y[n + q]
        st[i, _S_GAP] = 0.0
        st[i, _S_BACK] = 0.0
        st[i, _S_OVER] = 0.0
        if kind[i] == 0:
            d = delta - tab[1, i, j]
            dd = ddot - tab[2, i, j]
            k = tab[0, i, j]
            st[i, _S_D] = d
            if d > 0.0 or bl == np.inf:
                st[i, _S_F] = k * d + c_m[i] * dd
            elif d < -bl:
                st[i, _S_F] = k * (d + bl) + c_m[i] * dd
                st[i, _S_BACK] = 1.0
            else:
                st[i, _S_F] = 0.0
                st[i, _S_GAP] = 1.0
            continue
        # contact: bilinear in (row, approach beyond the first touch), transverse force
        r = int(tab[0, i, j])
        a = tab[1, i, j]
        g0 = tab[2, i, j]
        x = delta / cb
        u = x - g0
        st[i, _S_X] = x
        st[i, _S_D] = u * cb
        side = 1.0
        if u <= 0.0:
            u = -x - bl / cb - g0  # back flanks (mirror images of the drive flanks) across the backlash
            side = -1.0
            if u <= 0.0:
                st[i, _S_F] = 0.0
                st[i, _S_GAP] = 1.0
                st[i, _S_COL] = 0.0
                st[i, _S_B] = 0.0
                continue
            st[i, _S_BACK] = 1.0
        U = c_force.shape[2]
        sc = u / du[i]
        c = int(sc)
        if c > U - 2:
            c = U - 2
            st[i, _S_OVER] = 1.0
        b = sc - c
        f0 = c_force[i, r, c] + b * (c_force[i, r, c + 1] - c_force[i, r, c])
        f1 = c_force[i, r + 1, c] + b * (c_force[i, r + 1, c + 1] - c_force[i, r + 1, c])
        f = f0 + a * (f1 - f0)
        if f < 0.0:
            f = 0.0
        st[i, _S_COL] = c
        st[i, _S_B] = b
        st[i, _S_F] = side * f / cb + c_m[i] * (ddot - side * tab[3, i, j] * cb)


@njit(cache=True)
def _deriv(Y, st, Kr, Cr, B, f0, dY):
    n = Kr.shape[0]
    for p in range(n):
        dY[p] = Y[n + p]
        acc = f0[p]
        for q in range(n):
            acc -= Kr[p, q] * Y[q] + Cr[p, q] * Y[n + q]
        for i in range(B.shape[1]):
            acc -= B[p, i] * st[i, _S_F]
        dY[n + p] = acc


@njit(cache=True)
def _rk4_step(Y, j0, j2, h, Kr, Cr, B, G, f0, kind, tab, c_force, du, cb, c_m, bl, st, Yt, K1, K2, K3, K4):
    """One classical RK4 step of h (s) from stage phase index j0 (stages at j0, j0 + 1 twice,
    j2 = j0 + 2 of the 2m half steps), Y updated in place."""
    n = Kr.shape[0]
    _mesh_forces(Y, j0, G, kind, tab, c_force, du, cb, c_m, bl, st)
    _deriv(Y, st, Kr, Cr, B, f0, K1)
    for p in range(2 * n):
        Yt[p] = Y[p] + 0.5 * h * K1[p]
    _mesh_forces(Yt, j0 + 1, G, kind, tab, c_force, du, cb, c_m, bl, st)
    _deriv(Yt, st, Kr, Cr, B, f0, K2)
    for p in range(2 * n):
        Yt[p] = Y[p] + 0.5 * h * K2[p]
    _mesh_forces(Yt, j0 + 1, G, kind, tab, c_force, du, cb, c_m, bl, st)
    _deriv(Yt, st, Kr, Cr, B, f0, K3)
    for p in range(2 * n):
        Yt[p] = Y[p] + h * K3[p]
    _mesh_forces(Yt, j2, G, kind, tab, c_force, du, cb, c_m, bl, st)
    _deriv(Yt, st, Kr, Cr, B, f0, K4)
    for p in range(2 * n):
        Y[p] = Y[p] + (h / 6.0) * (K1[p] + 2.0 * K2[p] + 2.0 * K3[p] + K4[p])


@njit(cache=True)
def _periods(Ys, cycles, Kr, Cr, B, G, f0, kind, tab, c_force, c_geom, cb, c_m, bl, m, h):
    """Each row of Ys (K, 2n) advanced in place by ``cycles`` mesh periods of m steps from phase 0."""
    n = Kr.shape[0]
    nm = G.shape[0]
    du = c_geom[:, 3]
    st = np.zeros((nm, 8))
    Yt = np.empty(2 * n)
    K1 = np.empty(2 * n)
    K2 = np.empty(2 * n)
    K3 = np.empty(2 * n)
    K4 = np.empty(2 * n)
    for k in range(Ys.shape[0]):
        Y = Ys[k]
        for step in range(cycles * m):
            j0 = 2 * (step % m)
            j2 = j0 + 2
            if j2 == 2 * m:
                j2 = 0
            _rk4_step(Y, j0, j2, h, Kr, Cr, B, G, f0, kind, tab, c_force, du, cb, c_m, bl, st, Yt, K1, K2, K3, K4)


@njit(cache=True)
def _speed_kernel(Kr, Cr, B, G, f0, Y, ys, d_ref, kind, tab, c_force, c_enter, c_egap, c_estat, c_geom, cb, c_m, bl,
                  m, n_tr, n_rec, h, first_part, acc_y, acc_m, series, ser_t, ser_d, ser_f, ser_y, ser_v, ser_e):
    """RK4 at one speed: n_tr + n_rec mesh periods of m steps of h (s) from the state Y (2n,),
    updated in place; the statistics of the last n_rec periods into acc_y (3, n) and acc_m
    (_NQ, meshes); with ``series`` every recorded step into the ser_* arrays."""
    n = Kr.shape[0]
    nm = G.shape[0]
    du = c_geom[:, 3]
    Yt = np.empty(2 * n)
    K1 = np.empty(2 * n)
    K2 = np.empty(2 * n)
    K3 = np.empty(2 * n)
    K4 = np.empty(2 * n)
    st = np.zeros((nm, 8))
    prev_h = np.zeros(nm)
    prev_w = np.zeros(nm)
    prev_ok = np.zeros(nm, dtype=np.bool_)
    total = (n_tr + n_rec) * m
    rec0 = n_tr * m
    half0 = (n_tr + n_rec // 2) * m
    for i in range(nm):
        acc_m[_F_MIN, i] = np.inf
        acc_m[_F_MAX, i] = -np.inf
        acc_m[_D_MIN, i] = np.inf
        acc_m[_D_MAX, i] = -np.inf
        acc_m[_TOUCH, i] = np.inf
        acc_m[_IMPACT, i] = -np.inf
    k_ser = 0
    for step in range(total):
        j0 = 2 * (step % m)
        j2 = j0 + 2
        if j2 == 2 * m:
            j2 = 0
        if step >= rec0:
            _mesh_forces(Y, j0, G, kind, tab, c_force, du, cb, c_m, bl, st)
            second = step >= half0
            for p in range(n):
                yc = Y[p] - ys[p]
                acc_y[0, p] += yc
                acc_y[1, p] += yc * yc
                acc_y[2, p] += Y[n + p] * Y[n + p]
            for i in range(nm):
                dc = st[i, _S_D] - d_ref[i]
                app = 0.0
                for q in range(n):
                    app += G[i, q] * Y[q]
                ac = app - d_ref[i]
                F = st[i, _S_F]
                acc_m[_D_SUM, i] += dc
                acc_m[_D_SQ, i] += dc * dc
                if second:
                    acc_m[_DH_SUM, i] += dc
                    acc_m[_DH_SQ, i] += dc * dc
                acc_m[_A_SUM, i] += ac
                acc_m[_A_SQ, i] += ac * ac
                acc_m[_F_SUM, i] += F
                acc_m[_F_SQ, i] += F * F
                acc_m[_F_MIN, i] = min(acc_m[_F_MIN, i], F)
                acc_m[_F_MAX, i] = max(acc_m[_F_MAX, i], F)
                acc_m[_D_MIN, i] = min(acc_m[_D_MIN, i], st[i, _S_D])
                acc_m[_D_MAX, i] = max(acc_m[_D_MAX, i], st[i, _S_D])
                acc_m[_N_GAP, i] += st[i, _S_GAP]
                acc_m[_N_BACK, i] += st[i, _S_BACK]
                acc_m[_OVERRUN, i] += st[i, _S_OVER]
                fe = 0.0
                if kind[i] == 1:
                    pitch, dw = c_geom[i, 0], c_geom[i, 2]
                    r = int(tab[0, i, j0])
                    a = tab[1, i, j0]
                    w = (r + a) * dw
                    x = st[i, _S_X]
                    if st[i, _S_GAP] == 0.0 and st[i, _S_BACK] == 0.0:
                        c = int(st[i, _S_COL])
                        b = st[i, _S_B]
                        e0 = c_enter[i, r, c] + b * (c_enter[i, r, c + 1] - c_enter[i, r, c])
                        e1 = c_enter[i, r + 1, c] + b * (c_enter[i, r + 1, c + 1] - c_enter[i, r + 1, c])
                        fe = max(0.0, e0 + a * (e1 - e0)) / cb
                    eg0 = c_egap[i, r]
                    eg1 = c_egap[i, r + 1]
                    hh = -np.inf
                    if eg0 < np.inf and eg1 < np.inf:
                        hh = x - (eg0 + a * (eg1 - eg0))
                    if prev_ok[i] and w >= prev_w[i]:
                        if prev_h[i] <= 0.0 and hh > 0.0:
                            wt = prev_w[i] + (w - prev_w[i]) * (-prev_h[i]) / (hh - prev_h[i])
                            acc_m[_TOUCH, i] = min(acc_m[_TOUCH, i], wt)
                    elif hh > 0.0:  # a new window that starts in contact
                        acc_m[_TOUCH, i] = min(acc_m[_TOUCH, i], w)
                    prev_h[i] = hh
                    prev_w[i] = w
                    prev_ok[i] = True
                    if w <= (0.5 + first_part) * pitch:
                        quasi = (c_estat[i, r] + a * (c_estat[i, r + 1] - c_estat[i, r])) / cb
                        acc_m[_E_MAX, i] = max(acc_m[_E_MAX, i], fe)
                        acc_m[_IMPACT, i] = max(acc_m[_IMPACT, i], fe - quasi)
                if series:
                    ser_d[k_ser, i] = st[i, _S_D]
                    ser_f[k_ser, i] = F
                    ser_e[k_ser, i] = fe
            if series:
                ser_t[k_ser] = (step - rec0) * h
                for p in range(n):
                    ser_y[k_ser, p] = Y[p]
                    ser_v[k_ser, p] = Y[n + p]
                k_ser += 1
        _rk4_step(Y, j0, j2, h, Kr, Cr, B, G, f0, kind, tab, c_force, du, cb, c_m, bl, st, Yt, K1, K2, K3, K4)

def simulate(model: GearModel, speed_rpm, settings: SolverSettings = SolverSettings(), series: bool = False,
             y0: np.ndarray | None = None, progress=None) -> SweepResult:
    """Steady-state response of ``model`` at every speed (rpm) (package docstring, "Solver").

    Each speed starts from the static state (or ``y0``, reduced coordinates, at rest), runs its
    transient and records ``settings.record_cycles`` mesh periods. ``series=True`` also returns,
    per speed, the record window sampled at every step: time (s), δ (m, meshes), F (N), y (n),
    ẏ (n) and, for ``contact`` meshes, the entering pair's force Fe (N). Keep it for a few speeds
    only. ``progress`` (optional) is called with the fraction of steps done, about every 5 %.
    """
    speed_rpm = np.atleast_1d(np.asarray(speed_rpm, dtype=float))
    if speed_rpm.size == 0 or not np.all(np.isfinite(speed_rpm)) or np.any(speed_rpm <= 0):
        raise GearmeshInputError("speed_rpm", speed_rpm.tolist(), "must be positive finite speeds")
    if settings.record_cycles < 2 or settings.record_cycles % 2:
        raise GearmeshInputError("record_cycles", settings.record_cycles, "must be an even number >= 2")
    f_mesh, m, n_tr, dt = step_plan(model, speed_rpm, settings)
    S, n, nm = speed_rpm.size, model.n, model.m
    n_rec = settings.record_cycles
    kind = _kinds(model)
    ct = _contact_tables(model)
    ys = model.static_state() if y0 is None else np.asarray(y0, dtype=float)
    d_ref = model.G @ model.static_state()
    acc_y = np.zeros((S, 3, n))
    acc_m = np.zeros((S, _NQ, nm))
    damping = np.asarray(model.damping, dtype=float)
    bl, cb = float(model.backlash), model.cos_beta_b
    work = ((n_tr + n_rec) * m).astype(float)
    cum = np.cumsum(work) / work.sum()
    report_next = 0.05
    out_series = [] if series else None
    scale = _state_scale(model, ys)
    iterations = np.zeros(S, dtype=np.int64)
    periodic = np.full((S, 2 * n), np.nan)
    cycles_before = n_tr.copy()
    for s in range(S):
        Y = np.zeros(2 * n)
        Y[:n] = ys
        tab = _stage_tables(model, int(m[s]), float(f_mesh[s]))
        common = (model.Kr, model.Cr, model.B, model.G, model.f0, kind, tab, ct.force, ct.geom, cb, damping, bl,
                  int(m[s]), float(dt[s]))
        iterations[s] = -1
        if settings.steady_state == "shooting":
            Ys, it, ok = periodic_state(Y, common, scale * (2 * np.pi * f_mesh[s]) ** np.repeat([0, 1], n),
                                        settings.shooting_tolerance, settings.shooting_iterations)
            if ok:
                Y, iterations[s], cycles_before[s] = Ys, it, settings.settle_cycles
                periodic[s] = Ys
        k = int(n_rec * m[s]) if series else 0
        ser = (np.zeros(k), np.zeros((k, nm)), np.zeros((k, nm)), np.zeros((k, n)), np.zeros((k, n)),
               np.zeros((k, nm)))
        _speed_kernel(model.Kr, model.Cr, model.B, model.G, model.f0, Y, ys, d_ref, kind, tab, ct.force, ct.enter,
                      ct.enter_gap, ct.enter_static, ct.geom, cb, damping, bl, int(m[s]), int(cycles_before[s]), n_rec,
                      float(dt[s]), FIRST_PART_AFTER_A, acc_y[s], acc_m[s], series, *ser)
        if series:
            out_series.append(dict(zip(("t", "delta", "F", "y", "v", "Fe"), ser)))
        if progress is not None and cum[s] >= report_next:
            progress(float(cum[s]))
            report_next = float(cum[s]) + 0.05
    res = _result(speed_rpm, f_mesh, m, cycles_before, dt, n_rec, acc_y, acc_m, ys, d_ref, kind, ct.geom[:, 0],
                  out_series, int(((cycles_before + n_rec) * m).max()))
    res.shooting_iterations = iterations
    res.periodic_state = periodic
    return res


def _state_scale(model: GearModel, ys: np.ndarray) -> np.ndarray:
    """Length scale (m) of every reduced coordinate for the shooting residual: the largest static
    displacement or mesh approach of the model, for positions and velocities (2n,) (the caller scales
    the velocities by 2π f_mesh)."""
    length = max(float(np.max(np.abs(ys))), float(np.max(np.abs(model.G @ ys))), 1e-12)
    return np.full(2 * model.n, length)


def periodic_state(Y0: np.ndarray, common: tuple, scale: np.ndarray, tol: float, max_iter: int):
    """The periodic steady state of one speed by shooting: the state Y with P(Y) = Y, P the map
    over one mesh period (RK4, the same steps as the sweep), by Newton's method from ``Y0``.

    The Jacobian of P (the monodromy matrix of the discrete map) is formed by forward
    differences, one period per state component, and kept while the residual falls at least
    twofold per step (chord iterations); for the linear-in-state models (stiffness and LTCA
    excitations without contact loss) P is affine and one Newton step is exact. Returns (Y,
    iterations, ok): ok when ‖(P(Y) − Y)/scale‖∞ ≤ ``tol`` and the orbit is stable (every
    eigenvalue of the monodromy matrix inside the unit circle); otherwise the caller runs the
    physical-time transient. Shooting for periodic responses of gear models: e.g. Kahraman &
    Blankenship 1997 (J. Appl. Mech. 64:217); Parker et al. 2000 (J. Sound Vib. 237:435).
    """
    Y = np.array(Y0, dtype=float)
    J = None
    last = np.inf
    for it in range(max_iter + 1):
        P = Y[None].copy()
        _periods(P, 1, *common)
        r = P[0] - Y
        err = float(np.max(np.abs(r) / scale))
        if not np.isfinite(err):
            return Y0, it, False
        if err <= tol:
            if J is None:
                return Y, it, True
            return Y, it, bool(np.max(np.abs(np.linalg.eigvals(J))) < 1.0)
        if it == max_iter:
            break
        if J is None or err > 0.5 * last:
            eps = 1e-6 * scale
            Ys = Y[None] + np.diag(eps)
            _periods(Ys, 1, *common)
            J = (Ys - P[0]).T / eps
        try:
            Y = Y - np.linalg.solve(J - np.eye(Y.size), r)
        except np.linalg.LinAlgError:
            return Y0, it, False
        last = err
    return Y0, max_iter, False


def _result(speed_rpm, f_mesh, m, n_tr, dt, n_rec, acc_y, acc_m, ys, d_ref, kind, pitch, out_series, n_steps):
    """The :class:`SweepResult` from the kernel's accumulators (arrays (n, S) / (m, S))."""
    N = (n_rec * m).astype(float)[None, :]
    Nh = N / 2
    ay = np.transpose(acc_y, (1, 2, 0))  # (3, n, S)
    am = np.transpose(acc_m, (1, 2, 0))  # (_NQ, m, S)
    yc_mean = ay[0] / N
    dc_mean = am[_D_SUM] / N
    dte_var = np.maximum(am[_D_SQ] / N - dc_mean**2, 0.0)
    m1 = (am[_D_SUM] - am[_DH_SUM]) / Nh
    v1 = np.maximum((am[_D_SQ] - am[_DH_SQ]) / Nh - m1**2, 0.0)
    m2 = am[_DH_SUM] / Nh
    v2 = np.maximum(am[_DH_SQ] / Nh - m2**2, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        change = np.abs(np.sqrt(v2) - np.sqrt(v1)) / np.maximum(np.sqrt(dte_var), 1e-300)
    ac_mean = am[_A_SUM] / N
    f_mean = am[_F_SUM] / N
    contact = (kind == _CONTACT)[:, None]
    pitch = pitch[:, None]
    touch = np.where(np.isfinite(am[_TOUCH]), np.maximum(0.5 * pitch - am[_TOUCH], 0.0), 0.0)
    nan = np.full(am[_E_MAX].shape, np.nan)
    return SweepResult(
        speed_rpm=speed_rpm, mesh_frequency=f_mesh, steps_per_cycle=m, transient_cycles=n_tr, dt=dt,
        y_mean=yc_mean + ys[:, None], y_std=np.sqrt(np.maximum(ay[1] / N - yc_mean**2, 0.0)), v_rms=np.sqrt(ay[2] / N),
        dte_mean=dc_mean + d_ref[:, None], dte_std=np.sqrt(dte_var), dte_rms=np.sqrt(dte_var + (dc_mean + d_ref[:, None])**2),
        dte_min=am[_D_MIN], dte_max=am[_D_MAX], approach_mean=ac_mean + d_ref[:, None],
        approach_std=np.sqrt(np.maximum(am[_A_SQ] / N - ac_mean**2, 0.0)),
        force_mean=f_mean, force_min=am[_F_MIN], force_max=am[_F_MAX],
        force_std=np.sqrt(np.maximum(am[_F_SQ] / N - f_mean**2, 0.0)),
        gap_fraction=am[_N_GAP] / N, back_fraction=am[_N_BACK] / N, steady_change=change, n_steps=n_steps,
        series=out_series, enter_force_max=np.where(contact, am[_E_MAX], nan),
        impact_force=np.where(contact, am[_IMPACT], nan), touch_roll_before_A=np.where(contact, touch, nan),
        table_overrun=np.where(contact, am[_OVERRUN] / N, nan))
