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
speeds amortised it only for hundreds of speeds), a compiled loop does the arithmetic alone
(about 0.26 µs an RK4 step of the 8-DOF pair with the contact table, measured). One compiled
function, :func:`_sweep`, runs every speed of a sweep — the shooting with its monodromy matrix,
then the recorded periods — so that Python is entered twice a sweep, not per period. It is
cached on disk (numba ``cache=True``): a fresh installation compiles it once, in about 5 s
(measured), and every later process loads it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import GearmeshInputError
from ..limits import MAX_STEPS_PER_SPEED
from .model import GearModel


#: Window of the entering pair's "first part of the engagement" after A (fraction of p_bt): its
#: largest force and its dynamic impact are taken from the window start (p_bt/2 before A) to here.
FIRST_PART_AFTER_A = 0.25


@dataclass(frozen=True)
class SolverSettings:
    """Step and window rules of :func:`simulate` (package docstring).

    courant : ω_max·Δt bound (-); steps_per_cycle_min : m_min; transient_tau : n_τ (-); record_cycles : n_rec mesh
    periods (even); min_transient_cycles : at least this many mesh periods before recording; block : steps per block
    of the numpy reference. steady_state : 'shooting' (the periodic steady state by Newton's method on the one-period
    map, :func:`_sweep`, then ``settle_cycles`` periods before recording; the physical-time transient where it does
    not converge to a stable orbit) or 'transient' (always the physical-time transient); shooting_tolerance : the
    fixed point's residual relative to the state's scale; shooting_iterations : at most this many Newton steps;
    periodic_record_cycles : the mesh periods recorded where the shooting found a stable periodic orbit (even; None:
    ``record_cycles``). From a fixed point of the one-period map every period repeats the first to the shooting
    tolerance, so two periods give every statistic to that tolerance; ``record_cycles`` stays for the physical-time
    transient, whose response need not repeat.
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
    periodic_record_cycles: int | None = None


@dataclass
class SweepResult:
    """Steady-state statistics per speed (arrays (S,) or (n, S) / (m, S)), SI units.

    ``y_mean``, ``y_std`` (n, S) mean and standard deviation of each reduced coordinate (m), ``v_rms`` (n, S) RMS of
    its velocity (m/s); ``dte_*`` (m, S) of the mesh deflection δ (m, along the normal, eq. 1: the elastic approach,
    statically F/k; with ``contact`` the approach beyond the first touch, x − g_min); ``approach_mean``,
    ``approach_std`` (m, S) of the gear bodies' approach along the normal, G·y (statically the loaded TE × cos βb: the
    dynamic transmission error); ``force_*`` (m, S) of F (N; min and max at the steps, as ``dte_min``, ``dte_max``);
    ``gap_fraction``, ``back_fraction`` (m, S) fractions of the record window in contact loss and back-side contact;
    ``steady_change`` (m, S) relative change of the deflection standard deviation between the two halves of the
    window; ``series`` optional per-speed time series.

    ``contact`` meshes only (NaN otherwise), normal forces: ``enter_force_max`` (m, S) the entering pair's largest
    force over the first part of its engagement (from p_bt/2 before A to :data:`FIRST_PART_AFTER_A`·p_bt after it);
    ``impact_force`` (m, S) the largest excess there of its force over its quasi-static force at the same mesh
    position (the dynamic impact); ``touch_roll_before_A`` (m, S) the roll (m, transverse line of action) before A at
    which it first carried load, the earliest over the recorded cycles (0 at or after A); ``table_overrun`` (m, S)
    fraction of steps above the table's approach range (extrapolated). ``shooting_iterations`` (S,) Newton steps of
    the periodic steady state (−1: it did not converge to a stable orbit and the physical-time transient was run
    instead); ``periodic_state`` (S, 2n) that state (positions, velocities at mesh phase 0; NaN where none).
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

    Parameters
    ----------
    model, speed_rpm, settings : GearModel, array_like, SolverSettings
        The model, its (S,) driver speeds (rpm) and the solver settings (``courant``, ``transient_tau`` n_τ, ...).

    Returns
    -------
    f_mesh, m, cycles, dt : numpy.ndarray
        (S,) mesh frequency (Hz), steps per mesh period (even), transient mesh periods, time step Δt (s).
    """
    speed_rpm = np.asarray(speed_rpm, dtype=float)
    kmax = np.array([ml.k_max for ml in model.meshes])
    w_max = model.largest_eigenvalue(kmax)
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


def _stage_tables(model: GearModel, m, f_mesh) -> np.ndarray:
    """(4, meshes, 2m) values at the half-step phases j/(2m) of one speed: for a linear mesh
    k (N/m), e (m), ė (m/s) from its :class:`~gearmesh.dynamics.excitation.MeshLaw`; for a
    contact mesh the table row (as a float), the row weight, g_min (m) and dg_min/dt (m/s,
    transverse) at the window position of that phase. With arrays ``m``, ``f_mesh`` (S,): all
    speeds at once, (S, 4, meshes, 2·max m), each speed's 2m phases first."""
    m_s, f_s = np.atleast_1d(m), np.atleast_1d(np.asarray(f_mesh, dtype=float))
    ph = np.arange(2 * int(m_s.max()))[None, :] / (2.0 * m_s[:, None])  # (S, L)
    out = np.zeros((m_s.size, 4, model.m, ph.shape[1]))
    for i, ml in enumerate(model.meshes):
        if ml.contact is None:
            out[:, 0, i] = ml.stiffness(ph)
            e, es = ml.error(ph)
            out[:, 1, i], out[:, 2, i] = e, es * f_s[:, None]
            continue
        t = ml.contact
        w = t.window_position(np.mod(ph + ml.phase_offset, 1.0) * t.pitch)
        dw = t.pitch / t.positions
        row = np.minimum((w / dw).astype(np.int64), t.positions - 1)
        out[:, 0, i] = row
        out[:, 1, i] = w / dw - row
        out[:, 2, i] = t.gap_min[row] + out[:, 1, i] * (t.gap_min[row + 1] - t.gap_min[row])
        out[:, 3, i] = (t.gap_min[row + 1] - t.gap_min[row]) / dw * t.pitch * f_s[:, None]
    return out if np.ndim(m) else out[0]


