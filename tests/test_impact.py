"""Mesh-in impact (the mesh-in impact paper): the crossing, the two velocity formulations, the reverse-rotation
equation, the energy method and its limits, the scenarios, convergence and refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from gearmesh.contact_model import ContactModel
from gearmesh.cli import main
from gearmesh.errors import GearmeshInputError
from gearmesh.supports import read_supports
from gearmesh.gear import Material, Modification, pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.impact import (SCENARIOS, closed_form_force, energy_balance, fit_power_law, impact_model,
                             impact_response, impact_static, seed_edge_roll, simulate_engagement, vector_velocity)
from gearmesh.io import write_dataset, add_provenance

from conftest import ROOT
from pairs import low_fluctuation_pair1
from test_contact import geometry_or_skip, valid_pairs

ROOT_PAIR = "config/pairs/helical_z29_71_m5.yaml"
POINTS = 24
CONTACT = ContactModel(points=POINTS)


@pytest.fixture(scope="module")
def case():
    """The case pair's mesh alone (its shafts and bearings left out: the seed's rigid gearbox; the
    system deflection's misalignment in the impact model is tested in tests/test_deflection.py)."""
    return pair_geometry(load_pair(ROOT / ROOT_PAIR).with_changes(supports=read_supports({})))


@pytest.fixture(scope="module")
def case_model(case):
    return impact_model(case, CONTACT, window_positions=40, face_samples=129)


def _relieved(geom, tip_um=20.0, length_mm=3.0, crown_um=10.0):
    pair = geom.pair.with_changes(modification=(
        Modification(crowning=crown_um * 1e-6), Modification(tip_relief=tip_um * 1e-6, tip_relief_length=length_mm * 1e-3)))
    return pair_geometry(pair)


def _scenario(st, k=0):
    return SCENARIOS[int(st.scenario[0, k])]


def test_crossing_agrees_with_seed_reverse_rotation_equation(case, case_model, root):
    """Unmodified pairs: the grid crossing and the mesh-in impact paper's (corrected) equation are the same event."""
    st = impact_static(case_model, [100, 400, 1000, 1600])
    for k in range(4):
        assert _scenario(st, k) == "edge"
        ours = -float(st.tau[0, k])
        seed = seed_edge_roll(case, float(st.approach[0, k]))
        assert ours == pytest.approx(seed, rel=1e-7, abs=1e-12)
    other = pair_geometry(load_pair(low_fluctuation_pair1()))
    st = impact_static(impact_model(other, CONTACT, window_positions=40, face_samples=129), [150])
    assert -float(st.tau[0, 0]) == pytest.approx(seed_edge_roll(other, float(st.approach[0, 0])), rel=1e-7)


@pytest.mark.parametrize("driver", ["pinion", "gear"])
def test_vector_form_equals_closing_rate_for_edge_contact(case, driver):
    model = impact_model(case, CONTACT, window_positions=40, face_samples=129, driver=driver)
    st = impact_static(model, [300, 1200])
    st, rs = impact_response(model, st, [4000])
    for k in range(2):
        assert _scenario(st, k) == "edge"
        vec = vector_velocity(model, st, 4000.0, 0, k)
        # pinion tip edge (gear driving): the two agree to 0.4–2.6 % over the shipped pairs; the pinion tip
        # meets the gear flank off the line of action, where the rotation gap and the normal distance are
        # not proportional (docs/impact.md) — stated, not yet explained to round-off
        rel = 1e-4 if driver == "pinion" else 3e-2
        assert vec["transverse_equivalent"] == pytest.approx(float(rs.velocity_transverse[0, k, 0]), rel=rel)
        to_transverse = vec["transverse_equivalent"] / vec["normal_transverse"]  # r_b1/arm, 1 for a pinion involute
        assert vec["distance"] * to_transverse == pytest.approx(float(st.approach[0, k]), rel=rel / 10)


def test_vector_form_agrees_with_closing_rate_to_first_order_in_the_relief_slope(case):
    """Surface contact: the exact closest points lie off the line of action by slope/curvature,
    so the two velocities differ at second order — the relative difference halves with the relief."""
    diffs = []
    for amount in (4.0, 2.0):
        geom = _relieved(case, tip_um=amount, length_mm=4.0, crown_um=0.0)
        model = impact_model(geom, CONTACT, window_positions=40, face_samples=129)
        st = impact_static(model, [10])
        st, rs = impact_response(model, st, [5000])
        assert _scenario(st) == "surface"
        vec = vector_velocity(model, st, 5000.0)
        vt = float(rs.velocity_transverse[0, 0, 0])
        diffs.append(abs(vec["transverse_equivalent"] - vt) / vt)
    assert diffs[0] < 0.2 and diffs[1] < 0.6 * diffs[0]


