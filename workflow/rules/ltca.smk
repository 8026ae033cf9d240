# Loaded tooth contact analysis of one micro-geometry variant of a pair at the configured torques.


rule ltca:
    """LTCA at every torque over one mesh cycle: LTE, load per point (contact pattern), loaded mesh
    stiffness, pairs in contact, LTE at the start of engagement (ltca.nc); figures: TE and LTE against
    rotation, the loaded contact pattern on the pinion flank."""
    input:
        unpack(stage_inputs("ltca")),
    output:
        nc=stage_output("ltca"),
        te_lte=report_item("results/{study}/{pair}/{variant}/plots/te_lte.png", "te_lte", "LTCA", BY_VARIANT),
        contact_pattern=report_item("results/{study}/{pair}/{variant}/plots/contact_pattern.png", "contact_pattern",
                                    "LTCA", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/ltca.log",
    params:
        **stage_params("ltca"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule lte_table:
    """Loaded transmission error of every variant of a pair at every torque: mean, peak-to-peak and whether
    the entering pair touches before the start of engagement A (lte_table.nc); the report's landing page shows the table."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        ltca=every_variant("ltca"),
    output:
        nc="results/{study}/{pair}/lte_table.nc",
        csv=report_item("results/{study}/{pair}/lte_table.csv", "lte_table", "LTCA", BY_PAIR),
    log:
        "logs/{study}/{pair}/lte_table.log",
    params:
        function=versioned_param("gearmesh.datasets.ltca:lte_table_dataset"),
    conda:
        ENV
    script:
        "../scripts/collect.py"


rule lste_comparison:
    """Seed 001's LSTE of every pair: LTCA (standard variant, first torque) next to F/K(phi)."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        stiffness=every_pair("stiffness"),
        ltca=every_pair("ltca"),
    output:
        nc="results/{study}/lste_comparison.nc",
        csv=report_item("results/{study}/lste_comparison.csv", "lste_comparison", "LTCA", STUDY_TABLES),
    log:
        "logs/{study}/lste_comparison.log",
    params:
        function=versioned_param("gearmesh.datasets.ltca:lste_comparison_dataset"),
    conda:
        ENV
    script:
        "../scripts/collect.py"
