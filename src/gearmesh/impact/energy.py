"""The energy method of the mesh-in impact paper: the impact velocity from the closing rate at the
touch, ½·m_eq·v² = ∫F dδ solved on the entering pair's force–approach curve, the local stiffness
F = K_s·δ^n fitted over the range the impact reaches and the paper's closed form with it
(:func:`impact_response`); and the load window of the peak force against torque beside a reference.

Everything inside is SI (m, N, s, rad, kg); the event and its conventions: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from ..errors import GearmeshInputError
from ..limits import check_speeds
from .model import ImpactModel
from .static import ImpactStatic, _force_curve

ENERGY_VELOCITIES = ("transverse", "normal")
_FIT_POINTS = 24


# --------------------------------------------------------------------------------------
# Energy method
# --------------------------------------------------------------------------------------


def closed_form_force(mass, velocity, k_s, n):
    """The mesh-in impact paper's energy-method peak force F_s (N).

    F_s = ((n+1)/2·m·v²)^(n/(n+1))·K_s^(1/(n+1)), from ½·m·v² = ∫₀^δs K_s·δ^n dδ.

    Parameters
    ----------
    mass : float or array_like
        Equivalent mass m (kg).
    velocity : array_like
        Impact velocity v (m/s).
    k_s : array_like
        Local stiffness coefficient K_s (N/m^n).
    n : array_like
        Local stiffness exponent n (-).

    Returns
    -------
    numpy.ndarray
        Peak impact force F_s (N), broadcast over the inputs.

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md).
    """
    n = np.asarray(n, dtype=float)
    return ((n + 1) / 2 * mass * np.asarray(velocity) ** 2) ** (n / (n + 1)) * np.asarray(k_s) ** (1 / (n + 1))


def energy_balance(curve_approach, curve_force, energy):
    """Peak force and approach where ∫₀^δ F dδ = ``energy`` on a tabulated F–δ curve.

    Between nodes F is the power law through them (exact for a pure power law, so the closed
    form and this agree to round-off on F = K·δ^n); (0, 0) is implied before the first node.

    Parameters
    ----------
    curve_approach : array_like
        (..., K) approaches δ of the curve, increasing (m).
    curve_force : array_like
        (..., K) forces F at those approaches, increasing (N).
    energy : array_like
        Energy to absorb (J): (...,) or broadcastable with an extra speed axis last, (..., S).

    Returns
    -------
    force : numpy.ndarray
        (..., S) peak force (N); NaN where the curve does not reach the energy (extend it).
    approach : numpy.ndarray
        (..., S) peak approach (m); NaN likewise.
    """
    d = np.asarray(curve_approach, dtype=float)
    f = np.asarray(curve_force, dtype=float)
    e = np.asarray(energy, dtype=float)
    # segment exponents p_i = ln(F_i+1/F_i)/ln(δ_i+1/δ_i); the first segment continues to 0
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.log(f[..., 1:] / f[..., :-1]) / np.log(d[..., 1:] / d[..., :-1])
    p = np.concatenate([p[..., :1], p], axis=-1)  # segment k ends at node k
    d_prev = np.concatenate([np.zeros_like(d[..., :1]), d[..., :-1]], axis=-1)
    f_prev = np.concatenate([np.zeros_like(f[..., :1]), f[..., :-1]], axis=-1)
    seg = (d * f - d_prev * f_prev) / (p + 1)
    cum = np.cumsum(seg, axis=-1)  # energy at node k
    # locate the segment for every energy (last axis of e is extra)
    cum_e = cum[..., None, :]
    k = np.sum(cum_e < e[..., None], axis=-1)  # first node with cum ≥ e
    kk = np.clip(k, 0, d.shape[-1] - 1)
    take = lambda a: np.take_along_axis(np.broadcast_to(a[..., None, :], e.shape + a.shape[-1:]), kk[..., None], -1)[..., 0]  # noqa: E731
    ck, pk, dk, fk = take(cum), take(p), take(d), take(f)
    # within segment k: E(δ) = E_k − (δ_k F_k − δ F(δ))/(p+1), F(δ) = F_k (δ/δ_k)^p
    rest = (ck - e) * (pk + 1)  # = δ_k F_k − δ F(δ) ≥ 0
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = ((dk * fk - rest) / (dk * fk)) ** (1.0 / (pk + 1))  # (δ/δ_k)
        approach = dk * ratio
        force = fk * ratio**pk
    bad = (k >= d.shape[-1]) | ~np.isfinite(force)
    return np.where(bad, np.nan, force), np.where(bad, np.nan, approach)


def fit_power_law(curve_approach, curve_force, approach_max, n_points: int = _FIT_POINTS):
    """Least-squares fit F = K_s·δ^n (log-log) to the F–δ curve over the range an impact reaches.

    The fit is over [δ_s/n_points, δ_s] at ``n_points`` approaches evenly spaced in δ, δ_s the
    impact's peak approach; the curve is interpolated log-log (consistent with
    :func:`energy_balance`), with (0, 0) implied.

    Parameters
    ----------
    curve_approach : array_like
        (..., K) approaches δ of the curve, increasing (m).
    curve_force : array_like
        (..., K) forces F at those approaches (N).
    approach_max : array_like
        (..., S) peak approach δ_s of each impact (m); NaN: no impact, no fit.
    n_points : int, default 24
        Approaches of the fit.

    Returns
    -------
    k_s : numpy.ndarray
        (..., S) stiffness coefficient K_s (N/m^n).
    n : numpy.ndarray
        (..., S) exponent n (-).
    error : numpy.ndarray
        (..., S) RMS relative error of F of the fit (-). All NaN where there is no impact.

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md): the local stiffness F = K_s·δ^n.
    """
    d = np.asarray(curve_approach, dtype=float)
    f = np.asarray(curve_force, dtype=float)
    dm = np.asarray(approach_max, dtype=float)
    x = dm[..., None] * (np.arange(1, n_points + 1) / n_points)  # (..., S, P)
    # log-log interpolation of the curve (consistent with the energy balance), (0,0) implied
    ld, lf = np.log(d), np.log(f)
    lx = np.log(x)
    idx = np.clip(np.sum(ld[..., None, None, :] < lx[..., None], axis=-1), 1, d.shape[-1] - 1)

    def at(a, i):
        return np.take_along_axis(np.broadcast_to(a[..., None, None, :], lx.shape + a.shape[-1:]), i[..., None], -1)[..., 0]

    d0, d1, f0, f1 = at(ld, idx - 1), at(ld, idx), at(lf, idx - 1), at(lf, idx)
    with np.errstate(invalid="ignore", divide="ignore"):
        ly = f0 + (lx - d0) * (f1 - f0) / (d1 - d0)
    ok = np.isfinite(lx).all(axis=-1, keepdims=True)
    lx, ly = np.where(ok, lx, 0.0), np.where(ok, ly, 0.0)  # no impact: no fit (NaN below)
    xm, ym = lx.mean(axis=-1), ly.mean(axis=-1)
    n = ((lx - xm[..., None]) * (ly - ym[..., None])).sum(-1) / ((lx - xm[..., None]) ** 2).sum(-1)
    logk = ym - n * xm
    k_s = np.exp(logk)
    pred = np.exp(logk[..., None] + n[..., None] * lx)
    err = np.sqrt(np.mean((pred / np.exp(ly) - 1.0) ** 2, axis=-1))
    bad = ~ok[..., 0]
    return np.where(bad, np.nan, k_s), np.where(bad, np.nan, n), np.where(bad, np.nan, err)


@dataclass(frozen=True)
class ImpactResponse:
    """Speed-dependent impact quantities (C, T, S) for the speeds ``speed_rpm`` (S,) (SI).

    ``velocity_transverse`` v_t (m/s, the closing rate of g − δ); ``velocity_normal`` v_t·cos βb
    (the 3-D normal velocity of the helicoid normal); ``kinetic_energy`` ½·m_eq·v² of the
    velocity selected by ``energy_velocity``; ``force_energy_balance`` and
    ``approach_energy_balance`` from the computed F–δ curve; ``stiffness_coefficient`` K_s
    (N/m^n), ``stiffness_exponent`` n and ``fit_error`` of F = K_s·δ^n over that range;
    ``force`` the mesh-in impact paper's closed form with them (N).
    """

    speed_rpm: np.ndarray
    velocity_transverse: np.ndarray
    velocity_normal: np.ndarray
    kinetic_energy: np.ndarray
    force: np.ndarray
    force_energy_balance: np.ndarray
    approach_energy_balance: np.ndarray
    stiffness_coefficient: np.ndarray
    stiffness_exponent: np.ndarray
    fit_error: np.ndarray
    energy_velocity: str


def impact_response(model: ImpactModel, static: ImpactStatic, speeds_rpm,
                    energy_velocity: str = "transverse") -> tuple[ImpactStatic, ImpactResponse]:
    """Impact velocity, energy, peak force and fitted local stiffness at pinion speeds ``speeds_rpm``.

    For every (C, T) row of ``static``: v_t the closing rate of g − δ at the touch × r_b1·ω1,
    E_k = ½·m_eq·v², the energy balance on the computed F–δ curve (:func:`energy_balance`),
    the power-law fit over the range the impact reaches (:func:`fit_power_law`) and the
    paper's closed form with it (:func:`closed_form_force`). The F–δ curve is extended (and the
    static part returned anew) where an impact reaches beyond it; a RuntimeWarning says when the
    impact's approach reaches slices that ``local_keep`` left out.

    Parameters
    ----------
    model : ImpactModel
        The prepared model (:func:`impact_model`).
    static : ImpactStatic
        The speed-independent part (:func:`impact_static`), (C, T) rows.
    speeds_rpm : array_like
        (S,) pinion speeds (rpm).
    energy_velocity : {'transverse', 'normal'}, default 'transverse'
        Velocity in E_k: the transverse closing rate that m_eq belongs to (default), or the
        paper's literal 3-D normal velocity v_t·cos βb (:mod:`gearmesh.impact`).

    Returns
    -------
    static : ImpactStatic
        ``static``, with its F–δ curves extended where needed.
    response : ImpactResponse
        (C, T, S) ``velocity_transverse``/``velocity_normal`` (m/s), ``kinetic_energy`` (J),
        ``force`` closed form and ``force_energy_balance`` (N), ``approach_energy_balance`` (m),
        ``stiffness_coefficient`` (N/m^n), ``stiffness_exponent`` (-), ``fit_error`` (-).

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md); its kinetic energy corrected as docs/impact.md
       says.
    """
    if energy_velocity not in ENERGY_VELOCITIES:
        raise GearmeshInputError("energy_velocity", energy_velocity, f"must be one of {list(ENERGY_VELOCITIES)}")
    speeds = check_speeds(None, speeds_rpm)
    omega1 = speeds * (2 * math.pi / 60.0)
    rb1 = float(model.geom.base_radius[0])
    vt = np.maximum(static.slope, 0.0)[..., None] * rb1 * omega1  # (C, T, S)
    vn = vt * math.cos(model.geom.base_helix_angle)
    m = model.equivalent_mass
    ek = 0.5 * m * (vt if energy_velocity == "transverse" else vn) ** 2
    for _ in range(8):
        f_eb, d_eb = energy_balance(static.curve_approach, static.curve_force, ek)
        short = (np.isnan(f_eb) & (ek > 0) & np.isfinite(static.slope)[..., None]).any(axis=-1)
        if not short.any():
            break
        # extend the F–δ curve of the rows that do not reach the impact's energy (4× the approach)
        cf, ca = np.array(static.curve_force), np.array(static.curve_approach)
        f_new, d_new = _force_curve(model, static.curve_separation[short][None], static.curve_compliance[short][None],
                                    4.0 * ca[short][None, :, -1], cf.shape[-1])
        cf[short], ca[short] = f_new[0], d_new[0]
        static = replace(static, curve_force=cf, curve_approach=ca)
    reach = np.nanmax(np.where(np.isfinite(static.curve_separation), static.curve_separation, np.nan), axis=-1)
    if static.curve_separation.shape[-1] < model.local_points and np.any(d_eb > reach[..., None]):
        warnings.warn("impact: the impact's approach reaches beyond the slices kept for the local stiffness; "
                      "raise local_keep", RuntimeWarning, stacklevel=2)
    zero = ek <= 0
    f_eb = np.where(zero, 0.0, f_eb)
    d_eb = np.where(zero, 0.0, d_eb)
    with np.errstate(invalid="ignore", divide="ignore"):
        k_s, n, err = fit_power_law(static.curve_approach, static.curve_force, np.where(zero, np.nan, d_eb))
        force = np.where(zero, 0.0, closed_form_force(m, vt if energy_velocity == "transverse" else vn, k_s, n))
    return static, ImpactResponse(speed_rpm=speeds, velocity_transverse=vt, velocity_normal=vn, kinetic_energy=ek,
                                  force=force, force_energy_balance=f_eb, approach_energy_balance=d_eb,
                                  stiffness_coefficient=k_s, stiffness_exponent=n, fit_error=err,
                                  energy_velocity=energy_velocity)


# --------------------------------------------------------------------------------------
# Load window: F_s against torque beside a reference
# --------------------------------------------------------------------------------------


def load_grid(torques, step: float, top: float | None = None) -> np.ndarray:
    """Torques (N m) of the load window.

    Every multiple of ``step`` up to ``top``, and the ``torques`` themselves (sorted, unique).

    Parameters
    ----------
    torques : sequence of float
        Torques that must be on the grid (N m).
    step : float
        Grid step (N m).
    top : float or None
        Largest grid torque (N m); default 1.25 × the largest of ``torques``.

    Returns
    -------
    numpy.ndarray
        Sorted unique torques (N m).
    """
    top = 1.25 * max(torques) if top is None else top
    grid = step * np.arange(1, int(math.floor(top / step + 1e-9)) + 1)
    return np.unique(np.concatenate([grid, np.asarray(torques, dtype=float)]))


def load_window(grid: np.ndarray, force: np.ndarray, standard: np.ndarray, design: float) -> tuple[float, float]:
    """[low, high] (N m) of the run of torques around ``design`` where ``force`` is below ``standard``.

    The run is contiguous on ``grid``; (NaN, NaN) when ``force`` is not below ``standard`` at the
    design torque. The ends are grid torques, so a window reaching a grid end may extend further.

    Parameters
    ----------
    grid : numpy.ndarray
        (G,) torques, sorted (N m), e.g. :func:`load_grid`.
    force : numpy.ndarray
        (G,) peak impact force of the candidate at those torques (N).
    standard : numpy.ndarray
        (G,) the reference's force at those torques (N).
    design : float
        Design torque (N m); the grid torque nearest it starts the run.

    Returns
    -------
    tuple of float
        (low, high) torques (N m), or (NaN, NaN).
    """
    beats = np.asarray(force) < np.asarray(standard)
    k = int(np.argmin(np.abs(grid - design)))
    if not beats[k]:
        return math.nan, math.nan
    lo = k
    while lo > 0 and beats[lo - 1]:
        lo -= 1
    hi = k
    while hi < grid.size - 1 and beats[hi + 1]:
        hi += 1
    return float(grid[lo]), float(grid[hi])
