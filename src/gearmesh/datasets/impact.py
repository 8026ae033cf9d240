"""Mesh-in impact datasets (impact.nc, impact_table.nc) and the CLI summary of one impact.

Engineering units at the boundary (N·m, rpm), SI inside every Dataset; every variable
carries ``units`` and ``long_name``. Physics: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import json
from typing import Any, Sequence

import numpy as np
import xarray as xr

from ..body import describe_body
from ..choices import IMPACT_INDEX
from ..deflection import describe_deflection
from ..fe_tables import use_fe_tables
from ..errors import GearmeshInputError
from . import shared_torques, variant_names
from .ltca import refuse_operating_point
from ..gear import GEARS, GearPair, pair_geometry
from ..impact.energy import ImpactResponse, impact_response, load_grid, load_window
from ..impact.engagement import simulate_engagement
from ..impact.kinematics import mesh_in_point, seed_edge_roll, vector_velocity
from ..impact.model import SCENARIOS, ImpactModel, impact_model
from ..impact.static import ImpactStatic, impact_static
from ..pairfile import load_pair, pair_to_dict
from ..io import name_force_lines, variable
from ..limits import MAX_WINDOW_TORQUES, check_speeds, same_point
from ..ltca import MESH_ORDERS, check_torques, loaded_pinion_torques, pinion_torques
from ..surface import MODIFICATION_FIELDS
from ..tca import check_modifications
from ..robust import CRITERIA, CRITERION_UNITS, design_box_worst, gear_criteria, population_units
from ..tolerance import manufactured_population, study_population, study_tolerances
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..settings import Impact

UM = 1e-6

__all__ = ["impact_dataset", "impact_table_dataset", "impact_summary", "manufactured_gear"]


def _model(pair: GearPair, settings: Impact) -> ImpactModel:
    """The impact model of ``pair`` (its modification and deviations) from the parsed ``settings``'
    contact model, driver, added inertia and search window (:func:`gearmesh.impact.impact_model`)."""
    if not isinstance(pair, GearPair):
        raise GearmeshInputError("pair", type(pair).__name__, "must be a GearPair")
    check_modifications(pair)
    geom = pair_geometry(pair)
    s = settings
    return impact_model(geom, s.contact_model(), driver=s.driver, added_inertia_kg_m2=s.added_inertia_kg_m2,
                        window_positions=s.window_positions, face_samples=s.face_samples)


def _operating_points(pair: GearPair, torques, on: str, speeds_rpm, torque_field: str = "torques_Nm",
                      speed_field: str = "speeds_rpm") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Torques as given and as pinion torques (N m) and pinion speeds (rpm), each checked against
    the load and speed limits of :mod:`gearmesh.limits` before any model is built."""
    if not isinstance(pair, GearPair):
        raise GearmeshInputError("pair", type(pair).__name__, "must be a GearPair")
    geom = pair_geometry(pair)
    given, t1 = loaded_pinion_torques(geom, torques, on, torque_field)
    speeds = check_speeds(geom, speeds_rpm, speed_field)
    return given, t1, speeds


def _scenario_var(dims, scenario) -> xr.Variable:
    return variable(dims, np.asarray(scenario, dtype=np.int8), "1",
                    "mesh-in scenario: 0 none, 1 surface (flank-to-flank contact of modified flanks), "
                    "2 edge (tip-to-flank edge contact: a tip edge on the mating flank)",
                    flag_values=np.array([0, 1, 2], dtype=np.int8), flag_meanings=" ".join(SCENARIOS))


