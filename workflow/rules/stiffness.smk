rule stiffness:
    """Time-varying mesh stiffness K(phi), components, Fourier series, ISO 6336-1, LSTE (stiffness.nc)."""
    input:
        unpack(fe_tables("stiffness")),
        pair=pair_file,
    output:
        "results/{study}/{pair}/stiffness.nc",
    log:
        "logs/{study}/{pair}/stiffness.log",
    params:
        function=versioned("gearmesh.datasets.stiffness:stiffness_dataset"),
        settings=lambda wildcards: config["stiffness"],
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule stiffness_table:
    """Mesh stiffness over pairs, variants and cantilever methods (table as netCDF and CSV)."""
    input:
        pairs=study_pair_files("stiffness_table"),
    output:
        nc="results/{study}/stiffness_table.nc",
        csv=report_item("results/{study}/stiffness_table.csv", "stiffness_table", "Stiffness", STUDY_TABLES),
    log:
        "logs/{study}/stiffness_table.log",
    params:
        function=versioned("gearmesh.datasets.stiffness:stiffness_table_dataset"),
        settings=lambda wildcards: config["stiffness_table"],
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule slice_convergence:
    """Mean mesh stiffness against the slice count (seed 004's N = 1000 question)."""
    input:
        pairs=study_pair_files("slice_convergence"),
    output:
        nc="results/{study}/slice_convergence.nc",
        csv=report_item("results/{study}/slice_convergence.csv", "slice_convergence", "Stiffness", STUDY_TABLES),
    log:
        "logs/{study}/slice_convergence.log",
    params:
        function=versioned("gearmesh.datasets.stiffness:slice_convergence_dataset"),
        settings=lambda wildcards: config["slice_convergence"],
    conda:
        ENV
    script:
        "../scripts/study_stage.py"


rule plot_stiffness:
    """K(phi) with its Fourier fit and the ISO mean, one pair's k, the LSTE."""
    input:
        stiffness="results/{study}/{pair}/stiffness.nc",
    output:
        stiffness=report_item("results/{study}/{pair}/plots/stiffness.png", "stiffness", "Stiffness"),
    log:
        "logs/{study}/{pair}/plot_stiffness.log",
    params:
        function=versioned("gearmesh.plots.stiffness:stiffness_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_stiffness_table:
    input:
        stiffness_table="results/{study}/stiffness_table.nc",
    output:
        stiffness_table=report_item("results/{study}/plots/stiffness_table.png", "stiffness_table", "Stiffness",
                                    STUDY_TABLES),
    log:
        "logs/{study}/plot_stiffness_table.log",
    params:
        function=versioned("gearmesh.plots.stiffness:stiffness_table_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_slice_convergence:
    input:
        slice_convergence="results/{study}/slice_convergence.nc",
    output:
        slice_convergence=report_item("results/{study}/plots/slice_convergence.png", "slice_convergence", "Stiffness",
                                      STUDY_TABLES),
    log:
        "logs/{study}/plot_slice_convergence.log",
    params:
        function=versioned("gearmesh.plots.stiffness:slice_convergence_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"
