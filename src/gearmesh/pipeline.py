"""The glue between a Snakemake job and the package: logging, provenance, atomic output.

A workflow script is ``run_stage(snakemake, build)``: ``build(snakemake)`` returns the
stage's Dataset (or a mapping of output name to Dataset); this module attaches provenance
(the study config and the pair file as JSON with its sha256) and writes each file
atomically, so a failing job leaves no output with its final name.
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path
from typing import Any, Callable, Mapping

import xarray as xr

from .gear import GearPair, pair_to_dict
from .io import add_provenance, write_dataset


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


def run_stage(smk: Any, build: Callable[[Any], Any]) -> None:
    """Run one workflow job with its log file; exit non-zero with the reason on failure."""
    log_path = Path(smk.log[0])
    log_path.parent.mkdir(parents=True, exist_ok=True)
    logging.basicConfig(filename=log_path, level=logging.INFO, filemode="w",
                        format="%(asctime)s %(levelname)s %(message)s", force=True)
    try:
        build(smk)
    except Exception as exc:  # the log and stderr get the reason; Snakemake sees the exit code
        logging.exception("stage failed")
        print(f"gearmesh: error: {exc}", file=sys.stderr)
        sys.exit(2 if isinstance(exc, ValueError) else 1)
    logging.info("done: %s", ", ".join(map(str, smk.output)))


def _pair_stage(function: Callable[..., xr.Dataset], title: str):
    def build(smk: Any) -> None:
        from .gear import load_pair

        pair = load_pair(smk.input.pair)
        finish(function(pair, **smk.params.settings), smk.output[0], smk.config, pair, title)

    return build


def _helix_sweep(smk: Any) -> None:
    from .datasets import helix_sweep_dataset
    from .gear import load_pair

    settings = dict(smk.params.settings)
    pairs = {p.name: p for p in map(load_pair, smk.input.pairs)}
    ds = helix_sweep_dataset(pairs, settings["start_deg"], settings["stop_deg"], settings["step_deg"],
                             settings.get("positions", 360))
    finish(ds, smk.output[0], smk.config, None, "gearmesh contact length against helix angle")


def _stage_builders() -> dict[str, Callable[[Any], None]]:
    from . import datasets

    return {
        "geometry": _pair_stage(datasets.geometry_dataset, "gearmesh geometry"),
        "contact_lines": _pair_stage(datasets.contact_lines_dataset, "gearmesh contact lines"),
        "helix_sweep": _helix_sweep,
        "low_fluctuation_design": _low_fluctuation_design,
    }


def _low_fluctuation_design(smk: Any) -> None:
    from .datasets import low_fluctuation_design_dataset
    from .gear import load_pair

    pairs = {p.name: p for p in map(load_pair, smk.input.pairs)}
    ds = low_fluctuation_design_dataset(pairs)
    finish(ds, smk.output.nc, smk.config, None, "gearmesh low-fluctuation designs")
    table = ds.to_dataframe()
    table.to_csv(smk.output.csv)


def run_named_stage(smk: Any) -> None:
    """Run the stage named by the rule's ``params.stage``."""
    run_stage(smk, _stage_builders()[smk.params.stage])
