"""Benchmarks of the dynamics stage: the compiled step loop with shooting against the numpy batch
RK4 it replaced and against solve_ivp, for the three excitations, in one run.

* ``dynamics_default_sweep_<excitation>``: the default study's sweep (seed 000 case pair,
  1000 N·m on the pinion, 1000:15000:500 rpm plus the speeds the sweep adds around the predicted
  resonances, seed 001 bearings, backlash 60 µm, the study's solver settings) excited by
  ``tvms`` (slice stiffness), ``ltca`` (the LTCA's loaded stiffness and error) or ``contact``
  (the mesh-force table). References in the same run, on the same speeds: today's numpy batch
  kernel :func:`gearmesh.dynamics.simulate_numpy` (the kernel before issue 17, the contact table
  read with numpy's own indexing; always the physical-time transient of 10 decay times, so it
  agrees with the periodic orbit to e^-10 of the transient); solve_ivp (DOP853, rtol 1e-6) on the
  full equations from the compiled loop's periodic state over the record window at ``subset``
  speeds, scaled to all (a lower bound: over the physical-time transient it takes minutes a speed); and
  the compiled loop as it was before issue 17's kernel work (:mod:`bench_baseline`). Issue 17's
  target: ≥ 10× the numpy kernel. The model (stiffness, LTCA, table) is built outside the timing.
* ``dynamics_sweep_496_speeds``: seed 001 pair 1, 500:50000:100 rpm, new loop against the numpy
  batch (where the batch amortised numpy's overhead best).
* ``dynamics_contact_over_ltca``: the contact sweep's time over the ltca sweep's (issue 15: ≤ 1.5).

Run by hand: ``python benchmarks/bench_dynamics.py`` (several minutes: solve_ivp and the numpy
contact kernel are slow), or ``python benchmarks/run.py dynamics_default``.
"""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from gearmesh import dynamics as dy
from gearmesh.datasets.dynamics import build_pair_model, contact_table, resonance_refined, speed_grid
from gearmesh.datasets.ltca import ltca_dataset
from gearmesh.gear import load_pair, pair_geometry
from gearmesh.stiffness import mesh_stiffness

from common import ROOT, median_seconds, timed_calls


def _default_models() -> dict[str, dy.GearModel]:
    """The default study's pair at 1000 N·m under each excitation, the tooth model of
    :data:`bench_impact.TOOTH_METHOD` (the code before issue 17's kernel work computes it alike)."""
    from bench_impact import TOOTH_METHOD

    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    geom = pair_geometry(pair)
    ltca: xr.Dataset = ltca_dataset(pair, torques_Nm=[1000.0], positions=64, points=50, method=TOOTH_METHOD)
    table = contact_table(geom, [1000.0, 1600.0], method=TOOTH_METHOD)
    common = {"backlash_um": 60.0, "method": TOOTH_METHOD}
    return {"tvms": build_pair_model(pair, 1000.0, "pinion", excitation="tvms", **common),
            "ltca": build_pair_model(pair, 1000.0, "pinion", excitation="ltca", ltca=ltca, **common),
            "contact": build_pair_model(pair, 1000.0, "pinion", excitation="contact", table=table, **common)}


def _diff(a, b, keys=("force_max", "approach_std")) -> float:
    def get(r, k):
        return np.asarray(getattr(r, k) if hasattr(r, k) else r[k], dtype=float)

    return max(float(np.max(np.abs(get(a, k) / get(b, k) - 1))) for k in keys)


def _default_speeds(models) -> np.ndarray:
    return resonance_refined(speed_grid({"start": 1000, "stop": 15000, "step": 500}), models["ltca"])


def compiled_sweeps(repeats: int) -> dict:
    """{excitation: (wall s, CPU s, {force_max, approach_std}, shooting failures)} of the compiled
    loop over the default sweep (module docstring); also run by the baseline's code."""

    models = _default_models()
    speeds = _default_speeds(models)
    out = {}
    for name, model in models.items():
        wall, cpu, res, _ = timed_calls(lambda: dy.simulate(model, speeds), repeats)
        out[name] = (wall, cpu, {"force_max": res.force_max, "approach_std": res.approach_std},
                     int(np.sum(res.shooting_iterations < 0)))
    return out


