# Finite-element tooth compliance (issue 12): per pair, both gears along the active profile,
# beside the three potential-energy cantilevers. It is computed once per pair here; the stages
# whose section says method: fe (stiffness, ltca, impact, optimise) take their tables from this
# file (common.smk stage_inputs: Read("fe_compliance"), gearmesh.fe.seed_cache) instead of meshing again.


rule fe_compliance:
    """FE tooth compliance of both gears along the profile, with the PEM models (fe_compliance.nc), and its figure."""
    input:
        unpack(stage_inputs("fe_compliance")),
    output:
        nc=stage_output("fe_compliance"),
        fe_compliance=report_item("results/{study}/{pair}/plots/fe_compliance.png", "fe_compliance", "Stiffness"),
    log:
        "logs/{study}/{pair}/fe_compliance.log",
    params:
        **stage_params("fe_compliance"),
    priority: 10  # with method fe the optimiser (priority 10, the longest job) waits for it
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"
