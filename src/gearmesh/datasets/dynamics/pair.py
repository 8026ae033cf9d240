"""The 8-DOF helical pair (the low-fluctuation paper §4–5): its model from engineering-unit
settings, the speed sweeps at one or more torques as a dataset, and the per-speed summary of the CLI.
"""

from __future__ import annotations

import logging
import math
from typing import Any, Sequence

import numpy as np
import xarray as xr

from ...body import describe_body
from ...deflection import describe_deflection
from ...dynamics import (DAMPING_MEANING, FIRST_PART_AFTER_A, GearModel, SolverSettings, SweepResult, pair_model,
                         require_dynamics_data, resonance_band, simulate)
from ...errors import GearmeshInputError
from ...fe_tables import use_fe_tables
from ...gear import GearPair, PairGeometry, pair_geometry, pinion_torque
from ...io import name_force_lines, variable
from ...limits import MAX_SPEEDS, check_slice_grid, check_speeds, positive_values
from ...loads import check_load, check_loads
from ...contact_model import LTCA_CONTACT
from ...ltca import with_loaded_extension
from ...meshforce import MeshForceTable
from ...arguments import check_arguments
from ...schema import settings_object
from ...settings import Dynamics
from .excitation import (_stiffness_curve, _transmission_error, contact_table, contact_tables, excitation_used,
                         ltca_excitation, model_choices, resolve_excitation)
from .inputs import (SECTION_KEYS, _backlash, _bearing, _solver, backlash_source, positive_quantity, settings_speeds,
                     slice_grid, speed_grid, supports_note, table_keywords)
from .variables import _common_vars, _modal_vars, _series_arrays, _series_vars, _vibration_vars

_PAIR_GEARS = ("pinion", "gear")
_PAIR_DIRS = ("x", "y", "z")


@check_arguments(Dynamics, exclude=SECTION_KEYS[Dynamics])
def build_pair_model(pair: GearPair, torque_Nm: float, *, slices: int | None = None, positions: int | None = None,
                     stiffness: xr.Dataset | None = None, ltca: xr.Dataset | None = None,
                     table: MeshForceTable | None = None, **section: Any) -> GearModel:
    """The 8-DOF model of ``pair`` at one torque ``torque_Nm`` (N·m, on ``section``'s ``on``):
    ``section`` is a study's ``dynamics:`` section (keywords, :class:`gearmesh.settings.Dynamics`:
    every default and bound there), parsed once; ``slices`` and ``positions`` the slice grid without
    a ``stiffness`` dataset (:func:`.inputs.slice_grid`); the model as :func:`pair_model_of` builds it.

    Parameters
    ----------
    pair : GearPair
        The pair (its supports, body and micro-geometry).
    torque_Nm : float
        Torque (N·m) on the section's ``on`` gear, > 0.
    slices, positions : int, optional
        Slice grid of the stiffness computed without a ``stiffness`` dataset (the stiffness stage's defaults).
    stiffness, ltca : xarray.Dataset, optional
        The variant's stiffness and LTCA results.
    table : MeshForceTable, optional
        The ``contact`` excitation's mesh force table (built from the section when left out).
    **section
        The ``dynamics:`` section's keys, engineering units (:class:`gearmesh.settings.Dynamics`).

    Returns
    -------
    GearModel
        The 8-DOF model, SI (:func:`gearmesh.dynamics.pair_model`).

    Raises
    ------
    GearmeshInputError
        Naming the section key out of its declaration, ``torque_Nm`` beyond the pair's load limits,
        ``excitation`` ``ltca`` without an LTCA dataset, ``transmission_error_um`` given beside an
        LTCA or contact excitation.
    """
    s = settings_object(Dynamics, section)
    return pair_model_of(pair, torque_Nm, s, resolve_excitation(s.excitation, ltca), slice_grid(slices, positions),
                         stiffness=stiffness, ltca=ltca, table=table)


