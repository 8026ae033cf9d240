rule contact_lines:
    """Contact lines in the plane of action and L(phi) over one mesh cycle (contact_lines.nc), and their figures."""
    input:
        pair=pair_file,
    output:
        nc="results/{study}/{pair}/contact_lines.nc",
        contact_length=report_item("results/{study}/{pair}/plots/contact_length.png", "contact_length", "Contact lines"),
        contact_lines=report_item("results/{study}/{pair}/plots/contact_lines.png", "contact_lines", "Contact lines"),
    log:
        "logs/{study}/{pair}/contact_lines.log",
    params:
        function=versioned_param("gearmesh.datasets.geometry:contact_lines_dataset"),
        settings=lambda wildcards: config["contact_lines"],
        figures=versioned_param("gearmesh.plots.geometry:contact_lines_figures"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
