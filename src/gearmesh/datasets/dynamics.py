"""Dynamics-stage datasets: the speed sweep of the 8-DOF pair (the low-fluctuation paper §4–5) and the 9-DOF
plate–blanket–impression train (the improved potential-energy paper), from :mod:`gearmesh.dynamics`.

Engineering units at the boundary (rpm, N·m, µm, N·s/m), SI inside and in the datasets. Every
variable has ``units`` and ``long_name``. Statistics are over the steady-state record window
(whole mesh periods, :func:`gearmesh.dynamics.simulate`): ``*_rms`` is sqrt(mean(x²)) with the
mean included (as the low-fluctuation paper's RMS), ``*_std`` the fluctuation about the mean.
"""

from __future__ import annotations

import logging
import math
from typing import Any, Mapping, Sequence, get_args

import numpy as np
import xarray as xr

from ..body import describe_body
from ..dynamics import (
    DAMPING_MEANING,
    DEFAULT_DAMPING_RATIO,
    FIRST_PART_AFTER_A,
    LOW_FLUCTUATION_BEARING,
    TRAIN_GEARS,
    GearModel,
    full_translations,
    SolverSettings,
    SweepResult,
    pair_model,
    require_dynamics_data,
    mesh_energy_fraction,
    resonance_band,
    resonance_speeds,
    simulate,
    train_model,
)
from ..errors import GearmeshInputError
from . import one_pair, variant_names
from ..fe_tables import use_fe_tables
from ..gear import GearPair, PairGeometry, pair_geometry, pinion_torque
from ..io import name_force_lines, variable
from ..limits import (BEARING_STIFFNESS, MAX_SPEED_STEPS, same_point, MAX_SPEEDS, MAX_TABLE_POINTS, MAX_TRAIN_SPEEDS,
                      check_slice_grid, check_speeds, positive_values)
from ..loads import check_load, check_loads
from ..ltca import contact_tangent_compliance, with_loaded_extension
from ..deflection import mesh_misalignment
from ..deviation import with_misalignment
from ..meshforce import (DEFAULT_TABLE_APPROACHES, DEFAULT_TABLE_POINTS, DEFAULT_TABLE_POSITIONS, MeshForceTable,
                         table_layout, tabulate)
from ..tca import pair_lead_slope
from ..stiffness import DEFAULT_SLICES, mesh_stiffness
from ..schema import check_arguments, check_value, defaults, settings_fields
from ..choices import DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD, IMPACT_INDEX, pair_excitation
from ..settings import Dynamics, DynamicsComparison, PairExcitation, SteadyState, TrainDynamics

DEFAULT_SPEEDS = {"start": 500, "stop": 50000, "step": 100}
#: The improved potential-energy paper: mesh frequency 249.4 Hz of the 88-tooth gears -> 249.4·60/88 rpm.
PRINTING_TRAIN_MESH_FREQUENCY_HZ = 249.4
PRINTING_TRAIN_STATIC_FORCE_N = 2832.0


# --------------------------------------------------------------------------------------
# Boundary checks and conversions
# --------------------------------------------------------------------------------------


def parse_speeds(text: str) -> dict[str, float] | list[float]:
    """'START:STOP:STEP' (rpm) as {start, stop, step}, or 'SPEED' as [speed]: the forms of a
    study's ``speeds_rpm`` (GearmeshInputError naming ``speeds_rpm``)."""
    try:
        values = [float(p) for p in text.split(":")]
    except ValueError:
        raise GearmeshInputError("speeds_rpm", text, "must be START:STOP:STEP numbers") from None
    if len(values) == 1:
        return values
    if len(values) == 3:
        return dict(zip(("start", "stop", "step"), values))
    raise GearmeshInputError("speeds_rpm", text, "must be START:STOP:STEP or one speed")


def speed_grid(speeds: Mapping[str, float] | Sequence[float] | str | float) -> np.ndarray:
    """Speeds (rpm) from {start, stop, step} (stop included), a list, 'START:STOP:STEP' or one number.

    Refuses non-positive or non-finite speeds, stop < start, step <= 0 and more than
    :data:`MAX_SPEEDS` speeds (GearmeshInputError naming ``speeds_rpm``).
    """
    if isinstance(speeds, str):
        speeds = parse_speeds(speeds)
    if isinstance(speeds, Mapping):
        unknown = sorted(set(speeds) - {"start", "stop", "step"})
        if unknown:
            raise GearmeshInputError(f"speeds_rpm.{unknown[0]}", speeds[unknown[0]], "unknown key (start, stop, step)")
        try:
            start, stop, step = (float(speeds[k]) for k in ("start", "stop", "step"))
        except KeyError as exc:
            raise GearmeshInputError(f"speeds_rpm.{exc.args[0]}", None, "is required") from None
        except (TypeError, ValueError):
            raise GearmeshInputError("speeds_rpm", dict(speeds), "start, stop, step must be numbers") from None
        if not all(map(math.isfinite, (start, stop, step))):
            raise GearmeshInputError("speeds_rpm", dict(speeds), "start, stop, step must be finite")
        if start <= 0:
            raise GearmeshInputError("speeds_rpm.start", start, "must be positive")
        if step <= 0:
            raise GearmeshInputError("speeds_rpm.step", step, "must be positive")
        if stop < start:
            raise GearmeshInputError("speeds_rpm.stop", stop, f"must not be below start ({start})")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        if count > MAX_SPEEDS:
            raise GearmeshInputError("speeds_rpm", dict(speeds), f"gives {count} speeds; at most {MAX_SPEEDS}")
        return start + step * np.arange(count)
    arr = np.atleast_1d(np.asarray(speeds, dtype=float)) if not isinstance(speeds, (bool,)) else None
    if arr is None or arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise GearmeshInputError("speeds_rpm", speeds, "must be positive finite speeds")
    if arr.size > MAX_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{arr.size} speeds", f"at most {MAX_SPEEDS}")
    return arr


