"""The impact stage's manufactured gears (issue 35, the sign-off table's population basis): every
gear of the population, of the held-out population and of the box worst is a gear built by hand
from its unit deviations and evaluated alone; the nominal gear agrees with the LTCA and rating
stages on their own grid; the box worst is not below any sampled gear; the optimiser sees the
same gears; and every variable is documented."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from gearmesh.contact_model import ContactModel
from gearmesh.datasets.impact import impact_dataset
from gearmesh.datasets.ltca import ltca_dataset
from gearmesh.gear import Modification, pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.impact import impact_model
from gearmesh.robust import CRITERIA, gear_criteria
from gearmesh.surface import MODIFICATION_FIELDS, fit_modifications, modification_parameters
from gearmesh.tolerance import study_tolerances

from conftest import ROOT

TORQUES = (400.0, 1000.0)
SPEED = 5000.0
POINTS = 16
TOLERANCES = {"grade": 6, "modification": {"tip_relief_um": 2, "crowning_um": 2}, "samples": 3, "seed": 0,
              "sampling": "lhs", "population": 3, "heldout": 2, "heldout_seed": 1}
SETS = ("box_worst", "population", "heldout")


@pytest.fixture(scope="module")
def relief():
    """The default study's hand-chosen variant: gear tip relief and pinion crowning."""
    pair = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    return pair.with_changes(modification=(Modification(crowning=10e-6),
                                           Modification(tip_relief=20e-6, tip_relief_length=3e-3)))


@pytest.fixture(scope="module")
def impact(relief):
    return impact_dataset(relief, torques_Nm=TORQUES, speeds_rpm=(SPEED,), design_speed_rpm=SPEED, points=POINTS,
                          method="improved", tolerances=TOLERANCES, variant="relief")


def _by_hand(geom, units):
    """The manufactured gear of unit deviations ``units`` (one per toleranced dimension, ±1 its
    tolerance), built from the tolerance model's definition: (2, 6) parameters, (2,) lead slopes (m)."""
    tol = study_tolerances(geom, TOLERANCES)[0]
    params, lead = modification_parameters(geom), np.array(geom.pair.deviations.lead_slope, dtype=float)
    out = params.copy()
    for x, (kind, g, k) in zip(units, tol.dimensions):
        if kind == "lead":
            lead[g] += x * tol.lead[g]
        elif params[g, k] > 0:  # a parameter not designed is not made
            out[g, k] = max(params[g, k] + x * tol.modification[g, k], 0.0)
    return fit_modifications(geom, out)[0], lead


def _alone(relief, params, lead):
    """The criteria of one manufactured gear from an impact model built for that gear alone (its
    pair file's modification and lead deviations), not from the stage's batch."""
    made = relief.with_changes(modification=tuple(Modification(**dict(zip(MODIFICATION_FIELDS, row)))
                                                  for row in params))
    made = made.with_changes(deviations=replace(made.deviations, lead_slope=tuple(float(v) for v in lead)))
    model = impact_model(pair_geometry(made), ContactModel(points=POINTS, method="improved"))
    return gear_criteria(model, model.params(), np.asarray(model.lead_slope, dtype=float)[None], TORQUES,
                         SPEED).values[0]  # (T, criteria)


@pytest.mark.slow
def test_every_manufactured_gear_is_its_own_impact_model(relief, impact):
    """Independent path for every gear of the population and the held-out population: the gear
    built by hand from its stored unit deviations is the gear the stage stored (modification and
    lead slopes), and its criteria from a model of that gear alone are the stage's."""
    geom = pair_geometry(relief)
    assert impact.sizes["population_gear"] == TOLERANCES["population"] + 1  # gear 0 the nominal
    assert impact.sizes["heldout_gear"] == TOLERANCES["heldout"]
    assert np.all(impact["population_units"].values[0] == 0.0)
    for prefix in ("population", "heldout"):
        for g in range(impact.sizes[f"{prefix}_gear"]):
            params, lead = _by_hand(geom, impact[f"{prefix}_units"].values[g])
            np.testing.assert_allclose(impact[f"{prefix}_modification"].values[g], params, rtol=1e-12, atol=1e-15)
            np.testing.assert_allclose(impact[f"{prefix}_lead_slope"].values[g], lead, rtol=1e-12, atol=1e-15)
            want = _alone(relief, params, lead)
            for k, name in enumerate(CRITERIA):
                np.testing.assert_allclose(impact[f"{prefix}_{name}"].values[g], want[:, k], rtol=1e-7,
                                           atol=1e-9 * np.abs(want[:, k]).max(), err_msg=f"{prefix} {g} {name}")
    # the population is not the nominal gear repeated: the lead deviations move the root stress
    root = impact["population_peak_root_stress"].values
    assert np.ptp(root, axis=0).min() > 0.01 * root.min()


