"""The sign-off table: every micro-geometry variant of a pair beside the unmodified reference, per
LTCA torque, on what an engineer signs a modification off by, and whether it meets the study's
criteria (``signoff`` section).

No physics here: every number is read from the variants' own results as they are: ``impact.nc``
(F_s at the design speed, transverse; and every manufactured gear's criteria,
:mod:`gearmesh.robust`), ``ltca.nc`` (the nominal gear's loaded-TE orders and pressures),
``rating.nc`` (peak contact pressure anywhere, peak root stress, S_H, S_F) and, where the study has
a dynamics section, ``dynamics.nc`` (the largest dynamic mesh force over the speed sweep, normal).

Every criterion judges on one ``basis``:

- ``population`` (the default): **the worst manufactured gear**, the largest value of the quantity
  over the tolerance box — searched (:func:`gearmesh.robust.box_worst`), and never below the largest
  of the study's population and held-out gears — against the reference's worst. F_s included
  (the energy-method impact index of the mesh-in impact paper, at the design speed). The dynamic
  criterion stays on the nominal gear: the contact dynamics of every manufactured gear over the
  speed sweep would cost a dynamics stage each; each flag's ``basis`` attribute says so.
- ``nominal``: the nominal gears (ltca, rating and impact stages).

Beside the worst case, as columns and not as criteria: the median and the 90th percentile over the
population (``median_*``, ``p90_*``) and, gear for gear, the share of the population's gears that
are worse than the reference made with the same deviations (``share_worse_*``). The verdict is
checked on the held-out gears (their own seed, never seen by an optimiser): ``heldout_holds`` (the
held-out gears judged alone: meets when every one meets the criteria) and, where one does not, the
first held-out gear that fails (``heldout_breaking_gear``; write it as a pair file with ``gearmesh
manufactured``); ``meets_all`` holds only where both hold.

The criteria compare each variant with the reference variant at the same torque:

- peak contact pressure ≤ ``pressure_factor`` × the reference's, like against like: the flanks'
  peak against the reference's flanks' peak, and the tip edges' peak against the reference's
  tip-edge peak (its flank peak where it has no edge contact;
  :func:`gearmesh.stress.edge_pressure_reference`);
- peak root stress of either gear ≤ ``root_stress_factor`` × the reference's;
- loaded-TE amplitudes at ``harmonic_orders`` ≤ ``harmonic_factor`` × the reference's;
- F_s < ``impact_factor`` × the reference's, and the worst F_s over the torques
  ≤ ``worst_impact_factor`` × the reference's worst;
- the swept peak dynamic mesh force ≤ ``dynamic_factor`` × the reference's (nominal gears).
S_H and S_F stay the rating stage's (nominal gear, K_Hβ of its misaligned mesh).
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import xarray as xr

from ..errors import GearmeshInputError
from ..io import variable
from ..limits import same_point
from ..arguments import check_arguments
from ..schema import section_keys, settings_object
from ..settings import Signoff
from ..stress import edge_pressure_reference
from ..robust import CRITERION_UNITS
from . import one_pair, shared_torques, variant_names

__all__ = ["BASES", "CRITERIA", "signoff_table_dataset"]

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
BASES = {"population": "the worst manufactured gear (the largest over the tolerance box, searched, and over the "
                       "population and held-out gears) against the reference's worst",
         "nominal": "the nominal gear (ltca, rating and impact stages) against the reference's"}
#: Why a criterion stays nominal on the population basis.
NOMINAL_ONLY = {"meets_dynamics": "nominal gears: the contact dynamics of every manufactured gear over the speed "
                                  "sweep would cost a dynamics stage each"}

#: impact.nc's criteria of one gear (gearmesh.robust.CRITERIA) <- the table's keys
_GEAR = {"fs": "impact_force", "p_flank": "peak_flank_pressure", "p_edge": "peak_edge_pressure",
         "sigma_f": "peak_root_stress"}


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


def _manufactured(imp: xr.Dataset, torques: np.ndarray, orders: list[int], name: str) -> dict[str, np.ndarray]:
    """The manufactured gears of a variant's impact.nc at the LTCA ``torques``: per criterion key
    (``fs``, ``harm``, ``p_flank``, ``p_edge``, ``sigma_f``) the ``worst`` (torque, ...) — the box
    worst, never below the population's and the held-out gears' largest — the ``population`` and
    ``heldout`` values (gear, torque, ...)."""
    need = [f"box_worst_{c}" for c in CRITERIA_OF_GEAR] + [f"population_{c}" for c in CRITERIA_OF_GEAR]
    missing = [v for v in need if v not in imp]
    if missing:
        raise GearmeshInputError("signoff.basis", "population", f"needs the manufactured gears in {name}'s impact.nc "
                                 f"({missing[0]}): a tolerances section with a population and the impact section's "
                                 f"tolerance_torques_Nm; or basis: nominal")
    judged = np.asarray(imp["judged_torque"].values, dtype=float)
    order_names = [f"lte_order_{n}" for n in orders]

    def block(prefix: str) -> dict[str, np.ndarray]:
        if f"{prefix}_impact_force" not in imp:
            return {}
        def at(c):
            return np.moveaxis(_by_torque(np.moveaxis(imp[f"{prefix}_{c}"].values, -1, 0), judged, torques,
                                          "impact.tolerance_torques_Nm", name), 0, -1)
        out = {key: at(c) for key, c in _GEAR.items()}
        out["harm"] = np.stack([at(c) for c in order_names], axis=-1)
        return out

    box = {key: _by_torque(imp[f"box_worst_{c}"].values, judged, torques, "impact.tolerance_torques_Nm", name)
           for key, c in _GEAR.items()}
    box["harm"] = np.stack([_by_torque(imp[f"box_worst_{c}"].values, judged, torques, "impact.tolerance_torques_Nm",
                                       name) for c in order_names], axis=-1)
    population, heldout = block("population"), block("heldout")
    worst = {k: np.maximum(v, np.nanmax(population[k], axis=0)) for k, v in box.items()}
    if heldout:
        worst = {k: np.maximum(v, np.nanmax(heldout[k], axis=0)) for k, v in worst.items()}
    return {"worst": worst, "population": population, "heldout": heldout}


#: The criteria of one gear that impact.nc stores (gearmesh.robust.CRITERIA).
CRITERIA_OF_GEAR = ("impact_force", "peak_flank_pressure", "peak_edge_pressure", "peak_root_stress")


def _judge(c: dict[str, np.ndarray], ref: dict[str, np.ndarray], k_orders: list[int], s: Signoff
           ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The like-against-like pressure ratio and the pressure, root-stress and TE-order criteria of
    ``s`` met by columns ``c`` (p_flank, p_edge, sigma_f, harm; leading axes any) against the
    reference's ``ref`` (the same keys, (torque, ...))."""
    harm = c["harm"][..., k_orders]
    edge_ref = edge_pressure_reference(ref["p_flank"], ref["p_edge"])
    ratio = np.maximum(c["p_flank"] / ref["p_flank"], c["p_edge"] / edge_ref)
    return ratio, {"meets_pressure": ratio <= s.pressure_factor,
                   "meets_root_stress": c["sigma_f"] <= s.root_stress_factor * ref["sigma_f"],
                   "meets_te_harmonics": np.all(harm <= s.harmonic_factor * ref["harm"][..., k_orders], axis=-1)}