def positive_torque(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise GearmeshInputError(name, value, "must be a positive finite number (N m)")
    return float(value)


def _bearing(k_radial_N_per_m, k_axial_N_per_m, c_radial_Ns_per_m, c_axial_Ns_per_m) -> dict[str, float]:
    """The model's ``bearing`` overrides: a stiffness ``'pair'`` is the pair file's supports (left out)."""
    out = {}
    for key, name, v, positive in (("k_radial", "bearing_k_radial_N_per_m", k_radial_N_per_m, True),
                                   ("k_axial", "bearing_k_axial_N_per_m", k_axial_N_per_m, True),
                                   ("c_radial", "bearing_c_radial_Ns_per_m", c_radial_Ns_per_m, False),
                                   ("c_axial", "bearing_c_axial_Ns_per_m", c_axial_Ns_per_m, False)):
        if positive and v == "pair":
            continue
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0 \
                or (positive and v == 0):
            raise GearmeshInputError(name, v, "must be a positive finite number" if positive
                                     else "must be a non-negative finite number")
        if positive:  # a stiffness: within what bearings have, in the key's N/m
            BEARING_STIFFNESS.check(v, name, "N/m")
        out[key] = float(v)
    return out


def supports_note(pair: GearPair, bearing_k_radial_N_per_m="pair", bearing_k_axial_N_per_m="pair") -> str:
    """The supports a dynamics result used, one sentence (dataset attrs, CLI JSON)."""
    own = pair.supports.describe(pair.material.youngs_modulus)
    if bearing_k_radial_N_per_m == "pair" and bearing_k_axial_N_per_m == "pair":
        return own
    return (f"supports set by the study (both gears): radial {bearing_k_radial_N_per_m} N/m, axial "
            f"{bearing_k_axial_N_per_m} N/m, 'pair' meaning the pair file's: {own}")


#: The declared defaults of the dynamics settings (:class:`gearmesh.settings.Dynamics`).
_DEFAULTS = defaults(Dynamics)
#: The keys each settings class declares.
_DECLARED = {cls: {f.name for f in settings_fields(cls)} for cls in (Dynamics, TrainDynamics)}
#: Solver rules of the settings (:class:`gearmesh.dynamics.SolverSettings`), with their defaults.
_SOLVER_KEYS = {k: _DEFAULTS[k] for k in ("courant", "steps_per_cycle_min", "transient_tau", "record_cycles",
                                          "steady_state")}


def _solver(courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state="shooting") -> SolverSettings:
    """The solver rules as :class:`gearmesh.dynamics.SolverSettings`, each checked against its
    declaration (:class:`gearmesh.settings.Dynamics`: the bounds the study schema has)."""
    given = dict(zip(_SOLVER_KEYS, (courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state)))
    for key, value in given.items():
        check_value(Dynamics, key, value)
    return SolverSettings(courant=float(courant), steps_per_cycle_min=steps_per_cycle_min,
                          transient_tau=float(transient_tau), record_cycles=record_cycles, steady_state=steady_state)


#: How each speed reaches its steady state (:class:`gearmesh.dynamics.SolverSettings`).
STEADY_STATES = get_args(SteadyState)
#: Excitations of the pair model; None (the default) is 'ltca' when an LTCA dataset is given, else 'tvms'.
PAIR_EXCITATIONS = get_args(PairExcitation)


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
    import inspect

    from ..dynamics import step_plan

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
        for what, points in (("the excitation k(t)", excitation_points),
                             ("transmission_error_um", len(s.get("transmission_error_um") or []) or None)):
            if points is not None and not 2 * order < points:
                raise GearmeshInputError("fourier_order", order, f"needs more than {2 * order} samples of {what} "
                                         f"over a mesh cycle; it has {points}")
    coarse = max(_ESTIMATE_POSITIONS, 2 * order + 2)
    if not train:
        speeds = speed_grid(s["speeds_rpm"])
        check_speeds(pair_geometry(pair), speeds, "speeds_rpm")
        try:
            samples = speed_grid(list(s["sample_speeds_rpm"]) or 1.0)
        except GearmeshInputError as exc:
            raise GearmeshInputError("sample_speeds_rpm", exc.value, exc.rule) from None
        check_speeds(pair_geometry(pair), samples, "sample_speeds_rpm")
        known = set(inspect.signature(build_pair_model).parameters) - {"pair", "stiffness", "ltca", "table",
                                                                       "torque_Nm", "excitation"}
        models = [build_pair_model(pair, float(t), **{k: v for k, v in s.items() if k in known},
                                   excitation="tvms" if excitation in ("ltca", "contact") else excitation,
                                   slices=_ESTIMATE_SLICES, positions=coarse)
                  for t in positive_values(s["torques_Nm"], "torques_Nm", "N m")]
    else:
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
        models = [train_model(geom, torque, K, bearing=bearing, damping_ratio=s["damping_ratio"],
                              backlash=_backlash(geom, s["backlash_um"]), stiffness_form=s["stiffness_form"],
                              order=order, excitation="tvms" if excitation in (None, "contact") else excitation,
                              phase_offsets=tuple(s["phase_offsets_cycles"]), mesh_damping=s["mesh_damping_Ns_per_m"])]
    steps = 0
    for model in models:
        _, m, n_tr, _ = step_plan(model, speeds, solver)
        steps = max(steps, int(((n_tr + solver.record_cycles) * m).max()))
    if steps * speeds.size * len(models) > MAX_SPEED_STEPS:
        raise GearmeshInputError("speeds_rpm", s["speeds_rpm"],
                                 f"needs {len(models)} torques × {speeds.size} speeds × {steps} RK4 steps = "
                                 f"{steps * speeds.size * len(models):.3g} speed-steps; at most {MAX_SPEED_STEPS:.0e} "
                                 "(fewer or faster speeds)")


def _stiffness_curve(geom: PairGeometry, stiffness: xr.Dataset | None, method: str, slices: int,
                     positions: int, pinion_torque: float) -> np.ndarray:
    """Transverse TVMS K (N/m) at evenly spaced rolls over one base pitch: from the upstream
    stiffness dataset (``mesh_stiffness`` on ``position``; its contact term at its own torque) or
    computed here with the contact law's tangent at ``pinion_torque`` (N·m)."""
    if stiffness is not None:
        if "mesh_stiffness" not in stiffness:
            raise GearmeshInputError("stiffness", "dataset", "has no 'mesh_stiffness' variable")
        return np.asarray(stiffness["mesh_stiffness"].values, dtype=float)
    return mesh_stiffness(geom, n_positions=positions, n_slices=slices, method=method, components=False,
                          contact_compliance=contact_tangent_compliance(geom, pinion_torque)).K


def _transmission_error(transmission_error_um) -> np.ndarray | None:
    """A tabulated unloaded TE (µm, transverse, evenly over one mesh cycle) in m."""
    if transmission_error_um is None:
        return None
    te = np.asarray(transmission_error_um, dtype=float)
    if te.ndim != 1 or te.size < 2 or not np.all(np.isfinite(te)):
        raise GearmeshInputError("transmission_error_um", transmission_error_um,
                                 "must be a list of >= 2 finite values (µm) over one mesh cycle")
    return te * 1e-6


def ltca_excitation(geom: PairGeometry, ltca: xr.Dataset, pinion_torque: float) -> tuple[np.ndarray, np.ndarray]:
    """Mesh stiffness and equivalent error (both transverse, over one mesh cycle) from the LTCA.

    At the LTCA torque equal to ``pinion_torque`` (N m): k(t) = the loaded tangent mesh
    stiffness k_L and e(t) = LTE(t) − F/k_L(t), F = T1/r_b1, so that the static solution of
    F = k(δ − e) is δ = LTE: the quasi-static excitation of Velex & Ajmi (2006, J. Sound Vib.
    290:882) built from the loaded TE. Micro-geometry, edge contact and the nonlinear contact
    law thus enter the dynamics through the LTCA of each variant.
    """
    torques = np.asarray(ltca["torque"].values, dtype=float)
    match = np.flatnonzero(same_point(torques, pinion_torque))
    if not match.size:
        raise GearmeshInputError("ltca.torques_Nm", torques.tolist(),
                                 f"must include the dynamics torque ({pinion_torque:.6g} N m on the pinion)")
    k_l = np.asarray(ltca["loaded_mesh_stiffness"].values[match[0]], dtype=float)
    lte = np.asarray(ltca["lte"].values[match[0]], dtype=float)
    force = pinion_torque / float(geom.base_radius[0])
    return k_l, lte - force / k_l


# --------------------------------------------------------------------------------------
# Time series and spectra of chosen speeds
# --------------------------------------------------------------------------------------


def _series_arrays(res: SweepResult, points_per_cycle: int, max_order: int, n_rec: int):
    """Resample each speed's record window on ``points_per_cycle`` points per mesh period;
    amplitude spectra (one-sided, FFT of the full-resolution periodic window) up to
    ``max_order`` mesh orders; peak-to-peak of y, ẏ and ÿ (central differences)."""
    S = res.speed_rpm.size
    n_s = n_rec * points_per_cycle
    n_o = max_order * n_rec + 1
    out = {k: [] for k in ("t", "delta", "F", "Fe", "y", "v", "F_spec", "delta_spec", "y_pp", "v_pp", "a_pp")}
    for s in range(S):
        st = res.series[s]
        t = st["t"]
        T = n_rec / res.mesh_frequency[s]
        tg = np.arange(n_s) * (T / n_s)
        out["t"].append(tg)
        for key in ("delta", "F", "Fe", "y", "v"):
            arr = st[key]
            out[key].append(np.stack([np.interp(tg, t, arr[:, j], period=T) for j in range(arr.shape[1])], axis=1))
        N = t.size
        for key in ("F", "delta"):
            X = np.fft.rfft(st[key], axis=0) / N
            amp = np.abs(X[:n_o])
            amp[1:] *= 2.0
            out[f"{key}_spec"].append(amp)
        dt = float(res.dt[s])
        acc = (np.roll(st["v"], -1, axis=0) - np.roll(st["v"], 1, axis=0)) / (2 * dt)
        out["y_pp"].append(np.ptp(st["y"], axis=0))
        out["v_pp"].append(np.ptp(st["v"], axis=0))
        out["a_pp"].append(np.ptp(acc, axis=0))
    return {k: np.stack(v) for k, v in out.items()}


def excitation_used(excitation: str, ltca: xr.Dataset | None = None, transmission_error_um=None,
                    table: MeshForceTable | None = None) -> str:
    """What excited the model, for the ``excitation`` attribute of the dataset."""
    if excitation == "contact":
        return ("contact: the mesh force of the real tooth contact F(x, w) of every tooth pair (flanks and tip edges, "
                f"modifications and lead slopes; gearmesh.meshforce, {table.positions} positions x "
                f"{table.approach.size} approaches per mesh cycle)" if table is not None else "contact")
    if excitation == "ltca":
        return ("ltca: loaded mesh stiffness k_L(t) and equivalent error e = LTE - F/k_L of the variant's "
                f"LTCA ({ltca.attrs.get('contact_law', 'palmgren') if ltca is not None else 'palmgren'} contact)")
    if excitation == "lste":
        return "lste: slice-model stiffness K(t) and the low-fluctuation paper's error e = F/K(t)"
    te = " and the tabulated unloaded TE" if transmission_error_um is not None else " (unloaded TE zero)"
    return f"tvms: slice-model stiffness K(t){te}"


def model_choices(excitation: str, method: str, contact_law: str, stiffness: xr.Dataset | None = None,
                  ltca: xr.Dataset | None = None) -> dict[str, str]:
    """The tooth model and contact law behind a dynamics result (its ``tooth_model`` and
    ``contact_law`` attributes): the given stiffness dataset's tooth model or ``method`` for
    ``tvms``/``lste``; the LTCA's for ``ltca``; ``method`` and ``contact_law`` of the tabulated
    contact for ``contact``."""
    if excitation == "ltca" and ltca is not None:
        return {"tooth_model": str(ltca.attrs.get("tooth_model", method)),
                "contact_law": str(ltca.attrs.get("contact_law", contact_law))}
    if excitation == "contact":
        return {"tooth_model": method, "contact_law": contact_law}
    return {"tooth_model": str(stiffness.attrs.get("tooth_model", method)) if stiffness is not None else method}


def resolve_excitation(excitation: str | None, ltca: xr.Dataset | None) -> str:
    """The excitation to run (:func:`gearmesh.choices.pair_excitation`): as given, or (None) 'ltca'
    when an LTCA dataset is at hand, else 'tvms'."""
    if excitation is not None and excitation not in PAIR_EXCITATIONS:
        raise GearmeshInputError("excitation", excitation, f"must be one of {list(PAIR_EXCITATIONS)} or null")
    return pair_excitation(excitation, ltca is not None)


def resonance_refined(grid: np.ndarray, model: GearModel, harmonics: Sequence[int] = (1, 2, 3)) -> np.ndarray:
    """``grid`` plus the speeds around every resonance speed inside it
    (:func:`gearmesh.dynamics.resonance_band`), so a peak is resolved rather than caught by two
    points of the grid. Sorted, unique; at most :data:`MAX_SPEEDS`."""
    extra = resonance_band(model, float(grid.min()), float(grid.max()), harmonics)
    out = np.unique(np.concatenate([grid, extra]))
    if out.size > MAX_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{out.size} speeds with the resonance points",
                                 f"at most {MAX_SPEEDS} (refine_resonances: false, or a coarser grid)")
    return out


