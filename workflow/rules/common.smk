# Config loading and helpers shared by every rule. No physics here.
import sys

from gearmesh.config import check_study, lste_comparison_wanted, pair_path, study_excitation
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


def fe_tables(section):
    """Input function: the pair's FE tooth tables (rule fe_compliance) when the stage of
    ``section`` uses the stiffness method 'fe' — computed once per pair, read by every stage."""

    def inputs(wildcards):
        if config.get(section, {}).get("method") == "fe":
            return {"fe_compliance": f"results/{wildcards.study}/{wildcards.pair}/fe_compliance.nc"}
        return {}

    return inputs


def fe_wanted():
    """Whether the study uses the finite-element tooth (a stage's method fe, or fe among the
    stiffness table's methods): then every pair gets its FE tables and their figure."""
    sections = ("stiffness", "slice_convergence", "ltca", "impact", "dynamics", "train_dynamics")
    return (any((config.get(s) or {}).get("method") == "fe" for s in sections)
            or "fe" in (config.get("stiffness_table") or {}).get("methods", []))


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


def dynamics_inputs(wildcards):
    """The pair stage inputs of the dynamics: the variant's pair, the stiffness, the variant's
    LTCA when it excites the model (excitation ltca, or unset in a study that runs the LTCA) and
    the FE tooth tables when the contact table uses method fe."""
    base = f"results/{wildcards.study}/{wildcards.pair}"
    out = {"pair": variant_source_pair(wildcards), "stiffness": f"{base}/stiffness.nc"}
    if study_excitation(config) == "ltca":
        out["ltca"] = f"{base}/{wildcards.variant}/ltca.nc"
    out.update(fe_tables("dynamics")(wildcards))
    return out


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


def study_pair_files(section):
    """Input function: the pair files a study-level section names."""
    return lambda wildcards: [str(pair_path(config, n)) for n in config[section]["pairs"]]


def pair_results(name):
    """Files every pair of the study gets (each job's figures come with its netCDF file)."""
    base = f"results/{STUDY}/{name}"
    return [f"{base}/geometry.nc", f"{base}/contact_lines.nc", f"{base}/stiffness.nc"]


def variant_results(name, variant):
    """Files every micro-geometry variant of a pair gets, by the stages the study configures."""
    base = f"results/{STUDY}/{name}/{variant}"
    stages = {"tca": "tca", "ltca": "ltca", "dynamics": "dynamics", "train_dynamics": "train", "impact": "impact",
              "rating": "rating"}
    return [f"{base}/{stage}.nc" for section, stage in stages.items() if section in config]


def all_targets():
    targets = [f for name in config["pairs"] for f in pair_results(name)]
    targets += [f for name in config["pairs"] for v in VARIANTS for f in variant_results(name, v)]
    if "ltca" in config:
        targets += [f"results/{STUDY}/{name}/lte_table.nc" for name in config["pairs"]]
    if "impact" in config:
        for name in config["pairs"]:
            targets.append(f"results/{STUDY}/{name}/impact_table.nc")
    if "rating" in config:
        targets += [f"results/{STUDY}/{name}/load_capacity_table.nc" for name in config["pairs"]]
    if "signoff" in config:
        targets += [f"results/{STUDY}/{name}/signoff_table.nc" for name in config["pairs"]]
    for run, section in (config.get("optimise") or {}).items():
        for name in config["pairs"]:
            base = f"results/{STUDY}/{name}/optimise/{run}"
            targets.append(f"{base}/ga.nc")
            if section["method"] == "nsga2":
                targets.append(f"{base}/plots/pareto.png")
    if "dynamics" in config:
        targets += [f"results/{STUDY}/{name}/plots/dynamics_variants.png" for name in config["pairs"]]
        if dynamics_contact() and "impact" in config:
            targets += [f"results/{STUDY}/{name}/engagement_table.nc" for name in config["pairs"]]
    if "helix_sweep" in config:
        targets.append(f"results/{STUDY}/helix_sweep.nc")
    if fe_wanted():
        targets += [f"results/{STUDY}/{name}/fe_compliance.nc" for name in config["pairs"]]
    for table in ("stiffness_table", "slice_convergence"):
        if table in config:
            targets.append(f"results/{STUDY}/{table}.nc")
    if lste_comparison_wanted(config):
        targets.append(f"results/{STUDY}/lste_comparison.nc")
    if "dynamics_comparison" in config:
        targets.append(f"results/{STUDY}/dynamics_comparison.nc")
    if "low_fluctuation_design" in config:
        targets.append(f"results/{STUDY}/low_fluctuation_design.nc")
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
