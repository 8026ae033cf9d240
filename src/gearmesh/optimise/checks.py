"""The optimiser's settings, checked: :class:`OptimiseSettings` from raw values by
:func:`check_settings`, each bad value refused with the field it came from.

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import GearmeshInputError
from ..limits import same_point
from ..ltca import MESH_ORDERS
from ..tolerance import SAMPLINGS, check_statistic

METHODS = ("ga", "random", "nsga2")
OBJECTIVES = ("force", "velocity", "robust", "dynamic")
#: The objectives NSGA-II can trade (all minimised; :mod:`gearmesh.optimise`): the objective J (penalties
#: included), the peak-to-peak LTE at the design torque, and the worst ratio to the unmodified
#: pair's, over the load spectrum, of the TE harmonics (``harmonic_orders``), the contact pressure
#: (flank and edge each against its kind) and the root stress.
PARETO_OBJECTIVES = ("impact", "lte", "te_harmonics", "pressure", "root_stress")
LOAD_STATISTICS = ("max", "mean")


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
    """``value`` as a float above ``at_least`` (or None when allowed); GearmeshInputError otherwise.

    Parameters
    ----------
    field_name : str
        The setting's name, for the error line.
    value : Any
        The raw value.
    allow_none : bool, default False
        None is accepted (and returned).
    at_least : float, default 0
        The value must be greater than this (the setting's unit).

    Returns
    -------
    float or None
        The value as a float, or None.
    """
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
    from ..schema import defaults
    from ..settings import Constraints

    return defaults(Constraints)[key]


def _declared_bounds(key: str) -> tuple[int, int]:
    """(minimum, maximum) of integer setting ``key`` as :class:`gearmesh.settings.Optimise`
    declares it: the one bound of the schema, the CLI and this function."""
    from ..schema import settings_fields, spec_of
    from ..settings import Optimise

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
    """:class:`OptimiseSettings` from raw values, refusing bad ones (GearmeshInputError naming the field).

    The values are checked in a fixed order (the signature's groups, one helper each): of several bad values the same
    one is named first. Each setting is described in config/README.md (``optimise.NAME``).

    Parameters
    ----------
    method, objective, population, generations, seed, mutation_probability, mutation_scale, keep_elitism
        The search ('ga', 'nsga2', 'random'), the objective quantity, the GA's size, seed and operators.
    torque, torques, weights, statistic, speed_rpm
        Design torque and load spectrum (pinion torques, N m; ``torques`` None: the design torque alone), their time
        shares, the spectrum statistic ('max' or 'mean') and the pinion speed (rpm).
    tolerance_samples, sampling, tolerance_seed, tolerance_statistic, tolerance_level, criteria_over_samples
        The manufactured population (:mod:`gearmesh.tolerance`), its statistic at the level (%); None: the default.
    lte_factor, line_load_factor, harmonic_factor, pressure_factor, root_stress_factor, impact_factor, worst_impact_factor
        Constraint factors (-), relative to the unmodified pair's value (:mod:`gearmesh.optimise`).
    harmonic_orders, penalty, S_Hmin, S_Fmin
        Mesh orders of ``harmonic_factor`` and penalty weight (None: the declared default); least ISO 6336 safety
        factors S_H, S_F (-; None: not constrained).
    dynamic_speeds, dynamic_factor, backlash
        Speed grid (rpm) and factor of the dynamic constraint, backlash 2b0 (m) of its model.
    energy_velocity, load_window_step, load_window_top, random_baseline, pareto_objectives
        Impact energy velocity; load-window grid step and top (N m); a random search of the same budget; the
        objectives of method nsga2 (:data:`PARETO_OBJECTIVES`).

    Returns
    -------
    OptimiseSettings
        The checked settings.
    """
    method = _choice("method", method, METHODS)
    objective = _choice("objective", objective, OBJECTIVES)
    population = _integer("population", population, *_declared_bounds("population"))
    generations = _integer("generations", generations, *_declared_bounds("generations"))
    seed = _integer("seed", seed, *_declared_bounds("seed"))
    torque, torques, statistic, weights = _load_spectrum(torque, torques, statistic, weights)
    tolerance_samples, sampling, tolerance_seed = _population(tolerance_samples, sampling, tolerance_seed, seed,
                                                              tolerance_statistic, tolerance_level)
    _objective_fits(objective, method, torques, tolerance_statistic)
    speed_rpm = check_positive("speed_rpm", speed_rpm)
    if speed_rpm > 1e6:
        raise GearmeshInputError("speed_rpm", speed_rpm, "must lie in (0, 1e6] rpm")
    lte_factor = check_positive("constraints.lte_factor", lte_factor, allow_none=True)
    line_load_factor = check_positive("constraints.line_load_factor", line_load_factor, allow_none=True)
    penalty = check_positive("constraints.penalty", _declared_constraint("penalty") if penalty is None else penalty)
    mutation_probability, mutation_scale, keep_elitism = _ga_operators(mutation_probability, mutation_scale,
                                                                       keep_elitism, population)
    energy_velocity = _choice("energy_velocity", energy_velocity, ("transverse", "normal"))
    if not isinstance(random_baseline, bool):
        raise GearmeshInputError("random_baseline", random_baseline, "must be true or false")
    load_window_step, top = _load_window(load_window_step, load_window_top, torques)
    dynamic_speeds, dynamic_factor, backlash = _dynamics(dynamic_speeds, dynamic_factor, backlash)
    factors = _factors(harmonic_factor, pressure_factor, root_stress_factor, impact_factor, worst_impact_factor,
                       S_Hmin, S_Fmin)
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


def _load_spectrum(torque, torques, statistic: str, weights) -> tuple[float, tuple[float, ...], str, Any]:
    """The design torque, the load spectrum (distinct pinion torques, N m, the design torque one of
    them; None: the design torque alone), its statistic and the time shares of ``mean``."""
    from ..ltca import check_torques

    torque = check_positive("torque_Nm", torque)
    torques = (torque,) if torques is None else tuple(float(t) for t in check_torques(torques, "torques_Nm"))
    if len(set(torques)) != len(torques):
        raise GearmeshInputError("torques_Nm", list(torques), "must not repeat a torque")
    if not same_point(torques, torque).any():
        raise GearmeshInputError("torque_Nm", torque, f"must be one of torques_Nm {list(torques)} (the design torque "
                                                      "of the load spectrum)")
    statistic = _choice("statistic", statistic, LOAD_STATISTICS)
    return torque, torques, statistic, _weights(weights, torques, statistic)


def _population(tolerance_samples, sampling: str, tolerance_seed, seed: int, tolerance_statistic,
                tolerance_level) -> tuple[int, str, int]:
    """The manufactured population: sample count, sampling, seed (default the run's ``seed``), and
    its statistic, which needs samples."""
    tolerance_samples = _integer("tolerance_samples", tolerance_samples, 0, 4096)
    sampling = _choice("sampling", sampling, SAMPLINGS)
    tolerance_seed = seed if tolerance_seed is None else _integer("tolerances.seed", tolerance_seed, 0, 2**32 - 1)
    check_statistic(tolerance_statistic, tolerance_level, "tolerance_statistic")
    if tolerance_statistic is not None and tolerance_samples == 0:
        raise GearmeshInputError("tolerance_statistic", tolerance_statistic, "needs tolerance samples "
                                 "(tolerance_samples > 0 and tolerances that deviate); null: the nominal alone")
    return tolerance_samples, sampling, tolerance_seed


def _objective_fits(objective: str, method: str, torques: tuple[float, ...], tolerance_statistic) -> None:
    """Refuse an objective its method or its load points cannot serve: 'robust' needs a spectrum or a
    tolerance statistic, NSGA-II trades F_s ('force' or 'robust') against the LTE."""
    if objective == "robust" and len(torques) < 2 and tolerance_statistic is None:
        raise GearmeshInputError("objective", objective, "needs a load spectrum (two or more torques_Nm) or tolerance "
                                                         "samples with a tolerance_statistic; use 'force' for one point")
    if method == "nsga2" and objective not in ("force", "robust"):
        raise GearmeshInputError("objective", objective, "must be 'force' with method nsga2 (F_s against LTE p-p)")


def _ga_operators(mutation_probability, mutation_scale, keep_elitism, population: int) -> tuple[Any, Any, int]:
    """The GA's mutation probability and scale (each in (0, 1]) and its elitism (fewer than the
    population)."""
    if isinstance(mutation_probability, bool) or not isinstance(mutation_probability, (int, float)) \
            or not 0 < mutation_probability <= 1:
        raise GearmeshInputError("mutation_probability", mutation_probability, "must lie in (0, 1]")
    if isinstance(mutation_scale, bool) or not isinstance(mutation_scale, (int, float)) or not 0 < mutation_scale <= 1:
        raise GearmeshInputError("mutation_scale", mutation_scale, "must lie in (0, 1] (of each gene's range)")
    return mutation_probability, mutation_scale, _integer("keep_elitism", keep_elitism, 0, population - 1)


def _load_window(load_window_step, load_window_top, torques: tuple[float, ...]) -> tuple[float, float]:
    """The load window's grid step (finer than the spectrum's spacing) and top (N m; None: 1.25 × the
    largest torque, at least that torque, at most 2000 steps)."""
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
    return load_window_step, top


def _dynamics(dynamic_speeds, dynamic_factor, backlash) -> tuple[tuple[float, ...] | None, float | None, float | None]:
    """The dynamic objective's or constraint's speeds (two or more, rpm, sorted), the dynamic-factor
    constraint and the backlash (m)."""
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
    return dynamic_speeds, dynamic_factor, backlash


def _factors(harmonic_factor, pressure_factor, root_stress_factor, impact_factor, worst_impact_factor, S_Hmin,
             S_Fmin) -> dict[str, float | None]:
    """The constraints on the loaded contact and the impact (factors on the standard gear's value)
    and the least safety factors S_Hmin, S_Fmin (in (0, 10]), by their :class:`OptimiseSettings` names."""
    factors = {name: check_positive(f"constraints.{name}", value, allow_none=True) for name, value in (
        ("harmonic_factor", harmonic_factor), ("pressure_factor", pressure_factor),
        ("root_stress_factor", root_stress_factor), ("impact_factor", impact_factor),
        ("worst_impact_factor", worst_impact_factor))}
    for name, value in (("S_Hmin", S_Hmin), ("S_Fmin", S_Fmin)):
        factors[name] = check_positive(f"constraints.{name}", value, allow_none=True)
        if factors[name] is not None and factors[name] > 10:
            raise GearmeshInputError(f"constraints.{name}", value, "must lie in (0, 10] (a safety factor)")
    return factors


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
