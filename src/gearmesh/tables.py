"""CSV copies of the study tables: the netCDF dataset as one row per index combination, every
column headed ``name [units]`` (the variable's CF ``units``), and rows without values carrying
their reason (from the dataset's ``refused`` attribute, as in the netCDF file)."""

from __future__ import annotations

import re

import pandas as pd
import xarray as xr

NOTE = "note"


def _header(name: str, var: xr.Variable | xr.DataArray) -> str:
    units = var.attrs.get("units")
    return f"{name} [{units}]" if units and var.dtype.kind in "fiuc" else name


def table(ds: xr.Dataset) -> pd.DataFrame:
    """The dataset as a table with units in the headers and a ``note`` column for empty rows."""
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
    if any(notes):
        df[NOTE] = notes
    df = df.rename(columns={c: _header(c, ds[c]) for c in df.columns if c in ds.variables})
    df.index = df.index.set_names([_header(n, ds[n]) if n in ds.variables else n for n in df.index.names])
    return df


def write_csv(ds: xr.Dataset, path) -> None:
    """Write :func:`table` of ``ds`` to ``path`` (an open temporary path of an atomic write)."""
    table(ds).to_csv(path)
