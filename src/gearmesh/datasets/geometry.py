"""Geometry-stage datasets: pair geometry, contact lines, helix sweep, low-fluctuation designs.

Each function takes a :class:`~gearmesh.gear.GearPair` and the stage's settings, calls the
physics modules and returns a Dataset in SI units whose every variable carries ``units``
and ``long_name``; the workflow's scripts only add provenance and write it.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import xarray as xr

from ..contact import (
    contact_length_closed_form,
    contact_length_fluctuation,
    contact_length_summary,
    contact_line_end_points,
    contact_lines,
    mesh_cycle_rolls,
)
from ..design import integer_overlap_face_width, integer_overlap_helix_angle, overlap_fluctuation_curve
from ..errors import GearmeshInputError
from ..gear import GEARS, GearPair, PairGeometry, pair_geometry
from ..io import variable
from ..limits import check_sweep
from ..profile import tooth_profile
from ..surface import tooth_surface
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..settings import ContactLines, Geometry, HelixSweep, LowFluctuationDesign
from . import named_pairs



def _per_gear(values, units: str, long_name: str) -> xr.Variable:
    return variable(("gear",), np.asarray(values, dtype=float), units, long_name)


def _scalar(value, units: str, long_name: str) -> xr.Variable:
    return variable((), float(value), units, long_name)


def geometry_scalars(geom: PairGeometry) -> dict[str, xr.Variable]:
    """The pair's derived geometry as 0-d and per-gear variables (SI).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    dict[str, xarray.Variable]
        By name, each with ``units`` and ``long_name``: the contact ratios (1), module, centre
        distances, backlash, face width, base pitch, path of contact (m), the angles (rad), and per
        gear (dim ``gear``) the teeth, profile shift (1), radii, roll lengths of SAP/EAP, tip
        thickness and tip clearance (m) and undercut (0/1).
    """
    return {
        "eps_alpha": _scalar(geom.eps_alpha, "1", "transverse contact ratio"),
        "eps_beta": _scalar(geom.eps_beta, "1", "overlap ratio"),
        "eps_gamma": _scalar(geom.eps_gamma, "1", "total contact ratio"),
        "normal_module": _scalar(geom.pair.normal_module, "m", "normal module"),
        "normal_pressure_angle": _scalar(geom.pair.normal_pressure_angle, "rad", "normal pressure angle"),
        "helix_angle": _scalar(geom.pair.helix_angle, "rad", "helix angle at the reference circle"),
        "transverse_pressure_angle": _scalar(geom.transverse_pressure_angle, "rad", "transverse pressure angle"),
        "operating_pressure_angle": _scalar(geom.operating_pressure_angle, "rad",
                                            "operating transverse pressure angle"),
        "base_helix_angle": _scalar(geom.base_helix_angle, "rad", "base helix angle"),
        "center_distance": _scalar(geom.center_distance, "m", "operating centre distance"),
        "zero_backlash_center_distance": _scalar(geom.zero_backlash_center_distance, "m",
                                                 "zero-backlash centre distance of the profile shifts"),
        "backlash_normal": _scalar(geom.backlash_normal, "m", "normal backlash j_bn"),
        "backlash_circumferential": _scalar(geom.backlash_circumferential, "m",
                                            "circumferential backlash on the operating pitch circle"),
        "face_width": _scalar(geom.face_width, "m", "meshing face width (overlap of both gears)"),
        "transverse_base_pitch": _scalar(geom.transverse_base_pitch, "m", "transverse base pitch (mesh cycle)"),
        "path_of_contact": _scalar(geom.path_of_contact, "m", "length of the transverse path of contact"),
        "teeth": variable(("gear",), np.asarray(geom.pair.teeth), "1", "number of teeth"),
        "profile_shift": _per_gear(geom.profile_shift, "1", "profile shift coefficient"),
        "reference_radius": _per_gear(geom.reference_radius, "m", "reference (pitch) radius"),
        "base_radius": _per_gear(geom.base_radius, "m", "base radius"),
        "tip_radius": _per_gear(geom.tip_radius, "m", "tip radius"),
        "root_radius": _per_gear(geom.root_radius, "m", "root radius"),
        "form_radius": _per_gear(geom.form_radius, "m", "form radius (true start of the involute)"),
        "sap_radius": _per_gear(geom.sap_radius, "m", "radius of the start of active profile"),
        "eap_radius": _per_gear(geom.eap_radius, "m", "radius of the end of active profile"),
        "rho_sap": _per_gear(geom.rho_sap, "m", "roll length of the start of active profile"),
        "rho_eap": _per_gear(geom.rho_eap, "m", "roll length of the end of active profile"),
        "undercut": variable(("gear",), geom.undercut.astype(np.int8), "1", "tooth undercut (1) or not (0)"),
        "normal_tip_thickness": _per_gear(geom.normal_tip_thickness, "m", "normal tooth thickness at the tip"),
        "tip_clearance": _per_gear(geom.tip_clearance, "m", "tip clearance at this gear's root"),
        "mass": _per_gear(geom.mass, "kg", "body mass (pitch cylinder minus bore, as the low-fluctuation paper)"),
        "inertia": _per_gear(geom.inertia, "kg m2", "polar moment of inertia of the body"),
    }


def _gear_coord() -> dict[str, xr.Variable]:
    return {"gear": variable(("gear",), np.array(GEARS), "1", "gear of the pair (pinion drives)")}


@check_arguments(Geometry, exclude=section_keys(Geometry))
def geometry_dataset(pair: GearPair, **section: Any) -> xr.Dataset:
    """The pair's geometry: scalars, the transverse tooth profile with its hob fillet, and the
    (modified) flank surface of each gear on a (profile, face) grid, in each gear's body frame.

    Profile and surface come from :mod:`gearmesh.profile` (rack-generated involute and
    trochoid fillet, the transition-curve paper) and :mod:`gearmesh.surface` (involute helicoid, the contact-line paper, with
    the six-parameter modification of the mesh-in impact paper along the normal).

    Parameters
    ----------
    pair : GearPair
        The pair.
    **section
        A study's ``geometry:`` section (:class:`gearmesh.settings.Geometry`: the point counts),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        geometry.nc.
    """
    s = settings_object(Geometry, section)
    involute_points, fillet_points, face_points = s.involute_points, s.fillet_points, s.face_points
    geom = pair_geometry(pair)
    profiles = [tooth_profile(geom, g, n_fillet=fillet_points, n_involute=involute_points) for g in range(2)]
    surfaces = [tooth_surface(geom, g, n_profile=involute_points + fillet_points, n_face=face_points,
                              n_fillet=fillet_points) for g in range(2)]
    pdims, sdims = ("gear", "profile_point"), ("gear", "u", "v")

    def stack(items, attr):
        return np.stack([getattr(item, attr) for item in items])

    data = geometry_scalars(geom)
    data.update({
        "profile_x": variable(pdims, stack(profiles, "x"), "m",
                              "transverse profile: half thickness (x) from the tooth centreline"),
        "profile_y": variable(pdims, stack(profiles, "y"), "m", "transverse profile: height (y) along the centreline"),
        "profile_radius": variable(pdims, stack(profiles, "radius"), "m", "transverse profile: radius"),
        "profile_segment": variable(pdims, stack(profiles, "segment").astype(np.int8), "1",
                                    "profile segment: 0 root fillet (hob trochoid), 1 involute"),
        "profile_roll": variable(pdims, stack(profiles, "roll"), "m", "involute roll length (NaN on the fillet)"),
        "surface_x": variable(sdims, stack(surfaces, "x"), "m", "flank surface x (gear body frame)"),
        "surface_y": variable(sdims, stack(surfaces, "y"), "m", "flank surface y (gear body frame)"),
        "surface_z": variable(sdims, stack(surfaces, "z"), "m", "flank surface z (axial)"),
        "normal_x": variable(sdims, stack(surfaces, "nx"), "1", "outward unit normal x of the unmodified flank"),
        "normal_y": variable(sdims, stack(surfaces, "ny"), "1", "outward unit normal y of the unmodified flank"),
        "normal_z": variable(sdims, stack(surfaces, "nz"), "1", "outward unit normal z of the unmodified flank"),
        "surface_roll": variable(sdims, stack(surfaces, "rho"), "m", "involute roll length (NaN on the fillet)"),
        "modification_depth": variable(sdims, stack(surfaces, "depth"), "m",
                                       "micro-geometry: material removed along the normal "
                                       "(six-parameter profile and lead modification)"),
    })
    ds = xr.Dataset(data_vars=data, coords=_gear_coord())
    return ds


@check_arguments(ContactLines, exclude=section_keys(ContactLines))
def contact_lines_dataset(pair: GearPair, **section: Any) -> xr.Dataset:
    """Contact lines and total length L(φ) over one mesh cycle (the contact-line paper; the low-fluctuation paper §1, §5).

    Positions are pinion roll distances over one transverse base pitch. Each line is given
    by its clipped end points in the plane of action (s, z) and in 3-D, in the fixed frame
    and on the pinion flank (pinion body frame, tooth j rotated onto tooth 0), with its
    length. Mean/min/max of L are exact (L is piecewise linear: evaluated at its kinks,
    :func:`gearmesh.contact.contact_length_summary`) beside the closed forms.

    Parameters
    ----------
    pair : GearPair
        The pair.
    **section
        A study's ``contact_lines:`` section (:class:`gearmesh.settings.ContactLines`: ``positions``),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        contact_lines.nc (dims position, line, end, xyz).
    """
    positions = settings_object(ContactLines, section).positions
    geom = pair_geometry(pair)
    roll = mesh_cycle_rolls(geom, positions)
    lines = contact_lines(geom, roll)
    ends = contact_line_end_points(geom, lines).points
    summary = contact_length_summary(geom)
    b = geom.face_width
    pl, ple, plex = ("position", "line"), ("position", "line", "end"), ("position", "line", "end", "xyz")
    ds = xr.Dataset(
        data_vars={
            "line_length": variable(pl, lines.length, "m", "length of each contact line"),
            "s_start": variable(pl, lines.s_start, "m",
                                "start of the line: distance from the start of active profile along the line of action"),
            "s_end": variable(pl, lines.s_end, "m",
                              "end of the line: distance from the start of active profile along the line of action"),
            "z_start": variable(pl, lines.z_start, "m", "axial position of the line's start"),
            "z_end": variable(pl, lines.z_end, "m", "axial position of the line's end"),
            "end_fixed": variable(plex, ends.fixed, "m", "line end points in the fixed frame (pinion axis = z)"),
            "end_pinion": variable(plex, ends.pinion_tooth, "m",
                                   "line end points on the pinion flank (pinion body frame, tooth 0)"),
            "end_rho_pinion": variable(ple, ends.rho_pinion, "m", "pinion roll length at the line ends"),
            "end_rho_gear": variable(ple, ends.rho_gear, "m", "gear roll length at the line ends"),
            "total_length": variable(("position",), lines.total_length, "m", "total contact-line length L(phi)"),
            "mean_length": _scalar(summary.numeric_mean, "m", "mean total contact length over the mesh cycle (exact)"),
            "min_length": _scalar(summary.numeric_min, "m", "minimum total contact length (exact)"),
            "max_length": _scalar(summary.numeric_max, "m", "maximum total contact length (exact)"),
            "mean_length_closed_form": _scalar(summary.mean, "m", "mean total contact length, l_mean = b eps_alpha / cos beta_b"),
            "min_length_closed_form": _scalar(summary.min, "m", "minimum total contact length, closed form"),
            "max_length_closed_form": _scalar(summary.max, "m", "maximum total contact length, closed form"),
            "length_fluctuation": _scalar(summary.numeric_eps_l, "1",
                                          "contact-line fluctuation eps_l = (Lmax - Lmin)/b (low-fluctuation paper)"),
            "eps_alpha": _scalar(geom.eps_alpha, "1", "transverse contact ratio"),
            "eps_beta": _scalar(geom.eps_beta, "1", "overlap ratio"),
            "face_width": _scalar(b, "m", "meshing face width"),
            "base_helix_angle": _scalar(geom.base_helix_angle, "rad", "base helix angle"),
            "path_of_contact": _scalar(geom.path_of_contact, "m", "length of the transverse path of contact"),
        },
        coords={
            "position": variable(("position",), roll, "m", "pinion roll distance r_b1 phi_1 over one mesh cycle"),
            "pinion_angle": variable(("position",), roll / geom.base_radius[0], "rad", "pinion rotation angle phi_1"),
            "line": variable(("line",), lines.pairs, "1", "tooth-pair index j along the line of action"),
            "end": variable(("end",), np.array(["start", "end"]), "1", "line end: smaller z, larger z"),
            "xyz": variable(("xyz",), np.array(["x", "y", "z"]), "1", "Cartesian component"),
        },
    )
    return ds


@check_arguments(HelixSweep, exclude=section_keys(HelixSweep))
def helix_sweep_dataset(gear_pairs: Mapping[str, GearPair], **section: Any) -> xr.Dataset:
    """Contact-length statistics against helix angle for each pair (the contact-line paper; the
    low-fluctuation paper §5).

    Each helix angle is a full new pair geometry at its zero-backlash centre distance
    (:func:`gearmesh.design.overlap_fluctuation_curve`); angles whose pair cannot work are
    NaN, with the reasons in the ``refused`` attribute.

    Parameters
    ----------
    gear_pairs : mapping of str to GearPair
        Loaded pairs by name; the section's ``pairs`` picks the sweep's, in its order.
    **section
        A study's ``helix_sweep:`` section (:class:`gearmesh.settings.HelixSweep`: the angles in
        degrees and the positions per mesh cycle), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        helix_sweep.nc (dims pair, helix_angle).
    """
    s = settings_object(HelixSweep, section)
    start_deg, stop_deg, step_deg, positions = s.start_deg, s.stop_deg, s.step_deg, s.positions
    pairs = named_pairs(gear_pairs, s.pairs)
    check_sweep(start_deg, stop_deg, step_deg)  # its size from the three numbers, before any grid
    angles = np.arange(start_deg, stop_deg + 0.5 * step_deg, step_deg)
    names = list(pairs)
    curves = [overlap_fluctuation_curve(pairs[n], np.radians(angles), n_positions=positions) for n in names]
    dims = ("pair", "helix_angle")

    def stack(attr: str) -> np.ndarray:
        return np.stack([getattr(c, attr) for c in curves])

    refused = [f"{n} at {b:g} deg: {r}" for n, c in zip(names, curves) for b, r in zip(angles, c.reasons) if r]
    ds = xr.Dataset(
        data_vars={
            "eps_alpha": variable(dims, stack("eps_alpha"), "1", "transverse contact ratio"),
            "eps_beta": variable(dims, stack("eps_beta"), "1", "overlap ratio"),
            "mean_length": variable(dims, stack("l_mean"), "m", "mean total contact length, b eps_alpha / cos beta_b"),
            "min_length": variable(dims, stack("l_min"), "m", "minimum total contact length (closed form)"),
            "max_length": variable(dims, stack("l_max"), "m", "maximum total contact length (closed form)"),
            "length_fluctuation": variable(dims, stack("eps_l"), "1",
                                           "contact-line fluctuation eps_l = (Lmax - Lmin)/b, closed form (low-fluctuation paper)"),
            "length_fluctuation_numeric": variable(dims, stack("eps_l_numeric"), "1",
                                                   "eps_l from the exactly clipped contact lines"),
            "length_fluctuation_sampled": variable(dims, stack("eps_l_sampled"), "1",
                                                   f"eps_l sampled at {positions} positions per mesh cycle"),
        },
        coords={
            "pair": variable(("pair",), np.array(names), "1", "gear pair"),
            "helix_angle": variable(("helix_angle",), np.radians(angles), "rad", "helix angle"),
            "helix_angle_deg": variable(("helix_angle",), angles, "degree", "helix angle"),
        },
    )
    ds.attrs["refused"] = "; ".join(refused)
    return ds


DESIGN_ROUTES = {  # name -> (design function, direction)
    "helix_angle_forward": (integer_overlap_helix_angle, "forward"),
    "helix_angle_backward": (integer_overlap_helix_angle, "backward"),
    "face_width_forward": (integer_overlap_face_width, "forward"),
    "face_width_backward": (integer_overlap_face_width, "backward"),
}


@check_arguments(LowFluctuationDesign, exclude=section_keys(LowFluctuationDesign))
def low_fluctuation_design_dataset(gear_pairs: Mapping[str, GearPair], **section: Any) -> xr.Dataset:
    """Integer-overlap-ratio designs of each pair (the low-fluctuation paper §1, §5): the original
    and its helix-angle (forward/backward) and face-width (forward/backward) redesigns, with εα,
    εβ and the contact-line fluctuation ε_l of each. Routes with no solution are NaN and the
    reason is in the ``refused`` attribute.

    Parameters
    ----------
    gear_pairs : mapping of str to GearPair
        Loaded pairs by name; the section's ``pairs`` picks the table's, in its order.
    **section
        A study's ``low_fluctuation_design:`` section (:class:`gearmesh.settings.LowFluctuationDesign`),
        parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        low_fluctuation_design.nc (dims pair, design).
    """
    pairs = named_pairs(gear_pairs, settings_object(LowFluctuationDesign, section).pairs)
    names = list(pairs)
    routes = ["original", *DESIGN_ROUTES]
    keys = ("helix_angle", "face_width", "eps_alpha", "eps_beta", "eps_l", "mean_length")
    out = {k: np.full((len(names), len(routes)), np.nan) for k in keys}
    refused = []
    for i, name in enumerate(names):
        for k, route in enumerate(routes):
            try:
                if route == "original":
                    geom = pair_geometry(pairs[name])
                else:
                    function, direction = DESIGN_ROUTES[route]
                    geom = function(pairs[name], direction).geometry
            except GearmeshInputError as exc:
                refused.append(f"{name} {route}: {exc}")
                continue
            out["helix_angle"][i, k] = geom.pair.helix_angle
            out["face_width"][i, k] = geom.face_width
            out["eps_alpha"][i, k], out["eps_beta"][i, k] = geom.eps_alpha, geom.eps_beta
            out["eps_l"][i, k] = contact_length_fluctuation(geom)
            out["mean_length"][i, k] = contact_length_closed_form(geom)[0]
    dims = ("pair", "design")
    ds = xr.Dataset(
        data_vars={
            "helix_angle": variable(dims, out["helix_angle"], "rad", "helix angle"),
            "helix_angle_deg": variable(dims, np.degrees(out["helix_angle"]), "degree", "helix angle"),
            "face_width": variable(dims, out["face_width"], "m", "meshing face width"),
            "eps_alpha": variable(dims, out["eps_alpha"], "1", "transverse contact ratio"),
            "eps_beta": variable(dims, out["eps_beta"], "1", "overlap ratio"),
            "length_fluctuation": variable(dims, out["eps_l"], "1", "contact-line fluctuation eps_l = (Lmax - Lmin)/b"),
            "mean_length": variable(dims, out["mean_length"], "m", "mean total contact length"),
        },
        coords={
            "pair": variable(("pair",), np.array(names), "1", "gear pair"),
            "design": variable(("design",), np.array(routes), "1", "design route to an integer overlap ratio"),
        },
    )
    ds.attrs["refused"] = "; ".join(refused)
    return ds


def dataset_summary(ds: xr.Dataset) -> dict[str, Any]:
    """0-d variables of a dataset as a plain dict (for logs and the CLI).

    Parameters
    ----------
    ds : xarray.Dataset
        Any stage's dataset.

    Returns
    -------
    dict[str, float]
        Each 0-d data variable's value in the dataset's unit (its ``units`` attribute).
    """
    return {k: float(v) for k, v in ds.data_vars.items() if v.ndim == 0}