def _impact_flags(fs: np.ndarray, fs_ref: np.ndarray, s: Signoff) -> dict[str, np.ndarray]:
    """F_s below ``s.impact_factor`` × the reference's at each torque, and the worst over the torques
    (last axis) at most ``s.worst_impact_factor`` × the reference's worst."""
    worst = np.max(fs, axis=-1, keepdims=True)
    return {"meets_impact": fs < s.impact_factor * fs_ref,
            "meets_worst_impact": np.broadcast_to(worst <= s.worst_impact_factor * np.max(fs_ref), fs.shape)}


def _heldout_verdict(held: dict[str, np.ndarray], ref: dict[str, np.ndarray], k_orders: list[int], s: Signoff
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Whether every held-out gear (gear, torque, ...) meets the basis criteria against the reference's
    worst (torque,), and the first gear that breaks them at each torque (−1: none)."""
    _, flags = _judge(held, ref, k_orders, s)
    flags |= _impact_flags(held["fs"], ref["fs"], s)
    ok = np.all(list(flags.values()), axis=0)  # (gear, torque)
    broken = ~ok
    return ok.all(axis=0), np.where(broken.any(axis=0), np.argmax(broken, axis=0), -1)


@check_arguments(Signoff, exclude=section_keys(Signoff))
def signoff_table_dataset(impact: Sequence[xr.Dataset], ltca: Sequence[xr.Dataset], rating: Sequence[xr.Dataset],
                          dynamics: Sequence[xr.Dataset] = (), **section: Any) -> xr.Dataset:
    """Every variant beside the section's ``reference`` at each LTCA torque (variant × torque) and
    the criteria of the module docstring, judged on its ``basis``, as flags
    (``reference``/``fails``/``meets``); ``meets_all`` holds them together (and, on the population
    basis, the held-out check).

    Parameters
    ----------
    impact, ltca, rating : sequence of xarray.Dataset
        Each variant's impact.nc, ltca.nc and rating.nc, in any order; they must cover the same
        variants of one pair.
    dynamics : sequence of xarray.Dataset, optional
        Each variant's dynamics.nc; empty: no dynamic criterion.
    **section
        A study's ``signoff:`` section (:class:`gearmesh.settings.Signoff`: the reference, the basis
        and the factors), parsed once (:func:`gearmesh.schema.settings_object`).

    Returns
    -------
    xarray.Dataset
        signoff_table.nc (dims variant, torque).
    """
    s = settings_object(Signoff, section)
    reference, basis, harmonic_orders = s.reference, s.basis, s.harmonic_orders
    names = variant_names("ltca", ltca)
    one_pair(ltca=ltca, impact=impact, rating=rating, dynamics=dynamics)
    by = _by_variant(names, impact, rating, dynamics)
    if reference not in names:
        raise GearmeshInputError("signoff.reference", reference, f"must be one of the study's variants {names}")
    ref = names.index(reference)
    torques = shared_torques("ltca.torques_Nm", names, ltca)
    orders = ltca[ref]["mesh_order"].values.tolist()
    missing = [n for n in harmonic_orders if n not in orders]
    if missing:
        raise GearmeshInputError("signoff.harmonic_orders", list(harmonic_orders),
                                 f"must be among the LTCA's mesh orders {orders}")
    dims = ("variant", "torque")
    c, made = _variant_columns(names, ltca, by, torques, orders, basis, bool(dynamics))
    k_orders = [orders.index(n) for n in harmonic_orders]
    nominal_ref = {k: c[k][ref] for k in ("p_flank", "p_edge", "sigma_f", "harm")}
    pressure_ratio, flags = _judge(c, nominal_ref, k_orders, s)
    flags |= _impact_flags(c["fs"], c["fs"][ref], s)
    out: dict[str, xr.Variable] = {}
    if basis == "population":
        basis_flags, out, holds = _population_verdict(names, made, ref, k_orders, s, orders, dims)
        flags |= basis_flags
    if dynamics:
        flags["meets_dynamics"] = c["dyn_peak"] <= s.dynamic_factor * c["dyn_peak"][ref]
    verdict = np.all(list(flags.values()), axis=0)
    if "heldout_holds" in out:
        verdict &= holds
    flags["meets_all"] = verdict
    out = _nominal_columns(c, pressure_ratio, orders, dims, basis) | out
    out |= _safety_and_dynamics_columns(c, dims, bool(dynamics))
    out |= _flag_columns(flags, ref, basis, dims, "heldout_holds" in out)
    ds = xr.Dataset(out, coords={"variant": variable(("variant",), np.array(names), "1", "micro-geometry variant"),
                                 "torque": variable(("torque",), torques, "N m", "pinion torque T1")})
    ds.attrs.update(reference=reference, basis=basis, pressure_factor=s.pressure_factor,
                    root_stress_factor=s.root_stress_factor,
                    harmonic_orders=np.array(harmonic_orders, dtype=np.int64), harmonic_factor=s.harmonic_factor,
                    impact_factor=s.impact_factor, worst_impact_factor=s.worst_impact_factor,
                    dynamic_factor=s.dynamic_factor,
                    design_speed_rpm=float(by["impact"][reference].attrs["design_speed_rpm"]))
    if basis == "population":
        imp = by["impact"][reference]
        ds.attrs.update({key: int(imp.attrs.get(f"tolerance_{key}", 0)) for key in ("population", "heldout")} |
                        {"heldout_seed": int(imp.attrs.get("tolerance_heldout_seed", 0))})
    return ds


def _by_variant(names: list[str], impact: Sequence[xr.Dataset], rating: Sequence[xr.Dataset],
                dynamics: Sequence[xr.Dataset]) -> dict[str, dict[str, xr.Dataset]]:
    """The impact, rating and dynamics datasets of each variant (stage -> variant -> dataset), refused
    unless each stage covers the LTCA's variants ``names`` (dynamics may be empty)."""
    by = {}
    for stage, datasets in (("impact", impact), ("rating", rating), ("dynamics", dynamics)):
        by[stage] = dict(zip(variant_names(stage, datasets, empty_ok=stage == "dynamics"), datasets))
        if datasets and set(by[stage]) != set(names):
            raise GearmeshInputError("variants", sorted(by[stage]), f"{stage} and ltca must cover the same variants "
                                     f"({sorted(names)})")
    return by


