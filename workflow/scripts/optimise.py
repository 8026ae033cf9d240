"""Thin adapter: pair file -> gearmesh.pipeline.run_optimise (ga.nc and the optimum's pair file)."""
from gearmesh.jobserver import run

# on the run's job server when there is one (a fork of a process that has imported everything), else here
run(snakemake, "run_optimise")  # noqa: F821 (injected by Snakemake's script directive)
