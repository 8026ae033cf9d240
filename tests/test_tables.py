"""CSV tables: engineering units in every numeric header (those of the JSON output), force
columns named by their line, blank rows carry their reason."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
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
    assert list(df.columns) == ["k [N/µm]"] and list(df.index) == ["a", "b"] and df.index.name == "pair"
    np.testing.assert_allclose(df["k [N/µm]"].to_numpy(), [1e-6, 2e-6], rtol=1e-15)


def test_engineering_units_as_the_json_gives_them():
    """Lengths in mm, displacements in µm where the variable says so, stresses in MPa, an index
    coordinate converted with its column; the netCDF dataset itself stays in SI."""
    ds = xr.Dataset({"roll": variable(("x",), [0.00105039, 0.002], "m", "roll before A"),
                     "te": variable(("x",), [1.86e-5, 2e-5], "m", "loaded TE", engineering_units="µm"),
                     "stress": variable(("x",), [1.2e9, 1e9], "Pa", "contact pressure"),
                     "line_load": variable(("x",), [2.28e5, 1e5], "N m-1", "line load", engineering_units="N/mm")},
                    coords={"x": variable(("x",), [0.001, 0.002], "m", "face position")})
    df = table(ds)
    assert list(df.columns) == ["roll [mm]", "te [µm]", "stress [MPa]", "line_load [N/mm]"]
    assert df.index.name == "x [mm]"
    np.testing.assert_allclose(df.index.to_numpy(), [1.0, 2.0])
    np.testing.assert_allclose(df.iloc[0].to_numpy(), [1.05039, 18.6, 1200.0, 228.0])
    assert ds["roll"].attrs["units"] == "m" and float(ds["roll"][0]) == 0.00105039


def test_unknown_engineering_unit_is_refused():
    ds = xr.Dataset({"te": variable(("x",), [1.0], "m", "loaded TE", engineering_units="furlong")})
    with pytest.raises(ValueError, match="furlong"):
        table(ds)


def test_force_columns_name_their_line():
    ds = _impact_like()
    ds["impact_force"].attrs["force_line"] = "transverse"
    assert list(table(ds).columns) == ["scenario", "impact_force_transverse [N]"]


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
