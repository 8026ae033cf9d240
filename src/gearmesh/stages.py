"""What a workflow stage is, declared once beside its settings.

A stage's declaration is its settings dataclass in :mod:`gearmesh.settings` (its keys: type,
default, bounds, description) with a ``STAGE`` class attribute, a :class:`Stage`: the function
that computes it, the result it writes, the results of other stages it reads (and when), the
config sections it takes whole or needs, the figures it draws with their captions and report
category, the tables of the variants (or of the pairs) collected from its results
(:class:`Table`), and the work limits its settings are checked against before any job runs
(:class:`Torques`, :class:`Speeds`, :class:`Grid`). From that one declaration come

* the study schema, ``gearmesh validate`` and ``config/README.md`` (the settings fields);
* the stage function's defaults and argument checks (:func:`gearmesh.arguments.check_arguments`);
* every Snakemake rule of the study — input, output with the report's caption, category and
  subcategory, log, params, localrule, priority, script — and the study's targets
  (:mod:`gearmesh.plan`, which ``workflow/rules/stages.smk`` turns into rules in one loop);
* the sections a stage needs (:func:`required_sections`) and its work limits, checked before any
  job runs (:func:`gearmesh.config.check_stages`);
* the config sections a result depends on, which :mod:`gearmesh.upstream` compares when the
  file is read (:func:`dependencies`).

Functions are named ``"package.module:name"``, not by the function object: the settings module
declares the stages and is imported to read a config (``gearmesh validate``, the Snakefile), which
must not import the physics (numpy, numba, xarray); the stage functions' own modules import the
settings (their defaults). :func:`resolve` imports a declared function, and a test resolves every
declared name, so a rename that misses a declaration fails there.

This module imports only :mod:`gearmesh.choices`: the settings import it, and it imports no
settings, so the declarations form no import circle.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from pathlib import PurePosixPath
from typing import Any, Callable, Literal, Mapping

from .choices import DEFAULT_TOOTH_METHOD, pair_excitation

#: Where a stage's result lives under ``results/{study}/``: once per pair, per micro-geometry
#: variant of a pair, per named run of a pair (optimise), or once per study.
Scope = Literal["pair", "variant", "run", "study"]
#: The folder of each scope's files under ``results/{study}/`` (and ``logs/{study}/``).
FOLDERS: dict[str, str] = {"study": "", "pair": "{pair}/", "variant": "{pair}/{variant}/", "run": "{pair}/optimise/{run}/"}
#: The report's subcategory of each scope's figures and tables (Snakemake fills the wildcards).
SUBCATEGORIES: dict[str, str] = {"study": "Study tables", "pair": "{pair}", "variant": "{pair} / {variant}",
                                 "run": "{pair} / {run}"}
#: The wildcards of the workflow's paths.
WILDCARDS = ("study", "pair", "variant", "run")
#: A condition on the study config under which a stage reads a result, or a stage or table is
#: made (``config``, the section of the stage declaring it). A read's condition sees a section
#: the study leaves out as its declared defaults (:func:`gearmesh.plan.filled`).
When = Callable[[Mapping[str, Any], str], bool]
#: How a job runs (:data:`gearmesh.pipeline.RUNNERS`): a stage of one pair, a stage over the
#: study's pairs, a table of results, the optimiser, a figure job.
Runner = Literal["pair_stage", "study_stage", "collect", "optimise", "plot"]


def always(config: Mapping[str, Any], section: str) -> bool:
    """Read in every study.

    Parameters
    ----------
    config : mapping
        The study config.
    section : str
        The section of the stage declaring the read.

    Returns
    -------
    bool
        True.
    """
    return True


def method_fe(of: str | None = None) -> When:
    """Read when the tooth model of section ``of`` (default: the reading stage's own) is the
    finite-element tooth: its tables come from the pair's fe_compliance result, computed once.
    A section the study leaves out has the declared default method.

    Parameters
    ----------
    of : str, optional
        The section whose ``method`` decides; None: the reading stage's own.

    Returns
    -------
    When
        A condition of (config, section), True when that section's tooth model is ``fe``.
    """

    def when(config: Mapping[str, Any], section: str) -> bool:
        return (config.get(of or section) or {}).get("method", DEFAULT_TOOTH_METHOD) == "fe"

    when.__doc__ = f"the {of or 'stage'}'s method is fe"
    return when


def runs(other: str) -> When:
    """When the study runs stage ``other`` (has its section).

    Parameters
    ----------
    other : str
        The section of the other stage.

    Returns
    -------
    When
        A condition of (config, section), True when the config has section ``other``.
    """

    def when(config: Mapping[str, Any], section: str) -> bool:
        return other in config

    when.__doc__ = f"the study runs {other}"
    return when


def ltca_drives(config: Mapping[str, Any], section: str) -> bool:
    """Read when the LTCA excites the dynamics (:func:`gearmesh.choices.pair_excitation`: the
    section's excitation, or ltca when the study runs the LTCA).

    Parameters
    ----------
    config : mapping
        The study config.
    section : str
        The dynamics section reading the LTCA.

    Returns
    -------
    bool
        Whether that section's excitation is ``ltca``.
    """
    return pair_excitation((config.get(section) or {}).get("excitation"), "ltca" in config) == "ltca"


def contact_drives(config: Mapping[str, Any], section: str) -> bool:
    """When the real tooth contact excites the study's dynamics (excitation contact).

    Parameters
    ----------
    config : mapping
        The study config.
    section : str
        The section of the reading stage (unused: the ``dynamics`` section decides).

    Returns
    -------
    bool
        Whether the study runs the dynamics with excitation ``contact``.
    """
    return "dynamics" in config and pair_excitation((config.get("dynamics") or {}).get("excitation"),
                                                    "ltca" in config) == "contact"


def resolve(spec: str) -> Callable[..., Any]:
    """The function named by ``"package.module:function"`` (a ``"@digest"`` that
    :func:`gearmesh.codeversion.versioned` appends is dropped), imported.

    Parameters
    ----------
    spec : str
        ``"package.module:function"``, optionally with ``"@digest"`` appended.

    Returns
    -------
    callable
        The function.

    Raises
    ------
    ImportError, AttributeError
        When the module or the function does not exist.
    """
    module, _, name = spec.partition("@")[0].partition(":")
    return getattr(importlib.import_module(module), name)


@dataclass(frozen=True)
class Read:
    """A result of stage ``stage`` that a job reads (passed to its function under ``name``,
    default the stage's name): of the job's own pair (and variant and run); with
    ``every_variant`` the list of every variant's of the job's pair (a table of the variants);
    with ``every_pair`` the list of every pair's of the study (its standard variant's for a
    result per variant). Read when ``when`` says so; a read in every study (``when`` always)
    makes the stage's section one the reading stage needs (:func:`required_sections`)."""

    stage: str
    when: When = always
    every_variant: bool = False
    every_pair: bool = False
    name: str | None = None

    @property
    def argument(self) -> str:
        """The name the job's function (and its rule's input) gets the result under."""
        return self.name or self.stage


@dataclass(frozen=True)
class Figure:
    """A figure a job draws: its plot function writes it under output ``name``, as
    ``plots/{file}.png`` in the folder of the job's scope (``file`` default: ``name``); in the
    report with the caption ``workflow/report/{caption}.rst`` (default: ``file``), under the job's
    category and its scope's subcategory. Drawn when ``when`` says so."""

    name: str
    file: str | None = None
    caption: str | None = None
    when: When = always

    @property
    def stem(self) -> str:
        return self.file or self.name

    @property
    def caption_name(self) -> str:
        return self.caption or self.stem


# --------------------------------------------------------------------------------------
# Work limits, checked before any job runs (gearmesh.config.check_stages)
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Torques:
    """Setting ``key`` holds torques (one or a list; null: none) on the gear named by setting
    ``on`` (None: the pinion), each within every pair's contact-stress and deflection limits
    (:func:`gearmesh.loads.check_load`)."""

    key: str
    on: str | None = "on"


@dataclass(frozen=True)
class Speeds:
    """Setting ``key`` holds pinion speeds (one or a list; null: none), none above a pair's burst
    speed (:func:`gearmesh.limits.check_speeds`)."""

    key: str


@dataclass(frozen=True)
class Grid:
    """The grid of settings ``size`` × (``by`` + ``extra``) (the largest of a list) is at most
    ``limit`` ``what`` (:func:`gearmesh.limits.check_grid`, named by setting ``size``)."""

    size: str
    by: str
    limit: int
    what: str
    extra: int = 0

    def points(self, settings: Mapping[str, Any]) -> int:
        size = settings[self.size]
        return (max(size) if isinstance(size, (list, tuple)) else size) * (settings[self.by] + self.extra)


Limit = Torques | Speeds | Grid


# --------------------------------------------------------------------------------------
# Jobs: stages and the tables collected from them
# --------------------------------------------------------------------------------------


def _fill(template: str, wildcards: Mapping[str, str]) -> str:
    """``template`` with the given wildcards filled, the others kept as ``{name}``."""
    return template.format(**{**{k: "{" + k + "}" for k in WILDCARDS}, **wildcards})


class Job:
    """What a stage and a table share: where their files are (by scope), their figures and
    CSV copy in the report, their log."""

    writes: str | None
    scope: Scope
    category: str
    figures: tuple[Figure, ...]
    csv: bool
    log: str | None

    @property
    def folder(self) -> str:
        """The folder of the job's files under ``results/{study}/`` (wildcards unfilled)."""
        return FOLDERS[self.scope]

    def path(self, **wildcards: str) -> str:
        """The result's path, ``results/{study}/...`` with the given wildcards filled (others kept)."""
        return self.file(self.writes, **wildcards)

    def file(self, name: str, **wildcards: str) -> str:
        """The path of file ``name`` in the job's folder under ``results/{study}/``."""
        return _fill("results/{study}/" + self.folder + name, wildcards)

    def figure_path(self, figure: Figure, **wildcards: str) -> str:
        return self.file(f"plots/{figure.stem}.png", **wildcards)

    @property
    def stem(self) -> str | None:
        """The name of the result without its suffix (its CSV copy's and its caption's)."""
        return PurePosixPath(self.writes).stem if self.writes else None

    def csv_path(self, **wildcards: str) -> str:
        return self.file(f"{self.stem}.csv", **wildcards)

    def log_path(self, name: str) -> str:
        """The job's log: ``log`` (under ``logs/{study}/``) or the result's (or ``name``'s) in the
        job's folder, ``.log``."""
        stem = self.log or self.folder + (self.stem or name)
        return "logs/{study}/" + stem + ".log"

    @property
    def subcategory(self) -> str:
        return SUBCATEGORIES[self.scope]


@dataclass(frozen=True)
class Table(Job):
    """A job collected from a stage's results (its rule ``name``): ``function`` computes the table
    (``writes``, a netCDF file in the folder of ``scope``: per pair a table of the pair's
    variants, per study a table of its pairs) from the results it ``reads``; ``draws`` (a plot
    function) draws its ``figures`` from the table and those results. Without ``writes`` a figure
    job: ``function`` is the plot function. ``csv``: a CSV copy, in the report with the caption
    named as the table. Made when the study runs its stage and ``wanted`` says so; of a stage
    per run, for the runs whose settings ``of_runs`` accepts. A table runs where Snakemake runs
    (``localrule``: little work, growing with the number of pairs and variants only)."""

    name: str
    function: str
    writes: str | None
    scope: Scope
    category: str
    reads: tuple[Read, ...]
    figures: tuple[Figure, ...] = ()
    draws: str | None = None
    csv: bool = False
    wanted: When | None = None
    of_runs: Callable[[Mapping[str, Any]], bool] | None = None
    log: str | None = None
    localrule: bool = True
    priority: int = 0

    @property
    def runner(self) -> Runner:
        return "collect" if self.writes else "plot"


@dataclass(frozen=True)
class Stage(Job):
    """One stage, the rule of its config section: ``function`` (``module:name``) computes its
    dataset from the pair (or the study's pairs) and its settings; it ``writes`` one netCDF file
    (named in the folder of its ``scope``), ``reads`` other stages' results, and its plot function
    ``draws`` its ``figures`` from the written file, in the report under ``category``.
    ``carries``: other config sections the function takes whole (the impact stage's
    tolerances), on which its result therefore depends; ``needs``: sections the study must have
    besides those of the stages it always reads (:func:`required_sections`); ``variant_name``: the
    function also takes the variant's name; ``pair_file``: the job reads the pair file (not a table
    of results); ``also_writes``: further outputs (name, file) in its folder (the optimum's pair file);
    ``entry``: its pipeline entry when not the one :attr:`runner` derives.
    ``wanted``: whether a study with this section gets the result (default: whenever the section
    is in the config). ``tables``: the tables collected from its results. ``limits``: the work
    limits of its settings. ``csv``, ``localrule``, ``priority``, ``log``: as the rule's."""

    function: str
    writes: str
    scope: Scope
    reads: tuple[Read, ...] = ()
    category: str = ""
    figures: tuple[Figure, ...] = ()
    draws: str | None = None
    csv: bool = False
    carries: tuple[str, ...] = ()
    needs: tuple[str, ...] = ()
    variant_name: bool = False
    pair_file: bool = True
    also_writes: tuple[tuple[str, str], ...] = ()
    wanted: When | None = None
    tables: tuple[Table, ...] = ()
    limits: tuple[Limit, ...] = ()
    localrule: bool = False
    priority: int = 0
    log: str | None = None
    entry: Runner | None = None

    @property
    def per_variant(self) -> bool:
        """Whether the result depends on the micro-geometry (a variant's)."""
        return self.scope == "variant"

    @property
    def runner(self) -> Runner:
        """The pipeline entry of its job: the one named, else a table of results (no pair file),
        a stage over the study's pairs, or a stage of one pair."""
        if self.entry:
            return self.entry
        if not self.pair_file:
            return "collect"
        return "study_stage" if self.scope == "study" else "pair_stage"


def required_sections(stage: Stage) -> tuple[str, ...]:
    """The sections a study running ``stage`` must have: those of the stages it reads in every
    study, and those it ``needs``.

    Parameters
    ----------
    stage : Stage
        A stage declaration.

    Returns
    -------
    tuple of str
        The section names, in order, each once.
    """
    return tuple(dict.fromkeys([r.stage for r in stage.reads if r.when is always] + list(stage.needs)))


def dependencies(stage: Stage | None, section: str, config: Mapping[str, Any]) -> list[str]:
    """The config sections a result of ``stage`` (config ``section``) depends on: its own and
    each section it carries that the study has; :mod:`gearmesh.upstream` compares them with
    the reading run's.

    Parameters
    ----------
    stage : Stage or None
        The stage declaration (None: a result of no declared stage, only its own section counts).
    section : str
        The stage's config section.
    config : mapping
        The study config of the run that wrote (or reads) the result.

    Returns
    -------
    list of str
        ``section`` when the config has it, then the carried sections the config has, sorted.
    """
    own = [section] if section in config else []
    carried = sorted(s for s in (stage.carries if stage else ()) if isinstance(config.get(s), Mapping))
    return own + carried