def _log_progress(done: float) -> None:
    """Progress of a sweep into the job's log (the workflow's rule log)."""
    logging.info("speed sweep: %d %% of the RK4 steps", int(100 * done))


def _grid(ds: xr.Dataset) -> xr.Dataset:
    """The speeds of the configured grid (without the added resonance speeds), at the sweep's
    first torque."""
    ds = ds.isel(torque=0) if "torque" in ds.dims else ds
    return ds.isel(speed=ds["on_grid"].values.astype(bool)) if "on_grid" in ds else ds


# --------------------------------------------------------------------------------------
# 8-DOF pair sweep (the low-fluctuation paper)
# --------------------------------------------------------------------------------------

_PAIR_GEARS = ("pinion", "gear")
_PAIR_DIRS = ("x", "y", "z")


def _backlash(geom: PairGeometry, backlash_um) -> float | None:
    """Total backlash 2b0 (m) along the normal: 'pair' the pair's own (its centre distance and
    shifts), a number (µm), or None (no backlash: contact never lost)."""
    if backlash_um == "pair":
        return float(geom.backlash_normal)
    if backlash_um is not None and (isinstance(backlash_um, bool) or not isinstance(backlash_um, (int, float))
                                    or not math.isfinite(backlash_um) or backlash_um < 0):
        raise GearmeshInputError("backlash_um", backlash_um, "must be 'pair', a non-negative number (µm) or null (none)")
    return None if backlash_um is None else float(backlash_um) * 1e-6


#: Settings of the contact table (:func:`contact_table`), with their defaults.
_TABLE_KEYS = {k: _DEFAULTS[k] for k in ("contact_law", "points", "table_positions", "table_approaches",
                                         "table_force_factor")}


def _table_settings(**settings: Any) -> dict[str, Any]:
    """The contact-table settings (:data:`_TABLE_KEYS`; the declared defaults for those not
    given), each checked against its declaration, and their product against the work limit
    :data:`MAX_TABLE_POINTS` (GearmeshInputError naming the key)."""
    unknown = sorted(set(settings) - set(_TABLE_KEYS))
    if unknown:
        raise GearmeshInputError(unknown[0], settings[unknown[0]], f"is not a contact-table setting {list(_TABLE_KEYS)}")
    s = {**_TABLE_KEYS, **settings}
    for key, value in s.items():
        check_value(Dynamics, key, value)
    positions, approaches, points = s["table_positions"], s["table_approaches"], s["points"]
    if positions * approaches * points > MAX_TABLE_POINTS:
        raise GearmeshInputError("table_positions", positions, f"× table_approaches {approaches} × points {points} "
                                 f"must be at most {MAX_TABLE_POINTS:.0e} (the table's build time and memory)")
    return {"contact_law_name": s["contact_law"], "points": points, "positions": positions,
            "approaches": approaches, "factor": float(s["table_force_factor"])}


def contact_table(geom: PairGeometry, pinion_torques, method: str = DEFAULT_TOOTH_METHOD, **settings) -> MeshForceTable:
    """The mesh force table of ``geom`` (its micro-geometry and deviations) for the ``contact``
    excitation at the first of ``pinion_torques`` (N m): every row reaches ``table_force_factor``
    times the largest static force F_bt = T1/r_b1 of them, the separations carry the mesh
    misalignment of the first (:func:`contact_tables`); ``settings`` as :data:`_TABLE_KEYS`."""
    return contact_tables(geom, np.atleast_1d(pinion_torques)[:1], method, **settings)[0]


def contact_tables(geom: PairGeometry, pinion_torques, method: str = DEFAULT_TOOTH_METHOD,
                   **settings) -> list[MeshForceTable]:
    """One mesh force table per pinion torque of ``pinion_torques`` (N m) (:mod:`gearmesh.meshforce`):
    every row of each reaches ``table_force_factor`` times the largest static force F_bt of them;
    each table's separations carry the mesh misalignment at its own static force (the stated f_ma
    and the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`: the gearbox
    deflects with the mean load), so torques of one misalignment share one table."""
    t = _table_settings(**settings)
    rb1 = float(geom.base_radius[0])
    torques = np.atleast_1d(np.asarray(pinion_torques, dtype=float))
    force = t["factor"] * float(np.max(torques)) / rb1
    layout = table_layout(geom, t["positions"], t["points"], t["contact_law_name"], method)
    lead = pair_lead_slope(geom)
    built: dict[float, MeshForceTable] = {}
    for m in mesh_misalignment(geom, torques / rb1):
        if float(m) not in built:
            built[float(m)] = tabulate(layout, layout.gaps(lead_slope=with_misalignment(lead, float(m))), force,
                                       t["approaches"])
    return [built[float(m)] for m in mesh_misalignment(geom, torques / rb1)]


@check_arguments(Dynamics)
def build_pair_model(pair: GearPair, torque_Nm: float = 200.0, on: str = "pinion", backlash_um="pair",
                     bearing_k_radial_N_per_m: float | str = "pair",
                     bearing_k_axial_N_per_m: float | str = "pair",
                     bearing_c_radial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_radial"],
                     bearing_c_axial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_axial"],
                     damping_ratio: float = DEFAULT_DAMPING_RATIO, mesh_damping_Ns_per_m: float | None = None,
                     stiffness_form: str = "fourier", fourier_order: int = 3, excitation: str | None = None,
                     method: str = DEFAULT_TOOTH_METHOD, slices: int = DEFAULT_SLICES, positions: int = 360,
                     transmission_error_um=None, stiffness: xr.Dataset | None = None,
                     ltca: xr.Dataset | None = None, table: MeshForceTable | None = None) -> GearModel:
    """The 8-DOF model of ``pair`` at one torque from engineering-unit settings (:func:`dynamics_dataset`).

    Excitation (:func:`resolve_excitation`): 'contact' the mesh force ``table`` (built here
    with the default table settings when not given); 'ltca' the loaded stiffness and equivalent
    error of the ``ltca`` dataset (:func:`ltca_excitation`, the variant's micro-geometry
    included); 'tvms' / 'lste' the slice stiffness (``stiffness`` dataset or computed) with
    ``transmission_error_um`` (or none), 'tvms' with the loaded extension of contact beyond the
    active zone at the torque (:func:`gearmesh.ltca.with_loaded_extension`; 'lste' is the low-fluctuation paper's
    literal form without it).
    """
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    torque = positive_torque("torque_Nm", torque_Nm)
    if on not in _PAIR_GEARS:
        raise GearmeshInputError("on", on, "must be 'pinion' or 'gear' (where torque_Nm acts)")
    check_load(geom, pinion_torque(pair, torque, on), "torque_Nm", torque_Nm)
    if stiffness is None and ltca is None and table is None:
        check_slice_grid(slices, positions)
    t_out = torque if on == "gear" else torque * geom.base_radius[1] / geom.base_radius[0]
    backlash = _backlash(geom, backlash_um)
    exc = resolve_excitation(excitation, ltca)
    t1 = pinion_torque(pair, t_out, "gear")  # the pinion torque of the mesh's static force
    K = te = None
    if exc == "contact":
        if transmission_error_um is not None:
            raise GearmeshInputError("transmission_error_um", "given", "the contact excitation has the "
                                     "micro-geometry in its table; give no tabulated TE")
        if table is None:
            table = contact_table(geom, [t1], method)
    elif exc == "ltca":
        if ltca is None:
            raise GearmeshInputError("excitation", "ltca", "needs the variant's LTCA dataset (ltca.nc)")
        if transmission_error_um is not None:
            raise GearmeshInputError("transmission_error_um", "given", "give either a table or an ltca dataset")
        K, te = ltca_excitation(geom, ltca, t1)
    else:
        K = _stiffness_curve(geom, stiffness, method, slices, positions, t1)
        if exc == "tvms":  # the loaded extension of contact beyond the active zone (one stiffness at one load)
            K = with_loaded_extension(geom, K, t1, method)
        te = _transmission_error(transmission_error_um)
    return pair_model(geom, t_out, K, bearing=_bearing(bearing_k_radial_N_per_m, bearing_k_axial_N_per_m,
                                                         bearing_c_radial_Ns_per_m, bearing_c_axial_Ns_per_m),
                      damping_ratio=damping_ratio, backlash=backlash, stiffness_form=stiffness_form,
                      order=fourier_order, excitation="lste" if exc == "lste" else "tvms", transmission_error=te,
                      mesh_damping=mesh_damping_Ns_per_m, contact=table if exc == "contact" else None)


