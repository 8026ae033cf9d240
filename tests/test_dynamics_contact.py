"""The dynamics driven by the real tooth contact (issue 15): the mesh-force table against the
LTCA, the quasi-static limit, the small-amplitude limit against the LTCA excitation, convergence
in the time step and the table, engagement physics, the train, the compiled loop against the
numpy kernel and solve_ivp, and the refusals."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gearmesh.contact_model import ContactModel, TABLE_CONTACT
from gearmesh import dynamics as dy
from gearmesh.body import RIGID_WEBS
from gearmesh.config import variant_pair
from gearmesh.contact import mesh_cycle_rolls
from gearmesh.datasets.dynamics import build_pair_model, contact_table, dynamics_dataset, train_dataset
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.impact import impact_model, impact_static
from gearmesh.io import check_documented
from gearmesh.ltca import ltca
from gearmesh.meshforce import mesh_force_table

from pairs import low_fluctuation_pair1, torsional_mesh_damping

#: The low-fluctuation paper's bearings, which the tests of issue 15 were written with.
ISSUE15_BEARING = {"k_radial": 1.5e8, "k_axial": 1.0e7}

RELIEF = {"modification": {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 3},
                           "pinion": {"crowning_um": 10, "unmodified_lead_length_mm": 0}}}
TORQUES = (400.0, 1000.0, 1600.0)


@pytest.fixture(scope="module")
def pair():
    from pathlib import Path

    return load_pair(Path(__file__).resolve().parents[1] / "config" / "pairs" / "helical_z29_71_m5.yaml")


@pytest.fixture(scope="module")
def geom(pair):
    return pair_geometry(pair)


@pytest.fixture(scope="module")
def teeth(pair):
    """The pair with rigid webs: the teeth alone, as the convergence and kernel tests were written
    (the bodies' series term of the table is checked in tests/test_body.py)."""
    return pair_geometry(pair.with_changes(body=RIGID_WEBS))


@pytest.fixture(scope="module")
def table(geom):
    """The default table (200 points per line) for forces up to 4 × F_bt(1600 N m), its separations
    at the mesh misalignment of 1000 N m (the system deflection of the pair's shafts and bearings,
    as the LTCA at that torque)."""
    return mesh_force_table(geom, 4 * 1600.0 / float(geom.base_radius[0]),
                            static_force=1000.0 / float(geom.base_radius[0]))


def _model(geom, table, torque_1: float, **kw):
    """The contact-driven pair as issue 15 built it, which these tests pin: the low-fluctuation paper's bearings
    (1.5e8 / 1e7 N/m, not the pair file's supports) and the torsional mesh damper
    (:func:`pairs.torsional_mesh_damping`)."""
    torque_out = torque_1 * geom.base_radius[1] / geom.base_radius[0]
    if "mesh_damping" not in kw:
        k_mean = dy.pair_model(geom, torque_out, None, contact=table, backlash=60e-6,
                               bearing=ISSUE15_BEARING).meshes[0].k_mean
        kw["mesh_damping"] = torsional_mesh_damping(geom, k_mean)
    return dy.pair_model(geom, torque_out, None, contact=table, backlash=60e-6,
                         bearing={**ISSUE15_BEARING, **kw.pop("bearing", {})}, **kw)


def test_table_inverted_is_the_ltca(geom, table):
    """The table's static solution F(x, r) = F_bt at every roll is the LTCA's loaded TE (the LTCA
    solves Σ q_i(x) = F by Newton; the table tabulates the forward map and is inverted between
    columns), and its tangent the LTCA's loaded stiffness, at the same points per line."""
    res = ltca(geom, [1000.0], 32, ContactModel(points=200))
    w = table.window_position(mesh_cycle_rolls(geom, 32))
    x, k = table.static_approach(1000.0 / float(geom.base_radius[0]))
    np.testing.assert_allclose(np.interp(w, table.window, x), res.lte[0], rtol=2e-3)
    np.testing.assert_allclose(np.interp(w, table.window, k), res.stiffness[0], rtol=2e-2)


def test_quasi_static_limit_is_the_ltca(geom, table):
    """At 30 rpm (mesh frequency 14.5 Hz, far below the lowest mode, 82 Hz) the dynamic TE
    along the mesh cycle is the LTCA's LTE(τ) (mean and shape), the mean mesh force the static
    force, and the entering pair first carries load where the quasi-static mesh touches."""
    model = _model(geom, table, 1000.0)
    res = dy.simulate(model, [30.0], dy.SolverSettings(record_cycles=2), series=True)
    st = res.series[0]
    cb = model.cos_beta_b
    te = (model.G @ st["y"].T)[0] / cb  # bodies' approach along the transverse line of action
    roll = np.mod(st["t"] * res.mesh_frequency[0], 1.0) * geom.transverse_base_pitch
    lte = ltca(geom, [1000.0], 128, ContactModel(points=200))
    ref = np.interp(roll, mesh_cycle_rolls(geom, 128), lte.lte[0], period=geom.transverse_base_pitch)
    assert abs(te.mean() / ref.mean() - 1) < 2e-3
    assert np.max(np.abs(te - ref)) < 0.03 * np.ptp(ref)  # the shape, within 3 % of its peak-to-peak
    np.testing.assert_allclose(res.force_mean[0, 0], model.static_force[0], rtol=1e-6)
    touch = res.touch_roll_before_A[0, 0]
    assert touch > 0  # an unmodified pair's entering tip edge touches before A
    assert abs(touch - table.static_touch(1000.0 / float(geom.base_radius[0]))) < table.pitch / table.positions


def test_mesh_in_converges_to_the_impact_model(teeth):
    """The table's quasi-static first touch converges like 1/N in the points per line to the
    impact model's exact face-end corner (slice centres lie half a slice inside the face): the
    Richardson extrapolation 2·T(2N) − T(N) meets impact_static's roll before engagement."""
    geom = teeth
    force = 1000.0 / float(geom.base_radius[0])
    t = {n: mesh_force_table(geom, 2 * force, 128, 32, TABLE_CONTACT.with_(points=n)).static_touch(force)
         for n in (50, 100)}
    exact = -float(impact_static(impact_model(geom), [1000.0]).tau[0, 0])
    assert abs(exact - t[100]) < 0.6 * abs(exact - t[50])  # the error halves
    assert abs(2 * t[100] - t[50] - exact) < 0.01 * exact


def test_contact_and_ltca_excitation_agree_for_small_motion(pair, geom, table):
    """Unmodified pair at full load (no contact loss): the LTCA excitation is the contact's
    linearisation about its static state, so both have the same resonance speeds (modes within
    1 %) and, at speeds away from resonance, nearly the same TE fluctuation."""
    from gearmesh.datasets.ltca import ltca_dataset

    # the same tooth model as the table: both the declared default (the FE tooth)
    ds = ltca_dataset(pair, torques_Nm=[1000.0], positions=128, points=200)
    lin = build_pair_model(pair, 1000.0, on="pinion", backlash_um=60, stiffness_form="table", ltca=ds)
    # both on the pair file's supports, with the damper sized on the mesh mode
    con = dy.pair_model(geom, 1000.0 * geom.base_radius[1] / geom.base_radius[0], None, contact=table, backlash=60e-6)
    f_lin, f_con = lin.modes()["frequency_Hz"], con.modes()["frequency_Hz"]
    np.testing.assert_allclose(f_con, f_lin, rtol=0.01)
    speeds = [2000.0, 4500.0, 10000.0]
    a, b = dy.simulate(lin, speeds), dy.simulate(con, speeds)
    np.testing.assert_allclose(b.approach_std[0], a.approach_std[0], rtol=0.08)
    np.testing.assert_allclose(b.force_max[0], a.force_max[0], rtol=0.01)


def test_converges_in_time_step_and_table(teeth):
    """Halving the time step, or doubling the table's positions or approaches, changes the peak
    force and the TE fluctuation less each time (at the mesh resonance, 6500 rpm). On the
    cantilever tooth: the FE tooth's tabulated compliance has an interpolation floor of about
    7e-4 in these quantities, below which doubling the approaches no longer converges."""
    geom = teeth
    force = 1600.0 / float(geom.base_radius[0])
    speeds = [6500.0]

    def run(P=128, U=48, courant=0.25):
        tab = mesh_force_table(geom, 4 * force, P, U, TABLE_CONTACT.with_(points=100, method="transition"))
        r = dy.simulate(_model(geom, tab, 1000.0), speeds, dy.SolverSettings(courant=courant, record_cycles=4))
        return np.array([r.force_max[0, 0], r.approach_std[0, 0], r.impact_force[0, 0]])

    base = run()

    def change(a, b):
        return np.max(np.abs(a / b - 1))

    for kw in ({"P": 256}, {"U": 96}, {"courant": 0.125}):
        finer = run(**kw)
        key, value = next(iter(kw.items()))
        finest = run(**{key: value * 2 if key != "courant" else value / 2})
        assert change(finest, finer) < 0.6 * change(finer, base) + 1e-4, kw
        assert change(finer, base) < 0.05, kw


def test_engagement_grows_with_load_and_speed_and_relief_reduces_it(pair, geom, table):
    """Unmodified pair: the entering pair's dynamic impact (its force above its quasi-static
    force at the same mesh position) grows with load at every speed where it matters (≥ 4000 rpm),
    and with speed below the mesh resonance (about 6500 rpm, first harmonic); well above the
    resonance it is larger than well below it. (Above the resonance it falls again with speed:
    the mesh is mass-controlled there — unlike the energy method's F_s ∝ ω^(2n/(n+1)).) The
    relief (gear tip relief 20 µm / 3 mm, holding the entering tip off up to about 1300 N m)
    reduces it at 400 and 1000 N m at every one of these speeds."""
    speeds = [4000.0, 5000.0, 5500.0, 10000.0, 14000.0]
    impact = np.array([dy.simulate(_model(geom, table, t), speeds).impact_force[0] for t in TORQUES])
    assert np.all(np.diff(impact, axis=0) > 0)  # with load, at every speed
    assert np.all(np.diff(impact[:, :3], axis=1) > 0)  # with speed, below the resonance
    assert np.all(impact[:, 3] > impact[:, 0])
    relieved = variant_pair(pair, "relief", RELIEF)
    g_r = pair_geometry(relieved)
    tab_r = mesh_force_table(g_r, 4 * 1600.0 / float(g_r.base_radius[0]))
    relief = np.array([dy.simulate(_model(g_r, tab_r, t), speeds).impact_force[0] for t in (400.0, 1000.0)])
    assert np.all(relief < impact[:2])


def test_shooting_state_is_a_periodic_orbit_of_the_full_equations(geom):
    """The shooting's periodic state, integrated by solve_ivp on the unreduced equations over
    two more mesh periods, comes back to itself, and the record statistics agree with the
    compiled loop's (an independent integrator and formulation of the same contact model)."""
    force = 1000.0 / float(geom.base_radius[0])
    tab = mesh_force_table(geom, 4 * force, 128, 48, TABLE_CONTACT.with_(points=50))
    model = _model(geom, tab, 1000.0)
    s = dy.SolverSettings(record_cycles=2)
    res = dy.simulate(model, [6000.0], s)
    ref = dy.reference_solution(model, 6000.0, s, rtol=1e-9, atol=1e-14, start=res.periodic_state[0],
                                transient_cycles=0, samples_per_cycle=int(res.steps_per_cycle[0]))
    np.testing.assert_allclose(ref["force_mean"][0], res.force_mean[0, 0], rtol=2e-4)
    np.testing.assert_allclose(ref["approach_std"][0], res.approach_std[0, 0], rtol=2e-3)
    np.testing.assert_allclose(ref["force_max"][0], res.force_max[0, 0], rtol=2e-3)


def test_shooting_equals_the_physical_transient(geom):
    """With heavily damped bearings (short transients) the periodic state by shooting and the
    state after waiting out 10 time constants give the same statistics."""
    force = 1000.0 / float(geom.base_radius[0])
    tab = mesh_force_table(geom, 4 * force, 64, 32, TABLE_CONTACT.with_(points=30))
    model = _model(geom, tab, 1000.0, bearing={"c_radial": 3e4, "c_axial": 3e4})
    speeds = [3000.0, 6500.0]
    a = dy.simulate(model, speeds)
    b = dy.simulate(model, speeds, dy.SolverSettings(steady_state="transient"))
    assert np.all(a.shooting_iterations >= 1)
    for key in ("force_max", "approach_std", "impact_force", "touch_roll_before_A"):
        np.testing.assert_allclose(getattr(a, key), getattr(b, key), rtol=1e-6, err_msg=key)


def test_two_periods_of_the_periodic_orbit_give_the_statistics_of_eight(geom):
    """From the shooting's fixed point every period repeats the first: two recorded periods and
    none to settle (the population's solver) give the statistics of the default eight after two,
    to the shooting tolerance; the modes and static state the step plan reuses are the model's."""
    force = 1000.0 / float(geom.base_radius[0])
    tab = mesh_force_table(geom, 4 * force, 64, 32, TABLE_CONTACT.with_(points=30))
    model = _model(geom, tab, 1000.0)
    speeds = [2500.0, 5200.0, 6500.0, 12000.0]
    a = dy.simulate(model, speeds)
    b = dy.simulate(model, speeds, dy.SolverSettings(settle_cycles=0, periodic_record_cycles=2))
    assert np.all(a.shooting_iterations >= 1) and np.all(b.shooting_iterations >= 1)
    for key in ("force_max", "force_min", "force_mean", "approach_std", "impact_force", "enter_force_max"):
        np.testing.assert_allclose(getattr(b, key), getattr(a, key), rtol=1e-6, err_msg=key)
    assert np.all(b.n_steps < a.n_steps)
    fresh = model.modes(np.array([ml.k_mean for ml in model.meshes]))
    np.testing.assert_array_equal(model.modes()["eigenvalue"], fresh["eigenvalue"])


@pytest.mark.parametrize("speed", [1000.0, 6500.0])
def test_period_map_jacobian_is_its_forward_difference(geom, speed):
    """The monodromy matrix the shooting integrates beside the period (variational equations of
    the RK4 stages) is the derivative of the period map: equal to its central difference, column
    by column, on an orbit with contact loss and back-flank contact (large excitation)."""
    from gearmesh.dynamics.integrate import _Loop, step_plan

    force = 1000.0 / float(geom.base_radius[0])
    tab = mesh_force_table(geom, 4 * force, 64, 32, TABLE_CONTACT.with_(points=30))
    model = _model(geom, tab, 1000.0)
    f_mesh, m, _, dt = step_plan(model, np.array([speed]))
    run = _Loop(model).speed(int(m[0]), float(f_mesh[0]), float(dt[0]))
    y = np.concatenate([model.static_state(), np.zeros(model.n)])
    y[model.n:] = 0.3 * np.abs(y[:model.n]).max() * 2 * np.pi * f_mesh[0]  # far from the orbit: gaps open
    tangent = np.eye(y.size)[None].copy()
    end = y[None].copy()
    run.run(end, 1, tangent=tangent)
    plain = y[None].copy()
    run.run(plain, 1)
    assert np.array_equal(end, plain)  # the tangent leaves the trajectory untouched
    scale = np.abs(y).reshape(2, -1).max(axis=1).repeat(model.n)
    eps = 1e-7 * scale
    fd = np.empty_like(tangent[0])
    for k in range(y.size):
        pm = np.stack([y, y]) + np.outer([1.0, -1.0], np.eye(y.size)[k] * eps[k])
        run.run(pm, 1)
        fd[:, k] = (pm[0] - pm[1]) / (2 * eps[k])
    np.testing.assert_allclose(tangent[0] * scale[None, :], fd * scale[None, :], rtol=0,
                               atol=1e-5 * np.abs(fd * scale[None, :]).max())


@pytest.mark.parametrize("excitation", ["tvms", "ltca"])
def test_compiled_loop_equals_the_numpy_kernel(excitation):
    """The compiled step loop evaluates the same mesh laws at the same phases as the numpy batch
    kernel it replaced: identical to round-off (amplified to ~1e-9 by the impacts across the
    backlash) with the same physical-time transient, contact loss included."""
    from gearmesh.datasets.ltca import ltca_dataset

    pair = load_pair(low_fluctuation_pair1(center_distance_mm=69.30))
    if excitation == "ltca":
        kw = {"ltca": ltca_dataset(pair, torques_Nm=[30.0], on="gear", positions=32, points=12)}
    else:  # a kinematic error large enough to open the backlash at this load
        kw = {"transmission_error_um": list(8.0 * np.sin(2 * np.pi * np.arange(32) / 32))}
    model = build_pair_model(pair, 30.0, on="gear", backlash_um=60, excitation=excitation, positions=64, slices=40, **kw)
    s = dy.SolverSettings(transient_tau=3.0, record_cycles=2, steady_state="transient")
    speeds = [8000.0, 16000.0, 20000.0]  # (at 33000 rpm and above the impacting response is chaotic)
    a, b = dy.simulate(model, speeds, s), dy.simulate_numpy(model, speeds, s)
    for key in ("force_max", "force_min", "dte_std", "approach_mean", "gap_fraction", "y_std", "v_rms"):
        np.testing.assert_allclose(getattr(a, key), getattr(b, key), rtol=1e-7, atol=1e-18, err_msg=key)
    if excitation == "tvms":
        assert np.any(a.gap_fraction > 0)  # the backlash branch is exercised


def test_compiled_contact_loop_equals_the_numpy_kernel(teeth):
    """The contact table read by the compiled loop and by the numpy batch kernel (independent
    indexing, numpy's own RK4 over all speeds): the same trajectory to round-off through a start
    far from equilibrium that opens the mesh and hits the back flanks."""
    geom = teeth
    force = 1000.0 / float(geom.base_radius[0])
    tab = mesh_force_table(geom, 4 * force, 64, 32, TABLE_CONTACT.with_(points=30))
    model = dy.pair_model(geom, 400.0 * geom.base_radius[1] / geom.base_radius[0], None, contact=tab, backlash=20e-6)
    y0 = model.static_state()
    y0[-1] -= 10 * (model.G @ y0)[0] / model.G[0, -1]  # relative rotation pulled back by 10 static deflections
    s = dy.SolverSettings(transient_tau=1e-9, min_transient_cycles=0, record_cycles=2, steady_state="transient")
    speeds = [3000.0, 6000.0, 9000.0]
    a, b = dy.simulate(model, speeds, s, y0=y0), dy.simulate_numpy(model, speeds, s, y0=y0)
    assert np.all(a.gap_fraction > 0) and np.all(a.back_fraction[:, 1:] > 0)
    for key in ("force_max", "force_min", "dte_std", "approach_mean", "approach_std", "gap_fraction", "back_fraction",
                "y_std", "v_rms"):
        np.testing.assert_allclose(getattr(a, key), getattr(b, key), rtol=1e-10, atol=1e-18, err_msg=key)


def test_train_driven_by_contact_balances_the_torque():
    """The 9-DOF train with both meshes driven by the contact table: the mean mesh forces equal
    the static force (torque balance), and the idler's two meshes carry the same mean force."""
    from pathlib import Path

    pair = load_pair(Path(__file__).resolve().parents[1] / "config" / "pairs" / "printing_train_z88.yaml")
    ds = train_dataset(pair, excitation="contact", backlash_um=60, points=30, table_positions=64,
                       table_approaches=32, record_cycles=4, points_per_cycle=16, max_order=4)
    check_documented(ds)
    assert ds.attrs["excitation_name"] == "contact"
    np.testing.assert_allclose(ds.mesh_force_mean.values[0], ds.static_mesh_force.values, rtol=1e-5)


def test_dataset_cli_and_refusals(pair, tmp_path):
    """The dataset carries the entering pair per torque and speed; the CLI prints the issue's keys;
    bad settings are refused naming the field."""
    ds = dynamics_dataset(pair, torques_Nm=[600.0, 1200.0], speeds_rpm=[3000.0, 6000.0], backlash_um=60,
                          excitation="contact", sample_speeds_rpm=[3000.0], refine_resonances=False,
                          points=50, table_positions=64, table_approaches=32, record_cycles=2,
                          points_per_cycle=16, max_order=4, variant="standard")
    check_documented(ds)
    assert ds.dynamic_impact_force.dims == ("torque", "speed")
    assert ds.entering_pair_force_series.dims == ("torque", "sample_speed", "sample")
    assert np.all(ds.mesh_in_roll_before_A.values > 0) and ds.attrs["variant"] == "standard"
    assert float(ds.mesh_in_roll_before_A[1, 0]) > float(ds.mesh_in_roll_before_A[0, 0])  # load: earlier touch
    from gearmesh.cli import main
    import contextlib
    import io

    out = io.StringIO()
    path = tmp_path / "helical_z29_71_m5.yaml"
    import yaml

    from gearmesh.pairfile import pair_to_dict

    path.write_text(yaml.safe_dump(pair_to_dict(pair)))
    with contextlib.redirect_stdout(out):
        rc = main(["dynamics", str(path), "--torque-Nm", "1000", "--speeds", "5000:5000:1000",
                   "--excitation", "contact", "--json"])
    assert rc == 0
    row = json.loads(out.getvalue())["speeds"][0]
    assert {"mesh_force_max_normal_N", "dynamic_factor", "dynamic_te_mean_um", "dynamic_te_std_um",
            "entering_pair_force_max_normal_N", "mesh_in_roll_before_A_mm"} <= set(row)
    assert row["mesh_in_roll_before_A_mm"] > 0
    for kw, field in (({"excitation": "impact"}, "excitation"), ({"excitation": "ltca"}, "excitation"),
                      ({"excitation": "contact", "table_positions": 4}, "table_positions"),
                      ({"excitation": "contact", "table_force_factor": 0.5}, "table_force_factor"),
                      ({"excitation": "contact", "contact_law": "hertz"}, "contact_law"),
                      ({"steady_state": "guess"}, "steady_state"), ({"backlash_um": "wide"}, "backlash_um")):
        with pytest.raises(GearmeshInputError, match=field):
            dynamics_dataset(pair, torques_Nm=1000.0, speeds_rpm=[5000.0], sample_speeds_rpm=[], **kw)


def test_contact_table_is_built_once_per_mesh_misalignment(pair, geom, monkeypatch):
    """One table layout per pair and variant, and one tabulation per mesh misalignment: the sweep over
    three torques tabulates three (each torque deflects the shafts its own amount), the pair without
    its shafts and bearings one."""
    import gearmesh.datasets.dynamics.excitation as dd
    from gearmesh.supports import read_supports

    for p, expected in ((pair, 3), (pair.with_changes(supports=read_supports({})), 1)):
        layouts, tabs = [], []
        real_layout, real_tab = dd.table_layout, dd.tabulate
        monkeypatch.setattr(dd, "table_layout", lambda *a, **k: layouts.append(1) or real_layout(*a, **k))
        monkeypatch.setattr(dd, "tabulate", lambda *a, **k: tabs.append(1) or real_tab(*a, **k))
        dynamics_dataset(p, torques_Nm=list(TORQUES), speeds_rpm=[5000.0], excitation="contact", sample_speeds_rpm=[],
                         bearing_k_radial_N_per_m=1.5e8, bearing_k_axial_N_per_m=1e7, refine_resonances=False,
                         points=30, table_positions=32, table_approaches=16, record_cycles=2)
        assert (len(layouts), len(tabs)) == (1, expected)
        monkeypatch.setattr(dd, "table_layout", real_layout)
        monkeypatch.setattr(dd, "tabulate", real_tab)
    t = contact_table(geom, [1600.0], TABLE_CONTACT.with_(points=30), table_positions=32, table_approaches=16,
                      table_force_factor=3.0)
    assert math.isclose(t.force_max, 3.0 * 1600.0 / float(geom.base_radius[0]))


def test_simulated_engagement_window_spans_the_impact(pair):
    """The engagement simulation of the energy-method check reports its peaks over one natural
    period from the touch, not up to the entering pair's first local maximum — which, after the
    grazing touch of the single-point GA optimum (pinion root relief 38.96 µm / 2.105 mm, tip
    relief 16.21 µm / 0.824 mm, crowning 5 µm / 0.824 mm), closed 0.3 µs after the touch on a
    7.67 N wiggle while the entering pair went on to carry several kN."""
    from gearmesh.impact import simulate_engagement

    opt = variant_pair(pair, "optimised", {"modification": {"pinion": {
        "root_relief_um": 38.96, "tip_relief_um": 16.21, "root_relief_length_mm": 2.105, "tip_relief_length_mm": 0.824,
        "crowning_um": 5.0, "unmodified_lead_length_mm": 0.824}}})
    r = simulate_engagement(impact_model(pair_geometry(opt)), 1000.0, 5000.0, samples=300)
    window = (r["time"] >= r["touch_time"]) & (r["time"] <= r["touch_time"] + r["period"])
    assert r["entering_peak"] == pytest.approx(r["entering_force"][window].max())
    assert r["entering_peak"] > 0.5 * r["entering_static"][window].max() > 1000.0
    assert r["touch_time"] <= r["peak_time"] <= r["touch_time"] + r["period"]
