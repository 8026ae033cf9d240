"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_collect (the rule names the function)."""
from gearmesh.pipeline import run_collect

run_collect(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
