rule stiffness:
    """Time-varying mesh stiffness K(phi), components, Fourier series, ISO 6336-1, LSTE (stiffness.nc),
    and its figure."""
    input:
        unpack(stage_inputs("stiffness")),
    output:
        nc=stage_output("stiffness"),
        stiffness=report_item("results/{study}/{pair}/plots/stiffness.png", "stiffness", "Stiffness"),
    log:
        "logs/{study}/{pair}/stiffness.log",
    params:
        **stage_params("stiffness"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule stiffness_table:
    """Mesh stiffness over pairs, variants and cantilever methods (table as netCDF and CSV, and its figure)."""
    input:
        unpack(stage_inputs("stiffness_table")),
    output:
        nc=stage_output("stiffness_table"),
        csv=report_item("results/{study}/stiffness_table.csv", "stiffness_table", "Stiffness", STUDY_TABLES),
        stiffness_table=report_item("results/{study}/plots/stiffness_table.png", "stiffness_table", "Stiffness",
                                    STUDY_TABLES),
    log:
        "logs/{study}/stiffness_table.log",
    params:
        **stage_params("stiffness_table"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule slice_convergence:
    """Mean mesh stiffness against the slice count (seed 004's N = 1000 question), and its figure."""
    input:
        unpack(stage_inputs("slice_convergence")),
    output:
        nc=stage_output("slice_convergence"),
        csv=report_item("results/{study}/slice_convergence.csv", "slice_convergence", "Stiffness", STUDY_TABLES),
        slice_convergence=report_item("results/{study}/plots/slice_convergence.png", "slice_convergence", "Stiffness",
                                      STUDY_TABLES),
    log:
        "logs/{study}/slice_convergence.log",
    params:
        **stage_params("slice_convergence"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"
