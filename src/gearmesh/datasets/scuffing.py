"""Scuffing load capacity of an LTCA (:mod:`gearmesh.scuffing`): its variables, ready for a
per-variant stage, and the keys of ``gearmesh rating --json``.

The load factors are the rating's (:func:`gearmesh.rating.rating`, method 'ltca' with the LTCA's
own K_Hβ and K_Hα): the LTCA's line load is scaled by K_A K_v, and μ_mC takes the rating's
w_Bt = K_A K_v K_Hβ K_Hα F_t/b.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import xarray as xr

from ..gear import PairGeometry
from ..io import variable
from ..ltca import LTCAResult
from ..rating import RatingInputs, ltca_load_factors, rated_transverse_factor, rating, rating_inputs
from ..scuffing import ScuffingRating, scuffing_rating

__all__ = ["PATH_BINS", "scuffing_of", "scuffing_json", "scuffing_variables"]

#: Bins of the path of contact A–E in which the flash temperature's largest value over the face
#: is drawn (``flash_temperature_path``).
PATH_BINS = 48


def scuffing_of(geom: PairGeometry, res: LTCAResult, speed_rpm: float, inputs: RatingInputs,
                rated: list[Mapping[str, Any]]) -> ScuffingRating:
    """:func:`gearmesh.scuffing.scuffing_rating` of ``res`` at pinion speed ``speed_rpm`` with the load
    factors of ``rated`` (the rating's values at each of ``res``'s torques)."""
    load_factor = [v["K_A"] * v["K_v"] for v in rated]
    w_bt = [v["K_A"] * v["K_v"] * v["K_Hbeta"] * v["K_Halpha"] * v["force_tangential_N"] / (geom.face_width * 1e3)
            for v in rated]
    return scuffing_rating(geom, res.line_load, res.grid, speed_rpm, inputs, load_factor, w_bt)


def scuffing_json(sc: ScuffingRating, k: int = 0) -> dict[str, Any]:
    """The keys of ``gearmesh rating --json`` at torque ``k``: the flash temperature method's
    largest contact temperature and S_B, the integral method's θ_int and S_intS, and their parts."""
    return {"contact_temperature_max_C": float(sc.contact_max[k]), "scuffing_safety_flash": float(sc.safety_flash[k]),
            "integral_temperature_C": float(sc.integral[k]), "scuffing_safety_integral": float(sc.safety_integral[k]),
            "scuffing": {"flash_temperature_max_K": float(sc.flash_max[k]),
                         "flash_temperature_mean_K": float(sc.flash_mean[k]),
                         "bulk_temperature_flash_method_C": float(sc.bulk_flash[k]),
                         "scuffing_temperature_C": sc.scuffing_temperature,
                         "bulk_temperature_integral_method_C": float(sc.bulk_integral[k]),
                         "integral_scuffing_temperature_C": sc.integral_scuffing_temperature,
                         "friction_coefficient": float(sc.mu[k]),
                         "oil_viscosity_mm2_s": sc.viscosity_oil}}


def _along_path(geom: PairGeometry, sc: ScuffingRating) -> tuple[np.ndarray, np.ndarray]:
    """Bin centres (m from A) and the largest flash temperature over the face in each bin (T, bins)."""
    edges = np.linspace(0.0, geom.path_of_contact, PATH_BINS + 1)
    where = np.clip(np.digitize(sc.path.s, edges) - 1, 0, PATH_BINS - 1)
    out = np.full((sc.flash.shape[0], PATH_BINS), np.nan)
    on = sc.path.on_path
    for t in range(out.shape[0]):
        np.fmax.at(out[t], where[on], sc.flash[t][on])
    return 0.5 * (edges[:-1] + edges[1:]), out


