"""netCDF output with CF-style attributes, provenance and atomic writes (docs/modelling.md).

Every variable must carry ``units`` and ``long_name``; :func:`write_dataset` refuses a
dataset that does not, so no stage can write an undocumented number.

Every output is written to a temporary file beside it and renamed (:func:`atomic_output`): a
full disk is named as such; inside a workflow job (:func:`job_outputs`) a job whose Snakemake
is gone, or whose output another process wrote meanwhile, renames nothing. The temporaries of
killed writers are removed on the next run's start when no live process writes them
(:func:`remove_stale_temporaries`), and a study's output folders are checked up front
(:func:`check_output_tree`, and :func:`check_output_files` for a folder where a file belongs). What a stage reads is checked in :mod:`gearmesh.upstream`.
"""

from __future__ import annotations

import errno
import hashlib
import json
import logging
import math
import os
import re
import socket
import struct
import time
import zlib
from contextlib import contextmanager
from contextvars import ContextVar
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable, Iterator, Mapping

import numpy as np
import xarray as xr

from . import __version__
from .choices import FORCE_LINES
from .errors import GearmeshInputError


def config_digest(config: Mapping[str, Any]) -> tuple[str, str]:
    """The config as canonical JSON (sorted keys) and its sha256 hex digest.

    Parameters
    ----------
    config : mapping
        JSON-like (numpy numbers and arrays, paths allowed).
    digest : str
        Its sha256 (hex).
    """
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
    """An xarray Variable with its CF ``units`` and ``long_name``.

    Parameters
    ----------
    dims : str or tuple of str
        The dimensions.
    data : array_like
        The values, in ``units``.
    units : str
        CF/UDUNITS unit (SI: "m", "N", "Pa", "N m-1"; "1" for a ratio).
    long_name : str
        What the values are.
    **attrs
        Further attributes (``engineering_units``, ``flag_values``, ...).

    References
    ----------
    .. [1] Eaton B. et al., NetCDF Climate and Forecast (CF) Metadata Conventions 1.8 (2020), §3.1, §3.2.
    """
    return xr.Variable(dims, np.asarray(data), attrs={"units": units, "long_name": long_name, **attrs})


def name_force_lines(ds: xr.Dataset, line: str) -> xr.Dataset:
    """Mark every force variable (units N) of ``ds`` that names no line as acting along ``line``
    ('transverse' or 'normal', :data:`gearmesh.choices.FORCE_LINES`): its ``force_line``
    attribute, which the CSV copies add to the column name. Returns ``ds`` (changed in place).

    Parameters
    ----------
    ds : xarray.Dataset
        A stage's dataset.
    line : {'transverse', 'normal', 'tangential'}
        The line the unmarked forces act along.

    Raises
    ------
    ValueError
        For a line not in :data:`gearmesh.choices.FORCE_LINES`.
    """
    if line not in FORCE_LINES:
        raise ValueError(f"force line {line!r} is not one of {list(FORCE_LINES)}")
    for var in ds.variables.values():
        if var.attrs.get("units") == "N":
            var.attrs.setdefault("force_line", line)
    return ds


#: Name of a temporary file of :func:`atomic_output`: ``.NAME.HOST.PID.tmp.SUFFIX`` beside the
#: target, HOST the writer's host name (up to its first dot; not all digits), PID its process id;
#: without HOST, a temporary of an earlier gearmesh (removed only by age).
TEMPORARY_NAME = re.compile(r"\.(?P<stem>.+?)(?:\.(?P<host>[A-Za-z0-9-]*[A-Za-z-][A-Za-z0-9-]*))?\.(?P<pid>\d+)"
                            r"\.tmp(?P<suffix>\.[A-Za-z0-9]+)?")
#: Age (s) beyond which a temporary file of another host counts as stale: nothing writes one
#: file for a day (the SLURM profile gives a job at most an hour; a write takes seconds).
STALE_AGE = 24 * 3600.0
#: Free space (bytes) below which a failed write is reported as a full disk (the netCDF library
#: says only "NetCDF: HDF error" when the disk fills).
FULL_DISK_BYTES = 1 << 20


