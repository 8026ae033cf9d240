rule contact_lines:
    """Contact lines in the plane of action and L(phi) over one mesh cycle (contact_lines.nc)."""
    input:
        pair=pair_file,
    output:
        "results/{study}/{pair}/contact_lines.nc",
    log:
        "logs/{study}/{pair}/contact_lines.log",
    params:
        function=versioned("gearmesh.datasets.geometry:contact_lines_dataset"),
        settings=lambda wildcards: config["contact_lines"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
