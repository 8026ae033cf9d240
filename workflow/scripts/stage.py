"""Thin adapter: Snakemake job -> gearmesh.pipeline.run_named_stage -> netCDF."""
from gearmesh.pipeline import run_named_stage

run_named_stage(snakemake)  # noqa: F821 (snakemake is injected by the script directive)
