"""FE-compliance dataset: the finite-element tooth compliance of both gears of a pair along
the active profile, beside the three potential-energy cantilevers."""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import xarray as xr

from .. import fe
from ..gear import GEARS, GearPair, pair_geometry
from ..io import variable
from ..slice_compliance import tooth_slice_compliance
from ..tooth import PEM_METHODS, tooth_model
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..settings import FeCompliance


@check_arguments(FeCompliance, exclude=section_keys(FeCompliance))  # parsed below
def fe_compliance_dataset(pair: GearPair, **section: Any) -> xr.Dataset:
    """Per-unit-width tooth compliance (m²/N) of each gear at ``roll_nodes`` roll lengths over
    [ρ_SAP, ρ_EAP]: the FE total in ``plane`` (the table of ``stiffness.method: fe``) and in
    plane stress (the PEM's E and G), its body / tooth / wind-up / ring-shift / local parts
    (:class:`gearmesh.fe.ToothCompliance`), and the PEM's bending + shear + axial + foundation
    and its foundation alone for the three cantilever models. Mesh size and solve time per gear in
    the attributes (the time logged, not written: :data:`gearmesh.io.TIMING_SUFFIX`).

    Parameters
    ----------
    pair : GearPair
        The pair.
    **section
        A study's ``fe_compliance:`` section (:class:`gearmesh.settings.FeCompliance`: ``plane``,
        ``size``, ``roll_nodes``), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        fe_compliance.nc (dims gear, node, model).
    """
    s = settings_object(FeCompliance, section)
    plane, size, roll_nodes = s.plane, s.size, s.roll_nodes
    geom = pair_geometry(pair)
    planes = list(dict.fromkeys([plane, "stress"]))
    n = int(roll_nodes)
    shape = (2, n)
    roll = np.zeros(shape)
    fe_vals = {k: np.zeros(shape) for k in ("total", "total_stress", "body", "tooth", "wind_up", "ring_shift",
                                             "local", "load_angle")}
    pem_total = np.zeros((len(PEM_METHODS), 2, n))
    pem_fillet = np.zeros((len(PEM_METHODS), 2, n))
    attrs = {"plane": plane, "size_normal_modules": float(size), "roll_nodes": n}
    for gear in (0, 1):
        rho = np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], n)
        roll[gear] = rho
        for pl in planes:
            t0 = time.perf_counter()
            res = fe.tooth_compliance(geom, gear, rho, pl, size)
            seconds = time.perf_counter() - t0
            if pl == plane:
                for k in ("total", "body", "tooth", "wind_up", "ring_shift", "local", "load_angle"):
                    fe_vals[k][gear] = getattr(res, k)
                attrs.update({f"{GEARS[gear]}_elements": res.n_elements, f"{GEARS[gear]}_dofs": res.n_dofs,
                              f"{GEARS[gear]}_seconds": seconds})  # a time: logged, not written (gearmesh.io)
            if pl == "stress":
                fe_vals["total_stress"][gear] = res.total
        for k, m in enumerate(PEM_METHODS):
            c = tooth_slice_compliance(tooth_model(geom, gear, m), rho)
            pem_total[k, gear] = c["bending"] + c["shear"] + c["axial"] + c["fillet"]
            pem_fillet[k, gear] = c["fillet"]
    g2 = ("gear", "node")
    per = "m2 N-1"
    data = {
        "roll": variable(g2, roll, "m", "involute roll length of the load point"),
        "load_angle": variable(g2, fe_vals["load_angle"], "rad", "load angle alpha_1 to the normal of the tooth centre line"),
        "fe_compliance": variable(g2, fe_vals["total"], per,
                                  f"FE tooth compliance per unit width (plane {plane}), local contact part removed"),
        "fe_compliance_plane_stress": variable(g2, fe_vals["total_stress"], per,
                                               "FE tooth compliance per unit width in plane stress"),
        "fe_body": variable(g2, fe_vals["body"], per, "FE compliance carried by the rigid motion of the root section"),
        "fe_tooth": variable(g2, fe_vals["tooth"], per, "FE compliance of the tooth above its root section"),
        "fe_wind_up": variable(g2, fe_vals["wind_up"], per,
                               "FE compliance carried by the body's torsional wind-up (mean rotation at the root circle)"),
        "fe_ring_shift": variable(g2, fe_vals["ring_shift"], per,
                                  "FE compliance carried by the mean translation of the root circle"),
        "fe_local": variable(g2, fe_vals["local"], per,
                             "FE compliance relative to the body's rigid motion at the root circle"),
        "pem_compliance": variable(("model",) + g2, pem_total, per,
                                   "PEM bending + shear + axial + fillet-foundation compliance per unit width"),
        "pem_fillet": variable(("model",) + g2, pem_fillet, per,
                               "PEM fillet-foundation compliance per unit width (Sainsot et al. 2004)"),
    }
    ds = xr.Dataset(data, coords={
        "gear": variable(("gear",), np.array(GEARS), "1", "pinion or gear"),
        "node": variable(("node",), np.arange(n), "1", "roll node, SAP to EAP"),
        "model": variable(("model",), np.array(PEM_METHODS), "1", "potential-energy cantilever model"),
    })
    ds.attrs.update(attrs)
    return ds
