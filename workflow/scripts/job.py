"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_job, which runs the rule's job as its
stage declaration says (gearmesh.stages: a stage of one pair, a stage over the study's pairs, a
table, the optimiser or a figure job)."""
from gearmesh.jobserver import run

# on the run's job server when there is one (a fork of a process that has imported everything), else here
run(snakemake, "run_job")  # noqa: F821 (injected by Snakemake's script directive)
