"""Where the tooth models part: the mean mesh stiffness of a pair, one component swapped at a time (issue 19).

Run from the repository root (a minute per pair):

    python scripts/stiffness_decomposition.py                       # every shipped pair
    python scripts/stiffness_decomposition.py low_fluctuation_pair1 --line-load-N-per-mm 300

From the default potential-energy model (transition cantilever, Sainsot foundation, plane
stress E and G, Yang & Sun's constant Hertz term) to the 2-D finite-element tooth, one part
at a time, each replaced by its independent FE model on one mesh (gearmesh.fe.tooth_body_split):

  1 PEM transition                      bending+shear+axial (beam) + Sainsot + Yang-Sun
  2 beam -> FE tooth on a rigid base    (plane stress; clamped on the root chord)
  3 Sainsot -> FE body, rigid tooth     (plane stress)
  4 + tooth/body interaction            = FE whole gear, plane stress
  5 plane stress -> plane strain        = method 'fe' as shipped
  6 tooth strain on a body in stress    (the 2-D model the 3-D reference supports, docs/validation.md)
  7 Yang-Sun -> Weber's contact part    (on model 6, at the given line load)

and ISO 6336-1 c_gamma_alpha * b. With --reference (after scripts/stiffness_reference.py --shipped)
it adds the 3-D reference of each pair, with either contact term. Mean K over one mesh cycle in N/um along the transverse line
of action (200 slices, 360 positions). Results: results/stiffness_decomposition/PAIR.json.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from gearmesh import fe, fe_tables
from gearmesh import slice_compliance as sc
from gearmesh import stiffness as st
from gearmesh.body import RIGID_WEBS
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair

PAIRS = ("helical_z29_71_m5", "low_fluctuation_pair1", "low_fluctuation_pair2", "low_fluctuation_pair3", "low_fluctuation_pair4", "contact_lines_input_z29_36",
         "contact_lines_output_z15_65", "transition_curve_z23_62", "printing_train_z88")
ROLL_NODES = 17
SIZE = fe.DEFAULT_SIZE


def weber_pair_contact(geom, rho1, rho2, gear_tables, line_load):
    """Weber's contact part of both teeth per unit face width (m²/N, transverse convention) at
    the pinion/gear rolls (m) for a normal line load (N/m): the half-plane approach of each
    flank to its C (gearmesh.fe.weber_approach, plane strain) with the Hertz half-width of
    the two normal curvature radii ρ/cos βb (Johnson 1985, eq. 4.43)."""
    mat = geom.pair.material
    cb = math.cos(geom.base_helix_angle)
    r1, r2 = rho1 / cb, rho2 / cb
    radius = r1 * r2 / (r1 + r2)
    e_star = mat.youngs_modulus / (2 * (1 - mat.poisson_ratio**2))
    a = np.sqrt(4 * line_load * radius / (math.pi * e_star))
    out = 0.0
    for model, rho in zip(gear_tables, (rho1, rho2)):
        x_p, _, a1, _ = sc.contact_point(model, rho)
        depth = x_p / np.cos(a1)  # |PC| along the line of action
        out = out + fe.weber_approach(depth, a, mat.youngs_modulus, mat.poisson_ratio, "strain")
    # normal approach per normal load per unit contact length -> transverse per unit face width
    return out / cb


def mean_k(geom, tables, extra=None):
    """Mean mesh stiffness (N/µm) of the slice model with these gear tables; ``extra`` (s -> m²/N)
    added to the pair's slice compliance (the contact term swapped)."""
    if extra is None:
        return st.mesh_stiffness(geom, 360, method=tables[0].method, tables=tables, components=False).mean * 1e-6
    pt = sc.pair_slice_table(geom, tables)
    s = pt.s0 + pt.ds * np.arange(pt.total.size)
    total = pt.total - sc.hertz_compliance_transverse(geom) + extra(s)
    pt = sc.PairSliceTable(s0=pt.s0, ds=pt.ds, columns=pt.columns, values=pt.values, total=total, slopes=pt.slopes,
                           total_slope=np.diff(total))
    return st.mesh_stiffness(geom, 360, method=tables[0].method, pair_table=pt, components=False).mean * 1e-6


def _teeth(name: str):
    """The shipped pair with rigid webs: the teeth alone, as the 3-D reference's transverse load
    sees them (the bodies' tilt is compared on its own, gearmesh.body)."""
    return load_pair(Path("config/pairs") / f"{name}.yaml").with_changes(body=RIGID_WEBS)


