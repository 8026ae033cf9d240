"""The glue between a Snakemake job and the package: logging, provenance, atomic output.

Every rule names the one package function it runs in ``params.function``
("module:function") and passes its settings in ``params.settings``; its script
(``workflow/scripts/job.py``) calls :func:`run_job`, which runs the ``run_*`` function its stage
declaration names (:attr:`gearmesh.stages.Stage.runner`). A job's outputs are told apart by suffix: one ``.nc`` (the
dataset), an optional ``.csv`` copy, and ``.png`` figures drawn by the plot function
``params.figures`` from the netCDF file just written, in the same process (a figure job of
its own would cost a Python start-up and the imports for a fraction of a second's drawing).
Provenance (the study config and the pair data as JSON with its sha256) is attached here and
each file is written atomically, so a failing job leaves no output with its final name.
"""

from __future__ import annotations

import functools
import importlib
import logging
import os
import re
import resource
import sys
import time
from pathlib import Path
from typing import Any, Callable, Mapping

import xarray as xr

from .gear import GearPair
from .pairfile import load_pair, pair_notes, pair_to_dict, variant_pair
from .io import (DATA_ATTR, OutputError, add_provenance, atomic_output, figure_sources, job_outputs, normal_path,
                 read_dataset, space_errno, write_dataset)
from .registry import job_of, stage_of
from .stages import dependencies
from .tables import write_csv
from .upstream import (Expected, check_optimum, file_digest, identify, optimum_header, read_input, record_sources,
                       record_tables)


def provenance_config(study: Mapping[str, Any], pair: GearPair | None = None) -> dict[str, Any]:
    """What a result depends on: the study config and, for a pair stage, the pair data.

    Parameters
    ----------
    study : mapping
        The validated study config.
    pair : GearPair, optional
        The stage's pair (None for a stage over several pairs).

    Returns
    -------
    dict
        ``{"study": ..., "pair": ...}``, the pair as its pair-file keys (engineering units).
    """
    out: dict[str, Any] = {"study": dict(study)}
    if pair is not None:
        out["pair"] = pair_to_dict(pair)
    return out


def finish(ds: xr.Dataset, path: str | Path, study: Mapping[str, Any], pair: GearPair | None,
           title: str) -> Path:
    """Attach provenance and the pair name to ``ds`` and write it atomically.

    Parameters
    ----------
    ds : xarray.Dataset
        The stage's documented dataset; its attributes are changed in place.
    path : str or pathlib.Path
        The netCDF file.
    study : mapping
        The validated study config (its ``study`` name and ``source``).
    pair : GearPair or None
        The stage's pair (its name, notes and source), None for a stage over several pairs.
    title : str
        The dataset's ``title`` attribute.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        An undocumented variable (:func:`gearmesh.io.write_dataset`).
    OutputError
        The file could not be written.
    """
    source = pair.source if pair is not None and pair.source else study.get("source", "")
    add_provenance(ds, provenance_config(study, pair), source, title)
    if pair is not None:
        ds.attrs["pair_name"] = pair.name
        ds.attrs["pair_notes"] = "; ".join(pair_notes(pair))  # e.g. the material defaults used
    ds.attrs["study"] = study.get("study", "")
    return write_dataset(ds, path)


def resolve(spec: str) -> Callable[..., Any]:
    """The function named by "package.module:function", with or without the "@digest" that
    :func:`gearmesh.codeversion.versioned` appends.

    Parameters
    ----------
    spec : str
        ``"package.module:function"``, optionally followed by ``"@digest"``.

    Returns
    -------
    callable
        The function, its module imported.
    """
    module, _, name = spec.partition("@")[0].partition(":")
    return getattr(importlib.import_module(module), name)


def _process_age() -> float | None:
    """Seconds since the job's script started (interpreter start-up, Snakemake's script
    preamble and every import included), as :func:`gearmesh.jobserver.run` exports it in
    ``GEARMESH_JOB_STARTED``, or None where the start is not known (not Linux, or called
    without it)."""
    started = os.environ.get("GEARMESH_JOB_STARTED")
    return None if not started else time.time() - float(started)


