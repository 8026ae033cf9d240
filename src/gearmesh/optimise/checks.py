"""The optimiser's run settings, resolved once: :class:`OptimiseSettings` built by
:func:`resolve_settings` from a study's optimisation as its declaration parsed it
(:class:`gearmesh.settings.Optimise`, every default and bound there), the study's impact
model and its manufactured population; :func:`check_rules` refuses what the declaration cannot
express (rules between fields, and against the pair), naming the config's field.

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ..errors import GearmeshInputError
from ..gear import PairGeometry
from ..limits import MAX_WINDOW_TORQUES, same_point
from ..loads import check_load
from ..ltca import loaded_pinion_torques, pinion_torques
from ..schema import type_hints
from ..settings import Optimise
from ..tolerance import ToleranceModel, check_statistic, study_tolerances


def _declared_words(key: str) -> tuple[str, ...]:
    """The words setting ``key`` of :class:`gearmesh.settings.Optimise` may take, as declared."""
    hint = type_hints(Optimise)[key]
    while typing.get_origin(hint) is not typing.Literal:
        hint = next(a for a in typing.get_args(hint) if a is not type(None) and a is not Ellipsis)
    return typing.get_args(hint)


METHODS = _declared_words("method")
OBJECTIVES = _declared_words("objective")
#: The objectives NSGA-II can trade (all minimised; :mod:`gearmesh.optimise`): the objective J (penalties
#: included), the peak-to-peak LTE at the design torque, and the worst ratio to the unmodified
#: pair's, over the load spectrum, of the TE harmonics (``harmonic_orders``), the contact pressure
#: (flank and edge each against its kind) and the root stress.
PARETO_OBJECTIVES = _declared_words("pareto_objectives")
LOAD_STATISTICS = _declared_words("statistic")


@dataclass(frozen=True)
class OptimiseSettings:
    """The resolved settings of one optimisation run (no defaults of its own: :func:`resolve_settings`
    fills every field from the declaration). SI and pinion torques: ``torque`` the design torque and
    ``torques`` the load spectrum (N m; the design torque is one of them), ``weights`` their time
    shares (statistic 'mean'), ``speed_rpm`` the pinion speed, ``tolerance_samples`` / ``sampling`` /
    ``tolerance_seed`` the manufactured population (:mod:`gearmesh.tolerance`; 0 nominal only),
    ``tolerance_statistic`` its statistic in the objective (None: the nominal alone) at
    ``tolerance_level`` %, ``load_window_step`` (N m) the grid of the load window up to
    ``load_window_top`` (N m), ``dynamic_speeds`` (rpm) and ``backlash`` (m; None: the pair's) of
    the candidates' dynamics; the constraint factors, ``harmonic_orders``, ``penalty``, ``S_Hmin``,
    ``S_Fmin`` and ``criteria_over_samples`` as :class:`gearmesh.settings.Constraints` declares them."""

    method: str
    objective: str
    population: int
    generations: int
    seed: int
    torque: float
    torques: tuple[float, ...]
    weights: tuple[float, ...] | None
    statistic: str
    speed_rpm: float
    tolerance_samples: int
    sampling: str
    tolerance_seed: int
    tolerance_statistic: str | None
    tolerance_level: float
    lte_factor: float | None
    line_load_factor: float | None
    penalty: float
    mutation_probability: float
    mutation_scale: float
    keep_elitism: int
    random_baseline: bool
    energy_velocity: str
    load_window_step: float
    load_window_top: float
    dynamic_speeds: tuple[float, ...] | None
    dynamic_factor: float | None
    backlash: float | None
    harmonic_factor: float | None
    harmonic_orders: tuple[int, ...]
    pressure_factor: float | None
    root_stress_factor: float | None
    impact_factor: float | None
    worst_impact_factor: float | None
    pareto_objectives: tuple[str, ...]
    S_Hmin: float | None
    S_Fmin: float | None
    criteria_over_samples: bool

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


def _window_top(geom: PairGeometry, torques: tuple[float, ...]) -> float:
    """1.25 × the largest spectrum torque, lowered (in 5 % steps) to what the load limits allow."""
    top = 1.25 * max(torques)
    while top > max(torques):
        try:
            check_load(geom, top, "load_window_top_Nm", top)
            return top
        except GearmeshInputError:
            top = max(max(torques), top - 0.05 * max(torques))
    return top


def _floats(values) -> tuple[float, ...] | None:
    return None if values is None else tuple(float(v) for v in values)


def resolve_settings(geom: PairGeometry, declared: Optimise, energy_velocity: str,
                     tolerances: Mapping[str, Any] | None) -> tuple[OptimiseSettings, ToleranceModel]:
    """The run settings of one optimisation of ``geom``'s pair and its tolerance model: the one
    place the study's section becomes what the optimiser runs with.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    declared : gearmesh.settings.Optimise
        The optimisation as its declaration parsed it (:func:`gearmesh.schema.settings_object`).
    energy_velocity : {'transverse', 'normal'}
        The impact energy's velocity, the study's impact section's.
    tolerances : mapping or None
        The study's ``tolerances:`` section (:func:`gearmesh.tolerance.study_tolerances`).

    Returns
    -------
    settings : OptimiseSettings
        Torques as pinion torques (N m) within the load limits, the manufactured population's
        samples, sampling and seed, every rule of :func:`check_rules` met.
    tolerance : ToleranceModel
        The manufactured population's deviation model.
    """
    d, c = declared, declared.constraints
    # the load limits first: an absurd torque is named as such, not as a load window too fine for it
    design = float(loaded_pinion_torques(geom, [d.torque_Nm], d.on, field="torque_Nm")[1][0])
    spectrum = (design,) if d.torques_Nm is None else \
        _floats(loaded_pinion_torques(geom, d.torques_Nm, d.on, field="torques_Nm")[1])
    tol_model, samples, sampling, tol_seed = study_tolerances(geom, tolerances)
    factors = {name: None if getattr(c, name) is None else float(getattr(c, name)) for name in (
        "lte_factor", "line_load_factor", "dynamic_factor", "harmonic_factor", "pressure_factor", "root_stress_factor",
        "impact_factor", "worst_impact_factor", "S_Hmin", "S_Fmin")}
    settings = OptimiseSettings(
        method=d.method, objective=d.objective, population=int(d.population), generations=int(d.generations),
        seed=int(d.seed), torque=design, torques=spectrum, weights=_floats(d.weights),
        statistic=d.statistic, speed_rpm=float(d.speed_rpm), tolerance_samples=int(samples), sampling=sampling,
        tolerance_seed=int(tol_seed), tolerance_statistic=d.tolerance_statistic,
        tolerance_level=float(d.tolerance_level_percent), penalty=float(c.penalty),
        mutation_probability=float(d.mutation_probability), mutation_scale=float(d.mutation_scale),
        keep_elitism=int(d.keep_elitism), random_baseline=d.random_baseline, energy_velocity=energy_velocity,
        load_window_step=float(pinion_torques(geom, [d.load_window_step_Nm], d.on, field="load_window_step_Nm")[0]),
        load_window_top=_window_top(geom, spectrum),
        dynamic_speeds=None if d.dynamic_speeds_rpm is None else tuple(sorted(_floats(d.dynamic_speeds_rpm))),
        backlash=None if d.backlash_um == "pair" else float(d.backlash_um) * 1e-6,
        harmonic_orders=tuple(int(k) for k in c.harmonic_orders), pareto_objectives=tuple(d.pareto_objectives),
        criteria_over_samples=c.criteria_over_samples, **factors)
    check_rules(settings, tol_model)
    return settings, tol_model


def check_rules(s: OptimiseSettings, tolerance: ToleranceModel) -> None:
    """Refuse resolved settings that break a rule between fields, which the declaration
    (:class:`gearmesh.settings.Optimise`) cannot state, naming the config's field; checked in a
    fixed order, so of several the same one is named first.

    Parameters
    ----------
    s : OptimiseSettings
        The run settings (pinion torques, N m).
    tolerance : ToleranceModel
        The manufactured population's deviation model (a tolerance statistic needs a deviation).

    Raises
    ------
    GearmeshInputError
        The first rule broken: the load spectrum (distinct torques holding the design torque,
        one time share each for the mean), the tolerance statistic (a cvar level below 100 %,
        samples and deviations to take it over), the objective against the method and the load
        points, the elitism below the population, the load-window grid, NSGA-II's objectives.
    """
    _check_spectrum(s)
    check_statistic(s.tolerance_statistic, s.tolerance_level, "tolerance_statistic")  # cvar below 100 %
    if s.tolerance_statistic is not None and s.tolerance_samples == 0:
        raise GearmeshInputError("tolerance_statistic", s.tolerance_statistic, "needs tolerance samples "
                                 "(tolerance_samples > 0 and tolerances that deviate); null: the nominal alone")
    if s.objective == "robust" and len(s.torques) < 2 and s.tolerance_statistic is None:
        raise GearmeshInputError("objective", s.objective, "needs a load spectrum (two or more torques_Nm) or tolerance "
                                                           "samples with a tolerance_statistic; use 'force' for one point")
    if s.method == "nsga2" and s.objective not in ("force", "robust"):
        raise GearmeshInputError("objective", s.objective, "must be 'force' with method nsga2 (F_s against LTE p-p)")
    if s.keep_elitism > s.population - 1:
        raise GearmeshInputError("keep_elitism", s.keep_elitism, f"must be an integer in [0, {s.population - 1}]")
    spacing = np.diff(sorted(s.torques))
    if spacing.size and s.load_window_step >= spacing.min():
        raise GearmeshInputError("load_window_step_Nm", s.load_window_step, "must be finer than the spacing of "
                                                                            f"torques_Nm ({spacing.min():g} N m)")
    if s.load_window_top / s.load_window_step > MAX_WINDOW_TORQUES:
        raise GearmeshInputError("load_window_step_Nm", s.load_window_step,
                                 f"gives more than {MAX_WINDOW_TORQUES} window torques")
    if s.pareto_objectives[0] != "impact":
        raise GearmeshInputError("pareto_objectives", list(s.pareto_objectives), "must start with 'impact' (the "
                                 "objective J, whose least value on the front is the optimum)")
    if s.method != "nsga2" and s.pareto_objectives != ("impact", "lte"):
        raise GearmeshInputError("pareto_objectives", list(s.pareto_objectives), "apply to method nsga2 only")
    if s.tolerance_statistic is not None and not tolerance.dimensions:
        raise GearmeshInputError("tolerance_statistic", s.tolerance_statistic,
                                 "needs tolerances (tolerances.grade or tolerances.modification): nothing deviates")


def _check_spectrum(s: OptimiseSettings) -> None:
    """The load spectrum: distinct torques, the design torque one of them; time shares one per
    torque, not all zero, for the duty-cycle mean only."""
    if len(set(s.torques)) != len(s.torques):
        raise GearmeshInputError("torques_Nm", list(s.torques), "must not repeat a torque")
    if not same_point(s.torques, s.torque).any():
        raise GearmeshInputError("torque_Nm", s.torque, f"must be one of torques_Nm {list(s.torques)} (the design "
                                                        "torque of the load spectrum)")
    if s.weights is None:
        return
    if len(s.weights) != len(s.torques):
        raise GearmeshInputError("weights", list(s.weights), f"must be a list of {len(s.torques)} numbers, one per "
                                                             "torque")
    if sum(s.weights) <= 0:
        raise GearmeshInputError("weights", list(s.weights), "must not all be zero")
    if s.statistic != "mean":
        raise GearmeshInputError("weights", list(s.weights), "apply to statistic 'mean' only (the duty-cycle mean)")

