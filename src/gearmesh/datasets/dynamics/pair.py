"""The 8-DOF helical pair (the low-fluctuation paper §4–5): its model from engineering-unit
settings, the speed sweeps at one or more torques as a dataset, and the per-speed summary of the CLI.
"""

from __future__ import annotations

import logging
import math
from typing import Any, Mapping, Sequence

import numpy as np
import xarray as xr

from ...body import describe_body
from ...deflection import describe_deflection
from ...dynamics import (DAMPING_MEANING, DEFAULT_DAMPING_RATIO, FIRST_PART_AFTER_A, LOW_FLUCTUATION_BEARING,
                         GearModel, SolverSettings, SweepResult, pair_model, require_dynamics_data, resonance_band,
                         simulate)
from ...errors import GearmeshInputError
from ...fe_tables import use_fe_tables
from ...gear import GearPair, PairGeometry, pair_geometry, pinion_torque
from ...io import name_force_lines, variable
from ...limits import MAX_SPEEDS, check_slice_grid, check_speeds, positive_values
from ...loads import check_load, check_loads
from ...ltca import with_loaded_extension
from ...meshforce import DEFAULT_TABLE_APPROACHES, DEFAULT_TABLE_POINTS, DEFAULT_TABLE_POSITIONS, MeshForceTable
from ...stiffness import DEFAULT_SLICES
from ...schema import check_arguments
from ...choices import DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD
from ...settings import Dynamics
from .excitation import (_stiffness_curve, _transmission_error, contact_table, contact_tables, excitation_used,
                         ltca_excitation, model_choices, resolve_excitation)
from .inputs import (DEFAULT_SPEEDS, _DEFAULTS, _SOLVER_KEYS, _TABLE_KEYS, _backlash, _bearing, _solver,
                     backlash_source, positive_torque, speed_grid, supports_note)
from .variables import _common_vars, _modal_vars, _series_arrays, _series_vars, _vibration_vars

_PAIR_GEARS = ("pinion", "gear")
_PAIR_DIRS = ("x", "y", "z")


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
    given, t1 = _pair_torques(pair, geom, torques_Nm, on)
    grid, samples = _sweep_speeds(geom, speeds_rpm, sample_speeds_rpm)
    check_slice_grid(slices, positions)
    use_fe_tables(fe_compliance, geom)
    settings = _solver(courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state)
    exc = resolve_excitation(excitation, ltca)
    tables = (contact_tables(geom, t1, method, contact_law=contact_law, points=points, table_positions=table_positions,
                             table_approaches=table_approaches, table_force_factor=table_force_factor)
              if exc == "contact" else [None] * len(given))
    models = [build_pair_model(pair, float(t), on, backlash_um, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m,
                               bearing_c_radial_Ns_per_m, bearing_c_axial_Ns_per_m, damping_ratio,
                               mesh_damping_Ns_per_m, stiffness_form, fourier_order, exc, method, slices, positions,
                               transmission_error_um, stiffness, ltca, tab) for t, tab in zip(given, tables)]
    speeds = _resonance_refined_speeds(grid, models) if refine_resonances else grid
    ds = _torque_sweeps(pair, models, tables, given, on, speeds, grid, samples, settings, points_per_cycle, max_order)
    ds = _with_pair_scalars(ds, geom, t1, models[0], tables[0])
    ds.attrs.update(_sweep_attrs(
        pair, geom, exc, settings, ltca=ltca, transmission_error_um=transmission_error_um, table=tables[0],
        method=method, contact_law=contact_law, stiffness=stiffness, refine_resonances=refine_resonances,
        stiffness_form=stiffness_form, fourier_order=fourier_order, on=on, variant=variant, backlash_um=backlash_um,
        damping_ratio=damping_ratio, bearing_k_radial_N_per_m=bearing_k_radial_N_per_m,
        bearing_k_axial_N_per_m=bearing_k_axial_N_per_m, steady_state=steady_state, transient_tau=transient_tau,
        record_cycles=record_cycles))
    return name_force_lines(ds, "normal")


def _pair_torques(pair: GearPair, geom: PairGeometry, torques_Nm, on: str) -> tuple[np.ndarray, np.ndarray]:
    """The torques as given (N·m, on ``on``) and the pinion torques T1, checked against the load
    limits (:func:`gearmesh.loads.check_loads`)."""
    given = positive_values(torques_Nm, "torques_Nm", "N m")
    if on not in _PAIR_GEARS:
        raise GearmeshInputError("on", on, "must be 'pinion' or 'gear' (where torques_Nm act)")
    t1 = pinion_torque(pair, given, on)
    check_loads(geom, t1, "torques_Nm", given)
    return given, t1


