# Study-level stages: several pairs in one dataset.


rule helix_sweep:
    """Contact-line length statistics against helix angle (seed 002; seed 001 V-curve), and the V-curve figure."""
    input:
        unpack(stage_inputs("helix_sweep")),
    output:
        nc=stage_output("helix_sweep"),
        helix_sweep=report_item("results/{study}/plots/helix_sweep.png", "helix_sweep", "Contact lines", STUDY_TABLES),
    log:
        "logs/{study}/helix_sweep.log",
    params:
        **stage_params("helix_sweep"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule low_fluctuation_design:
    """Integer-overlap-ratio designs of each pair: helix angle forward/backward, face width."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        unpack(stage_inputs("low_fluctuation_design")),
    output:
        nc=stage_output("low_fluctuation_design"),
        csv=report_item("results/{study}/low_fluctuation_design.csv", "low_fluctuation_design", "Geometry", STUDY_TABLES),
    log:
        "logs/{study}/low_fluctuation_design.log",
    params:
        **stage_params("low_fluctuation_design"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"
