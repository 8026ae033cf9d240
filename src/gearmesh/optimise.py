"""Micro-geometry optimisation against the mesh-in impact force (seed 000), with pygad.

Genes
-----
Seed 000's six modification parameters y1..y6 (root and tip relief amounts, their lengths,
lead crowning, unmodified lead length; :data:`gearmesh.surface.MODIFICATION_FIELDS`) of
the gear(s) being modified, in engineering units (µm for amounts, mm for lengths: the
pair-file keys). Seed 000's bounds, in terms of the normal module m_n and the face width B:

    0.001 m_n ≤ y1, y2, y5 ≤ 0.015 m_n,   0.1 m_n ≤ y3, y4 ≤ 0.8 m_n,   0 < y6 ≤ 0.5 B,

each overridable; any gene can be fixed instead. Every decoded candidate is a valid
modification by construction (:func:`decode`): relief lengths whose sum exceeds the active
roll length of the flank are scaled down to fit it, an amount without a length (or the
reverse) is no relief, and the unmodified lead length stays inside the face — so
:func:`gearmesh.gear.validate_modifications` accepts every candidate and a run never
stops on one.

Objective
---------
``force``: seed 000's F_s^max (:func:`gearmesh.impact.impact_response`, closed form) at the
design torque and speed; ``velocity``: the impact velocity |v_n| there (seed 000's
alternative); ``robust``: the maximum, or a weighted mean, of F_s over a list of torques
(seed 000, Discussion 4: the duty cycle). A candidate whose entering pair never touches in
the search window (scenario 'none') or whose force is not finite is *failed*: its objective
is :data:`FAILURE_FACTOR` times the standard gear's, and failures are counted. So is a
candidate whose touch has no closing velocity (a crossing the impact model did not resolve:
its zero force would be an artefact the GA would exploit).

Constraints (optional) are an exterior static penalty (Homaifar, Qi & Lai 1994, Simulation
62(4); Coello Coello 2002, Comput. Methods Appl. Mech. Engrg. 191, §3.1): with m_k the
peak-to-peak LTE or the largest line load at the design torque
(:func:`gearmesh.impact.ltca_metrics`) and m_k,std the standard gear's,

    J = f + penalty · f_std · Σ_k max(0, m_k / (factor_k · m_k,std) − 1),

so a candidate that spoils the LTE or the line load by more than ``factor_k`` pays in
proportion to the excess, in units of the standard gear's objective f_std.

Methods
-------
``ga``: pygad's GA as its authors intend — three-argument fitness returning −J (pygad
maximises), one batch per generation (``fitness_batch_size`` = population), per-gene
``gene_space`` {low, high}, ``random_seed``, ``on_generation`` recording the history.
Mutation is Gaussian (:func:`_gaussian_mutation`, a pygad user-defined mutation), crossover
scattered (uniform), parents by 3-tournament, the best ``keep_elitism`` kept.
``nsga2``: pygad's NSGA-II on (F_s, LTE p-p) at the design torque, with the Pareto front of
every evaluated candidate. ``random``: uniform random search with the GA's nominal budget
(population × (generations + 1) evaluations, the same seed handling); as the baseline of a GA
run it gets exactly the GA's number of distinct evaluations. Candidates already
evaluated are not evaluated again (a cache keyed by the genes), so ``evaluations`` counts
distinct candidates. Same settings and seed → bit-identical history and optimum.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from .errors import GearmeshInputError
from .gear import GEARS, MAX_MODIFICATION_TO_MODULE, PairGeometry
from .impact import SCENARIO_NONE, ImpactModel, impact_response, impact_static, ltca_metrics
from .surface import MODIFICATION_FIELDS

#: Progress of a run, one line per generation: the rule's log records it, and the CLI shows it
#: on stderr in a terminal.
LOG = logging.getLogger(__name__)

__all__ = [
    "GENE_KEYS", "GENE_SYMBOLS", "GENE_UNITS", "METHODS", "OBJECTIVES", "FAILURE_FACTOR", "Gene",
    "OptimiseSettings", "check_settings", "check_positive", "seed000_bounds", "gene_table", "decode", "Problem", "problem",
    "Evaluation", "evaluate", "History", "OptimisationResult", "optimise", "random_search", "pareto_mask",
]

#: Pair-file keys of y1..y6, in the order of :data:`gearmesh.surface.MODIFICATION_FIELDS`.
GENE_KEYS = ("root_relief_um", "tip_relief_um", "root_relief_length_mm", "tip_relief_length_mm", "crowning_um",
             "unmodified_lead_length_mm")
GENE_SYMBOLS = ("y1", "y2", "y3", "y4", "y5", "y6")
GENE_UNITS = ("um", "um", "mm", "mm", "um", "mm")
_TO_SI = np.array([1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-3])
_AMOUNT, _LENGTH = (0, 1, 4), (2, 3)
METHODS = ("ga", "random", "nsga2")
OBJECTIVES = ("force", "velocity", "robust")
STATISTICS = ("max", "mean")
#: A failed candidate's objective, in units of the standard gear's.
FAILURE_FACTOR = 10.0


# --------------------------------------------------------------------------------------
# Settings
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class OptimiseSettings:
    """Checked optimiser settings (torques are pinion torques, N m; speed rpm)."""

    method: str = "ga"
    objective: str = "force"
    population: int = 40
    generations: int = 30
    seed: int = 0
    torque: float = 1000.0
    torques: tuple[float, ...] = (400.0, 1000.0, 1600.0)
    weights: tuple[float, ...] | None = None
    statistic: str = "max"
    speed_rpm: float = 5000.0
    lte_factor: float | None = None
    line_load_factor: float | None = None
    penalty: float = 10.0
    mutation_probability: float = 0.3
    mutation_scale: float = 0.1
    keep_elitism: int = 2
    random_baseline: bool = True
    energy_velocity: str = "transverse"

    @property
    def budget(self) -> int:
        """The nominal number of evaluations: population × (generations + 1)."""
        return self.population * (self.generations + 1)

    @property
    def constrained(self) -> bool:
        return self.lte_factor is not None or self.line_load_factor is not None

    @property
    def objective_torques(self) -> tuple[float, ...]:
        """The torques the objective is evaluated at (the design torque first)."""
        return self.torques if self.objective == "robust" else (self.torque,)


def _integer(field_name: str, value: Any, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
        raise GearmeshInputError(field_name, value, f"must be an integer in [{low}, {high}]")
    return int(value)


def check_positive(field_name: str, value: Any, allow_none: bool = False, at_least: float = 0.0) -> float | None:
    """``value`` as a float above ``at_least`` (or None when allowed); GearmeshInputError otherwise."""
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or not value > at_least:
        raise GearmeshInputError(field_name, value, f"must be a finite number above {at_least:g}")
    return float(value)


def _choice(field_name: str, value: Any, allowed) -> str:
    if value not in allowed:
        raise GearmeshInputError(field_name, value, f"must be one of {list(allowed)}")
    return value


def check_settings(method: str = "ga", objective: str = "force", population: int = 40, generations: int = 30,
                   seed: int = 0, torque: float = 1000.0, torques=(400.0, 1000.0, 1600.0), weights=None,
                   statistic: str = "max", speed_rpm: float = 5000.0, lte_factor=None, line_load_factor=None,
                   penalty: float = 10.0, mutation_probability: float = 0.3, mutation_scale: float = 0.1,
                   keep_elitism: int = 2, random_baseline: bool = True,
                   energy_velocity: str = "transverse") -> OptimiseSettings:
    """:class:`OptimiseSettings` from raw values, refusing bad ones (GearmeshInputError naming
    the field). Torques here are pinion torques (N m)."""
    from .ltca import check_torques

    method = _choice("method", method, METHODS)
    objective = _choice("objective", objective, OBJECTIVES)
    population = _integer("population", population, 4, 100_000)
    generations = _integer("generations", generations, 1, 100_000)
    seed = _integer("seed", seed, 0, 2**32 - 1)
    torque = check_positive("torque_Nm", torque)
    torques = tuple(float(t) for t in check_torques(torques, "torques_Nm"))
    statistic = _choice("statistic", statistic, STATISTICS)
    if weights is not None:
        if not isinstance(weights, (list, tuple)) or len(weights) != len(torques):
            raise GearmeshInputError("weights", weights, f"must be a list of {len(torques)} numbers, one per torque")
        for k, w in enumerate(weights):
            if isinstance(w, bool) or not isinstance(w, (int, float)) or not math.isfinite(w) or w < 0:
                raise GearmeshInputError(f"weights[{k}]", w, "must be a finite number >= 0")
        if sum(weights) <= 0:
            raise GearmeshInputError("weights", weights, "must not all be zero")
        weights = tuple(float(w) for w in weights)
        if statistic != "mean":
            raise GearmeshInputError("weights", weights, "apply to statistic 'mean' only")
    if method == "nsga2" and objective != "force":
        raise GearmeshInputError("objective", objective, "must be 'force' with method nsga2 (F_s against LTE p-p)")
    speed_rpm = check_positive("speed_rpm", speed_rpm)
    if speed_rpm > 1e6:
        raise GearmeshInputError("speed_rpm", speed_rpm, "must lie in (0, 1e6] rpm")
    lte_factor = check_positive("constraints.lte_factor", lte_factor, allow_none=True)
    line_load_factor = check_positive("constraints.line_load_factor", line_load_factor, allow_none=True)
    penalty = check_positive("constraints.penalty", penalty)
    if isinstance(mutation_probability, bool) or not isinstance(mutation_probability, (int, float)) \
            or not 0 < mutation_probability <= 1:
        raise GearmeshInputError("mutation_probability", mutation_probability, "must lie in (0, 1]")
    if isinstance(mutation_scale, bool) or not isinstance(mutation_scale, (int, float)) or not 0 < mutation_scale <= 1:
        raise GearmeshInputError("mutation_scale", mutation_scale, "must lie in (0, 1] (of each gene's range)")
    keep_elitism = _integer("keep_elitism", keep_elitism, 0, population - 1)
    energy_velocity = _choice("energy_velocity", energy_velocity, ("transverse", "normal"))
    if not isinstance(random_baseline, bool):
        raise GearmeshInputError("random_baseline", random_baseline, "must be true or false")
    return OptimiseSettings(method, objective, population, generations, seed, torque, torques, weights, statistic,
                            speed_rpm, lte_factor, line_load_factor, penalty, float(mutation_probability),
                            float(mutation_scale), keep_elitism, random_baseline, energy_velocity)


# --------------------------------------------------------------------------------------
# Genes
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Gene:
    """One free gene: parameter ``field`` (index into y1..y6) of gear ``gear`` (0 pinion, 1 gear),
    bounds ``low``..``high`` in its engineering unit (µm or mm)."""

    gear: int
    field: int
    low: float
    high: float

    @property
    def name(self) -> str:
        return f"{GEARS[self.gear]}.{GENE_KEYS[self.field]}"

    @property
    def symbol(self) -> str:
        return f"{GENE_SYMBOLS[self.field]} ({GEARS[self.gear]})"

    @property
    def unit(self) -> str:
        return GENE_UNITS[self.field]


def seed000_bounds(geom: PairGeometry) -> np.ndarray:
    """Seed 000's bounds (6, 2) of y1..y6 in µm / mm: y1, y2, y5 in [0.001, 0.015]·m_n, y3, y4 in
    [0.1, 0.8]·m_n, y6 in (0, 0.5·B] (B the meshing face width)."""
    mn, b = geom.pair.normal_module, geom.face_width
    si = np.array([[0.001 * mn, 0.015 * mn]] * 2 + [[0.1 * mn, 0.8 * mn]] * 2 + [[0.001 * mn, 0.015 * mn],
                                                                                  [0.0, 0.5 * b]])
    return si / _TO_SI[:, None]


def _limits(geom: PairGeometry, gear: int) -> np.ndarray:
    """Largest value (µm / mm) of each parameter that :func:`gearmesh.gear.validate_modifications`
    accepts on its own."""
    depth = MAX_MODIFICATION_TO_MODULE * geom.pair.normal_module
    active = float(geom.rho_eap[gear] - geom.rho_sap[gear])
    return np.array([depth, depth, active, active, depth, geom.face_width]) / _TO_SI


def gene_table(geom: PairGeometry, modify=("pinion",), bounds: Mapping[str, Any] | None = None,
               fixed: Mapping[str, Any] | None = None) -> tuple[tuple[Gene, ...], np.ndarray]:
    """The free genes and the base parameters (2, 6) (m): the pair's own modification, with the
    modified gears' parameters set to their ``fixed`` values (0 until a gene sets them).

    ``modify`` the gears whose six parameters are optimised ('pinion', 'gear' or both);
    ``bounds`` {pair-file key: [low, high]} overrides seed 000's bounds (µm / mm, on every
    modified gear); ``fixed`` {key: value} fixes a parameter instead of optimising it.
    """
    from .surface import modification_parameters

    if isinstance(modify, str):
        modify = [modify]
    if not isinstance(modify, (list, tuple)) or not modify or len(set(modify)) != len(modify):
        raise GearmeshInputError("modify", modify, "must name 'pinion', 'gear' or both, once each")
    for g in modify:
        _choice("modify", g, GEARS)
    bounds, fixed = dict(bounds or {}), dict(fixed or {})
    for section, spec in (("bounds", bounds), ("fixed", fixed)):
        for key in spec:
            if key not in GENE_KEYS:
                raise GearmeshInputError(f"{section}.{key}", spec[key], f"is not a gene; the genes are {list(GENE_KEYS)}")
    both = set(bounds) & set(fixed)
    if both:
        key = sorted(both)[0]
        raise GearmeshInputError(f"fixed.{key}", fixed[key], "is also given bounds: a gene is either free or fixed")
    table = seed000_bounds(geom)
    base = modification_parameters(geom).copy()
    genes = []
    for gear in sorted(GEARS.index(g) for g in modify):
        limits = _limits(geom, gear)
        base[gear] = 0.0
        for f, key in enumerate(GENE_KEYS):
            if key in fixed:
                v = fixed[key]
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                        or not 0 <= v <= limits[f]:
                    raise GearmeshInputError(f"fixed.{key}", v, f"must lie in [0, {limits[f]:.6g}] {GENE_UNITS[f]}")
                base[gear, f] = v * _TO_SI[f]
                continue
            low, high = table[f]
            if key in bounds:
                pair_ = bounds[key]
                if not isinstance(pair_, (list, tuple)) or len(pair_) != 2 or any(
                        isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in pair_):
                    raise GearmeshInputError(f"bounds.{key}", pair_, f"must be [low, high] in {GENE_UNITS[f]}")
                low, high = (float(v) for v in pair_)
                if not 0 <= low < high <= limits[f]:
                    raise GearmeshInputError(f"bounds.{key}", pair_, f"must satisfy 0 <= low < high <= "
                                             f"{limits[f]:.6g} {GENE_UNITS[f]} (the {GEARS[gear]}'s flank)")
            genes.append(Gene(gear, f, float(low), float(high)))
    if not genes:
        raise GearmeshInputError("fixed", fixed, "leaves no gene to optimise")
    return tuple(genes), base


def decode(geom: PairGeometry, genes: tuple[Gene, ...], base: np.ndarray, values) -> np.ndarray:
    """Modification parameters (C, 2, 6) in m of gene values (C, G) (µm / mm), repaired so that
    every candidate is a valid modification (module docstring): relief lengths scaled to fit
    the active roll length, amount and length zero together, y6 below the face width."""
    values = np.atleast_2d(np.asarray(values, dtype=float))
    p = np.broadcast_to(base, (values.shape[0], 2, 6)).copy()
    for k, gene in enumerate(genes):
        p[:, gene.gear, gene.field] = values[:, k] * _TO_SI[gene.field]
    for gear in range(2):
        active = float(geom.rho_eap[gear] - geom.rho_sap[gear]) * (1 - 1e-9)
        total = p[:, gear, 2] + p[:, gear, 3]
        scale = np.where(total > active, active / np.where(total > 0, total, 1.0), 1.0)
        p[:, gear, 2:4] *= scale[:, None]
        for amount, length in ((0, 2), (1, 3)):
            none = (p[:, gear, amount] <= 0) | (p[:, gear, length] <= 0)
            p[none, gear, amount] = 0.0
            p[none, gear, length] = 0.0
        p[:, gear, 5] = np.minimum(p[:, gear, 5], geom.face_width * (1 - 1e-6))
    return p


# --------------------------------------------------------------------------------------
# The objective, for a whole population at once
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Evaluation:
    """Objective and diagnostics of C candidates (SI): ``objective`` J (C,) (N, or m/s for
    'velocity', penalties included), ``force`` F_s (C, T) at the objective torques,
    ``velocity`` |v_n| (C, T), ``scenario`` (C, T), ``failed`` (C,), ``lte_peak_to_peak`` (C,) m
    and ``max_line_load`` (C,) N/m at the design torque (NaN when not needed), ``violation``
    (C,) the summed relative constraint excess."""

    objective: np.ndarray
    force: np.ndarray
    velocity: np.ndarray
    scenario: np.ndarray
    failed: np.ndarray
    lte_peak_to_peak: np.ndarray
    max_line_load: np.ndarray
    violation: np.ndarray


def _raw(model: ImpactModel, s: OptimiseSettings, params: np.ndarray, metrics: bool):
    """F_s, |v_n|, scenario (C, T) at the objective torques; LTE p-p and line load (C,)."""
    static = impact_static(model, list(s.objective_torques), params)
    static, resp = impact_response(model, static, [s.speed_rpm], energy_velocity=s.energy_velocity)
    force, vel = resp.force[..., 0], resp.velocity_normal[..., 0]
    nc = params.shape[0]
    if metrics:
        lte, line = (v[:, 0] for v in ltca_metrics(model, [s.torque], params))
    else:
        lte = line = np.full(nc, np.nan)
    return force, vel, static.scenario, lte, line


def _reduce(s: OptimiseSettings, force: np.ndarray, vel: np.ndarray) -> np.ndarray:
    """The unpenalised objective f (C,) from F_s and |v_n| (C, T)."""
    if s.objective == "velocity":
        return vel[:, 0]
    if s.objective == "force" or s.statistic == "max":
        return force.max(axis=1)
    w = np.ones(force.shape[1]) if s.weights is None else np.asarray(s.weights)
    return force @ (w / w.sum())


@dataclass(frozen=True)
class Problem:
    """Everything an evaluation needs: the impact model, the genes, the base parameters, the
    settings and the standard (unmodified) gear's objective and metrics."""

    model: ImpactModel
    genes: tuple[Gene, ...]
    base: np.ndarray
    settings: OptimiseSettings
    standard: Evaluation

    @property
    def geom(self) -> PairGeometry:
        return self.model.geom

    def decode(self, values) -> np.ndarray:
        return decode(self.geom, self.genes, self.base, values)


