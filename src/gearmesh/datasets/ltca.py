"""TCA and LTCA datasets (tca.nc, ltca.nc) and the CLI summary of an LTCA.

Engineering units at the boundary (µm, N·m), SI inside every Dataset; every variable
carries ``units`` and ``long_name``. Physics: :mod:`gearmesh.tca`, :mod:`gearmesh.ltca`.
Displacements are transverse along the line of action (r_b1·Δφ1, gear held); positive
TE/LTE means the gear lags its conjugate position.
"""

from __future__ import annotations

from typing import Sequence, Any

import numpy as np
import xarray as xr

from ..fe_tables import use_fe_tables
from ..errors import GearmeshInputError
from ..gear import GEARS, GearPair, pair_geometry
from . import shared_torques, variant_names
from ..io import name_force_lines, variable
from ..limits import check_contact_grid, same_point
from ..ltca import MESH_ORDERS, LTCAResult, loaded_pinion_torques, ltca
from ..tca import TCAResult, check_modifications, tca
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..body import describe_body, mesh_body_compliance
from ..deflection import describe_deflection
from ..settings import Ltca, Tca

UM = 1e-6

__all__ = ["tca_dataset", "ltca_dataset", "ltca_summary", "lte_table_dataset"]



def refuse_operating_point(section: dict[str, Any], keys: Sequence[str], instead: str) -> None:
    """Refuse a key of a stage's map (``keys``) given to a function of one operating point, naming
    the argument it takes ``instead``: it would be parsed and then ignored.

    Parameters
    ----------
    section : dict[str, Any]
        The keyword arguments the function was given (the study's section).
    keys : Sequence[str]
        The keys of the stage's map the function does not take.
    instead : str
        What the function takes in their place, as the error says it.

    Raises
    ------
    GearmeshInputError
        Naming the first of ``keys`` found in ``section``.
    """
    for key in keys:
        if key in section:
            raise GearmeshInputError(key, section[key], f"is the stage's map; this function takes {instead}")


def _geometry(pair: GearPair):
    if not isinstance(pair, GearPair):
        raise GearmeshInputError("pair", type(pair).__name__, "must be a GearPair")
    check_modifications(pair)
    return pair_geometry(pair)


def _scalar(value, units: str, long_name: str) -> xr.Variable:
    return variable((), float(value), units, long_name)


