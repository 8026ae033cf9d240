"""Runs: pygad's GA and NSGA-II, the random search of the same budget, the history of a run, and
its optimum checked on its own tolerance box (:func:`optimise`).

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..robust import BoxWorst, design_box_worst
from .constraints import _score, _with_reference
from .evaluation import Evaluation, Problem
from .genes import Gene
from .objective import Diagnostics, _evaluate, diagnose, evaluate

#: Progress of a run, one line per generation: the rule's log records it, and the CLI shows it
#: on stderr in a terminal. Named after the package (``gearmesh.optimise``), where it always was.
LOG = logging.getLogger("gearmesh.optimise")

# --------------------------------------------------------------------------------------
# Runs
# --------------------------------------------------------------------------------------


@dataclass
class History:
    """Per generation g = 0..G (0 the initial population): ``genes`` (G+1, P, n) in µm / mm,
    ``objective`` (G+1, P) J, ``force`` (G+1, P) nominal F_s at the design torque, ``scenario``
    (G+1, P) there, ``failed`` (G+1, P), ``lte`` (G+1, P) (NaN unless
    computed), ``pareto`` (G+1, P, M) the NSGA-II objectives (M = 0 for the other methods),
    ``violation`` (G+1, P) the summed relative constraint excess (0: meets every constraint; NaN
    when failed), ``evaluations`` (G+1,) distinct evaluations so far."""

    genes: list = field(default_factory=list)
    objective: list = field(default_factory=list)
    force: list = field(default_factory=list)
    scenario: list = field(default_factory=list)
    failed: list = field(default_factory=list)
    lte: list = field(default_factory=list)
    pareto: list = field(default_factory=list)
    violation: list = field(default_factory=list)
    evaluations: list = field(default_factory=list)

    def arrays(self) -> dict[str, np.ndarray]:
        return {k: np.asarray(v) for k, v in self.__dict__.items()}

    @property
    def best(self) -> np.ndarray:
        """Best objective so far after each generation (padding rows, NaN, left out)."""
        o = np.asarray(self.objective)
        return np.minimum.accumulate(np.min(np.where(np.isnan(o), np.inf, o), axis=1))


class _Evaluator:
    """Batch evaluation with a cache keyed by the gene values: each distinct candidate is
    evaluated once, in the order first met (so a run is reproducible bit for bit)."""

    def __init__(self, prob: Problem):
        self.prob = prob
        self.cache: dict[tuple, tuple] = {}
        self.count = 0

    def __call__(self, values: np.ndarray) -> list[tuple]:
        values = np.atleast_2d(np.asarray(values, dtype=float))
        keys = [tuple(row) for row in values.tolist()]
        new, seen = [], set()
        for k, key in enumerate(keys):
            if key not in self.cache and key not in seen:
                new.append(k)
                seen.add(key)
        if new:
            ev = evaluate(self.prob, self.prob.decode(values[new]))
            d = self.prob.settings.design_index
            for i, k in enumerate(new):
                self.cache[keys[k]] = (float(ev.objective[i]), float(ev.force[i, 0, d]), int(ev.scenario[i, 0, d]),
                                       bool(ev.failed[i]), float(ev.lte_peak_to_peak[i]),
                                       () if ev.pareto is None else tuple(float(v) for v in ev.pareto[i]),
                                       float(ev.violation[i]))
            self.count += len(new)
        return [self.cache[key] for key in keys]

    def record(self, history: History, values: np.ndarray, size: int | None = None) -> None:
        """Evaluate ``values`` and append them to ``history`` as one generation, padded to ``size``
        rows with NaN (scenario −1: not evaluated)."""
        values = np.asarray(values, dtype=float).reshape(-1, len(self.prob.genes))
        rows = self(values) if len(values) else []
        pad = (size or len(values)) - len(values)
        m = len(self.prob.settings.pareto_objectives) if self.prob.settings.method == "nsga2" else 0
        rows += [(math.nan, math.nan, -1, False, math.nan, (math.nan,) * m, math.nan)] * pad
        history.genes.append(np.vstack([values, np.full((pad, values.shape[1]), np.nan)]))
        for name, k in (("objective", 0), ("force", 1), ("scenario", 2), ("failed", 3), ("lte", 4), ("violation", 6)):
            getattr(history, name).append(np.array([r[k] for r in rows]))
        history.pareto.append(np.array([r[5] for r in rows], dtype=float).reshape(len(rows), m))
        history.evaluations.append(self.count)


@dataclass(frozen=True)
class OptimisationResult:
    """A run: its ``history``, the ``optimum`` genes (µm / mm) and parameters (2, 6) m, the
    evaluation of the optimum and of the standard gear, ``evaluations`` (distinct candidates),
    ``wall_s``; ``baseline`` the random search of the same budget (or None); ``pareto``
    (genes (K, n), objectives (K, M) of ``settings.pareto_objectives``) for NSGA-II; ``diagnostics`` the optimum's load
    window, tolerance spread and scenarios (:func:`diagnose`)."""

    problem: Problem
    method: str
    history: History
    optimum_genes: np.ndarray
    optimum: np.ndarray
    optimum_evaluation: Evaluation
    evaluations: int
    wall_s: float
    baseline: "OptimisationResult | None" = None
    pareto: tuple[np.ndarray, np.ndarray] | None = None
    diagnostics: Diagnostics | None = None
    verification: "Verification | None" = None


def _gene_space(genes: tuple[Gene, ...]) -> list[dict[str, float]]:
    return [{"low": g.low, "high": g.high} for g in genes]


def random_search(prob: Problem, evaluations: int | None = None) -> OptimisationResult:
    """Uniform random search over the gene bounds.

    ``evaluations`` candidates from numpy's PCG64 seeded with the settings' seed, in generations + 1 batches of
    ``population`` (when the budget is smaller the last batches are short, padded with NaN in the history: the GA's
    shape).

    Parameters
    ----------
    prob : Problem
        The problem (:func:`problem`).
    evaluations : int or None
        Candidates; default the GA's nominal budget, population × (generations + 1).

    Returns
    -------
    OptimisationResult
        Its ``history``, the ``optimum`` genes (µm / mm) and parameters (2, 6) m, its evaluation, ``evaluations``.
    """
    s = prob.settings
    budget = s.budget if evaluations is None else int(evaluations)
    t0 = time.perf_counter()
    rng = np.random.default_rng(s.seed)
    low = np.array([g.low for g in prob.genes])
    high = np.array([g.high for g in prob.genes])
    draws = low + (high - low) * rng.random((budget, low.size))
    ev, history = _Evaluator(prob), History()
    for g in range(s.generations + 1):
        ev.record(history, draws[g * s.population:(g + 1) * s.population], s.population)
        LOG.info("random search batch %d/%d done", g, s.generations)
    return _finish(prob, "random", history, ev, time.perf_counter() - t0)


def _gaussian_mutation(genes: tuple[Gene, ...], scale: float):
    """pygad user-defined mutation (``mutation_type`` callable(offspring, ga)): each gene of each
    offspring, with the GA's ``mutation_probability``, moves by a normal step of standard
    deviation ``scale`` × its range and is clipped to its bounds — the Gaussian mutation of
    real-coded GAs (Bäck & Schwefel 1993, Evolutionary Computation 1(1); Deb 2001, Multi-Objective
    Optimization using Evolutionary Algorithms, §4.2). pygad's own random mutation redraws a gene
    over its whole gene_space, a global jump that never refines a good candidate. Draws come from
    the GA's seeded generator (reproducible)."""
    low = np.array([g.low for g in genes])
    high = np.array([g.high for g in genes])

    def mutation(offspring, ga):
        rng = ga.numpy_random_generator
        mask = rng.random(offspring.shape) < ga.mutation_probability
        step = rng.normal(0.0, scale, offspring.shape) * (high - low)
        return np.clip(offspring + mask * step, low, high)

    return mutation