def problem(model: ImpactModel, settings: OptimiseSettings, modify=("pinion",), bounds=None,
            fixed=None) -> Problem:
    """Set up the optimisation of ``model``'s pair (its standard gear evaluated once)."""
    genes, base = gene_table(model.geom, modify, bounds, fixed)
    zero = np.zeros((1, 2, 6))
    metrics = settings.constrained or settings.method == "nsga2"
    force, vel, scen, lte, line = _raw(model, settings, zero, metrics)
    f = _reduce(settings, force, vel)
    if not np.all(np.isfinite(f)) or np.any(scen == SCENARIO_NONE):
        raise GearmeshInputError("torques_Nm" if settings.objective == "robust" else "torque_Nm",
                                 list(settings.objective_torques),
                                 "gives the standard (unmodified) gear no mesh-in impact: nothing to reduce")
    standard = Evaluation(f, force, vel, scen, np.zeros(1, bool), lte, line, np.zeros(1))
    return Problem(model, genes, base, settings, standard)


def evaluate(prob: Problem, params: np.ndarray) -> Evaluation:
    """The objective of candidates ``params`` (C, 2, 6) m in one batch (module docstring)."""
    s, std = prob.settings, prob.standard
    metrics = s.constrained or s.method == "nsga2"
    force, vel, scen, lte, line = _raw(prob.model, s, params, metrics)
    f = _reduce(s, force, vel)
    # failed: no impact found, a non-finite force, or a touch without a closing velocity (a
    # crossing the impact model did not resolve: zero force would be an artefact, not an optimum)
    failed = (~np.isfinite(f) | np.any(scen == SCENARIO_NONE, axis=1) | ~np.all(np.isfinite(force), axis=1)
              | np.any(~(vel > 0), axis=1))
    violation = np.zeros(params.shape[0])
    for factor, value, ref in ((s.lte_factor, lte, std.lte_peak_to_peak), (s.line_load_factor, line, std.max_line_load)):
        if factor is not None:
            with np.errstate(invalid="ignore"):
                violation += np.maximum(0.0, value / (factor * ref[0]) - 1.0)
    failed |= ~np.isfinite(violation)
    j = f + s.penalty * std.objective[0] * violation
    j = np.where(failed, FAILURE_FACTOR * std.objective[0], j)
    if s.method == "nsga2":
        lte = np.where(failed, FAILURE_FACTOR * std.lte_peak_to_peak[0], lte)
    return Evaluation(j, force, vel, scen, failed, lte, line, np.where(failed, np.nan, violation))


