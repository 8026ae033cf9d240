"""What a workflow stage reads, checked before it is used.

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
* it was made with other settings of its own stage (its config section), of another section it
  depends on (the impact stage's tolerances), or for another study;
* its data do not match the digest it claims (an edited value, a forged file);
* an input it was made from has changed or is gone since (:func:`record_sources`): it is stale.

A study table (no pair of its own) checks each file against that file's own pair and variant.
The optimum's pair file is checked against the run that wrote it and that run against the
reading job's study (:func:`check_optimum`), and :func:`check_tree` (``gearmesh check``, and
``snakemake --report`` first) checks every file of a results folder, those nothing downstream
reads included: each CSV table against the digest its netCDF file recorded
(:func:`record_tables`), each PNG figure against the provenance it carries
(:func:`check_figure`). A stage function handed another pair's dataset refuses it
(:func:`check_dataset_pair`).

Snakemake reruns a job whose inputs, code or params changed, so none of these happens in a run
that Snakemake alone drives; they catch the files a person or another program put in place,
and runs told to ignore their rerun triggers.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping

import xarray as xr

from .errors import GearmeshInputError, excerpt
from .gear import GearPair
from .pairfile import _REQUIRED_KEYS, pair_to_dict
from .io import DATA_ATTR, FIGURE_KEY, config_digest, data_digest, figure_provenance, normal_path

#: Global attributes :func:`identify` writes: the file as written (relative POSIX path), the
#: rule that made it and its job's wildcards (JSON).
OUTPUT_ATTR, RULE_ATTR, WILDCARDS_ATTR = "gearmesh_output", "gearmesh_rule", "gearmesh_wildcards_json"
#: Relative tolerance of numbers in pair data (a pair file's values pass through SI and back).
PAIR_RTOL = 1e-9


#: Global attributes of :func:`record_sources`: every input file of the job that made the file
#: with the digest it had then (JSON {path: digest}), and the study config sections it depends on.
SOURCES_ATTR, SECTIONS_ATTR = "gearmesh_sources_json", "gearmesh_sections_json"
#: First line of an optimisation's pair file (:func:`optimum_header`).
OPTIMUM_HEADER = "# gearmesh optimum: "


@dataclass(frozen=True)
class Expected:
    """What a reading job expects of the files it reads: its study ``config``, its ``pair``
    (None for a stage over several pairs) and its micro-geometry ``variant`` (None if none);
    for a stage over several pairs or variants, ``pair_of(pair name, variant or None)`` gives
    the pair each file must have been made for."""

    config: Mapping[str, Any]
    pair: GearPair | None = None
    variant: str | None = None
    pair_of: Callable[[str, str | None], GearPair] | None = None


def identify(ds: xr.Dataset, path: str | Path, rule: str, wildcards: Mapping[str, str],
             function: str | None = None) -> xr.Dataset:
    """Record in ``ds`` the file it is written as, the ``rule`` that made it, the job's
    ``wildcards`` and the ``function`` that made it (with its code digest): what
    :func:`check_input` and :func:`check_tree` compare.

    Parameters
    ----------
    ds : xarray.Dataset
        The job's result, changed in place.
    path : str or pathlib.Path
        The file it is written as.
    rule : str
        The rule that made it.
    wildcards : mapping of str to str
        The job's wildcards.
    function : str, optional
        ``"package.module:function@digest"`` of the function that made it.

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    ds.attrs.update({OUTPUT_ATTR: normal_path(path), RULE_ATTR: rule,
                     WILDCARDS_ATTR: json.dumps({k: str(v) for k, v in dict(wildcards).items()}, sort_keys=True)})
    if function:  # the whole text: a Versioned spec prints without its digest
        ds.attrs[FUNCTION_ATTR] = str.__str__(function)
    return ds


