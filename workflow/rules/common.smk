# Config loading and helpers shared by every rule. No physics here.
import sys

from gearmesh.config import pair_path, study_pairs
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry

STUDY = config["study"]
ENV = "../envs/gearmesh.yaml"

# Every pair of the study is loaded and checked before any job runs, so a bad pair stops the
# workflow with one message and no partial output.
try:
    PAIRS = study_pairs(config)
    for _pair in PAIRS.values():
        pair_geometry(_pair)
except GearmeshInputError as exc:
    print(f"gearmesh: error: {exc}", file=sys.stderr)
    sys.exit(2)


wildcard_constraints:
    study=STUDY,
    pair="|".join(PAIRS),


def pair_file(wildcards):
    return str(pair_path(config, wildcards.pair))


def study_pair_files(section):
    """Input function: the pair files a study-level section names."""
    return lambda wildcards: [str(pair_path(config, n)) for n in config[section]["pairs"]]


def pair_results(name):
    """Files every pair of the study gets."""
    base = f"results/{STUDY}/{name}"
    return [
        f"{base}/geometry.nc",
        f"{base}/contact_lines.nc",
        f"{base}/plots/tooth_profile.png",
        f"{base}/plots/contact_length.png",
        f"{base}/plots/contact_lines.png",
    ]


def all_targets():
    targets = [f for name in config["pairs"] for f in pair_results(name)]
    if "helix_sweep" in config:
        targets += [f"results/{STUDY}/helix_sweep.nc", f"results/{STUDY}/plots/helix_sweep.png"]
    if "low_fluctuation_design" in config:
        targets += [f"results/{STUDY}/low_fluctuation_design.nc", f"results/{STUDY}/low_fluctuation_design.csv"]
    return targets