# --------------------------------------------------------------------------------------
# Runs
# --------------------------------------------------------------------------------------


@dataclass
class History:
    """Per generation g = 0..G (0 the initial population): ``genes`` (G+1, P, n) in µm / mm,
    ``objective`` (G+1, P) J, ``force`` (G+1, P) F_s at the design torque (the first objective
    torque), ``scenario`` (G+1, P) there, ``failed`` (G+1, P), ``lte`` (G+1, P) (NaN unless
    computed), ``evaluations`` (G+1,) distinct evaluations so far."""

    genes: list = field(default_factory=list)
    objective: list = field(default_factory=list)
    force: list = field(default_factory=list)
    scenario: list = field(default_factory=list)
    failed: list = field(default_factory=list)
    lte: list = field(default_factory=list)
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
            for i, k in enumerate(new):
                self.cache[keys[k]] = (float(ev.objective[i]), float(ev.force[i, 0]), int(ev.scenario[i, 0]),
                                       bool(ev.failed[i]), float(ev.lte_peak_to_peak[i]))
            self.count += len(new)
        return [self.cache[key] for key in keys]

    def record(self, history: History, values: np.ndarray, size: int | None = None) -> None:
        """Evaluate ``values`` and append them to ``history`` as one generation, padded to ``size``
        rows with NaN (scenario −1: not evaluated)."""
        values = np.asarray(values, dtype=float).reshape(-1, len(self.prob.genes))
        rows = self(values) if len(values) else []
        pad = (size or len(values)) - len(values)
        rows += [(math.nan, math.nan, -1, False, math.nan)] * pad
        history.genes.append(np.vstack([values, np.full((pad, values.shape[1]), np.nan)]))
        for name, k in (("objective", 0), ("force", 1), ("scenario", 2), ("failed", 3), ("lte", 4)):
            getattr(history, name).append(np.array([r[k] for r in rows]))
        history.evaluations.append(self.count)


