rule geometry:
    """Radii, contact ratios, tooth profile with the hob fillet, flank surfaces (geometry.nc), and the
    tooth profile figure."""
    input:
        unpack(stage_inputs("geometry")),
    output:
        nc=stage_output("geometry"),
        tooth_profile=report_item("results/{study}/{pair}/plots/tooth_profile.png", "tooth_profile", "Geometry"),
    log:
        "logs/{study}/{pair}/geometry.log",
    params:
        **stage_params("geometry"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