class OutputError(OSError):
    """An output that could not be written, or was not written on purpose: the message is the
    one line ``PATH = 'not written': WHY; WHAT TO DO``."""


def host_name() -> str:
    """This host's name as it appears in temporary file names (letters, digits, '-').

    Returns
    -------
    str
    """
    name = re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname().split(".")[0])
    return name if re.search(r"[A-Za-z-]", name) else f"h{name}"


def temporary_path(path: str | Path) -> Path:
    """The temporary file of ``path`` for this process: ``.NAME.HOST.PID.tmp.SUFFIX`` beside it.

    Parameters
    ----------
    path : str or pathlib.Path
        The final file.
    """
    path = Path(path)
    return path.with_name(f".{path.stem}.{host_name()}.{os.getpid()}.tmp{path.suffix}")


#: The check a workflow job makes before each rename (:func:`job_outputs`); None outside a job.
_before_rename: Callable[[Path], None] | None = None


@contextmanager
def atomic_output(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` only if the block succeeds,
    so no partial file ever carries the final name (docs/architecture.md). A process killed outright
    (SIGKILL skips the cleanup) leaves the temporary file: :func:`remove_stale_temporaries`.

    Parameters
    ----------
    path : str or pathlib.Path
        The final file (its folder is made).

    Yields
    ------
    pathlib.Path
        The temporary file to write.

    Raises
    ------
    OutputError
        Naming ``path``: a write that fails on a full disk; inside a workflow job (:func:`job_outputs`),
        a rename the job's check refuses.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_path(path)
    try:
        yield tmp
        if _before_rename is not None:
            _before_rename(path)
        os.replace(tmp, path)
    except Exception as exc:
        if not isinstance(exc, OutputError) and disk_full(exc, path.parent):
            raise OutputError(f"{path} = 'not written': the disk is full ({_reason(exc)}; "
                              f"{_free_bytes(path.parent) / 1e6:.3g} MB free there); free space and rerun") from exc
        raise
    finally:
        if tmp.exists():
            tmp.unlink()


@contextmanager
def job_outputs() -> Iterator[None]:
    """Inside a workflow job: before each rename of :func:`atomic_output`, refuse
    (:class:`OutputError`, the temporary discarded, the target untouched) when

    * the Snakemake process that started the job is gone (killed with ``kill -9``: its jobs go on
      as orphans, and a recovery run may already be remaking the same files), or
    * the target exists: Snakemake removes a job's outputs before the job starts
      (``snakemake.jobs.Job.prepare``), so another process wrote it meanwhile, a job of a newer
      run or an orphan of an older one; the older writer must not clobber it, the newer one fails
      (Snakemake then removes the file) and the next run remakes it.

    A cluster job's controller runs on another host: there only the second check applies.

    Returns
    -------
    contextlib.AbstractContextManager
        A context manager (:func:`contextlib.contextmanager`).
    """
    global _before_rename
    controller = controller_process()

    def check(path: Path) -> None:
        if controller is not None and not _running(*controller):
            raise OutputError(f"{path} = 'not written': the Snakemake run that started this job is gone (killed?); "
                              "run snakemake --unlock, then rerun with --rerun-incomplete")
        if os.path.lexists(path):
            raise OutputError(f"{path} = 'not written': another process wrote it while this job ran (a job of a "
                              "killed run?); this job's result is discarded: rerun to remake it")

    previous, _before_rename = _before_rename, check
    try:
        yield
    finally:
        _before_rename = previous


#: Seconds between two looks of a job's watcher (:func:`stop_with_controller`) at its controller.
WATCH_INTERVAL = 0.5
#: The watcher of :func:`stop_with_controller`: a bare interpreter (no site, no imports but os and
#: time) given the job's and the controller's process ids, each with its start (field 22 of
#: /proc/PID/stat, so a reused process id is not taken for it), and the interval. A zombie is
#: gone: a killed controller whose parent does not reap it (a container's first process) stays
#: in the process table.
_WATCHER = """
import os, sys, time
job, job_started, controller, started, interval = sys.argv[1:6]
def alive(pid, started):
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass
    try:
        with open(f"/proc/{pid}/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
    except OSError:  # no /proc (not Linux): kill's answer; with /proc, the process has just gone
        return not os.path.isdir("/proc")
    return fields[0] != "Z" and (not started or fields[19] == started)
while alive(job, job_started):
    if not alive(controller, started):
        os.kill(int(job), 9)
        break
    time.sleep(float(interval))
"""


@contextmanager
def stop_with_controller(interval: float = WATCH_INTERVAL) -> Iterator[None]:
    """Inside a workflow job in a process of its own (no job server): a watcher process kills the job
    (SIGKILL) within ``interval`` seconds once the Snakemake process that started it is gone (``kill -9``:
    nobody waits for the job, and a recovery run may be remaking its files); it ends with the block.
    Not a thread: a compiled loop (the dynamics' RK4, seconds to minutes) holds the interpreter; not a
    fork: the job would pay a copy of every page it then writes. A job on the run's job server is stopped
    by the server (:mod:`gearmesh.jobserver`). Without a Snakemake ancestor (a cluster job, whose
    controller runs elsewhere) it does nothing; :func:`job_outputs` still keeps an orphan from writing.

    Parameters
    ----------
    interval : float, default WATCH_INTERVAL
        Seconds between the watcher's checks.
    """
    import subprocess
    import sys

    controller = controller_process()
    watcher = None
    if controller is not None:
        job = os.getpid()
        watcher = subprocess.Popen([sys.executable, "-I", "-S", "-c", _WATCHER, str(job), _start_ticks(job),
                                    str(controller[0]), _start_ticks(controller[0]), repr(interval)],
                                   stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        yield
    finally:
        if watcher is not None:
            watcher.kill()
            watcher.wait()


def _start_ticks(pid: int) -> str:
    """When process ``pid`` started (field 22 of /proc/PID/stat, clock ticks since boot), '' off Linux."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            return stat.read().rsplit(")", 1)[1].split()[19]
    except (OSError, IndexError):
        return ""


def controller_process() -> tuple[int, float] | None:
    """(pid, start time) of the nearest ancestor that is a Snakemake process (``.../snakemake``
    or ``python -m snakemake``), or None (no such ancestor, or no psutil).

    Returns
    -------
    tuple of (int, float) or None
        Process id and start time (s since the epoch, psutil's ``create_time``).
    """
    try:
        import psutil  # a Snakemake dependency
    except ImportError:  # pragma: no cover
        return None
    try:
        for proc in psutil.Process().parents():
            args = proc.cmdline()
            if any(Path(a).name == "snakemake" for a in args[:2]) or args[1:3] == ["-m", "snakemake"]:
                return proc.pid, proc.create_time()
    except psutil.Error:
        return None
    return None


def _running(pid: int, started: float) -> bool:
    """Whether process ``pid`` still runs and is the one that started at ``started`` (not a reuse, not
    a zombie: a killed process its parent has not reaped)."""
    import psutil

    try:
        process = psutil.Process(pid)
        return process.create_time() == started and process.status() != psutil.STATUS_ZOMBIE
    except psutil.Error:
        return False


def space_errno(exc: BaseException) -> int | None:
    """ENOSPC or EDQUOT when ``exc`` or an exception that caused it is one, else None.

    Parameters
    ----------
    exc : BaseException
        The exception of a failed write.
    """
    seen: BaseException | None = exc
    while seen is not None:
        if isinstance(seen, OSError) and seen.errno in (errno.ENOSPC, errno.EDQUOT):
            return seen.errno
        seen = seen.__cause__ or seen.__context__
    return None


def disk_full(exc: BaseException, folder: Path) -> bool:
    """Whether ``exc`` (or what caused it) is a full disk or quota (ENOSPC, EDQUOT), or a library
    error on a file system with less than :data:`FULL_DISK_BYTES` left.

    Parameters
    ----------
    exc : BaseException
        The exception of a failed write.
    folder : pathlib.Path
        The folder written to.
    """
    if space_errno(exc) is not None:
        return True
    return isinstance(exc, (OSError, RuntimeError)) and _free_bytes(folder) < FULL_DISK_BYTES


def _free_bytes(folder: Path) -> float:
    """Bytes an unprivileged process can still write on ``folder``'s file system (inf if unknown)."""
    try:
        st = os.statvfs(folder)
    except (OSError, AttributeError):
        return math.inf
    return float(st.f_bavail * st.f_frsize)


def _reason(exc: BaseException) -> str:
    """The failed write's cause in a few words (the system's text for ENOSPC/EDQUOT)."""
    code = space_errno(exc)
    return os.strerror(code) if code is not None else " ".join(str(exc).split())[:80] or type(exc).__name__


def writer_alive(pid: int) -> bool:
    """Whether process ``pid`` of this host exists (a process of another user counts).

    Parameters
    ----------
    pid : int
        A process id of this host.
    """
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale_temporaries(root: str | Path, now: float | None = None) -> list[Path]:
    """Delete the temporary files of :func:`atomic_output` under ``root`` that no live process writes,
    and return their paths: those of this host whose writer (its PID) is gone, and those of any host
    untouched for :data:`STALE_AGE`. A temporary of a live writer stays, so two runs in one checkout
    (different studies, or a run beside a job of a killed one) do not delete each other's files in
    flight; the workflow calls it on start.

    Parameters
    ----------
    root : str or pathlib.Path
        The folder searched (recursively); none when it does not exist.
    now : float, optional
        The time (s since the epoch); default the clock's.
    """
    root = Path(root)
    now = time.time() if now is None else now
    host = host_name()
    stale = []
    for p in (root.rglob(".*.tmp*") if root.is_dir() else ()):
        match = TEMPORARY_NAME.fullmatch(p.name)
        try:
            if not match or not p.is_file():
                continue
            if match["host"] == host and not writer_alive(int(match["pid"])) or now - p.stat().st_mtime > STALE_AGE:
                p.unlink()
                stale.append(p)
        except FileNotFoundError:  # renamed or removed by its writer meanwhile
            continue
    return stale


def study_folders(config: Mapping[str, Any]) -> list[Path]:
    """The folders a study's jobs write into (relative to the working directory): results and
    logs of the study, of each pair, of each micro-geometry variant and optimisation run, and
    their ``plots`` folders.

    Parameters
    ----------
    config : mapping
        A validated study config.
    """
    study = str(config["study"])
    leaves = [Path("results", study, "plots"), Path("logs", study)]
    for pair in config.get("pairs", []):
        base = Path(str(pair))
        leaves += [Path("results", study, base, "plots"), Path("logs", study, base, "optimise")]
        for variant in config.get("variants") or {}:
            leaves += [Path("results", study, base, str(variant), "plots"), Path("logs", study, base, str(variant))]
        for run in config.get("optimise") or {}:
            leaves.append(Path("results", study, base, "optimise", str(run), "plots"))
    return leaves


def check_output_tree(folders, root: str | Path = ".") -> None:
    """Refuse (GearmeshInputError) when a folder of ``folders``, or one above it, exists under
    ``root`` as something other than a folder (a file, a dangling link): the jobs could not
    write there, and Snakemake would stop mid-run with a traceback.

    Parameters
    ----------
    folders : iterable of pathlib.Path
        Folders relative to ``root`` (:func:`study_folders`).
    root : str or pathlib.Path, default "."
        The working directory of the study.

    Raises
    ------
    GearmeshInputError
        Naming the first path that exists and is not a folder.
    """
    root, seen = Path(root), set()
    for folder in folders:
        for part in reversed([folder, *folder.parents][:-1]):  # from the top, without '.'
            if part in seen:
                continue
            seen.add(part)
            path = root / part
            if os.path.lexists(path) and not path.is_dir():
                kind = "a link to nothing" if path.is_symlink() and not path.exists() else "a file"
                raise GearmeshInputError(str(part), kind, "must be a folder: the study writes its results under "
                                         "it; move or delete it")


def output_pattern(pattern: str) -> re.Pattern[str]:
    """The regular expression of a Snakemake output pattern (``results/{study}/{pair}/tca.nc``):
    each ``{wildcard}`` (with or without its own ``,regex``) one path component or more of
    one, the rest literal.

    Parameters
    ----------
    pattern : str
        A Snakemake output pattern.
    """
    parts = re.split(r"\{([^{}]+)\}", pattern)
    return re.compile("".join(re.escape(p) if k % 2 == 0 else "[^/]+" for k, p in enumerate(parts)))


def check_output_files(patterns, roots, root: str | Path = ".") -> None:
    """Refuse (GearmeshInputError) a folder under ``roots`` (e.g. ``results/STUDY``) where an
    output of ``patterns`` (the rules' file outputs) belongs: Snakemake takes an existing path
    for a made file, skips its job and leaves the result and its figure missing. Walks the
    folders only (a study has tens of them).

    Parameters
    ----------
    patterns : iterable of str
        The rules' output patterns.
    roots : iterable of str or pathlib.Path
        The folders walked, relative to ``root``.
    root : str or pathlib.Path, default "."
        The working directory of the study.

    Raises
    ------
    GearmeshInputError
        Naming the first folder that stands where an output file belongs.
    """
    regexes = [output_pattern(str(p)) for p in patterns]
    root = Path(root)
    for top in roots:
        for folder, dirs, _ in os.walk(root / top):
            for name in dirs:
                rel = (Path(folder) / name).relative_to(root).as_posix()
                if any(r.fullmatch(rel) for r in regexes):
                    raise GearmeshInputError(rel, "a folder", "must be a file: the study writes one of its results "
                                             "there; move or delete the folder, then rerun")


@lru_cache(maxsize=1)
def source_digest() -> str:
    """sha256 of the package's own source files (.py and .yaml, sorted by path): ties a result
    to the exact code that made it, with or without git.

    Returns
    -------
    str
        sha256 (hex), computed once per process.
    """
    package = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for f in sorted(p for p in package.rglob("*") if p.suffix in (".py", ".yaml") and "__pycache__" not in p.parts):
        h.update(str(f.relative_to(package)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def add_provenance(ds: xr.Dataset, config: Mapping[str, Any], source: str, title: str) -> xr.Dataset:
    """Attach the global provenance attributes (version, source digest, full config JSON and its
    sha256, source reference).

    Parameters
    ----------
    ds : xarray.Dataset
        A stage's dataset, changed in place.
    config : mapping
        What it was made from (the study settings and the pair data), JSON-like.
    source : str
        Where the model comes from (paper, standard).
    title : str
        The dataset's CF ``title``.

    Returns
    -------
    xarray.Dataset
        ``ds``, with ``Conventions = "CF-1.8"``.

    References
    ----------
    .. [1] Eaton B. et al., NetCDF Climate and Forecast (CF) Metadata Conventions 1.8 (2020), §2.6.
    """
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


#: Global attribute: the sha256 of a file's own data (:func:`data_digest`), written by
#: :func:`write_dataset` and compared by :func:`gearmesh.upstream.check_input` and ``gearmesh check``.
DATA_ATTR = "gearmesh_data_sha256"


def data_digest(ds: xr.Dataset) -> str:
    """sha256 of every data and coordinate variable of ``ds`` (name, dimensions, shape and the
    values: numbers by their bytes in little-endian order, text as UTF-8), in name order. The
    same before writing and after reading back (netCDF keeps dtypes; strings come back as
    objects, hashed by their text); an edited value changes it.

    Parameters
    ----------
    ds : xarray.Dataset
        Any dataset.
    """
    h = hashlib.sha256()
    for name in sorted(map(str, {**ds.data_vars, **ds.coords})):
        var = ds[name].variable
        values = np.asarray(var.values)
        h.update(json.dumps([name, list(var.dims), list(values.shape)]).encode())
        if values.dtype.kind in "OUS":
            h.update(json.dumps([str(v) for v in values.ravel().tolist()]).encode())
        else:
            h.update(values.dtype.newbyteorder("<").str.encode())
            h.update(np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("<")).tobytes())
    return h.hexdigest()


def check_documented(ds: xr.Dataset) -> None:
    """Raise if any data or coordinate variable lacks ``units`` or ``long_name``.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset about to be written.

    Raises
    ------
    ValueError
        Naming the first variable without ``units`` or ``long_name``.
    """
    for name, var in {**ds.data_vars, **ds.coords}.items():
        missing = [a for a in ("units", "long_name") if a not in var.attrs]
        if missing:
            raise ValueError(f"netCDF variable {name!r} lacks {', '.join(missing)}")


#: Suffix of a dataset attribute that is a measured time (s, e.g. the GA's ``wall_seconds``): it
#: differs from run to run, so it is no datum (outside :func:`data_digest`, which covers the
#: variables) and :func:`write_dataset` leaves it out of the file, whose bytes then depend on the
#: inputs and the code alone (two runs give the same file), and logs it (a job's log).
TIMING_SUFFIX = "_seconds"


def write_dataset(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically: a temporary file in the same folder, then rename; its
    measured times (attributes ending in :data:`TIMING_SUFFIX`) to the log instead of the file.

    Parameters
    ----------
    ds : xarray.Dataset
        A documented dataset with provenance (:func:`add_provenance`); its data digest is added.
    path : str or pathlib.Path
        The netCDF file.

    Raises
    ------
    ValueError
        For an undocumented variable or missing provenance.
    OutputError
        From :func:`atomic_output`.
    """
    check_documented(ds)
    for attr in ("gearmesh_version", "config_sha256"):
        if attr not in ds.attrs:
            raise ValueError(f"dataset lacks the provenance attribute {attr!r}")
    ds.attrs[DATA_ATTR] = data_digest(ds)
    timings = {k: v for k, v in ds.attrs.items() if k.endswith(TIMING_SUFFIX)}
    if timings:
        logging.getLogger(__name__).info("%s: %s", path, ", ".join(f"{k} {float(v):.3f}" for k, v in timings.items()))
    out = ds.copy(deep=False)
    out.attrs = {k: v for k, v in ds.attrs.items() if k not in timings}
    encoding = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars
                if ds[name].dtype.kind in "fiu" and ds[name].ndim > 0}
    with atomic_output(path) as tmp:
        out.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
    return Path(path)


def normal_path(path: str | Path) -> str:
    """``path`` as written in the provenance: normalised, relative as given, POSIX separators.

    Parameters
    ----------
    path : str or pathlib.Path
    """
    return Path(os.path.normpath(path)).as_posix()


# --------------------------------------------------------------------------------------
# Figures carry their provenance
# --------------------------------------------------------------------------------------

#: Keyword of the PNG text chunk (tEXt) in which a figure a workflow job drew carries its
#: provenance (:func:`stamp_figure`): JSON {file, drawn_from, image_sha256}.
FIGURE_KEY = b"gearmesh"
_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: The files the figures being drawn come from, {path: digest} (:func:`figure_sources`); None
#: outside a workflow job's drawing.
_figure_sources: ContextVar[dict[str, str] | None] = ContextVar("gearmesh_figure_sources", default=None)


@contextmanager
def figure_sources(sources: Mapping[str, str]) -> Iterator[None]:
    """Inside the block every figure saved (:func:`gearmesh.plots.common.save`) records that it
    was drawn from ``sources`` ({path: digest}: the netCDF files of the job, by their data digest,
    or the input files of a figure job), beside its own path and digest (:func:`stamp_figure`).

    Parameters
    ----------
    sources : mapping of str to str
        Path to digest of every file the job's figures are drawn from.
    """
    token = _figure_sources.set({normal_path(k): str(v) for k, v in sorted(sources.items())})
    try:
        yield
    finally:
        _figure_sources.reset(token)


def _png_chunks(data: bytes) -> Iterator[tuple[int, int, bytes, bytes]]:
    """(start, end, type, payload) of each chunk of the PNG ``data``; stops at the first chunk
    that does not fit (a truncated or foreign file)."""
    at = len(_PNG_SIGNATURE)
    while at + 12 <= len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        end = at + 12 + length
        if end > len(data):
            return
        yield at, end, data[at + 4:at + 8], data[at + 8:at + 8 + length]
        at = end


def stamp_figure(png: bytes, path: str | Path) -> bytes:
    """``png`` (a PNG file's bytes) with its provenance as a tEXt chunk :data:`FIGURE_KEY` after
    the header when it is drawn inside :func:`figure_sources`: the file it is written as, the files
    it was drawn from with their digests and the sha256 of the PNG without that chunk (so an edited
    or replaced figure, a copy of another job's and one drawn from a file that has changed since
    are told apart: :func:`gearmesh.upstream.check_figure`). Outside a job's drawing, as it is.
    Nothing in it depends on the run (no time or host): two runs give the same bytes.

    Parameters
    ----------
    png : bytes
        The PNG file's bytes.
    path : str or pathlib.Path
        The file it is written as.

    References
    ----------
    .. [1] W3C, PNG Specification (Second Edition), ISO/IEC 15948:2003, §5.3 (chunks), §11.3.4.3 (tEXt).
    """
    sources = _figure_sources.get()
    if sources is None or not png.startswith(_PNG_SIGNATURE):
        return png
    meta = {"file": normal_path(path), "drawn_from": sources, "image_sha256": hashlib.sha256(png).hexdigest()}
    payload = FIGURE_KEY + b"\0" + json.dumps(meta, sort_keys=True).encode("ascii")
    chunk = struct.pack(">I", len(payload)) + b"tEXt" + payload + struct.pack(">I", zlib.crc32(b"tEXt" + payload))
    _, header_end, _, _ = next(_png_chunks(png))  # IHDR, always the first chunk
    return png[:header_end] + chunk + png[header_end:]


def figure_provenance(data: bytes) -> tuple[dict[str, Any] | None, str]:
    """The provenance a figure's bytes ``data`` carry (:func:`stamp_figure`; None when it carries
    none or is not a PNG) and the sha256 of the bytes without it.

    Parameters
    ----------
    data : bytes
        A figure file's bytes.

    Returns
    -------
    meta : dict or None
        ``file``, ``drawn_from`` ({path: digest}) and ``image_sha256``.
    digest : str
        sha256 (hex) of ``data`` without the provenance chunk.
    """
    if data.startswith(_PNG_SIGNATURE):
        for start, end, kind, payload in _png_chunks(data):
            if kind == b"tEXt" and payload.startswith(FIGURE_KEY + b"\0"):
                rest = data[:start] + data[end:]
                try:
                    meta = json.loads(payload[len(FIGURE_KEY) + 1:].decode("ascii"))
                except ValueError:
                    meta = None
                return (meta if isinstance(meta, dict) else None), hashlib.sha256(rest).hexdigest()
    return None, hashlib.sha256(data).hexdigest()


def read_dataset(path: str | Path) -> xr.Dataset:
    """Open a gearmesh netCDF file fully into memory (the file is closed on return).

    Parameters
    ----------
    path : str or pathlib.Path
        A netCDF file.
    """
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()
