"""CSV tables: units in every numeric header, blank rows carry their reason."""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from gearmesh.io import variable
from gearmesh.tables import NOTE, table


def test_units_in_headers_and_reasons_for_blank_rows():
    ds = xr.Dataset({"beta": variable(("pair", "design"), [[0.2, np.nan], [0.3, 0.4]], "rad", "helix angle")},
                    coords={"pair": variable(("pair",), ["p1", "p2"], "1", "pair"),
                            "design": variable(("design",), ["forward", "backward"], "1", "route")})
    ds.attrs["refused"] = "p1 backward: eps_beta < 1: none below it (impossible; design forward); p3 forward: x"
    df = table(ds)
    assert list(df.columns) == ["beta [rad]", NOTE]
    assert df.loc[("p1", "backward"), NOTE] == "p1 backward: eps_beta < 1: none below it (impossible; design forward)"
    assert df.loc[("p2", "backward"), NOTE] == "" and df.loc[("p1", "forward"), "beta [rad]"] == 0.2


def test_one_dimensional_table():
    ds = xr.Dataset({"k": variable(("pair",), [1.0, 2.0], "N m-1", "stiffness")},
                    coords={"pair": variable(("pair",), ["a", "b"], "1", "pair")})
    df = table(ds)
    assert list(df.columns) == ["k [N m-1]"] and list(df.index) == ["a", "b"] and df.index.name == "pair"


def _impact_like() -> xr.Dataset:
    scenario = variable(("variant", "torque"), np.array([[2, 2], [1, 0]], dtype=np.int8), "1", "mesh-in scenario")
    scenario.attrs.update(flag_values=np.array([0, 1, 2], dtype=np.int8), flag_meanings="none surface edge")
    force = variable(("variant", "torque"), [[8214.73499248798, 13639.363487510822], [1 / 3, 1.23456789e-7]], "N",
                     "impact force")
    return xr.Dataset({"scenario": scenario, "impact_force": force},
                      coords={"variant": variable(("variant",), ["standard", "relief"], "1", "variant"),
                              "torque": variable(("torque",), [400.0, 1000.0 / 3], "N m", "pinion torque")})


def test_flag_variables_as_words_without_units():
    df = table(_impact_like())
    assert list(df.columns) == ["scenario", "impact_force [N]"]
    assert df["scenario"].tolist() == ["edge", "edge", "surface", "none"]


def test_csv_six_significant_digits(tmp_path):
    from gearmesh.tables import write_csv

    ds = _impact_like()
    path = tmp_path / "t.csv"
    write_csv(ds, path)
    lines = path.read_text().splitlines()
    assert lines[0] == "variant,torque [N m],scenario,impact_force [N]"
    rows = [line.split(",") for line in lines[1:]]
    assert [r[2] for r in rows] == ["edge", "edge", "surface", "none"]
    numbers = [cell for r in rows for cell in (r[1], r[3])]
    for cell in numbers:  # at most six significant digits, and the value kept to that precision
        mantissa = cell.lower().split("e")[0].lstrip("-").replace(".", "").lstrip("0")
        assert 1 <= len(mantissa) <= 6, cell
    back = pd.read_csv(path, index_col=[0, 1])
    np.testing.assert_allclose(back["impact_force [N]"].to_numpy(), ds["impact_force"].values.ravel(), rtol=5e-6)
    np.testing.assert_allclose(sorted(set(back.index.get_level_values(1))), sorted(ds["torque"].values), rtol=5e-6)