def pair_model_of(pair: GearPair, torque_Nm: float, settings: Dynamics, excitation: str, grid: tuple[int, int], *,
                  stiffness: xr.Dataset | None = None, ltca: xr.Dataset | None = None,
                  table: MeshForceTable | None = None) -> GearModel:
    """The 8-DOF model of ``pair`` at one torque from parsed ``settings``
    (:func:`gearmesh.schema.settings_object`) and the resolved ``excitation``.

    Parameters
    ----------
    pair : GearPair
        The pair (its supports, body and micro-geometry).
    torque_Nm : float
        Torque (N·m) on ``settings.on``.
    settings : gearmesh.settings.Dynamics
        The dynamics section as its declaration parsed it.
    excitation : {'contact', 'ltca', 'tvms', 'lste'}
        'contact' the mesh force ``table`` (built with the section's table settings when not
        given); 'ltca' the loaded stiffness and equivalent error of the ``ltca`` dataset
        (:func:`ltca_excitation`, the variant's micro-geometry included); 'tvms' / 'lste' the slice
        stiffness (``stiffness`` dataset or computed) with ``transmission_error_um`` (or none),
        'tvms' with the loaded extension of contact beyond the active zone at the torque
        (:func:`gearmesh.ltca.with_loaded_extension`; 'lste' is the low-fluctuation paper's literal
        form without it).
    grid : (int, int)
        Slices and positions of the slice stiffness computed without a ``stiffness`` dataset.
    stiffness, ltca : xarray.Dataset, optional
        The variant's stiffness and LTCA results.
    table : MeshForceTable, optional
        The contact excitation's mesh force table.

    Returns
    -------
    GearModel
        The model (:func:`gearmesh.dynamics.pair_model`), SI.
    """
    s, exc, (slices, positions) = settings, excitation, grid
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    torque = positive_quantity("torque_Nm", torque_Nm)
    check_load(geom, pinion_torque(pair, torque, s.on), "torque_Nm", torque_Nm)
    if stiffness is None and ltca is None and table is None:
        check_slice_grid(slices, positions)
    t_out = torque if s.on == "gear" else torque * geom.base_radius[1] / geom.base_radius[0]
    backlash = _backlash(geom, s.backlash_um)
    t1 = pinion_torque(pair, t_out, "gear")  # the pinion torque of the mesh's static force
    K = te = None
    if exc == "contact":
        if s.transmission_error_um is not None:
            raise GearmeshInputError("transmission_error_um", "given", "the contact excitation has the "
                                     "micro-geometry in its table; give no tabulated TE")
        if table is None:
            table = contact_table(geom, [t1], s.contact_model(), **table_keywords(s))
    elif exc == "ltca":
        if ltca is None:
            raise GearmeshInputError("excitation", "ltca", "needs the variant's LTCA dataset (ltca.nc)")
        if s.transmission_error_um is not None:
            raise GearmeshInputError("transmission_error_um", "given", "give either a table or an ltca dataset")
        K, te = ltca_excitation(geom, ltca, t1)
    else:
        K = _stiffness_curve(geom, stiffness, s.method, slices, positions, t1)
        if exc == "tvms":  # the loaded extension of contact beyond the active zone (one stiffness at one load)
            K = with_loaded_extension(geom, K, t1, LTCA_CONTACT.with_(method=s.method))
        te = _transmission_error(s.transmission_error_um)
    return pair_model(geom, t_out, K, bearing=_bearing(s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m,
                                                       s.bearing_c_radial_Ns_per_m, s.bearing_c_axial_Ns_per_m),
                      damping_ratio=s.damping_ratio, backlash=backlash, stiffness_form=s.stiffness_form,
                      order=s.fourier_order, excitation="lste" if exc == "lste" else "tvms", transmission_error=te,
                      mesh_damping=s.mesh_damping_Ns_per_m, contact=table if exc == "contact" else None)


