"""LTCA: equilibrium, exact complementarity, agreement with the stiffness stage, symmetry,
convergence, the contact law and refusals."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from pairs import low_fluctuation_pair1
from scipy.optimize import brentq

from gearmesh.contact_model import ContactModel
from gearmesh.body import mesh_body_compliance
from gearmesh import stiffness as st
from gearmesh.datasets.ltca import ltca_dataset, ltca_summary
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import Modification, pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict, pair_to_dict
from gearmesh.io import check_documented
from gearmesh.supports import read_supports
from gearmesh.ltca import ltca
from gearmesh.ltca_solve import solve_contact
from gearmesh.ltca_model import PALMGREN_COEFFICIENT, contact_law, ltca_model

ROOT = Path(__file__).resolve().parents[1]
MOD = (Modification(tip_relief=20e-6, tip_relief_length=3e-3, crowning=10e-6), Modification())


@pytest.fixture(scope="module")
def helical_z29_71_m5():
    """The case pair without its shafts and bearings: the mesh alone, so that the separations are the
    grid's (the system deflection's misalignment per torque is tested in tests/test_deflection.py)."""
    return load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml").with_changes(supports=read_supports({}))


@pytest.fixture(scope="module")
def modified(helical_z29_71_m5):
    return ltca(pair_geometry(helical_z29_71_m5.with_changes(modification=MOD)), [400.0, 1000.0, 1600.0])


def test_loads_sum_to_the_applied_force_and_complementarity_holds(modified, helical_z29_71_m5):
    res = modified
    c_body = mesh_body_compliance(pair_geometry(helical_z29_71_m5))  # the solid discs in series: δ = δ_teeth + c_body F
    total = res.load.sum(axis=(2, 3))
    assert np.allclose(total, res.force[:, None], rtol=1e-11, atol=0)
    assert np.all(res.load >= 0)
    g = res.grid.gap
    law, comp = res.model.law, res.model.compliance[:-1]
    for k in range(res.torque.size):
        q = res.load[k]
        delta = res.lte[k][:, None, None] - c_body * res.force[k]
        loaded = q > 0
        # zero gap where loaded: δ − g = c q + A q^0.9
        resid = delta - g - (comp * q + law.coefficient * q**law.exponent)
        assert np.max(np.abs(resid[loaded])) < 1e-12 * float(res.lte[k].max()) + 1e-16
        # open (or just closing) where unloaded: g ≥ δ
        free = np.isfinite(g) & ~loaded
        assert np.all((g - delta)[free] >= -1e-15)


def test_lte_exceeds_te_and_grows_with_torque(modified):
    assert np.all(modified.lte > modified.tca.te[None, :])
    assert np.all(np.diff(modified.lte, axis=0) > 0)
    # Palmgren's law hardens: the loaded mesh stiffness rises with torque
    assert np.all(np.diff(modified.stiffness.mean(axis=1)) > 0)


def test_linearised_lte_equals_F_over_K_of_the_stiffness_stage(helical_z29_71_m5):
    """Same compliances (the stiffness stage's pair table, Hertz linear, same slices and
    positions, no tip-edge candidates): LTE = F/K(φ) to round-off and dF/dδ = K; against the
    stage's default (200 clipped slices) within 1.5 % (the 50-point slice rule's O(Δz) ends)."""
    geom = pair_geometry(helical_z29_71_m5)
    model = ltca_model(geom, 64, ContactModel(points=50, contact_law="linear", extension=0.0))
    res = ltca(geom, [1000.0], model=model)
    K = st.mesh_stiffness(geom, n_positions=64, n_slices=50, rule="centre", pair_table=model.pair_table)
    assert np.allclose(res.lte[0], st.lste(K, 1000.0), rtol=1e-12, atol=0)
    assert np.allclose(res.stiffness[0], K.K, rtol=1e-12)
    K_default = st.mesh_stiffness(geom, n_positions=64)
    assert np.max(np.abs(res.lte[0] / st.lste(K_default, 1000.0) - 1)) < 0.015


def test_tangent_stiffness_is_dF_ddelta(helical_z29_71_m5):
    geom = pair_geometry(helical_z29_71_m5.with_changes(modification=MOD))
    model = ltca_model(geom, 8, ContactModel(points=30))
    a, b = ltca(geom, [1000.0, 1000.0 * (1 + 1e-6)], model=model).lte
    mid = ltca(geom, [1000.0 * (1 + 0.5e-6)], model=model)
    fd = 1000.0e-6 / geom.base_radius[0] / (b - a)
    assert np.allclose(mid.stiffness[0], fd, rtol=1e-4)


def test_solver_against_bisection_reference():
    """One position, random gaps and compliances, Palmgren law: δ from plain bisection with
    each load by brentq, no Newton anywhere."""
    rng = np.random.default_rng(7)
    gap = rng.uniform(0, 20e-6, size=(1, 40))
    gap[0, :5] = np.nan
    comp = rng.uniform(2e-9, 6e-9, size=(1, 40))
    pair = pair_from_dict(low_fluctuation_pair1())
    law = contact_law(pair_geometry(pair), 0.4e-3)
    force = np.array([3000.0])
    q, delta, k, _ = solve_contact(gap, comp, force, law)

    def loads(dl):
        out = np.zeros(40)
        for i in range(40):
            d = dl - gap[0, i]
            if np.isfinite(d) and d > 0:
                out[i] = brentq(lambda x: comp[0, i] * x + law.coefficient * x**0.9 - d, 0, d / comp[0, i], xtol=1e-14)
        return out

    ref = brentq(lambda dl: loads(dl).sum() - force[0], np.nanmin(gap), np.nanmin(gap) + 1e-3, xtol=1e-17, rtol=1e-15)
    assert delta[0] == pytest.approx(ref, rel=1e-10)
    assert np.allclose(q[0], loads(ref), rtol=1e-7, atol=1e-9)


def test_palmgren_law_matches_the_published_formula():
    """δ_n = 3.84e-5 Q^0.9 / l^0.8 (mm, N) for a whole line of length l under Q, transverse /cos βb."""
    geom = pair_geometry(pair_from_dict(low_fluctuation_pair1()))
    cb = math.cos(geom.base_helix_angle)
    dz = geom.face_width / 50
    law = contact_law(geom, dz)
    w = 150.0  # N/mm, normal load per unit contact length
    q = w * 1e3 * dz  # transverse load of the point
    l_mm = geom.face_width / cb * 1e3
    e_scale = (207e9 / 0.91) / (geom.pair.material.youngs_modulus / (1 - geom.pair.material.poisson_ratio**2))
    delta_n_mm = PALMGREN_COEFFICIENT * (w * e_scale * l_mm) ** 0.9 / l_mm**0.8
    assert law.coefficient * q**law.exponent == pytest.approx(delta_n_mm * 1e-3 / cb, rel=1e-12)
    assert law.force_exponent == pytest.approx(1 / 0.9)


@pytest.mark.parametrize("beta", [0.0])
def test_symmetric_crowning_gives_a_symmetric_pattern_for_spur(beta):
    pair = pair_from_dict(low_fluctuation_pair1(helix_angle_deg=beta))
    geom = pair_geometry(pair.with_changes(modification=(Modification(crowning=10e-6, unmodified_lead_length=4e-3),
                                                         Modification(crowning=5e-6))))
    res = ltca(geom, [150.0], 16, ContactModel(points=40))
    load = res.load[0]
    assert np.allclose(load, load[..., ::-1], rtol=1e-9, atol=1e-9 * load.max())
    centre = load[..., 19:21].sum(axis=-1)
    assert np.all(centre.max(axis=1) > load[..., :2].sum(axis=-1).max(axis=1))  # peaks at the centre


def _asymmetry(beta):
    pair = pair_from_dict(low_fluctuation_pair1(helix_angle_deg=beta))
    geom = pair_geometry(pair.with_changes(modification=(Modification(crowning=10e-6), Modification())))
    res = ltca(geom, [150.0], 16, ContactModel(points=40))
    pattern = res.line_load[0].max(axis=(0, 1))  # envelope over the cycle at each z
    return np.max(np.abs(pattern - pattern[::-1])) / pattern.max()


def test_crowned_pattern_becomes_symmetric_as_beta_goes_to_zero():
    a = [_asymmetry(b) for b in (8.0, 2.0, 0.5)]
    assert a[0] > a[1] > a[2] and a[2] < 0.05


def test_convergence_in_points_per_line(helical_z29_71_m5):
    geom = pair_geometry(helical_z29_71_m5.with_changes(modification=MOD))
    out = {}
    for n in (25, 50, 100, 200):
        res = ltca(geom, [1000.0], 16, ContactModel(points=n))
        out[n] = (res.lte[0].mean(), res.max_line_load[0].max(), res.stiffness[0].mean())
    for k in range(3):
        d1 = abs(out[50][k] - out[25][k])
        d3 = abs(out[200][k] - out[100][k])
        assert d3 < d1
        assert d3 / abs(out[200][k]) < 5e-3


def test_gear_torque_is_converted_by_the_ratio(helical_z29_71_m5):
    geom = pair_geometry(helical_z29_71_m5)
    a = ltca(geom, [1000.0], 8, ContactModel(points=20))
    b = ltca(geom, [1000.0 * 71 / 29], 8, ContactModel(points=20), on="gear")
    assert np.allclose(a.lte, b.lte, rtol=1e-12) and b.torque[0] == pytest.approx(1000.0)


def test_unmodified_pair_meets_with_an_edge_and_modification_delays_it(helical_z29_71_m5):
    std = ltca(pair_geometry(helical_z29_71_m5), [400.0], 8, ContactModel(points=30))
    assert std.lte_at_engagement[0] > std.tca.te_next_pair_at_engagement == 0.0
    assert std.corner_load.max() > 0  # tip edges carry load outside the active zone
    gear_relief = (Modification(), Modification(tip_relief=30e-6, tip_relief_length=4e-3))
    mod = ltca(pair_geometry(helical_z29_71_m5.with_changes(modification=gear_relief)), [400.0], 8,
               ContactModel(points=30))
    assert mod.lte_at_engagement[0] < mod.tca.te_next_pair_at_engagement  # surface-to-surface entry


@pytest.mark.parametrize("modification", [
    {}, {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 3}, "pinion": {"crowning_um": 10}},
    {"pinion": {"tip_relief_um": 12, "tip_relief_length_mm": 2, "root_relief_um": 15, "root_relief_length_mm": 2.5}},
    {"gear": {"tip_relief_um": 35, "tip_relief_length_mm": 4}}], ids=["standard", "relief", "pinion", "deep"])
def test_the_entry_is_one_answer_with_the_impact_stage(helical_z29_71_m5, modification):
    """Whether the entering pair touches before A is one answer in the LTCA (the mesh-in impact
    paper's criterion on the teeth's LTE at φ1A) and the impact stage (its search for the first
    touch, an independent formulation): the gear bodies' deflection, in series with the teeth in
    the LTCA, turns the entering tooth with the loaded ones and is left out of the criterion, so the
    teeth's LTE at φ1A is the impact stage's, and the two agree on the timing wherever the margin is
    above the grids' resolution (0.3 µm)."""
    from gearmesh.datasets.impact import impact_dataset

    # solid discs held at the bore (described: hub = bore) on rigid supports: a body term in the LTE
    pair = pair_from_dict({**pair_to_dict(helical_z29_71_m5), "modification": modification or None, "hub_diameter_mm": [60, 140],
                           "bearing_radial_stiffness_N_per_um": "rigid", "bearing_axial_stiffness_N_per_um": "rigid"})
    torques = [400.0, 1000.0, 1600.0]
    ltca_ds = ltca_dataset(pair, torques_Nm=torques, method="transition", positions=64, points=50)
    impact = impact_dataset(pair, torques_Nm=torques, method="transition", simulate_torques_Nm=[],
                            design_torque_Nm=None, load_window_step_Nm=None)
    teeth = ltca_ds["lte_teeth_at_engagement"].values
    np.testing.assert_allclose(teeth, impact["lte_at_engagement"].values, rtol=1e-6)
    body = mesh_body_compliance(pair_geometry(pair)) * ltca_ds["force"].values
    assert np.all(body > 0)  # the case pair's solid discs: the LTE holds a body term the criterion leaves out
    np.testing.assert_allclose(ltca_ds["lte_at_engagement"].values - teeth, body, rtol=1e-9)
    margin = teeth - float(ltca_ds["te_next_pair_at_engagement"])
    clear = np.abs(margin) > 0.3e-6
    assert clear.sum() >= 2
    early = ltca_ds["touches_before_engagement"].values.astype(bool)
    np.testing.assert_array_equal(early, margin > 0)
    np.testing.assert_array_equal(early[clear], impact["roll_before_engagement"].values[clear] > 0)
    # touching before A is off the line of action: on the mating gear's tip edge (the impact's scenario)
    assert np.all(impact["scenario"].values[early & clear] == 2)