def read_input(path: str | Path, expected: Expected) -> xr.Dataset:
    """The upstream netCDF file at ``path``, fully loaded, after :func:`check_input`.

    Parameters
    ----------
    path : str or pathlib.Path
        The upstream netCDF file.
    expected : Expected
        What the reading job expects of it.

    Returns
    -------
    xarray.Dataset
        The file's dataset, loaded into memory.

    Raises
    ------
    GearmeshInputError
        Naming ``path``: missing, unreadable as netCDF, or refused by :func:`check_input`; the rule
        says how to regenerate it.
    """
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
    """Refuse ``ds`` (read from ``path``) unless it is the workflow's file at ``path``, its data
    those its digest claims, made for the expected study, pair data and variant, with the
    current settings of every section it depends on, from inputs that are still the files it
    was made from (module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset read.
    path : str or pathlib.Path
        The file it was read from.
    expected : Expected
        What the reading job expects.

    Raises
    ------
    GearmeshInputError
        Naming ``path``, what the file is and what differs (the first differing key).
    """
    _check_identity(ds.attrs, path)
    _check_digests(ds, path, ds.attrs.get(RULE_ATTR, "?"))
    check_made_for(ds.attrs, path, expected)


def check_made_for(attrs: Mapping[str, Any], path: str | Path, expected: Expected) -> None:
    """Refuse a result by its attributes ``attrs`` alone (a header read of ``path``) unless it was
    made for the expected study, pair data and variant, with the current settings of every
    section it depends on, from inputs that are still the files it was made from.

    Parameters
    ----------
    attrs : mapping
        The file's global attributes.
    path : str or pathlib.Path
        The file.
    expected : Expected
        What the reading job expects.

    Raises
    ------
    GearmeshInputError
        Naming ``path`` and the first differing study, pair key, setting or changed input.
    """
    rule = attrs.get(RULE_ATTR, "?")
    made = json.loads(attrs["config_json"])
    study = made.get("study", {})
    if study.get("study") != expected.config.get("study"):
        raise GearmeshInputError(str(path), f"made for study {study.get('study')!r}",
                                 f"this run is study {expected.config.get('study')!r}; {_recovery(path)}")
    wildcards = json.loads(attrs.get(WILDCARDS_ATTR, "{}"))
    if expected.pair is None and expected.pair_of is not None and "pair" in wildcards:
        variant = wildcards.get("variant")  # a study table: each file against its own pair and variant
        expected = Expected(expected.config, expected.pair_of(wildcards["pair"], variant), variant)
    _check_pair(made.get("pair"), path, rule, wildcards, expected)
    _check_settings(study, path, rule, wildcards, expected.config)
    for section in json.loads(attrs.get(SECTIONS_ATTR, "[]")):
        if section != rule:
            _check_section(study, section, path, rule, expected.config)
    _check_sources(attrs, path)


def _check_digests(ds: xr.Dataset, path, rule: str) -> None:
    """The file's data against the digest it claims (an edited value, a forged file), and its
    recorded config against its config digest."""
    claimed = ds.attrs.get(DATA_ATTR)
    if not isinstance(claimed, str) or data_digest(ds) != claimed:
        what = "has no data digest" if not isinstance(claimed, str) else "has data that do not match its digest"
        raise GearmeshInputError(str(path), f"the {rule} result", f"{what} ({DATA_ATTR}): edited, forged or made "
                                 f"by an older gearmesh; {_recovery(path)}")
    if hashlib.sha256(str(ds.attrs["config_json"]).encode()).hexdigest() != ds.attrs.get("config_sha256"):
        raise GearmeshInputError(str(path), f"the {rule} result", "has a config that does not match its config_sha256 "
                                 f"(edited); {_recovery(path)}")


def _check_section(made_study: Mapping[str, Any], section: str, path, rule: str,
                   config: Mapping[str, Any]) -> None:
    """Another config section the file depends on (the impact stage's tolerances, an
    optimisation's impact model) against this run's."""
    key = first_difference(made_study.get(section), _plain(config.get(section)))
    if key is not None:
        field = f"{section}.{key}" if key else section
        raise GearmeshInputError(str(path), f"the {rule} result made with {field} = "
                                 f"{_value(made_study.get(section), key)}",
                                 f"this run has {field} = {_value(_plain(config.get(section)), key)}; {_recovery(path)}")