def _variant_columns(names: list[str], ltca: Sequence[xr.Dataset], by: dict[str, dict[str, xr.Dataset]],
                     torques: np.ndarray, orders: list[int], basis: str, with_dynamics: bool
                     ) -> tuple[dict[str, np.ndarray], list[dict]]:
    """Each variant's nominal values at the LTCA ``torques`` (key -> (variant, torque, ...)): F_s at
    the design speed, loaded TE, flank and tip-edge pressures, root stress, safety factors and,
    ``with_dynamics``, the dynamic peaks; on the population basis also its manufactured gears
    (:func:`_manufactured`, one per variant)."""
    cols: dict[str, list[np.ndarray]] = {k: [] for k in (
        "fs", "lte_pp", "harm", "p", "p_flank", "p_edge", "on_edge", "sigma_f", "S_H", "S_F", "dyn_peak", "kv_peak")}
    made = []
    for name, lt in zip(names, ltca):
        imp, rat = by["impact"][name], by["rating"][name]
        t_imp = np.asarray(imp["torque"].values, dtype=float)  # pinion torques, as the LTCA's
        speeds = np.asarray(imp["speed"].values, dtype=float)
        design = float(imp.attrs["design_speed_rpm"])
        j = int(np.argmin(np.abs(speeds - design)))
        cols["fs"].append(_by_torque(imp["impact_force"].values[:, j], t_imp, torques, "impact.torques_Nm", name))
        if basis == "population":
            made.append(_manufactured(imp, torques, orders, name))
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
        if with_dynamics:
            dyn = by["dynamics"][name]
            t_dyn = np.asarray(dyn["pinion_torque"].values, dtype=float)
            cols["dyn_peak"].append(_by_torque(dyn["mesh_force_max"].values.max(axis=1), t_dyn, torques,
                                               "dynamics.torques_Nm", name))
            cols["kv_peak"].append(_by_torque(dyn["dynamic_factor"].values.max(axis=1), t_dyn, torques,
                                              "dynamics.torques_Nm", name))
    return {k: np.array(v) for k, v in cols.items()}, made


