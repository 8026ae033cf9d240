rule stiffness:
    """Time-varying mesh stiffness K(phi), components, Fourier series, ISO 6336-1, LSTE (stiffness.nc),
    and its figure."""
    input:
        unpack(fe_tables("stiffness")),
        pair=pair_file,
    output:
        nc="results/{study}/{pair}/stiffness.nc",
        stiffness=report_item("results/{study}/{pair}/plots/stiffness.png", "stiffness", "Stiffness"),
    log:
        "logs/{study}/{pair}/stiffness.log",
    params:
        function=versioned_param("gearmesh.datasets.stiffness:stiffness_dataset"),
        settings=lambda wildcards: config["stiffness"],
        figures=versioned_param("gearmesh.plots.stiffness:stiffness_figures"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule stiffness_table:
    """Mesh stiffness over pairs, variants and cantilever methods (table as netCDF and CSV, and its figure)."""
    input:
        pairs=study_pair_files("stiffness_table"),
    output:
        nc="results/{study}/stiffness_table.nc",
        csv=report_item("results/{study}/stiffness_table.csv", "stiffness_table", "Stiffness", STUDY_TABLES),
        stiffness_table=report_item("results/{study}/plots/stiffness_table.png", "stiffness_table", "Stiffness",
                                    STUDY_TABLES),
    log:
        "logs/{study}/stiffness_table.log",
    params:
        function=versioned_param("gearmesh.datasets.stiffness:stiffness_table_dataset"),
        settings=lambda wildcards: config["stiffness_table"],
        figures=versioned_param("gearmesh.plots.stiffness:stiffness_table_figures"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule slice_convergence:
    """Mean mesh stiffness against the slice count (seed 004's N = 1000 question), and its figure."""
    input:
        pairs=study_pair_files("slice_convergence"),
    output:
        nc="results/{study}/slice_convergence.nc",
        csv=report_item("results/{study}/slice_convergence.csv", "slice_convergence", "Stiffness", STUDY_TABLES),
        slice_convergence=report_item("results/{study}/plots/slice_convergence.png", "slice_convergence", "Stiffness",
                                      STUDY_TABLES),
    log:
        "logs/{study}/slice_convergence.log",
    params:
        function=versioned_param("gearmesh.datasets.stiffness:slice_convergence_dataset"),
        settings=lambda wildcards: config["slice_convergence"],
        figures=versioned_param("gearmesh.plots.stiffness:slice_convergence_figures"),
    conda:
        ENV
    script:
        "../scripts/study_stage.py"
