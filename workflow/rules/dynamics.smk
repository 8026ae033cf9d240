# Dynamics stage (issue 5): the 8-DOF helical pair swept over speed (seed 001 §4-5) and the
# 9-DOF plate-blanket-impression train (seed 004). No physics here: each rule names one
# package function; the settings are the config sections "dynamics" and "train_dynamics".
# The mesh stiffness comes from the stiffness stage (per pair: the slice model does not
# depend on the micro-geometry).


rule dynamics:
    """Steady-state speed sweeps of the 8-DOF pair at the study's torques: RMS of DTE, displacements, velocities;
    mesh force; with excitation: contact the entering pair's force, mesh-in point and dynamic impact (dynamics.nc)."""
    input:
        unpack(dynamics_inputs),
    output:
        "results/{study}/{pair}/{variant}/dynamics.nc",
    log:
        "logs/{study}/{pair}/{variant}/dynamics.log",
    params:
        function=versioned("gearmesh.datasets.dynamics:dynamics_dataset"),
        settings=lambda wildcards: {**config["dynamics"], "variant": wildcards.variant},
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule train_dynamics:
    """The 9-DOF three-gear train of seed 004 at its speed and load: both mesh forces, spectra, vibration (train.nc)."""
    input:
        unpack(fe_tables("train_dynamics")),
        pair=variant_pair_file,
        stiffness="results/{study}/{pair}/stiffness.nc",
    output:
        "results/{study}/{pair}/{variant}/train.nc",
    log:
        "logs/{study}/{pair}/{variant}/train.log",
    params:
        function=versioned("gearmesh.datasets.dynamics:train_dataset"),
        settings=lambda wildcards: config["train_dynamics"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule plot_dynamics:
    """RMS against speed (DTE, x/y/z displacement and velocity, both gears), mesh-force spectra and, with the
    contact excitation, the mesh force and the entering pair's force over two mesh cycles."""
    input:
        dynamics="results/{study}/{pair}/{variant}/dynamics.nc",
    output:
        rms=report_item("results/{study}/{pair}/{variant}/plots/dynamics_rms.png", "dynamics_rms", "Dynamics",
                        BY_VARIANT),
        spectrum=report_item("results/{study}/{pair}/{variant}/plots/dynamics_spectrum.png", "dynamics_spectrum",
                             "Dynamics", BY_VARIANT),
        **({"engagement": report_item("results/{study}/{pair}/{variant}/plots/dynamics_engagement.png",
                                      "dynamics_engagement", "Dynamics", BY_VARIANT)} if dynamics_contact() else {}),
    log:
        "logs/{study}/{pair}/{variant}/plot_dynamics.log",
    params:
        function=versioned("gearmesh.plots.dynamics:dynamics_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_train_dynamics:
    """Mesh forces of both meshes of the train: time series and spectrum."""
    input:
        train="results/{study}/{pair}/{variant}/train.nc",
    output:
        spectrum=report_item("results/{study}/{pair}/{variant}/plots/train_spectrum.png", "train_spectrum", "Dynamics",
                             BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/plot_train.log",
    params:
        function=versioned("gearmesh.plots.dynamics:train_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule dynamics_comparison:
    """RMS changes between the study's pairs (standard variant): DTE, lateral and axial vibration."""
    input:
        dynamics=expand("results/{{study}}/{pair}/standard/dynamics.nc", pair=config["pairs"]),
    output:
        nc="results/{study}/dynamics_comparison.nc",
        csv=report_item("results/{study}/dynamics_comparison.csv", "dynamics_comparison", "Dynamics", STUDY_TABLES),
    log:
        "logs/{study}/dynamics_comparison.log",
    params:
        function=versioned("gearmesh.datasets.dynamics:dynamics_comparison_dataset"),
        settings=lambda wildcards: config.get("dynamics_comparison", {}),
    conda:
        ENV
    script:
        "../scripts/collect.py"


rule plot_dynamics_comparison:
    input:
        dynamics=expand("results/{{study}}/{pair}/standard/dynamics.nc", pair=config["pairs"]),
    output:
        dynamics_comparison=report_item("results/{study}/plots/dynamics_comparison.png", "dynamics_comparison",
                                        "Dynamics", STUDY_TABLES),
    log:
        "logs/{study}/plot_dynamics_comparison.log",
    params:
        function=versioned("gearmesh.plots.dynamics:dynamics_comparison_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_dynamics_variants:
    """Peak dynamic mesh force against speed, every variant of a pair on one axis, one panel per torque."""
    input:
        dynamics=expand("results/{{study}}/{{pair}}/{variant}/dynamics.nc", variant=VARIANTS),
    output:
        dynamics_variants=report_item("results/{study}/{pair}/plots/dynamics_variants.png", "dynamics_variants",
                                      "Dynamics"),
    log:
        "logs/{study}/{pair}/plot_dynamics_variants.log",
    params:
        function=versioned("gearmesh.plots.dynamics:dynamics_variants_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule engagement_table:
    """The energy method's F_s beside the contact-driven dynamics, per variant and torque at the design speed."""
    input:
        impact=expand("results/{{study}}/{{pair}}/{variant}/impact.nc", variant=VARIANTS),
        dynamics=expand("results/{{study}}/{{pair}}/{variant}/dynamics.nc", variant=VARIANTS),
    output:
        nc="results/{study}/{pair}/engagement_table.nc",
        csv=report_item("results/{study}/{pair}/engagement_table.csv", "engagement_table", "Dynamics", BY_PAIR),
    log:
        "logs/{study}/{pair}/engagement_table.log",
    params:
        function=versioned("gearmesh.datasets.dynamics:engagement_table_dataset"),
    conda:
        ENV
    script:
        "../scripts/collect.py"