def resonance_refined(grid: np.ndarray, model: GearModel, harmonics: Sequence[int] = (1, 2, 3)) -> np.ndarray:
    """``grid`` plus the speeds around every resonance speed inside it
    (:func:`gearmesh.dynamics.resonance_band`), so a peak is resolved rather than caught by two
    points of the grid. Sorted, unique; at most :data:`MAX_SPEEDS`.

    Parameters
    ----------
    grid : numpy.ndarray
        Pinion speeds (S,) (r/min).
    model : GearModel
        The linearised model whose resonance speeds are added.
    harmonics : sequence of int, default (1, 2, 3)
        Mesh-frequency harmonics whose resonances are refined.

    Returns
    -------
    numpy.ndarray
        The refined speeds (r/min), sorted and unique.

    Raises
    ------
    GearmeshInputError
        ``speeds_rpm`` when the refined grid exceeds :data:`MAX_SPEEDS`.
    """
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


@check_arguments(Dynamics, exclude=SECTION_KEYS[Dynamics])
def dynamics_dataset(pair: GearPair, *, variant: str = "", slices: int | None = None, positions: int | None = None,
                     stiffness: xr.Dataset | None = None, ltca: xr.Dataset | None = None,
                     fe_compliance: xr.Dataset | None = None, **section: Any) -> xr.Dataset:
    """Speed sweeps of the 8-DOF helical pair at one or more torques (the low-fluctuation paper §4; model and
    solver in :mod:`gearmesh.dynamics`). Dimensions (torque, speed) and, for the kept series,
    (torque, sample_speed, sample).

    Parameters
    ----------
    pair : GearPair
        The pair (its supports, body and micro-geometry).
    variant : str, default ""
        Name of the micro-geometry variant (recorded).
    slices, positions : int, optional
        Slice grid without a ``stiffness`` dataset (:func:`slice_grid`; the stiffness stage's defaults).
    stiffness, ltca, fe_compliance : xarray.Dataset, optional
        The variant's upstream stiffness, LTCA and finite-element tooth tables.
    **section
        A study's ``dynamics:`` section (:class:`gearmesh.settings.Dynamics`: every default and bound there), parsed
        once (:func:`gearmesh.schema.settings_object`); its keys, engineering units, follow. A bad value, and
        ``excitation`` ``ltca`` without an LTCA dataset, raise GearmeshInputError naming the key (limits included).
    torques_Nm : T (N·m) > 0, one or a list, acting on ``on`` ('pinion' or 'gear').
    speeds_rpm : pinion speeds {start, stop, step} (stop included), a list or 'a:b:c'.
    backlash_um : total backlash 2b0 (µm) along the normal; 'pair' the pair's own (from its centre distance and
        shifts; the dataset says which); null = none.
    bearing_* : bearing stiffness (N/m) and damping (N·s/m), radial (x, y) and axial (z), the low-fluctuation paper's
        values by default.
    damping_ratio : mesh damping ratio ζ (-), or ``mesh_damping_Ns_per_m`` directly.
    stiffness_form : 'fourier' (order ``fourier_order``, the improved potential-energy paper) or 'table'.
    excitation : 'contact' (the real tooth contact, :mod:`gearmesh.meshforce`: the table is built per torque (its mesh
        misalignment) from ``method``, ``contact_law``, ``points``, ``table_positions``, ``table_approaches`` and
        ``table_force_factor`` × the largest static force), 'ltca' (the ``ltca`` dataset's loaded stiffness and error
        at each torque), 'tvms' (the slice stiffness with ``transmission_error_um`` or none, plus the tip-edge contact
        the LTCA loads beyond the active zone at the torque), 'lste' (the low-fluctuation paper literal); null: 'ltca'
        with an ``ltca`` dataset, else 'tvms'. See :mod:`gearmesh.dynamics`.
    method : slice model (and of the contact table).
    sample_speeds_rpm : speeds whose time series (``points_per_cycle`` per mesh period over the record window) and
        spectra (to ``max_order`` mesh orders) are kept.
    courant, steps_per_cycle_min, transient_tau, record_cycles, steady_state : solver rules
        (:class:`gearmesh.dynamics.SolverSettings`).
    refine_resonances : add speeds around the resonance speeds the linearised model predicts at each torque
        (:func:`resonance_refined`; ``on_grid`` marks the configured speeds).

    Two displacements of the mesh are reported, both along the transverse line of action (the direction of the
    LTCA's ``lte``): the dynamic transmission error ``dynamic_te_*`` (the approach of the gear bodies, δ + e,
    statically the loaded TE) and the mesh deflection ``mesh_deflection_*`` (δ, statically F/k; with ``contact`` the
    approach beyond the first touch). ``torsional_std`` is the relative rotation alone, what encoders read when the
    gear centres move too. With ``contact``, the entering pair: ``entering_pair_force_max``,
    ``dynamic_impact_force``, ``mesh_in_roll_before_A`` (:func:`_contact_vars`).

    Returns
    -------
    xarray.Dataset
        Variables with ``units`` and ``long_name``; the model choices and provenance in the attributes.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, section 4.
    """
    s = settings_object(Dynamics, section)
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    given, t1 = _pair_torques(pair, geom, s.torques_Nm, s.on)
    grid, samples = _sweep_speeds(geom, s.speeds_rpm, s.sample_speeds_rpm)
    grid_slices = slice_grid(slices, positions)
    check_slice_grid(*grid_slices)
    use_fe_tables(fe_compliance, geom)
    settings = _solver(s)
    exc = resolve_excitation(s.excitation, ltca)
    tables = (contact_tables(geom, t1, s.contact_model(), **table_keywords(s)) if exc == "contact"
              else [None] * len(given))
    models = [pair_model_of(pair, float(t), s, exc, grid_slices, stiffness=stiffness, ltca=ltca, table=tab)
              for t, tab in zip(given, tables)]
    speeds = _resonance_refined_speeds(grid, models) if s.refine_resonances else grid
    ds = _torque_sweeps(pair, models, tables, given, s.on, speeds, grid, samples, settings, s.points_per_cycle,
                        s.max_order)
    ds = _with_pair_scalars(ds, geom, t1, models[0], tables[0])
    ds.attrs.update(_sweep_attrs(pair, geom, exc, settings, s, ltca=ltca, table=tables[0], stiffness=stiffness,
                                 variant=variant))
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
    grid = settings_speeds(speeds_rpm)
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


