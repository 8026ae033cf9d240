rule variant_pair:
    """The pair file of one micro-geometry variant ('standard': unmodified), input of tca/ltca/impact/dynamics."""
    input:
        pair=variant_source_pair,
    output:
        "results/{study}/{pair}/{variant}/pair.yaml",
    log:
        "logs/{study}/{pair}/{variant}/variant_pair.log",
    params:
        function=versioned("gearmesh.pipeline:run_variant_pair"),
        spec=lambda wildcards: config["variants"][wildcards.variant],
    conda:
        ENV
    script:
        "../scripts/variant_pair.py"
