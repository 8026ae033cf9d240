# Config loading and helpers shared by every rule. No physics here.
import sys

from gearmesh.config import check_study, lste_comparison_wanted, pair_path
from gearmesh.codeversion import versioned
from gearmesh.errors import GearmeshInputError
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


def fe_tables(section):
    """Input function: the pair's FE tooth tables (rule fe_compliance) when the stage of
    ``section`` uses the stiffness method 'fe' — computed once per pair, read by every stage."""

    def inputs(wildcards):
        if config.get(section, {}).get("method") == "fe":
            return {"fe_compliance": f"results/{wildcards.study}/{wildcards.pair}/fe_compliance.nc"}
        return {}

    return inputs


def pair_file(wildcards):
    return str(pair_path(config, wildcards.pair))


def variant_pair_file(wildcards):
    """The pair file of one micro-geometry variant (rule variant_pair)."""
    return f"results/{wildcards.study}/{wildcards.pair}/{wildcards.variant}/pair.yaml"


def variant_source_pair(wildcards):
    """The input of the variant_pair job: the pair file, or for a variant {from: optimise.NAME}
    that optimisation's pair file (its optimum, rule optimise)."""
    source = config["variants"][wildcards.variant].get("from")
    if source:
        return f"results/{wildcards.study}/{wildcards.pair}/optimise/{source.split('.', 1)[1]}/pair.yaml"
    return pair_file(wildcards)


def dynamics_contact():
    """Whether the study's dynamics is driven by the real tooth contact (excitation: contact)."""
    return config.get("dynamics", {}).get("excitation") == "contact"


def dynamics_inputs(wildcards):
    """The pair stage inputs of the dynamics: the variant's pair, the stiffness, the variant's
    LTCA when it excites the model (excitation ltca, or unset in a study that runs the LTCA) and
    the FE tooth tables when the contact table uses method fe."""
    base = f"results/{wildcards.study}/{wildcards.pair}"
    out = {"pair": variant_pair_file(wildcards), "stiffness": f"{base}/stiffness.nc"}
    if "ltca" in config and config["dynamics"].get("excitation") in (None, "ltca"):
        out["ltca"] = f"{base}/{wildcards.variant}/ltca.nc"
    out.update(fe_tables("dynamics")(wildcards))
    return out


def study_pair_files(section):
    """Input function: the pair files a study-level section names."""
    return lambda wildcards: [str(pair_path(config, n)) for n in config[section]["pairs"]]


def pair_results(name):
    """Files every pair of the study gets."""
    base = f"results/{STUDY}/{name}"
    return [
        f"{base}/geometry.nc",
        f"{base}/contact_lines.nc",
        f"{base}/stiffness.nc",
        f"{base}/plots/stiffness.png",
        f"{base}/plots/tooth_profile.png",
        f"{base}/plots/contact_length.png",
        f"{base}/plots/contact_lines.png",
    ]


def variant_results(name, variant):
    """Files every micro-geometry variant of a pair gets, by the stages the study configures."""
    base = f"results/{STUDY}/{name}/{variant}"
    out = []
    if "tca" in config:
        out += [f"{base}/tca.nc", f"{base}/plots/tca.png"]
    if "ltca" in config:
        out += [f"{base}/ltca.nc", f"{base}/plots/te_lte.png", f"{base}/plots/contact_pattern.png"]
    if "dynamics" in config:
        out += [f"{base}/dynamics.nc", f"{base}/plots/dynamics_rms.png", f"{base}/plots/dynamics_spectrum.png"]
        if dynamics_contact():
            out.append(f"{base}/plots/dynamics_engagement.png")
    if "train_dynamics" in config:
        out += [f"{base}/train.nc", f"{base}/plots/train_spectrum.png"]
    if "impact" in config:
        out += [f"{base}/impact.nc", f"{base}/plots/impact_speed.png", f"{base}/plots/mesh_in_trajectory.png",
                f"{base}/plots/impact_simulation.png"]
    return out


def all_targets():
    targets = [f for name in config["pairs"] for f in pair_results(name)]
    targets += [f for name in config["pairs"] for v in VARIANTS for f in variant_results(name, v)]
    if "impact" in config:
        for name in config["pairs"]:
            targets += [f"results/{STUDY}/{name}/impact_table.nc", f"results/{STUDY}/{name}/impact_table.csv",
                        f"results/{STUDY}/{name}/plots/impact_force.png", f"results/{STUDY}/{name}/plots/robustness.png"]
    for run, section in (config.get("optimise") or {}).items():
        for name in config["pairs"]:
            base = f"results/{STUDY}/{name}/optimise/{run}"
            targets += [f"{base}/ga.nc", f"{base}/pair.yaml", f"{base}/plots/convergence.png",
                        f"{base}/plots/modification.png"]
            if section["method"] == "nsga2":
                targets.append(f"{base}/plots/pareto.png")
    if "dynamics" in config:
        targets += [f"results/{STUDY}/{name}/plots/dynamics_variants.png" for name in config["pairs"]]
        if dynamics_contact() and "impact" in config:
            targets += [f"results/{STUDY}/{name}/engagement_table.{ext}" for name in config["pairs"]
                        for ext in ("nc", "csv")]
    if "helix_sweep" in config:
        targets += [f"results/{STUDY}/helix_sweep.nc", f"results/{STUDY}/plots/helix_sweep.png"]
    if "fe_compliance" in config:
        targets += [f"results/{STUDY}/{name}/{f}" for name in config["pairs"]
                    for f in ("fe_compliance.nc", "plots/fe_compliance.png")]
    for table in ("stiffness_table", "slice_convergence"):
        if table in config:
            targets += [f"results/{STUDY}/{table}.nc", f"results/{STUDY}/{table}.csv",
                        f"results/{STUDY}/plots/{table}.png"]
    if lste_comparison_wanted(config):
        targets += [f"results/{STUDY}/lste_comparison.nc", f"results/{STUDY}/lste_comparison.csv"]
    if "dynamics_comparison" in config:
        targets += [f"results/{STUDY}/dynamics_comparison.nc", f"results/{STUDY}/dynamics_comparison.csv",
                    f"results/{STUDY}/plots/dynamics_comparison.png"]
    if "low_fluctuation_design" in config:
        targets += [f"results/{STUDY}/low_fluctuation_design.nc", f"results/{STUDY}/low_fluctuation_design.csv"]
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
onstart:
    remove_stale_temporaries("results")
