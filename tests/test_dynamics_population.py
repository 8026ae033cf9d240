"""The optimiser's dynamic objective and constraint: the contact-driven dynamics of a population of
micro-geometries (gearmesh.dynamics.population) against the single-pair path of the dynamics
stage, its table convergence, and the penalty it drives."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from gearmesh.contact_model import ContactModel
from gearmesh import impact as im
from gearmesh import optimise as op
from gearmesh.optimise.search import _Evaluator
from gearmesh.cli import main as cli_main
from gearmesh.dynamics import pair_model, resonance_band, simulate
from gearmesh.dynamics.population import (POPULATION_CONTACT, POPULATION_HARMONICS, POPULATION_MESH_ENERGY,
                                          POPULATION_OFFSETS, POPULATION_TABLE, dynamic_factors, population_dynamics)
from gearmesh.gear import Modification, pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.meshforce import mesh_force_table
from gearmesh.surface import MODIFICATION_FIELDS, modification_parameters

from test_optimise import problem_of  # the run settings through the declaration

ROOT = Path(__file__).resolve().parents[1]
SPEEDS = (2000.0, 5000.0, 9000.0)
TORQUES = (400.0, 1000.0)


@pytest.fixture(scope="module")
def pair():
    return load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")


@pytest.fixture(scope="module")
def geom(pair):
    return pair_geometry(pair)


@pytest.fixture(scope="module")
def setup(geom):
    return population_dynamics(geom, TORQUES, SPEEDS, backlash=60e-6)


RELIEF = np.array([[40e-6, 20e-6, 2e-3, 2e-3, 10e-6, 10e-3], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])


def _modified(pair, params):
    mods = tuple(Modification(**{f: float(params[g, k]) for k, f in enumerate(MODIFICATION_FIELDS)}) for g in range(2))
    return pair.with_changes(modification=mods)


def test_population_member_equals_the_pair_with_that_modification_run_alone(pair, setup):
    """The batch path (separations of any modification from one layout, :meth:`TableLayout.gaps`)
    against the dynamics stage's path: the modified pair's own table, model and sweep."""
    lead = np.array([[4e-6, -1e-6]])
    kv = dynamic_factors(setup, RELIEF[None], lead)
    geom = pair_geometry(_modified(pair, RELIEF))
    np.testing.assert_allclose(modification_parameters(geom), RELIEF, atol=1e-15)
    rb1, rb2 = (float(r) for r in geom.base_radius)
    for t, torque in enumerate(TORQUES):  # each torque's table at its mesh misalignment, as the dynamics stage's
        table = mesh_force_table(geom, setup.force_max, POPULATION_TABLE["positions"], POPULATION_TABLE["approaches"],
                                 POPULATION_CONTACT, lead_slope=tuple(lead[0]), static_force=torque / rb1)
        model = pair_model(geom, torque * rb2 / rb1, None, contact=table, backlash=60e-6)
        speeds = np.unique(np.concatenate([SPEEDS, resonance_band(model, SPEEDS[0], SPEEDS[-1], POPULATION_HARMONICS,
                                                                  POPULATION_OFFSETS, POPULATION_MESH_ENERGY)]))
        res = simulate(model, speeds, setup.settings)
        assert kv[0, t] == pytest.approx(res.force_max[0].max() / model.static_force[0], rel=1e-12)


def test_models_share_cached_matrices_only_where_their_inputs_are_equal(geom, setup):
    """The reduced matrices a population reuses (gearmesh.dynamics.model: keyed by the bytes of the
    masses, bearings, mesh geometry and torque) are the ones a fresh reduction gives, read-only,
    shared by two members at one torque and not across torques; the modes cached on a model are
    those recomputed at its mean stiffness; and the GA's evaluator returns for a repeated
    candidate exactly what it returned the first time, evaluating it once."""
    from gearmesh.dynamics import model as dm
    from gearmesh.meshforce import tabulate

    gaps = setup.layout.gaps(np.stack([np.zeros((2, 6)), RELIEF]), np.zeros((2, 2)))
    tables = [tabulate(setup.layout, g, setup.force_max, 16) for g in gaps]
    a, b = (pair_model(geom, 2400.0, None, contact=t, backlash=60e-6) for t in tables)
    c = pair_model(geom, 900.0, None, contact=tables[0], backlash=60e-6)
    assert a.Kr is b.Kr and a.B is b.B and a.f0 is b.f0 and c.f0 is not a.f0
    assert not a.Kr.flags.writeable and a.meshes[0] is not b.meshes[0]
    dm._REDUCED.clear()
    fresh = pair_model(geom, 2400.0, None, contact=tables[0], backlash=60e-6)
    for name in ("Kr", "Cr", "B", "G", "f0"):
        assert fresh.__dict__[name] is not a.__dict__[name]
        np.testing.assert_array_equal(fresh.__dict__[name], a.__dict__[name])
    np.testing.assert_array_equal(b.modes()["eigenvalue"], b.modes(np.array([b.meshes[0].k_mean]))["eigenvalue"])
    model = im.impact_model(geom, ContactModel(points=16), window_positions=24, face_samples=65)
    prob = problem_of(model, population=4, generations=1)
    ev = _Evaluator(prob)
    genes = np.array([[g.low + 0.3 * (g.high - g.low) for g in prob.genes], [g.high for g in prob.genes]])
    first = ev(genes)
    again = ev(np.vstack([genes[::-1], genes[:1]]))
    assert ev.count == 2
    np.testing.assert_equal(again, [first[1], first[0], first[0]])
    np.testing.assert_equal(_Evaluator(prob)(genes[:1]), first[:1])  # a fresh cache: the same values


def test_dynamic_factor_is_converged_in_the_table_and_exceeds_one(geom, setup):
    """The population's coarse table against the dynamics stage's default one (256 x 96 x 200):
    the dynamic factor of the unmodified pair within 0.5 %; a peak mesh force above the static one
    (the mesh force fluctuates) but bounded (no contact loss at these loads)."""
    coarse = dynamic_factors(setup, np.zeros((1, 2, 6)), np.zeros((1, 2)))[0]
    fine = population_dynamics(geom, TORQUES, SPEEDS, backlash=60e-6, contact=POPULATION_CONTACT.with_(points=200),
                               positions=256, approaches=96)
    np.testing.assert_allclose(coarse, dynamic_factors(fine, np.zeros((1, 2, 6)), np.zeros((1, 2)))[0], rtol=5e-3)
    assert np.all((coarse > 1.0) & (coarse < 2.0))


def test_dynamic_objective_and_constraint_drive_the_evaluation(geom):
    """Objective 'dynamic' of the standard gear is the load statistic of its dynamic factors; the
    constraint adds penalty · f_std · (max over torques of K_v / K_v,std / factor − 1)₊ exactly, and
    the standard gear itself is feasible at factor 1."""
    model = im.impact_model(geom, ContactModel(points=16), window_positions=24, face_samples=65)
    common = dict(torques_Nm=list(TORQUES), torque_Nm=1000.0, population=4, generations=1,
                  dynamic_speeds_rpm=list(SPEEDS), backlash_um=60)
    dyn = problem_of(model, objective="dynamic", **common)
    std = dyn.standard
    assert std.objective[0] == pytest.approx(std.value[0, 0].max(), rel=1e-12)
    con = problem_of(model, objective="robust", constraints={"dynamic_factor": 1.0}, **common)
    np.testing.assert_allclose(con.standard.dynamic_factor, std.value[:, 0], rtol=1e-12)
    ev = op.evaluate(con, np.stack([np.zeros((2, 6)), RELIEF]))
    assert ev.violation[0] == 0.0
    ratio = np.max(ev.dynamic_factor[1] / con.standard.dynamic_factor[0])
    f_std = con.standard.objective[0]
    expected = ev.value[1].max() + con.settings.penalty * f_std * max(0.0, ratio - 1.0)
    assert ev.objective[1] == pytest.approx(expected, rel=1e-12)


def test_cli_dynamic_constraint_reports_the_dynamic_factors(tmp_path, capsys):
    code = cli_main(["optimise", str(ROOT / "config/pairs/helical_z29_71_m5.yaml"), "--torques-Nm", "400,1000",
                     "--objective", "robust", "--dynamic-factor", "1", "--dynamic-speeds-rpm", "2000,9000",
                     "--population", "4", "--generations", "1", "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    for row in out["by_torque"]:
        assert row["dynamic_factor"] > 1.0 and row["standard_dynamic_factor"] > 1.0


@pytest.mark.parametrize("flags, field", [(["--dynamic-speeds-rpm", "5000"], "dynamic_speeds_rpm"),
                                          (["--dynamic-factor", "-1"], "--dynamic-factor")])
def test_bad_dynamic_settings_are_refused(flags, field, capsys):
    code = cli_main(["optimise", str(ROOT / "config/pairs/helical_z29_71_m5.yaml"), "--torque-Nm", "1000",
                     "--population", "4", "--generations", "1", *flags])
    assert code == 2
    assert f"gearmesh: error: {field}" in capsys.readouterr().err