def _tca_variables(geom, res: TCAResult) -> dict[str, xr.Variable]:
    g = res.grid
    pjn, pj = ("position", "line", "point"), ("position", "line")
    return {
        "separation": variable(pjn, g.gap, "m", "unloaded transverse separation along the line of action "
                                                "(NaN: no candidate contact)"),
        "region": variable(pjn, g.region, "1", "candidate region: 0 none, 1 flank (active zone), 2 gear tip edge on "
                                               "pinion flank before A, 3 pinion tip edge on gear flank after E"),
        "s": variable(pjn, g.s, "m", "position on the transverse line of action from the start of active profile"),
        "rho_pinion": variable(pjn, g.rho_pinion, "m", "pinion roll length of the touched point"),
        "rho_gear": variable(pjn, g.rho_gear, "m", "gear roll length of the touched point"),
        "te": variable(("position",), res.te, "m",
                       "unloaded transmission error (transverse, along the line of action; + gear lags)"),
        "te_gear_angle": variable(("position",), res.te / geom.base_radius[1], "rad",
                                  "unloaded transmission error as gear lag angle TE/r_b2"),
        "te_pair": variable(pj, res.te_pair, "m", "unloaded separation of each tooth pair (its own TE curve)"),
        "contact_s": variable(pj, res.contact_s, "m", "first-contact point of each pair: position on the line of action"),
        "contact_z": variable(pj, res.contact_z, "m", "first-contact point of each pair: axial position"),
        "contact_rho_pinion": variable(pj, res.contact_rho_pinion, "m",
                                       "first-contact point of each pair: pinion roll length"),
        "contact_rho_gear": variable(pj, res.contact_rho_gear, "m", "first-contact point of each pair: gear roll length"),
        "te_peak_to_peak": _scalar(res.te_peak_to_peak, "m", "peak-to-peak unloaded transmission error"),
        "roll_engagement": _scalar(res.roll_engagement, "m",
                                   "pinion roll distance of the theoretical start of engagement phi_1A"),
        "pinion_angle_engagement": _scalar(res.roll_engagement / geom.base_radius[0], "rad",
                                           "pinion angle of the theoretical start of engagement phi_1A"),
        "pair_engagement": variable((), np.int64(res.pair_engagement), "1", "index of the entering tooth pair at phi_1A"),
        "z_engagement": _scalar(res.z_engagement, "m", "axial position of the entering corner at phi_1A"),
        "te_at_engagement": _scalar(res.te_at_engagement, "m", "unloaded TE of the mesh at phi_1A"),
        "te_next_pair_at_engagement": _scalar(res.te_next_pair_at_engagement, "m",
                                              "unloaded separation of the entering pair at phi_1A "
                                              "(TE(phi_1A) of the mesh-in impact paper)"),
        "lead_slope": variable(("gear",), np.array(res.lead_slope), "m",
                               "helix slope deviation f_Hbeta over the face width (transverse; + the flank stands "
                               "proud at the leading face end)"),
        "profile_slope": variable(("gear",), np.array(geom.pair.deviations.profile_slope), "m",
                                  "profile slope deviation f_Halpha over the active profile (+ the flank stands proud "
                                  "at the tip)"),
        "stated_mesh_misalignment": _scalar(res.misalignment, "m", "mesh misalignment f_ma stated in the pair file "
                                            "(the convention of the lead slope deviations; 0: none stated)"),
        "transverse_base_pitch": _scalar(geom.transverse_base_pitch, "m", "transverse base pitch (mesh cycle)"),
        "path_of_contact": _scalar(geom.path_of_contact, "m", "length of the transverse path of contact"),
        "face_width": _scalar(geom.face_width, "m", "meshing face width"),
        "base_helix_angle": _scalar(geom.base_helix_angle, "rad", "base helix angle"),
        "rho_sap": variable(("gear",), geom.rho_sap, "m", "roll length of the start of active profile"),
        "rho_eap": variable(("gear",), geom.rho_eap, "m", "roll length of the end of active profile"),
        "point_width": _scalar(g.dz, "m", "face width represented by each point (slice width)"),
    }


def _coords(geom, res: TCAResult) -> dict[str, xr.Variable]:
    g = res.grid
    return {
        "position": variable(("position",), g.roll, "m", "pinion roll distance r_b1 phi_1 over one mesh cycle"),
        "pinion_angle": variable(("position",), g.roll / geom.base_radius[0], "rad", "pinion rotation angle phi_1"),
        "line": variable(("line",), g.pairs, "1", "tooth-pair index j along the line of action"),
        "point": variable(("point",), g.z, "m", "axial position z of the point (slice centre), face centre at 0"),
        "gear": variable(("gear",), np.array(GEARS), "1", "gear of the pair (pinion drives)"),
    }


@check_arguments(Tca, exclude=section_keys(Tca))
def tca_dataset(pair: GearPair, **section: Any) -> xr.Dataset:
    """Unloaded TCA over one mesh cycle (dims position, line, point): separations of every
    candidate point (flank and tip edges), the TE curve of the mesh and of each pair, the
    first-contact point of each pair and the values at the start of engagement φ1A; the pair's
    manufacturing deviations included (:mod:`gearmesh.deviation`).

    Parameters
    ----------
    pair : GearPair
        The pair (its modification and deviations).
    **section
        A study's ``tca:`` section: ``positions``, ``points``, ``corner_extension``
        (:class:`gearmesh.settings.Tca` declares their defaults and bounds), parsed once by
        :func:`gearmesh.schema.settings_object`, which refuses a bad value naming its key.

    Returns
    -------
    xarray.Dataset
        tca.nc, SI.
    """
    s = settings_object(Tca, section)
    geom = _geometry(pair)
    positions, points = check_contact_grid(s.positions, s.points)
    res = tca(geom, positions, points, None, s.corner_extension)
    ds = xr.Dataset(data_vars=_tca_variables(geom, res), coords=_coords(geom, res))
    ds.attrs["displacement_convention"] = ("transverse along the line of action, r_b1 * dphi_1 with the gear held; "
                                           "normal depths divided by cos(beta_b)")
    return ds