def _header(path: str | Path) -> dict[str, Any]:
    """The global attributes of a netCDF file, read from its header alone."""
    import netCDF4

    try:
        with netCDF4.Dataset(path) as nc:
            return {k: nc.getncattr(k) for k in nc.ncattrs()}
    except (OSError, RuntimeError, ValueError) as exc:
        raise GearmeshInputError(str(path), "damaged", f"cannot be read as netCDF ({_reason(exc, path)}); "
                                 f"{_recovery(path)}") from None


def file_digest(path: str | Path) -> str:
    """What a file is as an input: a netCDF result's data digest (its attribute, read from the
    header only), any other file's sha256; '' for a file that is missing or cannot be read.

    Parameters
    ----------
    path : str or pathlib.Path
        Any file.

    Returns
    -------
    str
        The digest (hex), or ''.
    """
    path = Path(path)
    try:
        if path.suffix == ".nc":
            import netCDF4

            with netCDF4.Dataset(path) as nc:
                return str(nc.getncattr(DATA_ATTR)) if DATA_ATTR in nc.ncattrs() else ""
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except (OSError, RuntimeError, ValueError):
        return ""


def record_sources(ds: xr.Dataset, files, sections) -> xr.Dataset:
    """Record in ``ds`` every input file of the job with its :func:`file_digest` now, and the
    config ``sections`` the result depends on: what :func:`check_sources` and
    :func:`_check_section` compare when the file is read.

    Parameters
    ----------
    ds : xarray.Dataset
        The job's result, changed in place.
    files : iterable of str or pathlib.Path
        The job's input files.
    sections : iterable of str
        The config sections the result depends on (:func:`gearmesh.stages.dependencies`).

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    ds.attrs[SOURCES_ATTR] = json.dumps({normal_path(f): file_digest(f) for f in files}, sort_keys=True)
    ds.attrs[SECTIONS_ATTR] = json.dumps(list(sections))
    return ds


#: Global attribute of :func:`record_tables`: every CSV copy of the file's dataset its job wrote,
#: with its sha256 (JSON {path: sha256}), compared by :func:`check_tree`.
TABLES_ATTR = "gearmesh_tables_json"


def record_tables(ds: xr.Dataset, tables: Mapping[str, str]) -> xr.Dataset:
    """Record in ``ds`` the CSV tables its job wrote from it ({path: sha256}, written before the
    netCDF file), so an edited or replaced table is named (:func:`check_tree`).

    Parameters
    ----------
    ds : xarray.Dataset
        The job's result, changed in place.
    tables : mapping of str to str
        CSV path to its sha256.

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    ds.attrs[TABLES_ATTR] = json.dumps({normal_path(k): v for k, v in tables.items()}, sort_keys=True)
    return ds


def check_figure(path: str | Path, digest_of: Callable[[str], str] | None = None) -> None:
    """Refuse a figure (PNG) that is not the one its job drew at ``path``: without provenance
    (not drawn by a gearmesh job, or replaced), a copy of another job's figure (another
    variant's, moved or copied here), edited since it was drawn, or drawn from a file that has
    changed or gone since (stale). One line naming the file and how to remake it
    (:func:`gearmesh.io.stamp_figure` writes what this reads). ``digest_of``: :func:`file_digest`,
    or a memo of it over many figures drawn from the same files.

    Parameters
    ----------
    path : str or pathlib.Path
        The PNG figure.
    digest_of : callable, optional
        str -> str, a file's digest; default :func:`file_digest`.

    Raises
    ------
    GearmeshInputError
        Naming ``path``: unreadable, without provenance, a copy, edited, or stale.
    """
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise GearmeshInputError(str(path), "unreadable", f"cannot be read ({exc.strerror}); {_recovery(path)}") from None
    meta, digest = figure_provenance(data)
    if meta is None:
        raise GearmeshInputError(str(path), "a figure without provenance", "is not a figure a gearmesh job drew (no "
                                 f"{FIGURE_KEY.decode()!r} text chunk: replaced, or drawn by an older gearmesh); "
                                 f"{_recovery(path)}")
    if not _same_file(str(meta.get("file", "")), path):
        raise GearmeshInputError(str(path), f"the figure drawn as {meta.get('file')}", "is a copy of that figure (or was "
                                 f"moved here), not the one drawn for this place; {_recovery(path)}")
    if digest != meta.get("image_sha256"):
        raise GearmeshInputError(str(path), "an edited figure", "does not match the digest it was drawn with; "
                                 f"{_recovery(path)}")
    for source, recorded in (meta.get("drawn_from") or {}).items():
        now = (digest_of or file_digest)(source)
        if now != recorded:
            what = "is missing or unreadable now" if not now else "has changed since"
            raise GearmeshInputError(str(path), f"the figure drawn from {source}", f"that file {what}: this figure is "
                                     f"stale; {_recovery(path)}")


