"""The sign-off table (issue 27, item 5): every number read from the variants' own results, the
criteria at their boundaries, any order of the inputs, and the refusals."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from gearmesh.config import check_study, validate_study
from gearmesh.datasets.signoff import POPULATION, signoff_table_dataset
from gearmesh.errors import GearmeshInputError
from gearmesh.plots.signoff import plot_signoff
from gearmesh.tables import table

TORQUES = np.array([400.0, 1000.0, 1600.0])


def _variant(name: str, scale: dict[str, float], torques=TORQUES, edge: float = 9e9):
    """Minimal impact, ltca, rating and dynamics datasets of one variant: the reference's values
    times ``scale`` per quantity (the impact and dynamics grids hold more torques than the LTCA)."""
    s = lambda key: scale.get(key, 1.0)  # noqa: E731
    w = lambda key: scale.get(f"w_{key}", s(key))  # noqa: E731 (the manufactured gears' own scale)
    n = torques.size
    grid = np.array([200.0, *torques, 2000.0])
    base_fs = np.array([5e3, 8e3, 13e3, 17e3, 20e3])
    rise = np.array([1.0, 1.2])[:, None]  # sample 1 (a manufactured gear) 20 % above the nominal
    on_grid = np.array([0.5, 1.0, 2.0, 3.0, 4.0])  # the LTCA's torques' values at grid[1:4]
    impact = xr.Dataset({"impact_force": (("torque", "speed"), np.stack([base_fs * s("fs") * 0.5,
                                                                         base_fs * s("fs")], axis=1)),
                         "tolerance_impact_force": (("tolerance_sample", "torque"),
                                                    np.stack([base_fs * s("fs"), base_fs * s("fs") * 1.2])),
                         "tolerance_lte_peak_to_peak": (("tolerance_sample", "torque"), rise * on_grid * 1e-6 * w("lte")),
                         "tolerance_lte_harmonics": (("tolerance_sample", "torque", "mesh_order"),
                                                     rise[:, :, None] * np.outer(on_grid, [w("h1"), w("h2"),
                                                                                           w("h3")]) * 1e-7),
                         "tolerance_peak_flank_pressure": (("tolerance_sample", "torque"),
                                                           rise * np.full(5, 5e8) * w("p")),
                         "tolerance_peak_edge_pressure": (("tolerance_sample", "torque"), rise * np.full(5, edge)),
                         "tolerance_peak_root_stress": (("tolerance_sample", "torque"), rise * on_grid * 1e8 * w("sf"))},
                        coords={"torque": grid, "speed": [1000.0, 5000.0], "mesh_order": [1, 2, 3]},
                        attrs={"variant": name, "design_speed_rpm": 5000.0, "tolerance_samples": 1})
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
    at_limits = _variant("at_limits", {"p": 1.1, "sf": 1.1, "h1": 1.0, "h2": 1.0, "dyn": 1.0, "fs": 1.0})
    better = _variant("better", {"p": 0.5, "sf": 1.05, "h1": 0.9, "h2": 0.2, "h3": 5.0, "dyn": 0.9, "fs": 0.4})
    ds = _table([ref, at_limits, better])
    assert ds.attrs["reference"] == "standard"
    np.testing.assert_allclose(ds["impact_force"].sel(variant="better").values, [8e3 * 0.4, 13e3 * 0.4, 17e3 * 0.4])
    np.testing.assert_allclose(ds["impact_force_tolerance_max"].sel(variant="standard").values,
                               [8e3 * 1.2, 13e3 * 1.2, 17e3 * 1.2])
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
    ({"reference": "nominal"}, "signoff.reference"),
    ({"harmonic_orders": (4,)}, "harmonic_orders"),
    ({"pressure_factor": -1.0}, "pressure_factor"),
    ({"basis": "worst"}, "basis"),
])
def test_bad_settings_are_refused(change, field):
    with pytest.raises(GearmeshInputError) as err:
        _table([_variant("standard", {}), _variant("a", {})], **change)
    assert field in str(err.value)


def test_a_torque_the_impact_map_lacks_is_refused():
    ref = _variant("standard", {})
    other = _variant("a", {})
    impact = other[0].isel(torque=[0, 2, 4])  # 200, 1000 and 2000 N m: no 400 or 1600
    with pytest.raises(GearmeshInputError, match="impact.torques_Nm"):
        signoff_table_dataset([ref[0], impact], [ref[1], other[1]], [ref[2], other[2]])
    with pytest.raises(GearmeshInputError, match="same variants"):
        signoff_table_dataset([ref[0]], [ref[1], other[1]], [ref[2], other[2]])


def test_the_population_columns_are_the_worst_manufactured_gear():
    """Each worst_ column is the largest over the samples of that quantity on its own (the worst
    gear of one quantity need not be the worst of another), at the LTCA torques of the impact grid."""
    rng = np.random.default_rng(3)
    variants = [_variant("standard", {}), _variant("a", {"sf": 0.9})]
    for imp in (v[0] for v in variants):
        for name in POPULATION.values():
            imp[name] = imp[name].copy(data=imp[name].values * rng.uniform(0.5, 1.5, imp[name].shape))
    ds = _table(variants)
    for v, (imp, *_rest) in zip(("standard", "a"), variants):
        at = imp.sel(torque=TORQUES).max("tolerance_sample")  # the independent reduction: xarray's max
        for key, name in (("worst_lte_peak_to_peak", "tolerance_lte_peak_to_peak"),
                          ("worst_peak_flank_pressure", "tolerance_peak_flank_pressure"),
                          ("worst_peak_edge_pressure", "tolerance_peak_edge_pressure"),
                          ("worst_peak_root_stress", "tolerance_peak_root_stress")):
            np.testing.assert_array_equal(ds[key].sel(variant=v).values, at[name].values)
        for n in (1, 2, 3):
            np.testing.assert_array_equal(ds[f"worst_lte_order_{n}"].sel(variant=v).values,
                                          at["tolerance_lte_harmonics"].sel(mesh_order=n).values)
    assert ds.attrs["tolerance_statistic"] == "max" and ds.attrs["tolerance_samples"] == 1


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
    assert "judged on population" in population["meets_root_stress"].attrs["long_name"]
    csv = table(population)
    assert set(csv["judged_on"]) == {"population"} and "worst_peak_root_stress [MPa]" in csv.columns


def test_the_population_basis_without_the_population_is_refused():
    ref, other = _variant("standard", {}), _variant("a", {})
    bare = other[0].drop_vars(list(POPULATION.values()))
    with pytest.raises(GearmeshInputError) as err:
        signoff_table_dataset([ref[0], bare], [ref[1], other[1]], [ref[2], other[2]])
    assert err.value.field == "signoff.basis" and "a's impact.nc" in str(err.value)
    ds = signoff_table_dataset([ref[0], bare], [ref[1], other[1]], [ref[2], other[2]], basis="nominal")
    assert ds.attrs["basis"] == "nominal"
    short = other[0].isel(torque=[0, 1, 2, 4])  # no 1600 N m in the manufactured gears' torques
    with pytest.raises(GearmeshInputError, match="impact.torques_Nm"):
        signoff_table_dataset([ref[0], short], [ref[1], other[1]], [ref[2], other[2]])


def test_the_figure_is_drawn_from_the_table(tmp_path):
    ds = _table([_variant("standard", {}), _variant("a", {"p": 0.7, "fs": 0.3}), _variant("b", {"sf": 1.3})])
    path = plot_signoff(ds, tmp_path / "signoff.png")
    assert path.stat().st_size > 10000
    variants = [_variant("standard", {}), _variant("a", {"p": 0.7, "fs": 0.3})]
    nominal = plot_signoff(_table(variants, basis="nominal"), tmp_path / "signoff_nominal.png")
    assert nominal.stat().st_size > 10000


STUDY = {"study": "s", "pairs": ["seed001_pair1"], "variants": {"standard": {}},
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


def test_a_population_signoff_without_tolerance_samples_is_refused(root):
    without = {k: v for k, v in STUDY.items() if k != "tolerances"}
    for tolerances in (None, {"grade": 6, "samples": 0}):
        config = {**without, "signoff": {}} | ({"tolerances": tolerances} if tolerances else {})
        with pytest.raises(GearmeshInputError) as err:
            check_study(validate_study(config), root)
        assert err.value.field == "signoff.basis"
