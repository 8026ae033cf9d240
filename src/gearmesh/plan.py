"""The study's plan: every rule of the workflow and the study's targets, derived from the stage
declarations (:mod:`gearmesh.stages`, the ``STAGE`` of each settings class in
:mod:`gearmesh.settings`). ``workflow/rules/stages.smk`` defines one Snakemake rule per
:class:`Rule` in a loop; nothing else names a stage's files, figures, captions or tables.

The study runs every stage whose section it has (and whose ``wanted`` holds), every table of
those stages that is wanted, and every stage a running job reads (transitively): the rules
defined are those. A read's condition (:attr:`gearmesh.stages.Read.when`) sees the study's
settings filled (:func:`filled`): a section the study leaves out reads as its declared defaults,
so a job whose defaults take the FE tooth gets the pair's FE tables as its input. ``wanted``
and a figure's condition see the config as written (a section left out is a stage not run).

Reading a config imports no physics: this module needs the declarations, the config checks and
:mod:`gearmesh.codeversion` only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Iterator, Mapping

from .codeversion import versioned
from .config import pair_path
from .schema import defaults
from .registry import stage_sections, stages
from .stages import Job, Read, Stage, Table

#: The script of every job, relative to the rules' file ``workflow/rules/stages.smk``: it runs the
#: job as its declaration says (:func:`gearmesh.pipeline.run_job`). One script for every rule: a
#: ``script:`` directive is evaluated again when the job runs, after the loop that defines the
#: rules has moved on, so it cannot name a loop variable.
SCRIPT = "../scripts/job.py"
#: The report's captions, relative to the rules' file.
CAPTIONS = "../report"


class Filled(Mapping[str, Any]):
    """The study config with every stage section it leaves out read as that section's declared
    defaults (``in`` still says whether the study has the section)."""

    def __init__(self, config: Mapping[str, Any]):
        self._config = config
        self._defaults = {path: cls for path, cls in stage_sections() if "." not in path}

    def __getitem__(self, key: str) -> Any:
        if key in self._config:
            return self._config[key]
        if key in self._defaults:
            return defaults(self._defaults[key])
        raise KeyError(key)

    def __contains__(self, key: object) -> bool:
        return key in self._config

    def __iter__(self) -> Iterator[str]:
        return iter(self._config)

    def __len__(self) -> int:
        return len(self._config)


def filled(config: Mapping[str, Any]) -> Filled:
    """:class:`Filled` of ``config``.

    Parameters
    ----------
    config : mapping
        A validated study config.

    Returns
    -------
    Filled
        A read-only view of ``config``.
    """
    return Filled(config)


@dataclass(frozen=True)
class Output:
    """One output of a rule: ``path`` (a wildcard template), in the report with the caption
    ``workflow/report/{caption}.rst`` under ``category`` and ``subcategory`` when ``caption``."""

    path: str
    caption: str | None = None
    category: str | None = None
    subcategory: str | None = None


@dataclass(frozen=True)
class Rule:
    """One rule of the workflow (``stages.smk`` defines it): its ``name``, ``input`` function
    (of the wildcards; Snakemake's ``unpack``), outputs by name, ``log``, ``params``,
    ``localrule``, ``priority`` and what it makes (``doc``, ``snakemake --list-rules``)."""

    name: str
    input: Callable[[Any], dict[str, Any]]
    outputs: Mapping[str, Output]
    log: str
    params: Mapping[str, Any]
    localrule: bool
    priority: int
    doc: str

    def output(self, report: Callable[..., Any]) -> dict[str, Any]:
        """The outputs as Snakemake takes them: each report item marked with ``report`` (Snakemake's
        function) and its caption file."""
        return {name: report(o.path, caption=f"{CAPTIONS}/{o.caption}.rst", category=o.category,
                             subcategory=o.subcategory) if o.caption else o.path
                for name, o in self.outputs.items()}


def versioned_param(spec: str) -> Callable[[Any], str]:
    """A rule's ``params.function`` / ``params.figures``: the package function ``spec`` with the
    digest of the code it can run (:func:`gearmesh.codeversion.versioned`), so a code change reruns
    the job. Given as a function of the wildcards: Snakemake formats a plain string param with the
    wildcards (a plain ``str`` again) but keeps what a param function returns, so the report's job
    panel shows the function's name and the rerun trigger still compares the digest.

    Parameters
    ----------
    spec : str
        ``"package.module:function"``.

    Returns
    -------
    callable
        A function of the wildcards returning ``"package.module:function@digest"``, the same string
        also as its ``spec`` attribute.

    References
    ----------
    .. [1] Snakemake documentation, "Snakefiles and Rules", section "Non-file parameters for rules"
       (params given as functions), and "Command line interface", ``--rerun-triggers`` (a job reruns
       when its params change). https://snakemake.readthedocs.io/en/stable/snakefiles/rules.html
    """
    value = versioned(spec)
    param = lambda wildcards: value  # noqa: E731
    param.spec = value  # gearmesh.jobserver.rule_modules reads it without wildcards
    return param


# --------------------------------------------------------------------------------------
# What the study runs
# --------------------------------------------------------------------------------------


def stage_wanted(config: Mapping[str, Any], section: str, stage: Stage) -> bool:
    """Whether the study gets the result of ``stage``: it has the section, and ``wanted`` holds.

    Parameters
    ----------
    config : mapping
        The study config as written.
    section : str
        The stage's config section.
    stage : Stage
        Its declaration.

    Returns
    -------
    bool
    """
    return section in config and (stage.wanted is None or stage.wanted(config, section))


def table_wanted(config: Mapping[str, Any], section: str, table: Table) -> bool:
    """Whether the study gets ``table`` of the stage of ``section``.

    Parameters
    ----------
    config : mapping
        The study config as written.
    section : str
        The config section of the stage the table belongs to.
    table : Table
        The table's declaration.

    Returns
    -------
    bool
    """
    return section in config and (table.wanted is None or table.wanted(config, section))


def active_reads(config: Mapping[str, Any], section: str, job: Stage | Table) -> list[Read]:
    """The results the job of ``job`` (declared by the stage of ``section``) reads in this study.

    Parameters
    ----------
    config : mapping
        The study config (read through :func:`filled`).
    section : str
        The config section of the declaring stage.
    job : Stage or Table
        The job whose reads are asked for.

    Returns
    -------
    list of Read
        The reads whose ``when`` holds, in the declaration's order.
    """
    view = filled(config)
    return [r for r in job.reads if r.when(view, section)]


def study_stages(config: Mapping[str, Any]) -> dict[str, Stage]:
    """Every stage the study runs by section, in the declarations' order: those it wants, the
    stages their jobs and their tables read, and so on.

    Parameters
    ----------
    config : mapping
        A validated study config.

    Returns
    -------
    dict of str to Stage
        Section name to stage declaration, in the order of :func:`gearmesh.registry.stages`.
    """
    declared = stages()
    run = {s for s, stage in declared.items() if stage_wanted(config, s, stage)}
    todo = list(run)
    while todo:
        section = todo.pop()
        stage = declared[section]
        jobs = [stage, *(t for t in stage.tables if table_wanted(config, section, t))]
        for read in (r for job in jobs for r in active_reads(config, section, job)):
            if read.stage not in run:
                run.add(read.stage)
                todo.append(read.stage)
    return {s: stage for s, stage in declared.items() if s in run}


# --------------------------------------------------------------------------------------
# Rules
# --------------------------------------------------------------------------------------


def _units(config: Mapping[str, Any], scope: str, runs: Callable[[Mapping[str, Any]], bool] | None = None,
           section: str = "") -> list[dict[str, str]]:
    """The wildcards of every job of a scope in the study (study filled)."""
    study = {"study": str(config["study"])}
    pairs = list(config["pairs"])
    if scope == "study":
        return [study]
    if scope == "pair":
        return [{**study, "pair": p} for p in pairs]
    if scope == "variant":
        return [{**study, "pair": p, "variant": v} for p in pairs for v in config["variants"]]
    named = config.get(section) or {}
    return [{**study, "pair": p, "run": r} for p in pairs for r in named if runs is None or runs(named[r])]


def _inputs(config: Mapping[str, Any], section: str, job: Stage | Table) -> Callable[[Any], dict[str, Any]]:
    """Input function of the rule of ``job``: a stage's pair file (a variant's stage: the
    variant's source pair; a stage over the study's pairs: every pair it names), and each result
    the job reads in this study: of the job's own pair and variant, of every variant of its pair,
    or of every pair of the study."""
    declared = stages()
    reads = [(r, declared[r.stage].path) for r in active_reads(config, section, job)]
    variants = list(config["variants"])
    pairs = list(config["pairs"])
    pair_file = isinstance(job, Stage) and job.pair_file

    def inputs(wildcards: Any) -> dict[str, Any]:
        own = dict(wildcards.items())
        if pair_file and job.scope == "study":
            return {"pairs": [str(pair_path(config, n)) for n in config[section]["pairs"]]}
        out: dict[str, Any] = {}
        if pair_file:
            out["pair"] = _source_pair(config, own) if job.scope == "variant" else str(pair_path(config, own["pair"]))
        for read, path in reads:
            if read.every_variant:
                out[read.argument] = [path(**{**own, "variant": v}) for v in variants]
            elif read.every_pair:
                out[read.argument] = [path(study=own["study"], pair=p, variant="standard") for p in pairs]
            else:
                out[read.argument] = path(**own)
        return out

    return inputs


def _source_pair(config: Mapping[str, Any], wildcards: Mapping[str, str]) -> str:
    """The pair file a variant's stages read: the study's pair file, or for a variant
    {from: optimise.NAME} that optimisation's pair file (its optimum). The stage applies the
    variant's micro-geometry itself (params.variant, gearmesh.pairfile.variant_pair): a job of its own
    per variant would cost a Python start-up to copy a pair file."""
    source = config["variants"][wildcards["variant"]].get("from")
    if source:
        return f"results/{wildcards['study']}/{wildcards['pair']}/optimise/{source.split('.', 1)[1]}/pair.yaml"
    return str(pair_path(config, wildcards["pair"]))


def _outputs(config: Mapping[str, Any], section: str, job: Stage | Table) -> dict[str, Output]:
    """The outputs of ``job``: its netCDF result, its further files, its CSV copy and its
    figures (those the study draws), the last two as report items."""
    out: dict[str, Output] = {}
    if job.writes:
        out["nc"] = Output(job.path())
    for name, file in getattr(job, "also_writes", ()):
        out[name] = Output(job.file(file))
    report = {"category": job.category, "subcategory": job.subcategory}
    if job.csv:
        out["csv"] = Output(job.csv_path(), caption=job.stem, **report)
    for figure in job.figures:
        if figure.when(config, section):
            out[figure.name] = Output(job.figure_path(figure), caption=figure.caption_name, **report)
    return out


def _stage_params(config: Mapping[str, Any], section: str, stage: Stage) -> dict[str, Any]:
    """The params of the rule of ``stage``: the function it runs, its settings (its config
    section, the run's entry for a stage per run; the variant's name and the sections it carries
    when it takes them), the variant's spec and the function that draws its figures."""

    def settings(wildcards: Any) -> dict[str, Any]:
        own = config[section][wildcards.run] if stage.scope == "run" else config.get(section, {})
        return {**own, **({"variant": wildcards.variant} if stage.variant_name else {}),
                **{s: config.get(s) for s in stage.carries}}

    out: dict[str, Any] = {"function": versioned_param(stage.function), "settings": settings}
    if stage.scope == "variant":
        out["variant"] = lambda wildcards: config["variants"][wildcards.variant]
    if stage.draws:
        out["figures"] = versioned_param(stage.draws)
    return out


