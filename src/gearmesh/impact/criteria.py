"""What else a modification changes: the loaded contact over one mesh cycle on the impact model's
LTCA grid — LTE and its harmonics, line load, flank and tip-edge pressure, root stress
(:func:`ltca_criteria`) — for many micro-geometries and manufactured gears at once.

Everything inside is SI (m, N, s, rad, kg).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GearmeshInputError
from ..deflection import mesh_misalignment
from ..deviation import with_misalignment
from ..ltca import check_torques
from ..ltca_model import ContactLaw
from ..separation import SeparationBasis, basis_gap
from .model import ImpactModel


# --------------------------------------------------------------------------------------
# What else a modification changes: LTE and line load over the mesh cycle
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LTCACriteria:
    """What an engineer signs off, from the loaded contact over one mesh cycle, per (C, T) row
    (SI): ``lte_peak_to_peak`` (m), ``te_harmonics`` (C, T, 3) amplitudes of mesh orders 1–3 (m,
    :func:`gearmesh.ltca.lte_harmonics`), ``max_line_load`` (N/m), ``flank_pressure`` and
    ``edge_pressure`` the largest Hertzian pressure on the flanks (region 1) and on the tip edges
    (regions 2, 3; the pair's tip-edge radius, :mod:`gearmesh.stress`) (Pa, 0 where none is
    loaded), ``root_stress`` the largest ISO 6336-3 local root stress of either gear (Pa);
    ``load`` (C, T, P, J, N) the point loads (N), for ISO 6336's load factors from the LTCA
    (:func:`gearmesh.rating.ltca_load_factors`; None where not asked for)."""

    lte_peak_to_peak: np.ndarray
    te_harmonics: np.ndarray
    max_line_load: np.ndarray
    flank_pressure: np.ndarray
    edge_pressure: np.ndarray
    root_stress: np.ndarray
    load: np.ndarray | None

    @property
    def peak_pressure(self) -> np.ndarray:
        """(C, T) largest pressure wherever it sits (ltca.nc's peak_contact_pressure)."""
        return np.maximum(self.flank_pressure, self.edge_pressure)


def ltca_criteria(model: ImpactModel, torques, params=None, lead_slope=None, stresses: bool = True,
                  samples: int = 1, loads: bool = True) -> LTCACriteria:
    """The loaded contact of modification parameter sets over one mesh cycle, with its sign-off quantities.

    The LTCA of :mod:`gearmesh.ltca` on the model's mesh-cycle grid, gaps re-evaluated from its separation basis (no new
    geometry). Each (row, torque, position) is one contact problem on the position's candidate points, solved with the
    tabulated contact law (:func:`gearmesh.ltca_solve.solve_contact_tabulated`: the loads of
    :func:`gearmesh.ltca_solve.solve_contact` to its tolerance). The stresses are per point of the grid a fixed function
    of its line load w — the Hertzian peak p0 = √(w E*/(π R)) (:func:`gearmesh.stress.contact_stress`) and ISO 6336-3's
    local root stress σ = w cos α_t Y_F Y_S / m_n (:func:`gearmesh.stress.iso_root_stress_slices`), R and Y_F Y_S those
    of the point's roll lengths — so each is evaluated once at w = 1 and scaled: p0(w) = √w · p0(1), σ(w) = w · σ(1)
    (the same quantities, not an approximation).

    Parameters
    ----------
    model, torques : ImpactModel, array_like
        The prepared model (:func:`impact_model`; its LTCA grid is used) and (T,) pinion torques (N m).
    params, lead_slope : array_like or None
        (C, 2, 6) modification parameters and (C, 2) lead slopes [pinion, gear] (m); None: the pair's and the model's.
    stresses : bool, default True
        Also the pressures and root stress (False: left NaN).
    samples : int, default 1
        The rows come in runs of that many manufactured gears of one design, the first the nominal (a divisor of C;
        :func:`_cycle_loads` starts the others from it).
    loads : bool, default True
        Also the load of every point (``load``; False: None, for a caller that needs the criteria alone).

    Returns
    -------
    LTCACriteria
        (C, T) ``lte_peak_to_peak`` (m), ``max_line_load`` (N/m), pressures and ``root_stress`` (Pa), ``load`` (N).

    References
    ----------
    .. [1] ISO 6336-2:2019 and ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Parts 2 and 3.
    .. [2] Johnson K. L., Contact Mechanics, Cambridge University Press (1985): Hertzian line contact.
    """
    from ..ltca import lte_harmonics

    g, lt = model.geom, model.ltca
    params = model.params(params)
    nc = params.shape[0]
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1 or nc % samples:
        raise GearmeshInputError("samples", samples, f"must be a positive integer dividing the {nc} parameter sets")
    lead = np.broadcast_to(np.asarray(lt.lead_slope if lead_slope is None else lead_slope, dtype=float), (nc, 2))
    force = check_torques(torques) / float(g.base_radius[0])
    mis = mesh_misalignment(g, force)
    grid = lt.grid
    p = grid.gap.shape[0] - 1  # the last row is φ1A
    basis = SeparationBasis(*(getattr(grid.basis, f)[:p] for f in SeparationBasis.__dataclass_fields__))
    nt = force.size
    cols, picked = _candidate_points(basis)
    comp = picked(lt.compliance[:p])
    # the separations of the candidate points alone (each point's own, as on the whole grid)
    candidates = SeparationBasis(*(picked(getattr(basis, f)) for f in SeparationBasis.__dataclass_fields__))

    # (C, P, M') at one misalignment, or (C, T, P, M') at each torque's own (the system deflection
    # grows with the load): every row of _cycle_loads is its own contact problem, so the torques
    # solve together as they would one at a time
    one = bool(np.all(mis == mis[0]))
    m = np.asarray(mis[:1] if one else mis, dtype=float)
    lead_t = with_misalignment(np.broadcast_to(lead[:, None], (nc, m.size, 2)), m[None, :])  # (C, T or 1, 2)
    gp = basis_gap(g, candidates, picked(grid.z), lead_t[:, :, None, None, :],
                   params[:, None, None, None, :, :])  # (C, T or 1, P, M')
    q, delta = _cycle_loads(lt.law, gp[:, 0] if one else gp, comp, force, samples)
    w = q / grid.dz  # line loads (N/m), (C, T, P, M')
    nan = np.full((nc, nt), np.nan)
    flank = edge = root = nan
    if stresses:
        pressure, edge_point, root_stress = (picked(a) for a in _unit_load_stresses(model))
        p0 = np.sqrt(w) * pressure
        flank = np.where(edge_point, 0.0, p0).max(axis=(2, 3))
        edge = np.where(edge_point, p0, 0.0).max(axis=(2, 3))
        root = (w * root_stress).max(axis=(2, 3))
    return LTCACriteria(lte_peak_to_peak=np.ptp(delta, axis=-1), te_harmonics=lte_harmonics(delta),
                        max_line_load=w.max(axis=(2, 3)), flank_pressure=flank, edge_pressure=edge,
                        root_stress=root, load=_grid_loads(q, cols, basis.base.shape) if loads else None)


def _candidate_points(basis: SeparationBasis):
    """Each position's candidate points of the mesh-cycle grid (the same for every gear), first and in
    grid order: their columns ``cols`` (P, M') into the flattened grid (P, J·N), M' the most of any
    position (the rest of a shorter row are points that are no candidates), and the function that
    picks them out of a grid array (P, J, N) or one broadcast to it (:func:`ltca_criteria`)."""
    p = basis.base.shape[0]
    candidate = np.isfinite(basis.base).reshape(p, -1)
    cols = np.argsort(~candidate, axis=1, kind="stable")[:, :int(candidate.sum(axis=1).max())]

    def picked(a: np.ndarray) -> np.ndarray:
        return np.take_along_axis(np.broadcast_to(a, basis.base.shape).reshape(p, -1), cols, axis=1)

    return cols, picked


def _grid_loads(q: np.ndarray, cols: np.ndarray, grid_shape: tuple[int, ...]) -> np.ndarray:
    """The loads ``q`` (C, T, P, M') N of each position's candidate points ``cols`` (P, M') put back on
    the grid's points (C, T, P, J, N), 0 elsewhere (:func:`ltca_criteria`)."""
    load = np.zeros(q.shape[:3] + (int(np.prod(grid_shape[1:])),))
    np.put_along_axis(load, np.broadcast_to(cols, q.shape), q, axis=3)
    return load.reshape(q.shape[:3] + tuple(grid_shape[1:]))


def _cycle_loads(law: ContactLaw, gap: np.ndarray, compliance: np.ndarray, force: np.ndarray,
                 samples: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Loads (C, T, P, M) N and approach (C, T, P) m of C gears with separations ``gap`` (C, P, M),
    or (C, T, P, M) each torque's own, at the points of P positions (compliance (P, M) m/N) under
    the transverse forces ``force`` (T,) N: every row one contact problem of
    :func:`gearmesh.ltca_solve.solve_contact_tabulated`.

    With ``samples`` S > 1 the gears come in runs of S manufactured gears of one design, the
    first the nominal. A sample's separations differ from its nominal's by its deviations
    (Δg_i, µm), so its approach starts at the nominal's tangent estimate
    δ_n + Σ k_i Δg_i / Σ k_i (k_i = dq_i/dδ at the nominal's solution). It is an upper bound of
    the sample's: each q_i(d) is convex, so q_i(δ − g_i − Δg_i) ≥ q_i,n + k_i (δ − δ_n − Δg_i) and
    the loads at that δ carry at least F; Newton descends from it in a few steps."""
    from ..ltca_solve import solve_contact_tabulated

    nt = force.size
    if gap.ndim == 3:  # one set of separations for every torque
        gap = gap[:, None]
    nc, _, p, m = gap.shape

    def solve(gp: np.ndarray, start=None):
        k = gp.shape[0]
        rows = (k, nt, p, m)
        # every gear and torque at the same points: each position's compliance once (its row p)
        q, d, dq = solve_contact_tabulated(np.broadcast_to(gp, rows).reshape(-1, m), compliance,
                                           np.broadcast_to(force[:, None], rows[:3]).reshape(-1), law, start,
                                           compliance_rows=np.broadcast_to(np.arange(p), rows[:3]).reshape(-1))
        return q.reshape(rows), d.reshape(rows[:3]), dq.reshape(rows)

    if samples == 1:
        return solve(gap)[:2]
    g = gap.reshape(nc // samples, samples, *gap.shape[1:])
    qn, dn, kn = solve(g[:, 0])
    qs, ds, _ = solve(g[:, 1:].reshape(-1, *gap.shape[1:]), _tangent_start(g[:, 1:] - g[:, :1], dn, kn).reshape(-1))
    q = np.concatenate([qn[:, None], qs.reshape(-1, samples - 1, nt, p, m)], axis=1).reshape(nc, nt, p, m)
    d = np.concatenate([dn[:, None], ds.reshape(-1, samples - 1, nt, p)], axis=1).reshape(nc, nt, p)
    return q, d


def _tangent_start(change: np.ndarray, delta: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """Upper bound (C, S, T, P) m of the approach of gears whose separations differ from a solved
    one's by ``change`` (C, S, T, P, M) m, or (C, S, P, M) the same at every torque (inf/NaN where
    no point): δ + Σ k_i Δg_i / Σ k_i
    with the solved gear's approach ``delta`` (C, T, P) and point tangents ``tangent``
    k_i = dq_i/dδ (C, T, P, M) (:func:`_cycle_loads`)."""
    if change.ndim == tangent.ndim:  # (C, S, P, M): the same change at every torque
        change = change[:, :, None]
    with np.errstate(invalid="ignore"):  # inf − inf at points that are no candidates (k = 0 there)
        dg = np.where(tangent[:, None] > 0, change, 0.0)  # (C, S, T, P, M)
    return delta[:, None] + (tangent[:, None] * dg).sum(axis=-1) / tangent.sum(axis=-1)[:, None]


def _unit_load_stresses(model: ImpactModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per point of the mesh-cycle grid (P, J, N) under a line load of 1 N/m: the Hertzian
    peak pressure (Pa, 0 where no point), whether it is a tip-edge point, and the larger ISO 6336-3
    local root stress of the two gears (Pa) (:func:`ltca_criteria`)."""
    from ..stress import contact_stress, iso_root_stress_slices, pair_edge_radius

    g, grid = model.geom, model.ltca.grid
    p = grid.gap.shape[0] - 1
    region, r1, r2 = grid.region[:p], grid.rho_pinion[:p], grid.rho_gear[:p]
    unit = np.ones(region.shape)
    c = contact_stress(g, unit, region, r1, r2, pair_edge_radius(g))
    root = np.maximum(iso_root_stress_slices(g, 0, unit, r1), iso_root_stress_slices(g, 1, unit, r2))
    return c.pressure, np.asarray(c.edge), root


def ltca_metrics(model: ImpactModel, torques, params=None) -> tuple[np.ndarray, np.ndarray]:
    """Peak-to-peak LTE (m) and largest line load (N/m) over one mesh cycle, (C, T), of :func:`ltca_criteria`.

    Parameters
    ----------
    model : ImpactModel
        The prepared model (:func:`impact_model`).
    torques : array_like
        (T,) pinion torques (N m).
    params : array_like or None
        (C, 2, 6) modification parameter sets (m); None: the pair's own.

    Returns
    -------
    lte_peak_to_peak : numpy.ndarray
        (C, T) peak-to-peak loaded transmission error (m).
    max_line_load : numpy.ndarray
        (C, T) largest line load (N/m).
    """
    c = ltca_criteria(model, torques, params, stresses=False)
    return c.lte_peak_to_peak, c.max_line_load