def decompose(name: str, line_load: float) -> dict:
    pair = _teeth(name)
    geom = pair_geometry(pair)
    steps = {k: [] for k in ("beam_fe", "body_fe", "stress", "strain", "mixed")}
    pem = []
    for gear in (0, 1):
        rho = np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], ROLL_NODES)
        model = sc.tooth_model(geom, gear, "transition")
        c = sc.tooth_slice_compliance(model, rho)
        alpha = sc.contact_point(model, rho)[2]
        split = fe.tooth_body_split(geom, gear, rho, "stress", SIZE)
        strain = fe.tooth_compliance(geom, gear, rho, "strain", SIZE).total
        mixed = fe.tooth_body_split(geom, gear, rho, "strain", SIZE, body_plane="stress").total

        def table(tooth, body):
            return fe_tables.compliance_table(geom, gear, rho, tooth, body, alpha)

        pem.append(sc.slice_compliance_table(geom, gear, "transition"))
        steps["beam_fe"].append(table(split.tooth_rigid_base, c["fillet"]))
        steps["body_fe"].append(table(split.tooth_rigid_base, split.body_rigid_tooth))
        steps["stress"].append(table(split.total, 0 * rho))
        steps["strain"].append(table(strain, 0 * rho))
        steps["mixed"].append(table(mixed, 0 * rho))
    models = (sc.tooth_model(geom, 0, "transition"), sc.tooth_model(geom, 1, "transition"))

    def weber(s):
        return weber_pair_contact(geom, geom.rho_sap[0] + s, geom.rho_eap[1] - s, models, line_load)

    iso = st.iso6336_stiffness(geom)
    out = {
        "pair": name, "line_load_N_per_mm": line_load * 1e-3,
        "1_pem_transition": mean_k(geom, tuple(pem)),
        "2_beam_to_fe_tooth_rigid_base": mean_k(geom, tuple(steps["beam_fe"])),
        "3_sainsot_to_fe_body_rigid_tooth": mean_k(geom, tuple(steps["body_fe"])),
        "4_fe_plane_stress": mean_k(geom, tuple(steps["stress"])),
        "5_fe_plane_strain": mean_k(geom, tuple(steps["strain"])),
        "6_fe_tooth_strain_body_stress": mean_k(geom, tuple(steps["mixed"])),
        "7_fe_mixed_weber_contact": mean_k(geom, tuple(steps["mixed"]), weber),
        "pem_transition_weber_contact": mean_k(geom, tuple(pem), weber),
        "fe_strain_weber_contact": mean_k(geom, tuple(steps["strain"]), weber),
        "iso6336_K_gamma_alpha": iso["K_gamma_alpha"] * 1e-6,
        "yang_sun_contact_m2_per_N": sc.hertz_compliance_transverse(geom),
        "weber_contact_mid_m2_per_N": float(weber(np.array([0.5 * geom.path_of_contact]))[0]),
    }
    for m in ("traditional", "improved"):
        out[f"pem_{m}"] = st.mesh_stiffness(geom, 360, method=m, components=False).mean * 1e-6
    return out


def reference_k(name: str, ratios: dict, line_load: float) -> dict:
    """The 3-D reference of a pair's mean mesh stiffness (N/µm): each gear's 2-D plane-strain
    table (the converged 2-D mesh) times the 3-D / 2-D ratio of that gear measured on one
    mid-profile line (scripts/stiffness_reference.py --shipped: the ratio varies by ±1 %
    along the profile of the reference cases and converges to 0.1 % on meshes where neither
    value has, docs/validation.md), under the flank-normal load ('normal': the axial part
    tilts the body) and under the slice model's transverse load ('transverse'), with Yang &
    Sun's contact term and with Weber's."""
    geom = pair_geometry(_teeth(name))
    strain, alpha = [], []
    for gear in (0, 1):
        rho = np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], ROLL_NODES)
        alpha.append(sc.contact_point(sc.tooth_model(geom, gear, "transition"), rho)[2])
        strain.append((rho, fe.tooth_compliance(geom, gear, rho, "strain", SIZE).total))
    models = (sc.tooth_model(geom, 0, "transition"), sc.tooth_model(geom, 1, "transition"))

    def weber(s):
        return weber_pair_contact(geom, geom.rho_sap[0] + s, geom.rho_eap[1] - s, models, line_load)

    out = {}
    for load, key in (("normal", "c3d"), ("transverse", "c3d_transverse")):
        ratio = [ratios[f"{name}_{g}"][key] / ratios[f"{name}_{g}"]["strain"] for g in (0, 1)]
        tables = tuple(fe_tables.compliance_table(geom, g, strain[g][0], strain[g][1] * ratio[g], 0 * strain[g][0], alpha[g])
                       for g in (0, 1))
        out.update({f"3d_{load}_ratio_pinion": ratio[0], f"3d_{load}_ratio_gear": ratio[1],
                    f"3d_{load}_yang_sun": mean_k(geom, tables), f"3d_{load}_weber": mean_k(geom, tables, weber)})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pairs", nargs="*", default=list(PAIRS))
    ap.add_argument("--line-load-N-per-mm", type=float, default=300.0)
    ap.add_argument("--out", default="results/stiffness_decomposition")
    ap.add_argument("--reference", help="shipped.json of scripts/stiffness_reference.py --shipped: add the 3-D "
                                        "reference to each pair's results")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for name in args.pairs or PAIRS:
        if args.reference:
            res = json.loads((out / f"{name}.json").read_text())
            res.update(reference_k(name, json.loads(Path(args.reference).read_text()), args.line_load_N_per_mm * 1e3))
            (out / f"{name}.json").write_text(json.dumps(res, indent=1))
            print(name, {k: round(v, 3) for k, v in res.items() if k.startswith("3d")}, flush=True)
            continue
        res = decompose(name, args.line_load_N_per_mm * 1e3)
        (out / f"{name}.json").write_text(json.dumps(res, indent=1))
        print(json.dumps({k: (round(v, 1) if isinstance(v, float) and v > 1 else v) for k, v in res.items()}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
