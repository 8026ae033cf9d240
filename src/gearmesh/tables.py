"""CSV copies of the study tables: the netCDF dataset as one row per index combination, every
column headed ``name [units]`` in the engineering units of the JSON output (mm, µm, N/µm, MPa:
:data:`ENGINEERING_UNITS`; the netCDF file keeps SI), coded categories as their words
(CF ``flag_values``/``flag_meanings``: a scenario reads ``edge``, not ``2``), numbers to six
significant digits, and rows without values carrying their reason (from the dataset's
``refused`` attribute, as in the netCDF file)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import xarray as xr

NOTE = "note"

#: Six significant digits: 0.1 µm in a 1 m quantity, 1 ppm of a force; more than any model here
#: means (the netCDF file keeps the full double precision).
FLOAT_FORMAT = "%.6g"


#: SI unit of a netCDF variable -> {engineering unit: factor}: the units the CLI's JSON and the
#: figures use. The first entry is the default; a variable picks another by its
#: ``engineering_units`` attribute (a displacement in µm, a line load in N/mm).
ENGINEERING_UNITS = {
    "m": {"mm": 1e3, "µm": 1e6},
    "N m-1": {"N/µm": 1e-6, "N/mm": 1e-3},
    "N m-2": {"N/(mm µm)": 1e-9},
    "Pa": {"MPa": 1e-6},
}


def engineering(var: xr.Variable | xr.DataArray) -> tuple[str | None, float]:
    """The unit a table shows ``var`` in and the factor from its SI values: the variable's
    ``engineering_units`` or its SI unit's default (:data:`ENGINEERING_UNITS`), else its own
    unit unchanged.

    Parameters
    ----------
    var : xarray.Variable or xarray.DataArray
        A variable of a study dataset (SI ``units``, optionally ``engineering_units``).

    Returns
    -------
    units : str or None
        The unit the table shows (its own when it has no engineering unit, is not numeric or is a
        CF flag variable).
    factor : float
        The factor from the SI values to that unit (1.0 when unchanged).

    Raises
    ------
    ValueError
        When ``engineering_units`` is not one of :data:`ENGINEERING_UNITS` for the SI unit.
    """
    units = var.attrs.get("units")
    choices = ENGINEERING_UNITS.get(units)
    if not choices or var.dtype.kind not in "fiuc" or _flags(var):
        return units, 1.0
    wanted = var.attrs.get("engineering_units", next(iter(choices)))
    if wanted not in choices:
        raise ValueError(f"{var.attrs.get('long_name', 'variable')}: engineering_units {wanted!r} is not one of "
                         f"{list(choices)} for {units}")
    return wanted, choices[wanted]


def _header(name: str, var: xr.Variable | xr.DataArray) -> str:
    """``name [units]``; a force's name ends in its line (``_transverse``/``_normal``)."""
    line = var.attrs.get("force_line")
    if line and not name.endswith(f"_{line}"):
        name = f"{name}_{line}"
    units = engineering(var)[0]
    return f"{name} [{units}]" if units and var.dtype.kind in "fiuc" and not _flags(var) else name


def _flags(var: xr.Variable | xr.DataArray) -> dict[int, str]:
    """The words of a CF flag variable ({code: word}), empty for any other variable."""
    values, meanings = var.attrs.get("flag_values"), var.attrs.get("flag_meanings")
    if values is None or not meanings:
        return {}
    words = str(meanings).split()
    codes = [int(v) for v in np.atleast_1d(values)]
    return dict(zip(codes, words)) if len(words) == len(codes) else {}


def table(ds: xr.Dataset) -> pd.DataFrame:
    """The dataset as a table with units in the headers, flag variables as words and a ``note``
    column for empty rows.

    Parameters
    ----------
    ds : xarray.Dataset
        A study dataset (SI units, CF flag variables, the ``refused`` attribute of its refused cases).

    Returns
    -------
    pandas.DataFrame
        One row per index combination; columns and index levels headed ``name [units]`` in
        engineering units, flag variables as words, a ``note`` column when a row has no values.

    References
    ----------
    .. [1] Eaton B., Gregory J., Drach B., Taylor K., Hankin S. et al., NetCDF Climate and Forecast
       (CF) Metadata Conventions, version 1.8 (2020), section 3.5 "Flags" (``flag_values``, ``flag_meanings``).
    """
    df = ds.to_dataframe()
    # entries "NAME CASE: reason" joined by "; " (a reason may itself contain "; ")
    refused = [r.strip() for r in re.split(r"; (?=[^;:\s]+ [^;:\s]+: )", str(ds.attrs.get("refused", "")))
               if r.strip()]
    empty = df.select_dtypes("number").isna().all(axis=1) if len(df.columns) else pd.Series(False, index=df.index)
    notes = []
    for key, blank in zip(df.index, empty):
        if not blank:
            notes.append("")
            continue
        labels = [str(k) for k in (key if isinstance(key, tuple) else (key,))]
        reasons = [r for r in refused if all(label in r for label in labels)]
        notes.append("; ".join(reasons) or "no value: the design or case was refused (see the netCDF attributes)")
    for name in df.columns:
        words = _flags(ds[name]) if name in ds.variables else {}
        if words:
            df[name] = [words.get(int(v), "") if pd.notna(v) else "" for v in df[name]]
        elif name in ds.variables and (factor := engineering(ds[name])[1]) != 1.0:
            df[name] = df[name] * factor
    if any(notes):
        df[NOTE] = notes
    df = df.rename(columns={c: _header(c, ds[c]) for c in df.columns if c in ds.variables})
    index = df.index.to_frame(index=False)
    for n in index.columns:
        if n in ds.variables and (factor := engineering(ds[n])[1]) != 1.0:
            index[n] = index[n] * factor
    df.index = pd.MultiIndex.from_frame(index) if index.shape[1] > 1 else pd.Index(index.iloc[:, 0])
    df.index = df.index.set_names([_header(n, ds[n]) if n in ds.variables else n for n in df.index.names])
    return df


def write_csv(ds: xr.Dataset, path) -> None:
    """Write :func:`table` of ``ds`` to ``path`` (an open temporary path of an atomic write).

    Parameters
    ----------
    ds : xarray.Dataset
        A study dataset.
    path : str or path-like
        The CSV file to write (numbers as :data:`FLOAT_FORMAT`).
    """
    table(ds).to_csv(path, float_format=FLOAT_FORMAT)
