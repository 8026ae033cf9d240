# Unloaded tooth contact analysis of one micro-geometry variant of a pair (seed 000).


rule tca:
    """Unloaded TCA over one mesh cycle: separations, TE of the mesh and of each pair, first-contact path (tca.nc);
    figure: the unloaded TE and the first-contact points on the pinion flank."""
    input:
        unpack(stage_inputs("tca")),
    output:
        nc=stage_output("tca"),
        tca=report_item("results/{study}/{pair}/{variant}/plots/tca.png", "tca", "TCA", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/tca.log",
    params:
        **stage_params("tca"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