def test_no_impact_without_load_and_velocity_grows_like_root_of_approach(case_model):
    st = impact_static(case_model, [0.01, 1.0, 100.0])
    st, rs = impact_response(case_model, st, [5000])
    v = rs.velocity_transverse[0, :, 0]
    assert v[0] < 0.02 * v[2]
    # unmodified tip edge: gap ∝ s², so v ∝ √δ
    ratio = (v[2] / v[1]) / math.sqrt(st.approach[0, 2] / st.approach[0, 1])
    assert ratio == pytest.approx(1.0, abs=0.05)


def test_standard_force_rises_with_torque(case_model):
    st = impact_static(case_model, [200, 400, 700, 1000, 1300, 1600])
    st, rs = impact_response(case_model, st, [5000])
    assert np.all(np.diff(rs.force[0, :, 0]) > 0)
    assert np.all(np.diff(rs.force_energy_balance[0, :, 0]) > 0)


def test_closed_form_speed_scaling_is_exact():
    m, v, k_s, n = 2.5, 0.8, 3.0e10, 1.37
    assert closed_form_force(m, 2 * v, k_s, n) / closed_form_force(m, v, k_s, n) == pytest.approx(
        2 ** (2 * n / (n + 1)), rel=1e-13)


def test_energy_balance_equals_closed_form_on_a_pure_power_law():
    k_s, n, m = 4.0e9, 1.6, 2.0
    d = np.geomspace(1e-8, 1e-3, 30)
    f = k_s * d**n
    v = np.array([0.1, 0.5, 1.3])
    force, approach = energy_balance(d, f, 0.5 * m * v**2)
    np.testing.assert_allclose(force, closed_form_force(m, v, k_s, n), rtol=1e-10)
    kk, nn, err = fit_power_law(d, f, approach)
    np.testing.assert_allclose(nn, n, rtol=1e-10)
    np.testing.assert_allclose(kk, k_s, rtol=1e-8)
    assert np.all(err < 1e-10)


def test_relief_turns_edge_into_surface_at_light_load_and_heavy_load_turns_it_back(case):
    model = impact_model(_relieved(case), CONTACT, window_positions=40, face_samples=129)
    st = impact_static(model, [400, 1600])
    assert [_scenario(st, 0), _scenario(st, 1)] == ["surface", "edge"]
    assert st.lte_engagement[0, 0] < st.te_engagement[0, 0] < st.lte_engagement[0, 1]
    standard = impact_static(impact_model(case, CONTACT, window_positions=40, face_samples=129), [400])
    assert _scenario(standard) == "edge"


def test_batch_over_modifications_equals_one_by_one(case, case_model):
    geoms = [_relieved(case, 10.0, 2.0, 5.0), _relieved(case, 25.0, 4.0, 0.0), case]
    params = np.array([[[getattr(m, f) for f in ("root_relief", "tip_relief", "root_relief_length",
                                                 "tip_relief_length", "crowning", "unmodified_lead_length")]
                        for m in g.pair.modification] for g in geoms])
    batch = impact_static(case_model, [800], params)
    for c, g in enumerate(geoms):
        one = impact_static(impact_model(g, CONTACT, window_positions=40, face_samples=129), [800])
        assert batch.tau[c, 0] == pytest.approx(float(one.tau[0, 0]), rel=1e-9, abs=1e-13)
        assert batch.slope[c, 0] == pytest.approx(float(one.slope[0, 0]), rel=1e-6)


@pytest.mark.parametrize("method", ["transition", "fe"])
def test_convergence_in_points_per_line(case, method):
    """F_s as the contact lines get more points: the cantilever's steps shrink (367, 339, 2 N of
    13.2 kN); the FE tooth's are at the level of its tabulated compliance's interpolation from
    12 points on (40, 26, 75 N of 13.0 kN: within 0.6 %, not monotone)."""
    forces = []
    for points in (12, 24, 48, 96):
        model = impact_model(case, ContactModel(points=points, method=method), window_positions=40, face_samples=129)
        st, rs = impact_response(model, impact_static(model, [1000]), [5000])
        forces.append(float(rs.force_energy_balance[0, 0, 0]))
    steps = np.abs(np.diff(forces))
    if method == "transition":
        assert steps[2] < steps[0] and steps[2] < 0.03 * forces[-1]
    else:
        assert np.all(steps < 0.01 * forces[-1])


