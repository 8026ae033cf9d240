# Dynamics stage (issue 5): the 8-DOF helical pair swept over speed (seed 001 §4-5) and the
# 9-DOF plate-blanket-impression train (seed 004). No physics here: each rule names one
# package function; the settings are the config sections "dynamics" and "train_dynamics".
# The mesh stiffness comes from the stiffness stage (per pair: the slice model does not
# depend on the micro-geometry).


rule dynamics:
    """Steady-state speed sweeps of the 8-DOF pair at the study's torques: RMS of DTE, displacements, velocities;
    mesh force; with excitation: contact the entering pair's force, mesh-in point and dynamic impact (dynamics.nc);
    figures: RMS against speed (DTE, x/y/z displacement and velocity, both gears), mesh-force spectra and, with the
    contact excitation, the mesh force and the entering pair's force over two mesh cycles."""
    input:
        unpack(stage_inputs("dynamics")),
    output:
        nc=stage_output("dynamics"),
        **dynamics_figure_outputs(),
    log:
        "logs/{study}/{pair}/{variant}/dynamics.log",
    # the longest stage of a variant (3 s of CPU in the default study): once an optimisation ends, its
    # variant's dynamics starts first, its LTCA and rating (4) and impact (3) beside it, the study tables
    # (0) after them, so the sign-off and engagement tables do not wait for a stage started last
    priority: 5
    params:
        **stage_params("dynamics"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule train_dynamics:
    """The 9-DOF three-gear train of seed 004 at its speed and load: both mesh forces, spectra, vibration (train.nc);
    figure: the mesh forces of both meshes, time series and spectrum."""
    input:
        unpack(stage_inputs("train_dynamics")),
    output:
        nc=stage_output("train_dynamics"),
        spectrum=report_item("results/{study}/{pair}/{variant}/plots/train_spectrum.png", "train_spectrum", "Dynamics",
                             BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/train.log",
    params:
        **stage_params("train_dynamics"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule dynamics_comparison:
    """RMS changes between the study's pairs (standard variant): DTE, lateral and axial vibration; and its figure."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        dynamics=every_pair("dynamics"),
    output:
        nc=stage_output("dynamics_comparison"),
        csv=report_item("results/{study}/dynamics_comparison.csv", "dynamics_comparison", "Dynamics", STUDY_TABLES),
        dynamics_comparison=report_item("results/{study}/plots/dynamics_comparison.png", "dynamics_comparison",
                                        "Dynamics", STUDY_TABLES),
    log:
        "logs/{study}/dynamics_comparison.log",
    params:
        **stage_params("dynamics_comparison"),
    conda:
        ENV
    script:
        "../scripts/collect.py"


# Peak dynamic mesh force against speed of every variant of a pair: drawn by the engagement table's job
# where the study has one (contact excitation and an impact section), else by a figure job of its own.
if dynamics_contact() and "impact" in config:

    rule engagement_table:
        """The energy method's F_s beside the contact-driven dynamics, per variant and torque at the design speed;
        figure: the peak dynamic mesh force against speed, every variant on one axis, one panel per torque."""
        localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
        input:
            impact=every_variant("impact"),
            dynamics=every_variant("dynamics"),
        output:
            nc="results/{study}/{pair}/engagement_table.nc",
            csv=report_item("results/{study}/{pair}/engagement_table.csv", "engagement_table", "Dynamics", BY_PAIR),
            dynamics_variants=report_item("results/{study}/{pair}/plots/dynamics_variants.png", "dynamics_variants",
                                          "Dynamics"),
        log:
            "logs/{study}/{pair}/engagement_table.log",
        params:
            function=versioned_param("gearmesh.datasets.dynamics:engagement_table_dataset"),
            figures=versioned_param("gearmesh.plots.dynamics:dynamics_variants_figures"),
        conda:
            ENV
        script:
            "../scripts/collect.py"

else:

    rule plot_dynamics_variants:
        """Peak dynamic mesh force against speed, every variant of a pair on one axis, one panel per torque."""
        localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
        input:
            dynamics=every_variant("dynamics"),
        output:
            dynamics_variants=report_item("results/{study}/{pair}/plots/dynamics_variants.png", "dynamics_variants",
                                          "Dynamics"),
        log:
            "logs/{study}/{pair}/plot_dynamics_variants.log",
        params:
            function=versioned_param("gearmesh.plots.dynamics:dynamics_variants_figures"),
        conda:
            ENV
        script:
            "../scripts/plot.py"