def _sweep_attrs(pair: GearPair, geom: PairGeometry, exc: str, settings: SolverSettings, s: Dynamics, *,
                 ltca: xr.Dataset | None, table: MeshForceTable | None, stiffness: xr.Dataset | None,
                 variant: str) -> dict[str, Any]:
    """The attributes of a pair sweep: its model, excitation and model choices, settings, supports
    and how the steady state was reached (``s``: the parsed section of :func:`dynamics_dataset`)."""
    return {
        "model": "8-DOF bending-torsion-axial helical pair (the low-fluctuation paper, section 4, projections corrected; "
                 "gearmesh.dynamics)",
        "excitation": excitation_used(exc, ltca, s.transmission_error_um, table), "excitation_name": exc,
        **model_choices(exc, s.method, s.contact_law, stiffness, ltca),
        "resonance_refinement": "on" if s.refine_resonances else "off", "stiffness_form": s.stiffness_form,
        "fourier_order": s.fourier_order, "torque_on": s.on, "variant": variant,
        "backlash_source": backlash_source(s.backlash_um),
        "damping_ratio": float(s.damping_ratio),
        "damping_ratio_meaning": DAMPING_MEANING,
        "supports": supports_note(pair, s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m),
        "gear_body": describe_body(geom),
        "system_deflection": describe_deflection(geom),
        "steady_state": (f"periodic steady state by shooting (Newton on the one-period map), then "
                         f"{settings.settle_cycles} periods, then {s.record_cycles} recorded; the physical-time "
                         f"transient ({s.transient_tau} time constants of the slowest mode) where shooting does not "
                         "converge to a stable orbit") if s.steady_state == "shooting" else
                        (f"{s.transient_tau} time constants 1/sigma_min of the slowest linearised mode, then "
                         f"{s.record_cycles} mesh periods recorded"),
    }


