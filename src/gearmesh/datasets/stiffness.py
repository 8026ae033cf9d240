"""Stiffness-stage datasets: K(φ) of a pair, comparison tables over pairs and methods, and
the slice-count convergence study (seeds 001, 003, 004)."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import xarray as xr

from ..fe_tables import use_fe_tables
from ..design import pair_with_contact_ratios
from ..errors import GearmeshInputError
from ..gear import GearPair, PairGeometry, pair_geometry
from ..pairfile import pair_from_dict, pair_to_dict
from ..gear import pinion_torque as gear_pinion_torque
from ..io import variable
from ..limits import check_slice_grid
from ..loads import check_load
from ..body import describe_body
from ..deflection import describe_deflection, mesh_deflection
from ..ltca import contact_tangent_compliance
from ..slice_compliance import pair_slice_table, slice_compliance_table
from ..stiffness import (
    DEFAULT_RULE,
    fourier_fit,
    iso6336_stiffness,
    lste,
    mesh_stiffness,
)
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..choices import PEM_TOOTH_METHODS
from ..settings import SliceConvergence, Stiffness, StiffnessTable
from . import named_pairs

METHODS = PEM_TOOTH_METHODS


#: The contact term of the linear stiffness, as the dataset states it (with a torque, without).
CONTACT_TERM_NOTE = {
    True: "the tangent of the LTCA's Palmgren contact law at the mean line load of torque_Nm "
          "(gearmesh.ltca.contact_tangent_compliance): one mesh stiffness with the LTCA and the contact dynamics",
    False: "Yang & Sun's constant line-contact stiffness pi E/(4(1-nu^2)) (no torque given: 2.8-3.3x stiffer than "
           "the loaded contact: the documentation's validation page)"}

#: The stiffness section's keys: the functions below parse their section themselves, once.
_STIFFNESS_KEYS = section_keys(Stiffness)


def pinion_torque(geom: PairGeometry, torque_Nm: float, on: str) -> float:
    """Pinion torque (N m) from a torque on the pinion or on the gear (ratio z1/z2, no loss).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (its teeth z1, z2).
    torque_Nm : float
        The torque (N·m), positive and finite.
    on : {'pinion', 'gear'}
        The gear ``torque_Nm`` acts on.

    Returns
    -------
    float
        The pinion torque T1 (N·m).

    Raises
    ------
    GearmeshInputError
        Naming ``torque_Nm`` or ``torque_on``.
    """
    if not np.isfinite(torque_Nm) or torque_Nm <= 0:
        raise GearmeshInputError("torque_Nm", torque_Nm, "must be a positive finite number")
    if on not in ("pinion", "gear"):
        raise GearmeshInputError("torque_on", on, "must be 'pinion' or 'gear'")
    return gear_pinion_torque(geom.pair, torque_Nm, on)


@check_arguments(Stiffness, exclude=_STIFFNESS_KEYS)
def stiffness_dataset(pair: GearPair, *, fe_compliance: xr.Dataset | None = None, **section: Any) -> xr.Dataset:
    """K(φ) of ``pair`` by the slice potential energy method (:func:`gearmesh.stiffness.mesh_stiffness`),
    with its components, one tooth pair's k over its engagement, the Fourier series of K (the
    improved potential-energy paper) with its fitting error, ISO 6336-1 c', cγα, cγβ, and with a
    torque the LSTE F/K(φ) (the low-fluctuation paper). Stiffness is along the transverse line of
    action (force F = T1/r_b1); multiply by 1/cos²βb for the normal direction.

    Parameters
    ----------
    pair : GearPair
        The pair.
    fe_compliance : xarray.Dataset, optional
        The pair's fe_compliance.nc: the FE tables of ``method='fe'``
        (:func:`gearmesh.fe_tables.seed_cache`).
    **section
        A study's ``stiffness:`` section (:class:`gearmesh.settings.Stiffness`), parsed once
        (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        stiffness.nc (dims position, pair_position, component, harmonic).
    """
    return _stiffness_dataset(pair, settings_object(Stiffness, section), fe_compliance)


def _stiffness_dataset(pair: GearPair, s: Stiffness, fe_compliance: xr.Dataset | None) -> xr.Dataset:
    """:func:`stiffness_dataset` of the parsed section ``s``."""
    method, fourier_order, torque_Nm = s.method, s.fourier_order, s.torque_Nm
    geom = pair_geometry(pair)
    slices, positions = check_slice_grid(s.slices, s.positions)
    t1 = None
    if torque_Nm is not None:
        t1 = pinion_torque(geom, torque_Nm, s.torque_on)
        check_load(geom, t1, "torque_Nm", torque_Nm)
    use_fe_tables(fe_compliance, geom)
    result = mesh_stiffness(geom, n_positions=positions, n_slices=slices, method=method,
                            contact_compliance=None if t1 is None else contact_tangent_compliance(geom, t1))
    fit = fourier_fit(result.K, fourier_order)
    theta = 2 * np.pi * result.roll / geom.transverse_base_pitch
    iso = iso6336_stiffness(geom)
    names = list(result.components)
    data = {
        "mesh_stiffness": variable(("position",), result.K, "N m-1",
                                   "total mesh stiffness K(phi) along the transverse line of action"),
        "mesh_stiffness_fourier": variable(("position",), fit(theta), "N m-1",
                                           f"Fourier series of K of order {fourier_order}"),
        "component_stiffness": variable(("component", "position"), np.stack([result.components[n] for n in names]),
                                        "N m-1", "series-equivalent stiffness of each component (1/K = sum 1/K_x)"),
        "pair_stiffness": variable(("pair_position",), result.k_pair, "N m-1",
                                   "stiffness of one tooth pair over its engagement"),
        "mean_stiffness": variable((), result.mean, "N m-1", "mean mesh stiffness"),
        "min_stiffness": variable((), result.min, "N m-1", "minimum mesh stiffness (samples and kinks)"),
        "max_stiffness": variable((), result.max, "N m-1", "maximum mesh stiffness (samples and kinks)"),
        "fluctuation": variable((), result.fluctuation, "1", "fluctuation eps_k = (Kmax - Kmin)/Kmin (low-fluctuation paper)"),
        "fourier_mean": variable((), fit.mean, "N m-1", "Fourier series: mean k_m"),
        "fourier_cos": variable(("harmonic",), fit.a, "N m-1", "Fourier series: cosine coefficients a_j"),
        "fourier_sin": variable(("harmonic",), fit.b, "N m-1", "Fourier series: sine coefficients b_j"),
        "fourier_rms_error": variable((), fit.rms_error, "N m-1", "RMS of K minus its Fourier series"),
        "iso6336_c_single": variable((), iso["c_prime"] * 1e9, "N m-2",
                                     "ISO 6336-1 single stiffness c' (per unit face width)"),
        "iso6336_c_gamma_alpha": variable((), iso["c_gamma_alpha"] * 1e9, "N m-2",
                                          "ISO 6336-1 mesh stiffness c_gamma_alpha (per unit face width)"),
        "iso6336_c_gamma_beta": variable((), iso["c_gamma_beta"] * 1e9, "N m-2",
                                         "ISO 6336-1 mesh stiffness c_gamma_beta (per unit face width)"),
        "iso6336_mesh_stiffness": variable((), iso["K_gamma_alpha"], "N m-1",
                                           "ISO 6336-1 c_gamma_alpha times the face width"),
        "eps_alpha": variable((), geom.eps_alpha, "1", "transverse contact ratio"),
        "eps_beta": variable((), geom.eps_beta, "1", "overlap ratio"),
    }
    if t1 is not None:
        e = lste(result, t1)
        data.update({
            "lste": variable(("position",), e, "m", "loaded static transmission error F/K(phi) along the line of action"),
            "lste_mean": variable((), e.mean(), "m", "mean LSTE"),
            "lste_peak_to_peak": variable((), e.max() - e.min(), "m", "peak-to-peak LSTE"),
            "pinion_torque": variable((), t1, "N m", "pinion torque of the LSTE"),
        })
    ds = xr.Dataset(data, coords={
        "position": variable(("position",), result.roll, "m", "pinion roll distance r_b1 phi_1 over one mesh cycle"),
        "pair_position": variable(("pair_position",), result.pair_roll, "m",
                                  "position of one tooth pair's mid-face contact on the line of action"),
        "component": variable(("component",), np.array(names), "1", "stiffness component"),
        "harmonic": variable(("harmonic",), np.arange(1, fourier_order + 1), "1", "harmonic of the mesh frequency"),
    })
    ds.attrs.update({"tooth_model": method, "slices": slices, "slice_rule": result.rule, "fourier_order": fourier_order,
                     "contact_term": CONTACT_TERM_NOTE[t1 is not None], "gear_body": describe_body(geom),
                     "system_deflection": describe_deflection(geom)})
    deflection = mesh_deflection(geom)
    ds["system_approach_compliance"] = variable((), deflection.approach_per_force, "m N-1",
                                                "the supports' translation of the gear centres along the transverse line "
                                                "of action per unit F_bt (not in the mesh stiffness; gearmesh.deflection)")
    ds["shaft_misalignment_compliance"] = variable((), deflection.misalignment_per_force, "m N-1",
                                                   "the system deflection's lead mismatch f_sh per unit F_bt "
                                                   "(gearmesh.deflection; the LTCA takes it per torque)")
    return ds


@check_arguments(Stiffness, exclude=_STIFFNESS_KEYS)
def stiffness_summary(pair: GearPair, **section: Any) -> dict[str, Any]:
    """Headline stiffness numbers in one unit family, N, mm, µm, the unit in every key (the CLI's
    ``stiffness --json``); stiffnesses along the transverse line of action.

    Parameters
    ----------
    pair : GearPair
        The pair.
    **section
        A study's ``stiffness:`` section (:class:`gearmesh.settings.Stiffness`), parsed once
        (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    dict
        The headline numbers (N/µm, N/(mm·µm), µm, %).
    """
    s = settings_object(Stiffness, section)
    method, slices, torque_Nm = s.method, s.slices, s.torque_Nm
    ds = _stiffness_dataset(pair, s, None)
    out = {
        "name": pair.name, "tooth_model": method, "contact_term": ds.attrs["contact_term"], "slices": slices,
        "mean_mesh_stiffness_transverse_N_per_um": float(ds.mean_stiffness) * 1e-6,
        "min_mesh_stiffness_transverse_N_per_um": float(ds.min_stiffness) * 1e-6,
        "max_mesh_stiffness_transverse_N_per_um": float(ds.max_stiffness) * 1e-6,
        "fluctuation_percent": 100 * float(ds.fluctuation),
        "iso6336_c_single_N_per_mm_um": float(ds.iso6336_c_single) * 1e-9,
        "iso6336_c_gamma_alpha_N_per_mm_um": float(ds.iso6336_c_gamma_alpha) * 1e-9,
        "iso6336_c_gamma_beta_N_per_mm_um": float(ds.iso6336_c_gamma_beta) * 1e-9,
        "iso6336_mesh_stiffness_transverse_N_per_um": float(ds.iso6336_mesh_stiffness) * 1e-6,
        "fourier_mean_transverse_N_per_um": float(ds.fourier_mean) * 1e-6,
        "fourier_cos_transverse_N_per_um": (ds.fourier_cos.values * 1e-6).tolist(),
        "fourier_sin_transverse_N_per_um": (ds.fourier_sin.values * 1e-6).tolist(),
        "gear_body": ds.attrs["gear_body"], "system_deflection": ds.attrs["system_deflection"],
        "system_approach_um_per_kN": float(ds.system_approach_compliance) * 1e9,
        "shaft_misalignment_um_per_kN": float(ds.shaft_misalignment_compliance) * 1e9,
    }
    if torque_Nm is not None:
        out.update({"pinion_torque_Nm": float(ds.pinion_torque), "lste_mean_um": float(ds.lste_mean) * 1e6,
                    "lste_peak_to_peak_um": float(ds.lste_peak_to_peak) * 1e6})
    return out


def apply_variant(pair: GearPair, name: str, overrides: Mapping[str, Any]) -> GearPair:
    """``pair`` with some pair-file keys (engineering units) replaced, renamed ``PAIR-name``.

    Two keys are design targets rather than pair-file keys: ``eps_alpha`` (reached by the
    addendum) and ``eps_beta`` (by the face width), :func:`gearmesh.design.pair_with_contact_ratios`.
    A changed pressure angle, helix angle, module, teeth or profile shift without a centre distance
    of its own gets the zero-backlash centre distance.

    Parameters
    ----------
    pair : GearPair
        The base pair.
    name : str
        The variant's name, appended to the pair's.
    overrides : Mapping[str, Any]
        Pair-file keys in their engineering units (``helix_angle_deg``, ``normal_module_mm``, ...),
        and the targets ``eps_alpha``, ``eps_beta`` (1).

    Returns
    -------
    GearPair
        The changed pair, validated as a pair file is.
    """
    overrides = dict(overrides)
    targets = {k: overrides.pop(k) for k in ("eps_alpha", "eps_beta") if k in overrides}
    data = pair_to_dict(pair) | overrides
    data["name"] = f"{pair.name}-{name}"
    if "center_distance_mm" not in overrides and any(
            k in overrides for k in ("normal_pressure_angle_deg", "helix_angle_deg", "normal_module_mm",
                                     "teeth", "profile_shift")):
        data.pop("center_distance_mm", None)  # a changed pair gets its own zero-backlash distance
    return pair_with_contact_ratios(pair_from_dict(data), **targets)


@check_arguments(StiffnessTable, exclude=section_keys(StiffnessTable))
def stiffness_table_dataset(gear_pairs: Mapping[str, GearPair], **section: Any) -> xr.Dataset:
    """A comparison table over pairs (and pair-file variants of each) and cantilever methods:
    mean/min/max K, ε_k, ISO 6336-1 mesh stiffness and, with a torque, LSTE mean and
    peak-to-peak (the low-fluctuation paper Table/§3, the transition-curve paper parametric
    tables, the improved potential-energy paper method table).

    Parameters
    ----------
    gear_pairs : mapping of str to GearPair
        Loaded pairs by name; the section's ``pairs`` picks the table's, in its order.
    **section
        A study's ``stiffness_table:`` section (:class:`gearmesh.settings.StiffnessTable`),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        stiffness_table.nc (dims case, model).
    """
    s = settings_object(StiffnessTable, section)
    methods, slices, positions, torque_Nm, torque_on = s.methods, s.slices, s.positions, s.torque_Nm, s.torque_on
    cases: dict[str, GearPair] = {}
    for name, pair in named_pairs(gear_pairs, s.pairs).items():
        for vname, overrides in (s.variants or {"as_given": {}}).items():
            cases[name if not s.variants else f"{name}-{vname}"] = (
                apply_variant(pair, vname, overrides) if s.variants else pair)
    keys = ("mean", "min", "max", "fluctuation", "iso", "lste_mean", "lste_p2p", "eps_alpha", "eps_beta",
            "sap", "eap")
    out = {k: np.full((len(cases), len(methods)), np.nan) for k in keys}
    for i, (cname, pair) in enumerate(cases.items()):
        geom = pair_geometry(pair)
        t1 = pinion_torque(geom, torque_Nm, torque_on) if torque_Nm is not None else None
        iso = iso6336_stiffness(geom)["K_gamma_alpha"]
        for k, method in enumerate(methods):
            r = mesh_stiffness(geom, n_positions=positions, n_slices=slices, method=method, components=False)
            out["mean"][i, k], out["min"][i, k], out["max"][i, k] = r.mean, r.min, r.max
            out["fluctuation"][i, k] = r.fluctuation
            out["iso"][i, k] = iso
            out["eps_alpha"][i, k], out["eps_beta"][i, k] = geom.eps_alpha, geom.eps_beta
            out["sap"][i, k], out["eap"][i, k] = geom.rho_sap[0], geom.rho_eap[0]
            if t1 is not None:
                e = lste(r, t1)
                out["lste_mean"][i, k], out["lste_p2p"][i, k] = e.mean(), e.max() - e.min()
    dims = ("case", "model")  # not "method": that name is an argument of xarray's sel()
    data = {
        "mean_stiffness": variable(dims, out["mean"], "N m-1", "mean mesh stiffness"),
        "min_stiffness": variable(dims, out["min"], "N m-1", "minimum mesh stiffness"),
        "max_stiffness": variable(dims, out["max"], "N m-1", "maximum mesh stiffness"),
        "fluctuation": variable(dims, out["fluctuation"], "1", "eps_k = (Kmax - Kmin)/Kmin"),
        "iso6336_mesh_stiffness": variable(dims, out["iso"], "N m-1", "ISO 6336-1 c_gamma_alpha times face width"),
        "eps_alpha": variable(dims, out["eps_alpha"], "1", "transverse contact ratio"),
        "eps_beta": variable(dims, out["eps_beta"], "1", "overlap ratio"),
        "pinion_sap_roll": variable(dims, out["sap"], "m", "pinion roll length of the start of active profile"),
        "pinion_eap_roll": variable(dims, out["eap"], "m", "pinion roll length of the end of active profile"),
    }
    if torque_Nm is not None:
        data["lste_mean"] = variable(dims, out["lste_mean"], "m", "mean LSTE F/K", engineering_units="µm")
        data["lste_peak_to_peak"] = variable(dims, out["lste_p2p"], "m", "peak-to-peak LSTE", engineering_units="µm")
    ds = xr.Dataset(data, coords={
        "case": variable(("case",), np.array(list(cases)), "1", "pair (and variant)"),
        "model": variable(("model",), np.array(list(methods)), "1", "cantilever model of the tooth (method)"),
    })
    ds.attrs.update({"slices": slices, "positions": positions,
                     "torque": "" if torque_Nm is None else f"{torque_Nm} N m on the {torque_on}",
                     "contact_term": CONTACT_TERM_NOTE[False]})  # every model alike, at no load
    return ds


@check_arguments(SliceConvergence, exclude=section_keys(SliceConvergence))
def slice_convergence_dataset(gear_pairs: Mapping[str, GearPair], **section: Any) -> xr.Dataset:
    """K statistics against the slice count for both slice rules (the improved potential-energy
    paper argues N = 1000): 'centre' (whole slices, the documents' sampling) and 'clip' (end
    slices clipped), with the relative difference of the mean to the finest 'clip' result.

    Parameters
    ----------
    gear_pairs : mapping of str to GearPair
        Loaded pairs by name; the section's ``pairs`` picks the table's, in its order.
    **section
        A study's ``slice_convergence:`` section (:class:`gearmesh.settings.SliceConvergence`),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        slice_convergence.nc (dims pair, rule, slices).
    """
    s = settings_object(SliceConvergence, section)
    pairs, slices, method, positions = named_pairs(gear_pairs, s.pairs), s.slices, s.method, s.positions
    rules = ("centre", DEFAULT_RULE) if DEFAULT_RULE != "centre" else ("centre",)
    shape = (len(pairs), len(rules), len(slices))
    mean, lo, hi = (np.full(shape, np.nan) for _ in range(3))
    for i, pair in enumerate(pairs.values()):
        geom = pair_geometry(pair)
        pt = pair_slice_table(geom, (slice_compliance_table(geom, 0, method), slice_compliance_table(geom, 1, method)))
        for r, rule in enumerate(rules):
            for k, n in enumerate(slices):
                res = mesh_stiffness(geom, positions, n, method, components=False, pair_table=pt, rule=rule)
                mean[i, r, k], lo[i, r, k], hi[i, r, k] = res.mean, res.min, res.max
    reference = mean[:, -1:, -1:]
    dims = ("pair", "rule", "slices")
    return xr.Dataset({
        "mean_stiffness": variable(dims, mean, "N m-1", "mean mesh stiffness"),
        "min_stiffness": variable(dims, lo, "N m-1", "minimum mesh stiffness"),
        "max_stiffness": variable(dims, hi, "N m-1", "maximum mesh stiffness"),
        "mean_relative_difference": variable(dims, mean / reference - 1, "1",
                                             "mean stiffness relative to the finest clipped-slice result"),
    }, coords={
        "pair": variable(("pair",), np.array(list(pairs)), "1", "gear pair"),
        "rule": variable(("rule",), np.array(rules), "1", "slice rule: whole slices by centre, or clipped"),
        "slices": variable(("slices",), np.array(slices), "1", "number of slices over the face width"),
    })
