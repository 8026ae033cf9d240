"""The sign-off verdict (signoff_verdict.nc): the sign-off table (signoff_table.nc, its rule
and its criteria: :mod:`gearmesh.datasets.signoff`) as a reader takes it in at a glance — one
row per variant and torque, the reference left out, whether it meets every criterion, and per
criterion whether it meets it with its margin to the limit and the gear it was judged on.

No criterion is judged here. The criteria are the table's ``meets_*`` flags, whatever they are:
a flag the table gains appears here without a change. The margin of a criterion is read from the
quantity it holds against the reference's (:data:`MARGINS`), on the gear its flag was judged on
(the table's ``worst_`` columns for the worst manufactured gear); a criterion without a declared
margin shows meets or fails alone.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
import xarray as xr

from ..errors import GearmeshInputError
from ..io import variable

__all__ = ["MARGINS", "Margin", "criterion_margins", "signoff_verdict_dataset"]

#: The sign-off table's flag of every criterion together, and its words (CF flag_meanings).
ALL = "meets_all"
MEETS, FAILS = "meets", "fails"
#: A criterion's cell: met or failed at a glance, then the margin.
MARKS = {True: "✓", False: "✗"}
#: The table's prefix of the worst manufactured gear's columns.
WORST = "worst_"


@dataclass(frozen=True)
class Margin:
    """How far a criterion's quantity is from its limit ``factor`` × the reference's: its
    columns in the sign-off table (nominal gear; a ``{orders}`` column stands for one per mesh
    order of the table's ``harmonic_orders``, the largest ratio counts), the table attribute
    holding the factor, and whether the quantity is the worst over the torques (one value per
    variant, held against the reference's worst over the torques)."""

    column: str
    factor: str
    over_torques: bool = False


#: criterion flag -> its margin. Margin = 1 − (value / reference's value) / factor: positive
#: while the limit is kept (for a strict "below" a margin of exactly 0 fails).
MARGINS = {
    "meets_pressure": Margin("pressure_ratio", "pressure_factor"),
    "meets_root_stress": Margin("peak_root_stress", "root_stress_factor"),
    "meets_te_harmonics": Margin("lte_order_{orders}", "harmonic_factor"),
    "meets_impact": Margin("impact_force", "impact_factor"),
    "meets_worst_impact": Margin("impact_force", "worst_impact_factor", over_torques=True),
    "meets_dynamics": Margin("dynamic_mesh_force_peak", "dynamic_factor"),
}

#: criterion flag -> the name a reader knows it by (others: the flag's name in words).
NAMES = {"meets_pressure": "pressure", "meets_root_stress": "root stress", "meets_te_harmonics": "TE orders",
         "meets_impact": "F_s", "meets_worst_impact": "worst F_s", "meets_dynamics": "dynamics"}

#: The gear a criterion was judged on, in a reader's words.
BASIS_WORDS = {"population": "worst gear", "nominal": "nominal"}


def criteria(table: xr.Dataset) -> list[str]:
    """The criterion flags of a sign-off table in its order: every ``meets_*`` but ``meets_all``.

    Parameters
    ----------
    table : xarray.Dataset
        A sign-off table (signoff_table.nc, :mod:`gearmesh.datasets.signoff`).

    Returns
    -------
    list[str]
        The flags' variable names.
    """
    return [str(name) for name in table.data_vars if str(name).startswith("meets_") and name != ALL]


def judged_on(table: xr.Dataset, criterion: str) -> str:
    """The gear ``criterion`` was judged on: the flag's own ``basis`` attribute (the sign-off table
    names it on every flag; a flag that does not say: the nominal gear).

    Parameters
    ----------
    table : xarray.Dataset
        A sign-off table.
    criterion : str
        One of its flags (:func:`criteria`).

    Returns
    -------
    str
        ``'population'`` (the worst manufactured gear) or ``'nominal'``.
    """
    return str(table[criterion].attrs.get("basis", "nominal"))


def _columns(table: xr.Dataset, margin: Margin, basis: str) -> list[str]:
    names = ([margin.column.format(orders=n) for n in np.atleast_1d(table.attrs["harmonic_orders"])]
             if "{orders}" in margin.column else [margin.column])
    if basis == "population":  # the worst manufactured gear's columns where the table has them
        names = [WORST + n if WORST + n in table else n for n in names]
    missing = [n for n in names if n not in table]
    if missing:
        raise GearmeshInputError("signoff_table", missing[0], "is not a column of the sign-off table")
    return names


def criterion_margins(table: xr.Dataset, criterion: str) -> np.ndarray | None:
    """The margin of ``criterion`` (variant, torque), fractions of its limit (:data:`MARGINS`),
    or None for a criterion without a declared margin.

    Each judged column is taken relative to the reference variant's, its largest ratio set against
    the criterion's allowed factor (the table's attribute): margin = 1 − max(value/reference)/factor.

    Parameters
    ----------
    table : xarray.Dataset
        A sign-off table (dims variant, torque; attributes ``reference`` and the factors).
    criterion : str
        One of its flags (:func:`criteria`).

    Returns
    -------
    numpy.ndarray or None
        Margins, shape (variant, torque), 1 (a fraction of the limit; negative: fails).

    Raises
    ------
    GearmeshInputError
        Naming ``signoff_table`` when a column the margin needs is missing.
    """
    margin = MARGINS.get(criterion)
    if margin is None:
        return None
    ref = list(table["variant"].values).index(table.attrs["reference"])
    ratios = []
    for name in _columns(table, margin, judged_on(table, criterion)):
        value = table[name].transpose("variant", "torque").values
        if margin.over_torques:
            value = np.broadcast_to(value.max(axis=1, keepdims=True), value.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratios.append(value / value[ref])
    return 1.0 - np.max(ratios, axis=0) / float(table.attrs[margin.factor])


def _cell(meets: bool, margin: float | None) -> str:
    """'✓ +11 %' (meets, 11 % of the limit to spare), '✗ −13 %' (fails by 13 %): the flag and the
    margin in percent of the limit, without a break inside (no-break spaces)."""
    mark = MARKS[meets]
    if margin is None or not np.isfinite(margin):
        return mark
    return f"{mark}\u00a0{100 * margin:+.0f}\u00a0%".replace("-", "−")


def signoff_verdict_dataset(signoff: Sequence[xr.Dataset]) -> xr.Dataset:
    """The verdict of a pair's sign-off table (variant × torque, the reference left out): ``verdict``
    (meets every criterion or fails one), and per criterion a text column named by the criterion
    and the gear it was judged on ("pressure (worst gear)"): ✓ meets or ✗ fails, with the margin in
    percent of the limit (:func:`criterion_margins`).

    Parameters
    ----------
    signoff : Sequence[xarray.Dataset]
        The pair's sign-off table, as a list of one (signoff_table.nc).

    Returns
    -------
    xarray.Dataset
        signoff_verdict.nc (dims variant, torque): ``verdict`` (0 fails, 1 meets) and a text column
        per criterion; attributes ``reference``, ``basis``, ``criteria``.

    Raises
    ------
    GearmeshInputError
        Naming ``signoff`` when it is not one table, ``variants`` when the table holds the reference alone.
    """
    if len(signoff) != 1:
        raise GearmeshInputError("signoff", len(signoff), "must be one sign-off table (a list of one)")
    (table,) = signoff
    reference = table.attrs["reference"]
    keep = [v for v in table["variant"].values if v != reference]
    if not keep:
        raise GearmeshInputError("variants", [reference], "need a variant beside the reference for a verdict")
    variants = list(table["variant"].values)
    rows = [variants.index(v) for v in keep]
    dims = ("variant", "torque")
    flags = {name: table[name].transpose(*dims).values[rows] for name in (ALL, *criteria(table))}
    verdict = variable(dims, (flags[ALL] == 1).astype(np.int8), "1",
                       f"every criterion of the sign-off table met against {reference}")
    verdict.attrs.update(flag_values=np.array([0, 1], dtype=np.int8), flag_meanings=f"{FAILS} {MEETS}")
    out = {"verdict": verdict}
    for name in criteria(table):
        basis = judged_on(table, name)
        margins = criterion_margins(table, name)
        cells = np.array([[_cell(bool(f == 1), None if margins is None else m) for f, m in zip(row, mrow)]
                          for row, mrow in zip(flags[name], margins[rows] if margins is not None
                                               else np.full(flags[name].shape, np.nan))])
        label = f"{NAMES.get(name, name.removeprefix('meets_').replace('_', ' '))} " \
                f"({BASIS_WORDS.get(basis, basis)})"
        out[label] = variable(dims, cells, "1", f"{table[name].attrs.get('long_name', name)}: ✓ meets or ✗ fails, "
                              f"with the margin to the limit in percent of the limit")
    ds = xr.Dataset(out, coords={"variant": variable(("variant",), np.array(keep), "1", "micro-geometry variant"),
                                 "torque": table["torque"].variable.copy()})
    ds.attrs.update(reference=reference, basis=str(table.attrs.get("basis", "nominal")),
                    criteria=" ".join(criteria(table)))
    return ds
