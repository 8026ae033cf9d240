"""What an evaluation of candidates is: the optimisation :class:`Problem`, an :class:`Evaluation` of
C candidates, and the objective quantity per micro-geometry and torque (:func:`impact_values`,
:data:`OBJECTIVE_VALUES`) with its load-spectrum statistic (:func:`load_statistic`).

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..gear import PairGeometry
from ..dynamics.population import PopulationDynamics, dynamic_factors
from ..impact.criteria import LTCACriteria
from ..impact.energy import impact_response
from ..impact.model import ImpactModel
from ..impact.static import impact_static
from ..robust import BoxWorst
from ..tolerance import ToleranceModel
from .checks import OptimiseSettings
from .genes import Gene, decode

#: A failed candidate's objective, in units of the standard gear's.
FAILURE_FACTOR = 10.0


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
    """F_s, |v_n| and scenario of parameter sets at pinion ``torques`` and the settings' speed: one batch of the impact model.

    Parameters
    ----------
    model : ImpactModel
        The prepared impact model (:func:`gearmesh.impact.impact_model`).
    settings : OptimiseSettings
        Its ``speed_rpm`` (rpm) and ``energy_velocity``.
    params : numpy.ndarray
        (N, 2, 6) modification parameters (m).
    lead : numpy.ndarray
        (N, 2) lead slopes [pinion, gear] (m over the face width).
    torques : array_like
        (T,) pinion torques (N m).

    Returns
    -------
    ImpactValues
        (N, T) ``force`` F_s closed form and ``force_energy_balance`` (N), ``velocity`` |v_n| (m/s), ``scenario``.
    """
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
    """The load-spectrum statistic over the last axis (torques).

    Parameters
    ----------
    values : numpy.ndarray
        (..., T) values at the spectrum torques (any unit).
    statistic : {'max', 'mean'}
        The largest value, or the duty-cycle mean.
    weights : array_like or None
        (T,) time shares of the torques for 'mean' (equal shares without).

    Returns
    -------
    numpy.ndarray
        (...) the statistic (the unit of ``values``).
    """
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