@check_arguments(Ltca, exclude=section_keys(Ltca))
def ltca_dataset(pair: GearPair, *, fe_compliance: xr.Dataset | None = None, **section: Any) -> xr.Dataset:
    """LTCA at each torque over one mesh cycle (dims torque, position, line, point).

    Loaded TE, load and line load of every point (the contact pattern), load per tooth
    pair, maximum line load, tangent mesh stiffness dF/dδ, pairs in contact, load on tip
    edges, and LTE at the start of engagement φ1A beside the entering pair's unloaded
    separation there and whether the entering pair touches before A
    (:func:`teeth_approach_at_engagement`). Also carries the TCA variables of
    :func:`tca_dataset` on the same grid. The pair's deviations and the system deflection of its
    stated supports are in the contact (``mesh_misalignment``, ``system_approach``;
    :mod:`gearmesh.deflection`).

    Parameters
    ----------
    pair : GearPair
        The pair (its modification, deviations and supports).
    fe_compliance : xarray.Dataset, optional
        The FE tables of ``method='fe'`` (:func:`gearmesh.fe_tables.seed_cache`).
    **section
        A study's ``ltca:`` section (:class:`gearmesh.settings.Ltca`: every default and bound
        there), parsed once (:func:`gearmesh.schema.settings_object`): ``torques_Nm`` (N·m) on
        the pinion, or on the gear with ``on='gear'`` (then T1 = T2·z1/z2), the contact law, the
        slice model ``method``, the grid and the corner extension.

    Returns
    -------
    xarray.Dataset
        ltca.nc, SI.
    """
    s = settings_object(Ltca, section)
    geom = _geometry(pair)
    positions, _ = check_contact_grid(s.positions, s.points)
    given, t1 = loaded_pinion_torques(geom, s.torques_Nm, s.on)
    use_fe_tables(fe_compliance, geom)
    res = ltca(geom, t1, positions, s.contact_model())
    return _ltca_to_dataset(geom, res, given, s.on)


def teeth_approach_at_engagement(geom, res: LTCAResult) -> np.ndarray:
    """The loaded approach at the start of engagement φ1A that closes the entering pair's
    separation (T,), m: the LTE there less what the gear bodies' deflection adds in series
    (c_body·F, :mod:`gearmesh.body`). The bodies carry every tooth of a gear alike, the entering
    tooth with the loaded ones, so their deflection turns the gears without closing the entering
    pair's gap; the teeth's deflection does. It is the approach the impact stage compares with
    the same separation (``lte_at_engagement`` of impact.nc). The mesh-in impact paper's
    criterion (Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears): the
    entering pair touches before A when this approach exceeds its unloaded separation TE(φ1A).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    res : LTCAResult
        The loaded contact analysis of the pair (:func:`gearmesh.ltca.ltca`), T torques.

    Returns
    -------
    numpy.ndarray
        The teeth's approach at φ1A, shape (T,), m.

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears,
       docs/references.md (the mesh-in criterion).
    """
    return res.lte_at_engagement - mesh_body_compliance(geom) * res.force


def _touches_before_engagement(geom, res: LTCAResult) -> np.ndarray:
    """Per torque: does the entering pair touch before A (:func:`teeth_approach_at_engagement`)."""
    return teeth_approach_at_engagement(geom, res) > res.tca.te_next_pair_at_engagement


