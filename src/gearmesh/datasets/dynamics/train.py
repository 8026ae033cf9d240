"""The 9-DOF plate–blanket–impression train (the improved potential-energy paper) as a dataset."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from ...body import describe_body
from ...dynamics import (DAMPING_MEANING, TRAIN_GEARS, GearModel, SolverSettings, SweepResult, require_dynamics_data,
                         simulate, train_model)
from ...errors import GearmeshInputError
from ...fe_tables import use_fe_tables
from ...gear import GearPair, PairGeometry, pair_geometry, pinion_torque
from ...io import name_force_lines, variable
from ...limits import MAX_TRAIN_SPEEDS, check_speeds
from ...loads import check_load
from ...arguments import check_arguments
from ...schema import defaults, settings_object
from ...settings import TrainDynamics
from .excitation import _stiffness_curve, contact_table, excitation_used, model_choices
from .inputs import (SECTION_KEYS, _backlash, _bearing, _solver, backlash_source, positive_quantity, settings_speeds,
                     slice_grid, supports_note, table_keywords)
from .variables import _common_vars, _modal_vars, _series_arrays, _series_vars, _vibration_vars

#: The improved potential-energy paper's mesh frequency (249.4 Hz of the 88-tooth gears -> 249.4·60/88 rpm) and
#: static normal mesh force: the declared defaults of :class:`gearmesh.settings.TrainDynamics`.
PRINTING_TRAIN_MESH_FREQUENCY_HZ = float(defaults(TrainDynamics)["mesh_frequency_Hz"])
PRINTING_TRAIN_STATIC_FORCE_N = float(defaults(TrainDynamics)["static_force_N"])


@check_arguments(TrainDynamics, exclude=SECTION_KEYS[TrainDynamics])
def train_dataset(pair: GearPair, *, slices: int | None = None, positions: int | None = None,
                  stiffness: xr.Dataset | None = None, fe_compliance: xr.Dataset | None = None,
                  **section: Any) -> xr.Dataset:
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

    Parameters
    ----------
    pair : GearPair
        The pair whose gear is repeated three times.
    slices, positions : int, optional
        Slice grid without a ``stiffness`` dataset (:func:`.inputs.slice_grid`; the stiffness stage's defaults).
    stiffness, fe_compliance : xarray.Dataset, optional
        The upstream stiffness result and finite-element tooth tables.
    **section
        A study's ``train_dynamics:`` section (:class:`gearmesh.settings.TrainDynamics`: every default and bound
        there), parsed once (:func:`gearmesh.schema.settings_object`); engineering units (``torque_Nm`` N·m on the
        plate gear, ``static_force_N`` N, ``mesh_frequency_Hz`` Hz). A bad value raises GearmeshInputError naming
        the key (neither ``torque_Nm`` nor ``static_force_N``, load and speed limits, :data:`MAX_TRAIN_SPEEDS`).

    Returns
    -------
    xarray.Dataset
        On ``speed`` (r/min), ``gear``, ``direction`` (y, z), ``mesh``, ``mode``, ``sample_speed`` and ``order``;
        variables with ``units`` and ``long_name``, the model choices and provenance in the attributes.

    References
    ----------
    .. [1] *A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an Improved
       Potential Energy Method for Time-Varying Meshing Stiffness* (the 9-DOF three-gear train).
    .. [2] [untitled] *Low mesh-stiffness fluctuation design of helical gears* (the bearings).
    """
    s = settings_object(TrainDynamics, section)
    geom = pair_geometry(pair)
    require_dynamics_data(geom)
    rb = float(geom.base_radius[1])
    torque = _train_torque(pair, geom, s.torque_Nm, s.static_force_N)
    speeds = _train_speeds(geom, s.speeds_rpm, s.mesh_frequency_Hz)
    use_fe_tables(fe_compliance, geom)
    exc = "tvms" if s.excitation is None else s.excitation
    table = K = None
    if exc == "contact":
        table = contact_table(geom, [torque * float(geom.base_radius[0]) / rb], s.contact_model(),
                              **table_keywords(s))
    else:
        K = _stiffness_curve(geom, stiffness, s.method, *slice_grid(slices, positions),
                             torque * float(geom.base_radius[0]) / rb)
    model = train_model(geom, torque, K, bearing=_bearing(s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m,
                                                          s.bearing_c_radial_Ns_per_m, s.bearing_c_axial_Ns_per_m),
                        damping_ratio=s.damping_ratio, backlash=_backlash(geom, s.backlash_um),
                        stiffness_form=s.stiffness_form, order=s.fourier_order,
                        excitation="lste" if exc == "lste" else "tvms", contact=table,
                        phase_offsets=tuple(s.phase_offsets_cycles), mesh_damping=s.mesh_damping_Ns_per_m)
    settings = _solver(s)
    res = simulate(model, speeds, settings, series=True)
    data = _train_variables(geom, model, res, torque, settings, s.points_per_cycle, s.max_order)
    ds = xr.Dataset(data, coords=_train_coords(speeds, model, s.max_order, settings.record_cycles))
    ds.attrs.update({
        "model": "9-DOF plate-blanket-impression helical train (the improved potential-energy paper, projections corrected; gearmesh.dynamics)",
        "excitation": excitation_used(exc, None, None, table), "excitation_name": exc,
        **model_choices(exc, s.method, s.contact_law, stiffness), "stiffness_form": s.stiffness_form,
        "fourier_order": s.fourier_order,
        "backlash_source": backlash_source(s.backlash_um),
        "assumptions": "three alike gears (the pair file's gear, its supports for all three); plate drives, "
                       "impression loaded, blanket idles; meshes in phase unless phase_offsets_cycles; centres on "
                       "one line",
        "supports": supports_note(pair, s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m),
        "gear_body": describe_body(geom),
        "damping_ratio_meaning": DAMPING_MEANING,
    })
    return name_force_lines(ds, "normal")


