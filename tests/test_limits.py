"""The package enforces its own validity limits (issue 20): the functions that compute refuse an
out-of-range load, speed, tooth count or work size with one GearmeshInputError naming the field,
before they allocate anything, so a notebook user, the command line and the workflow get the
same refusal. Memory is measured with tracemalloc (numpy reports its buffers to it); no timing."""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest

from gearmesh.datasets.dynamics import build_pair_model, dynamics_dataset
from gearmesh.datasets.impact import impact_dataset
from gearmesh.datasets.ltca import ltca_dataset, tca_dataset
from gearmesh.datasets.stiffness import stiffness_dataset
from gearmesh.dynamics import SolverSettings, step_plan
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.limits import MAX_TEETH
from gearmesh.pairfile import pair_from_dict
from gearmesh.limits import MAX_RIM_STRESS, STEEL_DENSITY, check_speeds, max_speed_rpm
from pairs import low_fluctuation_pair1

#: Most memory (bytes) a refusal may trace: the pair geometry and the checks, nothing of the grid.
REFUSAL_BYTES = 50e6


@pytest.fixture(scope="module")
def pair():
    return pair_from_dict(low_fluctuation_pair1())


def _refused(call, field: str, *words: str) -> str:
    """Run ``call``; it must raise GearmeshInputError on ``field`` whose message holds ``words``,
    having traced less than :data:`REFUSAL_BYTES`. Returns the message."""
    tracemalloc.start()
    try:
        with pytest.raises(GearmeshInputError) as info:
            call()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert info.value.field == field, str(info.value)
    message = str(info.value)
    assert "\n" not in message
    for word in words:
        assert word in message, message
    assert peak < REFUSAL_BYTES, f"{peak / 1e6:.0f} MB traced before the refusal"
    return message


@pytest.mark.parametrize("stage", ["ltca", "impact", "dynamics"])
def test_an_absurd_torque_is_refused_by_every_stage_that_loads_the_mesh(pair, stage):
    """1e12 N m gave an LTE of ~7 km (LTCA), a NaN force (impact) and a TE std of 516 m after 38 s
    (dynamics); each is now the contact-stress limit of gearmesh.limits."""
    call = {"ltca": lambda: ltca_dataset(pair, torques_Nm=(1e12,)),
            "impact": lambda: impact_dataset(pair, torques_Nm=(1e12,)),
            "dynamics": lambda: dynamics_dataset(pair, torques_Nm=1e12)}[stage]
    _refused(call, "torques_Nm", "contact stress", "ISO 6336")


def test_the_refused_torque_is_named_by_its_index(pair):
    _refused(lambda: ltca_dataset(pair, torques_Nm=(100.0, 1e12)), "torques_Nm[1]", "1000000000000.0")


def test_the_stiffness_lste_torque_and_the_train_load_are_limited(pair):
    _refused(lambda: stiffness_dataset(pair, slices=20, positions=24, torque_Nm=1e12), "torque_Nm", "contact stress")
    _refused(lambda: build_pair_model(pair, torque_Nm=1e12), "torque_Nm", "contact stress")


def test_a_slice_grid_beyond_memory_is_refused_before_allocation(pair):
    """slices=10**9 took 15 GB and 28 s before a MemoryError."""
    _refused(lambda: stiffness_dataset(pair, slices=20000, positions=100000), "slices", "slice-positions", "at most")
    _refused(lambda: stiffness_dataset(pair, slices=10**9), "slices", "at most")  # the declared bound of slices
    _refused(lambda: stiffness_dataset(pair, slices=2.5), "slices", "integer")


def test_a_contact_grid_beyond_memory_is_refused_before_allocation(pair):
    _refused(lambda: tca_dataset(pair, positions=10000, points=2000), "points", "contact candidates")
    _refused(lambda: ltca_dataset(pair, torques_Nm=(100.0,), positions=5000, points=5000), "points")


@pytest.mark.parametrize("teeth", [10**9, 2**63, 10**400])
def test_an_absurd_tooth_count_names_the_teeth(teeth):
    """10**9 teeth blamed a profile shift, 2**63 reported eps_alpha = -610, 10**400 raised a raw
    OverflowError: each is now the teeth limit, compared as an integer (no conversion to float)."""
    message = _refused(lambda: pair_from_dict(low_fluctuation_pair1(teeth=[teeth, 49])), "teeth[0]", f"at most {MAX_TEETH}")
    assert len(message) < 400