def test_bad_torques_and_modifications_are_refused(helical_z29_71_m5):
    for bad in (0.0, -5.0, float("nan"), float("inf"), [], [100.0, -1.0], "100", True, None):
        with pytest.raises(GearmeshInputError, match="torques_Nm"):
            ltca_dataset(helical_z29_71_m5, torques_Nm=bad, positions=8, points=5)
    with pytest.raises(GearmeshInputError, match="torque_Nm"):
        ltca_summary(helical_z29_71_m5, -1.0)
    with pytest.raises(GearmeshInputError, match="on"):
        ltca_dataset(helical_z29_71_m5, torques_Nm=[100.0], on="wheel", positions=8, points=5)
    with pytest.raises(GearmeshInputError, match="corner_extension"):
        ltca_dataset(helical_z29_71_m5, torques_Nm=[100.0], corner_extension=-0.1, positions=8, points=5)
    with pytest.raises(GearmeshInputError, match="points"):
        ltca_dataset(helical_z29_71_m5, torques_Nm=[100.0], positions=8, points=0)
    with pytest.raises(GearmeshInputError, match="contact_law"):
        ltca_dataset(helical_z29_71_m5, torques_Nm=[100.0], contact_law="hertz", positions=8, points=5)
    neg = helical_z29_71_m5.with_changes(modification=(Modification(), Modification(root_relief=-1e-6, root_relief_length=1e-3)))
    with pytest.raises(GearmeshInputError, match="modification.gear.root_relief_um"):
        ltca_dataset(neg, torques_Nm=[100.0], positions=8, points=5)
    crown = helical_z29_71_m5.with_changes(modification=(Modification(crowning=5e-6, unmodified_lead_length=50e-3), Modification()))
    with pytest.raises(GearmeshInputError, match="unmodified_lead_length_mm"):
        ltca_dataset(crown, torques_Nm=[100.0], positions=8, points=5)


