"""netCDF output with CF-style attributes, provenance and atomic writes (docs/modelling.md).

Every variable must carry ``units`` and ``long_name``; :func:`write_dataset` refuses a
dataset that does not, so no stage can write an undocumented number.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path
from typing import Any, Iterator, Mapping

import numpy as np
import xarray as xr

from . import __version__


def config_digest(config: Mapping[str, Any]) -> tuple[str, str]:
    """The config as canonical JSON (sorted keys) and its sha256 hex digest."""
    text = json.dumps(config, sort_keys=True, default=_json_default)
    return text, hashlib.sha256(text.encode()).hexdigest()


def _json_default(obj: Any) -> Any:
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def variable(dims, data, units: str, long_name: str, **attrs) -> xr.Variable:
    """An xarray Variable with its CF ``units`` and ``long_name``."""
    return xr.Variable(dims, np.asarray(data), attrs={"units": units, "long_name": long_name, **attrs})


#: Name of a temporary file of :func:`atomic_output`: ``.NAME.PID.tmp.SUFFIX`` beside the target.
TEMPORARY_NAME = re.compile(r"\..+\.\d+\.tmp(\.[A-Za-z0-9]+)?")


@contextmanager
def atomic_output(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` only if the block succeeds,
    so no partial file ever carries the final name (docs/architecture.md). A process killed outright
    (SIGKILL skips the cleanup) leaves the temporary file: :func:`remove_stale_temporaries`."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def remove_stale_temporaries(root: str | Path) -> list[Path]:
    """Delete every temporary file of :func:`atomic_output` under ``root`` (the debris of
    killed writers) and return their paths. Only safe while nothing writes under ``root``:
    the workflow calls it on start, before any job, under Snakemake's directory lock."""
    root = Path(root)
    stale = [p for p in root.rglob(".*.tmp*") if p.is_file() and TEMPORARY_NAME.fullmatch(p.name)] \
        if root.is_dir() else []
    for p in stale:
        p.unlink(missing_ok=True)
    return stale


@lru_cache(maxsize=1)
def source_digest() -> str:
    """sha256 of the package's own source files (.py and .yaml, sorted by path): ties a result
    to the exact code that made it, with or without git."""
    package = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for f in sorted(p for p in package.rglob("*") if p.suffix in (".py", ".yaml") and "__pycache__" not in p.parts):
        h.update(str(f.relative_to(package)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def add_provenance(ds: xr.Dataset, config: Mapping[str, Any], source: str, title: str) -> xr.Dataset:
    """Attach the global provenance attributes (version, source digest, full config JSON and its
    sha256, source reference)."""
    text, digest = config_digest(config)
    ds.attrs.update({
        "title": title,
        "Conventions": "CF-1.8",
        "gearmesh_version": __version__,
        "gearmesh_source_sha256": source_digest(),
        "config_json": text,
        "config_sha256": digest,
        "source_reference": source,
    })
    return ds


def check_documented(ds: xr.Dataset) -> None:
    """Raise if any data or coordinate variable lacks ``units`` or ``long_name``."""
    for name, var in {**ds.data_vars, **ds.coords}.items():
        missing = [a for a in ("units", "long_name") if a not in var.attrs]
        if missing:
            raise ValueError(f"netCDF variable {name!r} lacks {', '.join(missing)}")


def write_dataset(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically: a temporary file in the same folder, then rename."""
    check_documented(ds)
    for attr in ("gearmesh_version", "config_sha256"):
        if attr not in ds.attrs:
            raise ValueError(f"dataset lacks the provenance attribute {attr!r}")
    encoding = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars
                if ds[name].dtype.kind in "fiu" and ds[name].ndim > 0}
    with atomic_output(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
    return Path(path)


def read_dataset(path: str | Path) -> xr.Dataset:
    """Open a gearmesh netCDF file fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()
