"""The sign-off table: every micro-geometry variant of a pair beside the unmodified reference, per
LTCA torque, on what an engineer signs a modification off by, and whether it meets the study's
criteria (``signoff`` section; issue 27's item 3 by default).

No physics here: every number is read from the variants' own results as they are:
``impact.nc`` (F_s at the design speed, nominal and the worst tolerance sample; transverse; and
the loaded contact of every manufactured gear, :func:`gearmesh.impact.ltca_criteria` on the
impact model), ``ltca.nc`` (loaded-TE peak-to-peak and its mesh-order amplitudes; peak pressure
on a flank), ``rating.nc`` (peak contact pressure anywhere, peak root stress, S_H, S_F) and, where
the study has a dynamics section, ``dynamics.nc`` (the largest dynamic mesh force over the speed
sweep, normal, and the peak dynamic factor).

The pressure, root-stress and TE-order criteria judge the gear ``basis`` names:

- ``population`` (the default): the worst manufactured gear — the largest value over the nominal
  and the study's tolerance samples (the ``tolerances`` section: lead slope within ±f_Hβ,
  modification amounts within their tolerance) — against the reference's worst, each quantity
  on its own (statistic ``max``). It is what the optimiser evaluates (the same function on the
  same model and population), and the basis of ISO 6336-1's K_Hβ, which counts the helix slope
  deviation f_Hβ (f_ma) of the manufactured gear, not the drawing's;
- ``nominal``: the nominal gear, from the LTCA and rating stages.

The table keeps both: the nominal columns under their own names, the population's prefixed
``worst_``. The criteria compare each variant with the reference variant at the same torque:

- peak contact pressure ≤ ``pressure_factor`` × the reference's, like against like: the flanks'
  peak against the reference's flanks' peak, and the tip edges' peak against the reference's
  tip-edge peak (its flank peak where it has no edge contact;
  :func:`gearmesh.stress.edge_pressure_reference`). The overall peak alone would let a
  modification raise the flank pressure at will wherever the reference's peak is a tip-edge
  pressure (several GPa with an assumed edge radius), which is the unmodified pair's usual case;
- peak root stress of either gear ≤ ``root_stress_factor`` × the reference's;
- loaded-TE amplitudes at ``harmonic_orders`` ≤ ``harmonic_factor`` × the reference's;
- F_s (nominal) < ``impact_factor`` × the reference's, and the worst F_s over the torques
  ≤ ``worst_impact_factor`` × the reference's worst;
- the swept peak dynamic mesh force ≤ ``dynamic_factor`` × the reference's.
S_H and S_F stay the rating stage's (nominal gear, K_Hβ from its LTCA).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import xarray as xr

from ..errors import GearmeshInputError
from ..io import variable
from ..limits import same_point
from ..schema import check_arguments
from ..settings import Signoff
from ..stress import edge_pressure_reference
from ..tolerance import sample_statistic
from . import one_pair, variant_names

__all__ = ["BASES", "CRITERIA", "POPULATION", "signoff_table_dataset"]

#: Criterion flags: the reference itself, fails, meets (CF flag_values / flag_meanings).
_FLAG_VALUES = np.array([-1, 0, 1], dtype=np.int8)
_FLAG_MEANINGS = "reference fails meets"

#: name -> what the criterion holds (the table's long names).
CRITERIA = {
    "meets_pressure": "peak flank and tip-edge contact pressures at most pressure_factor x the reference's (like "
                      "against like)",
    "meets_root_stress": "peak root stress at most root_stress_factor x the reference's",
    "meets_te_harmonics": "loaded-TE amplitudes at harmonic_orders at most harmonic_factor x the reference's",
    "meets_impact": "F_s below impact_factor x the reference's at this torque",
    "meets_worst_impact": "worst F_s over the torques at most worst_impact_factor x the reference's worst",
    "meets_dynamics": "swept peak dynamic mesh force at most dynamic_factor x the reference's",
}


#: What each basis judges.
BASES = {"population": "the worst manufactured gear (largest over the nominal and the tolerance samples, impact "
                       "model) against the reference's worst",
         "nominal": "the nominal gear (ltca and rating stages) against the reference's"}

#: The statistic over the manufactured population (the worst gear: every quantity's largest value).
STATISTIC = "max"

#: Table column of the worst manufactured gear <- impact.nc variable (tolerance_sample, torque, ...).
POPULATION = {"lte_pp": "tolerance_lte_peak_to_peak", "harm": "tolerance_lte_harmonics",
              "p_flank": "tolerance_peak_flank_pressure", "p_edge": "tolerance_peak_edge_pressure",
              "sigma_f": "tolerance_peak_root_stress"}


def _by_torque(values: np.ndarray, torques: np.ndarray, wanted: np.ndarray, field: str, name: str) -> np.ndarray:
    """``values`` (torque first) at each of ``wanted`` (pinion torques, to 1e-9 relative)."""
    out = []
    for t in wanted:
        k = np.flatnonzero(same_point(torques, t))
        if not k.size:
            raise GearmeshInputError(field, torques.tolist(), f"must include the LTCA torque {t:g} N m (pinion) for "
                                     f"the sign-off table ({name})")
        out.append(values[k[0]])
    return np.array(out)


def _flag(meets: np.ndarray, reference: int) -> np.ndarray:
    """Criterion flags from booleans (variant first), the reference row marked as such."""
    flags = np.where(meets, 1, 0).astype(np.int8)
    flags[reference] = -1
    return flags


def _worst(imp: xr.Dataset, torques: np.ndarray, orders: list[int], name: str) -> dict[str, np.ndarray]:
    """The worst manufactured gear of a variant's impact.nc at the LTCA ``torques``: each quantity of
    :data:`POPULATION` reduced over the samples by :data:`STATISTIC`."""
    missing = [v for v in POPULATION.values() if v not in imp]
    if missing:
        raise GearmeshInputError("signoff.basis", "population", f"needs the manufactured gears' loaded contact in "
                                 f"{name}'s impact.nc ({missing[0]}): a tolerances section with samples; or basis: "
                                 f"nominal")
    if imp["mesh_order"].values.tolist()[:len(orders)] != orders:
        raise GearmeshInputError("impact.mesh_order", imp["mesh_order"].values.tolist(),
                                 f"must be the LTCA's mesh orders {orders} ({name})")
    t_imp = np.asarray(imp["torque"].values, dtype=float)
    out = {}
    for key, var in POPULATION.items():
        worst = sample_statistic(np.moveaxis(imp[var].values, 0, -1), STATISTIC)  # (torque, ...)
        out[key] = _by_torque(worst, t_imp, torques, "impact.torques_Nm", name)
    out["harm"] = out["harm"][:, :len(orders)]
    return out


def _judge(c: dict[str, np.ndarray], ref: int, k_orders: list[int], pressure_factor: float,
           root_stress_factor: float, harmonic_factor: float) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The like-against-like pressure ratio (variant, torque) and the pressure, root-stress and
    TE-order criteria met, of one basis's columns ``c`` (p_flank, p_edge, sigma_f, harm)."""
    harm = c["harm"][:, :, k_orders]
    edge_ref = edge_pressure_reference(c["p_flank"][ref], c["p_edge"][ref])
    ratio = np.maximum(c["p_flank"] / c["p_flank"][ref], c["p_edge"] / edge_ref)
    return ratio, {"meets_pressure": ratio <= pressure_factor,
                   "meets_root_stress": c["sigma_f"] <= root_stress_factor * c["sigma_f"][ref],
                   "meets_te_harmonics": np.all(harm <= harmonic_factor * harm[ref], axis=2)}