def _ltca_to_dataset(geom, res: LTCAResult, given: np.ndarray, on: str) -> xr.Dataset:
    data = _tca_variables(geom, res.tca)
    tp, tpjn = ("torque", "position"), ("torque", "position", "line", "point")
    lte_pp = np.ptp(res.lte, axis=1)
    early = _touches_before_engagement(geom, res)
    data.update({
        "torque_input": variable(("torque",), given, "N m", f"torque as given, on the {on}"),
        "force": variable(("torque",), res.force, "N", "transverse force along the line of action F_bt = T1/r_b1"),
        "load": variable(tpjn, res.load, "N", "transverse load of each point (slice)"),
        "line_load": variable(tpjn, res.line_load, "N m-1",
                              "normal load per unit contact-line length (= transverse load per unit face width)"),
        "pair_load": variable(("torque", "position", "line"), res.load.sum(axis=3), "N",
                              "transverse load carried by each tooth pair"),
        "lte": variable(tp, res.lte, "m", "loaded transmission error (transverse approach; + gear lags)"),
        "lte_gear_angle": variable(tp, res.lte / geom.base_radius[1], "rad", "loaded transmission error as gear lag angle"),
        "loaded_mesh_stiffness": variable(tp, res.stiffness, "N m-1",
                                          "loaded (tangent) mesh stiffness dF/d(delta) along the transverse line of action"),
        "pairs_in_contact": variable(tp, res.pairs_in_contact.astype(np.int16), "1", "number of tooth pairs carrying load"),
        "max_line_load": variable(tp, res.max_line_load, "N m-1", "largest line load at each position"),
        "corner_load": variable(tp, res.corner_load, "N", "load carried by tip edges outside the active zone"),
        "lte_at_engagement": variable(("torque",), res.lte_at_engagement, "m", "loaded TE at the start of engagement phi_1A"),
        "loaded_mesh_stiffness_at_engagement": variable(("torque",), res.stiffness_at_engagement, "N m-1",
                                                        "loaded mesh stiffness at phi_1A"),
        "corner_load_at_engagement": variable(("torque",), res.corner_load_at_engagement, "N",
                                              "load on tip edges at phi_1A"),
        "lte_teeth_at_engagement": variable(("torque",), teeth_approach_at_engagement(geom, res), "m",
                                            "loaded TE of the teeth at phi_1A (the bodies' deflection, which moves "
                                            "the entering tooth with the loaded ones, left out)"),
        "touches_before_engagement": _before_a_flag(("torque",), early),
        "lte_mean": variable(("torque",), res.lte.mean(axis=1), "m", "mean loaded TE over the mesh cycle"),
        "lte_peak_to_peak": variable(("torque",), lte_pp, "m", "peak-to-peak loaded TE"),
        "max_line_load_cycle": variable(("torque",), res.max_line_load.max(axis=1), "N m-1",
                                        "largest line load over the mesh cycle"),
        "loaded_mesh_stiffness_mean": variable(("torque",), res.stiffness.mean(axis=1), "N m-1",
                                               "mean loaded mesh stiffness over the mesh cycle"),
        "contact_force_exponent": _scalar(res.model.law.force_exponent, "1",
                                          "exponent n of the local contact law F ~ delta^n (contact alone)"),
        "mesh_misalignment": variable(("torque",), res.misalignment, "m",
                                      "mesh misalignment beyond the gears' lead slopes: f_ma stated and the system "
                                      "deflection's f_sh (lead mismatch in the plane of action)"),
        "shaft_misalignment": variable(("torque",), res.misalignment - res.tca.misalignment, "m",
                                       "f_sh: the system deflection's lead mismatch in the plane of action "
                                       "(shafts, bearings, described bodies)"),
        "system_approach": variable(("torque",), res.system_approach, "m",
                                    "the supports' translation of the gear centres along the transverse line of "
                                    "action (not in lte: the dynamics carries it on its bearing springs)"),
    })
    data.update(_load_capacity_variables(geom, res))
    coords = _coords(geom, res.tca)
    coords["torque"] = variable(("torque",), res.torque, "N m", "pinion torque T1")
    ds = xr.Dataset(data_vars=data, coords=coords)
    ds.attrs.update({
        "contact_law": res.model.law.name, "tooth_model": res.model.method, "torque_on": on,
        "gear_body": describe_body(geom),
        "system_deflection": describe_deflection(geom),
        "slice_coupling": "independent slices (Smith slice theory, as the stiffness stage)",
        "displacement_convention": ("transverse along the line of action, r_b1 * dphi_1 with the gear held; "
                                    "normal depths divided by cos(beta_b)"),
    })
    return name_force_lines(ds, "transverse")


