"""The 3-D finite-element reference of the tooth compliance against the 2-D models (issue 19).

Run from the repository root (minutes; needs the optional extra: pip install -e ".[fe3d]"):

    python scripts/stiffness_reference.py                 # every case below
    python scripts/stiffness_reference.py spur_b20 --levels 0.56 0.4

For each case (a gear of a pair, a face width, contact lines given by their roll length at
mid-face as fractions of the active flank) and each mesh level (element edge on the loaded
tooth in normal modules, refined by √2), it solves the gear in 3-D (gearmesh.fe3d) and the
same ring section in 2-D plane strain, plane stress and a tooth in plane strain on a body in
plane stress (gearmesh.fe), and prints each line's compliance per unit face width
(transverse convention, 1e-12 m²/N = µm/(N/mm)), the 2-D values as the slice model would
load them (the mean over the loaded layers of the section compliance at each layer's
roll). Richardson extrapolation of the last three levels (gearmesh.fe3d.richardson).
Results: results/stiffness_reference/CASE.json.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import sys
import time
from pathlib import Path

import numpy as np

from gearmesh import fe, fe3d
from gearmesh import slice_compliance as sc
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair, pair_to_dict

PAIR1 = {"name": "low_fluctuation_pair1", "teeth": [29, 49], "normal_module_mm": 1.75, "normal_pressure_angle_deg": 25,
         "helix_angle_deg": 10, "face_width_mm": 20, "addendum_coefficient": 1.0, "dedendum_coefficient": 1.25,
         "bore_radius_mm": [15, 25], "material": {"youngs_modulus_GPa": 210, "poisson_ratio": 0.3,
                                                  "density_kg_m3": 7850}}
HELICAL_Z29_71 = {"name": "helical_z29_71_m5", "teeth": [29, 71], "normal_module_mm": 5, "normal_pressure_angle_deg": 20,
           "helix_angle_deg": 27.5, "helix_hand": "right", "face_width_mm": 42, "addendum_coefficient": 1.0,
           "dedendum_coefficient": 1.25, "tool_tip_radius_coefficient": 0.38, "bore_radius_mm": [30, 70],
           "material": {"youngs_modulus_GPa": 210, "poisson_ratio": 0.3, "density_kg_m3": 7850}}

#: name: (pair data, gear, line positions as fractions of [ρ_SAP, ρ_EAP] at mid-face)
CASES = {
    "spur_b20": ({**PAIR1, "name": "pair1_spur", "helix_angle_deg": 0}, 0, (0.1, 0.5, 0.9)),
    "spur_b5": ({**PAIR1, "name": "pair1_spur_b5", "helix_angle_deg": 0, "face_width_mm": 5.25}, 0, (0.1, 0.5, 0.9)),
    "spur_b60": ({**PAIR1, "name": "pair1_spur_b60", "helix_angle_deg": 0, "face_width_mm": 60}, 0, (0.5,)),
    "helical_pair1": (PAIR1, 0, (0.25, 0.5, 0.75)),
    "helical_z29_71_m5": (HELICAL_Z29_71, 0, (0.5,)),
}
LEVELS = (0.56, 0.4, 0.28)
LAYER_ASPECT = 2.0  # layer thickness over the in-plane edge (P2 in z; the field varies slowly along the face)


def slice_model_mean(geom, gear, rho, weights, size, plane, body_plane=None):
    """The 2-D section compliance (m²/N) averaged over each line's layers as the slice model
    loads them (uniform load: the mean of c(ρ(z)) with the trapezoidal weights)."""
    rolls = np.unique(rho[weights > 0])
    if body_plane is None:
        c = fe.tooth_compliance(geom, gear, rolls, plane=plane, size=size, neighbours=fe3d.DEFAULT_NEIGHBOURS,
                                ring=True).total
    else:
        c = fe.tooth_body_split(geom, gear, rolls, plane=plane, size=size, neighbours=fe3d.DEFAULT_NEIGHBOURS,
                                body_plane=body_plane, ring=True).total
    out = []
    for r in range(rho.shape[0]):
        w = weights[r]
        k = w > 0
        out.append(float(np.sum(w[k] * np.interp(rho[r, k], rolls, c)) / np.sum(w[k])))
    return np.array(out)


def pem_mean(geom, gear, rho, weights, method="transition"):
    """The potential-energy slice compliance (bending + shear + axial + fillet) over each line."""
    model = sc.tooth_model(geom, gear, method)
    out = []
    for r in range(rho.shape[0]):
        k = weights[r] > 0
        c = sc.tooth_slice_compliance(model, rho[r, k])
        out.append(float(np.sum(weights[r, k] * sum(c.values())) / np.sum(weights[r, k])))
    return np.array(out)


def run_case(name: str, levels, out_dir: Path, solver: str = "auto") -> dict:
    pair_data, gear, fractions = CASES[name]
    geom = pair_geometry(load_pair(pair_data))
    lo, hi = geom.rho_sap[gear], geom.rho_eap[gear]
    rho0_nominal = lo + np.asarray(fractions) * (hi - lo)
    rows = []
    for size in levels:
        h = size * geom.pair.normal_module
        layers = max(int(math.ceil(geom.face_width / (LAYER_ASPECT * h))), 2)
        z = np.linspace(-0.5 * geom.face_width, 0.5 * geom.face_width, layers + 1)
        # lines whose rolls at the layers fall on a grid of step dz·tan βb (vertices of the section)
        step = (z[1] - z[0]) * math.tan(geom.base_helix_angle)
        rho0 = rho0_nominal if step == 0 else lo + np.round((rho0_nominal - lo) / step) * step
        rolls = fe3d.layer_grid_rolls(geom, gear, rho0, z)
        t0 = time.perf_counter()
        model = fe3d.gear_model_3d(geom, gear, rolls, size=size, layers=layers, solver=solver)
        res = fe3d.line_compliance_3d(model, rho0)
        transverse = fe3d.line_compliance_3d(model, rho0, transverse_only=True).compliance if step else res.compliance
        t3 = time.perf_counter() - t0
        row = {"size": size, "layers": layers, "dofs": res.n_dofs, "elements": res.n_elements, "solver": model.solver,
               "rho0_mm": (rho0 * 1e3).tolist(), "c3d": res.compliance.tolist(), "c3d_transverse": transverse.tolist(),
               "iterations": res.iterations.tolist(), "seconds_3d": round(t3, 1),
               "peak_rss_GB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6, 2),
               "deflection_profile": (res.deflection[len(rho0) // 2] / math.cos(geom.base_helix_angle) ** 2).tolist(),
               "z_mm": (z * 1e3).tolist()}
        for label, plane, body in (("strain", "strain", None), ("stress", "stress", None), ("mixed", "strain", "stress")):
            row[label] = slice_model_mean(geom, gear, res.rho, res.weights, size, plane, body).tolist()
        row["pem_transition"] = pem_mean(geom, gear, res.rho, res.weights).tolist()
        rows.append(row)
        print(f"{name} size {size}: {res.n_dofs} dofs, {layers} layers, {model.solver}, {t3:.0f} s; "
              f"3-D {np.round(res.compliance * 1e12, 4)} (transverse load {np.round(transverse * 1e12, 4)}), strain {np.round(np.array(row['strain']) * 1e12, 4)}, "
              f"stress {np.round(np.array(row['stress']) * 1e12, 4)}, mixed {np.round(np.array(row['mixed']) * 1e12, 4)}",
              flush=True)
    out = {"case": name, "pair": pair_data, "gear": gear, "face_width_mm": geom.face_width * 1e3,
           "b_over_mn": geom.face_width / geom.pair.normal_module, "levels": rows}
    if len(rows) >= 3:
        ratio = rows[-2]["size"] / rows[-1]["size"]
        out["extrapolated"] = {
            key: [fe3d.richardson([r[key][i] for r in rows], ratio) for i in range(len(rows[-1][key]))]
            for key in ("c3d", "c3d_transverse", "strain", "stress", "mixed", "pem_transition")}
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / f"{name}.json").write_text(json.dumps(out, indent=1))
    return out


SHIPPED = ("helical_z29_71_m5", "low_fluctuation_pair1", "low_fluctuation_pair2", "low_fluctuation_pair3", "low_fluctuation_pair4", "contact_lines_input_z29_36",
           "contact_lines_output_z15_65", "transition_curve_z23_62", "printing_train_z88")


def run_shipped(size: float, out_dir: Path, solver: str = "auto") -> dict:
    """Every shipped pair's pinion and gear, one contact line through mid-profile at mid-face,
    at one mesh level: the 3-D compliance over the 2-D plane-strain one on the same section
    mesh (the ratio converges much faster than either value: docs/validation.md)."""
    out = {}
    for name in SHIPPED:
        pair = load_pair(Path("config/pairs") / f"{name}.yaml")
        for gear in (0, 1):
            CASES[f"{name}_{gear}"] = (pair_to_dict(pair), gear, (0.5,))
            res = run_case(f"{name}_{gear}", [size], out_dir, solver)
            row = res["levels"][0]
            out[f"{name}_{gear}"] = {k: row[k][0] for k in ("c3d", "c3d_transverse", "strain", "stress", "mixed",
                                                            "pem_transition")}
            out[f"{name}_{gear}"].update(size=size, dofs=row["dofs"], b_over_mn=res["b_over_mn"])
            print(name, gear, {k: round(v, 4) for k, v in out[f"{name}_{gear}"].items() if isinstance(v, float)},
                  flush=True)
    (out_dir / "shipped.json").write_text(json.dumps(out, indent=1))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", default=[], metavar="CASE", help=f"some of {list(CASES)} (default all)")
    ap.add_argument("--levels", nargs="+", type=float, default=list(LEVELS))
    ap.add_argument("--solver", default="auto", choices=fe3d.SOLVERS)
    ap.add_argument("--out", default="results/stiffness_reference")
    ap.add_argument("--shipped", action="store_true", help="every shipped pair, mid-line, at the first level only")
    args = ap.parse_args(argv)
    if args.shipped:
        run_shipped(args.levels[0], Path(args.out), args.solver)
        return 0
    for name in args.cases or list(CASES):
        run_case(name, args.levels, Path(args.out), args.solver)
    return 0


if __name__ == "__main__":
    sys.exit(main())
