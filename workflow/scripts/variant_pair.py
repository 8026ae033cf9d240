"""Thin adapter: pair file + variant spec -> the variant's pair file."""
from gearmesh.pipeline import run_variant_pair

run_variant_pair(snakemake)  # noqa: F821 (injected by Snakemake's script directive)
