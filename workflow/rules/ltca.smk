# Loaded tooth contact analysis of one micro-geometry variant of a pair at the configured torques.


rule ltca:
    """LTCA at every torque over one mesh cycle: LTE, load per point (contact pattern), loaded mesh
    stiffness, pairs in contact, LTE at the start of engagement (ltca.nc)."""
    input:
        pair=variant_pair_file,
    output:
        "results/{study}/{pair}/{variant}/ltca.nc",
    log:
        "logs/{study}/{pair}/{variant}/ltca.log",
    params:
        function="gearmesh.datasets.ltca:ltca_dataset",
        settings=lambda wildcards: config["ltca"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule plot_ltca:
    """TE and LTE against rotation for every torque, and the loaded contact pattern on the pinion flank."""
    input:
        ltca="results/{study}/{pair}/{variant}/ltca.nc",
    output:
        te_lte="results/{study}/{pair}/{variant}/plots/te_lte.png",
        contact_pattern="results/{study}/{pair}/{variant}/plots/contact_pattern.png",
    log:
        "logs/{study}/{pair}/{variant}/plot_ltca.log",
    params:
        function="gearmesh.plots.ltca:ltca_figures",
    conda:
        ENV
    script:
        "../scripts/plot.py"
