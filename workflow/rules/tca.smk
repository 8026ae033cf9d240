# Unloaded tooth contact analysis of one micro-geometry variant of a pair (seed 000).


rule tca:
    """Unloaded TCA over one mesh cycle: separations, TE of the mesh and of each pair, first-contact path (tca.nc);
    figure: the unloaded TE and the first-contact points on the pinion flank."""
    input:
        pair=variant_source_pair,
    output:
        nc="results/{study}/{pair}/{variant}/tca.nc",
        tca=report_item("results/{study}/{pair}/{variant}/plots/tca.png", "tca", "TCA", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/tca.log",
    params:
        function=versioned_param("gearmesh.datasets.ltca:tca_dataset"),
        settings=lambda wildcards: config["tca"],
        variant=variant_spec,
        figures=versioned_param("gearmesh.plots.ltca:tca_figures"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
