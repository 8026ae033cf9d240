"""``gearmesh run``: Snakemake started only after every config it would read has been read bounded.

Snakemake reads configuration before the Snakefile runs, so before any check of the workflow's
own: every ``--configfile`` (parsed by its own YAML loader, with no limit on size, nesting or
what it opens), and every profile (``--profile``, ``$SNAKEMAKE_PROFILE``, ``--workflow-profile``
and the workflow's default ``profiles/default``), whose ``config.yaml`` (or ``profile.yaml``) it
reads as a YTE template — Python, run at load time, when the file says ``__use_yte__: true`` —
and whose ``configfile``/``configfiles`` keys name more config files. :func:`snakemake_inputs`
finds all of them the way Snakemake does (its own argument parser and profile lookup, so an
abbreviated option or an environment variable is no way around), and :func:`check_inputs` reads
each with the package's bounded loader (:func:`gearmesh.inputfile.read_yaml`: a regular file of at
most MAX_INPUT_BYTES, MAX_INPUT_NODES nodes, MAX_INPUT_DEPTH levels, no alias, no duplicated
key), refuses ``__use_yte__`` in any of them and validates each config file as a study
(:func:`gearmesh.config.validate_study`). Whatever fails is refused in one line, exit 2, before
Snakemake starts (docs/workflow.md, trust model). :func:`run_snakemake` then runs it in this
process and lets the process exit as soon as it has returned.
"""

from __future__ import annotations

import contextlib
import io
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .errors import GearmeshInputError, excerpt

#: The study config Snakemake reads when nothing names one (the Snakefile's ``configfile``).
DEFAULT_STUDY = "config/config.yaml"
#: Profile keys that name config files (Snakemake's ``--configfile`` and its alias).
CONFIGFILE_KEYS = ("configfile", "configfiles")


@dataclass
class SnakemakeInputs:
    """What a Snakemake command line makes Snakemake read before the Snakefile runs: the profile
    files (in the order Snakemake applies them) and the config files (the command line's and
    every profile's; the default study when none names one); and whether its command line runs
    jobs on this machine (``local_jobs``: no ``--dry-run``, ``--report`` or ``--lint``, the local
    executor; a profile's own settings are not looked at)."""

    profiles: list[Path] = field(default_factory=list)
    configfiles: list[str] = field(default_factory=list)
    local_jobs: bool = True


def snakemake_inputs(argv: Sequence[str]) -> SnakemakeInputs:
    """The profiles and config files of the Snakemake command line ``argv`` (and of the
    environment: ``$SNAKEMAKE_PROFILE``), found by Snakemake's own parser and profile lookup
    (``snakemake.cli``); GearmeshInputError for arguments Snakemake would refuse and for a profile
    it would not find.

    Parameters
    ----------
    argv : sequence of str
        The arguments ``gearmesh run`` passes on to Snakemake.

    Returns
    -------
    SnakemakeInputs
        ``profiles``: the profile files in the order Snakemake applies them; ``configfiles``: the
        command line's, then every profile's (:data:`DEFAULT_STUDY` when none is named).

    Raises
    ------
    GearmeshInputError
        Naming "snakemake arguments" for arguments Snakemake's parser refuses, "--profile" for a
        profile it would not find, or the profile key that turns on YTE.

    References
    ----------
    .. [1] Snakemake documentation, "Profiles" (command-line interface): profile lookup,
       ``$SNAKEMAKE_PROFILE``, workflow-specific profiles and YTE templating.
       https://snakemake.readthedocs.io/en/stable/executing/cli.html#profiles
    """
    from snakemake.cli import get_argument_parser, get_profile_dir

    args = _parse(get_argument_parser(), argv)
    profiles = [] if args.profile in (None, ["none"]) else list(args.profile)
    workflow_profile = _workflow_profile(args)
    if workflow_profile is not None:
        profiles.append(workflow_profile)
    out = SnakemakeInputs()
    for profile in profiles:
        found = get_profile_dir(str(profile))
        if found is None:
            raise GearmeshInputError("--profile", str(profile), "has no profile.yaml or config.yaml (Snakemake looks in "
                                     "the working directory and its configuration folders)")
        folder, path = found
        out.profiles.append(Path(path))
        out.configfiles += _profile_configfiles(Path(folder), Path(path))
    out.configfiles = [str(p) for p in args.configfile or ()] + out.configfiles
    out.local_jobs = not (args.dryrun or args.report or args.lint) and args.executor in (None, "local")
    if not out.configfiles:
        out.configfiles = [DEFAULT_STUDY]
    return out


def _parse(parser, argv: Sequence[str]):
    """``argv`` parsed by Snakemake's parser, its refusal (argparse's usage and exit) as one line."""
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            return parser.parse_args(list(argv))
    except SystemExit:
        reason = err.getvalue().strip().splitlines()[-1:] or ["not snakemake's arguments"]
        raise GearmeshInputError("snakemake arguments", " ".join(argv), excerpt(reason[0].split("error: ", 1)[-1],
                                 120) + " (snakemake --help)") from None