def test_the_largest_tooth_count_is_accepted():
    geom = pair_geometry(pair_from_dict(low_fluctuation_pair1(teeth=[29, MAX_TEETH], face_width_mm=20)))
    assert geom.eps_alpha > 1


def test_a_speed_beyond_the_rim_strength_is_refused_with_the_right_advice(pair):
    """dynamics_dataset(speeds_rpm=[1e9]) advised "raise the speed"."""
    message = _refused(lambda: dynamics_dataset(pair, speeds_rpm=[1e9]), "speeds_rpm", "lower the speed",
                       "MAX_RIM_STRESS")
    assert "raise" not in message
    _refused(lambda: dynamics_dataset(pair, speeds_rpm=[1000.0], sample_speeds_rpm=[1e7]), "sample_speeds_rpm")
    _refused(lambda: impact_dataset(pair, torques_Nm=(100.0,), speeds_rpm=(1000.0, 1e6)), "speeds_rpm[1]",
             "lower the speed")


def test_the_speed_limit_is_the_hoop_stress_of_the_faster_tip_circle(pair):
    """Independent of max_speed_rpm: rho (omega r_a)^2 = MAX_RIM_STRESS on the faster tip circle at
    the limit, below it on the other; the limit scales as 1/sqrt(rho); the gear's limit is the
    pinion's times z1/z2."""
    geom = pair_geometry(pair)
    n1 = max_speed_rpm(geom)
    omega1 = n1 * math.pi / 30
    z1, z2 = pair.teeth
    stress = [STEEL_DENSITY * (omega1 * float(geom.tip_radius[0])) ** 2,
              STEEL_DENSITY * (omega1 * z1 / z2 * float(geom.tip_radius[1])) ** 2]
    assert max(stress) == pytest.approx(MAX_RIM_STRESS, rel=1e-12)
    assert min(stress) < MAX_RIM_STRESS
    assert max_speed_rpm(geom, "gear") == pytest.approx(n1 * z1 / z2, rel=1e-12)
    light = pair_geometry(pair_from_dict(low_fluctuation_pair1(material={"youngs_modulus_GPa": 210, "poisson_ratio": 0.3,
                                                                 "density_kg_m3": STEEL_DENSITY / 4})))
    assert max_speed_rpm(light) == pytest.approx(2 * n1, rel=1e-12)
    check_speeds(geom, [n1 * (1 - 1e-9)], "speeds_rpm")
    with pytest.raises(GearmeshInputError):
        check_speeds(geom, [n1 * (1 + 1e-9)], "speeds_rpm")


def test_the_shipped_studies_stay_within_the_speed_limit(pair):
    """The low-fluctuation paper's sweep to 50 000 rpm is within the limit of its pair (about 175 000 rpm)."""
    assert max_speed_rpm(pair_geometry(pair)) > 50000


@pytest.mark.parametrize("speed, advice", [(1.0, "raise the speed"), (1.5e5, "lower the speed")])
def test_the_step_budget_advice_points_the_way_the_work_falls(pair, speed, advice):
    """Below the speed where steps_per_cycle_min sets the step, the transient costs a fixed number
    of steps and a slower speed needs more of them per mesh period; above it the transient spans
    more mesh periods the faster the speed."""
    model = build_pair_model(pair, torque_Nm=100.0, slices=20, positions=24)
    settings = SolverSettings(transient_tau=1000.0)
    with pytest.raises(GearmeshInputError, match=advice):
        step_plan(model, np.array([speed]), settings)


def test_same_point_is_one_relative_tolerance_of_the_point_looked_for():
    """Stages find a torque or speed again to SAME_POINT_RTOL of it: 1000 N m after a unit
    conversion's round-off is the same point, 1000.001 is another; any unit, any shape."""
    from gearmesh.limits import SAME_POINT_RTOL, same_point

    torques = np.array([400.0, 1000.0 * (1 + 0.5 * SAME_POINT_RTOL), 1000.001, 1600.0])
    np.testing.assert_array_equal(same_point(torques, 1000.0), [False, True, False, False])
    assert same_point([5000.0], 5000.0 * (1 - 2 * SAME_POINT_RTOL)).tolist() == [False]
    assert same_point(np.full((2, 3), 7.5e-3), 7.5e-3).all()  # a speed in other units, a 2-D grid