def _load_capacity_variables(geom, res: LTCAResult) -> dict[str, xr.Variable]:
    """Contact pressure, root stress, load factors and loaded-TE harmonics (:mod:`gearmesh.datasets.rating`)."""
    from .rating import load_capacity_variables, reference_ltca

    return load_capacity_variables(geom, res, reference_ltca(geom, res))


@check_arguments(Ltca, exclude=section_keys(Ltca))
def ltca_summary(pair: GearPair, torque_Nm, **section: Any) -> dict[str, Any]:
    """Headline LTCA numbers at one torque in engineering units (the CLI's ``ltca --json``): the
    loaded TE and stiffness, the sign-off quantities of this gear (loaded-TE mesh orders 1–3, peak
    flank and tip-edge pressure, peak root stress [pinion, gear]) and the deviations and system
    deflection in its contact.

    Parameters
    ----------
    pair : GearPair
        The pair.
    torque_Nm : float
        The one torque (N·m) on ``section``'s ``on``.
    **section
        A study's ``ltca:`` section but its ``torques_Nm`` (:class:`gearmesh.settings.Ltca`),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    dict
        The headline numbers (µm, MPa, N, N/µm).
    """
    from .rating import load_capacity, reference_ltca

    refuse_operating_point(section, ("torques_Nm",), "one torque_Nm")
    s = settings_object(Ltca, section)
    if not (isinstance(torque_Nm, (int, float, np.floating, np.integer)) and not isinstance(torque_Nm, bool)):
        raise GearmeshInputError("torque_Nm", torque_Nm, "must be one positive number (N m)")
    geom = _geometry(pair)
    positions, _ = check_contact_grid(s.positions, s.points)
    t1 = loaded_pinion_torques(geom, [torque_Nm], s.on, "torque_Nm")[1]
    res = ltca(geom, t1, positions, s.contact_model())
    lc = load_capacity(geom, res, reference_ltca(geom, res))
    c = lc["contact"]
    um, mpa = 1e6, 1e-6
    lte = res.lte[0]
    orders = {f"lte_order_{k}_um": float(lc["te_harmonics"][0, i]) * um for i, k in enumerate(MESH_ORDERS)}
    return {
        "name": pair.name,
        "torque_Nm": float(torque_Nm),
        "torque_on": s.on,
        "pinion_torque_Nm": float(t1[0]),
        "force_transverse_N": float(res.force[0]),
        "tooth_model": res.model.method,
        "contact_law": res.model.law.name,
        "contact_force_exponent": res.model.law.force_exponent,
        "te_peak_to_peak_um": res.tca.te_peak_to_peak * um,
        "te_max_um": float(np.nanmax(res.tca.te)) * um,
        "lte_mean_um": float(lte.mean()) * um,
        "lte_peak_to_peak_um": float(np.ptp(lte)) * um,
        "max_line_load_normal_N_per_mm": float(res.max_line_load.max()) * 1e-3,
        "loaded_mesh_stiffness_mean_transverse_N_per_um": float(res.stiffness.mean()) * 1e-6,
        "loaded_mesh_stiffness_min_transverse_N_per_um": float(res.stiffness.min()) * 1e-6,
        "loaded_mesh_stiffness_max_transverse_N_per_um": float(res.stiffness.max()) * 1e-6,
        "pairs_in_contact_min": int(res.pairs_in_contact.min()),
        "pairs_in_contact_max": int(res.pairs_in_contact.max()),
        "corner_load_max_transverse_N": float(res.corner_load.max()),
        "pinion_angle_engagement_rad": res.tca.roll_engagement / geom.base_radius[0],
        "te_at_engagement_um": res.tca.te_at_engagement * um,
        "te_next_pair_at_engagement_um": res.tca.te_next_pair_at_engagement * um,
        "lte_at_engagement_um": float(res.lte_at_engagement[0]) * um,
        "lte_teeth_at_engagement_um": float(teeth_approach_at_engagement(geom, res)[0]) * um,
        "touches_before_engagement": bool(_touches_before_engagement(geom, res)[0]),
        **orders,
        "peak_flank_pressure_MPa": float(np.where(c.edge[0], 0.0, c.pressure[0]).max()) * mpa,
        "peak_edge_pressure_MPa": float(np.where(c.edge[0], c.pressure[0], 0.0).max()) * mpa,
        "peak_root_stress_MPa": [float(lc["root"][0, ..., i].max()) * mpa for i in (0, 1)],
        "K_Hbeta": float(lc["K_Hbeta"][0]),
        "K_Hbeta_rated": float(lc["K_Hbeta_rated"][0]),
        "lead_slope_deviation_um": [v * um for v in res.model.lead_slope],
        "profile_slope_deviation_um": [v * um for v in pair.deviations.profile_slope],
        "mesh_misalignment_um": float(res.misalignment[0]) * um,
        "shaft_misalignment_um": float(res.misalignment[0] - res.tca.misalignment) * um,
        "system_approach_um": float(res.system_approach[0]) * um,
        "system_deflection": describe_deflection(geom),
        "gear_body": describe_body(geom),
    }