def _workflow_profile(args) -> Path | None:
    """The workflow profile Snakemake applies (``snakemake.cli.parse_args``): ``--workflow-profile``,
    else ``profiles/default`` in the working directory or beside the Snakefile; None with
    ``--workflow-profile none`` or none found."""
    from snakemake.api import resolve_snakefile

    if args.workflow_profile == "none":
        return None
    given = Path(args.workflow_profile) if args.workflow_profile else None
    snakefile = resolve_snakefile(args.snakefile, allow_missing=True)
    if snakefile is None or (given is not None and given.is_file()):
        return given
    name = given or Path("default")
    candidates = [name, Path("profiles") / name]
    if isinstance(snakefile, Path):
        candidates.append(snakefile.parent / "profiles" / name)
    return next((c for c in candidates if c.exists()), None)


def _profile_configfiles(folder: Path, path: Path) -> list[str]:
    """The config files a profile names (``configfile``/``configfiles``; a single path as
    Snakemake's profile parser resolves it: variables expanded, relative to the profile's folder
    where it exists there), after the profile itself is read bounded, a mapping without
    ``__use_yte__``."""
    from .inputfile import read_yaml

    data = read_yaml(path, "profile")
    if not isinstance(data, Mapping):
        raise GearmeshInputError("profile", str(path), "must be a YAML mapping of snakemake options")
    if "__use_yte__" in data:
        raise GearmeshInputError("__use_yte__", data["__use_yte__"], f"in the profile {path} turns on Snakemake's YTE "
                                 "template engine, which runs Python from the profile when Snakemake loads it (before "
                                 "any check): remove the key")
    out = []
    for key in CONFIGFILE_KEYS:
        value = data.get(key)
        if value is None:
            continue
        if isinstance(value, list):
            out += [str(v) for v in value]
            continue
        value = os.path.expanduser(os.path.expandvars(str(value)))
        out.append(str(folder / value) if (folder / value).exists() else value)
    return out


def check_inputs(inputs: SnakemakeInputs) -> None:
    """Every config file of ``inputs`` read bounded, a mapping, valid as a study
    (:func:`gearmesh.config.validate_study`, which names ``__use_yte__``); the profiles were read
    bounded by :func:`snakemake_inputs`. GearmeshInputError naming the first that fails.

    Parameters
    ----------
    inputs : SnakemakeInputs
        What :func:`snakemake_inputs` found.

    Raises
    ------
    GearmeshInputError
        The first config file's failure (unreadable, not a mapping, not a valid study), the rule
        naming the file.
    """
    from .config import validate_study
    from .inputfile import read_yaml

    for path in inputs.configfiles:
        data = read_yaml(path, "config file")
        if not isinstance(data, Mapping):
            raise GearmeshInputError("config file", path, "must be a YAML mapping (a study config)")
        try:
            validate_study(data)
        except GearmeshInputError as exc:
            raise GearmeshInputError(exc.field, exc.value, f"{exc.rule} (in config file {path})") from None


def run_snakemake(argv: Sequence[str], local_jobs: bool = False) -> None:
    """Run Snakemake's command line ``argv`` in this process (its entry point, ``snakemake.cli.main``),
    then let the process exit at once.

    With ``local_jobs`` (the command line runs jobs here: :class:`SnakemakeInputs`) the job server
    starts first (:func:`gearmesh.jobserver.start_ahead`), so that its imports and the kernels'
    compile run on a free core while Snakemake reads the Snakefile and builds its DAG, single-
    threaded: the first jobs no longer wait for them (0.8 s, measured on the default study).

    Two things delayed that exit by about a second at the end of every run, measured on the
    default study: Snakemake's job-rate timers (a :class:`threading.Timer` after every scheduling
    round, each the timespan of ``--max-jobs-per-timespan``, 1 s by default; the interpreter waits
    for every non-daemon thread before it exits) and the interpreter's last garbage collection over
    a heap of Snakemake's DAG and the imported libraries (0.45 s). The timers, whose only work is to
    wake a scheduler that has finished, are cancelled; the heap is frozen (:func:`gc.freeze`), so
    that last collection skips it. The exit handlers (``atexit``: logging's flush and close among
    them) still run.

    Parameters
    ----------
    argv : sequence of str
        Snakemake's arguments.
    local_jobs : bool, default False
        Start the job server ahead of Snakemake.

    Raises
    ------
    SystemExit
        Always: Snakemake's exit code.

    References
    ----------
    .. [1] Python documentation, :class:`threading.Timer` (``cancel``), :func:`gc.freeze`, and
       "threading": the program exits when no alive non-daemon threads are left.
    """
    import gc

    from snakemake.cli import main

    from . import jobserver

    if local_jobs:
        jobserver.start_ahead(jobserver.stage_modules())
    try:
        main(list(argv))
    finally:
        cancel_timers()
        gc.freeze()


def cancel_timers() -> None:
    """Cancel this process's pending :class:`threading.Timer` threads: at the end of a run,
    Snakemake's job-rate timers (one per scheduling round, 1 s each by default), whose only work is
    to wake its finished scheduler, and for which the interpreter would wait before it exits
    (:func:`run_snakemake`; the Snakefile's ``onsuccess`` and ``onerror``, for a plain
    ``snakemake`` run).

    Returns
    -------
    None
    """
    import threading

    for thread in threading.enumerate():
        if isinstance(thread, threading.Timer):
            thread.cancel()