#: The two displacements of the mesh, both along the transverse line of action (normal values
#: of :mod:`gearmesh.dynamics` divided by cos βb), named so they cannot be mixed up.
DYNAMIC_TE = ("dynamic transmission error along the transverse line of action: relative displacement of the "
              "two gear bodies at the mesh (r_b1 theta_p - r_b2 theta_g plus the centre and axial motions "
              "projected on the line of action; what encoders on both gears measure when the bearings are "
              "rigid); statically the loaded TE (LTCA excitation) or F/K (stiffness excitation)")
MESH_DEFLECTION = ("mesh deflection delta_m along the transverse line of action: elastic approach of the flanks "
                   "(dynamic TE minus the excitation error e), statically F_bt/k with k the transverse mesh "
                   "stiffness (the low-fluctuation paper calls it the DTE)")


def _common_vars(model: GearModel, res: SweepResult, mesh_dim: bool, cos_beta_b: float) -> dict[str, xr.Variable]:
    """Mesh statistics of a sweep: (speed,) for one mesh, (speed, mesh) otherwise. The dynamic
    TE and the mesh deflection are converted from the model's normal direction to the
    transverse line of action (÷ cos βb), the direction of the LTCA's ``lte``."""
    dims = ("speed", "mesh") if mesh_dim else ("speed",)

    def v(a):
        return a.T if mesh_dim else a[0]

    fs = model.static_force[:, None]
    return {
        "mesh_frequency": variable(("speed",), res.mesh_frequency, "Hz", "mesh frequency"),
        "dynamic_te_mean": variable(dims, v(res.approach_mean) / cos_beta_b, "m", f"mean of the {DYNAMIC_TE}"),
        "dynamic_te_std": variable(dims, v(res.approach_std) / cos_beta_b, "m",
                                   f"standard deviation of the {DYNAMIC_TE}"),
        "mesh_deflection_mean": variable(dims, v(res.dte_mean) / cos_beta_b, "m", f"mean of the {MESH_DEFLECTION}"),
        "mesh_deflection_std": variable(dims, v(res.dte_std) / cos_beta_b, "m",
                                        f"standard deviation of the {MESH_DEFLECTION}"),
        "mesh_deflection_rms": variable(dims, v(res.dte_rms) / cos_beta_b, "m",
                                        f"RMS (mean included) of the {MESH_DEFLECTION}"),
        "mesh_deflection_min": variable(dims, v(res.dte_min) / cos_beta_b, "m",
                                        f"minimum (at the steps) of the {MESH_DEFLECTION}; below 0: teeth apart"),
        "mesh_deflection_max": variable(dims, v(res.dte_max) / cos_beta_b, "m",
                                        f"maximum (at the steps) of the {MESH_DEFLECTION}"),
        "mesh_force_mean": variable(dims, v(res.force_mean), "N", "mean dynamic mesh force (normal)"),
        "mesh_force_min": variable(dims, v(res.force_min), "N", "minimum dynamic mesh force (at the steps)"),
        "mesh_force_max": variable(dims, v(res.force_max), "N", "maximum dynamic mesh force (at the steps)"),
        "mesh_force_std": variable(dims, v(res.force_std), "N", "standard deviation of the dynamic mesh force"),
        "dynamic_factor": variable(dims, v(res.force_max / fs), "1", "dynamic factor: maximum over static mesh force"),
        "contact_loss_fraction": variable(dims, v(res.gap_fraction), "1",
                                          "fraction of time with the teeth apart (inside the backlash)"),
        "back_side_fraction": variable(dims, v(res.back_fraction), "1", "fraction of time in back-side contact"),
        "steady_state_change": variable(dims, v(res.steady_change), "1",
                                        "relative change of the mesh-deflection standard deviation between the "
                                        "halves of the record window (steady-state check)"),
        "steps_per_cycle": variable(("speed",), res.steps_per_cycle, "1", "RK4 steps per mesh period"),
        "transient_cycles": variable(("speed",), res.transient_cycles, "1",
                                     "mesh periods integrated and discarded before recording"),
        "time_step": variable(("speed",), res.dt, "s", "RK4 time step"),
        "static_mesh_force": variable(("mesh",) if mesh_dim else (), model.static_force if mesh_dim
                                      else model.static_force[0], "N", "static mesh force (normal) of the torque"),
        "mesh_stiffness_mean": variable(("mesh",) if mesh_dim else (),
                                        np.array([ml.k_mean for ml in model.meshes]) if mesh_dim
                                        else model.meshes[0].k_mean, "N m-1", "mean mesh stiffness along the normal"),
        "mesh_damping": variable(("mesh",) if mesh_dim else (), model.damping if mesh_dim else model.damping[0],
                                 "N s m-1", "mesh damping coefficient"),
    }


def _vibration_vars(res: SweepResult, model: GearModel, shape: tuple[int, int]) -> dict[str, xr.Variable]:
    """Displacement RMS/mean/std and velocity RMS per speed, gear and direction (m, m/s); zero in
    a rigidly supported direction (not a coordinate of the model)."""
    ym = full_translations(model, res.y_mean).T.reshape(-1, *shape)
    ys = full_translations(model, res.y_std).T.reshape(-1, *shape)
    dims = ("speed", "gear", "direction")
    return {
        "displacement_rms": variable(dims, np.sqrt(ym**2 + ys**2), "m", "RMS displacement (mean included)"),
        "displacement_mean": variable(dims, ym, "m", "mean displacement (static bearing deflection)"),
        "displacement_std": variable(dims, ys, "m", "standard deviation of the displacement (vibration)"),
        "velocity_rms": variable(dims, full_translations(model, res.v_rms).T.reshape(-1, *shape), "m s-1",
                                 "RMS velocity"),
    }


def _modal_vars(model: GearModel, harmonics=(1, 2, 3)) -> dict[str, xr.Variable]:
    md = model.modes()
    rs = resonance_speeds(model, harmonics)
    return {
        "mesh_energy_fraction": variable(("mode",), mesh_energy_fraction(model, md["shapes"]), "1",
                                         "fraction of the mode's strain energy in the mesh (mean stiffness)"),
        "natural_frequency": variable(("mode",), md["frequency_Hz"], "Hz",
                                      "natural frequencies of the linearised model (mean stiffness, in contact)"),
        "modal_damping_ratio": variable(("mode",), md["damping_ratio"], "1", "modal damping ratio"),
        "resonance_speed": variable(("harmonic", "mode"), rs["speed_rpm"], "rpm",
                                    "speed where harmonic j of the mesh frequency meets a natural frequency"),
    }


def _series_vars(res: SweepResult, arr, n_rec: int, max_order: int, ppc: int, gear_dims: tuple[str, str],
                 trans_shape: tuple[int, int], mesh_dim: bool, cos_beta_b: float,
                 model: GearModel) -> dict[str, xr.Variable]:
    S = res.speed_rpm.size
    ms = ("sample_speed", "sample", "mesh") if mesh_dim else ("sample_speed", "sample")
    msp = ("sample_speed", "order", "mesh") if mesh_dim else ("sample_speed", "order")

    def mv(a):
        return a if mesh_dim else a[..., 0]

    gd = ("sample_speed", "sample") + gear_dims
    pd = ("sample_speed",) + gear_dims
    y = full_translations(model, arr["y"], axis=2).reshape(S, -1, *trans_shape)
    vv = full_translations(model, arr["v"], axis=2).reshape(S, -1, *trans_shape)
    orders = np.arange(max_order * n_rec + 1) / n_rec
    return {
        "time": variable(("sample_speed", "sample"), arr["t"], "s", "time within the record window"),
        "mesh_deflection_series": variable(ms, mv(arr["delta"]) / cos_beta_b, "m", MESH_DEFLECTION),
        "mesh_force_series": variable(ms, mv(arr["F"]), "N", "dynamic mesh force, normal to the flanks"),
        "displacement_series": variable(gd, y, "m", "bearing-point displacement"),
        "velocity_series": variable(gd, vv, "m s-1", "bearing-point velocity"),
        "frequency": variable(("sample_speed", "order"), orders[None, :] * res.mesh_frequency[:, None], "Hz",
                              "frequency of each spectral line"),
        "mesh_force_spectrum": variable(msp, mv(arr["F_spec"]), "N",
                                        "one-sided amplitude spectrum of the mesh force (normal)"),
        "mesh_deflection_spectrum": variable(msp, mv(arr["delta_spec"]) / cos_beta_b, "m",
                                             f"one-sided amplitude spectrum of the {MESH_DEFLECTION}"),
        "displacement_peak_to_peak": variable(pd, full_translations(model, arr["y_pp"], axis=1).reshape(S, *trans_shape), "m",
                                              "peak-to-peak displacement"),
        "velocity_peak_to_peak": variable(pd, full_translations(model, arr["v_pp"], axis=1).reshape(S, *trans_shape), "m s-1",
                                          "peak-to-peak velocity"),
        "acceleration_peak_to_peak": variable(pd, full_translations(model, arr["a_pp"], axis=1).reshape(S, *trans_shape), "m s-2",
                                              "peak-to-peak acceleration (central differences of the velocity)"),
    }


