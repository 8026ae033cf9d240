# gearmesh workflow: pair.yaml -> geometry -> contact_lines -> ... (see DESIGN.md).
# Run the default study:   snakemake --cores 2
# Run another study:       snakemake --cores 2 --configfile config/studies/NAME.yaml
from snakemake.utils import min_version, validate

min_version("8.0")


# The default study only when no --configfile is given: Snakemake merges a --configfile into
# the configfile directive's config key by key, which would leak the default study's
# sections (variants, dynamics, ...) into every other study. (--config overrides still apply.)
if not workflow.overwrite_configfiles:

    configfile: "config/config.yaml"


validate(config, "workflow/schemas/config.schema.yaml", set_default=True)


# `snakemake --report report.html` (after a run): this page, then every figure and table.
report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/geometry.smk"
include: "workflow/rules/contact_lines.smk"
include: "workflow/rules/stiffness.smk"
include: "workflow/rules/variants.smk"
include: "workflow/rules/tca.smk"
include: "workflow/rules/ltca.smk"
include: "workflow/rules/dynamics.smk"
include: "workflow/rules/studies.smk"
include: "workflow/rules/plots.smk"


rule all:
    input:
        all_targets(),
    default_target: True
