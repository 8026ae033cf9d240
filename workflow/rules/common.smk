# Config loading and helpers shared by every rule. No physics here.
import sys

from gearmesh.config import check_study, lste_comparison_wanted, pair_path, study_excitation
from gearmesh.settings import stage_of, stages
from gearmesh.codeversion import versioned
from gearmesh.errors import GearmeshInputError
from gearmesh import jobserver
from gearmesh.io import remove_stale_temporaries

STUDY = config["study"]
ENV = "../envs/gearmesh.yaml"

# Every pair and variant of the study is loaded and checked before any job runs, so a bad
# input stops the workflow with one message and no partial output.
try:
    PAIRS = check_study(config)
except GearmeshInputError as exc:
    print(f"gearmesh: error: {exc}", file=sys.stderr)
    sys.exit(2)


VARIANTS = list(config["variants"])
RUNS = list(config.get("optimise") or {})


wildcard_constraints:
    study=STUDY,
    pair="|".join(PAIRS),
    variant="|".join(VARIANTS),
    run="|".join(RUNS) or "^$",


def versioned_param(spec):
    """A rule's ``params.function`` / ``params.figures``: the package function ``spec`` with the
    digest of the code it can run (gearmesh.codeversion.versioned), so a code change reruns the job.
    Given as a function of the wildcards: Snakemake formats a plain string param with the wildcards
    (a plain ``str`` again) but keeps what a param function returns, so the report's job panel shows
    the function's name and the rerun trigger still compares the digest."""
    value = versioned(spec)
    param = lambda wildcards: value
    param.spec = value  # gearmesh.jobserver.rule_modules reads it without wildcards
    return param


def pair_file(wildcards):
    return str(pair_path(config, wildcards.pair))


def variant_source_pair(wildcards):
    """The pair file a variant's stages read: the study's pair file, or for a variant
    {from: optimise.NAME} that optimisation's pair file (its optimum, rule optimise). The stage
    applies the variant's micro-geometry itself (params.variant, gearmesh.gear.variant_pair):
    a job of its own per variant would cost a Python start-up to copy a pair file."""
    source = config["variants"][wildcards.variant].get("from")
    if source:
        return f"results/{wildcards.study}/{wildcards.pair}/optimise/{source.split('.', 1)[1]}/pair.yaml"
    return pair_file(wildcards)


def variant_spec(wildcards):
    """The variant's section of the study config (params.variant of every variant stage)."""
    return config["variants"][wildcards.variant]


def dynamics_contact():
    """Whether the study's dynamics is driven by the real tooth contact (excitation: contact)."""
    return study_excitation(config) == "contact"


def dynamics_figure_outputs():
    """The figures of the dynamics job: RMS against speed and spectra, and with the contact excitation the
    entering pair's force over the engagement."""
    base = "results/{study}/{pair}/{variant}/plots"
    out = {"rms": report_item(f"{base}/dynamics_rms.png", "dynamics_rms", "Dynamics", BY_VARIANT),
           "spectrum": report_item(f"{base}/dynamics_spectrum.png", "dynamics_spectrum", "Dynamics", BY_VARIANT)}
    if dynamics_contact():
        out["engagement"] = report_item(f"{base}/dynamics_engagement.png", "dynamics_engagement", "Dynamics",
                                        BY_VARIANT)
    return out


def stage_inputs(section):
    """Input function of the rule of stage ``section`` (gearmesh.settings: its STAGE): its pair
    file (a variant's stage: the variant's source pair; a study stage: every pair it names), and
    each result the stage reads, of the job's own pair and variant, when the study config says so
    (the FE tables when its method is fe, the LTCA when it drives the dynamics)."""
    stage = stage_of(section)
    reads = [(read, stage_of(read.stage).path) for read in stage.reads]  # resolved once, not per job

    def inputs(wildcards):
        if stage.scope == "study":
            return {"pairs": [str(pair_path(config, n)) for n in config[section]["pairs"]]}
        out = {}
        if stage.pair_file:
            out["pair"] = variant_source_pair(wildcards) if stage.scope == "variant" else pair_file(wildcards)
        for read, path in reads:
            if not read.when(config, section):
                continue
            if read.every_variant:
                out[read.stage] = [path(**{**dict(wildcards.items()), "variant": v}) for v in VARIANTS]
            else:
                out[read.stage] = path(**dict(wildcards.items()))
        return out

    return inputs


def stage_output(section):
    """The netCDF file the rule of stage ``section`` writes (its declaration's)."""
    return stage_of(section).path()