def test_simulation_starts_in_equilibrium_and_the_entering_pair_takes_load(case_model):
    r = simulate_engagement(case_model, 1000.0, 5000.0, samples=300)
    assert r["mesh_force"][0] == pytest.approx(r["static_force"], rel=2e-3)
    assert np.all(r["entering_force"][r["time"] < r["touch_time"] * 0.99] == 0)
    assert r["entering_peak"] > 0.2 * r["static_force"]


def test_bad_torques_speeds_and_settings_are_refused(case, case_model):
    with pytest.raises(GearmeshInputError, match="torques_Nm"):
        impact_static(case_model, [float("nan")])
    with pytest.raises(GearmeshInputError, match="speeds_rpm"):
        impact_response(case_model, impact_static(case_model, [100]), [-5])
    with pytest.raises(GearmeshInputError, match="driver"):
        impact_model(case, driver="both")
    with pytest.raises(GearmeshInputError, match="added_inertia_kg_m2"):
        impact_model(case, added_inertia_kg_m2=(0.0, -1.0))


@pytest.mark.parametrize("args, field", [(["--torque-Nm", "0", "--speed-rpm", "5000"], "torque_Nm"),
                                         (["--torque-Nm", "100", "--speed-rpm", "inf"], "speed_rpm"),
                                         (["--torque-Nm", "100", "--speed-rpm", "-1"], "speed_rpm")])