def bench_default_sweep(repeats: int = 3, subset: int = 2) -> list[dict]:
    from bench_baseline import BASELINE_NAME, baseline_call

    models = _default_models()
    speeds = _default_speeds(models)
    new = compiled_sweeps(repeats)
    old = baseline_call("bench_dynamics", "compiled_sweeps", repeats)
    rows = []
    for name, model in models.items():
        fast, cpu, res, failures = new[name]
        row = {"name": f"dynamics_default_sweep_{name}", "median_s": fast, "cpu_s": cpu, "speeds": int(speeds.size),
               "shooting_failures": failures}
        numpy_s, ref = median_seconds(lambda: dy.simulate_numpy(model, speeds), 1)
        row.update({"baseline": "numpy batch RK4 (today's kernel before issue 17), same speeds, physical-time "
                                "transient", "baseline_median_s": numpy_s, "ratio": numpy_s / fast,
                    "max_rel_diff": _diff(res, ref)})
        pick = np.unique(np.linspace(0, speeds.size - 1, subset).round().astype(int))
        # from the compiled loop's periodic state over the record window only: over the physical-time
        # transient solve_ivp takes minutes a speed (ltca, contact: more than 4 min at 3500 rpm),
        # so its scaled time is a lower bound of what it would take to find the same steady states
        periodic = dy.simulate(model, speeds).periodic_state
        ivp, refs = median_seconds(lambda: [dy.reference_solution(model, float(speeds[i]), rtol=1e-6, atol=1e-13,
                                                                  start=periodic[i], transient_cycles=0)
                                            for i in pick], 1)
        row.update({"solve_ivp_scaled_s": ivp * speeds.size / pick.size,
                    "solve_ivp_ratio": ivp * speeds.size / pick.size / fast,
                    "solve_ivp_max_rel_diff": max(abs(float(res["approach_std"][0, i]) / float(r["approach_std"][0]) - 1)
                                                  for i, r in zip(pick, refs))})
        if old is not None:
            row.update({"compiled_before": BASELINE_NAME, "compiled_before_s": old[name][0],
                        "compiled_before_ratio": old[name][0] / fast, "compiled_before_max_rel_diff": _diff(res, old[name][2])})
        rows.append(row)
    rows.append({"name": "dynamics_contact_over_ltca", "median_s": new["contact"][0],
                 "baseline": "the ltca sweep, same speeds, same run", "baseline_median_s": new["ltca"][0],
                 "ratio": new["contact"][0] / new["ltca"][0]})
    return rows


def bench_dynamics(repeats: int = 3) -> dict:
    """The 496-speed sweep of seed 001 pair 1: the compiled loop against the numpy batch."""
    pair = load_pair(ROOT / "config/pairs/seed001_pair1.yaml")
    speeds = np.arange(500.0, 50000.0 + 1.0, 100.0)
    geom = pair_geometry(pair)
    model = dy.pair_model(geom, 200.0, mesh_stiffness(geom, components=False).K)
    dy.simulate(model, speeds[:1])
    fast, result = median_seconds(lambda: dy.simulate(model, speeds), repeats)
    base, ref = median_seconds(lambda: dy.simulate_numpy(model, speeds), max(1, repeats // 2))
    return {"name": "dynamics_sweep_496_speeds", "median_s": fast,
            "baseline": "numpy batch RK4 over all 496 speeds (the kernel before issue 17)",
            "baseline_median_s": base, "ratio": base / fast, "max_rel_diff": _diff(result, ref),
            "shooting_failures": int(np.sum(result.shooting_iterations < 0))}


if __name__ == "__main__":
    for row in bench_default_sweep():
        print(json.dumps(row), flush=True)
    print(json.dumps(bench_dynamics()), flush=True)


def bench_damping_search(repeats: int = 5) -> dict:
    """``mesh_damping_search_24_models``: the mesh damper of the GA's models (the default pair's
    contact-driven 8-DOF pair, 8 micro-geometries × the default study's 3 torques, the population
    tables), each model's modes included (the GA's resonance band asks for them). Today's search
    (:func:`gearmesh.dynamics.model._ray_damping_scale`, checked on the damped modes) against the
    secant on the complex eigenvalues that was the only search at c61da5b (kept as the fallback,
    :func:`gearmesh.dynamics.model._secant_damping_scale`), in one run; max_rel_diff of the dampers."""
    from dataclasses import replace

    from gearmesh.dynamics import model as dm
    from gearmesh.dynamics.population import population_dynamics
    from gearmesh.gear import load_pair, pair_geometry
    from gearmesh.meshforce import tabulate

    geom = pair_geometry(load_pair(ROOT / "config/pairs/seed000_case.yaml"))
    pd = population_dynamics(geom, [400.0, 1000.0, 1600.0], np.arange(1000, 15001, 500.0), method="fe")
    params = np.zeros((8, 2, 6))
    params[:, :, 0] = np.random.default_rng(0).random((8, 2)) * 30e-6  # root/tip reliefs up to 30 µm
    params[:, :, 2] = 2e-3
    tables = [tabulate(pd.layout, g, pd.force_max, pd.approaches) for g in pd.layout.gaps(params, np.zeros((8, 2)))]
    bare = [dm.pair_model(geom, float(t), None, contact=tb, backlash=pd.backlash, mesh_damping=0.0)
            for tb in tables for t in pd.torques_out]
    rb, inertia = geom.base_radius, geom.inertia

    def today():
        out = [dm._with_mesh_damping(m, None, pd.damping_ratio, rb, inertia) for m in bare]
        return np.array([m.modes()["frequency_Hz"].size and m.damping[0] for m in out])

    def before():
        out = []
        for m in bare:
            c0 = np.array([2 * pd.damping_ratio * np.sqrt(m.meshes[0].k_mean * dm._equivalent_mass(m.cos_beta_b, rb, inertia))])
            d = replace(m, damping=dm._secant_damping_scale(m, c0, pd.damping_ratio) * c0)
            d.modes()
            out.append(d.damping[0])
        return np.array(out)

    wall, cpu, new, _ = timed_calls(today, repeats)
    bwall, bcpu, old, _ = timed_calls(before, repeats)
    return {"name": "mesh_damping_search_24_models", "median_s": wall, "cpu_s": cpu,
            "baseline": "secant on the complex eigenvalues (c61da5b)", "baseline_median_s": bwall,
            "baseline_cpu_s": bcpu, "ratio": bwall / wall, "cpu_ratio": bcpu / cpu,
            "max_rel_diff": float(np.max(np.abs(new / old - 1)))}
