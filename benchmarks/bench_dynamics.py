"""Benchmarks of the dynamics stage: the compiled step loop with shooting against the numpy batch
RK4 it replaced, for the three excitations, in one run.

* ``dynamics_default_sweep_<excitation>``: the default study's sweep (the mesh-in impact paper case pair,
  1000 N·m on the pinion, 1000:15000:500 rpm plus the speeds the sweep adds around the predicted
  resonances, the pair file's bearings, backlash 60 µm, the study's solver settings) excited by
  ``tvms`` (slice stiffness), ``ltca`` (the LTCA's loaded stiffness and error) or ``contact``
  (the mesh-force table). The model (stiffness, LTCA, table) is built outside the timing.
* ``dynamics_sweep_496_speeds``: the low-fluctuation paper pair 1, 500:50000:100 rpm, where the numpy batch
  amortised its overhead best.
* ``dynamics_contact_over_ltca``: the contact sweep's time over the ltca sweep's (issue 15: ≤ 1.5).

Baseline: :func:`gearmesh.dynamics.simulate_numpy` on the same model and speeds (the kernel before
issue 17, the contact table read with numpy's own indexing). It always runs the physical-time
transient of ``transient_tau`` decay times, while :func:`gearmesh.dynamics.simulate` (timed) finds
the periodic steady state by shooting. The equality (``max_rel_diff``, of the peak force and the
approach's standard deviation) is therefore of the compiled loop run on the same route — the same
:func:`~gearmesh.dynamics.simulate` with ``steady_state: transient`` — against the numpy batch: the
same steps and phases, equal to round-off. How far the shooting's steady state lies from the
transient's is reported beside it (``shooting_vs_transient_rel_diff``, not an equality: the
transient leaves e^-n_τ of its start, and where contact loss gives the model more than one periodic
orbit the two routes may settle on different ones). ``dynamics_default`` also runs solve_ivp
(DOP853) on the full equations from the compiled loop's periodic state over the record window at a
few speeds: an independent integrator on an independent formulation, its time scaled to all speeds
(a lower bound: over the physical-time transient it takes minutes a speed); it differs from the
loop by the loop's fixed steps, within the bound :data:`IVP_BOUND` the row states and checks.

Run by hand: ``python benchmarks/bench_dynamics.py`` (a few minutes: the numpy contact kernel and
solve_ivp are slow), or ``python benchmarks/run.py dynamics_default``.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import xarray as xr

from gearmesh import dynamics as dy
from gearmesh.datasets.dynamics import build_pair_model, contact_table, resonance_refined, speed_grid
from gearmesh.datasets.ltca import ltca_dataset
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.stiffness import mesh_stiffness

from common import CASE_PAIR, ROOT, Swap, bounded_difference, equality, max_rel_diff, median_seconds, timed_calls

#: The compared statistics of a sweep.
KEYS = ("force_max", "approach_std")
#: solve_ivp's tolerances, and the bound on its difference from the compiled loop: the loop's fixed
#: RK4 steps (at least 32 a mesh period, ω_max·Δt ≤ 0.25) and its extremes taken at those steps
#: against an adaptive integrator sampled densely. It does not shrink with solve_ivp's rtol (the
#: default study's sweep: up to 2.9e-4 at rtol 1e-6, 1e-8 and 1e-10 alike); 2e-3 is the bound the
#: tests hold the two to (tests/test_dynamics_contact.py, the peak force of the contact excitation).
IVP_RTOL, IVP_ATOL, IVP_BOUND = 1e-6, 1e-13, 2e-3


def _stats(result) -> list[np.ndarray]:
    return [np.asarray(getattr(result, k) if hasattr(result, k) else result[k], dtype=float) for k in KEYS]


def _default_models() -> dict[str, dy.GearModel]:
    """The default study's pair at 1000 N·m under each excitation, the study's tooth model."""
    pair = load_pair(CASE_PAIR)
    geom = pair_geometry(pair)
    ltca: xr.Dataset = ltca_dataset(pair, torques_Nm=[1000.0], positions=64, points=50)
    table = contact_table(geom, [1000.0, 1600.0])
    common = {"backlash_um": 60.0}
    return {"tvms": build_pair_model(pair, torque_Nm=1000.0, on="pinion", excitation="tvms", **common),
            "ltca": build_pair_model(pair, torque_Nm=1000.0, on="pinion", excitation="ltca", ltca=ltca, **common),
            "contact": build_pair_model(pair, torque_Nm=1000.0, on="pinion", excitation="contact", table=table, **common)}


def kernel_rows(name: str, model, speeds, repeats: int, baseline_speeds: int | None = None) -> tuple[dict, object]:
    """The row of ``model`` over ``speeds`` (module docstring) and today's sweep result; the numpy
    baseline over ``baseline_speeds`` evenly spread speeds only (None: all, and the ratio)."""
    wall, cpu, result, _ = timed_calls(lambda: dy.simulate(model, speeds), repeats)
    pick = (np.arange(speeds.size) if baseline_speeds is None or baseline_speeds >= speeds.size
            else np.unique(np.linspace(0, speeds.size - 1, baseline_speeds).round().astype(int)))  # 1: the lowest
    transient = replace(dy.SolverSettings(), steady_state="transient")
    same_route = dy.simulate(model, speeds[pick], transient)
    numpy_s, reference = median_seconds(lambda: dy.simulate_numpy(model, speeds[pick]), 1)
    row = {"name": name, "median_s": wall, "cpu_s": cpu, "speeds": int(speeds.size),
           "shooting_failures": int(np.sum(result.shooting_iterations < 0)),
           "baseline": "numpy batch RK4 (the kernel before issue 17), physical-time transient",
           "baseline_speeds": int(pick.size), "baseline_median_s": numpy_s}
    if pick.size == speeds.size:
        row["ratio"] = numpy_s / wall
    row.update(equality(_stats(same_route), _stats(reference)))
    row["compared"] = "the compiled loop with steady_state 'transient' against the numpy batch: " + ", ".join(KEYS)
    row["shooting_vs_transient_rel_diff"] = max(max_rel_diff(a[..., pick], b) for a, b in
                                                zip(_stats(result), _stats(same_route)))
    return row, result


def bench_default_sweep(repeats: int = 3, subset: int = 2, baseline_speeds: int | None = None) -> list[dict]:
    """The default study's sweep under each excitation (module docstring); solve_ivp at ``subset``
    speeds, the numpy batch at ``baseline_speeds`` (None: all)."""
    models = _default_models()
    speeds = resonance_refined(speed_grid({"start": 1000, "stop": 15000, "step": 500}), models["ltca"])
    rows, walls = [], {}
    for name, model in models.items():
        row, res = kernel_rows(f"dynamics_default_sweep_{name}", model, speeds, repeats, baseline_speeds)
        walls[name] = row["median_s"]
        pick = (np.unique(np.linspace(0, speeds.size - 1, subset).round().astype(int)) if subset > 1
                else np.array([speeds.size - 1]))  # one speed: the fastest to integrate, the highest
        ivp, refs = median_seconds(lambda: [dy.reference_solution(model, float(speeds[i]), rtol=IVP_RTOL,
                                                                  atol=IVP_ATOL, start=res.periodic_state[i],
                                                                  transient_cycles=0) for i in pick], 1)
        diff = max(max_rel_diff(np.asarray(getattr(res, k))[..., i], r[k]) for i, r in zip(pick, refs) for k in KEYS)
        row.update({"solve_ivp_scaled_s": ivp * speeds.size / pick.size,
                    "solve_ivp_ratio": ivp * speeds.size / pick.size / row["median_s"],
                    "solve_ivp": bounded_difference(
                        diff, IVP_BOUND, f"solve_ivp (DOP853, rtol {IVP_RTOL:g}) on the full equations from the "
                                         f"compiled loop's periodic state at {pick.size} speeds: an adaptive "
                                         "integrator against the loop's fixed RK4 steps, its extremes at those steps")})
        row["equal"] = row["equal"] and row["solve_ivp"]["equal"]
        rows.append(row)
    rows.append({"name": "dynamics_contact_over_ltca", "median_s": walls["contact"],
                 "baseline": "the ltca sweep, same speeds, same run", "baseline_median_s": walls["ltca"],
                 "ratio": walls["contact"] / walls["ltca"]})
    return rows


def bench_dynamics(repeats: int = 3, baseline_speeds: int | None = None) -> dict:
    """The 496-speed sweep of the low-fluctuation paper pair 1: the compiled loop against the numpy batch."""
    pair = load_pair(ROOT / "config/pairs/low_fluctuation_pair1.yaml")
    speeds = np.arange(500.0, 50000.0 + 1.0, 100.0)
    geom = pair_geometry(pair)
    model = dy.pair_model(geom, 200.0, mesh_stiffness(geom, components=False).K)
    return kernel_rows("dynamics_sweep_496_speeds", model, speeds, repeats, baseline_speeds)[0]


if __name__ == "__main__":
    for r in bench_default_sweep():
        print(json.dumps(r), flush=True)
    print(json.dumps(bench_dynamics()), flush=True)


def bench_damping_search(repeats: int = 5) -> dict:
    """``mesh_damping_search_24_models``: the mesh damper of the GA's models (the default pair's
    contact-driven 8-DOF pair, 8 micro-geometries × the default study's 3 torques, the population
    tables), each model's modes included (the GA's resonance band asks for them). Today's search
    (:func:`gearmesh.dynamics.model._with_mesh_damping`: the ray search, checked on the damped
    modes) against the same function with the ray search switched off, so that the secant on the
    complex eigenvalues (:func:`gearmesh.dynamics.model._secant_damping_scale`, the only search at
    c61da5b) decides; equality of the dampers."""
    from gearmesh.dynamics import model as dm
    from gearmesh.dynamics.population import population_dynamics
    from gearmesh.gear import pair_geometry
    from gearmesh.pairfile import load_pair
    from gearmesh.meshforce import tabulate

    from common import swapped

    geom = pair_geometry(load_pair(CASE_PAIR))
    pd = population_dynamics(geom, [400.0, 1000.0, 1600.0], np.arange(1000, 15001, 500.0))
    params = np.zeros((8, 2, 6))
    params[:, :, 0] = np.random.default_rng(0).random((8, 2)) * 30e-6  # root/tip reliefs up to 30 µm
    params[:, :, 2] = 2e-3
    tables = [tabulate(pd.layout, g, pd.force_max, pd.approaches) for g in pd.layout.gaps(params, np.zeros((8, 2)))]
    bare = [dm.pair_model(geom, float(t), None, contact=tb, backlash=pd.backlash, mesh_damping=0.0)
            for tb in tables for t in pd.torques_out]
    rb, inertia = geom.base_radius, geom.inertia

    def search():
        out = [dm._with_mesh_damping(m, None, pd.damping_ratio, rb, inertia) for m in bare]
        return np.array([m.modes()["frequency_Hz"].size and m.damping[0] for m in out])

    wall, cpu, new, _ = timed_calls(search, repeats)
    with swapped(Swap("gearmesh.dynamics.model._ray_damping_scale", lambda original: lambda *a, **k: None)):
        bwall, bcpu, old, _ = timed_calls(search, repeats)
    return {"name": "mesh_damping_search_24_models", "median_s": wall, "cpu_s": cpu,
            "baseline": "the same _with_mesh_damping with the ray search off: the secant on the complex "
                        "eigenvalues (c61da5b's only search) decides", "baseline_median_s": bwall,
            "baseline_cpu_s": bcpu, "ratio": bwall / wall, "cpu_ratio": bcpu / cpu, **equality(new, old)}
