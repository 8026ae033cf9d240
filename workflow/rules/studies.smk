# Study-level stages: several pairs in one dataset.


rule helix_sweep:
    """Contact-line length statistics against helix angle (seed 002; seed 001 V-curve)."""
    input:
        pairs=lambda wildcards: [str(pair_path(config, n)) for n in config["helix_sweep"]["pairs"]],
    output:
        "results/{study}/helix_sweep.nc",
    log:
        "logs/{study}/helix_sweep.log",
    params:
        stage="helix_sweep",
        settings=lambda wildcards: config["helix_sweep"],
    conda:
        ENV
    script:
        "../scripts/stage.py"


rule low_fluctuation_design:
    """Integer-overlap-ratio designs of each pair: helix angle forward/backward, face width."""
    input:
        pairs=lambda wildcards: [str(pair_path(config, n)) for n in config["low_fluctuation_design"]["pairs"]],
    output:
        nc="results/{study}/low_fluctuation_design.nc",
        csv="results/{study}/low_fluctuation_design.csv",
    log:
        "logs/{study}/low_fluctuation_design.log",
    params:
        stage="low_fluctuation_design",
        settings=lambda wildcards: config["low_fluctuation_design"],
    conda:
        ENV
    script:
        "../scripts/stage.py"