def _train_torque(pair: GearPair, geom: PairGeometry, torque_Nm: float | None, static_force_N: float | None) -> float:
    """The torque (N·m) on the plate gear: ``torque_Nm``, else that of the static normal mesh force
    ``static_force_N``, T = F r_b cos βb; checked against the load limits."""
    rb, cb = float(geom.base_radius[1]), math.cos(geom.base_helix_angle)
    if torque_Nm is not None:
        torque = positive_quantity("torque_Nm", torque_Nm)
        check_load(geom, pinion_torque(pair, torque, "gear"), "torque_Nm", torque_Nm)
    elif static_force_N is not None:
        torque = positive_quantity("static_force_N", static_force_N) * rb * cb
        check_load(geom, pinion_torque(pair, torque, "gear"), "static_force_N", static_force_N)
    else:
        raise GearmeshInputError("torque_Nm", None, "give torque_Nm or static_force_N")
    return torque


def _train_speeds(geom: PairGeometry, speeds_rpm: Any, mesh_frequency_Hz: float) -> np.ndarray:
    """The speeds (rpm) of the gears: ``speeds_rpm``, else the one whose mesh frequency is
    ``mesh_frequency_Hz``; checked, at most :data:`MAX_TRAIN_SPEEDS`."""
    if speeds_rpm is None:
        f = positive_quantity("mesh_frequency_Hz", mesh_frequency_Hz)
        speeds = np.array([f * 60.0 / geom.pair.teeth[1]])
    else:
        speeds = settings_speeds(speeds_rpm)
    check_speeds(geom, speeds, "speeds_rpm" if speeds_rpm is not None else "mesh_frequency_Hz", on="gear")
    if len(speeds) > MAX_TRAIN_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{len(speeds)} speeds",
                                 f"at most {MAX_TRAIN_SPEEDS} for the train (series are kept)")
    return speeds


def _train_variables(geom: PairGeometry, model: GearModel, res: SweepResult, torque: float, settings: SolverSettings,
                     points_per_cycle: int, max_order: int) -> dict[str, xr.Variable]:
    """The variables of the train's result ``res``: mesh statistics per mesh, vibration of the
    three gears, torque, backlash, modes, and the series and spectra of every speed."""
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
    return data


def _train_coords(speeds: np.ndarray, model: GearModel, max_order: int, record_cycles: int) -> dict[str, xr.Variable]:
    """The coordinates of the train's dataset: speeds (each kept), gears, directions, meshes,
    harmonics, modes and spectral orders over ``record_cycles`` mesh periods."""
    return {
        "speed": variable(("speed",), speeds, "rpm", "speed of the gears"),
        "sample_speed": variable(("sample_speed",), speeds, "rpm", "speed of the kept time series"),
        "gear": variable(("gear",), np.array(TRAIN_GEARS), "1", "gear of the train"),
        "direction": variable(("direction",), np.array(["y", "z"]), "1", "direction: y along the centres, z axial"),
        "mesh": variable(("mesh",), np.array(["plate-blanket", "blanket-impression"]), "1", "mesh of the train"),
        "harmonic": variable(("harmonic",), np.array([1, 2, 3]), "1", "harmonic of the mesh frequency"),
        "mode": variable(("mode",), np.arange(model.n), "1", "mode number, by frequency"),
        "order": variable(("order",), np.arange(max_order * record_cycles + 1) / record_cycles,
                          "1", "spectral line in mesh orders (f / f_mesh)"),
    }