# --------------------------------------------------------------------------------------
# The compiled loop
# --------------------------------------------------------------------------------------

# statistics per mesh: indices into the accumulator
_D_SUM, _D_SQ, _DH_SUM, _DH_SQ, _A_SUM, _A_SQ, _F_SUM, _F_SQ, _F_MIN, _F_MAX, _D_MIN, _D_MAX, _N_GAP, _N_BACK, \
    _E_MAX, _IMPACT, _TOUCH, _OVERRUN = range(18)
_NQ = 18


@njit(cache=True, inline="always")
def _mesh_force(Y, j, i, G, kind, tab, c_force, du, cb, c_m, bl):
    """Normal force of mesh i at state Y and stage phase index j (the stage tables ``tab``), what
    the statistics need and its derivatives: (F (N), deflection statistic (m), in contact loss
    (0/1), on the back flanks (0/1), transverse approach x (m), table column, column weight, above
    the table (0/1), ∂F/∂δ (N/m), ∂F/∂δ̇ (N·s/m); δ = G·y, δ̇ = G·ẏ). Inlined: what a caller
    does not use costs nothing. The derivatives are those of the interpolated force (the table's
    cell slope; zero where the force is clipped to zero or the flanks are apart)."""
    n = G.shape[1]
    delta = 0.0
    ddot = 0.0
    for q in range(n):
        delta += G[i, q] * Y[q]
        ddot += G[i, q] * Y[n + q]
    if kind[i] == _LINEAR:
        d = delta - tab[1, i, j]
        dd = ddot - tab[2, i, j]
        k = tab[0, i, j]
        if d > 0.0 or bl == np.inf:
            return k * d + c_m[i] * dd, d, 0.0, 0.0, 0.0, 0, 0.0, 0.0, k, c_m[i]
        if d < -bl:
            return k * (d + bl) + c_m[i] * dd, d, 0.0, 1.0, 0.0, 0, 0.0, 0.0, k, c_m[i]
        return 0.0, d, 1.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0
    # contact: bilinear in (row, approach beyond the first touch), transverse force
    r = int(tab[0, i, j])
    a = tab[1, i, j]
    g0 = tab[2, i, j]
    x = delta / cb
    u = x - g0
    stat = u * cb
    side = 1.0
    back = 0.0
    if u <= 0.0:
        u = -x - bl / cb - g0  # back flanks (mirror images of the drive flanks) across the backlash
        side = -1.0
        if u <= 0.0:
            return 0.0, stat, 1.0, 0.0, x, 0, 0.0, 0.0, 0.0, 0.0
        back = 1.0
    U = c_force.shape[2]
    sc = u / du[i]
    c = int(sc)
    over = 0.0
    if c > U - 2:
        c = U - 2
        over = 1.0
    b = sc - c
    f0 = c_force[i, r, c] + b * (c_force[i, r, c + 1] - c_force[i, r, c])
    f1 = c_force[i, r + 1, c] + b * (c_force[i, r + 1, c + 1] - c_force[i, r + 1, c])
    f = f0 + a * (f1 - f0)
    slope = ((1.0 - a) * (c_force[i, r, c + 1] - c_force[i, r, c])
             + a * (c_force[i, r + 1, c + 1] - c_force[i, r + 1, c])) / du[i]
    if f < 0.0:
        f = 0.0
        slope = 0.0
    # F = side·f(u)/cb + …, u = side·δ/cb − …: ∂F/∂δ = f'(u)/cb² on either flank
    return (side * f / cb + c_m[i] * (ddot - side * tab[3, i, j] * cb), stat, 0.0, back, x, c, b, over,
            slope / (cb * cb), c_m[i])


