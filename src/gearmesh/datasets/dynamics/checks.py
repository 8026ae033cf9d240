"""The checks of a dynamics or train study section before any job runs: every setting against its
declaration, and the work of the sweep (RK4 steps, contact-table size) against the limits.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Mapping

import numpy as np

from ...dynamics import require_dynamics_data, train_model
from ...errors import GearmeshInputError
from ...gear import GearPair, pair_geometry
from ...limits import MAX_SPEED_STEPS, MAX_TRAIN_SPEEDS, check_speeds, positive_values
from ...stiffness import mesh_stiffness
from ...schema import jsonable, settings_object
from ...settings import Dynamics, TrainDynamics
from .excitation import resolve_excitation
from .inputs import (_backlash, _bearing, _solver, _table_settings, positive_quantity, settings_speeds, speed_grid,
                     table_keywords)
from .pair import pair_model_of

#: Coarse slice grid of the stiffness used only to estimate the step size (ω_max) up front.
_ESTIMATE_SLICES, _ESTIMATE_POSITIONS = 16, 24
#: The tooth model of that estimate, whatever the section's: the hob-fillet potential-energy
#: cantilever. The FE tooth (the default, :data:`gearmesh.choices.DEFAULT_TOOTH_METHOD`) costs two
#: plane-strain solves per pair, 0.8 s of the default study's 1.9 s of checks before any job runs
#: (measured), for a number the estimate needs only to its order: the step follows the highest mode,
#: ∝ √k, and the cantilever is 10–50 % more compliant than the FE tooth (docs/validation.md), so the
#: estimated steps are 0–20 % fewer (0.07 % on the default pair, 7 % on low-fluctuation pair 1,
#: measured), within the precision of the limit itself (:data:`gearmesh.limits.MAX_SPEED_STEPS`,
#: "a few minutes" of work).
_ESTIMATE_METHOD = "transition"


def check_dynamics_settings(pair: GearPair, settings: Mapping[str, Any] | Dynamics | TrainDynamics,
                            train: bool = False, excitation_points: int | None = None) -> None:
    """Check every setting of :func:`dynamics_dataset` (or :func:`train_dataset` with
    ``train``; ``settings`` its section, or the section already parsed,
    :func:`gearmesh.schema.settings_object`) for ``pair`` without simulating, and refuse a sweep whose work exceeds
    :data:`MAX_SPEED_STEPS` or a contact table larger than :data:`MAX_TABLE_POINTS`.

    The model is built on a coarse slice stiffness (:data:`_ESTIMATE_METHOD`) at each torque (the
    step size depends on the maximum stiffness only; an LTCA or contact excitation is of the same
    order), then :func:`gearmesh.dynamics.step_plan` gives the steps per speed (and refuses > 2e6)
    of the physical-time transient, the bound of a sweep whose shooting does not converge.
    ``excitation_points``: samples of k(t) over a mesh cycle the job will get (the stiffness
    or LTCA positions); a Fourier form needs more than twice its order. GearmeshInputError
    names the setting (as in the config section).

    Parameters
    ----------
    pair : GearPair
        The pair the section runs on.
    settings : Mapping or Dynamics or TrainDynamics
        The ``dynamics`` (or ``train_dynamics``) section, engineering units, or the section parsed.
    train : bool, default False
        Check ``settings`` as a train section (:class:`gearmesh.settings.TrainDynamics`).
    excitation_points : int, optional
        Samples of k(t) per mesh cycle the job will get; None when not yet known.

    Raises
    ------
    GearmeshInputError
        Naming the first bad setting (``speeds_rpm``, ``sample_speeds_rpm``, ``torques_Nm``,
        ``fourier_order``, a table setting, ...), or ``speeds_rpm`` when the sweep's RK4 work is over
        :data:`MAX_SPEED_STEPS`.
    """
    from ...dynamics import step_plan

    if isinstance(settings, (Dynamics, TrainDynamics)):
        s = settings
    else:
        s = settings_object(TrainDynamics if train else Dynamics, settings)
    train = isinstance(s, TrainDynamics)
    order = s.fourier_order
    if s.excitation == "contact":
        _table_settings(s.contact_model(), **table_keywords(s))
    if s.stiffness_form == "fourier" and s.excitation != "contact":
        _check_fourier_samples(order, excitation_points, getattr(s, "transmission_error_um", None))
    coarse = max(_ESTIMATE_POSITIONS, 2 * order + 2)
    speeds, models = (_train_estimate(pair, s, coarse) if train else _pair_estimate(pair, s, coarse))
    steps = 0
    solver = _solver(s)
    for model in models:
        _, m, n_tr, _ = step_plan(model, speeds, solver)
        steps = max(steps, int(((n_tr + solver.record_cycles) * m).max()))
    if steps * speeds.size * len(models) > MAX_SPEED_STEPS:
        raise GearmeshInputError("speeds_rpm", jsonable(s.speeds_rpm),
                                 f"needs {len(models)} torques × {speeds.size} speeds × {steps} RK4 steps = "
                                 f"{steps * speeds.size * len(models):.3g} speed-steps; at most {MAX_SPEED_STEPS:.0e} "
                                 "(fewer or faster speeds)")


def _check_fourier_samples(order: int, excitation_points: int | None, transmission_error_um) -> None:
    """Refuse a Fourier form of ``order`` without more than 2·order samples over a mesh cycle of
    the excitation k(t) (``excitation_points``) or of the tabulated TE."""
    for what, points in (("the excitation k(t)", excitation_points),
                         ("transmission_error_um", len(transmission_error_um or ()) or None)):
        if points is not None and not 2 * order < points:
            raise GearmeshInputError("fourier_order", order, f"needs more than {2 * order} samples of {what} "
                                     f"over a mesh cycle; it has {points}")


def _pair_estimate(pair: GearPair, s: Dynamics, coarse: int) -> tuple[np.ndarray, list]:
    """The speeds of a pair sweep (its grid and sample speeds checked) and one model per torque
    on the coarse slice stiffness (``coarse`` positions): what its work estimate needs."""
    speeds = settings_speeds(s.speeds_rpm)
    check_speeds(pair_geometry(pair), speeds, "speeds_rpm")
    try:
        samples = speed_grid(list(s.sample_speeds_rpm) or 1.0)
    except GearmeshInputError as exc:
        raise GearmeshInputError("sample_speeds_rpm", exc.value, exc.rule) from None
    check_speeds(pair_geometry(pair), samples, "sample_speeds_rpm")
    excitation = "tvms" if s.excitation in ("ltca", "contact") else resolve_excitation(s.excitation, None)
    estimate = dataclasses.replace(s, method=_ESTIMATE_METHOD)
    models = [pair_model_of(pair, float(t), estimate, excitation, (_ESTIMATE_SLICES, coarse))
              for t in positive_values(s.torques_Nm, "torques_Nm", "N m")]
    return speeds, models


def _train_estimate(pair: GearPair, s: TrainDynamics, coarse: int) -> tuple[np.ndarray, list]:
    """The speeds of a train run (checked, at most :data:`MAX_TRAIN_SPEEDS`) and its model on the
    coarse slice stiffness (``coarse`` positions): what its work estimate needs."""
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    if s.speeds_rpm is None:
        speeds = np.array([positive_quantity("mesh_frequency_Hz", s.mesh_frequency_Hz) * 60.0 / pair.teeth[1]])
    else:
        speeds = settings_speeds(s.speeds_rpm)
    check_speeds(geom, speeds, "speeds_rpm", on="gear")
    if s.torque_Nm is not None:
        torque = positive_quantity("torque_Nm", s.torque_Nm)
    else:
        torque = positive_quantity("static_force_N", s.static_force_N) \
            * float(geom.base_radius[1]) * math.cos(geom.base_helix_angle)
    if speeds.size > MAX_TRAIN_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{speeds.size} speeds",
                                 f"at most {MAX_TRAIN_SPEEDS} for the train (series are kept)")
    K = mesh_stiffness(geom, n_positions=coarse, n_slices=_ESTIMATE_SLICES, method=_ESTIMATE_METHOD,
                       components=False).K
    bearing = _bearing(s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m, s.bearing_c_radial_Ns_per_m,
                       s.bearing_c_axial_Ns_per_m)
    return speeds, [train_model(geom, torque, K, bearing=bearing, damping_ratio=s.damping_ratio,
                                backlash=_backlash(geom, s.backlash_um), stiffness_form=s.stiffness_form,
                                order=s.fourier_order,
                                excitation="tvms" if s.excitation in (None, "contact") else s.excitation,
                                phase_offsets=tuple(s.phase_offsets_cycles),
                                mesh_damping=s.mesh_damping_Ns_per_m)]
