# The sign-off table of a pair: every variant beside the reference variant at each LTCA torque, read
# from the variants' impact, LTCA, rating and (where the study has them) dynamics results, and
# whether each meets the study's signoff criteria. No physics here.

if "signoff" in config:

    rule signoff_table:
        """F_s, swept dynamic peak, loaded-TE orders, peak pressure, root stress, S_H and S_F of every variant and
        LTCA torque beside the reference, with the criteria met or failed (signoff_table.nc); figure: each quantity
        over the reference's against torque, with the criterion's limit."""
        localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
        input:
            unpack(stage_inputs("signoff")),
        output:
            nc=stage_output("signoff"),
            csv=report_item("results/{study}/{pair}/signoff_table.csv", "signoff_table", "Sign-off", BY_PAIR),
            signoff=report_item("results/{study}/{pair}/plots/signoff.png", "signoff", "Sign-off", BY_PAIR),
        log:
            "logs/{study}/{pair}/signoff_table.log",
        params:
            **stage_params("signoff"),
        conda:
            ENV
        script:
            "../scripts/collect.py"


    rule signoff_verdict:
        """The sign-off table as a reader takes it in at a glance (signoff_verdict.nc, .csv): per variant and
        torque whether it meets every criterion, and per criterion meets or fails with its margin to the limit
        and the gear it was judged on; the report's landing page shows it."""
        localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
        input:
            signoff="results/{study}/{pair}/signoff_table.nc",
        output:
            nc="results/{study}/{pair}/signoff_verdict.nc",
            csv=report_item("results/{study}/{pair}/signoff_verdict.csv", "signoff_verdict", "Sign-off", BY_PAIR),
        log:
            "logs/{study}/{pair}/signoff_verdict.log",
        params:
            function=versioned_param("gearmesh.datasets.verdict:signoff_verdict_dataset"),
        conda:
            ENV
        script:
            "../scripts/collect.py"