def test_cli_refuses_bad_torque_and_speed(root, capsys, args, field):
    assert main(["impact", str(root / ROOT_PAIR), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and field in err[0]


def test_dataset_is_documented(root, tmp_path):
    from gearmesh.datasets.impact import impact_dataset, impact_table_dataset

    pair = load_pair(root / ROOT_PAIR)
    ds = impact_dataset(pair, torques_Nm=[400, 1000], speeds_rpm=[2500, 5000], points=16, simulate_torques_Nm=[1000],
                        variant="standard")
    add_provenance(ds, {"test": True}, "", "test")
    write_dataset(ds, tmp_path / "impact.nc")
    assert set(ds["scenario"].values) == {2}
    table = impact_table_dataset([ds])
    np.testing.assert_allclose(table["reduction_percent"].values, 0.0)


def test_random_modifications_give_a_resolved_impact_with_a_closing_velocity(case_model, case):
    """Invariant over the mesh-in impact paper's design space: every crossing found is pinned down (h = 0) and
    approached from above (closing rate > 0), its force finite and positive."""
    rng = np.random.default_rng(7)
    mn, b = case.pair.normal_module, case.face_width
    n = 24
    params = np.zeros((n, 2, 6))
    params[:, 0] = np.column_stack([rng.uniform(0.001, 0.015, n) * mn, rng.uniform(0.001, 0.015, n) * mn,
                                    rng.uniform(0.1, 0.8, n) * mn, rng.uniform(0.1, 0.8, n) * mn,
                                    rng.uniform(0.001, 0.015, n) * mn, rng.uniform(0.01, 0.5, n) * b])
    st = impact_static(case_model, [400, 1600], params)
    st, rs = impact_response(case_model, st, [5000])
    found = st.scenario > 0
    assert found.mean() > 0.9
    assert np.all(st.slope[found] > 0)
    assert np.all(np.isfinite(rs.force[found]) & (rs.force[found] > 0))
    assert np.all(rs.fit_error[found] < 0.3)


def test_convergence_in_local_slices(case):
    """The entering pair's F–δ curve is converged in its own slices: the energy-balance force
    changes by less than 0.2 % from 150 to 1200 slices, the closed form (its fit) by < 2 %."""
    eb, cf = [], []
    for local in (150, 300, 600, 1200):
        model = impact_model(case, CONTACT, window_positions=40, face_samples=129, local_points=local, local_keep=local)
        st, rs = impact_response(model, impact_static(model, [400]), [5000])
        eb.append(float(rs.force_energy_balance[0, 0, 0]))
        cf.append(float(rs.force[0, 0, 0]))
    assert np.ptp(eb) < 2e-3 * eb[-1]
    assert np.ptp(cf) < 2e-2 * cf[-1]


@pytest.mark.slow
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(valid_pairs(), st.floats(0.05, 1.0))
def test_random_pairs_crossing_equals_seed_equation_and_velocities_agree(pair, load):
    """Over random valid unmodified pairs: the crossing is the mesh-in impact paper's (corrected) reverse-rotation
    solution, the scenario is an edge, and the vector form equals the closing rate."""
    r = np.array(pair.teeth) * pair.normal_module / (2 * math.cos(pair.helix_angle))
    pair = pair.with_changes(bore_radius=tuple(0.3 * r), material=Material(210e9, 0.3, 7850.0))
    geom = geometry_or_skip(pair)
    model = impact_model(geom, ContactModel(points=12), window_positions=24, face_samples=65, local_points=60,
                         local_keep=60)
    # a torque giving a line load of `load` × 300 N/mm
    torque = load * 300e3 * geom.face_width * float(geom.base_radius[0])
    st_ = impact_static(model, [torque])
    assume(st_.scenario[0, 0] > 0)
    assert SCENARIOS[int(st_.scenario[0, 0])] == "edge"
    assert -float(st_.tau[0, 0]) == pytest.approx(seed_edge_roll(geom, float(st_.approach[0, 0])), rel=1e-6, abs=1e-11)
    st_, rs = impact_response(model, st_, [3000])
    vec = vector_velocity(model, st_, 3000.0)
    assert vec["transverse_equivalent"] == pytest.approx(float(rs.velocity_transverse[0, 0, 0]), rel=1e-3)


def test_tabulated_law_inverse_equals_newton_inversion():
    """The universal table of the Palmgren inverse (one per exponent) against the exact Newton
    inversion over nine decades of approach and three of compliance."""
    from gearmesh.ltca_solve import _invert, invert_tabulated

    rng = np.random.default_rng(3)
    c = 10 ** rng.uniform(-9, -5, 20000)
    d = 10 ** rng.uniform(-13, -3, 20000)
    for coef, m in ((4e-7, 0.9), (2e-6, 0.8)):
        q, dq = invert_tabulated(d, c, coef, m)
        q0, dq0 = _invert(d, c, coef, m)
        np.testing.assert_allclose(q, q0, rtol=1e-12)
        np.testing.assert_allclose(dq, dq0, rtol=1e-12)
        np.testing.assert_allclose(c * q + coef * q**m, d, rtol=1e-12)
    q, _ = invert_tabulated(np.array([-1.0, 0.0]), 1e-7, 4e-7, 0.9)
    assert np.all(q == 0)


def test_lead_slopes_per_row_equal_models_built_with_them(case, case_model):
    """Tolerance samples: a lead slope per parameter set in one batch gives what a model built
    with that lead slope gives (the lead deviation is additive to the separations)."""
    params = np.zeros((3, 2, 6))
    params[:, 0] = [0, 20e-6, 0, 2e-3, 8e-6, 10e-3]
    lead = np.array([[0.0, 0.0], [6e-6, -2e-6], [-9e-6, 0.0]])
    batch = impact_static(case_model, [700, 1300], params, lead_slope=lead, engagement=False)
    for c in range(3):
        one = impact_static(impact_model(case, CONTACT, window_positions=40, face_samples=129,
                                         lead_slope=tuple(lead[c])), [700, 1300], params[c:c + 1])
        np.testing.assert_allclose(batch.tau[c], one.tau[0], rtol=1e-9, atol=1e-13)
        np.testing.assert_allclose(batch.slope[c], one.slope[0], rtol=1e-6)
        assert np.array_equal(batch.scenario[c], one.scenario[0])
    assert not np.allclose(batch.tau[1], batch.tau[0])  # the tilt moves the touch


def test_touch_is_where_the_separation_meets_the_solved_approach(case_model):
    """The crossing solved as F*(τ) = F_bt (one inversion per point, no load iteration) against an
    independent exact load solve of the pairs in mesh at the touch roll: the same approach."""
    from gearmesh.impact.static import _approach_at

    params = np.zeros((2, 2, 6))
    params[1, 1] = [0, 20e-6, 0, 3e-3, 0, 0]
    st = impact_static(case_model, [400, 1600], params, engagement=False)
    lead = np.zeros((2, 2))
    solved = _approach_at(case_model, params, lead, st.force[None, :], st.tau[None], others=True)[0]
    np.testing.assert_allclose(st.approach, solved, rtol=1e-9, atol=1e-13)