def _population_verdict(names: list[str], made: list[dict], ref: int, k_orders: list[int], s: Signoff,
                        orders: list[int], dims) -> tuple[dict[str, np.ndarray], dict[str, xr.Variable], np.ndarray | None]:
    """The criteria on the population basis (each variant's worst manufactured gear against the
    reference's worst), the population's columns and, when every variant has held-out gears,
    whether the verdict holds on them (per variant; None without them)."""
    w = {k: np.array([m["worst"][k] for m in made]) for k in made[ref]["worst"]}
    w_ref = {k: v[ref] for k, v in w.items()}
    worst_ratio, basis_flags = _judge(w, w_ref, k_orders, s)
    basis_flags |= _impact_flags(w["fs"], w_ref["fs"], s)
    out = _population_columns(names, made, ref, w, worst_ratio, orders, dims)
    holds = None
    if all(m["heldout"] for m in made):
        held = [_heldout_verdict(m["heldout"], w_ref, k_orders, s) for m in made]
        holds = np.array([h[0] for h in held])
        out["heldout_holds"] = variable(dims, _flag(holds, ref), "1", "the held-out gears (their own seed, never "
                                        "seen by an optimiser) judged alone: meets when every one meets the "
                                        "criteria (a meets verdict holds there), fails when one does not",
                                        flag_values=_FLAG_VALUES, flag_meanings=_FLAG_MEANINGS)
        out["heldout_breaking_gear"] = variable(dims, np.array([h[1] for h in held], dtype=np.int64), "1",
                                                "the first held-out gear that breaks the verdict (-1: none; "
                                                "gearmesh manufactured writes it as a pair file)")
    return basis_flags, out, holds


def _safety_and_dynamics_columns(c: dict[str, np.ndarray], dims, with_dynamics: bool) -> dict[str, xr.Variable]:
    """The nominal gears' safety factors and, ``with_dynamics``, their dynamic peaks over the sweep."""
    out = {
        "S_H": variable(dims, c["S_H"], "1", "safety factor against pitting, weaker gear (ISO 6336-2), nominal gear"),
        "S_F": variable(dims, c["S_F"], "1", "safety factor against tooth breakage, weaker gear (ISO 6336-3), "
                                             "nominal gear"),
    }
    if with_dynamics:
        out["dynamic_mesh_force_peak"] = variable(dims, c["dyn_peak"], "N", "largest dynamic mesh force over the "
                                                  "speed sweep, nominal gear", force_line="normal")
        out["dynamic_factor_peak"] = variable(dims, c["kv_peak"], "1", "largest dynamic factor (peak over static "
                                              "mesh force) over the speed sweep, nominal gear")
    return out