@njit(cache=True)
def _tangent_stage(J, Jt, dK, s, h, n, kr, cr, B, G, dF, gp, gv):
    """Stage s of the RK4 step's variational equations: Jt = J + c_s·h·dK[s−1] (c = 0, ½, ½, 1)
    and dK[s] = A(Yt)·Jt, A the Jacobian of the equations of motion at the stage state (mesh
    force derivatives dF (meshes, 2): ∂F/∂δ, ∂F/∂δ̇). Columns innermost (they vectorise); a
    function of its own: its arithmetic dwarfs the call."""
    n2 = 2 * n
    c = 0.0 if s == 0 else (1.0 if s == 3 else 0.5)
    for p in range(n2):
        for k in range(n2):
            Jt[p, k] = J[p, k] + c * h * dK[s - 1, p, k] if s > 0 else J[p, k]
    for p in range(n):
        for k in range(n2):
            dK[s, p, k] = Jt[n + p, k]
            dK[s, n + p, k] = -(kr[p] * Jt[p, k] + cr[p] * Jt[n + p, k])
    for i in range(G.shape[0]):
        for k in range(n2):
            gp[k] = 0.0
            gv[k] = 0.0
        for q in range(n):
            g = G[i, q]
            if g != 0.0:
                for k in range(n2):
                    gp[k] += g * Jt[q, k]
                    gv[k] += g * Jt[n + q, k]
        for p in range(n):
            b = B[p, i]
            if b != 0.0:
                for k in range(n2):
                    dK[s, n + p, k] -= b * (dF[i, 0] * gp[k] + dF[i, 1] * gv[k])


#: Modes of :func:`_sweep`.
_SHOOT, _PASS = 0, 1


@njit(cache=True)
def _solve(A, b):
    """x with A·x = b (n small) by Gaussian elimination with partial pivoting, and whether A was
    regular: the Newton step of the shooting, compiled without LAPACK (numba's bindings to it
    cost a fresh installation 3 s of compilation for a 14 × 14 solve)."""
    n = b.size
    a = A.copy()
    x = b.copy()
    for c in range(n):
        p = c
        big = abs(a[c, c])
        for r in range(c + 1, n):
            if abs(a[r, c]) > big:
                p, big = r, abs(a[r, c])
        if not big > 0.0 or not np.isfinite(big):
            return x, False
        if p != c:
            for q in range(n):
                a[c, q], a[p, q] = a[p, q], a[c, q]
            x[c], x[p] = x[p], x[c]
        for r in range(c + 1, n):
            f = a[r, c] / a[c, c]
            if f != 0.0:
                for q in range(c + 1, n):
                    a[r, q] -= f * a[c, q]
                x[r] -= f * x[c]
    for c in range(n - 1, -1, -1):
        acc = x[c]
        for q in range(c + 1, n):
            acc -= a[c, q] * x[q]
        x[c] = acc / a[c, c]
    return x, bool(np.all(np.isfinite(x)))


