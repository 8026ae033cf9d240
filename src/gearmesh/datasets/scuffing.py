"""Scuffing load capacity of an LTCA (:mod:`gearmesh.scuffing`): the scuffing stage's dataset
(scuffing.nc, per variant, from the variant's ltca.nc and rating.nc), the table of a pair's
variants, and the keys of ``gearmesh rating --json``. The stage and the CLI compute through the
one function :func:`scuffing_of`.

The load factors are the rating's (:func:`gearmesh.rating.rating`; the study's rating section:
its speed, K_A and where K_Hβ, K_Hα come from): the LTCA's line load is scaled by K_A K_v, and
μ_mC takes the rating's w_Bt = K_A K_v K_Hβ K_Hα F_t/b.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
import xarray as xr

from . import shared_torques, variant_names
from ..gear import GearPair, PairGeometry, pair_geometry
from ..io import variable
from ..errors import GearmeshInputError
from ..ltca import LTCAResult
from ..rating import RatingInputs, rating_inputs
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..scuffing import ScuffingRating, scuffing_rating
from ..settings import Scuffing

__all__ = ["LoadedContact", "scuffing_of", "scuffing_json", "rated_factors", "scuffing_variables",
           "scuffing_dataset", "scuffing_table_dataset"]


@dataclass(frozen=True)
class _PathGrid:
    """An LTCA's candidate grid as far as the path of contact needs it (arrays (P, J, N)):
    ``region`` (1: flank between A and E), ``s`` (m from A), the roll lengths ``rho_pinion``,
    ``rho_gear`` (m)."""

    region: np.ndarray
    s: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray


@dataclass(frozen=True)
class LoadedContact:
    """An LTCA's ``line_load`` (T, P, J, N) N/m on its ``grid`` at its pinion torques ``torque``
    (N·m): what :func:`scuffing_of` rates, from an LTCA result or read back from ltca.nc."""

    line_load: np.ndarray
    grid: Any
    torque: np.ndarray

    @classmethod
    def of(cls, ltca: LTCAResult | xr.Dataset) -> "LoadedContact":
        if isinstance(ltca, xr.Dataset):
            grid = _PathGrid(*(ltca[k].values for k in ("region", "s", "rho_pinion", "rho_gear")))
            return cls(ltca["line_load"].values, grid, ltca["torque"].values)
        return cls(ltca.line_load, ltca.grid, np.asarray(ltca.torque, dtype=float))


def scuffing_of(geom: PairGeometry, res: LTCAResult | LoadedContact, speed_rpm: float, inputs: RatingInputs,
                rated: Sequence[Mapping[str, Any]]) -> ScuffingRating:
    """:func:`gearmesh.scuffing.scuffing_rating` of the LTCA ``res`` (a result, or ltca.nc read
    back: :class:`LoadedContact`) at pinion speed ``speed_rpm`` with the load factors of ``rated``
    (the rating's values at each of its torques: K_A, K_v, K_Hbeta, K_Halpha, force_tangential_N).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    res : LTCAResult or LoadedContact
        The loaded contact: line load (T, P, J, N) N/m on its path grid, T torques.
    speed_rpm : float
        Pinion speed (rpm).
    inputs : RatingInputs
        The pair's rating inputs (:class:`gearmesh.rating.RatingInputs`: material, roughness, lubricant).
    rated : Sequence[Mapping[str, Any]]
        Per torque the load factors (1) and the nominal tangential force (N) (:func:`rated_factors`);
        the transverse unit load w_Bt = K_A K_v K_Hβ K_Hα F_t / b is formed in N/mm.

    Returns
    -------
    ScuffingRating
        Flash and integral temperature methods' temperatures and safety factors per torque.

    References
    ----------
    .. [1] ISO/TS 6336-20:2017, Calculation of load capacity of spur and helical gears — Part 20:
       Calculation of scuffing load capacity — Flash temperature method.
    .. [2] ISO/TS 6336-21:2017, Calculation of load capacity of spur and helical gears — Part 21:
       Calculation of scuffing load capacity — Integral temperature method.
    """
    load_factor = [v["K_A"] * v["K_v"] for v in rated]
    w_bt = [v["K_A"] * v["K_v"] * v["K_Hbeta"] * v["K_Halpha"] * v["force_tangential_N"] / (geom.face_width * 1e3)
            for v in rated]
    return scuffing_rating(geom, res.line_load, res.grid, speed_rpm, inputs, load_factor, w_bt)


def scuffing_json(sc: ScuffingRating, k: int = 0) -> dict[str, Any]:
    """The keys of ``gearmesh rating --json`` at torque ``k``: the flash temperature method's
    largest contact temperature and S_B, the integral method's θ_int and S_intS, and their parts.

    Parameters
    ----------
    sc : ScuffingRating
        The scuffing rating (:func:`scuffing_of`).
    k : int, default 0
        Index of the torque.

    Returns
    -------
    dict[str, Any]
        ``contact_temperature_max_C`` and ``integral_temperature_C`` (°C), ``scuffing_safety_flash``
        and ``scuffing_safety_integral`` (1), and ``scuffing``: flash temperatures (K), bulk and
        scuffing temperatures (°C), ``friction_coefficient`` (1), ``oil_viscosity_mm2_s`` (mm²/s).
    """
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


def rated_factors(geom: PairGeometry, rating: xr.Dataset) -> list[dict[str, float]]:
    """The rating's load factors at each torque of rating.nc (its ``K_v``, ``K_Hbeta``,
    ``K_Halpha`` and K_A, as :func:`gearmesh.datasets.rating.rating_dataset` rated them) with the
    nominal tangential force F_t = 2 T1/d1 at the reference circle (ISO 6336-1:2019, 6.1), the
    values :func:`scuffing_of` takes.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry: the pinion's reference radius d1/2 (m).
    rating : xarray.Dataset
        The pair's rating.nc (dim torque, pinion N·m).

    Returns
    -------
    list[dict[str, float]]
        Per torque ``K_A``, ``K_v``, ``K_Hbeta``, ``K_Halpha`` (1) and ``force_tangential_N`` (N).

    References
    ----------
    .. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1,
       clause 6.1 (nominal tangential load).
    """
    k_a = float(rating.attrs["application_factor"])
    return [{"K_A": k_a, "K_v": float(rating["K_v"].values[k]), "K_Hbeta": float(rating["K_Hbeta"].values[k]),
             "K_Halpha": float(rating["K_Halpha"].values[k]),
             "force_tangential_N": float(t1) / float(geom.reference_radius[0])}
            for k, t1 in enumerate(rating["torque"].values)]


def _along_path(geom: PairGeometry, sc: ScuffingRating, line_load: np.ndarray, bins: int
                ) -> tuple[np.ndarray, np.ndarray]:
    """Bin centres (m from A) and the largest flash temperature over the face in each bin of the
    path A–E (T, bins): NaN where no point of the bin carries load (no contact there, e.g. under a
    tip relief), which is not a flash temperature of zero."""
    edges = np.linspace(0.0, geom.path_of_contact, bins + 1)
    where = np.clip(np.digitize(sc.path.s, edges) - 1, 0, bins - 1)
    out = np.full((sc.flash.shape[0], bins), -np.inf)
    for t in range(out.shape[0]):
        loaded = sc.path.on_path & (line_load[t] > 0)
        np.maximum.at(out[t], where[loaded], sc.flash[t][loaded])
    return 0.5 * (edges[:-1] + edges[1:]), np.where(np.isfinite(out), out, np.nan)


def scuffing_variables(geom: PairGeometry, contact: LoadedContact, sc: ScuffingRating, bins: int
                       ) -> dict[str, xr.DataArray]:
    """The scuffing rating ``sc`` of ``contact`` as variables (units and long names; temperatures
    in °C, their rises in K): the flash temperature of every point and its largest value over the
    face in ``bins`` bins of the path, the pitch point's place on it, the flash and integral
    methods' temperatures and safety factors per torque.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    contact : LoadedContact
        The loaded contact the rating was made on (line load N/m, T torques).
    sc : ScuffingRating
        Its scuffing rating (:func:`scuffing_of`).
    bins : int
        Number of bins along the path of contact A–E for the largest flash temperature.

    Returns
    -------
    dict[str, xarray.DataArray]
        scuffing.nc's variables (dims torque, position, line, point, path), each with ``units``
        and ``long_name``.
    """
    centres, path_max = _along_path(geom, sc, contact.line_load, bins)
    t, tpjn = ("torque",), ("torque", "position", "line", "point")
    torque = {"torque": variable(t, contact.torque, "N m", "pinion torque T1")}
    path = {"path": variable(("path",), centres, "m", "distance along the path of contact from A (bin centre)")}
    pitch = float(geom.base_radius[0]) * np.tan(geom.operating_pressure_angle) - float(geom.rho_sap[0])

    def da(dims, data, units, long_name, coords=None):
        return xr.DataArray(variable(dims, data, units, long_name), coords=coords)

    return {
        "flash_temperature": da(tpjn, sc.flash, "K", "flash temperature of each contact point by Blok, NaN off the "
                                "path of contact (LTCA line load times K_A K_v)", torque),
        "flash_temperature_path": da(("torque", "path"), path_max, "K", "largest flash temperature over the face "
                                     "along the path of contact (NaN: no contact in the bin)", {**torque, **path}),
        "pitch_point": da((), pitch, "m", "distance of the pitch point C from A along the path of contact"),
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


@check_arguments(Scuffing, exclude=section_keys(Scuffing))  # parsed once below
def scuffing_dataset(pair: GearPair, *, ltca: xr.Dataset | None = None, rating: xr.Dataset | None = None,
                     **section: Any) -> xr.Dataset:
    """The scuffing rating of a pair (a variant) at each torque of its ``ltca`` dataset with the
    load factors and speed of its ``rating`` dataset (scuffing.nc): Blok's flash temperature of
    every contact point from the LTCA's line load, its largest value over the face along the path
    of contact, and the flash temperature method's (ISO/TS 6336-20: θ_B,max, S_B) and the integral
    temperature method's (ISO/TS 6336-21: θ_int, S_intS) temperatures and safety factors. Oil,
    roughness and FZG load stage are the pair file's (defaults named in the notes).

    Parameters
    ----------
    pair : GearPair
        The pair (a variant).
    ltca : xarray.Dataset
        Its ltca.nc.
    rating : xarray.Dataset
        Its rating.nc (speed and load factors), rated at the LTCA's torques.
    **section
        A study's ``scuffing:`` section (:class:`gearmesh.settings.Scuffing`: ``path_bins``, the bins
        of the path of contact), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        scuffing.nc (dims torque, position, line, point, path).
    """
    path_bins = settings_object(Scuffing, section).path_bins
    for name, ds, needed in (("ltca", ltca, "line_load"), ("rating", rating, "K_v")):
        if not isinstance(ds, xr.Dataset) or needed not in ds:
            raise GearmeshInputError(name, type(ds).__name__, f"must be the variant's {name}.nc dataset")
    contact = LoadedContact.of(ltca)
    if contact.torque.shape != rating["torque"].shape or not np.allclose(contact.torque, rating["torque"].values,
                                                                         rtol=1e-12):
        raise GearmeshInputError("rating", rating["torque"].values.tolist(), "must be rated at the LTCA's torques "
                                 f"{contact.torque.tolist()}")
    geom = pair_geometry(pair)
    speed = float(rating.attrs["speed_rpm"])
    sc = scuffing_of(geom, contact, speed, rating_inputs(dict(pair.rating_inputs)), rated_factors(geom, rating))
    ds = xr.Dataset(scuffing_variables(geom, contact, sc, path_bins))
    ds.attrs.update({"speed_rpm": speed, "application_factor": float(rating.attrs["application_factor"]),
                     "factor_method": rating.attrs.get("factor_method", ""), "scuffing_notes": "; ".join(sc.notes())})
    return ds


def scuffing_table_dataset(scuffing: Sequence[xr.Dataset]) -> xr.Dataset:
    """The scuffing load capacity of every variant of a pair side by side (variant × torque): the
    largest flash and contact temperatures and S_B (ISO/TS 6336-20), the integral temperature and
    S_intS (ISO/TS 6336-21).

    Parameters
    ----------
    scuffing : Sequence[xarray.Dataset]
        Each variant's scuffing.nc (:func:`scuffing_dataset`), of one pair and the same torques.

    Returns
    -------
    xarray.Dataset
        scuffing_table.nc (dims variant, torque): ``flash_temperature_max`` (K),
        ``contact_temperature_max`` and ``integral_temperature`` (°C), ``scuffing_safety_flash``
        and ``scuffing_safety_integral`` (1); units as the variants' datasets carry them.

    Raises
    ------
    GearmeshInputError
        Naming ``scuffing`` (not one pair's variants) or ``ltca.torques_Nm`` (torques that differ).
    """
    names = variant_names("scuffing", scuffing)
    torques = shared_torques("ltca.torques_Nm", names, scuffing)
    dims = ("variant", "torque")
    keys = ("flash_temperature_max", "contact_temperature_max", "scuffing_safety_flash", "integral_temperature",
            "scuffing_safety_integral")
    return xr.Dataset(
        {key: variable(dims, np.array([ds[key].values for ds in scuffing]), scuffing[0][key].attrs["units"],
                       scuffing[0][key].attrs["long_name"]) for key in keys},
        coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
                "torque": variable(("torque",), torques, "N m", "pinion torque T1")})
