"""Manufacturing tolerances: ISO 1328-1 f_Hbeta, the sampler (bounds, seed, Latin hypercube strata,
corners), the deviations applied to a micro-geometry, and each statistic against a hand
computation on a tiny population."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.optimise import load_statistic
from gearmesh.tolerance import (apply_deviations, helix_slope_tolerance, sample_statistic, study_tolerances,
                                tolerance_model, unit_deviations)

from conftest import ROOT

#: Four manufactured gears (rows) of two candidates: values 1, 2, 3, 10 and 5, 5, 5, 5.
POPULATION = np.array([[1.0, 3.0, 2.0, 10.0], [5.0, 5.0, 5.0, 5.0]])


@pytest.fixture(scope="module")
def case():
    return pair_geometry(load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml"))


def test_helix_slope_tolerance_is_iso_1328_formula_10():
    # d = 163.4 mm, b = 42 mm, class 5: 0.05*sqrt(163.4) + 0.35*sqrt(42) + 4 = 0.63914 + 2.26826 + 4 = 6.90740 um
    assert helix_slope_tolerance(0.1634, 0.042, 5) * 1e6 == pytest.approx(
        0.05 * math.sqrt(163.4) + 0.35 * math.sqrt(42) + 4, rel=1e-12)
    assert helix_slope_tolerance(0.1634, 0.042, 5) * 1e6 == pytest.approx(6.90740, abs=1e-5)
    # each class a factor sqrt(2) (ISO 1328-1:2013 5.2: the step between classes)
    for grade in range(1, 11):
        ratio = helix_slope_tolerance(0.4, 0.05, grade + 1) / helix_slope_tolerance(0.4, 0.05, grade)
        assert ratio == pytest.approx(math.sqrt(2), rel=1e-14)


def test_tolerance_model_of_the_case_pair(case):
    tol = tolerance_model(case, grade=6, modification={"tip_relief_um": 2})
    d = 2 * case.reference_radius * 1e3
    expected = [(0.05 * math.sqrt(di) + 0.35 * math.sqrt(42) + 4) * math.sqrt(2) for di in d]
    np.testing.assert_allclose(tol.lead * 1e6, expected, rtol=1e-12)  # 42 mm faces: no rescaling
    assert tol.modification[:, 1].tolist() == [2e-6, 2e-6]
    assert [label for label in tol.labels()] == ["pinion.tip_relief_um", "gear.tip_relief_um", "pinion.lead_slope_deviation_um",
                                                 "gear.lead_slope_deviation_um"]
    only_pinion = tolerance_model(case, grade=6, lead_on=["pinion"])
    assert only_pinion.lead[1] == 0 and only_pinion.lead[0] == tol.lead[0]
    assert tolerance_model(case).dimensions == []
    tiny = load_pair(ROOT / "config/pairs/low_fluctuation_pair1.yaml").with_changes(
        normal_module=1e-4, face_width=(5e-4, 5e-4), bore_radius=(2e-4, 2e-4), center_distance=None)
    with pytest.raises(GearmeshInputError, match="ISO 1328-1 does not cover the pinion's reference diameter"):
        tolerance_model(pair_geometry(tiny), grade=6)  # d1 = 2.9 mm, below the standard's 5 mm


def test_latin_hypercube_lies_in_the_box_fills_every_stratum_and_follows_its_seed():
    u = unit_deviations(3, 8, "lhs", seed=5)
    assert u.shape == (8, 3) and np.all(np.abs(u) <= 1)
    # one sample in each of the 8 equal strata of every dimension
    for j in range(3):
        assert sorted(np.floor((u[:, j] + 1) / 2 * 8).astype(int)) == list(range(8))
    assert np.array_equal(u, unit_deviations(3, 8, "lhs", seed=5))
    assert not np.array_equal(u, unit_deviations(3, 8, "lhs", seed=6))
    assert unit_deviations(3, 0).shape == (0, 3) and unit_deviations(0, 5).shape == (0, 0)


def test_corners_are_the_vertices_all_or_a_seeded_subset():
    all_corners = unit_deviations(3, 100, "corners")
    assert all_corners.shape == (8, 3) and set(np.abs(all_corners).ravel()) == {1.0}
    assert len({tuple(r) for r in all_corners}) == 8
    part = unit_deviations(4, 5, "corners", seed=1)
    assert part.shape == (5, 4) and len({tuple(r) for r in part}) == 5 and set(np.abs(part).ravel()) == {1.0}
    assert np.array_equal(part, unit_deviations(4, 5, "corners", seed=1))
    with pytest.raises(GearmeshInputError, match="sampling"):
        unit_deviations(13, 4, "corners")
    with pytest.raises(GearmeshInputError, match="tolerance_samples"):
        unit_deviations(2, -1)


def test_deviations_keep_zero_at_zero_clip_at_zero_and_tilt_the_lead(case):
    tol = tolerance_model(case, grade=6, modification={"tip_relief_um": 30, "crowning_um": 2})
    params = np.zeros((2, 2, 6))
    params[0, 0] = [0, 20e-6, 0, 2e-3, 8e-6, 0]  # candidate 0 relieved; candidate 1 the standard gear
    units = np.array([[1, 1, 1, 1, 1, 1], [-1, -1, -1, -1, -1, -1]], dtype=float)[:, :len(tol.dimensions)]
    p, lead = apply_deviations(tol, params, (1e-6, 0.0), units)
    assert p.shape == (2, 3, 2, 6) and lead.shape == (2, 3, 2)
    assert np.array_equal(p[:, 0], params) and np.allclose(lead[:, 0], [1e-6, 0.0])  # sample 0: nominal
    assert p[0, 1, 0, 1] == pytest.approx(50e-6) and p[0, 2, 0, 1] == 0.0  # 20 + 30, 20 - 30 clipped at 0
    assert p[0, 1, 0, 4] == pytest.approx(10e-6) and p[0, 2, 0, 4] == pytest.approx(6e-6)
    assert np.all(p[1] == 0)  # no relief designed: none made
    assert lead[0, 1, 0] == pytest.approx(1e-6 + tol.lead[0]) and lead[0, 2, 1] == pytest.approx(-tol.lead[1])


def test_statistics_against_hand_computation():
    x = POPULATION
    np.testing.assert_allclose(sample_statistic(x, "max"), [10, 5])
    np.testing.assert_allclose(sample_statistic(x, "mean"), [4, 5])
    # percentile 50 of 1, 2, 3, 10: halfway between 2 and 3; 90: 3 + 0.7*(10 - 3) (linear, type 7)
    np.testing.assert_allclose(sample_statistic(x, "percentile", 50), [2.5, 5])
    np.testing.assert_allclose(sample_statistic(x, "percentile", 90), [7.9, 5])
    # CVaR 75 %: the worst quarter of four equal atoms is the 10 alone; CVaR 60 %: the worst 40 %
    # is the 10 (25 %) and 15 % of the 3: (0.25*10 + 0.15*3)/0.4
    np.testing.assert_allclose(sample_statistic(x, "cvar", 75), [10, 5])
    np.testing.assert_allclose(sample_statistic(x, "cvar", 60), [(0.25 * 10 + 0.15 * 3) / 0.4, 5])
    np.testing.assert_allclose(sample_statistic(x, "cvar", 0), [4, 5])  # CVaR_0 = the mean
    # load spectrum: worst case, and the duty-cycle mean with time shares 0.5, 0.3, 0.2 (of 1, 3, 2)
    loads = np.array([[1.0, 3.0, 2.0]])
    np.testing.assert_allclose(load_statistic(loads, "max"), [3])
    np.testing.assert_allclose(load_statistic(loads, "mean", (5, 3, 2)), [0.5 * 1 + 0.3 * 3 + 0.2 * 2])
    np.testing.assert_allclose(load_statistic(loads, "mean"), [2])


def test_study_section_is_read_with_its_defaults_and_refuses_unknown_keys(case):
    tol, samples, sampling, seed = study_tolerances(case, {"grade": 5, "samples": 3})
    assert samples == 3 and sampling == "lhs" and seed == 0 and tol.grade == 5
    assert study_tolerances(case, None)[1] == 0
    with pytest.raises(GearmeshInputError) as err:
        study_tolerances(case, {"grades": 5})
    assert err.value.field == "tolerances.grades"
