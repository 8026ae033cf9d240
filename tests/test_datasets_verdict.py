"""The sign-off verdict (the landing page's table): every flag of the sign-off table as it is, a
margin that says what the flag says, a criterion the table gains shown without a change."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from test_datasets_signoff import _table, _variant

from gearmesh.datasets.signoff import CRITERIA
from gearmesh.datasets.verdict import MARGINS, MARKS, criteria, criterion_margins, signoff_verdict_dataset
from gearmesh.io import variable
from gearmesh.tables import table

QUANTITIES = ("p", "sf", "h1", "h2", "h3", "dyn", "fs", "w_p", "w_sf", "w_h1", "w_h2")


def _random_table(seed: int, basis: str):
    rng = np.random.default_rng(seed)
    variants = [_variant("standard", {})]
    for k in range(4):  # scales around the limits (0.5 to 1.5 of the reference's), both ways
        variants.append(_variant(f"v{k}", {q: float(rng.uniform(0.5, 1.5)) for q in QUANTITIES}))
    return _table(variants, reference="standard", basis=basis)


def test_every_criterion_of_the_sign_off_table_has_a_margin():
    assert set(CRITERIA) <= set(MARGINS)


@pytest.mark.parametrize("basis", ["population", "nominal"])
@pytest.mark.parametrize("seed", range(6))
def test_the_margin_says_what_the_flag_says(seed, basis):
    """An independent reading of the table's columns (value over the reference's, over the factor)
    against the table's own judgement, on the gear the flag was judged on: a positive margin meets,
    a negative one fails (a margin of exactly 0 is the limit itself: met by "at most", failed by
    the strict "below" of F_s)."""
    t = _random_table(seed, basis)
    ref = list(t["variant"].values).index("standard")
    others = [k for k in range(t.sizes["variant"]) if k != ref]
    seen = set()
    for name in criteria(t):
        margin = criterion_margins(t, name)[others]
        meets = t[name].transpose("variant", "torque").values[others] == 1
        clear = np.abs(margin) > 1e-9
        np.testing.assert_array_equal(meets[clear], margin[clear] > 0, err_msg=name)
        seen |= {bool(v) for v in meets[clear].ravel()}
    assert seen == {True, False}  # the draws met and failed criteria


def test_the_verdict_shows_each_flag_with_its_margin_and_basis():
    t = _random_table(3, "population")
    v = signoff_verdict_dataset([t])
    assert "standard" not in v["variant"].values and v.sizes["variant"] == t.sizes["variant"] - 1
    np.testing.assert_array_equal(v["verdict"].values,
                                  t["meets_all"].sel(variant=v["variant"]).transpose("variant", "torque").values)
    df = table(v)
    assert list(df.columns[:1]) == ["verdict"]
    # on the worst manufactured gear: every criterion but the dynamics (nominal: a dynamics stage per gear)
    assert {"pressure (worst gear)", "root stress (worst gear)", "TE orders (worst gear)", "F_s (worst gear)",
            "worst F_s (worst gear)", "dynamics (nominal)"} == set(df.columns[1:])
    flags = t["meets_root_stress"].sel(variant=v["variant"]).transpose("variant", "torque").values.ravel()
    cells = v["root stress (worst gear)"].values.ravel()
    assert [c.split("\u00a0")[0] for c in cells] == [MARKS[f == 1] for f in flags]
    margins = criterion_margins(t, "meets_root_stress")[1:].ravel()
    assert [c.split("\u00a0")[1] for c in cells] == [f"{100 * m:+.0f}".replace("-", "−") for m in margins]
    nominal = signoff_verdict_dataset([_random_table(3, "nominal")])
    assert "pressure (nominal)" in nominal and "pressure (worst gear)" not in nominal


def test_a_criterion_the_table_gains_appears_without_a_change():
    t = _random_table(1, "population")
    flag = variable(("variant", "torque"), np.where(np.arange(t.sizes["variant"])[:, None] == 0, -1, 1)
                    * np.ones((1, t.sizes["torque"]), dtype=np.int8), "1", "a new criterion")
    flag.attrs.update(flag_values=np.array([-1, 0, 1], dtype=np.int8), flag_meanings="reference fails meets")
    t["meets_held_out"] = flag.astype(np.int8)
    v = signoff_verdict_dataset([t])
    assert set(v["held out (nominal)"].values.ravel()) == {MARKS[True]}  # no margin declared: the flag alone


@pytest.mark.parametrize("count", [0, 2])
def test_the_verdict_is_of_one_table(count):
    """A list of no table or of two is refused by name, not by a bare unpacking error."""
    from gearmesh.datasets.verdict import signoff_verdict_dataset
    from gearmesh.errors import GearmeshInputError

    with pytest.raises(GearmeshInputError, match=rf"^signoff = {count}: must be one sign-off table"):
        signoff_verdict_dataset([xr.Dataset()] * count)
