"""The worst manufactured gear of a design: the worst case over the tolerance box (not a sample
maximum), the distributions over a population, gear for gear against a reference design, and a
held-out check (SI units).

A drawing allows every gear inside its tolerance box (:mod:`gearmesh.tolerance`: the lead slope of
each gear within ±f_Hβ, each toleranced modification amount and length within ± its tolerance).
A verdict "the design meets its criteria on the worst manufactured gear" must hold for every one
of them, so the worst gear is a maximum over the box, found by search, not the largest value of a
few random samples (which moves with the seed: an optimiser tuned on one sample set overfits it).

The box the mesh sees
---------------------
The lead slopes of the two gears enter the separations only through their sum, the mesh's lead
mismatch F = f1 + f2 (:func:`gearmesh.deviation.lead_gap`): of the box's two lead dimensions one
combination acts, u ∈ [−1, 1] with f_i = u·f_Hβ,i (every value of F is reached; the other
combination changes nothing). A modification deviation acts only where the design has that
modification (:func:`gearmesh.tolerance.apply_deviations`). The **effective box** of a design is
[−1, 1]^k over the mismatch and its active modification deviations (:class:`ToleranceBox`).

The search (:func:`box_worst`)
------------------------------
Each criterion (per torque) is a column of one batched evaluation of many manufactured gears. The
search evaluates every corner of the modification deviations at the mismatch levels
u ∈ {−1, −½, 0, ½, 1} (the mismatch acts most and its worst can lie inside the range: a loaded-TE
harmonic has its largest amplitude where the contact pattern just reaches a face end), then
refines each column's best point by a compass search over every dimension, each column with its
own halving step (Kolda, Lewis & Torczon 2003, *SIAM Review* 45:385, §3), all columns' trial points
in one batch per poll. Shown in a test to reach a dense grid's worst within 1 % on the default pair and on a random
valid pair (tests/test_robust.py).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .gear import PairGeometry
from .impact.criteria import ltca_criteria
from .impact.energy import impact_response
from .impact.model import ImpactModel
from .impact.static import impact_static
from .ltca import MESH_ORDERS
from .surface import fit_modifications
from .tolerance import ToleranceModel, apply_deviations, unit_deviations

__all__ = ["CRITERIA", "CRITERION_UNITS", "ToleranceBox", "tolerance_box", "GearCriteria", "gear_criteria", "BoxWorst", "box_worst", "design_box_worst", "population_units", "manufactured_pair",
           "box_scenarios",
           "MISMATCH_LEVELS"]

#: The sign-off criteria of one manufactured gear, per torque: the energy-method impact index F_s at
#: the design speed (the mesh-in impact paper's), the loaded-TE mesh orders, the largest flank and
#: tip-edge pressure, the largest root stress of either gear.
CRITERIA = ("impact_force", *(f"lte_order_{k}" for k in MESH_ORDERS), "peak_flank_pressure", "peak_edge_pressure",
            "peak_root_stress")
CRITERION_UNITS = {"impact_force": "N", **{f"lte_order_{k}": "m" for k in MESH_ORDERS}, "peak_flank_pressure": "Pa",
                   "peak_edge_pressure": "Pa", "peak_root_stress": "Pa"}
#: Mismatch levels of the first stage of the search (module docstring).
MISMATCH_LEVELS = np.linspace(-1.0, 1.0, 5)


@dataclass(frozen=True)
class ToleranceBox:
    """The effective tolerance box of one design (module docstring): ``model`` the tolerance model,
    ``active`` the indices into ``model.dimensions`` of the modification deviations the design has,
    ``mismatch`` whether the lead slopes are toleranced (then effective dimension 0 is u)."""

    model: ToleranceModel
    active: tuple[int, ...]
    mismatch: bool

    @property
    def size(self) -> int:
        """k, the effective dimensions."""
        return len(self.active) + int(self.mismatch)

    def full_units(self, units: np.ndarray) -> np.ndarray:
        """The effective unit points (n, k) as unit deviations (n, K) of the whole model (the lead
        dimensions both at u; inactive modification dimensions at 0)."""
        units = np.atleast_2d(np.asarray(units, dtype=float))
        dims = self.model.dimensions
        full = np.zeros((units.shape[0], len(dims)))
        col = 0
        if self.mismatch:
            for j, (kind, _, _) in enumerate(dims):
                if kind == "lead":
                    full[:, j] = units[:, 0]
            col = 1
        for j in self.active:
            full[:, j] = units[:, col]
            col += 1
        return full

    def gears(self, geom: PairGeometry, params: np.ndarray, lead_slope, units: np.ndarray):
        """The manufactured gears of design ``params`` (2, 6) (m) with nominal lead slopes (2,) (m) at
        effective unit points ``units`` (n, k): parameter rows (n, 2, 6) made valid
        (:func:`gearmesh.surface.fit_modifications`) and lead slopes (n, 2) (m)."""
        p, lead = apply_deviations(self.model, np.asarray(params, dtype=float)[None], lead_slope,
                                   self.full_units(units))
        return fit_modifications(geom, p[0, 1:]), lead[0, 1:]


def tolerance_box(model: ToleranceModel, params: np.ndarray) -> ToleranceBox:
    """The effective box of design ``params`` under ``model`` (module docstring, "The box the mesh sees").

    Parameters
    ----------
    model : ToleranceModel
        The tolerance model (:mod:`gearmesh.tolerance`): its dimensions (lead and modification deviations).
    params : numpy.ndarray
        (2, 6) modification parameters of the design (m); a deviation is active only where its amount is > 0.

    Returns
    -------
    ToleranceBox
        ``active`` the indices of the active modification dimensions, ``mismatch`` whether the lead mismatch is one.
    """
    params = np.asarray(params, dtype=float)
    active = tuple(j for j, (kind, g, k) in enumerate(model.dimensions) if kind == "modification" and params[g, k] > 0)
    return ToleranceBox(model=model, active=active, mismatch=any(kind == "lead" for kind, _, _ in model.dimensions))


@dataclass(frozen=True)
class GearCriteria:
    """The :data:`CRITERIA` of N manufactured gears at T torques (SI): ``values`` (N, T, K); and of
    F_s its energy-balance value ``impact_force_energy_balance`` and the mesh-in ``scenario`` (N, T)."""

    values: np.ndarray
    impact_force_energy_balance: np.ndarray
    scenario: np.ndarray


def gear_criteria(model: ImpactModel, rows: np.ndarray, lead: np.ndarray, torques, speed_rpm: float,
                  energy_velocity: str = "transverse", samples: int = 1) -> GearCriteria:
    """The :data:`CRITERIA` of N manufactured gears at pinion ``torques``.

    F_s at ``speed_rpm`` (closed form; 0 where the entering pair meets without a closing velocity) and the loaded contact
    over one mesh cycle (:func:`gearmesh.impact.ltca_criteria`).

    Parameters
    ----------
    model : ImpactModel
        The prepared impact model (:func:`gearmesh.impact.impact_model`).
    rows : numpy.ndarray
        (N, 2, 6) modification parameters of the gears (m).
    lead : numpy.ndarray
        (N, 2) lead slopes [pinion, gear] (m over the face width).
    torques : array_like
        (T,) pinion torques (N m).
    speed_rpm : float
        Pinion speed (rpm).
    energy_velocity : {'transverse', 'normal'}, default 'transverse'
        Velocity of the impact energy (:func:`gearmesh.impact.impact_response`).
    samples : int, default 1
        Rows per design, the first the nominal (:func:`gearmesh.impact.ltca_criteria`).

    Returns
    -------
    GearCriteria
        ``values`` (N, T, K) in :data:`CRITERIA` order (N, m, Pa), ``impact_force_energy_balance`` (N, T) (N) and the
        mesh-in ``scenario`` (N, T).
    """
    c = ltca_criteria(model, torques, rows, lead_slope=lead, samples=samples, loads=False)
    static = impact_static(model, torques, rows, lead_slope=lead, engagement=False)
    _, resp = impact_response(model, static, [speed_rpm], energy_velocity=energy_velocity)
    force = np.nan_to_num(resp.force[..., 0], nan=0.0)
    values = np.concatenate([force[..., None], c.te_harmonics, c.flank_pressure[..., None], c.edge_pressure[..., None],
                             c.root_stress[..., None]], axis=-1)
    return GearCriteria(values, resp.force_energy_balance[..., 0], static.scenario)


@dataclass(frozen=True)
class BoxWorst:
    """The worst of each column over the box: ``values`` (M,), ``points`` (M, k) the effective unit
    points where they were found, ``evaluated`` the number of manufactured gears evaluated."""

    values: np.ndarray
    points: np.ndarray
    evaluated: int


def _first_stage(k: int, mismatch: bool) -> np.ndarray:
    """The corners of the modification deviations at every mismatch level (module docstring)."""
    mods = k - int(mismatch)
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=mods))) if mods else np.zeros((1, 0))
    if not mismatch:
        return np.vstack([corners, np.zeros((1, mods))]) if mods else np.zeros((1, 0))
    levels = MISMATCH_LEVELS[:, None]
    return np.vstack([np.hstack([np.broadcast_to(levels, (levels.size, 1)), np.broadcast_to(c, (levels.size, mods))])
                      for c in corners])


def _point_key(point: np.ndarray) -> bytes:
    """The key of a unit point once clipped to the box (12 decimals): one gear, evaluated once."""
    return np.round(np.clip(point, -1.0, 1.0), 12).tobytes()


def box_worst(evaluate: Callable[[np.ndarray], np.ndarray], k: int, mismatch: bool = True,
              min_step: float = 1.0 / 32.0, starts: int = 2, first_stage_only: bool = False) -> BoxWorst:
    """The largest value of every column of ``evaluate`` over [−1, 1]^k (module docstring, "The search").

    The first stage, then a compass search [1]_ from each column's ``starts`` best first-stage points (a column can have
    more than one local maximum), each walker with its own step — polled along every dimension, kept while the poll
    improves its point, else halved, down to ``min_step`` — all walkers' trial points in one batch per poll.

    Parameters
    ----------
    evaluate : callable
        Unit points (n, k) → values (n, M).
    k, mismatch, min_step, starts : int, bool, float, int
        Dimensions of the box; dimension 0 the lead mismatch (default True); smallest step (1/32); walkers per column (2).
    first_stage_only : bool, default False
        The first stage's worst alone (a lower bound of the box's, for a quick refusal).

    Returns
    -------
    BoxWorst
        ``values`` (M,), ``points`` (M, k) where they were found, ``evaluated`` the gears evaluated.

    References
    ----------
    .. [1] Kolda T. G., Lewis R. M., Torczon V., "Optimization by direct search: new perspectives on some classical and
       modern methods", SIAM Review 45 (2003) 385–482, §3.
    """
    seen: dict[bytes, int] = {}
    points: list[np.ndarray] = []
    values: list[np.ndarray] = []

    def run(trial: np.ndarray) -> None:
        fresh = []
        for p in np.clip(trial, -1.0, 1.0):
            key = _point_key(p)
            if key not in seen:
                seen[key] = len(points) + len(fresh)
                fresh.append(p)
        if fresh:
            block = np.array(fresh)
            points.extend(block)
            values.append(np.asarray(evaluate(block), dtype=float).reshape(block.shape[0], -1))

    def best_of() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        vals = np.vstack(values)
        idx = np.nanargmax(np.where(np.isfinite(vals), vals, -np.inf), axis=0)
        return np.array(points), vals, idx

    run(_first_stage(k, mismatch))
    pts, vals, first = best_of()
    m = vals.shape[1]
    if first_stage_only:
        return BoxWorst(values=vals[first, np.arange(m)], points=pts[first], evaluated=len(points))
    finite = np.where(np.isfinite(vals), vals, -np.inf)
    order = np.argsort(-finite, axis=0, kind="stable")[:max(1, starts)]  # (starts, M) best first
    column = np.tile(np.arange(m), order.shape[0])  # each walker's column
    at = order.reshape(-1)  # each walker's point
    step = np.full(at.size, 0.5)
    moves = np.vstack([np.eye(k), -np.eye(k)]) if k else np.zeros((0, 0))
    while k and np.any(step >= min_step):
        active = np.flatnonzero(step >= min_step)
        trial = (pts[at[active]][:, None, :] + step[active, None, None] * moves[None])  # (walkers, 2k, k)
        run(trial.reshape(-1, k))
        pts, vals, _ = best_of()
        finite = np.where(np.isfinite(vals), vals, -np.inf)
        for w in active:  # each walker moves to the best of its own poll, if better
            key = [seen[_point_key(p)] for p in pts[at[w]] + step[w] * moves]
            j = key[int(np.argmax(finite[key, column[w]]))]
            if finite[j, column[w]] > finite[at[w], column[w]]:
                at[w] = j
            else:
                step[w] *= 0.5
    best = np.array([at[column == c][np.argmax(finite[at[column == c], c])] for c in range(m)])
    best = np.where(finite[best, np.arange(m)] >= finite.max(axis=0), best, np.argmax(finite, axis=0))
    cols = np.arange(m)
    return BoxWorst(values=vals[best, cols], points=pts[best], evaluated=len(points))


def design_box_worst(model: ImpactModel, tolerance: ToleranceModel, params: np.ndarray, torques, speed_rpm: float,
                     energy_velocity: str = "transverse", first_stage_only: bool = False
                     ) -> tuple[BoxWorst, ToleranceBox]:
    """The box worst of every criterion and torque of design ``params`` on ``model``, and its effective box.

    Parameters
    ----------
    model : ImpactModel
        The prepared impact model; its lead slopes are the nominal.
    tolerance : ToleranceModel
        The tolerance model (:mod:`gearmesh.tolerance`).
    params : numpy.ndarray
        (2, 6) modification parameters of the design (m).
    torques : array_like
        (T,) pinion torques (N m).
    speed_rpm : float
        Pinion speed (rpm).
    energy_velocity : {'transverse', 'normal'}, default 'transverse'
        Velocity of the impact energy (:func:`gearmesh.impact.impact_response`).
    first_stage_only : bool, default False
        The first stage of :func:`box_worst` alone.

    Returns
    -------
    worst : BoxWorst
        ``values`` (T, K) in :data:`CRITERIA` order (N, m, Pa), ``points`` (T, K, k), ``evaluated``.
    box : ToleranceBox
        The design's effective box (:func:`tolerance_box`).
    """
    box = tolerance_box(tolerance, params)
    nt = np.atleast_1d(torques).size

    def evaluate(units: np.ndarray) -> np.ndarray:
        # the nominal gear first, so every gear's contact solve starts at its tangent estimate
        # (ltca_criteria's samples): the same loads in fewer Newton steps
        with_nominal = np.vstack([np.zeros((1, units.shape[1])), units])
        rows, lead = box.gears(model.geom, params, model.lead_slope, with_nominal)
        values = gear_criteria(model, rows, lead, torques, speed_rpm, energy_velocity,
                               samples=with_nominal.shape[0]).values
        return values[1:].reshape(units.shape[0], -1)

    worst = box_worst(evaluate, box.size, box.mismatch, first_stage_only=first_stage_only)
    return BoxWorst(worst.values.reshape(nt, -1), worst.points.reshape(nt, len(CRITERIA), -1), worst.evaluated), box


def population_units(tolerance: ToleranceModel, samples: int, seed: int) -> np.ndarray:
    """A seeded Latin-hypercube population of the whole model's unit deviations.

    :func:`gearmesh.tolerance.unit_deviations`: the same gears for every design of a study, so a design and its reference
    are compared gear for gear.

    Parameters
    ----------
    tolerance : ToleranceModel
        The tolerance model; one column per dimension.
    samples : int
        Manufactured gears.
    seed : int
        Random seed.

    Returns
    -------
    numpy.ndarray
        (samples, K) unit deviations in [−1, 1].
    """
    return unit_deviations(len(tolerance.dimensions), samples, "lhs", seed)


def manufactured_pair(pair, params: np.ndarray, lead_slope):
    """The pair file of one manufactured gear: any gear of a population, evaluated again through any command.

    The design ``pair`` with the modification and the lead slope deviations it was made with (its profile slopes and mesh
    misalignment kept).

    Parameters
    ----------
    pair : GearPair
        The design (:class:`gearmesh.gear.GearPair`).
    params : numpy.ndarray
        (2, 6) modification parameters (m, :data:`gearmesh.surface.MODIFICATION_FIELDS`).
    lead_slope : array_like
        (2,) lead slope deviations [pinion, gear] (m).

    Returns
    -------
    GearPair
        The manufactured pair.
    """
    from dataclasses import replace

    from .gear import Modification
    from .surface import MODIFICATION_FIELDS

    p = np.asarray(params, dtype=float)
    mods = tuple(Modification(**{f: float(p[g, k]) for k, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
    lead = tuple(float(v) for v in np.asarray(lead_slope, dtype=float))
    return pair.with_changes(modification=mods, deviations=replace(pair.deviations, lead_slope=lead))


def box_scenarios(tolerance: ToleranceModel, reference: BoxWorst) -> np.ndarray:
    """The manufactured gears an optimiser evaluates each candidate on.

    At every lead mismatch where the reference design's worst gears lie (the box search's points of the unmodified pair,
    all criteria and torques), the modification deviations all at their lower and all at their upper tolerance — the
    structure of the box (the mismatch acts most; a relief or crowning slightly thinner or thicker than drawn acts on
    every criterion the same way round). A candidate's worst over these is checked on its own box afterwards
    (:func:`gearmesh.optimise.optimise`).

    Parameters
    ----------
    tolerance : ToleranceModel
        The tolerance model (:mod:`gearmesh.tolerance`).
    reference : BoxWorst
        The reference design's box worst (:func:`design_box_worst`).

    Returns
    -------
    numpy.ndarray
        (S, K) unit deviations of the scenarios.
    """
    points = np.asarray(reference.points)
    mismatch = np.unique(np.round(points[..., 0].ravel(), 9)) if points.shape[-1] else np.zeros(1)
    dims = tolerance.dimensions
    out = []
    for u in mismatch:
        for side in (-1.0, 1.0):
            row = np.array([u if kind == "lead" else side for kind, _, _ in dims])
            if not any(np.array_equal(row, r) for r in out):
                out.append(row)
    return np.array(out).reshape(-1, len(dims))
