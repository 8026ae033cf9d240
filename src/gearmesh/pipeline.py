"""The glue between a Snakemake job and the package: logging, provenance, atomic output.

Every rule names the one package function it runs in ``params.function``
("module:function") and passes its settings in ``params.settings``; three generic scripts
(``workflow/scripts/{pair_stage,study_stage,plot}.py``) call :func:`run_pair_stage`,
:func:`run_study_stage` or :func:`run_plot`. Provenance (the study config and the pair data
as JSON with its sha256) is attached here and each file is written atomically, so a failing
job leaves no output with its final name.
"""

from __future__ import annotations

import importlib
import logging
import resource
import sys
import time
from pathlib import Path
from typing import Any, Callable, Mapping

import xarray as xr

from .gear import GearPair, load_pair, pair_to_dict
from .io import add_provenance, atomic_output, write_dataset
from .tables import write_csv
from .upstream import Expected, identify, read_input


def provenance_config(study: Mapping[str, Any], pair: GearPair | None = None) -> dict[str, Any]:
    """What a result depends on: the study config and, for a pair stage, the pair data."""
    out: dict[str, Any] = {"study": dict(study)}
    if pair is not None:
        out["pair"] = pair_to_dict(pair)
    return out


def finish(ds: xr.Dataset, path: str | Path, study: Mapping[str, Any], pair: GearPair | None,
           title: str) -> Path:
    """Attach provenance and the pair name to ``ds`` and write it atomically."""
    source = pair.source if pair is not None and pair.source else study.get("source", "")
    add_provenance(ds, provenance_config(study, pair), source, title)
    if pair is not None:
        ds.attrs["pair_name"] = pair.name
    ds.attrs["study"] = study.get("study", "")
    return write_dataset(ds, path)


def resolve(spec: str) -> Callable[..., Any]:
    """The function named by "package.module:function", with or without the "@digest" that
    :func:`gearmesh.codeversion.versioned` appends."""
    module, _, name = spec.partition("@")[0].partition(":")
    return getattr(importlib.import_module(module), name)


def _run(smk: Any, body: Callable[[Any], None]) -> None:
    """Run one job with its log file; exit non-zero with the reason on failure."""
    log_path = Path(smk.log[0])
    log_path.parent.mkdir(parents=True, exist_ok=True)
    logging.basicConfig(filename=log_path, level=logging.INFO, filemode="w",
                        format="%(asctime)s %(levelname)s %(message)s", force=True)
    start = time.perf_counter()
    try:
        body(smk)
    except Exception as exc:  # the log and stderr get the reason; Snakemake sees the exit code
        logging.exception("job failed")
        print(f"gearmesh: error: {exc}", file=sys.stderr)
        sys.exit(2 if isinstance(exc, ValueError) else 1)
    # wall time and peak memory of every job, the measurements behind the profiles' resources
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # Linux: kB
    logging.info("done in %.1f s, peak RSS %.0f MB (threads %s): %s", time.perf_counter() - start, peak_mb,
                 getattr(smk, "threads", 1), ", ".join(map(str, smk.output)))


def _title(smk: Any) -> str:
    return f"gearmesh {smk.rule}"


def _expected(smk: Any, pair: GearPair | None = None) -> Expected:
    """What this job expects of the files it reads (:mod:`gearmesh.upstream`)."""
    return Expected(smk.config, pair, getattr(smk.wildcards, "variant", None))


def _upstream(smk: Any, pair: GearPair) -> dict[str, xr.Dataset]:
    """The job's named netCDF inputs (all but ``pair``), each checked for this job."""
    return {k: read_input(v, _expected(smk, pair)) for k, v in smk.input.items() if k != "pair"}


def _write_outputs(smk: Any, ds: xr.Dataset, pair: GearPair | None) -> None:
    identify(ds, smk.output[0], smk.rule, smk.wildcards)
    finish(ds, smk.output[0], smk.config, pair, _title(smk))
    if "csv" in smk.output.keys():
        with atomic_output(smk.output.csv) as tmp:
            write_csv(ds, tmp)


def run_pair_stage(smk: Any) -> None:
    """A stage of one pair: ``function(pair, **settings, **upstream datasets)`` -> Dataset.

    Named inputs other than ``pair`` are netCDF files of upstream stages, read and passed
    by name.
    """
    def body(smk: Any) -> None:
        pair = load_pair(smk.input.pair)
        upstream = _upstream(smk, pair)
        ds = resolve(smk.params.function)(pair, **dict(smk.params.settings), **upstream)
        _write_outputs(smk, ds, pair)

    _run(smk, body)


def run_study_stage(smk: Any) -> None:
    """A stage over several pairs: ``function({name: pair}, **settings)`` -> Dataset."""
    def body(smk: Any) -> None:
        pairs = {p.name: p for p in map(load_pair, smk.input.pairs)}
        settings = {k: v for k, v in dict(smk.params.settings).items() if k != "pairs"}
        _write_outputs(smk, resolve(smk.params.function)(pairs, **settings), None)

    _run(smk, body)


def run_collect(smk: Any) -> None:
    """A study table from per-pair results: ``function(**{input name: [Dataset, ...]}, **settings)``."""
    def body(smk: Any) -> None:
        inputs = {k: [read_input(p, _expected(smk)) for p in (v if isinstance(v, list) else [v])]
                  for k, v in smk.input.items()}
        settings = dict(getattr(smk.params, "settings", None) or {})
        _write_outputs(smk, resolve(smk.params.function)(**inputs, **settings), None)

    _run(smk, body)


def run_plot(smk: Any) -> None:
    """Figures: ``function({input name: Dataset}, {output name: path})`` writes the PNGs."""
    def body(smk: Any) -> None:
        inputs = {k: [read_input(p, _expected(smk)) for p in v] if isinstance(v, list)
                  else read_input(v, _expected(smk)) for k, v in smk.input.items()}
        resolve(smk.params.function)(inputs, dict(smk.output.items()))

    _run(smk, body)


def write_pair(pair: GearPair, path: str | Path) -> Path:
    """Write ``pair`` as a pair file (YAML, engineering units), checked by pair_geometry first."""
    import yaml

    from .gear import pair_geometry

    pair_geometry(pair)
    with atomic_output(path) as tmp:
        tmp.write_text(yaml.safe_dump(pair_to_dict(pair), sort_keys=False))
    return Path(path)


def run_variant_pair(smk: Any) -> None:
    """Write the pair file of one micro-geometry variant."""
    from .config import variant_pair

    def body(smk: Any) -> None:
        write_pair(variant_pair(load_pair(smk.input.pair), smk.wildcards.variant, smk.params.spec), smk.output[0])

    _run(smk, body)


def run_optimise(smk: Any) -> None:
    """The optimiser of one pair: ``function(pair, **settings)`` -> ga.nc (first output) and the
    optimum as a pair file (``output.pair``), the input of a variant ``{from: optimise}``."""
    from .datasets.optimise import optimum_pair

    def body(smk: Any) -> None:
        pair = load_pair(smk.input.pair)
        upstream = _upstream(smk, pair)
        ds = resolve(smk.params.function)(pair, **dict(smk.params.settings), **upstream)
        _write_outputs(smk, ds, pair)
        write_pair(optimum_pair(pair, ds), smk.output.pair)

    _run(smk, body)