def _check_tables(listed: Mapping[str, tuple[str, str]], root: Path) -> list[str]:
    """Every CSV under ``root`` against the digests the netCDF files recorded for their tables
    (``listed``: {csv path: (sha256, the netCDF file that lists it)}), and every listed table
    present: one problem line each."""
    problems = []
    for path in sorted(root.rglob("*.csv")):
        if any(part.startswith(".") for part in path.relative_to(root).parts):
            continue  # a temporary of a write in flight
        rel = normal_path(path)
        if rel not in listed:
            problems.append(str(GearmeshInputError(rel, "a table no result lists", "was not written by a job of these "
                                                   f"results (copied here or renamed?); {_recovery(rel)}")))
            continue
        digest, nc = listed[rel]
        if file_digest(path) != digest:
            problems.append(str(GearmeshInputError(rel, "an edited table", f"does not match the digest {nc} recorded "
                                                   f"when its job wrote both (edited or replaced); {_recovery(rel)}")))
    for rel, (_, nc) in sorted(listed.items()):
        if not Path(rel).exists():
            problems.append(str(GearmeshInputError(rel, "missing", f"{nc} lists it but it is gone; {_recovery(rel)}")))
    return problems


def check_sources(ds: xr.Dataset, path) -> None:
    """Refuse ``ds`` (read from ``path``) when an input it was made from is gone or is no longer
    the file it was made from (remade, replaced or edited since, and ``path`` not remade).

    Parameters
    ----------
    ds : xarray.Dataset
        A result read.
    path : str or pathlib.Path
        The file it was read from.

    Raises
    ------
    GearmeshInputError
        Naming ``path`` and the first input that changed or is gone.
    """
    _check_sources(ds.attrs, path)


def _check_sources(attrs: Mapping[str, Any], path) -> None:
    """:func:`check_sources` of a result's attributes."""
    rule = attrs.get(RULE_ATTR, "?")
    for source, digest in json.loads(attrs.get(SOURCES_ATTR, "{}")).items():
        now = file_digest(source)
        if now != digest:
            what = "is missing or unreadable now" if not now else "has changed since"
            raise GearmeshInputError(str(path), f"the {rule} result made from {source}",
                                     f"that input {what}: this file is stale; {_recovery(path)}")


def optimum_header(path: str | Path, body: str, made_by: Mapping[str, Any]) -> str:
    """The first line of an optimisation's pair file at ``path``: a YAML comment with the file
    as written, the digest of its content ``body`` and ``made_by`` (the run's ga.nc and its
    data digest).

    Parameters
    ----------
    path : str or pathlib.Path
        The pair file as written.
    body : str
        Its content after the header line.
    made_by : mapping
        ``ga`` (the run's ga.nc) and ``data_sha256`` (its data digest).

    Returns
    -------
    str
        The line, newline included.
    """
    meta = {"file": normal_path(path), "content_sha256": hashlib.sha256(body.encode()).hexdigest(), **made_by}
    return OPTIMUM_HEADER + json.dumps(meta, sort_keys=True) + "\n"


