"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_study_stage (the rule names the function)."""
from gearmesh.pipeline import run_study_stage

run_study_stage(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