def scuffing_variables(geom: PairGeometry, ltca_result: LTCAResult, speed_rpm: float,
                       inputs: RatingInputs | None = None, application_factor: float = 1.0,
                       reference: LTCAResult | None = None) -> dict[str, xr.DataArray]:
    """The scuffing rating of an LTCA at pinion speed ``speed_rpm`` as variables (units and long
    names; temperatures in °C, their rises in K): the flash temperature of every point and its
    largest value over the face along the path, the flash and integral methods' temperatures and
    safety factors per torque. ``inputs`` the rating inputs (default: the pair's); K_v by ISO
    6336-1 method C and K_Hβ, K_Hα from the LTCA (``reference`` the unmodified pair's LTCA)."""
    inputs = inputs or rating_inputs(dict(geom.pair.rating_inputs))
    lf = ltca_load_factors(ltca_result.load, None if reference is None else reference.load)
    rated = [rating(geom, float(t), speed_rpm, inputs, application_factor, None, None, "ltca",
                    {"K_Hbeta": float(lf["K_Hbeta"][k]), "K_Halpha": float(rated_transverse_factor(lf["K_Halpha"][k]))}
                    ).values for k, t in enumerate(ltca_result.torque)]
    sc = scuffing_of(geom, ltca_result, speed_rpm, inputs, rated)
    centres, path_max = _along_path(geom, sc)
    t, tpjn = ("torque",), ("torque", "position", "line", "point")
    torque = {"torque": variable(t, ltca_result.torque, "N m", "pinion torque T1")}
    path = {"path": variable(("path",), centres, "m", "distance along the path of contact from A (bin centre)")}

    def da(dims, data, units, long_name, coords=None):
        return xr.DataArray(variable(dims, data, units, long_name), coords=coords)

    return {
        "flash_temperature": da(tpjn, sc.flash, "K", "flash temperature of each contact point by Blok, NaN off the "
                                "path of contact (LTCA line load times K_A K_v)", torque),
        "flash_temperature_path": da(("torque", "path"), path_max, "K", "largest flash temperature over the face "
                                     "along the path of contact", {**torque, **path}),
        "friction_coefficient": da(t, sc.mu, "1", "mean coefficient of friction mu_mC (ISO/TR 13989-2)", torque),
        "flash_temperature_max": da(t, sc.flash_max, "K", "largest flash temperature over the mesh cycle", torque),
        "flash_temperature_mean": da(t, sc.flash_mean, "K", "mean flash temperature over the path of contact "
                                     "(theta_flm = theta_flaint)", torque),
        "bulk_temperature_flash": da(t, sc.bulk_flash, "degC", "bulk temperature theta_M of the flash temperature "
                                     "method (ISO/TS 6336-20)", torque),
        "contact_temperature_max": da(t, sc.contact_max, "degC", "largest contact temperature theta_B = theta_M + "
                                      "theta_fl (ISO/TS 6336-20)", torque),
        "scuffing_temperature": da((), sc.scuffing_temperature, "degC", "scuffing temperature theta_S of the FZG "
                                   "load stage (ISO/TS 6336-20)"),
        "scuffing_safety_flash": da(t, sc.safety_flash, "1", "scuffing safety factor S_B = (theta_S - theta_oil)/"
                                    "(theta_B,max - theta_oil) (ISO/TS 6336-20)", torque),
        "bulk_temperature_integral": da(t, sc.bulk_integral, "degC", "bulk temperature theta_M of the integral "
                                        "temperature method (ISO/TS 6336-21)", torque),
        "integral_temperature": da(t, sc.integral, "degC", "integral temperature theta_int = theta_M + C2 "
                                   "theta_flaint (ISO/TS 6336-21)", torque),
        "integral_scuffing_temperature": da((), sc.integral_scuffing_temperature, "degC", "scuffing integral "
                                            "temperature theta_intS of the FZG load stage (ISO/TS 6336-21)"),
        "scuffing_safety_integral": da(t, sc.safety_integral, "1", "scuffing safety factor S_intS = theta_intS/"
                                       "theta_int (ISO/TS 6336-21)", torque),
    }