def _contact_vars(res: SweepResult, model: GearModel, table: MeshForceTable) -> dict[str, xr.Variable]:
    """The entering pair in the steady state (``contact`` excitation): its largest force and its
    dynamic impact over the first part of its engagement, and the roll before A at which it first
    carries load, per speed; the same quasi-static (the table's own static solution)."""
    cb = model.cos_beta_b
    force_t = float(model.static_force[0]) * cb
    x_s, _ = table.static_approach(force_t)
    part = f"from p_bt/2 before A to {FIRST_PART_AFTER_A:g} p_bt after A"
    return {
        "entering_pair_force_max": variable(("speed",), res.enter_force_max[0], "N",
                                            f"largest force (normal) of the entering tooth pair over the first part "
                                            f"of its engagement ({part})"),
        "dynamic_impact_force": variable(("speed",), res.impact_force[0], "N",
                                         "dynamic impact: largest excess of the entering pair's force (normal) over "
                                         f"its quasi-static force at the same mesh position ({part})"),
        "mesh_in_roll_before_A": variable(("speed",), res.touch_roll_before_A[0], "m",
                                          "roll along the transverse line of action before A at which the entering "
                                          "pair first carries load (earliest over the recorded mesh cycles; 0 at or "
                                          "after A): the dynamic mesh-in point"),
        "table_overrun_fraction": variable(("speed",), res.table_overrun[0], "1",
                                           "fraction of the record window with the approach beyond the contact "
                                           "table (force extrapolated with its tangent)"),
        "static_mesh_in_roll_before_A": variable((), table.static_touch(force_t), "m",
                                                 "roll before A at which the entering pair first touches in the "
                                                 "quasi-static mesh (the table's static solution)"),
        "static_entering_pair_force_max": variable(
            (), float(np.max(table.entering(x_s, table.window)[table.window <= (0.5 + FIRST_PART_AFTER_A)
                                                                * table.pitch])) / cb, "N",
            f"largest quasi-static force (normal) of the entering pair over the same window ({part})"),
    }


def _pair_sweep(pair: GearPair, model: GearModel, speeds: np.ndarray, grid: np.ndarray, samples: np.ndarray,
                settings: SolverSettings, points_per_cycle: int, max_order: int,
                table: MeshForceTable | None) -> xr.Dataset:
    """One torque of :func:`dynamics_dataset`: the sweep and the kept series as a Dataset."""
    res = simulate(model, speeds, settings, progress=_log_progress)
    nt = model.n_trans  # 6: x, y, z of pinion then gear
    shape = (2, 3)
    cb = model.cos_beta_b
    data = _common_vars(model, res, mesh_dim=False, cos_beta_b=cb)
    data.update(_vibration_vars(res, model, shape))
    data["torsional_std"] = variable(("speed",), res.y_std[nt], "m",
                                     "standard deviation of the relative rotation r_b1 theta_p - r_b2 theta_g "
                                     "alone (transverse line of action; encoders on compliant bearings)")
    data["on_grid"] = variable(("speed",), np.isin(speeds, grid).astype(np.int8), "1",
                               "1: a speed of the configured grid; 0: added around a predicted resonance")
    data["shooting_iterations"] = variable(("speed",), res.shooting_iterations, "1",
                                           "Newton steps of the periodic steady state (-1: physical-time transient)")
    data.update(_modal_vars(model))
    if table is not None:
        data.update(_contact_vars(res, model, table))
    if samples.size:
        rs = simulate(model, samples, settings, series=True)
        arr = _series_arrays(rs, points_per_cycle, max_order, settings.record_cycles)
        data.update(_series_vars(rs, arr, settings.record_cycles, max_order, points_per_cycle, ("gear", "direction"),
                                 shape, mesh_dim=False, cos_beta_b=cb, model=model))
        if table is not None:
            data["entering_pair_force_series"] = variable(("sample_speed", "sample"), arr["Fe"][..., 0], "N",
                                                          "force (normal) of the tooth pair entering the mesh in "
                                                          "each mesh cycle")
    return xr.Dataset(data)


#: Variables of a sweep that do not depend on the torque (no torque dimension).
_TORQUE_FREE = ("mesh_frequency", "on_grid", "frequency", "time")