@dataclass(frozen=True)
class OptimisationResult:
    """A run: its ``history``, the ``optimum`` genes (µm / mm) and parameters (2, 6) m, the
    evaluation of the optimum and of the standard gear, ``evaluations`` (distinct candidates),
    ``wall_s``; ``baseline`` the random search of the same budget (or None); ``pareto``
    (genes (K, n), F_s (K,), LTE p-p (K,)) for NSGA-II."""

    problem: Problem
    method: str
    history: History
    optimum_genes: np.ndarray
    optimum: np.ndarray
    optimum_evaluation: Evaluation
    evaluations: int
    wall_s: float
    baseline: "OptimisationResult | None" = None
    pareto: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


def _gene_space(genes: tuple[Gene, ...]) -> list[dict[str, float]]:
    return [{"low": g.low, "high": g.high} for g in genes]


def random_search(prob: Problem, evaluations: int | None = None) -> OptimisationResult:
    """Uniform random search over the gene bounds: ``evaluations`` candidates (default the GA's
    nominal budget, population × (generations + 1)) from numpy's PCG64 seeded with the
    settings' seed, in generations + 1 batches of ``population`` (when the budget is smaller
    the last batches are short, padded with NaN in the history: the GA's shape)."""
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
            return [[-r[0], -r[4]] for r in rows]
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
    """Non-dominated rows of ``objectives`` (K, M), all minimised (Deb et al. 2002, IEEE TEC
    6(2): a point is dominated when another is no worse in every objective and better in
    one). Duplicates of a non-dominated point are all kept."""
    o = np.asarray(objectives, dtype=float)
    no_worse = np.all(o[:, None, :] <= o[None, :, :], axis=-1)  # [j, i]: j no worse than i
    better = np.any(o[:, None, :] < o[None, :, :], axis=-1)
    return ~np.any(no_worse & better, axis=0)