def stage_params(section):
    """The params of the rule of stage ``section``: the function it runs, its settings (its config
    section, the run's entry for a stage per run; the variant's name and the sections it carries
    when it takes them), the variant's spec and the function that draws its figures."""
    stage = stage_of(section)

    def settings(wildcards):
        own = config[section][wildcards.run] if stage.scope == "run" else config.get(section, {})
        return {**own, **({"variant": wildcards.variant} if stage.variant_name else {}),
                **{s: config.get(s) for s in stage.carries}}

    out = {"function": versioned_param(stage.function), "settings": settings}
    if stage.scope == "variant":
        out["variant"] = variant_spec
    if stage.figures:
        out["figures"] = versioned_param(stage.figures)
    return out


def every_variant(section):
    """Input function of a table of a pair's variants: the result of stage ``section`` of every
    variant of the job's pair (its path the stage's declaration)."""
    path = stage_of(section).path
    return lambda wildcards: [path(study=wildcards.study, pair=wildcards.pair, variant=v) for v in VARIANTS]


def every_pair(section, variant="standard"):
    """Input function of a study table: the result of stage ``section`` of every pair of the study
    (of its ``variant`` for a stage of the variants)."""
    path = stage_of(section).path
    return lambda wildcards: [path(study=wildcards.study, pair=name, variant=variant) for name in config["pairs"]]


def stage_targets():
    """The result of every stage the study runs (each job's figures come with its netCDF file):
    once per study, per pair, per variant of a pair or per optimisation run of a pair."""
    out = []
    for section, stage in stages().items():
        if section not in config or (stage.wanted is not None and not stage.wanted(config, section)):
            continue
        pairs = config["pairs"]
        if stage.scope == "study":
            out.append(stage.path(study=STUDY))
        elif stage.scope == "pair":
            out += [stage.path(study=STUDY, pair=name) for name in pairs]
        elif stage.scope == "variant":
            out += [stage.path(study=STUDY, pair=name, variant=v) for name in pairs for v in VARIANTS]
        else:
            out += [stage.path(study=STUDY, pair=name, run=r) for name in pairs for r in RUNS]
    return out


def all_targets():
    """Every stage's result, the study tables and the figures of no stage of their own."""
    targets = stage_targets()
    if "ltca" in config:
        targets += [f"results/{STUDY}/{name}/lte_table.nc" for name in config["pairs"]]
    if "impact" in config:
        targets += [f"results/{STUDY}/{name}/impact_table.nc" for name in config["pairs"]]
    if "rating" in config:
        targets += [f"results/{STUDY}/{name}/load_capacity_table.nc" for name in config["pairs"]]
    if "signoff" in config:
        targets += [f"results/{STUDY}/{name}/signoff_verdict.nc" for name in config["pairs"]]
    for run, section in (config.get("optimise") or {}).items():
        if section["method"] == "nsga2":
            targets += [f"results/{STUDY}/{name}/optimise/{run}/plots/pareto.png" for name in config["pairs"]]
    if "dynamics" in config:
        targets += [f"results/{STUDY}/{name}/plots/dynamics_variants.png" for name in config["pairs"]]
        if dynamics_contact() and "impact" in config:
            targets += [f"results/{STUDY}/{name}/engagement_table.nc" for name in config["pairs"]]
    if lste_comparison_wanted(config):
        targets.append(f"results/{STUDY}/lste_comparison.nc")
    return targets


# Results follow the code: each rule's params.function is versioned("module:function"),
# which appends the digest of the package modules that function can run; Snakemake reruns a
# job whose params changed, so a code change reruns exactly the jobs it can affect.
# `snakemake --report report.html`: every figure and table is marked with report_item(path,
# CAPTION, CATEGORY, SUBCATEGORY): caption workflow/report/CAPTION.rst (Jinja: snakemake.wildcards,
# snakemake.config), category = the stage, subcategory = the pair, pair / variant, or study tables.
BY_PAIR = "{pair}"
BY_VARIANT = "{pair} / {variant}"
BY_RUN = "{pair} / {run}"
STUDY_TABLES = "Study tables"


def report_item(path, caption, category, subcategory=BY_PAIR):
    return report(path, caption=f"../report/{caption}.rst", category=category, subcategory=subcategory)


# A job killed outright (kill -9, a lost node) skips the cleanup of its atomic write and leaves
# .NAME.PID.tmp.* beside its target: remove them before any job of this run starts.
# A local run then starts its job server: one process that imports the modules of the study's
# rules once and forks a child per job (gearmesh.jobserver; GEARMESH_JOBSERVER=off runs every
# job in a process of its own, as a cluster run does).
onstart:
    remove_stale_temporaries("results")
    if jobserver.wanted(workflow):
        jobserver.start(jobserver.rule_modules(workflow.rules))


onsuccess:
    jobserver.stop()


onerror:
    jobserver.stop()
