# Study-level stages: several pairs in one dataset.


rule helix_sweep:
    """Contact-line length statistics against helix angle (seed 002; seed 001 V-curve), and the V-curve figure."""
    input:
        pairs=study_pair_files("helix_sweep"),
    output:
        nc="results/{study}/helix_sweep.nc",
        helix_sweep=report_item("results/{study}/plots/helix_sweep.png", "helix_sweep", "Contact lines", STUDY_TABLES),
    log:
        "logs/{study}/helix_sweep.log",
    params:
        function=versioned_param("gearmesh.datasets.geometry:helix_sweep_dataset"),
        settings=lambda wildcards: config["helix_sweep"],
        figures=versioned_param("gearmesh.plots.geometry:helix_sweep_figures"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule low_fluctuation_design:
    """Integer-overlap-ratio designs of each pair: helix angle forward/backward, face width."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        pairs=study_pair_files("low_fluctuation_design"),
    output:
        nc="results/{study}/low_fluctuation_design.nc",
        csv=report_item("results/{study}/low_fluctuation_design.csv", "low_fluctuation_design", "Geometry", STUDY_TABLES),
    log:
        "logs/{study}/low_fluctuation_design.log",
    params:
        function=versioned_param("gearmesh.datasets.geometry:low_fluctuation_design_dataset"),
        settings=lambda wildcards: config["low_fluctuation_design"],
    conda:
        ENV
    script:
        "../scripts/study_stage.py"