def check_optimum(path: str | Path, expected: Expected | None = None) -> None:
    """Refuse an optimisation's pair file that is not the optimum its run wrote at ``path``:
    without the provenance line (hand-made), copied from another run or place, edited after it
    was written, or older than its run's ga.nc; with ``expected`` (the reading job's study config
    and the study's pair file of that pair) also one whose ga.nc was not made for this study: with
    other settings of that optimisation, tolerances or impact model, or for other pair data
    (another run's pair.yaml and ga.nc put in place together; :func:`check_input`). One line
    naming the file and how to remake it.

    Parameters
    ----------
    path : str or pathlib.Path
        An optimisation's ``pair.yaml``.
    expected : Expected, optional
        The reading job's study config and pair; None: provenance and digests only.

    Raises
    ------
    GearmeshInputError
        Naming ``path``, what is wrong and the ``snakemake --forcerun`` that remakes it.
    """
    from .inputfile import read_input_text

    text = read_input_text(path, "pair file")
    first, _, body = text.partition("\n")
    redo = f"remake it: snakemake --forcerun {normal_path(path)} (with this run's --configfile)"
    if not first.startswith(OPTIMUM_HEADER):
        raise GearmeshInputError(str(path), "an optimum without provenance", "has no '# gearmesh optimum' first line: "
                                 f"not the file an optimisation wrote (hand-made or replaced); {redo}")
    try:
        meta = json.loads(first[len(OPTIMUM_HEADER):])
    except ValueError:
        meta = {}
    if not _same_file(str(meta.get("file", "")), path):
        raise GearmeshInputError(str(path), f"the optimum written as {meta.get('file')}",
                                 f"is a copy of another run's optimum, not this run's; {redo}")
    if hashlib.sha256(body.encode()).hexdigest() != meta.get("content_sha256"):
        raise GearmeshInputError(str(path), "an edited optimum", "was changed after its optimisation wrote it (its "
                                 "content does not match its digest); to try a hand-made design give it as a variant's "
                                 f"modification instead; {redo}")
    ga = str(meta.get("ga", ""))
    if file_digest(ga) != meta.get("data_sha256"):
        raise GearmeshInputError(str(path), f"the optimum of an older {ga}",
                                 f"that run's result has changed since this file was written; {redo}")
    if expected is not None:
        try:  # the header is enough: its data are the digest the line above compared
            attrs = _header(ga)
            _check_identity(attrs, ga)
            check_made_for(attrs, ga, expected)
        except GearmeshInputError as exc:  # the run's own line names what differs and the --forcerun of its job
            raise GearmeshInputError(str(path), f"the optimum of {ga}", f"not this study's optimisation ({exc.value}: "
                                     f"{_without_recovery(exc.rule)}); {redo}") from None


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
    whether the result depends on the micro-geometry (TCA, LTCA, impact, dynamics).

    Parameters
    ----------
    ds : xarray.Dataset
        A stage's dataset, changed in place.
    pair : GearPair
        The pair it was computed for.
    per_variant : bool
        Whether the result depends on the micro-geometry.

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    data = pair_to_dict(pair)
    if not per_variant:
        data.pop("modification", None)
    ds.attrs[PAIR_ATTR] = config_digest({"pair": data, "per_variant": per_variant})[0]
    return ds