def _before_a_flag(dims: tuple[str, ...], early: np.ndarray) -> xr.Variable:
    """When the entering pair first touches, as a CF flag: before the theoretical start of
    engagement A (off the line of action, on the mating gear's tip edge) or at or after it. Where
    on the flank it touches (tip edge or modified flank, the ``scenario`` of impact.nc) is the
    impact stage's answer: near a face end a tip edge can also touch just after A."""
    flag = variable(dims, np.asarray(early, dtype=np.int8), "1",
                    "when the entering pair first touches: before the start of engagement A (the teeth's loaded TE "
                    "at phi_1A exceeds its unloaded separation there) or at or after A")
    flag.attrs.update(flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="after_A before_A")
    return flag


def lte_table_dataset(ltca: Sequence[xr.Dataset]) -> xr.Dataset:
    """The loaded transmission error of every micro-geometry variant of a pair at every torque:
    mean and peak-to-peak over the mesh cycle and whether the entering pair touches before the
    start of engagement A, taken from the variants' ``ltca.nc`` as they are (the report's
    landing page quotes this table). The variants must share their torques.

    Parameters
    ----------
    ltca : Sequence[xarray.Dataset]
        Each variant's ltca.nc (:func:`ltca_dataset`), of one pair and the same torques.

    Returns
    -------
    xarray.Dataset
        lte_table.nc (dims variant, torque): ``lte_mean`` and ``lte_peak_to_peak`` (m) and the
        ``first_touch`` flag (0 at or after A, 1 before A).

    Raises
    ------
    GearmeshInputError
        Naming ``ltca`` (not one pair's variants) or ``ltca.torques_Nm`` (torques that differ).
    """
    names = variant_names("ltca", ltca)
    torque = shared_torques("ltca.torques_Nm", names, ltca)
    dims = ("variant", "torque")
    first_touch = _before_a_flag(dims, np.array([ds["touches_before_engagement"].values for ds in ltca]))
    return xr.Dataset({
        "lte_mean": variable(dims, np.array([ds["lte_mean"].values for ds in ltca]), "m",
                             "mean loaded transmission error over the mesh cycle", engineering_units="µm"),
        "lte_peak_to_peak": variable(dims, np.array([ds["lte_peak_to_peak"].values for ds in ltca]), "m",
                                     "peak-to-peak loaded transmission error", engineering_units="µm"),
        "first_touch": first_touch,
    }, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
               "torque": variable(("torque",), torque, "N m", "pinion torque T1")})


