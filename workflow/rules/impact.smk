# Mesh-in impact (seed 000) of one micro-geometry variant of a pair over a torque x speed grid,
# and the variants side by side (seed 000 Table 4). No physics here: each rule names one
# package function; the settings are the config section "impact".


rule impact:
    """Mesh-in point, impact velocity, local stiffness and energy-method impact force over the
    torque x speed grid, and the direct simulation of the engagement at the design speed (impact.nc);
    figures: impact force against speed per torque, the trajectory of M on the flank, the simulated engagement."""
    input:
        unpack(stage_inputs("impact")),
    output:
        nc=stage_output("impact"),
        force_speed=report_item("results/{study}/{pair}/{variant}/plots/impact_speed.png", "impact_speed",
                                "Impact", BY_VARIANT),
        trajectory=report_item("results/{study}/{pair}/{variant}/plots/mesh_in_trajectory.png",
                               "mesh_in_trajectory", "Impact", BY_VARIANT),
        simulation=report_item("results/{study}/{pair}/{variant}/plots/impact_simulation.png",
                               "impact_simulation", "Impact", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/impact.log",
    priority: 3  # the next longest stage of a variant, beside its dynamics (rule dynamics)
    params:
        **stage_params("impact"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule impact_table:
    """Impact force of every variant at every torque at the design speed, with the reduction against standard;
    figures: all variants on one axis (impact force against torque and against speed) and, off the design point,
    their load windows and tolerance spreads side by side (the robustness page)."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        impact=every_variant("impact"),
    output:
        nc="results/{study}/{pair}/impact_table.nc",
        csv=report_item("results/{study}/{pair}/impact_table.csv", "impact_table", "Impact", BY_PAIR),
        impact_force=report_item("results/{study}/{pair}/plots/impact_force.png", "impact_force", "Impact", BY_PAIR),
        robustness=report_item("results/{study}/{pair}/plots/robustness.png", "robustness", "Impact", BY_PAIR),
    log:
        "logs/{study}/{pair}/impact_table.log",
    params:
        function=versioned_param("gearmesh.datasets.impact:impact_table_dataset"),
        figures=versioned_param("gearmesh.plots.impact:impact_study_figures"),
    conda:
        ENV
    script:
        "../scripts/collect.py"