def check_dataset_pair(argument: str, ds: xr.Dataset, pair: GearPair) -> None:
    """Refuse a dataset argument computed for other pair data than ``pair`` (GearmeshInputError
    naming the argument, the pair it was made for and the first differing key); a dataset
    without :data:`PAIR_ATTR` (made by hand) is taken as it is.

    Parameters
    ----------
    argument : str
        The stage function's argument the dataset was passed as.
    ds : xarray.Dataset
        The dataset passed.
    pair : GearPair
        The stage's pair.

    Raises
    ------
    GearmeshInputError
        Naming ``argument``, the pair the dataset was made for and the first differing key.
    """
    text = ds.attrs.get(PAIR_ATTR)
    if not isinstance(text, str):
        return
    made = json.loads(text)
    wanted = pair_to_dict(pair)
    if not made.get("per_variant"):
        wanted.pop("modification", None)
    recorded = made.get("pair", {})
    key = first_difference(recorded, wanted)
    if key is None:
        return
    if recorded.get("name") != pair.name:  # another pair's: say so, and where its gears differ first
        key = next((k for k in _REQUIRED_KEYS if first_difference(recorded.get(k), wanted.get(k)) is not None), None)
        where = "" if key is None else f" ({key} = {_value(recorded, key)}, this pair's {_value(wanted, key)})"
        raise GearmeshInputError(argument, f"a dataset of {recorded.get('name')!r}", f"was computed for pair "
                                 f"{recorded.get('name')!r}{where}, not for this pair {pair.name!r}: pass this pair's "
                                 f"own {argument} dataset (or none)")
    raise GearmeshInputError(argument, f"a dataset of {recorded.get('name')!r}",
                             f"was computed with {key} = {_value(recorded, key)}, this pair "
                             f"{pair.name!r} has {key} = {_value(wanted, key)}: pass this pair's own "
                             f"{argument} dataset (or none)")


#: Global attribute of :func:`identify`: the function that made the file, with the digest of
#: its code (:func:`gearmesh.codeversion.versioned`), compared by :func:`check_tree`.
FUNCTION_ATTR = "gearmesh_function"


def check_tree(root: str | Path, config: Mapping[str, Any] | None = None,
               pair_of: Callable[[str, str | None], GearPair] | None = None) -> list[str]:
    """Every problem of the results under ``root`` (a study's results folder), one line each
    naming the file, what is wrong and how to remake it: each netCDF file readable (not
    truncated, not empty), a gearmesh result at its own path (not a copy of another variant's,
    stage's or study's file), its data matching its digest, made by the current code of its
    function, from inputs that are still the files it was made from (none missing); each CSV the
    table its job wrote (:func:`record_tables`: listed, unedited) and each PNG the figure drawn for
    its place from files unchanged since (:func:`check_figure`); each optimisation's pair file its
    run's unedited optimum; with the study ``config`` (and ``pair_of``, the pair each file must be
    of) also the settings and pair data of each file, and of each optimum's run. The files nothing
    downstream reads (geometry, contact lines, TCA, tables, ga.nc, figures) included. Paths are
    relative to the working directory, the folder the study ran in.

    Parameters
    ----------
    root : str or pathlib.Path
        A study's results folder.
    config : mapping, optional
        The study config; None: no settings or pair-data checks.
    pair_of : callable, optional
        (pair name, variant or None) -> GearPair, the pair each file must be of.

    Returns
    -------
    list of str
        One line per problem, naming the file, what is wrong and how to remake it, each once;
        empty when every file is sound.
    """
    from .codeversion import versioned

    problems: list[str] = []
    root = Path(root)
    pair_of = functools.lru_cache(maxsize=None)(pair_of) if pair_of is not None else None  # a pair (optimum) once
    tables: dict[str, tuple[str, str]] = {}
    for path in sorted(root.rglob("*.nc")):
        if any(part.startswith(".") for part in path.relative_to(root).parts):
            continue  # a temporary of a write in flight
        rel = normal_path(path)
        if path.is_dir():
            problems.append(f"{rel}: a folder where a result file belongs; move or delete it, then rerun")
            continue
        try:
            with xr.open_dataset(path, engine="netcdf4") as ds:
                ds = ds.load()
        except (OSError, RuntimeError, ValueError, KeyError, IndexError) as exc:
            problems.append(f"{rel}: damaged (cannot be read as netCDF: {_reason(exc, path)}, truncated or empty); "
                            f"{_recovery(rel)}")
            continue
        tables.update({csv: (digest, rel) for csv, digest in _listed_tables(ds).items()})
        try:
            if config is not None:
                check_input(ds, rel, Expected(config, None, None, pair_of))
            else:
                _check_identity(ds.attrs, rel)
                _check_digests(ds, rel, ds.attrs.get(RULE_ATTR, "?"))
                check_sources(ds, rel)
            spec = ds.attrs.get(FUNCTION_ATTR)
            if isinstance(spec, str) and "@" in spec and versioned(spec.partition("@")[0]) != spec:
                raise GearmeshInputError(rel, f"made by {spec}", "older code of its function: stale; "
                                         f"{_recovery(rel)}")
        except GearmeshInputError as exc:
            problems.append(str(exc))
    problems += _check_tables(tables, root)
    digest_of = functools.lru_cache(maxsize=None)(file_digest)  # a file several figures were drawn from, read once
    for path in sorted(root.rglob("*.png")):
        if any(part.startswith(".") for part in path.relative_to(root).parts):
            continue
        try:
            check_figure(normal_path(path), digest_of)
        except GearmeshInputError as exc:
            problems.append(str(exc))
    for path in sorted(root.rglob("optimise/*/pair.yaml")):
        try:
            pair = pair_of(path.parent.parent.parent.name, None) if config is not None and pair_of else None
            check_optimum(normal_path(path), None if pair is None else Expected(config, pair))
        except GearmeshInputError as exc:
            problems.append(str(exc))
    return list(dict.fromkeys(problems))


