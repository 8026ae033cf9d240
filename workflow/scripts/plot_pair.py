"""Thin adapter: the pair's netCDF files -> PNG figures."""
from gearmesh.pipeline import run_stage
from gearmesh.plots import plot_pair_figures

run_stage(snakemake, plot_pair_figures)  # noqa: F821
