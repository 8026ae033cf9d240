"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_pair_stage (the rule names the function)."""
from gearmesh.pipeline import run_pair_stage

run_pair_stage(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