@njit(cache=True)
def _sweep(mode, Ys, Js, scales, tol, max_iter, cycles, n_rec, its, status, kr, cr, B, G, f0, kind, tabs, c_force,
           c_enter, c_egap, c_estat, c_geom, cb, c_m, bl, ms, hs, ys, d_ref, first_part, acc_y, acc_m, series,
           ser_start, ser_t, ser_d, ser_f, ser_y, ser_v, ser_e):
    """Every speed k of a sweep: ms[k] classical RK4 steps of hs[k] s per mesh period, the mesh laws
    at the stage phases of tabs[k] (:func:`_stage_tables`), in one of two modes.

    ``_PASS`` — Ys[k] advanced in place by cycles[k] mesh periods from mesh phase 0; the statistics
    of the last n_rec[k] periods into acc_y[k] (3, n), acc_m[k] (_NQ, meshes); with ``series`` every
    recorded step into the ser_* rows from ser_start[k]. With Js (S, 2n, 2n) (empty: none) each
    speed's tangent matrix is advanced too: the exact derivative of the discrete RK4 map,
    ∂Y(end)/∂Y(start) from Js[k] = I (the stages' variational equations with ∂F/∂δ, ∂F/∂δ̇ of
    :func:`_mesh_force`, :func:`_tangent_stage`).

    ``_SHOOT`` — the periodic steady state by shooting: the state Y with P(Y) = Y, P the map over
    one mesh period (the same steps), by Newton's method from Ys[k]. The Jacobian of P (the
    monodromy matrix of the discrete map) is integrated beside the period, exactly (about 3
    periods' work for the 14 states of the 8-DOF pair, against 14 periods by forward
    differences), and kept while the residual falls at least twofold per step (chord
    iterations); for the linear-in-state models (stiffness and LTCA excitations without contact
    loss) P is affine and one Newton step is exact. Converged when ‖(P(Y) − Y)/scales[k]‖∞ ≤
    ``tol``. Writes Ys[k] (the state; unchanged where not converged), its[k] (Newton steps),
    status[k] (1 converged after Newton steps, Js[k] the monodromy matrix of the last one, whose
    eigenvalues the caller checks for a stable orbit; 0 converged at the start; −1 not
    converged: the caller runs the physical-time transient). Shooting for periodic responses of
    gear models: e.g. Kahraman & Blankenship 1997 (J. Appl. Mech. 64:217); Parker et al. 2000
    (J. Sound Vib. 237:435).

    The reduced bearing matrices are diagonal (``kr``, ``cr``: every model's bearings act along
    their own coordinates and the relative rotations have none), so ÿ_p = f0_p − kr_p y_p −
    cr_p ẏ_p − Σ_i B_pi F_i. The RK4 step is written out once, in this one function: numba does
    not inline a function taking arrays well enough for a step of ~10² flops (a separate step
    function is 1.5–4× slower), and it compiles a loop once per function that calls it (what a
    fresh installation waits for). Whole-array assignments and arithmetic are written as loops
    too: numba compiles the shape-error formatting of each (`J[:] = eye`, `Y - start`), 3.5 s of
    the 8.6 s a fresh installation spent compiling this function."""
    n = kr.shape[0]
    n2 = 2 * n
    nm = G.shape[0]
    du = c_geom[:, 3]
    F = np.empty(nm)
    rs = np.empty((nm, 7))  # per mesh at the step's start: statistic, apart, back, x, column, weight, overrun
    Yt = np.empty(n2)
    K = np.empty((4, n2))
    Jt = np.empty((n2, n2))
    dK = np.empty((4, n2, n2))
    dF = np.zeros((nm, 2))
    gp = np.empty(n2)
    gv = np.empty(n2)
    prev_h = np.zeros(nm)
    prev_w = np.zeros(nm)
    prev_ok = np.zeros(nm, dtype=np.bool_)
    eye = np.zeros((n2, n2))
    for p in range(n2):
        eye[p, p] = 1.0
    J = np.empty((n2, n2))
    J_last = np.zeros((n2, n2))
    M = np.zeros((n2, n2))  # J_last − I: the Newton matrix
    resid = np.empty(n2)
    idle_y = np.zeros((3, n))
    idle_m = np.zeros((_NQ, nm))
    with_tangent = Js.shape[0] > 0
    for k in range(Ys.shape[0]):
        tab, m, h, o = tabs[k], ms[k], hs[k], ser_start[k]
        Y = Ys[k].copy()
        last = np.inf
        it = 0
        shoot = mode == _SHOOT
        tangent = shoot or with_tangent  # the first shooting period brings its monodromy matrix along
        while True:
            # one pass: Y (and J) over ``periods`` mesh periods, the last ``recorded`` of them recorded
            start = Y.copy()
            if tangent:
                J0 = eye if shoot else Js[k]
                for p in range(n2):
                    for q in range(n2):
                        J[p, q] = J0[p, q]
            periods, recorded = (1, 0) if shoot else (cycles[k], n_rec[k])
            into_y = idle_y if shoot else acc_y[k]
            into_m = idle_m if shoot else acc_m[k]
            keep = series and not shoot
            total = periods * m
            rec0 = (periods - recorded) * m
            half0 = (periods - recorded // 2) * m
            if recorded > 0:
                for i in range(nm):
                    into_m[_F_MIN, i] = np.inf
                    into_m[_F_MAX, i] = -np.inf
                    into_m[_D_MIN, i] = np.inf
                    into_m[_D_MAX, i] = -np.inf
                    into_m[_TOUCH, i] = np.inf
                    into_m[_IMPACT, i] = -np.inf
                    prev_ok[i] = False
            k_ser = 0
            for step in range(total):
                j0 = 2 * (step % m)
                j2 = j0 + 2
                if j2 == 2 * m:
                    j2 = 0
                # one classical RK4 step: stages at the half-step phase indices j0, j0 + 1 (twice), j2
                for s in range(4):
                    if s == 0:
                        j = j0
                        for p in range(n2):
                            Yt[p] = Y[p]
                    elif s == 3:
                        j = j2
                        for p in range(n2):
                            Yt[p] = Y[p] + h * K[2, p]
                    else:
                        j = j0 + 1
                        for p in range(n2):
                            Yt[p] = Y[p] + 0.5 * h * K[s - 1, p]
                    for i in range(nm):
                        res = _mesh_force(Yt, j, i, G, kind, tab, c_force, du, cb, c_m, bl)
                        F[i] = res[0]
                        dF[i, 0] = res[8]
                        dF[i, 1] = res[9]
                        if s == 0:  # what the record needs of the state at the step's start
                            rs[i, 0], rs[i, 1], rs[i, 2], rs[i, 3] = res[1], res[2], res[3], res[4]
                            rs[i, 4], rs[i, 5], rs[i, 6] = res[5], res[6], res[7]
                    if s == 0 and recorded > 0 and step >= rec0:  # the state at the step's start
                        second = step >= half0
                        for p in range(n):
                            yc = Y[p] - ys[p]
                            into_y[0, p] += yc
                            into_y[1, p] += yc * yc
                            into_y[2, p] += Y[n + p] * Y[n + p]
                        for i in range(nm):
                            Fi, d_i, gap_i, back_i, x, col, cw, over = (F[i], rs[i, 0], rs[i, 1], rs[i, 2], rs[i, 3],
                                                                        int(rs[i, 4]), rs[i, 5], rs[i, 6])
                            dc = d_i - d_ref[i]
                            app = 0.0
                            for q in range(n):
                                app += G[i, q] * Y[q]
                            ac = app - d_ref[i]
                            into_m[_D_SUM, i] += dc
                            into_m[_D_SQ, i] += dc * dc
                            if second:
                                into_m[_DH_SUM, i] += dc
                                into_m[_DH_SQ, i] += dc * dc
                            into_m[_A_SUM, i] += ac
                            into_m[_A_SQ, i] += ac * ac
                            into_m[_F_SUM, i] += Fi
                            into_m[_F_SQ, i] += Fi * Fi
                            into_m[_F_MIN, i] = min(into_m[_F_MIN, i], Fi)
                            into_m[_F_MAX, i] = max(into_m[_F_MAX, i], Fi)
                            into_m[_D_MIN, i] = min(into_m[_D_MIN, i], d_i)
                            into_m[_D_MAX, i] = max(into_m[_D_MAX, i], d_i)
                            into_m[_N_GAP, i] += gap_i
                            into_m[_N_BACK, i] += back_i
                            into_m[_OVERRUN, i] += over
                            fe = 0.0
                            if kind[i] == _CONTACT:
                                pitch, dw = c_geom[i, 0], c_geom[i, 2]
                                r = int(tab[0, i, j0])
                                a = tab[1, i, j0]
                                w = (r + a) * dw
                                if gap_i == 0.0 and back_i == 0.0:
                                    e0 = c_enter[i, r, col] + cw * (c_enter[i, r, col + 1] - c_enter[i, r, col])
                                    e1 = c_enter[i, r + 1, col] + cw * (c_enter[i, r + 1, col + 1] - c_enter[i, r + 1, col])
                                    fe = max(0.0, e0 + a * (e1 - e0)) / cb
                                eg0 = c_egap[i, r]
                                eg1 = c_egap[i, r + 1]
                                hh = -np.inf
                                if eg0 < np.inf and eg1 < np.inf:
                                    hh = x - (eg0 + a * (eg1 - eg0))
                                if prev_ok[i] and w >= prev_w[i]:
                                    if prev_h[i] <= 0.0 and hh > 0.0:
                                        wt = prev_w[i] + (w - prev_w[i]) * (-prev_h[i]) / (hh - prev_h[i])
                                        into_m[_TOUCH, i] = min(into_m[_TOUCH, i], wt)
                                elif hh > 0.0:  # a new window that starts in contact
                                    into_m[_TOUCH, i] = min(into_m[_TOUCH, i], w)
                                prev_h[i] = hh
                                prev_w[i] = w
                                prev_ok[i] = True
                                if w <= (0.5 + first_part) * pitch:
                                    quasi = (c_estat[i, r] + a * (c_estat[i, r + 1] - c_estat[i, r])) / cb
                                    into_m[_E_MAX, i] = max(into_m[_E_MAX, i], fe)
                                    into_m[_IMPACT, i] = max(into_m[_IMPACT, i], fe - quasi)
                            if keep:
                                ser_d[o + k_ser, i] = d_i
                                ser_f[o + k_ser, i] = Fi
                                ser_e[o + k_ser, i] = fe
                        if keep:
                            ser_t[o + k_ser] = (step - rec0) * h
                            for p in range(n):
                                ser_y[o + k_ser, p] = Y[p]
                                ser_v[o + k_ser, p] = Y[n + p]
                            k_ser += 1
                    for p in range(n):
                        K[s, p] = Yt[n + p]
                        acc = f0[p] - (kr[p] * Yt[p] + cr[p] * Yt[n + p])
                        for i in range(nm):
                            acc -= B[p, i] * F[i]
                        K[s, n + p] = acc
                    if tangent:
                        _tangent_stage(J, Jt, dK, s, h, n, kr, cr, B, G, dF, gp, gv)
                for p in range(n2):
                    Y[p] = Y[p] + (h / 6.0) * (K[0, p] + 2.0 * K[1, p] + 2.0 * K[2, p] + K[3, p])
                if tangent:
                    for p in range(n2):
                        for c in range(n2):
                            J[p, c] += (h / 6.0) * (dK[0, p, c] + 2.0 * dK[1, p, c] + 2.0 * dK[2, p, c] + dK[3, p, c])

            if not shoot:
                for p in range(n2):
                    Ys[k, p] = Y[p]
                    if with_tangent:
                        for q in range(n2):
                            Js[k, p, q] = J[p, q]
                break
            err = 0.0
            for p in range(n2):
                resid[p] = Y[p] - start[p]
                err = max(err, abs(resid[p]) / scales[k, p])
            if not np.isfinite(err) or it == max_iter and err > tol:
                status[k], its[k] = -1, it
                break
            if err <= tol:
                for p in range(n2):
                    Ys[k, p] = start[p]
                    for q in range(n2):
                        Js[k, p, q] = J_last[p, q]
                status[k], its[k] = 1 if it > 0 else 0, it
                break
            if tangent:
                for p in range(n2):
                    for q in range(n2):
                        J_last[p, q] = J[p, q]
                        M[p, q] = J[p, q] - eye[p, q]
                tangent = False
            elif err > 0.5 * last:  # the chord iteration slowed down: this period again, with its Jacobian
                tangent = True
                Y = start
                continue
            dY, regular = _solve(M, resid)
            if not regular:
                status[k], its[k] = -1, it
                break
            for p in range(n2):
                Y[p] = start[p] - dY[p]
            last = err
            it += 1


class _Loop:
    """The compiled loop's per-model arguments (diagonal bearing matrices, mesh kinds, contact
    tables) and the empty buffers of runs that record nothing (one signature: compiled once)."""

    def __init__(self, model: GearModel):
        kr, cr = np.diag(model.Kr).copy(), np.diag(model.Cr).copy()
        if np.any(model.Kr != np.diag(kr)) or np.any(model.Cr != np.diag(cr)):
            raise ValueError("the compiled loop needs diagonal reduced bearing matrices Kr, Cr")
        self.model = model
        self.n, self.nm = model.n, model.m
        self.kind = _kinds(model)
        self.contact = _contact_tables(model)
        ct = self.contact
        self.head = (kr, cr, model.B, model.G, model.f0, self.kind)
        self.tail = (ct.force, ct.enter, ct.enter_gap, ct.enter_static, ct.geom, model.cos_beta_b,
                     np.asarray(model.damping, dtype=float), float(model.backlash))
        self.no_tangent = np.zeros((0, 2 * model.n, 2 * model.n))
        self.no_series = _series_buffers(0, model.n, model.m)

    def speed(self, m: int, f_mesh: float, dt: float) -> "_Speed":
        """The loop at one speed: m steps of ``dt`` (s) per mesh period of frequency ``f_mesh`` (Hz)."""
        return _Speed(self, _stage_tables(self.model, np.array([m]), np.array([f_mesh])), int(m), float(dt))


class _Speed:
    """The compiled loop at one speed (:func:`_sweep` in its ``_PASS`` mode, row by row)."""

    def __init__(self, loop: _Loop, tabs: np.ndarray, m: int, dt: float):
        self.loop, self.tabs, self.m, self.dt = loop, tabs, m, dt

    def run(self, Ys: np.ndarray, cycles: int, n_rec: int = 0, ys=None, d_ref=None, acc_y=None, acc_m=None,
            series=None, tangent: np.ndarray | None = None) -> None:
        """Advance each row of Ys (K, 2n) in place by ``cycles`` mesh periods (from mesh phase 0);
        record the last ``n_rec`` of a single row into acc_y (3, n), acc_m (_NQ, meshes) (and the
        ``series`` buffers) when given; advance each row's ``tangent`` matrix (K, 2n, 2n) too when
        given (identity: the period map's Jacobian)."""
        loop = self.loop
        n, nm = loop.n, loop.nm
        if n_rec == 0:
            ys, d_ref, acc_y, acc_m = np.zeros(n), np.zeros(nm), np.zeros((3, n)), np.zeros((_NQ, nm))
        one = np.ones(1, dtype=np.int64)
        for r in range(Ys.shape[0]):
            _sweep(_PASS, Ys[r:r + 1], loop.no_tangent if tangent is None else tangent[r:r + 1],
                   np.ones((1, 2 * n)), 0.0, 0, int(cycles) * one, int(n_rec) * one, one.copy(), one.copy(), *loop.head,
                   self.tabs, *loop.tail, self.m * one, np.array([self.dt]), ys, d_ref, FIRST_PART_AFTER_A,
                   acc_y[None], acc_m[None], series is not None, 0 * one, *(series or loop.no_series))


def _series_buffers(k: int, n: int, nm: int) -> tuple:
    """Time series buffers of k recorded steps: t, δ, F, y, ẏ, Fe."""
    return np.zeros(k), np.zeros((k, nm)), np.zeros((k, nm)), np.zeros((k, n)), np.zeros((k, n)), np.zeros((k, nm))


def simulate(model: GearModel, speed_rpm, settings: SolverSettings = SolverSettings(), series: bool = False,
             y0: np.ndarray | None = None, progress=None) -> SweepResult:
    """Steady-state response (:class:`SweepResult`, SI) of ``model`` at every speed (package docstring, "Solver").

    Parameters
    ----------
    model, speed_rpm : GearModel, array_like
        The model and its (S,) driver speeds (rpm), positive.
    settings : SolverSettings
        Each speed starts from the static state (or ``y0``, reduced coordinates, at rest), runs its transient and records
        ``settings.record_cycles`` mesh periods (``periodic_record_cycles`` from a periodic orbit found by shooting).
    series, y0, progress : bool, numpy.ndarray or None, callable or None
        ``series=True`` also returns per speed the record window at every step (a few speeds only): time (s), δ (m,
        meshes), F (N), y (n), ẏ (n) and, for ``contact`` meshes, the entering pair's force Fe (N); ``y0`` the start
        state; ``progress`` (optional) is called with the fraction of steps done, about every 5 %.
    """
    speed_rpm = np.atleast_1d(np.asarray(speed_rpm, dtype=float))
    if speed_rpm.size == 0 or not np.all(np.isfinite(speed_rpm)) or np.any(speed_rpm <= 0):
        raise GearmeshInputError("speed_rpm", speed_rpm.tolist(), "must be positive finite speeds")
    for name in ("record_cycles", "periodic_record_cycles"):
        value = getattr(settings, name)
        if name == "record_cycles" or value is not None:
            if value < 2 or value % 2:
                raise GearmeshInputError(name, value, "must be an even number >= 2")
    f_mesh, m, n_tr, dt = step_plan(model, speed_rpm, settings)
    S, n, nm = speed_rpm.size, model.n, model.m
    n_rec = np.full(S, settings.record_cycles, dtype=np.int64)
    loop = _Loop(model)
    tabs = _stage_tables(model, m, f_mesh)
    ys = model.static_state() if y0 is None else np.asarray(y0, dtype=float)
    d_ref = model.G @ model.static_state()
    acc_y = np.zeros((S, 3, n))
    acc_m = np.zeros((S, _NQ, nm))
    work = ((n_tr + n_rec) * m).astype(float)
    cum = np.cumsum(work) / work.sum()
    report_next = 0.05
    out_series = [] if series else None
    scale = _state_scale(model, ys)
    iterations = np.full(S, -1, dtype=np.int64)
    periodic = np.full((S, 2 * n), np.nan)
    cycles_before = n_tr.copy()
    start = np.zeros((S, 2 * n))
    start[:, :n] = ys
    # all speeds in two compiled calls, or a speed at a time to report progress (a series records
    # the periodic window's length, known after the shooting)
    chunks = [slice(0, S)] if progress is None else [slice(k, k + 1) for k in range(S)]
    its, status, Js = np.full(S, -1, dtype=np.int64), np.full(S, -1, dtype=np.int64), np.zeros((S, 2 * n, 2 * n))
    scales = scale[None, :] * (2 * np.pi * f_mesh[:, None]) ** np.repeat([0, 1], n)[None, :]
    zero = np.zeros(S, dtype=np.int64)
    for sl in chunks:
        if settings.steady_state == "shooting":
            shot = start[sl].copy()
            _sweep(_SHOOT, shot, Js[sl], scales[sl], float(settings.shooting_tolerance),
                   int(settings.shooting_iterations), zero[sl], zero[sl], its[sl], status[sl], *loop.head, tabs[sl],
                   *loop.tail, m[sl], dt[sl], ys, d_ref, FIRST_PART_AFTER_A, acc_y[sl], acc_m[sl], False, zero[sl],
                   *loop.no_series)
            ok = status[sl] == 0
            step = status[sl] == 1  # converged after Newton steps: the orbit must be stable
            ok[step] = np.max(np.abs(np.linalg.eigvals(Js[sl][step])), axis=1) < 1.0
            k = np.flatnonzero(ok) + sl.start
            start[k], periodic[k], iterations[k] = shot[ok], shot[ok], its[k]
            cycles_before[k] = settings.settle_cycles
            n_rec[k] = settings.periodic_record_cycles or settings.record_cycles
        rows = (n_rec[sl] * m[sl]) if series else zero[sl]
        offsets = np.concatenate([[0], np.cumsum(rows)[:-1]]).astype(np.int64)
        buffers = _series_buffers(int(rows.sum()), n, nm)
        _sweep(_PASS, start[sl], loop.no_tangent, scales[sl], 0.0, 0, cycles_before[sl] + n_rec[sl], n_rec[sl],
               its[sl], status[sl], *loop.head, tabs[sl], *loop.tail, m[sl], dt[sl], ys, d_ref, FIRST_PART_AFTER_A,
               acc_y[sl], acc_m[sl], series, offsets, *buffers)
        if series:
            for o, r in zip(offsets, rows):
                out_series.append(dict(zip(("t", "delta", "F", "y", "v", "Fe"), (b[o:o + r] for b in buffers))))
        if progress is not None and cum[sl.stop - 1] >= report_next:
            progress(float(cum[sl.stop - 1]))
            report_next = float(cum[sl.stop - 1]) + 0.05
    res = _result(speed_rpm, f_mesh, m, cycles_before, dt, n_rec, acc_y, acc_m, ys, d_ref, loop.kind,
                  loop.contact.geom[:, 0], out_series, int(((cycles_before + n_rec) * m).max()))
    res.shooting_iterations = iterations
    res.periodic_state = periodic
    return res


def _state_scale(model: GearModel, ys: np.ndarray) -> np.ndarray:
    """Length scale (m) of every reduced coordinate for the shooting residual: the largest static
    displacement or mesh approach of the model, for positions and velocities (2n,) (the caller scales
    the velocities by 2π f_mesh)."""
    length = max(float(np.max(np.abs(ys))), float(np.max(np.abs(model.G @ ys))), 1e-12)
    return np.full(2 * model.n, length)


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
