"""Thin adapter: pair file -> gearmesh.pipeline.run_optimise (ga.nc and the optimum's pair file)."""
from gearmesh.pipeline import run_optimise

run_optimise(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