@check_arguments(Dynamics)
def dynamics_dataset(pair: GearPair, torques_Nm=200.0, on: str = "pinion",
                     speeds_rpm: Mapping[str, float] | Sequence[float] | str = DEFAULT_SPEEDS,
                     backlash_um="pair",
                     bearing_k_radial_N_per_m: float | str = "pair",
                     bearing_k_axial_N_per_m: float | str = "pair",
                     bearing_c_radial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_radial"],
                     bearing_c_axial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_axial"],
                     damping_ratio: float = DEFAULT_DAMPING_RATIO, mesh_damping_Ns_per_m: float | None = None,
                     stiffness_form: str = "fourier", fourier_order: int = 3, excitation: str | None = None,
                     method: str = DEFAULT_TOOTH_METHOD, slices: int = DEFAULT_SLICES, positions: int = 360,
                     transmission_error_um=None, sample_speeds_rpm: Sequence[float] = (5000, 13700, 27000),
                     courant: float = 0.25, steps_per_cycle_min: int = 32, transient_tau: float = 10.0,
                     record_cycles: int = 8, steady_state: str = "shooting", points_per_cycle: int = 64,
                     max_order: int = 10, refine_resonances: bool = True, contact_law: str = DEFAULT_CONTACT_LAW,
                     points: int = DEFAULT_TABLE_POINTS,
                     table_positions: int = DEFAULT_TABLE_POSITIONS, table_approaches: int = DEFAULT_TABLE_APPROACHES,
                     table_force_factor: float = 4.0, variant: str = "", stiffness: xr.Dataset | None = None,
                     ltca: xr.Dataset | None = None, fe_compliance: xr.Dataset | None = None) -> xr.Dataset:
    """Speed sweeps of the 8-DOF helical pair at one or more torques (the low-fluctuation paper §4; model and
    solver in :mod:`gearmesh.dynamics`). Dimensions (torque, speed) and, for the kept series,
    (torque, sample_speed, sample).

    Parameters (engineering units)
    ------------------------------
    torques_Nm : T (N·m) > 0, one or a list, acting on ``on`` ('pinion' or 'gear').
    speeds_rpm : pinion speeds {start, stop, step} (stop included), a list or 'a:b:c'.
    backlash_um : total backlash 2b0 (µm) along the normal; 'pair' the pair's own (from its
        centre distance and shifts; the dataset says which); null = none.
    bearing_* : bearing stiffness (N/m) and damping (N·s/m), radial (x, y) and axial (z),
        the low-fluctuation paper values by default.
    damping_ratio : mesh damping ratio ζ (-), or ``mesh_damping_Ns_per_m`` directly.
    stiffness_form : 'fourier' (order ``fourier_order``, the improved potential-energy paper) or 'table'.
    excitation : 'contact' (the real tooth contact, :mod:`gearmesh.meshforce`: the table is built
        per torque (its mesh misalignment) from ``method``, ``contact_law``, ``points``,
        ``table_positions``, ``table_approaches`` and ``table_force_factor`` × the largest static
        force), 'ltca' (the ``ltca`` dataset's loaded stiffness and error at each torque),
        'tvms' (the slice stiffness with ``transmission_error_um`` or none, plus the tip-edge contact
        the LTCA loads beyond the active zone at the torque), 'lste' (the low-fluctuation paper literal); null: 'ltca' with an ``ltca`` dataset, else 'tvms'. See :mod:`gearmesh.dynamics`.
    method, slices, positions : slice model (and the TVMS grid when no upstream ``stiffness``).
    sample_speeds_rpm : speeds whose time series (``points_per_cycle`` per mesh period over
        the record window) and spectra (to ``max_order`` mesh orders) are kept.
    courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state : solver rules
        (:class:`gearmesh.dynamics.SolverSettings`).
    refine_resonances : add speeds around the resonance speeds the linearised model predicts
        at each torque (:func:`resonance_refined`; ``on_grid`` marks the configured speeds).

    Two displacements of the mesh are reported, both along the transverse line of action
    (the direction of the LTCA's ``lte``): the dynamic transmission error ``dynamic_te_*``
    (the approach of the gear bodies, δ + e, statically the loaded TE) and the mesh deflection
    ``mesh_deflection_*`` (δ, statically F/k; with ``contact`` the approach beyond the first
    touch). ``torsional_std`` is the relative rotation alone, what encoders read when the gear
    centres move too. With ``contact``, the entering pair: ``entering_pair_force_max``,
    ``dynamic_impact_force``, ``mesh_in_roll_before_A`` (:func:`_contact_vars`).
    """
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    given = positive_values(torques_Nm, "torques_Nm", "N m")
    if on not in _PAIR_GEARS:
        raise GearmeshInputError("on", on, "must be 'pinion' or 'gear' (where torques_Nm act)")
    t1 = pinion_torque(pair, given, on)
    check_loads(geom, t1, "torques_Nm", given)
    grid = speed_grid(speeds_rpm)
    check_speeds(geom, grid, "speeds_rpm")
    samples = speed_grid(list(sample_speeds_rpm)) if len(sample_speeds_rpm) else np.zeros(0)
    check_speeds(geom, samples, "sample_speeds_rpm", empty_ok=True)
    check_slice_grid(slices, positions)
    use_fe_tables(fe_compliance, geom)
    settings = _solver(courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state)
    exc = resolve_excitation(excitation, ltca)
    tables = [None] * len(given)
    if exc == "contact":
        tables = contact_tables(geom, t1, method, contact_law=contact_law, points=points,
                                table_positions=table_positions, table_approaches=table_approaches,
                                table_force_factor=table_force_factor)
    table = tables[0]
    models = [build_pair_model(pair, float(t), on, backlash_um, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m,
                               bearing_c_radial_Ns_per_m, bearing_c_axial_Ns_per_m, damping_ratio,
                               mesh_damping_Ns_per_m, stiffness_form, fourier_order, exc, method, slices, positions,
                               transmission_error_um, stiffness, ltca, tab) for t, tab in zip(given, tables)]
    speeds = np.unique(np.concatenate([resonance_refined(grid, m) for m in models])) if refine_resonances else grid
    if speeds.size > MAX_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{speeds.size} speeds with the resonance points of every torque",
                                 f"at most {MAX_SPEEDS} (refine_resonances: false, or a coarser grid)")
    parts = []
    for k, model in enumerate(models):
        logging.info("torque %d of %d: %.6g N m on the %s", k + 1, len(models), given[k], on)
        parts.append(_pair_sweep(pair, model, speeds, grid, samples, settings, points_per_cycle, max_order, tables[k]))
    per_torque = [v for v in parts[0].data_vars if v not in _TORQUE_FREE]
    ds = xr.concat(parts, dim="torque", data_vars=per_torque, coords="minimal", compat="equals", join="exact")
    order_coord = np.arange(max_order * settings.record_cycles + 1) / settings.record_cycles
    coords = {
        "torque": variable(("torque",), given, "N m", f"torque on the {on}"),
        "speed": variable(("speed",), speeds, "rpm", "pinion speed"),
        "gear": variable(("gear",), np.array(_PAIR_GEARS), "1", "gear of the pair"),
        "direction": variable(("direction",), np.array(_PAIR_DIRS), "1",
                              "direction: x along the centres, y across, z axial"),
        "harmonic": variable(("harmonic",), np.array([1, 2, 3]), "1", "harmonic of the mesh frequency"),
        "mode": variable(("mode",), np.arange(models[0].n), "1", "mode number, by frequency"),
    }
    if samples.size:
        coords["sample_speed"] = variable(("sample_speed",), samples, "rpm", "pinion speed of the kept time series")
        coords["order"] = variable(("order",), order_coord, "1", "spectral line in mesh orders (f / f_mesh)")
    ds = ds.assign_coords(coords)
    ds["pinion_torque"] = variable(("torque",), t1, "N m", "pinion torque T1")
    ds["backlash"] = variable((), float(models[0].backlash) if math.isfinite(models[0].backlash) else np.nan, "m",
                              "total backlash 2b0 along the normal (NaN: none, contact never lost)")
    ds["transverse_base_pitch"] = variable((), geom.transverse_base_pitch, "m", "transverse base pitch (mesh cycle)")
    ds["roll_engagement"] = variable((), float(table.roll_engagement) if table is not None else
                                     float(_engagement_roll(geom)), "m",
                                     "pinion roll of the theoretical start of engagement A (mesh phase x p_bt)")
    ds.attrs.update({
        "model": "8-DOF bending-torsion-axial helical pair (the low-fluctuation paper, section 4, projections corrected; "
                 "gearmesh.dynamics)",
        "excitation": excitation_used(exc, ltca, transmission_error_um, table), "excitation_name": exc,
        **model_choices(exc, method, contact_law, stiffness, ltca),
        "resonance_refinement": "on" if refine_resonances else "off", "stiffness_form": stiffness_form,
        "fourier_order": fourier_order, "torque_on": on, "variant": variant,
        "backlash_source": "the pair's own (centre distance and shifts)" if backlash_um == "pair"
        else ("none" if backlash_um is None else "given"),
        "damping_ratio": float(damping_ratio),
        "damping_ratio_meaning": DAMPING_MEANING,
        "supports": supports_note(pair, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m),
        "gear_body": describe_body(geom),
        "steady_state": (f"periodic steady state by shooting (Newton on the one-period map), then "
                         f"{settings.settle_cycles} periods, then {record_cycles} recorded; the physical-time "
                         f"transient ({transient_tau} time constants of the slowest mode) where shooting does not "
                         "converge to a stable orbit") if steady_state == "shooting" else
                        (f"{transient_tau} time constants 1/sigma_min of the slowest linearised mode, then "
                         f"{record_cycles} mesh periods recorded"),
    })
    return name_force_lines(ds, "normal")


def _engagement_roll(geom: PairGeometry) -> float:
    from ..tca import engagement_point

    return engagement_point(geom)[0]


@check_arguments(Dynamics)
def dynamics_summary(pair: GearPair, torque_Nm: float = 200.0, speeds: Any = DEFAULT_SPEEDS, on: str = "pinion",
                     progress=None, **settings: Any) -> list[dict[str, float]]:
    """Per speed (for the CLI): speed_rpm, mesh_frequency_Hz, dynamic_te_mean_um, dynamic_te_std_um,
    mesh_deflection_mean_um (all three along the transverse line of action, as the LTCA's
    lte_mean_um; :func:`dynamics_dataset`), mesh_force_mean_normal_N, mesh_force_min_normal_N, mesh_force_max_normal_N
    (normal force), dynamic_factor, contact_loss_fraction; with the ``contact`` excitation also
    entering_pair_force_max_normal_N, dynamic_impact_force_normal_N (normal) and mesh_in_roll_before_A_mm."""
    model_settings = {k: v for k, v in settings.items() if k not in _SOLVER_KEYS and k not in _TABLE_KEYS}
    if resolve_excitation(settings.get("excitation"), settings.get("ltca")) == "contact":
        geom = pair_geometry(pair)
        t1 = pinion_torque(pair, positive_torque("torque_Nm", torque_Nm), on)
        model_settings["table"] = contact_table(geom, [t1], settings.get("method", _DEFAULTS["method"]),
                                                **{k: v for k, v in settings.items() if k in _TABLE_KEYS})
    model = build_pair_model(pair, torque_Nm, on, **model_settings)
    solver = _solver(*(settings.get(k, d) for k, d in _SOLVER_KEYS.items()))
    grid = speed_grid(speeds)
    check_speeds(pair_geometry(pair), grid, "speeds_rpm")
    res = simulate(model, grid, solver, progress=progress)
    fs = float(model.static_force[0])
    um = 1e6 / model.cos_beta_b  # normal (m) -> transverse (µm)
    rows = []
    for i in range(res.speed_rpm.size):
        row = {"speed_rpm": float(res.speed_rpm[i]), "mesh_frequency_Hz": float(res.mesh_frequency[i]),
               "dynamic_te_mean_um": float(res.approach_mean[0, i]) * um,
               "dynamic_te_std_um": float(res.approach_std[0, i]) * um,
               "mesh_deflection_mean_um": float(res.dte_mean[0, i]) * um,
               "mesh_force_mean_normal_N": float(res.force_mean[0, i]), "mesh_force_min_normal_N": float(res.force_min[0, i]),
               "mesh_force_max_normal_N": float(res.force_max[0, i]), "dynamic_factor": float(res.force_max[0, i]) / fs,
               "contact_loss_fraction": float(res.gap_fraction[0, i])}
        if model.meshes[0].contact is not None:
            row.update({"entering_pair_force_max_normal_N": float(res.enter_force_max[0, i]),
                        "dynamic_impact_force_normal_N": float(res.impact_force[0, i]),
                        "mesh_in_roll_before_A_mm": float(res.touch_roll_before_A[0, i]) * 1e3})
        rows.append(row)
    return rows




# --------------------------------------------------------------------------------------
# 9-DOF train (the improved potential-energy paper)
# --------------------------------------------------------------------------------------