def _cpu_seconds() -> float:
    """CPU time (user + system, s) this process has used so far."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def _run(smk: Any, body: Callable[[Any], float]) -> None:
    """Run one job with its log file; exit non-zero with the reason on failure.

    The last log line says how the job's time went: ``done in W s (figures F s) after S s of
    start-up, CPU C1 s + C2 s``, W the work inside the package (reading, computing, writing,
    drawing), S the time from the process start to the work (Python, Snakemake's script
    preamble, importing the modules of the job's functions), C1 and C2 the CPU time of each. ``benchmarks/bench_workflow.py`` sums both over a study's
    logs (the job overhead)."""
    log_path = Path(smk.log[0])
    log_path.parent.mkdir(parents=True, exist_ok=True)
    logging.basicConfig(filename=log_path, level=logging.INFO, filemode="w",
                        format="%(asctime)s %(levelname)s %(message)s", force=True)
    logging.raiseExceptions = False  # a log that cannot be written (full disk) must not bury the error line
    try:
        for name in ("function", "figures"):  # imports are start-up, not work
            if getattr(smk.params, name, None):
                resolve(getattr(smk.params, name))
        age, cpu = _process_age(), _cpu_seconds()
        start = time.perf_counter()
        with job_outputs():  # an orphan of a killed run, or a clobbered output, writes nothing
            figures = body(smk)
    except Exception as exc:  # the log and stderr get the reason; Snakemake sees the exit code
        logging.exception("job failed")
        print(f"gearmesh: error: {error_line(exc)}", file=sys.stderr)
        sys.exit(2 if isinstance(exc, ValueError) else 1)
    # wall time and peak memory of every job, the measurements behind the profiles' resources
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # Linux: kB
    startup = "" if age is None else f" after {age:.2f} s of start-up"
    logging.info("done in %.2f s (figures %.2f s)%s, CPU %.2f s + %.2f s, peak RSS %.0f MB (threads %s): %s",
                 time.perf_counter() - start, figures or 0.0, startup, cpu, _cpu_seconds() - cpu, peak_mb,
                 getattr(smk, "threads", 1), ", ".join(map(str, smk.output)))


def error_line(exc: BaseException) -> str:
    """The one line a failed job prints: the exception's text; for a full disk reported without a
    path (a library's own write: numba's cache of compiled code under the package's
    ``__pycache__`` or ``NUMBA_CACHE_DIR``), the file being written, from the traceback.

    Parameters
    ----------
    exc : BaseException
        The job's exception, with its traceback.

    Returns
    -------
    str
        The line, without the ``gearmesh: error:`` prefix.
    """
    code = space_errno(exc)
    if code is None or isinstance(exc, OutputError) or getattr(exc, "filename", None):
        return str(exc)
    path, where = _file_being_written(exc)
    if path is None:
        return f"{exc} (the disk is full: free space and rerun)"
    numba = " (numba's cache of compiled code; NUMBA_CACHE_DIR moves it)" if "numba" in where else ""
    return f"{path} = 'not written': the disk is full ({os.strerror(code)}){numba}; free space and rerun"


def _file_being_written(exc: BaseException) -> tuple[str | None, str]:
    """The file a failed write was writing: the last file opened for writing among the locals of
    the frames ``exc`` passed through (innermost wins), its name without a temporary's suffix
    (numba writes ``NAME.tmp.UID``), and the source file of that frame."""
    found: tuple[str | None, str] = (None, "")
    tb = exc.__traceback__
    while tb is not None:
        for local, value in tb.tb_frame.f_locals.items():
            if local == "self":  # the file's own method, not the code writing to it
                continue
            name, mode = getattr(value, "name", None), getattr(value, "mode", "")
            if isinstance(name, str) and isinstance(mode, str) and any(c in mode for c in "wax+"):
                found = (re.sub(r"\.tmp\.[0-9a-f]+$", "", name), tb.tb_frame.f_code.co_filename)
        tb = tb.tb_next
    return found


def _title(smk: Any) -> str:
    return f"gearmesh {smk.rule}"


def study_pair(config: Mapping[str, Any], name: str, variant: str | None) -> GearPair:
    """The pair ``name`` of a study as its ``variant``'s stages use it (None: the pair file):
    the pair file with the variant's micro-geometry, or an optimisation's pair file.

    Parameters
    ----------
    config : mapping
        The validated study config (``pairs_dir``, ``variants``, ``study``).
    name : str
        The pair's name.
    variant : str or None
        The micro-geometry variant's name; None for the pair file as it is.

    Returns
    -------
    GearPair
        The pair, SI units.

    Raises
    ------
    GearmeshInputError
        A ``{from: optimise.NAME}`` variant whose pair file is not the optimum this study's run
        wrote (:func:`gearmesh.upstream.check_optimum`), or a malformed pair file or variant.
    """
    from .config import pair_path

    spec = (config.get("variants") or {}).get(variant) if variant is not None else None
    pair = load_pair(pair_path(config, name))
    if spec is not None and spec.get("from"):
        source = Path("results", str(config["study"]), name, "optimise", spec["from"].split(".", 1)[1], "pair.yaml")
        check_optimum(source, Expected(config, pair))
        return variant_pair(load_pair(source), variant, spec)
    return pair if spec is None else variant_pair(pair, variant, spec)


def _expected(smk: Any, pair: GearPair | None = None) -> Expected:
    """What this job expects of the files it reads (:mod:`gearmesh.upstream`); a stage over
    several pairs or variants (a study table) expects each file's own pair and variant."""
    pair_of = functools.lru_cache(maxsize=None)(lambda name, variant: study_pair(smk.config, name, variant))
    return Expected(smk.config, pair, getattr(smk.wildcards, "variant", None), None if pair is not None else pair_of)


def _outputs(smk: Any, suffix: str) -> dict[str, str]:
    """The job's named outputs whose path ends with ``suffix`` ('.nc', '.csv', '.png')."""
    return {k: str(v) for k, v in smk.output.items() if str(v).endswith(suffix)}


def _draw(smk: Any, inputs: dict[str, Any]) -> float:
    """Draw the job's figures (its ``.png`` outputs, by output name) with the plot function
    ``params.figures`` from the netCDF file the job wrote (read back, so a figure shows what the
    file holds; passed under its file stem, e.g. 'ltca') and from ``inputs``; the seconds it took."""
    spec = getattr(smk.params, "figures", None)
    if not spec:
        return 0.0
    start = time.perf_counter()
    written = {path: read_dataset(path) for path in _outputs(smk, ".nc").values()}
    with figure_sources({path: ds.attrs[DATA_ATTR] for path, ds in written.items()}):
        resolve(spec)({**inputs, **{Path(path).stem: ds for path, ds in written.items()}}, _outputs(smk, ".png"))
    return time.perf_counter() - start


def _write_outputs(smk: Any, ds: xr.Dataset, pair: GearPair | None) -> None:
    """The dataset to its CSV output if any, then to the job's netCDF output (provenance, what it
    is and what it was made from attached: :func:`gearmesh.upstream.record_sources`, and the
    sha256 of each CSV written: :func:`gearmesh.upstream.record_tables`)."""
    (nc,) = _outputs(smk, ".nc").values()
    tables = {}
    for csv in _outputs(smk, ".csv").values():
        with atomic_output(csv) as tmp:
            write_csv(ds, tmp)
            tables[csv] = file_digest(tmp)
    identify(ds, nc, smk.rule, smk.wildcards, getattr(smk.params, "function", None))
    record_sources(ds, _input_files(smk), _sections(smk))
    record_tables(ds, tables)
    finish(ds, nc, smk.config, pair, _title(smk))


def _input_files(smk: Any) -> list[str]:
    """Every input file of the job (pair files and netCDF files), flattened."""
    out: list[str] = []
    for value in smk.input.values() if hasattr(smk.input, "values") else smk.input:
        out += [str(v) for v in value] if isinstance(value, list) else [str(value)]
    return out


def _sections(smk: Any) -> list[str]:
    """The study config sections the job's result depends on: its rule's, and every section its
    stage carries whole (:func:`gearmesh.stages.dependencies`: the impact stage's ``tolerances``,
    an optimisation's ``impact``)."""
    return dependencies(stage_of(smk.rule), smk.rule, smk.config)


def _job_pair(smk: Any) -> GearPair:
    """The job's pair: its pair file, carrying the micro-geometry of its variant when the rule
    names one (``params.variant``: the variant's spec from the study config); an optimisation's
    pair file (a variant ``{from: optimise.NAME}``) checked first (:func:`gearmesh.upstream.check_optimum`)."""
    spec = getattr(smk.params, "variant", None)
    if spec is not None and spec.get("from"):  # this study's optimum: its run made for the study's pair and settings
        check_optimum(smk.input.pair, Expected(smk.config, study_pair(smk.config, smk.wildcards.pair, None)))
    pair = load_pair(smk.input.pair)
    return pair if spec is None else variant_pair(pair, smk.wildcards.variant, spec)


def _pair_stage(smk: Any, then: Callable[[GearPair, xr.Dataset], None] | None = None) -> None:
    """A stage of one pair: ``function(pair, **settings, **upstream datasets)`` -> Dataset,
    written, then ``then(pair, dataset)``, then the figures drawn from it. Named inputs other
    than ``pair`` are netCDF files of upstream stages, read, checked for this job's pair
    (:mod:`gearmesh.upstream`) and passed by name."""
    def body(smk: Any) -> float:
        pair = _job_pair(smk)
        upstream = _read_inputs(smk, pair)
        ds = resolve(smk.params.function)(pair, **dict(smk.params.settings), **upstream)
        _write_outputs(smk, ds, pair)
        if then is not None:
            then(pair, ds)
        return _draw(smk, upstream)

    _run(smk, body)


def run_job(smk: Any) -> None:
    """The job of rule ``smk.rule`` as its declaration says (:func:`gearmesh.registry.job_of`):
    ``run_pair_stage``, ``run_study_stage``, ``run_collect``, ``run_optimise`` or ``run_plot``.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object: ``input``, ``output``, ``params`` (``function``, ``settings``,
        ``figures``), ``log``, ``wildcards``, ``config``, ``rule``.

    Returns
    -------
    None
        The outputs written (``.nc``, ``.csv``, ``.png``) and the log's last line.

    Raises
    ------
    SystemExit
        On failure, after one ``gearmesh: error: ...`` line on stderr and the traceback in the
        log: code 2 for bad input (a ``ValueError``), 1 otherwise.

    References
    ----------
    .. [1] Snakemake documentation, "Snakefiles and Rules": external scripts (the ``script``
       directive and its ``snakemake`` object) and non-file parameters for rules (``params``).
    """
    RUNNERS[job_of(smk.rule).runner](smk)


def run_pair_stage(smk: Any) -> None:
    """A stage of one pair (:func:`_pair_stage`).

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (:func:`run_job`).

    Raises
    ------
    SystemExit
        On failure, as :func:`run_job` says.
    """
    _pair_stage(smk)


def run_study_stage(smk: Any) -> None:
    """A stage over several pairs: ``function(gear_pairs, **section)`` -> Dataset, and its figures;
    ``gear_pairs`` the pair files the section's ``pairs`` name (its inputs, in that order), loaded,
    by the section's names.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (:func:`run_job`).

    Raises
    ------
    SystemExit
        On failure, as :func:`run_job` says.
    """
    def body(smk: Any) -> float:
        section = dict(smk.params.settings)
        gear_pairs = dict(zip(section["pairs"], map(load_pair, smk.input.pairs), strict=True))
        _write_outputs(smk, resolve(smk.params.function)(gear_pairs, **section), None)
        return _draw(smk, {})

    _run(smk, body)


def _read_inputs(smk: Any, pair: GearPair | None = None) -> dict[str, Any]:
    """Every named netCDF input (all but ``pair``) as a Dataset, or a list of Datasets for a list
    of files, each checked to be what this job expects (:func:`gearmesh.upstream.read_input`)."""
    expected = _expected(smk, pair)
    return {k: [read_input(p, expected) for p in v] if isinstance(v, list) else read_input(v, expected)
            for k, v in smk.input.items() if k != "pair"}


def run_collect(smk: Any) -> None:
    """A study table from per-pair results: ``function(**{input name: [Dataset, ...]}, **settings)``,
    and its figures (drawn from the inputs and the table).

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (:func:`run_job`).

    Raises
    ------
    SystemExit
        On failure, as :func:`run_job` says.
    """
    def body(smk: Any) -> float:
        inputs = _read_inputs(smk)
        lists = {k: v if isinstance(v, list) else [v] for k, v in inputs.items()}
        settings = dict(getattr(smk.params, "settings", None) or {})
        _write_outputs(smk, resolve(smk.params.function)(**lists, **settings), None)
        return _draw(smk, inputs)

    _run(smk, body)


def run_plot(smk: Any) -> None:
    """Figures alone: ``function({input name: Dataset}, {output name: path})`` writes the PNGs.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (:func:`run_job`).

    Raises
    ------
    SystemExit
        On failure, as :func:`run_job` says.
    """
    def body(smk: Any) -> float:
        start = time.perf_counter()
        inputs = _read_inputs(smk)
        with figure_sources({path: file_digest(path) for path in _input_files(smk)}):
            resolve(smk.params.function)(inputs, dict(smk.output.items()))
        return time.perf_counter() - start

    _run(smk, body)


def write_pair(pair: GearPair, path: str | Path, made_by: Mapping[str, Any] | None = None) -> Path:
    """Write ``pair`` as a pair file (YAML, engineering units), checked by pair_geometry first;
    with ``made_by`` (the run that wrote it) its first line is the provenance comment of
    :func:`gearmesh.upstream.optimum_header` (the content's digest and that run).

    Floats are kept to :data:`PAIR_FILE_DIGITS` significant digits.

    Parameters
    ----------
    pair : GearPair
        The pair (SI units; written in the pair file's engineering units).
    path : str or pathlib.Path
        The YAML file, written atomically.
    made_by : mapping, optional
        ``ga`` (the run's ga.nc) and ``data_sha256`` (its data digest); None: no provenance line.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    GearmeshInputError
        A pair that :func:`gearmesh.gear.pair_geometry` refuses (nothing written).
    """
    import yaml

    from .gear import pair_geometry

    pair_geometry(pair)
    body = yaml.safe_dump(_tidy(pair_to_dict(pair)), sort_keys=False)
    with atomic_output(path) as tmp:
        tmp.write_text(body if made_by is None else optimum_header(path, body, made_by) + body)
    return Path(path)


#: Significant digits a pair file keeps: 12 remove the round trip through SI (5 µm -> 5e-06 m ->
#: 5.000000000000001 µm) and keep an optimum to 5e-13 of itself, so a command reading the file
#: computes what the optimiser reported (to 1e-9; a 9-decimal rounding moved F_s by 2e-8).
PAIR_FILE_DIGITS = 12


def _tidy(value: Any) -> Any:
    """``value`` (a pair dict) with every float to PAIR_FILE_DIGITS significant digits (YAML then
    writes the shortest decimal that reads back as it: 5.0, not 5.000000000000001)."""
    if isinstance(value, float):
        return float(f"{value:.{PAIR_FILE_DIGITS}g}")
    if isinstance(value, dict):
        return {k: _tidy(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_tidy(v) for v in value]
    return value


def run_optimise(smk: Any) -> None:
    """The optimiser of one pair: ``function(pair, **settings)`` -> ga.nc, the optimum as a pair
    file (``output.pair``, the input of a variant ``{from: optimise.NAME}``) and its figures.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (:func:`run_job`).

    Raises
    ------
    SystemExit
        On failure, as :func:`run_job` says.
    """
    from .datasets.optimise import optimum_pair

    def then(pair: GearPair, ds: xr.Dataset) -> None:
        write_pair(optimum_pair(pair, ds), smk.output.pair, {"ga": normal_path(smk.output.nc), "data_sha256":
                                                             ds.attrs[DATA_ATTR]})

    _pair_stage(smk, then)


def check_results(config: Mapping[str, Any]) -> list[str]:
    """Every problem of the study's results folder against ``config`` (``gearmesh check``,
    :func:`gearmesh.upstream.check_tree`): what ``snakemake --report`` runs before it publishes
    the files, those nothing downstream reads included.

    Parameters
    ----------
    config : mapping
        The validated study config; its results are ``results/<study>`` under the working
        directory.

    Returns
    -------
    list of str
        One line per problem; empty when all is well or nothing was run yet.
    """
    from .upstream import check_tree

    root = Path("results", str(config["study"]))
    return check_tree(root, config, lambda name, variant: study_pair(config, name, variant)) if root.is_dir() else []


#: The job runners by the name a declaration gives (:data:`gearmesh.stages.Runner`).
RUNNERS: dict[str, Callable[[Any], None]] = {"pair_stage": run_pair_stage, "study_stage": run_study_stage,
                                             "collect": run_collect, "optimise": run_optimise, "plot": run_plot}