def _sweep_speeds(geom: PairGeometry, speeds_rpm, sample_speeds_rpm: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The configured grid of pinion speeds and the speeds whose series are kept (rpm; none: an
    empty array), each checked against the pair's speed limits."""
    grid = speed_grid(speeds_rpm)
    check_speeds(geom, grid, "speeds_rpm")
    samples = speed_grid(list(sample_speeds_rpm)) if len(sample_speeds_rpm) else np.zeros(0)
    check_speeds(geom, samples, "sample_speeds_rpm", empty_ok=True)
    return grid, samples


def _resonance_refined_speeds(grid: np.ndarray, models: Sequence[GearModel]) -> np.ndarray:
    """``grid`` with the resonance speeds of every torque's model (:func:`resonance_refined`), at
    most :data:`MAX_SPEEDS`."""
    speeds = np.unique(np.concatenate([resonance_refined(grid, m) for m in models]))
    if speeds.size > MAX_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{speeds.size} speeds with the resonance points of every torque",
                                 f"at most {MAX_SPEEDS} (refine_resonances: false, or a coarser grid)")
    return speeds


def _torque_sweeps(pair: GearPair, models: Sequence[GearModel], tables: Sequence[MeshForceTable | None],
                   given: np.ndarray, on: str, speeds: np.ndarray, grid: np.ndarray, samples: np.ndarray,
                   settings: SolverSettings, points_per_cycle: int, max_order: int) -> xr.Dataset:
    """The sweep of each torque's model (:func:`_pair_sweep`) joined along ``torque``, with the
    coordinates of the dataset."""
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
    return ds.assign_coords(coords)


def _with_pair_scalars(ds: xr.Dataset, geom: PairGeometry, t1: np.ndarray, model: GearModel,
                       table: MeshForceTable | None) -> xr.Dataset:
    """``ds`` with the pinion torques T1 and the sweep's scalars: backlash, base pitch and the roll
    of the start of engagement A (of ``table`` when the contact drives, else of the geometry)."""
    ds["pinion_torque"] = variable(("torque",), t1, "N m", "pinion torque T1")
    ds["backlash"] = variable((), float(model.backlash) if math.isfinite(model.backlash) else np.nan, "m",
                              "total backlash 2b0 along the normal (NaN: none, contact never lost)")
    ds["transverse_base_pitch"] = variable((), geom.transverse_base_pitch, "m", "transverse base pitch (mesh cycle)")
    ds["roll_engagement"] = variable((), float(table.roll_engagement) if table is not None else
                                     float(_engagement_roll(geom)), "m",
                                     "pinion roll of the theoretical start of engagement A (mesh phase x p_bt)")
    return ds


def _sweep_attrs(pair: GearPair, geom: PairGeometry, exc: str, settings: SolverSettings, *, ltca, transmission_error_um,
                 table, method, contact_law, stiffness, refine_resonances, stiffness_form, fourier_order, on, variant,
                 backlash_um, damping_ratio, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m, steady_state,
                 transient_tau, record_cycles) -> dict[str, Any]:
    """The attributes of a pair sweep: its model, excitation and model choices, settings, supports
    and how the steady state was reached (the keywords: those of :func:`dynamics_dataset`)."""
    return {
        "model": "8-DOF bending-torsion-axial helical pair (the low-fluctuation paper, section 4, projections corrected; "
                 "gearmesh.dynamics)",
        "excitation": excitation_used(exc, ltca, transmission_error_um, table), "excitation_name": exc,
        **model_choices(exc, method, contact_law, stiffness, ltca),
        "resonance_refinement": "on" if refine_resonances else "off", "stiffness_form": stiffness_form,
        "fourier_order": fourier_order, "torque_on": on, "variant": variant,
        "backlash_source": backlash_source(backlash_um),
        "damping_ratio": float(damping_ratio),
        "damping_ratio_meaning": DAMPING_MEANING,
        "supports": supports_note(pair, bearing_k_radial_N_per_m, bearing_k_axial_N_per_m),
        "gear_body": describe_body(geom),
        "system_deflection": describe_deflection(geom),
        "steady_state": (f"periodic steady state by shooting (Newton on the one-period map), then "
                         f"{settings.settle_cycles} periods, then {record_cycles} recorded; the physical-time "
                         f"transient ({transient_tau} time constants of the slowest mode) where shooting does not "
                         "converge to a stable orbit") if steady_state == "shooting" else
                        (f"{transient_tau} time constants 1/sigma_min of the slowest linearised mode, then "
                         f"{record_cycles} mesh periods recorded"),
    }


def _engagement_roll(geom: PairGeometry) -> float:
    from ...tca import engagement_point

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
