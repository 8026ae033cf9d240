rule contact_lines:
    """Contact lines in the plane of action and L(phi) over one mesh cycle (contact_lines.nc), and their figures."""
    input:
        unpack(stage_inputs("contact_lines")),
    output:
        nc=stage_output("contact_lines"),
        contact_length=report_item("results/{study}/{pair}/plots/contact_length.png", "contact_length", "Contact lines"),
        contact_lines=report_item("results/{study}/{pair}/plots/contact_lines.png", "contact_lines", "Contact lines"),
    log:
        "logs/{study}/{pair}/contact_lines.log",
    params:
        **stage_params("contact_lines"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
