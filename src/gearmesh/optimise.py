"""Micro-geometry optimisation against the mesh-in impact (the mesh-in impact paper) over a load spectrum and the
manufacturing tolerances, with pygad.

Genes
-----
The mesh-in impact paper's six modification parameters y1..y6 (root and tip relief amounts, their lengths,
lead crowning, unmodified lead length; :data:`gearmesh.surface.MODIFICATION_FIELDS`) of
the gear(s) being modified, in engineering units (µm for amounts, mm for lengths: the
pair-file keys). The mesh-in impact paper's bounds, in terms of the normal module m_n and the face width B:

    0.001 m_n ≤ y1, y2, y5 ≤ 0.015 m_n,   0.1 m_n ≤ y3, y4 ≤ 0.8 m_n,   0 < y6 ≤ 0.5 B,

each overridable; any gene can be fixed instead. Every decoded candidate is a valid
modification by construction (:func:`gearmesh.surface.fit_modifications`): relief lengths whose
sum exceeds the active roll length of the flank are scaled down to fit it, an amount without a
length (or the reverse) is no relief, and the unmodified lead length stays inside the face — so
:func:`gearmesh.gear.validate_modifications` accepts every candidate and a run never
stops on one.

Objective
---------
A quantity per (torque, manufactured sample) — ``force``: the mesh-in impact paper's F_s^max
(:func:`gearmesh.impact.impact_response`, closed form) at the pinion speed ``speed_rpm``;
``velocity``: the impact velocity |v_n| (the mesh-in impact paper's alternative); ``robust``: F_s like
``force``, the name for its load-spectrum and tolerance form (refused without either);
``dynamic``: the peak dynamic mesh force (not available yet: one function, added to
:data:`OBJECTIVE_VALUES`) — reduced in two steps:

1. over the **load spectrum** ``torques`` (pinion torques; default the design torque alone):
   the worst case (``statistic: max``) or the duty-cycle mean (``mean`` with ``weights`` the
   time shares) — one number per manufactured gear;
2. over the **manufactured population** (:mod:`gearmesh.tolerance`: the nominal and the
   tolerance samples, drawn once per run): ``tolerance_statistic`` max, mean, percentile or
   CVaR at ``tolerance_level`` %; None evaluates the nominal alone.

Every gear of the population is scored over the whole spectrum first, because a gear is made
once and then runs the whole duty cycle. The mesh-in impact paper asks for the modification that minimises the
impact "across a specified operational load range" and warns that a single-load optimum
degrades off-design; a single-torque nominal objective finds grazing touches (zero closing
velocity at exactly one load) that are worse elsewhere. A candidate whose entering pair never
touches in the search window (scenario 'none') or whose value is not finite, at any torque
and sample evaluated, is *failed*: its objective is :data:`FAILURE_FACTOR` times the standard
gear's, and failures are counted. So is a candidate whose touch has no closing velocity (a
crossing the impact model did not resolve: its zero force would be an artefact the GA would
exploit).

Constraints (optional) are an exterior static penalty (Homaifar, Qi & Lai 1994, Simulation
62(4); Coello Coello 2002, Comput. Methods Appl. Mech. Engrg. 191, §3.1): with m_k a criterion
of the loaded contact (:func:`gearmesh.impact.ltca_criteria`: LTE, line load, TE orders,
pressure, root stress; by default the tolerance statistic over the manufactured gears,
``criteria_over_samples``) or of the impact and the dynamics, and m_k,std the standard gear's,

    J = f + penalty · f_std · Σ_k max(0, m_k / (factor_k · m_k,std) − 1),

so a candidate that spoils a criterion by more than ``factor_k`` pays in
proportion to the excess, in units of the standard gear's objective f_std.

Diagnostics of every optimum (:func:`diagnose`): its **load window** — the contiguous range of
torques around the design torque over which its F_s beats the standard gear's, on a grid of
``load_window_step`` finer than the spectrum (:func:`load_grid`) — its F_s under every
tolerance sample at each spectrum torque (the **spread**), and the scenario at each torque.

Methods
-------
``ga``: pygad's GA as its authors intend — three-argument fitness returning −J (pygad
maximises), one batch per generation (``fitness_batch_size`` = population; the batch is every
candidate × torque × sample in one impact evaluation), per-gene ``gene_space`` {low, high},
``random_seed``, ``on_generation`` recording the history.
Mutation is Gaussian (:func:`_gaussian_mutation`, a pygad user-defined mutation), crossover
scattered (uniform), parents by 3-tournament, the best ``keep_elitism`` kept.
``nsga2``: pygad's NSGA-II on (F_s, LTE p-p) at the design torque, with the Pareto front of
every evaluated candidate. ``random``: uniform random search with the GA's nominal budget
(population × (generations + 1) evaluations, the same seed handling); as the baseline of a GA
run (``random_baseline``) it gets exactly the GA's number of distinct evaluations. Candidates already
evaluated are not evaluated again (a cache keyed by the genes), so ``evaluations`` counts
distinct candidates. Same settings and seed → bit-identical history and optimum.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Mapping

import numpy as np

from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
from .limits import MAX_MODIFICATION_TO_MODULE, same_point
from .dynamics.population import PopulationDynamics, dynamic_factors, population_dynamics
from .impact import (SCENARIO_NONE, ImpactModel, LTCACriteria, impact_response, impact_static, load_grid, load_window,
                     ltca_criteria)
from .ltca import MESH_ORDERS
from .stress import edge_pressure_reference
from .surface import fit_modifications
from .robust import CRITERIA, BoxWorst, box_scenarios, design_box_worst
from .tolerance import (SAMPLINGS, ToleranceModel, check_statistic, manufactured_population, sample_statistic,
                        unit_deviations)

#: Progress of a run, one line per generation: the rule's log records it, and the CLI shows it
#: on stderr in a terminal.
LOG = logging.getLogger(__name__)

__all__ = [
    "GENE_KEYS", "GENE_SYMBOLS", "GENE_UNITS", "METHODS", "OBJECTIVES", "PARETO_OBJECTIVES", "OBJECTIVE_VALUES", "FAILURE_FACTOR", "Gene",
    "OptimiseSettings", "check_settings", "check_positive", "impact_paper_bounds", "gene_table", "decode", "Problem",
    "problem", "Evaluation", "evaluate", "load_statistic", "load_grid", "load_window", "Diagnostics", "diagnose",
    "History", "OptimisationResult", "optimise", "random_search", "pareto_mask", "worst_ratio", "constraint_factors",
    "safety_factors", "ImpactValues", "impact_values",
]

#: Pair-file keys of y1..y6, in the order of :data:`gearmesh.surface.MODIFICATION_FIELDS`.
GENE_KEYS = ("root_relief_um", "tip_relief_um", "root_relief_length_mm", "tip_relief_length_mm", "crowning_um",
             "unmodified_lead_length_mm")
GENE_SYMBOLS = ("y1", "y2", "y3", "y4", "y5", "y6")
GENE_UNITS = ("um", "um", "mm", "mm", "um", "mm")
_TO_SI = np.array([1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-3])
METHODS = ("ga", "random", "nsga2")
OBJECTIVES = ("force", "velocity", "robust", "dynamic")
#: The objectives NSGA-II can trade (all minimised; module docstring): the objective J (penalties
#: included), the peak-to-peak LTE at the design torque, and the worst ratio to the unmodified
#: pair's, over the load spectrum, of the TE harmonics (``harmonic_orders``), the contact pressure
#: (flank and edge each against its kind) and the root stress.
PARETO_OBJECTIVES = ("impact", "lte", "te_harmonics", "pressure", "root_stress")
LOAD_STATISTICS = ("max", "mean")
#: A failed candidate's objective, in units of the standard gear's.
FAILURE_FACTOR = 10.0


# --------------------------------------------------------------------------------------
# Settings
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class OptimiseSettings:
    """Checked optimiser settings: ``torque`` the design torque and ``torques`` the load spectrum
    (pinion torques, N m; the design torque is one of them), ``weights`` their time shares
    (statistic 'mean'), ``speed_rpm`` the pinion speed, ``tolerance_samples`` / ``sampling`` /
    ``tolerance_seed`` the manufactured population (:mod:`gearmesh.tolerance`; 0 nominal only;
    the seed defaults to the run's), ``tolerance_statistic``
    its statistic in the objective (None: the nominal alone) at ``tolerance_level`` %,
    ``load_window_step`` (N m) the grid of the load window, up to ``load_window_top`` (N m;
    None: 1.25 × the largest spectrum torque)."""

    method: str = "ga"
    objective: str = "force"
    population: int = 40
    generations: int = 30
    seed: int = 0
    torque: float = 1000.0
    torques: tuple[float, ...] = (1000.0,)
    weights: tuple[float, ...] | None = None
    statistic: str = "max"
    speed_rpm: float = 5000.0
    tolerance_samples: int = 0
    sampling: str = "lhs"
    tolerance_seed: int = 0
    tolerance_statistic: str | None = None
    tolerance_level: float = 90.0
    lte_factor: float | None = None
    line_load_factor: float | None = None
    penalty: float = field(default_factory=lambda: _declared_constraint("penalty"))
    mutation_probability: float = 0.3
    mutation_scale: float = 0.1
    keep_elitism: int = 2
    random_baseline: bool = False
    energy_velocity: str = "transverse"
    load_window_step: float = 50.0
    load_window_top: float | None = None
    dynamic_speeds: tuple[float, ...] | None = None
    dynamic_factor: float | None = None
    backlash: float | None = None
    harmonic_factor: float | None = None
    harmonic_orders: tuple[int, ...] = field(default_factory=lambda: tuple(_declared_constraint("harmonic_orders")))
    pressure_factor: float | None = None
    root_stress_factor: float | None = None
    impact_factor: float | None = None
    worst_impact_factor: float | None = None
    pareto_objectives: tuple[str, ...] = ("impact", "lte")
    S_Hmin: float | None = None
    S_Fmin: float | None = None
    criteria_over_samples: bool = field(default_factory=lambda: _declared_constraint("criteria_over_samples"))

    @property
    def budget(self) -> int:
        """The nominal number of evaluations: population × (generations + 1)."""
        return self.population * (self.generations + 1)

    @property
    def constrained(self) -> bool:
        """A constraint on the loaded contact (:func:`gearmesh.impact.ltca_criteria`) is set."""
        return any(v is not None for v in (self.lte_factor, self.line_load_factor, self.harmonic_factor,
                                           self.pressure_factor, self.root_stress_factor, self.S_Hmin,
                                           self.S_Fmin))

    @property
    def needs_criteria(self) -> bool:
        """Each candidate's loaded contact is needed (a constraint on it, or NSGA-II)."""
        return self.constrained or self.method == "nsga2"

    @property
    def needs_stresses(self) -> bool:
        """Each candidate's contact pressure and root stress are needed."""
        return self.pressure_factor is not None or self.root_stress_factor is not None or (
            self.method == "nsga2" and bool({"pressure", "root_stress"} & set(self.pareto_objectives)))

    @property
    def uses_dynamics(self) -> bool:
        """The contact-driven dynamics of every candidate is needed (objective or constraint)."""
        return self.objective == "dynamic" or self.dynamic_factor is not None

    @property
    def dynamic_speed_grid(self) -> tuple[float, ...]:
        """The speeds (rpm) of the dynamic objective/constraint: given, or 0.2, 1 and 3 times the
        objective speed (its range bounds the resonance speeds added per candidate)."""
        return self.dynamic_speeds or tuple(f * self.speed_rpm for f in (0.2, 1.0, 3.0))

    @property
    def objective_torques(self) -> tuple[float, ...]:
        """The torques the objective is evaluated at (the load spectrum)."""
        return self.torques

    @property
    def design_index(self) -> int:
        """Index of the design torque among the objective torques."""
        return int(np.argmin(np.abs(np.asarray(self.torques) - self.torque)))


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


def _weights(weights, torques: tuple[float, ...], statistic: str):
    if weights is None:
        return None
    if not isinstance(weights, (list, tuple)) or len(weights) != len(torques):
        raise GearmeshInputError("weights", weights, f"must be a list of {len(torques)} numbers, one per torque")
    for k, w in enumerate(weights):
        if isinstance(w, bool) or not isinstance(w, (int, float)) or not math.isfinite(w) or w < 0:
            raise GearmeshInputError(f"weights[{k}]", w, "must be a finite number >= 0 (a time share)")
    if sum(weights) <= 0:
        raise GearmeshInputError("weights", weights, "must not all be zero")
    if statistic != "mean":
        raise GearmeshInputError("weights", weights, "apply to statistic 'mean' only (the duty-cycle mean)")
    return tuple(float(w) for w in weights)


def _declared_constraint(key: str) -> Any:
    """The default of constraint ``key`` as :class:`gearmesh.settings.Constraints` declares it (the
    one default of the schema, the study, the CLI and this module)."""
    from .schema import defaults
    from .settings import Constraints

    return defaults(Constraints)[key]


def _declared_bounds(key: str) -> tuple[int, int]:
    """(minimum, maximum) of integer setting ``key`` as :class:`gearmesh.settings.Optimise`
    declares it: the one bound of the schema, the CLI and this function."""
    from .schema import settings_fields, spec_of
    from .settings import Optimise

    spec = spec_of(next(f for f in settings_fields(Optimise) if f.name == key))
    return int(spec.minimum), int(spec.maximum)


def check_settings(method: str = "ga", objective: str = "force", population: int = 40, generations: int = 30,
                   seed: int = 0, torque: float = 1000.0, torques=None, weights=None,
                   statistic: str = "max", speed_rpm: float = 5000.0, tolerance_samples: int = 0,
                   sampling: str = "lhs", tolerance_seed: int | None = None,
                   tolerance_statistic: str | None = None, tolerance_level: float = 90.0,
                   lte_factor=None, line_load_factor=None, penalty: float | None = None, mutation_probability: float = 0.3,
                   mutation_scale: float = 0.1, keep_elitism: int = 2, random_baseline: bool = False,
                   energy_velocity: str = "transverse", load_window_step: float = 50.0,
                   load_window_top: float | None = None, dynamic_speeds=None, dynamic_factor=None,
                   backlash=None, harmonic_factor=None, harmonic_orders=None, pressure_factor=None,
                   root_stress_factor=None, impact_factor=None, worst_impact_factor=None,
                   pareto_objectives=("impact", "lte"), S_Hmin=None, S_Fmin=None,
                   criteria_over_samples: bool | None = None) -> OptimiseSettings:
    """:class:`OptimiseSettings` from raw values, refusing bad ones (GearmeshInputError naming
    the field). Torques here are pinion torques (N m); ``torques`` None is the design torque alone.
    The constraint factors (``*_factor``) are relative to the unmodified pair's value (module
    docstring); ``pareto_objectives`` the objectives of method nsga2 (:data:`PARETO_OBJECTIVES`);
    ``criteria_over_samples``, ``penalty``, ``harmonic_orders`` None: the declared default
    (:func:`_declared_constraint`)."""
    from .ltca import check_torques

    method = _choice("method", method, METHODS)
    objective = _choice("objective", objective, OBJECTIVES)
    population = _integer("population", population, *_declared_bounds("population"))
    generations = _integer("generations", generations, *_declared_bounds("generations"))
    seed = _integer("seed", seed, *_declared_bounds("seed"))
    torque = check_positive("torque_Nm", torque)
    torques = (torque,) if torques is None else tuple(float(t) for t in check_torques(torques, "torques_Nm"))
    if len(set(torques)) != len(torques):
        raise GearmeshInputError("torques_Nm", list(torques), "must not repeat a torque")
    if not same_point(torques, torque).any():
        raise GearmeshInputError("torque_Nm", torque, f"must be one of torques_Nm {list(torques)} (the design torque "
                                                      "of the load spectrum)")
    statistic = _choice("statistic", statistic, LOAD_STATISTICS)
    weights = _weights(weights, torques, statistic)
    tolerance_samples = _integer("tolerance_samples", tolerance_samples, 0, 4096)
    sampling = _choice("sampling", sampling, SAMPLINGS)
    tolerance_seed = seed if tolerance_seed is None else _integer("tolerances.seed", tolerance_seed, 0, 2**32 - 1)
    check_statistic(tolerance_statistic, tolerance_level, "tolerance_statistic")
    if tolerance_statistic is not None and tolerance_samples == 0:
        raise GearmeshInputError("tolerance_statistic", tolerance_statistic, "needs tolerance samples "
                                 "(tolerance_samples > 0 and tolerances that deviate); null: the nominal alone")
    if objective == "robust" and len(torques) < 2 and tolerance_statistic is None:
        raise GearmeshInputError("objective", objective, "needs a load spectrum (two or more torques_Nm) or tolerance "
                                                         "samples with a tolerance_statistic; use 'force' for one point")
    if method == "nsga2" and objective not in ("force", "robust"):
        raise GearmeshInputError("objective", objective, "must be 'force' with method nsga2 (F_s against LTE p-p)")
    speed_rpm = check_positive("speed_rpm", speed_rpm)
    if speed_rpm > 1e6:
        raise GearmeshInputError("speed_rpm", speed_rpm, "must lie in (0, 1e6] rpm")
    lte_factor = check_positive("constraints.lte_factor", lte_factor, allow_none=True)
    line_load_factor = check_positive("constraints.line_load_factor", line_load_factor, allow_none=True)
    penalty = check_positive("constraints.penalty", _declared_constraint("penalty") if penalty is None else penalty)
    if isinstance(mutation_probability, bool) or not isinstance(mutation_probability, (int, float)) \
            or not 0 < mutation_probability <= 1:
        raise GearmeshInputError("mutation_probability", mutation_probability, "must lie in (0, 1]")
    if isinstance(mutation_scale, bool) or not isinstance(mutation_scale, (int, float)) or not 0 < mutation_scale <= 1:
        raise GearmeshInputError("mutation_scale", mutation_scale, "must lie in (0, 1] (of each gene's range)")
    keep_elitism = _integer("keep_elitism", keep_elitism, 0, population - 1)
    energy_velocity = _choice("energy_velocity", energy_velocity, ("transverse", "normal"))
    if not isinstance(random_baseline, bool):
        raise GearmeshInputError("random_baseline", random_baseline, "must be true or false")
    load_window_step = check_positive("load_window_step_Nm", load_window_step)
    spacing = np.diff(sorted(torques))
    if spacing.size and load_window_step >= spacing.min():
        raise GearmeshInputError("load_window_step_Nm", load_window_step, "must be finer than the spacing of "
                                                                          f"torques_Nm ({spacing.min():g} N m)")
    top = 1.25 * max(torques) if load_window_top is None else check_positive("load_window_top_Nm", load_window_top)
    if top < max(torques):
        raise GearmeshInputError("load_window_top_Nm", top, f"must reach the largest torque {max(torques):g} N m")
    if top / load_window_step > 2000:
        raise GearmeshInputError("load_window_step_Nm", load_window_step, "gives more than 2000 window torques")
    if dynamic_speeds is not None:
        if not isinstance(dynamic_speeds, (list, tuple)) or len(dynamic_speeds) < 2:
            raise GearmeshInputError("dynamic_speeds_rpm", dynamic_speeds, "must list two or more speeds (rpm)")
        dynamic_speeds = tuple(sorted(check_positive(f"dynamic_speeds_rpm[{k}]", v) for k, v in
                                      enumerate(dynamic_speeds)))
        if dynamic_speeds[-1] > 1e6:
            raise GearmeshInputError("dynamic_speeds_rpm", list(dynamic_speeds), "must lie in (0, 1e6] rpm")
    dynamic_factor = check_positive("constraints.dynamic_factor", dynamic_factor, allow_none=True)
    if backlash is not None:
        backlash = float(backlash)
        if not (math.isfinite(backlash) and 0 <= backlash <= 1e-3):
            raise GearmeshInputError("backlash_um", backlash * 1e6, "must lie in [0, 1000] µm")
    factors = {name: check_positive(f"constraints.{name}", value, allow_none=True) for name, value in (
        ("harmonic_factor", harmonic_factor), ("pressure_factor", pressure_factor),
        ("root_stress_factor", root_stress_factor), ("impact_factor", impact_factor),
        ("worst_impact_factor", worst_impact_factor))}
    for name, value in (("S_Hmin", S_Hmin), ("S_Fmin", S_Fmin)):
        factors[name] = check_positive(f"constraints.{name}", value, allow_none=True)
        if factors[name] is not None and factors[name] > 10:
            raise GearmeshInputError(f"constraints.{name}", value, "must lie in (0, 10] (a safety factor)")
    harmonic_orders = _orders(_declared_constraint("harmonic_orders") if harmonic_orders is None else harmonic_orders)
    pareto_objectives = _pareto_objectives(pareto_objectives, method)
    if criteria_over_samples is None:
        criteria_over_samples = _declared_constraint("criteria_over_samples")
    if not isinstance(criteria_over_samples, bool):
        raise GearmeshInputError("constraints.criteria_over_samples", criteria_over_samples, "must be true or false")
    return OptimiseSettings(method, objective, population, generations, seed, torque, torques, weights, statistic,
                            speed_rpm, tolerance_samples, sampling, tolerance_seed, tolerance_statistic,
                            float(tolerance_level), lte_factor, line_load_factor, penalty,
                            float(mutation_probability), float(mutation_scale), keep_elitism, random_baseline,
                            energy_velocity, load_window_step, top, dynamic_speeds, dynamic_factor, backlash,
                            harmonic_orders=harmonic_orders, pareto_objectives=pareto_objectives,
                            criteria_over_samples=criteria_over_samples, **factors)


def _orders(orders) -> tuple[int, ...]:
    """The loaded-TE mesh orders of the harmonic constraint: distinct orders of :data:`MESH_ORDERS`."""
    if not isinstance(orders, (list, tuple)) or not orders or len(set(orders)) != len(orders) or any(
            isinstance(k, bool) or k not in MESH_ORDERS for k in orders):
        raise GearmeshInputError("constraints.harmonic_orders", orders, f"must list distinct mesh orders of "
                                                                  f"{list(MESH_ORDERS)}")
    return tuple(int(k) for k in orders)


def _pareto_objectives(names, method: str) -> tuple[str, ...]:
    """The NSGA-II objectives: two or more distinct names of :data:`PARETO_OBJECTIVES`, the first 'impact'."""
    if not isinstance(names, (list, tuple)) or len(names) < 2 or len(set(names)) != len(names):
        raise GearmeshInputError("pareto_objectives", names, f"must list two or more distinct objectives of "
                                                             f"{list(PARETO_OBJECTIVES)}")
    for k, name in enumerate(names):
        _choice(f"pareto_objectives[{k}]", name, PARETO_OBJECTIVES)
    if names[0] != "impact":
        raise GearmeshInputError("pareto_objectives", list(names), "must start with 'impact' (the objective J, whose "
                                                                   "least value on the front is the optimum)")
    if method != "nsga2" and tuple(names) != ("impact", "lte"):
        raise GearmeshInputError("pareto_objectives", list(names), "apply to method nsga2 only")
    return tuple(names)


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


def impact_paper_bounds(geom: PairGeometry) -> np.ndarray:
    """The mesh-in impact paper's bounds (6, 2) of y1..y6 in µm / mm: y1, y2, y5 in [0.001, 0.015]·m_n, y3, y4 in
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
    ``bounds`` {pair-file key: [low, high]} overrides the mesh-in impact paper's bounds (µm / mm, on every
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
    table = impact_paper_bounds(geom)
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
    """Modification parameters (C, 2, 6) in m of gene values (C, G) (µm / mm), made valid
    modifications by :func:`gearmesh.surface.fit_modifications` (module docstring)."""
    values = np.atleast_2d(np.asarray(values, dtype=float))
    p = np.broadcast_to(base, (values.shape[0], 2, 6)).copy()
    for k, gene in enumerate(genes):
        p[:, gene.gear, gene.field] = values[:, k] * _TO_SI[gene.field]
    return fit_modifications(geom, p)


# --------------------------------------------------------------------------------------
# The objective, for a whole population × load spectrum × manufactured population at once
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ImpactValues:
    """The impact of N micro-geometries (rows) at T torques and the objective speed (SI): ``force``
    F_s closed form, ``force_energy_balance``, ``velocity`` |v_n|, ``scenario`` (N, T)."""

    force: np.ndarray
    force_energy_balance: np.ndarray
    velocity: np.ndarray
    scenario: np.ndarray


def impact_values(model: ImpactModel, settings: OptimiseSettings, params: np.ndarray, lead: np.ndarray,
                  torques) -> ImpactValues:
    """F_s, |v_n| and scenario of parameter sets ``params`` (N, 2, 6) with lead slopes ``lead``
    (N, 2) at pinion ``torques`` and the settings' speed: one batch of the impact model."""
    static = impact_static(model, list(torques), params, lead_slope=lead, engagement=False)
    static, resp = impact_response(model, static, [settings.speed_rpm], energy_velocity=settings.energy_velocity)
    return ImpactValues(resp.force[..., 0], resp.force_energy_balance[..., 0], resp.velocity_normal[..., 0],
                        static.scenario)


#: The objective quantity per (row, torque) of each objective: f(problem, params (N, 2, 6), lead
#: (N, 2), impact values) -> (N, T). 'dynamic': the dynamic factor K_v of the contact-driven 8-DOF
#: pair over the speed range (:func:`gearmesh.dynamics.population.dynamic_factors`).
OBJECTIVE_VALUES: dict[str, Callable[["Problem", np.ndarray, np.ndarray, ImpactValues], np.ndarray]] = {
    "force": lambda prob, params, lead, iv: iv.force,
    "velocity": lambda prob, params, lead, iv: iv.velocity,
    "robust": lambda prob, params, lead, iv: iv.force,
    "dynamic": lambda prob, params, lead, iv: dynamic_factors(prob.dynamics, params, lead),
}


def load_statistic(values: np.ndarray, statistic: str, weights=None) -> np.ndarray:
    """The load-spectrum statistic over the last axis (torques): the largest value (``max``) or the
    duty-cycle mean (``mean``) with ``weights`` the time shares (equal shares without)."""
    values = np.asarray(values, dtype=float)
    if statistic == "max":
        return values.max(axis=-1)
    w = np.ones(values.shape[-1]) if weights is None else np.asarray(weights, dtype=float)
    return values @ (w / w.sum())


@dataclass(frozen=True)
class Evaluation:
    """Objective and diagnostics of C candidates (SI): ``objective`` J (C,) (N, or m/s for
    'velocity', penalties included); per (C, S, T) — S the manufactured population evaluated
    (sample 0 the nominal), T the objective torques — ``value`` the objective quantity,
    ``force`` F_s, ``velocity`` |v_n|, ``scenario``; ``failed`` (C,), ``lte_peak_to_peak`` (C,) m
    and ``max_line_load`` (C,) N/m at the design torque (NaN when not needed), ``dynamic_factor``
    (C, T) K_v of the nominal gear at the objective torques (NaN when no dynamic constraint),
    ``violation`` (C,) the summed relative constraint excess; ``criteria`` the loaded contact at the
    objective torques (:class:`gearmesh.impact.LTCACriteria`, (C, T): each quantity's tolerance
    statistic over the manufactured gears, or the nominal gear's, :func:`_criteria`; None when no
    constraint or objective needs it), ``pareto`` (C, M) the NSGA-II objectives
    (:data:`PARETO_OBJECTIVES`; None for the other methods)."""

    objective: np.ndarray
    value: np.ndarray
    force: np.ndarray
    velocity: np.ndarray
    scenario: np.ndarray
    failed: np.ndarray
    lte_peak_to_peak: np.ndarray
    max_line_load: np.ndarray
    dynamic_factor: np.ndarray
    violation: np.ndarray
    criteria: LTCACriteria | None = None
    pareto: np.ndarray | None = None
    worst_force: np.ndarray | None = None  # (C, T) F_s of the worst manufactured gear evaluated (the standard: its box's)


@dataclass(frozen=True)
class Problem:
    """Everything an evaluation needs: the impact model, the genes, the base parameters, the
    settings, the tolerance model with its unit deviations (S, k) (drawn once), the standard
    (unmodified) gear's evaluation, and the shared set-up of the candidates' dynamics (when the
    objective or a constraint needs it)."""

    model: ImpactModel
    genes: tuple[Gene, ...]
    base: np.ndarray
    settings: OptimiseSettings
    tolerance: ToleranceModel
    deviations: np.ndarray
    standard: Evaluation | None
    dynamics: PopulationDynamics | None = None
    reference: BoxWorst | None = None  # the standard gear's worst over the tolerance box

    @property
    def geom(self) -> PairGeometry:
        return self.model.geom

    def decode(self, values) -> np.ndarray:
        return decode(self.geom, self.genes, self.base, values)

    @property
    def population_deviations(self) -> np.ndarray:
        """The deviations the objective sees: all samples, or none for a nominal objective."""
        d = self.deviations
        return d if self.settings.tolerance_statistic is not None else d[:0]


def _evaluate(prob: "Problem", params: np.ndarray, standard: Evaluation | None) -> Evaluation:
    """:func:`evaluate`, against the ``standard`` evaluation (None: evaluating the standard itself)."""
    s, model = prob.settings, prob.model
    deviations = prob.population_deviations
    nc = params.shape[0]
    ns = deviations.shape[0] + 1
    rows, lead = _manufactured_rows(model, prob.tolerance, params, deviations)
    iv = impact_values(model, s, rows, lead, s.objective_torques)
    value = OBJECTIVE_VALUES[s.objective](prob, rows, lead, iv)
    shape = (nc, ns, len(s.objective_torques))
    value, force, vel, scen = (a.reshape(shape) for a in (value, iv.force, iv.velocity, iv.scenario))
    per_gear = load_statistic(value, s.statistic, s.weights)  # (C, S): each manufactured gear over the spectrum
    f = per_gear[:, 0] if s.tolerance_statistic is None else sample_statistic(per_gear, s.tolerance_statistic,
                                                                              s.tolerance_level)
    # with the max over the samples, a candidate its nominal gear refuses is refused: its samples' contact is spared
    screened = standard is not None and _over_samples(s) and s.tolerance_statistic == "max"
    crit = _criteria(prob, params, rows, lead, over_samples=not screened) if s.needs_criteria else None
    lte, line = _design_lte_line(s, crit, nc)
    # failed: no impact found, a non-finite value, or a touch without a closing velocity (a
    # crossing the impact model did not resolve: zero force would be an artefact, not an optimum)
    failed = (~np.isfinite(f) | np.any(scen == SCENARIO_NONE, axis=(1, 2)) | ~np.all(np.isfinite(value), axis=(1, 2))
              | np.any(~(vel > 0), axis=(1, 2)))
    kv = np.full((nc, len(s.objective_torques)), np.nan)
    if s.objective == "dynamic":  # the nominal gear is sample 0 of the objective's rows
        kv = value[:, 0]
    raw = Evaluation(f, value, force, vel, scen, failed, lte, line, kv, np.zeros(nc), crit,
                     worst_force=force.max(axis=1))
    if screened and crit is not None:
        raw = _with_sample_criteria(prob, params, rows, lead, raw, standard)
    if s.dynamic_factor is not None and s.objective != "dynamic":
        raw = _with_dynamics(prob, params, raw, standard)
    return raw if standard is None else _score(prob, raw, standard)


def _over_samples(s: "OptimiseSettings") -> bool:
    """Whether the loaded-contact criteria are taken over the manufactured samples."""
    return s.criteria_over_samples and s.tolerance_statistic is not None


def _design_lte_line(s: "OptimiseSettings", crit: LTCACriteria | None, nc: int) -> tuple[np.ndarray, np.ndarray]:
    """LTE peak-to-peak and largest line load at the design torque (NaN without criteria)."""
    if crit is None:
        return np.full(nc, np.nan), np.full(nc, np.nan)
    return crit.lte_peak_to_peak[:, s.design_index], crit.max_line_load[:, s.design_index]


def _with_sample_criteria(prob: "Problem", params: np.ndarray, rows: np.ndarray, lead: np.ndarray, raw: Evaluation,
                          standard: Evaluation) -> Evaluation:
    """``raw`` (criteria of the nominal gears) with the criteria over the manufactured samples for
    the candidates whose nominal gear meets every constraint (tolerance statistic max). The max over
    the samples is never below the nominal gear's (sample 0), so a candidate its nominal gear already
    refuses is refused: its violation, J and Pareto objectives stay the nominal gear's, lower bounds
    of its own, and its samples' contact is never solved (most candidates of a run)."""
    nc = params.shape[0]
    kv = np.array(raw.dynamic_factor, dtype=float)
    kv[:] = standard.dynamic_factor[0]  # the dynamic constraint is checked after, on its own
    pre = _score(prob, replace(raw, dynamic_factor=kv), standard)
    need = np.flatnonzero(~pre.failed & (pre.violation == 0))
    if not need.size:
        return raw
    ns = rows.shape[0] // nc
    take = (need[:, None] * ns + np.arange(ns)).reshape(-1)
    over = _criteria(prob, params[need], rows[take], lead[take])
    crit = raw.criteria
    merged = {}
    for name in ("lte_peak_to_peak", "te_harmonics", "max_line_load", "flank_pressure", "edge_pressure",
                 "root_stress"):
        a = np.array(getattr(crit, name), dtype=float, copy=True)
        a[need] = getattr(over, name)
        merged[name] = a
    crit = LTCACriteria(**merged, load=crit.load)
    lte, line = _design_lte_line(prob.settings, crit, nc)
    return replace(raw, criteria=crit, lte_peak_to_peak=lte, max_line_load=line)


def _with_dynamics(prob: "Problem", params: np.ndarray, raw: Evaluation, standard: Evaluation | None) -> Evaluation:
    """``raw`` with the dynamic factor of its nominal gears
    (:func:`gearmesh.dynamics.population.dynamic_factors`), computed for the candidates that meet every
    other constraint: the dynamic constraint cannot make another candidate feasible, so theirs is left
    at the standard's (no excess; their J a lower bound), which spares most candidates' dynamics."""
    nc = params.shape[0]
    need = np.ones(nc, dtype=bool)
    kv = np.array(raw.dynamic_factor, dtype=float)
    if standard is not None:
        kv[:] = standard.dynamic_factor[0]
        pre = _score(prob, replace(raw, dynamic_factor=kv), standard)
        need = ~pre.failed & (pre.violation == 0)
    if need.any():
        lead = np.broadcast_to(np.asarray(prob.model.lead_slope, float), (int(need.sum()), 2))
        kv[need] = dynamic_factors(prob.dynamics, params[need], lead)
    return replace(raw, dynamic_factor=kv)


def _score(prob: "Problem", raw: Evaluation, standard: Evaluation) -> Evaluation:
    """The candidates' measured ``raw`` evaluation (objective f, no penalty) scored against the
    ``standard``'s: the constraints' violation, J = f + penalty·f_std·violation, the NSGA-II
    objectives (module docstring)."""
    s, crit, f = prob.settings, raw.criteria, raw.objective
    lte, line, kv, nc = raw.lte_peak_to_peak, raw.max_line_load, raw.dynamic_factor, raw.objective.shape[0]
    ratios = _ratios(s, raw.worst_force, lte, line, kv, crit, standard)
    if s.S_Hmin is not None or s.S_Fmin is not None:
        sh, sf = safety_factors(prob, crit, standard.criteria)
        ratios.update(S_H=worst_ratio(np.divide(s.S_Hmin or 0.0, sh), 1.0),
                      S_F=worst_ratio(np.divide(s.S_Fmin or 0.0, sf), 1.0))
    violation = np.zeros(nc)
    for name, factor in constraint_factors(s).items():
        with np.errstate(invalid="ignore"):
            violation += np.maximum(0.0, ratios[name] / factor - 1.0)
    failed = raw.failed | ~np.isfinite(violation)
    j = f + s.penalty * standard.objective[0] * violation
    j = np.where(failed, FAILURE_FACTOR * standard.objective[0], j)
    pareto = None
    if s.method == "nsga2":
        lte = np.where(failed, FAILURE_FACTOR * standard.lte_peak_to_peak[0], lte)
        pareto = np.column_stack([j if k == "impact" else lte if k == "lte" else
                                  np.where(failed, FAILURE_FACTOR, ratios[k]) for k in s.pareto_objectives])
    return Evaluation(j, raw.value, raw.force, raw.velocity, raw.scenario, failed, lte, line, kv,
                      np.where(failed, np.nan, violation), crit, pareto, raw.worst_force)


def _criteria(prob: "Problem", params: np.ndarray, rows: np.ndarray, lead: np.ndarray,
              over_samples: bool = True) -> LTCACriteria:
    """The candidates' loaded-contact criteria (C, T, ...): of the nominal gears, or with
    ``criteria_over_samples`` (and a tolerance statistic, and ``over_samples``) of every manufactured
    gear ``rows``, ``lead`` ((C·S, ...), sample 0 the nominal, as :func:`_manufactured_rows`), each
    quantity reduced over the S gears by the tolerance statistic; the point loads stay the nominal
    gear's (S_Hmin, S_Fmin are nominal)."""
    s, model = prob.settings, prob.model
    if not (over_samples and _over_samples(s)):
        return ltca_criteria(model, s.objective_torques, params, stresses=s.needs_stresses)
    nc = params.shape[0]
    ns = rows.shape[0] // nc
    c = ltca_criteria(model, s.objective_torques, rows, lead_slope=lead, stresses=s.needs_stresses, samples=ns)

    def over_samples(a: np.ndarray) -> np.ndarray:
        a = np.asarray(a).reshape(nc, ns, *a.shape[1:])
        return sample_statistic(np.moveaxis(a, 1, -1), s.tolerance_statistic, s.tolerance_level)

    return LTCACriteria(lte_peak_to_peak=over_samples(c.lte_peak_to_peak), te_harmonics=over_samples(c.te_harmonics),
                        max_line_load=over_samples(c.max_line_load), flank_pressure=over_samples(c.flank_pressure),
                        edge_pressure=over_samples(c.edge_pressure), root_stress=over_samples(c.root_stress),
                        load=c.load.reshape(nc, ns, *c.load.shape[1:])[:, 0])


def worst_ratio(values: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """The largest ratio of ``values`` (C, ...) to the unmodified pair's ``reference`` (...) over
    every axis but the first (torques, orders): 1 or less exactly when no entry exceeds the
    reference. A zero reference counts a zero value as ratio 0 and a positive one as infinite."""
    v = np.asarray(values, dtype=float)
    ref = np.broadcast_to(np.asarray(reference, dtype=float), v.shape[1:])
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(ref > 0, v / np.where(ref > 0, ref, 1.0), np.where(v > 0, np.inf, 0.0))
    return r.reshape(v.shape[0], -1).max(axis=1)


def _ratios(s: OptimiseSettings, force: np.ndarray, lte, line, kv, crit: LTCACriteria | None,
            standard: Evaluation) -> dict[str, np.ndarray]:
    """Each criterion's worst ratio (C,) to the standard gear's (:func:`worst_ratio`), per torque
    of the spectrum unless said: F_s of the worst manufactured gear per torque ('force'; the nominal
    without a tolerance statistic) and its worst case over the torques ('worst_force'), LTE p-p and the largest line load at the design torque, the dynamic
    factor, and from the loaded contact the TE harmonics of ``harmonic_orders`` ('te_harmonics'), the
    flank pressure against the standard's flank pressure and the tip-edge pressure against its
    tip-edge pressure (its flank pressure where it has no edge contact) ('pressure'), and the
    root stress of either gear ('root_stress')."""
    nc = force.shape[0]
    nan = np.full(nc, np.nan)
    ref = standard.criteria
    out = {"force": worst_ratio(force, standard.worst_force[0]),
           "worst_force": worst_ratio(force.max(axis=1), standard.worst_force[0].max()),
           "lte": worst_ratio(lte[:, None], standard.lte_peak_to_peak[0]),
           "line_load": worst_ratio(line[:, None], standard.max_line_load[0]),
           "dynamic": worst_ratio(kv, standard.dynamic_factor[0])}
    if crit is None or ref is None:
        return {**out, "te_harmonics": nan, "pressure": nan, "root_stress": nan}
    k = [MESH_ORDERS.index(o) for o in s.harmonic_orders]
    out["te_harmonics"] = worst_ratio(crit.te_harmonics[..., k], ref.te_harmonics[0][..., k])
    edge_ref = edge_pressure_reference(ref.flank_pressure[0], ref.edge_pressure[0])
    out["pressure"] = np.maximum(worst_ratio(crit.flank_pressure, ref.flank_pressure[0]),
                                 worst_ratio(crit.edge_pressure, edge_ref))
    out["root_stress"] = worst_ratio(crit.root_stress, ref.root_stress[0])
    return out


def safety_factors(prob: "Problem", crit: LTCACriteria, reference: LTCACriteria) -> tuple[np.ndarray, np.ndarray]:
    """S_H and S_F (C, T) of the weaker gear of each candidate at the spectrum torques: ISO 6336-2/-3
    method B (:func:`gearmesh.rating.rating`, the pair's rating inputs, application factor 1) at the
    objective speed, with K_Hβ and K_Hα from the candidate's LTCA loads and the unmodified pair's
    (:func:`gearmesh.rating.ltca_load_factors`, K_Hα at least 1, as the rating stage)."""
    from .rating import ltca_load_factors, rated_transverse_factor, rating, rating_inputs

    s, geom = prob.settings, prob.geom
    inputs = rating_inputs(dict(geom.pair.rating_inputs))
    nc, nt = crit.load.shape[:2]
    ref = np.broadcast_to(reference.load[0][None], crit.load.shape).reshape(nc * nt, *crit.load.shape[2:])
    lf = ltca_load_factors(crit.load.reshape(nc * nt, *crit.load.shape[2:]), ref)
    sh, sf = np.empty(nc * nt), np.empty(nc * nt)
    for k in range(nc * nt):
        r = rating(geom, s.objective_torques[k % nt], s.speed_rpm, inputs, method="ltca",
                   ltca_factors={"K_Hbeta": float(lf["K_Hbeta"][k]), "K_Halpha": float(rated_transverse_factor(lf["K_Halpha"][k]))})
        sh[k], sf[k] = min(r.values["S_H"]), min(r.values["S_F"])
    return sh.reshape(nc, nt), sf.reshape(nc, nt)


def constraint_factors(s: OptimiseSettings) -> dict[str, float]:
    """The constraints set, {criterion of :func:`_ratios` (S_H, S_F: S_min/S): factor (1 for S_min)}."""
    given = {"lte": s.lte_factor, "line_load": s.line_load_factor, "dynamic": s.dynamic_factor,
             "te_harmonics": s.harmonic_factor, "pressure": s.pressure_factor,
             "root_stress": s.root_stress_factor, "force": s.impact_factor, "worst_force": s.worst_impact_factor,
             "S_H": None if s.S_Hmin is None else 1.0, "S_F": None if s.S_Fmin is None else 1.0}
    return {k: v for k, v in given.items() if v is not None}


def _manufactured_rows(model: ImpactModel, tolerance: ToleranceModel, params: np.ndarray, deviations: np.ndarray):
    """Rows (C·S, 2, 6) and lead slopes (C·S, 2) of the manufactured population of each candidate
    (sample 0 the nominal): :func:`gearmesh.tolerance.manufactured_population` on the model."""
    return manufactured_population(model.geom, tolerance, params, model.lead_slope, deviations)


def problem(model: ImpactModel, settings: OptimiseSettings, modify=("pinion",), bounds=None,
            fixed=None, tolerance: ToleranceModel | None = None) -> Problem:
    """Set up the optimisation of ``model``'s pair: genes, the manufactured population's unit
    deviations (``settings.tolerance_samples`` of ``tolerance``, seeded by the settings' seed),
    and the standard (unmodified) gear evaluated once, with the same population."""
    genes, base = gene_table(model.geom, modify, bounds, fixed)
    tolerance = tolerance or ToleranceModel(np.zeros((2, 6)), np.zeros(2))
    robust = settings.tolerance_statistic is not None and bool(tolerance.dimensions)
    reference = None
    if robust and (settings.criteria_over_samples or settings.sampling == "box"):
        reference = design_box_worst(model, tolerance, np.zeros((2, 6)), settings.objective_torques,
                                     settings.speed_rpm, settings.energy_velocity)[0]
    if settings.sampling == "box" and reference is not None:
        deviations = box_scenarios(tolerance, reference)
    else:
        deviations = unit_deviations(len(tolerance.dimensions), settings.tolerance_samples,
                                     "lhs" if settings.sampling == "box" else settings.sampling,
                                     settings.tolerance_seed)
    if settings.tolerance_statistic is not None and deviations.shape[0] == 0:
        raise GearmeshInputError("tolerances", None, "define no deviation (no lead grade, no modification "
                                                     "tolerance): the tolerance statistic has nothing to sample")
    dynamics = population_dynamics(model.geom, settings.objective_torques, settings.dynamic_speed_grid,
                                   backlash=settings.backlash, tables=model.ltca.tables,
                                   contact_law_name=model.ltca.law.name,
                                   misalignment_torque=settings.torque) if settings.uses_dynamics else None
    prob = Problem(model, genes, base, settings, tolerance, deviations, None, dynamics, reference)
    standard = _with_reference(_evaluate(prob, np.zeros((1, 2, 6)), None), reference)
    if not np.all(np.isfinite(standard.objective)) or np.any(standard.scenario == SCENARIO_NONE):
        raise GearmeshInputError("torques_Nm" if len(settings.objective_torques) > 1 else "torque_Nm",
                                 list(settings.objective_torques),
                                 "gives the standard (unmodified) gear no mesh-in impact: nothing to reduce")
    return replace(prob, standard=standard)


def _with_reference(standard: Evaluation, reference: BoxWorst | None) -> Evaluation:
    """The standard gear's evaluation with its criteria and F_s those of its worst manufactured gear
    over the tolerance box (``reference``, :func:`gearmesh.robust.design_box_worst`, columns
    :data:`gearmesh.robust.CRITERIA` per objective torque; never below its evaluated samples'): the
    reference every candidate's ratios are taken to, as the sign-off table's."""
    if reference is None or standard.criteria is None:
        return standard if reference is None else replace(standard, worst_force=np.maximum(
            standard.worst_force, reference.values[None, :, CRITERIA.index("impact_force")]))
    w = reference.values  # (T, K)
    c = standard.criteria
    orders = [CRITERIA.index(f"lte_order_{k}") for k in MESH_ORDERS]
    crit = replace(c, te_harmonics=np.maximum(c.te_harmonics, w[None][..., orders]),
                   flank_pressure=np.maximum(c.flank_pressure, w[None, :, CRITERIA.index("peak_flank_pressure")]),
                   edge_pressure=np.maximum(c.edge_pressure, w[None, :, CRITERIA.index("peak_edge_pressure")]),
                   root_stress=np.maximum(c.root_stress, w[None, :, CRITERIA.index("peak_root_stress")]))
    return replace(standard, criteria=crit, worst_force=np.maximum(
        standard.worst_force, w[None, :, CRITERIA.index("impact_force")]))


def standard_penalised_objective(prob: Problem) -> float:
    """The unmodified pair as a candidate of the run: its J with the constraints' penalties, scored
    from its evaluation in :func:`problem` (no second impact batch)."""
    return float(_score(prob, prob.standard, prob.standard).objective[0])


def evaluate(prob: Problem, params: np.ndarray) -> Evaluation:
    """The objective of candidates ``params`` (C, 2, 6) m: every candidate × torque × manufactured
    sample in one batch of the impact model (module docstring)."""
    return _evaluate(prob, params, prob.standard)


# --------------------------------------------------------------------------------------
# Diagnostics of an optimum: load window, tolerance spread, scenario per torque
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Diagnostics:
    """An optimum against the standard gear (SI): ``window_torque`` (W,) the load-window grid
    (pinion, N m), ``window_force`` / ``window_standard`` (W,) their nominal F_s there,
    ``window_scenario`` / ``window_standard_scenario`` (W,), ``load_window`` (low, high) N m;
    ``spread_force`` / ``spread_standard`` (S, T) F_s of every manufactured sample (0 the nominal)
    at the objective torques, ``spread_scenario`` (S, T)."""

    window_torque: np.ndarray
    window_force: np.ndarray
    window_standard: np.ndarray
    window_scenario: np.ndarray
    window_standard_scenario: np.ndarray
    load_window: tuple[float, float]
    spread_force: np.ndarray
    spread_standard: np.ndarray
    spread_scenario: np.ndarray
    spread_standard_scenario: np.ndarray


def diagnose(prob: Problem, params: np.ndarray) -> Diagnostics:
    """Load window, tolerance spread and scenarios of the micro-geometry ``params`` (2, 6) against
    the standard gear (module docstring): two batches of the impact model."""
    s, model = prob.settings, prob.model
    both = np.stack([np.asarray(params, dtype=float), np.zeros((2, 6))])
    grid = load_grid(s.objective_torques, s.load_window_step, s.load_window_top)
    lead = np.broadcast_to(np.asarray(model.lead_slope, dtype=float), (2, 2))
    w = impact_values(model, s, both, lead, grid)
    rows, rows_lead = _manufactured_rows(model, prob.tolerance, both, prob.deviations)
    sp = impact_values(model, s, rows, rows_lead, s.objective_torques)
    shape = (2, prob.deviations.shape[0] + 1, len(s.objective_torques))
    force, scen = sp.force.reshape(shape), sp.scenario.reshape(shape)
    return Diagnostics(window_torque=grid, window_force=w.force[0], window_standard=w.force[1],
                       window_scenario=w.scenario[0], window_standard_scenario=w.scenario[1],
                       load_window=load_window(grid, w.force[0], w.force[1], s.torque),
                       spread_force=force[0], spread_standard=force[1], spread_scenario=scen[0],
                       spread_standard_scenario=scen[1])


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
    """Run the configured method (and, for 'ga' and 'nsga2' with ``random_baseline``, the random
    search of the same budget as ``baseline``)."""
    s = prob.settings
    if s.method == "random":
        return random_search(prob)
    result = _run_pygad(prob)
    if s.random_baseline:
        result = replace(result, baseline=random_search(prob, result.evaluations))
    return result