def _flag_columns(flags: dict[str, np.ndarray], ref: int, basis: str, dims, heldout: bool) -> dict[str, xr.Variable]:
    """Each criterion's flags (``reference``/``fails``/``meets``) with the basis it was judged on
    (``heldout``: ``meets_all`` includes the held-out gears)."""
    out = {}
    for key, meets in flags.items():
        on = "nominal" if basis == "nominal" or key in NOMINAL_ONLY else basis
        why = NOMINAL_ONLY.get(key, BASES[basis]) if key != "meets_all" else \
            BASES[basis] + ("; and the held-out gears" if heldout else "")
        out[key] = variable(dims, _flag(np.asarray(meets), ref), "1", CRITERIA.get(key, "every criterion met"),
                            flag_values=_FLAG_VALUES, flag_meanings=_FLAG_MEANINGS, basis=on, judged_on=why)
    return out


def _nominal_columns(c: dict[str, np.ndarray], pressure_ratio: np.ndarray, orders: list[int], dims, basis: str
                     ) -> dict[str, xr.Variable]:
    """The nominal gears' columns (kept on either basis)."""
    out = {
        "judged_on": variable((), basis, "1", f"the gear the criteria judge: {BASES[basis]}"),
        "impact_force": variable(dims, c["fs"], "N", "energy-method impact index F_s of the mesh-in impact paper at "
                                 "the design speed, nominal gear", force_line="transverse"),
        "lte_peak_to_peak": variable(dims, c["lte_pp"], "m", "peak-to-peak loaded transmission error, nominal gear",
                                     engineering_units="µm"),
    }
    for k, n in enumerate(orders):
        out[f"lte_order_{n}"] = variable(dims, c["harm"][:, :, k], "m", f"amplitude of the loaded transmission error "
                                         f"at mesh order {n}, nominal gear", engineering_units="µm")
    return out | {
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


#: The population columns' table keys and long names (units from gearmesh.robust.CRITERION_UNITS).
_COLUMNS = {"fs": ("impact_force", "energy-method impact index F_s (transverse) at the design speed"),
            "p_flank": ("peak_flank_pressure", "largest Hertzian contact pressure on the flanks' active zone"),
            "p_edge": ("peak_edge_pressure", "largest Hertzian contact pressure of a tip edge on the mating flank"),
            "sigma_f": ("peak_root_stress", "largest tooth-root stress of either gear (ISO 6336-3 local form)")}


def _population_columns(names, made, ref: int, w: dict[str, np.ndarray], worst_ratio: np.ndarray, orders, dims
                        ) -> dict[str, xr.Variable]:
    """The worst manufactured gear's columns, the distributions and the gear-for-gear shares."""
    of = "worst manufactured gear (the tolerance box's, searched)"
    quantities = dict(_COLUMNS)
    for k, n in enumerate(orders):
        quantities[f"harm{k}"] = (f"lte_order_{n}", f"amplitude of the loaded transmission error at mesh order {n}")

    def take(block: dict[str, np.ndarray], key: str) -> np.ndarray:
        return block["harm"][..., int(key[4:])] if key.startswith("harm") else block[key]

    out: dict[str, xr.Variable] = {}
    pop = [m["population"] for m in made]
    for key, (col, what) in quantities.items():
        units = CRITERION_UNITS[col]
        eng = {"engineering_units": "µm"} if units == "m" else {}
        worst = take(w, key)
        values = np.array([take(p, key)[1:] for p in pop])  # (variant, gear, torque): the nominal (gear 0) left out
        out[f"worst_{col}"] = variable(dims, worst, units, f"{what}, {of}", **eng)
        out[f"median_{col}"] = variable(dims, np.median(values, axis=1), units, f"{what}, median over the "
                                        f"{values.shape[1]} gears of the population", **eng)
        out[f"p90_{col}"] = variable(dims, np.percentile(values, 90, axis=1), units, f"{what}, 90th percentile over "
                                     f"the {values.shape[1]} gears of the population", **eng)
        share = np.mean(values > values[ref][None], axis=1)
        share[ref] = np.nan
        out[f"share_worse_{col}"] = variable(dims, share, "1", f"{what}: share of the population's gears worse than "
                                             "the reference made with the same deviations (gear for gear)")
    out["worst_pressure_ratio"] = variable(dims, worst_ratio, "1", f"peak contact pressure over the reference's, like "
                                           f"against like (as pressure_ratio), {of} against the reference's")
    return out