@check_arguments(Impact, exclude=section_keys(Impact))
def impact_dataset(pair: GearPair, *, variant: str = "", fe_compliance: xr.Dataset | None = None,
                   tolerances: dict[str, Any] | None = None, **section: Any) -> xr.Dataset:
    """Mesh-in impact over a torque × speed grid (dims torque, speed): scenario, mesh-in point
    M (3-D, profile and face position, common normal), impact velocity (closing rate and seed
    000's vector form), local stiffness fit, kinetic energy, impact force (closed form and
    exact energy balance), the F–δ curve of each torque, and — at ``design_speed_rpm`` for
    the torques in ``simulate_torques_Nm`` — the direct time integration of the engagement.

    Torques (N·m) on the ``on`` gear, speeds (rpm) of the pinion; ``driver`` which gear drives;
    ``variant`` the micro-geometry variant's name (recorded for the study table); with
    ``method='fe'``, ``fe_compliance`` supplies the FE tables (:func:`gearmesh.fe_tables.seed_cache`).
    ``window_positions``, ``face_samples``: the search window's rolls and the entering line's
    face samples (:func:`gearmesh.impact.impact_model`).

    At the design speed, with ``load_window_step_Nm`` also F_s on a torque grid of that step up
    to 1.25 × the largest torque (:func:`gearmesh.impact.load_grid`; the impact table's load
    windows, anchored at ``design_torque_Nm``, default the middle torque), and with the study's
    ``tolerances`` (:func:`gearmesh.tolerance.study_tolerances`) F_s of the nominal and
    every tolerance sample at each torque (the tolerance spread) and the loaded contact of each
    of those manufactured gears at each torque (:func:`gearmesh.impact.ltca_criteria`, the
    optimiser's criteria on the same model and population: the sign-off table's population basis).

    Parameters
    ----------
    pair : GearPair
        The pair (its modification and deviations).
    variant : str
        The micro-geometry variant's name.
    fe_compliance : xarray.Dataset, optional
        The FE tables of ``method='fe'``.
    tolerances : dict, optional
        The study's ``tolerances:`` section.
    **section
        A study's ``impact:`` section (:class:`gearmesh.settings.Impact`: every default and bound
        there), parsed once (:func:`gearmesh.schema.settings_object`); a bad value is refused
        naming its key.

    Returns
    -------
    xarray.Dataset
        impact.nc, SI.
    """
    s = settings_object(Impact, section)
    on, driver, energy_velocity = s.on, s.driver, s.energy_velocity
    given, t1, speeds = _operating_points(pair, s.torques_Nm, on, s.speeds_rpm)
    design = float(_operating_points(pair, given, on, [s.design_speed_rpm], speed_field="design_speed_rpm")[2][0])
    anchor = _design_torque(given, s.design_torque_Nm)
    if fe_compliance is not None:  # the FE tables of the workflow, before any model is built
        use_fe_tables(fe_compliance, pair_geometry(pair))
    model = _model(pair, s)
    geom = model.geom
    sim_given = _simulated_torques(given, s.simulate_torques_Nm)
    static = impact_static(model, t1)
    static, resp = impact_response(model, static, speeds, energy_velocity)
    ds = xr.Dataset(data_vars=_variables(model, static, resp, *_mesh_in_kinematics(model, static, speeds, driver)),
                    coords={"torque": variable(("torque",), t1, "N m", "pinion torque T1"),
                            "speed": variable(("speed",), speeds, "rpm", "pinion speed"),
                            "level": variable(("level",), np.arange(static.curve_force.shape[-1]), "1",
                                              "load step of the entering pair's force-approach curve"),
                            "xyz": variable(("xyz",), np.array(["x", "y", "z"]), "1", "Cartesian component"),
                            "gear": variable(("gear",), np.array(GEARS), "1", "gear of the pair")})
    ds["torque_input"] = variable(("torque",), given, "N m", f"torque as given, on the {on}")
    ds["design_torque"] = variable((), float(pinion_torques(geom, [anchor], on)[0]), "N m",
                                   "pinion torque the load window is anchored at")
    _add_simulation(ds, model, given, t1, sim_given, design)
    if s.load_window_step_Nm is not None:
        step = float(pinion_torques(geom, [s.load_window_step_Nm], on, "load_window_step_Nm")[0])
        _add_load_grid(ds, model, t1, step, design, energy_velocity)
    judged = t1 if s.tolerance_torques_Nm is None else _among(given, t1, s.tolerance_torques_Nm, "tolerance_torques_Nm")
    _add_tolerance_spread(ds, model, judged, tolerances, design, energy_velocity)
    ds.attrs.update({"variant": variant, "driver": driver, "torque_on": on, "energy_velocity": energy_velocity,
                     "contact_law": model.ltca.law.name, "tooth_model": model.ltca.method,
                     "design_speed_rpm": design, "gear_body": describe_body(model.geom),
                     "system_deflection": describe_deflection(model.geom),
                     "displacement_convention": ("transverse along the line of action, r_b1 * dphi_1 with the gear "
                                                 "held; forces transverse (F_bt = T1/r_b1)")})
    return name_force_lines(ds, "transverse")


def _simulated_torques(given: np.ndarray, simulate_torques_Nm) -> np.ndarray:
    """The torques (as given) whose engagement is integrated in time, each one of ``given``."""
    sim_given = check_torques(simulate_torques_Nm, "simulate_torques_Nm") if len(simulate_torques_Nm) else np.array([])
    for k, t in enumerate(sim_given):
        if not same_point(given, t).any():
            raise GearmeshInputError(f"simulate_torques_Nm[{k}]", float(t), "must be one of torques_Nm")
    return sim_given


def _mesh_in_kinematics(model: ImpactModel, static: ImpactStatic, speeds: np.ndarray, driver: str):
    """Per torque: the mesh-in point M (:func:`gearmesh.impact.kinematics.mesh_in_point`), the
    vector-form impact velocity at each speed (T, S; NaN without a touch) and, for an unmodified
    pair driven by the pinion in edge contact, the roll before A by the mesh-in impact paper's
    reverse-rotation equation (T; NaN elsewhere)."""
    nt = static.scenario.shape[1]
    points = [mesh_in_point(model, static, 0, k) for k in range(nt)]
    vec = np.full((nt, speeds.size), np.nan)
    for k in range(nt):  # v is linear in the speed at fixed geometry: one evaluation per torque
        if static.scenario[0, k]:
            vec[k] = vector_velocity(model, static, float(speeds[0]), 0, k)["transverse_equivalent"] * speeds / speeds[0]
    seed_roll = np.full(nt, np.nan)
    unmodified = not np.any(static.params[0])
    if unmodified and driver == "pinion":
        for k in range(nt):
            if static.scenario[0, k] == 2:
                seed_roll[k] = seed_edge_roll(model.geom, float(static.approach[0, k]))
    return points, vec, seed_roll