def _run_pygad(prob: Problem) -> OptimisationResult:
    import pygad

    s = prob.settings
    ev, history = _Evaluator(prob), History()
    nsga2 = s.method == "nsga2"

    def fitness_func(ga, solutions, indices):  # noqa: ARG001 (pygad's three-argument form)
        rows = ev(solutions)
        if nsga2:
            return [[-v for v in r[5]] for r in rows]
        return [-r[0] for r in rows]

    def on_generation(ga):
        if not history.genes:  # generation 0: the initial population and its fitness
            ev.record(history, ga.initial_population)
        ev.record(history, ga.population)
        LOG.info("%s generation %d/%d done, %d evaluations", s.method, ga.generations_completed, s.generations,
                 ev.count)

    t0 = time.perf_counter()
    ga = pygad.GA(num_generations=s.generations, num_parents_mating=max(2, s.population // 2),
                  sol_per_pop=s.population, num_genes=len(prob.genes), gene_space=_gene_space(prob.genes),
                  gene_type=float, fitness_func=fitness_func, fitness_batch_size=s.population,
                  parent_selection_type="nsga2" if nsga2 else "tournament", K_tournament=3,
                  crossover_type="scattered", mutation_type=_gaussian_mutation(prob.genes, s.mutation_scale),
                  mutation_probability=s.mutation_probability, keep_elitism=s.keep_elitism, random_seed=s.seed,
                  on_generation=on_generation, suppress_warnings=True, save_solutions=False)
    ga.run()
    return _finish(prob, s.method, history, ev, time.perf_counter() - t0)


def pareto_mask(objectives: np.ndarray) -> np.ndarray:
    """Non-dominated rows of ``objectives``, all minimised.

    A point is dominated when another is no worse in every objective and better in one. Duplicates of a non-dominated
    point are all kept.

    Parameters
    ----------
    objectives : numpy.ndarray
        (K, M) objective values of K points.

    Returns
    -------
    numpy.ndarray
        (K,) bool, True where the row is non-dominated.

    References
    ----------
    .. [1] Deb K., Pratap A., Agarwal S., Meyarivan T., "A fast and elitist multiobjective genetic algorithm: NSGA-II",
       IEEE Transactions on Evolutionary Computation 6(2) (2002) 182–197.
    """
    o = np.asarray(objectives, dtype=float)
    no_worse = np.all(o[:, None, :] <= o[None, :, :], axis=-1)  # [j, i]: j no worse than i
    better = np.any(o[:, None, :] < o[None, :, :], axis=-1)
    return ~np.any(no_worse & better, axis=0)


def _finish(prob: Problem, method: str, history: History, ev: _Evaluator, wall: float) -> OptimisationResult:
    h = history.arrays()
    genes = h["genes"].reshape(-1, len(prob.genes))
    obj, failed = h["objective"].reshape(-1), h["failed"].reshape(-1)
    pareto = None
    if method == "nsga2":
        _, first = np.unique(genes, axis=0, return_index=True)
        order = np.sort(first)
        ok = order[~failed[order]]
        pts = h["pareto"].reshape(-1, h["pareto"].shape[-1])
        keep = ok[pareto_mask(pts[ok])]
        keep = keep[np.argsort(obj[keep], kind="stable")]
        pareto = (genes[keep], pts[keep])
        best = int(keep[0])  # the front's member of least J (penalties included: a feasible one when any is)
    else:
        best = int(np.nanargmin(obj))  # first occurrence
    verification = None
    if prob.reference is not None:  # the run's best on the population it saw, checked on its own tolerance box
        ranked = _ranked(genes, obj, failed, None if pareto is None else keep)
        best, verification = _verified(prob, genes, ranked)
    optimum_genes = genes[best]
    optimum = prob.decode(optimum_genes)[0]
    return OptimisationResult(prob, method, history, optimum_genes, optimum, evaluate(prob, optimum[None]),
                              ev.count, wall, None, pareto, diagnose(prob, optimum), verification)


#: Candidates checked on their own tolerance box after a run, the best first, until one meets every
#: constraint there (:func:`_verified`).
VERIFY_LIMIT = 3


@dataclass(frozen=True)
class Verification:
    """The optimum checked on its own tolerance box: ``worst`` its worst manufactured gear
    (:func:`gearmesh.robust.design_box_worst`, columns :data:`gearmesh.robust.CRITERIA` per objective
    torque), ``violation`` its constraints' summed relative excess there (0: every one met), ``rank``
    its place among the run's candidates (0: the run's best), ``tried`` how many were checked and
    ``searched`` whether its box was searched in full (else its first stage alone: the corners of
    the modification deviations at five lead mismatches, a lower bound of the worst and of the
    violation, enough to refuse it)."""

    worst: BoxWorst
    violation: float
    rank: int
    tried: int
    searched: bool


def _ranked(genes: np.ndarray, objective: np.ndarray, failed: np.ndarray, front: np.ndarray | None) -> np.ndarray:
    """Distinct candidates (indices into the history), best first: the Pareto front by J, then the
    others by J (without a front: all by J); failed ones left out."""
    _, first = np.unique(genes, axis=0, return_index=True)
    first = np.sort(first)
    first = first[~failed[first]]
    by_j = first[np.argsort(objective[first], kind="stable")]
    if front is None:
        return by_j
    return np.concatenate([front, by_j[~np.isin(by_j, front)]])


def _verified(prob: Problem, genes: np.ndarray, ranked: np.ndarray) -> tuple[int, Verification]:
    """The first of ``ranked`` (at most :data:`VERIFY_LIMIT`) whose worst gear over its own tolerance
    box meets every constraint against the standard's box worst; else the one of least violation
    there. The box is searched as the sign-off table searches it; a candidate whose gears of the
    search's first stage already violate a constraint is refused on them (a lower bound of its
    box's) and is not searched further: when every one is refused, the compromise taken keeps its
    first stage's worst (the sign-off's impact stage searches its box in full)."""
    s = prob.settings

    def check(params: np.ndarray, quick: bool) -> tuple[float, BoxWorst]:
        worst = design_box_worst(prob.model, prob.tolerance, params, s.objective_torques, s.speed_rpm,
                                 s.energy_velocity, first_stage_only=quick)[0]
        raw = _with_reference(_evaluate(prob, params[None], None), worst)
        return float(_score(prob, raw, prob.standard).violation[0]), worst

    checked = []
    for rank, k in enumerate(ranked[:VERIFY_LIMIT]):
        params = prob.decode(genes[k])[0]
        violation, worst = check(params, quick=True)
        full = violation == 0.0
        if full:
            violation, worst = check(params, quick=False)
        checked.append((violation, rank, int(k), worst, full))
        LOG.info("optimum check %d: the worst manufactured gear over its tolerance box violates the constraints by "
                 "%s%.4g", rank + 1, "" if full else "at least ", violation)
        if full and violation == 0.0:
            break
    violation, rank, k, worst, full = min(checked, key=lambda c: (np.nan_to_num(c[0], nan=np.inf), c[1]))
    return k, Verification(worst, violation, rank, len(checked), full)


def optimise(prob: Problem) -> OptimisationResult:
    """Run the configured method.

    For 'ga' and 'nsga2' with ``random_baseline`` also the random search of the same budget, as ``baseline``.

    Parameters
    ----------
    prob : Problem
        The problem (:func:`problem`); ``prob.settings.method`` 'ga', 'nsga2' or 'random'.

    Returns
    -------
    OptimisationResult
        The run: ``history``, the ``optimum`` genes (µm / mm) and parameters (2, 6) m, ``evaluations``, ``wall_s``,
        ``baseline``, ``pareto`` (NSGA-II) and the optimum's ``diagnostics``.
    """
    s = prob.settings
    if s.method == "random":
        return random_search(prob)
    result = _run_pygad(prob)
    if s.random_baseline:
        result = replace(result, baseline=random_search(prob, result.evaluations))
    return result
