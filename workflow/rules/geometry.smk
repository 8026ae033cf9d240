rule geometry:
    """Radii, contact ratios, tooth profile with the hob fillet, flank surfaces (geometry.nc), and the
    tooth profile figure."""
    input:
        pair=pair_file,
    output:
        nc="results/{study}/{pair}/geometry.nc",
        tooth_profile=report_item("results/{study}/{pair}/plots/tooth_profile.png", "tooth_profile", "Geometry"),
    log:
        "logs/{study}/{pair}/geometry.log",
    params:
        function=versioned_param("gearmesh.datasets.geometry:geometry_dataset"),
        settings=lambda wildcards: config["geometry"],
        figures=versioned_param("gearmesh.plots.geometry:geometry_figures"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