def test_dataset_and_summary(helical_z29_71_m5):
    ds = ltca_dataset(helical_z29_71_m5.with_changes(modification=MOD), torques_Nm=[500.0, 1000.0], positions=8, points=20)
    check_documented(ds)
    assert ds["load"].dims == ("torque", "position", "line", "point")
    total, force = xr.broadcast(ds["load"].sum(("line", "point")), ds["force"])
    assert np.allclose(total.values, force.values, rtol=1e-11)
    summary = ltca_summary(helical_z29_71_m5, 1000.0)
    for key in ("te_peak_to_peak_um", "lte_mean_um", "lte_peak_to_peak_um", "max_line_load_normal_N_per_mm",
                "loaded_mesh_stiffness_mean_transverse_N_per_um"):
        assert math.isfinite(summary[key])
    assert summary["te_peak_to_peak_um"] == 0.0 and summary["lte_mean_um"] > 0


def test_the_contact_commands_differ_from_a_study_only_by_their_listed_overrides(helical_z29_71_m5):
    """``gearmesh ltca`` and ``gearmesh impact`` run a study's section (commands._ltca_section,
    commands._impact_section): given only their operating point, every key they set is the declared
    default, and what they leave out is the map the one operating point replaces (and, for the LTCA,
    nothing else but the corner extension's default). The one-point functions refuse a map key
    rather than parse it and ignore it."""
    from gearmesh.cli import build_parser
    from gearmesh.commands import _impact_section, _ltca_section
    from gearmesh.datasets.impact import _MAP_KEYS, impact_summary
    from gearmesh.schema import defaults, jsonable
    from gearmesh.settings import Impact, Ltca

    path = str(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    for command, section_of, cls, left_out in (
            (["ltca", path, "--torque-Nm", "1000"], _ltca_section, Ltca, {"torques_Nm", "corner_extension"}),
            (["impact", path, "--torque-Nm", "1000", "--speed-rpm", "5000"], _impact_section, Impact,
             set(_MAP_KEYS) | {"contact_law", "method", "corner_extension", "added_inertia_kg_m2",
                               "window_positions", "face_samples"})):
        section, declared = section_of(build_parser().parse_args(command)), defaults(cls)
        assert set(section) == set(declared) - left_out, command[0]
        assert {k: jsonable(v) for k, v in section.items()} == {k: declared[k] for k in section}, command[0]
    with pytest.raises(GearmeshInputError, match="torques_Nm"):
        ltca_summary(helical_z29_71_m5, 1000.0, torques_Nm=[1000.0])
    with pytest.raises(GearmeshInputError, match="speeds_rpm"):
        impact_summary(helical_z29_71_m5, 1000.0, 5000.0, speeds_rpm=[5000.0])