@check_arguments(TrainDynamics)
def train_dataset(pair: GearPair, static_force_N: float | None = PRINTING_TRAIN_STATIC_FORCE_N,
                  torque_Nm: float | None = None, speeds_rpm: Any = None,
                  mesh_frequency_Hz: float = PRINTING_TRAIN_MESH_FREQUENCY_HZ, backlash_um="pair",
                  bearing_k_radial_N_per_m: float | str = "pair",
                  bearing_k_axial_N_per_m: float | str = "pair",
                  bearing_c_radial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_radial"],
                  bearing_c_axial_Ns_per_m: float = LOW_FLUCTUATION_BEARING["c_axial"],
                  damping_ratio: float = DEFAULT_DAMPING_RATIO, mesh_damping_Ns_per_m: float | None = None,
                  stiffness_form: str = "fourier", fourier_order: int = 3, excitation: str | None = None,
                  method: str = DEFAULT_TOOTH_METHOD, slices: int = DEFAULT_SLICES, positions: int = 360,
                  phase_offsets_cycles: Sequence[float] = (0.0, 0.0), courant: float = 0.25,
                  steps_per_cycle_min: int = 32, transient_tau: float = 10.0, record_cycles: int = 8,
                  steady_state: str = "shooting", points_per_cycle: int = 64, max_order: int = 10,
                  contact_law: str = DEFAULT_CONTACT_LAW, points: int = DEFAULT_TABLE_POINTS,
                  table_positions: int = DEFAULT_TABLE_POSITIONS, table_approaches: int = DEFAULT_TABLE_APPROACHES,
                  table_force_factor: float = 4.0, stiffness: xr.Dataset | None = None,
                  fe_compliance: xr.Dataset | None = None) -> xr.Dataset:
    """The 9-DOF plate–blanket–impression train of the improved potential-energy paper (:func:`gearmesh.dynamics.train_model`).

    Assumptions (the improved potential-energy paper gives neither torque nor speed nor bearings): the three gears are
    the pair file's gear repeated (the improved potential-energy paper: alike, 88 teeth) with the pair's TVMS for both
    meshes; the load is given as the static normal mesh force ``static_force_N`` (the improved potential-energy paper:
    2832 N; T = F r_b cos βb) unless ``torque_Nm`` is given; the speed is the one whose mesh
    frequency is ``mesh_frequency_Hz`` (the improved potential-energy paper: 249.4 Hz → 170.05 rpm) unless
    ``speeds_rpm`` is given; bearings are the low-fluctuation paper's, the backlash the pair's own unless
    given; meshes in phase. ``excitation`` 'tvms' (default), 'lste' or 'contact' (both meshes
    driven by the pair's mesh force table, settings as :func:`dynamics_dataset`).
    Time series and spectra are kept at every speed (give few).
    """
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    rb, cb = float(geom.base_radius[1]), math.cos(geom.base_helix_angle)
    if torque_Nm is not None:
        torque = positive_torque("torque_Nm", torque_Nm)
        check_load(geom, pinion_torque(pair, torque, "gear"), "torque_Nm", torque_Nm)
    elif static_force_N is not None:
        torque = positive_torque("static_force_N", static_force_N) * rb * cb
        check_load(geom, pinion_torque(pair, torque, "gear"), "static_force_N", static_force_N)
    else:
        raise GearmeshInputError("torque_Nm", None, "give torque_Nm or static_force_N")
    if speeds_rpm is None:
        f = positive_torque("mesh_frequency_Hz", mesh_frequency_Hz)
        speeds = np.array([f * 60.0 / geom.pair.teeth[1]])
    else:
        speeds = speed_grid(speeds_rpm)
    check_speeds(geom, speeds, "speeds_rpm" if speeds_rpm is not None else "mesh_frequency_Hz", on="gear")
    if len(speeds) > MAX_TRAIN_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{len(speeds)} speeds",
                                 f"at most {MAX_TRAIN_SPEEDS} for the train (series are kept)")
    use_fe_tables(fe_compliance, geom)
    exc = "tvms" if excitation is None else excitation
    if exc not in ("tvms", "lste", "contact"):
        raise GearmeshInputError("excitation", excitation, "must be 'tvms', 'lste', 'contact' or null for the train")
    table = None
    if exc == "contact":
        table = contact_table(geom, [torque * float(geom.base_radius[0]) / rb], method, contact_law=contact_law,
                              points=points, table_positions=table_positions,
                              table_approaches=table_approaches, table_force_factor=table_force_factor)
        K = None
    else:
        K = _stiffness_curve(geom, stiffness, method, slices, positions, torque * float(geom.base_radius[0]) / rb)
    model = train_model(geom, torque, K, bearing=_bearing(bearing_k_radial_N_per_m, bearing_k_axial_N_per_m,
                                                          bearing_c_radial_Ns_per_m, bearing_c_axial_Ns_per_m),
                        damping_ratio=damping_ratio, backlash=_backlash(geom, backlash_um),
                        stiffness_form=stiffness_form, order=fourier_order,
                        excitation="lste" if exc == "lste" else "tvms", contact=table,
                        phase_offsets=tuple(phase_offsets_cycles), mesh_damping=mesh_damping_Ns_per_m)
    settings = _solver(courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state)
    res = simulate(model, speeds, settings, series=True)
    shape = (3, 2)
    cb = math.cos(geom.base_helix_angle)
    data = _common_vars(model, res, mesh_dim=True, cos_beta_b=cb)
    data.update(_vibration_vars(res, model, shape))
    data["torque"] = variable((), torque, "N m", "torque on the plate gear (= load on the impression gear)")
    data["backlash"] = variable((), float(model.backlash) if math.isfinite(model.backlash) else np.nan, "m",
                                "total backlash 2b0 along the normal (NaN: none, contact never lost)")
    data.update(_modal_vars(model))
    arr = _series_arrays(res, points_per_cycle, max_order, settings.record_cycles)
    data.update(_series_vars(res, arr, settings.record_cycles, max_order, points_per_cycle, ("gear", "direction"),
                             shape, mesh_dim=True, cos_beta_b=cb, model=model))
    coords = {
        "speed": variable(("speed",), speeds, "rpm", "speed of the gears"),
        "sample_speed": variable(("sample_speed",), speeds, "rpm", "speed of the kept time series"),
        "gear": variable(("gear",), np.array(TRAIN_GEARS), "1", "gear of the train"),
        "direction": variable(("direction",), np.array(["y", "z"]), "1", "direction: y along the centres, z axial"),
        "mesh": variable(("mesh",), np.array(["plate-blanket", "blanket-impression"]), "1", "mesh of the train"),
        "harmonic": variable(("harmonic",), np.array([1, 2, 3]), "1", "harmonic of the mesh frequency"),
        "mode": variable(("mode",), np.arange(model.n), "1", "mode number, by frequency"),
        "order": variable(("order",), np.arange(max_order * settings.record_cycles + 1) / settings.record_cycles,
                          "1", "spectral line in mesh orders (f / f_mesh)"),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({
        "model": "9-DOF plate-blanket-impression helical train (the improved potential-energy paper, projections corrected; gearmesh.dynamics)",
        "excitation": excitation_used(exc, None, None, table), "excitation_name": exc,
        **model_choices(exc, method, contact_law, stiffness), "stiffness_form": stiffness_form,
        "fourier_order": fourier_order,
        "backlash_source": "the pair's own (centre distance and shifts)" if backlash_um == "pair"
        else ("none" if backlash_um is None else "given"),
        "assumptions": "three alike gears (the pair file's gear, its supports for all three); plate drives, "
                       "impression loaded, blanket idles; meshes in phase unless phase_offsets_cycles; centres on "
                       "one line",
        "supports": supports_note(pair, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m),
        "gear_body": describe_body(geom),
        "damping_ratio_meaning": DAMPING_MEANING,
    })
    return name_force_lines(ds, "normal")


@check_arguments(DynamicsComparison)
def dynamics_comparison_dataset(dynamics: Sequence[xr.Dataset],
                                couples: Sequence[Sequence[str]] | None = None) -> xr.Dataset:
    """RMS changes between pairs over a common speed sweep (the low-fluctuation paper §4–5, its comparisons).

    Over the configured speeds (``on_grid``; each pair's added resonance speeds differ), at each
    sweep's first torque. For
    each (pair, reference) couple: the mean over speeds of the relative change of the
    mesh-deflection standard deviation (the low-fluctuation paper's "DTE"), and for each gear and direction the mean relative change and the
    change of the highest peak of the displacement standard deviation and velocity RMS
    (the low-fluctuation paper reports "across most speeds" and "at the resonance peaks"). Default couples:
    every pair against the first.
    """
    by_name = {d.attrs.get("pair_name", str(i)): d for i, d in enumerate(dynamics)}
    names = list(by_name)
    couples = [tuple(c) for c in couples] if couples else [(n, names[0]) for n in names[1:]]
    for pair, ref in couples:
        for n in (pair, ref):
            if n not in by_name:
                raise GearmeshInputError("dynamics_comparison.couples", [pair, ref], f"{n} is not a pair of the study")
        if not np.array_equal(_grid(by_name[pair])["speed"].values, _grid(by_name[ref])["speed"].values):
            raise GearmeshInputError("dynamics.speeds_rpm", None, f"{pair} and {ref} were swept over different speeds")

    def change(new, old):
        return float(np.mean(new / old - 1)), float(new.max() / old.max() - 1)

    rows = {"dte_mean": [], "dte_peak": []}
    grid = {f"{q}_{k}": [] for q in ("displacement", "velocity") for k in ("mean", "peak")}
    for pair, ref in couples:
        new, old = _grid(by_name[pair]), _grid(by_name[ref])
        m, p = change(new["mesh_deflection_std"].values, old["mesh_deflection_std"].values)
        rows["dte_mean"].append(m)
        rows["dte_peak"].append(p)
        for q, var in (("displacement", "displacement_std"), ("velocity", "velocity_rms")):
            a, b = new[var].values, old[var].values  # (speed, gear, direction)
            grid[f"{q}_mean"].append(np.mean(a / b - 1, axis=0))
            grid[f"{q}_peak"].append(a.max(axis=0) / b.max(axis=0) - 1)
    d1, d3 = ("couple",), ("couple", "gear", "direction")
    first = dynamics[0]
    return xr.Dataset({
        "mesh_deflection_std_change_mean": variable(d1, rows["dte_mean"], "1",
                                                    "mean over speeds of the relative change of the mesh-deflection "
                                                    "std (the low-fluctuation paper's DTE)"),
        "mesh_deflection_std_change_peak": variable(d1, rows["dte_peak"], "1",
                                                    "relative change of the highest mesh-deflection std peak"),
        "displacement_change_mean": variable(d3, np.array(grid["displacement_mean"]), "1",
                                             "mean over speeds of the relative change of displacement std"),
        "displacement_change_peak": variable(d3, np.array(grid["displacement_peak"]), "1",
                                             "relative change of the highest displacement std peak"),
        "velocity_change_mean": variable(d3, np.array(grid["velocity_mean"]), "1",
                                         "mean over speeds of the relative change of velocity RMS"),
        "velocity_change_peak": variable(d3, np.array(grid["velocity_peak"]), "1",
                                         "relative change of the highest velocity RMS peak"),
    }, coords={
        "couple": variable(d1, np.array([f"{p} vs {r}" for p, r in couples]), "1", "pair against its reference"),
        "gear": variable(("gear",), first["gear"].values, "1", "gear of the pair"),
        "direction": variable(("direction",), first["direction"].values, "1", "x, y lateral; z axial"),
    })


def engagement_table_dataset(impact: Sequence[xr.Dataset], dynamics: Sequence[xr.Dataset]) -> xr.Dataset:
    """The energy method beside the dynamics driven by the real contact, per variant and torque at
    the impact stage's design speed: does F_s rank the variants as the dynamics does?

    From ``impact.nc``: F_s (closed form and energy balance), the quasi-static mesh-in roll, and
    the undamped engagement simulation's largest excess of the entering pair over its
    quasi-static load where it was run; from ``dynamics.nc`` (``contact`` excitation) at the
    speed of its grid nearest the design speed: the entering pair's dynamic impact, its largest
    force, the dynamic mesh-in roll, the peak mesh force, and the peak mesh force over the whole
    sweep. Every force transverse (the impact stage's direction: normal × cos βb), so F_s and
    the dynamics stand in one unit. Torques are those both stages ran (pinion torques).
    """
    names = variant_names("impact", impact)
    by_name = dict(zip(variant_names("dynamics", dynamics), dynamics))
    one_pair(impact=impact, dynamics=dynamics)
    if set(by_name) != set(names):
        raise GearmeshInputError("variants", sorted(by_name), f"impact and dynamics must cover the same variants "
                                 f"({sorted(names)})")
    for d in dynamics:
        if d.attrs.get("excitation_name") != "contact":
            raise GearmeshInputError("dynamics.excitation", d.attrs.get("excitation_name"),
                                     "must be 'contact' for the engagement table")
    ref = dynamics[0]
    t_dyn = np.asarray(ref["pinion_torque"].values, dtype=float)
    t_imp = np.asarray(impact[0]["torque"].values, dtype=float)
    torques = np.array([t for t in t_dyn if same_point(t_imp, t).any()])
    if not torques.size:
        raise GearmeshInputError("dynamics.torques_Nm", t_dyn.tolist(), f"share no torque with impact.torques_Nm "
                                 f"{t_imp.tolist()} (pinion torques)")
    design = float(impact[0].attrs["design_speed_rpm"])
    cols = {k: np.full((len(names), torques.size), np.nan) for k in (
        "fs", "fs_eb", "sim", "static_roll", "impact", "enter", "roll", "peak", "peak_all")}
    speed_used = np.nan
    for v, name in enumerate(names):
        imp, dyn = impact[v], by_name[name]
        # normal -> transverse: cos βb = F_bt / F_normal of the static mesh force (F_bt = T1/r_b1)
        c = float(dyn["pinion_torque"].values[0]) / float(imp["base_radius"].values[0]) \
            / float(dyn["static_mesh_force"].values[0])
        grid = dyn["speed"].values[dyn["on_grid"].values.astype(bool)]
        speed_used = float(grid[np.argmin(np.abs(grid - design))])
        for k, t in enumerate(torques):
            i = int(np.flatnonzero(same_point(imp["torque"].values, t))[0])
            j = int(np.flatnonzero(same_point(dyn["pinion_torque"].values, t))[0])
            at = imp.sel(speed=design)
            cols["fs"][v, k] = float(at["impact_force"].values[i])
            cols["fs_eb"][v, k] = float(at["impact_force_energy_balance"].values[i])
            if "simulated_entering_excess" in imp:
                cols["sim"][v, k] = float(imp["simulated_entering_excess"].values[i])
            cols["static_roll"][v, k] = float(imp["roll_before_engagement"].values[i])
            d = dyn.isel(torque=j).sel(speed=speed_used)
            cols["impact"][v, k] = float(d["dynamic_impact_force"]) * c
            cols["enter"][v, k] = float(d["entering_pair_force_max"]) * c
            cols["roll"][v, k] = float(d["mesh_in_roll_before_A"])
            cols["peak"][v, k] = float(d["mesh_force_max"]) * c
            cols["peak_all"][v, k] = float(dyn.isel(torque=j)["mesh_force_max"].max()) * c
    dims = ("variant", "torque")
    with np.errstate(divide="ignore", invalid="ignore"):
        over = {key: np.where(cols[key] > 0, cols["fs"] / cols[key], np.nan) for key in ("sim", "impact")}
    ds = xr.Dataset({
        "impact_force": variable(dims, cols["fs"], "N", f"{IMPACT_INDEX} at the design speed (closed form of the "
                                                        f"energy method; an index of the impact, not a force the teeth "
                                                        f"carry)"),
        "impact_force_energy_balance": variable(dims, cols["fs_eb"], "N",
                                                f"{IMPACT_INDEX} by the energy balance at the design speed"),
        "simulated_entering_excess": variable(dims, cols["sim"], "N",
                                              "undamped engagement simulation: the entering pair's largest excess "
                                              "over its quasi-static load (NaN: not simulated)"),
        "impact_index_over_simulated_excess": variable(dims, over["sim"], "1", "F_s over the simulated excess of the "
                                                       "entering pair (NaN: not simulated)"),
        "impact_index_over_dynamic_impact": variable(dims, over["impact"], "1", "F_s over the entering pair's excess in "
                                                     "the steady-state dynamics (NaN: no excess)"),
        "dynamic_impact_force": variable(dims, cols["impact"], "N",
                                         "steady-state dynamics (contact excitation) at the speed nearest the design "
                                         "speed: the entering pair's largest excess over its quasi-static force "
                                         "(transverse)"),
        "entering_pair_force_max": variable(dims, cols["enter"], "N",
                                            "steady-state dynamics: the entering pair's largest force in the first "
                                            "part of its engagement (transverse)"),
        "static_mesh_in_roll_before_A": variable(dims, cols["static_roll"], "m",
                                                 "impact model: roll before A at which the entering pair first "
                                                 "touches in the quasi-static mesh"),
        "mesh_in_roll_before_A": variable(dims, cols["roll"], "m",
                                          "steady-state dynamics: roll before A at which the entering pair first "
                                          "carries load"),
        "peak_mesh_force": variable(dims, cols["peak"], "N",
                                    "steady-state dynamics: peak mesh force at the speed nearest the design speed "
                                    "(transverse)"),
        "peak_mesh_force_sweep": variable(dims, cols["peak_all"], "N",
                                          "steady-state dynamics: peak mesh force over the whole speed sweep "
                                          "(transverse)"),
    }, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
               "torque": variable(("torque",), torques, "N m", "pinion torque T1")})
    ds.attrs.update({"design_speed_rpm": design, "dynamics_speed_rpm": speed_used,
                     "force_direction": "transverse (F_bt convention of the LTCA and the impact model)",
                     **{f"{key}_{stage}": str(sets[0].attrs.get(key, "")) for stage, sets in
                        (("impact", impact), ("dynamics", dynamics)) for key in ("tooth_model", "contact_law")}})
    return name_force_lines(ds, "transverse")