def _variables(model: ImpactModel, st: ImpactStatic, rs: ImpactResponse, pts, vec, seed_roll) -> dict:
    t, ts, tl, tx = ("torque",), ("torque", "speed"), ("torque", "level"), ("torque", "xyz")
    c = 0
    geom = model.geom
    return {
        "scenario": _scenario_var(t, st.scenario[c]),
        "roll_before_engagement": variable(t, -st.tau[c], "m",
                                           "pinion roll distance before the theoretical start of engagement at which "
                                           "the entering pair touches (negative: after it)"),
        "roll_before_engagement_seed_equation": variable(
            t, seed_roll, "m", "the same by the mesh-in impact paper's reverse-rotation equation (corrected; unmodified pairs with "
                               "edge contact only, else NaN)"),
        "approach_at_mesh_in": variable(t, st.approach[c], "m",
                                        "loaded approach of the pairs in mesh when the entering pair touches"),
        "te_at_engagement": variable(t, st.te_engagement[c], "m",
                                     "entering pair's unloaded separation at phi_1A (TE(phi_1A) of the mesh-in impact paper)"),
        "lte_at_engagement": variable(t, st.lte_engagement[c], "m", "loaded TE of the mesh at phi_1A (LTE(phi_1A))"),
        "gap_rate": variable(t, st.gap_rate[c], "1", "closing rate of the entering pair's separation per unit roll"),
        "approach_rate": variable(t, st.approach_rate[c], "1", "rate of the loaded approach per unit roll"),
        "mesh_in_s": variable(t, st.s[c], "m", "mesh-in point M: position on the transverse line of action from A"),
        "mesh_in_point": variable(tx, np.array([p["point"] for p in pts]), "m",
                                  "mesh-in point M in the fixed frame at the touch (pinion centre at 0, gear at +x)"),
        "mesh_in_point_pinion": variable(tx, np.array([p["point_pinion"] for p in pts]), "m",
                                         "mesh-in point M in the pinion body frame (tooth centreline on +y)"),
        "mesh_in_normal": variable(tx, np.array([p["normal"] for p in pts]), "1",
                                   "unit common normal at M (fixed frame, out of the pinion flank)"),
        "mesh_in_pinion_radius": variable(t, np.array([p["pinion_radius"] for p in pts]), "m",
                                          "pinion radius of M (profile position)"),
        "mesh_in_rho_pinion": variable(t, st.rho_pinion[c], "m", "pinion roll length of M"),
        "mesh_in_rho_gear": variable(t, st.rho_gear[c], "m", "gear roll length of M"),
        "mesh_in_face_position": variable(t, st.z[c], "m", "axial position of M (face centre at 0)"),
        "velocity_transverse": variable(ts, rs.velocity_transverse[c], "m s-1",
                                        "impact velocity: closing rate of the entering pair's separation, transverse "
                                        "line of action"),
        "velocity_normal": variable(ts, rs.velocity_normal[c], "m s-1",
                                    "impact velocity along the 3-D common normal (transverse x cos beta_b)"),
        "velocity_vector_form": variable(ts, vec, "m s-1",
                                         "the mesh-in impact paper's (w1 - w2) x r - E x w2 on the common normal at the exact closest "
                                         "points of the modified profiles, in the transverse line-of-action coordinate"),
        "kinetic_energy": variable(ts, rs.kinetic_energy[c], "J", "kinetic energy 1/2 m_eq v^2 of the impact"),
        "impact_force": variable(ts, rs.force[c], "N",
                                 f"{IMPACT_INDEX}: the mesh-in impact paper's energy method, closed form with the fitted "
                                 f"K_s, n (transverse; an index of the impact, not a force the teeth carry)"),
        "impact_force_energy_balance": variable(ts, rs.force_energy_balance[c], "N",
                                                f"{IMPACT_INDEX} by the energy balance on the computed "
                                                "force-approach curve (transverse)"),
        "impact_approach": variable(ts, rs.approach_energy_balance[c], "m", "peak approach of the entering pair"),
        "stiffness_coefficient": variable(ts, rs.stiffness_coefficient[c], "N m-n",
                                          "K_s of F = K_s delta^n at M (transverse, SI)"),
        "stiffness_exponent": variable(ts, rs.stiffness_exponent[c], "1", "n of F = K_s delta^n at M"),
        "stiffness_fit_rel_error": variable(ts, rs.fit_error[c], "1", "RMS relative error of the power-law fit"),
        "curve_force": variable(tl, st.curve_force[c], "N", "entering pair alone from M: transverse force"),
        "curve_approach": variable(tl, st.curve_approach[c], "m", "entering pair alone from M: approach"),
        "equivalent_mass": variable((), model.equivalent_mass, "kg", "m_eq = J1 J2/(J1 r_b2^2 + J2 r_b1^2)"),
        "inertia": variable(("gear",), model.inertia, "kg m2", "polar moment (disc of the base radius less "
                                                               "the bore, as the mesh-in impact paper, "
                                                               "plus added inertia)"),
        "base_radius": variable(("gear",), geom.base_radius, "m", "base radius"),
        "rho_sap": variable(("gear",), geom.rho_sap, "m", "roll length of the start of active profile"),
        "rho_eap": variable(("gear",), geom.rho_eap, "m", "roll length of the end of active profile"),
        "face_width": variable((), geom.face_width, "m", "meshing face width"),
    }


