"""The checks of a dynamics or train study section before any job runs: every setting against its
declaration, and the work of the sweep (RK4 steps, contact-table size) against the limits.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from ...dynamics import require_dynamics_data, train_model
from ...errors import GearmeshInputError
from ...gear import GearPair, pair_geometry
from ...limits import MAX_SPEED_STEPS, MAX_TRAIN_SPEEDS, check_speeds, positive_values
from ...stiffness import mesh_stiffness
from ...schema import check_value, defaults
from ...settings import Dynamics, TrainDynamics
from .inputs import (_DECLARED, _SOLVER_KEYS, _TABLE_KEYS, _backlash, _bearing, _solver, _table_settings,
                     positive_torque, speed_grid)
from .pair import build_pair_model

#: Coarse slice grid of the stiffness used only to estimate the step size (ω_max) up front.
_ESTIMATE_SLICES, _ESTIMATE_POSITIONS = 16, 24


def check_dynamics_settings(pair: GearPair, settings: Mapping[str, Any], train: bool = False,
                            excitation_points: int | None = None) -> None:
    """Check every setting of :func:`dynamics_dataset` (or :func:`train_dataset` with
    ``train``) for ``pair`` without simulating, and refuse a sweep whose work exceeds
    :data:`MAX_SPEED_STEPS` or a contact table larger than :data:`MAX_TABLE_POINTS`.

    The model is built on a coarse slice stiffness at each torque (the step size depends on the
    maximum stiffness only; an LTCA or contact excitation is of the same order), then
    :func:`gearmesh.dynamics.step_plan` gives the steps per speed (and refuses > 2e6) of the
    physical-time transient, the bound of a sweep whose shooting does not converge.
    ``excitation_points``: samples of k(t) over a mesh cycle the job will get (the stiffness
    or LTCA positions); a Fourier form needs more than twice its order. GearmeshInputError
    names the setting (as in the config section).
    """
    from ...dynamics import step_plan

    section = TrainDynamics if train else Dynamics
    s = {**defaults(section), **settings}  # the declared defaults of what is not given
    for key, value in settings.items():
        if key in _DECLARED[section]:
            check_value(section, key, value)
    solver = _solver(*(s[k] for k in _SOLVER_KEYS))
    order = s["fourier_order"]
    excitation = s["excitation"]
    if excitation == "contact":
        _table_settings(**{k: s[k] for k in _TABLE_KEYS})
    if s["stiffness_form"] == "fourier" and excitation != "contact":
        _check_fourier_samples(order, excitation_points, s)
    coarse = max(_ESTIMATE_POSITIONS, 2 * order + 2)
    speeds, models = (_train_estimate(pair, s, coarse) if train else _pair_estimate(pair, s, coarse))
    steps = 0
    for model in models:
        _, m, n_tr, _ = step_plan(model, speeds, solver)
        steps = max(steps, int(((n_tr + solver.record_cycles) * m).max()))
    if steps * speeds.size * len(models) > MAX_SPEED_STEPS:
        raise GearmeshInputError("speeds_rpm", s["speeds_rpm"],
                                 f"needs {len(models)} torques × {speeds.size} speeds × {steps} RK4 steps = "
                                 f"{steps * speeds.size * len(models):.3g} speed-steps; at most {MAX_SPEED_STEPS:.0e} "
                                 "(fewer or faster speeds)")


def _check_fourier_samples(order: int, excitation_points: int | None, s: Mapping[str, Any]) -> None:
    """Refuse a Fourier form of ``order`` without more than 2·order samples over a mesh cycle of
    the excitation k(t) (``excitation_points``) or of the tabulated TE."""
    for what, points in (("the excitation k(t)", excitation_points),
                         ("transmission_error_um", len(s.get("transmission_error_um") or []) or None)):
        if points is not None and not 2 * order < points:
            raise GearmeshInputError("fourier_order", order, f"needs more than {2 * order} samples of {what} "
                                     f"over a mesh cycle; it has {points}")


def _pair_estimate(pair: GearPair, s: Mapping[str, Any], coarse: int) -> tuple[np.ndarray, list]:
    """The speeds of a pair sweep (its grid and sample speeds checked) and one model per torque
    on the coarse slice stiffness (``coarse`` positions): what its work estimate needs."""
    import inspect

    speeds = speed_grid(s["speeds_rpm"])
    check_speeds(pair_geometry(pair), speeds, "speeds_rpm")
    try:
        samples = speed_grid(list(s["sample_speeds_rpm"]) or 1.0)
    except GearmeshInputError as exc:
        raise GearmeshInputError("sample_speeds_rpm", exc.value, exc.rule) from None
    check_speeds(pair_geometry(pair), samples, "sample_speeds_rpm")
    known = set(inspect.signature(build_pair_model).parameters) - {"pair", "stiffness", "ltca", "table",
                                                                   "torque_Nm", "excitation"}
    excitation = s["excitation"]
    models = [build_pair_model(pair, float(t), **{k: v for k, v in s.items() if k in known},
                               excitation="tvms" if excitation in ("ltca", "contact") else excitation,
                               slices=_ESTIMATE_SLICES, positions=coarse)
              for t in positive_values(s["torques_Nm"], "torques_Nm", "N m")]
    return speeds, models


def _train_estimate(pair: GearPair, s: Mapping[str, Any], coarse: int) -> tuple[np.ndarray, list]:
    """The speeds of a train run (checked, at most :data:`MAX_TRAIN_SPEEDS`) and its model on the
    coarse slice stiffness (``coarse`` positions): what its work estimate needs."""
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    if s["speeds_rpm"] is None:
        speeds = np.array([positive_torque("mesh_frequency_Hz", s["mesh_frequency_Hz"]) * 60.0 / pair.teeth[1]])
    else:
        speeds = speed_grid(s["speeds_rpm"])
    check_speeds(geom, speeds, "speeds_rpm", on="gear")
    if s["torque_Nm"] is not None:
        torque = positive_torque("torque_Nm", s["torque_Nm"])
    else:
        torque = positive_torque("static_force_N", s["static_force_N"]) \
            * float(geom.base_radius[1]) * math.cos(geom.base_helix_angle)
    if speeds.size > MAX_TRAIN_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{speeds.size} speeds",
                                 f"at most {MAX_TRAIN_SPEEDS} for the train (series are kept)")
    K = mesh_stiffness(geom, n_positions=coarse, n_slices=_ESTIMATE_SLICES, components=False).K
    bearing = _bearing(*(s[f"bearing_{key}_{unit}"] for key, unit in (
        ("k_radial", "N_per_m"), ("k_axial", "N_per_m"), ("c_radial", "Ns_per_m"), ("c_axial", "Ns_per_m"))))
    excitation = s["excitation"]
    return speeds, [train_model(geom, torque, K, bearing=bearing, damping_ratio=s["damping_ratio"],
                                backlash=_backlash(geom, s["backlash_um"]), stiffness_form=s["stiffness_form"],
                                order=s["fourier_order"],
                                excitation="tvms" if excitation in (None, "contact") else excitation,
                                phase_offsets=tuple(s["phase_offsets_cycles"]),
                                mesh_damping=s["mesh_damping_Ns_per_m"])]