@pytest.mark.slow
def test_the_box_worst_is_a_gear_of_the_box_and_above_every_sampled_gear(relief, impact):
    """Each criterion's box worst is the value of the gear stored beside it (evaluated alone), that
    gear lies in the box (unit deviations within ±1), and no gear of either population exceeds it."""
    for name in ("impact_force", "lte_order_1", "peak_root_stress"):
        for t in range(len(TORQUES)):
            units = impact[f"box_worst_units_{name}"].values[t]
            assert np.all(np.abs(units) <= 1.0 + 1e-12)
            want = _alone(relief, impact[f"box_worst_modification_{name}"].values[t],
                          impact[f"box_worst_lead_slope_{name}"].values[t])
            k = CRITERIA.index(name)
            assert impact[f"box_worst_{name}"].values[t] == pytest.approx(want[t, k], rel=1e-7, abs=1e-12), name
    for k, name in enumerate(CRITERIA):
        sampled = np.maximum(impact[f"population_{name}"].max("population_gear"),
                             impact[f"heldout_{name}"].max("heldout_gear")).values
        assert np.all(impact[f"box_worst_{name}"].values >= sampled * (1 - 1e-9)), name


@pytest.mark.slow
def test_the_nominal_gear_agrees_with_the_ltca_and_rating_stages(relief):
    """Gear 0 of the population on the impact model's mesh-cycle grid against the LTCA and rating
    stages on their own grid (the same contact law and tooth model, other roll positions), at the
    study's 50 points per line: held to 1.5 % (TE order 1, pressures, root stress) and 2 % (order 2)."""
    from gearmesh.datasets.rating import rating_dataset

    impact = impact_dataset(relief, torques_Nm=TORQUES, speeds_rpm=(SPEED,), design_speed_rpm=SPEED, points=50,
                            method="improved", tolerances={**TOLERANCES, "population": 1, "heldout": 0})
    lt = ltca_dataset(relief, torques_Nm=TORQUES, positions=64, points=50, method="improved")
    rating = rating_dataset(relief, speed_rpm=SPEED, application_factor=1.0, life_hours=None, method="ltca", ltca=lt)
    nominal = impact.isel(population_gear=0)
    region, pressure = lt["region"].values, np.nan_to_num(lt["contact_pressure"].values)
    for name, want, rtol in (
            ("lte_order_1", lt["lte_harmonics"].values[:, 0], 0.015),
            ("lte_order_2", lt["lte_harmonics"].values[:, 1], 0.02),
            ("peak_flank_pressure", np.where(region == 1, pressure, 0.0).reshape(2, -1).max(axis=1), 0.015),
            ("peak_edge_pressure", np.where(region >= 2, pressure, 0.0).reshape(2, -1).max(axis=1), 0.015),
            ("peak_root_stress", rating["peak_root_stress"].values.max(axis=1), 0.015)):
        got = nominal[f"population_{name}"].values
        assert np.all(np.abs(got / want - 1.0) <= rtol), (name, got, want)


def test_the_manufactured_gears_are_documented_and_absent_without_tolerances(relief, impact):
    names = [v for v in impact.variables if str(v).startswith(SETS)]
    assert {f"{s}_{c}" for s in SETS for c in CRITERIA} <= set(names)
    for name in [*names, "criterion", "judged_torque", "tolerance_dimension", "parameter"]:
        assert impact[name].attrs["units"] and impact[name].attrs["long_name"], name
    assert impact["population_lte_order_2"].dims == ("population_gear", "judged_torque")
    bare = impact_dataset(relief, torques_Nm=TORQUES[:1], speeds_rpm=(SPEED,), design_speed_rpm=SPEED,
                          points=POINTS, method="improved")
    assert not [v for v in bare.variables if str(v).startswith(SETS)]


@pytest.mark.slow
def test_the_optimiser_sees_the_same_manufactured_gears(relief, impact):
    """One answer through every door: the optimiser's criteria over its samples (criteria_over_samples,
    statistic max, the study's seeded Latin hypercube of the same size) for the same modification,
    with the same impact and tolerances sections, equal the impact stage's population reduced by max."""
    from gearmesh.datasets.optimise import run_problem
    from gearmesh.optimise import evaluate

    base = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    prob = run_problem(base, torques_Nm=list(TORQUES), tolerance_statistic="max", population=4, generations=1,
                       speed_rpm=SPEED, constraints={"root_stress_factor": 1.1, "criteria_over_samples": True},
                       impact={"method": "improved", "points": POINTS}, tolerances=TOLERANCES)
    crit = evaluate(prob, modification_parameters(pair_geometry(relief))[None]).criteria
    worst = {name: impact[f"population_{name}"].max("population_gear").values for name in CRITERIA}
    for k, name in enumerate(f"lte_order_{o}" for o in (1, 2, 3)):
        np.testing.assert_allclose(crit.te_harmonics[0][:, k], worst[name], rtol=1e-9, atol=0, err_msg=name)
    for attr, name in (("flank_pressure", "peak_flank_pressure"), ("edge_pressure", "peak_edge_pressure"),
                       ("root_stress", "peak_root_stress")):
        np.testing.assert_allclose(getattr(crit, attr)[0], worst[name], rtol=1e-9, atol=0, err_msg=name)