def _among(given: np.ndarray, t1: np.ndarray, torques, field: str) -> np.ndarray:
    """The pinion torques of ``torques`` (as given, on the section's gear), each one of ``given``."""
    out = []
    for k, t in enumerate(check_torques(torques, field)):
        match = np.flatnonzero(same_point(given, t))
        if not match.size:
            raise GearmeshInputError(f"{field}[{k}]", float(t), "must be one of torques_Nm")
        out.append(t1[match[0]])
    return np.array(out)


def _design_torque(given: np.ndarray, design_torque_Nm: float | None) -> float:
    """The anchor of the load window: ``design_torque_Nm`` (one of the torques), or the middle torque."""
    if design_torque_Nm is None:
        return float(np.sort(given)[(given.size - 1) // 2])
    if not same_point(given, design_torque_Nm).any():
        raise GearmeshInputError("design_torque_Nm", design_torque_Nm, "must be one of torques_Nm")
    return float(design_torque_Nm)


def _design_response(model: ImpactModel, torques, params, lead, speed: float, energy_velocity: str):
    """F_s (closed form, energy balance) and scenario (C, T) at one speed."""
    static = impact_static(model, torques, params, lead_slope=lead, engagement=False)
    static, resp = impact_response(model, static, [speed], energy_velocity)
    return resp.force[..., 0], resp.force_energy_balance[..., 0], static.scenario


def _add_load_grid(ds: xr.Dataset, model: ImpactModel, t1, step: float, design: float, energy_velocity: str) -> None:
    if not step > 0 or not np.isfinite(step) or 1.25 * t1.max() / step > MAX_WINDOW_TORQUES:
        raise GearmeshInputError("load_window_step_Nm", step,
                                 f"must be a positive step giving at most {MAX_WINDOW_TORQUES} torques")
    grid = load_grid(t1, step)
    force, force_eb, scen = _design_response(model, grid, None, None, design, energy_velocity)
    w = ("window_torque",)
    ds.coords["window_torque"] = variable(w, grid, "N m", "pinion torques of the load-window grid")
    ds["window_impact_force"] = variable(w, force[0], "N", "F_s (closed form) on the load-window grid at the design "
                                                           "speed")
    ds["window_impact_force_energy_balance"] = variable(w, force_eb[0], "N", "F_s (energy balance) on the load-window "
                                                                             "grid at the design speed")
    ds["window_scenario"] = _scenario_var(w, scen[0])


def _add_tolerance_spread(ds: xr.Dataset, model: ImpactModel, t1, tolerances, design: float,
                          energy_velocity: str) -> None:
    """The manufactured gears of the study's ``tolerances`` (:mod:`gearmesh.robust`) at every torque and
    the design speed: the worst of each criterion over the tolerance box (``box_worst_*``, and the
    gear, as unit deviations, where it was found), a seeded population beside it for the
    distributions (``population_*``, gear 0 the nominal; the same deviations for every variant, so
    the sign-off table compares gear for gear) and a held-out population (``heldout_*``, its own
    seed) that checks the verdict on gears no optimiser saw; every gear is a pair file again with
    :func:`gearmesh.robust.manufactured_pair` (``gearmesh manufactured``)."""
    tol = study_tolerances(model.geom, tolerances)[0]
    population, seed, heldout, heldout_seed = study_population(tolerances)
    if not tol.dimensions:
        return
    params = model.params()[0]
    dims = tol.labels()
    ds.coords["criterion"] = variable(("criterion",), np.array(CRITERIA), "1", "sign-off criterion of one gear")
    ds.coords["judged_torque"] = variable(("judged_torque",), t1, "N m", "pinion torques at which the manufactured "
                                          "gears are judged")
    ds.coords["tolerance_dimension"] = variable(("tolerance_dimension",), np.array(dims), "1",
                                                "toleranced quantity (unit deviation: ±1 its tolerance)")
    worst, box = design_box_worst(model, tol, params, t1, design, energy_velocity)
    of = "over the tolerance box at the design speed (the worst manufactured gear, searched)"
    for k, name in enumerate(CRITERIA):
        ds[f"box_worst_{name}"] = variable(("judged_torque",), worst.values[:, k], CRITERION_UNITS[name],
                                           f"{_CRITERION_NAMES[name]}, largest {of}")
        ds[f"box_worst_units_{name}"] = variable(("judged_torque", "tolerance_dimension"),
                                                 box.full_units(worst.points[:, k]), "1",
                                                 f"the manufactured gear of box_worst_{name}: its unit deviations")
    ds.coords["parameter"] = variable(("parameter",), np.array(MODIFICATION_FIELDS), "1", "modification parameter")
    for k, name in enumerate(CRITERIA):
        rows, lead = box.gears(model.geom, params, model.lead_slope, worst.points[:, k])
        ds[f"box_worst_modification_{name}"] = variable(("judged_torque", "gear", "parameter"), rows, "m",
                                                        f"modification of the manufactured gear of box_worst_{name}")
        ds[f"box_worst_lead_slope_{name}"] = variable(("judged_torque", "gear"), lead, "m",
                                                      f"lead slope deviations of the gear of box_worst_{name}")
    ds.attrs.update({"box_evaluated": int(worst.evaluated), "box_dimensions": int(box.size)})
    for prefix, count, seed_, what in (("population", population, seed, "seeded population (gear 0 the nominal)"),
                                       ("heldout", heldout, heldout_seed, "held-out population")):
        units = population_units(tol, count, seed_)
        if prefix == "population":
            units = np.vstack([np.zeros((1, len(dims))), units])
        if not units.shape[0]:
            continue
        rows, lead = manufactured_population(model.geom, tol, params[None], model.lead_slope, units)
        rows, lead = rows[1:], lead[1:]  # manufactured_population puts the nominal before the units' gears
        c = gear_criteria(model, rows, lead, t1, design, energy_velocity,
                          samples=rows.shape[0] if prefix == "population" else 1)
        gear = f"{prefix}_gear"
        ds.coords[gear] = variable((gear,), np.arange(units.shape[0]), "1", f"manufactured gear of the {what}")
        ds[f"{prefix}_units"] = variable((gear, "tolerance_dimension"), units, "1",
                                         f"unit deviations of each gear of the {what}")
        ds[f"{prefix}_modification"] = variable((gear, "gear", "parameter"), rows, "m",
                                                f"modification of each gear of the {what}, as made")
        ds[f"{prefix}_lead_slope"] = variable((gear, "gear"), lead, "m",
                                              f"lead slope deviations of each gear of the {what}")
        for k, name in enumerate(CRITERIA):
            ds[f"{prefix}_{name}"] = variable((gear, "judged_torque"), c.values[..., k], CRITERION_UNITS[name],
                                              f"{_CRITERION_NAMES[name]} of each gear of the {what}")
        if prefix == "population":
            ds["population_impact_force_energy_balance"] = variable(
                (gear, "judged_torque"), c.impact_force_energy_balance, "N", f"F_s by the energy balance, {what}")
            ds["population_scenario"] = _scenario_var((gear, "judged_torque"), c.scenario)
    ds.attrs["design_pair_json"] = json.dumps(pair_to_dict(model.geom.pair))
    ds.attrs.update({"tolerance_population": int(population), "tolerance_seed": int(seed),
                     "tolerance_heldout": int(heldout), "tolerance_heldout_seed": int(heldout_seed),
                     "lead_grade_iso1328": -1 if tol.grade is None else tol.grade, "toleranced": ", ".join(dims)})


#: The long names of the sign-off criteria of one gear (:data:`gearmesh.robust.CRITERIA`).
_CRITERION_NAMES = {"impact_force": "energy-method impact index F_s (closed form, transverse)",
                    **{f"lte_order_{k}": f"amplitude of the loaded transmission error at mesh order {k}"
                       for k in MESH_ORDERS},
                    "peak_flank_pressure": "largest Hertzian contact pressure on the flanks' active zone (tip edges "
                                           "left out) over one mesh cycle",
                    "peak_edge_pressure": "largest Hertzian contact pressure of a tip edge on the mating flank "
                                          "(0: no edge contact) over one mesh cycle",
                    "peak_root_stress": "largest tooth-root stress of either gear (ISO 6336-3 local form, slice by "
                                        "slice) over one mesh cycle"}


def _add_simulation(ds: xr.Dataset, model: ImpactModel, given, t1, sim_given, design: float) -> None:
    nt = t1.size
    peak, enter, excess = np.full(nt, np.nan), np.full(nt, np.nan), np.full(nt, np.nan)
    series = None
    for t in sim_given:
        k = int(np.flatnonzero(same_point(given, t))[0])
        r = simulate_engagement(model, float(t1[k]), design)
        peak[k], enter[k], excess[k] = r["peak_above_static"], r["entering_peak"], r["entering_excess"]
        if series is None:
            series = (k, r)
    window = "from the touch to one natural period of the mesh after it"
    ds["simulated_peak_above_static"] = variable(("torque",), peak, "N",
                                                 "direct time integration at the design speed: mesh force peak "
                                                 f"above the static force {window} (NaN: not run)")
    ds["simulated_entering_peak"] = variable(("torque",), enter, "N",
                                             f"direct time integration: the entering pair's largest force {window}")
    ds["simulated_entering_excess"] = variable(("torque",), excess, "N",
                                               "direct time integration: the entering pair's largest excess over its "
                                               f"quasi-static force {window} (the dynamic impact)")
    if series is not None:
        k, r = series
        dims = ("sim_time",)
        ds.coords["sim_time"] = variable(dims, r["time"], "s", "time from the start of the simulation")
        ds["sim_mesh_force"] = variable(dims, r["mesh_force"], "N", "simulated transverse mesh force (all pairs)")
        ds["sim_entering_force"] = variable(dims, r["entering_force"], "N", "simulated force of the entering pair")
        ds["sim_approach"] = variable(dims, r["approach"], "m", "simulated approach (relative coordinate)")
        ds["sim_static_force"] = variable((), r["static_force"], "N", "static transverse force F_bt")
        ds["sim_touch_time"] = variable((), r["touch_time"], "s", "time of the quasi-static touch")
        ds["sim_period"] = variable((), r["period"], "s", "natural period 2 pi sqrt(m_eq/k) of the loaded mesh")
        ds["sim_peak_time"] = variable((), r["peak_time"], "s", "time of the entering pair's largest excess over "
                                       "its quasi-static force")
        ds["sim_entering_static"] = variable(dims, r["entering_static"], "N",
                                             "quasi-static force of the entering pair at the same mesh position")
        ds["sim_torque"] = variable((), float(t1[k]), "N m", "pinion torque of the simulated time series")


def impact_table_dataset(impact: Sequence[xr.Dataset]) -> xr.Dataset:
    """The mesh-in impact paper's table of impact forces: the impact index F_s of every variant at
    every torque at the design speed, with the scenario and the reduction against the ``standard``
    variant (%); and, where the impact stage computed them, each variant's load window against
    ``standard``, the range of F_s under the study's tolerance samples, and at the simulated
    torques the entering pair's simulated excess over its quasi-static force with F_s over it.

    Parameters
    ----------
    impact : Sequence[xarray.Dataset]
        Each variant's impact.nc (:func:`impact_dataset`), of one pair and the same torques.

    Returns
    -------
    xarray.Dataset
        impact_table.nc (dims variant, torque; judged_torque where the tolerances were judged):
        ``impact_force`` and ``impact_force_energy_balance`` (N), ``scenario``,
        ``velocity_transverse`` (m/s), ``reduction_percent`` (%), and where computed
        ``load_window_low``/``_high`` (N·m), ``tolerance_min``/``max_impact_force`` (N),
        ``simulated_entering_excess`` (N) and ``impact_index_over_simulated_excess`` (1).

    Raises
    ------
    GearmeshInputError
        Naming ``impact`` (not one pair's variants), ``impact.torques_Nm`` or
        ``impact.tolerance_torques_Nm`` (torques that differ between variants), or
        ``impact.load_window_step_Nm`` (load-window grids that differ).

    References
    ----------
    .. [1] *Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears*
       (docs/references.md, document 000): its table of impact forces per variant.
    """
    names = variant_names("impact", impact)
    torque = shared_torques("impact.torques_Nm", names, impact)
    rows = []
    for ds in impact:
        design = float(ds.attrs["design_speed_rpm"])
        sel = ds.sel(speed=design)
        rows.append((sel["impact_force"].values, sel["impact_force_energy_balance"].values, ds["scenario"].values,
                     sel["velocity_transverse"].values))
    force = np.array([r[0] for r in rows])
    ref = force[names.index("standard")] if "standard" in names else np.full(torque.size, np.nan)
    dims = ("variant", "torque")
    extra = _table_windows(impact, names) | _table_spread(impact, names) | _table_simulated(impact, force)
    table = xr.Dataset(extra | {
        "impact_force": variable(dims, force, "N", f"{IMPACT_INDEX} at the design speed (closed form of the energy "
                                                   f"method; an index of the impact, not a force the teeth carry)"),
        "impact_force_energy_balance": variable(dims, np.array([r[1] for r in rows]), "N",
                                                f"{IMPACT_INDEX} by the energy balance at the design speed"),
        "scenario": _scenario_var(dims, np.array([r[2] for r in rows])),
        "velocity_transverse": variable(dims, np.array([r[3] for r in rows]), "m s-1", "impact velocity (transverse)"),
        "reduction_percent": variable(dims, 100.0 * (1.0 - force / ref[None, :]), "%",
                                      "reduction of F_s against the standard variant"),
    }, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
               "torque": variable(("torque",), torque, "N m", "pinion torque T1")})
    table.attrs.update({key: str(impact[0].attrs.get(key, "")) for key in ("tooth_model", "contact_law")})
    return name_force_lines(table, "transverse")


def _table_simulated(impact: Sequence[xr.Dataset], force: np.ndarray) -> dict[str, xr.Variable]:
    """At the torques whose engagement was simulated in time (design speed; NaN elsewhere): the
    entering pair's largest excess over its quasi-static force and F_s over it, beside F_s."""
    if not all("simulated_entering_excess" in ds for ds in impact):
        return {}
    excess = np.array([ds["simulated_entering_excess"].values for ds in impact])
    if not np.isfinite(excess).any():
        return {}
    dims = ("variant", "torque")
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(excess > 0, force / excess, np.nan)
    return {
        "simulated_entering_excess": variable(dims, excess, "N", "direct time integration of the engagement: the "
                                              "entering pair's largest excess over its quasi-static force"),
        "impact_index_over_simulated_excess": variable(dims, ratio, "1", "F_s over the simulated excess of the "
                                                       "entering pair: how far the energy method's index lies above "
                                                       "what the teeth carry in the time integration"),
    }


def _table_windows(impact: Sequence[xr.Dataset], names: list[str]) -> dict[str, xr.Variable]:
    """Each variant's load window against ``standard`` (when the variants have the load-window grid)."""
    if "standard" not in names or not all("window_impact_force" in ds for ds in impact):
        return {}
    std = impact[names.index("standard")]
    bounds = []
    for ds in impact:
        if not np.array_equal(ds["window_torque"].values, std["window_torque"].values):
            raise GearmeshInputError("impact.load_window_step_Nm", None, "must give the same grid for every variant")
        bounds.append(load_window(ds["window_torque"].values, ds["window_impact_force"].values,
                                  std["window_impact_force"].values, float(ds["design_torque"])))
    bounds = np.array(bounds)
    what = ("the contiguous pinion-torque range around the design torque where the variant's F_s (closed form, design "
            "speed) is below the standard's (grid ends; NaN: not at the design torque; standard: none)")
    return {"load_window_low": variable(("variant",), bounds[:, 0], "N m", f"load window, low end: {what}"),
            "load_window_high": variable(("variant",), bounds[:, 1], "N m", f"load window, high end: {what}")}


def _table_spread(impact: Sequence[xr.Dataset], names: list[str]) -> dict[str, xr.Variable]:
    """F_s of each variant over its manufactured gears at each torque: the smallest of the population,
    and the largest over the tolerance box (the box worst, or the population's where larger)."""
    if not all("population_impact_force" in ds for ds in impact):
        return {}
    dims = ("variant", "judged_torque")
    judged = shared_torques("impact.tolerance_torques_Nm", names, impact, "judged_torque")
    spread = np.array([ds["population_impact_force"].values for ds in impact])  # (V, S, T)
    worst = np.maximum(spread.max(axis=1), np.array([ds["box_worst_impact_force"].values for ds in impact]))
    return {
        "judged_torque": variable(("judged_torque",), judged, "N m", "pinion torques of the manufactured gears"),
        "tolerance_min_impact_force": variable(dims, spread.min(axis=1), "N",
                                               "smallest F_s over the manufactured population"),
        "tolerance_max_impact_force": variable(dims, worst, "N", "largest F_s over the tolerance box (the worst "
                                               "manufactured gear)"),
    }


def manufactured_gear(path, heldout: int | None = None, population: int | None = None, worst: str | None = None,
                      torque_Nm: float | None = None) -> GearPair:
    """One manufactured gear of a variant's impact.nc (``path``) as a pair
    (:func:`gearmesh.robust.manufactured_pair`): gear ``heldout`` of the held-out population, gear
    ``population`` of the population, or the worst gear over the tolerance box of criterion ``worst``
    at pinion torque ``torque_Nm``. Refused in one line naming the option otherwise.

    Parameters
    ----------
    path : str or path-like
        A variant's impact.nc of a study with a ``tolerances`` section.
    heldout : int, optional
        Index of a gear of the held-out population.
    population : int, optional
        Index of a gear of the population (used when ``heldout`` is None).
    worst : str, optional
        A criterion of :data:`gearmesh.robust.CRITERIA`: the worst gear over the tolerance box;
        takes precedence over ``heldout`` and ``population``.
    torque_Nm : float, optional
        Pinion torque (N·m), one of the file's judged torques; required with ``worst``.

    Returns
    -------
    GearPair
        The design pair with that gear's micro-geometry and lead slope, named after it.

    Raises
    ------
    GearmeshInputError
        Naming ``impact`` (no readable impact.nc, or one without manufactured gears),
        ``--worst``, ``--torque-Nm``, ``--heldout`` or ``--population``.
    """
    from pathlib import Path

    from ..io import read_dataset
    from ..robust import manufactured_pair

    if not Path(path).is_file():
        raise GearmeshInputError("impact", str(path), "must be a variant's impact.nc file")
    try:
        ds = read_dataset(path)
    except (OSError, ValueError) as exc:
        raise GearmeshInputError("impact", str(path), f"cannot be read as netCDF ({type(exc).__name__})") from None
    if "design_pair_json" not in ds.attrs:
        raise GearmeshInputError("impact", str(path), "holds no manufactured gears (a study with a tolerances section)")
    design = load_pair(json.loads(ds.attrs["design_pair_json"]))
    if worst is not None:
        if worst not in CRITERIA:
            raise GearmeshInputError("--worst", worst, f"must be one of {list(CRITERIA)}")
        judged = ds["judged_torque"].values
        k = np.flatnonzero(same_point(judged, torque_Nm)) if torque_Nm is not None else np.array([], dtype=int)
        if not k.size:
            raise GearmeshInputError("--torque-Nm", torque_Nm, f"must be one of the judged pinion torques "
                                     f"{judged.tolist()} (N m)")
        params, lead = (ds[f"box_worst_{what}_{worst}"].values[k[0]] for what in ("modification", "lead_slope"))
        return manufactured_pair(design.with_changes(name=f"{design.name}_worst_{worst}"), params, lead)
    prefix, gear = ("heldout", heldout) if heldout is not None else ("population", population)
    size = ds.sizes.get(f"{prefix}_gear", 0)
    if gear is None or not 0 <= gear < size:
        raise GearmeshInputError(f"--{prefix}", gear, f"must be a gear 0 ... {size - 1} of the {prefix} population")
    return manufactured_pair(design.with_changes(name=f"{design.name}_{prefix}_{gear}"),
                             ds[f"{prefix}_modification"].values[gear], ds[f"{prefix}_lead_slope"].values[gear])


#: The keys of the impact map that one impact (:func:`impact_summary`) takes as its own arguments or has not.
_MAP_KEYS = ("torques_Nm", "speeds_rpm", "design_speed_rpm", "simulate_torques_Nm", "design_torque_Nm",
             "load_window_step_Nm", "tolerance_torques_Nm")


@check_arguments(Impact, exclude=section_keys(Impact))
def impact_summary(pair: GearPair, torque_Nm, speed_rpm, *, simulate: bool = False, **section: Any) -> dict[str, Any]:
    """Headline numbers of one impact in engineering units (the CLI's ``impact --json``).

    Parameters
    ----------
    pair : GearPair
        The pair (its modification and deviations).
    torque_Nm : float
        The one torque (N·m) on ``section``'s ``on``.
    speed_rpm : float
        The one pinion speed (rpm).
    simulate : bool
        Also integrate the engagement in time at this torque and speed.
    **section
        A study's ``impact:`` section but its map (torques, speeds, load window, simulated and
        judged torques; :class:`gearmesh.settings.Impact`), parsed once
        (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    dict
        The headline numbers (N, m/s, µm, mm).
    """
    refuse_operating_point(section, _MAP_KEYS, "one torque_Nm and one speed_rpm")
    s = settings_object(Impact, section)
    for name, value in (("torque_Nm", torque_Nm), ("speed_rpm", speed_rpm)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
            raise GearmeshInputError(name, value, "must be one positive number")
    t1, speed = _operating_points(pair, [torque_Nm], s.on, [speed_rpm], "torque_Nm", "speed_rpm")[1:]
    model = _model(pair, s)
    energy_velocity = s.energy_velocity
    static = impact_static(model, t1)
    static, resp = impact_response(model, static, speed, energy_velocity)
    um, mm = 1e6, 1e3
    scen = SCENARIOS[int(static.scenario[0, 0])]
    out: dict[str, Any] = {
        "name": pair.name, "torque_Nm": float(torque_Nm), "torque_on": s.on, "pinion_torque_Nm": float(t1[0]),
        "speed_rpm": float(speed[0]), "driver": s.driver, "tooth_model": s.method, "contact_law": s.contact_law,
        "scenario": scen,
        "impact_force_transverse_N": float(resp.force[0, 0, 0]),
        "impact_force_energy_balance_transverse_N": float(resp.force_energy_balance[0, 0, 0]),
        "impact_velocity_normal_m_per_s": float(resp.velocity_normal[0, 0, 0]),
        "impact_velocity_transverse_m_per_s": float(resp.velocity_transverse[0, 0, 0]),
        "approach_at_mesh_in_um": float(static.approach[0, 0]) * um,
        "te_at_engagement_um": float(static.te_engagement[0, 0]) * um,
        "lte_at_engagement_um": float(static.lte_engagement[0, 0]) * um,
        "stiffness_coefficient": float(resp.stiffness_coefficient[0, 0, 0]),
        "stiffness_exponent": float(resp.stiffness_exponent[0, 0, 0]),
        "stiffness_fit_rel_error": float(resp.fit_error[0, 0, 0]),
        "equivalent_mass_kg": model.equivalent_mass,
        "kinetic_energy_J": float(resp.kinetic_energy[0, 0, 0]),
        "roll_before_engagement_mm": -float(static.tau[0, 0]) * mm,
    }
    if scen != "none":
        vec = vector_velocity(model, static, float(speed[0]))
        out["impact_velocity_vector_form_transverse_m_per_s"] = vec["transverse_equivalent"]
        p = mesh_in_point(model, static)
        x, y, z = (float(v) * mm for v in p["point_pinion"])
        out["mesh_in_point"] = {"x_mm": x, "y_mm": y, "z_mm": z, "pinion_radius_mm": p["pinion_radius"] * mm,
                                "face_position_mm": p["face_position"] * mm}
        out["common_normal"] = [float(v) for v in p["normal"]]
    if simulate:
        if scen == "none":
            raise GearmeshInputError("torque_Nm", torque_Nm, "gives no mesh-in contact to simulate")
        r = simulate_engagement(model, float(t1[0]), float(speed[0]))
        out["simulated_peak_force_transverse_N"] = r["peak_above_static"]
        out["simulated_entering_peak_force_transverse_N"] = r["entering_peak"]
        out["simulated_entering_impact_force_transverse_N"] = r["entering_excess"]
        out["static_force_transverse_N"] = r["static_force"]
    return out
