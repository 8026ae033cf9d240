"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_plot (the rule names the function)."""
from gearmesh.pipeline import run_plot

run_plot(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
