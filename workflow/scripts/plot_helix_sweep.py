"""Thin adapter: helix_sweep.nc -> the V-curve PNG."""
from gearmesh.io import read_dataset
from gearmesh.pipeline import run_stage
from gearmesh.plots import plot_helix_sweep

run_stage(snakemake, lambda smk: plot_helix_sweep(read_dataset(smk.input[0]), smk.output[0]))  # noqa: F821
