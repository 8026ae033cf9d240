# Every rule of the study, one per stage it runs and per table of those stages, from the stage
# declarations (gearmesh.settings: each settings class's STAGE; gearmesh.stages): the function
# each job runs, the files it reads and writes, its figures with their captions
# (workflow/report/CAPTION.rst), report categories and subcategories, its log, whether it runs
# where Snakemake runs (localrule) and its priority. gearmesh.plan derives them; nothing here
# names a stage.
#
# Results follow the code: each job's params.function is versioned("module:function"), which
# appends the digest of the package modules that function can run; Snakemake reruns a job whose
# params changed, so a code change reruns exactly the jobs it can affect.
# `snakemake --report report.html`: every figure and table is a report item with its caption
# (Jinja: snakemake.wildcards, snakemake.config), category = the stage, subcategory = the pair,
# pair / variant, pair / run, or the study tables.
from gearmesh import plan

for job in plan.rules(config):

    rule:
        name:
            job.name
        input:
            unpack(job.input),
        output:
            **job.output(report),
        log:
            job.log,
        params:
            **job.params,
        localrule: job.localrule
        priority: job.priority
        conda:
            ENV
        script:
            "../scripts/job.py"  # every rule (gearmesh.plan.SCRIPT): a loop variable here is read when the job runs

    workflow.get_rule(job.name).docstring = job.doc  # snakemake --list-rules (a docstring must be a literal)
