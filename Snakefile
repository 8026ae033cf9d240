# gearmesh workflow: pair.yaml -> geometry -> contact_lines -> ... (see docs/architecture.md).
# Run the default study:   snakemake --cores 2
# Run another study:       snakemake --cores 2 --configfile config/studies/NAME.yaml
import sys

from snakemake.utils import min_version

from gearmesh.config import workflow_config
from gearmesh.errors import GearmeshInputError
from gearmesh.io import check_output_files

min_version("8.0")


# The default study only when no --configfile is given: Snakemake merges a --configfile into
# the configfile directive's config key by key, which would leak the default study's
# sections (variants, dynamics, ...) into every other study. (--config overrides still apply.)
if not workflow.overwrite_configfiles:

    configfile: "config/config.yaml"


# The config as `gearmesh validate` judges it (its files re-read bounded and strictly, schema
# defaults filled): a bad config stops here with one line and exit code 2. A file Snakemake's
# own loader cannot parse (binary, endless) fails in Snakemake before this line, exit 1.
try:
    config.update(workflow_config(config, workflow.configfiles))
except GearmeshInputError as exc:
    print(f"gearmesh: error: {exc}", file=sys.stderr)
    sys.exit(2)


# `snakemake --report report.html` (after a run): this page, then every figure and table, once
# `gearmesh check` finds every file of the study's results what it claims to be (gearmesh.pipeline.check_results).
report: "workflow/report/workflow.rst"

if any(arg == "--report" or arg.startswith("--report=") for arg in sys.argv):
    from gearmesh.pipeline import check_results

    problems = check_results(config)
    for line in problems:
        print(f"gearmesh: error: {line}", file=sys.stderr)
    if problems:
        sys.exit(2)


include: "workflow/rules/common.smk"
include: "workflow/rules/stages.smk"


rule all:
    input:
        plan.targets(config),
    default_target: True


# A folder where a result file belongs is refused up front (Snakemake would take it for the made
# file and skip the job), as common.smk refuses a file where a folder belongs.
try:
    check_output_files([f for r in workflow.rules for f in (*r.output, *r.log)],
                       [f"results/{STUDY}", f"logs/{STUDY}"])
except GearmeshInputError as exc:
    print(f"gearmesh: error: {exc}", file=sys.stderr)
    sys.exit(2)