def _listed_tables(ds: xr.Dataset) -> dict[str, str]:
    """The CSV tables a result's job wrote with it ({path: sha256}, :func:`record_tables`)."""
    try:
        listed = json.loads(ds.attrs.get(TABLES_ATTR, "{}"))
    except ValueError:
        return {}
    return {str(k): str(v) for k, v in listed.items()} if isinstance(listed, dict) else {}  # a bad optimum is named once, not once per file of its variant


def _check_identity(attrs: Mapping[str, Any], path) -> None:
    """The file (its attributes ``attrs``) is a gearmesh result (provenance) written as ``path``
    (not a copy or a move)."""
    if "config_json" not in attrs or OUTPUT_ATTR not in attrs:
        raise GearmeshInputError(str(path), "no gearmesh provenance", "is not a result of a gearmesh workflow job "
                                 f"(no {OUTPUT_ATTR} attribute); {_recovery(path)}")
    written = attrs[OUTPUT_ATTR]
    if not _same_file(written, path):
        raise GearmeshInputError(str(path), f"the {attrs.get(RULE_ATTR, '?')} result written as {written}",
                                 f"is a copy of that file (or was moved here), not the one this job reads; "
                                 f"{_recovery(path)}")


def first_difference(made: Any, wanted: Any, prefix: str = "") -> str | None:
    """The dotted key (``a.b[2]``) of the first difference between two JSON-like values, numbers
    equal within :data:`PAIR_RTOL`; ``''`` when the values differ at the top; None if equal.

    Parameters
    ----------
    made, wanted : object
        JSON-like values (mappings, lists, numbers, strings, booleans).
    prefix : str, default ""
        The key of the values themselves.

    Returns
    -------
    str or None
        The dotted key of the first difference (keys sorted), '' at the top, None when equal.
    """
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


def _same_file(written: str, path: str | Path) -> bool:
    """Whether the recorded ``written`` names ``path`` (both relative to the working directory,
    or either absolute)."""
    return normal_path(written) == normal_path(path) or os.path.abspath(written) == os.path.abspath(path)


def _reason(exc: BaseException, path: str | Path) -> str:
    """The library's reason without the path it repeats (e.g. 'NetCDF: HDF error')."""
    text = getattr(exc, "strerror", None) or str(exc)
    for form in (f": '{path}'", f": '{os.path.abspath(path)}'", str(os.path.abspath(path)), str(path)):
        text = text.replace(form, "")
    return excerpt(" ".join(text.split()).strip(" :") or type(exc).__name__, 80)


_RECOVERY = "regenerate it: snakemake --forcerun"


def _recovery(path: str | Path) -> str:
    return f"{_RECOVERY} {normal_path(path)} (with this run's --configfile)"


def _without_recovery(rule: str) -> str:
    """A refusal's rule without its closing :func:`_recovery` (when another file's line takes it)."""
    return rule.split(f"; {_RECOVERY}", 1)[0]