def _engagement_roll(geom: PairGeometry) -> float:
    from ...tca import engagement_point

    return engagement_point(geom)[0]


@check_arguments(Dynamics, exclude=SECTION_KEYS[Dynamics])
def dynamics_summary(pair: GearPair, *, ltca: xr.Dataset | None = None, progress=None,
                     **section: Any) -> list[dict[str, float]]:
    """The per-speed summary (:func:`pair_summary`) of ``section``, a study's ``dynamics:`` section
    (keywords, :class:`gearmesh.settings.Dynamics`) at one torque, parsed once.

    Parameters
    ----------
    pair : GearPair
        The pair.
    ltca : xarray.Dataset, optional
        The variant's LTCA (the ``ltca`` excitation).
    progress : callable, optional
        Called with the fraction of the RK4 steps done (0–1).
    **section
        The ``dynamics:`` section's keys, engineering units, with one torque.

    Returns
    -------
    list of dict
        One row per speed, as :func:`pair_summary`.

    Raises
    ------
    GearmeshInputError
        Naming the section key out of its declaration, ``torques_Nm`` when more than one.
    """
    return pair_summary(pair, settings_object(Dynamics, section), ltca=ltca, progress=progress)


def pair_summary(pair: GearPair, settings: Dynamics, *, ltca: xr.Dataset | None = None,
                 progress=None) -> list[dict[str, float]]:
    """Per speed of ``settings.speeds_rpm`` at its one torque (for the CLI; the grid as given:
    ``refine_resonances`` and ``sample_speeds_rpm`` are :func:`dynamics_dataset`'s): speed_rpm, mesh_frequency_Hz, dynamic_te_mean_um, dynamic_te_std_um,
    mesh_deflection_mean_um (all three along the transverse line of action, as the LTCA's
    lte_mean_um; :func:`dynamics_dataset`), mesh_force_mean_normal_N, mesh_force_min_normal_N, mesh_force_max_normal_N
    (normal force), dynamic_factor, contact_loss_fraction; with the ``contact`` excitation also
    entering_pair_force_max_normal_N, dynamic_impact_force_normal_N (normal) and mesh_in_roll_before_A_mm.

    Parameters
    ----------
    pair : GearPair
        The pair.
    settings : gearmesh.settings.Dynamics
        The parsed ``dynamics:`` section, one torque.
    ltca : xarray.Dataset, optional
        The variant's LTCA (the ``ltca`` excitation).
    progress : callable, optional
        Called with the fraction of the RK4 steps done (0–1).

    Returns
    -------
    list of dict of str to float
        One row per speed, the units in the key names (rpm, Hz, µm, N, mm; factors dimensionless).

    Raises
    ------
    GearmeshInputError
        ``torques_Nm`` when it is not one torque; ``speeds_rpm`` beyond the pair's speed limits.
    """
    s = settings
    torques = positive_values(s.torques_Nm, "torques_Nm", "N m")
    if torques.size != 1:
        raise GearmeshInputError("torques_Nm", list(s.torques_Nm), "one torque for the per-speed summary")
    torque = float(torques[0])
    exc, table = resolve_excitation(s.excitation, ltca), None
    if exc == "contact":
        t1 = pinion_torque(pair, positive_quantity("torque_Nm", torque), s.on)
        table = contact_table(pair_geometry(pair), [t1], s.contact_model(), **table_keywords(s))
    model = pair_model_of(pair, torque, s, exc, slice_grid(None, None), ltca=ltca, table=table)
    grid = settings_speeds(s.speeds_rpm)
    check_speeds(pair_geometry(pair), grid, "speeds_rpm")
    res = simulate(model, grid, _solver(s), progress=progress)
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