def lste_comparison_dataset(stiffness: Sequence[xr.Dataset], ltca: Sequence[xr.Dataset]) -> xr.Dataset:
    """LSTE of each pair by the LTCA next to F/K(φ) of the stiffness stage (the low-fluctuation paper §3).

    The LTCA torque equal to the stiffness stage's LSTE torque (pinion torques) is compared.

    Parameters
    ----------
    stiffness : Sequence[xarray.Dataset]
        Each pair's stiffness.nc (:func:`gearmesh.datasets.stiffness.stiffness_dataset`), with its LSTE.
    ltca : Sequence[xarray.Dataset]
        Each pair's ltca.nc (:func:`ltca_dataset`), in the same pair order.

    Returns
    -------
    xarray.Dataset
        lste_comparison.nc (dim pair): ``lste_stiffness_mean``/``_peak_to_peak``,
        ``lte_ltca_mean``/``_peak_to_peak`` (m) and ``stiffness_fluctuation`` ε_k (1).

    Raises
    ------
    GearmeshInputError
        Naming ``stiffness.torque_Nm`` (a stiffness dataset without LSTE) or ``ltca.torques_Nm``
        (the LTCA torques miss the LSTE torque).

    References
    ----------
    .. [1] [untitled] Low mesh-stiffness fluctuation design of helical gears, docs/references.md, §3.
    """
    names, rows = [], []
    for k_ds, l_ds in zip(stiffness, ltca):
        name = k_ds.attrs.get("pair_name", "")
        if "lste" not in k_ds:
            raise GearmeshInputError("stiffness.torque_Nm", None, f"is needed for the LSTE of {name}")
        t_k, t_l = float(k_ds.pinion_torque), l_ds["torque"].values  # both pinion torques
        match = np.flatnonzero(same_point(t_l, t_k))
        if not match.size:
            raise GearmeshInputError("ltca.torques_Nm", t_l.tolist(), f"must include the stiffness stage's LSTE "
                                     f"torque ({t_k} N m on the pinion) for {name}")
        lte = l_ds["lte"].values[match[0]]
        names.append(name)
        rows.append([float(k_ds.lste_mean), float(k_ds.lste_peak_to_peak), float(np.mean(lte)), float(np.ptp(lte)),
                     float(k_ds.fluctuation)])
    v = np.array(rows)
    dims = ("pair",)
    return xr.Dataset({
        "lste_stiffness_mean": variable(dims, v[:, 0], "m", "mean LSTE F/K(phi) of the stiffness stage",
                                        engineering_units="µm"),
        "lste_stiffness_peak_to_peak": variable(dims, v[:, 1], "m", "peak-to-peak LSTE F/K(phi)",
                                        engineering_units="µm"),
        "lte_ltca_mean": variable(dims, v[:, 2], "m", "mean loaded TE of the LTCA",
                                        engineering_units="µm"),
        "lte_ltca_peak_to_peak": variable(dims, v[:, 3], "m", "peak-to-peak loaded TE of the LTCA",
                                        engineering_units="µm"),
        "stiffness_fluctuation": variable(dims, v[:, 4], "1", "eps_k = (Kmax - Kmin)/Kmin"),
    }, coords={"pair": variable(dims, np.array(names), "1", "gear pair")})