@check_arguments(Signoff)
def signoff_table_dataset(impact: Sequence[xr.Dataset], ltca: Sequence[xr.Dataset], rating: Sequence[xr.Dataset],
                          dynamics: Sequence[xr.Dataset] = (), *, reference: str, basis: str,
                          pressure_factor: float, root_stress_factor: float, harmonic_orders: Sequence[int],
                          harmonic_factor: float, impact_factor: float, worst_impact_factor: float,
                          dynamic_factor: float) -> xr.Dataset:
    """Every variant beside ``reference`` at each LTCA torque (variant × torque) and the criteria
    of the module docstring, judged on ``basis``, as flags (``reference``/``fails``/``meets``);
    ``meets_all`` holds them together. The variants' datasets may come in any order; they must
    cover the same variants (``dynamics`` may be empty: no dynamic criterion)."""
    names = variant_names("ltca", ltca)
    one_pair(ltca=ltca, impact=impact, rating=rating, dynamics=dynamics)
    by = {}
    for stage, datasets in (("impact", impact), ("rating", rating), ("dynamics", dynamics)):
        by[stage] = dict(zip(variant_names(stage, datasets, empty_ok=stage == "dynamics"), datasets))
        if datasets and set(by[stage]) != set(names):
            raise GearmeshInputError("variants", sorted(by[stage]), f"{stage} and ltca must cover the same variants "
                                     f"({sorted(names)})")
    if reference not in names:
        raise GearmeshInputError("signoff.reference", reference, f"must be one of the study's variants {names}")
    ref = names.index(reference)
    torques = np.asarray(ltca[ref]["torque"].values, dtype=float)
    orders = ltca[ref]["mesh_order"].values.tolist()
    missing = [n for n in harmonic_orders if n not in orders]
    if missing:
        raise GearmeshInputError("signoff.harmonic_orders", list(harmonic_orders),
                                 f"must be among the LTCA's mesh orders {orders}")
    dims = ("variant", "torque")
    cols: dict[str, list[np.ndarray]] = {k: [] for k in (
        "fs", "fs_tol", "lte_pp", "harm", "p", "p_flank", "p_edge", "on_edge", "sigma_f", "S_H", "S_F", "dyn_peak",
        "kv_peak")}
    worst: dict[str, list[np.ndarray]] = {k: [] for k in POPULATION}
    for name, lt in zip(names, ltca):
        if not np.allclose(lt["torque"].values, torques, rtol=1e-12):
            raise GearmeshInputError("ltca.torques_Nm", lt["torque"].values.tolist(),
                                     f"must be the same for every variant ({name})")
        imp, rat = by["impact"][name], by["rating"][name]
        t_imp = np.asarray(imp["torque"].values, dtype=float)  # pinion torques, as the LTCA's
        speeds = np.asarray(imp["speed"].values, dtype=float)
        design = float(imp.attrs["design_speed_rpm"])
        j = int(np.argmin(np.abs(speeds - design)))
        cols["fs"].append(_by_torque(imp["impact_force"].values[:, j], t_imp, torques, "impact.torques_Nm", name))
        tol = imp["tolerance_impact_force"].values.max(axis=0) if "tolerance_impact_force" in imp \
            else np.full(t_imp.size, np.nan)
        cols["fs_tol"].append(_by_torque(tol, t_imp, torques, "impact.torques_Nm", name))
        if basis == "population":
            for key, value in _worst(imp, torques, orders, name).items():
                worst[key].append(value)
        cols["lte_pp"].append(lt["lte_peak_to_peak"].values)
        cols["harm"].append(lt["lte_harmonics"].values)
        region, pressure = lt["region"].values, np.nan_to_num(lt["contact_pressure"].values)
        for key, where in (("p_flank", region == 1), ("p_edge", region >= 2)):
            cols[key].append(np.where(where, pressure, 0.0).reshape(torques.size, -1).max(axis=1))
        cols["p"].append(rat["peak_contact_pressure"].values)
        cols["on_edge"].append(rat["peak_contact_pressure_on_edge"].values)
        cols["sigma_f"].append(rat["peak_root_stress"].values.max(axis=1))
        cols["S_H"].append(rat["S_H"].values.min(axis=1))
        cols["S_F"].append(rat["S_F"].values.min(axis=1))
        if dynamics:
            dyn = by["dynamics"][name]
            t_dyn = np.asarray(dyn["pinion_torque"].values, dtype=float)
            cols["dyn_peak"].append(_by_torque(dyn["mesh_force_max"].values.max(axis=1), t_dyn, torques,
                                               "dynamics.torques_Nm", name))
            cols["kv_peak"].append(_by_torque(dyn["dynamic_factor"].values.max(axis=1), t_dyn, torques,
                                              "dynamics.torques_Nm", name))
    c = {k: np.array(v) for k, v in cols.items()}
    w = {k: np.array(v) for k, v in worst.items() if v}
    k_orders = [orders.index(n) for n in harmonic_orders]
    factors = (pressure_factor, root_stress_factor, harmonic_factor)
    pressure_ratio, nominal_flags = _judge(c, ref, k_orders, *factors)
    flags = nominal_flags
    if basis == "population":
        worst_ratio, flags = _judge(w, ref, k_orders, *factors)
    fs_worst = c["fs"].max(axis=1)
    flags |= {
        "meets_impact": c["fs"] < impact_factor * c["fs"][ref],
        "meets_worst_impact": np.broadcast_to((fs_worst <= worst_impact_factor * fs_worst[ref])[:, None],
                                              c["fs"].shape),
    }
    if dynamics:
        flags["meets_dynamics"] = c["dyn_peak"] <= dynamic_factor * c["dyn_peak"][ref]
    flags["meets_all"] = np.all(list(flags.values()), axis=0)
    judged = f"; judged on {basis}: {BASES[basis]}"
    out = {
        "judged_on": variable((), basis, "1", f"the gear the pressure, root-stress and TE-order criteria judge: "
                              f"{BASES[basis]}"),
        "impact_force": variable(dims, c["fs"], "N", "mesh-in impact force F_s at the design speed, nominal gears",
                                 force_line="transverse"),
        "impact_force_tolerance_max": variable(dims, c["fs_tol"], "N", "largest F_s over the nominal and the "
                                               "tolerance samples at the design speed", force_line="transverse"),
        "lte_peak_to_peak": variable(dims, c["lte_pp"], "m", "peak-to-peak loaded transmission error, nominal gear",
                                     engineering_units="µm"),
    }
    for k, n in enumerate(orders):
        out[f"lte_order_{n}"] = variable(dims, c["harm"][:, :, k], "m", f"amplitude of the loaded transmission error "
                                         f"at mesh order {n}, nominal gear", engineering_units="µm")
    out |= {
        "peak_contact_pressure": variable(dims, c["p"], "Pa", "largest Hertzian contact pressure over the mesh "
                                          "cycle, flank or tip edge, nominal gear"),
        "peak_contact_pressure_on_edge": variable(dims, c["on_edge"], "1", "1: the largest contact pressure sits on "
                                                  "a tip edge, 0: on a flank (nominal gear)"),
        "peak_flank_pressure": variable(dims, c["p_flank"], "Pa", "largest Hertzian contact pressure on the flanks' "
                                        "active zone (tip edges left out), nominal gear"),
        "peak_edge_pressure": variable(dims, c["p_edge"], "Pa", "largest Hertzian contact pressure of a tip edge on "
                                       "the mating flank (0: no edge contact), nominal gear"),
        "pressure_ratio": variable(dims, pressure_ratio, "1", "peak contact pressure over the reference's, like "
                                   "against like: the larger of flank over its flank peak and tip edge over its "
                                   "tip-edge peak (its flank peak where it has no edge contact), nominal gears"),
        "peak_root_stress": variable(dims, c["sigma_f"], "Pa", "largest tooth-root stress of either gear "
                                     "(ISO 6336-3 local form, slice by slice), nominal gear"),
    }
    if w:
        of = "worst manufactured gear (largest over the nominal and the tolerance samples, impact model)"
        out |= {
            "worst_lte_peak_to_peak": variable(dims, w["lte_pp"], "m", f"peak-to-peak loaded transmission error, {of}",
                                               engineering_units="µm"),
            **{f"worst_lte_order_{n}": variable(dims, w["harm"][:, :, k], "m", f"amplitude of the loaded "
                                                f"transmission error at mesh order {n}, {of}", engineering_units="µm")
               for k, n in enumerate(orders)},
            "worst_peak_flank_pressure": variable(dims, w["p_flank"], "Pa", f"largest Hertzian contact pressure on "
                                                  f"the flanks' active zone (tip edges left out), {of}"),
            "worst_peak_edge_pressure": variable(dims, w["p_edge"], "Pa", f"largest Hertzian contact pressure of a "
                                                 f"tip edge on the mating flank (0: no edge contact), {of}"),
            "worst_pressure_ratio": variable(dims, worst_ratio, "1", f"peak contact pressure over the reference's, "
                                             f"like against like (as pressure_ratio), {of} against the reference's"),
            "worst_peak_root_stress": variable(dims, w["sigma_f"], "Pa", f"largest tooth-root stress of either gear "
                                               f"(ISO 6336-3 local form, slice by slice), {of}"),
        }
    out |= {
        "S_H": variable(dims, c["S_H"], "1", "safety factor against pitting, weaker gear (ISO 6336-2), nominal gear"),
        "S_F": variable(dims, c["S_F"], "1", "safety factor against tooth breakage, weaker gear (ISO 6336-3), "
                                             "nominal gear"),
    }
    if dynamics:
        out["dynamic_mesh_force_peak"] = variable(dims, c["dyn_peak"], "N", "largest dynamic mesh force over the "
                                                  "speed sweep", force_line="normal")
        out["dynamic_factor_peak"] = variable(dims, c["kv_peak"], "1", "largest dynamic factor (peak over static "
                                              "mesh force) over the speed sweep")
    on_basis = ("meets_pressure", "meets_root_stress", "meets_te_harmonics")
    for key, meets in flags.items():
        what = CRITERIA.get(key, "every criterion met") + (judged if key in on_basis else "")
        v = variable(dims, _flag(np.asarray(meets), ref), "1", what)
        v.attrs.update(flag_values=_FLAG_VALUES, flag_meanings=_FLAG_MEANINGS)
        out[key] = v
    ds = xr.Dataset(out, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
                                 "torque": variable(("torque",), torques, "N m", "pinion torque T1")})
    ds.attrs.update(reference=reference, basis=basis, pressure_factor=pressure_factor,
                    root_stress_factor=root_stress_factor,
                    harmonic_orders=np.array(harmonic_orders, dtype=np.int64), harmonic_factor=harmonic_factor,
                    impact_factor=impact_factor, worst_impact_factor=worst_impact_factor,
                    dynamic_factor=dynamic_factor,
                    design_speed_rpm=float(by["impact"][reference].attrs["design_speed_rpm"]))
    if basis == "population":
        ds.attrs.update(tolerance_statistic=STATISTIC,
                        tolerance_samples=int(by["impact"][reference].attrs.get("tolerance_samples", 0)))
    return ds
