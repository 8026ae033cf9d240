"""Load capacity of an LTCA: its stress variables for ltca.nc and the CLI's ``rating --json``.

Physics: :mod:`gearmesh.stress` (Hertzian pressure, ISO 6336-3 local root stress) and
:mod:`gearmesh.rating` (ISO 6336-2/-3 method B, load factors from the LTCA). Engineering units
at the boundary, SI in the Dataset variables (units and long_name on each).
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Mapping, Sequence

import numpy as np
import xarray as xr

from ..body import describe_body
from ..deflection import describe_deflection
from ..errors import GearmeshInputError
from ..contact_model import ContactModel
from ..gear import GEARS, GearPair, Modification, PairGeometry, pair_geometry
from ..pairfile import missing_key, pair_notes
from ..io import variable
from . import shared_torques, variant_names
from ..limits import check_contact_grid, check_speeds
from ..ltca import MESH_ORDERS, LTCAResult, loaded_pinion_torques, lte_harmonics, ltca
from ..rating import check_factors, ltca_load_factors, rated_transverse_factor, rating, rating_inputs
from ..rating_factors import face_factor_root
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..settings import Ltca, Rating
from .scuffing import scuffing_json, scuffing_of
from ..stress import ContactStress, contact_stress, iso_root_stress_slices, pair_edge_radius

__all__ = ["MESH_ORDERS", "load_capacity", "load_capacity_variables", "reference_ltca", "rating_summary",
           "rating_dataset", "load_capacity_table_dataset"]

#: The rating section's keys: the functions below parse their section themselves, once.
_RATING_KEYS = section_keys(Rating)



def _unmodified(geom: PairGeometry) -> PairGeometry | None:
    """The pair without micro-geometry (the K_Hα reference), or None when it has none."""
    if all(m.is_zero for m in geom.pair.modification):
        return None
    return pair_geometry(geom.pair.with_changes(modification=(Modification(), Modification())))


def rated_mesh_misalignment(geom: PairGeometry, res: LTCAResult) -> tuple[np.ndarray | None, str]:
    """The mesh misalignment (m) per torque of ``res`` under which the rating takes its face load
    factor, and where f_ma comes from (ISO 6336-1:2019, 7.6: K_Hβ belongs to the mesh misalignment
    f_sh + f_ma). The pair's stated ``mesh_misalignment_um`` is in ``res`` already (None returned:
    rate ``res`` as it is); else f_ma = f_Hβ of the pair's accuracy grade (ISO 6336-1 method C's
    f_ma = 1.0·f_Hβ for gears without provision for adjustment; f_HβT of ISO 1328-1:2013, eq. 10,
    :func:`gearmesh.tolerance.helix_slope_tolerance`, of the gear with the larger tolerance), in the
    sense that adds to the mesh's own mismatch at that torque (the lead slopes and the system
    deflection's f_sh: ISO's F_βx adds the magnitudes), positive where that is zero.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    res : LTCAResult
        Its loaded contact analysis (:func:`gearmesh.ltca.ltca`), T torques.

    Returns
    -------
    misalignment : numpy.ndarray or None
        f_sh + f_ma per torque, shape (T,), m; None where the pair states its own.
    source : str
        Where f_ma comes from, for the dataset's long name.

    References
    ----------
    .. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1,
       clause 7.6 (mesh misalignment, method C f_ma).
    .. [2] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification —
       Part 1, eq. 10 (helix slope tolerance f_HβT).
    """
    from ..deviation import mesh_lead_sum
    from ..tolerance import helix_slope_tolerance

    if geom.pair.deviations.mesh_misalignment is not None:
        return None, "stated in the pair file (mesh_misalignment_um)"
    grade = rating_inputs(dict(geom.pair.rating_inputs))["accuracy_grade"]
    widths = np.broadcast_to(np.asarray(geom.pair.face_width, dtype=float), (2,))
    f_ma = max(helix_slope_tolerance(2.0 * float(geom.reference_radius[i]), float(widths[i]), grade)
               for i in (0, 1)) * geom.face_width / float(widths.max())
    own = mesh_lead_sum(res.model.lead_slope, res.misalignment)
    sense = np.where(own < 0, -1.0, 1.0)
    return res.misalignment + sense * f_ma, (f"ISO 6336-1 f_ma = f_Hbeta of accuracy grade {grade} "
                                             f"({f_ma * 1e6:.3g} um, ISO 1328-1:2013), in the unfavourable sense")


def load_capacity(geom: PairGeometry, res: LTCAResult, reference: LTCAResult | None = None) -> dict[str, Any]:
    """Stresses and load factors of an LTCA result (SI): ``contact`` (:class:`ContactStress`),
    ``root`` (T, P, J, N, 2) ISO 6336-3 local root stress of pinion and gear teeth (Pa),
    ``K_Hbeta``, ``K_Fbeta`` (T,) of the mesh as it is, ``K_Hbeta_rated``, ``K_Fbeta_rated`` (T,)
    those of the mesh under the rating's misalignment (:func:`rated_mesh_misalignment`: one more
    load solve on the same model when the pair states no f_ma), ``f_ma_source`` where that came
    from, ``K_Halpha`` (T,), ``te_harmonics`` (T, 3) amplitudes of the loaded TE at mesh orders 1–3
    (m).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    res : LTCAResult
        Its loaded contact analysis (:func:`gearmesh.ltca.ltca`): T torques, P positions, J
        contact lines, N points.
    reference : LTCAResult, optional
        The unmodified pair's LTCA (:func:`reference_ltca`) for K_Hα; None: K_Hα = 1.

    Returns
    -------
    dict[str, Any]
        The keys above, plus ``rated_misalignment`` (T,) m.

    References
    ----------
    .. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1
       (face and transverse load factors, K_Fβ = K_Hβ^N_F).
    .. [2] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3:
       Calculation of tooth bending strength (local root stress with Y_F, Y_S).
    """
    g = res.grid
    w = res.line_load
    contact = contact_stress(geom, w, g.region, g.rho_pinion, g.rho_gear, pair_edge_radius(geom))
    root = np.stack([iso_root_stress_slices(geom, 0, w, g.rho_pinion),
                     iso_root_stress_slices(geom, 1, w, g.rho_gear)], axis=-1)
    factors = ltca_load_factors(res.load, None if reference is None else reference.load)
    b_over_h = geom.face_width / max(float(geom.tip_radius[i] - geom.root_radius[i]) for i in (0, 1))
    k_fb = np.array([face_factor_root(k, b_over_h) for k in factors["K_Hbeta"]])
    rated, source = rated_mesh_misalignment(geom, res)
    k_hb_rated = factors["K_Hbeta"]
    if rated is not None:
        misaligned = ltca(geom, res.torque, model=res.model, misalignment=rated)
        k_hb_rated = ltca_load_factors(misaligned.load)["K_Hbeta"]
    harm = lte_harmonics(res.lte)
    return {"contact": contact, "root": root, "K_Hbeta": factors["K_Hbeta"], "K_Fbeta": k_fb,
            "K_Hbeta_rated": k_hb_rated, "K_Fbeta_rated": np.array([face_factor_root(k, b_over_h) for k in k_hb_rated]),
            "rated_misalignment": res.misalignment if rated is None else rated, "f_ma_source": source,
            "K_Halpha": factors["K_Halpha"], "te_harmonics": harm}


def load_capacity_variables(geom: PairGeometry, res: LTCAResult, reference: LTCAResult | None = None
                            ) -> dict[str, xr.Variable]:
    """The ltca.nc variables of :func:`load_capacity` (units and long names).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    res : LTCAResult
        Its loaded contact analysis (:func:`gearmesh.ltca.ltca`).
    reference : LTCAResult, optional
        The unmodified pair's LTCA (K_Hα); None: K_Hα = 1.

    Returns
    -------
    dict[str, xarray.Variable]
        Contact pressure and half-width (Pa, m) per (torque, position, line, point), root stress (Pa)
        per gear, their peaks per torque, the load factors K_Hβ, K_Fβ (LTCA and rated), K_Hα, K_Fα (1),
        the rated mesh misalignment (m), the tip-edge radius (m) and the LTE harmonics (m).
    """
    lc = load_capacity(geom, res, reference)
    c: ContactStress = lc["contact"]
    tpjn = ("torque", "position", "line", "point")
    root = lc["root"]
    peak_root = root.max(axis=(1, 2, 3))  # (T, 2)
    k_ha = rated_transverse_factor(lc["K_Halpha"])
    return {
        "contact_pressure": variable(tpjn, c.pressure, "Pa", "Hertzian peak pressure p0 of each point's line contact "
                                                             "(tip edges as cylinders of radius tip_edge_radius)"),
        "contact_half_width": variable(tpjn, c.half_width, "m", "Hertzian half-width of each point's line contact"),
        "peak_contact_pressure": variable(("torque",), c.peak(), "Pa", "largest contact pressure over the mesh cycle"),
        "peak_contact_pressure_on_edge": variable(("torque",), c.peak_on_edge().astype(np.int8), "1",
                                                  "1 when the largest contact pressure sits on a tip edge, 0 on a flank"),
        "tip_edge_radius": variable((), c.edge_radius, "m", "tip-edge rounding radius of the edge-contact pressure"
                                    + ("" if c.edge_radius_given else " (default 0.1 m_n, assumed)")),
        "root_stress": variable(tpjn + ("gear",), root, "Pa", "tooth-root stress of each point's tooth slice, ISO 6336-3 "
                                "local form w cos(alpha_t)/m_n Y_F Y_S with Y_F, Y_S for the load at the point"),
        "peak_root_stress": variable(("torque", "gear"), peak_root, "Pa",
                                     "largest tooth-root stress over the mesh cycle and the face (ISO 6336-3 local)"),
        "K_Hbeta_ltca": variable(("torque",), lc["K_Hbeta"], "1",
                                 "face load factor K_Hbeta from the LTCA (peak over mean of the cycle's face load)"),
        "K_Fbeta_ltca": variable(("torque",), lc["K_Fbeta"], "1", "face load factor K_Fbeta = K_Hbeta^N_F (ISO 6336-1)"),
        "K_Hbeta_rated": variable(("torque",), lc["K_Hbeta_rated"], "1",
                                  "face load factor K_Hbeta the rating takes: the LTCA's under the rating's mesh "
                                  f"misalignment (f_ma {lc['f_ma_source']}, with f_sh; ISO 6336-1 method A)"),
        "K_Fbeta_rated": variable(("torque",), lc["K_Fbeta_rated"], "1",
                                  "face load factor K_Fbeta = K_Hbeta_rated^N_F the rating takes"),
        "rated_mesh_misalignment": variable(("torque",), lc["rated_misalignment"], "m",
                                            "mesh misalignment of the rating's K_Hbeta (f_sh + f_ma, the convention "
                                            "of the lead slope deviations)"),
        "K_Halpha_ltca": variable(("torque",), k_ha, "1", "transverse load factor K_Halpha from the LTCA (largest "
                                  "tooth-pair load over the unmodified pair's, at least 1)"),
        "K_Falpha_ltca": variable(("torque",), k_ha, "1", "transverse load factor K_Falpha (= K_Halpha)"),
        "mesh_order": variable(("mesh_order",), np.array(MESH_ORDERS), "1", "harmonic of the mesh frequency"),
        "lte_harmonics": variable(("torque", "mesh_order"), lc["te_harmonics"], "m",
                                  "amplitude of the loaded transmission error at mesh orders 1-3"),
    }


def reference_ltca(geom: PairGeometry, res: LTCAResult) -> LTCAResult | None:
    """The LTCA of the unmodified pair on ``res``'s grid and torques (None when unmodified).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry, with its micro-geometry.
    res : LTCAResult
        Its loaded contact analysis: the grid, torques, tooth model and contact law to reuse.

    Returns
    -------
    LTCAResult or None
        The unmodified pair's LTCA (the tip-edge zone widened as :func:`gearmesh.ltca.ltca` does
        when loaded edges reach its end), or None when the pair has no micro-geometry.
    """
    base = _unmodified(geom)
    if base is None:
        return None
    m = res.model
    # res's contact model (the grid keeps the extension in m), the tip-edge zone widened by ltca() itself
    contact = ContactModel(points=res.grid.z.size, contact_law=m.law.name, method=m.method,
                           extension=res.grid.extension / geom.transverse_base_pitch)
    with warnings.catch_warnings():  # loaded edges past a whole base pitch: the reference as far as it reaches
        warnings.simplefilter("ignore", RuntimeWarning)
        return ltca(base, res.torque, res.grid.roll.size, contact, m.lead_slope,
                    tables=m.tables)  # the teeth's compliance does not see the relief


def _fe_root_check(geom: PairGeometry, res: LTCAResult, root: np.ndarray) -> dict[str, Any]:
    """The FE tooth's fillet stress at each gear's peak ISO-local root-stress point, under the same
    load (:func:`gearmesh.stress.fe_fillet_stress`, transverse slice, plane strain), and its ratio to
    the ISO local value: where the two differ, the FE value is the one to use (docs/load_capacity.md)."""
    from ..stress import fe_fillet_stress

    g = res.grid
    w = res.line_load[0]
    peaks, where = [], []
    for gear, rho_all in enumerate((g.rho_pinion, g.rho_gear)):
        k = np.unravel_index(int(root[..., gear].argmax()), root[..., gear].shape)
        lo, hi = float(geom.rho_form[gear]), float(geom.rho_eap[gear])
        rho = min(max(float(rho_all[k]), lo), hi)
        peaks.append(float(fe_fillet_stress(geom, gear, [rho]).peak[0]) * float(w[k]))
        where.append(rho)
    iso = [float(root[..., i].max()) for i in (0, 1)]
    return {"peak_root_stress_fe_MPa": [p * 1e-6 for p in peaks],
            "root_stress_fe_over_iso": [p / s if s > 0 else None for p, s in zip(peaks, iso)],
            "peak_root_stress_roll_mm": [r * 1e3 for r in where]}


@check_arguments(Rating, exclude=_RATING_KEYS)
def rating_summary(pair: GearPair, torque_Nm, *, factors: Mapping[str, float] | None = None,
                   ltca_section: Mapping[str, Any] | None = None, **section: Any) -> dict[str, Any]:
    """ISO 6336-2/-3 rating at one torque and speed with the LTCA's stresses and its scuffing rating
    (ISO/TS 6336-20/-21 from the LTCA's load along the path, :mod:`gearmesh.datasets.scuffing`; the
    CLI's ``rating --json``).

    Parameters
    ----------
    pair : GearPair
        The pair, with its rating inputs.
    torque_Nm : float
        The one torque (N·m) on ``ltca_section``'s ``on``.
    factors : mapping, optional
        Factors given instead of computed (``K_v``, ``Z_L``, ...).
    ltca_section : mapping, optional
        A study's ``ltca:`` section but its ``torques_Nm`` (:class:`gearmesh.settings.Ltca`): the
        gear the torque acts on and the LTCA's grid and model.
    **section
        A study's ``rating:`` section (:class:`gearmesh.settings.Rating`; ``speed_rpm`` the speed of
        the gear the torque acts on), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    dict
        Per-gear values [pinion, gear]; ``factors_given`` names the factors given; ``factor_sources``
        where each load factor came from; ``ltca`` the LTCA's peak contact pressure (and whether on an
        edge), peak root stress per gear and its K factors; ``notes`` the defaults taken.
    """
    if "torques_Nm" in (ltca_section or {}):
        raise GearmeshInputError("torques_Nm", ltca_section["torques_Nm"], "is the stage's map; this function "
                                 "takes one torque_Nm")
    if isinstance(torque_Nm, bool) or not isinstance(torque_Nm, (int, float)) or not math.isfinite(torque_Nm) \
            or torque_Nm <= 0:
        raise GearmeshInputError("torque_Nm", torque_Nm, "must be one positive number")
    s, lt = settings_object(Rating, section), settings_object(Ltca, ltca_section)
    speed_rpm, method, on = s.speed_rpm, s.method, lt.on
    application_factor, life_hours = s.application_factor, s.life_hours
    check_factors(factors)  # every input checked before the LTCA, the expensive step
    inputs = rating_inputs(dict(pair.rating_inputs))
    geom = pair_geometry(pair)
    check_speeds(geom, speed_rpm, "speed_rpm", on=on)  # not above the burst speed of the faster tip circle
    positions, _ = check_contact_grid(lt.positions, lt.points)
    t1 = loaded_pinion_torques(geom, [torque_Nm], on, "torque_Nm")[1]
    speed1 = speed_rpm if on == "pinion" else speed_rpm * pair.teeth[1] / pair.teeth[0]
    if method == "iso" and pair.bore_radius is None:  # the standard's factors need no LTCA, the LTCA a bore
        r = rating(geom, float(t1[0]), float(speed1), inputs, application_factor, life_hours, factors, method)
        return {"name": pair.name, "torque_Nm": float(torque_Nm), "torque_on": on, "method": method, **r.values,
                "factors_given": r.given, "factor_sources": r.sources, "gears": list(GEARS),
                "notes": pair_notes(pair) + r.notes + [f"the LTCA's contact pressure and root stress not computed: "
                                                       f"{missing_key('bore_radius_mm').rule}"]}
    res = ltca(geom, t1, positions, lt.contact_model())
    lc = load_capacity(geom, res, reference_ltca(geom, res))
    k_ha = float(rated_transverse_factor(lc["K_Halpha"][0]))
    r = rating(geom, float(t1[0]), float(speed1), inputs, application_factor, life_hours, factors, method,
               {"K_Hbeta": float(lc["K_Hbeta_rated"][0]), "K_Halpha": k_ha})
    sc = scuffing_of(geom, res, float(speed1), inputs, [r.values])
    c: ContactStress = lc["contact"]
    g = res.grid
    k = np.unravel_index(int(c.pressure[0].argmax()), c.pressure[0].shape)
    root = lc["root"][0]
    ltca_part = {
        "peak_contact_pressure_MPa": float(c.pressure[0].max()) * 1e-6,
        "peak_contact_pressure_at": {"on": "edge" if bool(c.edge[0][k]) else "flank",
                                     "roll_mm": float(g.roll[k[0]]) * 1e3, "s_mm": float(g.s[k]) * 1e3,
                                     "z_mm": float(g.z[k[2]]) * 1e3},
        "tip_edge_radius_mm": c.edge_radius * 1e3,
        "peak_root_stress_MPa": [float(root[..., i].max()) * 1e-6 for i in (0, 1)],
        "K_Hbeta": float(lc["K_Hbeta_rated"][0]), "K_Fbeta": float(lc["K_Fbeta_rated"][0]), "K_Halpha": k_ha,
        "K_Falpha": k_ha, "K_Hbeta_as_is": float(lc["K_Hbeta"][0]),
        "mesh_misalignment_rated_um": float(lc["rated_misalignment"][0]) * 1e6, "f_ma_source": lc["f_ma_source"],
        "max_line_load_normal_N_per_mm": float(res.max_line_load.max()) * 1e-3,
        **_fe_root_check(geom, res, root),
    }
    notes = pair_notes(pair) + r.notes + sc.notes()
    if not c.edge_radius_given:
        notes.append(f"tip_edge_radius_mm not given: {c.edge_radius * 1e3:g} mm (0.1 m_n, an assumed edge break)")
    notes.append("LTCA root stress: ISO 6336-3 local form per slice (Y_F, Y_S at the point's load, no Y_beta)")
    return {"name": pair.name, "torque_Nm": float(torque_Nm), "torque_on": on, "method": method, **r.values,
            **scuffing_json(sc), "factors_given": r.given, "factor_sources": r.sources, "ltca": ltca_part, "gears": list(GEARS),
            "notes": notes}


@check_arguments(Rating, exclude=_RATING_KEYS)
def rating_dataset(pair: GearPair, *, ltca: xr.Dataset | None = None, **section: Any) -> xr.Dataset:
    """ISO 6336-2/-3 rating of a pair (a variant) at each torque of its ``ltca`` dataset (rating.nc):
    safety factors, stresses and the load factors by the standard and from the LTCA, beside the
    LTCA's peak contact pressure (and whether on an edge) and peak root stress.

    Parameters
    ----------
    pair : GearPair
        The pair (a variant).
    ltca : xarray.Dataset
        Its ltca.nc, with the variables of :func:`load_capacity_variables`.
    **section
        A study's ``rating:`` section (:class:`gearmesh.settings.Rating`: the pinion speed, K_A,
        the life and where the load factors come from), parsed once
        (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        rating.nc (dims torque, gear).
    """
    s = settings_object(Rating, section)
    speed_rpm, application_factor, life_hours, method = s.speed_rpm, s.application_factor, s.life_hours, s.method
    if not isinstance(ltca, xr.Dataset) or "K_Hbeta_rated" not in ltca:
        raise GearmeshInputError("ltca", type(ltca).__name__, "must be an ltca.nc dataset with its load-capacity "
                                 "variables")
    geom = pair_geometry(pair)
    check_speeds(geom, speed_rpm, "speed_rpm")  # not above the burst speed of the faster tip circle
    inputs = rating_inputs(dict(pair.rating_inputs))
    torques = ltca["torque"].values
    rows = []
    for k, t1 in enumerate(torques):
        lf = {"K_Hbeta": float(ltca["K_Hbeta_rated"].values[k]), "K_Halpha": float(ltca["K_Halpha_ltca"].values[k])}
        rows.append(rating(geom, float(t1), speed_rpm, inputs, application_factor, life_hours, None, method, lf))
    tg, t = ("torque", "gear"), ("torque",)

    def per_gear(key):
        return np.array([r.values[key] for r in rows], dtype=float)

    def iso(key):
        return np.array([float(r.values["iso_factors"][key]) for r in rows])

    data = {
        "S_H": variable(tg, per_gear("S_H"), "1", "safety factor against pitting S_H = sigma_HG/sigma_H (ISO 6336-2)"),
        "S_F": variable(tg, per_gear("S_F"), "1", "safety factor against tooth breakage S_F = sigma_FG/sigma_F "
                                                  "(ISO 6336-3)"),
        "sigma_H": variable(tg, per_gear("sigma_H_MPa") * 1e6, "Pa", "contact stress sigma_H (ISO 6336-2 method B)"),
        "sigma_HP": variable(tg, per_gear("sigma_HP_MPa") * 1e6, "Pa", "permissible contact stress sigma_HP"),
        "sigma_F": variable(tg, per_gear("sigma_F_MPa") * 1e6, "Pa", "tooth-root stress sigma_F (ISO 6336-3 method B)"),
        "sigma_FP": variable(tg, per_gear("sigma_FP_MPa") * 1e6, "Pa", "permissible tooth-root stress sigma_FP"),
        "K_v": variable(t, per_gear("K_v"), "1", "dynamic factor K_v (ISO 6336-1:1996 method C)"),
    }
    for name in ("K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha"):
        data[name] = variable(t, per_gear(name), "1", f"{name} used ({method})")
        data[f"{name}_iso"] = variable(t, iso(name), "1", f"{name} by ISO 6336-1 methods B/C")
    data.update({
        "peak_contact_pressure": variable(t, ltca["peak_contact_pressure"].values, "Pa",
                                          "LTCA: largest Hertzian contact pressure over the mesh cycle"),
        "peak_contact_pressure_on_edge": variable(t, ltca["peak_contact_pressure_on_edge"].values, "1",
                                                  "LTCA: 1 when the largest contact pressure sits on a tip edge"),
        "peak_root_stress": variable(tg, ltca["peak_root_stress"].values, "Pa",
                                     "LTCA: largest tooth-root stress (ISO 6336-3 local form, slice by slice)"),
        "shaft_misalignment": variable(t, ltca["shaft_misalignment"].values, "m",
                                       "f_sh: the system deflection's lead mismatch in the plane of action (LTCA)"),
        "rated_mesh_misalignment": variable(t, ltca["rated_mesh_misalignment"].values, "m",
                                            "mesh misalignment f_sh + f_ma of the rating's K_Hbeta"),
    })
    coords = {"torque": variable(t, torques, "N m", "pinion torque T1"),
              "gear": variable(("gear",), np.array(GEARS), "1", "gear of the pair")}
    ds = xr.Dataset(data_vars=data, coords=coords)
    ds.attrs.update({"speed_rpm": float(speed_rpm), "application_factor": float(application_factor),
                     "factor_method": method, "rating_notes": "; ".join(rows[0].notes),
                     "gear_body": describe_body(geom), "system_deflection": describe_deflection(geom)})
    return ds


def load_capacity_table_dataset(rating: Sequence[xr.Dataset], scuffing: Sequence[xr.Dataset] = ()) -> xr.Dataset:
    """The load capacity of every variant of a pair side by side (variant × torque): S_H and S_F of the
    weaker gear, the peak contact pressure and where it sits, the peak root stress of either gear, and
    with the variants' ``scuffing`` datasets (the study runs the scuffing stage) S_B and S_intS.

    Parameters
    ----------
    rating : Sequence[xarray.Dataset]
        Each variant's rating.nc (:func:`rating_dataset`), of one pair and the same torques.
    scuffing : Sequence[xarray.Dataset], default ()
        Each variant's scuffing.nc (:func:`gearmesh.datasets.scuffing.scuffing_dataset`), or none.

    Returns
    -------
    xarray.Dataset
        load_capacity_table.nc (dims variant, torque): ``S_H``, ``S_F`` (1, weaker gear),
        ``peak_contact_pressure`` (Pa) and ``_on_edge`` (0/1), ``peak_root_stress`` (Pa),
        ``K_Hbeta`` (1), ``shaft_misalignment`` (m), and with scuffing S_B and S_intS (1).

    Raises
    ------
    GearmeshInputError
        Naming ``rating`` (not one pair's variants), ``ltca.torques_Nm`` (torques that differ, also
        between rating and scuffing) or ``variants`` (scuffing of other variants than the rating).
    """
    names = variant_names("rating", rating)
    torques = shared_torques("ltca.torques_Nm", names, rating)
    scuffed = _scuffing_columns(names, torques, scuffing)
    stack = lambda key, f: np.array([f(ds[key].values) for ds in rating])  # noqa: E731
    dims = ("variant", "torque")
    return xr.Dataset({
        "S_H": variable(dims, stack("S_H", lambda v: v.min(axis=1)), "1", "safety factor against pitting, weaker gear"),
        "S_F": variable(dims, stack("S_F", lambda v: v.min(axis=1)), "1",
                        "safety factor against tooth breakage, weaker gear"),
        "peak_contact_pressure": variable(dims, stack("peak_contact_pressure", lambda v: v), "Pa",
                                          "LTCA: largest contact pressure over the mesh cycle"),
        "peak_contact_pressure_on_edge": variable(dims, stack("peak_contact_pressure_on_edge", lambda v: v), "1",
                                                  "1: the largest contact pressure sits on a tip edge, 0: on a flank"),
        "peak_root_stress": variable(dims, stack("peak_root_stress", lambda v: v.max(axis=1)), "Pa",
                                     "LTCA: largest tooth-root stress of either gear (ISO 6336-3 local form)"),
        "K_Hbeta": variable(dims, stack("K_Hbeta", lambda v: v), "1", "face load factor K_Hbeta the rating used"),
        "shaft_misalignment": variable(dims, stack("shaft_misalignment", lambda v: v), "m",
                                       "f_sh: the system deflection's lead mismatch", engineering_units="µm"),
        **scuffed,
    }, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
               "torque": variable(("torque",), torques, "N m", "pinion torque T1")})


def _scuffing_columns(names: Sequence[str], torques: np.ndarray, scuffing: Sequence[xr.Dataset]) -> dict:
    """S_B and S_intS of each variant (``names``, in order) at ``torques`` from the variants' scuffing.nc."""
    if not scuffing:
        return {}
    by = dict(zip(variant_names("scuffing", scuffing), scuffing))
    if set(by) != set(names):
        raise GearmeshInputError("variants", sorted(by), f"scuffing and rating must cover the same variants "
                                 f"({sorted(names)})")
    ordered = [by[n] for n in names]
    if not np.allclose(shared_torques("ltca.torques_Nm", names, ordered), torques, rtol=1e-12):
        raise GearmeshInputError("ltca.torques_Nm", ordered[0]["torque"].values.tolist(),
                                 "must be the same for the scuffing and the rating stages")
    out = {}
    for key in ("scuffing_safety_flash", "scuffing_safety_integral"):
        first = ordered[0][key]
        out[key] = variable(("variant", "torque"), np.array([ds[key].values for ds in ordered]),
                            first.attrs["units"], first.attrs["long_name"])
    return out
