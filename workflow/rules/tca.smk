# Unloaded tooth contact analysis of one micro-geometry variant of a pair (seed 000).


rule tca:
    """Unloaded TCA over one mesh cycle: separations, TE of the mesh and of each pair, first-contact path (tca.nc)."""
    input:
        pair=variant_pair_file,
    output:
        "results/{study}/{pair}/{variant}/tca.nc",
    log:
        "logs/{study}/{pair}/{variant}/tca.log",
    params:
        function=versioned("gearmesh.datasets.ltca:tca_dataset"),
        settings=lambda wildcards: config["tca"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule plot_tca:
    """Unloaded TE of the mesh and of each tooth pair, and the first-contact points on the pinion flank."""
    input:
        tca="results/{study}/{pair}/{variant}/tca.nc",
    output:
        tca=report_item("results/{study}/{pair}/{variant}/plots/tca.png", "tca", "TCA", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/plot_tca.log",
    params:
        function=versioned("gearmesh.plots.ltca:tca_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"
