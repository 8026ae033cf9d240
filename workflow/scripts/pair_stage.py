"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_pair_stage (the rule names the function)."""
from gearmesh.jobserver import run

# on the run's job server when there is one (a fork of a process that has imported everything), else here
run(snakemake, "run_pair_stage")  # noqa: F821 (injected by Snakemake's script directive)
