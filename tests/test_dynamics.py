"""Physics tests of the dynamics stage (issue 5): static limit, resonances against an independent
eigen-solution, step halving, backlash, the train's torque balance, batch RK4 against solve_ivp."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import scipy.linalg

from gearmesh import dynamics as dy
from gearmesh.datasets.dynamics import dynamics_dataset, dynamics_summary, parse_speeds, speed_grid, train_dataset
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict
from gearmesh.io import check_documented
from gearmesh.stiffness import mesh_stiffness

from pairs import low_fluctuation_pair1, torsional_mesh_damping


@pytest.fixture(scope="module")
def geom():
    return pair_geometry(pair_from_dict(low_fluctuation_pair1(center_distance_mm=69.30)))


@pytest.fixture(scope="module")
def K(geom):
    return mesh_stiffness(geom, components=False).K


@pytest.fixture(scope="module")
def model(geom, K):
    """The low-fluctuation paper's pair and bearings with the mesh damper these solver tests were written for
    (:func:`pairs.torsional_mesh_damping`)."""
    k_mean = dy.pair_model(geom, 200.0, K).meshes[0].k_mean
    return dy.pair_model(geom, 200.0, K, mesh_damping=torsional_mesh_damping(geom, k_mean))


FAST = dy.SolverSettings(transient_tau=8.0, record_cycles=4)


def full_matrices(geom, k_normal: float, bearing=dy.LOW_FLUCTUATION_BEARING):
    """The 8-DOF mass and stiffness matrices written out independently from the equations of
    motion in the module docstring (x, y, z, θ per gear; meshes closed at k_normal)."""
    a, bb = geom.operating_pressure_angle, geom.base_helix_angle
    rb1, rb2 = geom.base_radius
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    g = np.array([math.sin(a) * math.cos(bb), math.cos(a) * math.cos(bb), -h * math.sin(bb), rb1 * math.cos(bb),
                  -math.sin(a) * math.cos(bb), -math.cos(a) * math.cos(bb), h * math.sin(bb), -rb2 * math.cos(bb)])
    M = np.diag([geom.mass[0]] * 3 + [geom.inertia[0]] + [geom.mass[1]] * 3 + [geom.inertia[1]])
    kr, ka = bearing["k_radial"], bearing["k_axial"]
    Kmat = np.diag([kr, kr, ka, 0.0, kr, kr, ka, 0.0]) + k_normal * np.outer(g, g)
    return M, Kmat, g


def test_constant_stiffness_settles_to_static_deflection(geom, K):
    """K constant, no TE, started from rest (not from the static state): the transient decays
    by e^(−n_τ) and the response settles to δ = F/k_n, F = T_out/(r_b2 cos βb), with the
    bearings deflected by F·n/k. No backlash: from rest the teeth first close the gap."""
    kc = np.full(64, K.mean())
    m = dy.pair_model(geom, 200.0, kc, backlash=None)
    settings = dy.SolverSettings(transient_tau=12.0, record_cycles=4)
    res = dy.simulate(m, [3000.0, 27000.0], settings, y0=np.zeros(m.n))
    cb = math.cos(geom.base_helix_angle)
    F = 200.0 / (geom.base_radius[1] * cb)
    k_n = K.mean() / cb**2
    tol = 10 * math.exp(-12.0)  # the slowest transient after n_τ = 12 decay times
    np.testing.assert_allclose(res.force_mean[0], F, rtol=tol)
    np.testing.assert_allclose(res.dte_mean[0], F / k_n, rtol=tol)
    assert np.all(res.dte_std[0] < tol * F / k_n)
    _, _, g = full_matrices(geom, k_n)
    expected = -F * g[[0, 1, 2, 4, 5, 6]] / np.array([1.5e8, 1.5e8, 1e7] * 2)
    np.testing.assert_allclose(res.y_mean[:6, 0], expected, rtol=tol)


def test_mean_mesh_force_equals_static_force(model):
    """⟨F⟩ cos βb r_b2 = T_out over whole periods at every speed (⟨q̈⟩ = 0 in steady state)."""
    res = dy.simulate(model, np.arange(1000.0, 50001.0, 7000.0), FAST)
    # exact for a periodic steady state; the residual transient (e^-8) leaves ~1e-6
    np.testing.assert_allclose(res.force_mean[0], model.static_force[0], rtol=1e-5)


def test_eigenfrequencies_match_independent_eig(geom, model):
    """Reduced model (rigid mode removed) against scipy.linalg.eig of the full 8-DOF K, M."""
    k_n = model.meshes[0].k_mean
    M, Kmat, _ = full_matrices(geom, k_n)
    w2 = np.sort(scipy.linalg.eig(Kmat, M)[0].real)
    assert abs(w2[0]) < 1e-6 * w2[-1]  # the rigid-body rotation
    f_full = np.sqrt(w2[1:]) / (2 * np.pi)
    # undamped modes of the reduced model
    Kr, _ = model.linear_matrices()
    f_red = np.sort(np.sqrt(np.linalg.eigvals(Kr).real)) / (2 * np.pi)
    np.testing.assert_allclose(f_red, f_full, rtol=1e-9)
    assert len(f_full) == 7 and np.all(model.modes()["decay_rate"] > 0)  # no drift mode left


def test_resonance_peaks_sit_at_eigenfrequencies(geom, model):
    """Peaks of the sweep where mesh frequency (or 2×) meets an eigenfrequency of the full model."""
    M, Kmat, g = full_matrices(geom, model.meshes[0].k_mean)
    w2, vec = scipy.linalg.eigh(Kmat, M)
    f = np.sqrt(np.clip(w2, 0, None)) / (2 * np.pi)
    # mesh-dominated mode: largest share of strain energy in the mesh spring
    share = model.meshes[0].k_mean * (g @ vec) ** 2 / np.einsum("im,ij,jm->m", vec, Kmat, vec).clip(1e-30)
    mesh_mode = int(np.argmax(share[1:])) + 1
    z1 = geom.pair.teeth[0]
    n_mesh = 60 * f[mesh_mode] / z1
    speeds = np.arange(0.8 * n_mesh, 1.2 * n_mesh, 0.005 * n_mesh)
    res = dy.simulate(model, speeds, FAST)
    peak = speeds[np.argmax(res.dte_std[0])]
    assert abs(peak / n_mesh - 1) < 0.03, (peak, n_mesh)
    # second mesh harmonic of the same mode: a local DTE maximum near n/2
    speeds2 = np.arange(0.45 * n_mesh, 0.55 * n_mesh, 0.0025 * n_mesh)
    res2 = dy.simulate(model, speeds2, FAST)
    peak2 = speeds2[np.argmax(res2.dte_std[0])]
    assert abs(peak2 / (n_mesh / 2) - 1) < 0.03, (peak2, n_mesh / 2)
    # a bearing (lateral) mode with the largest pinion-y participation among the low modes,
    # excited by the first mesh harmonic: the pinion y vibration peaks there
    low = [i for i in range(1, 8) if f[i] < 0.5 * f[mesh_mode]]
    lat = max(low, key=lambda i: abs(vec[1, i]) * np.sqrt(M[1, 1]) * abs(g @ vec[:, i]))
    n_lat = 60 * f[lat] / z1
    speeds3 = np.arange(0.9 * n_lat, 1.1 * n_lat, 0.005 * n_lat)
    res3 = dy.simulate(model, speeds3, FAST)
    peak3 = speeds3[np.argmax(res3.y_std[1])]
    assert abs(peak3 / n_lat - 1) < 0.03, (peak3, n_lat)


def test_halving_the_step_changes_rms_little(model):
    """Tolerance: 1e-4 relative on the DTE, displacement and velocity RMS and the peak force."""
    speeds = [2000.0, 13700.0, 27000.0, 45000.0]
    a = dy.simulate(model, speeds, FAST)
    b = dy.simulate(model, speeds, dy.SolverSettings(courant=FAST.courant / 2,
                                                     steps_per_cycle_min=2 * FAST.steps_per_cycle_min,
                                                     transient_tau=FAST.transient_tau,
                                                     record_cycles=FAST.record_cycles))
    for name in ("dte_std", "dte_rms", "y_std", "v_rms"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=1e-4, err_msg=name)
    # the sampled maximum also moves with the sampling (32 vs 64 points per period)
    np.testing.assert_allclose(a.force_max, b.force_max, rtol=5e-3)


def test_contact_loss_only_where_the_linear_force_turns_negative(geom, K):
    """An unloaded TE of 0.6 µm at 20 N·m: the backlash model loses contact exactly at the speeds
    where the same model without backlash has δ < 0 (force < 0); elsewhere both coincide."""
    te = 0.6e-6 * np.cos(2 * np.pi * np.arange(64) / 64)
    speeds = np.arange(10000.0, 50001.0, 4000.0)
    lin = dy.simulate(dy.pair_model(geom, 20.0, K, transmission_error=te, backlash=None), speeds, FAST)
    nl = dy.simulate(dy.pair_model(geom, 20.0, K, transmission_error=te, backlash=60e-6), speeds, FAST)
    would_separate = lin.dte_min[0] < 0
    assert would_separate.any() and (~would_separate).any()
    assert np.all(lin.force_min[0][would_separate] < 0)
    np.testing.assert_array_equal(nl.gap_fraction[0] > 0, would_separate)
    same = ~would_separate
    np.testing.assert_allclose(nl.dte_std[0][same], lin.dte_std[0][same], rtol=1e-7)
    assert np.all(nl.back_fraction == 0)


def test_train_meshes_balance_the_torque():
    pair = load_pair(_root() / "config/pairs/printing_train_z88.yaml")
    ds = train_dataset(pair, transient_tau=6.0, record_cycles=4, points_per_cycle=32, max_order=4)
    check_documented(ds)
    geom = pair_geometry(pair)
    rb, cb = geom.base_radius[1], math.cos(geom.base_helix_angle)
    F = ds.mesh_force_mean.values[0]
    # plate: T = F1 r_b cos βb; blanket idles: F1 = F2; impression: F2 r_b cos βb = T
    np.testing.assert_allclose(F * rb * cb, float(ds.torque), rtol=1e-6)
    np.testing.assert_allclose(F, 2832.0, rtol=1e-6)
    np.testing.assert_allclose(float(ds.mesh_frequency[0]), 249.4, rtol=1e-12)
    # the radial mesh forces on the blanket cancel; plate and impression deflect oppositely
    ym = ds.displacement_mean.sel(direction="y").values[0]
    assert abs(ym[1]) < 1e-9 * abs(ym[0])
    np.testing.assert_allclose(ym[0], -ym[2], rtol=1e-9)


def _train_model():
    geom4 = pair_geometry(load_pair(_root() / "config/pairs/printing_train_z88.yaml"))
    return geom4, dy.train_model(geom4, 400.0, mesh_stiffness(geom4, components=False).K)


@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("which", ["pair", "train"])
def test_screw_motion_of_any_gear_changes_no_mesh_deflection(K, hand, which):
    """A helical gear slid by dz and turned by dθ = h tan βb dz / r_b maps its flank onto itself
    (h = ±1 the pinion's/plate's hand; each θ positive in its gear's own turning sense, in
    which gears of opposite hand and opposite rotation have the same screw sense): every δ is
    unchanged (the rule behind every axial term of both models)."""
    if which == "pair":
        g = pair_geometry(pair_from_dict(low_fluctuation_pair1(helix_hand=hand)))
        mdl = dy.pair_model(g, 200.0, K)
        radii = dict(zip(("pinion", "gear"), g.base_radius))
    else:
        g, _ = _train_model()
        g = pair_geometry(g.pair.with_changes(helix_hand=hand))
        mdl = dy.train_model(g, 400.0, np.full(16, 1e9))
        radii = {name: g.base_radius[1] for name in dy.TRAIN_GEARS}
    names, G = mdl.full["names"], mdl.full["G"]
    tan_bb = math.tan(g.base_helix_angle) * (1 if hand == "right" else -1)
    for gear, rb in radii.items():
        dz = 1e-6
        d = np.zeros(len(names))
        d[names.index(f"z_{gear}")] = dz
        d[names.index(f"theta_{gear}")] = tan_bb * dz / rb
        np.testing.assert_allclose(G @ d, 0.0, atol=1e-12 * dz)


def test_the_idler_of_the_train_carries_no_net_thrust():
    _, mdl = _train_model()
    names, G = mdl.full["names"], mdl.full["G"]
    axial = {gear: -G[:, names.index(f"z_{gear}")] @ mdl.static_force for gear in dy.TRAIN_GEARS}
    f_axial = mdl.static_force[0] * math.sin(math.atan(abs(G[0, names.index("z_plate")]) /
                                                        math.sqrt(1 - G[0, names.index("z_plate")] ** 2)))
    assert abs(axial["blanket"]) < 1e-9 * mdl.static_force[0]
    # plate and impression carry equal and opposite thrust F sin βb
    assert axial["plate"] == pytest.approx(-axial["impression"], rel=1e-12)
    assert abs(axial["plate"]) == pytest.approx(f_axial, rel=1e-9)


@pytest.mark.parametrize("speed", [13700.0, 27000.0])
def test_batch_rk4_matches_solve_ivp(model, speed):
    """Batch RK4 (reduced, rigid mode removed) against DOP853 rtol 1e-10 on the full 8-DOF
    equations; 27000 rpm is the mesh resonance, 13700 rpm its second harmonic."""
    res = dy.simulate(model, [speed], FAST)
    ref = dy.reference_solution(model, speed, FAST, rtol=1e-9, atol=1e-13)
    np.testing.assert_allclose(res.dte_std[:, 0], ref["dte_std"], rtol=2e-4)
    np.testing.assert_allclose(res.dte_mean[:, 0], ref["dte_mean"], rtol=2e-5)
    np.testing.assert_allclose(res.y_std[:, 0], ref["y_std"], rtol=2e-4)
    np.testing.assert_allclose(res.v_rms[:, 0], ref["v_rms"], rtol=2e-4)


def test_lste_excitation_counts_the_fluctuation_twice(geom, K):
    """Quasi-static (mesh frequency ≪ lowest mode): with e = 0 the approach of the bodies
    (r_b1 θ_p − r_b2 θ_g) cos βb is the LSTE F/K(t); the low-fluctuation paper's literal e = F/K(t) with k(t)
    doubles it (module docstring), while δ = approach − e stays F/K(t) in both."""
    s = dy.SolverSettings(courant=0.5, transient_tau=3.0, record_cycles=2, min_transient_cycles=1)
    a = dy.simulate(dy.pair_model(geom, 200.0, K, excitation="tvms"), [60.0], s)
    b = dy.simulate(dy.pair_model(geom, 200.0, K, excitation="lste"), [60.0], s)
    model = dy.pair_model(geom, 200.0, K)
    ph = np.linspace(0, 1, 4096, endpoint=False)
    lste_n = model.static_force[0] / model.meshes[0].stiffness(ph)  # normal LSTE of the Fourier k
    cb = math.cos(geom.base_helix_angle)
    assert abs(a.dte_std[0, 0] / lste_n.std() - 1) < 0.02
    assert abs(b.dte_std[0, 0] / lste_n.std() - 1) < 0.02
    assert abs(a.y_std[-1, 0] * cb / lste_n.std() - 1) < 0.02
    assert abs(b.y_std[-1, 0] / a.y_std[-1, 0] - 2) < 0.04


def test_dataset_summary_and_inputs():
    pair = pair_from_dict(low_fluctuation_pair1(center_distance_mm=69.30))
    ds = dynamics_dataset(pair, speeds_rpm={"start": 20000, "stop": 30000, "step": 5000},
                          sample_speeds_rpm=[27000], transient_tau=4.0, record_cycles=4, points_per_cycle=32,
                          max_order=4)
    check_documented(ds)
    assert int(ds.on_grid.sum()) == 3 and ds.displacement_rms.dims == ("torque", "speed", "gear", "direction")
    assert ds.attrs["torque_on"] == "pinion" and float(ds.torque[0]) == 200.0  # the torque and its gear, stated
    spec = ds.mesh_force_spectrum.isel(torque=0, sample_speed=0)
    assert float(spec.sel(order=1.0)) > 10 * float(spec.sel(order=0.5))  # lines at mesh orders only
    rows = dynamics_summary(pair, torques_Nm=200.0, speeds_rpm=parse_speeds("25000:27000:2000"), transient_tau=4.0,
                            record_cycles=4)
    assert [r["speed_rpm"] for r in rows] == [25000.0, 27000.0]
    assert {"speed_rpm", "dynamic_te_mean_um", "dynamic_te_std_um", "mesh_deflection_mean_um", "mesh_force_mean_normal_N",
            "mesh_force_max_normal_N"} <= set(rows[0])
    with pytest.raises(GearmeshInputError, match="torques_Nm"):
        dynamics_dataset(pair, torques_Nm=-5.0)
    with pytest.raises(GearmeshInputError, match="speeds_rpm.stop"):
        speed_grid({"start": 1000, "stop": 500, "step": 100})
    with pytest.raises(GearmeshInputError, match="speeds_rpm.step"):
        speed_grid({"start": 500, "stop": 1000, "step": 0})
    with pytest.raises(GearmeshInputError, match="speeds_rpm.start"):
        speed_grid("0:100:10")
    with pytest.raises(GearmeshInputError, match="bore_radius_mm"):
        dynamics_dataset(pair.with_changes(bore_radius=None))
    with pytest.raises(GearmeshInputError, match="material"):
        dynamics_dataset(pair.with_changes(material=None))


def _root():
    from pathlib import Path

    return Path(__file__).resolve().parents[1]


def test_ltca_excitation_reproduces_the_loaded_te_and_sees_the_modification():
    """With the LTCA excitation k = k_L, e = LTE − F/k_L, the static balance at each mesh
    position gives the bodies' approach G·y = LTE·cos βb (normal direction) exactly, and a
    tip relief changes the dynamic response."""
    from gearmesh.datasets.dynamics import build_pair_model
    from gearmesh.datasets.ltca import ltca_dataset

    std = []
    for mod in (None, {"gear": {"tip_relief_um": 15, "tip_relief_length_mm": 1.0}}):
        data = low_fluctuation_pair1(**({"modification": mod} if mod else {}))
        pair = load_pair(data)
        g = pair_geometry(pair)
        ltca = ltca_dataset(pair, torques_Nm=[200], on="gear", positions=64, points=30)
        mdl = build_pair_model(pair, 200.0, on="gear", stiffness_form="table", ltca=ltca)
        law = mdl.meshes[0]
        phase = np.arange(64) / 64
        k, e = law.stiffness(phase), law.error(phase)[0]
        approach = []
        for kk, ee in zip(k, e):
            K_t, _ = mdl.linear_matrices(np.array([kk]))
            y = np.linalg.solve(K_t, mdl.f0 + mdl.B @ np.array([kk * ee]))
            approach.append((mdl.G @ y)[0])
        np.testing.assert_allclose(approach, ltca["lte"].values[0] * math.cos(g.base_helix_angle), rtol=1e-6)
        res = dy.simulate(mdl, np.array([6000.0]), FAST)
        std.append(float(res.dte_std[0, 0]))
        # the default smooth (Fourier) form keeps the periodic mean force = static force
        smooth = build_pair_model(pair, 200.0, on="gear", ltca=ltca)
        fast = dy.simulate(smooth, np.array([50000.0]), FAST)
        np.testing.assert_allclose(fast.force_mean[0], smooth.static_force[0], rtol=1e-5)
    assert abs(std[1] / std[0] - 1) > 0.05


def test_low_speed_dynamic_te_is_the_mean_lte_and_mesh_deflection_is_f_over_k():
    """Two displacements, two definitions (issue 10): at a speed far below the first mode the
    dynamic TE (approach of the bodies along the transverse line of action) of an LTCA-excited
    variant averages to the LTCA's mean loaded TE, the mesh deflection to the mean of F_bt/k_L
    (F_bt = T1/r_b1, k_L the LTCA's loaded stiffness) — both taken from the LTCA dataset, not
    from the model; the dataset records the LTCA as its excitation."""
    from gearmesh.datasets.ltca import ltca_dataset

    pair = pair_from_dict(low_fluctuation_pair1(modification={"gear": {"tip_relief_um": 15, "tip_relief_length_mm": 1.0}}))
    ltca = ltca_dataset(pair, torques_Nm=[200], on="gear", positions=32, points=12)
    ds = dynamics_dataset(pair, torques_Nm=200.0, on="gear", speeds_rpm=[40.0], sample_speeds_rpm=[], stiffness_form="table",
                          refine_resonances=False, transient_tau=6.0, record_cycles=2, ltca=ltca)
    check_documented(ds)
    assert ds.attrs["excitation"].startswith("ltca")
    lte = ltca["lte"].values[0]
    f_bt = float(ltca["torque"].values[0]) / float(pair_geometry(pair).base_radius[0])
    np.testing.assert_allclose(float(ds.dynamic_te_mean[0, 0]), lte.mean(), rtol=2e-3)
    np.testing.assert_allclose(float(ds.mesh_deflection_mean[0, 0]),
                               np.mean(f_bt / ltca["loaded_mesh_stiffness"].values[0]), rtol=2e-3)
    assert float(ds.dynamic_te_mean[0, 0]) > float(ds.mesh_deflection_mean[0, 0]) * 1.05  # the relief: e > 0
    assert "transverse line of action" in ds.dynamic_te_mean.attrs["long_name"]


def test_sweep_adds_speeds_around_predicted_resonances(model):
    from gearmesh.datasets.dynamics import resonance_refined
    from gearmesh.dynamics import RESONANCE_OFFSETS

    grid = speed_grid("2000:30000:1000")
    speeds = resonance_refined(grid, model)
    assert set(grid) <= set(speeds) and speeds.size > grid.size and np.all(np.diff(speeds) > 0)
    first = dy.resonance_speeds(model)["speed_rpm"][0]
    zeta = np.clip(model.modes()["damping_ratio"], 0.005, 0.2)
    checked = 0
    for n, z in zip(first, zeta):  # each predicted resonance and its half-power band are sampled
        band = n * (1 + np.array(RESONANCE_OFFSETS) * z)
        if grid[0] < band.min() and band.max() < grid[-1]:
            assert np.all(np.min(np.abs(speeds[:, None] - band[None, :]), axis=0) < 1e-9 * n)
            checked += 1
    assert checked >= 3


def test_encoder_rotation_adds_the_static_bearing_deflection(geom, K):
    """Statically, the relative rotation r_b1 θ_p − r_b2 θ_g (what shaft encoders read) exceeds
    the dynamic TE (the bodies' approach along the transverse line of action) by the bearing
    deflection 2 F_bt (1/k_radial + tan²βb/k_axial), written out from the bearing balance."""
    model = dy.pair_model(geom, 200.0, K)
    y = model.static_state()
    cb, tb = math.cos(geom.base_helix_angle), math.tan(geom.base_helix_angle)
    f_bt = float(model.static_force[0]) * cb
    bearing = 2 * f_bt * (1 / dy.LOW_FLUCTUATION_BEARING["k_radial"] + tb**2 / dy.LOW_FLUCTUATION_BEARING["k_axial"])
    np.testing.assert_allclose(y[model.n_trans] - (model.G @ y)[0] / cb, bearing, rtol=1e-9)


def test_the_dynamics_functions_take_their_section_whole():
    """Issue 37 item 1: the stage functions restate no default of their declaration. Every key of
    settings.Dynamics / settings.TrainDynamics reaches them through ``**section``, parsed once
    (schema.settings_object), so a key the declaration lacks is refused naming it, and a bad value
    names its key as the study's section does."""
    import inspect

    from gearmesh.datasets.dynamics import build_pair_model
    from gearmesh.schema import key_of, settings_fields
    from gearmesh.settings import Dynamics, TrainDynamics

    for func, cls in ((dynamics_dataset, Dynamics), (build_pair_model, Dynamics), (dynamics_summary, Dynamics),
                      (train_dataset, TrainDynamics)):
        params = inspect.signature(func).parameters
        restated = sorted({key_of(f) for f in settings_fields(cls)} & set(params))
        assert not restated, (func.__name__, restated)
        assert any(p.kind is p.VAR_KEYWORD for p in params.values())
    with pytest.raises(GearmeshInputError, match=r"^torque_Nm"):
        dynamics_dataset(None, torque_Nm=200.0)  # the pair's key is torques_Nm
    with pytest.raises(GearmeshInputError, match=r"^excitation = 'ltca': must be one of"):
        train_dataset(None, excitation="ltca")


def test_the_command_differs_from_a_study_only_by_its_listed_overrides():
    """``gearmesh dynamics`` runs a study's section (commands._dynamics_section): besides its torque,
    gear, speeds and backlash options, the keys it sets are the listed differences (no kept series;
    the excitation tvms, the study's null without an LTCA upstream); everything else is the declared
    default, parsed by the same settings_object as the study's section."""
    from gearmesh.cli import build_parser
    from gearmesh.commands import _dynamics_section
    from gearmesh.schema import defaults, jsonable, settings_object
    from gearmesh.settings import Dynamics

    args = build_parser().parse_args(["dynamics", "config/pairs/helical_z29_71_m5.yaml", "--torque-Nm", "300",
                                      "--speeds", "3000:5000:1000"])
    section = _dynamics_section(args)
    declared = defaults(Dynamics)
    assert section == {"torques_Nm": 300.0, "on": declared["on"], "backlash_um": declared["backlash_um"],
                       "speeds_rpm": {"start": 3000.0, "stop": 5000.0, "step": 1000.0},
                       "sample_speeds_rpm": [], "excitation": "tvms"}
    parsed = jsonable(settings_object(Dynamics, section))
    assert {k: v for k, v in parsed.items() if k not in section} == {k: v for k, v in declared.items()
                                                                     if k not in section}


@pytest.mark.parametrize("section, field", [
    ({"couples": [["low_fluctuation_pair2"]]}, "couples[0]"),  # a couple is [pair, reference]
    ({"couples": []}, "couples"),
    ({"couples": None}, "couples"),  # left out means every pair against the first; null is not a value
    ({"pairs": ["low_fluctuation_pair1"]}, "pairs"),  # an unknown key: the pairs are the dynamics results'
])
def test_the_dynamics_comparison_takes_its_section_whole(section, field):
    """The comparison table parses its ``dynamics_comparison:`` section once (schema.settings_object):
    a bad value and an unknown key are refused by their key before any result is read."""
    from gearmesh.datasets.dynamics import dynamics_comparison_dataset

    with pytest.raises(GearmeshInputError) as info:
        dynamics_comparison_dataset([], **section)
    assert info.value.field == field


@pytest.mark.parametrize("name, unit", [("torque_Nm", "(N m)"), ("static_force_N", "(N)"), ("mesh_frequency_Hz", "(Hz)")])
def test_a_non_positive_boundary_quantity_is_refused_in_its_own_unit(name, unit):
    """The train's torque, static force and mesh frequency share one check; each refusal says its own unit."""
    from gearmesh.datasets.dynamics import positive_quantity

    for bad in (0.0, -1.0, float("nan"), True, "5"):
        with pytest.raises(GearmeshInputError, match=rf"^{name} = .*: must be a positive finite number {re.escape(unit)}$"):
            positive_quantity(name, bad)
    assert positive_quantity(name, 2) == 2.0