def _finish(prob: Problem, method: str, history: History, ev: _Evaluator, wall: float) -> OptimisationResult:
    h = history.arrays()
    genes = h["genes"].reshape(-1, len(prob.genes))
    obj, force, failed = h["objective"].reshape(-1), h["force"].reshape(-1), h["failed"].reshape(-1)
    pareto = None
    if method == "nsga2":
        _, first = np.unique(genes, axis=0, return_index=True)
        order = np.sort(first)
        ok = order[~failed[order]]
        pts = np.column_stack([obj[ok], h["lte"].reshape(-1)[ok]])
        keep = ok[pareto_mask(pts)]
        keep = keep[np.argsort(obj[keep], kind="stable")]
        pareto = (genes[keep], obj[keep], h["lte"].reshape(-1)[keep])
        best = int(keep[0])  # the front's member of least F_s
    else:
        best = int(np.nanargmin(obj))  # first occurrence
    optimum_genes = genes[best]
    optimum = prob.decode(optimum_genes)[0]
    return OptimisationResult(prob, method, history, optimum_genes, optimum, evaluate(prob, optimum[None]),
                              ev.count, wall, None, pareto)


def optimise(prob: Problem) -> OptimisationResult:
    """Run the configured method (and, for 'ga' and 'nsga2' with ``random_baseline``, the random
    search of the same budget as ``baseline``)."""
    s = prob.settings
    if s.method == "random":
        return random_search(prob)
    result = _run_pygad(prob)
    if s.random_baseline:
        from dataclasses import replace

        result = replace(result, baseline=random_search(prob, result.evaluations))
    return result
