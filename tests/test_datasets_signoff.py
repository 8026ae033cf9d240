"""The sign-off table (issue 27, item 5): every number read from the variants' own results, the
criteria at their boundaries, any order of the inputs, and the refusals."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from gearmesh.config import check_study, validate_study
from gearmesh.datasets.signoff import signoff_table_dataset
from gearmesh.errors import GearmeshInputError
from gearmesh.plots.signoff import plot_signoff
from gearmesh.tables import table

TORQUES = np.array([400.0, 1000.0, 1600.0])


#: The manufactured gears' values relative to the nominal's: the population (gear 0 the nominal), the
#: held-out gears and the worst over the tolerance box (searched), the largest.
POPULATION_RISE = np.array([1.0, 1.1, 1.2])
HELDOUT_RISE = np.array([1.05, 1.15])
BOX_RISE = 1.25


def _variant(name: str, scale: dict[str, float], torques=TORQUES, edge: float = 9e9, heldout=None):
    """Minimal impact, ltca, rating and dynamics datasets of one variant: the reference's values
    times ``scale`` per quantity (the impact and dynamics grids hold more torques than the LTCA;
    ``w_KEY`` the manufactured gears' own scale; ``heldout`` the held-out gears' rise)."""
    s = lambda key: scale.get(key, 1.0)  # noqa: E731
    w = lambda key: scale.get(f"w_{key}", s(key))  # noqa: E731 (the manufactured gears' own scale)
    n = torques.size
    grid = np.array([200.0, *torques, 2000.0])
    base_fs = np.array([5e3, 8e3, 13e3, 17e3, 20e3])
    nominal = {"impact_force": base_fs[1:4] * w("fs"),
               **{f"lte_order_{k}": np.array([1.0, 2.0, 3.0]) * 1e-7 * w(f"h{k}") for k in (1, 2, 3)},
               "peak_flank_pressure": np.full(n, 5e8) * w("p"), "peak_edge_pressure": np.full(n, edge),
               "peak_root_stress": np.array([1.0, 2.0, 3.0]) * 1e8 * w("sf")}
    held = HELDOUT_RISE if heldout is None else np.asarray(heldout)
    data = {"impact_force": (("torque", "speed"), np.stack([base_fs * s("fs") * 0.5, base_fs * s("fs")], axis=1))}
    for c, v in nominal.items():
        data[f"box_worst_{c}"] = ("judged_torque", BOX_RISE * v)
        data[f"population_{c}"] = (("population_gear", "judged_torque"), np.outer(POPULATION_RISE, v))
        data[f"heldout_{c}"] = (("heldout_gear", "judged_torque"), np.outer(held, v))
    impact = xr.Dataset(data, coords={"torque": grid, "speed": [1000.0, 5000.0], "judged_torque": torques},
                        attrs={"variant": name, "design_speed_rpm": 5000.0, "tolerance_population": 2,
                               "tolerance_heldout": held.size, "tolerance_heldout_seed": 1})
    region = np.ones((4, 2, 3), dtype=np.int8)
    # a tip-edge point (edge > 0): its pressure stays out of the flank's peak
    pressure = np.broadcast_to(np.linspace(1e8, 5e8, 24).reshape(4, 2, 3), (n, 4, 2, 3)).copy() * s("p")
    pressure[:, 0, 0, 0] = edge
    region[0, 0, 0] = 2 if edge else 1
    ltca = xr.Dataset({"lte_peak_to_peak": ("torque", np.array([1.0, 2.0, 3.0]) * 1e-6 * s("lte")),
                       "lte_harmonics": (("torque", "mesh_order"), np.outer([1.0, 2.0, 3.0],
                                                                             [s("h1"), s("h2"), s("h3")]) * 1e-7),
                       "region": (("position", "line", "point"), region),
                       "contact_pressure": (("torque", "position", "line", "point"), pressure)},
                      coords={"torque": torques, "mesh_order": [1, 2, 3]},
                      attrs={"gearmesh_wildcards_json": json.dumps({"variant": name})})
    peak = pressure.reshape(n, -1).max(axis=1)
    rating = xr.Dataset({"peak_contact_pressure": ("torque", peak),
                         "peak_contact_pressure_on_edge": ("torque", (peak == edge).astype(np.int8)),
                         "peak_root_stress": (("torque", "gear"), np.outer([1e8, 2e8, 3e8], [1.0, 0.9]) * s("sf")),
                         "S_H": (("torque", "gear"), np.full((n, 2), 2.0) / s("sf")),
                         "S_F": (("torque", "gear"), np.full((n, 2), 4.0) / s("sf"))},
                        coords={"torque": torques}, attrs={"variant": name})
    dynamics = xr.Dataset({"mesh_force_max": (("torque", "speed"), np.outer(grid * 20.0, [1.0, 1.3]) * s("dyn")),
                           "dynamic_factor": (("torque", "speed"), np.full((grid.size, 2), 1.3) * s("dyn")),
                           "pinion_torque": ("torque", grid)}, attrs={"variant": name})
    return impact, ltca, rating, dynamics


def _table(variants, **settings):
    sets = list(zip(*variants))
    return signoff_table_dataset(*[list(s) for s in sets], **settings)


def test_numbers_are_the_variants_own_and_flags_follow_the_criteria():
    """At exactly the limits a ≤ criterion is met and the strict F_s one is not; the flank's
    pressure leaves the tip edge out; a variant's worst F_s is judged against the reference's."""
    ref = _variant("standard", {})
    # limits exact in binary (1.25 = 5/4), so "at the limit" is exact after the box's rise too
    at_limits = _variant("at_limits", {"p": 1.25, "sf": 1.25, "h1": 1.0, "h2": 1.0, "dyn": 1.0, "fs": 1.0})
    better = _variant("better", {"p": 0.5, "sf": 1.05, "h1": 0.9, "h2": 0.2, "h3": 5.0, "dyn": 0.9, "fs": 0.4})
    ds = _table([ref, at_limits, better], pressure_factor=1.25, root_stress_factor=1.25)
    assert ds.attrs["reference"] == "standard"
    np.testing.assert_allclose(ds["impact_force"].sel(variant="better").values, [8e3 * 0.4, 13e3 * 0.4, 17e3 * 0.4])
    np.testing.assert_allclose(ds["worst_impact_force"].sel(variant="standard").values,
                               [8e3 * BOX_RISE, 13e3 * BOX_RISE, 17e3 * BOX_RISE])
    np.testing.assert_allclose(ds["peak_flank_pressure"].sel(variant="standard").values, 5e8)
    np.testing.assert_allclose(ds["peak_root_stress"].sel(variant="standard").values, [1e8, 2e8, 3e8])
    np.testing.assert_allclose(ds["dynamic_mesh_force_peak"].sel(variant="standard").values, TORQUES * 26.0)
    flags = {k: ds[k].sel(variant="at_limits").values.tolist() for k in ds.data_vars if k.startswith("meets_")}
    assert flags["meets_pressure"] == flags["meets_root_stress"] == flags["meets_te_harmonics"] == [1, 1, 1]
    assert flags["meets_dynamics"] == [1, 1, 1]
    assert flags["meets_impact"] == [0, 0, 0] and flags["meets_all"] == [0, 0, 0]
    assert ds["meets_all"].sel(variant="better").values.tolist() == [1, 1, 1]  # order 3 is not held (default)
    assert set(ds["meets_all"].sel(variant="standard").values.tolist()) == {-1}
    csv = table(ds)
    assert set(csv["meets_all"].loc["standard"]) == {"reference"} and set(csv["meets_all"].loc["better"]) == {"meets"}


def test_pressure_is_held_like_against_like():
    """A flank pressure 20 % up fails although the overall peak (the reference's tip edge) is far
    higher; a variant's edge contact where the reference has none is held against its flank peak."""
    ref = _variant("standard", {})
    flank_up = _variant("flank_up", {"p": 1.2}, edge=1e9)
    ds = _table([ref, flank_up])
    assert (ds["peak_contact_pressure"].sel(variant="flank_up") < ds["peak_contact_pressure"].sel(variant="standard")).all()
    np.testing.assert_allclose(ds["pressure_ratio"].sel(variant="flank_up").values, 1.2)
    assert ds["meets_pressure"].sel(variant="flank_up").values.tolist() == [0, 0, 0]
    clean = _variant("standard", {}, edge=0.0)
    np.testing.assert_allclose(_table([clean, _variant("a", {}, edge=0.0)])["peak_edge_pressure"].values, 0.0)
    ds = _table([clean, _variant("edgy", {}, edge=5.4e8)])  # the reference's flank peak is 5e8
    np.testing.assert_allclose(ds["pressure_ratio"].sel(variant="edgy").values, 1.08)
    assert ds["meets_pressure"].sel(variant="edgy").values.tolist() == [1, 1, 1]


def test_worst_case_and_orders_and_factors_are_settings():
    ref = _variant("standard", {})
    half = _variant("half", {"fs": 0.5, "h3": 1.5})
    ds = _table([ref, half])
    assert ds["meets_worst_impact"].sel(variant="half").values.tolist() == [1, 1, 1]
    ds = _table([ref, half], worst_impact_factor=0.49, harmonic_orders=(1, 3))
    assert ds["meets_worst_impact"].sel(variant="half").values.tolist() == [0, 0, 0]
    assert ds["meets_te_harmonics"].sel(variant="half").values.tolist() == [0, 0, 0]


def test_any_order_of_inputs_gives_the_same_table():
    variants = [_variant("standard", {}), _variant("a", {"p": 0.7, "fs": 0.3}), _variant("b", {"sf": 1.3})]
    ds = _table(variants)
    impact, ltca, rating, dynamics = (list(s) for s in zip(*variants))
    shuffled = signoff_table_dataset(impact[::-1], ltca, rating[1:] + rating[:1], dynamics[::-1])
    xr.testing.assert_identical(ds, shuffled)
    without = signoff_table_dataset(impact, ltca, rating)  # no dynamics section: no dynamic criterion
    assert "meets_dynamics" not in without and "dynamic_mesh_force_peak" not in without


@pytest.mark.parametrize("change, field", [
    ({"reference": "nominal"}, "signoff.reference"),  # a valid name, not a variant of the study
    ({"reference": "a b"}, "reference"),
    ({"harmonic_orders": (4,)}, "harmonic_orders[0]"),
    ({"harmonic_orders": (1, 1)}, "harmonic_orders"),
    ({"pressure_factor": -1.0}, "pressure_factor"),
    ({"dynamic_factor": 0}, "dynamic_factor"),
    ({"basis": "worst"}, "basis"),
    ({"impact_factors": 1.0}, "impact_factors"),  # an unknown key
])
def test_bad_settings_are_refused_by_their_key(change, field):
    """The table parses its section once (gearmesh.schema.settings_object): a value outside its
    declaration and an unknown key are refused by their key; a reference that is not one of the
    variants by the table itself, with the variants it has."""
    with pytest.raises(GearmeshInputError) as err:
        _table([_variant("standard", {}), _variant("a", {})], **change)
    assert err.value.field == field


def test_a_torque_the_impact_map_lacks_is_refused():
    ref = _variant("standard", {})
    other = _variant("a", {})
    impact = other[0].isel(torque=[0, 2, 4])  # 200, 1000 and 2000 N m: no 400 or 1600
    with pytest.raises(GearmeshInputError, match="impact.torques_Nm"):
        signoff_table_dataset([ref[0], impact], [ref[1], other[1]], [ref[2], other[2]])
    with pytest.raises(GearmeshInputError, match="same variants"):
        signoff_table_dataset([ref[0]], [ref[1], other[1]], [ref[2], other[2]])


def test_the_population_columns_are_the_worst_manufactured_gear_and_its_distributions():
    """Each worst_ column is the largest of the box worst, the population and the held-out gears of
    that quantity on its own; median and P90 over the population's gears (the nominal left out),
    independently by numpy; the share of gears worse than the reference, gear for gear."""
    rng = np.random.default_rng(3)
    variants = [_variant("standard", {}), _variant("a", {"sf": 0.9})]
    for imp in (v[0] for v in variants):
        for name in [k for k in imp.data_vars if k.startswith(("population_", "heldout_"))]:
            imp[name] = imp[name].copy(data=imp[name].values * rng.uniform(0.5, 1.5, imp[name].shape))
    ds = _table(variants)
    for v, (imp, *_rest) in zip(("standard", "a"), variants):
        for name in ("peak_flank_pressure", "peak_root_stress", "impact_force", "lte_order_2"):
            expect = np.max([imp[f"box_worst_{name}"].values, imp[f"population_{name}"].values.max(axis=0),
                             imp[f"heldout_{name}"].values.max(axis=0)], axis=0)
            np.testing.assert_array_equal(ds[f"worst_{name}"].sel(variant=v).values, expect)
            gears = imp[f"population_{name}"].values[1:]
            np.testing.assert_allclose(ds[f"median_{name}"].sel(variant=v).values, np.median(gears, axis=0))
            np.testing.assert_allclose(ds[f"p90_{name}"].sel(variant=v).values, np.percentile(gears, 90, axis=0))
    mine, theirs = (variants[k][0]["population_peak_root_stress"].values[1:] for k in (1, 0))
    np.testing.assert_allclose(ds["share_worse_peak_root_stress"].sel(variant="a").values, (mine > theirs).mean(axis=0))
    assert np.all(np.isnan(ds["share_worse_peak_root_stress"].sel(variant="standard").values))
    assert ds.attrs["population"] == 2 and ds.attrs["heldout"] == 2


def test_a_heldout_gear_that_breaks_the_verdict_is_named():
    """A held-out gear 40 % above the nominal in root stress (the box and the population 25 % at
    most): the verdict fails on it, the table says the held-out check does not hold and names the
    gear; a variant whose held-out gears stay inside holds."""
    variants = [_variant("standard", {}), _variant("fine", {"sf": 0.85, "fs": 0.3}),
                _variant("lucky", {"sf": 0.85, "fs": 0.3}, heldout=[1.0, 1.4])]
    ds = _table(variants)
    assert ds["heldout_holds"].sel(variant="fine").values.tolist() == [1, 1, 1]
    assert ds["heldout_breaking_gear"].sel(variant="fine").values.tolist() == [-1, -1, -1]
    assert ds["heldout_holds"].sel(variant="lucky").values.tolist() == [0, 0, 0]
    assert ds["heldout_breaking_gear"].sel(variant="lucky").values.tolist() == [1, 1, 1]
    assert ds["meets_all"].sel(variant="lucky").values.tolist() == [0, 0, 0]
    assert ds["meets_root_stress"].attrs["basis"] == "population" and ds["meets_dynamics"].attrs["basis"] == "nominal"


def test_the_flags_judge_the_basis_and_the_table_names_it():
    """A crowned-like variant (nominal root stress 30 % up, its worst manufactured gear 10 % down:
    crowning takes the lead deviations' face-end load off) meets on the population basis and fails on
    the nominal one; a lead-sensitive variant the reverse. The nominal columns stay in both."""
    variants = [_variant("standard", {}), _variant("crowned", {"sf": 1.3, "w_sf": 0.9}),
                _variant("sensitive", {"sf": 1.0, "w_sf": 1.3, "w_h2": 1.5, "w_p": 1.2})]
    population, nominal = _table(variants), _table(variants, basis="nominal")
    assert population.attrs["basis"] == "population" and nominal.attrs["basis"] == "nominal"
    assert str(population["judged_on"].values) == "population" and "worst manufactured" in \
        population["judged_on"].attrs["long_name"]
    for key, want_pop, want_nom in (("meets_root_stress", {"crowned": 1, "sensitive": 0},
                                     {"crowned": 0, "sensitive": 1}),
                                    ("meets_te_harmonics", {"crowned": 1, "sensitive": 0},
                                     {"crowned": 1, "sensitive": 1}),
                                    ("meets_pressure", {"crowned": 1, "sensitive": 0},
                                     {"crowned": 1, "sensitive": 1})):
        for v in want_pop:
            assert set(population[key].sel(variant=v).values.tolist()) == {want_pop[v]}, (key, v)
            assert set(nominal[key].sel(variant=v).values.tolist()) == {want_nom[v]}, (key, v)
    np.testing.assert_allclose(population["worst_pressure_ratio"].sel(variant="sensitive").values, 1.2)
    xr.testing.assert_identical(population["peak_root_stress"], nominal["peak_root_stress"])
    assert "worst_peak_root_stress" not in nominal
    assert population["meets_root_stress"].attrs["basis"] == "population"
    assert nominal["meets_root_stress"].attrs["basis"] == "nominal"
    csv = table(population)
    assert set(csv["judged_on"]) == {"population"} and "worst_peak_root_stress [MPa]" in csv.columns


def test_the_population_basis_without_the_population_is_refused():
    ref, other = _variant("standard", {}), _variant("a", {})
    bare = other[0].drop_vars([k for k in other[0].data_vars if k.startswith(("box_worst_", "population_"))])
    with pytest.raises(GearmeshInputError) as err:
        signoff_table_dataset([ref[0], bare], [ref[1], other[1]], [ref[2], other[2]])
    assert err.value.field == "signoff.basis" and "a's impact.nc" in str(err.value)
    ds = signoff_table_dataset([ref[0], bare], [ref[1], other[1]], [ref[2], other[2]], basis="nominal")
    assert ds.attrs["basis"] == "nominal"
    short = other[0].isel(judged_torque=[0, 1])  # no 1600 N m in the manufactured gears' torques
    with pytest.raises(GearmeshInputError, match="impact.tolerance_torques_Nm"):
        signoff_table_dataset([ref[0], short], [ref[1], other[1]], [ref[2], other[2]])


def test_the_figure_is_drawn_from_the_table(tmp_path):
    ds = _table([_variant("standard", {}), _variant("a", {"p": 0.7, "fs": 0.3}), _variant("b", {"sf": 1.3})])
    path = plot_signoff(ds, tmp_path / "signoff.png")
    assert path.stat().st_size > 10000
    variants = [_variant("standard", {}), _variant("a", {"p": 0.7, "fs": 0.3})]
    nominal = plot_signoff(_table(variants, basis="nominal"), tmp_path / "signoff_nominal.png")
    assert nominal.stat().st_size > 10000


STUDY = {"study": "s", "pairs": ["low_fluctuation_pair1"], "variants": {"standard": {}},
         "ltca": {"torques_Nm": [100]}, "rating": {"speed_rpm": 3000},
         "impact": {"torques_Nm": [100, 200], "speeds_rpm": [3000], "design_speed_rpm": 3000},
         "tolerances": {"grade": 6}}


@pytest.mark.parametrize("change, field", [
    ({"signoff": {"reference": "relief"}}, "signoff.reference"),
    ({"signoff": {}, "rating": None}, "signoff"),
    ({"signoff": {}, "impact": {"torques_Nm": [200], "speeds_rpm": [3000], "design_speed_rpm": 3000}},
     "impact.torques_Nm"),
    ({"signoff": {}, "ltca": {"torques_Nm": [100, 200]}, "dynamics": {"torques_Nm": [100], "speeds_rpm": [3000]}},
     "dynamics.torques_Nm"),
])
def test_a_study_whose_signoff_lacks_its_inputs_is_refused(root, change, field):
    config = {**STUDY, **change}
    config = {k: v for k, v in config.items() if v is not None}
    with pytest.raises(GearmeshInputError) as err:
        check_study(validate_study(config), root)
    assert err.value.field == field


def test_a_complete_signoff_study_is_accepted(root):
    check_study(validate_study({**STUDY, "signoff": {}}), root)
    without = {k: v for k, v in STUDY.items() if k != "tolerances"}
    check_study(validate_study({**without, "signoff": {"basis": "nominal"}}), root)


def test_a_population_signoff_without_a_population_is_refused(root):
    without = {k: v for k, v in STUDY.items() if k != "tolerances"}
    for tolerances in (None, {"grade": 6, "population": 0}, {"population": 8}):
        config = {**without, "signoff": {}} | ({"tolerances": tolerances} if tolerances else {})
        with pytest.raises(GearmeshInputError) as err:
            check_study(validate_study(config), root)
        assert err.value.field == "signoff.basis"
