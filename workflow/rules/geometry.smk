rule geometry:
    """Radii, contact ratios, tooth profile with the hob fillet, flank surfaces (geometry.nc)."""
    input:
        pair=pair_file,
    output:
        "results/{study}/{pair}/geometry.nc",
    log:
        "logs/{study}/{pair}/geometry.log",
    params:
        function=versioned("gearmesh.datasets.geometry:geometry_dataset"),
        settings=lambda wildcards: config["geometry"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
