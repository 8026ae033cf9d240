"""The 8-DOF pair against ISO 6336-1 method B (docs/validation.md, "Dynamics against ISO 6336-1").

For the default study's pair at one torque: ISO's n_E1 and K_v(n) for perfect gears (and with a
tip relief), the model's mesh-mode resonance and peak dynamic factor (maximum over static mesh
force) over a speed sweep, with rigid supports, the pair file's and the low-fluctuation paper's, for the
``contact`` and ``tvms`` excitations, with the pair file's gear bodies (by default none described:
the teeth alone, ISO's model) or ``--web-thickness-mm T`` (mm: a web of that thickness held at the
bore, its compliance in series, :mod:`gearmesh.body`; the face width a solid disc; then without the
low-fluctuation paper's bearings, which are the model's defaults and not stated: a body needs its
bearings stated). Writes results/dynamics_iso/helical_z29_71_m5[_web<T>].json and prints a table. Run: ``python scripts/dynamics_iso.py`` (about 10 s on a quiet 2-core machine).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from gearmesh.datasets.dynamics import build_pair_model, dynamics_dataset
from gearmesh.dynamics import iso6336, mesh_mode
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pair, load_pair, pair_to_dict, variant_pair
from gearmesh.stiffness import iso6336_stiffness
from gearmesh.supports import SUPPORT_KEYS

SUPPORTS = {"rigid": {"bearing_radial_stiffness_N_per_um": "rigid", "bearing_axial_stiffness_N_per_um": "rigid"},
            "pair file": None,
            "the low-fluctuation paper": {}}


def _web(value: str) -> float | str:
    return value if value == "rigid" else float(value)


def _pair(name: str, supports: dict | None, relief_um: float, web_thickness_mm: float | str | None = None):
    pair = load_pair(example_pair(name))
    if supports is not None or web_thickness_mm is not None:
        data = pair_to_dict(pair)
        if supports is not None:
            data = {k: v for k, v in data.items() if k not in SUPPORT_KEYS}
            data.update(supports)
        if web_thickness_mm is not None:
            data["web_thickness_mm"] = web_thickness_mm
        pair = load_pair(data)
    if relief_um:
        pair = variant_pair(pair, "relief", {"modification": {"pinion": {"tip_relief_um": relief_um,
                                                                         "tip_relief_length_mm": 3.0},
                                                              "gear": {"tip_relief_um": relief_um,
                                                                       "tip_relief_length_mm": 3.0}}})
    return pair


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pair", default="helical_z29_71_m5")
    ap.add_argument("--torque-Nm", type=float, default=1000.0)
    ap.add_argument("--speeds", default="1000:12000:250", help="start:stop:step (r/min)")
    ap.add_argument("--relief-um", type=float, default=20.0, help="tip relief of the relieved cases (µm; 0: none)")
    ap.add_argument("--out", default="results/dynamics_iso")
    ap.add_argument("--web-thickness-mm", type=_web, default=None,
                    help="the gear bodies' web (gearmesh.body; mm, or rigid: none; default the pair file's)")
    args = ap.parse_args()
    a, b, c = (float(v) for v in args.speeds.split(":"))
    speeds = np.arange(a, b + 0.5 * c, c)
    geom = pair_geometry(load_pair(example_pair(args.pair)))
    iso = iso6336_stiffness(geom)
    out = {"pair": args.pair, "torque_Nm": args.torque_Nm, "speeds_rpm": speeds.tolist(),
           "iso": {"c_gamma_alpha_N_per_mm_um": iso["c_gamma_alpha"], "n_E1_rpm": iso6336.resonance_speed(geom),
                   "m_red_kg_per_mm": iso6336.reduced_mass_per_width(geom), "eps_gamma": geom.eps_gamma,
                   "K_v_perfect": iso6336.dynamic_factor(geom, speeds, args.torque_Nm).tolist(),
                   f"K_v_tip_relief_{args.relief_um:g}um": iso6336.dynamic_factor(
                       geom, speeds, args.torque_Nm, tip_relief_um=args.relief_um).tolist()},
           "model": {}}
    print(f"ISO 6336-1: c_gamma_alpha {iso['c_gamma_alpha']:.2f} N/(mm um), n_E1 {out['iso']['n_E1_rpm']:.0f} r/min")
    for label, sup in SUPPORTS.items():
        try:  # a pair the package refuses (gear bodies beside bearings left to the model's defaults: gearmesh.body)
            pair_geometry(_pair(args.pair, sup, 0.0, args.web_thickness_mm))
        except GearmeshInputError as exc:
            print(f"{label}: left out ({exc})")
            continue
        for exc in ("contact", "tvms"):
            for relief in ((0.0, args.relief_um) if exc == "contact" and args.relief_um else (0.0,)):
                pair = _pair(args.pair, sup, relief, args.web_thickness_mm)
                model = build_pair_model(pair, args.torque_Nm, on="pinion", backlash_um=60, excitation=exc)
                md = model.modes()
                i = mesh_mode(model)
                n_res = md["frequency_Hz"][i] / model.mesh_frequency_per_rpm
                ds = dynamics_dataset(pair, torques_Nm=args.torque_Nm, speeds_rpm=speeds.tolist(), backlash_um=60,
                                      excitation=exc, sample_speeds_rpm=[], refine_resonances=True)
                df = ds["dynamic_factor"].values.ravel()
                sp = ds["speed"].values
                key = f"{label} / {exc}" + (f" / tip relief {relief:g} um" if relief else "")
                out["model"][key] = {
                    "mesh_stiffness_transverse_N_per_um": model.meshes[0].k_mean * model.cos_beta_b**2 / 1e6,
                    "mesh_mode_Hz": float(md["frequency_Hz"][i]), "mesh_mode_rpm": float(n_res),
                    "mesh_mode_damping_ratio": float(md["damping_ratio"][i]),
                    "peak_dynamic_factor": float(df.max()), "peak_speed_rpm": float(sp[np.argmax(df)]),
                    "dynamic_factor_on_grid": df[ds["on_grid"].values.ravel() == 1].tolist(),
                    "supports": ds.attrs["supports"]}
                r = out["model"][key]
                print(f"{key:40s} k {r['mesh_stiffness_transverse_N_per_um']:6.1f} N/um  mesh mode {n_res:6.0f} r/min "
                      f"(zeta {r['mesh_mode_damping_ratio']:.3f})  peak DF {r['peak_dynamic_factor']:.3f} at "
                      f"{r['peak_speed_rpm']:.0f} r/min")
    kv = np.array(out["iso"]["K_v_perfect"])
    print(f"ISO K_v perfect gears: max {kv.max():.3f}; with {args.relief_um:g} um tip relief: "
          f"max {max(out['iso'][f'K_v_tip_relief_{args.relief_um:g}um']):.3f}")
    path = Path(args.out) / (f"{args.pair}.json" if args.web_thickness_mm is None
                             else f"{args.pair}_web{args.web_thickness_mm}.json")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(out, indent=1))
    print("wrote", path)


if __name__ == "__main__":
    main()