def _table_params(table: Table) -> dict[str, Any]:
    out: dict[str, Any] = {"function": versioned_param(table.function)}
    if table.writes and table.draws:
        out["figures"] = versioned_param(table.draws)
    return out


def _rule(config: Mapping[str, Any], name: str, section: str, job: Stage | Table, params: dict[str, Any]) -> Rule:
    return Rule(name=name, input=_inputs(config, section, job), outputs=_outputs(config, section, job),
                log=job.log_path(name), params=params, localrule=job.localrule, priority=job.priority,
                doc=_doc(config, section, job))


def _doc(config: Mapping[str, Any], section: str, job: Stage | Table) -> str:
    """What the job makes: a stage's settings class's description; a table's file (or figures) and
    the results it is made from."""
    if isinstance(job, Stage):
        return " ".join((dict(stage_sections())[section if job.scope != "run" else f"{section}.NAME"].__doc__ or
                         "").split())
    made = job.writes or ", ".join(f"{f.stem}.png" for f in job.figures if f.when(config, section))
    sources = ", ".join(r.stage + (" of every variant of the pair" if r.every_variant else
                                   " of every pair" if r.every_pair else "") for r in job.reads)
    return f"{made}, from the results of {sources}"


def rules(config: Mapping[str, Any]) -> list[Rule]:
    """Every rule of the study (a validated config, defaults filled): the rule of each stage it
    runs (:func:`study_stages`, named as its section) and of each wanted table of those stages
    (named as the table).

    Parameters
    ----------
    config : mapping
        A validated study config, defaults filled.

    Returns
    -------
    list of Rule
        The rules in the order of their stages, each stage's rule before its tables'.

    References
    ----------
    .. [1] Snakemake documentation, "Snakefiles and Rules" (input functions and ``unpack``,
       ``localrule``, ``priority``, ``log``) and "Snakemake Reports" (``report`` captions,
       categories and subcategories). https://snakemake.readthedocs.io/en/stable/snakefiles/rules.html
    """
    out = []
    for section, stage in study_stages(config).items():
        out.append(_rule(config, section, section, stage, _stage_params(config, section, stage)))
        for table in stage.tables:
            if table_wanted(config, section, table):
                out.append(_rule(config, table.name, section, table, _table_params(table)))
    return out


