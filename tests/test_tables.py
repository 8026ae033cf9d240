"""CSV tables: units in every numeric header, blank rows carry their reason."""

from __future__ import annotations

import numpy as np
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
