"""What a workflow stage reads, checked before it is used (issue 20).

Every netCDF file a job writes records what it is (:func:`identify`): the path it was written
as, the rule that made it and that job's wildcards, beside the provenance of
:func:`gearmesh.io.add_provenance` (the study config and the pair data it was made from).
A job reading an upstream file (:func:`read_input`) refuses it, with one line naming the file,
what it is, what was expected and how to regenerate it, when

* it cannot be read (truncated or corrupt: "NetCDF: HDF error");
* it is not a result of a workflow job (no provenance);
* it was written as another file (a copy or a move: another variant's, another stage's,
  another study's file);
* it was made for other pair data than the reading job's (the pair file or the variant's
  modification changed, and the file was not remade);
* it was made with other settings of its own stage (its config section) or for another study.

Snakemake reruns a job whose inputs, code or params changed, so none of these happens in a run
that Snakemake alone drives; they catch the files a person or another program put in place,
and runs told to ignore their rerun triggers.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import xarray as xr

from .errors import GearmeshInputError, excerpt
from .gear import GearPair, pair_to_dict
from .io import config_digest

#: Global attributes :func:`identify` writes: the file as written (relative POSIX path), the
#: rule that made it and its job's wildcards (JSON).
OUTPUT_ATTR, RULE_ATTR, WILDCARDS_ATTR = "gearmesh_output", "gearmesh_rule", "gearmesh_wildcards_json"
#: Relative tolerance of numbers in pair data (a pair file's values pass through SI and back).
PAIR_RTOL = 1e-9


@dataclass(frozen=True)
class Expected:
    """What a reading job expects of the files it reads: its study ``config``, its ``pair``
    (None for a stage over several pairs) and its micro-geometry ``variant`` (None if none)."""

    config: Mapping[str, Any]
    pair: GearPair | None = None
    variant: str | None = None


def identify(ds: xr.Dataset, path: str | Path, rule: str, wildcards: Mapping[str, str]) -> xr.Dataset:
    """Record in ``ds`` the file it is written as, the ``rule`` that made it and the job's
    ``wildcards``: what :func:`check_input` compares."""
    ds.attrs.update({OUTPUT_ATTR: _normal(path), RULE_ATTR: rule,
                     WILDCARDS_ATTR: json.dumps({k: str(v) for k, v in dict(wildcards).items()}, sort_keys=True)})
    return ds


def read_input(path: str | Path, expected: Expected) -> xr.Dataset:
    """The upstream netCDF file at ``path``, fully loaded, after :func:`check_input`."""
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds = ds.load()
    except FileNotFoundError:
        raise GearmeshInputError(str(path), "missing", f"does not exist; {_recovery(path)}") from None
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as exc:
        raise GearmeshInputError(str(path), "damaged", f"cannot be read as netCDF ({_reason(exc, path)}): the file "
                                 f"is truncated or corrupt; {_recovery(path)}") from None
    check_input(ds, path, expected)
    return ds


def check_input(ds: xr.Dataset, path: str | Path, expected: Expected) -> None:
    """Refuse ``ds`` (read from ``path``) unless it is the workflow's file at ``path``, made for
    the expected study, pair data and variant, with the current settings of its stage."""
    attrs = ds.attrs
    if "config_json" not in attrs or OUTPUT_ATTR not in attrs:
        raise GearmeshInputError(str(path), "no gearmesh provenance", "is not a result of a gearmesh workflow job "
                                 f"(no {OUTPUT_ATTR} attribute); {_recovery(path)}")
    rule = attrs.get(RULE_ATTR, "?")
    written = attrs[OUTPUT_ATTR]
    if not _same_file(written, path):
        raise GearmeshInputError(str(path), f"the {rule} result written as {written}",
                                 f"is a copy of that file (or was moved here), not the one this job reads; {_recovery(path)}")
    made = json.loads(attrs["config_json"])
    study = made.get("study", {})
    if study.get("study") != expected.config.get("study"):
        raise GearmeshInputError(str(path), f"made for study {study.get('study')!r}",
                                 f"this run is study {expected.config.get('study')!r}; {_recovery(path)}")
    _check_pair(made.get("pair"), path, rule, json.loads(attrs.get(WILDCARDS_ATTR, "{}")), expected)
    _check_settings(study, path, rule, json.loads(attrs.get(WILDCARDS_ATTR, "{}")), expected.config)


def _check_pair(made: Mapping[str, Any] | None, path, rule: str, wildcards: Mapping[str, str],
                expected: Expected) -> None:
    """The pair data the file was made from against the reading job's pair: all of it for a
    file of the same variant, all but the modification for a file of the pair (no variant)."""
    if made is None or expected.pair is None:
        return
    if wildcards.get("variant") not in (None, expected.variant):
        return
    wanted = pair_to_dict(expected.pair)
    if "variant" not in wildcards:  # a stage of the pair (geometry, stiffness): made before the variants
        made, wanted = ({k: v for k, v in d.items() if k != "modification"} for d in (made, wanted))
    key = first_difference(made, wanted)
    if key is not None:
        what = f"variant {expected.variant}" if "variant" in wildcards else "pair"
        raise GearmeshInputError(str(path), f"the {rule} result of {made.get('name')} made with {key} = "
                                 f"{_value(made, key)}", f"this job's {what} has {key} = {_value(wanted, key)}: the "
                                 f"pair data changed since the file was made; {_recovery(path)}")


def _check_settings(made_study: Mapping[str, Any], path, rule: str, wildcards: Mapping[str, str],
                    config: Mapping[str, Any]) -> None:
    """The file's own stage settings (the config section named after its rule; for a rule
    with a ``run`` wildcard that run's entry) against this run's."""
    if rule not in config or not isinstance(config[rule], Mapping):
        return
    made, now, prefix = made_study.get(rule), _plain(config[rule]), rule
    run = wildcards.get("run")
    if run is not None and isinstance(made, Mapping) and run in now:
        made, now, prefix = made.get(run), now[run], f"{rule}.{run}"
    key = first_difference(made, now)
    if key is not None:
        field = f"{prefix}.{key}" if key else prefix
        raise GearmeshInputError(str(path), f"the {rule} result made with {field} = {_value(made, key)}",
                                 f"this run has {field} = {_value(now, key)}; {_recovery(path)}")


#: Global attribute of a stage's dataset: the pair data it was computed for (canonical JSON of
#: the pair file's form; without the modification for a stage of the pair, which does not use it),
#: so a stage handed another pair's dataset refuses it (:func:`check_dataset_pair`).
PAIR_ATTR = "gearmesh_pair_json"


def stamp_pair(ds: xr.Dataset, pair: GearPair, per_variant: bool) -> xr.Dataset:
    """Record in ``ds`` the pair data it was computed for (:data:`PAIR_ATTR`); ``per_variant``
    whether the result depends on the micro-geometry (TCA, LTCA, impact, dynamics)."""
    data = pair_to_dict(pair)
    if not per_variant:
        data.pop("modification", None)
    ds.attrs[PAIR_ATTR] = config_digest({"pair": data, "per_variant": per_variant})[0]
    return ds


def check_dataset_pair(argument: str, ds: xr.Dataset, pair: GearPair) -> None:
    """Refuse a dataset argument computed for other pair data than ``pair`` (GearmeshInputError
    naming the argument, the pair it was made for and the first differing key); a dataset
    without :data:`PAIR_ATTR` (made by hand) is taken as it is."""
    text = ds.attrs.get(PAIR_ATTR)
    if not isinstance(text, str):
        return
    made = json.loads(text)
    wanted = pair_to_dict(pair)
    if not made.get("per_variant"):
        wanted.pop("modification", None)
    recorded = made.get("pair", {})
    key = first_difference(recorded, wanted)
    if key is not None:
        raise GearmeshInputError(argument, f"a dataset of {recorded.get('name')!r}",
                                 f"was computed with {key} = {_value(recorded, key)}, this pair "
                                 f"{pair.name!r} has {key} = {_value(wanted, key)}: pass this pair's own "
                                 f"{argument} dataset (or none)")


def first_difference(made: Any, wanted: Any, prefix: str = "") -> str | None:
    """The dotted key (``a.b[2]``) of the first difference between two JSON-like values, numbers
    equal within :data:`PAIR_RTOL`; ``''`` when the values differ at the top; None if equal."""
    if isinstance(made, Mapping) and isinstance(wanted, Mapping):
        for key in sorted(set(made) | set(wanted)):
            sub = f"{prefix}.{key}" if prefix else str(key)
            if key not in made or key not in wanted:
                return sub
            found = first_difference(made[key], wanted[key], sub)
            if found is not None:
                return found
        return None
    if isinstance(made, list) and isinstance(wanted, list):
        if len(made) != len(wanted):
            return prefix
        for k, (a, b) in enumerate(zip(made, wanted)):
            found = first_difference(a, b, f"{prefix}[{k}]")
            if found is not None:
                return found
        return None
    numbers = (int, float)
    if isinstance(made, numbers) and isinstance(wanted, numbers) and not isinstance(made, bool) \
            and not isinstance(wanted, bool):
        return None if math.isclose(made, wanted, rel_tol=PAIR_RTOL, abs_tol=0.0) else prefix
    return None if made == wanted and isinstance(made, bool) == isinstance(wanted, bool) else prefix


def _value(data: Any, key: str) -> str:
    """The value at dotted ``key`` of :func:`first_difference` (absent: 'absent'), as short text."""
    for part in [p for p in key.replace("[", ".[").split(".") if p]:
        if part.startswith("["):
            index = int(part[1:-1])
            data = data[index] if isinstance(data, list) and index < len(data) else "absent"
        else:
            data = data.get(part, "absent") if isinstance(data, Mapping) else "absent"
    return excerpt(json.dumps(data, sort_keys=True, default=str), 60)


def _plain(value: Any) -> Any:
    """``value`` as JSON would give it back (the form of the recorded config)."""
    return json.loads(config_digest({"v": value})[0])["v"]


def _normal(path: str | Path) -> str:
    return Path(os.path.normpath(path)).as_posix()


def _same_file(written: str, path: str | Path) -> bool:
    """Whether the recorded ``written`` names ``path`` (both relative to the working directory,
    or either absolute)."""
    return _normal(written) == _normal(path) or os.path.abspath(written) == os.path.abspath(path)


def _reason(exc: BaseException, path: str | Path) -> str:
    """The library's reason without the path it repeats (e.g. 'NetCDF: HDF error')."""
    text = getattr(exc, "strerror", None) or str(exc)
    for form in (f": '{path}'", f": '{os.path.abspath(path)}'", str(os.path.abspath(path)), str(path)):
        text = text.replace(form, "")
    return excerpt(" ".join(text.split()).strip(" :") or type(exc).__name__, 80)


def _recovery(path: str | Path) -> str:
    return f"regenerate it: snakemake --forcerun {_normal(path)} (with this run's --configfile)"