def _job_targets(config: Mapping[str, Any], job: Job, runs: Callable[[Mapping[str, Any]], bool] | None = None,
                 section: str = "") -> list[str]:
    """What the study asks of ``job``: its result for every unit of its scope (a figure job: its figures)."""
    units = _units(config, job.scope, runs, section)
    if job.writes:
        return [job.path(**u) for u in units]
    return [job.figure_path(f, **u) for u in units for f in job.figures if f.when(config, section)]


def targets(config: Mapping[str, Any]) -> list[str]:
    """Every file the study asks for: the result of every stage it wants (each job's figures and
    tables come with its netCDF file), then every wanted table's (once per study, per pair, per
    variant of a pair or per run of a pair).

    Parameters
    ----------
    config : mapping
        A validated study config, defaults filled.

    Returns
    -------
    list of str
        Paths under ``results/{study}/`` (the wildcards filled), stages first, then tables.
    """
    declared = stages()
    wanted = [(s, stage) for s, stage in declared.items() if stage_wanted(config, s, stage)]
    out = [path for s, stage in wanted for path in _job_targets(config, stage, section=s)]
    for section, stage in wanted:
        for table in stage.tables:
            if table_wanted(config, section, table):
                out += _job_targets(config, table, table.of_runs, section)
    return out
